"""The compiled right-hand side of a system of bodies and lines.

State: ``y = [Q, V, S]``. Q holds, per dynamic body, its reference point's position (3) and, for
a rigid body, its orientation quaternion (4); then the interior nodes of every lumped-mass line
(3 each). V holds, per dynamic body, its velocity (3) and, for a rigid body, its angular
velocity (3, earth frame); then the interior nodes' velocities. S holds the force models'
states (first-order: a servo's force; ``force_state``). The offsets are
``body_q``/``body_v`` and ``line_q``/``line_v`` (system.assemble): every array is flat with
offsets, so the compiled types depend on no count.

One evaluation: (1) every body's pose and twist (fixed, imposed from its channels, dynamic from
the state); (2) every point's position and velocity; (3) every tie's force and every line's
loads, the interior nodes' accelerations, the end nodes' mass and loads handed to their bodies;
(4) every force model; (5) each dynamic body's 6x6 equation solved on its free degrees of
freedom. O(total nodes + bodies).
"""

from typing import NamedTuple

import numpy as np
from numba import njit

from seacable.bodies import dynamics, kinematics
from seacable.forces import compensator, hydrostatic, kinds, radiation
from seacable.kernels import chain3d as c3
from seacable.kernels import hull, indirect, memory, records, surface, waves
from seacable.kernels import lumped as lk
from seacable.kernels.jit import JIT, inner
from seacable.lines import lumped_mass, tip_joint
from seacable.system import rigid

DYNAMIC = kinematics.DYNAMIC
IMPOSED = kinematics.IMPOSED
TIP = kinematics.TIP


