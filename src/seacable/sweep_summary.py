"""A sweep's summary (seacable.sweep): its load cases (``Plan``, ``LoadCase``), each run's row
(``summarise``: what an engineer reads first of a run) and the Dataset of the rows over the
sweep's dimensions (``dataset``), with each line's envelope, its fatigue damage a year over the
load cases' shares of the time and, with three seeds or more, a Gumbel estimate of the storm's
largest tension."""

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import xarray as xr

from seacable import fatigue, files
from seacable import stats as st
from seacable.case import loader
from seacable.case.sweep import Sweep
from seacable.case.system import SystemCase
from seacable.results import Results
from seacable.system import utilisation

# a load case's status in the summary
COMPLETE, DIVERGED, FAILED, REFUSED, NOT_RUN = (
    "complete", "diverged", "failed", "refused", "not run")  # fmt: skip
STATUSES = (COMPLETE, DIVERGED, FAILED, REFUSED, NOT_RUN)
DOFS = ("x", "y", "z", "roll", "pitch", "yaw")
_BODY_KEYS = ("position_x", "position_y", "position_z", "roll", "pitch", "yaw")
TITLE = "seacable sweep summary"


@dataclass
class LoadCase:
    """One run of a sweep: where it sits in the summary (``index`` along ``Plan.dims``), its
    label (``significant_height=4, seed=2``), the case's mapping, the run's file name, and the
    reason the case refused these values (then no data)."""

    index: tuple[int, ...]
    label: str
    data: dict | None = None
    file: str = ""
    refused: str = ""


@dataclass
class Plan:
    """A sweep's load cases: ``dims`` maps each dimension to its values (the summary's
    coordinates), ``along`` each variation without a dimension to (its dimension, its values),
    ``probability`` the load cases' shares of the time (None unless every dimension has them)."""

    case: SystemCase
    sweep: Sweep
    dims: dict[str, list] = field(default_factory=dict)
    along: dict[str, tuple[str, list]] = field(default_factory=dict)
    cases: list[LoadCase] = field(default_factory=list)
    probability: np.ndarray | None = None

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(v) for v in self.dims.values())


def shown(value) -> str:
    """A value as a label shows it (numbers in their shortest form)."""
    return f"{value:g}" if isinstance(value, float) else str(value)


def status_row(status: str, message: str) -> dict:
    """A row of a run with no figures: its status and message."""
    return {"status": status, "message": message, "lines": {}, "bodies": {}}


def summarise(results: Results, case: SystemCase, storm: float) -> dict:
    """A run's summary row, from the end of its build-up on (``simulation.build_up``: the ramp
    that starts its waves is left out; stats.steady): its status and message; per line
    (``lines``: name -> values) the largest and least tension over the run and the line, and
    at its more loaded end the mean,
    standard deviation and most probable largest of a ``storm`` [s] (Rayleigh's, NaN for a
    run too short to cross its mean twice), the largest tension's share of the sections'
    breaking strengths (NaN without one); per moving body (``bodies``) the largest horizontal
    offset from its start and each motion's largest, least and standard deviation. A run that
    did not complete has its status and no figures."""
    row = status_row(results.status, results.message)
    if results.status != COMPLETE:
        return row
    tree = results.dataset
    t = np.asarray(tree["time"].values, dtype=float)
    kept = st.steady(t, case.simulation.build_up)
    lines = tree["lines"].children if "lines" in tree.children else {}
    tensions = {name: np.asarray(node["tension"].values, float).reshape(len(t), -1)[kept]
                for name, node in lines.items() if "tension" in node}  # fmt: skip
    t = t[kept]
    row["duration"] = float(t[-1] - t[0])
    shares: dict[str, list[float]] = {}
    for load in utilisation.section_loads(case, tensions):
        if load.utilisation is not None:
            shares.setdefault(load.line, []).append(load.utilisation)
    for name, tension in tensions.items():
        ends = tension[:, [0, -1]]
        which = int(np.argmax(ends.mean(axis=0)))
        end = ends[:, which]
        s = st.summary(t, end, storm)
        row["lines"][name] = {
            "tension_max": float(np.max(tension)), "tension_min": float(np.min(tension)),
            "tension_mean": s.mean, "tension_std": s.std, "tension_mpm": s.mpm,
            "utilisation": max(shares.get(name, [math.nan])),
            "damage": _damage(case, name, which, end),
        }  # fmt: skip
    bodies = tree["bodies"].children if "bodies" in tree.children else {}
    for name, node in bodies.items():
        whole = np.stack([np.asarray(node[k].values, float) if k in node
                          else np.zeros(len(kept)) for k in _BODY_KEYS], axis=1)  # fmt: skip
        if not np.ptp(whole, axis=0).any():
            continue  # fixed, or held still
        motion = whole[kept]  # the offset from where the body starts (t = start)
        offset = np.hypot(motion[:, 0] - whole[0, 0], motion[:, 1] - whole[0, 1])
        row["bodies"][name] = {
            "offset_max": float(offset.max()), "motion_max": motion.max(axis=0).tolist(),
            "motion_min": motion.min(axis=0).tolist(), "motion_std": motion.std(axis=0).tolist(),
        }  # fmt: skip
    return row


