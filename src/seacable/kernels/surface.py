"""The free surface z = 0 for bodies: the submerged fraction of a body's volume (numba).

Every model (planar, 3D, lumped, stars) asks :func:`submersion` how much of a body lies below
the still-water surface, given the elevation z [m] of the body's reference point (its position)
and a **shape row**, a float64 array of a width fixed per case::

    [kind, a, b, K, z_0 .. z_{K-1}, f_0 .. f_{K-1}, (padding)]

- ``POINT`` (kind 0): a point volume, always wholly submerged (f = 1): seacable's behaviour for a
  body without a shape, kept so that such cases give bitwise the results they always gave.
- ``SPHERE`` (1): radius a [m], centred on the reference point. Draft d = a - z in [0, 2a],
  submerged cap V(d) = pi d^2 (3a - d) / 3, f = d^2 (3a - d) / (4 a^3); C1 in z everywhere
  (the waterplane area pi (2 a d - d^2) vanishes at both poles).
- ``CYLINDER`` (2): vertical cylinder of radius a [m] and height b [m], centred on the reference
  point. d = b/2 - z in [0, b], f = d / b; the waterplane area pi a^2 jumps at the two ends
  (f is C0 there, C1 elsewhere).
- ``TABLE`` (3): K elevations z_k of the reference point (ascending) and the submerged fraction
  f_k there (1 at z_0, 0 at z_{K-1}, non-increasing), interpolated linearly; f = 1 below z_0, 0
  above z_{K-1}; C0 at the table points.

The body's buoyancy is rho g V f, its added mass m_a f, its drag area A f (see
docs/conventions.md). Buoyancy is conservative: its potential is -rho g V I(z), with

    I(z) = integral of f from z_full to z, plus z_full,

z_full the highest elevation at which the body is wholly submerged: I(z) = z below z_full (the
point volume's potential, rho g V z), constant once the body is clear of the water (then the
height of the volume's centroid above the reference point: 0 for the centred sphere and
cylinder).

Cable segments have no shape: :func:`segment_submersion` gives the submerged fraction of a
straight segment's length from its ends' heights, and where its buoyancy acts (the lumped-mass,
planar rigid-link and 3D rigid-segment models all use it).
"""

import numpy as np
from numba import njit

from seacable.kernels.jit import JIT, inner

POINT, SPHERE, CYLINDER, TABLE = 0, 1, 2, 3
HEADER = 4  # kind, a, b, K


def point_row(width: int = HEADER) -> np.ndarray:
    """The shape row of a point volume (always submerged)."""
    return np.zeros(max(width, HEADER))


@inner
def _table(z, row):
    """Linear interpolation of the fraction table and the integral I(z)."""
    count = int(row[3])
    zs = row[HEADER : HEADER + count]
    fs = row[HEADER + count : HEADER + 2 * count]
    if z <= zs[0]:
        return 1.0, 0.0, z
    integral = zs[0]
    for k in range(count - 1):
        z0, z1, f0, f1 = zs[k], zs[k + 1], fs[k], fs[k + 1]
        slope = (f1 - f0) / (z1 - z0)
        if z < z1:
            s = z - z0
            return f0 + slope * s, slope, integral + s * (f0 + 0.5 * slope * s)
        integral += 0.5 * (z1 - z0) * (f0 + f1)
    return 0.0, 0.0, integral


@njit(**JIT)
def submersion(z, row):
    """Submerged fraction of a body whose reference point is at elevation z [m].

    Returns (f, df/dz [1/m], I(z) [m]): the fraction of the volume below z = 0, its derivative
    (-A_wp / V, A_wp the waterplane area) and the buoyancy potential's integral (module doc).
    """
    kind = int(row[0])
    if kind == POINT:
        return 1.0, 0.0, z
    if kind == SPHERE:
        r = row[1]
        if z <= -r:
            return 1.0, 0.0, z
        if z >= r:
            return 0.0, 0.0, 0.0
        d = r - z
        scale = 1.0 / (4.0 * r * r * r)
        fraction = d * d * (3.0 * r - d) * scale
        slope = -3.0 * d * (2.0 * r - d) * scale
        # integral of f over the draft from 0 to d is (r d^3 - d^4 / 4) / (4 r^3)
        return fraction, slope, -(r * d * d * d - 0.25 * d * d * d * d) * scale
    if kind == CYLINDER:
        half = 0.5 * row[2]
        if z <= -half:
            return 1.0, 0.0, z
        if z >= half:
            return 0.0, 0.0, 0.0
        d = half - z
        return d / row[2], -1.0 / row[2], -0.5 * d * d / row[2]
    return _table(z, row)


@njit(inline="always", **JIT)
def segment_submersion(za, zb):
    """A straight cable segment between ends at elevations za and zb [m]: the submerged
    fraction s of its length, the share of its buoyancy rho g A l s carried by end a (the lever
    rule about the submerged part's centroid: the exact hydrostatic load on a rigid segment,
    1/2 when wholly submerged; the centroid lies (1/2 - share) l from the centre towards end b)
    and the mean of min(z, 0) along it [m] (its buoyancy potential is
    -rho g A l times it; the centre's elevation when wholly submerged). s is C0 in za and zb."""
    low, high = min(za, zb), max(za, zb)
    if high <= 0.0:
        return 1.0, 0.5, 0.5 * (za + zb)
    if low >= 0.0:
        return 0.0, 0.5, 0.0
    s = -low / (high - low)
    share_low = 1.0 - 0.5 * s
    return s, share_low if za < zb else 1.0 - share_low, 0.5 * s * low


@njit(inline="always", **JIT)
def segment_potential(wet_weight, buoyancy, za, zb, zc):
    """Gravity and buoyancy potential [J] of a straight segment between elevations za and zb,
    centre at zc, apparent weight ``wet_weight`` and buoyancy ``buoyancy`` [N] when wholly
    submerged: wet_weight zc - rho g A l (mean of min(z, 0) - zc)."""
    wet, _, mean_depth = segment_submersion(za, zb)
    if wet < 1.0:
        return wet_weight * zc + buoyancy * (zc - mean_depth)
    return wet_weight * zc
