"""Implicit steps of the 3D rigid-segment chain: its Newton system in maximal coordinates
(numba). See docs/architecture.md, "Rigid links in maximal coordinates"."""

import math

import numpy as np
from numba import njit

from seacable.kernels.chain3d import (
    _A,
    _BD,
    _BK,
    _BM,
    _E,
    _EDD,
    _P,
    _SA,
    _SF,
    _SJ,
    _TQ,
    _V,
    OK,
    TOP_HEAVE,
    _below_point_body,
    _current,
    _node_force,
    is_closed,
    solve,
)
from seacable.kernels.planar_newton import put_entry, top_rows
from seacable.kernels.timefn import JIT

# ---- implicit steps: the Newton system in maximal coordinates -----------------------------------
# As in ``planar_chain``: node k carries NEWTON_BLOCK unknowns [s_k (3), A_k (3), lam_k (3)], with
# s_k the director acceleration of the segment above node k (s_0: the heave acceleration in its
# first entry). Segment i gives three vector equations:
#   kinematics  A_{i+1} - A_i - l s = 0                                          (block i + 1)
#   rotation    J s + l/2 P (lam_i' + lam_{i+1}) - G + J |u|^2 e = 0             (block i + 1)
#   translation (m I + m_a P) C + m_b A_i - lam_i + lam_{i+1} - F - F_b = 0       (block i)
# with P = I - e e^T, C = (A_i + A_{i+1}) / 2, G = -e x (joint moments), lam_i' the force on the
# segment's top (lam_i less the share of a point body at node i) and m_b, F_b that body. The
# rotation equation holds both the normal part of the segment's angular momentum balance and,
# along e, the constraint e . s = -|u|^2 (scaled by J).
NEWTON_BLOCK = 9


@njit(**JIT)
def _put3(diag, upper, lower, rb, r0, cb, c0, m, scale):
    """Add ``scale`` times the 3x3 row-major ``m`` at rows r0.., columns c0.. of the blocks."""
    for r in range(3):
        for c in range(3):
            v = m[3 * r + c] * scale
            if v != 0.0:
                put_entry(diag, upper, lower, NEWTON_BLOCK, rb, r0 + r, cb, c0 + c, v)


@njit(**JIT)
def _put_identity(diag, upper, lower, rb, r0, cb, c0, value):
    for r in range(3):
        put_entry(diag, upper, lower, NEWTON_BLOCK, rb, r0 + r, cb, c0 + r, value)


@njit(**JIT)
def _joint_moment(ax, ay, az, bx, by, bz, uax, uay, uaz, ubx, uby, ubz, k, c):
    """Moment joint (a, b) exerts on segment a (minus it on b): the gradient of k phi^2 / 2 and
    a damper on the relative angular velocity (as ``chain3d_loads.joint_torques``). Scalars
    only: it is
    called 38 times per segment for each Newton matrix."""
    wax, way, waz = ay * uaz - az * uay, az * uax - ax * uaz, ax * uay - ay * uax
    wbx, wby, wbz = by * ubz - bz * uby, bz * ubx - bx * ubz, bx * uby - by * ubx
    cx, cy, cz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
    sin_phi = math.sqrt(cx * cx + cy * cy + cz * cz)
    phi = math.atan2(sin_phi, ax * bx + ay * by + az * bz)
    kf = k * (phi / sin_phi if sin_phi > 1e-12 else 1.0)
    return kf * cx + c * (wbx - wax), kf * cy + c * (wby - way), kf * cz + c * (wbz - waz)


