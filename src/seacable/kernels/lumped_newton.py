"""Implicit steps of the lumped-mass cable: the Newton residual and block-tridiagonal matrix of
one step (numba). See docs/architecture.md, "Implicit integration (fixed step)"."""

import math

import numpy as np
from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels.lumped import (
    _L,
    _SF,
    _SK,
    _TX,
    _free_axes,
    _node_mass_into,
    is_held,
    rhs,
)
from seacable.kernels.timefn import JIT


# ---- implicit integration: the Newton system of one step ----------------------------------------
@njit(**JIT)
def _add_block(blocks, k, g, scale):
    """blocks[k] += scale * g (3x3 row-major, 9 values)."""
    for c in range(9):
        blocks[k, c] += scale * g[c]


@njit(**JIT)
def _segment_jacobians(y, v0, i, l0, ea, alpha, slack_allowed, c_n, c_t2, cz, cu_, cv_, g):
    """Derivatives for segment i of its tension pull N t with respect to d = r_{i+1} - r_i (gx)
    and to d' (gv), and of its drag force on its centre's relative velocity (gd); 3x3 each,
    row-major, in g[0], g[1], g[2]. Scalars and tuples only: no heap allocation and no
    parameter tuple per segment (``c_t2`` is twice the tangential drag factor)."""
    gx, gv, gd = g[0], g[1], g[2]
    a = 3 * i
    b = 3 * (i + 1)
    dx, dy, dz = y[b] - y[a], y[b + 1] - y[a + 1], y[b + 2] - y[a + 2]
    dvx = y[v0 + b] - y[v0 + a]
    dvy = y[v0 + b + 1] - y[v0 + a + 1]
    dvz = y[v0 + b + 2] - y[v0 + a + 2]
    length = math.sqrt(dx * dx + dy * dy + dz * dz)
    t = (dx / length, dy / length, dz / length)
    rate = (dvx * t[0] + dvy * t[1] + dvz * t[2]) / l0
    tension = ea * (length / l0 - 1.0 + alpha * rate)
    slack = tension < 0.0 and slack_allowed == 1
    # dv projected normal to the tangent: how the strain rate turns with the segment
    s = rate * l0
    pdv = (dvx - s * t[0], dvy - s * t[1], dvz - s * t[2])
    kt = ea / l0
    kn = tension / length
    kd = ea * alpha / (l0 * length)
    cd = ea * alpha / l0
    # drag on the relative velocity of the centre
    zc = 0.5 * (y[a + 2] + y[b + 2])
    cu, cv = c3._current(cz, cu_, cv_, zc)
    rx = 0.5 * (y[v0 + a] + y[v0 + b]) - cu
    ry = 0.5 * (y[v0 + a + 1] + y[v0 + b + 1]) - cv
    rz = 0.5 * (y[v0 + a + 2] + y[v0 + b + 2])
    vt = rx * t[0] + ry * t[1] + rz * t[2]
    rn = (rx - vt * t[0], ry - vt * t[1], rz - vt * t[2])
    vn = math.sqrt(rn[0] * rn[0] + rn[1] * rn[1] + rn[2] * rn[2])
    inv_vn = 1.0 / vn if vn > 0.0 else 0.0
    c_t = c_t2 * abs(vt)
    for r in range(3):
        for c in range(3):
            tt = t[r] * t[c]
            eye = 1.0 if r == c else 0.0
            if slack:
                gx[3 * r + c] = 0.0
                gv[3 * r + c] = 0.0
            else:
                gx[3 * r + c] = kt * tt + kn * (eye - tt) + kd * t[r] * pdv[c]
                gv[3 * r + c] = cd * tt
            gd[3 * r + c] = -c_n * (vn * (eye - tt) + rn[r] * rn[c] * inv_vn) - c_t * tt


