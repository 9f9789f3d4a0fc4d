"""Implicit steps of the planar rigid-link chain: its Newton system in maximal coordinates
(numba), and the rows shared with the 3D chain (``put_entry``, ``top_rows``). See
docs/architecture.md, "Rigid links in maximal coordinates"."""

import math

from numba import njit

from seacable.kernels.planar_chain import (
    _EX,
    _EZ,
    _PZ,
    _THDD,
    _VX,
    _VZ,
    BOTTOM_PINNED,
    OK,
    TOP_HEAVE,
    _body_now,
    _current,
    _node_force,
    solve,
)
from seacable.kernels.surface import segment_submersion
from seacable.kernels.timefn import JIT

# ---- implicit steps: the Newton system in maximal coordinates -----------------------------------
# In link angles the Newton matrix of an implicit step is dense (the inverse mass matrix is), so it
# is written in maximal coordinates instead: node k carries a block of NEWTON_BLOCK unknowns
# [s_k, A_k (2), lam_k (2)], with s_k the angular acceleration of link k - 1 (the link above node
# k; the heave acceleration for k = 0), A_k the node acceleration and lam_k the node force. Each
# link contributes its kinematic relation, its translational and its rotational Newton-Euler
# equation; every equation involves neighbouring blocks only, so the matrix is block-tridiagonal
# and one step costs O(n) (``numerics.implicit.block_lu_factor``).
NEWTON_BLOCK = 5


@njit(inline="always", **JIT)
def put_entry(diag, upper, lower, bs, rb, rl, cb, cl, value):
    """Add ``value`` at row ``rl`` of block row ``rb``, column ``cl`` of block column ``cb`` of a
    block-tridiagonal matrix of bs x bs row-major blocks (``upper[k]`` at (k, k+1), ``lower[k]``
    at (k+1, k)); shared by the rigid-link models' Newton systems."""
    k = rl * bs + cl
    if cb == rb:
        diag[rb, k] += value
    elif cb == rb + 1:
        upper[rb, k] += value
    else:
        lower[cb, k] += value


@njit(**JIT)
def top_rows(diag, bs, s_size, dims, heave, cm, spring, mass):
    """Rows of the top in block 0 of a rigid-link Newton system, whose unknowns are
    [s (s_size), A_0 (dims), lam_0 (dims)]: an imposed top holds s and A_0 (identity rows); a
    heaving structure keeps the unused entries of s and the horizontal axes at zero, ties the
    vertical acceleration to its heave acceleration s[0] (A_0z = cm s_0) and adds its equation
    M A_0z + (k cx + c cv) s_0 + lam_0z = ... (``spring`` = k cx + c cv)."""
    if not heave:
        for r in range(s_size + dims):
            diag[0, r * bs + r] = 1.0
        return
    row = 0
    for r in range(1, s_size):  # unused entries of s
        diag[0, row * bs + r] = 1.0
        row += 1
    for a in range(dims - 1):  # horizontal axes held
        diag[0, row * bs + s_size + a] = 1.0
        row += 1
    z = s_size + dims - 1
    diag[0, row * bs + z] = 1.0  # A_0z = heave acceleration
    diag[0, row * bs + 0] = -cm
    row += 1
    diag[0, row * bs + 0] = spring
    diag[0, row * bs + z] = mass
    diag[0, row * bs + z + dims] = 1.0


@njit(**JIT)
def _drag_jacobian(dn, dt, vn, vt, nx, nz, ex, ez):
    """Derivatives of the link drag F = fn n + ft e: (dF/dv as xx, xz, zx, zz; dF/dtheta)."""
    fn = -dn * abs(vn) * vn
    ft = -dt * abs(vt) * vt
    dfn = -2.0 * dn * abs(vn)
    dft = -2.0 * dt * abs(vt)
    jxx = dfn * nx * nx + dft * ex * ex
    jxz = dfn * nx * nz + dft * ex * ez
    jzz = dfn * nz * nz + dft * ez * ez
    # d n / d theta = -e, d e / d theta = n, d vn / d theta = -vt, d vt / d theta = vn
    ftx = -dfn * vt * nx - fn * ex + dft * vn * ex + ft * nx
    ftz = -dfn * vt * nz - fn * ez + dft * vn * ez + ft * nz
    return jxx, jxz, jzz, ftx, ftz


