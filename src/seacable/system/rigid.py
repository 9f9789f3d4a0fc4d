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
from seacable.kernels.timefn import JIT
from seacable.lines import rigid_links, rigid_segments

SEGMENTS_3D, PLANAR = 0, 1


@njit(inline="always", **JIT)
def _tf(p):
    return (p.tf_breaks, p.tf_coefs, p.tf_count, p.tf_sine, p.tf_build_up)


@njit(inline="always", **JIT)
def point_acceleration(p, w, k, out):
    """Acceleration (3) of point k (``w.parm``, ``w.omega`` and, of a dynamic body, ``w.acc``
    filled): kinematics.point_acceleration."""
    b = p.point_body[k]
    kinematics.point_acceleration(p.body_kind[b], w.acc[b], w.parm[k], w.omega[b], out)


@njit(inline="always", **JIT)
def _view(p, w, li):
    """One rigid line's segment count, first segment and workspace: a C-contiguous block of
    (chain3d_layout.N_WORK_ROWS, n + 1) in the flat ``w.rs`` (contiguous rows keep the sweeps
    as fast as the single cable's)."""
    n, s0, c0 = p.rs_n[li], p.rs_seg[li], p.rs_node[li]
    rows = c3.N_WORK_ROWS
    return n, s0, w.rs[rows * c0 : rows * (c0 + n + 1)].reshape((rows, n + 1))


@njit(**JIT)
def workspace(p, w, li):
    """``_view``'s workspace of rigid line ``li`` (outputs, energies)."""
    return _view(p, w, li)[2]


@njit(inline="always", **JIT)
def _held(p, li):
    h = p.rs_held[li]
    if p.rs_kind[li] == PLANAR:
        return h[0] != 0.0 or h[2] != 0.0
    return h[0] != 0.0 or h[1] != 0.0 or h[2] != 0.0


@njit(**JIT)
def nodes_and_loads(y, p, w):
    """Every rigid line's nodes and loads, bases first; a carried body's position and velocity
    from its line's last node."""
    ref = w.scratch[120:123]
    for j in range(p.rs_order.shape[0] - 1, -1, -1):
        li = p.rs_order[j]
        n, s0, ws = _view(p, w, li)
        e = s0 + n
        a = p.rs_from[li]
        kinematics.point_state(a, p.point_body, p.point_offset, w.pos, w.rot, w.vel, w.omega,
                               w.ppos, w.pvel, w.parm)  # fmt: skip
        base = p.point_body[a]
        for c in range(3):
            ref[c] = (w.rot[base, c, 0] * p.rs_ref[li, 0] + w.rot[base, c, 1] * p.rs_ref[li, 1]
                      + w.rot[base, c, 2] * p.rs_ref[li, 2])  # fmt: skip
        tip = p.rs_tip[li]
        if p.rs_kind[li] == PLANAR:
            ws[pc._PX, 0], ws[pc._PZ, 0] = w.ppos[a, 0], w.ppos[a, 2]
            ws[pc._VX, 0], ws[pc._VZ, 0] = w.pvel[a, 0], w.pvel[a, 2]
            # the reference turns with the base's pitch: d(angle)/dt = -omega_y
            pc.link_loads(
                n, y, p.rs_q[li], p.rs_v[li], p.rs_length[s0:e], p.rs_wet_weight[s0:e],
                p.rs_buoyancy[s0:e], p.rs_drag_normal[s0:e], p.rs_drag_tangential[s0:e],
                p.rs_joint_stiffness[s0:e], p.rs_joint_damping[s0:e],
                math.atan2(ref[0], -ref[2]), -w.omega[base, 1], p.current_z, p.current_u, ws,
            )  # fmt: skip
            if tip >= 0:
                w.pos[tip, 0], w.pos[tip, 1], w.pos[tip, 2] = ws[pc._PX, n], w.ppos[a, 1], ws[
                    pc._PZ, n]  # fmt: skip
                w.vel[tip, 0], w.vel[tip, 1], w.vel[tip, 2] = ws[pc._VX, n], 0.0, ws[pc._VZ, n]
            continue
        for c in range(3):
            ws[c3._P + c, 0] = w.ppos[a, c]
            ws[c3._V + c, 0] = w.pvel[a, c]
        segment_loads(
            n, y, p.rs_q[li], p.rs_v[li], p.rs_length[s0:e], p.rs_wet_weight[s0:e],
            p.rs_buoyancy[s0:e], p.rs_drag_normal[s0:e], p.rs_drag_tangential[s0:e],
            p.rs_added[s0:e], p.rs_inertia[s0:e], p.rs_joint_stiffness[s0:e],
            p.rs_joint_damping[s0:e], ref, w.omega[base], p.current_z, p.current_u,
            p.current_v, ws,
        )  # fmt: skip
        if tip >= 0:
            for c in range(3):
                w.pos[tip, c] = ws[c3._P + c, n]
                w.vel[tip, c] = ws[c3._V + c, n]


