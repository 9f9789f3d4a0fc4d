"""Compiled pieces of the planar rigid-link lines of a system (Pouzada's chain of
``kernels.planar_chain``, through its shared ``link_loads`` and ``link_back``), in the vertical
plane x-z of the line's base: the backward sweep, the map of the tip's acceleration, the closure
on a held tip, the forward sweep, node forces and the statics' moment balance.

A line of n links has nodes 0..n; its states are the links' angles from the downward vertical
(positive towards +x) at ``y[q + i]`` and their rates at ``y[v + i]``. The coupling to the
bodies is that of the rigid-segment lines (``lines.rigid_segments``, docs/rigid_segment_lines.md)
with 2x2 articulated inertias in (x, z): the base body receives [[m11, 0, m12], [0, 0, 0],
[m12, 0, m22]] at its point, a carried body its line's tip motion in the plane.
"""

import math

from numba import njit

from seacable.kernels import planar_chain as pc
from seacable.kernels.jit import JIT, inner
from seacable.kernels.planar_chain import (
    _AX,
    _AZ,
    _BX,
    _BZ,
    _D,
    _EX,
    _EZ,
    _FX,
    _FZ,
    _HX,
    _HZ,
    _M11,
    _M12,
    _M22,
    _Q,
    _RSX,
    _RSZ,
    _S11,
    _S12,
    _S21,
    _S22,
    _THDD,
    _U,
)


@njit(**JIT)
def backward(n, length, mass, inertia, y, v, w, st, pinned):
    """The backward sweep from the tip's ``st`` = (m11, m12, m22, bx, bz, s11, s12, s21, s22)
    to node 0's, in place; every node's rows stored."""
    w[_M11, n], w[_M12, n], w[_M22, n], w[_BX, n], w[_BZ, n] = st[0], st[1], st[2], st[3], st[4]
    w[_S11, n], w[_S12, n], w[_S21, n], w[_S22, n] = st[5], st[6], st[7], st[8]
    for i in range(n - 1, -1, -1):
        pc.link_back(i, length[i], mass[i], inertia[i], y[v + i], w, st, pinned)


@njit(**JIT)
def tip_map(n, length, y, v, w, ac, ga, al):
    """The tip's acceleration as A_n = ac + ga A_0 + al L in (x, z) (``ga``, ``al`` 2x2
    row-major)."""
    ac[0] = ac[1] = 0.0
    ga[0], ga[1], ga[2], ga[3] = 1.0, 0.0, 0.0, 1.0
    al[0] = al[1] = al[2] = al[3] = 0.0
    for i in range(n):
        li = length[i]
        om = y[v + i]
        ex, ez = w[_EX, i], w[_EZ, i]
        nx, nz = -ez, ex
        inv_d, hx, hz = w[_D, i], w[_HX, i], w[_HZ, i]
        thc = (w[_U, i] - hx * ac[0] - hz * ac[1]) * inv_d
        ac[0] += li * (thc * nx - om * om * ex)
        ac[1] += li * (thc * nz - om * om * ez)
        for c in range(2):
            thg = -(hx * ga[c] + hz * ga[2 + c]) * inv_d
            ga[c] += li * nx * thg
            ga[2 + c] += li * nz * thg
            rs = w[_RSX, i] if c == 0 else w[_RSZ, i]
            thl = (rs - hx * al[c] - hz * al[2 + c]) * inv_d
            al[c] += li * nx * thl
            al[2 + c] += li * nz * thl


