"""A hull's triangle mesh clipped at the free surface, and integrals over its wetted part
(numba).

A mesh is one flat float row (``mesh_row``): ``[nv, nt, x_0, y_0, z_0, ..., i_0, j_0, k_0, ...,
e_0, f_0, g_0, ...]``, the vertices in the body frame relative to the body's reference point [m],
the triangles as vertex numbers, each wound anticlockwise seen from outside (its area vector
S = (b - a) x (c - a) / 2 points out of the hull), and each triangle's edges i-j, j-k, k-i as
edge numbers (0 .. 3 nt - 1; an edge two triangles share has one number).

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

from seacable.kernels import waves
from seacable.kernels.jit import JIT, inner

HEADER = 2  # nv, nt
# the integrands of surface_integrals, in this order
INTEGRANDS = ("1", "x", "y", "z", "xx", "yy", "zz", "xy", "xz", "yz")


def mesh_row(vertices: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """The flat row of a mesh: vertices (nv, 3) [m, body frame], triangles (nt, 3) int."""
    vertices = np.asarray(vertices, dtype=float)
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    head = [float(len(vertices)), float(len(triangles))]
    ends = np.stack([triangles, np.roll(triangles, -1, axis=1)], axis=-1).reshape(-1, 2)
    _, edges = np.unique(np.sort(ends, axis=1), axis=0, return_inverse=True)
    return np.concatenate([head, vertices.ravel(), triangles.ravel().astype(float),
                           edges.ravel().astype(float)])  # fmt: skip


@inner
def place(row, pos, rot, wave, t, work):
    """Each vertex's arm R v from the reference point (earth frame) into ``work[i, 0:3]`` and
    its depth below the free surface, eta(x, y) - z (kernels.waves; 0 for still water), into
    ``work[i, 3]``."""
    trig = waves.scratch(wave)
    for i in range(int(row[0])):
        k = HEADER + 3 * i
        x, y, z = row[k], row[k + 1], row[k + 2]
        for c in range(3):
            work[i, c] = rot[c, 0] * x + rot[c, 1] * y + rot[c, 2] * z
        eta = 0.0
        if wave.shape[1] > 0:
            eta = waves.elevation(wave, t, pos[0] + work[i, 0], pos[1] + work[i, 1], trig)
        work[i, 3] = eta - pos[2] - work[i, 2]


@njit(inline="always", **JIT)
def _wet(row, t0, t, work):
    """Triangle t's wetted part: (count, parts) of ``clip``."""
    i, j, k = int(row[t0 + 3 * t]), int(row[t0 + 3 * t + 1]), int(row[t0 + 3 * t + 2])
    a = (work[i, 0], work[i, 1], work[i, 2])
    b = (work[j, 0], work[j, 1], work[j, 2])
    c = (work[k, 0], work[k, 1], work[k, 2])
    return clip(a, b, c, work[i, 3], work[j, 3], work[k, 3])


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
def add_hydrostatic(row, level, pos, rho, gravity, work, rhs):
    """The hydrostatic pressure rho g (level - z) integrated on the mesh's part under the free
    surface (``place`` first), added to the body's force and moment about its reference point
    (earth frame)."""
    t0 = HEADER + 3 * int(row[0])
    depth0 = level - pos[2]  # the level's height above the reference point
    rho_g = rho * gravity
    for t in range(int(row[1])):
        count, parts = _wet(row, t0, t, work)
        if count >= 1:
            _add_pressure(parts[0], parts[1], parts[2], depth0, rho_g, rhs)
        if count == 2:
            _add_pressure(parts[3], parts[4], parts[5], depth0, rho_g, rhs)


@njit(inline="always", **JIT)
def _add_wave_load(p, m, s, rhs):
    """-p/3 S and its moment m x (-p/3 S): one edge midpoint m's share of its triangle's load."""
    p = p / 3.0
    rhs[0] -= p * s[0]
    rhs[1] -= p * s[1]
    rhs[2] -= p * s[2]
    rhs[3] -= p * (m[1] * s[2] - m[2] * s[1])
    rhs[4] -= p * (m[2] * s[0] - m[0] * s[2])
    rhs[5] -= p * (m[0] * s[1] - m[1] * s[0])


