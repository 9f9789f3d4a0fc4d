"""Every implementation honours its contract (the Protocol or enumeration that states it)."""

import ast
import inspect
import math
import typing
from pathlib import Path

import numpy as np
import pytest
from numba import njit

import seacable
from seacable.bodies.contract import BodyDynamics, BodyKinematics
from seacable.case.forces import ForceModel
from seacable.forces import kinds, table
from seacable.forces.contract import ForceTable, StatefulForceModel
from seacable.kernels import chain3d as c3
from seacable.kernels import planar_chain as pc
from seacable.lines import lumped_mass, natural_string, rigid_links, rigid_segments
from seacable.lines.contract import LumpedLineModel, NaturalStringModel, RigidLineModel
from seacable.numerics.contract import ChunkIntegrator
from seacable.system import energy, kernel
from seacable.system import model as system_model
from seacable.system.contract import RunModel


def test_the_system_model_is_a_run_model():
    members = {n for n in vars(RunModel) if not n.startswith("_")}
    members |= set(RunModel.__annotations__)
    missing = sorted(name for name in members if not hasattr(system_model, name))
    assert not missing, f"system.model lacks {missing} of RunModel"
    assert isinstance(system_model, RunModel)
    assert hasattr(system_model, "variables")


def _schema_force_models() -> list[str]:
    union = typing.get_args(typing.get_args(ForceModel)[0])
    return [typing.get_args(cls.model_fields["model"].annotation)[0] for cls in union]


def test_every_force_model_in_the_schema_has_a_kind_and_a_branch():
    """Each ``model:`` of ``external forces`` has a ForceKind, and system.evaluation evaluates
    each kind, behind its flag where it has one (a kind nobody evaluates would be accepted and
    silently do nothing)."""
    from seacable.system import evaluation, variants

    names = _schema_force_models()
    assert sorted(kinds.kind_of(name) for name in names) == sorted(kinds.ForceKind)
    source = inspect.getsource(evaluation.add_all.py_func)
    branches = {node.id for node in ast.walk(ast.parse(source)) if isinstance(node, ast.Name)}
    for kind in kinds.ForceKind:
        if kind in table.LAST:  # after every other load: the models' part calls its module
            source = inspect.getsource(evaluation._models.py_func)
            assert f"{kind.name.lower()}.apply_all(" in source
            continue
        assert kind.name in branches, f"evaluation.add_all has no branch for {kind.name}"
        flag = variants.FORCE_FLAG[int(kind)]  # None: compiled into every copy
        assert flag is None or flag in branches, f"{kind.name}'s branch lacks its flag {flag}"


def _rigid_line_at_a_moving_state(example: str, seed: int):
    """A system's first rigid line with its workspace filled by one right-hand side at the
    example's start with random segment rates: (params, state, workspace, line index)."""
    from seacable.case.loader import derive_case
    from seacable.system import rigid as system_rigid

    case = seacable.load_case(Path(__file__).parent.parent / "examples" / f"{example}.yaml")
    built = system_model.build(derive_case(case, {"simulation": {"duration": 0.1}}))
    p, y = built.params, built.y0.copy()
    li = 0
    per = 1 if p.rs_kind[li] == system_rigid.PLANAR else 3
    v, n = int(p.rs_v[li]), int(p.rs_n[li])
    y[v : v + per * n] += np.random.default_rng(seed).normal(scale=0.05, size=per * n)
    w = kernel.make_work(p)
    kernel.rhs(0.0, y, p, w, np.zeros_like(y))
    return p, y, system_rigid.workspace(p, w, li).copy(), li


