"""The parameters a continuation or a map varies, named by paths into the case:

- ``current.speed`` [m/s], ``current.towards_deg``, ``wind.speed`` [m/s], ``wind.towards_deg``:
  the weather (a uniform current and a constant wind; the directions they go towards);
  ``waves.height`` [m] (the significant height the case's sea is scaled to) and
  ``waves.towards_deg`` (its mean direction), acting through the ships' ``wave drift``
  (``plane.Weather``);
- ``lines.<tie>.unstretched_length`` [m], ``lines.<tie>.stiffness`` [N/m] (a linear tie);
- ``bodies.<body>.points.<point>.x`` (or ``.y``) [m]: a point's place on its body (a turret,
  a hawser's fairlead);
- ``bodies.<body>.external forces.<k>.force_x`` (any of an ``applied`` model's six channels,
  k counted from 0 in the body's list) [N, N m]: a constant load (a shuttle's astern thrust);
- ``bodies.<body>.external forces.<k>.distance`` (or ``heading_deg``, ``frequency``,
  ``heading_frequency``, ``max_ahead``, ``max_astern``, ``max_yaw_moment``) of a
  ``compensator`` [m, deg, rad/s, N, N m]: its set points, laws and limits.

Each is written into the built system's parameters in place (``Parameter.set``).
"""

import math
from dataclasses import replace

from seacable.case import forces as fm
from seacable.case import ship_forces as sf
from seacable.errors import CaseError
from seacable.forces import applied, compensator
from seacable.stability.continuation import Parameter
from seacable.stability.plane import Plane, Weather, set_constant

FORMS = ("current.speed", "current.towards_deg", "wind.speed", "wind.towards_deg",
         "waves.height", "waves.towards_deg",
         "lines.<tie>.unstretched_length", "lines.<tie>.stiffness",
         "bodies.<body>.points.<point>.x (or .y)",
         "bodies.<body>.external forces.<k>.<force_x ... moment_z>",
         "bodies.<body>.external forces.<k>.<distance, heading_deg, ...> (compensator)",
         )  # fmt: skip


# the weather's parameters: the Weather field each sets
WEATHER = {"current": {"speed": "current_speed", "towards_deg": "current_towards_deg"},
           "wind": {"speed": "wind_speed", "towards_deg": "wind_towards_deg"},
           "waves": {"height": "wave_height", "towards_deg": "wave_towards_deg"}}  # fmt: skip
# a compensator's settings: their place in its row and their steps' scale
SETTINGS = {"distance": compensator.DISTANCE, "heading_deg": compensator.HEADING,
            "frequency": compensator.W1, "heading_frequency": compensator.W2,
            "max_ahead": compensator.MAX_AHEAD, "max_astern": compensator.MAX_ASTERN,
            "max_yaw_moment": compensator.MAX_MOMENT}  # fmt: skip
SCALES = {"distance": 1.0, "heading_deg": 1.0, "frequency": 1e-3,
          "heading_frequency": 1e-3, "max_ahead": 1e4, "max_astern": 1e4,
          "max_yaw_moment": 1e6}  # fmt: skip
# the unit of each parameter, by its path's last name (``unit``)
UNITS = {"speed": "m/s", "towards_deg": "deg", "height": "m", "unstretched_length": "m",
         "stiffness": "N/m", "x": "m", "y": "m", "distance": "m", "heading_deg": "deg",
         "frequency": "rad/s", "heading_frequency": "rad/s", "max_ahead": "N",
         "max_astern": "N", "max_yaw_moment": "N m",
         **{f"force_{a}": "N" for a in "xyz"}, **{f"moment_{a}": "N m" for a in "xyz"}}  # fmt: skip


def unit(path: str) -> str:
    """The unit of the parameter at ``path`` (module docstring; "" for a path that is none)."""
    return UNITS.get(path.rsplit(".", 1)[-1], "")


def _refuse(path: str, why: str) -> CaseError:
    return CaseError(f"parameter '{path}': {why}; the parameters are {', '.join(FORMS)}")