class _ParamsFields(NamedTuple):
    """Flat parameters of a system (SI units); see system.assemble for how each is built."""

    n_q: int  # position variables
    n_v: int  # velocity variables
    n_s: int  # force models' states, after the velocities
    body_kind: np.ndarray  # (nb,) int: kinematics.FIXED, IMPOSED or DYNAMIC
    body_rigid: np.ndarray  # (nb,) int: 1 with an orientation state
    body_q: np.ndarray  # (nb,) int: offset of the position in y (-1: none)
    body_v: np.ndarray  # (nb,) int: offset of the velocity in y (-1: none)
    body_channel: np.ndarray  # (nb,) int: an imposed body's first channel (x y z roll pitch yaw)
    body_motion: np.ndarray  # (nb,) int: how an imposed body moves (kinematics.MOVES, TURNS,
    # TRACK)
    body_track: np.ndarray  # (nb, 5) an imposed body's track (kinematics.track_point)
    body_parent: np.ndarray  # (nb,) int: the imposed body an imposed body's position is
    # relative to (-1: none)
    body_pose: np.ndarray  # (nb, 7) fixed bodies: position, quaternion
    body_mass: np.ndarray  # (nb,) [kg]
    body_cog: np.ndarray  # (nb, 3) centre of gravity, body frame [m]
    body_inertia: np.ndarray  # (nb, 3, 3) about the CoG, body frame [kg m^2]
    body_added: np.ndarray  # (nb, 6, 6) added mass, body frame at the reference point
    body_coriolis: np.ndarray  # (nb,) int: its velocity terms (bodies.dynamics RIGID_BODY, EXACT)
    body_free: np.ndarray  # (nb, 6) 1.0 on a free degree of freedom
    body_volume: np.ndarray  # (nb,) wholly submerged [m^3]
    body_cob: np.ndarray  # (nb, 3) centre of buoyancy, body frame [m]
    body_shape: np.ndarray  # (nb, L) shape rows (kernels.surface)
    # free bodies that rigid lines held on them join (system.topology.port_groups) are solved
    # together with those lines' holding forces, group by group (few arrays: each one in these
    # tuples costs every call of ``rhs`` a reference taken and dropped)
    body_group: np.ndarray  # (nb, 2) int: a body's group (-1: alone), its place in it
    group_first: np.ndarray  # (groups + 1, 2) int: a group's first body, first line in
    # group_member
    group_member: np.ndarray  # int: the groups' bodies, then their lines (rigid-line numbers)
    # and joints (-1 - j)
    joint: np.ndarray  # (nj, 2) int: a joint's points, on the pinned body, on the other
    point_body: np.ndarray  # (np,) int
    point_offset: np.ndarray  # (np, 3) body frame [m]
    force_kind: np.ndarray  # (nf,) int: forces.kinds
    force_body: np.ndarray  # (nf,) int
    force_at: np.ndarray  # (nf,) int: first float of the row in force_data
    force_first: np.ndarray  # (nf,) int: first channel
    force_state: np.ndarray  # (nf,) int: first state in y (-1: none; forces.table.state_count)
    force_data: np.ndarray  # floats of every row
    compensator: np.ndarray  # (nc,) int: the force rows of the compensators (forces.compensator)
    line_n: np.ndarray  # (nl,) int: segments
    line_seg: np.ndarray  # (nl,) int: first segment in the segment arrays
    line_node: np.ndarray  # (nl,) int: first node (workspace column, node arrays)
    line_q: np.ndarray  # (nl,) int: first interior position in y
    line_v: np.ndarray  # (nl,) int: first interior velocity in y
    line_from: np.ndarray  # (nl,) int: point of node 0 (a failure moves it: system.failures)
    line_to: np.ndarray  # (nl,) int: point of node n
    # line failures, a row per released end (system.failures): the line, its end (0 from,
    # 1 to), the failure, its point body and point, the point the end was attached to, the
    # time [s] and tension [N] that release it (inf: none), NaN or the time it was released
    fail_line: np.ndarray
    fail_end: np.ndarray
    fail_group: np.ndarray
    fail_body: np.ndarray
    fail_point: np.ndarray
    fail_orig: np.ndarray
    fail_time: np.ndarray
    fail_tension: np.ndarray
    fail_state: np.ndarray
    seg_length: np.ndarray  # unstretched [m]
    seg_stiffness: np.ndarray  # EA [N]
    seg_damping: np.ndarray  # alpha [s]
    slack_allowed: int  # kernels.lumped LAW (no compression), LINEAR (statics), FROZEN (Newton)
    seg_drag_normal: np.ndarray  # 0.5 rho Cd_n d li [N s^2/m^2]
    seg_drag_tangential: np.ndarray  # [N s^2/m^2]
    seg_wet_weight: np.ndarray  # positive down [N]
    seg_buoyancy: np.ndarray  # rho g A li [N]
    seg_added_mass: np.ndarray  # (segments, 2) normal and tangential [kg]
    node_mass: np.ndarray  # [kg]
    node_seabed_stiffness: np.ndarray  # [N/m]
    node_seabed_damping: np.ndarray  # [N s/m]
    node_bend: np.ndarray  # EI / mean span at interior nodes [N m]
    tie_from: np.ndarray  # (nt,) int: point
    tie_to: np.ndarray  # (nt,) int
    tie_first: np.ndarray  # (nt,) int: first table row
    tie_count: np.ndarray  # (nt,) int: table rows (0: linear)
    tie_length: np.ndarray  # L0 [m]
    tie_stiffness: np.ndarray  # k [N/m] (0 with a table)
    tie_damping: np.ndarray  # c [N s/m]
    tie_table: np.ndarray  # (K, 2) elongation [m], tension [N]
    # rigid-segment lines (lines.rigid_segments): per line, then per segment
    rs_n: np.ndarray  # (nr,) int: segments
    rs_seg: np.ndarray  # (nr,) int: first segment
    rs_node: np.ndarray  # (nr,) int: first workspace column (n + 1 each)
    rs_q: np.ndarray  # (nr,) int: first director in y
    rs_v: np.ndarray  # (nr,) int: first director rate in y
    rs_from: np.ndarray  # (nr,) int: point of node 0
    rs_to: np.ndarray  # (nr,) int: point of node n
    rs_tip: np.ndarray  # (nr,) int: the point body carried at node n (-1: held on ``to``)
    rs_order: np.ndarray  # (nr,) int: lines in the order of the backward sweeps (children first)
    rs_kind: np.ndarray  # (nr,) int: 0 rigid segments in 3D (directors), 1 planar links (angles)
    rs_held: np.ndarray  # (nr, 3) 1.0 on the axes the tip is held on
    rs_port: np.ndarray  # (nr,) int: 1 when the tip is held on a free (point or rigid) body
    rs_ref: np.ndarray  # (nr, 3) first joint's unloaded direction, base body frame
    # (m, 7) per joint at a line's end (lines.tip_joint): the line (its last segment), the
    # line that continues it (its first segment; -1: the body the end is held on), the
    # unloaded direction on a held end (3, that body's frame), k [N m/rad], c [N m s/rad]
    rs_tip_joint: np.ndarray
    rs_length: np.ndarray  # [m]
    rs_mass: np.ndarray  # structural [kg]
    rs_added: np.ndarray  # normal added mass [kg]
    rs_inertia: np.ndarray  # about the centre, added included [kg m^2]
    rs_wet_weight: np.ndarray  # positive down [N]
    rs_buoyancy: np.ndarray  # rho g A l [N]
    rs_drag_normal: np.ndarray  # 0.5 rho Cd d l [N s^2/m^2]
    rs_drag_tangential: np.ndarray  # [N s^2/m^2]
    rs_joint_stiffness: np.ndarray  # joint i at the top of segment i [N m/rad]
    rs_joint_damping: np.ndarray  # [N m s/rad]
    # natural-variables strings (lines.natural_string): per line
    nat_n: np.ndarray  # (nn,) int: elements
    nat_q: np.ndarray  # (nn,) int: first node variable in y
    nat_v: np.ndarray  # (nn,) int: first rate in y
    nat_from: np.ndarray  # (nn,) int: the pivot's point
    nat_tip: np.ndarray  # (nn,) int: the end body
    nat_cartesian: np.ndarray  # (nn,) int: 1 (eps, t_x, t_z), 0 (eps, phi)
    nat_length: np.ndarray  # [m]
    nat_mu: np.ndarray  # mass per unstretched length [kg/m]
    nat_ea: np.ndarray  # EA [N]
    nat_alpha: np.ndarray  # axial damping time [s]
    stabilization_frequency: float  # held tips, Baumgarte [rad/s]
    gravity: float  # [m/s^2]
    rho: float  # water density, 0 in air [kg/m^3]
    seabed_z: float  # [m] (-1e30: none)
    seabed_friction: float
    seabed_slip_speed: float  # [m/s]
    seabed_band: float  # [m] over which the contact stiffness rises (kernels.lumped)
    current_z: np.ndarray
    current_u: np.ndarray
    current_v: np.ndarray
    wave: np.ndarray  # (n, 7) incident wave components (kernels.waves; none: (0, 7))
    wave_depth: float  # the depth the waves feel [m] (kernels.waves.DEEP: deep water)
    wave_stretch: int  # kernels.waves WHEELER or VERTICAL
    wind_channel: int  # the wind's speed channel, its direction [rad] the next (-1: no wind)
    tf_breaks: np.ndarray
    tf_coefs: np.ndarray
    tf_count: np.ndarray
    tf_sine: np.ndarray
    tf_build_up: np.ndarray
    # the addresses of the evaluation's entries compiled for this system's kinds (ENTRIES,
    # system.variants.bind; 0: not bound), valid in this process only
    entries: np.ndarray = np.zeros(11, dtype=np.int64)  # ENTRIES, then PARTS


