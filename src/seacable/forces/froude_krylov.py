"""Non-linear Froude-Krylov force (the ship-simulator document's excitation by the incident
wave): the incident waves' dynamic pressure (kernels.waves, with the environment's stretching)
integrated on the body's hull mesh under the wave elevation at each evaluation (kernels.hull),
three points per wetted triangle (its edge midpoints: second order in the panel size). With
``non-linear hydrostatic`` it gives the whole undisturbed pressure, which vanishes at the wave
surface.

The row: ``forces.hydrostatic.pack``'s (its level and still flag unused: every mesh row has one
layout).
"""

from seacable.forces.hydrostatic import MESH_AT
from seacable.kernels import hull
from seacable.kernels.jit import inner


@inner
def add(row, body, pos, rot, rho, gravity, wave, t, depth, stretch, work, rhs):
    if wave.shape[1] == 0:
        return
    hull.place(row[MESH_AT:], body, pos, rot, wave, t, work)
    hull.add_froude_krylov(row[MESH_AT:], rho, gravity, wave, t, depth, stretch, work, rhs)
