"""Cost of radiation memory: the convolution over the velocity history against the state-space
fit (``radiation damping`` with ``method: state_space``), on the shipped hemisphere's database
(examples/data/hemisphere_hydrodb.nc: 18 non-negligible kernel entries) with all six degrees
of freedom, K over ``--memory`` seconds sampled every ``--step``.

Two figures per method: (1) one right-hand-side evaluation of the system
(``system.kernel.evaluate`` in a compiled loop, ``--count`` times), with the convolution's history
filled (``after_step`` recorded every sample time up to the evaluation's time, so that every
sample enters the sum); (2) a 300 s run with rk4 at 0.01 s from a heave offset and a surge
velocity. ``none``: the same without radiation, the rest's cost. Thread CPU time, the fastest
of ``--repeat`` rounds. The ratio convolution / state space is printed: it is the figure to
compare between machines.

Run: python benchmarks/radiation_cost.py [--memory 25] [--step 0.05] [--count 20000]
"""

import argparse
import logging
import time
from pathlib import Path

import numpy as np
from numba import njit

import seacable
from seacable.system import kernel
from seacable.system import model as system_model

DATA = Path(__file__).resolve().parent.parent / "examples" / "data" / "hemisphere_hydrodb.nc"
RADIUS = 2.5  # [m] the hemisphere's
RHO, G = 1025.0, 9.81
DURATION = 300.0  # [s] of the timed runs


def case(method: str, memory: float, step: float, duration: float = 300.0):
    """A floating hemisphere (mass of its displaced water), free in six degrees of freedom,
    held by its waterplane stiffness in heave and soft springs elsewhere."""
    mass = RHO * 2.0 / 3.0 * np.pi * RADIUS**3
    heave = RHO * G * np.pi * RADIUS**2
    radiation = [{"model": "radiation damping", "memory": memory, "memory_step": step,
                  "method": method}] if method != "none" else []  # fmt: skip
    return seacable.load_case({
        "bodies": [{
            "name": "buoy", "type": "rigid", "position": [0, 0, -0.3], "velocity": [0.4, 0, 0],
            "mass": mass, "inertia": [0.4 * mass * RADIUS**2] * 3,
            "hydrodynamics": {"file": str(DATA)},
            "external forces": [
                {"model": "linear_stiffness", "diagonal": [1e3, 1e3, heave, 1e6, 1e6, 1e3],
                 "equilibrium_position": [0, 0, 0]}, *radiation]}],
        "start": "as_given",
        "simulation": {"duration": duration, "output_interval": 0.5, "integrator": "rk4",
                       "time_step": 0.01},
    })  # fmt: skip


@njit
def _evaluations(t, y, p, w, ydot, count):
    status = 0
    for _ in range(count):
        status |= kernel.evaluate(t, y, p, w, ydot)
    return status


def rhs_cost(method: str, memory: float, step: float, count: int, repeat: int) -> float:
    """[us] per evaluation at t = memory + 5 s with the history full."""
    built = system_model.build(case(method, memory, step))
    p, y = built.params, built.y0.copy()
    y[p.n_q : p.n_q + 6] = [0.3, 0.1, 0.2, 0.01, 0.02, 0.01]
    y[p.n_q + p.n_v :] = 0.01
    w = kernel.make_work(p)
    kernel.start_memory(0.0, y, p, w)
    t = memory + 5.0
    for k in range(1, int(t / step) + 1):
        kernel.after_step(k * step, y, p, w)
    ydot = np.zeros_like(y)
    _evaluations(t, y, p, w, ydot, 10)
    best = np.inf
    for _ in range(repeat):
        start = time.thread_time()
        _evaluations(t, y, p, w, ydot, count)
        best = min(best, (time.thread_time() - start) / count)
    return best * 1e6


def run_cost(method: str, memory: float, step: float, repeat: int) -> float:
    """[s] of thread time for a ``DURATION`` run (after a first, compiling one)."""
    seacable.simulate(case(method, memory, step, duration=1.0))
    best = np.inf
    for _ in range(repeat):
        start = time.thread_time()
        seacable.simulate(case(method, memory, step))
        best = min(best, time.thread_time() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--memory", type=float, default=25.0)
    parser.add_argument("--step", type=float, default=0.05)
    parser.add_argument("--count", type=int, default=20000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    logging.getLogger("seacable").setLevel(logging.ERROR)  # ``none`` rises undamped above z = 0
    methods = ("none", "convolution", "state_space")
    rhs = {m: rhs_cost(m, args.memory, args.step, args.count, args.repeat) for m in methods}
    runs = {m: run_cost(m, args.memory, args.step, args.repeat) for m in methods}
    states = system_model.build(case("state_space", args.memory, args.step)).params.n_s
    print(f"hemisphere, six degrees of freedom, memory {args.memory:g} s every {args.step:g} s; "
          f"state space: {states} states")  # fmt: skip
    for m in methods:
        print(f"  {m:12s} rhs {rhs[m]:8.2f} us   {DURATION:g} s run (rk4, 0.01 s) "
              f"{runs[m]:6.2f} s")  # fmt: skip
    own = {m: rhs[m] - rhs["none"] for m in methods}
    print(f"  ratio convolution / state space: rhs {rhs['convolution'] / rhs['state_space']:.1f}"
          f" (radiation's own part {own['convolution'] / own['state_space']:.1f}), run "
          f"{runs['convolution'] / runs['state_space']:.1f}")  # fmt: skip


if __name__ == "__main__":
    main()