class _WorkFields(NamedTuple):
    """Scratch arrays of one evaluation (allocated once per run)."""

    pos: np.ndarray  # (nb, 3)
    rot: np.ndarray  # (nb, 3, 3)
    vel: np.ndarray  # (nb, 3)
    omega: np.ndarray  # (nb, 3)
    acc: np.ndarray  # (nb, 6) accelerations (dynamic: solved; imposed: from the channels)
    fraction: np.ndarray  # (nb,) submerged fraction
    load: np.ndarray  # (nb, 6) force and moment at the reference point (earth frame)
    mass: np.ndarray  # (nb, 6, 6)
    bias: np.ndarray  # (nb, 6)
    ppos: np.ndarray  # (np, 3)
    pvel: np.ndarray  # (np, 3)
    parm: np.ndarray  # (np, 3)
    nodes: np.ndarray  # (lumped.N_WORK_ROWS, total nodes)
    line: np.ndarray  # (6 (max n + 1),) one line's nodes
    end_mass: np.ndarray  # (nl, 2, 9) end nodes' mass matrices
    end_load: np.ndarray  # (nl, 2, 3) end nodes' loads
    tie_tension: np.ndarray  # (nt,)
    tie_force: np.ndarray  # (nt, 3) on the from point
    rhs6: np.ndarray  # (6,) one body's right-hand side
    quat: np.ndarray  # (nb, 4) orientation quaternions
    rs: np.ndarray  # (chain3d_layout.N_WORK_ROWS * rigid-line nodes) flat: system.rigid._view
    rs_force: np.ndarray  # (nr, 3) holding force L at a held tip (its constant part l0 between
    # the backward and the forward sweeps)
    # (nr, 30) dL/dA_0 (9, row-major); of a line held on a free body instead its closure's
    # right-hand side r (3), the tip's maps G = dA_n/dA_0 and A_L = dA_n/dL, and
    # S_0 = dlam_0/dL (3x3 each, row-major)
    rs_la: np.ndarray
    group: np.ndarray  # (m + 2, m) one group's equations, then its right-hand side and
    # solution (m: 6 per body and 3 per line, the largest group's)
    own_load: np.ndarray  # (nb, 3) every body's force before its rigid lines' (statics)
    scratch: np.ndarray  # (168,) the rigid lines' and the groups' small vectors of one evaluation
    imposed: np.ndarray  # (18,) an imposed body's channels (kinematics.imposed_channels)
    nat: np.ndarray  # (6 (max n + 1),) a natural string's state in the kernel's layout
    nat_dot: np.ndarray  # its rates
    nat_work: np.ndarray  # (9, max n + 1) kernels.natural's workspace
    nat_out: np.ndarray  # (max n + 1, 4) a string's nodes: x, z from the pivot, strain, tension
    hull: np.ndarray  # kernels.hull.place's workspace (hull.workspace, the largest mesh)
    trig: np.ndarray  # (kernels.waves.SCRATCH, wave components) the force models' wave scratch
    memory: np.ndarray  # a force model's scratch, then the radiation models' velocity
    # histories (kernels.memory)
    models: np.ndarray  # (nb, 6) the force models' loads at the last evaluation of them
    control: np.ndarray  # (nc, compensator.RECORD) each compensator's force and moment
    models_key: np.ndarray  # (1 + 13 nb + n_s,) what they were evaluated at: the time, every
    # body's pos, quat, vel and omega, the models' states (NaN: none; see _models_kept)