@njit(**JIT)
def _director_force(x, ref, k_here, c_here, k_next, c_next, first, last, out):
    """G_i = -e_i x (moments on segment i) into ``out`` from the local directors and rates
    x = [e_{i-1}, e_i, e_{i+1}, u_{i-1}, u_i, u_{i+1}] (18)."""
    ex, ey, ez = x[3], x[4], x[5]
    ux, uy, uz = x[12], x[13], x[14]
    if first:  # the top joint: against the fixed reference direction
        tx, ty, tz = _joint_moment(
            ref[0], ref[1], ref[2], ex, ey, ez, 0.0, 0.0, 0.0, ux, uy, uz, k_here, c_here
        )
    else:
        tx, ty, tz = _joint_moment(
            x[0], x[1], x[2], ex, ey, ez, x[9], x[10], x[11], ux, uy, uz, k_here, c_here
        )
    mx, my, mz = -tx, -ty, -tz
    if not last:
        tx, ty, tz = _joint_moment(
            ex, ey, ez, x[6], x[7], x[8], ux, uy, uz, x[15], x[16], x[17], k_next, c_next
        )
        mx += tx
        my += ty
        mz += tz
    out[0] = -(ey * mz - ez * my)
    out[1] = -(ez * mx - ex * mz)
    out[2] = -(ex * my - ey * mx)


@njit(**JIT)
def _joint_rows(y, p, i, cx, cv, diag, upper, lower, x, g0):
    """-dG_i/d(e, u) of the three segments around segment i by forward differences (local:
    19 evaluations of two joint moments), into the rotation rows of block i + 1."""
    n = p.n
    u0 = 3 * n + 1
    k_here, c_here = p.joint_stiffness[i], p.joint_damping[i]
    last = i == n - 1
    k_next = 0.0 if last else p.joint_stiffness[i + 1]
    c_next = 0.0 if last else p.joint_damping[i + 1]
    if k_here == 0.0 and c_here == 0.0 and k_next == 0.0 and c_next == 0.0:
        return
    x[:] = 0.0
    for j in range(3):
        seg = i - 1 + j
        if 0 <= seg < n:
            for c in range(3):
                x[3 * j + c] = y[3 * seg + c]
                x[9 + 3 * j + c] = y[u0 + 3 * seg + c]
    _director_force(x, p.top_reference, k_here, c_here, k_next, c_next, i == 0, last, g0)
    g1 = g0[3:6]
    for j in range(3):
        seg = i - 1 + j
        if seg < 0 or seg >= n:
            continue
        for half in range(2):  # directors, then rates
            weight = cx if half == 0 else cv
            for c in range(3):
                idx = 9 * half + 3 * j + c
                keep = x[idx]
                step = 1e-7 * max(1.0, abs(keep))
                x[idx] = keep + step
                _director_force(
                    x, p.top_reference, k_here, c_here, k_next, c_next, i == 0, last, g1
                )
                x[idx] = keep
                for r in range(3):
                    d = -(g1[r] - g0[r]) / step * weight
                    if d != 0.0:
                        put_entry(diag, upper, lower, NEWTON_BLOCK, i + 1, 3 + r, seg + 1, c, d)


@njit(**JIT)
def _drag_jacobians(dn, dt, v, e, jv, je):
    """dF/dv (jv) and dF/de (je), 3x3 row-major, of F = -dn |v_n| v_n - dt |v_t| v_t e with
    v_t = v . e and v_n = v - v_t e."""
    vt = v[0] * e[0] + v[1] * e[1] + v[2] * e[2]
    vn = v - vt * e
    speed = math.sqrt(vn[0] * vn[0] + vn[1] * vn[1] + vn[2] * vn[2])
    q = np.empty(9)  # d(|vn| vn) / d vn = |vn| I + vn vn^T / |vn|
    for r in range(3):
        for c in range(3):
            q[3 * r + c] = (speed if r == c else 0.0) + (
                vn[r] * vn[c] / speed if speed > 0.0 else 0.0
            )
    for r in range(3):
        for c in range(3):
            delta = 1.0 if r == c else 0.0
            jv_rc = -2.0 * dt * abs(vt) * e[r] * e[c]
            je_rc = -dt * (2.0 * abs(vt) * e[r] * v[c] + abs(vt) * vt * delta)
            for k in range(3):
                dvn_dv = (1.0 if k == c else 0.0) - e[k] * e[c]
                dvn_de = -(e[k] * v[c] + (vt if k == c else 0.0))
                jv_rc -= dn * q[3 * r + k] * dvn_dv
                je_rc -= dn * q[3 * r + k] * dvn_de
            jv[3 * r + c] = jv_rc
            je[3 * r + c] = je_rc


