"""The rigid lines of a system in one evaluation (system.kernel calls these; compiled on their
own, not inlined: a third less compile time for the right-hand side, the same speed): their
nodes and loads, bases before the lines they carry; their backward sweeps, children first, each
giving its base body its articulated inertia and bias; after the bodies' solve, their forward
sweeps. Two models share the tree and the coupling: rigid segments in 3D (``rs_kind`` 0,
lines.rigid_segments: directors) and planar rigid links in x-z (1, lines.rigid_links: angles).
Derivation: docs/rigid_segment_lines.md."""

import math

import numpy as np
from numba import njit

from seacable.bodies import dynamics, kinematics
from seacable.kernels import chain3d as c3
from seacable.kernels import planar_chain as pc
from seacable.kernels.chain3d_loads import segment_loads
from seacable.kernels.jit import JIT, inner
from seacable.lines import rigid_links, rigid_segments

SEGMENTS_3D, PLANAR = 0, 1


@njit(inline="always", **JIT)
def point_acceleration(p, w, k, out):
    """Acceleration (3) of point k (``w.parm``, ``w.omega`` and, of a dynamic body, ``w.acc``
    filled): kinematics.point_acceleration."""
    b = p.point_body[k]
    kinematics.point_acceleration(p.body_kind[b], w.acc[b], w.parm[k], w.omega[b], out)


@njit(inline="always", **JIT)
def _view(rs_n, rs_seg, rs_node, work, li):
    """One rigid line's segment count, first segment and workspace: a C-contiguous block of
    (chain3d_layout.N_WORK_ROWS, n + 1) in the flat ``work`` (``w.rs``; contiguous rows keep
    the sweeps as fast as the single cable's)."""
    n, s0, c0 = rs_n[li], rs_seg[li], rs_node[li]
    rows = c3.N_WORK_ROWS
    return n, s0, work[rows * c0 : rows * (c0 + n + 1)].reshape((rows, n + 1))


@njit(inline="always", **JIT)
def workspace(p, w, li):
    """``_view``'s workspace of rigid line ``li`` (outputs, energies)."""
    return _view(p.rs_n, p.rs_seg, p.rs_node, w.rs, li)[2]


@njit(inline="always", **JIT)
def _held(kind, rs_held, li):
    """True when line ``li`` (of ``kind``) has its tip held on some axis."""
    if kind == PLANAR:
        return rs_held[li, 0] != 0.0 or rs_held[li, 2] != 0.0
    return rs_held[li, 0] != 0.0 or rs_held[li, 1] != 0.0 or rs_held[li, 2] != 0.0


@njit(inline="always", **JIT)
def planar_reference(rot, ref):
    """The angle [rad] of a planar line's first joint's unloaded direction: ``ref`` (3, base
    body frame) turned by the base's rotation ``rot`` (3x3), from the downward vertical,
    positive towards +x."""
    x = rot[0, 0] * ref[0] + rot[0, 1] * ref[1] + rot[0, 2] * ref[2]
    z = rot[2, 0] * ref[0] + rot[2, 1] * ref[1] + rot[2, 2] * ref[2]
    return math.atan2(x, -z)


