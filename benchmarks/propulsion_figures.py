"""Print the figures of the propeller and the fins (forces.propeller, forces.bseries,
forces.fin): the B-series' curves over the series (zero-thrust advance, best open-water
efficiency), the roll decays' damping ratios against their linearised values
(tests/test_propulsion.py), and the example examples/propeller_and_fins_roll_at_speed.yaml
with and without its fins. Run: python benchmarks/propulsion_figures.py"""

import math
import sys
from pathlib import Path

import numpy as np
import yaml
from scipy.optimize import brentq

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests import test_propulsion as tp  # noqa: E402

import seacable  # noqa: E402
from seacable.forces import bseries  # noqa: E402

EXAMPLE = ROOT / "examples" / "propeller_and_fins_roll_at_speed.yaml"


def b_series():
    print("B-series (Rn 2e6): J where K_T vanishes over P/D, best eta_0 (at J)")
    for blades in (3, 4, 5):
        for area in (0.4, 0.7, 1.0):
            cells = []
            for pitch in (0.5, 0.8, 1.0, 1.2, 1.4):
                kt, kq = bseries.cubics(pitch, area, blades)
                zero = bseries.zero_thrust(kt)
                advance = np.linspace(0.0, zero, 2001)
                eta = bseries.efficiency(advance, np.polyval(kt[::-1], advance),
                                         np.polyval(kq[::-1], advance))  # fmt: skip
                cells.append(f"{zero / pitch:.3f} {eta.max():.3f} ({advance[eta.argmax()]:.2f})")
            print(f"  B{blades}-{round(100 * area)}: " + "; ".join(cells))


def roll_decays():
    print("roll decay at 6 m/s: damping ratio measured (3 periods) / linearised")
    gain = 2 * tp.FIN_ARM * 0.5 * tp.RHO * tp.SPEED**2 * tp.FIN_AREA * tp.FIN_SLOPE
    for label, fins, damping, stiffness in (
        ("hull alone", [], tp.ROLL_DAMPING, tp.ROLL_STIFFNESS),
        ("fins held at 0", tp._fins(angle_deg=0.0), tp.ROLL_DAMPING + gain * tp.FIN_ARM / tp.SPEED,
         tp.ROLL_STIFFNESS),
        ("roll controller", tp._fins(roll_controller={"gain": 0.5, "rate_gain": 2.0}),
         tp.ROLL_DAMPING + gain * (2.0 + tp.FIN_ARM / tp.SPEED), tp.ROLL_STIFFNESS + 0.5 * gain),
    ):  # fmt: skip
        ratios = tp._roll_decay(fins)
        expected = damping / (2.0 * math.sqrt(stiffness * tp.ROLL_INERTIA))
        print(f"  {label:16s} {np.round(ratios, 5).tolist()} / {expected:.5f}")


def _amplitude(roll, time, start):
    late = roll[time >= start]
    return 0.5 * (late.max() - late.min()), late.mean()


def example():
    data = yaml.safe_load(EXAMPLE.read_text())
    print(f"{EXAMPLE.name}:")
    for label in ("with its fins", "without fins"):
        results = seacable.simulate(seacable.load_case(data))
        ship, time = results["bodies/ship"], results["time"].values
        roll = ship["roll"].values
        amplitude, mean = _amplitude(roll, time, 500.0)
        early = np.abs(roll[time <= 120.0]).max()
        print(f"  {label}: speed {ship['velocity_x'].values[-1]:.4f} m/s; roll up to "
              f"{early:.2f} deg in the first 120 s, {amplitude:.2f} deg from 500 s "
              f"(mean {mean:.3f} deg)")  # fmt: skip
        forces = data["bodies"][0]["external forces"]
        data["bodies"][0]["external forces"] = [f for f in forces if f.get("model") != "fin"]
    rate, diameter, wake, deduction = 200.0 / 60.0, 2.6, 0.25, 0.15

    def excess(speed):
        advance = (1 - wake) * speed / (rate * diameter)
        thrust = bseries.coefficients(advance, 1.0, 0.7, 4)[0]
        return (1 - deduction) * 1025.0 * rate**2 * diameter**4 * thrust - 2500.0 * speed**2

    speed = brentq(excess, 0.5, 15.0, xtol=1e-12)
    torque = 1025.0 * rate**2 * diameter**5 * bseries.coefficients(
        (1 - wake) * speed / (rate * diameter), 1.0, 0.7, 4)[1]  # fmt: skip
    print(f"  brentq, hull alone: {speed:.4f} m/s; shaft torque {torque:.0f} N m, a heel of "
          f"{math.degrees(torque / 1.57e7):.3f} deg to port on the hull's stiffness")  # fmt: skip


if __name__ == "__main__":
    b_series()
    roll_decays()
    example()
