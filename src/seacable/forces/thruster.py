"""A thruster or propeller of a vessel (``model: thruster``): a thrust T [N] along a body-frame
direction d at a body-frame point P; its moment about the reference point is r_P x F. (A
propeller on its open-water curves, with its rate of turn, wake and torque, is ``model:
propeller``, ``forces.propeller``.)

d is a fixed unit vector (a propeller, a tunnel thruster) or, for an azimuth thruster,
(cos a, sin a, 0) with a(t) the azimuth [rad] from the bow (+x) towards port (+y). T is a time
function, or the surge-speed controller's proportional-integral law (forces.speed_control)

    T = T_ff(t) + K (U(t) - u) + K_i I,        dI/dt = U(t) - u,        u = (R^T v)_x,

u the surge speed over ground of the reference point [m/s], U the target [m/s], K the gain
[N s/m], K_i the integral gain [N/m], T_ff a feed-forward thrust [N] (the ship's resistance at
U). Proportional alone (K_i = 0, no state), the speed settles below U unless T_ff is the
resistance there; the integral I [m] (a state of the system, from 0) removes that offset.
|T| is limited to ``max_thrust`` when given; while the limit holds the thrust and the error
would push it further, I is held (conditional integration: no wind-up past the limit).
Row: P (3), d (3), 1 when d turns with the azimuth, 1 with the controller, K, the largest |T|
(0: none), K_i. Channels from the model's first: T or U, T_ff, a [rad].
"""

import math

from numba import njit

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.forces import speed_control
from seacable.kernels.jit import JIT
from seacable.kernels.timefn import evaluate

CHANNELS = 3  # thrust (or target speed), feed-forward thrust, azimuth
CONTROLLED, GAIN, LIMIT, INTEGRAL_GAIN = 7, 8, 9, 10


def pack(point, direction, azimuth: bool, controlled: bool, gain: float,
         max_thrust: float | None, integral_gain: float = 0.0) -> list[float]:  # fmt: skip
    """The row: ``point`` P [m] and unit ``direction`` d (body frame), whether d turns with the
    azimuth channel, whether T comes from the speed controller of ``gain`` K [N s/m] and
    ``integral_gain`` K_i [N/m], and the largest |T| [N] (None: unlimited)."""
    norm = math.sqrt(sum(float(v) ** 2 for v in direction))
    return [*(float(v) for v in point), *(float(v) / norm for v in direction),
            float(azimuth), float(controlled), float(gain), float(max_thrust or 0.0),
            float(integral_gain)]  # fmt: skip


def state_count(row) -> int:
    """The controller's integral I [m] when it has an integral gain; none otherwise."""
    return speed_control.state_count(row, CONTROLLED, INTEGRAL_GAIN)


@njit(inline="always", **JIT)
def _law(row, first, t, rot, vel, tf, y, state):
    """T [N] before its limits, and the controller's error U - u [m/s] (0 without it)."""
    return speed_control.command(row, CONTROLLED, GAIN, INTEGRAL_GAIN, first, t, rot, vel, tf,
                                 y, state)  # fmt: skip


@njit(inline="always", **JIT)
def thrust(row, first, t, rot, vel, tf, y, state):
    """T [N], limited (``y[state]``: the controller's integral; ``state`` -1: none)."""
    value, _ = _law(row, first, t, rot, vel, tf, y, state)
    limit = row[LIMIT]
    if limit > 0.0:
        value = min(limit, max(-limit, value))
    return value


@njit(inline="always", **JIT)
def rates(row, first, t, rot, vel, tf, y, state, ydot):
    """dI/dt = U - u into ``ydot[state]``, 0 while the limit holds and the error pushes the
    thrust further beyond it (forces.speed_control)."""
    value, error = _law(row, first, t, rot, vel, tf, y, state)
    limit = row[LIMIT] if row[LIMIT] > 0.0 else math.inf
    ydot[state] = speed_control.integral_rate(value, error, -limit, limit)


@njit(inline="always", **JIT)
def add(row, first, t, rot, vel, tf, y, state, rhs):
    """The thrust and its moment, in the earth frame, added to ``rhs``."""
    value = thrust(row, first, t, rot, vel, tf, y, state)
    dx, dy, dz = row[3], row[4], row[5]
    if row[6] != 0.0:
        breaks, coefs, count, sine, build_up = tf
        azimuth, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 2, t)
        dx, dy, dz = math.cos(azimuth), math.sin(azimuth), 0.0
    arm = turn(rot, (row[0], row[1], row[2]))
    f0, f1, f2 = turn(rot, (value * dx, value * dy, value * dz))
    add_force(arm, f0, f1, f2, rhs)