@njit(**JIT)
def _seabed_jacobian(y, v0, k, seabed_z, stiff, damp, slip, mu, cx, cv, diag):
    """diag[k] -= cx dF/dx + cv dF/dv of the seabed's normal and friction force on node k."""
    depth = seabed_z - y[3 * k + 2]
    if depth <= 0.0:
        return
    vx, vy, vz = y[v0 + 3 * k], y[v0 + 3 * k + 1], y[v0 + 3 * k + 2]
    normal = stiff * depth - damp * vz
    if normal <= 0.0:
        return
    s = math.sqrt(vx * vx + vy * vy + slip * slip)
    # dFz/dz = -k, dFz/dvz = -c; Fx = -mu N vx / s
    diag[k, 8] += cx * stiff + cv * damp
    s3 = s * s * s
    diag[k, 0] += cv * mu * normal * (1.0 / s - vx * vx / s3)
    diag[k, 1] += cv * mu * normal * (-vx * vy / s3)
    diag[k, 3] += cv * mu * normal * (-vx * vy / s3)
    diag[k, 4] += cv * mu * normal * (1.0 / s - vy * vy / s3)
    # through the normal force: dFx/dz = mu k vx / s, dFx/dvz = mu c vx / s
    diag[k, 2] -= (cx * stiff + cv * damp) * mu * vx / s
    diag[k, 5] -= (cx * stiff + cv * damp) * mu * vy / s


@njit(**JIT)
def _sphere_drag_jacobian(y, v0, k, drag, cz, cu_, cv_, cv, diag):
    """diag[k] += cv d(drag |r| r)/dr of a point body's sphere drag."""
    cu, cvv = c3._current(cz, cu_, cv_, y[3 * k + 2])
    r = (y[v0 + 3 * k] - cu, y[v0 + 3 * k + 1] - cvv, y[v0 + 3 * k + 2])
    speed = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
    if speed == 0.0:
        return
    for a in range(3):
        for b in range(3):
            term = r[a] * r[b] / speed + (speed if a == b else 0.0)
            diag[k, 3 * a + b] += cv * drag * term


@njit(**JIT)
def _bending_jacobian(n, stiffness, w, cx, diag, upper, lower):
    """Add cx times a block-tridiagonal stand-in for the bending Hessian: near a straight line,
    V = k phi^2 / 2 with phi = (w_{i+1} - w_i) / l_b - (w_i - w_{i-1}) / l_a for the transverse
    displacements w, so the Hessian is k g g^T P, g = (1/l_a, -(1/l_a + 1/l_b), 1/l_b), P the
    projector normal to the mean tangent. Its corner (i-1, i+1) falls outside the three block
    diagonals: it is moved onto the two diagonal blocks, which keeps the stand-in positive."""
    for i in range(1, n):
        k = stiffness[i]
        if k == 0.0:
            continue
        tx = w[_TX, i - 1] + w[_TX, i]
        ty = w[_TX + 1, i - 1] + w[_TX + 1, i]
        tz = w[_TX + 2, i - 1] + w[_TX + 2, i]
        norm = math.sqrt(tx * tx + ty * ty + tz * tz)
        if norm == 0.0:
            continue
        t = (tx / norm, ty / norm, tz / norm)
        ga, gb = 1.0 / w[_L, i - 1], 1.0 / w[_L, i]
        gm = -(ga + gb)
        corner = k * ga * gb
        for r in range(3):
            for c in range(3):
                proj = (1.0 if r == c else 0.0) - t[r] * t[c]
                e = 3 * r + c
                diag[i - 1, e] += cx * (k * ga * ga + corner) * proj
                diag[i, e] += cx * k * gm * gm * proj
                diag[i + 1, e] += cx * (k * gb * gb + corner) * proj
                upper[i - 1, e] += cx * k * ga * gm * proj
                lower[i - 1, e] += cx * k * ga * gm * proj
                upper[i, e] += cx * k * gm * gb * proj
                lower[i, e] += cx * k * gm * gb * proj


