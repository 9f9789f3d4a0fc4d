"""The ships in one weather without and with their compensators, side by side
(``seacable.compare``): each run from the nominal places on the analyses' RK4 flow, its rows,
and a verdict against the operator's limits."""

import math

import numpy as np
import xarray as xr

from seacable.case.system import SystemCase
from seacable.errors import CaseError
from seacable.stability import equilibria as eq
from seacable.stability import operability, orbits
from seacable.stability.datasets import (
    hull_variables,
    plane_of,
    weather_attrs,
    weather_of,
)
from seacable.stability.operability import CONTROLS, Limits
from seacable.stability.plane import Plane, Weather

STARTS = ("nominal", "case")  # where the ships start (``compare``)


def compare(case: SystemCase | str, weather: Weather | None = None,
            duration: float | None = None, step: float = 1.0, every: float = 10.0,
            limits: Limits | None = None, start: str = "nominal",
            headings: int = 12) -> xr.Dataset:  # fmt: skip
    """The ships in ``weather`` (the case's by default) without and with their compensator
    (forces.compensator), side by side: each run for ``duration`` [s] (default the case's),
    on the RK4 flow of ``step`` [s] split at the ties' kinks (seacable.stability.orbits), a
    row every ``every`` [s]; ``limits``: the operator's (seacable.stability.operability.Limits;
    none by default). ``start`` (``STARTS``): "nominal", the ships at rest at their nominal
    places (as the case puts them relative to each other) around the first ship at its
    equilibrium in that weather, with the compensator as in the run (the one an operability
    map keeps, found as it finds them with ``headings`` per body:
    ``operability.nominal_start``): the same start as the map's, so the two agree; or "case",
    the ships as the case places them (its headings were chosen for its own weather).

    Returns
    -------
    xarray.Dataset
        Per ``control`` (uncontrolled, controlled), ``time`` and ``body``: ``x``, ``y`` [m],
        ``heading`` [deg]; per control and time: ``tension`` and ``distance`` per ``tie``
        [N, m], ``clearance`` [m] (the first two hulls' outlines), ``surge_force`` [N] and
        ``yaw_moment`` [N m] (the compensator's, applied), ``surge_demand``, ``yaw_demand``
        (before saturation); per control: ``verdict`` (safe, limit exceeded, collision risk,
        diverged), ``message``, ``least_clearance`` [m], ``peak_tension`` per tie [N],
        ``peak_surge_force`` [N], ``peak_yaw_moment`` [N m], ``saturated`` (the fraction of
        rows where the limits cut the demand); per ``body`` and ``corner``: ``hull_x``,
        ``hull_y`` [m], its outline in its body frame (nan: no hull model).
    """
    plane = plane_of(case)
    if plane.controlled is None:
        raise CaseError("compare: no ship has a 'compensator' force model; add one ({model: "
                        "compensator, point, target, distance}) to compare the ships with and "
                        "without it")  # fmt: skip
    weather = weather or weather_of(plane.built.case)
    weather.apply(plane.built)
    limits = limits or Limits()
    duration = float(duration if duration is not None else plane.built.case.simulation.duration)
    steps = max(1, math.ceil(duration / step))
    stride = max(1, round(every / (duration / steps)))
    if start not in STARTS:
        raise CaseError(f"compare: start '{start}': give one of {', '.join(STARTS)}")
    was = plane.controlled
    runs = []
    try:
        for enabled in (False, True):
            plane.control(enabled)
            x0 = plane.start() if start == "case" else _nominal(plane, weather, headings)
            runs.append(_run(plane, x0, duration, steps, stride, limits))
    finally:
        plane.control(bool(was))
    rows = min(len(r["time"]) for r in runs)
    ties = list(plane.built.layout.ties)

    def stack(name):
        return np.stack([r[name][:rows] for r in runs])

    per_time = {"tension": ("tie", "N"), "distance": ("tie", "m"), "clearance": (None, "m"),
                "surge_force": (None, "N"), "yaw_moment": (None, "N m"),
                "surge_demand": (None, "N"), "yaw_demand": (None, "N m")}  # fmt: skip
    data: dict = {
        name: (("control", "time") + ((dim,) if dim else ()), stack(name), {"units": unit})
        for name, (dim, unit) in per_time.items()
    }
    for name, unit in (("x", "m"), ("y", "m"), ("heading", "deg")):
        data[name] = (("control", "time", "body"), stack(name), {"units": unit})
    for name, unit in (("least_clearance", "m"), ("peak_surge_force", "N"),
                       ("peak_yaw_moment", "N m"), ("saturated", "1")):  # fmt: skip
        data[name] = ("control", np.array([r[name] for r in runs]), {"units": unit})
    data["peak_tension"] = (("control", "tie"), np.stack([r["peak_tension"] for r in runs]),
                            {"units": "N"})  # fmt: skip
    data.update(hull_variables(plane))
    data["verdict"] = ("control", np.array([r["verdict"] for r in runs], dtype=str))
    data["message"] = ("control", np.array([r["message"] for r in runs], dtype=str))
    return xr.Dataset(
        data,
        coords={"control": list(CONTROLS), "time": runs[0]["time"][:rows],
                "body": plane.names, "tie": ties},  # fmt: skip
        attrs={**weather_attrs(weather), "duration": duration, "step": duration / steps,
               "start": start,
               "clearance_limit": limits.clearance,
               "tension_limits": "; ".join(f"{t} {v:g} N" for t, v in limits.tension)},
    )  # fmt: skip


