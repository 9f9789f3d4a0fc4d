"""The 3D rigid-segment line: agreement with the planar model, invariants, statics against the
closed-form critical angle, tow force against the sum of loads, convergence, restricted bodies.
Cases are written in the single-cable form and run as the systems ``seacable upgrade`` writes
(``helpers.upgraded``; variables under the single-cable names, ``helpers.rows``)."""

import math
from pathlib import Path

import numpy as np
import pytest

import seacable
from helpers import rows, upgraded
from seacable.case.loader import derive_case
from seacable.numerics import integrators
from seacable.system import model

EXAMPLES = Path(__file__).parent.parent / "examples"
RHO = 1025.0


def _as_3d(case):
    """The system with its rigid-link line in 3D rigid segments without added mass."""
    line_types = [
        t.model_dump(mode="json", exclude_none=True) | {"added_mass_coefficient": 0.0}
        for t in case.line_types
    ]
    lines = [
        line.model_dump(mode="json", by_alias=True, exclude_none=True)
        | {"model": "rigid_segments_3d"}
        for line in case.lines
    ]
    return derive_case(case, {"line_types": line_types, "lines": lines})


def _built(case):
    """The assembled system at its start (``start: static``: the steady tow)."""
    return model.build(case, case._base_dir)


def _directors(built, line=0):
    """The unit vectors of a rigid-segment line's segments at the start (n, 3)."""
    p = built.params
    q, n = int(p.rs_q[line]), int(p.rs_n[line])
    return built.y0[q : q + 3 * n].reshape(n, 3)


@pytest.mark.parametrize(
    "example",
    [
        "thesis_6_1_sim6_submerged_60_links_forced",
        "thesis_6_2_pinned_exact_60_links",
        "thesis_6_3_sim3_two_floating_structures",
        "thesis_6_4_sim2_end_forces",
        "crane_tip_lowering_imposed_motion",
    ],
)
def test_planar_motion_agrees_with_planar_model(example):
    base = seacable.load_case(EXAMPLES / f"{example}.yaml")
    planar = derive_case(base, {"simulation": {"duration": 2.0}})
    a = rows(planar)
    b = rows(_as_3d(planar))
    scale = 240.0
    assert np.max(np.abs(a["node_x"] - b["node_x"])) < 1e-9 * scale
    assert np.max(np.abs(a["node_z"] - b["node_z"])) < 1e-9 * scale
    assert np.max(np.abs(b["node_y"])) == 0.0
    np.testing.assert_allclose(b["tension"], a["tension"], rtol=1e-7, atol=1e-6)


def towing_case(n=40, body=True, speed=2.5, friction=0.02, joint_stiffness=0.0, **top):
    bottom = {"type": "free"}
    if body:
        bottom["body"] = {"mass": 150.0, "volume": 0.05, "added_mass": 30.0,
                          "drag_coefficient": 1.0, "drag_area": 0.1}  # fmt: skip
    return upgraded(
        {
            "environment": {"water_density": RHO},
            "cables": [
                {
                    "model": "rigid_segments_3d",
                    "links": n,
                    "length": 500.0,
                    "diameter": 0.02,
                    "mass_per_length": 1.47,
                    "drag_coefficient_normal": 1.8,
                    "friction_coefficient": friction,
                    "joint_stiffness": joint_stiffness,
                    "top": {"type": "towing_ship", "speed": speed, **top},
                    "bottom": bottom,
                    "initial": {"shape": "static"},
                }
            ],
            "simulation": {"duration": 5.0, "output_interval": 0.5, "time_step": 0.01},
        }
    )


def critical_angle(speed=2.5):
    """Closed form: normal drag balances the normal part of the apparent weight."""
    w = (1.47 - RHO * math.pi * 0.01**2) * 9.81
    r = 0.5 * RHO * 1.8 * 0.02 * speed**2 / w
    return math.degrees(math.acos((math.sqrt(1 + 4 * r * r) - 1) / (2 * r)))


def _angles(case):
    """Each segment's angle below the horizontal, trailing the ship (-x) [degree]."""
    e = _directors(_built(case))
    return np.degrees(np.arctan2(-e[:, 2], -e[:, 0]))


@pytest.mark.parametrize("friction", [0.0, 0.02])
def test_towed_cable_without_body_lies_at_the_critical_angle(friction):
    angles = _angles(towing_case(n=50, body=False, friction=friction))
    np.testing.assert_allclose(angles, critical_angle(), atol=1e-9)