@njit(**JIT)
def _segment_rows(t, y, p, w, i, lam_top, lam_bottom, cm, cx, cv, diag, upper, lower, m3, jv, je):
    """Kinematic and rotation rows (block i + 1) and translation rows (block i) of segment i."""
    n = p.n
    u0 = 3 * n + 1
    b = i + 1
    li = p.length[i]
    e = w[_E : _E + 3, i].copy()
    u = y[u0 + 3 * i : u0 + 3 * i + 3]
    u2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2]
    J = w[_SJ, i]
    # kinematics
    _put_identity(diag, upper, lower, b, 0, b, 3, 1.0)
    _put_identity(diag, upper, lower, b, 0, i, 3, -1.0)
    _put_identity(diag, upper, lower, b, 0, b, 0, -cm * li)
    # rotation, as the kernel solves it: P X = 0 with X = J s + (l/2) L - G (P the projector
    # normal to e) and e . s = -|u|^2 |e|^2 (scaled by J). At the dynamic solution X = xi e with
    # xi = (l/2) e.L - J |u|^2, so d/de = -xi P + e (J f + 2 J |u|^2 e - G)^T (f the director
    # acceleration of the dynamics; G's own dependence is added by _joint_rows), d/du 2 J e u^T,
    # d/ds J I, d/dlam (l/2) P
    lam_sum = lam_top + lam_bottom
    xi = 0.5 * li * (e[0] * lam_sum[0] + e[1] * lam_sum[1] + e[2] * lam_sum[2]) - J * u2
    tq = w[_TQ : _TQ + 3, i]
    g = -np.cross(e, tq)
    for r in range(3):
        for c in range(3):
            delta = 1.0 if r == c else 0.0
            de = -xi * (delta - e[r] * e[c])
            de += e[r] * (J * w[_EDD + c, i] + 2.0 * J * u2 * e[c] - g[c])
            du = 2.0 * J * e[r] * u[c]
            m3[3 * r + c] = cm * J * delta + cx * de + cv * du
    _put3(diag, upper, lower, b, 3, b, 0, m3, 1.0)
    for r in range(3):
        for c in range(3):
            m3[3 * r + c] = 0.5 * li * ((1.0 if r == c else 0.0) - e[r] * e[c])
    _put3(diag, upper, lower, b, 3, i, 6, m3, 1.0)
    _put3(diag, upper, lower, b, 3, b, 6, m3, 1.0)
    nm = p.node_mass[i]
    body = i > 0 and (nm[0] != 0.0 or nm[1] != 0.0 or nm[2] != 0.0 or p.node_drag[i] != 0.0)
    if body:
        # a point body at node i: m_b A_i - F_b in the translation rows of this segment, and
        # lam_i' = lam_i - (m_b A_i - F_b) in its rotation rows
        _point_matrix(p, w, i, cv / cm, cx / cm, jv)
        _put3(diag, upper, lower, i, 6, i, 3, jv, 1.0)
        for r in range(3):
            for c in range(3):
                v = 0.0
                for k in range(3):
                    v -= m3[3 * r + k] * jv[3 * k + c]
                put_entry(diag, upper, lower, NEWTON_BLOCK, b, 3 + r, i, 3 + c, v)
    # translation
    ma = w[_SA, i]
    cu, cv_ = _current(p.current_z, p.current_u, p.current_v, w[_P + 2, i] + 0.5 * li * e[2])
    vrel = np.empty(3)
    for k in range(3):
        vrel[k] = 0.5 * (w[_V + k, i] + w[_V + k, b])
    vrel[0] -= cu
    vrel[1] -= cv_
    wet = w[_SF, i]  # the drag of the submerged part
    _drag_jacobians(wet * p.drag_normal[i], wet * p.drag_tangential[i], vrel, e, jv, je)
    ratio = cv / cm
    for r in range(3):
        for c in range(3):
            delta = 1.0 if r == c else 0.0
            m3[3 * r + c] = 0.5 * (p.mass[i] * delta + ma * (delta - e[r] * e[c]))
            m3[3 * r + c] -= 0.5 * ratio * jv[3 * r + c]
    _put3(diag, upper, lower, i, 6, i, 3, m3, 1.0)
    _put3(diag, upper, lower, i, 6, b, 3, m3, 1.0)
    _put_identity(diag, upper, lower, i, 6, i, 6, -1.0)
    _put_identity(diag, upper, lower, i, 6, b, 6, 1.0)
    # d/de of m_a P C and of the drag, C the centre acceleration of the dynamics
    centre = np.empty(3)
    for k in range(3):
        centre[k] = 0.5 * (w[_A + k, i] + w[_A + k, b])
    e_c = e[0] * centre[0] + e[1] * centre[1] + e[2] * centre[2]
    for r in range(3):
        for c in range(3):
            delta = 1.0 if r == c else 0.0
            m3[3 * r + c] = cx * (-ma * (e[r] * centre[c] + e_c * delta) - je[3 * r + c])
    _put3(diag, upper, lower, i, 6, b, 0, m3, 1.0)


