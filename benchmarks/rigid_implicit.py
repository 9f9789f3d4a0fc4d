"""Implicit steps on rigid-link cables against the explicit compiled RK4 (n = 120, 480, 1920).

A 120 m umbilical (0.05 m, 4 kg/m, bending stiffness EI = 2000 N m^2, submerged) hangs from a
crane tip that surges 2 m with a 6 s period and carries a 200 kg clump at its free end; in the 3D
model (``rigid_segments_3d``) the tip also sways 1 m with a 5 s period across a 0.3 m/s current
at 45 degrees, and the segments carry added mass. It runs as a system of bodies and lines: the
imposed body ``top`` (the crane tip), the point body ``end`` (the clump, carried at the line's
end) and one rigid line ``umbilical`` between them, hanging straight down at rest. With
bending, the fastest motion of n rigid links is the zigzag mode, omega ~ sqrt(48 EI / (mu l^4))
~ n^2: RK4 must take steps that shrink like 1 / n^2, while the implicit step is chosen for the
physics (the swing and the surge). Each implicit step solves Newton's system over the
accelerations (``numerics.system_implicit``): its matrix from finite differences of the residual
over colour groups, the line's block factorised as a band. A rigid line's accelerations depend
on all its angles, so its block is dense: a matrix costs n residuals and its factorisation
O(n^3), which the run pays whenever the modified Newton iteration rebuilds it.

For each n the script runs RK4 at its largest stable step (found by halving from the step the
zigzag estimate allows, rounded down to a divisor of the 0.1 s output interval) and
generalized-alpha (spectral radius 0.9) at 5 and 20 ms, all for the same simulated time, and
prints the wall time per simulated second, the ratio, the Newton iterations per step, the
implicit cost per link and step, and the agreement with RK4 on the top tension (largest gap
over the run, relative to the largest tension) and on the clump's position.
Run: ``python benchmarks/rigid_implicit.py [--quick] [--model rigid_links|rigid_segments_3d]``
(--quick: n = 120 and 480 only; both models by default).
"""

import argparse
import logging
import math
import time

import numpy as np

import seacable
from seacable.numerics import stability
from seacable.system import model as system_model

LENGTH, DURATION, IMPLICIT_STEPS = 120.0, 2.0, (0.005, 0.02)
# [s] the fixed steps must divide it (the schema refuses a step that does not, within 1 %)
OUTPUT = 0.1
MODELS = ("rigid_links", "rigid_segments_3d")
DIAMETER, MU, EI, CD_N = 0.05, 4.0, 2000.0, 1.2  # [m], [kg/m], [N m^2], [-]
CLUMP_MASS, CLUMP_VOLUME = 200.0, 0.025  # [kg], [m^3]
CURRENT = 0.3  # [m/s], 3D model only
RHO, G = 1025.0, 9.81  # the environment's defaults [kg/m^3], [m/s^2]


def case(model, n, integrator, step, duration=DURATION):
    """The umbilical as a system: the imposed body ``top`` (the crane tip), the point body
    ``end`` (the clump, carried at the line's end) and the rigid line ``umbilical`` between
    them, hanging straight down at rest."""
    top = {"name": "top", "type": "imposed", "x": {"kind": "sine", "amplitude": 2.0, "period": 6.0}}
    environment = {"water_depth": 500.0}
    line_type = {
        "name": "umbilical",
        "diameter": DIAMETER,
        "mass_per_length": MU,
        "bending_stiffness": EI,
        "drag_coefficient_normal": CD_N,
        "drag_coefficient_tangential": 0.01,
    }
    if model == "rigid_segments_3d":
        top["y"] = {"kind": "sine", "amplitude": 1.0, "period": 5.0}
        environment["current"] = {"velocity": CURRENT, "direction_deg": 45.0}
    else:
        line_type["added_mass_coefficient"] = 0.0  # the planar links carry no added mass
    clump = {
        "name": "end",
        "type": "point",
        "position": [0.0, 0.0, -LENGTH],
        "mass": CLUMP_MASS,
        "volume": CLUMP_VOLUME,
        "external forces": [{"model": "gravity"}, {"model": "buoyancy"}],
    }
    line = {
        "name": "umbilical",
        "model": model,
        "from": "top",
        "to": "end",
        "sections": [{"type": "umbilical", "segments": n, "length": LENGTH}],
        "initial": {"arc_deg": [0.0, 0.0]},
        "base_reference": [0.0, 0.0, -1.0],
    }
    simulation = {
        "duration": duration,
        "output_interval": OUTPUT,
        "integrator": integrator,
        "time_step": step,
        "spectral_radius": 0.9,
    }
    return seacable.load_case(
        {
            "environment": environment,
            "bodies": [top, clump],
            "line_types": [line_type],
            "lines": [line],
            "start": "as_given",
            "simulation": simulation,
        }
    )


def run(model, n, integrator, step):
    """(wall time [s], results tree) or None when the run diverges."""
    try:
        seacable.simulate(case(model, n, integrator, step, duration=OUTPUT))  # compile (or load)
        start = time.perf_counter()
        ds = seacable.simulate(case(model, n, integrator, step)).dataset
    except seacable.SimulationDiverged:
        return None
    return time.perf_counter() - start, ds


def rk4_limit(model, n):
    """rk4's longest stable step [s] about the line's start (``numerics.stability.rk4_limit``:
    the eigenvalues of the linearised system, the zigzag of a link against its joint springs
    and the tension)."""
    return stability.rk4_limit(system_model.build(case(model, n, "rk4", OUTPUT))).step


def rk4_stable(model, n):
    """RK4 at the largest step within its stability limit that divides the output interval,
    halved until the run completes."""
    step = OUTPUT / math.ceil(OUTPUT / rk4_limit(model, n) - 1e-9)
    while True:
        result = run(model, n, "rk4", step)
        if result is not None and np.isfinite(result[1]["bodies/top/line_force_x"].values).all():
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
    """The magnitude of the line's force on the crane tip [N] (y is zero in the plane)."""
    forces = [ds[f"bodies/top/line_force_{a}"].values for a in "xyz"]
    return np.linalg.norm(np.stack(forces), axis=0)


def _end(ds):
    """The clump's position (the line's end) [m]."""
    return np.stack([ds[f"bodies/end/position_{a}"].values for a in "xyz"], axis=1)


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
        f"{solves:11.2f} {per_link:12.0f} | {rk4_wall / wall:6.3g} | {gap_t:10.2%} "
        f"{gap_x * 1e3:7.2f}mm"
    )


if __name__ == "__main__":
    main()