@pytest.mark.parametrize(
    ("model", "example"),
    [(rigid_links, "thesis_6_1_sim2_submerged_12_links"),
     (rigid_segments, "rising_body_single_cable_added_mass")],
)  # fmt: skip
def test_every_rigid_line_model_honours_its_contract(model, example):
    """Each rigid line model has the contract's functions, and its tip map is the forward
    sweep's (rule 2): for random node-0 accelerations A_0 and holding forces L on a held tip,
    the tip's acceleration from ``forward`` is ac + ga A_0 + al L from ``tip_map``."""
    assert isinstance(model, RigidLineModel)
    p, y, ws, li = _rigid_line_at_a_moving_state(example, seed=3)
    n, s0 = int(p.rs_n[li]), int(p.rs_seg[li])
    q, v = int(p.rs_q[li]), int(p.rs_v[li])
    length, mass = p.rs_length[s0 : s0 + n], p.rs_mass[s0 : s0 + n]
    rng = np.random.default_rng(7)
    planar = model is rigid_links
    dims = 2 if planar else 3
    if planar:
        st = np.array([5.0, 0.3, 7.0, *rng.normal(size=2), 1.0, 0.0, 0.0, 1.0])
        model.backward(n, length, mass, p.rs_inertia[s0 : s0 + n], y, v, ws, st, True)
        ac, ga, al = np.empty(2), np.empty(4), np.empty(4)
        model.tip_map(n, length, y, v, ws, ac, ga, al)
    else:
        m = np.array([5.0, 0.3, 0.1, 6.0, 0.2, 7.0])
        model.backward(n, length, mass, ws, m, rng.normal(size=3), np.eye(3).ravel(), True)
        ac, ga, al = np.empty(3), np.empty(9), np.empty(9)
        model.tip_map(n, length, ws, ac, ga, al)
    for _ in range(3):
        a0, force = rng.normal(size=dims), rng.normal(size=dims) * 100.0
        ydot = np.zeros_like(y)
        if planar:
            model.forward(n, length, ws, a0[0], a0[1], force[0], force[1], True, y, q, v, ydot)
            tip = ws[[pc._AX, pc._AZ], n]
        else:
            model.forward(n, length, ws, a0, force, True, y, q, v, ydot)
            tip = ws[c3._A : c3._A + 3, n]
        mapped = ac + ga.reshape(dims, dims) @ a0 + al.reshape(dims, dims) @ force
        np.testing.assert_allclose(tip, mapped, rtol=1e-10, atol=1e-10 * np.abs(mapped).max())


def _moving(case_data: dict | str, seed: int, spread: float = 0.3):
    """A system built from an example's name or a case mapping, its start as given, with
    random velocities on every state and its lumped lines' interior nodes moved by up to
    ``spread`` [m]: (built, state, rates, workspace) after one right-hand side."""
    from seacable.case.loader import derive_case

    if isinstance(case_data, str):
        case = seacable.load_case(Path(__file__).parent.parent / "examples" / f"{case_data}.yaml")
        case = derive_case(case, {"start": "as_given"})
    else:
        case = seacable.load_case(case_data)
    built = system_model.build(case)
    p, y = built.params, built.y0.copy()
    rng = np.random.default_rng(seed)
    y[p.n_q : p.n_q + p.n_v] += rng.normal(scale=0.5, size=p.n_v)
    for li in range(len(p.line_n)):
        q, size = int(p.line_q[li]), 3 * (int(p.line_n[li]) - 1)
        y[q : q + size] += rng.uniform(-spread, spread, size=size)
    w = kernel.make_work(p)
    ydot = np.zeros_like(y)
    kernel.rhs(0.0, y, p, w, ydot)
    return built, y, ydot, w


@pytest.mark.parametrize(
    "example", ["catenary_mooring_line_surge", "buoy_three_lines_clump_weight"]
)
def test_a_lumped_end_node_is_a_node_like_any_other(example):
    """LumpedLineModel rules 2-4: at a moving state (drag, added mass, seabed), the mass and
    loads ``end_mass_force`` hands a body, taken at each interior node, give exactly the
    acceleration ``interior_rates`` gives that node (to 1e-12)."""
    assert isinstance(lumped_mass, LumpedLineModel)
    built, y, ydot, w = _moving(example, seed=5, spread=0.05)
    p = built.params
    m3, force = np.empty(9), np.empty(3)
    checked = 0
    for li in range(len(p.line_n)):
        n, c0, v = int(p.line_n[li]), int(p.line_node[li]), int(p.line_v[li])
        for j in range(1, n):
            lumped_mass.end_mass_force(p.node_mass, w.nodes, c0 + j, m3, force)
            solved = np.linalg.solve(m3.reshape(3, 3), force)
            given = ydot[v + 3 * (j - 1) : v + 3 * j]
            np.testing.assert_allclose(solved, given, rtol=1e-12, atol=1e-12 * p.gravity)
            checked += 1
    assert checked > 20