@records.register
class SystemParams(_ParamsFields, records.Unshared):
    """Flat parameters of a system (SI units; system.assemble builds them): a named tuple in
    Python, passed by reference to compiled code (kernels.records)."""


@records.register
class SystemWork(_WorkFields, records.Unshared):
    """Scratch arrays of one evaluation (allocated once per run): a named tuple in Python,
    passed by reference to compiled code (kernels.records)."""


def make_work(p: SystemParams) -> SystemWork:
    nb, npt, nl, nt = len(p.body_kind), len(p.point_body), len(p.line_n), len(p.tie_from)
    nr = len(p.rs_n)
    rs_nodes = int((p.rs_n + 1).sum()) if nr else 1
    nmax = int(p.line_n.max()) if nl else 1
    nat = int(p.nat_n.max()) + 1 if len(p.nat_n) else 2
    g = 6
    if len(p.group_first) > 1:
        g = int((np.diff(p.group_first, axis=0) @ np.array([6, 3])).max())
    return SystemWork(
        pos=np.zeros((nb, 3)), rot=np.zeros((nb, 3, 3)), vel=np.zeros((nb, 3)),
        omega=np.zeros((nb, 3)), acc=np.zeros((nb, 6)), fraction=np.ones(nb),
        load=np.zeros((nb, 6)), mass=np.zeros((nb, 6, 6)), bias=np.zeros((nb, 6)),
        ppos=np.zeros((npt, 3)), pvel=np.zeros((npt, 3)), parm=np.zeros((npt, 3)),
        nodes=np.zeros((lk.N_WORK_ROWS, max(1, len(p.node_mass)))),
        line=np.zeros(6 * (nmax + 1)), end_mass=np.zeros((nl, 2, 9)),
        end_load=np.zeros((nl, 2, 3)), tie_tension=np.zeros(nt), tie_force=np.zeros((nt, 3)),
        rhs6=np.zeros(6), quat=np.zeros((nb, 4)), rs=np.zeros(c3.N_WORK_ROWS * rs_nodes),
        rs_force=np.zeros((max(nr + len(p.joint), 1), 3)), rs_la=np.zeros((max(nr, 1), 30)),
        group=np.zeros((g + 2, g)),
        own_load=np.zeros((nb, 3)), scratch=np.zeros(168), imposed=np.zeros(18),
        nat=np.zeros(6 * nat), nat_dot=np.zeros(6 * nat), nat_work=np.zeros((9, nat)),
        nat_out=np.zeros((nat, 4)), hull=hull.workspace(_vertices(p), p.wave.shape[1]),
        trig=np.zeros((waves.SCRATCH, p.wave.shape[1])),
        memory=np.zeros(max(memory.SCRATCH, _memory(p))), models=np.zeros((nb, 6)),
        models_key=np.full(1 + 13 * nb + int(p.n_s), np.nan),
        control=np.zeros((max(1, len(p.compensator)), compensator.RECORD)),
    )  # fmt: skip