@njit(**JIT)
def _body_jacobian(p, w):
    """-dF/dV and -dF/dP of the bottom body's force (xx, xz, zz each): drag, ties and the
    free surface's heave stiffness."""
    n = p.n
    cxx, cxz, czz = p.tie_cx, 0.0, p.tie_cz
    _, _, drag, heave = _body_now(p, w[_PZ, n])
    if drag != 0.0:
        vrx = w[_VX, n] - _current(p.current_z, p.current_u, w[_PZ, n])
        vrz = w[_VZ, n]
        speed = math.sqrt(vrx * vrx + vrz * vrz)
        if speed > 0.0:
            cxx += drag * (speed + vrx * vrx / speed)
            cxz += drag * vrx * vrz / speed
            czz += drag * (speed + vrz * vrz / speed)
    return cxx, cxz, czz, p.tie_kx, 0.0, p.tie_kz + heave


@njit(**JIT)
def _link_rows(p_arrays, n, y, w, i, lam, cm, cx, cv, diag, upper, lower):
    """Matrix rows of link i: kinematics and rotation (block i + 1), translation (block i)."""
    length, mass, inertia, joint_k, joint_c, drag_n, drag_t, current_z, current_u = p_arrays
    li = length[i]
    om = y[n + 1 + i]
    ex, ez = w[_EX, i], w[_EZ, i]
    nx, nz = -ez, ex
    a = w[_THDD, i]  # the Jacobian of the reduced residual linearises about the dynamics
    b = i + 1
    # kinematics A_{i+1} - A_i - l (s n - om^2 e) = 0; d/dtheta = l (s e + om^2 n),
    # d/domega = 2 l om e
    kx = cm * li * nx - cx * li * (a * ex + om * om * nx) - cv * 2.0 * li * om * ex
    kz = cm * li * nz - cx * li * (a * ez + om * om * nz) - cv * 2.0 * li * om * ez
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 0, b, 1, 1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 1, b, 2, 1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 0, i, 1, -1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 1, i, 2, -1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 0, b, 0, -kx)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 1, b, 0, -kz)
    # rotation about the centre: J s + l/2 n.(lam_i + lam_{i+1}) - Q = 0
    k_here, c_here = joint_k[i], joint_c[i]
    k_next = joint_k[i + 1] if i + 1 < n else 0.0
    c_next = joint_c[i + 1] if i + 1 < n else 0.0
    sum_x = lam[0, i] + lam[0, i + 1]
    sum_z = lam[1, i] + lam[1, i + 1]
    geometric = -0.5 * li * (ex * sum_x + ez * sum_z)
    rot = cm * inertia[i] + cx * (geometric + k_here + k_next) + cv * (c_here + c_next)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, b, 0, rot)
    if i > 0:
        put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, i, 0, -(cx * k_here + cv * c_here))
    if i + 1 < n:
        put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, b + 1, 0, -(cx * k_next + cv * c_next))
    for blk in (i, b):
        put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, blk, 3, 0.5 * li * nx)
        put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, blk, 4, 0.5 * li * nz)
    # translation: m (A_i + A_{i+1}) / 2 - lam_i + lam_{i+1} - F = 0
    zc = 0.5 * (w[_PZ, i] + w[_PZ, b])
    vx = 0.5 * (w[_VX, i] + w[_VX, b]) - _current(current_z, current_u, zc)
    vz = 0.5 * (w[_VZ, i] + w[_VZ, b])
    vn = vx * nx + vz * nz
    vt = vx * ex + vz * ez
    wet, _, _ = segment_submersion(w[_PZ, i], w[_PZ, b])  # the drag of the submerged part
    jxx, jxz, jzz, ftx, ftz = _drag_jacobian(wet * drag_n[i], wet * drag_t[i], vn, vt, nx, nz,
                                             ex, ez)  # fmt: skip
    half_m = 0.5 * mass[i]
    r = 0.5 * cv / cm
    for blk in (i, b):
        put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, blk, 1, half_m - r * jxx)
        put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, blk, 2, -r * jxz)
        put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, blk, 1, -r * jxz)
        put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, blk, 2, half_m - r * jzz)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, i, 3, -1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, i, 4, -1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, b, 3, 1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, b, 4, 1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, b, 0, -cx * ftx)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, b, 0, -cx * ftz)


