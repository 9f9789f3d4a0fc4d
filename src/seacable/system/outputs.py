"""Compiled outputs of a system at output times: every body's pose, twist and the force and
moment its lines and ties apply to it; every lumped line's nodes, tensions and end forces;
every tie's tension and length."""

import math
from typing import NamedTuple

import numpy as np
from numba import njit, typeof

from seacable.bodies.dynamics import add_force
from seacable.forces.compensator import RECORD
from seacable.kernels import chain3d as c3
from seacable.kernels import planar_chain as pc
from seacable.kernels.jit import JIT, inner
from seacable.kernels.status import OK
from seacable.lines import lumped_mass, natural_string, rigid_links, rigid_segments
from seacable.system import energy as system_energy
from seacable.system import kernel, rigid
from seacable.system.rigid import point_acceleration

BODY_COLUMNS = 18  # position 3, roll pitch yaw 3 [deg], velocity 3, omega 3, force 3, moment 3


@njit(**JIT)
def outputs_chunk(times, states, p, w, bodies, nodes, tension, ends, ties, energy, rigid,
                  control, lumped, planar, segments, natural, mesh):  # fmt: skip
    """Rows of every output time (bodies (m, nb, BODY_COLUMNS), nodes (m, total nodes, 3),
    tension (m, total segments), ends (m, nl, 2, 3): force of the line on its from / to
    point, ties (m, nt, 8): tension, length, from point, to point, energy (m, 3): kinetic,
    gravity potential, elastic (system.energy)); ``rigid`` the rigid lines' (nodes, tension,
    ends) alike; ``control`` (m, nc, compensator.RECORD) the compensators' (w.control).
    ``lumped``, ``planar``, ``segments``, ``natural``, ``mesh``: True, or None where the system
    holds no line of that model (no hull mesh): numba compiles the function apart for each set
    of None and prunes what they leave out before typing it (``kernel.present``)."""
    status = OK
    ydot = np.empty(states.shape[1])
    on_body = np.zeros((p.body_kind.shape[0], 6))
    for j in range(times.shape[0]):
        t, y = times[j], states[j]
        st = kernel.evaluate(t, y, p, w, ydot)
        if st != OK and status == OK:
            status = st
        for k in range(p.compensator.shape[0]):
            control[j, k, :] = w.control[k]
        on_body[:, :] = 0.0
        if lumped is not None:
            _lumped_rows(j, y, p, w, on_body, nodes, tension, ends)
        for k in range(p.tie_from.shape[0]):
            f = w.tie_force[k]
            a_, b_ = p.tie_from[k], p.tie_to[k]
            add_force(w.parm[a_], f[0], f[1], f[2], on_body[p.point_body[a_]])
            add_force(w.parm[b_], -f[0], -f[1], -f[2], on_body[p.point_body[b_]])
            ties[j, k, 0] = w.tie_tension[k]
            d = 0.0
            for c in range(3):
                d += (w.ppos[b_, c] - w.ppos[a_, c]) ** 2
            ties[j, k, 1] = math.sqrt(d)
            for c in range(3):
                ties[j, k, 2 + c] = w.ppos[a_, c]
                ties[j, k, 5 + c] = w.ppos[b_, c]
        _joint_loads(p, w, on_body)
        if planar is not None or segments is not None:
            _rigid_rows(p, w, on_body, rigid[0][j], rigid[1][j], rigid[2][j], rigid[3][j],
                        planar, segments)  # fmt: skip
        if natural is not None:
            _string_rows(y, p, w, rigid[4][j])
        _bodies(y, p, w, on_body, bodies[j])
        energy[j, 0], energy[j, 1], energy[j, 2] = system_energy.energies(
            y, p, w, lumped, planar, segments, natural, mesh
        )
    return status


@inner
def _joint_loads(p, w, on_body):
    """Each joint's force on its two bodies, at their points (``rigid.solve_groups``: the force
    on the body it pins to, in the last rows of ``w.rs_force``)."""
    last = w.rs_force.shape[0]
    for k in range(p.joint.shape[0]):
        f = w.rs_force[last - 1 - k]
        pc, pp = p.joint[k, 0], p.joint[k, 1]
        add_force(w.parm[pc], -f[0], -f[1], -f[2], on_body[p.point_body[pc]])
        add_force(w.parm[pp], f[0], f[1], f[2], on_body[p.point_body[pp]])


