"""A ship's propeller from its open-water curves (``model: propeller``): thrust and torque from
the rate of turn n [rev/s], the speed of advance and the curves K_T(J), K_Q(J).

At the body-frame point P, along the shaft's unit direction d (body frame; the thrust's
direction when turning ahead):

    u_a = s . d,    s = R^T (v + omega x r_P - c(z_P))     the propeller's speed through the
                                                           water along its shaft [m/s]
    V_a = (1 - w) u_a,    J = V_a / (n D)
    T = (1 - t) rho n^2 D^4 K_T(J)     along d        (the thrust the hull feels)
    Q = rho n^2 D^5 K_Q(J) / eta_R     about d

c the current at P's elevation (as the rudder's inflow), w the wake fraction, t the thrust
deduction, D the diameter [m], eta_R the relative rotative efficiency. The torque the water
puts on the turning propeller reaches the hull through the shaft and the engine's seat: a
moment -sigma Q d, sigma = +1 for a right-handed propeller (clockwise seen from astern,
looking along d, when turning ahead), -1 for a left-handed one (a right-handed propeller
heels its ship to port). The thrust acts at P (its moment about the reference point follows).

n >= 0 only: a stopped propeller (n = 0, J undefined) gives neither thrust nor torque (its
drag as a locked or windmilling propeller is left out); a time function of n that goes below
0 is refused when the case is built, and the controller's n is limited to [0, n_max] (the
curves cover the first quadrant only: the propeller turning ahead). J beyond the curves is
held at their ends (clamped, not extrapolated): going astern with n > 0 (J < 0) takes the
first point's coefficients (the bollard values at J = 0 for the B-series), and faster than
the curves' last J their last point's (the B-series' end where K_T vanishes: no thrust, no
braking, K_Q held there).

n is a time function, or the surge-speed controller's law (``forces.speed_control``, as the
thruster's): n = n_ff(t) + K (U(t) - u) + K_i I, u the surge speed over ground of the
reference point, its integral I [m] a state (from 0) held while n is at 0 or n_max and the
error pushes it further.

The curves: a cubic in J for each of K_T and K_Q (the Wageningen B-series, ``forces.bseries``)
over [J_lo, J_hi], or a table of rows (J ascending, K_T, K_Q), linear between rows.

Row: P (3), d (3), D, 1 - w, 1 - t, sigma, 1 / eta_R, 1 with the controller, K [rev/s per
m/s], K_i [rev/s per m], n_max [rev/s] (0: none), the table's rows m (0: the cubics), J_lo,
J_hi, then the cubics (K_T's then K_Q's coefficients of J^0 to J^3) or m rows (J, K_T, K_Q).
Channels from the model's first: n [rev/s] or U [m/s], n_ff [rev/s].
"""

import math

import numpy as np
from numba import njit

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.case.ship_forces import BSeries
from seacable.forces import bseries, speed_control
from seacable.forces.coefficients import csv_rows, flow_at
from seacable.kernels.jit import JIT

CHANNELS = 2  # rate of turn (or target speed), feed-forward rate
DIAMETER, WAKE, DEDUCTION, HAND, ROTATIVE = 6, 7, 8, 9, 10
CONTROLLED, GAIN, INTEGRAL_GAIN, LIMIT, ROWS, J_LOW, J_HIGH = 11, 12, 13, 14, 15, 16, 17
HEADER = 18


def open_water(spec, base_dir=None) -> tuple[tuple, list[str]]:
    """The ``open_water`` curves of a propeller (``case.ship_forces.Propeller``) as ``pack``
    takes them, and what looks wrong with a table (lines: it starts beyond J = 0, so a ship
    starting from rest takes its first row; it ends with K_T > 0, so a faster ship keeps the
    last row's thrust; K_Q <= 0 somewhere). A ValueError line when its file cannot be read or
    its J do not increase."""
    curves = spec.open_water
    if isinstance(curves, BSeries):
        thrust, torque = bseries.cubics(curves.pitch_ratio, curves.area_ratio, curves.blades)
        return ("cubics", (0.0, bseries.zero_thrust(thrust)), thrust, torque), []
    if isinstance(curves.coefficients, str):
        rows = csv_rows(curves.coefficients, base_dir, (3,), "J, K_T, K_Q")
        if rows.shape[0] < 2 or np.any(np.diff(rows[:, 0]) <= 0.0):
            raise ValueError(f"coefficients file '{curves.coefficients}': give 2 rows or more "
                             "[J, K_T, K_Q] with J increasing strictly")  # fmt: skip
    else:
        rows = np.array(curves.coefficients, dtype=float)
    notes = []
    if rows[0, 0] > 0.0:
        notes.append(f"its first row is at J = {rows[0, 0]:g}: below it (a ship starting from "
                     "rest, the bollard pull at J = 0) K_T and K_Q are held at that row's; "
                     "give the curves from J = 0")  # fmt: skip
    if rows[-1, 1] > 0.0:
        notes.append(f"its last row (J = {rows[-1, 0]:g}) has K_T = {rows[-1, 1]:g} > 0: "
                     "beyond it the thrust is held, not falling to zero; give the curves to "
                     "where K_T vanishes")  # fmt: skip
    if np.any(rows[:, 2] <= 0.0):
        notes.append("K_Q is 0 or less in some rows: a propeller turning ahead absorbs torque "
                     "(K_Q > 0) up to beyond where K_T vanishes")  # fmt: skip
    return ("table", rows.tolist()), notes


