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
PHASES = 4  # where the vertices' half phases start in place's workspace
NEAR = 16  # where the key row holds the reuse distance [m] (``place``; set by its caller)
RADIUS = 17  # the placed mesh's radius, its farthest vertex from the reference point [m]
LOADS = 18  # where the key row's cached loads start: a flag and 6 floats per model
HYDROSTATIC, FROUDE_KRYLOV = 0, 1  # the cached loads' slots
FAR = LOADS + 14  # the Froude-Krylov force's own reuse distance [m] (``add_froude_krylov``)
HELD = FAR + 1  # the pose (pos, then rot row by row) the Froude-Krylov force was computed at
KEY = HELD + 12  # the floats of the workspace's key row (place)
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


def workspace(vertices: int, components: int) -> np.ndarray:
    """The workspace ``place`` fills for a mesh of up to ``vertices`` vertices in waves of
    ``components`` components (``PHASES`` on)."""
    return np.zeros((vertices + 1, max(PHASES + 2 * components, KEY)))


@inner
def place(row, body, pos, rot, wave, t, work):
    """Each vertex's arm R v from the reference point (earth frame) into ``work[i, 0:3]``, its
    depth below the free surface, eta(x, y) - z (kernels.waves; 0 for still water), into
    ``work[i, 3]`` and, with waves, the cosines and sines of its components' half phases
    into ``work[i, PHASES:PHASES + n]`` and ``work[i, PHASES + n:PHASES + 2 n]``
    (kernels.waves.half_phases: ``add_froude_krylov`` takes its edge midpoints' from them).
    ``work``'s last row keys the placement (``body``, t, the number of components, pos, rot)
    and caches the loads computed on it (``add_hydrostatic``, ``add_froude_krylov``): a
    placement that would move no vertex by more than ``work[-1, NEAR]`` [m] from the last
    (0, the default: the same pose) is not repeated and the loads computed on the last are
    reused (the hydrostatics and the Froude-Krylov force of one body share it; another body,
    time or surface, or a pose moved further, places again). The implicit integrators set
    that distance within a step's Newton iteration (numerics.system_implicit, NEAR). The
    Froude-Krylov force keeps the pose it was computed at and is held over placements of the
    same body, time and surface within its own distance ``work[-1, FAR]``
    (``add_froude_krylov``)."""
    n = wave.shape[1]
    key = work[work.shape[0] - 1]
    same = key[0] == 1.0 and key[1] == body and key[2] == t and key[3] == n
    if same and _move(key, 4, pos, rot) <= key[NEAR]:
        return
    key[0] = 0.0  # unset while the workspace changes
    trig = waves.scratch(wave)
    radius = 0.0
    for i in range(int(row[0])):
        k = HEADER + 3 * i
        x, y, z = row[k], row[k + 1], row[k + 2]
        radius = max(radius, x * x + y * y + z * z)
        for c in range(3):
            work[i, c] = rot[c, 0] * x + rot[c, 1] * y + rot[c, 2] * z
        eta = 0.0
        if n > 0:
            eta = waves.half_phases(wave, t, pos[0] + work[i, 0], pos[1] + work[i, 1], trig,
                                    work[i, PHASES : PHASES + n],
                                    work[i, PHASES + n : PHASES + 2 * n])  # fmt: skip
        work[i, 3] = eta - pos[2] - work[i, 2]
    key[1], key[2], key[3] = body, t, n
    for c in range(3):
        key[4 + c] = pos[c]
        for d in range(3):
            key[7 + 3 * c + d] = rot[c, d]
    key[RADIUS] = 1.000001 * np.sqrt(radius)  # above its rounding
    key[LOADS] = 0.0  # no load computed on it yet; the Froude-Krylov force's pose is its own
    if not same:
        key[LOADS + 7] = 0.0
    key[0] = 1.0


@njit(inline="always", **JIT)
def reuse(work, near, far):
    """Set the workspace's reuse distances [m], ``near`` of every load's placement (``place``)
    and ``far`` of the Froude-Krylov force (``add_froude_krylov``); returns the last ones."""
    key = work[work.shape[0] - 1]
    last = (key[NEAR], key[FAR])
    key[NEAR], key[FAR] = near, far
    return last


