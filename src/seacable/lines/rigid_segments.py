"""Compiled pieces of the rigid-segment lines of a system (the 3D chain of ``kernels.chain3d``,
through its shared ``segment_loads`` and ``segment_back``): one line's backward sweep, the map
of its tip's acceleration, its closure on a held tip, its forward sweep and its node forces.

A line of n rigid segments has nodes 0..n; node 0 follows the point ``from`` of its base body;
its states are the segments' unit directors ``e_i`` at ``y[q + 3 i]`` and their rates
``u_i = de_i/dt`` at ``y[v + 3 i]``. Its tip (node n) either carries a point body absorbed into
the line (the body's motion is the tip's; its mass and loads start the backward sweep) or is
held on a fixed or imposed body's point. On a held axis the tip's acceleration is the
Baumgarte-stabilised target's and the holding force L is an unknown of the sweep.

Articulated form (Featherstone's articulated-body inertia, 3D translational): the force the
part above node k exerts on node k and everything below it is ``lam_k = M_k A_k + b_k + S_k L``
(rows _M, _B, _S of column k), A_k node k's acceleration. The body at the base receives
-lam_0: the mass M_0 at its point and the load -b_0 (``bodies.dynamics.add_point_mass``), with
L eliminated first on a held tip (``closure``): the tip's acceleration is affine in the base's,
A_n = ac + G A_0 + al L (``tip_map``), so L = l0 + la A_0 and lam_0 = (M_0 + S_0 la) A_0 +
(b_0 + S_0 l0). Derivation: docs/rigid_segment_lines.md.
"""

from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels.chain3d_layout import (
    _A,
    _E,
    _EDD,
    _F,
    _H,
    _ID11,
    _ID12,
    _ID22,
    _RS,
    _T1,
    _T2,
    _TQ,
    _U,
    _W,
)
from seacable.kernels.jit import JIT, inner


@njit(**JIT)
def backward(n, length, mass, w, m, b, s, pinned):
    """The backward sweep from the tip's articulated inertia ``m`` (6: 11 12 13 22 23 33), bias
    ``b`` (3) and reaction map ``s`` (9; the identity on a held tip) to node 0's, in place; rows
    _M, _B, _S stored at every node."""
    c3._store_node(w, n, m, b, s)
    for i in range(n - 1, -1, -1):
        c3.segment_back(i, length[i], mass[i], w, m, b, s, pinned)
        c3._store_node(w, i, m, b, s)


@njit(inline="always", **JIT)
def _director_acceleration(w, i, r1, r2):
    """x = D^-1 (r1, r2), the director acceleration's components on (t1, t2)."""
    x1 = w[_ID11, i] * r1 + w[_ID12, i] * r2
    x2 = w[_ID12, i] * r1 + w[_ID22, i] * r2
    return x1, x2


