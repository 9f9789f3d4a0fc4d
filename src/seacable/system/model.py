"""What the run loop (``simulation``) reaches of a system of bodies and lines: its build, its
output variables per group (``bodies/<name>``, ``lines/<name>``), its output rows, the scales and
frequencies the integrators' defaults and warnings use."""

import logging
import math

import numpy as np
from scipy import sparse

from seacable.bodies import kinematics
from seacable.case import system as sch
from seacable.system import (
    coordinates,
    failures,
    geometry,
    kernel,
    outputs,
    servo,
    statics,
    topology,
)
from seacable.system import rigid as rigid_kind
from seacable.system.assemble import BuiltSystem
from seacable.system.assemble import build as _assemble
from seacable.system.force_rows import rods_at_rest
from seacable.system.frequency import fastest_frequency  # noqa: F401 (the contract's)
from seacable.system.initial import end_points, initial_state
from seacable.system.variables import (  # noqa: F401 (the contract's)
    ANGLES,
    AXES,
    BODY_NAMES,
    COMPENSATOR_VARIABLES,
    ENERGY_VARIABLES,
    controls,
    coords,
    sizes,
    variables,
)

log = logging.getLogger("seacable")
RATE_WHAT = ("component", "speed", "m/s", 1)  # what ``rates`` measures (divergence messages)
DAMPING_ADVICE = "add axial damping (line_types[k].axial_damping_ratio, e.g. 0.8)"
JOINT_ADVICE = "add joint damping (lines[k].joint_damping [N m s/rad])"


def build(case: sch.SystemCase, base_dir=None) -> BuiltSystem:
    """Parameters and initial state: lines at their static shape, and with ``start: static``
    every free body at its static equilibrium too (the velocities the case gives are kept)."""
    servo.check_body(case)
    built = _assemble(case, base_dir)
    case = built.case  # with the failures' point bodies (system.failures)
    if case.start == "static":
        topology.check_held(case)
    y0, params = initial_state(built)
    built = BuiltSystem(params=params, y0=built.y0, layout=built.layout, case=case)
    p = built.params
    if servo.servos(built):  # each servo's stiffness and start: its body held at its target
        p, held = servo.start(built, y0)
        if case.start == "static":
            y0 = held
        else:
            y0[p.n_q + p.n_v :] = held[p.n_q + p.n_v :]
        built = BuiltSystem(params=p, y0=y0, layout=built.layout, case=case)
    elif case.start == "static":
        given = y0[p.n_q : p.n_q + p.n_v].copy()
        y0 = statics.equilibrium(built, y0)
        rods_at_rest(built, y0)
        steady = statics.steady_velocities(p, y0)  # a tow keeps its steady motion
        if steady.any():
            _replaced_velocities(built, given, steady)
        y0[p.n_q : p.n_q + p.n_v] = steady if steady.any() else given
    built = BuiltSystem(params=p, y0=y0, layout=built.layout, case=case)
    _place_failures(built, y0)
    servo.check(built, y0)
    _carried_velocities(built)
    geometry.check_start(built, y0)
    return built


def _replaced_velocities(built: BuiltSystem, given: np.ndarray, steady: np.ndarray) -> None:
    """Report the free bodies whose given velocity a tow's static start replaces by the steady
    motion (nothing is changed silently)."""
    p = built.params
    for b, body in enumerate(built.case.bodies):
        if p.body_kind[b] != kinematics.DYNAMIC:
            continue
        v = int(p.body_v[b]) - p.n_q
        if np.any(given[v : v + 3] != 0.0) and np.any(given[v : v + 3] != steady[v : v + 3]):
            log.warning(
                f"bodies[{b}] ({body.name}).velocity {np.round(given[v : v + 3], 6).tolist()} "
                f"m/s is replaced by the tow's steady motion, "
                f"{np.round(steady[v : v + 3], 6).tolist()} m/s (start: static starts a tow in "
                "its steady state; use start: as_given to keep the velocity)"
            )