@inner
def nodes_and_loads(y, order, kind, rs_n, rs_seg, rs_node, rs_q, rs_v, rs_from, rs_tip, rs_ref,
                    length, wet_weight, buoyancy, drag_normal, drag_tangential, added, inertia,
                    joint_stiffness, joint_damping, current_z, current_u, current_v, t, gravity,
                    wave, wave_depth, wave_stretch, point_body, point_offset, pos, rot, vel,
                    omega, ppos, pvel, parm, work, ref, planar, segments):  # fmt: skip
    """Every rigid line's nodes and loads, bases first; a carried body's position and velocity
    from its line's last node. The arrays of the parameter and work tuples (``rs_*``,
    ``point_*``, ``current_*``, the waves' (at time ``t``: 3D lines only), the bodies' and
    points' states, ``work`` = ``w.rs``; ``ref``: 3 floats of scratch) come one by one: a call
    that receives the tuples takes and drops a reference to each of their arrays
    (docs/architecture.md). ``planar`` and ``segments``: True, or None to leave the planar
    links' or the 3D segments' code out (numba compiles the function apart for a None argument
    and prunes the branches that test it before typing them: a system's evaluation
    compiles only the models it holds, system.evaluation)."""
    for j in range(order.shape[0] - 1, -1, -1):
        li = order[j]
        n, s0, ws = _view(rs_n, rs_seg, rs_node, work, li)
        e = s0 + n
        a = rs_from[li]
        kinematics.point_state(a, point_body, point_offset, pos, rot, vel, omega, ppos, pvel,
                               parm)  # fmt: skip
        base = point_body[a]
        for c in range(3):
            ref[c] = (rot[base, c, 0] * rs_ref[li, 0] + rot[base, c, 1] * rs_ref[li, 1]
                      + rot[base, c, 2] * rs_ref[li, 2])  # fmt: skip
        tip = rs_tip[li]
        if kind[li] == PLANAR:
            if planar is not None:
                _planar_nodes(n, s0, e, y, rs_q[li], rs_v[li], length, wet_weight, buoyancy,
                              drag_normal, drag_tangential, joint_stiffness, joint_damping,
                              rs_ref[li], current_z, current_u, a, base, tip, pos, rot, vel,
                              omega, ppos, pvel, ws)  # fmt: skip
            continue
        if segments is None:
            continue
        for c in range(3):
            ws[c3._P + c, 0] = ppos[a, c]
            ws[c3._V + c, 0] = pvel[a, c]
        segment_loads(
            n, y, rs_q[li], rs_v[li], length[s0:e], wet_weight[s0:e], buoyancy[s0:e],
            drag_normal[s0:e], drag_tangential[s0:e], added[s0:e], inertia[s0:e],
            joint_stiffness[s0:e], joint_damping[s0:e], ref, omega[base], current_z, current_u,
            current_v, t, gravity, wave, wave_depth, wave_stretch, ws,
        )  # fmt: skip
        if tip >= 0:
            for c in range(3):
                pos[tip, c] = ws[c3._P + c, n]
                vel[tip, c] = ws[c3._V + c, n]


@inner
def _planar_nodes(n, s0, e, y, q, v, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                  joint_stiffness, joint_damping, rs_ref, current_z, current_u, a, base, tip, pos,
                  rot, vel, omega, ppos, pvel, ws):  # fmt: skip
    """A planar line's nodes and loads (``nodes_and_loads``) from its base point ``a`` on body
    ``base``; its carried body ``tip`` (-1: none) placed at its last node."""
    ws[pc._PX, 0], ws[pc._PZ, 0] = ppos[a, 0], ppos[a, 2]
    ws[pc._VX, 0], ws[pc._VZ, 0] = pvel[a, 0], pvel[a, 2]
    # the reference turns with the base's pitch: d(angle)/dt = -omega_y
    pc.link_loads(
        n, y, q, v, length[s0:e], wet_weight[s0:e], buoyancy[s0:e], drag_normal[s0:e],
        drag_tangential[s0:e], joint_stiffness[s0:e], joint_damping[s0:e],
        planar_reference(rot[base], rs_ref), -omega[base, 1], current_z, current_u, ws,
    )  # fmt: skip
    if tip >= 0:
        pos[tip, 0], pos[tip, 1], pos[tip, 2] = ws[pc._PX, n], ppos[a, 1], ws[pc._PZ, n]
        vel[tip, 0], vel[tip, 1], vel[tip, 2] = ws[pc._VX, n], 0.0, ws[pc._VZ, n]


@njit(inline="always", **JIT)
def _tip_target(rs_tip, rs_to, body_pose, body_kind, point_body, point_offset, pos, rot, vel,
                omega, acc, ppos, pvel, parm, li, target, point_acc, zero):  # fmt: skip
    """Position, velocity and acceleration (``target``, 9) a held tip is held to: a carried
    body where it starts, or the point ``to`` of a fixed, imposed or free body (of a free one,
    the acceleration's part its twist gives, w x (w x r): ``zero`` is 6 zeros)."""
    tip = rs_tip[li]
    if tip >= 0:
        for c in range(3):
            target[c] = body_pose[tip, c]
            target[3 + c] = target[6 + c] = 0.0
        return
    k = rs_to[li]
    kinematics.point_state(k, point_body, point_offset, pos, rot, vel, omega, ppos, pvel, parm)
    b = point_body[k]
    free = body_kind[b] == kinematics.DYNAMIC  # a free body (a two-port): the known part alone
    kinematics.point_acceleration(body_kind[b], zero if free else acc[b], parm[k], omega[b],
                                  point_acc)  # fmt: skip
    for c in range(3):
        target[c] = ppos[k, c]
        target[3 + c] = pvel[k, c]
        target[6 + c] = point_acc[c]