def parameter(plane: Plane, path: str, weather: Weather | None = None,
              shared: dict | None = None) -> Parameter:  # fmt: skip
    """The parameter at ``path`` (module docstring) of ``plane``; ``weather`` is the weather
    whose one field a weather parameter changes (calm by default); ``shared``: the holder of
    that weather for two weather parameters varied together (``{"weather": weather}``), so
    that each keeps the other's field."""
    parts = path.split(".")
    if parts[0] in WEATHER and len(parts) == 2:
        return _weather(path, parts, weather or Weather(), shared)
    if parts[0] == "lines" and len(parts) == 3:
        return _tie(plane, path, parts)
    if parts[0] == "bodies" and len(parts) == 5:
        names = [b.name for b in plane.built.case.bodies]
        if parts[1] not in names:
            raise _refuse(path, f"no body '{parts[1]}' (bodies: {names})")
        if parts[2] == "points" and parts[4] in ("x", "y"):
            return _point(plane, path, parts)
        if parts[2] == "external forces" and parts[4] in (*applied.CHANNELS, *SETTINGS):
            return _load(plane, path, parts, names.index(parts[1]))
    raise _refuse(path, "not one of them")


def _weather(path: str, parts: list[str], weather: Weather, shared: dict | None) -> Parameter:
    names = WEATHER[parts[0]]
    if parts[1] not in names:
        raise _refuse(path, f"'{parts[1]}' is not {' or '.join(names)}")
    name = names[parts[1]]
    state = {"weather": weather} if shared is None else shared

    def set_weather(pl: Plane, value: float) -> None:
        state["weather"] = replace(state["weather"], **{name: value})
        state["weather"].apply(pl.built)

    return Parameter(path, set_weather, 10.0 if parts[1] == "towards_deg" else 1.0)


def _tie(plane: Plane, path: str, parts: list[str]) -> Parameter:
    built, p = plane.built, plane.built.params
    if parts[1] not in built.layout.ties:
        raise _refuse(path, f"no tie '{parts[1]}' (ties: {built.layout.ties})")
    k = built.layout.ties.index(parts[1])
    if parts[2] == "unstretched_length":

        def set_length(pl: Plane, value: float) -> None:
            pl.built.params.tie_length[k] = value

        return Parameter(path, set_length, max(float(p.tie_length[k]), 1.0) / 10.0)
    if parts[2] != "stiffness":
        raise _refuse(path, f"'{parts[2]}' is not unstretched_length or stiffness")
    if p.tie_count[k] > 0:
        raise _refuse(path, f"tie '{parts[1]}' follows a tension table")

    def set_stiffness(pl: Plane, value: float) -> None:
        pl.built.params.tie_stiffness[k] = value

    return Parameter(path, set_stiffness, float(p.tie_stiffness[k]) / 10.0)


def _point(plane: Plane, path: str, parts: list[str]) -> Parameter:
    key = f"{parts[1]}.{parts[3]}"
    if key not in plane.built.layout.point_index:
        raise _refuse(path, f"body '{parts[1]}' has no point '{parts[3]}' used by a line or a "
                      "model")  # fmt: skip
    i = plane.built.layout.point_index[key]
    axis = "xy".index(parts[4])

    def set_point(pl: Plane, value: float) -> None:
        pl.built.params.point_offset[i, axis] = value

    return Parameter(path, set_point, 10.0)


def _load(plane: Plane, path: str, parts: list[str], b: int) -> Parameter:
    p = plane.built.params
    models = getattr(plane.built.case.bodies[b], "external_forces", [])
    try:
        k = int(parts[3])
        spec = models[k]
    except (ValueError, IndexError):
        raise _refuse(path, f"body '{parts[1]}' has {len(models)} force models, counted "
                      f"from 0; '{parts[3]}' is none of them") from None  # fmt: skip
    rows = [f for f in range(p.force_body.shape[0]) if p.force_body[f] == b]
    if isinstance(spec, sf.Compensator) and parts[4] in SETTINGS:
        at = int(p.force_at[rows[k]]) + SETTINGS[parts[4]]
        unit = math.pi / 180.0 if parts[4] == "heading_deg" else 1.0  # the row's in radians

        def set_setting(pl: Plane, value: float) -> None:
            pl.built.params.force_data[at] = value * unit

        return Parameter(path, set_setting, SCALES[parts[4]])
    if not isinstance(spec, fm.AppliedForce) or parts[4] not in applied.CHANNELS:
        raise _refuse(path, f"force model {k} of '{parts[1]}' is '{spec.model}': no "
                      f"'{parts[4]}' there")  # fmt: skip
    channel = int(p.force_first[rows[k]]) + applied.CHANNELS.index(parts[4])

    def set_load(pl: Plane, value: float) -> None:
        set_constant(pl.built.params, channel, value)

    return Parameter(path, set_load, 1e4 if parts[4].startswith("force") else 1e6)