def _carried_velocities(built: BuiltSystem) -> None:
    """Report the bodies carried at a rigid line's tip whose case gives a velocity: they move
    with the tip, and the velocity is not used."""
    for b, body in enumerate(built.case.bodies):
        given = getattr(body, "velocity", (0.0, 0.0, 0.0))
        if built.params.body_kind[b] == kinematics.TIP and any(v != 0.0 for v in given):
            log.warning(
                f"bodies[{b}] ({body.name}).velocity {list(given)} m/s is not used: the body "
                "rides at the tip of a rigid line and moves with it (give the line's motion, "
                "or leave the velocity out)"
            )


def watch(system: BuiltSystem) -> geometry.Watch:
    """What a run watches its rows for (``system.geometry.Watch``)."""
    return geometry.Watch(system)


def damping_advice(system: BuiltSystem) -> str:
    """What a divergence message suggests: axial damping for lumped lines and strings, joint
    damping for rigid lines, whichever the system has."""
    p = system.params
    advice = [DAMPING_ADVICE] if len(p.line_n) or len(p.nat_n) else []
    if len(p.rs_n):
        advice.append(JOINT_ADVICE)
    return " or ".join(advice) if advice else "add damping to the ties (lines[k].damping)"


def _place_failures(built: BuiltSystem, y0: np.ndarray) -> None:
    """Each failure's point body (system.failures) at the point its line ends are attached to
    at the start ``y0``, in ``y0``."""
    p = built.params
    if not len(p.fail_line):
        return
    ppos, _ = end_points(built, y0)
    for k in range(len(p.fail_line)):
        at = int(p.body_q[p.fail_body[k]])
        y0[at : at + 3] = ppos[p.fail_orig[k]]


def refresh_interval(case: sch.SystemCase) -> float | None:
    """How often [s] the run must call :func:`refresh` (None: never)."""
    return servo.refresh_interval(case)


def refresh(case: sch.SystemCase, p: kernel.SystemParams, time: float, y: np.ndarray):
    """Parameters for the next stretch of the run: the servos' K about the current target."""
    built = _assemble(case, case._base_dir)
    built = BuiltSystem(params=p, y0=built.y0, layout=built.layout, case=built.case)
    return servo.refresh(built, p, time, y)


def workspace(system: BuiltSystem) -> kernel.SystemWork:
    return kernel.make_work(system.params)


def start_memory(system: BuiltSystem, w: kernel.SystemWork, t: float, y: np.ndarray) -> None:
    """The radiation models' velocity histories at a run's start (kernel.start_memory)."""
    kernel.start_memory(t, y, system.params, w)


def after_step(system: BuiltSystem, w: kernel.SystemWork, t: float, y: np.ndarray) -> None:
    """An accepted step of an integrator driven from Python (kernel.after_step)."""
    kernel.after_step(t, y, system.params, w)


def _control_rows(system: BuiltSystem, states, out: dict) -> None:
    """Each rudder's steering-gear angle and fin's actuator angle [deg], and speed controller's
    integral [m]."""
    for b, body in enumerate(system.case.bodies):
        for s, name, kind in controls(system, b):
            values = states[:, s]
            out[f"bodies/{body.name}/{name}"] = np.degrees(values) if kind in ANGLES else values


