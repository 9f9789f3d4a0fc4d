"""The extensible lumped-mass cable: closed-form elastic catenary (against MoorPy), a mooring
line started from it, energy, the axial natural frequency, no compression."""

import math

import numpy as np
import pytest

import seacable
from helpers import chain_case
from seacable.case import legacy
from seacable.lines import catenary
from seacable.models import lumped_mass


def _load(source):
    """A case of either form: the single-cable form (``cables:``) through
    ``load_single_cable`` while the single-cable core exists, a system through ``load_case``."""
    from pathlib import Path

    from seacable.case import loader

    text = (
        Path(source).read_text()
        if isinstance(source, (str, Path)) and Path(str(source)).exists()
        else source
    )
    single = ("cables" in text) if isinstance(text, dict) else ("\ncables:" in "\n" + str(text))
    return loader.load_single_cable(source) if single else seacable.load_case(source)


moorpy_catenary = pytest.importorskip("moorpy.Catenary").catenary

RHO = 1025.0
W = (126.0 - RHO * math.pi * 0.137**2 / 4) * 9.81  # chain apparent weight [N/m]
EA = 5.8e8


@pytest.mark.parametrize("span", [80.0, 100.0, 120.0, 140.0, 155.0])
def test_closed_form_catenary_matches_moorpy(span):
    h, v = catenary.solve(span, 190.0, 250.0, W, EA, seabed=True)
    fa_h, fa_v, fb_h, fb_v, _ = moorpy_catenary(span, 190.0, 250.0, EA, W, CB=0.0)
    np.testing.assert_allclose([h, v], [-fb_h, -fb_v], rtol=1e-8)
    x, z = catenary.profile([0.0, 250.0], h, v, 250.0, W, EA, seabed=True)
    np.testing.assert_allclose([x[-1], z[-1]], [span, 190.0], atol=1e-6)


def mooring(n=40, duration=20.0, top=None, **simulation):
    return _load(
        {
            "environment": {
                "water_density": RHO,
                "water_depth": 200.0,
                "seabed": {"stiffness": 3.0e5, "damping": 3.0e3},
            },  # fmt: skip
            "cables": [
                {
                    "model": "lumped_mass",
                    "links": n,
                    "length": 250.0,
                    "diameter": 0.137,
                    "mass_per_length": 126.0,
                    "axial_stiffness": EA,
                    "axial_damping_time": 0.002,
                    "drag_coefficient_normal": 1.2,
                    "drag_coefficient_tangential": 0.1,
                    "top": top or {"type": "fixed", "position": [0.0, 0.0, -10.0]},
                    "bottom": {"type": "pinned", "anchor": [-100.0, 0.0, -200.0]},
                    "initial": {"shape": "catenary"},
                }
            ],
            "simulation": {
                "duration": duration,
                "output_interval": 0.5,
                "integrator": "dopri5",
                "rtol": 1e-6,
                "atol": 1e-8,
                **simulation,
            },  # fmt: skip
        }
    )


def test_mooring_line_starts_in_discrete_equilibrium_near_the_closed_form():
    """The catenary start is polished to the discrete line's equilibrium (the chords through the
    continuous curve are short where it bends): the line then stays still, its fairlead tension
    within 0.1 % of the closed-form elastic catenary with 40 segments."""
    h, v = catenary.solve(100.0, 190.0, 250.0, W, EA, seabed=True)
    ds = seacable.simulate(mooring(duration=20.0)).dataset
    tension = np.hypot(ds["top_force_x"].values, ds["top_force_z"].values)
    assert np.ptp(tension) < 1e-6 * tension[0]
    assert abs(tension[0] / math.hypot(h, v) - 1) < 1e-3
    on_seabed = np.sum(ds["node_z"].values[-1] < -199.9) * 250.0 / 40
    assert abs(on_seabed - (250.0 - v / W)) < 2 * 250.0 / 40  # within two segments
    assert np.all(ds["tension"].values > 0.0)


