"""Wind and current loads on a vessel from coefficient tables (OCIMF style): ``model: wind``
and ``model: current``.

With V_r the speed [m/s] of the flow (air or water) relative to the coefficients' point P in
the horizontal body plane and psi_r the direction it comes FROM, measured in the body frame
from the bow (+x) towards port (+y, counter-clockwise seen from above; 0: from ahead, 90 deg:
from port, 180 deg: from astern):

    F_x = 1/2 rho V_r^2 A_T C_X(psi_r)        [N], along the body's x (forward)
    F_y = 1/2 rho V_r^2 A_L C_Y(psi_r)        [N], along the body's y (to port)
    M_z = 1/2 rho V_r^2 A_L L C_N(psi_r)      [N m], about the body's z (up) through P

C_X, C_Y, C_N dimensionless (SI: V_r in m/s, rho in kg/m^3, A_T the transverse and A_L the
lateral projected area [m^2], L the length [m]), interpolated linearly in psi_r, periodic over
360 deg. The flow relative to P: w = c - (v + omega x r_P) (earth frame), c the current at P's
elevation (``model: current``, rho the water's) or the wind (``model: wind``, rho the air's),
its body-frame x and y components giving V_r and psi_r = atan2(-w_y, -w_x). The force acts at
P (its moment about the reference point follows). Row: P (3), A_T, A_L, L, the air density,
the wind's first channel (speed, then direction; -1: current), the table's rows n, then n rows
(psi [rad] ascending, C_X, C_Y, C_N).
"""

import math

import numpy as np
from numba import njit

from seacable import files
from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn, turn_back
from seacable.case.base import LARGEST_NUMBER, Table
from seacable.kernels import chain3d as c3
from seacable.kernels.jit import JIT
from seacable.kernels.timefn import evaluate

HEADER = 9
COLUMNS = 4  # psi, C_X, C_Y, C_N


def table_rows(spec, base_dir=None) -> np.ndarray:
    """The rows (psi [deg], C_X, C_Y, C_N) of a ``wind`` or ``current`` model's
    ``coefficients`` (inline, or a CSV file), mirrored when ``symmetric``; a ValueError line
    when the file cannot be read or the angles are not ascending within 360 deg."""
    if isinstance(spec.coefficients, str):
        rows = csv_rows(spec.coefficients, base_dir, (COLUMNS,), "psi_deg, C_X, C_Y, C_N")
    else:
        rows = np.array(spec.coefficients, dtype=float).reshape(-1, COLUMNS)
    return heading_table(rows, spec.symmetric, "[psi_deg, C_X, C_Y, C_N]")


def heading_table(rows: np.ndarray, symmetric: bool, columns: str) -> np.ndarray:
    """``rows`` (angle [deg], X, Y, N) checked (at least 2, the angles increasing strictly
    over less than 360 deg) and, when ``symmetric`` (0 to 180 deg given), mirrored: X even,
    Y and N odd in the angle. ``columns`` names them in the messages (ValueError lines)."""
    if rows.shape[0] < 2:
        raise ValueError(f"coefficients: give at least 2 rows {columns}")
    psi = rows[:, 0]
    if np.any(np.diff(psi) <= 0) or psi[-1] - psi[0] >= 360.0:
        raise ValueError(f"coefficients: angles {psi.tolist()} must increase strictly and "
                         "span less than 360 deg")  # fmt: skip
    if symmetric:
        if psi[0] < 0.0 or psi[-1] > 180.0:
            raise ValueError(f"coefficients: a symmetric table covers 0 to 180 deg; its "
                             f"angles run from {psi[0]:g} to {psi[-1]:g}")  # fmt: skip
        inside = rows[(psi > 0.0) & (psi < 180.0)][::-1]
        mirror = np.column_stack([360.0 - inside[:, 0], inside[:, 1], -inside[:, 2],
                                  -inside[:, 3]])  # fmt: skip
        rows = np.vstack([rows, mirror])
    return rows


def csv_rows(file: str, base_dir, widths: tuple[int, ...], names: str) -> np.ndarray:
    """The rows of a CSV file of numbers, each row of one of ``widths`` columns, all alike
    (comment lines with '#', a header allowed); ``names`` the columns, for the messages."""
    text = Table(kind="table", file=file).text(base_dir)
    rows: list[list[float]] = []
    header = False
    for _, row in files.csv_rows(text, f"coefficients file '{file}'", ValueError):
        try:
            values = [float(v) for v in row]
        except ValueError:
            if rows or header:
                raise ValueError(f"coefficients file '{file}': bad row {row!r}") from None
            header = True  # one header line, before the numbers
            continue
        if len(values) not in widths or (rows and len(values) != len(rows[0])):
            raise ValueError(f"coefficients file '{file}': row {row!r} needs "
                             f"{' or '.join(map(str, widths))} columns ({names}), as many "
                             "as the first row")  # fmt: skip
        rows.append(values)
    data = np.array(rows, dtype=float).reshape(-1, len(rows[0]) if rows else widths[0])
    if not np.all(np.isfinite(data)) or (data.size and np.abs(data).max() > LARGEST_NUMBER):
        raise ValueError(f"coefficients file '{file}': NaN, infinite or huge values (beyond "
                         f"{LARGEST_NUMBER:.0e})")  # fmt: skip
    return data


