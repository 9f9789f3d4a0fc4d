"""Derivatives by finite differences for the rigid lines' Newton rows in maximal coordinates
(``numerics.rigid_newton``, docs/rigid_newton.md, section 3): each planar link's loads by its top
node's position and velocity, its angle and rate and its joint neighbours' (from
``kernels.planar_chain.link_loads``, where they are written once), and a body's force models by
its position and velocity (``system.evaluation.body_forces``)."""

import numpy as np

from seacable.kernels import chain3d as c3
from seacable.kernels import planar_chain as pc
from seacable.kernels.chain3d_loads import segment_loads
from seacable.kernels.jit import inner
from seacable.lines import tip_joint
from seacable.system import kernel as system_kernel
from seacable.system import rigid

FD_STEP = 1.5e-8  # relative change of a position, velocity, angle or rate (difference quotients)
DERIVATIVES = 22  # rows of one line's loads derivatives (``loads_derivatives``)


@inner
def _call_loads(n, y, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u, ws,
                base, end, out):  # fmt: skip
    """The line's loads with node 0 at ``base`` (P, V in x, z) and its held end's joint
    (``end``: ``end_joint``) into ``out`` (3, n: F x, F z, Q) and its nodes' positions and
    velocities into ``ws``."""
    ws[pc._PX, 0], ws[pc._PZ, 0], ws[pc._VX, 0], ws[pc._VZ, 0] = base[0], base[1], base[2], base[3]
    pc.link_loads(n, y, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                  joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u,
                  ws)  # fmt: skip
    if end[0] != 0.0:
        tip_joint.add_torque(end[9] != 0.0, n, y, q0, v0, end[1:4], end[4:7], end[7], end[8], ws)
    for i in range(n):
        out[0, i], out[1, i], out[2, i] = ws[pc._FX, i], ws[pc._FZ, i], ws[pc._Q, i]


@inner
def loads_derivatives(n, y, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                       joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u,
                       end, ws, der):  # fmt: skip
    """Each link's loads (F, Q) differentiated, into ``der`` (22, n): by its top node's
    position (rows 0-3: dF_c/dP_e at 2c + e; 8-9: dQ/dP) and velocity (4-7, 10-11), by its
    angle and rate (12-13, 14-15: F; 16, 17: Q) and, for Q, by its neighbours' (18, 19: the
    link above; 20, 21: below). Forward differences: node 0 moved (the whole line translates),
    then every third link's angle or rate turned (the links below it translate: their share,
    from the first derivatives, is taken off). ``ws`` is the line's workspace after the
    residual's evaluation (node 0's state read, nothing written); ``end``: the held end's joint
    (``end_joint``)."""
    base = np.empty(4)
    for c in range(4):
        base[c] = ws[(pc._PX, pc._PZ, pc._VX, pc._VZ)[c], 0]
    work = np.empty_like(ws)
    y2 = y.copy()
    f0, f1 = np.empty((3, n)), np.empty((3, n))
    nodes = np.empty((4, n + 1))
    der[:, :] = 0.0
    _call_loads(n, y2, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u, work,
                base, end, f0)  # fmt: skip
    for k in range(n + 1):
        nodes[0, k], nodes[1, k] = work[pc._PX, k], work[pc._PZ, k]
        nodes[2, k], nodes[3, k] = work[pc._VX, k], work[pc._VZ, k]
    moved = base.copy()
    for c in range(4):  # node 0 (and so every node) moved along x, z, then its velocity
        eps = FD_STEP * max(1.0, abs(base[c]))
        moved[:] = base
        moved[c] += eps
        _call_loads(n, y2, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                    joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u,
                    work, moved, end, f1)  # fmt: skip
        row_f, row_q = (0, 8) if c < 2 else (4, 10)
        e = c % 2
        for i in range(n):
            der[row_f + e, i] = (f1[0, i] - f0[0, i]) / eps
            der[row_f + 2 + e, i] = (f1[1, i] - f0[1, i]) / eps
            der[row_q + e, i] = (f1[2, i] - f0[2, i]) / eps
    eps_of = np.empty(n)
    own = np.empty(3)
    for rate in range(2):  # angles, then rates
        at = v0 if rate else q0
        for colour in range(3):
            for j in range(colour, n, 3):
                eps_of[j] = FD_STEP * max(1.0, abs(y[at + j]))
                y2[at + j] = y[at + j] + eps_of[j]
            _call_loads(n, y2, q0, v0, length, wet_weight, buoyancy, drag_normal,
                        drag_tangential, joint_stiffness, joint_damping, ref_angle, ref_rate,
                        current_z, current_u, work, base, end, f1)  # fmt: skip
            for j in range(colour, n, 3):
                y2[at + j] = y[at + j]
            for i in range(n):
                dpx, dpz = work[pc._PX, i] - nodes[0, i], work[pc._PZ, i] - nodes[1, i]
                dvx, dvz = work[pc._VX, i] - nodes[2, i], work[pc._VZ, i] - nodes[3, i]
                for r in range(3):  # the change less the translation of the link's top node
                    rp = (0, 2, 8)[r]
                    rv = (4, 6, 10)[r]
                    own[r] = (f1[r, i] - f0[r, i] - der[rp, i] * dpx - der[rp + 1, i] * dpz
                              - der[rv, i] * dvx - der[rv + 1, i] * dvz)  # fmt: skip
                if i % 3 == colour:
                    der[12 + 2 * rate, i] = own[0] / eps_of[i]
                    der[13 + 2 * rate, i] = own[1] / eps_of[i]
                    der[16 + rate, i] = own[2] / eps_of[i]
                elif i >= 1 and (i - 1) % 3 == colour:
                    der[18 + rate, i] = own[2] / eps_of[i - 1]
                elif i + 1 < n and (i + 1) % 3 == colour:
                    der[20 + rate, i] = own[2] / eps_of[i + 1]