@njit(**JIT)
def tip_map(n, length, w, ac, ga, al):
    """The tip's acceleration as A_n = ac + ga A_0 + al L (``ga``, ``al`` 3x3 row-major): the
    forward sweep run on the constant part and on each column of A_0 and of L."""
    for k in range(3):
        ac[k] = 0.0
        for c in range(3):
            ga[3 * k + c] = 1.0 if k == c else 0.0
            al[3 * k + c] = 0.0
    for i in range(n):
        li = length[i]
        u2 = w[_U, i] ** 2 + w[_U + 1, i] ** 2 + w[_U + 2, i] ** 2
        h1x, h1y, h1z = w[_H, i], w[_H + 2, i], w[_H + 4, i]
        h2x, h2y, h2z = w[_H + 1, i], w[_H + 3, i], w[_H + 5, i]
        t1x, t1y, t1z = w[_T1, i], w[_T1 + 1, i], w[_T1 + 2, i]
        t2x, t2y, t2z = w[_T2, i], w[_T2 + 1, i], w[_T2 + 2, i]
        r1 = w[_W, i] - (h1x * ac[0] + h1y * ac[1] + h1z * ac[2])
        r2 = w[_W + 1, i] - (h2x * ac[0] + h2y * ac[1] + h2z * ac[2])
        x1, x2 = _director_acceleration(w, i, r1, r2)
        ac[0] += li * (x1 * t1x + x2 * t2x - u2 * w[_E, i])
        ac[1] += li * (x1 * t1y + x2 * t2y - u2 * w[_E + 1, i])
        ac[2] += li * (x1 * t1z + x2 * t2z - u2 * w[_E + 2, i])
        for c in range(3):
            g0, g1, g2 = ga[c], ga[3 + c], ga[6 + c]
            x1, x2 = _director_acceleration(
                w, i, -(h1x * g0 + h1y * g1 + h1z * g2), -(h2x * g0 + h2y * g1 + h2z * g2)
            )
            ga[c] += li * (x1 * t1x + x2 * t2x)
            ga[3 + c] += li * (x1 * t1y + x2 * t2y)
            ga[6 + c] += li * (x1 * t1z + x2 * t2z)
            a0, a1, a2 = al[c], al[3 + c], al[6 + c]
            x1, x2 = _director_acceleration(
                w, i,
                w[_RS + c, i] - (h1x * a0 + h1y * a1 + h1z * a2),
                w[_RS + 3 + c, i] - (h2x * a0 + h2y * a1 + h2z * a2),
            )  # fmt: skip
            al[c] += li * (x1 * t1x + x2 * t2x)
            al[3 + c] += li * (x1 * t1y + x2 * t2y)
            al[6 + c] += li * (x1 * t1z + x2 * t2z)


@inner
def closure(held, ac, ga, al, target, tip, omega, l0, la, system, rhs):
    """The holding force at the tip as L = l0 + la A_0 (``la`` 3x3 row-major): on each held
    axis k the tip's acceleration equals the target's, stabilised (Baumgarte):
    a_k - 2 omega (v_n - v)_k - omega^2 (p_n - p)_k, with ``target`` (9: position, velocity,
    acceleration) and ``tip`` (6: node n's position and velocity); on a free axis L_k = 0.
    ``system`` (9) and ``rhs`` (3) are scratch. False when the closure is singular (a line
    pulled straight between held ends)."""
    for k in range(3):
        if held[k] != 0.0:
            for c in range(3):
                system[3 * k + c] = al[3 * k + c]
        else:
            for c in range(3):
                system[3 * k + c] = 1.0 if k == c else 0.0
    scale = 0.0  # of the system's entries: a heavy line's are small
    for v in system:
        scale = max(scale, abs(v))
    for col in range(4):
        for k in range(3):
            if held[k] == 0.0:
                rhs[k] = 0.0
            elif col == 0:
                rhs[k] = (
                    target[6 + k] - 2.0 * omega * (tip[3 + k] - target[3 + k])
                    - omega * omega * (tip[k] - target[k]) - ac[k]
                )  # fmt: skip
            else:
                rhs[k] = -ga[3 * k + col - 1]
        x, det = c3._solve3(system, rhs)
        if not abs(det) > 1e-12 * scale**3:
            return False
        for k in range(3):
            if col == 0:
                l0[k] = x[k]
            else:
                la[3 * k + col - 1] = x[k]
    return True


