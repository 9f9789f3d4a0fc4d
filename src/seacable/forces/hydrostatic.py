"""Non-linear hydrostatics (the ship-simulator document's ``non-linear hydrostatic``): the
still-water pressure rho g (level - z) integrated exactly on the body's hull mesh clipped at
the free surface z = level at each evaluation (kernels.hull), so that buoyancy and its moment
are exact at any draft, heel and trim, on planar faces to round-off. Conservative: its
potential is -rho g int (z - level) dV over the displaced volume (``potential``).

The row: the level [m], then the mesh's row (kernels.hull.mesh_row), its vertices in the body
frame relative to the reference point.
"""

from seacable.kernels import hull
from seacable.kernels.jit import inner

LEVEL = 0.0  # the still-water surface [m]


def pack(mesh_row) -> list[float]:
    return [LEVEL, *mesh_row]


@inner
def add(row, pos, rot, rho, gravity, rhs):
    hull.add_hydrostatic(row[1:], row[0], pos, rot, rho, gravity, rhs)


@inner
def potential(row, pos, rot, rho, gravity):
    return hull.hydrostatic_potential(row[1:], row[0], pos, rot, rho, gravity)