def test_towed_cable_with_body_approaches_critical_angle_upwards():
    angles = _angles(towing_case(n=100))
    gaps = np.abs(angles - critical_angle())
    assert gaps[0] < 1e-4 and gaps[-1] > 10.0
    assert np.all(np.diff(gaps) >= -1e-12)  # the shape relaxes monotonically towards it


def test_steady_tow_force_equals_sum_of_loads():
    """Towed steadily from the static shape: nothing moves relative to the ship, and the force
    at the tow point balances every load on cable and body (computed here independently)."""
    ds = rows(towing_case(n=40))
    force = np.array([ds[f"top_force_{a}"] for a in "xyz"])
    assert np.ptp(force, axis=1).max() < 1e-6 * np.abs(force).max()
    nodes = np.stack([ds[f"node_{a}"][-1] for a in "xyz"], axis=1)
    e = np.diff(nodes, axis=0)
    length = np.linalg.norm(e, axis=1)
    e /= length[:, None]
    v = np.array([2.5, 0.0, 0.0])
    vt = e @ v
    vn = v - vt[:, None] * e
    w = (1.47 - RHO * math.pi * 1e-4) * 9.81 * length
    drag_n = -0.5 * RHO * 1.8 * 0.02 * length[:, None] * np.linalg.norm(vn, axis=1)[:, None] * vn
    drag_t = -0.5 * RHO * 0.02 * 1.8 * 0.02 * length[:, None] * (np.abs(vt) * vt)[:, None] * e
    loads = (drag_n + drag_t).sum(axis=0) + np.array([0.0, 0.0, -w.sum()])
    body = -0.5 * RHO * 1.0 * 0.1 * 2.5 * v + np.array([0.0, 0.0, -(150.0 - RHO * 0.05) * 9.81])
    np.testing.assert_allclose(force[:, -1], loads + body, rtol=1e-9)


def test_static_shape_converges_with_segments():
    ends = []
    for n in (25, 50, 100, 200):
        built = _built(towing_case(n=n))
        ends.append(np.sum(built.params.rs_length[:, None] * _directors(built), 0))
    gaps = [np.linalg.norm(a - b) for a, b in zip(ends[:-1], ends[1:], strict=True)]
    assert gaps[2] < 0.1  # m, on a 500 m cable
    orders = [math.log2(a / b) for a, b in zip(gaps[:-1], gaps[1:], strict=True)]
    assert orders[0] > 1.4 and orders[1] > 1.8, (gaps, orders)  # second order as n grows


def test_turning_circle_runs_through_every_direction():
    """A towed cable in a full turn: every horizontal direction, no singularity."""
    case = towing_case(n=20, turn={"start_time": 5.0, "radius": 150.0, "side": "right"})
    sim = {"duration": 400.0, "output_interval": 5.0, "time_step": 0.02}
    ds = rows(derive_case(case, {"simulation": sim}))
    heading = np.degrees(np.arctan2(ds["direction_y"][:, 0], ds["direction_x"][:, 0]))
    covered = np.unique(np.floor((heading % 360) / 30))
    assert len(covered) == 12, covered  # the top segment pointed through every 30 deg sector
    directions = np.stack([ds[f"direction_{a}"] for a in "xyz"], axis=-1)
    np.testing.assert_allclose(np.linalg.norm(directions, axis=-1), 1.0, atol=1e-12)


STILL_WATER = {"water_density": RHO}  # with drag and added mass off below
IN_AIR = {"in_air": True}


def _hanging_3d(n=12, environment=None, **cable):
    if environment is not None and not environment.get("in_air"):
        cable = {"drag_coefficient_normal": 0.0, "added_mass_coefficient": 0.0, **cable}
    return upgraded(
        {
            "environment": environment or IN_AIR,
            "cables": [
                {
                    "model": "rigid_segments_3d",
                    "links": n,
                    "length": 10.0,
                    "diameter": 0.01,
                    "mass_per_length": 1.0,
                    "top": {"type": "fixed"},
                    "bottom": {
                        "type": "free",
                        "body": {
                            "mass": 2.0,
                            "force_y": {
                                "kind": "ramp",
                                "start_time": 0.0,
                                "end_time": 0.5,
                                "start_value": 30.0,
                                "end_value": 0.0,
                            },
                        },
                    },
                    "initial": {"shape": "arc", "top_angle_deg": 40.0, "bottom_angle_deg": 70.0},
                    **cable,
                }
            ],
            "simulation": {"duration": 4.0, "output_interval": 0.05, "time_step": 5e-4},
        }
    )


