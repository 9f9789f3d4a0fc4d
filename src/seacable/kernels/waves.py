"""Incident waves: linear (Airy) components superposed (numba).

Component i has amplitude a_i [m], angular frequency w_i [rad/s], wave number k_i [rad/m]
(w^2 = g k tanh(k h), h the water depth), the direction it travels towards (cos b_i, sin b_i;
b from +x towards +y) and a phase p_i. With theta_i = k_i (x cos b_i + y sin b_i) - w_i t + p_i
(a time dependence e^{-i w t}: eta = Re sum a_i e^{i theta_i}):

    elevation           eta = sum a_i cos(theta_i)
    dynamic pressure    p   = rho g sum a_i C_i(z) cos(theta_i)
    velocity            u_h = sum a_i w_i D_i(z) cos(theta_i) (cos b_i, sin b_i),
                        w   = sum a_i w_i E_i(z) sin(theta_i)
    acceleration        the time derivatives of u_h and w at a fixed point

with C = cosh(k(z + h)) / cosh(k h), D = cosh(k(z + h)) / sinh(k h), E = sinh(k(z + h)) /
sinh(k h), each written with e^{kz} and e^{-k(z + 2h)} so that deep water (h = DEEP) is exact
and nothing overflows. Above z = 0, under a crest, the kinematics are stretched (``STRETCH``):
Wheeler's (z evaluated at h (z - eta) / (h + eta), so that the dynamic pressure is rho g eta at
the surface and the total pressure there vanishes) or vertical (z evaluated at min(z, 0)).
Above the surface every quantity keeps its value at the surface: the callers integrate over the
wetted part only, whose edges may lie a rounding above it.

Build-up: every quantity is multiplied by the ramp r(t) of the components' build-up duration
(kernels.timefn.smoothstep, the case's ``simulation.build_up``; 0: none), the acceleration by
r a + r' u: the sea rises from still water at rest, with no jump in force or its rate.

``row`` (n, 7) holds per component a, w, k, cos b, sin b, p and the build-up duration [s].
"""

import math

import numpy as np
from numba import njit

from seacable.kernels.jit import JIT
from seacable.kernels.timefn import smoothstep
from seacable.kernels.trig import cos_sin

DEEP = 1e30  # the depth of deep water [m]
WHEELER, VERTICAL = 0, 1
A, W, K, COS, SIN, PHASE, BUILD_UP = range(7)
COLUMNS = 7


@njit(inline="always", **JIT)
def ramp(row, t):
    """The build-up's r and r' at ``t`` (1, 0 without build-up or components)."""
    if row.shape[0] == 0 or row[0, BUILD_UP] <= 0.0:
        return 1.0, 0.0
    r, dr, _ = smoothstep(t, row[0, BUILD_UP])
    return r, dr


@njit(inline="always", **JIT)
def elevation(row, t, x, y, trig):
    """eta [m] at (x, y) (``trig``: scratch of (3, n) floats, as ``kinematics``')."""
    return ramp(row, t)[0] * _phases(row, t, x, y, trig)


@njit(inline="always", **JIT)
def stretched(z, eta, depth, stretch):
    """The elevation at which the kinematics are evaluated for a point at z."""
    if stretch == VERTICAL:
        return min(z, 0.0)
    if depth >= DEEP:
        return min(z - eta, 0.0)
    return min(depth * (z - eta) / (depth + eta), 0.0)


@njit(inline="always", **JIT)
def _factors(k, z, depth):
    """C, D, E of the module docstring at z <= 0 (one exponential in deep water, two in
    finite depth: e^{-k (z + 2h)} = e^{-2kh} / e^{kz}; below the seabed, their values on it)."""
    if depth >= DEEP or k * depth > 40.0:
        up = math.exp(k * z)
        return up, up, up
    up = math.exp(k * max(z, -depth))
    deep = math.exp(-2.0 * k * depth)
    down = deep / up
    return (up + down) / (1.0 + deep), (up + down) / (1.0 - deep), (up - down) / (1.0 - deep)