def pack(point, areas, length, air_density, wind_channel, table) -> list[float]:
    """The row: ``point`` P (body frame) [m], ``areas`` (A_T, A_L) [m^2], ``length`` L [m],
    ``air_density`` [kg/m^3] (wind), ``wind_channel`` (the wind's speed channel; -1: the
    current's load), ``table`` rows (psi [deg] ascending over less than 360 deg, C_X, C_Y,
    C_N)."""
    rows = [[math.radians(r[0]), float(r[1]), float(r[2]), float(r[3])] for r in table]
    return [*(float(v) for v in point), float(areas[0]), float(areas[1]), float(length),
            float(air_density), float(wind_channel), float(len(rows)),
            *(v for r in rows for v in r)]  # fmt: skip


@njit(inline="always", **JIT)
def periodic(row, at, n, width, column, angle):
    """Column ``column`` of the table of ``n`` rows of ``width`` floats from ``row[at]`` (its
    first column the angle [rad], ascending, spanning at most 2 pi), interpolated linearly at
    ``angle`` [rad], periodic over 2 pi (between the last row and the first plus 2 pi)."""
    first = row[at]
    turns = math.floor((angle - first) / (2.0 * math.pi))
    a = angle - 2.0 * math.pi * turns  # in [first, first + 2 pi)
    lo, hi = 0, n - 1
    if a >= row[at + width * (n - 1)]:  # past the last row: towards the first, 2 pi on
        a0, a1 = row[at + width * (n - 1)], first + 2.0 * math.pi
        y0, y1 = row[at + width * (n - 1) + column], row[at + column]
    else:
        while hi - lo > 1:  # row lo <= a < row hi
            mid = (lo + hi) // 2
            if row[at + width * mid] <= a:
                lo = mid
            else:
                hi = mid
        a0, a1 = row[at + width * lo], row[at + width * hi]
        y0, y1 = row[at + width * lo + column], row[at + width * hi + column]
    if a1 <= a0:
        return y0
    return y0 + (y1 - y0) * (a - a0) / (a1 - a0)


@njit(inline="always", **JIT)
def relative_flow(arm, rot, vel, omega, fx, fy):
    """The flow (fx, fy, 0) [m/s] (earth frame) relative to the point at ``arm`` (earth frame,
    from the reference point) of a body moving with ``vel`` and ``omega``, in the body frame."""
    px = vel[0] + omega[1] * arm[2] - omega[2] * arm[1]
    py = vel[1] + omega[2] * arm[0] - omega[0] * arm[2]
    pz = vel[2] + omega[0] * arm[1] - omega[1] * arm[0]
    return turn_back(rot, (fx - px, fy - py, -pz))


@njit(inline="always", **JIT)
def flow_at(point, pos, rot, vel, omega, current_z, current_u, current_v):
    """The arm of the body-frame ``point`` [m] (earth frame, from the reference point) and the
    water's flow past it in the body frame (``relative_flow``, the current at its elevation):
    a rudder's, a fin's or a propeller's inflow is minus that flow."""
    arm = turn(rot, point)
    cu, cv = c3._current(current_z, current_u, current_v, pos[2] + arm[2])
    return arm, relative_flow(arm, rot, vel, omega, cu, cv)


@njit(inline="always", **JIT)
def add(row, t, tf, rho, pos, rot, vel, omega, current_z, current_u, current_v, rhs):
    """The wind's or the current's load at P, in the earth frame, added to ``rhs``."""
    arm = turn(rot, (row[0], row[1], row[2]))
    wind = int(row[7])
    if wind >= 0:
        density = row[6]
        breaks, coefs, count, sine, build_up = tf
        speed, _, _ = evaluate(breaks, coefs, count, sine, build_up, wind, t)
        towards, _, _ = evaluate(breaks, coefs, count, sine, build_up, wind + 1, t)
        fx, fy = speed * math.cos(towards), speed * math.sin(towards)
    else:
        density = rho
        fx, fy = c3._current(current_z, current_u, current_v, pos[2] + arm[2])
    w = relative_flow(arm, rot, vel, omega, fx, fy)
    q = 0.5 * density * (w[0] * w[0] + w[1] * w[1])
    if q == 0.0:
        return
    psi = math.atan2(-w[1], -w[0])
    n = int(row[8])
    cx = periodic(row, HEADER, n, COLUMNS, 1, psi)
    cy = periodic(row, HEADER, n, COLUMNS, 2, psi)
    cn = periodic(row, HEADER, n, COLUMNS, 3, psi)
    add_plane_load(rot, arm, q * row[3] * cx, q * row[4] * cy, q * row[4] * row[5] * cn, rhs)


@njit(inline="always", **JIT)
def add_plane_load(rot, arm, fx, fy, moment, rhs):
    """A load in the body's horizontal plane: the force (``fx``, ``fy``) [N] (body frame) at
    the point at ``arm`` (earth frame, from the reference point) and the ``moment`` [N m]
    about the body's z through it, added to ``rhs`` in the earth frame."""
    f0, f1, f2 = turn(rot, (fx, fy, 0.0))
    add_force(arm, f0, f1, f2, rhs)
    rhs[3] += rot[0, 2] * moment
    rhs[4] += rot[1, 2] * moment
    rhs[5] += rot[2, 2] * moment
