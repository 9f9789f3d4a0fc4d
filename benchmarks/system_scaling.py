"""Cost of a system of bodies and lines against its size (issue 14): 10 bodies with 20, 40 and 80
lumped-mass lines of 100 segments each (2,000, 4,000 and 8,000 segments).

The system, generated here (a dict given to ``seacable.load_case``): 10 subsurface point buoys
on a ring of radius 200 m at 20 m depth in 100 m of water, each joined to its two neighbours by a
130 m wire (10 ring lines, 124 m apart: a coupled system, not 10 copies) and moored by k chain
legs of 200 m to anchors on the seabed 160 m away, spread evenly around it (k = 1, 3, 7 gives 20,
40, 80 lines). Each buoy's volume grows with its legs (net buoyancy about 51 kN per leg and 10 kN
for its share of the ring). The run starts as given (``start: as_given``: buoys where the case
puts them, each line at its static shape between them), so no statics of the whole is needed.

For each size, in this process (one thread, kernels compiled or loaded before timing):

* start-up: ``seacable.system.model.build`` (the lines' static shapes with the bodies held);
* rhs: the compiled right-hand side ``system.kernel.rhs`` called in a Python loop after a
  warm-up, the median over ``--repeat`` loops of the time per call (each call also pays the
  dispatch of its arguments from Python, a constant);
* step: rk4 at a fixed 0.1 ms step (below rk4's limit for the 1.3 m ring segments' axial waves)
  in the compiled loop ``seacable.simulate`` runs (``numerics.integrators.rk4_chunk``), from the
  start state, median over ``--repeat`` runs of ``--steps`` steps, with its work counters (rhs
  evaluations per step);
* simulate: one whole ``seacable.simulate`` of ``--steps`` rk4 steps, start-up and output
  included, and that time per accepted step (results' attribute ``solver_accepted_steps``);
* statics: ``seacable.statics`` of the same case (``start: static``: the lines' shapes, then
  Newton over every coordinate, which fails here, then over the buoys with the lines settled,
  ``system.nested``), start-up and output row included; its time, or its failure, and the
  largest force left on a buoy recomputed from its lines' end loads and its net lift.

Printed: cost per step, per segment per step, and their ratios to the smallest case (linear
growth: a constant cost per segment). Times are wall times (perf_counter) of single-threaded
work; the load average is printed with the table. Run with OPENBLAS_NUM_THREADS=1:
``python benchmarks/system_scaling.py [--sizes 20 40 80] [--repeat N] [--steps N] [--no-statics]``.
"""

import argparse
import math
import os
import statistics
import time

import numpy as np

import seacable
from seacable.numerics import integrators
from seacable.system import kernel, model, statics
from seacable.system.statics import StaticsError

BODIES, SEGMENTS = 10, 100
DEPTH, RING_RADIUS, BUOY_Z = 100.0, 200.0, -20.0  # [m]
LEG_LENGTH, LEG_SPAN, LINK_LENGTH = 200.0, 160.0, 130.0  # [m]
NET_PER_LEG, NET_RING = 51.0e3, 10.0e3  # [N] buoy net buoyancy per leg, for its ring share
TIME_STEP = 1.0e-4  # [s] rk4
CHAIN = {
    "name": "chain", "diameter": 0.1, "mass_per_length": 60.0, "axial_stiffness": 3.0e8,
    "axial_damping_ratio": 0.8, "drag_coefficient_normal": 2.4, "drag_coefficient_tangential": 0.4,
}  # fmt: skip
WIRE = {
    "name": "wire", "diameter": 0.05, "mass_per_length": 10.0, "axial_stiffness": 2.0e8,
    "axial_damping_ratio": 0.8, "drag_coefficient_normal": 1.2,
}  # fmt: skip


def _buoy(i: int, legs: int, buoys: int, damping: float) -> dict:
    angle = 2 * math.pi * i / buoys
    radius = RING_RADIUS * (math.sin(math.pi / BODIES) / math.sin(math.pi / buoys))  # one chord
    rho, g = 1025.0, 9.81
    volume = round((NET_PER_LEG * legs + NET_RING) / (0.7 * rho * g), 1)  # mass 0.3 rho V
    forces = [
        {"model": "gravity"}, {"model": "buoyancy"},
        {"model": "drag", "drag_coefficient": 0.5, "area": 10.0},
    ]  # fmt: skip
    if damping:
        forces.append({"model": "linear_damping", "diagonal": [damping] * 3 + [0.0] * 3})
    return {
        "name": f"buoy_{i}", "type": "point",
        "position": [radius * math.cos(angle), radius * math.sin(angle), BUOY_Z],
        "mass": 0.3 * rho * volume, "volume": volume, "added_mass": 0.5 * rho * volume,
        "external forces": forces,
    }  # fmt: skip


