"""A hydrodynamic database computed from a hull mesh with Capytaine (the optional extra:
``pip install seacable[bem]``; ``seacable hydrodb hull.stl``).

The mesh (seacable.meshes: any format it reads, placed as given) is cut at z = 0, the six
rigid-body motions about ``rotation_center`` are solved in radiation and the waves of
``directions`` in diffraction at each frequency, and the result is written as NetCDF in
Capytaine's layout with seacable's conventions (seacable.hydrodb.write). A lid on the hull's
inner free surface, at z = 0, removes the irregular frequencies: on the 90 m box barge of
examples/data/make_barge.py (3 m panels) it gives a smooth damping to 2.2 rad/s, where a lid
lowered to Capytaine 3.0's ``lowest_lid_position`` (2.9 m down for 1.8 rad/s) left spikes at
1.6-1.7 rad/s and negative heave and pitch damping. Capytaine's first solve builds its
Green-function table (about half a minute).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr

from seacable import hydrodb, meshes
from seacable.errors import memory_check


def compute(mesh: meshes.Mesh, omega, directions_deg=(0.0,), rotation_center=(0.0, 0.0, 0.0),
            rho: float = 1025.0, gravity: float = 9.81, depth: float = math.inf,
            name: str = "hull", allow_large: bool = False) -> hydrodb.HydroDB:  # fmt: skip
    """Capytaine's database of the hull ``mesh``. Its solver holds dense matrices of the
    panels: about 75 N^2 bytes for N panels below the waterline (measured on the box barge:
    3,136 panels 0.75 GB, 7,056 panels 3.6 GB, whatever the frequencies); beyond
    ``errors.MEMORY_BUDGET`` the mesh is refused unless ``allow_large``."""
    mesh = meshes.checked(mesh)  # a mesh that is no hull is refused before Capytaine loads
    check_memory(mesh, allow_large)
    try:
        import capytaine as cpt
    except ImportError:
        raise ImportError(
            "computing a hydrodynamic database needs Capytaine: pip install 'seacable[bem]'"
        ) from None
    omega = np.asarray(omega, dtype=float)
    cmesh = cpt.Mesh(vertices=mesh.vertices, faces=mesh.triangles, name=name)
    cmesh = cmesh.immersed_part()
    # a lid on the inner free surface (z = 0) removes the irregular frequencies; one lowered to
    # Capytaine's lowest_lid_position left spikes and negative damping on the box barge
    lid = cmesh.generate_lid(z=0.0)
    body = cpt.FloatingBody(mesh=cmesh, lid_mesh=lid, name=name,
                            dofs=cpt.rigid_body_dofs(rotation_center=rotation_center),
                            center_of_mass=rotation_center)  # fmt: skip
    test = xr.Dataset(coords={
        "omega": omega,
        "wave_direction": np.radians(np.asarray(directions_deg, dtype=float)),
        "radiating_dof": list(body.dofs), "water_depth": [depth], "rho": [rho], "g": [gravity],
    })  # fmt: skip
    ds = cpt.BEMSolver().fill_dataset(test, body)
    order = {"radiating_dof": list(hydrodb.DOFS), "influenced_dof": list(hydrodb.DOFS)}
    ds = ds.sel(order)

    def matrix(var):
        return ds[var].transpose("omega", "influenced_dof", "radiating_dof").values

    def force(var):
        return np.asarray(ds[var].transpose("omega", "wave_direction", "influenced_dof").values)

    return hydrodb.HydroDB(
        omega=np.asarray(ds.coords["omega"].values, float), added_mass=matrix("added_mass"),
        damping=matrix("radiation_damping"),
        directions=np.asarray(ds.coords["wave_direction"].values, float),
        diffraction=force("diffraction_force"), froude_krylov=force("Froude_Krylov_force"),
        reference_point=np.asarray(rotation_center, float), rho=rho, gravity=gravity,
        depth=depth, source=f"capytaine {cpt.__version__}: {name}",
    )  # fmt: skip


def check_memory(mesh: meshes.Mesh, allow_large: bool = False) -> None:
    """Refuse a mesh whose solve ``compute`` estimates beyond ``errors.MEMORY_BUDGET``."""
    wetted = int(np.count_nonzero(mesh.vertices[mesh.triangles][:, :, 2].min(axis=1) < 0.0))
    memory_check(
        f"hydrodb: the {wetted:,} panels below the waterline make dense matrices that grow "
        "with the square of the panels",
        75.0 * wetted**2,
        "coarsen the mesh (panels of about a twentieth of the hull's length are usual)",
        allow_large,
    )


def compute_file(mesh_file: str | Path, output: str | Path, omega, **options) -> hydrodb.HydroDB:
    mesh = meshes.checked(meshes.read(mesh_file), where=f"mesh file '{mesh_file}'")
    db = compute(mesh, omega, name=Path(mesh_file).stem, **options)
    hydrodb.write(db, output)
    return db