def rows(times, states, system: BuiltSystem, w) -> tuple[dict, int]:
    """The output rows of ``states`` at ``times``, evaluated with the run's workspace ``w`` (its
    radiation histories) but leaving its lines' records (``w.nodes``: the branches and water
    kinematics an implicit step's residuals reuse, kernels.lumped LAGGED) as the steps left
    them: the outputs run where a chunk ends, and an output's evaluation at the next step's
    start time made that step reuse its records instead of the last step's, so that results
    depended on where chunks ended, that is on the machine's load (1.4e-5 in 10 s of the
    moored barge; ``tests/test_reproducible.py``)."""
    p = system.params
    m = len(times)
    filled = outputs.allocate(p, m)
    kept = w.nodes.copy()
    status = failures.fill(times, states, p, w, filled)
    w.nodes[:] = kept
    bodies, nodes, tension, ends, ties, energy, rigid, control = filled
    out: dict = {"time": times}
    for k, name in enumerate(list(ENERGY_VARIABLES)[:3]):
        out[name] = energy[:, k]
    out["total_energy"] = energy.sum(axis=1)
    for b, body in enumerate(system.case.bodies):
        for k, name in enumerate(BODY_NAMES):
            out[f"bodies/{body.name}/{name}"] = bodies[:, b, k]
    _servo_rows(system, states, bodies, out)
    _control_rows(system, states, out)
    for k, f in enumerate(p.compensator):
        group = f"bodies/{system.case.bodies[int(p.force_body[f])].name}"
        for i, (name, _, _) in enumerate(COMPENSATOR_VARIABLES):
            out[f"{group}/{name}"] = control[:, k, i]
    for li, line in enumerate(system.layout.lines):
        n, c0, s0 = int(p.line_n[li]), int(p.line_node[li]), int(p.line_seg[li])
        for c, axis in enumerate(AXES):
            out[f"lines/{line}/node_{axis}"] = nodes[:, c0 : c0 + n + 1, c]
            out[f"lines/{line}/from_force_{axis}"] = ends[:, li, 0, c]
            out[f"lines/{line}/to_force_{axis}"] = ends[:, li, 1, c]
        out[f"lines/{line}/tension"] = tension[:, s0 : s0 + n]
    for li, line in enumerate(system.layout.rigid):
        n, c0, s0 = int(p.rs_n[li]), int(p.rs_node[li]), int(p.rs_seg[li])
        for c, axis in enumerate(AXES):
            out[f"lines/{line}/node_{axis}"] = rigid[0][:, c0 : c0 + n + 1, c]
            out[f"lines/{line}/from_force_{axis}"] = rigid[2][:, li, 0, c]
            out[f"lines/{line}/to_force_{axis}"] = rigid[2][:, li, 1, c]
        out[f"lines/{line}/tension"] = rigid[1][:, s0 : s0 + n]
        q, v = int(p.rs_q[li]), int(p.rs_v[li])
        if p.rs_kind[li] == rigid_kind.PLANAR:
            out[f"lines/{line}/angle"] = states[:, q : q + n]
            out[f"lines/{line}/angular_velocity"] = states[:, v : v + n]
        else:
            e = states[:, q : q + 3 * n].reshape(m, n, 3)
            for c, axis in enumerate(AXES):
                out[f"lines/{line}/direction_{axis}"] = e[:, :, c]
            rates = states[:, v : v + 3 * n].reshape(m, n, 3)
            out[f"lines/{line}/angular_rate"] = np.linalg.norm(rates, axis=2)
        if p.rs_held[li].any():
            out[f"lines/{line}/constraint_error"] = rigid[3][:, li]
    _string_rows(system, rigid[4], out)
    for k, line in enumerate(system.layout.ties):
        out[f"lines/{line}/tension"] = ties[:, k, 0]
        out[f"lines/{line}/distance"] = ties[:, k, 1]
        for c, axis in enumerate(AXES):
            out[f"lines/{line}/from_{axis}"] = ties[:, k, 2 + c]
            out[f"lines/{line}/to_{axis}"] = ties[:, k, 5 + c]
    return out, status


def _servo_rows(system: BuiltSystem, states, bodies, out: dict) -> None:
    """Each servo's force (its state), target and the body's distance from it."""
    p = system.params
    for f, b, spec in servo.servos(system):
        group = f"bodies/{system.case.bodies[b].name}"
        s = int(p.force_state[f])
        k = system.layout.point_index[spec.target]
        target = _point_rows(bodies, int(p.point_body[k]), p.point_offset[k])
        for c, axis in enumerate(AXES):
            out[f"{group}/servo_force_{axis}"] = states[:, s + c]
            out[f"{group}/target_{axis}"] = target[:, c]
        position = bodies[:, b, :3]
        out[f"{group}/tracking_error"] = np.linalg.norm(target - position, axis=1)


