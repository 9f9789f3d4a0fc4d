"""Implicit steps on a rigid-link cable against the explicit compiled RK4 (n = 120, 480, 1920).

A 120 m umbilical (0.05 m, 4 kg/m, bending stiffness EI = 2000 N m^2, submerged) hangs from a
crane tip that surges 2 m with a 6 s period and carries a 200 kg clump at its free end. With
bending, the fastest motion of n rigid links is the zigzag mode, omega ~ sqrt(48 EI / (mu l^4))
~ n^2: RK4 must take steps that shrink like 1 / n^2, while the implicit step is chosen for the
physics (the swing and the surge). Each implicit step solves a block-tridiagonal Newton system
in maximal coordinates (angle and node accelerations, node forces), O(n).

For each n the script runs RK4 at its largest stable step (found by halving from the step the
zigzag estimate allows) and generalized-alpha (spectral radius 0.9) at 5 and 20 ms, all for the
same simulated time, and prints the wall time per simulated second, the ratio, the implicit cost
per link and step, and the agreement with RK4 on the top tension (largest gap over the run,
relative to the largest tension) and on the end position.
Run: ``python benchmarks/rigid_implicit.py [--quick]`` (--quick: n = 120 and 480 only).
"""

import argparse
import logging
import time

import numpy as np

import seacable
from seacable.simulation import build_system, fastest_frequency

LENGTH, DURATION, IMPLICIT_STEPS = 120.0, 2.0, (0.005, 0.02)


def case(n, integrator, step, duration=DURATION):
    cable = {
        "links": n,
        "length": LENGTH,
        "diameter": 0.05,
        "mass_per_length": 4.0,
        "bending_stiffness": 2000.0,
        "drag_coefficient_normal": 1.2,
        "drag_coefficient_tangential": 0.01,
        "top": {"type": "imposed", "x": {"kind": "sine", "amplitude": 2.0, "period": 6.0}},
        "bottom": {"type": "free", "body": {"mass": 200.0, "volume": 0.025}},
        "initial": {"shape": "arc", "top_angle_deg": 0.0},
    }
    simulation = {
        "duration": duration,
        "output_interval": 0.05,
        "integrator": integrator,
        "time_step": step,
        "spectral_radius": 0.9,
    }
    return seacable.load_case(
        {"environment": {"water_depth": 500.0}, "cables": [cable], "simulation": simulation}
    )


def run(n, integrator, step):
    """(wall time [s], dataset) or None when the run diverges."""
    seacable.simulate(case(n, integrator, step, duration=0.05))  # compile (or load) first
    start = time.perf_counter()
    try:
        ds = seacable.simulate(case(n, integrator, step)).dataset
    except seacable.SimulationDiverged:
        return None
    return time.perf_counter() - start, ds


def rk4_stable(n):
    """RK4 at the largest stable step among 2.8 / omega, halved until the run completes."""
    omega, _ = fastest_frequency(build_system(case(n, "rk4", 1e-3)))
    step = 2.8 / omega
    while True:
        result = run(n, "rk4", step)
        if result is not None and np.isfinite(result[1]["top_force_x"].values).all():
            return step, result
        step /= 2.0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="n = 120 and 480 only")
    args = parser.parse_args(argv)
    logging.getLogger("seacable").setLevel(logging.ERROR)
    sizes = (120, 480) if args.quick else (120, 480, 1920)
    print(f"{DURATION} s simulated; wall time per simulated second (s/s)")
    print(
        f"{'n':>5} | {'RK4 step':>9} {'RK4 s/s':>8} | {'implicit':>8} {'s/s':>7} "
        f"{'Newton/step':>11} {'ns/link/step':>12} | {'ratio':>6} | {'top tension':>11} "
        f"{'end pos.':>9}"
    )
    for n in sizes:
        step, (rk4_wall, ref) = rk4_stable(n)
        for implicit_step in IMPLICIT_STEPS:
            compare(n, step, rk4_wall, ref, implicit_step)


def compare(n, step, rk4_wall, ref, implicit_step):
    result = run(n, "generalized_alpha", implicit_step)
    if result is None:
        print(f"{n:5d} | implicit run at {implicit_step} s diverged")
        return
    wall, ds = result
    tension = np.hypot(ds["top_force_x"].values, ds["top_force_z"].values)
    tension_ref = np.hypot(ref["top_force_x"].values, ref["top_force_z"].values)
    gap_t = np.max(np.abs(tension - tension_ref)) / np.max(tension_ref)
    gap_x = np.max(
        np.hypot(
            ds["node_x"].values[:, -1] - ref["node_x"].values[:, -1],
            ds["node_z"].values[:, -1] - ref["node_z"].values[:, -1],
        )
    )
    steps = ds.attrs["solver_accepted_steps"]
    solves = ds.attrs["solver_linear_solves"] / steps
    per_link = wall / steps / n * 1e9
    print(
        f"{n:5d} | {step * 1e3:7.3f}ms {rk4_wall / DURATION:8.3f} | "
        f"{implicit_step * 1e3:6.0f}ms {wall / DURATION:7.3f} "
        f"{solves:11.2f} {per_link:12.0f} | {rk4_wall / wall:6.1f} | {gap_t:10.2%} "
        f"{gap_x * 1e3:7.2f}mm"
    )


if __name__ == "__main__":
    main()