def _memory(p: SystemParams) -> int:
    """The floats of every radiation convolution's history block (kernels.memory: each row's
    offset and its count)."""
    rows = [
        p.force_data[at + radiation.MEMORY :]
        for kind, at in zip(p.force_kind, p.force_at, strict=True)
        if kind == kinds.RADIATION_DAMPING and radiation.uses_history(p.force_data[at:])
    ]
    ends = [int(row[2]) + memory.block_size(int(row[0])) for row in rows]  # fmt: skip
    return max(ends, default=memory.SCRATCH)


def _vertices(p: SystemParams) -> int:
    """The most vertices a mesh force model's row holds (kernels.hull: the first float of the
    mesh's row)."""
    at_mesh = hydrostatic.MESH_AT
    counts = [int(p.force_data[at + at_mesh]) for kind, at in zip(p.force_kind, p.force_at,
              strict=True) if kind in kinds.MESH]  # fmt: skip
    return max(counts, default=1)


@inner
def _fractions(kind, shape, pos, fraction):
    for b in range(kind.shape[0]):
        fraction[b] = 1.0
        if shape[b, 0] != surface.POINT:
            fraction[b], _, _ = surface.submersion(pos[b, 2], shape[b])


@inner
def _tip_joints(y, kind, rs_n, rs_seg, rs_node, rs_q, rs_v, rs_to, joints, point_body, rot,
                omega, work, ref):  # fmt: skip
    """The joints at lines' ends (``rs_tip_joint``): each one's moment on its line's last
    segment and, between two lines, the opposite one on the next line's first segment
    (lines.tip_joint), after the lines' loads and before their sweeps."""
    for j in range(joints.shape[0]):
        li, nxt = int(joints[j, 0]), int(joints[j, 1])
        n, _, ws = rigid._view(rs_n, rs_seg, rs_node, work, li)
        planar = kind[li] == rigid.PLANAR
        if nxt >= 0:
            _, _, wn = rigid._view(rs_n, rs_seg, rs_node, work, nxt)
            tip_joint.add_between(planar, n, y, rs_q[li], rs_v[li], rs_q[nxt], rs_v[nxt],
                                  joints[j, 5], joints[j, 6], ws, wn)  # fmt: skip
            continue
        b = point_body[rs_to[li]]
        for c in range(3):
            ref[c] = (rot[b, c, 0] * joints[j, 2] + rot[b, c, 1] * joints[j, 3]
                      + rot[b, c, 2] * joints[j, 4])  # fmt: skip
        tip_joint.add_torque(planar, n, y, rs_q[li], rs_v[li], ref, omega[b], joints[j, 5],
                             joints[j, 6], ws)  # fmt: skip