def _string_rows(system: BuiltSystem, strings, out: dict) -> None:
    """Each natural string's nodes, strain and tension (outputs.rigid_rows' fifth array)."""
    at = 0
    for li, line in enumerate(system.layout.natural):
        n = int(system.params.nat_n[li])
        for c, axis in enumerate(AXES):
            out[f"lines/{line}/node_{axis}"] = strings[:, at : at + n + 1, c]
        out[f"lines/{line}/strain"] = strings[:, at : at + n + 1, 3]
        out[f"lines/{line}/tension"] = strings[:, at : at + n + 1, 4]
        at += n + 1


def _point_rows(bodies: np.ndarray, b: int, offset: np.ndarray) -> np.ndarray:
    """(m, 3) positions of a point at ``offset`` (body frame) of body b, from the bodies' rows
    (position, then roll, pitch, yaw [deg]: R = Rz Ry Rx, scipy's extrinsic "xyz")."""
    if not np.any(offset):
        return bodies[:, b, :3].copy()
    from scipy.spatial.transform import Rotation  # here: its import is slow (docs/architecture.md)

    turn = Rotation.from_euler("xyz", bodies[:, b, 3:6], degrees=True)
    return bodies[:, b, :3] + turn.apply(np.asarray(offset, float))


def _size(system: BuiltSystem) -> float:
    """A length scale of the system [m]: its lines' total length, else 1 m."""
    p = system.params
    total = (p.seg_length.sum() if len(p.line_n) else 0.0) + (
        p.rs_length.sum() if len(p.rs_n) else 0.0) + float(np.sum(p.nat_length))  # fmt: skip
    return float(max(1.0, total))


def state_scale(case, system: BuiltSystem) -> np.ndarray:
    """Typical magnitude of each state: positions the system's length scale L, quaternions,
    rigid segments' directors and links' angles 1, velocities sqrt(g L) (angular, and the
    directors' and angles' rates: sqrt(g / L)), force models' states (forces [N]) their
    largest start value (at least 1 N)."""
    p = system.params
    size = _size(system)
    q = np.full(p.n_q, size)
    v = np.full(p.n_v, math.sqrt(p.gravity * size))
    turning = math.sqrt(p.gravity / size)
    for b in range(len(p.body_kind)):
        if p.body_q[b] >= 0 and p.body_rigid[b]:
            q[p.body_q[b] + 3 : p.body_q[b] + 7] = 1.0
            at = p.body_v[b] - p.n_q  # body_v is an offset in y, v holds the velocities only
            v[at + 3 : at + 6] = turning
    for li in range(len(p.rs_n)):
        width = (3 if p.rs_kind[li] == rigid_kind.SEGMENTS_3D else 1) * int(p.rs_n[li])
        q[p.rs_q[li] : p.rs_q[li] + width] = 1.0
        v[p.rs_v[li] - p.n_q : p.rs_v[li] - p.n_q + width] = turning
    for li in range(len(p.nat_n)):  # strains: the string's weight over EA; angles, tangents 1
        block = 3 if p.nat_cartesian[li] else 2
        size_li = block * (int(p.nat_n[li]) + 1)
        strain = p.nat_mu[li] * p.nat_length[li] * p.gravity / p.nat_ea[li]
        per_node = np.ones(block)
        per_node[0] = strain
        q[p.nat_q[li] : p.nat_q[li] + size_li] = np.tile(per_node, int(p.nat_n[li]) + 1)
        v[p.nat_v[li] - p.n_q : p.nat_v[li] - p.n_q + size_li] = (
            np.tile(per_node, int(p.nat_n[li]) + 1) * turning
        )
    states = system.y0[p.n_q + p.n_v :]
    s = np.full(p.n_s, max(1.0, float(np.abs(states).max())) if p.n_s else 1.0)
    return np.concatenate([q, v, s])