def test_energy_is_conserved_without_damping():
    case = _load(
        {
            "environment": {"in_air": True},
            "cables": [
                {
                    "model": "lumped_mass",
                    "links": 20,
                    "length": 10.0,
                    "diameter": 0.01,
                    "mass_per_length": 1.0,
                    "axial_stiffness": 2.0e4,
                    "top": {"type": "fixed"},
                    "bottom": {"type": "free", "body": {"mass": 1.0}},
                    "initial": {"shape": "arc", "top_angle_deg": 50.0},
                }
            ],
            "simulation": {
                "duration": 3.0,
                "output_interval": 0.02,
                "integrator": "dopri5",
                "rtol": 1e-10,
                "atol": 1e-12,
            },  # fmt: skip
        }
    )
    ds = seacable.simulate(case).dataset
    energy = ds["total_energy"].values
    drift = np.max(np.abs(energy - energy[0])) / np.ptp(ds["kinetic_energy"].values)
    assert drift < 1e-6, drift


def test_axial_frequency_of_a_hanging_mass():
    """A light elastic line with a heavy end mass bounces at omega = sqrt(EA / (L (M + m/3)))."""
    length, ea, end_mass, line_mass = 20.0, 1.0e6, 500.0, 5.0
    case = _load(
        {
            "environment": {"in_air": True},
            "cables": [
                {
                    "model": "lumped_mass",
                    "links": 20,
                    "length": length,
                    "diameter": 0.01,
                    "mass_per_length": line_mass / length,
                    "axial_stiffness": ea,
                    "top": {"type": "fixed"},
                    "bottom": {"type": "free", "body": {"mass": end_mass}},
                    "initial": {"shape": "arc", "top_angle_deg": 0.0},
                }
            ],
            "simulation": {
                "duration": 4.0,
                "output_interval": 0.001,
                "integrator": "dopri5",
                "rtol": 1e-9,
                "atol": 1e-11,
            },  # fmt: skip
        }
    )
    ds = seacable.simulate(case).dataset
    z = ds["node_z"].values[:, -1]
    t = ds["time"].values
    centre = 0.5 * (z.max() + z.min())
    crossings = t[1:][np.diff(np.sign(z - centre)) > 0]
    period = np.mean(np.diff(crossings))
    expected = 2 * math.pi / math.sqrt(ea / (length * (end_mass + line_mass / 3)))
    assert abs(period / expected - 1) < 2e-3
    assert np.all(ds["tension"].values >= 0.0)  # it never pushes


def test_lumped_model_needs_axial_stiffness():
    data = {
        "cables": [
            {
                "model": "lumped_mass",
                "links": 5,
                "length": 10.0,
                "diameter": 0.01,
                "mass_per_length": 1.0,
                "top": {"type": "fixed"},
                "bottom": {"type": "free"},
            }
        ],
        "simulation": {"duration": 1.0, "output_interval": 0.5},
    }
    with pytest.raises(seacable.CaseError, match=r"axial_stiffness: a lumped-mass cable needs EA"):
        seacable.simulate(_load(data))


def test_clump_weight_adds_its_weight_to_the_tension_above_it():
    """A vertical line in air settles (strong axial damping) with a 5 kg clump weight at node 5:
    the tension steps by the clump's weight plus one segment's across it, and every segment
    carries what hangs below it."""
    g, mu, body, clump = 9.81, 1.0, 10.0, 5.0
    case = _load(
        {
            "environment": {"in_air": True, "gravity": g},
            "cables": [
                {
                    "model": "lumped_mass",
                    "links": 10,
                    "length": 10.0,
                    "diameter": 0.01,
                    "mass_per_length": mu,
                    "axial_stiffness": 1e5,
                    "axial_damping_time": 0.05,
                    "point_bodies": [{"node": 5, "mass": clump}],
                    "top": {"type": "fixed"},
                    "bottom": {"type": "free", "body": {"mass": body}},
                    "initial": {"shape": "arc", "top_angle_deg": 0.0},
                }
            ],
            "simulation": {
                "duration": 3.0,
                "output_interval": 0.5,
                "integrator": "bdf",
            },  # fmt: skip
        }
    )
    tension = seacable.simulate(case).dataset["tension"].values[-1]
    # each segment carries the nodes below its centre: the body, the half segments and clump
    expected = g * (body + mu * (9 - np.arange(10)) + 0.5 * mu + clump * (np.arange(10) < 5))
    assert np.allclose(tension, expected, rtol=1e-4), (tension, expected)