@njit(inline="always", **JIT)
def _move(key, at, pos, rot):
    """A bound on how far the pose (pos, rot) moves a vertex of the placed mesh from the pose
    kept in ``key[at:at + 12]``: |dpos + dR v| <= |dpos| + |dR|_F |v| (the Frobenius norm
    bounds the matrix's; sums of squares, not maxima: a pose that is not a number is never
    within reach)."""
    moved = turned = 0.0
    for c in range(3):
        moved += (key[at + c] - pos[c]) ** 2
        for d in range(3):
            turned += (key[at + 3 + 3 * c + d] - rot[c, d]) ** 2
    return np.sqrt(moved) + np.sqrt(turned) * key[RADIUS]


@njit(inline="always", **JIT)
def _cached(work, slot, rhs):
    """Whether the load of ``slot`` was computed on the placement in ``work`` (``place``);
    if so, it is added to ``rhs``. Otherwise the slot's floats are zeroed to receive it."""
    key = work[work.shape[0] - 1]
    at = LOADS + 7 * slot
    if key[at] == 1.0:
        for c in range(6):
            rhs[c] += key[at + 1 + c]
        return True
    key[at + 1 : at + 7] = 0.0
    return False


@njit(inline="always", **JIT)
def _keep(work, slot, rhs):
    """The load just computed into ``slot``'s floats kept for the placement and added to
    ``rhs``."""
    key = work[work.shape[0] - 1]
    at = LOADS + 7 * slot
    key[at] = 1.0
    for c in range(6):
        rhs[c] += key[at + 1 + c]


@njit(inline="always", **JIT)
def _wet(row, t0, t, work):
    """Triangle t's wetted part: (count, parts, turn) of ``clip``."""
    i, j, k = int(row[t0 + 3 * t]), int(row[t0 + 3 * t + 1]), int(row[t0 + 3 * t + 2])
    a = (work[i, 0], work[i, 1], work[i, 2])
    b = (work[j, 0], work[j, 1], work[j, 2])
    c = (work[k, 0], work[k, 1], work[k, 2])
    return clip(a, b, c, work[i, 3], work[j, 3], work[k, 3])


@njit(inline="always", **JIT)
def _cut(p, q, hp, hq):
    """The point of the edge p-q where the depth is zero (hp >= 0 > hq)."""
    s = hp / (hp - hq)
    return (p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]), p[2] + s * (q[2] - p[2]))


@njit(inline="always", **JIT)
def clip(a, b, c, ha, hb, hc):
    """The part of triangle a b c where the depth h >= 0, as ``count`` triangles (0, 1 or 2)
    of the same winding: (count, (a0, b0, c0, a1, b1, c1), turn), the triangle turned by
    ``turn`` (0, 1, 2: the vertex it starts from) so that a is the odd vertex out (one wet:
    the part a pab pca; two: the quadrilateral pab b c pca split from pab). An edge is cut
    from its wet end, so that the two triangles sharing it cut it at the same point."""
    wa, wb, wc = ha >= 0.0, hb >= 0.0, hc >= 0.0
    wet = int(wa) + int(wb) + int(wc)
    if wet == 3:
        return 1, (a, b, c, a, b, c), 0
    if wet == 0:
        return 0, (a, b, c, a, b, c), 0
    turn = 0
    if wet == 1:
        if wb:
            a, b, c, ha, hb, hc, turn = b, c, a, hb, hc, ha, 1
        elif wc:
            a, b, c, ha, hb, hc, turn = c, a, b, hc, ha, hb, 2
        pab, pca = _cut(a, b, ha, hb), _cut(a, c, ha, hc)
        return 1, (a, pab, pca, a, pab, pca), turn
    if not wb:
        a, b, c, ha, hb, hc, turn = b, c, a, hb, hc, ha, 1
    elif not wc:
        a, b, c, ha, hb, hc, turn = c, a, b, hc, ha, hb, 2
    # a dry, b and c wet: the quadrilateral pab b c pca
    pab, pca = _cut(b, a, hb, ha), _cut(c, a, hc, ha)
    return 2, (pab, b, c, pab, c, pca), turn


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
def add_hydrostatic(row, level, rho, gravity, work, rhs):
    """The hydrostatic pressure rho g (level - z) integrated on the mesh's part under the free
    surface (``place`` first), added to the body's force and moment about its reference point
    (earth frame); computed once per placement (``place``)."""
    if not _cached(work, HYDROSTATIC, rhs):
        key = work[work.shape[0] - 1]
        _hydrostatic(row, level, key[4:7], rho, gravity, work, key[LOADS + 1 : LOADS + 7])
        _keep(work, HYDROSTATIC, rhs)