def present(p: SystemParams) -> tuple[bool | None, ...]:
    """(lumped, planar, segments, natural, mesh): True where the system holds lumped-mass lines,
    planar rigid-link lines, 3D rigid-segment lines, natural strings, a hull mesh; None where it
    does not. Compiled functions that take them (the outputs, the energies) are compiled apart
    for each set of None and leave out the code of a kind that is None (numba prunes a branch
    on ``x is None`` for an argument before typing it)."""
    mesh = any(int(k) in kinds.MESH for k in p.force_kind)
    held = (len(p.line_n) > 0, bool(np.any(p.rs_kind == rigid.PLANAR)),
            bool(np.any(p.rs_kind == rigid.SEGMENTS_3D)), len(p.nat_n) > 0, mesh)  # fmt: skip
    return tuple(True if h else None for h in held)


# The entries of the evaluation compiled for a system's kinds (system.evaluation), whose
# addresses system.variants.bind writes into ``SystemParams.entries``; the trampolines below
# call them (kernels.indirect). Those with a Python entry (njit) serve Python callers; compiled
# callers call the inner ones, so that no Python entry's code is linked into them.
EVALUATE, BODY_FORCES, PROJECT, AFTER_STEP, START_MEMORY = range(5)
ENTRIES = ("evaluate", "body_forces", "project", "after_step", "start_memory")
# the evaluate entry's parts, each compiled apart and called by its address, which follows the
# entries' (``SystemParams.entries[len(ENTRIES) + k]``; 0 for a part a copy does not call)
PARTS = ("_motions", "_masses", "_lines", "_models", "_backward", "_solve")


@njit(inline="always", **JIT)
def _bound(entries):
    """Refuse parameters no compiled evaluation was bound to (an address 0 would crash)."""
    if entries[EVALUATE] == 0:
        raise RuntimeError("seacable: system parameters not bound to a compiled evaluation "
                           "(system.variants.bind)")  # fmt: skip


@njit(inline="always", **JIT)
def evaluate(t, y, p, w, ydot):
    """Fill the workspace and ``ydot``; returns a status (kernels.status codes): the
    evaluation compiled for the kinds this system holds (``system.evaluation``), called through
    its address so that no caller compiles it in (kernels.indirect). For compiled callers;
    Python calls ``rhs``. Inlined: the call that passes the tuples is the evaluation's alone."""
    _bound(p.entries)
    return indirect.call5(p.entries[EVALUATE], t, y, p, w, ydot)


@njit(**JIT)
def _from_python(entry, t, y, p, w, ydot):
    """Entry ``entry`` (``ENTRIES``) called from Python: one Python entry for all of them (its
    unboxing of the two tuples is most of its compilation, about 3 s)."""
    _bound(p.entries)
    at = p.entries[entry]
    if entry == EVALUATE:
        return indirect.call5(at, t, y, p, w, ydot)
    if entry == PROJECT:
        return indirect.call2(at, y, p)
    return indirect.call4(at, t, y, p, w)  # AFTER_STEP, START_MEMORY


def rhs(t: float, y: np.ndarray, p: SystemParams, w: SystemWork, ydot: np.ndarray) -> int:
    """``evaluate`` for Python callers."""
    return _from_python(EVALUATE, t, y, p, w, ydot)