def _bent(model, n=20, **simulation):
    cable = {
        "model": model,
        "links": n,
        "length": 4.0,
        "diameter": 0.02,
        "mass_per_length": 1.0,
        "joint_stiffness": [0.0] + [50.0] * (n - 1),  # the lumped top is a pin
        "top": {"type": "fixed"},
        "bottom": {"type": "free", "body": {"mass": 1.0}},
        "initial": {"shape": "arc", "top_angle_deg": 60.0, "bottom_angle_deg": 0.0},
    }
    if model == "lumped_mass":
        cable.update(axial_stiffness=1e5)
    sim = {"duration": 1.0, "output_interval": 0.05, "integrator": "dopri5", "rtol": 1e-9}
    sim.update({"atol": 1e-10, **simulation})
    return _load({"environment": {"in_air": True}, "cables": [cable], "simulation": sim})


def test_bending_forces_are_the_gradient_of_the_bending_energy():
    """No damping: total energy, bending energy included, is kept to the integrator's
    tolerance."""
    ds = seacable.simulate(_bent("lumped_mass")).dataset
    energy = ds["total_energy"].values
    assert np.max(np.abs(energy - energy[0])) < 1e-6 * np.ptp(ds["kinetic_energy"].values)


@pytest.mark.slow  # 10 s: six runs
def test_a_bent_lumped_line_swings_like_the_rigid_segment_cable():
    """A stiff lumped line with bending swings like the rigid-segment cable with the same
    joint springs, closer as the segments get shorter (their masses differ by the segments'
    rotational inertia)."""
    gaps = []
    for n in (10, 20, 40):
        a = seacable.simulate(_bent("lumped_mass", n=n)).dataset
        b = seacable.simulate(_bent("rigid_segments_3d", n=n)).dataset
        gap = np.hypot(
            a["node_x"].values[:, -1] - b["node_x"].values[:, -1],
            a["node_z"].values[:, -1] - b["node_z"].values[:, -1],
        )
        gaps.append(gap.max())
    assert gaps[2] < 0.02 and gaps[2] < 0.25 * gaps[0], gaps


def _heaving(model, **simulation):
    cable = {
        "model": model,
        "links": 20,
        "length": 20.0,
        "diameter": 0.05,
        "mass_per_length": 5.0,
        "top": {
            "type": "floating_structure",
            "mass": 1000.0,
            "heave_stiffness": 2.0e4,
            "heave_damping": simulation.pop("heave_damping", 0.0),
            "force": {"kind": "sine", "amplitude": 5000.0, "period": 3.0},
        },
        "bottom": {"type": "free", "body": {"mass": 50.0}},
        "initial": {"shape": "arc", "top_angle_deg": 30.0, "bottom_angle_deg": 10.0},
    }
    if model == "lumped_mass":
        cable["axial_stiffness"] = 1e8
    sim = {"duration": 4.0, "output_interval": 0.1, "integrator": "dopri5", "rtol": 1e-9}
    sim.update({"atol": 1e-10, **simulation})
    return _load({"environment": {"in_air": True}, "cables": [cable], "simulation": sim})


@pytest.mark.slow  # 13 s; a heaving body over a line is checked on the system path by the goldens
def test_floating_structure_top_heaves_like_the_rigid_link_model():
    """A stiff lumped line under a heaving structure against the planar rigid-link cable: the
    structure's heave and the end mass agree to the difference of the two discretisations
    (rotational inertia of the links) and the axial compliance."""
    rigid = seacable.simulate(_heaving("rigid_links")).dataset
    lumped = seacable.simulate(_heaving("lumped_mass")).dataset
    heave_gap = np.abs(lumped["node_z"].values[:, 0] - rigid["node_z"].values[:, 0]).max()
    end_gap = np.hypot(
        lumped["node_x"].values[:, -1] - rigid["node_x"].values[:, -1],
        lumped["node_z"].values[:, -1] - rigid["node_z"].values[:, -1],
    ).max()
    swing = np.ptp(rigid["node_z"].values[:, 0])
    assert swing > 0.1
    assert heave_gap < 0.01 * swing and end_gap < 0.05, (heave_gap, end_gap, swing)


