"""Non-linear hydrostatics (the ship-simulator document's ``non-linear hydrostatic``): the
hydrostatic pressure rho g (level - z) integrated exactly on the body's hull mesh clipped at the
free surface at each evaluation (kernels.hull): the still-water level z = 0, or the incident
waves' elevation (kernels.waves) when the environment has waves. Buoyancy and its moment are
exact at any draft, heel and trim, on planar faces to round-off. In still water it is
conservative: its potential is -rho g int (z - level) dV over the displaced volume
(``potential``).

The row: the level [m], then the mesh's row (kernels.hull.mesh_row), its vertices in the body
frame relative to the reference point. ``work`` (nv, 4) is the hull workspace
(kernels.hull.place).
"""

from seacable.kernels import hull
from seacable.kernels.jit import inner

LEVEL = 0.0  # the still-water surface [m]


def pack(mesh_row) -> list[float]:
    return [LEVEL, *mesh_row]


@inner
def add(row, pos, rot, rho, gravity, wave, t, work, rhs):
    hull.place(row[1:], pos, rot, wave, t, work)
    hull.add_hydrostatic(row[1:], row[0], pos, rho, gravity, work, rhs)


@inner
def potential(row, pos, rot, rho, gravity, still, work):
    """The still-water potential [J] (``still``: an empty wave table)."""
    hull.place(row[1:], pos, rot, still, 0.0, work)
    return rho * gravity * hull.hydrostatic_potential(row[1:], row[0], pos, work)