@pytest.mark.parametrize("environment", [IN_AIR, STILL_WATER], ids=["air", "still_water"])
def test_energy_is_conserved_in_3d_without_drag(environment):
    """After a sideways push ends (t > 0.5 s) the swinging chain conserves energy."""
    ds = rows(_hanging_3d(environment=environment, joint_stiffness=3.0))
    after = ds["time"] >= 0.5
    energy = ds["total_energy"][after]
    assert np.max(np.abs(ds["node_y"][after])) > 0.5  # it really moves in 3D
    drift = np.max(np.abs(energy - energy[0])) / np.ptp(ds["kinetic_energy"][after])
    assert drift < 1e-6, drift


@pytest.mark.parametrize("environment", [IN_AIR, STILL_WATER], ids=["air", "still_water"])
def test_vertical_angular_momentum_is_conserved(environment):
    """Fixed top, no drag, no joint springs: gravity and the top force have no moment about the
    vertical through the top, so the angular momentum about it is constant."""
    built = _built(_hanging_3d(environment=environment, joint_stiffness=0.0))
    p = built.params
    q, v, n = int(p.rs_q[0]), int(p.rs_v[0]), int(p.rs_n[0])
    y = built.y0.copy()
    w = model.workspace(built)
    states = np.empty((40, y.size))
    times = np.empty(40)
    work = np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
    integrators.rk4_chunk(0, y, 100 * 5e-4, 100, 40 * 100, p, w, states, times, work)
    end_mass = p.body_mass[list(built.layout.bodies).index("end")]

    def lz(state):
        e = state[q : q + 3 * n].reshape(n, 3)
        u = state[v : v + 3 * n].reshape(n, 3)
        nodes = np.vstack([np.zeros(3), np.cumsum(p.rs_length[:, None] * e, axis=0)])
        vel = np.vstack([np.zeros(3), np.cumsum(p.rs_length[:, None] * u, axis=0)])
        centre = 0.5 * (nodes[:-1] + nodes[1:])
        vc = 0.5 * (vel[:-1] + vel[1:])
        total = np.sum(p.rs_mass * np.cross(centre, vc)[:, 2])
        total += np.sum(p.rs_inertia * np.cross(e, u)[:, 2])
        return total + end_mass * np.cross(nodes[-1], vel[-1])[2]

    after = [lz(s) for s, t in zip(states, times, strict=True) if t > 0.5]
    assert abs(after[0]) > 1.0
    assert np.ptp(after) < 1e-8 * abs(after[0])


def _rising_body(added_horizontal):
    return upgraded(
        {
            "environment": {"water_density": RHO},
            "cables": [
                {
                    "model": "rigid_segments_3d",
                    "links": 20,
                    "length": 30.0,
                    "diameter": 0.02,
                    "mass_per_length": 1.0,
                    "drag_coefficient_normal": 1.8,
                    "top": {"type": "fixed", "position": [0.0, 0.0, -60.0]},
                    "bottom": {
                        "type": "free",
                        "body": {
                            "mass": 100.0,
                            "volume": 0.3,
                            "added_mass": [added_horizontal, added_horizontal, 50.0],
                            "drag_coefficient": 1.0,
                            "drag_area": 0.5,
                        },
                    },  # fmt: skip
                    "initial": {"shape": "arc", "top_angle_deg": 150.0, "bottom_angle_deg": 100.0},
                }
            ],
            "simulation": {"duration": 10.0, "output_interval": 0.5, "time_step": 0.005},
        }
    )


def test_restricted_body_moves_only_vertically():
    """A very large added mass in x and y (Jacquot & Marichal's trick) restrains the body to a
    vertical track; what is left of its sideways motion shrinks as 1 / that added mass."""
    drift = {}
    for added in (1e7, 1e9):
        ds = rows(_rising_body(added))
        drift[added] = np.max(
            np.hypot(
                ds["node_x"][:, -1] - ds["node_x"][0, -1], ds["node_y"][:, -1] - ds["node_y"][0, -1]
            )
        )
        rise = ds["node_z"][-1, -1] - ds["node_z"][0, -1]
        assert rise > 1.0
    assert drift[1e9] < 1e-4 * rise
    assert 80 < drift[1e7] / drift[1e9] < 120