def test_a_body_moves_with_its_lumped_end_node_as_one():
    """LumpedLineModel rule 4 on a system: a 10 kg ball hung in air from a fixed point by a
    lumped line of four segments, at a random moving state. Its acceleration is that of one
    body of the ball's mass plus the end node's (half the last segment's), loaded by both
    weights and the last segment's tension EA (|d| / l - 1) (to 1e-12, independent sums)."""
    rope = {"name": "rope", "diameter": 0.01, "mass_per_length": 2.0, "axial_stiffness": 1e5}
    case = {
        "name": "ball", "start": "as_given", "environment": {"in_air": True},
        "bodies": [
            {"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0]},
            {"name": "ball", "type": "point", "position": [3.0, 1.0, -4.0], "mass": 10.0,
             "external forces": [{"model": "gravity"}]},
        ],
        "line_types": [rope],
        "lines": [{"name": "rope", "model": "lumped_mass", "from": "top", "to": "ball",
                   "sections": [{"type": "rope", "length": 5.0, "segments": 4}],
                   "initial": "straight"}],
        "simulation": {"duration": 0.1, "output_interval": 0.1},
    }  # fmt: skip
    built, y, ydot, w = _moving(case, seed=11, spread=0.05)
    p = built.params
    g, segment = 9.81, 5.0 / 4
    node = 2.0 * segment / 2.0  # the end node's mass [kg]
    last = y[int(p.line_q[0]) + 6 : int(p.line_q[0]) + 9]  # node 3, the last interior one
    ball = y[int(p.body_q[1]) : int(p.body_q[1]) + 3]
    d = last - ball
    tension = 1e5 * (np.linalg.norm(d) / segment - 1.0)
    force = tension * d / np.linalg.norm(d) - (10.0 + node) * g * np.array([0.0, 0.0, 1.0])
    expected = force / (10.0 + node)
    v = int(p.body_v[1])
    np.testing.assert_allclose(ydot[v : v + 3], expected, rtol=1e-12, atol=1e-12 * g)
    assert abs(tension) > 100.0  # the state pulls the ball: the check has a load to see


@pytest.mark.parametrize("tangent", ["angle", "cartesian"])
def test_a_natural_string_at_its_static_balance_has_no_rates(tangent):
    """NaturalStringModel rules 3-4: Poth's string (10 m, 1 kg/m, EA 1e6 N, 10 kg end body)
    hanging still with each node's strain the weight below it over EA, eps(s) = g (mu (l - s)
    + m) / EA, has zero rates (1e-10 of the pivot's gravity term 2 k g / l), and its end body
    hangs at the pivot less l + (g / EA)(mu l^2 / 2 + m l) (the trapezoidal rule is exact on a
    linear strain): each in both parametrisations of the tangent."""
    from seacable.case.loader import derive_case

    assert isinstance(natural_string, NaturalStringModel)
    example = Path(__file__).parent.parent / "examples"
    case = seacable.load_case(example / "poth_string_pendulum_natural_variables.yaml")
    lines = [case.lines[0].model_dump(mode="json", by_alias=True, exclude_none=True)]
    lines[0]["tangent"] = tangent
    built = system_model.build(derive_case(case, {"lines": lines}))
    p = built.params
    k, length, mu, mass, ea, g = int(p.nat_n[0]), 10.0, 1.0, 10.0, 1e6, 9.81
    s = np.linspace(0.0, length, k + 1)
    strain = g * (mu * (length - s) + mass) / ea
    y = built.y0.copy()
    per = 3 if tangent == "cartesian" else 2
    q, v = int(p.nat_q[0]), int(p.nat_v[0])
    nodes = np.zeros((k + 1, per))
    nodes[:, 0] = strain
    if tangent == "cartesian":
        nodes[:, 2] = -1.0  # t = (0, -1): straight down
    y[q : q + per * (k + 1)] = nodes.ravel()
    y[v : v + per * (k + 1)] = 0.0
    w = kernel.make_work(p)
    ydot = np.ones_like(y)
    kernel.rhs(0.0, y, p, w, ydot)
    rates = ydot[v : v + per * (k + 1)]
    assert np.abs(rates).max() < 1e-10 * 2.0 * k * g / length
    drop = length + g / ea * (mu * length**2 / 2.0 + mass * length)
    tip = int(p.nat_tip[0])
    np.testing.assert_allclose(w.pos[tip], [0.0, 0.0, -drop], rtol=0, atol=1e-12 * length)
    y[q] *= 1.01  # out of balance: the check sees it
    kernel.rhs(0.0, y, p, w, ydot)
    assert np.abs(ydot[v : v + per * (k + 1)]).max() > 1e-3 * 2.0 * k * g / length


def _sine(amplitude, period, offset=0.0):
    return {"kind": "sine", "amplitude": amplitude, "period": period, "offset": offset}


def _kinematic_case() -> dict:
    """A ship heaving, surging, rolling, pitching and yawing by sines, a vehicle moving
    relative to it, a boat on a track that turns after 1 s, and an anchor, joined by ties."""
    ship = {
        "name": "ship",
        "type": "imposed",
        "x": _sine(2.0, 7.0),
        "z": _sine(0.5, 5.0),
        "roll_deg": _sine(8.0, 6.0),
        "pitch_deg": _sine(5.0, 4.0, 2.0),
        "yaw_deg": _sine(20.0, 9.0, 30.0),
        "points": {"crane": [5.0, 2.0, 3.0]},
    }
    fish = {
        "name": "fish",
        "type": "imposed",
        "relative_to": "ship",
        "x": _sine(3.0, 3.0),
        "z": _sine(1.0, 2.0, -20.0),
    }
    boat = {
        "name": "boat",
        "type": "imposed",
        "points": {"bow": [4.0, -1.0, 0.5]},
        "track": {
            "start": [10.0, 5.0],
            "heading_deg": 30.0,
            "speed": 3.0,
            "turn": {"start_time": 1.0, "radius": 40.0, "side": "left"},
        },
    }
    anchor = {"name": "anchor", "type": "fixed", "position": [1.0, 2.0, -50.0]}
    ties = [
        {
            "name": "a",
            "model": "tie",
            "from": "ship.crane",
            "to": "fish",
            "unstretched_length": 30.0,
            "stiffness": 1e3,
        },
        {
            "name": "b",
            "model": "tie",
            "from": "anchor",
            "to": "boat.bow",
            "unstretched_length": 80.0,
            "stiffness": 1e3,
        },
    ]
    return {"name": "kinematics", "start": "as_given", "bodies": [ship, fish, boat, anchor],
            "lines": ties, "simulation": {"duration": 5.0, "output_interval": 0.1}}  # fmt: skip


def _product(a, b):
    """The quaternion product a b (w, x, y, z)."""
    return np.array([
        a[0] * b[0] - a[1:] @ b[1:], *(a[0] * b[1:] + b[0] * a[1:] + np.cross(a[1:], b[1:]))
    ])  # fmt: skip


@pytest.mark.parametrize("time", [0.7, 2.3])
def test_imposed_and_fixed_bodies_move_as_their_derivatives_say(time):
    """BodyKinematics rules 1, 2 and 5: at a time, each imposed body's twist is its pose's
    derivative (the quaternion's 1/2 (0, omega) q), its acceleration its twist's, and each
    point's velocity and acceleration the derivatives of its position and velocity (central
    differences, 1e-7 of the scale: ships turning, a vehicle relative to its ship, a track's
    turning circle); a fixed body stays at rest."""
    from seacable.bodies import kinematics

    assert isinstance(kinematics, BodyKinematics)
    built = system_model.build(seacable.load_case(_kinematic_case()))
    p, y = built.params, built.y0
    w = kernel.make_work(p)

    def at(t):
        kernel.rhs(t, y, p, w, np.zeros_like(y))
        points = np.empty_like(w.ppos)
        for k in range(len(points)):
            b = int(p.point_body[k])
            kinematics.point_acceleration(p.body_kind[b], w.acc[b], w.parm[k], w.omega[b],
                                          points[k])  # fmt: skip
        names = ("pos", "vel", "quat", "omega", "acc", "ppos", "pvel")
        return {name: np.array(getattr(w, name)) for name in names} | {"pacc": points}

    h = 1e-4
    now, up, down = at(time), at(time + h), at(time - h)

    def rate(name):
        return (up[name] - down[name]) / (2.0 * h)

    moving = np.flatnonzero(np.asarray(p.body_kind) == kinematics.IMPOSED)
    assert len(moving) == 3
    for b in moving:
        quat_rate = 0.5 * _product(np.array([0.0, *now["omega"][b]]), now["quat"][b])
        pairs = ((rate("pos")[b], now["vel"][b]), (rate("vel")[b], now["acc"][b, :3]),
                 (rate("omega")[b], now["acc"][b, 3:]), (rate("quat")[b], quat_rate))  # fmt: skip
        for got, want in pairs:
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * max(1.0, np.abs(want).max()))
    for k in range(len(now["ppos"])):
        for got, want in ((rate("ppos")[k], now["pvel"][k]), (rate("pvel")[k], now["pacc"][k])):
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * max(1.0, np.abs(want).max()))
    anchor = built.layout.bodies.index("anchor")
    assert np.all(now["pos"][anchor] == [1.0, 2.0, -50.0])
    assert not now["vel"][anchor].any() and not now["acc"][anchor].any()
    ship, boat = built.layout.bodies.index("ship"), built.layout.bodies.index("boat")
    assert np.abs(now["acc"][ship, 3:]).max() > 1e-3  # the ship's turns accelerate
    assert time < 1.0 or abs(now["omega"][boat, 2]) > 0.07  # on its circle: 3 m/s over 40 m