def test_floating_structure_energy_balance():
    """No damping but the applied force: total energy changes by the force's work only; with
    the force off it is kept."""
    case = _heaving("lumped_mass", duration=2.0)
    data = case.model_dump(mode="json", exclude_unset=True)
    data["cables"][0]["top"]["force"] = 0.0
    data["cables"][0]["top"]["initial_heave"] = 0.3
    ds = seacable.simulate(_load(data)).dataset
    energy = ds["total_energy"].values
    assert np.max(np.abs(energy - energy[0])) < 1e-6 * np.ptp(ds["kinetic_energy"].values)


def test_two_floating_structures_like_the_rigid_link_model():
    """Thesis 6.3 (a cable between two floating structures; the second one held by heave and
    surge spring-dampers) without joint springs, as a system, both lines started on their
    catenary: a steel lumped line (EA of the 20 mm rod) under generalized-alpha moves both
    structures like the rigid-link line over the first 3 s."""
    case = _load("examples/thesis_6_3_sim1_two_floating_structures.yaml")
    data = case.model_dump(mode="json", by_alias=True, exclude_unset=True)
    data["line_types"][0].pop("bending_stiffness")
    data["lines"][0].update(joint_damping=0.0, initial="catenary")  # both lines start on it
    data["simulation"].update(duration=3.0)
    rigid = seacable.simulate(_load(data)).dataset
    data["line_types"][0]["axial_stiffness"] = 2.1e11 * math.pi * 0.01**2
    data["lines"][0] = {k: v for k, v in data["lines"][0].items()
                        if k in ("name", "from", "to", "sections")}  # fmt: skip
    data["lines"][0].update(model="lumped_mass", initial="catenary")
    data["simulation"].update(integrator="generalized_alpha", time_step=2e-3)
    lumped = seacable.simulate(_load(data)).dataset
    for body in ("top", "end"):
        for axis in ("position_x", "position_z"):
            a, b = lumped[f"bodies/{body}/{axis}"].values, rigid[f"bodies/{body}/{axis}"].values
            assert np.abs(a - b).max() < 0.02, (body, axis, np.abs(a - b).max())
    assert np.ptp(rigid["bodies/top/position_z"].values) > 1.0  # the top structure does heave


def _held_case(model, bottom, shape, duration=8.0, links=30):
    cable = {
        "model": model,
        "links": links,
        "length": 100.0,
        "diameter": 0.03,
        "mass_per_length": 2.0,
        "drag_coefficient_normal": 1.2,
        "top": {"type": "fixed", "position": [0.0, 0.0, 0.0]},
        "initial": shape,
        "bottom": bottom,
    }
    if model == "lumped_mass":
        cable.update(axial_stiffness=1e8, axial_damping_time=0.001)
    simulation = {"duration": duration, "output_interval": 0.1, "integrator": "dopri5"}
    return _load(
        {"environment": {"water_depth": 200.0}, "cables": [cable], "simulation": simulation}
    )


def _trajectory(moving=True):
    # starts at rest at (40, 0, -80) and moves smoothly in x and y (1 - cos)
    amp_x, amp_y = (4.0, 3.0) if moving else (0.0, 0.0)
    phase = -math.pi / 2
    return {
        "type": "trajectory",
        "relative_to_top": False,
        "x": {"kind": "sine", "amplitude": amp_x, "period": 12.0, "phase": phase,
              "offset": 40.0 + amp_x},
        "y": {"kind": "sine", "amplitude": amp_y, "period": 10.0, "phase": phase, "offset": amp_y},
        "z": {"kind": "constant", "value": -80.0},
    }  # fmt: skip