def system(lines: int, start: str = "as_given", duration: float = 0.01, buoys: int = BODIES,
           segments: int = SEGMENTS, damping: float = 0.0) -> dict:  # fmt: skip
    """The case mapping of the ring of ``buoys`` buoys (its ring lines one chord long whatever
    their number: the ring's radius scales) with ``lines`` lines in all, each of ``segments``
    segments; ``damping`` [N s/m] a linear damper on every buoy's translations (none at rest:
    the statics is the same)."""
    legs, extra = divmod(lines - buoys, buoys)
    if extra or legs < 1:
        raise SystemExit(f"lines must be {buoys} ring lines + a multiple of {buoys}; got {lines}")
    bodies, all_lines = [], []
    for i in range(buoys):
        buoy = _buoy(i, legs, buoys, damping)
        bodies.append(buoy)
        x, y, _ = buoy["position"]
        for k in range(legs):
            phi = 2 * math.pi * (i / buoys + k / legs)
            anchor = f"anchor_{i}_{k}"
            bodies.append({
                "name": anchor, "type": "fixed",
                "position": [x + LEG_SPAN * math.cos(phi), y + LEG_SPAN * math.sin(phi), -DEPTH],
            })  # fmt: skip
            all_lines.append({
                "name": f"leg_{i}_{k}", "model": "lumped_mass", "from": anchor, "to": buoy["name"],
                "sections": [{"type": "chain", "length": LEG_LENGTH, "segments": segments}],
            })  # fmt: skip
    for i in range(buoys):
        all_lines.append({
            "name": f"link_{i}", "model": "lumped_mass",
            "from": f"buoy_{i}", "to": f"buoy_{(i + 1) % buoys}",
            "sections": [{"type": "wire", "length": LINK_LENGTH, "segments": segments}],
        })  # fmt: skip
    return {
        "name": f"ring of {buoys} buoys, {lines} lines of {segments} segments",
        "start": start,
        "environment": {
            "water_depth": DEPTH,
            "seabed": {"stiffness": 1.0e5, "damping": 1.0e3, "friction_coefficient": 0.5},
        },
        "bodies": bodies,
        "line_types": [CHAIN, WIRE],
        "lines": all_lines,
        "simulation": {
            "duration": duration, "output_interval": duration, "integrator": "rk4",
            "time_step": TIME_STEP,
        },
    }  # fmt: skip


