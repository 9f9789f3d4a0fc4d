"""Extensible lumped-mass cable in 3D (Poth's displacement variables): the loads of the
system's lumped-mass lines (``lines.lumped_mass``; numba kernels).

Nodes 0..n carry the mass of half of each adjacent segment; segment i joins node i to node i+1.
Axial law (Kelvin-Voigt, no compression): N_i = max(0, EA (eps_i + alpha d eps_i / dt)),
eps_i = |r_{i+1} - r_i| / l_i - 1. Per segment, on the velocity of its centre relative to the
current: normal drag 0.5 rho Cd_n d l |v_n| v_n, tangential drag, added mass
rho pi d^2/4 l (Ca (I - t t^T) + Ca_t t t^T) (normal and along the segment), apparent
weight; each shared half and half by its nodes. In incident waves (kernels.morison): the drag
on the velocity relative to the current and the waves' velocity, the Froude-Krylov and
added-mass force of the water's acceleration, the wetted part under the instantaneous
surface, at its centroid (the lever rule). Seabed contact per node below z = -depth: a
vertical spring-damper and Coulomb friction (regularised) along the seabed. Every step is
O(n): each free node solves its own 3x3 mass matrix.
"""

import math

import numpy as np
from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels import morison, waves
from seacable.kernels.jit import JIT, inner
from seacable.kernels.surface import segment_submersion

# workspace rows (length n + 1)
_F = 0  # 3 rows: force on each node (without inertia)
_MA = 3  # 6 rows: symmetric added-mass matrix of each node (11, 12, 13, 22, 23, 33)
_T = 9  # segment tension
_TX = 10  # 3 rows: unit tangent of each segment
_L = 13  # stretched length of each segment
# floats, clump weights and the end body as the free surface leaves them (_hydrostatics)
_SF = 14  # submerged fraction of the node's body (1 without a shape)
_SK = 15  # hydrostatic heave stiffness rho g A_wp [N/m]
_PM = 16  # 3 rows: point_mass less the emerged share of the added mass [kg]
# the laws' branches at the last evaluation with ``slack`` LAW or LAGGED (the active set),
# read back with ``slack`` FROZEN: 1.0 where segment i is taut, where node k touches the seabed
_TAUT = 19
_CONTACT = 20
# the water's velocity and acceleration at segment i's wetted centroid at the last evaluation
# with ``slack`` LAW (or LAGGED, where it evaluated them), read back with FROZEN: Newton's
# matrix is built without evaluating the waves again (their gradient along a difference
# quotient's small move is left out of the matrix, not of the residual); zero where dry
_WU = 21
_WA = 24
# where and when they were evaluated (``slack`` LAW or LAGGED): the wetted centroid (3 rows)
# and the time (NaN where the segment was dry)
_WX = 27
_WT = 30
N_WORK_ROWS = 31

# ``slack`` modes of segment_loads and seabed_loads
LINEAR = 0  # the axial law linear in tension and compression (smooth static solves)
LAW = 1  # the physical laws: no compression, the seabed pushes only; records the active set
FROZEN = 2  # the laws on the recorded active set: a semismooth Newton's matrix (its
# difference quotients never straddle a kink: a slack segment stays slack, a taut one taut)
LAGGED = 3  # the physical laws, recording the active set as LAW does, with the water's
# kinematics of a segment reused from the last evaluation at the same time while its wetted
# centroid has moved less than REUSE / k_max (an implicit step's residuals: _water)
REUSE = 1e-3  # k_max times the move [rad]: the kinematics' first-order change, relative