@njit(**JIT)
def _jacobian(y, p, w, cx, cv, diag, upper, lower):
    """Add -cx dF/dx - cv dF/dv of the segments, the seabed and the end body's drag."""
    n = p.n
    v0 = 3 * (n + 1)
    g = np.empty((3, 9))
    for i in range(n):
        _segment_jacobians(
            y, v0, i, p.length[i], p.axial_stiffness, p.axial_damping[i], p.slack_allowed,
            p.drag_normal[i], 2.0 * p.drag_tangential[i], p.current_z, p.current_u, p.current_v,
            g,
        )  # fmt: skip
        gx, gv, gd = g[0], g[1], g[2]
        for c in range(9):
            # the pull on node i is +N t, on node i+1 is -N t, with d = r_{i+1} - r_i; drag is
            # shared half and half on the mean velocity of the two nodes
            pull = cx * gx[c] + cv * gv[c]
            dd = -0.25 * cv * gd[c]
            diag[i, c] += pull + dd
            diag[i + 1, c] += pull + dd
            upper[i, c] = -pull + dd
            lower[i, c] = -pull + dd
    for k in range(n + 1):
        _seabed_jacobian(
            y, v0, k, p.seabed_z, p.seabed_stiffness[k], p.seabed_damping[k],
            p.seabed_slip_speed, p.seabed_friction, cx, cv, diag,
        )  # fmt: skip
    for k in range(n + 1):
        if p.point_drag[k] > 0.0:
            _sphere_drag_jacobian(y, v0, k, w[_SF, k] * p.point_drag[k], p.current_z,
                                  p.current_u, p.current_v, cv, diag)  # fmt: skip
        diag[k, 8] += cx * w[_SK, k]  # the free surface's heave stiffness (zero without it)
    if not _free_axes(p):
        return
    # the end body's drag and ties (zero without them)
    cu, cvv = c3._current(p.current_z, p.current_u, p.current_v, y[3 * n + 2])
    r = np.array([y[v0 + 3 * n] - cu, y[v0 + 3 * n + 1] - cvv, y[v0 + 3 * n + 2]])
    speed = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
    for a in range(3):
        for b in range(3):
            term = r[a] * r[b] / speed if speed > 0.0 else 0.0
            if a == b:
                term += speed
            diag[n, 3 * a + b] += cv * w[_SF, n] * p.body_drag[a] * term
    for a in range(3):
        diag[n, 4 * a] += cx * p.tie_k[a] + cv * p.tie_c[a]


@njit(**JIT)
def newton_system(t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix=True):
    """Residual and matrix of an implicit step's Newton iteration, in force units, per node.

    ``y`` is the state where the forces are evaluated, ``a_alpha`` the accelerations the scheme
    asks for. ``res[k] = M_k (a_alpha_k - a_k(t, y))`` and the block-tridiagonal matrix is
    ``cm M - cx dF/dx - cv dF/dv`` (``diag`` (n+1, 9); ``upper[k]`` couples node k to k+1 and
    ``lower[k]`` node k+1 to k, (n, 9) each). Nodes the model prescribes (the top, a pin) get an
    identity row and a zero residual. The added mass's dependence on the tangent is left out of
    the matrix (a quasi-Newton iteration). With ``matrix`` False only the residual is formed.
    Returns the kernel status of the right-hand side.
    """
    n = p.n
    v0 = 3 * (n + 1)
    status = rhs(t, y, p, w, ydot)
    mass = np.empty(9)  # not diag: without ``matrix`` it holds the caller's factors
    for k in range(n + 1):
        _node_mass_into(p.node_mass[k], w, k, mass)
        if k == 0 and p.top_kind == c3.TOP_HEAVE:
            mass[8] += p.top_mass
        for r in range(3):
            acc = 0.0
            for c in range(3):
                acc += mass[3 * r + c] * (a_alpha[3 * k + c] - ydot[v0 + 3 * k + c])
            res[3 * k + r] = acc
        if matrix:
            for c in range(9):
                diag[k, c] = cm * mass[c]
    if not matrix:
        for c in range(3):
            if c < 2 or p.top_kind != c3.TOP_HEAVE:
                res[c] = 0.0  # the top is prescribed (a floating structure: in x and y)
            if is_held(p) and p.constrained[c] != 0.0:
                res[3 * n + c] = 0.0
        return status
    _jacobian(y, p, w, cx, cv, diag, upper, lower)
    _bending_jacobian(n, p.bend_stiffness, w, cx, diag, upper, lower)
    if p.top_kind == c3.TOP_HEAVE:
        _heave_rows(p, cx, cv, diag, upper, lower, res)
    else:
        _prescribed_rows(p, diag, upper, lower, res, 0)
    if is_held(p):
        _held_rows(p, diag, lower, res)
    return status


