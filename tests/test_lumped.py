"""The extensible lumped-mass cable: closed-form elastic catenary (against MoorPy), a mooring
line started from it, energy, the axial natural frequency, no compression."""

import math

import numpy as np
import pytest

import seacable
from helpers import chain_case, rows, system_data, upgraded
from seacable.case import loader
from seacable.case.system import SystemCase
from seacable.lines import catenary
from seacable.system import model
from seacable.system.assemble import _sections

moorpy_catenary = pytest.importorskip("moorpy.Catenary").catenary

RHO = 1025.0
W = (126.0 - RHO * math.pi * 0.137**2 / 4) * 9.81  # chain apparent weight [N/m]
EA = 5.8e8


def _rows(case) -> dict:
    """A run's rows under the single-cable names (``helpers.rows``) of a system, or of the
    system ``seacable upgrade`` writes for a single-cable case's mapping."""
    return rows(case if isinstance(case, SystemCase) else upgraded(case))


@pytest.mark.parametrize("span", [80.0, 100.0, 120.0, 140.0, 155.0])
def test_closed_form_catenary_matches_moorpy(span):
    h, v = catenary.solve(span, 190.0, 250.0, W, EA, seabed=True)
    fa_h, fa_v, fb_h, fb_v, _ = moorpy_catenary(span, 190.0, 250.0, EA, W, CB=0.0)
    np.testing.assert_allclose([h, v], [-fb_h, -fb_v], rtol=1e-8)
    x, z = catenary.profile([0.0, 250.0], h, v, 250.0, W, EA, seabed=True)
    np.testing.assert_allclose([x[-1], z[-1]], [span, 190.0], atol=1e-6)