@njit(**JIT)
def segment_loads(
    y, n, s0, c0, length, stiffness, damping, slack, drag_normal, drag_tangential, wet_weight,
    buoyancy, added_mass, current_z, current_u, current_v, t, gravity, wave, wave_depth,
    wave_stretch, w,
):  # fmt: skip
    """Tension, tangent, hydrodynamic and weight loads of the n segments of one line, shared
    to its nodes: the line's nodes at ``y = [r_0 .. r_n, v_0 .. v_n]`` (3 each), its segment
    properties at ``[s0 + i]`` of the flat arrays (EA ``stiffness`` [N], alpha ``damping`` [s],
    ``slack``: LAW no compression, LINEAR linear, FROZEN the recorded active set), its nodes'
    workspace columns ``c0 + k``; at time ``t`` [s] in the incident waves ``wave`` (kernels.waves'
    rows, none: (0, 6); ``wave_depth`` [m], ``wave_stretch``; kernels.morison's loads,
    ``gravity`` [m/s^2] giving the displaced mass from the buoyancy; ``wave`` None: compiled
    without the waves' code). Every line model and every line of a system computes its segment
    loads here."""
    v0 = 3 * (n + 1)
    # ``wave`` None: compiled without the waves' code (a system without waves: kernels'
    # switches, system.evaluation's WAVES); rows of none: none of it runs
    waves_on = False if wave is None else wave.shape[1] > 0
    highest = morison.crest(wave) if wave is not None and waves_on else 0.0
    reach = _reach(wave) if wave is not None and slack == LAGGED else 0.0
    trig = np.empty((0, 0)) if wave is None else waves.scratch(wave)  # each phase once
    wax = way = waz = 0.0  # the water's inertia force on a segment [N]
    uniform = current_z.shape[0] == 1  # read once: a call per segment with the current's
    u_uniform, v_uniform = current_u[0], current_v[0]  # arrays takes and drops 3 references
    for k in range(c0, c0 + n + 1):
        for c in range(3):
            w[_F + c, k] = 0.0
        for c in range(6):
            w[_MA + c, k] = 0.0
    for i in range(n):
        s = s0 + i
        a = 3 * i
        b = 3 * (i + 1)
        ka, kb = c0 + i, c0 + i + 1
        dx, dy, dz = y[b] - y[a], y[b + 1] - y[a + 1], y[b + 2] - y[a + 2]
        length_now = math.sqrt(dx * dx + dy * dy + dz * dz)
        tx, ty, tz = dx / length_now, dy / length_now, dz / length_now
        dvx, dvy, dvz = (
            y[v0 + b] - y[v0 + a],
            y[v0 + b + 1] - y[v0 + a + 1],
            y[v0 + b + 2] - y[v0 + a + 2],
        )
        l0 = length[s]
        strain = length_now / l0 - 1.0
        strain_rate = (dvx * tx + dvy * ty + dvz * tz) / l0
        tension = stiffness[s] * (strain + damping[s] * strain_rate)
        if slack == LAW or slack == LAGGED:
            w[_TAUT, ka] = 1.0 if tension > 0.0 else 0.0
            tension = max(tension, 0.0)
        elif slack == FROZEN and w[_TAUT, ka] == 0.0:
            tension = 0.0
        w[_T, ka] = tension
        w[_TX, ka], w[_TX + 1, ka], w[_TX + 2, ka] = tx, ty, tz
        w[_L, ka] = length_now
        # loads at the segment centre on the relative velocity; drag, added mass and buoyancy of
        # its submerged part (kernels.surface), the buoyancy at that part's centroid
        zc = 0.5 * (y[a + 2] + y[b + 2])
        if wave is not None and waves_on:  # wet under the instantaneous surface
            wet, share_a = morison.wet_part(wave, t, highest, y[a], y[a + 1], y[a + 2], y[b],
                                            y[b + 1], y[b + 2], trig)  # fmt: skip
        else:
            wet, share_a, _ = segment_submersion(y[a + 2], y[b + 2])
        if uniform:
            cu, cv = u_uniform, v_uniform
        else:
            cu, cv = c3._current(current_z, current_u, current_v, zc)
        rx = 0.5 * (y[v0 + a] + y[v0 + b]) - cu
        ry = 0.5 * (y[v0 + a + 1] + y[v0 + b + 1]) - cv
        rz = 0.5 * (y[v0 + a + 2] + y[v0 + b + 2])
        if wave is not None and waves_on:
            # the water's velocity and acceleration at the wetted part's centroid
            u, acc = _water(wave, t, slack, wet, share_a, y, a, b, wave_depth, wave_stretch,
                            trig, reach, w, ka)  # fmt: skip
            wax, way, waz = morison.inertia(wet * buoyancy[s] / gravity, wet * added_mass[s, 0],
                                            wet * added_mass[s, 1], acc[0], acc[1], acc[2], tx,
                                            ty, tz)  # fmt: skip
            rx -= u[0]
            ry -= u[1]
            rz -= u[2]
        vt = rx * tx + ry * ty + rz * tz
        nx, ny, nz = rx - vt * tx, ry - vt * ty, rz - vt * tz
        vn = math.sqrt(nx * nx + ny * ny + nz * nz)
        cn = -drag_normal[s] * vn
        ct = -drag_tangential[s] * abs(vt) * vt
        if wet < 1.0:  # (a branch: wholly submerged segments compute as they always did)
            cn *= wet
            ct *= wet
        fx = 0.5 * (cn * nx + ct * tx)
        fy = 0.5 * (cn * ny + ct * ty)
        fz = 0.5 * (cn * nz + ct * tz - wet_weight[s])
        # the pull N t on node i, -N t on node i + 1; loads and added mass half and half
        px, py, pz = tension * tx, tension * ty, tension * tz
        w[_F, ka] += fx + px
        w[_F + 1, ka] += fy + py
        w[_F + 2, ka] += fz + pz
        w[_F, kb] += fx - px
        w[_F + 1, kb] += fy - py
        w[_F + 2, kb] += fz - pz
        ma, mt = 0.5 * added_mass[s, 0], 0.5 * added_mass[s, 1]  # normal, along the segment
        if wet < 1.0:
            # the buoyancy's shares less the halves in wet_weight, and the submerged added mass
            w[_F + 2, ka] += buoyancy[s] * (share_a * wet - 0.5)
            w[_F + 2, kb] += buoyancy[s] * ((1.0 - share_a) * wet - 0.5)
            ma *= wet
            mt *= wet
        if wave is not None and waves_on and wet > 0.0:
            # the water's inertia force at the wetted part's centroid
            w[_F, ka] += share_a * wax
            w[_F + 1, ka] += share_a * way
            w[_F + 2, ka] += share_a * waz
            w[_F, kb] += (1.0 - share_a) * wax
            w[_F + 1, kb] += (1.0 - share_a) * way
            w[_F + 2, kb] += (1.0 - share_a) * waz
        # ma (I - t t^T) + mt t t^T
        d = mt - ma
        m00, m11, m22 = ma + d * tx * tx, ma + d * ty * ty, ma + d * tz * tz
        m01, m02, m12 = d * tx * ty, d * tx * tz, d * ty * tz
        for k in (ka, kb):
            w[_MA, k] += m00
            w[_MA + 1, k] += m01
            w[_MA + 2, k] += m02
            w[_MA + 3, k] += m11
            w[_MA + 4, k] += m12
            w[_MA + 5, k] += m22