@njit(inline="always", **JIT)
def body_forces(t, y, p, w, pos, vel, fraction, load):
    """Every force model's load into ``load`` (nb, 6), the bodies at ``pos`` moving at ``vel``
    and submerged by ``fraction`` (``system.evaluation.body_forces``, by its address)."""
    _bound(p.entries)
    indirect.call8(p.entries[BODY_FORCES], t, y, p, w, pos, vel, fraction, load)


@njit(inline="always", **JIT)
def projected(y, p):
    """The state projected (unit quaternions, directors and tangents), as ``accept`` does, for
    a state no step accepted (an output interpolated inside a step, ``numerics.dense``)."""
    _bound(p.entries)
    indirect.call2(p.entries[PROJECT], y, p)


@njit(inline="always", **JIT)
def accept(t, y, p, w):
    """An accepted step ending at (t, y): the state projected (unit quaternions, directors and
    tangents) and the radiation convolutions' histories recorded (``system.evaluation``'s
    ``project`` and ``after_step``). Every integrator calls it on each accepted step. Returns
    1 when a line's failure changed the system at (t, y) (system.failures: the derivatives an
    integrator kept from before are stale), else 0."""
    _bound(p.entries)
    indirect.call2(p.entries[PROJECT], y, p)
    return indirect.call4(p.entries[AFTER_STEP], t, y, p, w)


def project(y: np.ndarray, p: SystemParams, w: SystemWork) -> None:
    """The state projected (``system.evaluation.project``), for Python callers (``w``, a
    workspace of ``p``'s, is not used: the call's types are those of every entry's)."""
    _from_python(PROJECT, 0.0, y, p, w, y)


def after_step(t: float, y: np.ndarray, p: SystemParams, w: SystemWork) -> None:
    """The histories recorded after an accepted step (``system.evaluation.after_step``), for
    integrators driven from Python."""
    _from_python(AFTER_STEP, t, y, p, w, y)


def start_memory(t: float, y: np.ndarray, p: SystemParams, w: SystemWork) -> None:
    """The radiation convolutions' histories at the run's start
    (``system.evaluation.start_memory``)."""
    _from_python(START_MEMORY, t, y, p, w, y)


@njit(inline="always", **JIT)
def _key_holds(y, s0, pos, quat, vel, omega, key):
    """Whether ``key`` holds the bodies' and the models' states to the bit (plain loops and
    tests: slices' and short circuits' code compiles slowly)."""
    nb = pos.shape[0]
    for b in range(nb):
        o = 1 + 13 * b
        for c in range(3):
            if key[o + c] != pos[b, c] or key[o + 7 + c] != vel[b, c]:
                return False
            if key[o + 10 + c] != omega[b, c]:
                return False
        for c in range(4):
            if key[o + 3 + c] != quat[b, c]:
                return False
    for i in range(y.shape[0] - s0):
        if key[1 + 13 * nb + i] != y[s0 + i]:
            return False
    return True


@inner
def _models_kept(t, y, s0, reuse, pos, quat, vel, omega, key):
    """Whether the force models' loads of the last evaluation that computed them hold here:
    with ``reuse`` (Newton's matrix: kernels.lumped FROZEN), at the same time, bodies' states
    and models' states (``y[s0:]``) to the bit, as where a difference quotient moves only a
    line's nodes (a model reads nothing else that an evaluation changes; the radiation
    histories change between steps only, and after_step forgets the key). Otherwise records
    the key of the evaluation about to compute them and returns False."""
    nb = pos.shape[0]
    n = y.shape[0] - s0
    if reuse and key[0] == t and _key_holds(y, s0, pos, quat, vel, omega, key):
        return True
    key[0] = t
    for b in range(nb):
        o = 1 + 13 * b
        for c in range(3):
            key[o + c] = pos[b, c]
            key[o + 7 + c] = vel[b, c]
            key[o + 10 + c] = omega[b, c]
        for c in range(4):
            key[o + 3 + c] = quat[b, c]
    for i in range(n):
        key[1 + 13 * nb + i] = y[s0 + i]
    return False