@inner
def backward(order, kind, rs_n, rs_seg, rs_node, rs_v, rs_from, rs_to, rs_tip, rs_held, rs_port,
             length, mass, inertia, stabilization_frequency, point_body, point_offset, body_kind,
             body_pose, y, pos, rot, vel, omega, acc, ppos, pvel, parm, body_mass, bias, load,
             work, rs_force, rs_la, scratch, planar, segments):  # fmt: skip
    """Every rigid line's backward sweep, children first: a carried body's mass and loads start
    its line's sweep; a held tip's force is eliminated (the closures); the base body receives
    the line's articulated inertia ``m9`` and load. A line held on a free body (``rs_port``)
    keeps its tip's force L unknown: its base receives M_0 and -b_0 alone, and ``rs_la`` its
    maps for the bodies' joint solve (``solve_groups``). False when a closure is singular. The
    arrays of the parameter and work tuples come one by one (``work`` = ``w.rs``,
    ``body_mass`` = ``w.mass``; ``scratch``: 168 floats), as in ``nodes_and_loads`` (and
    ``planar``, ``segments``)."""
    sweep = scratch[0:60]
    m9, line_load = scratch[60:69], scratch[69:72]
    target, point_acc, zero = scratch[106:115], scratch[115:118], scratch[128:134]
    zero[:] = 0.0
    ok = True
    for j in range(order.shape[0]):
        li = order[j]
        n, s0, ws = _view(rs_n, rs_seg, rs_node, work, li)
        e = s0 + n
        pinned = _held(kind[li], rs_held, li)
        if pinned:
            _tip_target(rs_tip, rs_to, body_pose, body_kind, point_body, point_offset, pos, rot,
                        vel, omega, acc, ppos, pvel, parm, li, target, point_acc,
                        zero)  # fmt: skip
        port = rs_port[li] != 0
        sound = True
        if kind[li] == PLANAR:
            if planar is None:
                continue
            sound = _planar_backward(
                n, length[s0:e], mass[s0:e], inertia[s0:e], y, rs_v[li], ws, rs_tip[li],
                body_mass, bias, load, rs_held[li], pinned, target, stabilization_frequency, m9,
                line_load, rs_force[li], rs_la[li], port, rs_la[li], sweep,
            )  # fmt: skip
        elif segments is not None:
            sound = _segments_backward(
                n, length[s0:e], mass[s0:e], ws, rs_tip[li], body_mass, bias, load,
                rs_held[li], pinned, target, stabilization_frequency, m9, line_load,
                rs_force[li], rs_la[li], port, rs_la[li], sweep, scratch[72:90],
            )  # fmt: skip
        ok = ok and sound
        a = rs_from[li]
        base = point_body[a]
        if kinematics.has_mass(body_kind[base]):
            dynamics.add_point_mass(m9, parm[a], omega[base], line_load, body_mass[base],
                                    load[base])  # fmt: skip
    return ok


@njit(inline="always", **JIT)
def _held_rhs(held, target, tip, omega, ac, out):
    """On each held axis k, the tip's acceleration the closure asks for less the sweep's
    constant part: a*_k - 2 omega (v_n - v*)_k - omega^2 (p_n - p*)_k - ac_k (``target``: 9,
    ``tip``: node n's position and velocity, 6); 0 on a free axis."""
    for k in range(3):
        out[k] = 0.0
        if held[k] != 0.0:
            out[k] = (target[6 + k] - 2.0 * omega * (tip[3 + k] - target[3 + k])
                      - omega * omega * (tip[k] - target[k]) - ac[k])  # fmt: skip