def positions(system: BuiltSystem) -> int:
    """The unknowns the implicit schemes solve for: the acceleration of every velocity variable,
    then the rate of every force model's state (a servo's force)."""
    return int(system.params.n_v) + int(system.params.n_s)


def rates(system: BuiltSystem, y) -> np.ndarray:
    """Speed of every dynamic body and interior node [m/s] (divergence messages)."""
    p = system.params
    v = y[p.n_q : p.n_q + p.n_v]
    return np.abs(v) if len(v) else np.zeros(1)


def _pairs(rows_at, rows_n, cols_at, cols_n) -> tuple[np.ndarray, np.ndarray]:
    """Every (row, column) with the row in range(rows_at[k], rows_at[k] + rows_n[k]) and the
    column in range(cols_at[k], cols_at[k] + cols_n[k]), for each k (integer arrays)."""
    per = rows_n * cols_n
    k = np.repeat(np.arange(len(per)), per)
    offset = np.arange(int(per.sum())) - np.repeat(np.cumsum(per) - per, per)
    return rows_at[k] + offset // cols_n[k], cols_at[k] + offset % cols_n[k]


def jacobian_sparsity(system: BuiltSystem) -> sparse.csc_matrix:
    """The pattern of d(ydot)/dy (SciPy's stiff integrators colour its columns): positions
    move with their velocities (a quaternion with its angular velocity and itself), every
    acceleration depends on the positions and velocities of the coordinates
    ``coordinates.pattern`` couples it to."""
    p = system.params
    coords_ = coordinates.coordinates(p)
    coupled = coordinates.pattern(p, coords_).tocoo()
    n = p.n_q + p.n_v + p.n_s
    kind = np.asarray(coords_.kind)
    q, v = np.asarray(coords_.q, dtype=np.int64), np.asarray(coords_.v, dtype=np.int64)
    # a quaternion's 4 positions, a director's 3 (and its 3 rates), else 1
    n_q = np.where(kind == 1, 4, np.where(kind == 3, 3, 1)).astype(np.int64)
    n_v = np.where(kind == 3, 3, 1).astype(np.int64)
    own = (kind == 1) | (kind == 3)
    i, j = coupled.row.astype(np.int64), coupled.col.astype(np.int64)
    parts = [
        _pairs(q, n_q, v, n_v),  # dq/dt from v (a quaternion: from omega and itself)
        _pairs(q[own], n_q[own], q[own], n_q[own]),
        _pairs(v[i], n_v[i], q[j], n_q[j]),  # an acceleration from coupled positions
        _pairs(v[i], n_v[i], v[j], n_v[j]),  # ... and velocities
    ]
    rows: list[int] = np.concatenate([r for r, _ in parts]).tolist()
    cols: list[int] = np.concatenate([c for _, c in parts]).tolist()
    for li in range(len(p.nat_n)):  # a natural string: each node with its neighbours
        block, nodes = (3 if p.nat_cartesian[li] else 2), int(p.nat_n[li]) + 1
        q0, v0 = int(p.nat_q[li]), int(p.nat_v[li])
        for i in range(nodes):
            mine = range(block * i, block * (i + 1))
            near = range(block * max(0, i - 1), block * min(nodes, i + 2))
            for r in mine:
                rows.extend([q0 + r] * block)
                cols.extend(v0 + c for c in mine)
                rows.extend([v0 + r] * (2 * len(near)))
                cols.extend([q0 + c for c in near] + [v0 + c for c in near])
    for s in range(p.n_q + p.n_v, n):  # a force model's state: its rates read the state, and
        rows.extend([s] * n)  # its force reaches the accelerations (taken as coupled to all)
        cols.extend(range(n))
        rows.extend(range(p.n_q, p.n_q + p.n_v))
        cols.extend([s] * p.n_v)
    return sparse.csc_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))


def shortest_segment(system: BuiltSystem) -> float:
    p = system.params
    lengths = [p.seg_length[: int(p.line_n.sum())], p.rs_length[: int(p.rs_n.sum())]]
    every = np.concatenate(lengths)
    return float(every.min()) if every.size else 1.0
