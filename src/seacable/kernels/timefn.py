"""Compiled evaluation of time functions.

Every time function of a case (constant, sine, ramp, acceleration profile, table) is compiled by
``seacable.case.timefunctions`` into one representation that numba can evaluate fast:

    f(t) = p_k(t - b_k) + A sin(omega t + phi)       for b_k <= t < b_{k+1}

where ``p_k`` is a cubic with coefficients ``coefs[k] = (c0, c1, c2, c3)`` on breakpoint ``b_k``.
A case holds several such functions ("channels"), stacked in arrays:

- ``breaks``  (C, K)    float64: breakpoints of channel c (first ``count[c]`` are used, ascending)
- ``coefs``   (C, K, 4) float64: cubic coefficients per piece
- ``count``   (C,)      int64  : number of pieces of channel c
- ``sine``    (C, 3)    float64: amplitude, angular frequency [rad/s], phase [rad]
- ``build_up`` (C, 2)   float64: build-up duration T [s] (0: none) and the value f(0)

The first breakpoint is a large negative sentinel with a constant piece, so evaluation never
extrapolates a non-constant polynomial backwards.

Build-up (as OrcaFlex's build-up period): a channel with T > 0 is taken smoothly from its value
at t = 0, at rest, to its time function,

    F(t) = f(0) + r(s) (f(t) - f(0)),   s = t / T,   r = s^3 (10 - 15 s + 6 s^2)  (r = 1 for s >= 1)

r is the quintic smoothstep: r(0) = 0, r(1) = 1, and r', r'' vanish at both ends, so F starts with
zero velocity and acceleration and joins f with continuous velocity and acceleration at t = T.
The derivatives are exact (product rule): F' = r' g + r f', F'' = r'' g + 2 r' f' + r f'' with
g = f - f(0).
"""

import math

from numba import njit

from seacable.kernels.jit import JIT, inner


@njit(**JIT)
def evaluate(breaks, coefs, count, sine, build_up, channel, t):
    """Value, first and second time derivative of channel ``channel`` at time ``t`` [s], its
    build-up included."""
    f, df, ddf = _unramped(breaks, coefs, count, sine, channel, t)
    duration = build_up[channel, 0]
    if duration <= 0.0 or t >= duration:
        return f, df, ddf
    start = build_up[channel, 1]
    if t <= 0.0:
        return start, 0.0, 0.0
    r, dr, ddr = smoothstep(t, duration)
    g = f - start
    return start + r * g, dr * g + r * df, ddr * g + 2.0 * dr * df + r * ddf


@inner
def smoothstep(t, duration):
    """r, r', r'' of the build-up ramp at time ``t`` [s] over ``duration`` [s] (> 0): 0 before
    it, 1 after it."""
    if t <= 0.0:
        return 0.0, 0.0, 0.0
    if t >= duration:
        return 1.0, 0.0, 0.0
    s = t / duration
    r = s * s * s * (10.0 + s * (-15.0 + 6.0 * s))
    dr = 30.0 * s * s * (1.0 - s) * (1.0 - s) / duration
    ddr = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) / (duration * duration)
    return r, dr, ddr


@inner
def _unramped(breaks, coefs, count, sine, channel, t):
    """The time function itself: piecewise cubic plus sine."""
    k_count = count[channel]
    lo = 0
    hi = k_count - 1
    # binary search for the last breakpoint <= t
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if breaks[channel, mid] <= t:
            lo = mid
        else:
            hi = mid - 1
    dt = t - breaks[channel, lo]
    c0 = coefs[channel, lo, 0]
    c1 = coefs[channel, lo, 1]
    c2 = coefs[channel, lo, 2]
    c3 = coefs[channel, lo, 3]
    f = c0 + dt * (c1 + dt * (c2 + dt * c3))
    df = c1 + dt * (2.0 * c2 + 3.0 * c3 * dt)
    ddf = 2.0 * c2 + 6.0 * c3 * dt
    amplitude = sine[channel, 0]
    if amplitude != 0.0:
        omega = sine[channel, 1]
        arg = omega * t + sine[channel, 2]
        s = math.sin(arg)
        f += amplitude * s
        df += amplitude * omega * math.cos(arg)
        ddf -= amplitude * omega * omega * s
    return f, df, ddf