@njit(inline="always", **JIT)
def _wave_pressure(m, pos, wave, t, depth, stretch, rho_g, trig):
    """The incident wave's dynamic pressure at the arm ``m`` from ``pos``."""
    return waves.pressure(wave, t, pos[0] + m[0], pos[1] + m[1], pos[2] + m[2], depth, stretch,
                          rho_g, trig)  # fmt: skip


@njit(inline="always", **JIT)
def _add_wave_pressure(a, b, c, pos, wave, t, depth, stretch, rho_g, trig, rhs):
    """-int p n dA and its moment over triangle a b c (arms), p the incident wave's dynamic
    pressure at its three edge midpoints."""
    s = _area_vector(a, b, c)
    for m in (_mid(a, b), _mid(b, c), _mid(c, a)):
        _add_wave_load(_wave_pressure(m, pos, wave, t, depth, stretch, rho_g, trig), m, s, rhs)


@inner
def add_froude_krylov(row, pos, rho, gravity, wave, t, depth, stretch, work, rhs):
    """The incident wave's dynamic pressure (kernels.waves) integrated on the mesh's part under
    the free surface (``place`` first) by the edge-midpoint rule, added to the body's force
    and moment. A wholly wet triangle's edge midpoints are those of its neighbours: the
    pressure there is evaluated once per edge (``pressures``, NaN until then; the midpoint
    0.5 (a + b) is the same float from either side, so the sum is the one triangle by
    triangle); a cut triangle's parts take theirs."""
    if wave.shape[1] == 0:
        return
    nv, nt = int(row[0]), int(row[1])
    t0 = HEADER + 3 * nv
    e0 = t0 + 3 * nt
    rho_g = rho * gravity
    trig = waves.scratch(wave)
    pressures = np.full(3 * nt, np.nan)
    for k in range(nt):
        count, parts = _wet(row, t0, k, work)
        corners = (int(row[t0 + 3 * k]), int(row[t0 + 3 * k + 1]), int(row[t0 + 3 * k + 2]))
        if work[corners[0], 3] >= 0.0 and work[corners[1], 3] >= 0.0 and work[corners[2], 3] >= 0.0:
            s = _area_vector(parts[0], parts[1], parts[2])
            for side in range(3):
                i, j = corners[side], corners[(side + 1) % 3]
                m = _mid((work[i, 0], work[i, 1], work[i, 2]), (work[j, 0], work[j, 1], work[j, 2]))
                e = int(row[e0 + 3 * k + side])
                if np.isnan(pressures[e]):
                    pressures[e] = _wave_pressure(m, pos, wave, t, depth, stretch, rho_g, trig)
                _add_wave_load(pressures[e], m, s, rhs)
            continue
        if count >= 1:
            _add_wave_pressure(parts[0], parts[1], parts[2], pos, wave, t, depth, stretch, rho_g,
                               trig, rhs)  # fmt: skip
        if count == 2:
            _add_wave_pressure(parts[3], parts[4], parts[5], pos, wave, t, depth, stretch, rho_g,
                               trig, rhs)  # fmt: skip


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
    work = np.zeros((int(row[0]), 4))
    place(row, pos, rot, waves.still(), 0.0, work)
    for i in range(work.shape[0]):
        work[i, 3] += level
    t0 = HEADER + 3 * int(row[0])
    for t in range(int(row[1])):
        count, parts = _wet(row, t0, t, work)
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
def hydrostatic_potential(row, level, pos, work):
    """The potential of ``add_hydrostatic``'s force in still water [J] over rho g: -int
    (z - level) dV over the volume below the level (the divergence theorem on the wetted
    surface; zero on the waterplane). ``place`` first, without waves."""
    t0 = HEADER + 3 * int(row[0])
    depth0 = level - pos[2]
    total = 0.0
    for t in range(int(row[1])):
        count, parts = _wet(row, t0, t, work)
        if count >= 1:
            total += _add_potential(parts[0], parts[1], parts[2], depth0)
        if count == 2:
            total += _add_potential(parts[3], parts[4], parts[5], depth0)
    return -total
