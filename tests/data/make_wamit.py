"""Regenerate the small databases of tests/test_hydrodb_formats.py with Capytaine (the [bem]
extra): one BEM run on a box offset from the origin (so that the matrices couple every mode
and the excitation's phase depends on where the waves meet the hull), exported twice:

- by Capytaine's own WAMIT writer (``capytaine.io.wamit.export_to_wamit``): ``box.1`` (with the
  infinite-frequency row, WAMIT's PER = 0), ``box.3``, ``box.3fk``, ``box.3sc``, ``box.hst``;
  and ``box_ulen2.1``, ``box_ulen2.3``, nondimensionalised with WAMIT's ULEN = 2 m;
- by seacable (``hydrodb.write``, our conventions): ``box.nc``.

Run from the repository root: ``python tests/data/make_wamit.py`` (about a minute: Capytaine
builds its Green-function table first).
"""

import math
from pathlib import Path

import capytaine as cpt
import numpy as np
import xarray as xr
from capytaine.io.wamit import _export_wamit_excitation_force, export_to_wamit, export_wamit_1

from seacable import hydrodb, meshes

HERE = Path(__file__).parent
CENTRE = (0.6, 0.25, 0.0)  # the box's centre [m]: off the origin, the database's point
OMEGA = np.linspace(0.4, 4.0, 13)  # [rad/s]
DIRECTIONS_DEG = (0.0, 45.0, 90.0)
RHO, G = 1025.0, 9.81


def _body():
    hull = meshes.box(2.0, 1.2, 1.0, n=6)
    cmesh = cpt.Mesh(vertices=hull.vertices + np.array(CENTRE), faces=hull.triangles, name="box")
    cmesh = cmesh.immersed_part()
    lid = cmesh.generate_lid(z=cmesh.lowest_lid_position(float(OMEGA.max()), g=G))
    return cpt.FloatingBody(
        mesh=cmesh,
        lid_mesh=lid,
        name="box",
        dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)),
        center_of_mass=(CENTRE[0], CENTRE[1], -0.1),
        mass=RHO * 1.2,
    )


def main():
    body = _body()
    omega = np.concatenate([OMEGA, [np.inf]])  # inf: the radiation problems only (WAMIT's PER 0)
    test = xr.Dataset(
        coords={
            "omega": omega,
            "wave_direction": np.radians(DIRECTIONS_DEG),
            "radiating_dof": list(body.dofs),
            "water_depth": [math.inf],
            "rho": [RHO],
            "g": [G],
        }
    )
    ds = cpt.BEMSolver().fill_dataset(test, body, hydrostatics=True)
    export_to_wamit(ds, str(HERE / "box"), exports=("1", "3", "3fk", "3sc", "hst"))
    # the same run nondimensionalised with WAMIT's ULEN = 2 m (its .hst is left out: Capytaine
    # 3.0 scales it with the added mass's powers of L, not WAMIT's)
    export_wamit_1(ds, str(HERE / "box_ulen2.1"), length_scale=2.0)
    _export_wamit_excitation_force(
        ds, "excitation_force", str(HERE / "box_ulen2.3"), length_scale=2.0
    )
    order = {"radiating_dof": list(hydrodb.DOFS), "influenced_dof": list(hydrodb.DOFS)}
    ds = ds.sel(order)

    def matrix(name, at):
        return ds[name].sel(omega=at).transpose(..., "influenced_dof", "radiating_dof").values

    def force(name):
        return np.asarray(
            ds[name].sel(omega=OMEGA).transpose("omega", "wave_direction", "influenced_dof").values
        )

    db = hydrodb.HydroDB(
        omega=OMEGA,
        added_mass=matrix("added_mass", OMEGA),
        damping=matrix("radiation_damping", OMEGA),
        directions=np.radians(DIRECTIONS_DEG),
        diffraction=force("diffraction_force"),
        froude_krylov=force("Froude_Krylov_force"),
        reference_point=np.zeros(3),
        infinite=matrix("added_mass", np.inf),
        rho=RHO,
        gravity=G,
        hydrostatic_stiffness=ds["hydrostatic_stiffness"]
        .transpose("influenced_dof", "radiating_dof")
        .values,
        source=f"capytaine {cpt.__version__}: box 2 x 1.2 x 1 m centred at {CENTRE}",
    )
    hydrodb.write(db, HERE / "box.nc")


if __name__ == "__main__":
    main()
