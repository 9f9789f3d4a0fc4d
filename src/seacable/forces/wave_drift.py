"""The mean wave drift force on a ship from coefficient tables: ``model: wave drift``.

The mean (time-averaged) second-order wave force in the body's horizontal plane, for the
incident sea of the case (``environment.waves``, realised into components by ``seastate``:
amplitude a_i [m], angular frequency w_i [rad/s], the direction b_i the waves travel towards;
kernels.waves), is

    F_x = sum_i a_i^2 D_X(w_i, beta_i)      [N], along the body's x (forward)
    F_y = sum_i a_i^2 D_Y(w_i, beta_i)      [N], along the body's y (to port)
    M_z = sum_i a_i^2 D_N(w_i, beta_i)      [N m], about the body's z (up) through P

with D_X, D_Y [N/m^2] and D_N [N m/m^2] the drift coefficients per unit squared wave
amplitude (a quadratic transfer function's diagonal, as WAMIT's or a model test's mean drift
divided by a^2) and beta_i the relative wave heading: the direction the component comes FROM,
in the body frame, from the bow (+x) towards port (+y), counter-clockwise seen from above
(0: head seas, 90 deg: from port, 180 deg: following seas; the wind's psi_r), so beta_i =
b_i + pi - psi with psi the heading of the body's x axis: the force turns with the ship. The
force acts at P (its moment about the reference point follows). For a spectrum, a_i^2 =
2 S(w_i) dw, so the sum is 2 int S(w) D(w, beta) dw; with a table independent of frequency it
is D(beta) sum a_i^2 = D(beta) Hs^2 / 8 (the bands seastate keeps). For a regular wave of
height H, a = H / 2. The force rises with the sea over ``simulation.build_up`` (the ramp
squared, as a^2); the statics, taken in still water, do not feel it.

The tables: rows [beta_deg, D_X, D_Y, D_N] (one table, for every frequency) or [w [rad/s],
beta_deg, D_X, D_Y, D_N] (a table per frequency, the frequencies ascending, each with the same
headings), inline or a CSV file of those columns. The headings ascend over less than 360 deg
and are interpolated linearly and periodically (``forces.coefficients.periodic``, the wind's
and current's); the frequencies linearly, held at the first and last (give a row of zeros at
a low frequency for the long waves' vanishing drift). ``symmetric``: 0 to 180 deg given, the
other side mirrored (D_X even, D_Y and D_N odd in beta), for a port-starboard symmetric hull.

Left out: the slowly varying (difference-frequency, Newman) drift and its resonance with the
moorings; the drift's change with the ship's own speed (wave-current interaction, wave drift
damping); the waves' first-order loads (``diffraction``, ``non-linear Froude-Krylov``), which
are separate models.

Row: P (3), m frequencies, n headings, the m frequencies [rad/s] (0 when the table does not
depend on frequency), then m tables of n rows (beta [rad] ascending, D_X, D_Y, D_N).
"""

import math

import numpy as np
from numba import njit

from seacable.bodies.kinematics import turn
from seacable.forces.coefficients import add_plane_load, csv_rows, heading_table, periodic
from seacable.kernels import waves
from seacable.kernels.jit import JIT

HEADER = 5
COLUMNS = 4  # beta, D_X, D_Y, D_N
NAMES = "[beta_deg, D_X, D_Y, D_N] or [omega, beta_deg, D_X, D_Y, D_N]"