@njit(inline="always", **JIT)
def _finite(ydot):
    total = 0.0
    for v in ydot:
        total += v
    return np.isfinite(total)


@inner
def _lumped_lines(y, line_n, line_seg, line_node, line_q, line_v, line_from, line_to, length,
                  stiffness, damping, slack_allowed, drag_normal, drag_tangential, wet_weight,
                  buoyancy, added_mass, bend, node_mass, seabed_stiffness, seabed_damping,
                  seabed_z, seabed_friction, seabed_slip_speed, seabed_band, current_z, current_u,
                  current_v, t, gravity, wave, wave_depth, wave_stretch, point_body, body_kind,
                  ppos, pvel, parm, omega, line, nodes, end_mass, end_load, body_mass, load,
                  ydot):  # fmt: skip
    """Every lumped-mass line: its loads (at time ``t`` [s], in the incident waves ``wave``),
    its interior nodes' rates into ``ydot``, its end nodes' mass and loads handed to their
    bodies (``body_mass`` = ``w.mass``). False when a rate is not finite. The arrays come one
    by one, as in ``_solve_bodies``."""
    ok = True
    for li in range(line_n.shape[0]):
        n, s0, c0 = line_n[li], line_seg[li], line_node[li]
        lumped_mass.gather(y, n, line_q[li], line_v[li], ppos, pvel, line_from[li], line_to[li],
                           line)  # fmt: skip
        lumped_mass.loads(
            line, n, s0, c0, length, stiffness, damping, slack_allowed, drag_normal,
            drag_tangential, wet_weight, buoyancy, added_mass, bend, seabed_stiffness,
            seabed_damping, seabed_z, seabed_friction, seabed_slip_speed, seabed_band, current_z,
            current_u, current_v, t, gravity, wave, wave_depth, wave_stretch, nodes,
        )  # fmt: skip
        ok = lumped_mass.interior_rates(line, n, line_q[li], line_v[li], c0, node_mass, nodes,
                                        ydot) and ok  # fmt: skip
        for end in range(2):
            point = line_from[li] if end == 0 else line_to[li]
            lumped_mass.end_mass_force(node_mass, nodes, c0 + end * n, end_mass[li, end],
                                       end_load[li, end])  # fmt: skip
            b = point_body[point]
            if kinematics.has_mass(body_kind[b]):
                dynamics.add_point_mass(end_mass[li, end], parm[point], omega[b],
                                        end_load[li, end], body_mass[b], load[b])  # fmt: skip
    return ok


@inner
def _solve_bodies(y, kind, free, body_q, body_v, rigid_body, group, load, bias, mass, acc, rhs,
                  ydot):  # fmt: skip
    """Each dynamic body's accelerations (but a group's: ``rigid.solve_groups``) and its rates into
    ``ydot``. The arrays come as arguments, not as fields of the parameter and work tuples: a
    field read inside the loop would take and drop a reference at each pass (four times
    slower, measured)."""
    ok = True
    for b in range(kind.shape[0]):
        if kind[b] != DYNAMIC or group[b, 0] >= 0:
            continue
        for i in range(6):
            rhs[i] = load[b, i] - bias[b, i]
        ok = dynamics.solve_free(mass[b], rhs, free[b], acc[b]) and ok
        dynamics.body_rates(y, body_q[b], body_v[b], rigid_body[b], acc[b], ydot)
    return ok


@njit(inline="always", **JIT)
def projects(p):
    """True when ``project`` changes the state: some dynamic body has an orientation, or some
    line has rigid segments in 3D."""
    for li in range(p.rs_n.shape[0]):
        if p.rs_kind[li] == rigid.SEGMENTS_3D:
            return True
    for li in range(p.nat_n.shape[0]):
        if p.nat_cartesian[li] == 1:
            return True
    for b in range(p.body_kind.shape[0]):
        if p.body_kind[b] == DYNAMIC and p.body_rigid[b] == 1:
            return True
    return False