@njit(**JIT)
def _end_rows(p, w, cm, cx, cv, diag):
    """Rows of the top (block 0, rows 0-2) and bottom (block n, rows 3-4) conditions."""
    n = p.n
    heave = p.top_kind == TOP_HEAVE
    spring = p.top_stiffness * cx + p.top_damping * cv
    top_rows(diag, NEWTON_BLOCK, 1, 2, heave, cm, spring, p.top_mass)
    rx, rz = 3 * NEWTON_BLOCK, 4 * NEWTON_BLOCK
    if p.bottom_kind == BOTTOM_PINNED:
        om = p.stabilization_frequency
        c = 1.0 + (2.0 * om * cv + om * om * cx) / cm
        diag[n, rx + 1] += c
        diag[n, rz + 2] += c
    else:
        # m_b A_n - lam_n - F_body = 0
        dxx, dxz, dzz, kxx, kxz, kzz = _body_jacobian(p, w)
        mass, _, _, _ = _body_now(p, w[_PZ, n])
        diag[n, rx + 1] += mass + (cv * dxx + cx * kxx) / cm
        diag[n, rx + 2] += (cv * dxz + cx * kxz) / cm
        diag[n, rz + 1] += (cv * dxz + cx * kxz) / cm
        diag[n, rz + 2] += mass + (cv * dzz + cx * kzz) / cm
        diag[n, rx + 3] -= 1.0
        diag[n, rz + 4] -= 1.0


@njit(**JIT)
def newton_system(t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix):
    """Residual (and, when ``matrix``, the block-tridiagonal matrix) of an implicit step's
    Newton iteration at the alpha point (t, y) with accelerations ``a_alpha``; see
    ``numerics.implicit`` for cm, cx, cv. Returns the status.

    The residual is built from the mismatch g = a_alpha - f(t, y) between the iterate and the
    O(n) forward dynamics: the node accelerations the iterate implies differ from the dynamic
    ones by E (E_{k+1} = E_k + l n g), so the translational rows get m E at the link centre,
    the rotational rows J g and the bottom body m_b E_n; a converged iterate (g = 0) zeroes
    every row whatever approximation the matrix makes. The matrix is the exact linearisation
    of the Newton-Euler equations except that node positions and velocities follow the node
    accelerations as (cx / cm) dA and (cv / cm) dA (Newmark's update applied to the nodes),
    which drops terms of order h^2 omega^2 relative to the kept ones."""
    n = p.n
    pinned = p.bottom_kind == BOTTOM_PINNED
    status, top_acc, lx, lz = solve(t, y, p, w)
    if status != OK:
        return status
    bs = NEWTON_BLOCK
    for k in range(res.shape[0]):
        res[k] = 0.0
    # the node forces of the dynamic solution, kept in the scratch rows of ydot
    lam = ydot[: 2 * (n + 1)].reshape((2, n + 1))
    for k in range(n + 1):
        lam[0, k], lam[1, k] = _node_force(w, k, lx, lz, pinned)
    ex_, ez_ = 0.0, 0.0
    if p.top_kind == TOP_HEAVE:
        ez_ = a_alpha[n] - top_acc
        res[2] = p.top_mass * ez_
    for i in range(n):
        g = a_alpha[i] - w[_THDD, i]
        li = p.length[i]
        nx, nz = -w[_EZ, i], w[_EX, i]
        ex_next = ex_ + li * nx * g
        ez_next = ez_ + li * nz * g
        res[bs * i + 3] = 0.5 * p.mass[i] * (ex_ + ex_next)
        res[bs * i + 4] = 0.5 * p.mass[i] * (ez_ + ez_next)
        res[bs * (i + 1) + 2] = p.inertia[i] * g
        ex_, ez_ = ex_next, ez_next
    scale = 1.0 if pinned else _body_now(p, w[_PZ, n])[0]
    res[bs * n + 3] = scale * ex_
    res[bs * n + 4] = scale * ez_
    if not matrix:
        return OK
    diag[:, :] = 0.0
    upper[:, :] = 0.0
    lower[:, :] = 0.0
    arrays = (
        p.length, p.mass, p.inertia, p.joint_stiffness, p.joint_damping, p.drag_normal,
        p.drag_tangential, p.current_z, p.current_u,
    )  # fmt: skip
    for i in range(n):
        _link_rows(arrays, n, y, w, i, lam, cm, cx, cv, diag, upper, lower)
    _end_rows(p, w, cm, cx, cv, diag)
    return OK


@njit(**JIT)
def newton_correct(length, da, a1):
    """Subtract the Newton correction (the s entries of the solver's blocks) from the
    accelerations; returns the largest as a node acceleration (angle correction x length)."""
    n = length.shape[0]
    bs = NEWTON_BLOCK
    largest = abs(da[0])
    a1[n] -= da[0]
    for i in range(n):
        d = da[bs * (i + 1)]
        a1[i] -= d
        largest = max(largest, abs(d) * length[i])
    return largest