@njit(inline="always", **JIT)
def _reach(wave):
    """How far [m] a segment's wetted centroid may move with its water kinematics reused
    (LAGGED): REUSE / k_max, the shortest component's wave number."""
    k_max = 0.0
    for k in wave[waves.K]:
        k_max = max(k_max, k)
    return REUSE / k_max if k_max > 0.0 else 0.0


@njit(inline="always", **JIT)
def _water(wave, t, slack, wet, share_a, y, a, b, depth, stretch, trig, reach, w, ka):
    """The water's velocity and acceleration (kernels.morison.water_at) at the wetted
    centroid of the segment from node a to b (``y`` indices), zero where it is dry. With
    ``slack`` LAW recorded in the workspace column ``ka`` with the centroid and the time; with
    FROZEN read from it; with LAGGED read from it when recorded at time ``t`` within ``reach``
    [m] of the centroid (else evaluated and recorded). Reused values differ from the field's by its
    gradient along the move: at most about REUSE times the component's own size."""
    if slack == FROZEN:
        return ((w[_WU, ka], w[_WU + 1, ka], w[_WU + 2, ka]),
                (w[_WA, ka], w[_WA + 1, ka], w[_WA + 2, ka]))  # fmt: skip
    centre = morison.centroid(share_a, (y[a], y[a + 1], y[a + 2]),
                              (y[b], y[b + 1], y[b + 2]))  # fmt: skip
    if slack == LAGGED and w[_WT, ka] == t:
        dx, dy = centre[0] - w[_WX, ka], centre[1] - w[_WX + 1, ka]
        dz = centre[2] - w[_WX + 2, ka]
        if dx * dx + dy * dy + dz * dz <= reach * reach:
            return ((w[_WU, ka], w[_WU + 1, ka], w[_WU + 2, ka]),
                    (w[_WA, ka], w[_WA + 1, ka], w[_WA + 2, ka]))  # fmt: skip
    u = acc = (0.0, 0.0, 0.0)
    if wet > 0.0:
        u, acc = morison.water_at(wave, t, centre, depth, stretch, trig)
    if slack == LAW or slack == LAGGED:
        for c in range(3):
            w[_WU + c, ka], w[_WA + c, ka] = u[c], acc[c]
        w[_WX, ka], w[_WX + 1, ka], w[_WX + 2, ka] = centre
        w[_WT, ka] = t if wet > 0.0 else math.nan
    return u, acc


