"""Compiled equations of motion of a body: its 6x6 mass matrix in the earth frame at its
reference point, the velocity-dependent (gyroscopic and centripetal) terms, the mass and force
a line's end gives it at one of its points, and the solve for the accelerations of its free
degrees of freedom.

With r = R r_G the arm of the centre of gravity, [r] the cross-product matrix and I_G the inertia
about G in the earth frame (R I_body R^T):

    [ m I      -m [r]          ] [a    ]   [F  ]   [m w x (w x r)                    ]
    [ m [r]    I_G - m [r][r]  ] [alpha] = [M_O] - [w x (I_G w) + m r x (w x (w x r))]

plus the added-mass matrix A (body frame at the reference point) turned into the earth frame,
A_e = diag(R, R) A diag(R, R)^T, and its velocity terms, in one of two forms (``coriolis``):

- ``RIGID_BODY`` (the ship-simulator document's): the body-frame equation
  (M + A) nu' = C_RB(nu) nu + F with the Coriolis matrix of the rigid-body mass only: the added
  mass acts on the body-frame rate of the body-frame velocity nu = (u, w), nu' = (R^T a - w x u,
  R^T alpha), i.e. A_e (a, alpha) - A_e (w x v, 0) in the earth frame. A ship turning steadily
  (nu constant) feels no added inertia; the document reports this closer to trials.
- ``EXACT`` (Kirchhoff's equations): the fluid's impulse (P, H) = A_e (v, w) also turns with
  the body, adding (w x P, w x H + v x P): the kinetic energy 1/2 (v, w)^T (M + A_e) (v, w) of a
  body moving freely is conserved, and a slender body feels Munk's moment.

A held degree of freedom has its row replaced by a_i = 0.
"""

import numpy as np
from numba import njit

from seacable.bodies.kinematics import has_mass
from seacable.kernels import chain3d as c3
from seacable.kernels import surface
from seacable.kernels.jit import JIT, inner

RIGID_BODY, EXACT = 0, 1  # the added mass's velocity terms (module docstring)


@inner
def rigid_mass(mass, cog, inertia, added, rot, vel, omega, scale_added, coriolis, m6, bias):
    """Fill ``m6`` (6, 6) and ``bias`` (6) of one body (``cog`` body frame, ``inertia`` about
    G body frame, ``added`` 6x6 body frame at the reference point times ``scale_added``, its
    velocity terms in the form ``coriolis``)."""
    rx = rot[0, 0] * cog[0] + rot[0, 1] * cog[1] + rot[0, 2] * cog[2]
    ry = rot[1, 0] * cog[0] + rot[1, 1] * cog[1] + rot[1, 2] * cog[2]
    rz = rot[2, 0] * cog[0] + rot[2, 1] * cog[1] + rot[2, 2] * cog[2]
    ig = np.zeros((3, 3))  # R I_body R^T
    for i in range(3):
        for j in range(3):
            total = 0.0
            for k in range(3):
                for m in range(3):
                    total += rot[i, k] * inertia[k, m] * rot[j, m]
            ig[i, j] = total
    cr = ((0.0, -rz, ry), (rz, 0.0, -rx), (-ry, rx, 0.0))
    for i in range(6):
        for j in range(6):
            m6[i, j] = 0.0
    for i in range(3):
        m6[i, i] = mass
        for j in range(3):
            m6[i, 3 + j] = -mass * cr[i][j]
            m6[3 + i, j] = mass * cr[i][j]
            rr = 0.0
            for k in range(3):
                rr += cr[i][k] * cr[k][j]
            m6[3 + i, 3 + j] = ig[i, j] - mass * rr
    if scale_added != 0.0:
        _add_turned(added, rot, scale_added, m6)
    wx, wy, wz = omega[0], omega[1], omega[2]
    # w x r, then w x (w x r)
    ax, ay, az = wy * rz - wz * ry, wz * rx - wx * rz, wx * ry - wy * rx
    cx, cy, cz = wy * az - wz * ay, wz * ax - wx * az, wx * ay - wy * ax
    bias[0], bias[1], bias[2] = mass * cx, mass * cy, mass * cz
    hx = ig[0, 0] * wx + ig[0, 1] * wy + ig[0, 2] * wz
    hy = ig[1, 0] * wx + ig[1, 1] * wy + ig[1, 2] * wz
    hz = ig[2, 0] * wx + ig[2, 1] * wy + ig[2, 2] * wz
    bias[3] = wy * hz - wz * hy + mass * (ry * cz - rz * cy)
    bias[4] = wz * hx - wx * hz + mass * (rz * cx - rx * cz)
    bias[5] = wx * hy - wy * hx + mass * (rx * cy - ry * cx)
    if scale_added != 0.0 and (wx != 0.0 or wy != 0.0 or wz != 0.0):
        _added_bias(added, rot, vel, omega, scale_added, coriolis, bias)


