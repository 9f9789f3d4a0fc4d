"""Three-dimensional chain of rigid cylindrical segments: the articulated sweep of the system's
3D rigid lines (``lines.rigid_segments``, ``system.rigid``; numba).

Frame: x, y horizontal, z up. Segment ``i`` joins node ``i`` (top) to node ``i + 1``; its
orientation is the unit **director** ``e_i`` (top -> bottom) and its rate ``u_i = de_i/dt`` with
``u_i . e_i = 0``. Directors have no singular direction (unlike the two Euler angles of
Jacquot & Marichal, singular along one axis); rotation about the segment's own axis carries no
inertia or stiffness for an axisymmetric slender cylinder and is not a degree of freedom.

Method: the articulated recursion of ``planar_chain`` in 3D. ``lam_k = M_k A_k + b_k`` with a
symmetric 3x3 ``M_k``; each segment solves a 2x2 system in the plane normal to its director
(any orthonormal basis of that plane: it is a computation device, not a state). A segment's
translational inertia is ``m I + m_a (I - e e^T)`` (added mass normal to the axis only, none
axially) and its rotational inertia about the centre ``m l^2/12 + m_a l^2/12``. Point bodies at
nodes (floats, clump weights) join the articulated inertia of the part below them.
"""

import math

import numpy as np
from numba import njit

from seacable.kernels.chain3d_layout import (
    _A,
    _B,
    _E,
    _F,
    _H,
    _ID11,
    _ID12,
    _ID22,
    _M,
    _P,
    _RS,
    _S,
    _SA,
    _SJ,
    _T1,
    _T2,
    _TQ,
    _U,
    _V,
    _W,
    N_WORK_ROWS,
    _current,
)
from seacable.kernels.jit import JIT, inner

# re-exported: the chain's other kernels and the lumped-mass kernel read them as ``c3.X``
__all__ = [
    "N_WORK_ROWS",
    "_A",
    "_B",
    "_E",
    "_F",
    "_H",
    "_ID11",
    "_ID12",
    "_ID22",
    "_M",
    "_P",
    "_RS",
    "_S",
    "_SA",
    "_SJ",
    "_T1",
    "_T2",
    "_TQ",
    "_U",
    "_V",
    "_W",
    "_current",
]


@inner
def _basis(ex, ey, ez):
    """Orthonormal t1, t2 normal to e (t1 built from the axis least aligned with e)."""
    ax, ay, az = abs(ex), abs(ey), abs(ez)
    if ax <= ay and ax <= az:
        t1x, t1y, t1z = 0.0, ez, -ey  # -(x_hat x e): any vector normal to e will do
    elif ay <= az:
        t1x, t1y, t1z = -ez, 0.0, ex
    else:
        t1x, t1y, t1z = ey, -ex, 0.0
    norm = 1.0 / math.sqrt(t1x * t1x + t1y * t1y + t1z * t1z)
    t1x *= norm
    t1y *= norm
    t1z *= norm
    t2x = ey * t1z - ez * t1y
    t2y = ez * t1x - ex * t1z
    t2z = ex * t1y - ey * t1x
    return t1x, t1y, t1z, t2x, t2y, t2z


@inner
def _store_node(w, k, m, b, s):
    for r in range(6):
        w[_M + r, k] = m[r]
    for r in range(3):
        w[_B + r, k] = b[r]
    for r in range(9):
        w[_S + r, k] = s[r]


@njit(inline="always", **JIT)
def _sym_mul(m, x0, x1, x2):
    """M x for M stored as (11, 12, 13, 22, 23, 33)."""
    return (
        m[0] * x0 + m[1] * x1 + m[2] * x2,
        m[1] * x0 + m[3] * x1 + m[4] * x2,
        m[2] * x0 + m[4] * x1 + m[5] * x2,
    )


