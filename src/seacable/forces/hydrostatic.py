"""Non-linear hydrostatics (the ship-simulator document's ``non-linear hydrostatic``): the
hydrostatic pressure rho g (level - z) integrated exactly on the body's hull mesh clipped at the
free surface at each evaluation (kernels.hull): the still-water level z = 0, or the incident
waves' elevation (kernels.waves) when the environment has waves. Buoyancy and its moment are
exact at any draft, heel and trim, on planar faces to round-off. In still water it is
conservative: its potential is -rho g int (z - level) dV over the displaced volume
(``potential``).

``free_surface: still`` clips the mesh at z = 0 whatever the waves: with a database's linear
excitation that already holds the incident wave's pressure (``diffraction`` with
``froude_krylov: true``), clipping at the wave elevation too would count its rho g eta twice.

The row: the level [m], 1 when clipped at still water whatever the waves, then the mesh's row
(kernels.hull.mesh_row), its vertices in the body frame relative to the reference point.
``work`` is the hull workspace (kernels.hull.place), ``body`` the body's number (its key).
"""

from seacable.kernels import hull, waves
from seacable.kernels.jit import inner

LEVEL = 0.0  # the still-water surface [m]


MESH_AT = 2  # where the mesh's row starts in the force model's row


def pack(mesh_row, still: bool = False) -> list[float]:
    return [LEVEL, float(still), *mesh_row]


@inner
def add(row, body, pos, rot, rho, gravity, wave, t, work, rhs):
    surface = waves.still() if row[1] != 0.0 else wave
    hull.place(row[MESH_AT:], body, pos, rot, surface, t, work)
    hull.add_hydrostatic(row[MESH_AT:], row[0], rho, gravity, work, rhs)


@inner
def potential(row, body, pos, rot, rho, gravity, still, work):
    """The still-water potential [J] (``still``: an empty wave table)."""
    hull.place(row[MESH_AT:], body, pos, rot, still, 0.0, work)
    return rho * gravity * hull.hydrostatic_potential(row[MESH_AT:], row[0], pos, work)
