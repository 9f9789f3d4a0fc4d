"""The published trajectory case (Jacquot & Marichal, section 4): the stiffness-matrix servo's
closed loop and its precision, against the exact method.

1. The loop linearised about the start (``models.servo_loop``): growth rates against a and the
   servo step dt, continuous (as integrated) and sampled (the paper's once-per-step update), the
   largest gain the run accepts, and the prediction checked against runs at rest.
2. Why the error is what it is: the servo is an integral controller, so following a required end
   force F(t) leaves an error e ~ (dt / a) K^-1 dF/dt; the exact run gives dF/dt.
3. The table: exact method, the paper's servo as written and variants: largest tracking error,
   end force against the exact method's, wall time per simulated second of the run loop.

Run: PYTHONPATH=src python benchmarks/trajectory_servo_scan.py  (about 3 minutes; timings are
the best of three runs, the refreshed-K run once)"""

import math
import time
from pathlib import Path

import numpy as np

import seacable
from seacable import simulation
from seacable.models.servo_loop import servo_loop
from seacable.simulation import build_system, model_of

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
# the exact method's example is a system now; its single-cable form (the same core as the
# servo's, until the servo is a force model of systems) is kept with the tests
LEGACY = EXAMPLES.parent / "tests" / "legacy_cases"
SERVO, EXACT = "jacquot_marichal_trajectory_servo", "jacquot_marichal_trajectory_exact"
PAPER_ERROR = 0.025  # m, the paper's largest position error


def case_of(name, time_step=None, duration=None, **servo):
    folder = LEGACY if (LEGACY / f"{name}.yaml").exists() else EXAMPLES
    case = seacable.load_case(folder / f"{name}.yaml")
    cable = case.cables[0]
    if servo:
        bottom = cable.bottom.model_copy(
            update={"servo": cable.bottom.servo.model_copy(update=servo)}
        )
        cable = cable.model_copy(update={"bottom": bottom})
    update = {"time_step": time_step, "duration": duration}
    sim = case.simulation.model_copy(update={k: v for k, v in update.items() if v is not None})
    return case.model_copy(update={"cables": [cable], "simulation": sim})


def timed_run(case, repeat=3):
    """(dataset, wall time of the run loop per simulated second [s/s], best of ``repeat``): the
    build (statics, the servo's K and its stability check) timed apart and taken out."""
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        system = build_system(case)
        workspace = model_of(case).workspace(system)
        simulation.check_servo_loop(case, system.params, system.y0, workspace)
        build = time.perf_counter() - start
        start = time.perf_counter()
        ds = seacable.simulate(case).dataset
        best = min(best, time.perf_counter() - start - build)
    return ds, best / case.simulation.duration


def loop_analysis(loop):
    print("1. the servo loop linearised about the start: growth rate sigma [1/s] (b = 0.5),")
    print("   continuous (integrated) / sampled (the paper's once-per-step update)")
    for step in (0.01, 0.003, 0.001):
        cells = []
        for gain in (0.2, 0.5, 1.0, 2.0):
            continuous = loop.growth_rate(gain, 0.5, step)
            sampled = loop.sampled_growth_rate(gain, 0.5, step)
            cells.append(f"a={gain:<3}: {continuous:.4f}/{sampled:.4f}")
        print(f"   dt = {step:<5} s: " + "  ".join(cells))
    for step in (0.01, 0.001):
        largest = loop.largest_stable_gain(0.5, step, 1.0 / 55.0)
        print(
            f"   accepted for the 55 s run (sigma <= 1/55 s): a <= {largest:.3g} at dt = {step} s"
        )
    original = simulation.check_servo_loop
    simulation.check_servo_loop = lambda *args: None  # run refused settings to measure them
    try:
        for gain in (2.0, 1.5):
            ds = seacable.simulate(case_of(SERVO, 0.001, 8.0, gain=gain, step=0.001)).dataset
            error, times = ds["tracking_error"].values, ds["time"].values
            growing = (error > 1e-8) & (error < 1e-2)
            measured = np.polyfit(times[growing], np.log(error[growing]), 1)[0]
            predicted = loop.growth_rate(gain, 0.5, 0.001)
            print(f"   at rest, a = {gain}, dt = 1 ms: sigma predicted {predicted:.3f}, "
                  f"measured {measured:.3f} /s; error {error[-1]:.3g} m after 8 s")  # fmt: skip
    finally:
        simulation.check_servo_loop = original


def error_prediction(exact, servo, stiffness):
    times = exact["time"].values
    force = np.stack([-exact[f"bottom_force_{a}"].values for a in "xyz"], axis=1)
    rate = np.gradient(force, times, axis=0)
    predicted = np.linalg.norm(0.01 * np.linalg.solve(stiffness, rate.T), axis=0)
    largest = predicted.max()
    print("2. integral action: error ~ (dt / a) |K^-1 dF/dt|, dF/dt from the exact run")
    run = servo["tracking_error"].values.max()
    print(f"   a = 1, dt = 0.01 s: predicted largest {largest:.2f} m, run {run:.2f} m")
    print(f"   for the paper's {PAPER_ERROR} m: a / dt >= {100 * largest / PAPER_ERROR:.0f} /s")


def table(rows, exact, exact_wall):
    print("3. method                                  largest error [m]  force vs exact  s/s")
    times = exact["time"].values
    during = (times > 12.0) & (times < 50.0)
    reference = np.stack([exact[f"bottom_force_{a}"].values[during] for a in "xz"])
    scale = np.abs(reference).max()
    print(f"   {'exact':<40} {exact['tracking_error'].values.max():<18.1e} {'-':<15} "
          f"{exact_wall:.3f} (1)")  # fmt: skip
    for label, ds, wall in rows:
        force = np.stack([ds[f"bottom_force_{a}"].values[during] for a in "xz"])
        difference = np.abs(force - reference).max() / scale
        print(f"   {label:<40} {ds['tracking_error'].values.max():<18.3f} {difference:<15.1%} "
              f"{wall:.3f} ({wall / exact_wall:.1f})")  # fmt: skip


def main() -> None:
    case = case_of(SERVO)
    system = build_system(case)
    loop = servo_loop(system.params, system.y0, model_of(case).workspace(system))
    loop_analysis(loop)
    exact, exact_wall = timed_run(case_of(EXACT))
    servo, servo_wall = timed_run(case)
    error_prediction(exact, servo, system.params.servo_stiffness)
    rows = [("servo as written: a 1, b 0.5, dt 0.01 s", servo, servo_wall)]
    for label, settings, repeat in (
        ("servo, K refreshed every 1 s", dict(recompute_interval=1.0), 1),
        ("servo, a 2 (the largest a / dt accepted)", dict(gain=2.0), 3),
    ):
        rows.append((label, *timed_run(case_of(SERVO, **settings), repeat)))
    table(rows, exact, exact_wall)


if __name__ == "__main__":
    main()
