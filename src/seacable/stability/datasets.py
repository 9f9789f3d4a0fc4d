"""What the horizontal-plane analyses' Datasets share: the case's own weather, the plane view
of a case, and the variables of poses, weather and hulls."""

import numpy as np

from seacable.case import loader
from seacable.case.base import Constant
from seacable.case.system import SystemCase
from seacable.errors import CaseError
from seacable.stability.plane import Plane, Weather


def weather_of(case: SystemCase) -> Weather:
    """The case's own weather: its uniform current and its constant wind (a CaseError line for
    a wind that changes in time)."""
    env = case.environment
    current = env.current
    speed = float(current.velocity or 0.0) if current is not None else 0.0
    towards = float(current.direction_deg) if current is not None else 0.0
    wind_speed, wind_towards = 0.0, 0.0
    if env.wind is not None:
        for name in ("speed", "direction_deg"):
            if not isinstance(getattr(env.wind, name), Constant):
                raise CaseError(f"environment.wind.{name}: a time function; the horizontal-plane "
                                "analyses take a constant wind: give a number")  # fmt: skip
        wind_speed = float(env.wind.speed.value)  # type: ignore[union-attr]
        wind_towards = float(env.wind.direction_deg.value)  # type: ignore[union-attr]
    return Weather(speed, towards, wind_speed, wind_towards)


def plane_of(case: SystemCase | str) -> Plane:
    """The plane view of ``case`` (a case or its file), refused with one line if it is not one
    the analyses take."""
    if isinstance(case, str):
        case = loader.load_case(case)
    if not isinstance(case, SystemCase):
        raise CaseError("the horizontal-plane analyses need a case with bodies: and lines:")
    return Plane.of(case, loader.case_base_dir(case))


def pose_variables(plane: Plane, xs: np.ndarray, dim: str) -> dict:
    """``x``, ``y`` [m] and ``heading`` [deg] per ``dim`` and ``body`` from the positions."""
    return {
        "x": ((dim, "body"), xs[:, 0::3], {"units": "m", "long_name": "reference point x"}),
        "y": ((dim, "body"), xs[:, 1::3], {"units": "m", "long_name": "reference point y"}),
        "heading": ((dim, "body"), np.degrees(xs[:, 2::3]),
                    {"units": "deg", "long_name": "heading, from +x towards +y"}),
    }  # fmt: skip


def weather_attrs(weather: Weather) -> dict:
    """The weather's fields (its waves' only when they differ from the case's)."""
    attrs = {
        "current_speed": weather.current_speed,
        "current_towards_deg": weather.current_towards_deg,
        "wind_speed": weather.wind_speed,
        "wind_towards_deg": weather.wind_towards_deg,
    }
    for name in ("wave_height", "wave_towards_deg"):
        if getattr(weather, name) is not None:
            attrs[name] = getattr(weather, name)
    return attrs


def hull_variables(plane: Plane) -> dict:
    """Each body's hull outline in its body frame (``Plane.hulls``; nan: no hull model)."""
    hulls = np.array([np.full((4, 2), np.nan) if h is None else h for h in plane.hulls()])
    unit = {"units": "m", "long_name": "hull outline, body frame"}
    return {"hull_x": (("body", "corner"), hulls[:, :, 0], unit),
            "hull_y": (("body", "corner"), hulls[:, :, 1], unit)}  # fmt: skip