@njit(**JIT)
def _heave_rows(p, cx, cv, diag, upper, lower, res):
    """A floating structure: node 0 held in x and y (identity rows, zero residual), free in z
    with the structure's mass (already in the residual's mass), spring and damper."""
    for r in range(2):
        for c in range(3):
            diag[0, 3 * r + c] = 1.0 if r == c else 0.0
            diag[0, 3 * c + r] = 1.0 if r == c else 0.0
            upper[0, 3 * r + c] = 0.0
            lower[0, 3 * c + r] = 0.0
        res[r] = 0.0
    diag[0, 8] += cx * p.top_stiffness + cv * p.top_damping


@njit(**JIT)
def _prescribed_rows(p, diag, upper, lower, res, k):
    for c in range(9):
        diag[k, c] = 1.0 if c in (0, 4, 8) else 0.0
        if k < p.n:
            upper[k, c] = 0.0
            lower[k, c] = 0.0
        if k > 0:
            upper[k - 1, c] = 0.0
            lower[k - 1, c] = 0.0
    for c in range(3):
        res[3 * k + c] = 0.0


@njit(**JIT)
def _held_rows(p, diag, lower, res):
    """Identity rows and zero residual for the held axes of the end node."""
    n = p.n
    for r in range(3):
        if p.constrained[r] == 0.0:
            continue
        for c in range(3):
            diag[n, 3 * r + c] = 1.0 if r == c else 0.0
            lower[n - 1, 3 * r + c] = 0.0
        res[3 * n + r] = 0.0


# ---- the block-tridiagonal solver (3x3 blocks; O(n)) -------------------------------------------
@njit(**JIT)
def _inverse3(a, out):
    """out = inverse of the 3x3 row-major ``a``; returns the determinant (0: singular)."""
    c00 = a[4] * a[8] - a[5] * a[7]
    c01 = a[5] * a[6] - a[3] * a[8]
    c02 = a[3] * a[7] - a[4] * a[6]
    det = a[0] * c00 + a[1] * c01 + a[2] * c02
    if det == 0.0 or not math.isfinite(det):
        return 0.0
    inv = 1.0 / det
    out[0] = c00 * inv
    out[1] = (a[2] * a[7] - a[1] * a[8]) * inv
    out[2] = (a[1] * a[5] - a[2] * a[4]) * inv
    out[3] = c01 * inv
    out[4] = (a[0] * a[8] - a[2] * a[6]) * inv
    out[5] = (a[2] * a[3] - a[0] * a[5]) * inv
    out[6] = c02 * inv
    out[7] = (a[1] * a[6] - a[0] * a[7]) * inv
    out[8] = (a[0] * a[4] - a[1] * a[3]) * inv
    return det


@njit(**JIT)
def _matmul3(a, b, out):
    for r in range(3):
        for c in range(3):
            out[3 * r + c] = a[3 * r] * b[c] + a[3 * r + 1] * b[3 + c] + a[3 * r + 2] * b[6 + c]


