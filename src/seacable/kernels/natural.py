"""Planar extensible string in natural variables (Poth 2002): strain and tangent direction.

The string of unstretched length l, mass mu per unstretched length and axial law
N = EA (eps + alpha d eps/dt) (no compression when ``slack_allowed``) hangs from a fixed pivot
and carries an end mass m_s. Its field is q(s) = dr/ds = (1 + eps) t, and the equation of
motion differentiated along s, mu q'' = (N t)'', is discretised at k + 1 nodes s_i = i l / k by
central differences, the boundary conditions being folded in with ghost points (the pivot:
r'' = 0; the end mass: m_s r_s'' = m_s g - N t):

    q_0''   = 2 (k / l) g + 2 c (F_1 - F_0)
    q_i''   = c (F_{i+1} - 2 F_i + F_{i-1})                  (0 < i < k)
    q_k''   = -2 c (F_k - F_{k-1}) - 2 (k / (m_s l)) F_k,     c = k^2 / (mu l^2),  F = N t

Positions follow by the trapezoidal rule, r_j = sum (l / 2k) (q_{j-1} + q_j), r_0 = 0.

Two parametrisations of the tangent (``cartesian`` flag):

* angle (eps, phi), t = (sin phi, -cos phi) in the (x, z) plane, phi from the downward vertical:
  eps'' = q''.t + (1 + eps) phi'^2, phi'' = (q''.n - 2 eps' phi') / (1 + eps), n = (cos, sin);
  two variables per node (``BLOCK_ANGLE``);
* cartesian (eps, t_x, t_z) with |t| = 1 kept at the acceleration level (Poth's eq. 22):
  [(1+eps) I, t; t^T, 0] [t''; eps''] = [q'' - 2 eps' t'; -|t'|^2]; three per node.

State ``y = [node variables (B per node), their rates]``; every node is free.
"""

import math
from typing import NamedTuple

from numba import njit

from seacable.kernels.jit import JIT, inner
from seacable.kernels.status import NON_FINITE, OK


class NaturalParams(NamedTuple):
    n: int  # k, elements
    length: float  # l [m]
    mu: float  # mass per unstretched length [kg/m]
    end_mass: float  # m_s [kg]
    axial_stiffness: float  # EA [N]
    axial_damping: float  # alpha [s]
    slack_allowed: int
    gravity: float  # g [m/s^2], acting along -z
    cartesian: int  # 1: (eps, t_x, t_z); 0: (eps, phi)


@inner
def fields(y, p, w):
    """q, q', F = N t and N of every node from the state."""
    n = p.n
    b = 3 if p.cartesian == 1 else 2
    v0 = b * (n + 1)
    ea, alpha = p.axial_stiffness, p.axial_damping
    for i in range(n + 1):
        eps = y[b * i]
        deps = y[v0 + b * i]
        if p.cartesian == 1:
            tx, tz = y[b * i + 1], y[b * i + 2]
            dtx, dtz = y[v0 + b * i + 1], y[v0 + b * i + 2]
        else:
            phi, dphi = y[b * i + 1], y[v0 + b * i + 1]
            tx, tz = math.sin(phi), -math.cos(phi)
            dtx, dtz = dphi * math.cos(phi), dphi * math.sin(phi)
        w[0, i] = (1.0 + eps) * tx
        w[1, i] = (1.0 + eps) * tz
        w[2, i] = deps * tx + (1.0 + eps) * dtx
        w[3, i] = deps * tz + (1.0 + eps) * dtz
        tension = ea * (eps + alpha * deps)
        if tension < 0.0 and p.slack_allowed == 1:
            tension = 0.0
        w[4, i] = tension * tx
        w[5, i] = tension * tz
        w[6, i] = tension