@njit(inline="always", **JIT)
def _segments_backward(n, length, mass, ws, tip, body_mass, bias, load, held, pinned, target,
                       stabilization_frequency, m9, line_load, force, la_out, port, kkt, scratch,
                       closure_scratch):  # fmt: skip
    m, b, s = scratch[0:6], scratch[6:9], scratch[9:18]
    ac, ga, al, la = scratch[18:21], scratch[21:30], scratch[30:39], scratch[39:48]
    tipv, system, rhs3 = closure_scratch[0:6], closure_scratch[6:15], closure_scratch[15:18]
    m[:] = 0.0
    b[:] = 0.0
    s[:] = 0.0
    if tip >= 0:
        mt = body_mass[tip]
        m[0], m[3], m[5] = mt[0, 0], mt[1, 1], mt[2, 2]
        m[1], m[2], m[4] = mt[0, 1], mt[0, 2], mt[1, 2]
        for c in range(3):
            b[c] = bias[tip, c] - load[tip, c]
    if pinned:
        s[0] = s[4] = s[8] = 1.0
    rigid_segments.backward(n, length, mass, ws, m, b, s, pinned)
    m9[0], m9[1], m9[2] = m[0], m[1], m[2]
    m9[3], m9[4], m9[5] = m[1], m[3], m[4]
    m9[6], m9[7], m9[8] = m[2], m[4], m[5]
    for c in range(3):
        line_load[c] = -b[c]
    force[:] = 0.0
    ok = True
    if pinned:
        rigid_segments.tip_map(n, length, ws, ac, ga, al)
        for c in range(3):
            tipv[c] = ws[c3._P + c, n]
            tipv[3 + c] = ws[c3._V + c, n]
        if port:  # L stays an unknown of the bodies' solve
            _held_rhs(held, target, tipv, stabilization_frequency, ac, kkt[0:3])
            kkt[3:12] = ga
            kkt[12:21] = al
            kkt[21:30] = s
            return True
        ok = rigid_segments.closure(held, ac, ga, al, target, tipv, stabilization_frequency,
                                    force, la, system, rhs3)  # fmt: skip
        # lam_0 = (M_0 + S_0 la) A_0 + (b_0 + S_0 l0): s holds S_0
        for r in range(3):
            for c in range(3):
                m9[3 * r + c] += (s[3 * r] * la[c] + s[3 * r + 1] * la[3 + c]
                                  + s[3 * r + 2] * la[6 + c])  # fmt: skip
            line_load[r] -= (s[3 * r] * force[0] + s[3 * r + 1] * force[1]
                             + s[3 * r + 2] * force[2])  # fmt: skip
        for c in range(9):
            la_out[c] = la[c]
    return ok


@njit(inline="always", **JIT)
def _planar_backward(n, length, mass, inertia, y, v, ws, tip, body_mass, bias, load, held,
                     pinned, target, stabilization_frequency, m9, line_load, force, la_out, port,
                     kkt, scratch):  # fmt: skip
    st = scratch[0:9]
    ac, ga, al, l0, la = scratch[9:11], scratch[11:15], scratch[15:19], scratch[19:21], scratch[
        21:25]  # fmt: skip
    tipv = scratch[37:41]
    st[:] = 0.0
    if tip >= 0:
        mt = body_mass[tip]
        st[0], st[1], st[2] = mt[0, 0], mt[0, 2], mt[2, 2]
        st[3] = bias[tip, 0] - load[tip, 0]
        st[4] = bias[tip, 2] - load[tip, 2]
    if pinned:
        st[5] = st[8] = 1.0
    rigid_links.backward(n, length, mass, inertia, y, v, ws, st, pinned)
    m9[:] = 0.0
    m9[0], m9[2], m9[6], m9[8] = st[0], st[1], st[1], st[2]
    line_load[0], line_load[1], line_load[2] = -st[3], 0.0, -st[4]
    force[:] = 0.0
    ok = True
    if pinned:
        rigid_links.tip_map(n, length, y, v, ws, ac, ga, al)
        tipv[0], tipv[1] = ws[pc._PX, n], ws[pc._PZ, n]
        tipv[2], tipv[3] = ws[pc._VX, n], ws[pc._VZ, n]
        if port:  # as in 3D, the (x, z) maps in the plane's rows and columns of 3x3 ones
            tip6 = scratch[41:47]
            tip6[0], tip6[1], tip6[2] = tipv[0], target[1], tipv[1]
            tip6[3], tip6[4], tip6[5] = tipv[2], 0.0, tipv[3]
            flat = scratch[47:50]
            flat[0], flat[1], flat[2] = ac[0], 0.0, ac[1]
            _held_rhs(held, target, tip6, stabilization_frequency, flat, kkt[0:3])
            kkt[3:30] = 0.0
            for r in range(2):
                for c in range(2):
                    at = 3 * (2 * r) + 2 * c
                    kkt[3 + at] = ga[2 * r + c]
                    kkt[12 + at] = al[2 * r + c]
            kkt[21 + 0], kkt[21 + 2], kkt[21 + 6], kkt[21 + 8] = st[5], st[6], st[7], st[8]
            return True
        planar_target = (target[0], target[2], target[3], target[5], target[6], target[8])
        ok = rigid_links.closure(held[0], held[2], ac, ga, al, planar_target, tipv,
                                 stabilization_frequency, l0, la)  # fmt: skip
        # lam_0 = (M_0 + S_0 la) A_0 + (b_0 + S_0 l0) in (x, z): S_0 = (s11 s12; s21 s22)
        s11, s12, s21, s22 = st[5], st[6], st[7], st[8]
        m9[0] += s11 * la[0] + s12 * la[2]
        m9[2] += s11 * la[1] + s12 * la[3]
        m9[6] += s21 * la[0] + s22 * la[2]
        m9[8] += s21 * la[1] + s22 * la[3]
        line_load[0] -= s11 * l0[0] + s12 * l0[1]
        line_load[2] -= s21 * l0[0] + s22 * l0[1]
        force[0], force[2] = l0[0], l0[1]
        la_out[0], la_out[2] = la[0], la[1]
        la_out[6], la_out[8] = la[2], la[3]
    return ok