@njit(inline="always", **JIT)
def segment_back(i, li, mi, w, m, b, s, pinned):
    """One segment of the backward sweep: from the articulated inertia ``m`` (symmetric 3x3 as
    (11, 12, 13, 22, 23, 33)), bias ``b`` and, when ``pinned``, the reaction map ``s`` (3x3) at
    the segment's lower node to those at its upper node, in place; the segment's rows _T1, _T2,
    _ID, _H, _W (and _RS) of column i for the forward sweep. Reads rows _E, _U, _F, _TQ, _SA,
    _SJ of column i; ``li``, ``mi`` its length and structural mass."""
    ma = w[_SA, i]
    mt = mi + ma
    ex, ey, ez = w[_E, i], w[_E + 1, i], w[_E + 2, i]
    u2 = w[_U, i] ** 2 + w[_U + 1, i] ** 2 + w[_U + 2, i] ** 2
    t1x, t1y, t1z, t2x, t2y, t2z = _basis(ex, ey, ez)
    a1x, a1y, a1z = _sym_mul(m, t1x, t1y, t1z)
    a2x, a2y, a2z = _sym_mul(m, t2x, t2y, t2z)
    mex, mey, mez = _sym_mul(m, ex, ey, ez)
    base = w[_SJ, i] + 0.25 * mt * li * li
    d11 = base + li * li * (t1x * a1x + t1y * a1y + t1z * a1z)
    d12 = li * li * (t1x * a2x + t1y * a2y + t1z * a2z)
    d22 = base + li * li * (t2x * a2x + t2y * a2y + t2z * a2z)
    inv_det = 1.0 / (d11 * d22 - d12 * d12)
    i11, i12, i22 = d22 * inv_det, -d12 * inv_det, d11 * inv_det
    h1x, h1y, h1z = (
        li * (0.5 * mt * t1x + a1x),
        li * (0.5 * mt * t1y + a1y),
        li * (0.5 * mt * t1z + a1z),
    )
    h2x, h2y, h2z = (
        li * (0.5 * mt * t2x + a2x),
        li * (0.5 * mt * t2y + a2y),
        li * (0.5 * mt * t2z + a2z),
    )
    # generalised director force G = -e x torque
    tqx, tqy, tqz = w[_TQ, i], w[_TQ + 1, i], w[_TQ + 2, i]
    gx, gy, gz = -(ey * tqz - ez * tqy), -(ez * tqx - ex * tqz), -(ex * tqy - ey * tqx)
    qx = -2.0 * li * u2 * mex + 2.0 * b[0] - w[_F, i]
    qy = -2.0 * li * u2 * mey + 2.0 * b[1] - w[_F + 1, i]
    qz = -2.0 * li * u2 * mez + 2.0 * b[2] - w[_F + 2, i]
    w1 = t1x * gx + t1y * gy + t1z * gz - 0.5 * li * (t1x * qx + t1y * qy + t1z * qz)
    w2 = t2x * gx + t2y * gy + t2z * gz - 0.5 * li * (t2x * qx + t2y * qy + t2z * qz)
    k1x, k1y, k1z = i11 * h1x + i12 * h2x, i11 * h1y + i12 * h2y, i11 * h1z + i12 * h2z
    k2x, k2y, k2z = i12 * h1x + i22 * h2x, i12 * h1y + i22 * h2y, i12 * h1z + i22 * h2z
    if pinned:
        # rows of dw/dL = -l T^T S
        r1 = np.empty(3)
        r2 = np.empty(3)
        for c in range(3):
            r1[c] = -li * (t1x * s[c] + t1y * s[3 + c] + t1z * s[6 + c])
            r2[c] = -li * (t2x * s[c] + t2y * s[3 + c] + t2z * s[6 + c])
            w[_RS + c, i] = r1[c]
            w[_RS + 3 + c, i] = r2[c]
        kk = (k1x, k1y, k1z, k2x, k2y, k2z)
        for r in range(3):
            for c in range(3):
                s[3 * r + c] += kk[r] * r1[c] + kk[3 + r] * r2[c]
    w[_T1, i], w[_T1 + 1, i], w[_T1 + 2, i] = t1x, t1y, t1z
    w[_T2, i], w[_T2 + 1, i], w[_T2 + 2, i] = t2x, t2y, t2z
    w[_ID11, i], w[_ID12, i], w[_ID22, i] = i11, i12, i22
    w[_H, i], w[_H + 1, i] = h1x, h2x
    w[_H + 2, i], w[_H + 3, i] = h1y, h2y
    w[_H + 4, i], w[_H + 5, i] = h1z, h2z
    w[_W, i], w[_W + 1, i] = w1, w2
    # b <- b - F + K w - l u^2 (m/2 e + M e)
    b[0] += -w[_F, i] + k1x * w1 + k2x * w2 - li * u2 * (0.5 * mi * ex + mex)
    b[1] += -w[_F + 1, i] + k1y * w1 + k2y * w2 - li * u2 * (0.5 * mi * ey + mey)
    b[2] += -w[_F + 2, i] + k1z * w1 + k2z * w2 - li * u2 * (0.5 * mi * ez + mez)
    # M <- m_t I - m_a e e^T + M - K H^T
    m[0] += mt - ma * ex * ex - (k1x * h1x + k2x * h2x)
    m[1] += -ma * ex * ey - (k1x * h1y + k2x * h2y)
    m[2] += -ma * ex * ez - (k1x * h1z + k2x * h2z)
    m[3] += mt - ma * ey * ey - (k1y * h1y + k2y * h2y)
    m[4] += -ma * ey * ez - (k1y * h1z + k2y * h2z)
    m[5] += mt - ma * ez * ez - (k1z * h1z + k2z * h2z)