@inner
def end_joint(p, w, li):
    """The joint at line ``li``'s held end (``lines.tip_joint``), as the loads add it: (1.0,
    its unloaded direction (3, earth frame), the held body's angular velocity (3, rad/s),
    k [N m/rad], c [N m s/rad], 1.0 for a planar line), or zeros without one (a joint to a line
    that continues this one: its trees keep the dense block)."""
    out = np.zeros(10)
    out[9] = 1.0 if p.rs_kind[li] == rigid.PLANAR else 0.0
    joints = p.rs_tip_joint
    for j in range(joints.shape[0]):
        if int(joints[j, 0]) != li or joints[j, 1] >= 0:
            continue
        b = p.point_body[p.rs_to[li]]
        out[0] = 1.0
        for c in range(3):
            out[1 + c] = (w.rot[b, c, 0] * joints[j, 2] + w.rot[b, c, 1] * joints[j, 3]
                          + w.rot[b, c, 2] * joints[j, 4])  # fmt: skip
            out[4 + c] = w.omega[b, c]
        out[7], out[8] = joints[j, 5], joints[j, 6]
    return out


@inner
def point_derivatives(t, y, p, w, body, out):
    """d force / d position and d force / d velocity (3x3 each, row-major: out[3 c + e] and
    out[9 + 3 c + e]) of the force models of ``body`` (its submerged fraction followed), by
    forward differences; its state and the others' as ``w`` holds them."""
    pos, vel, fraction = w.pos.copy(), w.vel.copy(), w.fraction.copy()
    load0, load1 = np.zeros_like(w.load), np.zeros_like(w.load)
    for case in range(7):
        pos[:, :] = w.pos
        vel[:, :] = w.vel
        eps = 1.0
        axis = (case - 1) % 3
        if case > 0:
            target = pos if case <= 3 else vel
            eps = FD_STEP * max(1.0, abs(target[body, axis]))
            target[body, axis] += eps
        system_kernel._fractions(p.body_kind, p.body_shape, pos, fraction)
        load = load0 if case == 0 else load1
        load[:, :] = 0.0
        system_kernel.body_forces(t, y, p, w, pos, vel, fraction, load)
        if case > 0:
            first = 0 if case <= 3 else 9
            for c in range(3):
                out[first + 3 * c + axis] = (load1[body, c] - load0[body, c]) / eps


# one 3D line's loads derivatives (``segments_derivatives``), rows of ``der`` (., n): each
# segment's 8 outputs o (F (3), torque (3), normal added mass SA, rotational inertia SJ) by its
# 12 own inputs j (top node's P (3), V (3), its director e (3) and rate u (3)) at 12 o + j, then
# its torque's by the segment above's e, u (6) at ABOVE_3D + 6 (o - 3) + j and below's at
# BELOW_3D + 6 (o - 3) + j (the joints)
OUTPUTS_3D, INPUTS_3D = 8, 12
ABOVE_3D = OUTPUTS_3D * INPUTS_3D
BELOW_3D = ABOVE_3D + 18
DERIVATIVES_3D = BELOW_3D + 18