FORCES = [f"{end}_force_{a}" for end in ("top", "bottom") for a in "xyz"]


def test_trajectory_end_starts_in_the_rigid_models_static_equilibrium():
    # the discrete line's equilibrium polished from the catenary through the target, against the
    # rigid-segment model's static shape (an inextensible chain: EA = 1e8 stretches it 1e-5)
    lumped = seacable.simulate(
        _held_case("lumped_mass", _trajectory(False), {"shape": "catenary"}, duration=0.5)
    ).dataset
    rigid = seacable.simulate(
        _held_case("rigid_segments_3d", _trajectory(False), {"shape": "static"}, duration=0.5)
    ).dataset
    for name in FORCES:
        a, b = lumped[name].values, rigid[name].values
        assert np.allclose(a, b[0], rtol=2e-3, atol=0.5), (name, a, b)  # static: constant too


def test_trajectory_end_follows_its_target_like_the_rigid_model():
    lumped = seacable.simulate(
        _held_case("lumped_mass", _trajectory(), {"shape": "catenary"})
    ).dataset
    rigid = seacable.simulate(
        _held_case("rigid_segments_3d", _trajectory(), {"shape": "static"})
    ).dataset
    t = lumped["time"].values
    target_x = 44.0 - 4.0 * np.cos(2 * np.pi * t / 12.0)
    assert np.abs(lumped["node_x"].values[:, -1] - target_x).max() < 1e-6
    for a in "xyz":
        mid = lumped[f"node_{a}"].values[:, 15]
        assert np.abs(mid - rigid[f"node_{a}"].values[:, 15]).max() < 0.02  # [m], the models
    for name in ("top_force_x", "top_force_z", "bottom_force_x"):
        a, b = lumped[name].values, rigid[name].values
        assert np.abs(a - b).max() < 0.08 * np.abs(b).max(), name


def test_guided_end_moves_like_the_rigid_model_and_all_axes_hold_like_a_pin():
    bottom = {
        "type": "free",
        "body": {"mass": 20.0, "volume": 0.005, "drag_coefficient": 1.0, "drag_area": 0.2},
        "hold_axes": ["x", "y"],
    }
    arc = {"shape": "arc", "top_angle_deg": 30.0, "bottom_angle_deg": 60.0}
    cases = {
        "lumped": _held_case("lumped_mass", bottom, arc),
        "rigid": _held_case("rigid_segments_3d", bottom, arc),
    }
    runs = {k: seacable.simulate(c).dataset for k, c in cases.items()}
    end_z = {k: ds["node_z"].values[:, -1] for k, ds in runs.items()}
    assert np.ptp(end_z["lumped"]) > 0.5  # it moves along its guide
    assert np.ptp(runs["lumped"]["node_x"].values[:, -1]) == 0.0
    assert np.abs(end_z["lumped"] - end_z["rigid"]).max() < 5e-3
    everywhere = {**bottom, "hold_axes": ["x", "y", "z"]}
    held = seacable.simulate(_held_case("lumped_mass", everywhere, arc, duration=2.0)).dataset
    pinned = seacable.simulate(
        _held_case("lumped_mass", {"type": "pinned"}, arc, duration=2.0)
    ).dataset
    assert np.abs(held["node_x"].values - pinned["node_x"].values).max() < 1e-9
    for name in FORCES:  # the body's own loads are not the cable's
        assert np.abs(held[name].values - pinned[name].values).max() < 1e-3, name