@njit(inline="always", **JIT)
def _hydrostatic(row, level, pos, rho, gravity, work, rhs):
    """``add_hydrostatic``'s load on the placement of the reference point at ``pos``."""
    t0 = HEADER + 3 * int(row[0])
    depth0 = level - pos[2]  # the level's height above the reference point
    rho_g = rho * gravity
    for t in range(int(row[1])):
        count, parts, _ = _wet(row, t0, t, work)
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
def _add_at(pressures, e, p, q, s, pos, wave, t, depth, stretch, rho_g, trig, rhs):
    """The load of the midpoint of p and q (arms) for a part of area vector ``s``: on edge
    ``e`` (its pressure evaluated once for the edge's two triangles), or on the waterline
    (``e`` < 0: its own)."""
    m = _mid(p, q)
    if e < 0:
        pressure = _wave_pressure(m, pos, wave, t, depth, stretch, rho_g, trig)
    else:
        if np.isnan(pressures[e]):
            pressures[e] = _wave_pressure(m, pos, wave, t, depth, stretch, rho_g, trig)
        pressure = pressures[e]
    _add_wave_load(pressure, m, s, rhs)


@njit(inline="always", **JIT)
def _at_wet_edge(pressures, e, i, j, pos, wave, t, depth, stretch, rho_g, work, trig):
    """The pressure at the midpoint of the wholly wet edge ``e`` from vertex i to j (its
    components' cosines the products of the vertices' half phases, ``place``), evaluated once
    for the edge's two triangles; and the midpoint (arm)."""
    m = _mid((work[i, 0], work[i, 1], work[i, 2]), (work[j, 0], work[j, 1], work[j, 2]))
    if np.isnan(pressures[e]):
        n = wave.shape[1]
        ci, si = work[i, PHASES : PHASES + n], work[i, PHASES + n : PHASES + 2 * n]
        cj, sj = work[j, PHASES : PHASES + n], work[j, PHASES + n : PHASES + 2 * n]
        cos_mid = trig[0]
        for q in range(n):
            cos_mid[q] = ci[q] * cj[q] - si[q] * sj[q]
        eta = waves.cos_sum(wave, trig)
        pressures[e] = waves.pressure_given(wave, t, pos[2] + m[2], eta, depth, stretch, rho_g,
                                            trig)  # fmt: skip
    return pressures[e], m


@inner
def add_froude_krylov(row, rho, gravity, wave, t, depth, stretch, work, rhs):
    """The incident wave's dynamic pressure (kernels.waves) integrated on the mesh's part under
    the free surface (``place`` first) by the edge-midpoint rule, added to the body's force
    and moment; computed once per placement (``place``), and held while the placement's pose
    moves no vertex by more than ``work[-1, FAR]`` [m] from the pose it was computed at (0,
    the default: a new placement computes it again; numerics.system_implicit, FAR)."""
    if wave.shape[1] == 0:
        return
    key = work[work.shape[0] - 1]
    at = LOADS + 7 * FROUDE_KRYLOV
    if key[at] == 1.0 and not _move(key, HELD, key[4:7], key[7:16].reshape((3, 3))) <= key[FAR]:
        key[at] = 0.0  # moved further (or not a number)
    if not _cached(work, FROUDE_KRYLOV, rhs):
        _froude_krylov(row, key[4:7], rho, gravity, wave, t, depth, stretch, work,
                       key[at + 1 : at + 7])  # fmt: skip
        key[HELD : HELD + 12] = key[4:16]
        _keep(work, FROUDE_KRYLOV, rhs)


