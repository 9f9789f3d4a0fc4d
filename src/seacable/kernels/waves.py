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

A wave table (``FIELDS``, n) holds one component per column, in contiguous rows so that the
loops over components vectorise (:func:`table` builds it, its components sorted by wave
number): a, w, k, cos b, sin b, p, the build-up duration [s] and ``GROUP``, the index of the
component's wave number among the m distinct ones; and in its first m columns, per distinct
wave number, ``NUMBER`` (k) and the depth's scales 1 / (1 + e^{-2kh}) and 1 / (1 - e^{-2kh})
(1 in deep water). A spread sea has a few components per wave number: C, D and E are
evaluated per distinct wave number at a point, from e^{kz} and e^{-k(z + 2h)} (kernels.trig's
vectorised exp). The elevation and the pressure are summed in interleaved partial sums (the
kinematics' six sums are independent already).
Callers allocate one scratch of ``SCRATCH`` rows per table (:func:`scratch`).
"""

import math

import numpy as np
from numba import njit

from seacable.kernels.jit import JIT, inner
from seacable.kernels.timefn import smoothstep
from seacable.kernels.trig import cos_sin, exp_rows

DEEP = 1e30  # the depth of deep water [m]
NEGLIGIBLE = 2.0**-54  # below this share of e^{kz}, e^{-k(z + 2h)} changes no sum (_depth_terms)
WHEELER, VERTICAL = 0, 1
A, W, K, COS, SIN, PHASE, BUILD_UP, GROUP = range(8)  # per component
NUMBER, COSH_SCALE, SINH_SCALE = range(8, 11)  # per distinct wave number
FIELDS = 11
GIVEN = 7  # the fields a table is built from (A .. BUILD_UP)
SCRATCH = 5  # rows: cos theta, sin theta, theta (then exp's scratch), and two per wave number


def table(rows, depth: float) -> np.ndarray:
    """The wave table (FIELDS, n) of components given as rows (n, GIVEN: a, w, k, cos b,
    sin b, p, build-up [s]) at water depth ``depth`` [m] (DEEP: deep water), sorted by wave
    number (stable: the given order among equal ones)."""
    rows = np.asarray(rows, dtype=float).reshape(-1, GIVEN)
    rows = rows[np.argsort(rows[:, K], kind="stable")]
    out = np.zeros((FIELDS, len(rows)))
    out[:GIVEN] = rows.T
    numbers, out[GROUP] = np.unique(rows[:, K], return_inverse=True)
    m = len(numbers)
    out[NUMBER, :m] = numbers
    out[COSH_SCALE:, :m] = 1.0
    if depth < DEEP:
        decay = np.exp(-2.0 * numbers * depth)
        with np.errstate(divide="ignore"):
            out[COSH_SCALE, :m] = 1.0 / (1.0 + decay)
            out[SINH_SCALE, :m] = 1.0 / (1.0 - decay)
    return out


@njit(inline="always", **JIT)
def still():
    """A table without components (still water; from Python or compiled code)."""
    return np.zeros((FIELDS, 0))


@njit(inline="always", **JIT)
def scratch(wave):
    """The scratch the functions below need for ``wave`` (allocate once per caller)."""
    return np.empty((SCRATCH, wave.shape[1]))


@njit(inline="always", **JIT)
def ramp(wave, t):
    """The build-up's r and r' at ``t`` (1, 0 without build-up or components)."""
    if wave.shape[1] == 0 or wave[BUILD_UP, 0] <= 0.0:
        return 1.0, 0.0
    r, dr, _ = smoothstep(t, wave[BUILD_UP, 0])
    return r, dr


@inner
def elevation(wave, t, x, y, trig):
    """eta [m] at (x, y) (``trig``: :func:`scratch`)."""
    return ramp(wave, t)[0] * _phases(wave, t, x, y, trig)


@njit(inline="always", **JIT)
def stretched(z, eta, depth, stretch):
    """The elevation at which the kinematics are evaluated for a point at z."""
    if stretch == VERTICAL:
        return min(z, 0.0)
    if depth >= DEEP:
        return min(z - eta, 0.0)
    return min(depth * (z - eta) / (depth + eta), 0.0)


@inner
def _phases(wave, t, x, y, trig):
    """cos theta_i and sin theta_i at (x, y) into ``trig[0, i]`` and ``trig[1, i]`` (row 2:
    the phases; kernels.trig, a vectorised loop); returns the elevation before the build-up's
    ramp, sum a_i cos theta_i [m]."""
    n = wave.shape[1]
    k, w, cb, sb, p = wave[K], wave[W], wave[COS], wave[SIN], wave[PHASE]
    theta = trig[2]
    for i in range(n):
        theta[i] = k[i] * (x * cb[i] + y * sb[i]) - w[i] * t + p[i]
    cos_sin(trig, n)
    return _sum(wave[A], trig[0], n)


@njit(inline="always", **JIT)
def cos_sum(wave, trig):
    """sum a_i cos theta_i of the cosines in ``trig[0]``: the elevation before the ramp."""
    return _sum(wave[A], trig[0], wave.shape[1])


@njit(inline="always", **JIT)
def _sum(a, c, n):
    """sum a_i c_i over i < n (four interleaved partial sums: a vectorised loop)."""
    s0 = s1 = s2 = s3 = 0.0
    m = n - n % 4
    for i in range(0, m, 4):
        s0 += a[i] * c[i]
        s1 += a[i + 1] * c[i + 1]
        s2 += a[i + 2] * c[i + 2]
        s3 += a[i + 3] * c[i + 3]
    for i in range(m, n):
        s0 += a[i] * c[i]
    return (s0 + s1) + (s2 + s3)


@inner
def half_phases(wave, t, x, y, trig, c, s):
    """cos and sin of half of each component's phase at (x, y), theta_i / 2, into ``c`` and
    ``s`` (n each): the phase being linear in x and y, e^{i theta} at the midpoint of two
    points is the product of their e^{i theta / 2}, two products and a difference per
    component where a cosine costs a polynomial (kernels.hull's edge midpoints). Returns the
    elevation [m] at (x, y), the ramp's r times sum a_i (c_i^2 - s_i^2). ``trig``:
    :func:`scratch`."""
    n = wave.shape[1]
    k, w, cb, sb, p = wave[K], wave[W], wave[COS], wave[SIN], wave[PHASE]
    theta, cos_theta = trig[2], trig[3]
    for i in range(n):
        theta[i] = 0.5 * (k[i] * (x * cb[i] + y * sb[i]) - w[i] * t + p[i])
    cos_sin(trig, n)
    for i in range(n):
        c[i], s[i] = trig[0, i], trig[1, i]
        cos_theta[i] = trig[0, i] * trig[0, i] - trig[1, i] * trig[1, i]
    return ramp(wave, t)[0] * _sum(wave[A], cos_theta, n)


@inner
def _depth_terms(wave, zs, depth, trig):
    """e^{k_j z} and e^{-k_j (z + 2h)} into ``trig[3, j]`` and ``trig[4, j]`` for the m
    distinct wave numbers, at z = ``zs`` <= 0 (below the seabed, on it); returns m. C, D and E
    of the module docstring are their sum and difference times the table's scales. The second
    is left 0 where it is below NEGLIGIBLE times the first (2 k (z + h) > -ln NEGLIGIBLE: the
    wave numbers are sorted, so from some j on), where their sum and difference round to the
    first: always in deep water."""
    n = wave.shape[1]
    m = int(wave[GROUP, n - 1]) + 1 if n > 0 else 0
    k = wave[NUMBER]
    zc = max(zs, -depth)
    reach = -0.5 * math.log(NEGLIGIBLE) / (zc + depth) if zc + depth > 0.0 else math.inf
    below = -(zc + 2.0 * depth)
    up, down = trig[3], trig[4]
    for j in range(m):
        up[j] = k[j] * zc
        down[j] = k[j] * below
    felt = 0
    while felt < m and k[felt] <= reach:
        felt += 1
    exp_rows(trig, 3, 4, m, 2)
    exp_rows(trig, 4, 5, felt, 2)
    down[felt:m] = 0.0
    return m


@inner
def pressure(wave, t, x, y, z, depth, stretch, rho_g, trig):
    """The dynamic pressure [Pa] at (x, y, z); above the free surface, its value there (the
    callers integrate over the wetted part: points on its edges may lie a rounding above).
    ``trig``: :func:`scratch`. Each component's phase is evaluated once, for the elevation
    and the pressure."""
    return pressure_given(wave, t, z, _phases(wave, t, x, y, trig), depth, stretch, rho_g, trig)


@inner
def pressure_given(wave, t, z, eta, depth, stretch, rho_g, trig):
    """The dynamic pressure [Pa] at height z of a point whose components' cos theta_i are
    in ``trig[0]`` (:func:`pressure`'s, from the point's phases or another way) and whose
    elevation before the ramp is ``eta`` (:func:`cos_sum` of them)."""
    n = wave.shape[1]
    a, group, c = wave[A], wave[GROUP], trig[0]
    r = ramp(wave, t)[0]
    zs = stretched(z, r * eta, depth, stretch)
    groups = _depth_terms(wave, zs, depth, trig)
    scale, up, down = wave[COSH_SCALE], trig[3], trig[4]
    for j in range(groups):
        up[j] = (up[j] + down[j]) * scale[j]  # C
    s0 = s1 = 0.0
    m = n - n % 2
    for i in range(0, m, 2):
        s0 += a[i] * up[int(group[i])] * c[i]
        s1 += a[i + 1] * up[int(group[i + 1])] * c[i + 1]
    for i in range(m, n):
        s0 += a[i] * up[int(group[i])] * c[i]
    return rho_g * r * (s0 + s1)


@inner
def kinematics(wave, t, x, y, z, depth, stretch, trig):
    """Velocity (3) and acceleration (3) of the water at (x, y, z) [m/s, m/s^2]; above the
    free surface, their values there (the callers weigh by the submerged part). ``trig``:
    :func:`scratch`. Each component's phase is evaluated once, for the elevation and the
    kinematics."""
    r, dr = ramp(wave, t)
    zs = stretched(z, r * _phases(wave, t, x, y, trig), depth, stretch)
    groups = _depth_terms(wave, zs, depth, trig)
    scale, d, e = wave[SINH_SCALE], trig[3], trig[4]
    for j in range(groups):
        d[j], e[j] = (d[j] + e[j]) * scale[j], (d[j] - e[j]) * scale[j]
    n = wave.shape[1]
    a, w, cb, sb, group = wave[A], wave[W], wave[COS], wave[SIN], wave[GROUP]
    c, s = trig[0], trig[1]
    ux = uy = uz = ax = ay = az = 0.0
    for i in range(n):
        g, aw = int(group[i]), a[i] * w[i]
        horizontal, vertical = aw * d[g], aw * e[g]
        hc, hs = horizontal * c[i], horizontal * w[i] * s[i]
        ux += hc * cb[i]
        uy += hc * sb[i]
        uz += vertical * s[i]
        ax += hs * cb[i]
        ay += hs * sb[i]
        az -= vertical * w[i] * c[i]
    if r == 1.0 and dr == 0.0:
        return (ux, uy, uz), (ax, ay, az)
    return ((r * ux, r * uy, r * uz),
            (r * ax + dr * ux, r * ay + dr * uy, r * az + dr * uz))  # fmt: skip


@njit(**JIT)
def elevation_at(wave, t, x, y):
    """eta [m] (from Python: tests, outputs)."""
    return elevation(wave, t, x, y, scratch(wave))


@njit(**JIT)
def pressure_at(wave, t, x, y, z, depth, stretch, rho_g):
    """The dynamic pressure [Pa] (from Python)."""
    return pressure(wave, t, x, y, z, depth, stretch, rho_g, scratch(wave))


@njit(**JIT)
def field(wave, t, x, y, z, depth, stretch):
    """(u_x, u_y, u_z, a_x, a_y, a_z) of the water at a point (from Python)."""
    u, a = kinematics(wave, t, x, y, z, depth, stretch, scratch(wave))
    return u[0], u[1], u[2], a[0], a[1], a[2]
