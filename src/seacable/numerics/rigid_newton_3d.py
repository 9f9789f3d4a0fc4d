"""Newton's rows of 3D rigid-segment lines (``rigid_segments_3d``) in maximal coordinates: the
director form's counterpart of ``numerics.rigid_newton``'s planar rows (derivation:
docs/rigid_newton.md, section 5), a banded block per line, O(n) to build and to factorise.

Per segment i the unknowns are (all changes scaled by (1 - af), as in the planar rows)

    delta_i (3), dA_(i+1) (3), dlam_i (3), dP_(i+1) (3), dV_(i+1) (3)    (15, in this order)

and dlam_n (3) at the tip; the rows paired with them are the segment's two rotations (on t1,
t2) and the radial condition e.f + |u|^2 |e|^2 = 0, its kinematics, its translation, its lower
node's position and velocity; then the tip's. They are the exact linearisation of the equations
the sweeps of ``kernels.chain3d`` solve, at the states Newton visits, where the director is not
of unit length (t2 = e x t1 is then |e| long): the correction is the dense one. The loads'
derivatives come from differences of ``segment_loads`` (``rigid_derivatives``).
"""

import math

import numpy as np
from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels import chain3d_layout as cl
from seacable.kernels.jit import JIT, inner
from seacable.numerics.rigid_derivatives import (
    ABOVE_3D,
    BELOW_3D,
    DERIVATIVES_3D,
    INPUTS_3D,
    OUTPUTS_3D,
    end_joint,
    point_derivatives,
    segments_derivatives,
)
from seacable.system import rigid

PER_SEGMENT = 15  # unknowns (and rows) per segment; TIP more at the tip
TIP = 3
# where each of a segment's unknowns (delta (3), dA (3), dlam (3), dP (3), dV (3)) stands in its
# part of the block: dlam_i first, as the planar rows' order (kl = 16, ku = 17; a local search
# over swaps from 30 starts found none narrower)
BLOCK_ORDER = np.array([3, 4, 5, 6, 7, 8, 0, 1, 2, 9, 10, 11, 12, 13, 14])
GEO = 18  # per segment, for the right-hand side: c t1, c t2 / |e|^2, e, t1, t2, l mt / 2, mt, ma
# rows of ``entries``' state (., n + 1): each segment's director, rate, acceleration (f), basis
# t1, t2, loads F and torque, added mass SA, inertia SJ, mass, length; each node's A and lam
_E, _U, _FA, _T1, _T2, _A, _LAM, _LOAD, _TQ = 0, 3, 6, 9, 12, 15, 18, 21, 24
_SA, _SJ, _MASS, _LEN = 27, 28, 29, 30
STATE_ROWS = 31


@njit(inline="always", **JIT)
def put(rows, cols, vals, k, r, c, value):
    """Entry k of a line's (row, column, value) triplets (here and ``numerics.rigid_newton``):
    returns k + 1."""
    rows[k], cols[k], vals[k] = r, c, value
    return k + 1


@njit(inline="always", **JIT)
def _cross(a, b, out):
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@njit(inline="always", **JIT)
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(inline="always", **JIT)
def _upper(rows, cols, vals, k, r, i, col, base, axis, value, factor):
    """An entry on node i's unknown ``col`` (i > 0) or, at node 0, on a dynamic base's
    translation ``axis`` (its columns from ``base`` >= 0) with ``value * factor``; none for a
    fixed or imposed base."""
    if i > 0:
        return put(rows, cols, vals, k, r, col, value)
    if base >= 0:
        return put(rows, cols, vals, k, r, base + axis, value * factor)
    return k


@njit(inline="always", **JIT)
def _free(base_free, axis):
    """1.0 on a free translation of a dynamic base (0.0 on a held one, or no such base)."""
    return base_free[axis] if base_free.shape[0] > 0 else 0.0