def _nominal(plane: Plane, weather: Weather, headings: int) -> np.ndarray:
    """``compare``'s "nominal" start: the ships at rest at their nominal places around the
    first ship at the equilibrium an operability map keeps."""
    nominal = eq.relative(plane, plane.start()[: 3 * len(plane.bodies)])
    found = operability.search(plane, headings)
    best, _ = operability.kept(plane, found, nominal, weather.calm(plane.built))
    if best is None:
        raise CaseError(
            "compare: the search found no equilibrium in this weather to start "
            "the ships around; start them as the case places them: start 'case'"
        )
    return operability.nominal_start(plane, best, nominal)


def _run(plane: Plane, x0: np.ndarray, duration: float, steps: int, stride: int,
         limits: Limits) -> dict:  # fmt: skip
    """One run's rows (``compare``) from ``x0``; a run that leaves finite values keeps the
    rows before."""
    n, ties = len(plane.bodies), list(plane.built.layout.ties)
    try:
        _, path = orbits.integrate(plane, x0, duration, steps, record=True)
        diverged = ""
    except FloatingPointError:  # rerun in pieces to keep what was finite
        path, diverged = _finite_part(plane, x0, duration, steps), "the motion left finite values"
    path = path[::stride]
    m = path.shape[0]
    out: dict = {"time": np.arange(m) * stride * duration / steps,
                 "tension": np.empty((m, len(ties))), "distance": np.empty((m, len(ties))),
                 "clearance": np.full(m, math.nan)}  # fmt: skip
    control = np.zeros((m, 4))
    p = plane.built.params
    for i, state in enumerate(path):
        plane.rates(state)
        out["tension"][i] = plane.work.tie_tension
        for k in range(len(ties)):
            a, b = p.tie_from[k], p.tie_to[k]
            out["distance"][i, k] = np.linalg.norm(plane.work.ppos[b] - plane.work.ppos[a])
        if p.compensator.shape[0]:
            control[i] = plane.work.control[0]
        out["clearance"][i] = operability.clearance_at(plane, state[: 3 * n])
    for k, name in enumerate(("surge_force", "yaw_moment", "surge_demand", "yaw_demand")):
        out[name] = control[:, k]
    out["x"], out["y"] = path[:, 0 : 3 * n : 3], path[:, 1 : 3 * n : 3]
    out["heading"] = np.degrees(path[:, 2 : 3 * n : 3])
    out["least_clearance"] = float(np.nanmin(out["clearance"])) if m else math.nan
    out["peak_tension"] = out["tension"].max(axis=0) if m else np.zeros(len(ties))
    out["peak_surge_force"] = float(np.abs(control[:, 0]).max()) if m else 0.0
    out["peak_yaw_moment"] = float(np.abs(control[:, 1]).max()) if m else 0.0
    cut = (control[:, 0] != control[:, 2]) | (control[:, 1] != control[:, 3])
    out["saturated"] = float(cut.mean()) if m else 0.0
    out["verdict"], out["message"] = _verdict(out, ties, limits, diverged)
    return out


def _finite_part(plane: Plane, x0: np.ndarray, duration: float, steps: int) -> np.ndarray:
    """The states of the flow from ``x0`` up to where it stopped being finite (in pieces of
    100 steps)."""
    h = duration / steps
    x = x0
    kept = [x[None, :]]
    for first in range(0, steps, 100):
        count = min(100, steps - first)
        try:
            x, path = orbits.integrate(plane, x, count * h, count, record=True)
        except FloatingPointError:
            break
        kept.append(path[1:])
    return np.concatenate(kept)


def _verdict(run: dict, ties: list[str], limits: Limits, diverged: str) -> tuple[str, str]:
    if diverged:
        return "diverged", diverged
    least = run["least_clearance"]
    if least < max(limits.clearance, 0.0) or least == 0.0:
        return "collision risk", f"hulls {least:.1f} m apart (limit {limits.clearance:g} m)"
    for tie, limit in limits.tension:
        peak = float(run["peak_tension"][ties.index(tie)])
        if peak > limit:
            return "limit exceeded", f"tie {tie} at {peak / limit:.2f} times its tension limit"
    return "safe", ""