@njit(inline="always", **JIT)
def _tip_target(t, p, w, li, target, acc):
    """Position, velocity and acceleration (``target``, 9) a held tip is held to: a carried
    body where it starts, or the point ``to`` of a fixed or imposed body."""
    tip = p.rs_tip[li]
    if tip >= 0:
        for c in range(3):
            target[c] = p.body_pose[tip, c]
            target[3 + c] = target[6 + c] = 0.0
        return
    k = p.rs_to[li]
    kinematics.point_state(k, p.point_body, p.point_offset, w.pos, w.rot, w.vel, w.omega,
                           w.ppos, w.pvel, w.parm)  # fmt: skip
    point_acceleration(p, w, k, acc)
    for c in range(3):
        target[c] = w.ppos[k, c]
        target[3 + c] = w.pvel[k, c]
        target[6 + c] = acc[c]


@njit(**JIT)
def backward(t, y, p, w):
    """Every rigid line's backward sweep, children first: a carried body's mass and loads start
    its line's sweep; a held tip's force is eliminated (the closures); the base body receives
    the line's articulated inertia ``m9`` and load. False when a closure is singular."""
    scratch = w.scratch[0:60]
    m9, load = w.scratch[60:69], w.scratch[69:72]
    ok = True
    for j in range(p.rs_order.shape[0]):
        li = p.rs_order[j]
        if p.rs_kind[li] == PLANAR:
            sound = _planar_backward(t, y, p, w, li, m9, load, scratch)
        else:
            sound = _segments_backward(t, p, w, li, m9, load, scratch)
        ok = ok and sound
        base = p.point_body[p.rs_from[li]]
        if kinematics.has_mass(p.body_kind[base]):
            dynamics.add_point_mass(m9, w.parm[p.rs_from[li]], w.omega[base], load,
                                    w.mass[base], w.load[base])  # fmt: skip
    return ok


@njit(inline="always", **JIT)
def _segments_backward(t, p, w, li, m9, load, scratch):
    n, s0, ws = _view(p, w, li)
    m, b, s = scratch[0:6], scratch[6:9], scratch[9:18]
    ac, ga, al, la = scratch[18:21], scratch[21:30], scratch[30:39], scratch[39:48]
    target, tipv, system = scratch[48:57], w.scratch[72:78], w.scratch[78:87]
    rhs3, acc = w.scratch[87:90], w.scratch[90:93]
    tip = p.rs_tip[li]
    held = p.rs_held[li]
    pinned = _held(p, li)
    m[:] = 0.0
    b[:] = 0.0
    s[:] = 0.0
    if tip >= 0:
        mt = w.mass[tip]
        m[0], m[3], m[5] = mt[0, 0], mt[1, 1], mt[2, 2]
        m[1], m[2], m[4] = mt[0, 1], mt[0, 2], mt[1, 2]
        for c in range(3):
            b[c] = w.bias[tip, c] - w.load[tip, c]
    if pinned:
        s[0] = s[4] = s[8] = 1.0
    rigid_segments.backward(n, p.rs_length[s0 : s0 + n], p.rs_mass[s0 : s0 + n], ws, m, b, s,
                            pinned)  # fmt: skip
    m9[0], m9[1], m9[2] = m[0], m[1], m[2]
    m9[3], m9[4], m9[5] = m[1], m[3], m[4]
    m9[6], m9[7], m9[8] = m[2], m[4], m[5]
    for c in range(3):
        load[c] = -b[c]
    force = w.rs_force[li]
    force[:] = 0.0
    ok = True
    if pinned:
        rigid_segments.tip_map(n, p.rs_length[s0 : s0 + n], ws, ac, ga, al)
        _tip_target(t, p, w, li, target, acc)
        for c in range(3):
            tipv[c] = ws[c3._P + c, n]
            tipv[3 + c] = ws[c3._V + c, n]
        ok = rigid_segments.closure(held, ac, ga, al, target, tipv, p.stabilization_frequency,
                                    force, la, system, rhs3)  # fmt: skip
        # lam_0 = (M_0 + S_0 la) A_0 + (b_0 + S_0 l0): s holds S_0
        for r in range(3):
            for c in range(3):
                m9[3 * r + c] += (s[3 * r] * la[c] + s[3 * r + 1] * la[3 + c]
                                  + s[3 * r + 2] * la[6 + c])  # fmt: skip
            load[r] -= s[3 * r] * force[0] + s[3 * r + 1] * force[1] + s[3 * r + 2] * force[2]
        for c in range(9):
            w.rs_la[li, c] = la[c]
    return ok