@pytest.mark.parametrize("dofs", [None, ["surge", "heave", "pitch"]])
def test_a_dynamic_rigid_body_obeys_newton_euler(dofs):
    """BodyDynamics rules 1-4 and BodyKinematics rule 3: a rigid body turning in air (off-
    centre centre of gravity, hung by a taut lumped rope at one point and tied to a weight at
    another). Its accelerations from the system satisfy Newton-Euler about its centre of
    gravity, m a_G = sum F and I_G alpha + w x I_G w = sum (r - r_G) x F, with the loads
    summed here independently (weight, the rope's last segment EA (|d| / l - 1) on the end
    node carried at the hook, the node's weight and inertia, the tie's k (d - L0)) to 1e-10;
    with ``dofs`` the rows of the free degrees of freedom (forces and moments about the
    reference point, earth axes) balance and the held accelerations are zero. Its quaternion's
    rate is 1/2 (0, w) q."""
    from scipy.spatial.transform import Rotation

    from helpers import turning_body_case
    from seacable.bodies import dynamics

    assert isinstance(dynamics, BodyDynamics)

    case = turning_body_case({"duration": 0.1, "output_interval": 0.1})
    box = case["bodies"][1]
    box["position"] = [3.0, 1.0, -6.2]  # the rope taut (2 % strain)
    if dofs is not None:
        box |= {"dofs": dofs, "velocity": [0.4, 0.0, -0.2], "angular_velocity": [0.0, 0.5, 0.0]}
    built, y, ydot, w = _moving(case, seed=2, spread=0.0)
    p = built.params
    b, g = built.layout.bodies.index("float"), 9.81
    q, v = int(p.body_q[b]), int(p.body_v[b])
    x, quat, vel, omega = y[q : q + 3], y[q + 3 : q + 7], y[v : v + 3], y[v + 3 : v + 6]
    acc, alpha = ydot[v : v + 3], ydot[v + 3 : v + 6]
    np.testing.assert_array_equal(ydot[q : q + 3], vel)
    np.testing.assert_allclose(ydot[q + 3 : q + 7], 0.5 * _product(np.r_[0.0, omega], quat),
                               rtol=1e-12, atol=1e-12)  # fmt: skip
    rot = Rotation.from_quat([*quat[1:], quat[0]]).as_matrix()
    r_g, r_hook, r_eye = (rot @ np.array(a) for a in ([0.1, 0.0, -0.2], [0.2, 0.1, 0.5],
                                                      [-0.3, 0.0, -0.4]))  # fmt: skip

    def carried(r):
        return acc + np.cross(alpha, r) + np.cross(omega, np.cross(omega, r))

    segment = 6.5 / 6
    node = 2.0 * segment / 2.0  # the rope's end node, carried at the hook [kg]
    rope = int(p.line_q[0])
    d = y[rope + 12 : rope + 15] - (x + r_hook)  # to node 5, the last interior one
    tension = max(0.0, 2.0e5 * (np.linalg.norm(d) / segment - 1.0))
    at_hook = tension * d / np.linalg.norm(d) - node * (g * np.array([0, 0, 1.0]) + carried(r_hook))
    weight = y[int(p.body_q[2]) : int(p.body_q[2]) + 3]
    e = weight - (x + r_eye)
    at_eye = 3000.0 * max(0.0, np.linalg.norm(e) - 1.0) * e / np.linalg.norm(e)
    at_g = np.array([0.0, 0.0, -50.0 * g])
    force = at_g + at_hook + at_eye
    moment = np.cross(r_hook, at_hook) + np.cross(r_eye, at_eye) + np.cross(r_g, at_g)  # about O
    inertia = rot @ np.diag([4.0, 6.0, 8.0]) @ rot.T
    momentum = 50.0 * carried(r_g)
    spin = inertia @ alpha + np.cross(omega, inertia @ omega) + np.cross(r_g, momentum)
    residual = np.r_[force - momentum, moment - spin]
    scale = 50.0 * g + tension + np.abs(at_eye).max()
    free = np.ones(6, bool) if dofs is None else np.isin(
        ["surge", "sway", "heave", "roll", "pitch", "yaw"], dofs)  # fmt: skip
    np.testing.assert_allclose(residual[free], 0.0, atol=1e-10 * scale)
    assert not np.r_[acc, alpha][~free].any()
    assert tension > 1e3  # the rope pulls: the check has a load to see
    assert dofs is None or np.abs(residual[~free]).max() > 1e-3 * scale  # held rows react