@njit(**JIT)
def forward(n, length, w, a0, held_force, pinned, y, q, v, ydot):
    """The forward sweep from node 0's acceleration ``a0`` (and the holding force when
    ``pinned``): rows _A (nodes) and _EDD (directors), and the line's rates into ``ydot``."""
    ax, ay, az = a0[0], a0[1], a0[2]
    w[_A, 0], w[_A + 1, 0], w[_A + 2, 0] = ax, ay, az
    for i in range(n):
        li = length[i]
        u2 = w[_U, i] ** 2 + w[_U + 1, i] ** 2 + w[_U + 2, i] ** 2
        r1 = w[_W, i] - (w[_H, i] * ax + w[_H + 2, i] * ay + w[_H + 4, i] * az)
        r2 = w[_W + 1, i] - (w[_H + 1, i] * ax + w[_H + 3, i] * ay + w[_H + 5, i] * az)
        if pinned:
            for c in range(3):
                r1 += w[_RS + c, i] * held_force[c]
                r2 += w[_RS + 3 + c, i] * held_force[c]
        x1, x2 = _director_acceleration(w, i, r1, r2)
        for k in range(3):
            edd = x1 * w[_T1 + k, i] + x2 * w[_T2 + k, i] - u2 * w[_E + k, i]
            w[_EDD + k, i] = edd
            ydot[q + 3 * i + k] = y[v + 3 * i + k]
            ydot[v + 3 * i + k] = edd
        ax += li * w[_EDD, i]
        ay += li * w[_EDD + 1, i]
        az += li * w[_EDD + 2, i]
        w[_A, i + 1], w[_A + 1, i + 1], w[_A + 2, i + 1] = ax, ay, az


@inner
def node_force(w, k, held_force, pinned):
    """lam_k: the force the part of the line above node k exerts on node k and below it (at
    node 0, the force the base applies to the line; at the tip, the line's pull on the tip)."""
    return c3._node_force(w, k, held_force, pinned)


@inner
def march(n, w, lam, e):
    """At rest, from the tip's force ``lam``: each segment turned along the pull it carries,
    e_i = -(lam_(i+1) - F_i / 2) / |...| (tension positive, joint springs ignored; F_i its loads
    as ``w`` holds them), into ``e`` (3 n); lam_i = lam_(i+1) - F_i. One pass of the fixed
    point that gives the statics of a hanging or towed line its first shape."""
    for i in range(n - 1, -1, -1):
        hx = lam[0] - 0.5 * w[_F, i]
        hy = lam[1] - 0.5 * w[_F + 1, i]
        hz = lam[2] - 0.5 * w[_F + 2, i]
        size = (hx * hx + hy * hy + hz * hz) ** 0.5
        if size > 0.0:
            e[3 * i], e[3 * i + 1], e[3 * i + 2] = -hx / size, -hy / size, -hz / size
        else:
            e[3 * i], e[3 * i + 1], e[3 * i + 2] = w[_E, i], w[_E + 1, i], w[_E + 2, i]
        for c in range(3):
            lam[c] -= w[_F + c, i]


@inner
def moment_balance(n, length, w, lam, out):
    """At rest: the force lam_k down the line from the tip's ``lam`` (lam_i = lam_(i+1) - F_i,
    F_i the segment's loads) and each segment's moment about its centre,
    l e x (lam_(i+1) - F_i / 2) - torque_i, on (t1, t2) into ``out`` (2 n): zero when the
    segment is in balance. Returns lam_0 in ``lam``."""
    for i in range(n - 1, -1, -1):
        li = length[i]
        ex, ey, ez = w[_E, i], w[_E + 1, i], w[_E + 2, i]
        hx = lam[0] - 0.5 * w[_F, i]
        hy = lam[1] - 0.5 * w[_F + 1, i]
        hz = lam[2] - 0.5 * w[_F + 2, i]
        mx = li * (ey * hz - ez * hy) - w[_TQ, i]
        my = li * (ez * hx - ex * hz) - w[_TQ + 1, i]
        mz = li * (ex * hy - ey * hx) - w[_TQ + 2, i]
        t1x, t1y, t1z, t2x, t2y, t2z = c3._basis(ex, ey, ez)
        out[2 * i] = t1x * mx + t1y * my + t1z * mz
        out[2 * i + 1] = t2x * mx + t2y * my + t2z * mz
        for c in range(3):
            lam[c] -= w[_F + c, i]