def test_float_at_a_joint_changes_tension_by_its_net_buoyancy():
    case = upgraded(
        {
            "environment": {"water_density": RHO},
            "cables": [
                {
                    "model": "rigid_segments_3d",
                    "links": 10,
                    "length": 20.0,
                    "diameter": 0.02,
                    "mass_per_length": 2.0,
                    "top": {"type": "fixed"},
                    "bottom": {"type": "free", "body": {"mass": 50.0}},
                    "point_bodies": [{"node": 4, "mass": 5.0, "volume": 0.02, "drag_area": 0.1}],
                }
            ],
            "simulation": {"duration": 0.1, "output_interval": 0.1},
        }
    )
    tension = rows(case)["tension"][-1]
    link_weight = (2.0 * 2.0 - RHO * math.pi * 1e-4 * 2.0) * 9.81
    jump = tension[3] - tension[4] - link_weight
    np.testing.assert_allclose(jump, (5.0 - RHO * 0.02) * 9.81, rtol=1e-9)


def _single_segment(top, initial_deg, ca=1.0):
    return upgraded(
        {
            "environment": {"water_density": RHO},
            "cables": [
                {
                    "model": "rigid_segments_3d",
                    "links": 1,
                    "length": 2.0,
                    "diameter": 0.1,
                    "mass_per_length": 20.0,
                    "drag_coefficient_normal": 0.0,
                    "added_mass_coefficient": ca,
                    "top": top,
                    "bottom": {"type": "free"},
                    "initial": {"shape": "arc", "top_angle_deg": initial_deg},
                }
            ],
            "simulation": {"duration": 20.0, "output_interval": 0.01, "time_step": 0.001},
        }
    )


@pytest.mark.parametrize("ca", [0.0, 1.0])
def test_normal_added_mass_slows_a_swinging_segment(ca):
    """Small swings of one submerged segment about its top: omega^2 = W (l/2) / ((m + m_a) l^2/3)
    with m_a = Ca rho pi d^2/4 l (the added mass acts on every point's normal motion)."""
    ds = rows(_single_segment({"type": "fixed"}, 2.0, ca))
    x = ds["node_x"][:, -1]
    t = ds["time"]
    crossings = t[1:][np.diff(np.sign(x)) != 0]
    period = 2 * np.mean(np.diff(crossings))
    area = math.pi * 0.1**2 / 4
    m, ma = 40.0, ca * RHO * area * 2.0
    weight = (m - RHO * area * 2.0) * 9.81
    omega = math.sqrt(weight * 1.0 / ((m + ma) * 4.0 / 3.0))
    assert abs(2 * math.pi / period / omega - 1) < 2e-3


def test_no_added_mass_along_the_axis():
    """A vertical segment moved up and down along its axis (under water): the top force is
    m a + W only."""
    motion = {"kind": "sine", "amplitude": 0.5, "period": 2.0, "offset": -1.0}
    ds = rows(_single_segment({"type": "imposed", "z": motion}, 0.0))
    t = ds["time"]
    acc = -0.5 * (math.pi) ** 2 * np.sin(math.pi * t)
    area = math.pi * 0.1**2 / 4
    weight = (40.0 - RHO * area * 2.0) * 9.81
    expected = -(40.0 * acc + weight)  # force of the cable on its top, z
    np.testing.assert_allclose(ds["top_force_z"], expected, rtol=1e-9, atol=1e-6)


@pytest.mark.parametrize("stiffness", [50.0, 500.0])
def test_static_start_is_steady_with_elastic_joints(stiffness):
    ds = rows(towing_case(n=30, joint_stiffness=stiffness))
    force = ds["top_force_x"]
    assert np.ptp(force) < 1e-8 * abs(force[0])
    assert np.ptp(ds["node_z"][:, -1]) < 1e-8


TIED_REST = np.array([20.0, 5.0, -90.0])  # the tie's rest [m]; it pulls in x and y only


def _tied_case():
    """A 20-link 3D rigid cable hanging in a 0.5 m/s current from a floating structure that
    heaves on 2e4 N/m, an 80 kg body at its end tied sideways (500 N/m in x and y) to a point
    20.6 m from where the end starts; the top joint's spring (20 N m/rad) against the
    vertical."""
    return upgraded(
        {
            "environment": {"water_density": RHO, "current": {"velocity": 0.5}},
            "cables": [
                {
                    "model": "rigid_segments_3d",
                    "links": 20,
                    "length": 100.0,
                    "diameter": 0.05,
                    "mass_per_length": 5.0,
                    "drag_coefficient_normal": 1.8,
                    "joint_stiffness": 20.0,
                    "top": {"type": "floating_structure", "mass": 5000.0, "heave_stiffness": 2e4},
                    "bottom": {
                        "type": "free",
                        "body": {"mass": 80.0, "volume": 0.01},
                        "tie": {
                            "stiffness_x": 500.0,
                            "stiffness_y": 500.0,
                            "rest_position": TIED_REST.tolist(),
                        },
                    },  # fmt: skip
                    "initial": {"shape": "static"},
                }
            ],
            "simulation": {"duration": 5.0, "output_interval": 1.0, "time_step": 0.005},
        }
    )