def _damage(case: SystemCase, name: str, which: int, tension: np.ndarray) -> float:
    """Miner's damage of a line's end (``which``: 0 its 'from' end, 1 its 'to' end) on the
    fatigue curve of the line type of the section there (NaN without one)."""
    line = next((line for line in case.lines if line.name == name), None)
    sections = getattr(line, "sections", None)
    if not sections:
        return math.nan
    kind = next(t for t in case.line_types if t.name == sections[-which].type)
    return fatigue.damage(tension, kind)


def dataset(todo: Plan, rows: dict[tuple, dict], runs: str = "") -> xr.Dataset:
    """The summary of ``rows`` (load case index -> ``summarise``'s row with ``file`` and
    ``seconds``) over ``todo``'s dimensions, its runs in the folder ``runs``; a load case
    without a row is ``not run``."""
    dims, shape = tuple(todo.dims), todo.shape
    lines = [line.name for line in todo.case.lines]
    bodies = [b.name for b in todo.case.bodies if any(b.name in r["bodies"] for r in rows.values())]
    status = np.full(shape, NOT_RUN, dtype=object)
    message = np.full(shape, "", dtype=object)
    run_files = np.full(shape, "", dtype=object)
    seconds = np.full(shape, math.nan)
    durations = np.full(shape, math.nan)  # [s] simulated by each complete run
    per_line = {k: np.full((*shape, len(lines)), math.nan) for k in _LINE_KEYS}
    offset = np.full((*shape, len(bodies)), math.nan)
    motion = {k: np.full((*shape, len(bodies), len(DOFS)), math.nan) for k in _MOTION_KEYS}
    for index, row in rows.items():
        status[index], message[index] = row["status"], row["message"]
        run_files[index], seconds[index] = row.get("file", ""), row.get("seconds", math.nan)
        durations[index] = row.get("duration", math.nan)
        for i, name in enumerate(lines):
            for key, values in per_line.items():
                values[(*index, i)] = row["lines"].get(name, {}).get(key, math.nan)
        for j, name in enumerate(bodies):
            if name in row["bodies"]:
                offset[(*index, j)] = row["bodies"][name]["offset_max"]
                for key, values in motion.items():
                    values[(*index, j)] = row["bodies"][name][key]
    line_dims, body_dims = (*dims, "line"), (*dims, "body")
    data: dict[str, Any] = {
        "status": (dims, status.astype(str), {"long_name": "the run's status",
                                              "values": ", ".join(STATUSES)}),
        "message": (dims, message.astype(str), {"long_name": "the run's status message"}),
        "file": (dims, run_files.astype(str), {"long_name": "its results, in the runs folder"}),
        "seconds": (dims, seconds, {"units": "s", "long_name": "the run's wall time"}),
        **{key: (line_dims, values, _LINE_KEYS[key]) for key, values in per_line.items()},
        "offset_max": (body_dims, offset, {"units": "m", "long_name":
                       "largest horizontal distance from the body's start"}),
        **{key: ((*body_dims, "dof"), values, _MOTION_KEYS[key])
           for key, values in motion.items()},
    }  # fmt: skip
    if todo.probability is not None:
        data["probability"] = (dims, todo.probability, {"long_name": "the load case's share "
                                                        "of the time"})  # fmt: skip
    if todo.probability is not None and np.isfinite(per_line["damage"]).any():
        data |= _lives(todo.probability, per_line["damage"], durations)
    if len(todo.dims.get("seed", ())) >= 3:
        data["tension_gumbel_mpm"] = _gumbel(todo, per_line["tension_max"], durations)
    coords: dict[str, Any] = {d: (d, _coordinate(v)) for d, v in todo.dims.items()}
    coords |= {name: (d, _coordinate(v)) for name, (d, v) in todo.along.items()}
    coords |= {"line": ("line", np.array(lines, dtype=str)),
               "body": ("body", np.array(bodies, dtype=str)),
               "dof": ("dof", np.array(DOFS, dtype=str))}  # fmt: skip
    paths = {v.label: v.path for v in todo.sweep.vary}
    found = xr.Dataset(data, coords=coords)
    for name, path in paths.items():
        found[name].attrs["path"] = path
    from seacable import __version__

    return found.assign_attrs(
        title=TITLE, seacable_version=__version__, case_name=todo.case.name,
        case=loader.case_text(todo.case), storm=todo.sweep.storm,
        runs=runs, statuses=", ".join(STATUSES),
        counts="; ".join(f"{n} {int(np.sum(status == n))}" for n in STATUSES
                         if np.any(status == n)),
        motion_units="x, y, z in m; roll, pitch, yaw in deg",
        statistics_from="each run's build-up on (simulation.build_up); the offsets from where "
        "each body starts",
    )  # fmt: skip