@njit(inline="always", **JIT)
def _loads(n, i, der, weight, joints, kx, kv, base, coef, r, rows, cols, vals, k):
    """Row r's terms in segment i's load changes, ``weight`` (8) its coefficients on dF (3),
    dtorque (3), dSA and dSJ: its own director's and rate's added to ``coef`` (3), its top
    node's P and V (at node 0 a dynamic base's translations, first column ``base``), and with
    ``joints`` its neighbours' directors and rates (the joints' torques)."""
    d = PER_SEGMENT * i
    up = d - PER_SEGMENT
    for j in range(3):
        sp, sv, se, su = 0.0, 0.0, 0.0, 0.0
        for o in range(OUTPUTS_3D):
            at = INPUTS_3D * o + j
            sp += weight[o] * der[at, i]
            sv += weight[o] * der[at + 3, i]
            se += weight[o] * der[at + 6, i]
            su += weight[o] * der[at + 9, i]
        coef[j] += kx * se + kv * su
        if i > 0:
            k = put(rows, cols, vals, k, r, up + 9 + j, sp)
            k = put(rows, cols, vals, k, r, up + 12 + j, sv)
        elif base >= 0:
            k = put(rows, cols, vals, k, r, base + j, kx * sp + kv * sv)
        if not joints:
            continue
        above, below = 0.0, 0.0
        for o in range(3):
            wo = weight[3 + o]
            above += wo * (
                kx * der[ABOVE_3D + 6 * o + j, i] + kv * der[ABOVE_3D + 6 * o + 3 + j, i]
            )
            below += wo * (
                kx * der[BELOW_3D + 6 * o + j, i] + kv * der[BELOW_3D + 6 * o + 3 + j, i]
            )
        if i > 0:
            k = put(rows, cols, vals, k, r, up + j, above)
        if i + 1 < n:
            k = put(rows, cols, vals, k, r, d + PER_SEGMENT + j, below)
    return k


@njit(inline="always", **JIT)
def _basis_change(e, t1, x, hat, side, scratch, g):
    """g: the gradient by e of t1.x (``side`` 0) or t2.x (1), t1 = (e x hat) / |e x hat| and
    t2 = e x t1 (``kernels.chain3d._basis``): dt1 = (I - t1 t1^T)(de x hat) / |e x hat|,
    dt2 = de x t1 + e x dt1."""
    z, zp = scratch[0], scratch[1]
    _cross(e, hat, zp)
    norm = math.sqrt(_dot(zp, zp))
    if side == 0:
        z[:] = x
        g[:] = 0.0
    else:
        _cross(x, e, z)
        _cross(t1, x, g)
    along = _dot(t1, z)
    for q in range(3):
        zp[q] = z[q] - along * t1[q]
    _cross(hat, zp, z)
    for q in range(3):
        g[q] += z[q] / norm


@njit(**JIT)
def entries(n, state, der, tip_mass, tip_der, held, stabilization, base_free, km, kx, kv, rows,
            cols, vals):  # fmt: skip
    """One 3D line's entries (local row, local column, value; docs/rigid_newton.md, section 5)
    from ``state`` (STATE_ROWS, n + 1: the evaluation's values), ``der``
    (``rigid_derivatives.segments_derivatives``), the tip body's mass ``tip_mass`` (3x3) and
    force derivatives ``tip_der`` (``point_derivatives``); ``held`` (3): 1.0 on an axis the tip
    is held on (Baumgarte, at ``stabilization`` rad/s); ``base_free`` (3, or empty for a fixed
    or imposed base): the free translations of the dynamic base body (its columns local
    15 n + 3 + axis). Returns the count; the entries do not depend on the values."""
    k = 0
    base = PER_SEGMENT * n + TIP if base_free.shape[0] > 0 else -1
    vec = np.empty((15, 3))  # e, u, f, A_i, lam_(i+1), torque, F, t1, t2, then scratch
    scalars = np.empty(4)
    coef = np.empty(3)
    weight = np.empty(OUTPUTS_3D)
    for i in range(n):
        for q in range(3):
            for j, row in enumerate((_E, _U, _FA, _A, _LAM, _TQ, _LOAD, _T1, _T2)):
                vec[j, q] = state[row + q, i + 1 if row == _LAM else i]
        li, sa = state[_LEN, i], state[_SA, i]
        mt = state[_MASS, i] + sa
        scalars[0], scalars[1], scalars[2] = li, sa, mt
        scalars[3] = state[_SJ, i] + 0.25 * mt * li * li
        k = _rotations(n, i, der, vec, scalars, base, base_free, km, kx, kv, coef, weight, rows,
                       cols, vals, k)  # fmt: skip
        k = _translations(n, i, der, vec, scalars, base, base_free, km, kx, kv, coef, weight,
                          rows, cols, vals, k)  # fmt: skip
    return tip_entries(n, PER_SEGMENT, 3, (3, 9, 12), tip_mass, tip_der, held, stabilization,
                       rows, cols, vals, k)  # fmt: skip


