"""Line failures (the case's ``failures``: MoorDyn's FAILURE, OrcaFlex's release of a line's
end): the ends of some lumped-mass lines at a point let go during the run, at a time or when
the tension of one of them there first reaches a threshold, and stay joined to one another by
a free massless point (MoorDyn's, created at the failure).

Here that point is a point body named after the failure, in the system from the start (its
states and outputs exist throughout): held (no free degree of freedom) and joined to nothing
before the release, it sits where the ends are attached at the start. At the release, in the
compiled code after an accepted step (``system.evaluation``'s ``_failures``), its position and
velocity become those of the attachment point at that time, its three degrees of freedom are
freed, and the released ends are moved onto it (``line_from`` / ``line_to``); the ends' nodes
give it their mass. Every row of a failure is released together. The parameters' failure
rows are reset at each run's start (``start_memory``), so that a built system runs again from
intact lines.

One row per released line end: ``fail_line``, ``fail_end`` (0: its ``from`` end, 1: its
``to`` end), ``fail_group`` (the failure), ``fail_body`` and ``fail_point`` (the released ends'
point body and its point), ``fail_orig`` (the point they were attached to), ``fail_time`` [s]
and ``fail_tension`` [N] (inf: none), ``fail_state`` (NaN while attached, then the time of the
release [s]).
"""

import math

import numpy as np
from numba import njit

from seacable.case import system as sch
from seacable.kernels.jit import JIT, inner
from seacable.system import outputs

FIELDS = ("fail_line", "fail_end", "fail_group", "fail_body", "fail_point", "fail_orig",
          "fail_time", "fail_tension", "fail_state")  # fmt: skip
INT_FIELDS = FIELDS[:6]


def names(case: sch.SystemCase) -> list[str]:
    """Each failure's name (its released ends' point body)."""
    return [f.name or f"failure{k + 1}" for k, f in enumerate(case.failures)]


def derived(case: sch.SystemCase) -> sch.SystemCase:
    """The case with a massless, held point body per failure (named after it); the case
    itself without failures."""
    if not case.failures:
        return case
    extra = [
        sch.PointBody(name=name, type="point", position=(0.0, 0.0, 0.0), mass=0.0, dofs=[])
        for name in names(case)
    ]
    return case.model_copy(update={"bodies": [*case.bodies, *extra]})


def fields(case: sch.SystemCase, point) -> dict[str, np.ndarray]:
    """The failure rows (module docstring) of ``case`` (the derived one); ``point(ref,
    where)`` is the index of a point (system.assemble's, created on first use)."""
    rows: dict[str, list] = {name: [] for name in FIELDS}
    lines = {line.name: li for li, line in enumerate(_lumped(case))}
    for group, (failure, name) in enumerate(zip(case.failures, names(case), strict=True)):
        where = f"failures[{group}]"
        ends = failure.lines or [
            line.name for line in _lumped(case) if failure.at in (line.from_, line.to)
        ]
        for line_name in ends:
            line = _lumped(case)[lines[line_name]]
            rows["fail_line"].append(lines[line_name])
            rows["fail_end"].append(0 if line.from_ == failure.at else 1)
            rows["fail_group"].append(group)
            rows["fail_body"].append([b.name for b in case.bodies].index(name))
            rows["fail_point"].append(point(name, f"{where}.name"))
            rows["fail_orig"].append(point(failure.at, f"{where}.at"))
            rows["fail_time"].append(math.inf if failure.time is None else failure.time)
            rows["fail_tension"].append(math.inf if failure.tension is None else failure.tension)
            rows["fail_state"].append(math.nan)
    return {
        name: np.array(values, dtype=np.int64 if name in INT_FIELDS else float)
        for name, values in rows.items()
    }


def _lumped(case: sch.SystemCase) -> list[sch.LumpedMassLine]:
    """The lumped-mass lines in the order of the parameters' ``line_*`` rows."""
    return [line for line in case.lines if isinstance(line, sch.LumpedMassLine)]


def report(p, case: sch.SystemCase) -> dict[str, object]:
    """The results' attributes: each failure's release time [s] (NaN: not released) and one
    sentence for a person."""
    if not len(p.fail_line):
        return {}
    out: dict[str, object] = {}
    said = []
    for group, name in enumerate(names(case)):
        rows = [k for k in range(len(p.fail_line)) if p.fail_group[k] == group]
        when = float(p.fail_state[rows[0]])
        out[f"failure_{name}_time"] = when
        released = [_lumped(case)[int(p.fail_line[k])].name for k in rows]
        said.append(
            f"{name}: {', '.join(released)} released at t = {when:.6g} s"
            if math.isfinite(when)
            else f"{name}: not released"
        )
    out["failures"] = "; ".join(said)
    return out


def fill(times, states, p, w, rows) -> int:
    """``system.outputs.fill``, each row with the line ends attached as they were at its time
    (a row at or after a release sees the ends released): the outputs are evaluated after a
    chunk, with the parameters as the chunk left them. The parameters are as they were when it
    returns. The worst kernel status met."""
    released = p.fail_state
    events = np.unique(released[np.isfinite(released)]) if len(p.fail_line) else np.empty(0)
    if not len(events):
        return outputs.fill(times, states, p, w, rows)
    kept = (p.line_from.copy(), p.line_to.copy(), p.body_free.copy())
    worst = 0
    edges = [0, *np.searchsorted(times, events, side="left"), len(times)]
    try:
        for start, end in zip(edges[:-1], edges[1:], strict=True):
            if end <= start:
                continue
            p.line_from[:], p.line_to[:], p.body_free[:] = kept
            for k in range(len(p.fail_line)):  # attached again where released after the rows
                if not released[k] <= times[start]:
                    b, line = int(p.fail_body[k]), int(p.fail_line[k])
                    p.body_free[b, :3] = 0.0
                    ends = p.line_from if p.fail_end[k] == 0 else p.line_to
                    ends[line] = p.fail_orig[k]
            cut: list = [
                tuple(a[start:end] for a in r) if isinstance(r, tuple) else r[start:end]
                for r in rows
            ]
            part = outputs.Rows(*cut)
            worst = max(worst, outputs.fill(times[start:end], states[start:end], p, w, part))
    finally:
        p.line_from[:], p.line_to[:], p.body_free[:] = kept
    return worst


@inner
def release(t, y, p, w, k):
    """Failure row k's end onto its point body, placed and moving as the point it leaves (in
    ``y`` and the parameters; ``w``: the points at (t, y)), at time ``t`` [s]."""
    b, old = p.fail_body[k], p.fail_orig[k]
    for c in range(3):
        y[p.body_q[b] + c] = w.ppos[old, c]
        y[p.body_v[b] + c] = w.pvel[old, c]
        p.body_free[b, c] = 1.0
    attach(p, k, p.fail_point[k])
    p.fail_state[k] = t


@njit(inline="always", **JIT)
def attach(p, k, point):
    """Failure row k's line end at ``point``."""
    if p.fail_end[k] == 0:
        p.line_from[p.fail_line[k]] = point
    else:
        p.line_to[p.fail_line[k]] = point