@inner
def _lumped_rows(j, y, p, w, on_body, nodes, tension, ends):
    """Row ``j`` of every lumped-mass line: its nodes, tensions and end forces, which it adds
    to ``on_body``."""
    a = np.empty(3)
    for li in range(p.line_n.shape[0]):
        n, c0, s0 = p.line_n[li], p.line_node[li], p.line_seg[li]
        lumped_mass.gather(y, n, p.line_q[li], p.line_v[li], w.ppos, w.pvel, p.line_from[li],
                           p.line_to[li], w.line)  # fmt: skip
        for k in range(n + 1):
            for c in range(3):
                nodes[j, c0 + k, c] = w.line[3 * k + c]
        for i in range(n):
            tension[j, s0 + i] = w.nodes[lumped_mass.T_ROW, c0 + i]
        for end in range(2):
            point = p.line_from[li] if end == 0 else p.line_to[li]
            point_acceleration(p, w, point, a)
            m3 = w.end_mass[li, end]
            for c in range(3):
                inertia = m3[3 * c] * a[0] + m3[3 * c + 1] * a[1] + m3[3 * c + 2] * a[2]
                ends[j, li, end, c] = w.end_load[li, end, c] - inertia
            f = ends[j, li, end]
            add_force(w.parm[point], f[0], f[1], f[2], on_body[p.point_body[point]])


@njit(inline="always", **JIT)
def _string_rows(y, p, w, out):
    """Every natural string's nodes (x, y, z), strain and tension, node after node."""
    at = 0
    for li in range(p.nat_n.shape[0]):
        n = p.nat_n[li]
        natural_string.own(y, p, w, li)
        k = p.nat_from[li]
        for i in range(n + 1):
            out[at + i, 0] = w.ppos[k, 0] + w.nat_out[i, 0]
            out[at + i, 1] = w.ppos[k, 1]
            out[at + i, 2] = w.ppos[k, 2] + w.nat_out[i, 1]
            out[at + i, 3] = w.nat_out[i, 2]
            out[at + i, 4] = w.nat_out[i, 3]
        at += n + 1


class Rows(NamedTuple):
    """Output rows of ``m`` times, as ``outputs_chunk`` fills them: bodies (m, nb,
    BODY_COLUMNS), lumped nodes (m, total nodes, 3), tensions (m, total segments), line ends
    (m, nl, 2, 3), ties (m, nt, 8), energies (m, 3), the rigid lines' and strings'
    (``rigid_rows``), the compensators' force and moment (m, nc, compensator.RECORD)."""

    bodies: np.ndarray
    nodes: np.ndarray
    tension: np.ndarray
    ends: np.ndarray
    ties: np.ndarray
    energy: np.ndarray
    rigid: tuple
    control: np.ndarray


def allocate(p, m: int) -> Rows:
    """Room for ``m`` output rows of a system of parameters ``p``."""
    nb, nl, nt = len(p.body_kind), len(p.line_n), len(p.tie_from)
    return Rows(
        np.empty((m, nb, BODY_COLUMNS)), np.empty((m, len(p.node_mass), 3)),
        np.empty((m, len(p.seg_length))), np.empty((m, nl, 2, 3)), np.empty((m, nt, 8)),
        np.empty((m, 3)), rigid_rows(p, m), np.empty((m, len(p.compensator), RECORD)),
    )  # fmt: skip


def fill(times, states, p, w, rows: Rows) -> int:
    """``rows`` filled at ``times`` and ``states``; the worst kernel status met."""
    return outputs_chunk(*_arguments(times, states, p, w, rows))


def signature(p, w) -> tuple:
    """The signature ``fill`` compiles ``outputs_chunk`` for (system.variants' jobs)."""
    states = np.empty((0, int(p.n_q + p.n_v + p.n_s)))
    return tuple(typeof(a) for a in _arguments(np.empty(0), states, p, w, allocate(p, 0)))


def _arguments(times, states, p, w, rows: Rows) -> tuple:
    return (times, states, p, w, *rows, *kernel.present(p))


def at(p, y: np.ndarray, time: float = 0.0, w=None) -> Rows:
    """The output row (m = 1) of one state ``y`` at ``time`` (``w``: the workspace to fill,
    default a new one)."""
    rows = allocate(p, 1)
    fill(np.full(1, time), y[None, :], p, kernel.make_work(p) if w is None else w, rows)
    return rows


def rigid_rows(p, m: int) -> tuple:
    """Arrays of ``m`` rows of the rigid lines' outputs (nodes, tensions, end forces, held
    ends' errors) and of the natural strings' (nodes, strain and tension: 5 per node)."""
    nodes = int((p.rs_n + 1).sum())
    strings = int((p.nat_n + 1).sum())
    return (np.empty((m, nodes, 3)), np.empty((m, int(p.rs_n.sum()))),
            np.empty((m, len(p.rs_n), 2, 3)), np.empty((m, len(p.rs_n))),
            np.empty((m, strings, 5)))  # fmt: skip


