"""Implicit steps on rigid-link cables against the explicit compiled RK4 (n = 120, 480, 1920).

A 120 m umbilical (0.05 m, 4 kg/m, bending stiffness EI = 2000 N m^2, submerged) hangs from a
crane tip that surges 2 m with a 6 s period and carries a 200 kg clump at its free end; in the 3D
model (``rigid_segments_3d``) the tip also sways 1 m with a 5 s period across a 0.3 m/s current
at 45 degrees, and the segments carry added mass. With
bending, the fastest motion of n rigid links is the zigzag mode, omega ~ sqrt(48 EI / (mu l^4))
~ n^2: RK4 must take steps that shrink like 1 / n^2, while the implicit step is chosen for the
physics (the swing and the surge). Each implicit step solves a block-tridiagonal Newton system
in maximal coordinates (angle and node accelerations, node forces), O(n).

For each n the script runs RK4 at its largest stable step (found by halving from the step the
zigzag estimate allows) and generalized-alpha (spectral radius 0.9) at 5 and 20 ms, all for the
same simulated time, and prints the wall time per simulated second, the ratio, the implicit cost
per link and step, and the agreement with RK4 on the top tension (largest gap over the run,
relative to the largest tension) and on the end position.
Run: ``python benchmarks/rigid_implicit.py [--quick] [--model rigid_links|rigid_segments_3d]``
(--quick: n = 120 and 480 only; both models by default).
"""

import argparse
import logging
import time

import numpy as np

import seacable
from seacable.simulation import build_system, fastest_frequency

LENGTH, DURATION, IMPLICIT_STEPS = 120.0, 2.0, (0.005, 0.02)
MODELS = ("rigid_links", "rigid_segments_3d")


def case(model, n, integrator, step, duration=DURATION):
    top = {"type": "imposed", "x": {"kind": "sine", "amplitude": 2.0, "period": 6.0}}
    environment = {"water_depth": 500.0}
    if model == "rigid_segments_3d":
        top["y"] = {"kind": "sine", "amplitude": 1.0, "period": 5.0}
        environment["current"] = {"velocity": 0.3, "direction_deg": 45.0}
    cable = {
        "model": model,
        "links": n,
        "length": LENGTH,
        "diameter": 0.05,
        "mass_per_length": 4.0,
        "bending_stiffness": 2000.0,
        "drag_coefficient_normal": 1.2,
        "drag_coefficient_tangential": 0.01,
        "top": top,
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
        {"environment": environment, "cables": [cable], "simulation": simulation}
    )


def run(model, n, integrator, step):
    """(wall time [s], dataset) or None when the run diverges."""
    seacable.simulate(case(model, n, integrator, step, duration=0.05))  # compile (or load)
    start = time.perf_counter()
    try:
        ds = seacable.simulate(case(model, n, integrator, step)).dataset
    except seacable.SimulationDiverged:
        return None
    return time.perf_counter() - start, ds


def rk4_stable(model, n):
    """RK4 at the largest stable step among 2.8 / omega, halved until the run completes."""
    omega, _ = fastest_frequency(build_system(case(model, n, "rk4", 1e-3)))
    step = 2.8 / omega
    while True:
        result = run(model, n, "rk4", step)
        if result is not None and np.isfinite(result[1]["top_force_x"].values).all():
            return step, result
        step /= 2.0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="n = 120 and 480 only")
    parser.add_argument("--model", choices=MODELS, help="one model only")
    args = parser.parse_args(argv)
    logging.getLogger("seacable").setLevel(logging.ERROR)
    sizes = (120, 480) if args.quick else (120, 480, 1920)
    for model in [args.model] if args.model else MODELS:
        table(model, sizes)


def table(model, sizes):
    print(f"{model}: {DURATION} s simulated; wall time per simulated second (s/s)")
    print(
        f"{'n':>5} | {'RK4 step':>9} {'RK4 s/s':>8} | {'implicit':>8} {'s/s':>7} "
        f"{'Newton/step':>11} {'ns/link/step':>12} | {'ratio':>6} | {'top tension':>11} "
        f"{'end pos.':>9}"
    )
    for n in sizes:
        step, (rk4_wall, ref) = rk4_stable(model, n)
        for implicit_step in IMPLICIT_STEPS:
            compare(model, n, step, rk4_wall, ref, implicit_step)
    print()


def _top_tension(ds):
    axes = [a for a in "xyz" if f"top_force_{a}" in ds]
    return np.linalg.norm(np.stack([ds[f"top_force_{a}"].values for a in axes]), axis=0)


def _end(ds):
    axes = [a for a in "xyz" if f"node_{a}" in ds]
    return np.stack([ds[f"node_{a}"].values[:, -1] for a in axes], axis=1)


def compare(model, n, step, rk4_wall, ref, implicit_step):
    result = run(model, n, "generalized_alpha", implicit_step)
    if result is None:
        print(f"{n:5d} | implicit run at {implicit_step} s diverged")
        return
    wall, ds = result
    tension, tension_ref = _top_tension(ds), _top_tension(ref)
    gap_t = np.max(np.abs(tension - tension_ref)) / np.max(tension_ref)
    gap_x = np.max(np.linalg.norm(_end(ds) - _end(ref), axis=1))
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
