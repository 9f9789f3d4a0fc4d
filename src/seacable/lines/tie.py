"""Massless elastic ties between two body points (hawsers, mooring springs): tension
k (d - L0) + c dd/dt, or from a tension-elongation table (linear interpolation, extrapolated
with the last slope), zero when slack (d <= L0) and never negative; along the line between the
points, pulling them together."""

import math

from numba import njit

from seacable.kernels.jit import JIT, inner


@inner
def tension(elongation, rate, stiffness, damping, table, first, count):
    """Tension [N] at ``elongation`` d - L0 [m] and its rate [m/s] (``stiffness`` k [N/m] > 0:
    linear; else the table's rows first .. first + count - 1)."""
    if elongation <= 0.0:
        return 0.0
    if stiffness > 0.0:
        value = stiffness * elongation
    else:
        value = 0.0
        for k in range(first + 1, first + count):
            e0, t0, e1, t1 = table[k - 1, 0], table[k - 1, 1], table[k, 0], table[k, 1]
            if elongation <= e1 or k == first + count - 1:
                value = t0 + (t1 - t0) * (elongation - e0) / (e1 - e0)
                break
    value += damping * rate
    return max(value, 0.0)


@njit(inline="always", **JIT)  # inlined: a call would pass and count every array
def forces(ppos, pvel, point_from, point_to, length, stiffness, damping, table, first, count,
           out_tension, out_force):  # fmt: skip
    """Tension of every tie (``out_tension``) and its force on its ``from`` point
    (``out_force`` (nt, 3); the ``to`` point gets the opposite)."""
    for k in range(point_from.shape[0]):
        a, b = point_from[k], point_to[k]
        dx, dy, dz = ppos[b, 0] - ppos[a, 0], ppos[b, 1] - ppos[a, 1], ppos[b, 2] - ppos[a, 2]
        d = math.sqrt(dx * dx + dy * dy + dz * dz)
        if d == 0.0:
            out_tension[k] = 0.0
            out_force[k, :] = 0.0
            continue
        ux, uy, uz = dx / d, dy / d, dz / d
        rate = (
            (pvel[b, 0] - pvel[a, 0]) * ux
            + (pvel[b, 1] - pvel[a, 1]) * uy
            + (pvel[b, 2] - pvel[a, 2]) * uz
        )
        value = tension(d - length[k], rate, stiffness[k], damping[k], table, first[k], count[k])
        out_tension[k] = value
        out_force[k, 0], out_force[k, 1], out_force[k, 2] = value * ux, value * uy, value * uz