def test_bodies_at_rigid_line_tips_are_carried_at_their_last_nodes():
    """BodyKinematics rule 4: the bodies carried at rigid lines' tips (a float between two
    lines, a body at the end) are at their line's last node, x_0 + sum l_i e_i, and move
    with it, v_0 + sum l_i de_i/dt (at a moving state of an example, to 1e-12)."""
    from seacable.bodies import kinematics

    built, y, ydot, w = _moving("rising_body_single_cable_added_mass", seed=4)
    p = built.params
    tips = 0
    for li in range(len(p.rs_n)):
        tip = int(p.rs_tip[li])
        n, s0, q, v = int(p.rs_n[li]), int(p.rs_seg[li]), int(p.rs_q[li]), int(p.rs_v[li])
        assert p.body_kind[tip] == kinematics.TIP
        lengths = p.rs_length[s0 : s0 + n, None]
        base = int(p.rs_from[li])
        end = w.ppos[base] + (lengths * y[q : q + 3 * n].reshape(n, 3)).sum(axis=0)
        speed = w.pvel[base] + (lengths * y[v : v + 3 * n].reshape(n, 3)).sum(axis=0)
        np.testing.assert_allclose(w.pos[tip], end, rtol=0, atol=1e-12 * lengths.sum())
        np.testing.assert_allclose(w.vel[tip], speed, rtol=0, atol=1e-12 * np.abs(speed).max())
        tips += 1
    assert tips == 2