def time_rhs(built, repeat: int) -> float:
    """Median time of one compiled rhs call [s]."""
    p, y = built.params, built.y0
    work, ydot = kernel.make_work(p), np.zeros_like(y)
    for _ in range(5):
        kernel.rhs(0.0, y, p, work, ydot)
    calls = max(20, 400_000 // int(p.line_n.sum()))
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(calls):
            kernel.rhs(0.0, y, p, work, ydot)
        times.append((time.perf_counter() - start) / calls)
    return statistics.median(times)


def time_steps(built, steps: int, repeat: int) -> tuple[float, float]:
    """(median time of one rk4 step [s], rhs evaluations per step) of the compiled loop
    ``simulate`` runs (``integrators.rk4_chunk``), ``steps`` steps from the start state."""
    p = built.params
    w = kernel.make_work(p)
    states, times = np.empty((1, len(built.y0))), np.empty(1)
    warm_up = np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
    integrators.rk4_chunk(0, built.y0.copy(), TIME_STEP, 1, 1, p, w, states, times, warm_up)
    elapsed = []
    for _ in range(repeat):
        y, work = built.y0.copy(), np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
        start = time.perf_counter()
        integrators.rk4_chunk(0, y, steps * TIME_STEP, steps, steps, p, w, states, times, work)
        elapsed.append((time.perf_counter() - start) / steps)
        if not np.all(np.isfinite(y)):
            raise SystemExit("the rk4 steps diverged: lower TIME_STEP")
    counters = dict(zip(integrators.WORK_NAMES, work, strict=True))
    return statistics.median(elapsed), counters["rhs_evaluations"] / counters["accepted_steps"]


def run(lines: int, steps: int) -> tuple[float, int, int]:
    """(wall time [s], accepted steps, rhs evaluations) of ``seacable.simulate``, rk4, ``steps``
    steps: the whole run, start-up (the lines' static shapes) and output included."""
    case = seacable.load_case(system(lines, duration=steps * TIME_STEP))
    start = time.perf_counter()
    results = seacable.simulate(case)
    elapsed = time.perf_counter() - start
    attrs = results.dataset.attrs
    if not results.complete:
        raise SystemExit(f"{lines} lines: the run did not complete: {results.message}")
    return elapsed, int(attrs["solver_accepted_steps"]), int(attrs["solver_rhs_evaluations"])


def time_statics(lines: int) -> tuple[float, str]:
    """(wall time [s] of ``seacable.statics``, its outcome): converged, with the largest force
    [N] left on a buoy recomputed from its lines' end loads at rest (``statics.line_loads``)
    and its own buoyancy less its weight, against its net buoyancy; or its failure."""
    case = seacable.load_case(system(lines, start="static"))
    start = time.perf_counter()
    try:
        seacable.statics(case)
    except StaticsError as exc:
        return time.perf_counter() - start, "FAILED: " + str(exc).split("; ")[-1].split(". ")[0]
    elapsed = time.perf_counter() - start
    built = model.build(case)  # the same balance, for the check
    loads = statics.line_loads(built, built.y0, at_rest=True)
    worst, net = 0.0, 0.0
    for b, body in enumerate(built.case.bodies):
        if body.type == "point":
            lift = (built.params.rho * body.volume - body.mass) * built.params.gravity
            worst = max(worst, float(np.abs(loads[b, :3] + [0.0, 0.0, lift]).max()))
            net = max(net, lift)
    return elapsed, f"converged; largest force left on a buoy {worst:.2g} N (net lift {net:.3g} N)"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[20, 40, 80], help="lines")
    parser.add_argument("--repeat", type=int, default=5, help="rhs loops (median)")
    parser.add_argument("--steps", type=int, default=100, help="rk4 steps of the short run")
    parser.add_argument("--no-statics", action="store_true", help="skip the statics timing")
    args = parser.parse_args()
    if os.environ.get("OPENBLAS_NUM_THREADS") != "1":
        print("note: set OPENBLAS_NUM_THREADS=1 (the figures are single-threaded)")

    print("compiling (or loading the compiled kernels) ...", flush=True)
    run(args.sizes[0], 2)
    print(f"load average at start: {os.getloadavg()[0]:.2f}")
    units = ("", "", "[s]", "[us]", "[ns]", "[ms]", "", "[ns]", "", "[s]", "[ms]", "")
    names = ("lines", "segments", "start-up", "rhs", "rhs/seg", "step", "rhs/step", "step/seg",
             "ratio", "simulate", "per step", "load")  # fmt: skip
    widths = (5, 8, 8, 8, 7, 7, 8, 8, 5, 8, 8, 5)
    for row in (units, names):
        print(" ".join(f"{text:>{wide}}" for text, wide in zip(row, widths, strict=True)))
    first = None
    for lines in args.sizes:
        segments = lines * SEGMENTS
        start = time.perf_counter()
        built = model.build(seacable.load_case(system(lines)))
        startup = time.perf_counter() - start
        rhs = time_rhs(built, args.repeat)
        step, rhs_per_step = time_steps(built, args.steps, args.repeat)
        whole, accepted, _ = run(lines, args.steps)
        first = first or step / segments
        print(
            f"{lines:>5} {segments:>8} {startup:>8.2f} {rhs * 1e6:>8.1f} "
            f"{rhs / segments * 1e9:>7.1f} {step * 1e3:>7.3f} {rhs_per_step:>8.0f} "
            f"{step / segments * 1e9:>8.1f} {step / segments / first:>5.2f} {whole:>8.2f} "
            f"{whole / accepted * 1e3:>8.2f} {os.getloadavg()[0]:>5.2f}",
            flush=True,
        )
    print(
        "start-up: model.build, the lines' static shapes; rhs: one compiled call from Python; "
        f"step: one rk4 step of the compiled loop simulate runs (median of {args.repeat} runs of "
        f"{args.steps} steps); ratio: step/seg over the first size's (1.00 = linear); "
        f"simulate: a whole seacable.simulate of {args.steps} rk4 steps (start-up included) "
        "and that time per accepted step (results' solver_accepted_steps)"
    )
    if args.no_statics:
        return
    print("statics (start: static; seacable.statics, line shapes + Newton on the whole):")
    first = None
    for lines in args.sizes:
        elapsed, outcome = time_statics(lines)
        first = first or elapsed
        print(
            f"{lines:>5} lines {lines * SEGMENTS:>6} segments: {elapsed:7.2f} s "
            f"(x{elapsed / first:.2f}) {outcome}",
            flush=True,
        )


if __name__ == "__main__":
    main()