@njit(inline="always", **JIT)
def _dot(added, i, v):
    """Row i of ``added`` times the 6-vector v."""
    return (added[i, 0] * v[0] + added[i, 1] * v[1] + added[i, 2] * v[2] + added[i, 3] * v[3]
            + added[i, 4] * v[4] + added[i, 5] * v[5])  # fmt: skip


@inner
def _added_bias(added, rot, vel, omega, scale, coriolis, bias):
    """The added mass's velocity terms (module docstring), computed in the body frame and
    turned into the earth frame: -A (w x u, 0), and for EXACT (w x p, w x h + u x p) with
    (p, h) = A (u, w)."""
    u = (rot[0, 0] * vel[0] + rot[1, 0] * vel[1] + rot[2, 0] * vel[2],
         rot[0, 1] * vel[0] + rot[1, 1] * vel[1] + rot[2, 1] * vel[2],
         rot[0, 2] * vel[0] + rot[1, 2] * vel[1] + rot[2, 2] * vel[2])  # fmt: skip
    w = (rot[0, 0] * omega[0] + rot[1, 0] * omega[1] + rot[2, 0] * omega[2],
         rot[0, 1] * omega[0] + rot[1, 1] * omega[1] + rot[2, 1] * omega[2],
         rot[0, 2] * omega[0] + rot[1, 2] * omega[1] + rot[2, 2] * omega[2])  # fmt: skip
    wu = (w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2], w[0] * u[1] - w[1] * u[0], 0.0,
          0.0, 0.0)  # fmt: skip
    out = (-_dot(added, 0, wu), -_dot(added, 1, wu), -_dot(added, 2, wu), -_dot(added, 3, wu),
           -_dot(added, 4, wu), -_dot(added, 5, wu))  # fmt: skip
    if coriolis == EXACT:
        nu = (u[0], u[1], u[2], w[0], w[1], w[2])
        p = (_dot(added, 0, nu), _dot(added, 1, nu), _dot(added, 2, nu))
        h = (_dot(added, 3, nu), _dot(added, 4, nu), _dot(added, 5, nu))
        out = (
            out[0] + w[1] * p[2] - w[2] * p[1],
            out[1] + w[2] * p[0] - w[0] * p[2],
            out[2] + w[0] * p[1] - w[1] * p[0],
            out[3] + w[1] * h[2] - w[2] * h[1] + u[1] * p[2] - u[2] * p[1],
            out[4] + w[2] * h[0] - w[0] * h[2] + u[2] * p[0] - u[0] * p[2],
            out[5] + w[0] * h[1] - w[1] * h[0] + u[0] * p[1] - u[1] * p[0],
        )
    for block in range(2):
        k = 3 * block
        for i in range(3):
            bias[k + i] += scale * (rot[i, 0] * out[k] + rot[i, 1] * out[k + 1]
                                    + rot[i, 2] * out[k + 2])  # fmt: skip


@inner
def _add_turned(added, rot, scale, m6):
    """m6 += scale diag(R, R) A diag(R, R)^T, block by block (nothing when A is zero)."""
    empty = True
    for i in range(6):
        for j in range(6):
            if added[i, j] != 0.0:
                empty = False
    if empty:
        return
    for bi in range(2):
        for bj in range(2):
            for i in range(3):
                for j in range(3):
                    total = 0.0
                    for k in range(3):
                        row = 0.0
                        for m in range(3):
                            row += added[3 * bi + k, 3 * bj + m] * rot[j, m]
                        total += rot[i, k] * row
                    m6[3 * bi + i, 3 * bj + j] += scale * total