def test_a_line_held_at_both_ends_starts_with_velocities_between_its_ends():
    """A surging fairlead over an anchor: the initial node velocities go linearly along the line
    from the fairlead's to the anchor's (zero), so no segment starts with a jump in strain rate
    (every node at the fairlead's velocity but the anchored one gave 511 kN at the anchor at
    t = 0 on the mooring example without build-up, against 21-29 kN in the steady state)."""
    from seacable.simulation import build_system

    surge = {"kind": "sine", "amplitude": 5.0, "period": 12.0, "offset": 5.0}
    case = mooring(top={"type": "imposed", "x": surge, "z": -10.0}, duration=1.0)
    system = build_system(case)
    n = system.params.n
    velocities = system.y0[3 * (n + 1) : 6 * (n + 1)].reshape(n + 1, 3)
    fairlead = 5.0 * 2.0 * math.pi / 12.0
    along = np.linspace(0.0, 1.0, n + 1)  # equal segments
    np.testing.assert_allclose(velocities[:, 0], fairlead * (1.0 - along), atol=1e-12)
    np.testing.assert_array_equal(velocities[:, 1:], 0.0)
    first = seacable.simulate(case).dataset
    steady = 30e3  # N: the steady state's largest anchor force is under 29 kN
    bottom = np.hypot(first["bottom_force_x"], first["bottom_force_z"])
    assert float(bottom.max()) < 2.0 * steady


def _lone_segment(ratio, ea=100.0, mass=1.0, pull=20.0, duration=1.5):
    """One segment (1 m, ``mass`` kg, EA ``ea`` N) free at both ends, in air: its top on a
    floating structure of negligible mass free in heave, its lower end pulled down by ``pull``
    N from t = 0. Both ends fall with g; their separation s obeys (m/4) s'' = -N + pull / 2
    with N = EA (s + alpha s') / l: a spring-mass of reduced mass m/4, whose step response
    from rest settles at s = pull l / (2 EA)."""
    simulation = {"duration": duration, "output_interval": 5e-4, "integrator": "dopri5"}
    data = chain_case(
        1,
        top={"type": "floating_structure", "mass": 1e-9, "heave_stiffness": 0.0},
        bottom={"type": "free", "body": {"force_z": -pull}},
        simulation={**simulation, "rtol": 1e-10, "atol": 1e-12},
        model="lumped_mass",
        length=1.0,
        mass_per_length=mass,
        axial_stiffness=ea,
        axial_damping_ratio=ratio,
    )
    return _load(data)


@pytest.mark.parametrize("ratio", [0.5, 1.0])
def test_axial_damping_ratio_damps_a_lone_segment_as_its_fraction_of_critical(ratio):
    """Ratio 1 returns without overshoot (critical); 0.5 overshoots by exp(-pi z / sqrt(1 - z^2))
    = 16.3 % (a ratio off by a factor sqrt 2 either way would give 4.3 % or 44 %)."""
    ea, pull = 100.0, 20.0
    ds = seacable.simulate(_lone_segment(ratio, ea=ea, pull=pull)).dataset
    stretch = ds["node_z"].values[:, 0] - ds["node_z"].values[:, 1] - 1.0
    settled = pull / (2 * ea)
    overshoot = stretch.max() / settled - 1
    if ratio < 1:
        expected = math.exp(-math.pi * ratio / math.sqrt(1 - ratio**2))
        assert abs(overshoot - expected) < 2e-3, (overshoot, expected)
    else:
        assert overshoot < 1e-6, overshoot
        assert abs(stretch[-1] / settled - 1) < 1e-5  # and it has settled within 1.5 s
    assert np.all(ds["tension"].values[1:] > 0.0)  # the linear law throughout


def test_axial_damping_ratio_is_the_fraction_of_each_segments_critical_damping():
    """alpha_i = zeta l_i sqrt(mu_i / EA) per segment (unequal segments), i.e. MoorDyn's
    BA = zeta l sqrt(EA mu) [N s] = EA alpha; the time form gives the same alpha everywhere."""
    lengths, masses, ea, ratio = [2.0, 1.0, 0.5], [10.0, 3.0, 2.0], 4.0e6, 0.8
    cable = {
        "model": "lumped_mass",
        "links": 3,
        "link_lengths": lengths,
        "link_masses": masses,
        "diameter": 0.05,
        "axial_stiffness": ea,
        "axial_damping_ratio": ratio,
        "top": {"type": "fixed"},
        "bottom": {"type": "free"},
    }
    data = {"cables": [cable], "simulation": {"duration": 1.0, "output_interval": 0.5}}
    alpha = lumped_mass.build(_load(data)).params.axial_damping
    mu = np.array(masses) / np.array(lengths)
    np.testing.assert_allclose(ea * alpha, ratio * np.array(lengths) * np.sqrt(ea * mu), rtol=1e-14)
    del cable["axial_damping_ratio"]
    cable["axial_damping_time"] = 0.003
    alpha = lumped_mass.build(_load(data)).params.axial_damping
    np.testing.assert_array_equal(alpha, [0.003] * 3)


