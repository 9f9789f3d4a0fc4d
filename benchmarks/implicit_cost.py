"""Cost of the implicit schemes' Newton matrix and of an implicit step on a rigid line against
its number of links n: the line's block dense (differences over every angle, as before: n
residuals of O(n) each and an O(n^3) factorisation) and in maximal coordinates
(``numerics.rigid_newton``: a banded block, O(n)).

The line is benchmarks/rigid_implicit.py's umbilical (120 m, EI 2000 N m^2, submerged, a 200 kg
clump at its free end, the crane tip surging 2 m with a 6 s period), planar links
(``rigid_links``, by default) or 3D segments (``--model rigid_segments_3d``: the tip also sways
across a current, ``numerics.rigid_newton_3d``), with n = 30, 60, 120, 240, 480. For each n
and each form the script times, in compiled code and as thread CPU time (the fastest of
``--repeat`` rounds):
- a Newton matrix: built (``system_implicit._jacobian``) and factorised (``bordered.factor``) at
  the state 0.5 s into the run;
- a step: ``--steps`` generalized-alpha steps of 20 ms from that state (``system_implicit.chunk``,
  modified Newton: the matrix is rebuilt only when the iteration needs it), per step;
and prints them with their ratio to the n = 30 figure of the same form (linear growth: 2, 4, 8,
16), the residual evaluations and matrices per step, the step's cost less its matrices' (the
residuals, solves and line searches: O(n) in both forms), and how far the two forms' states
are apart after the steps (the same Newton iteration, to the Newton tolerance). A finer line is
stiffer (its zigzag modes grow like n^2), so at the same step Newton rebuilds its matrix more
often: the matrices per step grow with n in both forms, the cost of each is what changes.
Run: ``python benchmarks/implicit_cost.py [--model rigid_links|rigid_segments_3d]
[--sizes 30 60 ...] [--steps K] [--repeat R]``
"""

import argparse
import logging
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from rigid_implicit import MODELS, case  # noqa: E402
from seacable.numerics import bordered, implicit_setup, integrators, system_implicit  # noqa: E402
from seacable.system import kernel  # noqa: E402
from seacable.system import model as system_model  # noqa: E402

STEP = 0.02  # [s]
START = 0.5  # [s] the state the matrix and the steps are taken at (the line in motion)
SCHEME = "generalized_alpha"
TOLERANCE = 1e-6  # [m] Newton's tolerance (the schema's default newton_tolerance x shortest link)
COEF = implicit_setup.scheme(SCHEME, spectral_radius=0.9)


def _rigid(rows):
    """system_implicit.chunk's last argument: True with rigid lines' Newton rows, else None."""
    return True if rows.line.shape[0] > 0 else None


def _setup(model, n):
    """The case, its system and its state at START (reached by the implicit steps)."""
    c = case(model, n, "rk4", STEP, duration=START)
    system = system_model.build(c)
    p = system.params
    y = system.y0.copy()
    acc = np.zeros(int(p.n_v))
    w = kernel.make_work(p)
    implicit_setup.initial_acceleration(0.0, y, p, w, acc)
    inc, lay, rows = implicit_setup.newton(c, system)
    _, status = system_implicit.chunk(
        0, y, acc, START, round(START / STEP), 1, round(START / STEP), COEF, TOLERANCE, 20, p,
        implicit_setup.frozen(p), w, inc, lay, rows, implicit_setup.carry(system, lay),
        np.empty((1, len(y))), np.empty(1), _counters(), _rigid(rows),
    )  # fmt: skip
    if status != 0:
        raise RuntimeError(f"the implicit steps to t = {START} s failed (status {status})")
    return c, system, y


def _counters():
    return np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)


def _time(function, repeat):
    best = np.inf
    for _ in range(repeat):
        start = time.thread_time()
        function()
        best = min(best, time.thread_time() - start)
    return best


def measure(c, system, y0, maximal, steps, repeat):
    """(matrix [s], step [s], residuals per step, matrices per step, state after the steps)."""
    p = system.params
    inc, lay, rows = implicit_setup.newton(c, system, maximal=maximal)
    w = kernel.make_work(p)
    coef = COEF
    nv = int(p.n_v)
    acc = np.zeros(nv)
    implicit_setup.initial_acceleration(START, y0, p, w, acc)
    pj = implicit_setup.frozen(p)
    ny = len(y0)
    vec = np.zeros((10, ny))
    work = _counters()
    res = np.zeros(nv)
    mat = np.zeros(lay.size)
    piv = np.zeros(lay.order.shape[0], dtype=np.int64)

    def matrix():
        system_implicit._residual(START, y0, acc, acc, STEP, coef, p, w, inc, vec[0], vec[1],
                                  vec[2][:nv], res, vec[9][:nv])  # fmt: skip
        system_implicit._jacobian(START, y0, acc, acc, STEP, coef, pj, w, inc, lay, rows, mat,
                                  res, vec, work)  # fmt: skip
        if not bordered.factor(lay, mat, piv):
            raise RuntimeError("singular Newton matrix")

    matrix()  # compile
    t_matrix = _time(matrix, repeat)

    def run():
        y = y0.copy()
        a = acc.copy()
        carried = implicit_setup.carry(system, lay)
        counters = _counters()
        done, status = system_implicit.chunk(
            round(START / (STEP * steps)) * steps, y, a, STEP * steps, steps, 1, steps, coef,
            TOLERANCE, 20, p,
            pj, w, inc, lay, rows, carried, np.empty((1, ny)), np.empty(1), counters,
            _rigid(rows),
        )  # fmt: skip
        if status != 0:
            raise RuntimeError(f"the implicit steps failed (status {status})")
        return y, counters

    run()  # compile
    t_steps = _time(run, repeat) / steps
    y, counters = run()
    return t_matrix, t_steps, counters[2] / steps, counters[4] / steps, y


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", choices=MODELS, default=MODELS[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[30, 60, 120, 240, 480])
    parser.add_argument("--steps", type=int, default=10)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    logging.getLogger("seacable").setLevel(logging.ERROR)
    print(f"{args.model}, {SCHEME} at {STEP * 1e3:.0f} ms from t = {START} s; thread CPU time")
    print(
        f"{'n':>5} {'form':>7} | {'matrix [ms]':>11} {'ratio':>6} | {'step [ms]':>9} "
        f"{'ratio':>6} | {'rhs/step':>8} {'matrices/step':>13} {'rest [ms]':>9} | "
        f"{'gap to dense [m]':>16}"
    )
    first: dict[bool, tuple[float, float]] = {}
    for n in args.sizes:
        states = {}
        c, system, y0 = _setup(args.model, n)
        for maximal in (False, True):
            t_matrix, t_step, rhs, matrices, y = measure(c, system, y0, maximal, args.steps,
                                                         args.repeat)  # fmt: skip
            states[maximal] = y
            base = first.setdefault(maximal, (t_matrix, t_step))
            gap = np.abs(y - states[False]).max() if maximal else 0.0
            rest = t_step - matrices * t_matrix
            print(
                f"{n:5d} {'banded' if maximal else 'dense':>7} | {t_matrix * 1e3:11.3f} "
                f"{t_matrix / base[0]:6.2f} | {t_step * 1e3:9.3f} {t_step / base[1]:6.2f} | "
                f"{rhs:8.1f} {matrices:13.2f} {rest * 1e3:9.3f} | {gap:16.2e}"
            )


if __name__ == "__main__":
    main()