@inner
def add_point_mass(m3, arm, omega, force, m6, rhs):
    """A mass matrix ``m3`` (3x3, row-major 9) rigidly carried at ``arm`` (earth frame) from the
    reference point and loaded by ``force`` besides its carrier (a line's end node): adds
    Phi^T m3 Phi to ``m6`` and Phi^T (force - m3 w x (w x arm)) to ``rhs``, Phi = [I, -[arm]]."""
    rx, ry, rz = arm[0], arm[1], arm[2]
    if rx == 0.0 and ry == 0.0 and rz == 0.0:  # at the reference point: Phi = [I, 0]
        for i in range(3):
            rhs[i] += force[i]
            for j in range(3):
                m6[i, j] += m3[3 * i + j]
        return
    wx, wy, wz = omega[0], omega[1], omega[2]
    ax, ay, az = wy * rz - wz * ry, wz * rx - wx * rz, wx * ry - wy * rx
    c = (wy * az - wz * ay, wz * ax - wx * az, wx * ay - wy * ax)
    f = (
        force[0] - (m3[0] * c[0] + m3[1] * c[1] + m3[2] * c[2]),
        force[1] - (m3[3] * c[0] + m3[4] * c[1] + m3[5] * c[2]),
        force[2] - (m3[6] * c[0] + m3[7] * c[1] + m3[8] * c[2]),
    )
    add_force(arm, f[0], f[1], f[2], rhs)
    for i in range(6):
        for j in range(6):
            total = 0.0
            for k in range(3):
                for m in range(3):
                    total += _phi(arm, k, i) * m3[3 * k + m] * _phi(arm, m, j)
            m6[i, j] += total


@njit(inline="always", **JIT)
def _phi(arm, k, j):
    """Phi[k, j] of Phi = [I, -[arm]] (3x6): a point's acceleration at ``arm`` from its body's
    (a, alpha), w x (w x arm) aside."""
    if j < 3:
        return 1.0 if k == j else 0.0
    c = j - 3
    if k == c:
        return 0.0
    if k == 0:
        return arm[2] if c == 1 else -arm[1]
    if k == 1:
        return -arm[2] if c == 0 else arm[0]
    return arm[1] if c == 0 else -arm[0]


@njit(inline="always", **JIT)
def add_phi_t(m3, arm, sign, block):
    """``block`` (6x3) += sign Phi^T m3: a force m3 x at the point ``arm`` on its body's six
    equations (system.rigid.solve_groups)."""
    for i in range(6):
        for c in range(3):
            total = 0.0
            for k in range(3):
                total += _phi(arm, k, i) * m3[3 * k + c]
            block[i, c] += sign * total


@njit(inline="always", **JIT)
def add_m_phi(m3, arm, sign, block):
    """``block`` (3x6) += sign m3 Phi: m3 times the acceleration of the point ``arm`` in its
    body's accelerations (system.rigid.solve_groups)."""
    for r in range(3):
        for j in range(6):
            total = 0.0
            for k in range(3):
                total += m3[3 * r + k] * _phi(arm, k, j)
            block[r, j] += sign * total


@njit(inline="always", **JIT)
def add_force(arm, fx, fy, fz, rhs):
    """Add a force (earth frame) acting at ``arm`` from the reference point: the force, and
    its moment arm x f about the reference point."""
    rhs[0] += fx
    rhs[1] += fy
    rhs[2] += fz
    rhs[3] += arm[1] * fz - arm[2] * fy
    rhs[4] += arm[2] * fx - arm[0] * fz
    rhs[5] += arm[0] * fy - arm[1] * fx


@njit(inline="always", **JIT)
def _single(free):
    """The one free degree of freedom, or -1 when there are several (or none)."""
    only = -1
    for i in range(6):
        if free[i] != 0.0:
            if only >= 0:
                return -1
            only = i
    return only