@inner
def solve_groups(y, kind, free, body_q, body_v, rigid_body, body_group, group_first,
                 group_member, joint, rs_from, rs_to, rs_held, point_body, acc, omega, parm,
                 ppos, pvel, frequency, rs_la, rs_force, load, bias, mass, big, scratch,
                 ydot):  # fmt: skip
    """The accelerations of each group of free bodies that rigid lines held on them or joints
    join, with those lines' holding forces L (the KKT form, docs/rigid_segment_lines.md section
    5): each body's 6x6 equations with L's action on it (+Phi_a^T S_0 L at its base point,
    -Phi_P^T L at the held point), each line's closure A_L L + G A_0 - a_P = r on its held axes
    (L_k = 0 on a free one; the maps in ``rs_la``, ``backward``), each joint's (``_joint_rows``),
    a held degree of freedom's row a_i = 0; Gaussian elimination with partial pivoting
    (``big``'s last two rows: right-hand side and solution). The rates into ``ydot``, L into
    ``rs_force`` (a joint's force on the body it pins to in its last rows: joint j at -1 - j).
    False when a group's system is singular."""
    ok = True
    unit, zero, a0 = scratch[143:152], scratch[152:158], scratch[158:161]
    a1 = scratch[161:164]
    unit[:] = 0.0
    unit[0] = unit[4] = unit[8] = 1.0
    zero[:] = 0.0
    m = big.shape[1]
    lines_at = group_first[group_first.shape[0] - 1, 0]  # the lines after every body
    for g in range(group_first.shape[0] - 1):
        first, bodies = group_first[g, 0], group_first[g + 1, 0] - group_first[g, 0]
        line0, lines = group_first[g, 1], group_first[g + 1, 1] - group_first[g, 1]
        size = 6 * bodies + 3 * lines
        a, rhs, out = big[:size, :size], big[m, :size], big[m + 1, :size]
        a[:, :] = 0.0
        for s in range(bodies):
            b = group_member[first + s]
            for i in range(6):
                rhs[6 * s + i] = load[b, i] - bias[b, i]
                for j in range(6):
                    a[6 * s + i, 6 * s + j] = mass[b, i, j]
        for j in range(lines):
            li = group_member[lines_at + line0 + j]
            if li < 0:
                _joint_rows(joint[-1 - li], 6 * bodies + 3 * j, kind, body_group, point_body,
                            acc, omega, parm, ppos, pvel, frequency, a, rhs, unit, zero, a0,
                            a1)  # fmt: skip
                continue
            _line_rows(li, 6 * bodies + 3 * j, kind, body_group, rs_from, rs_to, rs_held,
                       point_body, acc, omega, parm, rs_la[li], a, rhs, unit, zero,
                       a0)  # fmt: skip
        for s in range(bodies):
            b = group_member[first + s]
            for i in range(6):
                if free[b, i] == 0.0:
                    a[6 * s + i, :] = 0.0
                    a[6 * s + i, 6 * s + i] = 1.0
                    rhs[6 * s + i] = 0.0
        ok = dynamics.gauss(a, rhs, out) and ok
        for s in range(bodies):
            b = group_member[first + s]
            acc[b, :] = out[6 * s : 6 * s + 6]
            dynamics.body_rates(y, body_q[b], body_v[b], rigid_body[b], acc[b], ydot)
        for j in range(lines):
            li = group_member[lines_at + line0 + j]
            at = li if li >= 0 else rs_force.shape[0] + li  # a joint's after the lines'
            for r in range(3):
                rs_force[at, r] = out[6 * bodies + 3 * j + r]
    return ok


