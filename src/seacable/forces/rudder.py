"""A rudder of a vessel (``model: rudder``): lift and drag of a foil of area A [m^2] at a
body-frame point P, in the horizontal body plane (``forces.foil``: the foil's law, with its
span down, a = -z, and its chord at zero angle ahead, c0 = +x).

Rudder angle delta [rad]: positive with the trailing edge to port (+y), which turns a ship
going ahead to port (a positive yaw rate, counter-clockwise seen from above) when the rudder is
aft. The foil's chord, trailing edge to leading edge, points along e = (cos delta, -sin delta)
in the body frame.

Inflow: s = R^T (v + omega x r_P - c(z_P)), the rudder's velocity through the water in the body
frame (c the current at P's elevation), its x component times the slipstream factor k (a
propeller's wash); (s_x, s_y) its horizontal part, V its length. The angle of attack alpha is
the signed angle from e to (s_x, s_y) (counter-clockwise positive: alpha = delta when going
straight ahead), folded into [-90, 90] deg (the foil taken as symmetric fore and aft, for flow
from astern). With q = 1/2 rho V^2, the force in the body frame is

    F = q A (C_L(alpha) (s_y, -s_x) / V - C_D(alpha) (s_x, s_y) / V),

lift perpendicular to the inflow, drag along the water's flow past the foil. C_L = a alpha up
to the stall angle and held at a alpha_stall beyond (a the lift slope [1/rad]), C_D = C_D0 +
C_L^2 / (pi Lambda) (Lambda the aspect ratio; no induced drag when not given); or C_L, C_D from
a table in alpha (held at its end values).

delta is a time function, or the heading autopilot's PD law
delta = K_p wrap(psi_t - psi) - K_d r, psi the heading (atan2(R_10, R_00)), r the yaw rate
(omega_z) [rad/s], K_p [-], K_d [s], limited to +-max_angle.

The steering gear (optional): the law above is then the command delta_c, and delta is a
state of the system, from 0 (amidships), that follows it as a rate-limited first-order lag,

    d delta/dt = clip((delta_c - delta) / T, -rate, rate),

T the gear's time constant [s], ``rate`` its largest turning rate [rad/s] (SOLAS II-1/29 asks
for 35 deg on one side to 30 deg on the other within 28 s: 2.3 deg/s).

Row: P (3), k, 1 with the autopilot, K_p, K_d, the largest |delta| [rad] (0: none), the gear's
rate [rad/s] (0: no gear) and T [s], then the foil's block (``forces.foil``: A, a,
alpha_stall, C_D0, 1/(pi Lambda), the table). Channel: delta, or psi_t [rad].
"""

import math

from numba import njit

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.forces import foil
from seacable.forces.coefficients import flow_at
from seacable.kernels.jit import JIT
from seacable.kernels.timefn import evaluate

SLIPSTREAM, AUTOPILOT, GAIN, RATE_GAIN, LIMIT, GEAR_RATE, GEAR_TIME = 3, 4, 5, 6, 7, 8, 9
FOIL = 10  # the foil's block
SPAN, CHORD = (0.0, 0.0, -1.0), (1.0, 0.0, 0.0)


def pack(point, area, lift_slope, stall_deg, drag, aspect_ratio, slipstream, autopilot,
         max_angle_deg, table, gear=None) -> list[float]:  # fmt: skip
    """The row: ``point`` P [m] (body frame), ``area`` [m^2], ``lift_slope`` [1/rad], the stall
    angle [deg], C_D0, the aspect ratio (None: no induced drag), the slipstream factor, the
    autopilot's (K_p, K_d [s]) or None, the largest |delta| [deg] (None: none), the table's
    rows (alpha [deg], C_L, C_D) or None, the steering gear's (rate [deg/s], T [s]) or
    None."""
    gains = autopilot or (0.0, 0.0)
    rate, lag = gear or (0.0, 0.0)
    return [*(float(v) for v in point), float(slipstream), 1.0 if autopilot else 0.0,
            float(gains[0]), float(gains[1]), math.radians(max_angle_deg or 0.0),
            math.radians(rate), float(lag),
            *foil.pack(area, lift_slope, stall_deg, drag, aspect_ratio, table)]  # fmt: skip


def state_count(row) -> int:
    """The rudder's angle when it has a steering gear; none otherwise."""
    return 1 if row[GEAR_RATE] > 0.0 else 0


@njit(inline="always", **JIT)
def angle(row, first, t, rot, omega, tf):
    """The rudder angle delta [rad] its law commands: its time function or the
    autopilot's, limited."""
    breaks, coefs, count, sine, build_up = tf
    value, _, _ = evaluate(breaks, coefs, count, sine, build_up, first, t)
    if row[AUTOPILOT] != 0.0:
        heading = math.atan2(rot[1, 0], rot[0, 0])
        error = value - heading
        error -= 2.0 * math.pi * math.floor((error + math.pi) / (2.0 * math.pi))  # [-pi, pi)
        value = row[GAIN] * error - row[RATE_GAIN] * omega[2]
    return foil.limited(value, row[LIMIT])


@njit(inline="always", **JIT)
def rates(row, first, t, rot, omega, tf, y, state, ydot):
    """The steering gear's d delta/dt into ``ydot[state]``."""
    command = angle(row, first, t, rot, omega, tf)
    ydot[state] = foil.gear_rate(command, y[state], row[GEAR_RATE], row[GEAR_TIME])


@njit(inline="always", **JIT)
def add(row, first, t, rho, pos, rot, vel, omega, current_z, current_u, current_v, tf, y,
        state, rhs):  # fmt: skip
    """The rudder's lift and drag at P, in the earth frame, added to ``rhs`` (``y[state]``:
    the steering gear's angle; ``state`` -1: none)."""
    # the water's flow past P, -s
    arm, w = flow_at((row[0], row[1], row[2]), pos, rot, vel, omega, current_z, current_u,
                     current_v)  # fmt: skip
    delta = y[state] if state >= 0 else angle(row, first, t, rot, omega, tf)
    inflow = (-w[0] * row[SLIPSTREAM], -w[1], -w[2])
    fx, fy, fz = foil.force(row, FOIL, rho, inflow, SPAN, CHORD, delta)
    f0, f1, f2 = turn(rot, (fx, fy, fz))
    add_force(arm, f0, f1, f2, rhs)
