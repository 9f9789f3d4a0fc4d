"""Extensible lumped-mass cable in 3D (Poth's displacement variables): numba kernels.

Nodes 0..n carry the mass of half of each adjacent segment; segment i joins node i to node i+1.
Axial law (Kelvin-Voigt, no compression): N_i = max(0, EA (eps_i + alpha d eps_i / dt)),
eps_i = |r_{i+1} - r_i| / l_i - 1. Per segment, on the velocity of its centre relative to the
current: normal drag 0.5 rho Cd_n d l |v_n| v_n, tangential drag, normal added mass
Ca rho pi d^2/4 l (I - t t^T), apparent weight; each shared half and half by its nodes. Seabed
contact per node below z = -depth: a vertical spring-damper and Coulomb friction (regularised)
along the seabed. Every step is O(n): each free node solves its own 3x3 mass matrix.

State: ``y = [r_0 .. r_n (3 each), v_0 .. v_n (3 each)]``; node 0 follows the top motion, node n
is free (with a body), or held on the axes of ``constrained``: pinned at ``pin`` (all axes, or
some of them: a guide), or carried along a trajectory (time functions, all axes). A held axis
follows its target exactly; the node's free axes obey its equation of motion with the held
accelerations known. A servo end is free, pulled by the force F of Jacquot & Marichal's
stiffness servo, three more states after the velocities: dF/dt = K (a dE / dt_s - b dE'),
dE the target less the end's position (the paper's per-step correction as a rate over its
step dt_s).
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels.status import NON_FINITE, OK
from seacable.kernels.surface import POINT, segment_submersion, submersion
from seacable.kernels.timefn import JIT

BOTTOM_FREE = c3.BOTTOM_FREE
BOTTOM_PINNED = c3.BOTTOM_PINNED  # held at ``pin`` on the ``constrained`` axes
BOTTOM_TRAJECTORY = c3.BOTTOM_TRAJECTORY  # held on a moving target (all axes)
BOTTOM_SERVO = c3.BOTTOM_SERVO  # free end pulled by the stiffness servo's force (a state)
SERVO_STATES = 3  # after the velocities, with a servo end only

SCALAR_NAMES = (
    "top_force_x",
    "top_force_y",
    "top_force_z",
    "bottom_force_x",
    "bottom_force_y",
    "bottom_force_z",
    "kinetic_energy",
    "gravity_potential_energy",
    "elastic_energy",
    "tracking_error",
    "target_x",
    "target_y",
    "target_z",
    "servo_force_x",
    "servo_force_y",
    "servo_force_z",
)
N_SCALARS = len(SCALAR_NAMES)

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
# the laws' branches at the last evaluation with ``slack`` LAW (the active set), read back
# with ``slack`` FROZEN: 1.0 where segment i is taut, where node k touches the seabed
_TAUT = 19
_CONTACT = 20
N_WORK_ROWS = 21

# ``slack`` modes of segment_loads and seabed_loads
LINEAR = 0  # the axial law linear in tension and compression (smooth static solves)
LAW = 1  # the physical laws: no compression, the seabed pushes only; records the active set
FROZEN = 2  # the laws on the recorded active set: a semismooth Newton's matrix (its
# difference quotients never straddle a kink: a slack segment stays slack, a taut one taut)


class LumpedParams(NamedTuple):
    """Flat parameters of one lumped-mass cable (SI units). Field names shared with
    ``Chain3DParams`` let the top motion and time functions of ``chain3d`` serve both."""

    n: int
    length: np.ndarray  # (n,) unstretched segment length [m]
    node_mass: np.ndarray  # (n+1,) structural mass lumped at nodes [kg]
    added_mass: np.ndarray  # (n,) normal added mass of each segment [kg]
    wet_weight: np.ndarray  # (n,) apparent weight of each segment, positive down [N]
    buoyancy: np.ndarray  # (n,) rho g A l of each segment wholly submerged [N]
    axial_stiffness: float  # EA [N]
    segment_stiffness: np.ndarray  # (n,) EA of each segment [N] (the kernels read this one)
    axial_damping: np.ndarray  # (n,) alpha of each segment [s]
    slack_allowed: int  # 1: no compression (the physical law); 0: linear (smooth static solves)
    drag_normal: np.ndarray  # (n,) 0.5 rho Cd_n d l [N s^2/m^2]
    drag_tangential: np.ndarray  # (n,) [N s^2/m^2]
    current_z: np.ndarray
    current_u: np.ndarray
    current_v: np.ndarray
    seabed_z: float  # elevation of the seabed [m] (-inf: none)
    seabed_stiffness: np.ndarray  # (n+1,) vertical stiffness per node [N/m]
    seabed_damping: np.ndarray  # (n+1,) [N s/m]
    seabed_friction: float  # Coulomb coefficient
    seabed_slip_speed: float  # regularisation speed of friction [m/s]
    top_kind: int
    top_x: float
    top_y: float
    top_mass: float  # floating structure: mass + heave added mass [kg]
    top_stiffness: float  # [N/m]
    top_damping: float  # [N s/m]
    top_rest_z: float  # [m]
    top_net_weight: float  # [N], positive down
    track_origin: np.ndarray
    track_heading: float
    track_turn_at: float
    track_radius: float
    bottom_kind: int
    body_mass: np.ndarray  # (3,) [kg]; the kernel uses point_mass[n], which includes it
    point_mass: np.ndarray  # (n+1, 3) floats and clump weights (+ added mass) per node [kg]
    point_weight: np.ndarray  # (n+1,) their apparent weight, positive down [N]
    point_drag: np.ndarray  # (n+1,) their 0.5 rho Cd A (sphere) [N s^2/m^2]
    # the free surface (kernels.surface), as chain3d's: row k for the body at node k, row n for
    # the end body; point_* and body_* are wholly submerged values
    node_shape: np.ndarray  # (n+1, L) shape rows
    node_added: np.ndarray  # (n+1, 3) added mass when wholly submerged [kg]
    node_buoyancy: np.ndarray  # (n+1,) rho g V [N]
    bend_stiffness: np.ndarray  # (n+1,) EI / mean span at interior nodes, 0 at the ends [N m]
    body_wet_weight: float
    body_drag: np.ndarray  # (3,)
    tie_k: np.ndarray  # (3,) elastic ties (or a second structure's springs) at the end [N/m]
    tie_c: np.ndarray  # (3,) [N s/m]
    tie_rest: np.ndarray  # (3,) where the ties are unloaded [m]
    pin: np.ndarray  # (3,)
    constrained: np.ndarray  # (3,) 1.0 on the axes a held end follows its target
    target_relative: int  # 1: trajectory channels are offsets from the top node
    servo_stiffness: np.ndarray  # (3, 3) K: holding force on the end per displacement [N/m]
    servo_gain: float  # a
    servo_rate_gain: float  # b
    servo_step: float  # the update interval Delta t of the servo [s]
    tf_breaks: np.ndarray
    tf_coefs: np.ndarray
    tf_count: np.ndarray
    tf_sine: np.ndarray
    tf_build_up: np.ndarray


def state_size(n, servo=False):
    return 6 * (n + 1) + (SERVO_STATES if servo else 0)


def make_workspace(n):
    return np.zeros((N_WORK_ROWS, n + 1))


@njit(inline="always", **JIT)
def _segment_forces(t, y, p, w):
    """Tension, tangent, hydrodynamic and weight loads of every segment, shared to its nodes."""
    segment_loads(
        y, p.n, 0, 0, p.length, p.segment_stiffness, p.axial_damping, p.slack_allowed,
        p.drag_normal, p.drag_tangential, p.wet_weight, p.buoyancy, p.added_mass,
        p.current_z, p.current_u, p.current_v, w,
    )  # fmt: skip


@njit(**JIT)
def segment_loads(
    y, n, s0, c0, length, stiffness, damping, slack, drag_normal, drag_tangential, wet_weight,
    buoyancy, added_mass, current_z, current_u, current_v, w,
):  # fmt: skip
    """Tension, tangent, hydrodynamic and weight loads of the n segments of one line, shared
    to its nodes: the line's nodes at ``y = [r_0 .. r_n, v_0 .. v_n]`` (3 each), its segment
    properties at ``[s0 + i]`` of the flat arrays (EA ``stiffness`` [N], alpha ``damping`` [s],
    ``slack``: LAW no compression, LINEAR linear, FROZEN the recorded active set), its nodes'
    workspace columns ``c0 + k``. Every line model and every line of a system computes its
    segment loads here."""
    v0 = 3 * (n + 1)
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
        if slack == LAW:
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
        wet, share_a, _ = segment_submersion(y[a + 2], y[b + 2])
        if uniform:
            cu, cv = u_uniform, v_uniform
        else:
            cu, cv = c3._current(current_z, current_u, current_v, zc)
        rx = 0.5 * (y[v0 + a] + y[v0 + b]) - cu
        ry = 0.5 * (y[v0 + a + 1] + y[v0 + b + 1]) - cv
        rz = 0.5 * (y[v0 + a + 2] + y[v0 + b + 2])
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
        ma = 0.5 * added_mass[s]
        if wet < 1.0:
            # the buoyancy's shares less the halves in wet_weight, and the submerged added mass
            w[_F + 2, ka] += buoyancy[s] * (share_a * wet - 0.5)
            w[_F + 2, kb] += buoyancy[s] * ((1.0 - share_a) * wet - 0.5)
            ma *= wet
        m00, m11, m22 = ma * (1.0 - tx * tx), ma * (1.0 - ty * ty), ma * (1.0 - tz * tz)
        m01, m02, m12 = -ma * tx * ty, -ma * tx * tz, -ma * ty * tz
        for k in (ka, kb):
            w[_MA, k] += m00
            w[_MA + 1, k] += m01
            w[_MA + 2, k] += m02
            w[_MA + 3, k] += m11
            w[_MA + 4, k] += m12
            w[_MA + 5, k] += m22


@njit(inline="always", **JIT)
def _seabed(y, p, w):
    seabed_loads(
        y, p.n, 0, p.seabed_z, p.seabed_stiffness, p.seabed_damping, p.seabed_friction,
        p.seabed_slip_speed, LAW, w,
    )  # fmt: skip


@njit(**JIT)
def seabed_loads(y, n, c0, seabed_z, stiffness, damping, friction, slip_speed, mode, w):
    """Seabed contact of the n + 1 nodes of one line (``y`` as in segment_loads; per-node
    stiffness [N/m] and damping [N s/m] at ``[c0 + k]``, as its workspace columns): a
    vertical spring-damper below ``seabed_z`` that only pushes, and regularised Coulomb
    friction along it. ``mode`` FROZEN: on the contacts recorded by the last evaluation in
    any other mode (see segment_loads)."""
    v0 = 3 * (n + 1)
    for j in range(n + 1):
        k = c0 + j
        depth = seabed_z - y[3 * j + 2]
        vz = y[v0 + 3 * j + 2]
        normal = stiffness[k] * depth - damping[k] * vz
        if mode == FROZEN:
            if w[_CONTACT, k] == 0.0:
                continue
        else:
            touching = depth > 0.0 and normal > 0.0
            w[_CONTACT, k] = 1.0 if touching else 0.0
            if not touching:
                continue
        w[_F + 2, k] += normal
        vx, vy = y[v0 + 3 * j], y[v0 + 3 * j + 1]
        speed = math.sqrt(vx * vx + vy * vy + slip_speed**2)
        w[_F, k] -= friction * normal * vx / speed
        w[_F + 1, k] -= friction * normal * vy / speed


@njit(**JIT)
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


@njit(**JIT)
def _bending(n, stiffness, w):
    bending(n, 0, stiffness, w)


@njit(**JIT)
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


@njit(inline="always", **JIT)
def _hydrostatics(y, p, w):
    """Rows _SF, _SK, _PM of every node from its elevation (kernels.surface)."""
    for k in range(p.n + 1):
        fraction, slope = 1.0, 0.0
        if p.node_shape[k, 0] != POINT:
            fraction, slope, _ = submersion(y[3 * k + 2], p.node_shape[k])
        w[_SF, k] = fraction
        w[_SK, k] = -slope * p.node_buoyancy[k]
        for c in range(3):
            w[_PM + c, k] = p.point_mass[k, c] - (1.0 - fraction) * p.node_added[k, c]


@njit(inline="always", **JIT)
def _point_forces(y, p, w):
    """Apparent weight and sphere drag of the floats and clump weights (the end body at node n
    is _body_load's)."""
    n = p.n
    v0 = 3 * (n + 1)
    for k in range(n):
        fraction = w[_SF, k]
        weight = p.point_weight[k] + (1.0 - fraction) * p.node_buoyancy[k]
        drag = fraction * p.point_drag[k]
        if weight == 0.0 and drag == 0.0:
            continue
        w[_F + 2, k] -= weight
        if drag > 0.0:
            cu, cv = c3._current(p.current_z, p.current_u, p.current_v, y[3 * k + 2])
            rx, ry, rz = y[v0 + 3 * k] - cu, y[v0 + 3 * k + 1] - cv, y[v0 + 3 * k + 2]
            c = drag * math.sqrt(rx * rx + ry * ry + rz * rz)
            w[_F, k] -= c * rx
            w[_F + 1, k] -= c * ry
            w[_F + 2, k] -= c * rz


@njit(inline="always", **JIT)
def _body_load(t, y, p):
    """Force on the end body besides the cable: applied, drag, apparent weight, ties (zero
    without a body), the submerged fraction scaling buoyancy and drag."""
    n = p.n
    v0 = 3 * (n + 1)
    fraction, _, _ = submersion(y[3 * n + 2], p.node_shape[n])
    wet_weight = p.body_wet_weight + (1.0 - fraction) * p.node_buoyancy[n]
    cu, cv = c3._current(p.current_z, p.current_u, p.current_v, y[3 * n + 2])
    rx, ry, rz = y[v0 + 3 * n] - cu, y[v0 + 3 * n + 1] - cv, y[v0 + 3 * n + 2]
    speed = math.sqrt(rx * rx + ry * ry + rz * rz)
    f = np.empty(3)
    f[0], _, _ = c3._tf(p, c3.CH_BODY_FX, t)
    f[1], _, _ = c3._tf(p, c3.CH_BODY_FY, t)
    f[2], _, _ = c3._tf(p, c3.CH_BODY_FZ, t)
    speed *= fraction
    f[0] -= p.body_drag[0] * speed * rx
    f[1] -= p.body_drag[1] * speed * ry
    f[2] -= p.body_drag[2] * speed * rz + wet_weight
    for c in range(3):
        f[c] -= p.tie_k[c] * (y[3 * n + c] - p.tie_rest[c]) + p.tie_c[c] * y[v0 + 3 * n + c]
    if p.bottom_kind == BOTTOM_SERVO:
        for c in range(3):
            f[c] += y[2 * v0 + c]
    return f


@njit(inline="always", **JIT)
def _body_force(t, y, p, w):
    f = _body_load(t, y, p)
    for c in range(3):
        w[_F + c, p.n] += f[c]


@njit(**JIT)
def _node_mass(p, w, k):
    """The 3x3 mass matrix of node k, row-major."""
    a = np.empty(9)
    _node_mass_into(p.node_mass[k], w, k, a)
    return a


@njit(**JIT)
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


@njit(**JIT)
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


@njit(inline="always", **JIT)
def top_state(t, y, p):
    """Top node position, velocity and acceleration (3 each). A floating structure is node 0
    itself, free in heave (its acceleration comes from the dynamics: zero here), held in x, y."""
    if p.top_kind == c3.TOP_HEAVE:
        v0 = 3 * (p.n + 1)
        pos = np.array([p.top_x, p.top_y, y[2]])
        vel = np.array([0.0, 0.0, y[v0 + 2]])
        return pos, vel, np.zeros(3)
    return c3.top_motion(t, y, p)


@njit(inline="always", **JIT)
def _structure_force(t, y, p):
    """Vertical force on a floating structure besides the cable: spring, damper, u(t), net
    weight."""
    v0 = 3 * (p.n + 1)
    u, _, _ = c3._tf(p, c3.CH_TOP_FORCE, t)
    return (
        -p.top_stiffness * (y[2] - p.top_rest_z) - p.top_damping * y[v0 + 2] + u - p.top_net_weight
    )


is_held = c3.is_closed  # the end node follows a target on some axes (pinned, guided, trajectory)


@njit(inline="always", **JIT)
def target_state(t, y, p):
    """Position, velocity and acceleration (3 each) a held (or servo) end follows."""
    if p.bottom_kind == BOTTOM_PINNED:  # a pin or a guide: at rest (no top needed)
        return c3.target_channels(t, p)
    top_pos, top_vel, top_acc = top_state(t, y, p)
    return c3.target_from(t, p, top_pos, top_vel, top_acc)


@njit(inline="always", **JIT)  # inlined: a call that passes the parameter tuple copies it
def _free_axes(p):
    """True when the end node moves along some axis (a free end, or a guide)."""
    if not is_held(p):
        return True
    return p.constrained[0] == 0.0 or p.constrained[1] == 0.0 or p.constrained[2] == 0.0


@njit(inline="always", **JIT)
def _held_end(t, y, p, w, ydot):
    """Derivatives of the end node held on some axes: those follow the target; the free ones
    solve the node's equation with the held accelerations known. False when singular."""
    n = p.n
    v0 = 3 * (n + 1)
    _, vel, acc = target_state(t, y, p)
    mass = _node_mass(p, w, n)
    system = np.zeros(9)
    rhs_ = np.zeros(3)
    for c in range(3):
        if p.constrained[c] != 0.0:
            system[4 * c] = 1.0
            rhs_[c] = acc[c]
        else:
            for k in range(3):
                system[3 * c + k] = mass[3 * c + k]
            rhs_[c] = w[_F + c, n]
    a, det = c3._solve3(system, rhs_)
    for c in range(3):
        held = p.constrained[c] != 0.0
        ydot[3 * n + c] = vel[c] if held else y[v0 + 3 * n + c]
        ydot[v0 + 3 * n + c] = a[c]
    return det != 0.0


@njit(**JIT)
def rhs(t, y, p, w, ydot):
    n = p.n
    v0 = 3 * (n + 1)
    _segment_forces(t, y, p, w)
    _hydrostatics(y, p, w)
    _bending(p.n, p.bend_stiffness, w)
    _seabed(y, p, w)
    _point_forces(y, p, w)
    if _free_axes(p):  # a body (its loads act on the free axes only)
        _body_force(t, y, p, w)
    pos, vel, acc = top_state(t, y, p)
    heave = p.top_kind == c3.TOP_HEAVE
    status = OK
    for k in range(n + 1):
        for c in range(3):
            ydot[3 * k + c] = y[v0 + 3 * k + c]
        if k == 0:
            for c in range(3):
                ydot[c] = vel[c]
                ydot[v0 + c] = acc[c]
            if heave:
                # held in x and y: the vertical equation alone, the structure's mass added
                mass = p.node_mass[0] + w[_PM + 2, 0] + w[_MA + 5, 0] + p.top_mass
                ydot[v0 + 2] = (w[_F + 2, 0] + _structure_force(t, y, p)) / mass
            continue
        if k == n and is_held(p):
            if p.bottom_kind == BOTTOM_PINNED and not _free_axes(p):  # a pin: at rest
                for c in range(3):
                    ydot[3 * n + c] = 0.0
                    ydot[v0 + 3 * n + c] = 0.0
            elif not _held_end(t, y, p, w, ydot):
                status = NON_FINITE
            continue
        ax, ay, az, ok = _node_acceleration(p.node_mass[k], w, k)
        if not ok:
            status = NON_FINITE
        ydot[v0 + 3 * k] = ax
        ydot[v0 + 3 * k + 1] = ay
        ydot[v0 + 3 * k + 2] = az
    if p.bottom_kind == BOTTOM_SERVO:
        _servo_rates(t, y, p, ydot)
    if not math.isfinite(ydot[v0 + 3 * n] + ydot[v0 + 3 * n + 2]):
        status = NON_FINITE
    return status


@njit(inline="always", **JIT)
def _servo_rates(t, y, p, ydot):
    """dF/dt = K (a dE / dt_s - b dE') of the servo's force (the states after the velocities)."""
    n = p.n
    v0 = 3 * (n + 1)
    pos, vel, _ = target_state(t, y, p)
    end = 3 * n
    c3.servo_rates(p, pos, vel, y[end : end + 3], y[v0 + end : v0 + end + 3], ydot, 2 * v0)