def _lone_box(forces: list[dict], **more) -> dict:
    """A turned rigid box under water with only ``forces`` on it (its one line, a tie to an
    anchor, is slack)."""
    box = {"name": "box", "type": "rigid", "position": [1.0, -2.0, -8.0], "mass": 40.0,
           "inertia": [3.0, 4.0, 5.0], "centre_of_gravity": [0.2, -0.1, -0.3], "volume": 0.05,
           "centre_of_buoyancy": [-0.1, 0.3, 0.4], "orientation_deg": [20.0, -35.0, 60.0],
           "external forces": forces} | more  # fmt: skip
    anchor = {"name": "anchor", "type": "fixed", "position": [0.0, 0.0, -8.0]}
    slack = {"name": "slack", "model": "tie", "from": "anchor", "to": "box",
             "unstretched_length": 100.0, "stiffness": 1e3}  # fmt: skip
    return {"name": "box", "start": "as_given", "bodies": [box, anchor], "lines": [slack],
            "simulation": {"duration": 0.1, "output_interval": 0.1}}  # fmt: skip


STIFFNESS = [[9e3, 1e3, 0.0, 0.0, 2e2, 0.0], [1e3, 8e3, 0.0, 0.0, 0.0, 0.0],
             [0.0, 0.0, 3e4, 5e2, 0.0, 0.0], [0.0, 0.0, 5e2, 4e4, 0.0, 0.0],
             [2e2, 0.0, 0.0, 0.0, 5e4, 1e3], [0.0, 0.0, 0.0, 0.0, 1e3, 6e4]]  # fmt: skip


@njit
def _energies(y, p, w):
    """system.energy.energies, which has no Python entry (kernels.jit.inner), with every kind
    compiled."""
    return energy.energies(y, p, w, True, True, True, True, True)


