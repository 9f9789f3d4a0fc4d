"""Cosines, sines and exponentials of many arguments at once, written so that the compiler
vectorises the loops (numba): the waves' components' phases and depth factors at a point
(kernels.waves) are the hottest loops of a vessel's lines in an irregular sea, and the C
library's ``cos``, ``sin`` and ``exp``, a call each per argument, keep the loops scalar.

Each angle x is reduced to r = x - q pi/2 (q the nearest integer to 2 x / pi; pi/2 split in
three parts, the first two of 32 significant bits, so that q P1 and q P2 are exact for
|q| < 2^21, |x| < 3.2e6 rad) with |r| <= pi/4, and

    sin r = r + r z (S_1 + z (S_2 + ... + z S_7)),   cos r = 1 - z / 2 + z^2 (C_1 + ... + z^6 C_7),

z = r^2, the Taylor series of sin and cos (S_k = (-1)^k / (2k + 1)!, C_k = (-1)^k / (2k + 2)!)
cut where the next term is below 2e-18 at r = pi/4; the quadrant q mod 4 then swaps and signs
them without branches. Agreement with numpy's cos and sin: 2.3e-16 for |x| <= 3e4 (the
phase of 180 components over three hours; ``tests/test_waves.py``), where the angle itself
carries a rounding of about 3e-12. Beyond |x| = 3.2e6 the reduction loses digits as the angle
has already lost them.

``exp_rows``: x is clamped to [-708, 709] and reduced to r = x - q ln 2 (q the nearest
integer to x / ln 2, ln 2 in two parts) with |r| <= ln(2)/2; e^r is its Taylor series to
r^13 (the next term is below 4e-18 there) and 2^q is built in the exponent's bits. Below
x = -708 (e^x < 3.3e-308, where the doubles turn subnormal) the result is 0. Agreement with
numpy's exp: 4.4e-16 relative (``tests/test_waves.py``).
"""

import math

import numpy as np
from numba import njit

from seacable.kernels.jit import JIT

# pi/2 = P1 + P2 + P3 (P1, P2: 32 significant bits; computed from pi's decimal digits)
P1 = 1.5707963267341256
P2 = 6.077100506303966e-11
P3 = 2.0222662487959506e-21
TWO_OVER_PI = 0.6366197723675814
# Taylor coefficients: sin's (-1)^k / (2k + 1)!, cos's (-1)^k / (2k + 2)!, k = 1..7
S1, S2, S3, S4 = -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362880.0
S5, S6, S7 = -1.0 / 39916800.0, 1.0 / 6227020800.0, -1.0 / 1307674368000.0
C1, C2, C3, C4 = 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0, -1.0 / 3628800.0
C5, C6, C7 = 1.0 / 479001600.0, -1.0 / 87178291200.0, 1.0 / 20922789888000.0
# ln 2 = L1 + L2 (L1: 32 significant bits) and 1 / ln 2; exp's Taylor coefficients 1 / k!
L1 = 6.93147180369123816490e-01
L2 = 1.90821492927058770002e-10
ONE_OVER_LN2 = 1.4426950408889634
ROUND = 6755399441055744.0  # 1.5 2^52: x + ROUND - ROUND rounds x to an integer
E2, E3, E4, E5 = 1.0 / 2.0, 1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0
E6, E7, E8, E9 = 1.0 / 720.0, 1.0 / 5040.0, 1.0 / 40320.0, 1.0 / 362880.0
E10, E11, E12, E13 = 1.0 / 3628800.0, 1.0 / 39916800.0, 1.0 / 479001600.0, 1.0 / 6227020800.0


@njit(inline="always", **JIT)
def cos_sin(rows, n):
    """``rows[0, :n]`` and ``rows[1, :n]`` set to the cosines and sines of the angles
    ``rows[2, :n]`` [rad] (``rows`` (3, m) floats, m >= n)."""
    for i in range(n):
        x = rows[2, i]
        q = math.floor(x * TWO_OVER_PI + 0.5)  # the nearest quarter turn
        r = ((x - q * P1) - q * P2) - q * P3
        z = r * r
        s = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * (S6 + z * S7))))))
        c = (
            1.0
            - 0.5 * z
            + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * (C6 + z * C7))))))
        )
        odd = q - 2.0 * math.floor(0.5 * q)  # q mod 2: 0.0 or 1.0
        m4 = q - 4.0 * math.floor(0.25 * q)  # q mod 4: 0.0 .. 3.0
        sign_s = 1.0 - 2.0 * (m4 >= 2.0)
        sign_c = 1.0 - 2.0 * ((m4 == 1.0) | (m4 == 2.0))
        rows[0, i] = sign_c * ((1.0 - odd) * c + odd * s)
        rows[1, i] = sign_s * ((1.0 - odd) * s + odd * c)


@njit(inline="always", **JIT)
def exp_rows(rows, first, last, n, spare):
    """``rows[first:last, :n]`` replaced by their exponentials; ``rows[spare, :n]`` is scratch
    (``rows`` (m, p) floats, p >= n; ``spare`` outside first..last - 1)."""
    scale = rows[spare]
    bits = scale.view(np.int64)
    for j in range(first, last):
        v = rows[j]
        for i in range(n):
            x = min(max(v[i], -708.0), 709.0)
            q = (x * ONE_OVER_LN2 + ROUND) - ROUND
            r = (x - q * L1) - q * L2
            p = r * (E7 + r * (E8 + r * (E9 + r * (E10 + r * (E11 + r * (E12 + r * E13))))))
            p = 1.0 + r * (1.0 + r * (E2 + r * (E3 + r * (E4 + r * (E5 + r * (E6 + p))))))
            v[i] = p * (v[i] > -708.0)
            scale[i] = q + (ROUND + 1023.0)  # q + 1023 in the low bits of the significand
        for i in range(n):
            bits[i] = bits[i] << 52  # ... moved to the exponent's: 2^q
        for i in range(n):
            v[i] *= scale[i]


@njit(**JIT)
def exp_at(values):
    """exp of an array (from Python: tests)."""
    n = values.shape[0]
    rows = np.empty((2, n))
    rows[0, :] = values
    exp_rows(rows, 0, 1, n, 1)
    return rows[0].copy()


@njit(**JIT)
def cos_sin_at(angles):
    """(cos, sin) of an array of angles [rad] (from Python: tests)."""
    n = angles.shape[0]
    rows = np.empty((3, n))
    rows[2, :] = angles
    cos_sin(rows, n)
    return rows[0].copy(), rows[1].copy()
