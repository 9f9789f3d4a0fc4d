"""The published trajectory case (Jacquot & Marichal, section 4) with the stiffness-matrix servo
for several gains a, b, correction steps and K refresh intervals, against the exact method: the
largest tracking error of each. Run: python benchmarks/trajectory_servo_scan.py"""

import itertools
from pathlib import Path

import seacable

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def largest_error(name, time_step=0.01, **servo):
    case = seacable.load_case(EXAMPLES / f"{name}.yaml")
    cable = case.cables[0]
    if servo:
        bottom = cable.bottom.model_copy(
            update={"servo": cable.bottom.servo.model_copy(update=servo)}
        )
        cable = cable.model_copy(update={"bottom": bottom})
    sim = case.simulation.model_copy(update={"time_step": time_step})
    case = case.model_copy(update={"cables": [cable], "simulation": sim})
    try:
        return seacable.simulate(case)["tracking_error"].values.max()
    except seacable.SimulationDiverged:
        return float("nan")


def main() -> None:
    print("largest tracking error [m] over the 60 m excursion of the published case")
    print(f"  exact end force: {largest_error('jacquot_marichal_trajectory_exact'):.2e}")
    for a, b in itertools.product((0.05, 0.2, 1.0), (0.0, 0.5, 0.9)):
        error = largest_error("jacquot_marichal_trajectory_servo", gain=a, rate_gain=b)
        print(f"  servo a = {a:<4} b = {b:<3}: {error:.3f}")
    for interval in (5.0, 1.0):
        error = largest_error("jacquot_marichal_trajectory_servo", recompute_interval=interval)
        print(f"  servo a = 1 b = 0.5, K refreshed every {interval:g} s: {error:.3f}")
    error = largest_error("jacquot_marichal_trajectory_servo", time_step=0.001, step=0.001)
    print(f"  servo a = 1 b = 0.5, dt = 0.001 s: {error:.3f}")


if __name__ == "__main__":
    main()
