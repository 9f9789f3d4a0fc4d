"""Regenerate the box barge of the moored-vessel example: its hull mesh (barge.stl, 90 m x 24 m,
12 m deep, the waterline at mid-depth: draft 6 m) and its hydrodynamic database
(barge_hydrodb.nc, computed with Capytaine: pip install 'seacable[bem]').

    python examples/data/make_barge.py
"""

from pathlib import Path

import numpy as np

from seacable import bem, hydrodb, meshes

HERE = Path(__file__).parent
LENGTH, BEAM, DEPTH, PANEL = 90.0, 24.0, 12.0, 3.0  # [m]


def main() -> None:
    hull = meshes.barge(LENGTH, BEAM, DEPTH, PANEL)
    meshes.write_stl(hull, HERE / "barge.stl")
    omega = np.linspace(0.1, 1.8, 35)  # [rad/s]: panels of 3 m resolve waves to 1.8 rad/s
    db = bem.compute(hull, omega, directions_deg=np.arange(0.0, 360.0, 30.0), name="barge")
    hydrodb.write(db, HERE / "barge_hydrodb.nc")
    print(f"{len(hull.triangles)} triangles; {len(db.omega)} frequencies, "
          f"{len(db.directions)} directions")


if __name__ == "__main__":
    main()