@njit(inline="always", **JIT)
def _froude_krylov(row, pos, rho, gravity, wave, t, depth, stretch, work, rhs):
    """``add_froude_krylov``'s load on the placement of the reference point at ``pos``. Each
    point is the midpoint of two parts at most and evaluated once
    (``pressures`` per edge, NaN until then; a midpoint 0.5 (p + q) is the same float from
    either side, so the sum is the one part by part): a wholly wet edge's midpoint, its
    components' cosines the products of its vertices' half phases (``place``); a cut edge's,
    between its wet vertex and its cut point (``clip`` cuts it at one point from either
    side); a wet quadrilateral's diagonal's; only the waterline's midpoints serve one part."""
    n = wave.shape[1]
    if n == 0:
        return
    nv, nt = int(row[0]), int(row[1])
    t0 = HEADER + 3 * nv
    e0 = t0 + 3 * nt
    rho_g = rho * gravity
    trig = waves.scratch(wave)
    pressures = np.full(3 * nt, np.nan)
    for k in range(nt):
        count, parts, turn = _wet(row, t0, k, work)
        if count == 0:
            continue
        # the corners and edges as clip turned them: a is the odd one out, ab the edge a-b
        a, b, c = (int(row[t0 + 3 * k + turn]), int(row[t0 + 3 * k + (turn + 1) % 3]),
                   int(row[t0 + 3 * k + (turn + 2) % 3]))  # fmt: skip
        ab, bc, ca = (int(row[e0 + 3 * k + turn]), int(row[e0 + 3 * k + (turn + 1) % 3]),
                      int(row[e0 + 3 * k + (turn + 2) % 3]))  # fmt: skip
        if work[a, 3] >= 0.0 and work[b, 3] >= 0.0 and work[c, 3] >= 0.0:
            s = _area_vector(parts[0], parts[1], parts[2])
            for i, j, e in ((a, b, ab), (b, c, bc), (c, a, ca)):
                p, m = _at_wet_edge(pressures, e, i, j, pos, wave, t, depth, stretch, rho_g,
                                    work, trig)  # fmt: skip
                _add_wave_load(p, m, s, rhs)
        elif count == 1:  # a wet: the part a pab pca
            pa, pab, pca = parts[0], parts[1], parts[2]
            s = _area_vector(pa, pab, pca)
            _add_at(pressures, ab, pa, pab, s, pos, wave, t, depth, stretch, rho_g, trig, rhs)
            _add_at(pressures, -1, pab, pca, s, pos, wave, t, depth, stretch, rho_g, trig, rhs)
            _add_at(pressures, ca, pca, pa, s, pos, wave, t, depth, stretch, rho_g, trig, rhs)
        else:  # a dry: pab b c and pab c pca, sharing the diagonal pab c
            pab, pb, pc, pca = parts[0], parts[1], parts[2], parts[5]
            diagonal = _mid(pab, pc)
            across = _wave_pressure(diagonal, pos, wave, t, depth, stretch, rho_g, trig)
            s = _area_vector(pab, pb, pc)
            _add_at(pressures, ab, pab, pb, s, pos, wave, t, depth, stretch, rho_g, trig, rhs)
            p, m = _at_wet_edge(pressures, bc, b, c, pos, wave, t, depth, stretch, rho_g, work,
                                trig)  # fmt: skip
            _add_wave_load(p, m, s, rhs)
            _add_wave_load(across, diagonal, s, rhs)
            s = _area_vector(pab, pc, pca)
            _add_wave_load(across, diagonal, s, rhs)
            _add_at(pressures, ca, pc, pca, s, pos, wave, t, depth, stretch, rho_g, trig, rhs)
            _add_at(pressures, -1, pca, pab, s, pos, wave, t, depth, stretch, rho_g, trig, rhs)


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
    work = np.zeros((int(row[0]) + 1, KEY))  # workspace(nv, 0)
    place(row, 0, pos, rot, waves.still(), 0.0, work)
    for i in range(work.shape[0]):
        work[i, 3] += level
    t0 = HEADER + 3 * int(row[0])
    for t in range(int(row[1])):
        count, parts, _ = _wet(row, t0, t, work)
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
        count, parts, _ = _wet(row, t0, t, work)
        if count >= 1:
            total += _add_potential(parts[0], parts[1], parts[2], depth0)
        if count == 2:
            total += _add_potential(parts[3], parts[4], parts[5], depth0)
    return -total
