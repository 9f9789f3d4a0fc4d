"""The surge-speed controller's proportional-integral law, shared by the models it drives: a
thruster (``forces.thruster``: it sets the thrust) and a propeller (``forces.propeller``: it
sets the rate of turn). Whatever it sets, c:

    c = c_ff(t) + K (U(t) - u) + K_i I,        dI/dt = U(t) - u,        u = (R^T v)_x,

u the surge speed over ground of the body's reference point [m/s], U the target [m/s], K the
gain [unit of c per m/s], K_i the integral gain [unit of c per m], c_ff the feed-forward
(the value that holds the ship at U). c is limited to [low, high] by its model; while a limit
holds and the error would push c further beyond it, I is held (conditional integration: no
wind-up past the limit). I [m] is a state of the system, from 0, when K_i > 0.
"""

from numba import njit

from seacable.kernels.jit import JIT
from seacable.kernels.timefn import evaluate


def state_count(row, controlled: int, integral_gain: int) -> int:
    """The integral I [m] of a model whose row has the controller (``row[controlled]`` not 0)
    with an integral gain (``row[integral_gain]`` > 0); none otherwise."""
    return 1 if row[controlled] != 0.0 and row[integral_gain] > 0.0 else 0


@njit(inline="always", **JIT)
def surge(rot, vel):
    """The body's surge speed over ground u = (R^T v)_x [m/s] (``rot`` its rotation matrix,
    ``vel`` its reference point's velocity, earth frame)."""
    return rot[0, 0] * vel[0] + rot[1, 0] * vel[1] + rot[2, 0] * vel[2]


@njit(inline="always", **JIT)
def law(target, feed, gain, integral_gain, speed, y, state):
    """c before its limits and the error U - u: ``target`` U [m/s], ``feed`` c_ff, ``speed``
    u [m/s]; the integral I is ``y[state]`` (``state`` -1: none)."""
    error = target - speed
    value = feed + gain * error
    if state >= 0:
        value += integral_gain * y[state]
    return value, error


@njit(inline="always", **JIT)
def command(row, controlled, gain, integral_gain, first, t, rot, vel, tf, y, state):
    """A model's c before its limits and the error U - u [m/s] (0 without the controller): its
    time function at channel ``first`` or, when ``row[controlled]`` is not 0, the law with the
    target U at ``first``, c_ff at ``first + 1``, K at ``row[gain]``, K_i at
    ``row[integral_gain]``."""
    breaks, coefs, count, sine, build_up = tf
    value, _, _ = evaluate(breaks, coefs, count, sine, build_up, first, t)
    if row[controlled] == 0.0:
        return value, 0.0
    feed, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 1, t)
    return law(value, feed, row[gain], row[integral_gain], surge(rot, vel), y, state)


@njit(inline="always", **JIT)
def integral_rate(value, error, low, high):
    """dI/dt: the error, or 0 while c (before its limits) is at or beyond ``high`` and the
    error pushes it up, or at or below ``low`` and the error pushes it down."""
    held = (value >= high and error > 0.0) or (value <= low and error < 0.0)
    return 0.0 if held else error
