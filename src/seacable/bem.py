"""A hydrodynamic database computed from a hull mesh with Capytaine (the optional extra:
``pip install seacable[bem]``; ``seacable hydrodb hull.stl``).

The mesh (seacable.meshes: any format it reads, placed as given) is cut at z = 0, the six
rigid-body motions about ``rotation_center`` are solved in radiation and the waves of
``directions`` in diffraction at each frequency, the radiation once more at infinite frequency
for the added mass the time domain uses (``HydroDB.infinite``, written as
``added_mass_infinite``: system.hulls takes it before Ogilvie's estimate), and the result is
written as NetCDF in Capytaine's layout with seacable's conventions (seacable.hydrodb.write).
One frequency is allowed (wave excitation at it; the radiation memory needs many).

A lid on the hull's inner free surface, Capytaine's ``generate_lid`` at z = 0, removes the
irregular frequencies. Measured with Capytaine 3.0 on the 90 m box barge of
examples/data/make_barge.py (3 m panels, 0.05 to 2.4 rad/s; its first irregular frequency near
1.41 rad/s) and on the hemisphere of tests/test_hemisphere_bem.py (24 bands, K a 0.02 to 8),
against the lid at z = 0 ("negative": the diagonal damping, as a share of its peak):

- no lid: the barge's roll damping -0.44 at 1.65 rad/s, heave and pitch negative from 1.85 and
  1.95 rad/s; the hemisphere's heave damping 46 % under Hulme's at K a = 2.5;
- the lid 0.03, 0.12 or 0.3 m down (a hundredth to a tenth of a panel): negative damping on the
  barge from 1.55, 1.65 or 2.1 rad/s (pitch -1 at 1.55 rad/s with 0.03 m); on the hemisphere
  5 mm down, heave damping 4.6 times Hulme's at K a = 4;
- at Capytaine's ``lowest_lid_position`` (2.9 m down for make_barge.py's 1.8 rad/s, 1.56 m for
  2.4 rad/s): spikes at 1.65 rad/s and heave and pitch negative at 1.70-1.75 rad/s, or roll from
  2.2 rad/s (-0.84 at 2.4);
- a tenth of the draft down (0.6 m; 0.1 m on the hemisphere): clean on the barge to 1.8 rad/s,
  heave and pitch -0.02 at 2.4 rad/s; the hemisphere's heave damping negative at K a = 3.8 and
  8; its infinite-frequency added mass moves with the mesh where the lid-free one converges
  (barge surge on a lid of the panels' size: +0.2, -3.7, -0.8, +0.3 % of the lid-free 6.86,
  6.62, 6.52, 6.46e5 kg at 3, 2, 1.5, 1.2 m panels);
- at z = 0: no negative damping and no spike on either hull; the barge's A and B within 0.55 %
  of the lid-free ones below 1.2 rad/s, the hemisphere's within 1.56 % (A) and 1.19 % (B) of
  Hulme's from K a = 0.05 to 2 (+1.0 % for B at K a = 3). At infinite frequency a lid at z = 0
  changes nothing (the potential is zero on it): A_inf is the lid-free one.

Ogilvie's consistency (``HydroDB.ogilvie``: A_inf from each frequency's A(w) and the retardation
function of B over 60 s, with the w^-3 tail, against the solver's A_inf) on make_barge.py's
frequencies with the lid at z = 0: the mean -0.78 % (heave) and -0.67 % (pitch), each frequency
within 1.65 % and 0.88 %. A tenth of the draft down gives -0.10 % and -0.24 % for the mean, but
through its own A_inf (heave 0.50 % under the lid-free one), not a better A(w): below 1.2 rad/s
both agree with the lid-free A(w) within 0.17 %. The hemisphere's A_inf is 1.90 % above the exact
0.5 rho V at 24 bands (1.56 % at 32, 1.31 % at 40), as the panels' error at finite frequencies
is. No other placement is offered: z = 0 is the one clean on both hulls. Capytaine's first solve
builds its Green-function table (about half a minute).
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
    body = cpt.FloatingBody(mesh=cmesh, lid_mesh=cmesh.generate_lid(z=0.0), name=name,
                            dofs=cpt.rigid_body_dofs(rotation_center=rotation_center),
                            center_of_mass=rotation_center)  # fmt: skip
    water = {"radiating_dof": list(body.dofs), "water_depth": [depth], "rho": [rho],
             "g": [gravity]}  # fmt: skip
    solver = cpt.BEMSolver()
    test = xr.Dataset(coords={
        "omega": omega, "wave_direction": np.radians(np.asarray(directions_deg, dtype=float)),
        **water,
    })  # fmt: skip
    order = {"radiating_dof": list(hydrodb.DOFS), "influenced_dof": list(hydrodb.DOFS)}
    ds = solver.fill_dataset(test, body).sel(order)
    # the radiation alone at infinite frequency (no diffraction is defined there)
    limit = solver.fill_dataset(xr.Dataset(coords={"omega": [np.inf], **water}), body).sel(order)

    def matrix(data, var):
        return data[var].transpose("omega", "influenced_dof", "radiating_dof").values

    def force(var):
        return np.asarray(ds[var].transpose("omega", "wave_direction", "influenced_dof").values)

    return hydrodb.HydroDB(
        omega=np.asarray(ds.coords["omega"].values, float), added_mass=matrix(ds, "added_mass"),
        damping=matrix(ds, "radiation_damping"),
        directions=np.asarray(ds.coords["wave_direction"].values, float),
        diffraction=force("diffraction_force"), froude_krylov=force("Froude_Krylov_force"),
        reference_point=np.asarray(rotation_center, float), rho=rho, gravity=gravity,
        depth=depth, source=f"capytaine {cpt.__version__}: {name}",
        infinite=np.asarray(matrix(limit, "added_mass")[0], float),
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