@inner
def _rigid_rows(p, w, on_body, nodes, tension, ends, error, planar, segments):
    """Every rigid line's nodes, axial forces at its segments' centres, forces on its ends and
    the distance of a held end from where it is held (on the held axes); ``planar``,
    ``segments``: as ``outputs_chunk``'s."""
    for li in range(p.rs_n.shape[0]):
        n, c0, s0 = p.rs_n[li], p.rs_node[li], p.rs_seg[li]
        ws = rigid.workspace(p, w, li)
        if p.rs_kind[li] == rigid.PLANAR:
            if planar is not None:
                _planar_line(p, w, li, ws, n, nodes[c0 : c0 + n + 1], tension[s0 : s0 + n],
                             ends[li])  # fmt: skip
        elif segments is not None:
            _segments_line(p, w, li, ws, n, nodes[c0 : c0 + n + 1], tension[s0 : s0 + n],
                           ends[li])  # fmt: skip
        tip = p.rs_tip[li]
        miss = 0.0
        for c in range(3):
            target = p.body_pose[tip, c] if tip >= 0 else w.ppos[p.rs_to[li], c]
            miss += p.rs_held[li, c] * (nodes[c0 + n, c] - target) ** 2
        error[li] = math.sqrt(miss)
        for end in range(2):
            point = p.rs_from[li] if end == 0 else p.rs_to[li]
            f = ends[li, end]
            add_force(w.parm[point], f[0], f[1], f[2], on_body[p.point_body[point]])


@njit(inline="always", **JIT)
def _planar_line(p, w, li, ws, n, nodes, tension, ends):
    """One planar rigid line's rows: nodes (n + 1, 3), tension (n), ends (2, 3)."""
    held = p.rs_held[li]
    force = w.rs_force[li]
    pinned = held[0] != 0.0 or held[2] != 0.0
    plane = w.ppos[p.rs_from[li], 1]
    for k in range(n + 1):
        nodes[k, 0], nodes[k, 1], nodes[k, 2] = ws[pc._PX, k], plane, ws[pc._PZ, k]
    ax, az = rigid_links.node_force(ws, np.int64(0), force[0], force[2], pinned)
    ends[0, 0], ends[0, 1], ends[0, 2] = -ax, 0.0, -az
    for i in range(n):
        bx, bz = rigid_links.node_force(ws, i + 1, force[0], force[2], pinned)
        ex, ez = ws[pc._EX, i], ws[pc._EZ, i]
        tension[i] = -0.5 * (ex * ax + ez * az + ex * bx + ez * bz)
        ax, az = bx, bz
    ends[1, 0], ends[1, 1], ends[1, 2] = ax, 0.0, az


@njit(inline="always", **JIT)
def _segments_line(p, w, li, ws, n, nodes, tension, ends):
    """One 3D rigid-segment line's rows: nodes (n + 1, 3), tension (n), ends (2, 3)."""
    held = p.rs_held[li]
    force = w.rs_force[li]
    pinned = held[0] != 0.0 or held[1] != 0.0 or held[2] != 0.0
    for k in range(n + 1):
        for c in range(3):
            nodes[k, c] = ws[c3._P + c, k]
    above = rigid_segments.node_force(ws, np.int64(0), force, pinned)
    for c in range(3):
        ends[0, c] = -above[c]
    for i in range(n):
        below = rigid_segments.node_force(ws, i + 1, force, pinned)
        e0, e1, e2 = ws[c3._E, i], ws[c3._E + 1, i], ws[c3._E + 2, i]
        t_top = -(e0 * above[0] + e1 * above[1] + e2 * above[2])
        t_bottom = -(e0 * below[0] + e1 * below[1] + e2 * below[2])
        tension[i] = 0.5 * (t_top + t_bottom)
        above = below
    for c in range(3):
        ends[1, c] = above[c]


@inner
def _bodies(y, p, w, on_body, out):
    for b in range(p.body_kind.shape[0]):
        rot = w.rot[b]
        # the rotation matrix's Euler angles (R = Rz Ry Rx)
        pitch = math.asin(max(-1.0, min(1.0, -rot[2, 0])))
        roll = math.atan2(rot[2, 1], rot[2, 2])
        yaw = math.atan2(rot[1, 0], rot[0, 0])
        for c in range(3):
            out[b, c] = w.pos[b, c]
            out[b, 6 + c] = w.vel[b, c]
            out[b, 9 + c] = w.omega[b, c]
            out[b, 12 + c] = on_body[b, c]
            out[b, 15 + c] = on_body[b, 3 + c]
        out[b, 3], out[b, 4], out[b, 5] = (
            math.degrees(roll), math.degrees(pitch), math.degrees(yaw),
        )  # fmt: skip
