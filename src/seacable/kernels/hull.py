"""A hull's triangle mesh clipped at the free surface, and integrals over its wetted part
(numba).

A mesh is one flat float row (``mesh_row``): ``[nv, nt, x_0, y_0, z_0, ..., i_0, j_0, k_0, ...]``,
the vertices in the body frame relative to the body's reference point [m] and the triangles as
vertex numbers, each wound anticlockwise seen from outside (its area vector
S = (b - a) x (c - a) / 2 points out of the hull).

Each step the vertices are placed in the earth frame (r = R v from the reference point at
``pos``), every triangle is cut by the plane z = ``level`` (its vertices' depths
h = level - z interpolated linearly along the edges the plane crosses) and what lies below is
kept as one triangle or a quadrilateral split in two; the triangles keep their winding. Over a
plane triangle the integral of a polynomial of degree two is exact by the rule of its three
edge midpoints, A/3 sum f(m): so

- the hydrostatic force -int p n dA with p = rho g (level - z) is -p(centroid) S, and its moment
  about the reference point -int p (r x n) dA is -1/3 sum_m p(m) r(m) x S, exactly
  (``add_hydrostatic``);
- the moments int f n dA of f in (1, x, y, z, x^2, y^2, z^2, xy, xz, yz) over the wetted surface
  (``surface_integrals``) give, through the divergence theorem on the wetted surface closed by
  its waterplane, the displaced volume three ways, the centre of buoyancy and the waterplane's
  area and moments (``seacable.meshes.hydrostatics``).
"""

import numpy as np
from numba import njit

from seacable.kernels.jit import JIT, inner

HEADER = 2  # nv, nt
# the integrands of surface_integrals, in this order
INTEGRANDS = ("1", "x", "y", "z", "xx", "yy", "zz", "xy", "xz", "yz")


def mesh_row(vertices: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """The flat row of a mesh: vertices (nv, 3) [m, body frame], triangles (nt, 3) int."""
    vertices = np.asarray(vertices, dtype=float)
    triangles = np.asarray(triangles, dtype=np.int64)
    head = [float(len(vertices)), float(len(triangles))]
    return np.concatenate([head, vertices.ravel(), triangles.ravel().astype(float)])


@njit(inline="always", **JIT)
def _vertex(row, i, rot):
    """R v of vertex i (its arm from the reference point, earth frame)."""
    k = HEADER + 3 * i
    x, y, z = row[k], row[k + 1], row[k + 2]
    return (
        rot[0, 0] * x + rot[0, 1] * y + rot[0, 2] * z,
        rot[1, 0] * x + rot[1, 1] * y + rot[1, 2] * z,
        rot[2, 0] * x + rot[2, 1] * y + rot[2, 2] * z,
    )


@njit(inline="always", **JIT)
def _cut(p, q, hp, hq):
    """The point of the edge p-q where the depth is zero (hp >= 0 > hq or the reverse)."""
    s = hp / (hp - hq)
    return (p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]), p[2] + s * (q[2] - p[2]))


@njit(inline="always", **JIT)
def clip(a, b, c, ha, hb, hc):
    """The part of triangle a b c where the depth h >= 0, as ``count`` triangles (0, 1 or 2)
    of the same winding: (count, (a0, b0, c0, a1, b1, c1))."""
    wa, wb, wc = ha >= 0.0, hb >= 0.0, hc >= 0.0
    wet = int(wa) + int(wb) + int(wc)
    if wet == 3:
        return 1, (a, b, c, a, b, c)
    if wet == 0:
        return 0, (a, b, c, a, b, c)
    # turn the triangle (keeping its winding) so that a is the odd vertex out
    if wet == 1:
        if wb:
            a, b, c, ha, hb, hc = b, c, a, hb, hc, ha
        elif wc:
            a, b, c, ha, hb, hc = c, a, b, hc, ha, hb
        pab, pca = _cut(a, b, ha, hb), _cut(c, a, hc, ha)
        return 1, (a, pab, pca, a, pab, pca)
    if not wb:
        a, b, c, ha, hb, hc = b, c, a, hb, hc, ha
    elif not wc:
        a, b, c, ha, hb, hc = c, a, b, hc, ha, hb
    # a dry, b and c wet: the quadrilateral pab b c pca
    pab, pca = _cut(a, b, ha, hb), _cut(c, a, hc, ha)
    return 2, (pab, b, c, pab, c, pca)


@njit(inline="always", **JIT)
def _area_vector(a, b, c):
    ux, uy, uz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    vx, vy, vz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    return 0.5 * (uy * vz - uz * vy), 0.5 * (uz * vx - ux * vz), 0.5 * (ux * vy - uy * vx)


@njit(inline="always", **JIT)
def _mid(p, q):
    return 0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])