def _tied_loads(nodes):
    """Independent loads [N] of the tied case at rest with its nodes (21, 3): each segment's
    wet weight and Morison normal drag in the current (at its centre), the end body's weight,
    buoyancy and tie (at the last node); and the top joint spring's moment on the line [N m]."""
    d, length, g = 0.05, 5.0, 9.81
    e = np.diff(nodes, axis=0) / length
    current = np.array([0.5, 0.0, 0.0])
    normal = current[None, :] - (e @ current)[:, None] * e
    speed = np.linalg.norm(normal, axis=1)[:, None]
    segment = 0.5 * RHO * 1.8 * d * length * speed * normal
    segment[:, 2] -= (5.0 - RHO * math.pi * d**2 / 4) * length * g
    end = np.zeros(3)
    end[:2] = 500.0 * (TIED_REST[:2] - nodes[-1, :2])
    end[2] = -(80.0 - RHO * 0.01) * g
    down = np.array([0.0, 0.0, -1.0])  # the top joint's unloaded direction
    axis = np.cross(e[0], down)
    angle = math.atan2(np.linalg.norm(axis), e[0] @ down)
    joint = 20.0 * angle * axis / np.linalg.norm(axis)
    return segment, end, joint


def test_static_start_with_heaving_structure_and_tied_end():
    """The tied case starts at rest in the balance with every segment pulled (the statics
    once found one folded back and pushed): the line's forces and its moments about the top
    balance with the structure's restoring force and the tie (loads summed independently, to
    1e-9), and the structure holds still."""
    ds = rows(_tied_case())
    assert np.max(np.abs(ds["angular_rate"])) < 1e-8
    assert np.ptp(ds["node_z"][:, 0]) < 1e-8  # the structure does not heave
    nodes = np.column_stack([ds[f"node_{c}"][0] for c in "xyz"])
    segment, end, joint = _tied_loads(nodes)
    total = segment.sum(axis=0) + end
    scale = float(np.abs(end).max() + np.abs(segment).sum())
    top = np.array([ds[f"top_force_{c}"][0] for c in "xyz"])  # the line's pull on the top
    np.testing.assert_allclose(top, total, rtol=0, atol=1e-9 * scale)
    heave = float(ds["node_z"][0, 0])
    assert heave < -0.1  # settled under the cable's weight (3.6 kN on 2e4 N/m, less drag's)
    assert abs(2e4 * heave - total[2]) < 1e-9 * scale  # the structure's restoring force
    arms = 0.5 * (nodes[1:] + nodes[:-1]) - nodes[0]
    moment = np.cross(arms, segment).sum(axis=0) + np.cross(nodes[-1] - nodes[0], end)
    np.testing.assert_allclose(moment + joint, 0.0, atol=1e-9 * scale * 100.0)
    assert nodes[-1, 2] < -97.0  # hanging below the top, not folded back
    assert np.all(np.diff(nodes[:, 2]) < 0.0)


def test_tied_case_settles_dynamically_to_its_static_start():
    """The tied case run from straight down (the tie pulling 10 kN sideways) with dampers on
    the structure's heave and the end body settles, after 300 s, onto the static start."""
    case = _tied_case()
    static = rows(case)
    bodies = [body.model_dump(mode="json", by_alias=True, exclude_none=True)
              for body in case.bodies]  # fmt: skip
    bodies[0]["external forces"].append(
        {"model": "linear_damping", "diagonal": [0.0, 0.0, 2e4, 0.0, 0.0, 0.0]}
    )
    for force in bodies[1]["external forces"]:
        if force["model"] == "linear_damping":
            force["diagonal"] = [3000.0, 3000.0, 3000.0, 0.0, 0.0, 0.0]
    changes = {"bodies": bodies, "start": "as_given",
               "simulation": {"duration": 300.0, "output_interval": 10.0}}  # fmt: skip
    settled = rows(derive_case(case, changes))
    assert abs(settled["node_x"][0, -1] - static["node_x"][0, -1]) > 19.0  # starts far off
    for c in "xyz":
        start = static[f"node_{c}"][0]
        assert np.abs(settled[f"node_{c}"][-1] - start).max() < 1e-3  # measured 1.6e-4 m
