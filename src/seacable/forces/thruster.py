"""A thruster or propeller of a vessel (``model: thruster``): a thrust T [N] along a body-frame
direction d at a body-frame point P; its moment about the reference point is r_P x F.

d is a fixed unit vector (a propeller, a tunnel thruster) or, for an azimuth thruster,
(cos a, sin a, 0) with a(t) the azimuth [rad] from the bow (+x) towards port (+y). T is a time
function, or the surge-speed controller's proportional law

    T = T_ff(t) + K (U(t) - u),        u = (R^T v)_x,

u the surge speed over ground of the reference point [m/s], U the target [m/s], K the gain
[N s/m], T_ff a feed-forward thrust [N] (the ship's resistance at U: without it the speed
settles below U, where K (U - u) balances the resistance). |T| is limited to ``max_thrust``
when given. Row: P (3), d (3), 1 when d turns with the azimuth, 1 with the controller, K,
the largest |T| (0: none). Channels from the model's first: T or U, T_ff, a [rad].
"""

import math

from numba import njit

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.kernels.jit import JIT
from seacable.kernels.timefn import evaluate

CHANNELS = 3  # thrust (or target speed), feed-forward thrust, azimuth


def pack(point, direction, azimuth: bool, controlled: bool, gain: float,
         max_thrust: float | None) -> list[float]:  # fmt: skip
    """The row: ``point`` P [m] and unit ``direction`` d (body frame), whether d turns with the
    azimuth channel, whether T comes from the speed controller of ``gain`` K [N s/m], and the
    largest |T| [N] (None: unlimited)."""
    norm = math.sqrt(sum(float(v) ** 2 for v in direction))
    return [*(float(v) for v in point), *(float(v) / norm for v in direction),
            float(azimuth), float(controlled), float(gain), float(max_thrust or 0.0)]  # fmt: skip


@njit(inline="always", **JIT)
def thrust(row, first, t, rot, vel, tf):
    """T [N], saturated."""
    breaks, coefs, count, sine, build_up = tf
    value, _, _ = evaluate(breaks, coefs, count, sine, build_up, first, t)
    if row[7] != 0.0:
        surge = rot[0, 0] * vel[0] + rot[1, 0] * vel[1] + rot[2, 0] * vel[2]
        feed, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 1, t)
        value = feed + row[8] * (value - surge)
    limit = row[9]
    if limit > 0.0:
        value = min(limit, max(-limit, value))
    return value


@njit(inline="always", **JIT)
def add(row, first, t, rot, vel, tf, rhs):
    """The thrust and its moment, in the earth frame, added to ``rhs``."""
    value = thrust(row, first, t, rot, vel, tf)
    dx, dy, dz = row[3], row[4], row[5]
    if row[6] != 0.0:
        breaks, coefs, count, sine, build_up = tf
        azimuth, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 2, t)
        dx, dy, dz = math.cos(azimuth), math.sin(azimuth), 0.0
    arm = turn(rot, (row[0], row[1], row[2]))
    f0, f1, f2 = turn(rot, (value * dx, value * dy, value * dz))
    add_force(arm, f0, f1, f2, rhs)