def mooring(n=40, duration=20.0, top=None, **simulation):
    """The mooring line as ``seacable upgrade`` writes it (a system of one line)."""
    return upgraded(
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
    ds = _rows(mooring(duration=20.0))
    tension = np.hypot(ds["top_force_x"], ds["top_force_z"])
    assert np.ptp(tension) < 1e-6 * tension[0]
    assert abs(tension[0] / math.hypot(h, v) - 1) < 1e-3
    on_seabed = np.sum(ds["node_z"][-1] < -199.9) * 250.0 / 40
    assert abs(on_seabed - (250.0 - v / W)) < 2 * 250.0 / 40  # within two segments
    assert np.all(ds["tension"] > 0.0)


def test_energy_is_conserved_without_damping():
    case = upgraded(
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
    ds = _rows(case)
    energy = ds["total_energy"]
    drift = np.max(np.abs(energy - energy[0])) / np.ptp(ds["kinetic_energy"])
    assert drift < 1e-6, drift


def test_axial_frequency_of_a_hanging_mass():
    """A light elastic line with a heavy end mass bounces at omega = sqrt(EA / (L (M + m/3)))."""
    length, ea, end_mass, line_mass = 20.0, 1.0e6, 500.0, 5.0
    case = upgraded(
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
    ds = _rows(case)
    z = ds["node_z"][:, -1]
    t = ds["time"]
    centre = 0.5 * (z.max() + z.min())
    crossings = t[1:][np.diff(np.sign(z - centre)) > 0]
    period = np.mean(np.diff(crossings))
    expected = 2 * math.pi / math.sqrt(ea / (length * (end_mass + line_mass / 3)))
    assert abs(period / expected - 1) < 2e-3
    assert np.all(ds["tension"] >= 0.0)  # it never pushes


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
    refusal = r"line type 'cable type' has no axial_stiffness; a lumped-mass line needs EA \[N\]"
    with pytest.raises(seacable.CaseError, match=refusal):
        seacable.simulate(upgraded(data))


def test_clump_weight_adds_its_weight_to_the_tension_above_it():
    """A vertical line in air settles (strong axial damping) with a 5 kg clump weight at node 5:
    the tension steps by the clump's weight plus one segment's across it, and every segment
    carries what hangs below it."""
    g, mu, body, clump = 9.81, 1.0, 10.0, 5.0
    case = upgraded(
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
    tension = _rows(case)["tension"][-1]
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
    return {"environment": {"in_air": True}, "cables": [cable], "simulation": sim}


def test_bending_forces_are_the_gradient_of_the_bending_energy():
    """No damping: total energy, bending energy included, is kept to the integrator's
    tolerance."""
    ds = _rows(_bent("lumped_mass"))
    energy = ds["total_energy"]
    assert np.max(np.abs(energy - energy[0])) < 1e-6 * np.ptp(ds["kinetic_energy"])


@pytest.mark.slow  # 10 s: six runs
def test_a_bent_lumped_line_swings_like_the_rigid_segment_cable():
    """A stiff lumped line with bending swings like the rigid-segment cable with the same
    joint springs, closer as the segments get shorter (their masses differ by the segments'
    rotational inertia)."""
    gaps = []
    for n in (10, 20, 40):
        a = _rows(_bent("lumped_mass", n=n))
        b = _rows(_bent("rigid_segments_3d", n=n))
        gap = np.hypot(
            a["node_x"][:, -1] - b["node_x"][:, -1],
            a["node_z"][:, -1] - b["node_z"][:, -1],
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
    return {"environment": {"in_air": True}, "cables": [cable], "simulation": sim}


@pytest.mark.slow  # 13 s; a heaving body over a line is checked on the system path by the goldens
def test_floating_structure_top_heaves_like_the_rigid_link_model():
    """A stiff lumped line under a heaving structure against the planar rigid-link cable: the
    structure's heave and the end mass agree to the difference of the two discretisations
    (rotational inertia of the links) and the axial compliance."""
    rigid = _rows(_heaving("rigid_links"))
    lumped = _rows(_heaving("lumped_mass"))
    heave_gap = np.abs(lumped["node_z"][:, 0] - rigid["node_z"][:, 0]).max()
    end_gap = np.hypot(
        lumped["node_x"][:, -1] - rigid["node_x"][:, -1],
        lumped["node_z"][:, -1] - rigid["node_z"][:, -1],
    ).max()
    swing = np.ptp(rigid["node_z"][:, 0])
    assert swing > 0.1
    assert heave_gap < 0.01 * swing and end_gap < 0.05, (heave_gap, end_gap, swing)


def test_floating_structure_energy_balance():
    """No damping but the applied force: total energy changes by the force's work only; with
    the force off it is kept."""
    data = _heaving("lumped_mass", duration=2.0)
    data["cables"][0]["top"]["force"] = 0.0
    data["cables"][0]["top"]["initial_heave"] = 0.3
    ds = _rows(data)
    energy = ds["total_energy"]
    assert np.max(np.abs(energy - energy[0])) < 1e-6 * np.ptp(ds["kinetic_energy"])


def test_two_floating_structures_like_the_rigid_link_model():
    """Thesis 6.3 (a cable between two floating structures; the second one held by heave and
    surge spring-dampers) without joint springs, as a system, both lines started on their
    catenary: a steel lumped line (EA of the 20 mm rod) under generalized-alpha moves both
    structures like the rigid-link line over the first 3 s."""
    case = seacable.load_case("examples/thesis_6_3_sim1_two_floating_structures.yaml")
    data = case.model_dump(mode="json", by_alias=True, exclude_unset=True)
    data["line_types"][0].pop("bending_stiffness")
    data["lines"][0].update(joint_damping=0.0, initial="catenary")  # both lines start on it
    data["simulation"].update(duration=3.0)
    rigid = seacable.simulate(seacable.load_case(data)).dataset
    data["line_types"][0]["axial_stiffness"] = 2.1e11 * math.pi * 0.01**2
    data["lines"][0] = {k: v for k, v in data["lines"][0].items()
                        if k in ("name", "from", "to", "sections")}  # fmt: skip
    data["lines"][0].update(model="lumped_mass", initial="catenary")
    data["simulation"].update(integrator="generalized_alpha", time_step=2e-3)
    lumped = seacable.simulate(seacable.load_case(data)).dataset
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
    return {"environment": {"water_depth": 200.0}, "cables": [cable], "simulation": simulation}


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
    lumped = _rows(
        _held_case("lumped_mass", _trajectory(False), {"shape": "catenary"}, duration=0.5)
    )
    rigid = _rows(
        _held_case("rigid_segments_3d", _trajectory(False), {"shape": "static"}, duration=0.5)
    )
    for name in FORCES:
        a, b = lumped[name], rigid[name]
        assert np.allclose(a, b[0], rtol=2e-3, atol=0.5), (name, a, b)  # static: constant too


def test_trajectory_end_follows_its_target_like_the_rigid_model():
    lumped = _rows(_held_case("lumped_mass", _trajectory(), {"shape": "catenary"}))
    rigid = _rows(_held_case("rigid_segments_3d", _trajectory(), {"shape": "static"}))
    t = lumped["time"]
    target_x = 44.0 - 4.0 * np.cos(2 * np.pi * t / 12.0)
    assert np.abs(lumped["node_x"][:, -1] - target_x).max() < 1e-6
    for a in "xyz":
        mid = lumped[f"node_{a}"][:, 15]
        assert np.abs(mid - rigid[f"node_{a}"][:, 15]).max() < 0.02  # [m], the models
    for name in ("top_force_x", "top_force_z", "bottom_force_x"):
        a, b = lumped[name], rigid[name]
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
    runs = {k: _rows(c) for k, c in cases.items()}
    end_z = {k: ds["node_z"][:, -1] for k, ds in runs.items()}
    assert np.ptp(end_z["lumped"]) > 0.5  # it moves along its guide
    assert np.ptp(runs["lumped"]["node_x"][:, -1]) == 0.0
    assert np.abs(end_z["lumped"] - end_z["rigid"]).max() < 5e-3
    everywhere = {**bottom, "hold_axes": ["x", "y", "z"]}
    held = _rows(_held_case("lumped_mass", everywhere, arc, duration=2.0))
    pinned = _rows(_held_case("lumped_mass", {"type": "pinned"}, arc, duration=2.0))
    assert np.abs(held["node_x"] - pinned["node_x"]).max() < 1e-9
    for name in FORCES:  # the body's own loads are not the cable's (dopri5's steps differ)
        scale = np.abs(pinned[name]).max()
        assert np.abs(held[name] - pinned[name]).max() < 1e-3 + 1e-6 * scale, name


def test_a_line_held_at_both_ends_starts_with_velocities_between_its_ends():
    """A surging fairlead over an anchor: the initial node velocities go linearly along the line
    from the fairlead's to the anchor's (zero), so no segment starts with a jump in strain rate
    (every node at the fairlead's velocity but the anchored one gave 511 kN at the anchor at
    t = 0 on the mooring example without build-up, against 21-29 kN in the steady state)."""
    surge = {"kind": "sine", "amplitude": 5.0, "period": 12.0, "offset": 5.0}
    case = mooring(top={"type": "imposed", "x": surge, "z": -10.0}, duration=1.0)
    system = model.build(case)
    n, start = 40, system.params.line_v[0]
    interior = system.y0[start : start + 3 * (n - 1)].reshape(n - 1, 3)  # nodes 1 .. n - 1
    fairlead = 5.0 * 2.0 * math.pi / 12.0
    along = np.linspace(0.0, 1.0, n + 1)[1:-1]  # equal segments
    np.testing.assert_allclose(interior[:, 0], fairlead * (1.0 - along), atol=1e-12)
    np.testing.assert_array_equal(interior[:, 1:], 0.0)
    first = _rows(case)
    steady = 30e3  # N: the steady state's largest anchor force is under 29 kN
    bottom = np.hypot(first["bottom_force_x"], first["bottom_force_z"])
    assert float(bottom.max()) < 2.0 * steady


def _lone_pair(ratio, ea=100.0, mass=1.0, pull=20.0, duration=1.5):
    """Two segments (0.5 m each, ``mass`` kg in all, EA ``ea`` N) between two massless point
    bodies, in air, pulled apart by ``pull`` N at each end from t = 0. They fall with g; by
    symmetry the middle node stays at their centre, and each end's stretch x from it obeys
    (m/4) x'' = pull - 2 EA (x + alpha x'): a spring-mass of damping ratio
    alpha sqrt(2 EA / m) = ratio / sqrt(2) (alpha = ratio l_i sqrt(mu / EA)), settling at
    x = pull / (2 EA)."""
    simulation = {"duration": duration, "output_interval": 5e-4, "integrator": "dopri5",
                  "rtol": 1e-10, "atol": 1e-12}  # fmt: skip
    rope = {"name": "rope", "diameter": 0.01, "mass_per_length": mass, "axial_stiffness": ea,
            "axial_damping_ratio": ratio}  # fmt: skip
    return seacable.load_case({
        "name": "lone pair", "start": "as_given", "environment": {"in_air": True},
        "bodies": [{"name": "top", "type": "point", "position": [0.0, 0.0, 0.0], "mass": 0.0,
                    "external forces": [{"model": "applied", "force_z": pull}]},
                   {"name": "end", "type": "point", "position": [0.0, 0.0, -1.0], "mass": 0.0,
                    "external forces": [{"model": "applied", "force_z": -pull}]}],
        "line_types": [rope],
        "lines": [{"name": "rope", "model": "lumped_mass", "from": "top", "to": "end",
                   "sections": [{"type": "rope", "length": 1.0, "segments": 2}],
                   "initial": "straight"}],
        "simulation": simulation,
    })  # fmt: skip


@pytest.mark.parametrize("ratio", [0.5, 1.0])
def test_axial_damping_ratio_damps_a_segment_pair_as_its_fraction_of_critical(ratio):
    """The pair's damping ratio z = ratio / sqrt 2 overshoots by exp(-pi z / sqrt(1 - z^2)):
    30.5 % at 0.5 and 4.3 % at 1 (a ratio off by a factor sqrt 2 either way would give
    16.3 % or 44 % at 0.5)."""
    ea, pull = 100.0, 20.0
    ds = _rows(_lone_pair(ratio, ea=ea, pull=pull))
    stretch = 0.5 * (ds["node_z"][:, 0] - ds["node_z"][:, 2] - 1.0)  # each end from the middle
    settled = pull / (2 * ea)
    overshoot = stretch.max() / settled - 1
    zeta = ratio / math.sqrt(2.0)
    expected = math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2))
    assert abs(overshoot - expected) < 2e-3, (overshoot, expected)
    assert abs(stretch[-1] / settled - 1) < 1e-5  # and it has settled within 1.5 s
    assert np.all(ds["tension"][1:] > 0.0)  # the linear law throughout


def _axial_damping(data) -> np.ndarray:
    """alpha [s] of each segment of the upgraded cable's one line, as the system assembles it."""
    case = upgraded(data)
    return _sections(case, case.lines[0], rho=0.0)["damping"]


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
    alpha = _axial_damping(data)
    mu = np.array(masses) / np.array(lengths)
    np.testing.assert_allclose(ea * alpha, ratio * np.array(lengths) * np.sqrt(ea * mu), rtol=1e-14)
    del cable["axial_damping_ratio"]
    cable["axial_damping_time"] = 0.003
    alpha = _axial_damping(data)
    np.testing.assert_array_equal(alpha, [0.003] * 3)


def test_axial_damping_is_given_one_way():
    data = chain_case(3, model="lumped_mass", axial_stiffness=1e6)
    data["cables"][0].update(axial_damping_time=0.01, axial_damping_ratio=1.0)
    with pytest.raises(
        seacable.CaseError,
        match=r"cables\[0\]: give at most one of 'axial_damping_time' \[s\] or "
        r"'axial_damping_ratio'",
    ):
        loader.load_single_cable(data)
    data = chain_case(3, model="natural_string", axial_stiffness=1e6, axial_damping_ratio=1.0)
    with pytest.raises(
        seacable.CaseError,
        match=r"cables\[0\]: axial_damping_ratio is for model 'lumped_mass' \(got model "
        r"'natural_string'\); give axial_damping_time",
    ):
        loader.load_single_cable(data)


ARC = {"shape": "arc", "top_angle_deg": 30.0, "bottom_angle_deg": 60.0}


def test_a_lumped_line_at_given_angles_must_reach_its_end_point():
    system = system_data(_held_case("lumped_mass", {"type": "pinned"}, ARC, duration=0.1))
    system["bodies"][1]["position"][0] += 0.5  # the anchor, moved off the shape's end
    with pytest.raises(seacable.CaseError, match=r"lines \(cable\)\.initial: the given angles "
                       r"end the line at .* \(0\.5 m apart; allowed 1 mm\)"):  # fmt: skip
        seacable.simulate(seacable.load_case(system))


def test_a_line_of_one_segment_is_a_spring_between_its_ends():
    """A one-segment rope (MoorDyn's decks use them) holding a 100 kg clump in air: the clump
    hangs at the stretch of its weight and the end node's half of the rope, W / (EA / L), to
    1e-9 m, and bounces at 2 pi sqrt(m / (EA / L)) with m the clump and that half (1e-3)."""
    rope = {"name": "rope", "diameter": 0.02, "mass_per_length": 1.0, "axial_stiffness": 1.0e5}

    def case(start, duration):
        return seacable.load_case({
            "environment": {"in_air": True, "gravity": 9.81},
            "bodies": [{"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0]},
                       {"name": "clump", "type": "point", "position": [0.0, 0.0, -10.2],
                        "mass": 100.0, "external forces": [{"model": "gravity"}]}],
            "line_types": [rope],
            "lines": [{"name": "rope", "model": "lumped_mass", "from": "top", "to": "clump",
                       "sections": [{"type": "rope", "length": 10.0, "segments": 1}]}],
            "start": start,
            "simulation": {"duration": duration, "output_interval": 0.001,
                           "integrator": "rk4", "time_step": 0.0005},
        })  # fmt: skip

    stiffness, mass = 1.0e5 / 10.0, 105.0
    rest = -10.0 - mass * 9.81 / stiffness
    ds = seacable.statics(case("static", 1.0)).dataset
    assert float(ds["bodies/clump"].to_dataset().isel(time=0)["position_z"]) == pytest.approx(
        rest, abs=1e-9
    )
    run = seacable.simulate(case("as_given", 3.0)).dataset["bodies/clump"].to_dataset()
    z, t = run["position_z"].values - rest, run["time"].values
    up = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))
    crossings = t[up] - z[up] * (t[up + 1] - t[up]) / (z[up + 1] - z[up])
    period = np.diff(crossings).mean()
    assert period == pytest.approx(2 * math.pi * math.sqrt(mass / stiffness), rel=1e-3)