@njit(inline="always", **JIT)
def _rotations(n, i, der, vec, scalars, base, base_free, km, kx, kv, coef, weight, rows, cols,
               vals, k):  # fmt: skip
    """Segment i's rotation rows c (t_k.f) / |t_k|^2 + t_k.s = 0 (k = 1, 2; s = l mt A_i / 2 +
    l lam_(i+1) - l F / 2 + e x torque, c = SJ + mt l^2 / 4) and its radial row
    e.f + |u|^2 |e|^2 = 0 (``entries``; ``vec`` and ``scalars`` as it fills them)."""
    e, u, f, a, lam1, tq, load = vec[0], vec[1], vec[2], vec[3], vec[4], vec[5], vec[6]
    x, s, hat, g = vec[9], vec[10], vec[11], vec[12]
    li, mt, c = scalars[0], scalars[2], scalars[3]
    d = PER_SEGMENT * i
    lam_next = d + PER_SEGMENT + 6 if i + 1 < n else d + PER_SEGMENT
    nu = _dot(e, e)
    _cross(e, tq, s)  # -G = e x torque
    for q in range(3):
        s[q] += 0.5 * li * mt * a[q] + li * lam1[q] - 0.5 * li * load[q]
    hat[:] = 0.0  # kernels.chain3d._basis's axis
    if abs(e[0]) <= abs(e[1]) and abs(e[0]) <= abs(e[2]):
        hat[0] = 1.0
    elif abs(e[1]) <= abs(e[2]):
        hat[1] = 1.0
    else:
        hat[2] = 1.0
    for side in range(2):
        t = vec[7 + side]
        scale = 1.0 if side == 0 else nu
        tf = _dot(t, f)
        for q in range(3):
            x[q] = c * f[q] / scale + s[q]
        _basis_change(e, vec[7], x, hat, side, vec[13:15], g)
        _cross(tq, t, x)  # de.(torque x t_k)
        for q in range(3):
            coef[q] = kx * (g[q] + x[q]) + c / scale * km * t[q]
            if side == 1:
                coef[q] -= 2.0 * kx * c * tf / (scale * scale) * e[q]
        _cross(t, e, x)  # the torque's weight
        for q in range(3):
            weight[q], weight[3 + q] = -0.5 * li * t[q], x[q]
        weight[6] = 0.25 * li * li * tf / scale + 0.5 * li * _dot(t, a)
        weight[7] = tf / scale
        k = _loads(n, i, der, weight, True, kx, kv, base, coef, d + side, rows, cols, vals, k)
        for q in range(3):
            k = put(rows, cols, vals, k, d + side, d + q, coef[q])
            k = _upper(rows, cols, vals, k, d + side, i, d - 12 + q, base, q,
                       0.5 * li * mt * t[q], km * _free(base_free, q))  # fmt: skip
            k = put(rows, cols, vals, k, d + side, lam_next + q, li * t[q])
    u2 = _dot(u, u)
    for q in range(3):
        value = kx * f[q] + km * e[q] + 2.0 * nu * kv * u[q] + 2.0 * u2 * kx * e[q]
        k = put(rows, cols, vals, k, d + 2, d + q, value)
    return k


@njit(inline="always", **JIT)
def _translations(n, i, der, vec, scalars, base, base_free, km, kx, kv, coef, weight, rows,
                  cols, vals, k):  # fmt: skip
    """Segment i's kinematics, translation and lower node's position and velocity rows
    (``entries``)."""
    e, u, f, a = vec[0], vec[1], vec[2], vec[3]
    li, sa, mt = scalars[0], scalars[1], scalars[2]
    u2, ea = _dot(u, u), _dot(e, a)
    d = PER_SEGMENT * i
    up = d - PER_SEGMENT
    lam_next = d + PER_SEGMENT + 6 if i + 1 < n else d + PER_SEGMENT
    for q in range(3):
        # kinematics: A_(i+1) - A_i - l f = 0
        r = d + 3 + q
        k = put(rows, cols, vals, k, r, d + 3 + q, 1.0)
        k = _upper(rows, cols, vals, k, r, i, up + 3 + q, base, q, -1.0,
                   km * _free(base_free, q))  # fmt: skip
        k = put(rows, cols, vals, k, r, d + q, -li * km)
        # translation: lam_i - lam_(i+1) - mt A_i + sa e (e.A_i) - l/2 mt f - l/2 sa |u|^2 e
        # + F = 0
        r = d + 6 + q
        k = put(rows, cols, vals, k, r, d + 6 + q, 1.0)
        k = put(rows, cols, vals, k, r, lam_next + q, -1.0)
        for p in range(3):
            value = sa * e[q] * e[p] - (mt if p == q else 0.0)
            k = _upper(rows, cols, vals, k, r, i, up + 3 + p, base, p, value,
                       km * _free(base_free, p))  # fmt: skip
            diagonal = ea * kx * sa - 0.5 * li * (mt * km + sa * u2 * kx) if p == q else 0.0
            coef[p] = diagonal + kx * sa * e[q] * a[p] - li * sa * kv * e[q] * u[p]
        weight[:] = 0.0
        weight[q] = 1.0
        weight[6] = -a[q] + e[q] * ea - 0.5 * li * (f[q] + u2 * e[q])
        k = _loads(n, i, der, weight, False, kx, kv, base, coef, r, rows, cols, vals, k)
        for p in range(3):
            k = put(rows, cols, vals, k, r, d + p, coef[p])
        # the lower node's position and velocity: P_(i+1) = P_i + l e, V_(i+1) = V_i + l u
        for kind in range(2):
            at, rate = (9, kx) if kind == 0 else (12, kv)
            r = d + at + q
            k = put(rows, cols, vals, k, r, d + at + q, 1.0)
            k = _upper(rows, cols, vals, k, r, i, up + at + q, base, q, -1.0, rate)
            k = put(rows, cols, vals, k, r, d + q, -li * rate)
    return k