@njit(**JIT)
def _point_matrix(p, w, k, ratio, stiff_ratio, out):
    """d(m_b A - F_b)/dA of the point body at node k (velocities following the accelerations
    by ``ratio``, positions by ``stiff_ratio``: the hydrostatic heave stiffness rho g A_wp at the
    free surface), 3x3 row-major into ``out``. The submerged added mass's own dependence on z
    is left out (its term m_a' A dz is small; the residual stays exact)."""
    vx, vy, vz = w[_V, k], w[_V + 1, k], w[_V + 2, k]
    cu, cv = _current(p.current_z, p.current_u, p.current_v, w[_P + 2, k])
    rel = (vx - cu, vy - cv, vz)
    speed = math.sqrt(rel[0] ** 2 + rel[1] ** 2 + rel[2] ** 2)
    for r in range(3):
        for c in range(3):
            value = w[_BM + r, k] if r == c else 0.0
            if speed > 0.0:
                jac = (speed if r == c else 0.0) + rel[r] * rel[c] / speed
                value += ratio * w[_BD + r, k] * jac
            out[3 * r + c] = value
    out[8] += stiff_ratio * w[_BK, k]


@njit(**JIT)
def _end_rows(p, w, cm, cx, cv, diag):
    """Top rows (block 0, rows 0-5) and lower-end rows (block n, rows 6-8)."""
    n = p.n
    bs = NEWTON_BLOCK
    spring = p.top_stiffness * cx + p.top_damping * cv
    top_rows(diag, bs, 3, 3, p.top_kind == TOP_HEAVE, cm, spring, p.top_mass)
    closed = is_closed(p)
    om = p.stabilization_frequency
    ratio = cv / cm
    vx, vy, vz = w[_V, n], w[_V + 1, n], w[_V + 2, n]
    cu, cv_ = _current(p.current_z, p.current_u, p.current_v, w[_P + 2, n])
    rel = (vx - cu, vy - cv_, vz)
    speed = math.sqrt(rel[0] ** 2 + rel[1] ** 2 + rel[2] ** 2)
    for r in range(3):
        row = (6 + r) * bs
        if closed and p.constrained[r] != 0.0:
            diag[n, row + 3 + r] += 1.0 + (2.0 * om * cv + om * om * cx) / cm
            continue
        # m_b A_n - lam_n - F_body = 0 on a free axis
        diag[n, row + 6 + r] -= 1.0
        stiffness = p.tie_k[r] + (w[_BK, n] if r == 2 else 0.0)  # ties, hydrostatic heave
        diag[n, row + 3 + r] += w[_BM + r, n] + ratio * p.tie_c[r] + cx / cm * stiffness
        if speed > 0.0:
            for c in range(3):
                jac = (speed if r == c else 0.0) + rel[r] * rel[c] / speed
                diag[n, row + 3 + c] += ratio * w[_BD + r, n] * jac