@njit(inline="always", **JIT)
def _add_pressure(a, b, c, depth0, rho_g, rhs):
    """-int p n dA and its moment over triangle a b c (arms), p = rho_g (depth0 - z_arm)."""
    s = _area_vector(a, b, c)
    pc = rho_g * (depth0 - (a[2] + b[2] + c[2]) / 3.0)
    rhs[0] -= pc * s[0]
    rhs[1] -= pc * s[1]
    rhs[2] -= pc * s[2]
    for m in (_mid(a, b), _mid(b, c), _mid(c, a)):
        pm = rho_g * (depth0 - m[2]) / 3.0
        rhs[3] -= pm * (m[1] * s[2] - m[2] * s[1])
        rhs[4] -= pm * (m[2] * s[0] - m[0] * s[2])
        rhs[5] -= pm * (m[0] * s[1] - m[1] * s[0])


@inner
def add_hydrostatic(row, level, pos, rot, rho, gravity, rhs):
    """The still-water pressure rho g (level - z) integrated on the wetted mesh, added to the
    body's force and moment about its reference point (earth frame)."""
    nt = int(row[1])
    t0 = HEADER + 3 * int(row[0])
    depth0 = level - pos[2]  # the level's height above the reference point
    rho_g = rho * gravity
    for t in range(nt):
        a = _vertex(row, int(row[t0 + 3 * t]), rot)
        b = _vertex(row, int(row[t0 + 3 * t + 1]), rot)
        c = _vertex(row, int(row[t0 + 3 * t + 2]), rot)
        count, parts = clip(a, b, c, depth0 - a[2], depth0 - b[2], depth0 - c[2])
        if count >= 1:
            _add_pressure(parts[0], parts[1], parts[2], depth0, rho_g, rhs)
        if count == 2:
            _add_pressure(parts[3], parts[4], parts[5], depth0, rho_g, rhs)


@njit(inline="always", **JIT)
def _add_moments(a, b, c, out):
    s = _area_vector(a, b, c)
    for m in (_mid(a, b), _mid(b, c), _mid(c, a)):
        x, y, z = m
        values = (1.0, x, y, z, x * x, y * y, z * z, x * y, x * z, y * z)
        for k in range(10):
            f = values[k] / 3.0
            out[k, 0] += f * s[0]
            out[k, 1] += f * s[1]
            out[k, 2] += f * s[2]


@njit(**JIT)
def surface_integrals(row, level, pos, rot, out):
    """``out`` (10, 3): int f n dA over the mesh's part below z = ``level``, f the
    ``INTEGRANDS`` of the arms from ``pos`` (earth axes)."""
    out[:, :] = 0.0
    nt = int(row[1])
    t0 = HEADER + 3 * int(row[0])
    depth0 = level - pos[2]
    for t in range(nt):
        a = _vertex(row, int(row[t0 + 3 * t]), rot)
        b = _vertex(row, int(row[t0 + 3 * t + 1]), rot)
        c = _vertex(row, int(row[t0 + 3 * t + 2]), rot)
        count, parts = clip(a, b, c, depth0 - a[2], depth0 - b[2], depth0 - c[2])
        if count >= 1:
            _add_moments(parts[0], parts[1], parts[2], out)
        if count == 2:
            _add_moments(parts[3], parts[4], parts[5], out)


@njit(inline="always", **JIT)
def _add_potential(a, b, c, depth0):
    """int (z - level)^2 / 2 n_z dA over triangle a b c (arms; level - z_ref = ``depth0``)."""
    s = _area_vector(a, b, c)
    total = 0.0
    for m in (_mid(a, b), _mid(b, c), _mid(c, a)):
        total += 0.5 * (m[2] - depth0) ** 2 / 3.0
    return total * s[2]


@inner
def hydrostatic_potential(row, level, pos, rot, rho, gravity):
    """The potential of ``add_hydrostatic``'s force [J]: -rho g int (z - level) dV over the
    volume below the level (the divergence theorem on the wetted surface; zero on the
    waterplane)."""
    nt = int(row[1])
    t0 = HEADER + 3 * int(row[0])
    depth0 = level - pos[2]
    total = 0.0
    for t in range(nt):
        a = _vertex(row, int(row[t0 + 3 * t]), rot)
        b = _vertex(row, int(row[t0 + 3 * t + 1]), rot)
        c = _vertex(row, int(row[t0 + 3 * t + 2]), rot)
        count, parts = clip(a, b, c, depth0 - a[2], depth0 - b[2], depth0 - c[2])
        if count >= 1:
            total += _add_potential(parts[0], parts[1], parts[2], depth0)
        if count == 2:
            total += _add_potential(parts[3], parts[4], parts[5], depth0)
    return -rho * gravity * total
