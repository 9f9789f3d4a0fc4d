"""What ``seacable upgrade`` once refused, now written as systems: the upgraded system of each
single-cable case of tests/legacy_cases/gaps/, run with the case's integrator, gives the
positions, tensions and end loads of the golden the single-cable core recorded
(tests/golden/record_gaps.py) within 1e-9 of each variable's scale. The new physics of each
is checked against something independent."""

import math

import numpy as np
import pytest
import yaml

import seacable
from golden import record_gaps
from golden.record import compare_to_golden, system_rows
from seacable.case import legacy, loader

# started from a static balance: the single-cable core's Newton stops at 1e-9 of its
# residual's scale, the system's tighter (measured: 4e-9 of the top force's scale in the tows,
# 7e-9 of the anchor force's at t = 0 in the rigid line's static start)
TOLERANCES = {"lumped_exact_tow": 1e-8, "lumped_servo_tow": 1e-8, "rigid_static_to_anchor": 1e-8}


@pytest.mark.parametrize("stem", record_gaps.stems())
def test_upgraded_case_moves_as_its_golden(stem):
    golden = record_gaps.load(stem)
    rows = record_gaps.upgraded(stem)
    tolerance = TOLERANCES.get(stem, 1e-9)
    failures = compare_to_golden(golden, rows, tolerance=tolerance,
                                 label=f"{stem} (system against golden)")  # fmt: skip
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


@pytest.mark.parametrize("method", ["exact", "stiffness_servo"])
def test_a_lumped_tow_starts_in_its_steady_motion(method):
    """A lumped umbilical towed at constant speed with its end held (exactly, or by the servo)
    at a constant offset from the ship, started on its catenary (seacable upgrade: the
    system's static start in the tow's steady motion): the tow is steady, so the tensions
    stay at their start within 1e-9 of their largest and a servo's end stays on its target
    (its force the one that holds it there)."""
    data = yaml.safe_load((record_gaps.CASES / "lumped_servo_tow.yaml").read_text())
    cable = data["cables"][0]
    cable["bottom"].update(method=method, x={"kind": "constant", "value": 60.0},
                           z={"kind": "constant", "value": -60.0})  # fmt: skip
    data["simulation"].update(duration=0.5, output_interval=0.1)
    system = seacable.load_case(legacy.upgrade(loader.load_single_cable(data)))
    ds = seacable.simulate(system).dataset
    tension = ds["lines/umbilical/tension"].values
    assert np.abs(tension - tension[0]).max() < 1e-9 * np.abs(tension).max()
    assert tension.min() > 0.0
    if method == "stiffness_servo":
        assert ds["bodies/end/tracking_error"].values.max() < 1e-9
        force = np.column_stack([ds[f"bodies/end/servo_force_{c}"].values for c in "xyz"])
        assert np.abs(force - force[0]).max() < 1e-9 * np.abs(force).max()


def _star_with(**joints):
    data = yaml.safe_load((record_gaps.CASES / "rigid_star_jointed.yaml").read_text())
    for cable in data["cables"]:
        cable.update(joints)
    return loader.load_single_cable(data)


