"""A fin of a vessel (``model: fin``): a roll stabiliser's fin, or any foil fixed to the hull
and turned about its span, at a body-frame point P; its lift and drag are the foil's
(``forces.foil``) on its inflow.

Geometry (body frame): the span direction a (unit, from the root at the hull to the tip: a
starboard fin's is -y, a port fin's +y); the chord at zero angle, c0, is the body's x axis
made normal to a (the fin lying along the flow going ahead; a span along x is refused by the
schema). The
fin angle delta turns the chord about a by the right-hand rule: a starboard fin (a = -y) at
delta > 0 has its leading edge up, a port fin (a = +y) down, so that a pair at one angle
lifts the starboard side and pushes the port side down (a moment heeling the ship to port).

Inflow: s = R^T (v + omega x r_P - c(z_P)), the fin's velocity through the water in the body
frame, rotation included (c the current at P's elevation): a rolling ship's fin meets the
water at the angle its heave velocity makes, and damps the roll without being turned.

delta is a time function, or the roll controller's law

    delta = -sigma (K_p phi + K_d p),    limited to +-max_angle,

phi the roll angle (atan2(R_21, R_22), R = Rz Ry Rx), p the roll rate (the body-frame angular
velocity about x) [rad/s], K_p [-], K_d [s], and sigma = +1 or -1 the sign of the roll moment
about the reference point's x axis that a positive angle gives going ahead (from the fin's
point and span, with the lift slope positive), so that positive gains always oppose the
roll: the fin's moment is -|dM/d delta| (K_p phi + K_d p) whichever side it is on. A fin
whose lift has no roll moment is refused a roll controller. Going astern the lift reverses and
the law would feed the roll: it is a law for going ahead.

The actuator (optional): the law is then the command and delta a state from 0, d delta/dt =
clip((delta_c - delta) / T, -rate, rate) (``forces.foil``'s gear).

Row: P (3), a (3), c0 (3), 1 with the roll controller, sigma, K_p, K_d, the largest |delta|
[rad] (0: none), the actuator's rate [rad/s] (0: none) and T [s], then the foil's block.
Channel: delta [rad] (zero with the controller).
"""

import math

from numba import njit

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.forces import foil
from seacable.forces.coefficients import flow_at
from seacable.kernels.jit import JIT
from seacable.kernels.timefn import evaluate

CONTROLLED, SIGN, GAIN, RATE_GAIN, LIMIT, GEAR_RATE, GEAR_TIME = 9, 10, 11, 12, 13, 14, 15
FOIL = 16  # the foil's block


def geometry(point, span) -> tuple[tuple[float, ...], tuple[float, ...], float]:
    """The unit span a, the chord at zero angle c0 (the body's x made normal to a), and the
    roll moment about the reference point's x axis per unit lift going ahead (its sign is
    sigma's; 0: no roll moment). The span has a length and is not along x (the schema's
    ``Fin`` checks it)."""
    norm = math.sqrt(sum(float(v) ** 2 for v in span))
    a = tuple(float(v) / norm for v in span)
    chord = (1.0 - a[0] * a[0], -a[0] * a[1], -a[0] * a[2])  # x - (x . a) a
    length = math.sqrt(sum(v * v for v in chord))
    c0 = tuple(v / length for v in chord)
    lift = (a[1] * c0[2] - a[2] * c0[1], a[2] * c0[0] - a[0] * c0[2], a[0] * c0[1] - a[1] * c0[0])
    return a, c0, float(point[1]) * lift[2] - float(point[2]) * lift[1]  # (P x lift) . x


def pack(point, span, foil_block, controller, max_angle_deg, gear) -> list[float]:
    """The row: ``point`` P [m] and ``span`` a (body frame), the foil's block
    (``foil.pack``), the roll controller's (K_p, K_d [s]) or None, the largest |delta| [deg]
    (None: none), the actuator's (rate [deg/s], T [s]) or None. A ValueError line for a roll
    controller on a fin whose lift has no roll moment."""
    a, c0, arm = geometry(point, span)
    if controller and abs(arm) < 1e-9 * max(1.0, math.sqrt(sum(float(v) ** 2 for v in point))):
        raise ValueError("roll_controller: the fin's lift has no roll moment about the "
                         "reference point's x axis (its point and span put the lift through "
                         "it); move the fin, or give angle_deg")  # fmt: skip
    gains = controller or (0.0, 0.0)
    rate, lag = gear or (0.0, 0.0)
    return [*(float(v) for v in point), *a, *c0, 1.0 if controller else 0.0,
            1.0 if arm >= 0.0 else -1.0, float(gains[0]), float(gains[1]),
            math.radians(max_angle_deg or 0.0), math.radians(rate), float(lag),
            *foil_block]  # fmt: skip


def state_count(row) -> int:
    """The fin's angle when it has an actuator; none otherwise."""
    return 1 if row[GEAR_RATE] > 0.0 else 0


@njit(inline="always", **JIT)
def angle(row, first, t, rot, omega, tf):
    """The fin angle delta [rad] its law commands: its time function or the roll
    controller's, limited."""
    if row[CONTROLLED] != 0.0:
        roll = math.atan2(rot[2, 1], rot[2, 2])
        rate = rot[0, 0] * omega[0] + rot[1, 0] * omega[1] + rot[2, 0] * omega[2]
        value = -row[SIGN] * (row[GAIN] * roll + row[RATE_GAIN] * rate)
    else:
        breaks, coefs, count, sine, build_up = tf
        value, _, _ = evaluate(breaks, coefs, count, sine, build_up, first, t)
    return foil.limited(value, row[LIMIT])


@njit(inline="always", **JIT)
def rates(row, first, t, rot, omega, tf, y, state, ydot):
    """The actuator's d delta/dt into ``ydot[state]``."""
    command = angle(row, first, t, rot, omega, tf)
    ydot[state] = foil.gear_rate(command, y[state], row[GEAR_RATE], row[GEAR_TIME])


@njit(inline="always", **JIT)
def add(row, first, t, rho, pos, rot, vel, omega, current_z, current_u, current_v, tf, y,
        state, rhs):  # fmt: skip
    """The fin's lift and drag at P, in the earth frame, added to ``rhs`` (``y[state]``: the
    actuator's angle; ``state`` -1: none)."""
    # the water's flow past P, -s
    arm, w = flow_at((row[0], row[1], row[2]), pos, rot, vel, omega, current_z, current_u,
                     current_v)  # fmt: skip
    delta = y[state] if state >= 0 else angle(row, first, t, rot, omega, tf)
    span, chord = (row[3], row[4], row[5]), (row[6], row[7], row[8])
    fx, fy, fz = foil.force(row, FOIL, rho, (-w[0], -w[1], -w[2]), span, chord, delta)
    f0, f1, f2 = turn(rot, (fx, fy, fz))
    add_force(arm, f0, f1, f2, rhs)