@pytest.mark.parametrize(
    ("force", "turns"),
    [({"model": "gravity"}, True), ({"model": "buoyancy"}, True),
     ({"model": "linear_stiffness", "matrix": STIFFNESS, "equilibrium_position": [0, 0, -7],
       "equilibrium_orientation_deg": [0.0, 10.0, 0.0]}, False)],
)  # fmt: skip
def test_conservative_force_models_derive_from_their_potential(force, turns):
    """ForceTable rules 2 and 3: along random small motions of a turned box (translations, and
    rotations about earth axes where the rule is exact), the virtual work F . dx + M . dtheta
    of the model's force and moment about the reference point is minus the change of the
    potential ``system.energy`` reports (central differences, 1e-7 of the force's scale)."""
    from seacable.system import evaluation
    from seacable.system.coordinates import rotate

    assert isinstance(evaluation, ForceTable)
    built = system_model.build(seacable.load_case(_lone_box([force])))
    p, y = built.params, built.y0.copy()
    w = kernel.make_work(p)

    def potential(state):
        kernel.rhs(0.0, state, p, w, np.zeros_like(state))
        _, gravity, elastic = _energies(state, p, w)
        return gravity + elastic

    potential(y)
    load = w.load[0].copy()
    rng = np.random.default_rng(9)
    h = 1e-5
    for _ in range(4):
        dx, dtheta = rng.normal(size=3), rng.normal(size=3) if turns else np.zeros(3)
        moved = []
        for sign in (1.0, -1.0):
            state = y.copy()
            state[0:3] += sign * h * dx
            state[3:7] = rotate(y[3:7], sign * h * dtheta)
            moved.append(potential(state))
        work = load[:3] @ dx + load[3:] @ dtheta
        assert abs(work + (moved[0] - moved[1]) / (2.0 * h)) < 1e-7 * np.abs(load).max()
    assert np.abs(load).max() > 100.0


@pytest.mark.parametrize(
    "force",
    [{"model": "drag", "drag_coefficient": 1.1, "area": [0.5, 1.5, 2.5]},
     {"model": "linear_damping", "matrix": [[v * 10.0 for v in row] for row in STIFFNESS]}],
)  # fmt: skip
def test_dissipative_force_models_never_do_positive_work(force):
    """ForceTable rule 4: for random twists of a turned box (no current), the power of the
    model's force and moment, F . v + M . omega, is negative."""

    built = system_model.build(seacable.load_case(_lone_box([force])))
    p, y = built.params, built.y0.copy()
    w = kernel.make_work(p)
    rng = np.random.default_rng(3)
    for _ in range(20):
        y[p.n_q : p.n_q + 6] = rng.normal(size=6)
        kernel.rhs(0.0, y, p, w, np.zeros_like(y))
        assert w.load[0] @ y[p.n_q : p.n_q + 6] < 0.0


def test_the_servo_state_rests_at_its_equilibrium():
    """StatefulForceModel rule 3: the servo's force rates vanish with its body on its target
    and moving with it, and are K (a dE / dt - b dE') off it (a random K)."""
    from seacable.forces import servo

    assert isinstance(servo, StatefulForceModel)
    rng = np.random.default_rng(8)
    row = np.array(servo.pack(gain=0.7, rate_gain=0.4, step=0.5, target=1), dtype=float)
    stiffness = rng.normal(size=(3, 3)) * 1e3
    row[:9] = stiffness.ravel()
    points, speeds = rng.normal(size=(2, 3)), rng.normal(size=(2, 3))
    ydot = np.ones(5)
    servo.rates(row, points[1].copy(), speeds[1].copy(), points, speeds, 2, ydot)
    assert not ydot[2:].any()
    pos, vel = points[1] - [0.1, 0.0, 0.2], speeds[1] + [0.0, 0.3, 0.0]
    servo.rates(row, pos, vel, points, speeds, 2, ydot)
    expected = stiffness @ (0.7 * (points[1] - pos) / 0.5 - 0.4 * (speeds[1] - vel))
    np.testing.assert_allclose(ydot[2:], expected, rtol=1e-12)