@njit(inline="always", **JIT)
def _joint_rows(points, col, kind, body_group, point_body, acc, omega, parm, ppos, pvel,
                frequency, a, rhs, unit, zero, a0, a1):  # fmt: skip
    """A joint's part of its group's system (``solve_groups``): its force L, on the other body
    at its point ``points[1]`` (that body's rows when it is free; -Phi^T L in the matrix, as a
    held line's) and -L on the pinned body at ``points[0]``, and its closure: the two points'
    accelerations equal,
    Phi_c a_c - Phi_p a_p = w_p x (w_p x r_p) - w_c x (w_c x r_c) (all of the other point's
    acceleration on a fixed or imposed body) - 2 f (v_c - v_p) - f^2 (x_c - x_p), the last
    terms (Baumgarte's, ``frequency`` f) holding the points together against the
    integration's drift. The matrix stays symmetric."""
    pc, pp = points[0], points[1]
    child, other = point_body[pc], point_body[pp]
    free_other = kind[other] == kinematics.DYNAMIC
    kinematics.point_acceleration(kind[other], zero if free_other else acc[other], parm[pp],
                                  omega[other], a0)  # fmt: skip
    kinematics.point_acceleration(kinematics.DYNAMIC, zero, parm[pc], omega[child], a1)
    sc = 6 * body_group[child, 1]
    dynamics.add_phi_t(unit, parm[pc], 1.0, a[sc : sc + 6, col : col + 3])
    dynamics.add_m_phi(unit, parm[pc], 1.0, a[col : col + 3, sc : sc + 6])
    if free_other:
        so = 6 * body_group[other, 1]
        dynamics.add_phi_t(unit, parm[pp], -1.0, a[so : so + 6, col : col + 3])
        dynamics.add_m_phi(unit, parm[pp], -1.0, a[col : col + 3, so : so + 6])
    for r in range(3):
        rhs[col + r] = (a0[r] - a1[r] - 2.0 * frequency * (pvel[pc, r] - pvel[pp, r])
                        - frequency * frequency * (ppos[pc, r] - ppos[pp, r]))  # fmt: skip


@njit(inline="always", **JIT)
def _line_rows(li, col, kind, body_group, rs_from, rs_to, rs_held, point_body, acc, omega, parm,
               kkt, a, rhs, unit, zero, a0):  # fmt: skip
    """Line li's part of its group's system (``solve_groups``): its holding force's columns
    from ``col`` in its bodies' rows, its closure's rows."""
    base, end = point_body[rs_from[li]], point_body[rs_to[li]]
    arm_a, arm_p = parm[rs_from[li]], parm[rs_to[li]]
    free_base = kind[base] == kinematics.DYNAMIC
    # the base point's acceleration's known part: all of it on a fixed or imposed base
    kinematics.point_acceleration(kind[base], zero if free_base else acc[base], arm_a,
                                  omega[base], a0)  # fmt: skip
    sp = 6 * body_group[end, 1]
    dynamics.add_phi_t(unit, arm_p, -1.0, a[sp : sp + 6, col : col + 3])
    dynamics.add_m_phi(unit, arm_p, -1.0, a[col : col + 3, sp : sp + 6])
    if free_base:
        sa = 6 * body_group[base, 1]
        dynamics.add_phi_t(kkt[21:30], arm_a, 1.0, a[sa : sa + 6, col : col + 3])
        dynamics.add_m_phi(kkt[3:12], arm_a, 1.0, a[col : col + 3, sa : sa + 6])
    for r in range(3):
        for c in range(3):
            a[col + r, col + c] += kkt[12 + 3 * r + c]
        rhs[col + r] = kkt[r] - (kkt[3 + 3 * r] * a0[0] + kkt[4 + 3 * r] * a0[1]
                                 + kkt[5 + 3 * r] * a0[2])  # fmt: skip
        if rs_held[li, r] == 0.0:  # a free axis: L_r = 0
            a[col + r, :] = 0.0
            a[col + r, col + r] = 1.0
            rhs[col + r] = 0.0