@njit(inline="always", **JIT)
def tip_entries(n, per, dims, at, tip_mass, tip_der, held, stabilization, rows, cols, vals, k):
    """The tip's rows, planar (``dims`` 2: x, z) or 3D (3), after n links of ``per`` unknowns,
    node n's A, P, V from ``at`` (3) in the last link's: on a held axis A_n = target -
    2 w (V_n - v*) - w^2 (P_n - p*) (lam_n's component there is the holding force's), on a free
    one lam_n = M_t A_n + bias - load(P_n, V_n) (``tip_mass`` 3x3, ``tip_der``:
    ``point_derivatives``' 18)."""
    last = per * (n - 1)
    for c in range(dims):
        r = per * n + c
        if held[c] != 0.0:
            k = put(rows, cols, vals, k, r, last + at[0] + c, 1.0)
            k = put(rows, cols, vals, k, r, last + at[2] + c, 2.0 * stabilization)
            k = put(rows, cols, vals, k, r, last + at[1] + c, stabilization * stabilization)
            continue
        k = put(rows, cols, vals, k, r, r, 1.0)
        axis = c if dims == 3 else 2 * c
        for e in range(dims):
            other = 3 * axis + (e if dims == 3 else 2 * e)
            k = put(rows, cols, vals, k, r, last + at[0] + e, -tip_mass[other])
            k = put(rows, cols, vals, k, r, last + at[1] + e, tip_der[other])
            k = put(rows, cols, vals, k, r, last + at[2] + e, tip_der[9 + other])
    return k


def entries_pattern(n: int, held: np.ndarray, dynamic_base: bool) -> tuple[np.ndarray, np.ndarray]:
    """The local rows and columns of a 3D line's entries, in ``entries``' order."""
    size = 140 * n + 40
    rows, cols, vals = np.empty(size, np.int64), np.empty(size, np.int64), np.empty(size)
    state = np.ones((STATE_ROWS, n + 1))
    count = entries(np.int64(n), state, np.zeros((DERIVATIVES_3D, n)), np.zeros(9),
                    np.zeros(18), np.asarray(held, dtype=np.float64), 1.0,
                    np.ones(3 if dynamic_base else 0), 1.0, 1.0, 1.0, rows, cols,
                    vals)  # fmt: skip
    return rows[:count], cols[:count]


