"""Write ``box.hdb``, the HDB file (AQUA+'s layout, as xdyn's documentation describes it) of
tests/test_hydrodb_formats.py, from ``box.nc`` (Capytaine's box, our conventions) at five of its
periods, by the rules derived by hand in seacable.hydrodb_formats: periods T = 2 pi / w [s],
headings [deg], A and B as they are (row i: the force in mode i), the excitation as modulus
|X| and phase phi = -arg(X) [rad] (AQUA+'s F = -|X| a sin(k x - w t + p - phi) against our
F = Re(X a e^{i (k x - w t + p')}), p' = p + pi/2), seven significant digits.

Run from the repository root: ``python tests/data/make_hdb.py`` (no Capytaine needed).
"""

import math
from pathlib import Path

import numpy as np

from seacable import hydrodb

HERE = Path(__file__).parent
KEEP = [0, 3, 6, 9, 12]  # the frequencies of box.nc kept (0.4, 1.3, 2.2, 3.1, 4.0 rad/s)


def _row(period, values):
    return f"  {period:10.6f}" + "".join(f"  {v: .6E}" for v in values)


def main():
    db = hydrodb.read(HERE / "box.nc")
    order = KEEP[::-1]  # by increasing period
    periods = 2.0 * math.pi / db.omega[order]
    headings = np.degrees(db.directions)
    out = [
        " [SOFT] AQUA+",
        "[FORWARD_SPEED]   0.00",
        f"[PERIODS_NUMBER]  {len(order)}",
        f"[HEADINGS_NUMBER] {len(headings)}",
        f"[LOWEST_HEADINGS]  {headings.min():.2f}",
        f"[HIGHEST_HEADINGS] {headings.max():.2f}",
        " [List_calculated_periods]",
    ]
    out += [f"  {p:10.6f}" for p in periods]
    out += [" [List_calculated_headings]"] + [f"  {h:10.5f}" for h in headings]
    out += [" [Hydrostatic_matrix]"]
    out += ["".join(f"  {v: .6E}" for v in row) for row in db.hydrostatic_stiffness]
    out += [" [Added_mass_Radiation_Damping]"]
    for name, matrix in (("ADDED_MASS_LINE", db.added_mass), ("DAMPING_TERM", db.damping)):
        for i in range(6):
            out += [f" [{name}_{i + 1}]"]
            out += [_row(p, matrix[k, i]) for p, k in zip(periods, order, strict=True)]
    for section, force in (
        ("DIFFRACTION_FORCES_AND_MOMENTS", db.diffraction),
        ("FROUDE-KRYLOV_FORCES_AND_MOMENTS", db.froude_krylov),
    ):
        out += [f" [{section}]"]
        for kind, part in (("MOD", np.abs(force)), ("PH", -np.angle(force))):
            for m, h in enumerate(headings):
                out += [f" [INCIDENCE_EFM_{kind}_001]   {h:.6f}"]
                out += [_row(p, part[k, m]) for p, k in zip(periods, order, strict=True)]
    (HERE / "box.hdb").write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
