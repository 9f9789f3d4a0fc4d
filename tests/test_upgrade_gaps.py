"""What ``seacable upgrade`` once refused, now written as systems: each single-cable case of
tests/legacy_cases/gaps/ and its upgraded system run with the same integrator give the same
positions, tensions and end loads within 1e-9 of each variable's scale, and match the golden
the single-cable core recorded (tests/golden/record_gaps.py: the comparison that remains when
that core is deleted). The new physics of each is checked against something independent."""

import math

import numpy as np
import pytest

import seacable
from golden import record_gaps
from golden.record import compare_to_golden


@pytest.mark.parametrize("stem", record_gaps.stems())
def test_upgraded_case_moves_as_the_single_cable_and_its_golden(stem):
    golden = record_gaps.load(stem)
    rows = record_gaps.upgraded(stem)
    failures = compare_to_golden(golden, rows, label=f"{stem} (system against golden)")
    old = record_gaps.single_cable(stem)  # while the single-cable core exists
    failures += compare_to_golden(old, rows, label=f"{stem} (system against single cable)")
    assert not failures, "\n".join(failures)


def test_sections_give_each_joint_its_spring_on_unequal_links():
    """Two planar links of unequal lengths and masses, each joint with its own spring (the
    sections' joint_stiffness), a point mass m_e at the end, in air, started at small angles
    along the slow mode of the closed-form linear problem M q'' + K q = 0 in the links'
    angles (uniform rods): the first link swings at that mode's period (zero crossings of its
    angle over three periods, within 1e-6; measured 1e-9)."""
    l1, l2, mu1, mu2, k0, k1, tip, g = 0.7, 0.4, 3.0, 1.2, 40.0, 9.0, 0.5, 9.81
    m1, m2 = mu1 * l1, mu2 * l2
    mass = np.array([[m1 * l1**2 / 3 + (m2 + tip) * l1**2, (m2 / 2 + tip) * l1 * l2],
                     [(m2 / 2 + tip) * l1 * l2, m2 * l2**2 / 3 + tip * l2**2]])  # fmt: skip
    stiffness = np.array([[k0 + k1 + (m1 / 2 + m2 + tip) * g * l1, -k1],
                          [-k1, k1 + (m2 / 2 + tip) * g * l2]])  # fmt: skip
    values, vectors = np.linalg.eig(np.linalg.solve(mass, stiffness))
    slow = int(np.argmin(values.real))
    period = 2 * math.pi / math.sqrt(values.real[slow])
    angles = 1e-3 * vectors[:, slow].real / np.abs(vectors[:, slow].real).max()  # [rad]
    end = [l1 * math.sin(angles[0]) + l2 * math.sin(angles[1]), 0.0,
           -l1 * math.cos(angles[0]) - l2 * math.cos(angles[1])]  # fmt: skip
    types = [{"name": name, "diameter": 0.02, "mass_per_length": mu,
              "added_mass_coefficient": 0.0} for name, mu in (("a", mu1), ("b", mu2))]  # fmt: skip
    case = seacable.load_case({
        "environment": {"in_air": True, "gravity": g}, "start": "as_given",
        "bodies": [{"name": "pin", "type": "fixed", "position": [0, 0, 0]},
                   {"name": "end", "type": "point", "position": end, "mass": tip,
                    "external forces": [{"model": "gravity"}]}],
        "line_types": types,
        "lines": [{"name": "chain", "model": "rigid_links", "from": "pin", "to": "end",
                   "base_reference": [0.0, 0.0, -1.0],
                   "initial": {"angles_deg": np.degrees(angles).tolist()},
                   "sections": [{"type": "a", "length": l1, "segments": 1, "joint_stiffness": k0},
                                {"type": "b", "length": l2, "segments": 1,
                                 "joint_stiffness": k1}]}],
        "simulation": {"duration": round(3.2 * period, 2), "output_interval": 0.002,
                       "integrator": "dopri5", "rtol": 1e-11},
    })  # fmt: skip
    ds = seacable.simulate(case).dataset
    t = ds["time"].values
    first = ds["lines/chain/node_x"].values[:, 1]  # l1 sin(angle 1)
    down = np.flatnonzero((first[:-1] > 0) & (first[1:] <= 0))
    crossings = t[down] - first[down] * (t[down + 1] - t[down]) / (first[down + 1] - first[down])
    measured = (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    assert len(crossings) == 3
    assert abs(measured / period - 1) < 1e-6, (measured, period)