@inner
def forward(order, kind, rs_n, rs_seg, rs_node, rs_q, rs_v, rs_from, rs_tip, rs_held, rs_port,
            length, point_body, body_kind, y, omega, acc, parm, work, rs_force, rs_la, scratch,
            ydot, planar, segments):  # fmt: skip
    """Every rigid line's forward sweep, bases first: node 0's acceleration from its body's,
    the holding force from it, the segments' accelerations; a carried body's acceleration is
    its line's last node's. The arrays come one by one, as in ``nodes_and_loads`` (and
    ``planar``, ``segments``)."""
    a0, held_force = scratch[100:103], scratch[103:106]
    for j in range(order.shape[0] - 1, -1, -1):
        li = order[j]
        n, s0, ws = _view(rs_n, rs_seg, rs_node, work, li)
        a = rs_from[li]
        base = point_body[a]
        kinematics.point_acceleration(body_kind[base], acc[base], parm[a], omega[base], a0)
        pinned = _held(kind[li], rs_held, li)
        la = rs_la[li]
        for r in range(3):  # held on a free body: L solved with the bodies (rs_force)
            held_force[r] = rs_force[li, r]
            if pinned and rs_port[li] == 0:
                held_force[r] += la[3 * r] * a0[0] + la[3 * r + 1] * a0[1] + la[3 * r + 2] * a0[2]
            rs_force[li, r] = held_force[r]
        tip = rs_tip[li]
        if kind[li] == PLANAR:
            if planar is None:
                continue
            rigid_links.forward(n, length[s0 : s0 + n], ws, a0[0], a0[2], held_force[0],
                                held_force[2], pinned, y, rs_q[li], rs_v[li], ydot)  # fmt: skip
            if tip >= 0:
                acc[tip, 0], acc[tip, 1], acc[tip, 2] = ws[pc._AX, n], 0.0, ws[pc._AZ, n]
        elif segments is not None:
            rigid_segments.forward(n, length[s0 : s0 + n], ws, a0, held_force, pinned, y,
                                   rs_q[li], rs_v[li], ydot)  # fmt: skip
            if tip >= 0:
                for c in range(3):
                    acc[tip, c] = ws[c3._A + c, n]
        if tip >= 0:
            acc[tip, 3] = acc[tip, 4] = acc[tip, 5] = 0.0


@njit(**JIT)
def moments(p, w, use, out, march):
    """After ``rhs`` at rest: every rigid line's balance (the moment balances of
    lines.rigid_segments and lines.rigid_links) into ``out`` (per segment 2 in 3D, 1 planar,
    line after line), for the lines with ``use[li]`` (trees whose tips all hang free), children
    first: a carried body's force is its own loads and the pull of the lines it carries. With
    ``march``: instead, each segment turned along the pull it carries, its director (3) or angle
    (1) into ``out``."""
    lam = np.empty(3)
    pull = np.zeros((p.body_kind.shape[0], 3))
    at = np.empty(p.rs_n.shape[0], dtype=np.int64)
    total = 0
    for li in range(p.rs_n.shape[0]):
        at[li] = total
        per = 1 if p.rs_kind[li] == PLANAR else (3 if march else 2)
        total += per * p.rs_n[li]
    for j in range(p.rs_order.shape[0]):
        li = p.rs_order[j]
        if not use[li]:
            continue
        n, s0, ws = _view(p.rs_n, p.rs_seg, p.rs_node, w.rs, li)
        tip = p.rs_tip[li]
        for c in range(3):
            lam[c] = -(w.own_load[tip, c] + pull[tip, c])
        first = at[li]
        if p.rs_kind[li] == PLANAR:
            flat = np.array([lam[0], lam[2]])
            if march:
                rigid_links.march(n, ws, flat, out[first : first + n])
            else:
                rigid_links.moment_balance(n, p.rs_length[s0 : s0 + n], ws, flat,
                                           out[first : first + n])  # fmt: skip
            lam[0], lam[1], lam[2] = flat[0], 0.0, flat[1]
        elif march:
            rigid_segments.march(n, ws, lam, out[first : first + 3 * n])
        else:
            rigid_segments.moment_balance(n, p.rs_length[s0 : s0 + n], ws, lam,
                                          out[first : first + 2 * n])  # fmt: skip
        base = p.point_body[p.rs_from[li]]
        for c in range(3):
            pull[base, c] -= lam[c]
