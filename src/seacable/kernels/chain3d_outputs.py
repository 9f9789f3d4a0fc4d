"""Energies of a 3D rigid-segment line (``segment_energies``: kinetic, gravity potential and
joint springs; the system's ``system.energy``; numba)."""

import math

from seacable.kernels.chain3d import (
    _E,
    _P,
    _SA,
    _SJ,
    _U,
    _V,
)
from seacable.kernels.jit import inner
from seacable.kernels.surface import segment_potential


@inner
def segment_energies(n, length, mass, wet_weight, buoyancy, joint_stiffness, ref, w):
    """Kinetic (own and added mass, translation and rotation), gravity and buoyancy potential
    and joint-spring energy of one line's segments (its workspace ``w`` filled); joint 0 is
    unloaded along ``ref``."""
    kinetic = 0.0
    gravity = 0.0
    elastic = 0.0
    for i in range(n):
        li = length[i]
        ex, ey, ez = w[_E, i], w[_E + 1, i], w[_E + 2, i]
        vx = 0.5 * (w[_V, i] + w[_V, i + 1])
        vy = 0.5 * (w[_V + 1, i] + w[_V + 1, i + 1])
        vz = 0.5 * (w[_V + 2, i] + w[_V + 2, i + 1])
        va = vx * ex + vy * ey + vz * ez
        v2 = vx * vx + vy * vy + vz * vz
        u2 = w[_U, i] ** 2 + w[_U + 1, i] ** 2 + w[_U + 2, i] ** 2
        kinetic += 0.5 * mass[i] * v2 + 0.5 * w[_SA, i] * (v2 - va * va)
        kinetic += 0.5 * w[_SJ, i] * u2
        gravity += segment_potential(wet_weight[i], buoyancy[i], w[_P + 2, i], w[_P + 2, i + 1],
                                     w[_P + 2, i] + 0.5 * li * ez)  # fmt: skip
        if i == 0:
            ax, ay, az = ref[0], ref[1], ref[2]
        else:
            ax, ay, az = w[_E, i - 1], w[_E + 1, i - 1], w[_E + 2, i - 1]
        cx, cy, cz = ay * ez - az * ey, az * ex - ax * ez, ax * ey - ay * ex
        phi = math.atan2(math.sqrt(cx * cx + cy * cy + cz * cz), ax * ex + ay * ey + az * ez)
        elastic += 0.5 * joint_stiffness[i] * phi * phi
    return kinetic, gravity, elastic