@njit(inline="always", **JIT)
def _held_rows(m6, rhs, free):
    """Copies of M and rhs with every held degree of freedom's row a_i = 0."""
    a = m6.copy()
    b = rhs.copy()
    for i in range(6):
        if free[i] == 0.0:
            for j in range(6):
                a[i, j] = 0.0
            a[i, i] = 1.0
            b[i] = 0.0
    return a, b


@njit(inline="always", **JIT)
def _solve_one(m6, rhs, only, out):
    for i in range(6):
        out[i] = 0.0
    out[only] = rhs[only] / m6[only, only]
    return m6[only, only] != 0.0


@inner
def solve_free(m6, rhs, free, out):
    """Accelerations ``out`` (6) of M a = rhs with a_i = 0 on every held degree of freedom
    (``free[i] == 0``): Gaussian elimination with partial pivoting (one free degree of freedom:
    a division). False when singular."""
    only = _single(free)
    if only >= 0:
        return _solve_one(m6, rhs, only, out)
    a, b = _held_rows(m6, rhs, free)
    return gauss(a, b, out)


@njit(inline="always", **JIT)
def gauss(a, b, out):
    """``out`` of a x = b (n x n, overwritten): Gaussian elimination with partial pivoting.
    False when singular."""
    n = b.shape[0]
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(a[i, k]) > abs(a[p, k]):
                p = i
        if a[p, k] == 0.0:
            return False
        if p != k:
            for j in range(n):
                a[k, j], a[p, j] = a[p, j], a[k, j]
            b[k], b[p] = b[p], b[k]
        for i in range(k + 1, n):
            factor = a[i, k] / a[k, k]
            if factor != 0.0:
                for j in range(k, n):
                    a[i, j] -= factor * a[k, j]
                b[i] -= factor * b[k]
    for i in range(n - 1, -1, -1):
        total = b[i]
        for j in range(i + 1, n):
            total -= a[i, j] * out[j]
        out[i] = total / a[i, i]
    return True


@njit(inline="always", **JIT)
def body_rates(y, q, v, rigid_body, acc, ydot):
    """A free body's rates into ``ydot``: its position's (its velocity), its velocity's (its
    acceleration ``acc``, 6) and, of a rigid body, its quaternion's and angular velocity's."""
    for c in range(3):
        ydot[q + c] = y[v + c]
        ydot[v + c] = acc[c]
    if rigid_body == 1:
        wx, wy, wz = y[v + 3], y[v + 4], y[v + 5]
        qw, qx, qy, qz = y[q + 3], y[q + 4], y[q + 5], y[q + 6]
        # dq/dt = 1/2 (0, w) q
        ydot[q + 3] = 0.5 * (-wx * qx - wy * qy - wz * qz)
        ydot[q + 4] = 0.5 * (wx * qw + wy * qz - wz * qy)
        ydot[q + 5] = 0.5 * (wy * qw + wz * qx - wx * qz)
        ydot[q + 6] = 0.5 * (wz * qw + wx * qy - wy * qx)
        for c in range(3):
            ydot[v + 3 + c] = acc[3 + c]


@inner
def body_masses(p_kind, p_rigid, mass, cog, inertia, added, coriolis, shape, fraction, pos,
                 rot, vel, omega, current_z, current_u, current_v, out_mass, out_bias):  # fmt: skip
    """Each body's mass matrix and velocity terms; the added mass's act on the velocity
    relative to the water at the reference point (the current's there): a hull's added mass
    is the water's, so that a body carried by a steady current feels what it feels at rest in
    still water (the rigid-body terms do not depend on the translation's velocity)."""
    relative = np.empty(3)  # an array, as energy.py's call gives: one compiled signature
    for b in range(p_kind.shape[0]):
        if not has_mass(p_kind[b]):
            continue
        # a shaped body's added mass follows its submerged fraction
        scale = fraction[b] if shape[b, 0] != surface.POINT else 1.0
        cx, cy = c3._current(current_z, current_u, current_v, pos[b, 2])
        relative[0], relative[1], relative[2] = vel[b, 0] - cx, vel[b, 1] - cy, vel[b, 2]
        rigid_mass(
            mass[b],
            cog[b],
            inertia[b],
            added[b],
            rot[b],
            relative,
            omega[b],
            scale,
            coriolis[b],
            out_mass[b],
            out_bias[b],
        )