@inner
def _call_segments(t, p, li, y, ref, ref_omega, work, base, end, out):
    """Line ``li``'s segment loads (``kernels.chain3d_loads.segment_loads``, at time ``t``
    [s]) with node 0 at ``base`` (P, V) and its held end's joint (``end``: ``end_joint``) into
    ``out`` (8, n: F, torque, SA, SJ), its nodes into ``work``."""
    n, s0 = p.rs_n[li], p.rs_seg[li]
    e = s0 + n
    for c in range(3):
        work[c3._P + c, 0], work[c3._V + c, 0] = base[c], base[3 + c]
    segment_loads(
        n, y, p.rs_q[li], p.rs_v[li], p.rs_length[s0:e], p.rs_wet_weight[s0:e],
        p.rs_buoyancy[s0:e], p.rs_drag_normal[s0:e], p.rs_drag_tangential[s0:e],
        p.rs_added[s0:e], p.rs_inertia[s0:e], p.rs_joint_stiffness[s0:e],
        p.rs_joint_damping[s0:e], ref, ref_omega, p.current_z, p.current_u, p.current_v, t,
        p.gravity, p.wave, p.wave_depth, p.wave_stretch, work,
    )  # fmt: skip
    if end[0] != 0.0:
        tip_joint.add_torque(end[9] != 0.0, n, y, p.rs_q[li], p.rs_v[li], end[1:4], end[4:7],
                             end[7], end[8], work)  # fmt: skip
    for i in range(n):
        for c in range(3):
            out[c, i], out[3 + c, i] = work[c3._F + c, i], work[c3._TQ + c, i]
        out[6, i], out[7, i] = work[c3._SA, i], work[c3._SJ, i]


@inner
def segments_derivatives(t, p, li, y, ref, ref_omega, end, ws, der):
    """Each 3D segment's loads (F, torque, SA, SJ) differentiated into ``der``
    (DERIVATIVES_3D, n; layout above) at time ``t`` [s], as ``loads_derivatives`` does for
    planar links: node 0 moved (the whole line translates), then one component of every third
    segment's director or rate changed (the segments below it translate: their share is taken
    off). ``ref``, ``ref_omega``: the first joint's reference and its rate; ``end``: the held
    end's joint (``end_joint``); ``ws`` the line's workspace after the residual's evaluation
    (node 0's state read)."""
    n = p.rs_n[li]
    at = (p.rs_q[li], p.rs_v[li])
    base = np.empty(6)
    for c in range(3):
        base[c], base[3 + c] = ws[c3._P + c, 0], ws[c3._V + c, 0]
    work = np.empty_like(ws)
    y2 = y.copy()
    f0, f1 = np.empty((OUTPUTS_3D, n)), np.empty((OUTPUTS_3D, n))
    nodes = np.empty((6, n + 1))
    der[:, :] = 0.0
    _call_segments(t, p, li, y2, ref, ref_omega, work, base, end, f0)
    for k in range(n + 1):
        for c in range(3):
            nodes[c, k], nodes[3 + c, k] = work[c3._P + c, k], work[c3._V + c, k]
    moved = base.copy()
    for j in range(6):  # node 0 (and so every node) moved, then its velocity changed
        eps = FD_STEP * max(1.0, abs(base[j]))
        moved[:] = base
        moved[j] += eps
        _call_segments(t, p, li, y2, ref, ref_omega, work, moved, end, f1)
        for i in range(n):
            for o in range(OUTPUTS_3D):
                der[INPUTS_3D * o + j, i] = (f1[o, i] - f0[o, i]) / eps
    eps_of = np.empty(n)
    for rate in range(2):  # directors, then rates
        for comp in range(3):
            for colour in range(3):
                for s in range(colour, n, 3):
                    k = at[rate] + 3 * s + comp
                    eps_of[s] = FD_STEP * max(1.0, abs(y[k]))
                    y2[k] = y[k] + eps_of[s]
                _call_segments(t, p, li, y2, ref, ref_omega, work, base, end, f1)
                for s in range(colour, n, 3):
                    y2[at[rate] + 3 * s + comp] = y[at[rate] + 3 * s + comp]
                _attribute(n, colour, 6 + 3 * rate + comp, f0, f1, work, nodes, eps_of, der)


@inner
def _attribute(n, colour, col, f0, f1, work, nodes, eps_of, der):
    """``segments_derivatives``' share of one changed input (own column ``col``) of the
    segments of ``colour``: each segment's change ``f1 - f0`` less its top node's translation
    (``work``'s nodes against ``nodes``), by the segment's own input, or its joint neighbour's
    (the torque's)."""
    own = np.empty(OUTPUTS_3D)
    for i in range(n):
        for o in range(OUTPUTS_3D):
            total = f1[o, i] - f0[o, i]
            for c in range(6):
                row = c3._P + c if c < 3 else c3._V + c - 3
                total -= der[INPUTS_3D * o + c, i] * (work[row, i] - nodes[c, i])
            own[o] = total
        if i % 3 == colour:
            for o in range(OUTPUTS_3D):
                der[INPUTS_3D * o + col, i] = own[o] / eps_of[i]
        elif i >= 1 and (i - 1) % 3 == colour:
            for o in range(3):
                der[ABOVE_3D + 6 * o + col - 6, i] = own[3 + o] / eps_of[i - 1]
        elif i + 1 < n and (i + 1) % 3 == colour:
            for o in range(3):
                der[BELOW_3D + 6 * o + col - 6, i] = own[3 + o] / eps_of[i + 1]