@pytest.mark.parametrize(
    ("joints", "spring", "damper"),
    [({"joint_damping": 2.0}, 0.0, 2.0), ({"bending_stiffness": 50.0}, 50.0 / 2.5, 0.0)],
)  # fmt: skip
def test_a_star_joint_at_the_top_is_the_lines_tip_joint(joints, spring, damper):
    """A star's cable runs from the shared body and ends held on its top: the single cable's
    joint 0 (one damping for every joint, or EI over the first link) becomes the line's tip
    joint, unloaded along the top's reference direction turned back up the line (it was once
    written with the damper moved to the body's end, a different motion, then refused)."""
    data = {"joint_stiffness": None, "joint_damping": 0.0, **joints}
    single = _star_with(**data)
    lines = legacy.upgrade(single)["lines"]
    tops = [line for line in lines if line["to"].endswith("top")]
    assert len(tops) == 3
    for line, cable in zip(tops, single.cables, strict=True):
        assert line["tip_joint_stiffness"] == spring
        assert line["tip_joint_damping"] == damper
        azimuth = np.radians(cable.initial.azimuth_deg)
        reference = np.radians(cable.top_reference_angle_deg)
        up = [-np.sin(reference) * np.cos(azimuth), -np.sin(reference) * np.sin(azimuth),
              np.cos(reference)]  # fmt: skip
        np.testing.assert_allclose(line["tip_reference"], up, atol=1e-15)
    case = seacable.load_case(legacy.upgrade(single))
    seacable.simulate(
        loader.derive_case(case, {"simulation": {"duration": 0.05, "output_interval": 0.05}})
    )


def test_a_spring_at_a_body_along_the_cable_joins_its_two_lines():
    """A cable cut at a body along it, with a spring and damper at that joint: the line below
    the body ``continues`` the one above, its first section holding the joint's values; with
    the body massless, dragless and without volume, the two lines move as the cable upgraded
    without the body, one line (nodes within 1e-9 m over 1 s)."""
    data = yaml.safe_load((record_gaps.CASES / "float_between_jointed_links.yaml").read_text())
    cable = data["cables"][0]
    cable["joint_stiffness"][3], cable["joint_damping"][3] = 40.0, 0.7
    lines = legacy.upgrade(loader.load_single_cable(data))["lines"]
    assert lines[1]["continues"] == lines[0]["name"] and "continues" not in lines[0]
    first = lines[1]["sections"][0]
    assert (first["joint_stiffness"], first["joint_damping"]) == (40.0, 0.7)
    cable["point_bodies"][0].update(mass=0.0, volume=0.0, drag_coefficient=0.0)
    cut = seacable.load_case(legacy.upgrade(loader.load_single_cable(data)))
    del cable["point_bodies"]
    whole = seacable.load_case(legacy.upgrade(loader.load_single_cable(data)))
    assert len(cut.lines) == 2 and len(whole.lines) == 1
    a, b = (system_rows(seacable.simulate(case).dataset, case) for case in (cut, whole))
    for c in "xyz":
        np.testing.assert_allclose(a[f"node_{c}"], b[f"node_{c}"], rtol=0, atol=1e-9)


@pytest.mark.parametrize("model", ["lumped_mass", "natural_string"])
def test_section_joints_a_line_model_has_not_are_refused(model):
    """A section's joint_damping on a lumped-mass line (no bending damper), any joint on a
    natural string (no joints): refused naming the section."""
    section = {"type": "t", "length": 10.0, "segments": 4, "joint_damping": 1.0}
    line = {"name": "l", "model": model, "from": "pin", "to": "ball", "sections": [section]}
    if model == "natural_string":
        line.update(initial={"arc_deg": [10.0, 10.0]})
    case = seacable.load_case({
        "environment": {"in_air": True},
        "bodies": [{"name": "pin", "type": "fixed", "position": [0, 0, 0]},
                   {"name": "ball", "type": "point", "position": [0, 0, -10.0], "mass": 1.0,
                    "external forces": [{"model": "gravity"}]}],
        "line_types": [{"name": "t", "diameter": 0.01, "mass_per_length": 0.1,
                        "axial_stiffness": 1e5}],
        "lines": [line], "start": "as_given",
        "simulation": {"duration": 0.1, "output_interval": 0.05},
    })  # fmt: skip
    message = (r"lines\[0\] \(l\)\.sections\[0\]\.joint_damping: a natural_string has no joints"
               if model == "natural_string" else
               r"lines\[0\] \(l\)\.sections: joint_damping is for rigid lines")  # fmt: skip
    with pytest.raises(seacable.CaseError, match=message):
        seacable.simulate(case)