def test_the_control_states_rest_at_their_equilibrium():
    """StatefulForceModel rules on the controls: a speed controller's integral and a steering
    gear's angle (their modules follow the protocol); their rates vanish with the ship at its
    target speed and the rudder on its command, and are U - u and the gear's law off them."""
    from seacable.forces import fin, propeller, radiation, rudder, servo, thruster

    for module in (servo, radiation, rudder, thruster, propeller, fin):
        assert isinstance(module, StatefulForceModel)
    controller = {"kind": "surge_speed", "target": 3.0, "gain": 1e5, "integral_gain": 1e4}
    gear = {"max_rate_deg_s": 2.0, "time_constant": 0.5}
    case = seacable.load_case({
        "bodies": [{"name": "ship", "type": "rigid", "position": [0, 0, 0], "mass": 1e6,
                    "inertia": [1e8, 1e8, 1e8], "dofs": ["surge", "sway", "yaw"],
                    "external forces": [
                        {"model": "thruster", "controller": controller},
                        {"model": "rudder", "point": [-40, 0, -3], "area": 10.0,
                         "lift_slope": 3.0, "angle_deg": 12.0, "steering_gear": gear}]}],
        "start": "as_given", "simulation": {"duration": 1.0, "output_interval": 1.0},
    })  # fmt: skip
    built = system_model.build(case)
    p, y = built.params, built.y0.copy()
    w, ydot = kernel.make_work(p), np.zeros_like(y)
    s_thrust, s_rudder = int(p.force_state[0]), int(p.force_state[1])
    v = int(p.body_v[0])
    for speed, angle in ((3.0, 12.0), (2.5, 11.0), (3.4, -20.0)):
        y[v] = speed
        y[s_rudder] = math.radians(angle)
        kernel.rhs(0.0, y, p, w, ydot)
        assert ydot[s_thrust] == pytest.approx(3.0 - speed, abs=1e-15)
        expected = max(-2.0, min(2.0, (12.0 - angle) / 0.5))
        assert math.degrees(ydot[s_rudder]) == pytest.approx(expected, abs=1e-12)


def _small_run():
    """The thesis's 12-link chain in air (a planar rigid line), as a built system."""
    case = seacable.load_case(
        Path(__file__).parent.parent / "examples" / "thesis_6_1_sim1_air_12_links.yaml"
    )
    return system_model.build(case)


@pytest.mark.parametrize("name", ["rk4", "dopri5"])
def test_every_compiled_integrator_honours_its_chunk_contract(name):
    """ChunkIntegrator rules 1-4 on rk4 and dopri5: a chunk of 3 output intervals from output
    index 5 writes its rows at exactly (5 + j + 1) * interval, leaves ``y`` at the last row and
    counts its work (rk4: 4 evaluations per step, 40 steps per interval); with a parameter
    turned NaN it stops at once, ``y`` untouched, and reports the status without raising."""
    from seacable.kernels.status import OK
    from seacable.numerics import integrators

    built = _small_run()
    p, y0 = built.params, built.y0.copy()
    interval, steps = 0.05, 40
    k, fsal = np.zeros((7, len(y0))), np.zeros(1, dtype=np.int64)

    def chunk(params, y, states, times, work):
        w = kernel.make_work(params)
        if name == "rk4":
            assert isinstance(integrators.rk4_chunk, ChunkIntegrator)
            return integrators.rk4_chunk(5 * steps, y, interval, steps, 3 * steps, params, w,
                                         states, times, work)  # fmt: skip
        atol = np.full(len(y), 1e-9)
        out = integrators.dopri5_chunk(
            5, y, interval, 3, 1e-3, 1e-7, atol, np.empty(0), interval, params, w, states, times,
            work, k, fsal, np.zeros(2), 2**62,
        )  # fmt: skip
        return out[:2]

    y = y0.copy()
    states, times = np.full((3, len(y)), np.nan), np.full(3, np.nan)
    work = np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
    completed, status = chunk(p, y, states, times, work)
    assert (completed, status) == (3, OK)
    assert np.array_equal(times, np.array([6, 7, 8]) * interval)
    assert np.array_equal(y, states[-1]) and np.isfinite(states).all()
    accepted, _, evaluations = work[:3]
    if name == "rk4":
        assert accepted == 3 * steps and evaluations == 4 * accepted
    else:
        assert accepted > 0 and evaluations >= 6 * accepted
    broken = p._replace(gravity=np.nan)
    y = y0.copy()
    completed, status = chunk(broken, y, states, times, np.zeros_like(work))
    assert completed == 0 and status != OK
    assert np.array_equal(y, y0)