def test_axial_damping_is_given_one_way():
    data = chain_case(3, model="lumped_mass", axial_stiffness=1e6)
    data["cables"][0].update(axial_damping_time=0.01, axial_damping_ratio=1.0)
    with pytest.raises(
        seacable.CaseError,
        match=r"cables\[0\]: give at most one of 'axial_damping_time' \[s\] or "
        r"'axial_damping_ratio'",
    ):
        _load(data)
    data = chain_case(3, model="natural_string", axial_stiffness=1e6, axial_damping_ratio=1.0)
    with pytest.raises(
        seacable.CaseError,
        match=r"cables\[0\]: axial_damping_ratio is for model 'lumped_mass' \(got model "
        r"'natural_string'\); give axial_damping_time",
    ):
        _load(data)


def _upgraded_gap(case) -> float:
    """Largest gap [m] between the single-cable run's nodes and those of its system form
    (``seacable upgrade``: the cable's lines joined end to end)."""
    old = seacable.simulate(case).dataset
    system = legacy.upgrade(case)
    new = seacable.simulate(_load(system)).dataset
    lines = [new[f"lines/{line['name']}"] for line in system["lines"]]
    gap = 0.0
    for axis in ("node_x", "node_z"):
        parts = [lines[0][axis].values, *(ln[axis].values[:, 1:] for ln in lines[1:])]
        joined = np.concatenate(parts, axis=1)
        gap = max(gap, float(np.abs(joined - old[axis].values).max()))
    return gap


ARC = {"shape": "arc", "top_angle_deg": 30.0, "bottom_angle_deg": 60.0}


@pytest.mark.parametrize(
    "bottom",
    [
        {"type": "free", "body": {"mass": 20.0, "volume": 0.005, "drag_coefficient": 1.0,
                                  "drag_area": 0.2}, "hold_axes": ["x", "y"]},
        {"type": "pinned"},
        {"type": "free", "body": {"mass": 20.0}},
    ],
    ids=["guided", "pinned", "free"],
)  # fmt: skip
def test_upgraded_lumped_cable_moves_as_the_single_cable(bottom):
    """seacable upgrade writes a lumped cable started at given angles as a system (its nodes at
    those angles, the end body where the shape ends): the same motion to round-off."""
    assert _upgraded_gap(_held_case("lumped_mass", bottom, ARC, duration=2.0)) < 1e-9


def test_upgraded_lumped_cable_with_a_float_along_it_moves_as_the_single_cable():
    """A float at node 10 of 30: the cable cut into two lines that meet at a point body."""
    case = _held_case("lumped_mass", {"type": "pinned"}, ARC, duration=2.0)
    data = case.model_dump(mode="json", exclude_unset=True)
    data["cables"][0]["point_bodies"] = [{"node": 10, "mass": 30.0, "volume": 0.1,
                                          "drag_coefficient": 0.8, "drag_area": 0.3}]  # fmt: skip
    assert _upgraded_gap(_load(data)) < 1e-9


def test_a_lumped_line_at_given_angles_must_reach_its_end_point():
    case = _held_case("lumped_mass", {"type": "pinned"}, ARC, duration=0.1)
    system = legacy.upgrade(case)
    system["bodies"][1]["position"][0] += 0.5  # the anchor, moved off the shape's end
    with pytest.raises(seacable.CaseError, match=r"lines \(cable\)\.initial: the given angles "
                       r"end the line at .* \(0\.5 m apart; allowed 1 mm\)"):  # fmt: skip
        seacable.simulate(_load(system))