@njit(inline="always", **JIT)
def _planar_backward(t, y, p, w, li, m9, load, scratch):
    n, s0, ws = _view(p, w, li)
    st = scratch[0:9]
    ac, ga, al, l0, la = scratch[9:11], scratch[11:15], scratch[15:19], scratch[19:21], scratch[
        21:25]  # fmt: skip
    target, acc = scratch[25:34], scratch[34:37]
    tipv = scratch[37:41]
    tip = p.rs_tip[li]
    held = p.rs_held[li]
    pinned = _held(p, li)
    st[:] = 0.0
    if tip >= 0:
        mt = w.mass[tip]
        st[0], st[1], st[2] = mt[0, 0], mt[0, 2], mt[2, 2]
        st[3] = w.bias[tip, 0] - w.load[tip, 0]
        st[4] = w.bias[tip, 2] - w.load[tip, 2]
    if pinned:
        st[5] = st[8] = 1.0
    e = s0 + n
    rigid_links.backward(n, p.rs_length[s0:e], p.rs_mass[s0:e], p.rs_inertia[s0:e], y,
                         p.rs_v[li], ws, st, pinned)  # fmt: skip
    m9[:] = 0.0
    m9[0], m9[2], m9[6], m9[8] = st[0], st[1], st[1], st[2]
    load[0], load[1], load[2] = -st[3], 0.0, -st[4]
    force = w.rs_force[li]
    force[:] = 0.0
    ok = True
    if pinned:
        rigid_links.tip_map(n, p.rs_length[s0:e], y, p.rs_v[li], ws, ac, ga, al)
        _tip_target(t, p, w, li, target, acc)
        tipv[0], tipv[1] = ws[pc._PX, n], ws[pc._PZ, n]
        tipv[2], tipv[3] = ws[pc._VX, n], ws[pc._VZ, n]
        planar_target = (target[0], target[2], target[3], target[5], target[6], target[8])
        ok = rigid_links.closure(held[0], held[2], ac, ga, al, planar_target, tipv,
                                 p.stabilization_frequency, l0, la)  # fmt: skip
        # lam_0 = (M_0 + S_0 la) A_0 + (b_0 + S_0 l0) in (x, z): S_0 = (s11 s12; s21 s22)
        s11, s12, s21, s22 = st[5], st[6], st[7], st[8]
        m9[0] += s11 * la[0] + s12 * la[2]
        m9[2] += s11 * la[1] + s12 * la[3]
        m9[6] += s21 * la[0] + s22 * la[2]
        m9[8] += s21 * la[1] + s22 * la[3]
        load[0] -= s11 * l0[0] + s12 * l0[1]
        load[2] -= s21 * l0[0] + s22 * l0[1]
        force[0], force[2] = l0[0], l0[1]
        w.rs_la[li, 0], w.rs_la[li, 2] = la[0], la[1]
        w.rs_la[li, 6], w.rs_la[li, 8] = la[2], la[3]
    return ok


@njit(**JIT)
def forward(t, y, p, w, ydot):
    """Every rigid line's forward sweep, bases first: node 0's acceleration from its body's,
    the holding force from it, the segments' accelerations; a carried body's acceleration is
    its line's last node's."""
    a0, held_force = w.scratch[100:103], w.scratch[103:106]
    for j in range(p.rs_order.shape[0] - 1, -1, -1):
        li = p.rs_order[j]
        n, s0, ws = _view(p, w, li)
        a = p.rs_from[li]
        point_acceleration(p, w, a, a0)
        pinned = _held(p, li)
        la = w.rs_la[li]
        for r in range(3):
            held_force[r] = w.rs_force[li, r]
            if pinned:
                held_force[r] += la[3 * r] * a0[0] + la[3 * r + 1] * a0[1] + la[3 * r + 2] * a0[2]
            w.rs_force[li, r] = held_force[r]
        tip = p.rs_tip[li]
        if p.rs_kind[li] == PLANAR:
            rigid_links.forward(n, p.rs_length[s0 : s0 + n], ws, a0[0], a0[2], held_force[0],
                                held_force[2], pinned, y, p.rs_q[li], p.rs_v[li], ydot)  # fmt: skip
            if tip >= 0:
                w.acc[tip, 0], w.acc[tip, 1], w.acc[tip, 2] = ws[pc._AX, n], 0.0, ws[pc._AZ, n]
        else:
            rigid_segments.forward(n, p.rs_length[s0 : s0 + n], ws, a0, held_force, pinned, y,
                                   p.rs_q[li], p.rs_v[li], ydot)  # fmt: skip
            if tip >= 0:
                for c in range(3):
                    w.acc[tip, c] = ws[c3._A + c, n]
        if tip >= 0:
            w.acc[tip, 3] = w.acc[tip, 4] = w.acc[tip, 5] = 0.0


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
        n, s0, ws = _view(p, w, li)
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
