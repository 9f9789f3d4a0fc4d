"""Cost of one right-hand-side evaluation of a system, as a ratio to the thesis's dense NumPy
model evaluated in the same process (benchmarks/dense_reference.py: the dense inertia matrix
formed and solved at every evaluation; the ratio, not the microseconds, is the figure to
compare between machines and between loads, and the load average is printed with it).

Cases: the thesis's first case with n = 120 links (benchmarks/thesis_timings.py: a floating
structure heaving, a 60 kg terminal mass, submerged, RK4 at its stable step) as a system of
bodies and lines, and, for the reference, the dense model of the same chain; and two examples
without rigid lines, the two buoys moored with a hawser (lumped lines, a tie) and the platform
on three catenary lines (a rigid body), so that a change for one line model can be seen not to
slow the others.

Each case's state is its initial state; a compiled loop of this file evaluates
``system.kernel.evaluate`` ``--count`` times, and (", in rk4") the integrator's own compiled chunk
takes ``--count`` / 4 steps of 0.1 ms (four evaluations a step, and the stages' arithmetic:
what a run pays per evaluation; the two differ by how LLVM lays out each caller: after the
two-ports' arrays were packed, this loop got slower and the runs faster); the dense model a
Python loop of ``--count`` / 20 evaluations. The cases are timed in turn, ``--repeat`` rounds,
and each keeps its fastest round (thread CPU time, so that time spent waiting for a core on a
shared machine does not count). On a loaded machine even CPU times vary by some tens of
percent (caches, shared cores).

What makes a system's evaluation cost more than it might is mostly reference counting: numba
takes and drops a reference to every array a compiled function receives (docs/
architecture.md, "Calls cost reference counts"); a hot function that receives the whole
parameter tuple shows here as about 1.2 us more per evaluation.

Run: python benchmarks/rhs_cost.py [--count N] [--repeat R]
"""

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import seacable  # noqa: E402
import thesis_timings  # noqa: E402
from dense_reference import DenseThesisModel, dense_state, thesis_chain  # noqa: E402
from seacable.numerics import integrators  # noqa: E402
from seacable.system import kernel  # noqa: E402
from seacable.system import model as system_model  # noqa: E402

EXAMPLES = HERE.parent / "examples"
THESIS_LINKS = 120
TIME = 0.1  # [s] the time the right-hand side is evaluated at


@njit
def _direct(t, y, p, w, ydot, count):
    status = 0
    for _ in range(count):
        status |= kernel.evaluate(t, y, p, w, ydot)
    return status


def _rk4(t, y, p, w, ydot, count):
    """count / 4 rk4 steps of 0.1 ms through the integrator's own compiled chunk (four
    evaluations a step, and the stages' arithmetic): what a run pays per evaluation."""
    steps = max(1, count // 4)
    states, work = np.empty((1, y.shape[0])), np.zeros(len(integrators.WORK_NAMES), np.int64)
    integrators.rk4_chunk(0, y, 1e-4 * steps, steps, steps, p, w, states, np.empty(1), work)
    return 0


REFERENCE = "thesis n=120, dense NumPy model"
DENSE_SHARE = 20  # the dense model is evaluated count / DENSE_SHARE times per round


def _dense(t, y, model, _w, _ydot, count):
    for _ in range(count):
        model.rhs(t, y)
    return 0


def cases():
    """name -> (loop, y, p, w, evaluations per round / count): what is timed."""
    dt = thesis_timings.stable_step(THESIS_LINKS)
    thesis = thesis_timings.case_for(THESIS_LINKS, dt)
    systems = {
        "thesis n=120, system": thesis,
        "two buoys + hawser": seacable.load_case(EXAMPLES / "two_buoys_moored_with_hawser.yaml"),
        "platform, 3 lines": seacable.load_case(EXAMPLES / "platform_three_catenary_lines.yaml"),
    }
    out = {}
    for name, case in systems.items():
        built = system_model.build(case)
        out[name] = (_direct, built.y0, built.params, system_model.workspace(built), 1)
        out[f"{name}, in rk4"] = (_rk4, built.y0, built.params, system_model.workspace(built), 1)
        if case is thesis:
            chain = thesis_chain(built)
            y = dense_state(chain, built.y0)
            out[REFERENCE] = (_dense, y, DenseThesisModel(chain), None, 1 / DENSE_SHARE)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=2000, help="evaluations per round")
    parser.add_argument("--repeat", type=int, default=30, help="rounds (fastest kept)")
    args = parser.parse_args()

    print(f"load average before: {os.getloadavg()[0]:.2f}")
    timed = cases()
    best = dict.fromkeys(timed, math.inf)
    for loop, y, p, w, _ in timed.values():  # compile
        loop(TIME, y.copy(), p, w, np.zeros_like(y), 1)
    for _ in range(args.repeat):
        for name, (loop, y, p, w, share) in timed.items():
            state, ydot = y.copy(), np.zeros_like(y)
            count = max(1, round(args.count * share))
            start = time.thread_time()
            loop(TIME, state, p, w, ydot, count)
            best[name] = min(best[name], (time.thread_time() - start) / count)
    reference = best[REFERENCE]
    print(f"{'case':<45} {'us/eval':>8} {'/ dense NumPy':>14}")
    for name, seconds in best.items():
        print(f"{name:<45} {seconds * 1e6:>8.2f} {seconds / reference:>14.2f}")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