def pack(point, direction, diameter, wake_fraction, thrust_deduction, right_handed: bool,
         rotative_efficiency, gains, max_rate, curves) -> list[float]:  # fmt: skip
    """The row: ``point`` P [m] and ``direction`` d (body frame, normalised), ``diameter`` D
    [m], w, t, whether right-handed, eta_R, the controller's ``gains`` (K [rev/s per m/s],
    K_i [rev/s per m]) or None, ``max_rate`` n_max [rev/s] or None, and the ``curves``:
    ("cubics", (J_lo, J_hi), K_T's and K_Q's coefficients of J^0 to J^3) or ("table", rows
    (J ascending, K_T, K_Q))."""
    norm = math.sqrt(sum(float(v) ** 2 for v in direction))
    kind, *data = curves
    if kind == "cubics":
        (low, high), thrust, torque = data
        rows, tail = 0, [*(float(c) for c in thrust), *(float(c) for c in torque)]
    else:
        table = [[float(v) for v in r] for r in data[0]]
        rows, low, high = len(table), table[0][0], table[-1][0]
        tail = [v for r in table for v in r]
    gain, integral_gain = gains or (0.0, 0.0)
    return [*(float(v) for v in point), *(float(v) / norm for v in direction), float(diameter),
            1.0 - float(wake_fraction), 1.0 - float(thrust_deduction),
            1.0 if right_handed else -1.0, 1.0 / float(rotative_efficiency),
            1.0 if gains else 0.0, float(gain), float(integral_gain), float(max_rate or 0.0),
            float(rows), float(low), float(high), *tail]  # fmt: skip


def state_count(row) -> int:
    """The controller's integral I [m] when it has an integral gain; none otherwise."""
    return speed_control.state_count(row, CONTROLLED, INTEGRAL_GAIN)


@njit(inline="always", **JIT)
def _law(row, first, t, rot, vel, tf, y, state):
    """n [rev/s] before its limits, and the controller's error U - u [m/s] (0 without it)."""
    return speed_control.command(row, CONTROLLED, GAIN, INTEGRAL_GAIN, first, t, rot, vel, tf,
                                 y, state)  # fmt: skip


@njit(inline="always", **JIT)
def _highest(row):
    """n_max [rev/s] (infinite without one)."""
    return row[LIMIT] if row[LIMIT] > 0.0 else math.inf


@njit(inline="always", **JIT)
def rate(row, first, t, rot, vel, tf, y, state):
    """The rate of turn n [rev/s], within [0, n_max] (``y[state]``: the controller's
    integral; ``state`` -1: none)."""
    value, _ = _law(row, first, t, rot, vel, tf, y, state)
    return min(_highest(row), max(0.0, value))


@njit(inline="always", **JIT)
def rates(row, first, t, rot, vel, tf, y, state, ydot):
    """dI/dt = U - u into ``ydot[state]``, 0 while n is held at a limit the error pushes it
    beyond (forces.speed_control)."""
    value, error = _law(row, first, t, rot, vel, tf, y, state)
    ydot[state] = speed_control.integral_rate(value, error, 0.0, _highest(row))


@njit(inline="always", **JIT)
def curves(row, advance):
    """K_T and K_Q at the advance ratio ``advance`` J, held at the curves' ends."""
    j = min(row[J_HIGH], max(row[J_LOW], advance))
    m = int(row[ROWS])
    if m == 0:
        at = HEADER
        thrust = row[at] + j * (row[at + 1] + j * (row[at + 2] + j * row[at + 3]))
        torque = row[at + 4] + j * (row[at + 5] + j * (row[at + 6] + j * row[at + 7]))
        return thrust, torque
    k = 0  # row k <= j < row k + 1
    while k < m - 2 and row[HEADER + 3 * (k + 1)] <= j:
        k += 1
    at = HEADER + 3 * k
    share = (j - row[at]) / (row[at + 3] - row[at])
    return (row[at + 1] + share * (row[at + 4] - row[at + 1]),
            row[at + 2] + share * (row[at + 5] - row[at + 2]))  # fmt: skip


@njit(inline="always", **JIT)
def advance_speed(row, pos, rot, vel, omega, current_z, current_u, current_v):
    """The propeller's speed through the water along its shaft, u_a [m/s], and its arm (the
    point P from the reference point, earth frame)."""
    # the water's flow past P, -s
    arm, w = flow_at((row[0], row[1], row[2]), pos, rot, vel, omega, current_z, current_u,
                     current_v)  # fmt: skip
    return -(w[0] * row[3] + w[1] * row[4] + w[2] * row[5]), arm


@njit(inline="always", **JIT)
def add(row, first, t, rho, pos, rot, vel, omega, current_z, current_u, current_v, tf, y,
        state, rhs):  # fmt: skip
    """The thrust at P and its moment, and the shaft's torque, in the earth frame, added to
    ``rhs`` (``y[state]``: the controller's integral; ``state`` -1: none)."""
    n = rate(row, first, t, rot, vel, tf, y, state)
    if n <= 0.0:
        return
    speed, arm = advance_speed(row, pos, rot, vel, omega, current_z, current_u, current_v)
    diameter = row[DIAMETER]
    kt, kq = curves(row, row[WAKE] * speed / (n * diameter))
    scale = rho * n * n * diameter**4
    thrust = row[DEDUCTION] * scale * kt
    torque = -row[HAND] * scale * diameter * kq * row[ROTATIVE]
    d = (row[3], row[4], row[5])
    f0, f1, f2 = turn(rot, (thrust * d[0], thrust * d[1], thrust * d[2]))
    add_force(arm, f0, f1, f2, rhs)
    m0, m1, m2 = turn(rot, (torque * d[0], torque * d[1], torque * d[2]))
    rhs[3] += m0
    rhs[4] += m1
    rhs[5] += m2