def tables(spec, base_dir=None) -> tuple[np.ndarray, list[np.ndarray]]:
    """The frequencies [rad/s] (one 0: independent of frequency) and, per frequency, the rows
    (beta [deg], D_X, D_Y, D_N) of a ``wave drift`` model's ``coefficients``, mirrored when
    ``symmetric``; a ValueError line when they are malformed."""
    if isinstance(spec.coefficients, str):
        rows = csv_rows(spec.coefficients, base_dir, (COLUMNS, COLUMNS + 1), NAMES)
    else:
        widths = {len(r) for r in spec.coefficients}
        if len(widths) != 1:
            raise ValueError(f"coefficients: rows of {sorted(widths)} numbers; give every row "
                             f"as {NAMES}")  # fmt: skip
        rows = np.array(spec.coefficients, dtype=float)
    if rows.shape[1] == COLUMNS:
        return np.zeros(1), [heading_table(rows, spec.symmetric, NAMES)]
    omegas, first = np.unique(rows[:, 0], return_index=True)
    if np.any(np.diff(rows[:, 0]) < 0.0) or omegas[0] <= 0.0:
        raise ValueError(f"coefficients: frequencies {omegas.tolist()} [rad/s] must be "
                         "positive, the rows grouped by frequency in ascending order")  # fmt: skip
    per = [heading_table(rows[rows[:, 0] == w, 1:], spec.symmetric, NAMES) for w in omegas]
    for w, table in zip(omegas, per, strict=True):
        if table.shape != per[0].shape or np.any(table[:, 0] != per[0][:, 0]):
            raise ValueError(f"coefficients: the headings at {w:g} rad/s "
                             f"{table[:, 0].tolist()} differ from those at {omegas[0]:g} "
                             f"rad/s {per[0][:, 0].tolist()}; give every frequency the same "
                             "headings")  # fmt: skip
    return omegas, per


def pack(point, omegas, per) -> list[float]:
    """The row: ``point`` P (body frame) [m], the ``omegas`` [rad/s] and their tables ``per``
    (rows beta [deg], D_X [N/m^2], D_Y [N/m^2], D_N [N m/m^2])."""
    n = per[0].shape[0]
    out = [*(float(v) for v in point), float(len(omegas)), float(n),
           *(float(w) for w in omegas)]  # fmt: skip
    for table in per:
        for r in table:
            out += [math.radians(r[0]), float(r[1]), float(r[2]), float(r[3])]
    return out


@njit(inline="always", **JIT)
def _frequency(row, m, omega):
    """(j, f): the frequency interval of the row's m frequencies holding ``omega`` [rad/s]
    and the fraction across it (held at the ends: f = 0)."""
    if m == 1 or omega <= row[HEADER]:
        return 0, 0.0
    if omega >= row[HEADER + m - 1]:
        return m - 1, 0.0
    j = 0
    while row[HEADER + j + 1] <= omega:
        j += 1
    lo, hi = row[HEADER + j], row[HEADER + j + 1]
    return j, (omega - lo) / (hi - lo)


@njit(inline="always", **JIT)
def coefficients(row, omega, beta):
    """(D_X, D_Y, D_N) at ``omega`` [rad/s] and the relative heading ``beta`` [rad]."""
    m, n = int(row[3]), int(row[4])
    j, f = _frequency(row, m, omega)
    at = HEADER + m + COLUMNS * n * j
    dx = periodic(row, at, n, COLUMNS, 1, beta)
    dy = periodic(row, at, n, COLUMNS, 2, beta)
    dn = periodic(row, at, n, COLUMNS, 3, beta)
    if f > 0.0:
        at += COLUMNS * n
        dx += f * (periodic(row, at, n, COLUMNS, 1, beta) - dx)
        dy += f * (periodic(row, at, n, COLUMNS, 2, beta) - dy)
        dn += f * (periodic(row, at, n, COLUMNS, 3, beta) - dn)
    return dx, dy, dn


@njit(inline="always", **JIT)
def add(row, t, wave, rot, rhs):
    """The mean drift of the sea ``wave`` (kernels.waves table; none in still water) at P, in
    the earth frame, added to ``rhs``."""
    count = wave.shape[1]
    if count == 0:
        return
    heading = math.atan2(rot[1, 0], rot[0, 0])
    fx, fy, mz = 0.0, 0.0, 0.0
    for i in range(count):
        a2 = wave[waves.A, i] * wave[waves.A, i]
        beta = math.atan2(-wave[waves.SIN, i], -wave[waves.COS, i]) - heading
        dx, dy, dn = coefficients(row, wave[waves.W, i], beta)
        fx += a2 * dx
        fy += a2 * dy
        mz += a2 * dn
    r = waves.ramp(wave, t)[0]
    r2 = r * r
    arm = turn(rot, (row[0], row[1], row[2]))
    add_plane_load(rot, arm, r2 * fx, r2 * fy, r2 * mz, rhs)