@njit(inline="always", **JIT)
def adjugate3(a):
    """The determinant and the adjugate (9 floats, row by row: a^-1 = adjugate / det) of the
    3x3 matrix ``a`` (row-major, 9 values), by cofactors."""
    c00 = a[4] * a[8] - a[5] * a[7]
    c01 = a[5] * a[6] - a[3] * a[8]
    c02 = a[3] * a[7] - a[4] * a[6]
    det = a[0] * c00 + a[1] * c01 + a[2] * c02
    adjugate = (
        c00, a[2] * a[7] - a[1] * a[8], a[1] * a[5] - a[2] * a[4],
        c01, a[0] * a[8] - a[2] * a[6], a[2] * a[3] - a[0] * a[5],
        c02, a[1] * a[6] - a[0] * a[7], a[0] * a[4] - a[1] * a[3],
    )  # fmt: skip
    return det, adjugate


@inner
def _solve3(a, r):
    """Solve the 3x3 system a x = r (a row-major, 9 values); returns x and the determinant."""
    det, m = adjugate3(a)
    x = np.zeros(3)
    if det == 0.0:
        return x, det
    inv = 1.0 / det
    x[0] = (m[0] * r[0] + m[1] * r[1] + m[2] * r[2]) * inv
    x[1] = (m[3] * r[0] + m[4] * r[1] + m[5] * r[2]) * inv
    x[2] = (m[6] * r[0] + m[7] * r[1] + m[8] * r[2]) * inv
    return x, det


@inner
def project_directors(y, n, q, v):
    """Unit directors at ``y[q + 3 i]``, their rates at ``y[v + 3 i]`` made normal to them."""
    for i in range(n):
        ex, ey, ez = y[q + 3 * i], y[q + 3 * i + 1], y[q + 3 * i + 2]
        inv = 1.0 / math.sqrt(ex * ex + ey * ey + ez * ez)
        ex *= inv
        ey *= inv
        ez *= inv
        y[q + 3 * i], y[q + 3 * i + 1], y[q + 3 * i + 2] = ex, ey, ez
        dot = y[v + 3 * i] * ex + y[v + 3 * i + 1] * ey + y[v + 3 * i + 2] * ez
        y[v + 3 * i] -= dot * ex
        y[v + 3 * i + 1] -= dot * ey
        y[v + 3 * i + 2] -= dot * ez


@inner
def _node_force(w, k, reaction, pinned):
    m = w[_M : _M + 6, k]
    f = np.empty(3)
    ax, ay, az = w[_A, k], w[_A + 1, k], w[_A + 2, k]
    mx, my, mz = _sym_mul(m, ax, ay, az)
    f[0] = mx + w[_B, k]
    f[1] = my + w[_B + 1, k]
    f[2] = mz + w[_B + 2, k]
    if pinned:
        for r in range(3):
            for c in range(3):
                f[r] += w[_S + 3 * r + c, k] * reaction[c]
    return f