@inner
def seabed_spring(depth, stiffness, band):
    """The seabed's elastic push [N] on a node ``depth`` [m] below it, and the share (0 to 1)
    of its damping that acts: C1 in the depth, so that Newton does not cycle across the kink
    of a plain spring. Over the first ``band`` [m] the stiffness rises linearly from 0 to
    ``stiffness`` [N/m]; below it the spring is linear, offset by band / 2 (the push is
    k (depth - band / 2)). With band 0 it is the plain spring k depth, continued linearly
    above the seabed (where only ``seabed_loads`` FROZEN evaluates it)."""
    if depth >= band:
        return stiffness * (depth - 0.5 * band), 1.0
    if depth > 0.0:
        return 0.5 * stiffness * depth * depth / band, depth / band
    if band == 0.0:
        return stiffness * depth, 1.0
    return 0.0, 0.0


@inner
def seabed_slopes(depth, stiffness, band):
    """d(push)/d(depth) [N/m] and d(share)/d(depth) [1/m] of seabed_spring at ``depth``."""
    if depth >= band:
        return stiffness, 0.0
    if depth > 0.0:
        return stiffness * depth / band, 1.0 / band
    if band == 0.0:
        return stiffness, 0.0
    return 0.0, 0.0


@njit(**JIT)
def seabed_gradient(z, vx, vy, vz, seabed_z, stiffness, damping, friction, slip_speed, band,
                    out):  # fmt: skip
    """The derivatives of seabed_loads' force on one node (position height ``z``, velocity
    ``v``) under its physical law (``mode`` LAW): ``out[0:3]`` = dF/dz, ``out[3:12]`` = dF/dv
    row by row (dF_x/dv_x, dF_x/dv_y, ...); zero where the node does not touch. Its position
    along the seabed does not enter the law."""
    out[:] = 0.0
    depth = seabed_z - z
    if depth <= 0.0:
        return
    spring, share = seabed_spring(depth, stiffness, band)
    normal = spring - share * damping * vz
    if normal <= 0.0:
        return
    slope, share_slope = seabed_slopes(depth, stiffness, band)
    dn_dz = -(slope - share_slope * damping * vz)  # depth = seabed_z - z
    dn_dvz = -share * damping
    speed = math.sqrt(vx * vx + vy * vy + slip_speed**2)
    cube = speed * speed * speed
    # F_x = -mu N v_x / speed, F_y = -mu N v_y / speed, F_z = N
    out[0] = -friction * vx / speed * dn_dz
    out[1] = -friction * vy / speed * dn_dz
    out[2] = dn_dz
    out[3] = -friction * normal * (speed * speed - vx * vx) / cube
    out[4] = friction * normal * vx * vy / cube
    out[5] = -friction * vx / speed * dn_dvz
    out[6] = friction * normal * vx * vy / cube
    out[7] = -friction * normal * (speed * speed - vy * vy) / cube
    out[8] = -friction * vy / speed * dn_dvz
    out[11] = dn_dvz


@inner
def seabed_potential(depth, stiffness, band):
    """The elastic energy [J] of seabed_spring's push at ``depth`` [m] (zero above it)."""
    if depth <= 0.0:
        return 0.0
    if depth < band:
        return stiffness * depth**3 / (6.0 * band)
    return stiffness * (0.5 * depth * depth - 0.5 * band * depth + band * band / 6.0)


def seabed_resting_depth(weight, stiffness, band):
    """The depth [m] at which seabed_spring carries ``weight`` [N] (seabed_spring's inverse)."""
    if weight >= 0.5 * stiffness * band:
        return weight / stiffness + 0.5 * band
    return math.sqrt(2.0 * band * weight / stiffness)


@njit(**JIT)
def seabed_loads(y, n, c0, seabed_z, stiffness, damping, friction, slip_speed, band, mode, w):
    """Seabed contact of the n + 1 nodes of one line (``y`` as in segment_loads; per-node
    stiffness [N/m] and damping [N s/m] at ``[c0 + k]``, as its workspace columns): a
    vertical spring-damper below ``seabed_z`` that only pushes (seabed_spring, its stiffness
    rising over the first ``band`` [m]), and regularised Coulomb friction along it. ``mode``
    FROZEN: on the contacts recorded by the last evaluation in any other mode (see
    segment_loads)."""
    v0 = 3 * (n + 1)
    for j in range(n + 1):
        k = c0 + j
        depth = seabed_z - y[3 * j + 2]
        vz = y[v0 + 3 * j + 2]
        if mode == FROZEN:
            if w[_CONTACT, k] == 0.0:
                continue
        elif depth <= 0.0:
            w[_CONTACT, k] = 0.0
            continue
        spring, share = seabed_spring(depth, stiffness[k], band)
        normal = spring - share * damping[k] * vz
        if mode != FROZEN:
            w[_CONTACT, k] = 1.0 if normal > 0.0 else 0.0
            if normal <= 0.0:
                continue
        w[_F + 2, k] += normal
        vx, vy = y[v0 + 3 * j], y[v0 + 3 * j + 1]
        speed = math.sqrt(vx * vx + vy * vy + slip_speed**2)
        w[_F, k] -= friction * normal * vx / speed
        w[_F + 1, k] -= friction * normal * vy / speed