@njit(inline="always", **JIT)
def _phases(row, t, x, y, trig):
    """cos theta_i and sin theta_i at (x, y) into ``trig[0, i]`` and ``trig[1, i]`` (row 2:
    the phases; kernels.trig, a vectorised loop); returns the elevation before the build-up's
    ramp, sum a_i cos theta_i [m]."""
    n = row.shape[0]
    for i in range(n):
        trig[2, i] = (row[i, K] * (x * row[i, COS] + y * row[i, SIN]) - row[i, W] * t
                      + row[i, PHASE])  # fmt: skip
    cos_sin(trig, n)
    total = 0.0
    for i in range(n):
        total += row[i, A] * trig[0, i]
    return total


@njit(inline="always", **JIT)
def pressure(row, t, x, y, z, depth, stretch, rho_g, trig):
    """The dynamic pressure [Pa] at (x, y, z); above the free surface, its value there (the
    callers integrate over the wetted part: points on its edges may lie a rounding above).
    ``trig``: scratch of (3, n) floats (allocated once per caller). Each component's phase is
    evaluated once, for the elevation and the pressure, and C once per distinct wave number
    (the rows of a spectrum come frequency by frequency)."""
    r = ramp(row, t)[0]
    zs = stretched(z, r * _phases(row, t, x, y, trig), depth, stretch)
    total = 0.0
    k_last = -1.0
    c = 0.0
    for i in range(row.shape[0]):
        if row[i, K] != k_last:
            k_last = row[i, K]
            c, _, _ = _factors(k_last, zs, depth)
        total += row[i, A] * c * trig[0, i]
    return rho_g * r * total


@njit(inline="always", **JIT)
def kinematics(row, t, x, y, z, depth, stretch, trig):
    """Velocity (3) and acceleration (3) of the water at (x, y, z) [m/s, m/s^2]; above the
    free surface, their values there (the callers weigh by the submerged part). ``trig``:
    scratch of (3, n) floats. Each component's phase is evaluated once, for the
    elevation and the kinematics, and D and E once per distinct wave number."""
    r, dr = ramp(row, t)
    zs = stretched(z, r * _phases(row, t, x, y, trig), depth, stretch)
    ux = uy = uz = ax = ay = az = 0.0
    k_last = -1.0
    d = e = 0.0
    for i in range(row.shape[0]):
        if row[i, K] != k_last:
            k_last = row[i, K]
            _, d, e = _factors(k_last, zs, depth)
        w = row[i, W]
        cos_t, sin_t = trig[0, i], trig[1, i]
        horizontal = row[i, A] * w * d
        ux += horizontal * cos_t * row[i, COS]
        uy += horizontal * cos_t * row[i, SIN]
        uz += row[i, A] * w * e * sin_t
        ax += horizontal * w * sin_t * row[i, COS]
        ay += horizontal * w * sin_t * row[i, SIN]
        az -= row[i, A] * w * w * e * cos_t
    if r == 1.0 and dr == 0.0:
        return (ux, uy, uz), (ax, ay, az)
    return ((r * ux, r * uy, r * uz),
            (r * ax + dr * ux, r * ay + dr * uy, r * az + dr * uz))  # fmt: skip


@njit(**JIT)
def elevation_at(row, t, x, y):
    """eta [m] (from Python: tests, outputs)."""
    return elevation(row, t, x, y, np.empty((3, row.shape[0])))


@njit(**JIT)
def pressure_at(row, t, x, y, z, depth, stretch, rho_g):
    """The dynamic pressure [Pa] (from Python)."""
    return pressure(row, t, x, y, z, depth, stretch, rho_g, np.empty((3, row.shape[0])))


@njit(**JIT)
def field(row, t, x, y, z, depth, stretch):
    """(u_x, u_y, u_z, a_x, a_y, a_z) of the water at a point (from Python)."""
    u, a = kinematics(row, t, x, y, z, depth, stretch, np.empty((3, row.shape[0])))
    return u[0], u[1], u[2], a[0], a[1], a[2]