@inner
def closure(held_x, held_z, ac, ga, al, target, tip, omega, l0, la):
    """The holding force at the tip in (x, z) as L = l0 + la A_0: on a held axis the tip's
    acceleration is the target's, Baumgarte-stabilised (``target``: position, velocity,
    acceleration in x and z; ``tip``: node n's position and velocity); on a free axis L = 0.
    False when singular (the line pulled straight between held ends)."""
    s = (al[0], al[1], al[2], al[3])
    if held_x == 0.0:
        s = (1.0, 0.0, s[2], s[3])
    if held_z == 0.0:
        s = (s[0], s[1], 0.0, 1.0)
    det = s[0] * s[3] - s[1] * s[2]
    scale = max(abs(s[0]), abs(s[1]), abs(s[2]), abs(s[3]))
    if not abs(det) > 1e-12 * scale * scale:
        return False
    for col in range(3):
        r = [0.0, 0.0]
        for k in range(2):
            held = held_x if k == 0 else held_z
            if held == 0.0:
                continue
            if col == 0:
                r[k] = (
                    target[4 + k] - 2.0 * omega * (tip[2 + k] - target[2 + k])
                    - omega * omega * (tip[k] - target[k]) - ac[k]
                )  # fmt: skip
            else:
                r[k] = -ga[2 * k + col - 1]
        x0 = (s[3] * r[0] - s[1] * r[1]) / det
        x1 = (-s[2] * r[0] + s[0] * r[1]) / det
        if col == 0:
            l0[0], l0[1] = x0, x1
        else:
            la[col - 1], la[2 + col - 1] = x0, x1
    return True


@njit(**JIT)
def forward(n, length, w, ax, az, lx, lz, pinned, y, q, v, ydot):
    """The forward sweep from node 0's acceleration (and the holding force when ``pinned``):
    rows _AX, _AZ (nodes) and _THDD (angles), and the line's rates into ``ydot``."""
    w[_AX, 0], w[_AZ, 0] = ax, az
    for i in range(n):
        li = length[i]
        om = y[v + i]
        ex, ez = w[_EX, i], w[_EZ, i]
        nx, nz = -ez, ex
        r = w[_U, i] - w[_HX, i] * ax - w[_HZ, i] * az
        if pinned:
            r += w[_RSX, i] * lx + w[_RSZ, i] * lz
        thdd = r * w[_D, i]
        w[_THDD, i] = thdd
        ydot[q + i] = om
        ydot[v + i] = thdd
        ax += li * (thdd * nx - om * om * ex)
        az += li * (thdd * nz - om * om * ez)
        w[_AX, i + 1], w[_AZ, i + 1] = ax, az


@inner
def node_force(w, k, lx, lz, pinned):
    """lam_k in (x, z): the force the part above node k exerts on node k and below it."""
    return pc._node_force(w, k, lx, lz, pinned)


@inner
def march(n, w, lam, angles):
    """At rest, from the tip's force ``lam`` (x, z): each link turned along the pull it carries
    (tension positive, joint springs ignored), its angle into ``angles``; lam_i = lam_(i+1) - F_i
    (see ``lines.rigid_segments.march``)."""
    for i in range(n - 1, -1, -1):
        hx = lam[0] - 0.5 * w[_FX, i]
        hz = lam[1] - 0.5 * w[_FZ, i]
        if hx != 0.0 or hz != 0.0:
            angles[i] = math.atan2(-hx, hz)  # e = -h / |h| = (sin a, -cos a)
        else:
            angles[i] = math.atan2(w[_EX, i], -w[_EZ, i])
        lam[0] -= w[_FX, i]
        lam[1] -= w[_FZ, i]


@inner
def moment_balance(n, length, w, lam, out):
    """At rest: each link's generalised force l n . (lam_(i+1) - F_i / 2) - Q_i into ``out``
    (n), zero when the link is in balance; lam_0 returned in ``lam`` (x, z)."""
    for i in range(n - 1, -1, -1):
        nx, nz = -w[_EZ, i], w[_EX, i]
        hx = lam[0] - 0.5 * w[_FX, i]
        hz = lam[1] - 0.5 * w[_FZ, i]
        out[i] = length[i] * (nx * hx + nz * hz) - w[_Q, i]
        lam[0] -= w[_FX, i]
        lam[1] -= w[_FZ, i]
