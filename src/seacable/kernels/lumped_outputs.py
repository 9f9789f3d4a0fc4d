"""Energies of an extensible lumped-mass line (``line_energies``: kinetic, gravity potential,
axial and bending; the system's ``system.energy``; numba)."""

import math

import numpy as np

from seacable.kernels.jit import inner
from seacable.kernels.lumped import (
    _bend_angle,
    _node_mass_into,
    seabed_potential,
)
from seacable.kernels.surface import segment_potential


@inner
def line_energies(
    yl, n, s0, c0, node_mass, length, stiffness, wet_weight, buoyancy, seabed_z, seabed_k,
    seabed_band, bend, slack, w,
):  # fmt: skip
    """Kinetic (added mass included), gravity potential (apparent weight and the buoyancy of
    the submerged part) and elastic (axial, seabed, bending) energies of one line's nodes
    ``yl = [r_0 .. r_n, v_0 .. v_n]`` [J]: segment arrays at ``[s0 + i]``, node arrays and
    workspace columns at ``[c0 + k]`` (filled by the rates), ``slack`` as in segment_loads.
    Every lumped line, alone or in a system, counts its energies here."""
    v0 = 3 * (n + 1)
    kinetic = gravity = elastic = 0.0
    m3 = np.empty(9)
    for j in range(n + 1):
        k = c0 + j
        _node_mass_into(node_mass[k], w, k, m3)
        vx, vy, vz = yl[v0 + 3 * j], yl[v0 + 3 * j + 1], yl[v0 + 3 * j + 2]
        kinetic += 0.5 * (
            vx * (m3[0] * vx + m3[1] * vy + m3[2] * vz)
            + vy * (m3[3] * vx + m3[4] * vy + m3[5] * vz)
            + vz * (m3[6] * vx + m3[7] * vy + m3[8] * vz)
        )
        elastic += seabed_potential(seabed_z - yl[3 * j + 2], seabed_k[k], seabed_band)
        if 0 < j < n and bend[k] > 0.0:
            phi, _, _ = _bend_angle(w, k)
            elastic += 0.5 * bend[k] * phi * phi
    for i in range(n):
        s = s0 + i
        za, zb = yl[3 * i + 2], yl[3 * i + 5]
        gravity += segment_potential(wet_weight[s], buoyancy[s], za, zb, 0.5 * (za + zb))
        dx = yl[3 * i + 3] - yl[3 * i]
        dy = yl[3 * i + 4] - yl[3 * i + 1]
        dz = yl[3 * i + 5] - yl[3 * i + 2]
        strain = math.sqrt(dx * dx + dy * dy + dz * dz) / length[s] - 1.0
        if strain > 0.0 or slack == 0:
            elastic += 0.5 * stiffness[s] * length[s] * strain * strain
    return kinetic, gravity, elastic