@njit(**JIT)
def newton_system(t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix):
    """Residual (and, when ``matrix``, the block-tridiagonal matrix) of an implicit step's
    Newton iteration, as ``planar_newton.newton_system`` (see the comment above NEWTON_BLOCK).
    The residual comes from the mismatch g = a_alpha - f(t, y) with the O(n) dynamics, so a
    converged iterate zeroes it whatever the matrix approximates. The matrix is the
    linearisation of the three segment equations except that node velocities and positions
    follow the node accelerations by Newmark's rule (drag, current, ties, the closed end's
    Baumgarte terms) and the current's gradient is left out; joint moments are differentiated
    by local forward differences."""
    n = p.n
    bs = NEWTON_BLOCK
    closed = is_closed(p)
    status, top_acc, reaction = solve(t, y, p, w)
    if status != OK:
        return status
    for k in range(res.shape[0]):
        res[k] = 0.0
    err = np.zeros(3)  # E_k: node acceleration of the iterate minus the dynamic one
    if p.top_kind == TOP_HEAVE:
        err[2] = a_alpha[3 * n] - top_acc
        res[5] = p.top_mass * err[2]
    for i in range(n):
        li = p.length[i]
        e = w[_E : _E + 3, i]
        ma = w[_SA, i]
        nm = p.node_mass[i]
        g = np.empty(3)
        for k in range(3):
            g[k] = a_alpha[3 * i + k] - w[_EDD + k, i]
        nxt = err + li * g
        mid = 0.5 * (err + nxt)
        e_mid = e[0] * mid[0] + e[1] * mid[1] + e[2] * mid[2]
        # a point body at node i: its inertia m_b E_i in the translation rows, and the force
        # on the segment's top differs from the dynamic one by -m_b E_i (rotation rows)
        body = np.zeros(3)
        if i > 0 and (nm[0] != 0.0 or nm[1] != 0.0 or nm[2] != 0.0):
            for k in range(3):
                body[k] = w[_BM + k, i] * err[k]
        e_body = e[0] * body[0] + e[1] * body[1] + e[2] * body[2]
        for k in range(3):
            res[bs * i + 6 + k] = p.mass[i] * mid[k] + ma * (mid[k] - e_mid * e[k]) + body[k]
            res[bs * (i + 1) + 3 + k] = w[_SJ, i] * g[k] - 0.5 * li * (body[k] - e_body * e[k])
        err = nxt
    for k in range(3):
        held = closed and p.constrained[k] != 0.0
        res[bs * n + 6 + k] = err[k] if held else w[_BM + k, n] * err[k]
    if not matrix:
        return OK
    diag[:, :] = 0.0
    upper[:, :] = 0.0
    lower[:, :] = 0.0
    m3 = np.empty(9)
    jv = np.empty(9)
    je = np.empty(9)
    x = np.empty(18)
    g0 = np.empty(6)  # the joint force and a perturbed one
    lam_above = _node_force(w, 0, reaction, closed)
    for i in range(n):
        lam_top = _below_point_body(p, w, i, t, lam_above) if i > 0 else lam_above
        lam_below = _node_force(w, i + 1, reaction, closed)
        _segment_rows(t, y, p, w, i, lam_top, lam_below, cm, cx, cv, diag, upper, lower, m3, jv, je)
        _joint_rows(y, p, i, cx, cv, diag, upper, lower, x, g0)
        lam_above = lam_below
    _end_rows(p, w, cm, cx, cv, diag)
    return OK


@njit(**JIT)
def newton_correct(length, da, a1):
    """Subtract the Newton correction (the s entries of the solver's blocks) from the director
    and heave accelerations; returns the largest as a node acceleration."""
    n = length.shape[0]
    bs = NEWTON_BLOCK
    largest = abs(da[0])
    a1[3 * n] -= da[0]
    for i in range(n):
        for k in range(3):
            d = da[bs * (i + 1) + k]
            a1[3 * i + k] -= d
            largest = max(largest, abs(d) * length[i])
    return largest