@njit(**JIT)
def block_tridiagonal_factor(diag, upper, lower, factor, chain=0):
    """Block LU (Thomas) of the block-tridiagonal matrix with 3x3 blocks (row-major, 9 values
    each): ``diag[k]`` on the diagonal, ``upper[k]`` at (k, k+1), ``lower[k]`` at (k+1, k).
    Overwrites ``diag`` with the inverted pivots and fills ``factor[k] = lower[k] pivot[k]^-1``
    (``factor`` as long as ``lower``); O(n). Returns False when a pivot is singular.

    With ``chain`` > 0 the matrix is a star (``kernels.lumped_star``): chains of ``chain`` nodes
    one after another, then one hub node (the last) coupled to each chain's last node, whose
    ``upper``/``lower`` entries hold that coupling; chains do not couple to each other. Each
    chain is eliminated towards the hub, then the hub. ``chain`` = 0: one chain (the plain
    block-tridiagonal matrix)."""
    m = diag.shape[0]
    hub = m - 1
    if chain <= 0:
        chain = max(hub, 1)
    inv = np.empty(9)
    tmp = np.empty(9)
    for k in range(hub):
        if _inverse3(diag[k], inv) == 0.0:
            return False
        for c in range(9):
            diag[k, c] = inv[c]
        # eliminate node k from the next one's rows (a chain's last node: the hub's)
        following = hub if k % chain == chain - 1 else k + 1
        _matmul3(lower[k], diag[k], factor[k])
        _matmul3(factor[k], upper[k], tmp)
        for c in range(9):
            diag[following, c] -= tmp[c]
    if _inverse3(diag[hub], inv) == 0.0:
        return False
    for c in range(9):
        diag[hub, c] = inv[c]
    return True


@njit(inline="always", **JIT)
def _less_product(x, k, g, v, j):
    """x[k] -= g v[j] for 3-vectors at block k of x and j of v and the 3x3 block g."""
    p0, p1, p2 = v[3 * j], v[3 * j + 1], v[3 * j + 2]
    x[3 * k] -= g[0] * p0 + g[1] * p1 + g[2] * p2
    x[3 * k + 1] -= g[3] * p0 + g[4] * p1 + g[5] * p2
    x[3 * k + 2] -= g[6] * p0 + g[7] * p1 + g[8] * p2


@njit(**JIT)
def block_tridiagonal_apply(diag, upper, factor, rhs, x, chain=0):
    """Solve with the factors of ``block_tridiagonal_factor`` (forward, then back
    substitution); O(n). ``chain`` as given to the factorisation."""
    m = diag.shape[0]
    hub = m - 1
    if chain <= 0:
        chain = max(hub, 1)
    x[: 3 * m] = rhs[: 3 * m]
    for k in range(hub):
        _less_product(x, hub if k % chain == chain - 1 else k + 1, factor[k], x, k)
    for k in range(m - 1, -1, -1):
        if k < hub:
            _less_product(x, k, upper[k], x, hub if k % chain == chain - 1 else k + 1)
        d = diag[k]
        r0, r1, r2 = x[3 * k], x[3 * k + 1], x[3 * k + 2]
        x[3 * k] = d[0] * r0 + d[1] * r1 + d[2] * r2
        x[3 * k + 1] = d[3] * r0 + d[4] * r1 + d[5] * r2
        x[3 * k + 2] = d[6] * r0 + d[7] * r1 + d[8] * r2


@njit(**JIT)
def block_tridiagonal_solve(diag, upper, lower, rhs, x, chain=0):
    """Solve the block-tridiagonal (or, with ``chain``, star) system (see
    ``block_tridiagonal_factor``; ``diag`` is overwritten). Returns False when a pivot is
    singular."""
    factor = np.empty((max(diag.shape[0] - 1, 1), 9))
    if not block_tridiagonal_factor(diag, upper, lower, factor, chain):
        return False
    block_tridiagonal_apply(diag, upper, factor, rhs, x, chain)
    return True