_LINE_KEYS = {
    "tension_max": {"units": "N", "long_name": "largest tension over the run and the line"},
    "tension_min": {"units": "N", "long_name": "least tension over the run and the line"},
    "tension_mean": {"units": "N", "long_name": "mean tension at the line's more loaded end"},
    "tension_std": {"units": "N", "long_name": "standard deviation of that end's tension"},
    "tension_mpm": {"units": "N", "long_name": "most probable largest tension of that end "
                    "over the storm (Rayleigh's law of the peaks)"},
    "utilisation": {"units": "1", "long_name": "largest tension over the breaking strength "
                    "(the largest share of the line's sections)"},
    "damage": {"units": "1", "long_name": "Miner's fatigue damage of the run at the line's "
               "more loaded end, on its line type's curve"},
}  # fmt: skip
_MOTION_KEYS = {
    "motion_max": {"long_name": "largest value of each motion"},
    "motion_min": {"long_name": "least value of each motion"},
    "motion_std": {"long_name": "standard deviation of each motion"},
}


class Envelope(NamedTuple):
    """A line's largest tension over a sweep's complete runs [N], its utilisation there, the
    largest most probable largest tension of the runs [N] (NaN without one) and where the
    largest tension is (``significant_height=4, seed=2``)."""

    line: str
    tension: float
    utilisation: float
    mpm: float
    at: str


def envelope(found: xr.Dataset) -> list[Envelope]:
    """Each line's envelope over a sweep's summary (the lines no run completed left out)."""
    out = []
    for line in found["line"].values:
        tension = found["tension_max"].sel(line=line)
        if not np.isfinite(tension.values).any():
            continue
        where = np.unravel_index(int(np.nanargmax(tension.values)), tension.shape)
        at = ", ".join(f"{d}={shown(found[d].values[k].item())}"
                       for d, k in zip(tension.dims, where, strict=True))  # fmt: skip
        mpm = found["tension_mpm"].sel(line=line).values
        out.append(Envelope(str(line), float(tension.values[where]),
                            float(found["utilisation"].sel(line=line).values[where]),
                            float(np.nanmax(mpm)) if np.isfinite(mpm).any() else math.nan,
                            at))  # fmt: skip
    return out


def _lives(probability: np.ndarray, damage: np.ndarray, durations: np.ndarray) -> dict:
    """Each line's damage a year over the sweep's load cases, each for its share of the time
    (sum of p d year / duration), and the fatigue life it gives; NaN when a load case of a
    share above zero has no damage (it did not complete, or the line has no curve)."""
    rate = damage * fatigue.SECONDS_PER_YEAR / durations[..., None]
    weight = np.broadcast_to(probability[..., None], rate.shape)
    parts = np.where(weight > 0.0, weight * rate, 0.0)
    annual = parts.reshape(-1, rate.shape[-1]).sum(axis=0)
    life = np.divide(1.0, annual, out=np.full_like(annual, math.inf), where=annual > 0.0)
    life[np.isnan(annual)] = math.nan  # no damage known: no life either
    return {
        "annual_damage": (("line",), annual, {"units": "1/year", "long_name": "fatigue damage "
                          "a year: the load cases' damages, each for its share of the time"}),
        "fatigue_life": (("line",), life, {"units": "year", "long_name": "1 / annual_damage "
                         "(no design factor)"}),
    }  # fmt: skip


def _gumbel(todo: Plan, largest: np.ndarray, durations: np.ndarray) -> tuple:
    """Per load case but the seed, per line: the most probable largest tension over the storm
    from a Gumbel law fitted to the seeds' largest tensions (stats.gumbel_mpm; NaN where fewer
    than three seeds completed)."""
    axis = list(todo.dims).index("seed")
    moved = np.moveaxis(largest, axis, -2)  # (..., seed, line)
    spans = np.moveaxis(durations, axis, -1)  # (..., seed)
    out = np.full(moved.shape[:-2] + moved.shape[-1:], math.nan)
    for index in np.ndindex(*moved.shape[:-2]):
        for j in range(moved.shape[-1]):
            maxima, span = moved[index + (slice(None), j)], spans[index]
            done = np.isfinite(maxima) & np.isfinite(span)
            if done.sum() >= 3:
                out[index + (j,)] = st.gumbel_mpm(maxima[done], float(np.mean(span[done])),
                                                  todo.sweep.storm)  # fmt: skip
    dims = tuple(d for d in todo.dims if d != "seed") + ("line",)
    return dims, out, {"units": "N", "long_name": "most probable largest tension over the storm "
                       "from a Gumbel law fitted to the seeds' largest tensions"}  # fmt: skip


def _coordinate(values: list) -> np.ndarray:
    """A dimension's values as a coordinate: numbers as numbers, anything else as its text."""
    if all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=float)
    return np.array([shown(v) for v in values], dtype=str)


def write(found: xr.Dataset, output: Path) -> None:
    """The summary to ``output`` (NetCDF, or Zarr for .zarr), written aside then moved in: an
    interrupted write leaves the previous summary whole."""
    with files.replacing(output) as aside:
        if output.suffix.lower() == ".zarr":
            found.to_zarr(aside, mode="w", zarr_format=2)  # its text arrays have a specification
        else:
            found.to_netcdf(aside, engine="h5netcdf")
