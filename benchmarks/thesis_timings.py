"""Table 6.6 of Pouzada (2015), timed: the first case (floating structure, free terminal mass),
submerged, 10 s simulated, for n = 20 ... 120, 480 and 960 links.

For each n, seacable (compiled O(n) recursion, RK4) and a faithful dense-mass-matrix NumPy
implementation of the thesis's approach (benchmarks/dense_reference.py) integrate the same
equations with the same RK4 step, so they reach the same accuracy (the final states are compared
and the largest difference printed). The dense code stops when a run would exceed the budget.
seacable runs the example's system of bodies and lines with n links (its joints' stiffness,
the thesis's k = 5/6 n E I / L, is the line type's bending stiffness 5/6 E I over the link).

Run: python benchmarks/thesis_timings.py [--dense-budget SECONDS] [--repeat N]
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import seacable  # noqa: E402
from dense_reference import DenseThesisModel, dense_state, thesis_chain  # noqa: E402
from seacable.case.loader import derive_case  # noqa: E402
from seacable.numerics import stability  # noqa: E402
from seacable.system import model  # noqa: E402

EXAMPLE = HERE.parent / "examples" / "thesis_6_1_sim4_submerged_60_links.yaml"
THESIS_SECONDS = {20: 56, 40: 173, 60: 408, 80: 806, 100: 1272, 120: 1856}  # table 6.6, MATLAB
SIZES = (20, 40, 60, 80, 100, 120, 480, 960)
DURATION = 10.0
OUTPUT_INTERVAL = 0.1


def case_for(n: int, time_step: float):
    """The example with n links (the bending stiffness of table 6.1 unchanged: the joints'
    stiffness follows n)."""
    base = seacable.load_case(EXAMPLE)
    lines = [base.lines[0].model_dump(mode="json", by_alias=True, exclude_none=True)]
    lines[0]["sections"][0]["segments"] = n
    sim = {"duration": DURATION, "output_interval": OUTPUT_INTERVAL, "time_step": time_step}
    return derive_case(base, {"lines": lines, "simulation": sim})


def stable_step(n: int) -> float:
    """A step <= 5 ms dividing the output interval that RK4 takes safely: 0.6 of its stability
    limit about the start (``numerics.stability.rk4_limit``; the margin the run's warning asks
    for covers the start-up transient, whose tension exceeds the static one)."""
    limit = stability.rk4_limit(model.build(case_for(n, 0.005)))
    wanted = min(0.005, 0.6 * limit.step)
    return OUTPUT_INTERVAL / math.ceil(OUTPUT_INTERVAL / wanted - 1e-9)


def time_seacable(case, repeat: int):
    seacable.simulate(case)  # compile (or load from cache) and warm up
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        results = seacable.simulate(case)
        best = min(best, time.perf_counter() - start)
    return best, results


def final_state(results):
    """Link angles and the structure's heave at the end of a system's run."""
    tree = results.dataset
    angles = tree["lines/umbilical/angle"].values[-1]
    return np.concatenate([angles, [tree["bodies/top/position_z"].values[-1]]]), len(angles)


def time_dense(case, dt: float):
    built = model.build(case)
    chain = thesis_chain(built)
    dense = DenseThesisModel(chain)
    steps = round(DURATION / dt)
    start = time.perf_counter()
    y = dense.run_rk4(dense_state(chain, built.y0), dt, steps)
    return time.perf_counter() - start, y[: chain.n + 1]


def first_run_seconds() -> tuple[float, float]:
    """Wall time of a first run in a fresh compile cache (compilation included), then again."""
    code = (
        "import time; t = time.perf_counter(); import seacable; "
        f"seacable.simulate(seacable.load_case({str(EXAMPLE)!r})); "
        "print(time.perf_counter() - t)"
    )
    times = []
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        for _ in range(2):
            out = subprocess.run(
                [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
            )
            times.append(float(out.stdout.strip().splitlines()[-1]))
    return times[0], times[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dense-budget", type=float, default=60.0, help="seconds per dense run")
    parser.add_argument("--repeat", type=int, default=3, help="seacable runs per size (best)")
    args = parser.parse_args()

    print("thesis table 6.6 case: floating structure + 60 kg terminal mass, submerged, 10 s")
    header = (
        f"{'n':>5} {'step [ms]':>9} {'seacable [s]':>12} "
        f"{'dense NumPy [s]':>15} {'dense/seacable':>14} {'thesis MATLAB [s]':>17} "
        f"{'MATLAB/seacable':>15} "
        f"{'max |dx|':>9}"
    )
    print(header)
    rows = {}
    dense_last = None
    for n in SIZES:
        dt = stable_step(n)
        case = case_for(n, dt)
        wall, results = time_seacable(case, args.repeat)
        ours, _ = final_state(results)
        dense_text, ratio_text, diff_text = "skipped", "", ""
        predicted = None if dense_last is None else dense_last[1] * (n / dense_last[0]) ** 3
        predicted = None if predicted is None else predicted * (dense_last[2] / dt)
        if predicted is None or predicted < args.dense_budget:
            dense_wall, theirs = time_dense(case, dt)
            dense_last = (n, dense_wall, dt)
            dense_text = f"{dense_wall:.3f}"
            ratio_text = f"{dense_wall / wall:.0f}x"
            diff_text = f"{np.max(np.abs(ours - theirs)):.1e}"
        thesis = THESIS_SECONDS.get(n)
        thesis_text = f"{thesis}" if thesis else ""
        matlab_ratio = f"{thesis / wall:.0f}x" if thesis else ""
        print(
            f"{n:>5} {dt * 1e3:>9.3f} {wall:>12.4f} {dense_text:>15} "
            f"{ratio_text:>14} {thesis_text:>17} {matlab_ratio:>15} {diff_text:>9}",
            flush=True,
        )
        rows[n] = wall

    same_step = stable_step(960)
    t120, _ = time_seacable(case_for(120, same_step), args.repeat)
    t960, _ = time_seacable(case_for(960, same_step), args.repeat)
    first, cached = first_run_seconds()
    print(
        f"same step {same_step * 1e3:.3f} ms: n=120 {t120:.4f} s, n=960 {t960:.4f} s, "
        f"ratio {t960 / t120:.1f} (8x more links; target <= 10)"
    )
    print(
        f"first run in a fresh environment (compile included): {first:.1f} s; "
        f"next run with the compile cache: {cached:.1f} s (target first run < 20 s)"
    )
    print(
        f"summary: n=120 in {rows[120]:.4f} s (target < 0.1 s), "
        f"{THESIS_SECONDS[120] / rows[120]:.0f}x faster than the thesis's MATLAB; "
        f"n=960 / n=120 at the same step: {t960 / t120:.1f}x"
    )


if __name__ == "__main__":
    main()