@inner
def rhs(t, y, p, w, ydot):
    n = p.n
    b = 3 if p.cartesian == 1 else 2
    v0 = b * (n + 1)
    fields(y, p, w)
    k, span = float(n), p.length
    c = k * k / (p.mu * span * span)
    for i in range(n + 1):
        for j in range(2):
            f = w[4 + j, i]
            if i == 0:
                acc = 2.0 * c * (w[4 + j, 1] - f)
                if j == 1:
                    acc -= 2.0 * (k / span) * p.gravity
            elif i == n:
                acc = -2.0 * c * (f - w[4 + j, n - 1]) - 2.0 * (k / (p.end_mass * span)) * f
            else:
                acc = c * (w[4 + j, i + 1] - 2.0 * f + w[4 + j, i - 1])
            w[7 + j, i] = acc
    status = OK
    for i in range(n + 1):
        for j in range(b):
            ydot[b * i + j] = y[v0 + b * i + j]
        ax, az = w[7, i], w[8, i]
        eps = y[b * i]
        deps = y[v0 + b * i]
        if p.cartesian == 1:
            tx, tz = y[b * i + 1], y[b * i + 2]
            dtx, dtz = y[v0 + b * i + 1], y[v0 + b * i + 2]
            # [(1+e) I, t; t^T, 0] [ttx, ttz, ee] = [ax - 2 e' t'x, az - 2 e' t'z, -|t'|^2]
            e1 = 1.0 + eps
            r0 = ax - 2.0 * deps * dtx
            r1 = az - 2.0 * deps * dtz
            r2 = -(dtx * dtx + dtz * dtz)
            tt = tx * tx + tz * tz
            if e1 == 0.0 or tt == 0.0:
                status = NON_FINITE
                continue
            # eliminate: t'' = (r01 - ee t) / e1, t . t'' = r2  ->  ee = (t . r01 - e1 r2) / tt
            ee = (tx * r0 + tz * r1 - e1 * r2) / tt
            ydot[v0 + b * i] = ee
            ydot[v0 + b * i + 1] = (r0 - ee * tx) / e1
            ydot[v0 + b * i + 2] = (r1 - ee * tz) / e1
        else:
            phi, dphi = y[b * i + 1], y[v0 + b * i + 1]
            tx, tz = math.sin(phi), -math.cos(phi)
            nx, nz = math.cos(phi), math.sin(phi)
            e1 = 1.0 + eps
            if e1 == 0.0:
                status = NON_FINITE
                continue
            ydot[v0 + b * i] = ax * tx + az * tz + e1 * dphi * dphi
            ydot[v0 + b * i + 1] = (ax * nx + az * nz - 2.0 * deps * dphi) / e1
    if not math.isfinite(ydot[v0] + ydot[2 * v0 - 1]):
        status = NON_FINITE
    return status


@inner
def project_tangents(y, n, q, v):
    """The cartesian tangents of n + 1 nodes, (eps, t_x, t_z) from ``y[q]`` and their rates
    from ``y[v]``, back to |t| = 1 and t . t' = 0."""
    for i in range(n + 1):
        tx, tz = y[q + 3 * i + 1], y[q + 3 * i + 2]
        norm = math.sqrt(tx * tx + tz * tz)
        if norm == 0.0:
            continue
        tx /= norm
        tz /= norm
        y[q + 3 * i + 1], y[q + 3 * i + 2] = tx, tz
        dtx, dtz = y[v + 3 * i + 1], y[v + 3 * i + 2]
        along = dtx * tx + dtz * tz
        y[v + 3 * i + 1] = dtx - along * tx
        y[v + 3 * i + 2] = dtz - along * tz


@njit(inline="always", **JIT)
def trapezoid(w, h, i):
    """The position and velocity of node i less those of node i - 1 (the trapezoidal rule on
    the tangent field q and its rate in the workspace ``w``, elements of length h)."""
    return (0.5 * h * (w[0, i - 1] + w[0, i]), 0.5 * h * (w[1, i - 1] + w[1, i]),
            0.5 * h * (w[2, i - 1] + w[2, i]), 0.5 * h * (w[3, i - 1] + w[3, i]))  # fmt: skip


@inner
def outputs(t, y, p, w, node_pos, strain, tension, scalars):
    """Node positions (trapezoidal integral of q), strain and tension per node, end mass and
    energies (trapezoidal quadrature of the string's integrals)."""
    n = p.n
    b = 3 if p.cartesian == 1 else 2
    fields(y, p, w)
    h = p.length / n
    x = z = vx = vz = 0.0
    kinetic = gravity = elastic = 0.0
    for i in range(n + 1):
        if i > 0:
            dx, dz, dvx, dvz = trapezoid(w, h, i)
            x, z, vx, vz = x + dx, z + dz, vx + dvx, vz + dvz
        node_pos[i, 0] = x
        node_pos[i, 1] = z
        eps = y[b * i]
        strain[i] = eps
        tension[i] = w[6, i]
        weight = 0.5 * h if (i == 0 or i == n) else h
        kinetic += 0.5 * p.mu * weight * (vx * vx + vz * vz)
        gravity += p.mu * weight * p.gravity * z
        if eps > 0.0 or p.slack_allowed == 0:
            elastic += 0.5 * p.axial_stiffness * weight * eps * eps
    kinetic += 0.5 * p.end_mass * (vx * vx + vz * vz)
    gravity += p.end_mass * p.gravity * z
    scalars[0] = x
    scalars[1] = z
    scalars[2] = kinetic
    scalars[3] = gravity
    scalars[4] = elastic