@inner
def fill_line(t, y, p, w, li, dynamic, km, kx, kv, geo, r_loc, c_loc, vals):
    """Line ``li``'s entries at the evaluation ``w`` holds (state y, time t; ``dynamic``: its
    base is a written dynamic body), and its right-hand side's geometry into ``geo`` (GEO per
    segment). Returns the count."""
    n, s0 = p.rs_n[li], p.rs_seg[li]
    ws = rigid.workspace(p, w, li)
    base = p.point_body[p.rs_from[li]]
    ref = np.empty(3)
    for c in range(3):
        ref[c] = (w.rot[base, c, 0] * p.rs_ref[li, 0] + w.rot[base, c, 1] * p.rs_ref[li, 1]
                  + w.rot[base, c, 2] * p.rs_ref[li, 2])  # fmt: skip
    der = np.empty((DERIVATIVES_3D, n))
    segments_derivatives(t, p, li, y, ref, w.omega[base], end_joint(p, w, li), ws, der)
    held = p.rs_held[li]
    pinned = held[0] != 0.0 or held[1] != 0.0 or held[2] != 0.0
    state = np.zeros((STATE_ROWS, n + 1))
    for node in range(n + 1):
        lam = c3._node_force(ws, node, w.rs_force[li], pinned)
        for c in range(3):
            state[_A + c, node], state[_LAM + c, node] = ws[cl._A + c, node], lam[c]
    for i in range(n):
        for c in range(3):
            state[_E + c, i], state[_U + c, i] = ws[cl._E + c, i], ws[cl._U + c, i]
            state[_FA + c, i] = ws[cl._EDD + c, i]
            state[_T1 + c, i], state[_T2 + c, i] = ws[cl._T1 + c, i], ws[cl._T2 + c, i]
            state[_LOAD + c, i], state[_TQ + c, i] = ws[cl._F + c, i], ws[cl._TQ + c, i]
        state[_SA, i], state[_SJ, i] = ws[cl._SA, i], ws[cl._SJ, i]
        state[_MASS, i], state[_LEN, i] = p.rs_mass[s0 + i], p.rs_length[s0 + i]
        mt = state[_MASS, i] + state[_SA, i]
        c = state[_SJ, i] + 0.25 * mt * state[_LEN, i] ** 2
        nu = state[_E, i] ** 2 + state[_E + 1, i] ** 2 + state[_E + 2, i] ** 2
        g = geo[GEO * i : GEO * (i + 1)]
        for q in range(3):
            g[q], g[3 + q] = c * state[_T1 + q, i], c * state[_T2 + q, i] / nu
            g[6 + q], g[9 + q], g[12 + q] = state[_E + q, i], state[_T1 + q, i], state[_T2 + q, i]
        g[15], g[16], g[17] = 0.5 * state[_LEN, i] * mt, mt, state[_SA, i]
    tip_mass, point = tip_body(t, y, p, w, p.rs_tip[li])
    base_free = p.body_free[base, :3] if dynamic else np.zeros(0)
    return entries(n, state, der, tip_mass, point, held, p.stabilization_frequency, base_free, km,
                   kx, kv, r_loc, c_loc, vals)  # fmt: skip


@inner
def tip_body(t, y, p, w, tip):
    """The translational mass (3x3, row-major) and the force models' derivatives
    (``point_derivatives``' 18) of the body a line carries at its tip (``tip`` >= 0; zeros
    without one)."""
    tip_mass, point = np.zeros(9), np.zeros(18)
    if tip >= 0:
        for c in range(3):
            for e in range(3):
                tip_mass[3 * c + e] = w.mass[tip, c, e]
        point_derivatives(t, y, p, w, tip, point)
    return tip_mass, point


@njit(inline="always", **JIT)
def rhs_line(p, li, aux, geo, res, big, base):
    """Line ``li``'s part of Newton's right-hand side (``rigid_newton.rhs``): its delta rows
    c t_k.r / |t_k|^2 and e.r, its kinematics rows -l r, its translation rows -l mt r / 2, and
    from a dynamic base (``base`` >= 0, its residual r_b on the free axes) link 0's
    kinematics -r_b, translation -(mt r_b - ma e (e.r_b)), rotations l mt t_k.r_b / 2."""
    n, s0, v = p.rs_n[li], p.rs_seg[li], p.rs_v[li] - p.n_q
    per = PER_SEGMENT - 3
    for i in range(n):
        g = geo[GEO * i : GEO * (i + 1)]
        r = res[v + 3 * i : v + 3 * i + 3]
        big[v + 3 * i] = g[0] * r[0] + g[1] * r[1] + g[2] * r[2]
        big[v + 3 * i + 1] = g[3] * r[0] + g[4] * r[1] + g[5] * r[2]
        big[v + 3 * i + 2] = g[6] * r[0] + g[7] * r[1] + g[8] * r[2]
        for q in range(3):
            big[aux + per * i + q] = -p.rs_length[s0 + i] * r[q]
            big[aux + per * i + 3 + q] = -g[15] * r[q]
    if base < 0:
        return
    bv = p.body_v[base] - p.n_q
    rb = np.empty(3)
    for q in range(3):
        rb[q] = p.body_free[base, q] * res[bv + q]
    g = geo[:GEO]
    erb = g[6] * rb[0] + g[7] * rb[1] + g[8] * rb[2]
    for q in range(3):
        big[aux + q] -= rb[q]
        big[aux + 3 + q] -= g[16] * rb[q] - g[17] * g[6 + q] * erb
    for side in range(2):
        t = g[9 + 3 * side : 12 + 3 * side]
        big[v + side] += g[15] * (t[0] * rb[0] + t[1] * rb[1] + t[2] * rb[2])