@inner
def _bend_angle(w, i):
    """Angle phi between the tangents of segments i - 1 and i (workspace columns), and
    phi / sin(phi)."""
    ax, ay, az = w[_TX, i - 1], w[_TX + 1, i - 1], w[_TX + 2, i - 1]
    bx, by, bz = w[_TX, i], w[_TX + 1, i], w[_TX + 2, i]
    cx, cy, cz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
    sine = math.sqrt(cx * cx + cy * cy + cz * cz)
    cosine = ax * bx + ay * by + az * bz
    phi = math.atan2(sine, cosine)
    ratio = phi / sine if sine > 1e-12 else 1.0
    return phi, ratio, cosine


@inner
def bending(n, c0, stiffness, w):
    """Bending moment k phi at each interior node of one line (columns and ``stiffness``
    [N m] at ``c0 + k``), from V = k phi^2 / 2 with phi the angle between the two segments'
    tangents: the forces are -k phi dphi/dr on the three nodes, dphi/d(d_a) = -u_a / L_a with
    u_a the unit normal to t_a towards t_b (and the same for b)."""
    for j in range(1, n):
        i = c0 + j
        k = stiffness[i]
        if k == 0.0:
            continue
        phi, ratio, cosine = _bend_angle(w, i)
        if phi == 0.0:
            continue
        la, lb = w[_L, i - 1], w[_L, i]
        for c in range(3):
            ta, tb = w[_TX + c, i - 1], w[_TX + c, i]
            # k phi u_a = k (phi / sin) (t_b - cos t_a)
            ua = k * ratio * (tb - cosine * ta)
            ub = k * ratio * (ta - cosine * tb)
            fa = -ua / la  # on node i - 1
            fb = ub / lb  # on node i + 1
            w[_F + c, i - 1] += fa
            w[_F + c, i + 1] += fb
            w[_F + c, i] -= fa + fb


@inner
def _node_mass_into(m, w, k, a):
    """Node k's mass matrix: structural mass m, the segments' added mass and the point masses
    of the workspace (rows _MA, _PM)."""
    a[0] = m + w[_MA, k]
    a[1] = a[3] = w[_MA + 1, k]
    a[2] = a[6] = w[_MA + 2, k]
    a[4] = m + w[_MA + 3, k]
    a[5] = a[7] = w[_MA + 4, k]
    a[8] = m + w[_MA + 5, k]
    a[0] += w[_PM, k]
    a[4] += w[_PM + 1, k]
    a[8] += w[_PM + 2, k]


@inner
def _node_acceleration(m, w, k):
    """Solve node k's symmetric 3x3 mass matrix (structural mass m, added and point masses
    from the workspace) against its force. Scalars only, and no parameter tuple: per-node
    helpers that take the whole tuple copy it at every call.
    Returns ax, ay, az and False when singular."""
    a00, a01, a02 = m + w[_MA, k], w[_MA + 1, k], w[_MA + 2, k]
    a11, a12, a22 = m + w[_MA + 3, k], w[_MA + 4, k], m + w[_MA + 5, k]
    a00 += w[_PM, k]
    a11 += w[_PM + 1, k]
    a22 += w[_PM + 2, k]
    fx, fy, fz = w[_F, k], w[_F + 1, k], w[_F + 2, k]
    c00 = a11 * a22 - a12 * a12
    c01 = a12 * a02 - a01 * a22
    c02 = a01 * a12 - a11 * a02
    det = a00 * c00 + a01 * c01 + a02 * c02
    if det == 0.0:
        return 0.0, 0.0, 0.0, False
    inv = 1.0 / det
    c11 = a00 * a22 - a02 * a02
    c12 = a02 * a01 - a00 * a12
    c22 = a00 * a11 - a01 * a01
    ax = (c00 * fx + c01 * fy + c02 * fz) * inv
    ay = (c01 * fx + c11 * fy + c12 * fz) * inv
    az = (c02 * fx + c12 * fy + c22 * fz) * inv
    return ax, ay, az, True
