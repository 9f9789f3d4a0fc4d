"""Three-dimensional chain of rigid cylindrical segments: O(n) dynamics and loads (numba).

Frame: x, y horizontal, z up. Segment ``i`` joins node ``i`` (top) to node ``i + 1``; its
orientation is the unit **director** ``e_i`` (top -> bottom) and its rate ``u_i = de_i/dt`` with
``u_i . e_i = 0``. Directors have no singular direction (unlike the two Euler angles of
Jacquot & Marichal, singular along one axis); rotation about the segment's own axis carries no
inertia or stiffness for an axisymmetric slender cylinder and is not a degree of freedom.

State layout (flat float64, length ``6 n + 5``)::

    y = [e_0 (3) .. e_{n-1} (3), z_top, u_0 (3) .. u_{n-1} (3), zdot_top, F_servo (3)]

The servo force (the force a trajectory-following vehicle applies to the cable end, updated by
the stiffness-matrix servo of Jacquot & Marichal) is zero unless the lower end is a servo end.

After every integration step the state is projected back (|e| = 1, u . e = 0):
:func:`project`.

Method: the articulated recursion of ``planar_chain`` in 3D. ``lam_k = M_k A_k + b_k`` with a
symmetric 3x3 ``M_k``; each segment solves a 2x2 system in the plane normal to its director
(any orthonormal basis of that plane: it is a computation device, not a state). A segment's
translational inertia is ``m I + m_a (I - e e^T)`` (added mass normal to the axis only, none
axially) and its rotational inertia about the centre ``m l^2/12 + m_a l^2/12``. Point bodies at
nodes (floats, clump weights) join the articulated inertia of the part below them.
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from seacable.kernels.planar_chain import (
    BOTTOM_FREE,
    BOTTOM_PINNED,
    TOP_HEAVE,
    TOP_IMPOSED,
)
from seacable.kernels.status import NON_FINITE, OK, SINGULAR_CLOSURE
from seacable.kernels.surface import POINT, segment_submersion, submersion
from seacable.kernels.timefn import JIT
from seacable.kernels.timefn import of_params as tf_of_params

__all__ = ["BOTTOM_FREE", "BOTTOM_PINNED", "TOP_HEAVE", "TOP_IMPOSED", "TOP_TRACK"]
SERVO_STATES = 3  # the servo force, at the end of every state vector (zero when unused)

TOP_TRACK = 2  # towing ship on a track: straight, then optionally a circle; s(t) from a channel
BOTTOM_TRAJECTORY = 2  # lower end held on a moving target (exact end force), all axes
BOTTOM_SERVO = 3  # free lower end pulled by a force the stiffness-matrix servo updates

CH_TOP_X, CH_TOP_Y, CH_TOP_Z, CH_TOP_FORCE = 0, 1, 2, 3
CH_BODY_FX, CH_BODY_FY, CH_BODY_FZ = 4, 5, 6
CH_TRACK_S = 7  # distance travelled along the track [m]
CH_TARGET_X, CH_TARGET_Y, CH_TARGET_Z = 8, 9, 10  # target of the lower end (trajectory, servo)
N_CHANNELS = 11

SCALAR_NAMES = (
    "top_force_x",
    "top_force_y",
    "top_force_z",
    "bottom_force_x",
    "bottom_force_y",
    "bottom_force_z",
    "top_velocity_x",
    "top_velocity_y",
    "top_velocity_z",
    "bottom_velocity_x",
    "bottom_velocity_y",
    "bottom_velocity_z",
    "kinetic_energy",
    "gravity_potential_energy",
    "elastic_energy",
    "constraint_error",
    "target_x",
    "target_y",
    "target_z",
    "tracking_error",
    "servo_force_x",
    "servo_force_y",
    "servo_force_z",
)
N_SCALARS = len(SCALAR_NAMES)

# workspace rows, each of length n + 1
_P, _V, _E, _U, _F, _TQ = 0, 3, 6, 9, 12, 15  # 3 rows each: node pos, node vel, e, u, F, torque
_T1, _T2 = 18, 21  # basis of the plane normal to e (3 rows each)
_ID11, _ID12, _ID22 = 24, 25, 26  # inverse of the 2x2 D
_H = 27  # 6 rows: H (3x2), row-major H[r, c] at _H + 2 r + c
_W = 33  # 2 rows
_RS = 35  # 6 rows: dw/dL (2x3), row-major at _RS + 3 r + c
_M = 41  # 6 rows: symmetric M (11, 12, 13, 22, 23, 33)
_B = 47  # 3 rows
_S = 50  # 9 rows: S (3x3) row-major
_XC = 59  # 2 rows: xi constant part
_XL = 61  # 6 rows: d xi / d L (2x3)
_A = 67  # 3 rows: node acceleration
_EDD = 70  # 3 rows: director acceleration
# point bodies at nodes (the end body at node n) as the free surface leaves them (_hydrostatics)
_BM = 73  # 3 rows: mass + submerged share of the added mass per axis [kg]
_BW = 76  # apparent weight, positive down [N]
_BD = 77  # 3 rows: 0.5 rho Cd A times the submerged fraction per axis [N s^2/m^2]
_BK = 80  # hydrostatic heave stiffness rho g A_wp [N/m]
# segments as the free surface leaves them (_kinematics_and_loads): the submerged fraction of the
# length, the added mass and rotational inertia with the added mass of that fraction, and the
# buoyancy's moment arm times its force (centroid of the submerged part from the centre along e)
_SF = 81  # submerged fraction [1]
_SA = 82  # normal added mass [kg]
_SJ = 83  # rotational inertia about the centre [kg m^2]
_SQ = 84  # arm x buoyancy [N m]
N_WORK_ROWS = 85


class Chain3DParams(NamedTuple):
    """Flat parameters of one 3D rigid-segment cable and its end conditions (SI units)."""

    n: int
    length: np.ndarray  # (n,) [m]
    mass: np.ndarray  # (n,) structural mass [kg]
    added_mass: np.ndarray  # (n,) normal added mass [kg]
    inertia: np.ndarray  # (n,) rotational inertia about the centre, added included [kg m^2]
    wet_weight: np.ndarray  # (n,) apparent weight, positive down [N]
    buoyancy: np.ndarray  # (n,) rho g A l of the segment wholly submerged [N]
    drag_normal: np.ndarray  # (n,) 0.5 rho Cd d l [N s^2/m^2]
    drag_tangential: np.ndarray  # (n,) 0.5 rho f Cd d l (Richtmyer) [N s^2/m^2]
    joint_stiffness: np.ndarray  # (n,) [N m/rad]; joint i between segment i-1 (or top) and i
    joint_damping: np.ndarray  # (n,) [N m s/rad]
    top_reference: np.ndarray  # (3,) direction the top joint spring is unloaded at
    current_z: np.ndarray  # (K,) ascending elevations [m]
    current_u: np.ndarray  # (K,) current along x [m/s]
    current_v: np.ndarray  # (K,) current along y [m/s]
    node_mass: np.ndarray  # (n+1, 3) point-body mass + added mass per axis at nodes [kg]
    node_wet_weight: np.ndarray  # (n+1,) point-body apparent weight, positive down [N]
    node_drag: np.ndarray  # (n+1,) point-body 0.5 rho Cd A (sphere) [N s^2/m^2]
    # the free surface (kernels.surface): row k for the point body at node k, row n for the end
    # body; node_mass, node_wet_weight, node_drag and body_* are their wholly submerged values
    node_shape: np.ndarray  # (n+1, L) shape rows
    node_added: np.ndarray  # (n+1, 3) added mass when wholly submerged [kg]
    node_buoyancy: np.ndarray  # (n+1,) rho g V [N]
    top_kind: int
    top_x: float  # heaving structure x, y [m]
    top_y: float
    top_mass: float
    top_stiffness: float
    top_damping: float
    top_rest_z: float
    top_net_weight: float
    track_origin: np.ndarray  # (3,) tow point at s = 0 [m]
    track_heading: float  # initial heading from +x towards +y [rad]
    track_turn_at: float  # distance along the track where the turn starts [m]
    track_radius: float  # signed turning radius (+ turns towards +y/left), 0: no turn [m]
    bottom_kind: int
    body_mass: np.ndarray  # (3,) mass + added mass per axis [kg]
    body_wet_weight: float
    body_drag: np.ndarray  # (3,) 0.5 rho Cd A per axis [N s^2/m^2]
    tie_k: np.ndarray  # (3,) [N/m]
    tie_c: np.ndarray  # (3,) [N s/m]
    tie_rest: np.ndarray  # (3,)
    pin: np.ndarray  # (3,)
    constrained: np.ndarray  # (3,) 1.0 on the axes a closed lower end holds, 0.0 where it is free
    target_relative: int  # 1: target channels are offsets from the top attachment
    servo_stiffness: np.ndarray  # (3, 3) K: force on the end per displacement [N/m]
    servo_gain: float  # a
    servo_rate_gain: float  # b
    servo_step: float  # the update interval Delta t of the servo [s]
    stabilization_frequency: float
    tf_breaks: np.ndarray
    tf_coefs: np.ndarray
    tf_count: np.ndarray
    tf_sine: np.ndarray
    tf_build_up: np.ndarray


def state_size(n):
    return 6 * n + 2 + SERVO_STATES


def make_workspace(n):
    return np.zeros((N_WORK_ROWS, n + 1))


@njit(**JIT)
def _current(current_z, current_u, current_v, z):
    if current_z.shape[0] == 1:
        return current_u[0], current_v[0]
    return np.interp(z, current_z, current_u), np.interp(z, current_z, current_v)


@njit(inline="always", **JIT)
def _tf(p, channel, t):
    return tf_of_params(p, channel, t)


@njit(inline="always", **JIT)
def top_motion(t, y, p):
    """Top position (3), velocity (3), acceleration (3) (zero acceleration for heave)."""
    n = p.n
    pos = np.zeros(3)
    vel = np.zeros(3)
    acc = np.zeros(3)
    if p.top_kind == TOP_HEAVE:
        pos[0] = p.top_x
        pos[1] = p.top_y
        pos[2] = y[3 * n]
        vel[2] = y[6 * n + 1]
        return pos, vel, acc
    if p.top_kind == TOP_TRACK:
        s, sd, sdd = _tf(p, CH_TRACK_S, t)
        c0 = math.cos(p.track_heading)
        s0 = math.sin(p.track_heading)
        if p.track_radius == 0.0 or s <= p.track_turn_at:
            pos[0] = p.track_origin[0] + s * c0
            pos[1] = p.track_origin[1] + s * s0
            vel[0] = sd * c0
            vel[1] = sd * s0
            acc[0] = sdd * c0
            acc[1] = sdd * s0
        else:
            r = p.track_radius
            phi = (s - p.track_turn_at) / r  # heading change (signed with r)
            heading = p.track_heading + phi
            ch = math.cos(heading)
            sh = math.sin(heading)
            # centre of the circle: left of the track for r > 0
            cx = p.track_origin[0] + p.track_turn_at * c0 - r * s0
            cy = p.track_origin[1] + p.track_turn_at * s0 + r * c0
            pos[0] = cx + r * sh
            pos[1] = cy - r * ch
            vel[0] = sd * ch
            vel[1] = sd * sh
            kappa = sd * sd / r
            acc[0] = sdd * ch - kappa * sh
            acc[1] = sdd * sh + kappa * ch
        pos[2] = p.track_origin[2]
        return pos, vel, acc
    pos[0], vel[0], acc[0] = _tf(p, CH_TOP_X, t)
    pos[1], vel[1], acc[1] = _tf(p, CH_TOP_Y, t)
    pos[2], vel[2], acc[2] = _tf(p, CH_TOP_Z, t)
    return pos, vel, acc


@njit(inline="always", **JIT)  # inlined: a call that passes the parameter tuple copies it
def is_closed(p):
    """True when the lower end is held (pinned, guided or on a trajectory): a closed loop."""
    return p.bottom_kind == BOTTOM_PINNED or p.bottom_kind == BOTTOM_TRAJECTORY


@njit(inline="always", **JIT)
def target_channels(t, p):
    """The lower end's target as the case gives it (3 each: position, velocity, acceleration):
    the pin, or the trajectory's channels (offsets from the top when ``target_relative``).
    Shared with the lumped-mass kernel (same field names)."""
    pos = np.empty(3)
    vel = np.zeros(3)
    acc = np.zeros(3)
    if p.bottom_kind == BOTTOM_PINNED:
        pos[:] = p.pin
        return pos, vel, acc
    pos[0], vel[0], acc[0] = _tf(p, CH_TARGET_X, t)
    pos[1], vel[1], acc[1] = _tf(p, CH_TARGET_Y, t)
    pos[2], vel[2], acc[2] = _tf(p, CH_TARGET_Z, t)
    return pos, vel, acc


@njit(inline="always", **JIT)
def target_from(t, p, top_pos, top_vel, top_acc):
    """``target_channels`` made absolute with the top's motion (given) when relative."""
    pos, vel, acc = target_channels(t, p)
    if p.bottom_kind != BOTTOM_PINNED and p.target_relative == 1:
        pos += top_pos
        vel += top_vel
        acc += top_acc
    return pos, vel, acc


@njit(**JIT)
def target_motion(t, y, p):
    """Position, velocity and acceleration (3 each) the lower end is to follow."""
    top_pos, top_vel, top_acc = top_motion(t, y, p)
    return target_from(t, p, top_pos, top_vel, top_acc)


@njit(**JIT)
def _joint_torques(y, p, w):
    """Bending moments V = k phi^2 / 2 and dampers on the relative angular velocity."""
    n = p.n
    u0 = 3 * n + 1
    for i in range(n):
        w[_TQ, i] = 0.0
        w[_TQ + 1, i] = 0.0
        w[_TQ + 2, i] = 0.0
    for i in range(n):
        bx, by, bz = y[3 * i], y[3 * i + 1], y[3 * i + 2]
        if i == 0:
            ax, ay, az = p.top_reference[0], p.top_reference[1], p.top_reference[2]
            wax, way, waz = 0.0, 0.0, 0.0
        else:
            ax, ay, az = y[3 * i - 3], y[3 * i - 2], y[3 * i - 1]
            uax, uay, uaz = y[u0 + 3 * i - 3], y[u0 + 3 * i - 2], y[u0 + 3 * i - 1]
            wax, way, waz = ay * uaz - az * uay, az * uax - ax * uaz, ax * uay - ay * uax
        ubx, uby, ubz = y[u0 + 3 * i], y[u0 + 3 * i + 1], y[u0 + 3 * i + 2]
        wbx, wby, wbz = by * ubz - bz * uby, bz * ubx - bx * ubz, bx * uby - by * ubx
        cx, cy, cz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx  # e_a x e_b
        sin_phi = math.sqrt(cx * cx + cy * cy + cz * cz)
        cos_phi = ax * bx + ay * by + az * bz
        phi = math.atan2(sin_phi, cos_phi)
        factor = phi / sin_phi if sin_phi > 1e-12 else 1.0
        k = p.joint_stiffness[i] * factor
        c = p.joint_damping[i]
        tx = k * cx + c * (wbx - wax)  # moment the joint exerts on segment a; -t on segment b
        ty = k * cy + c * (wby - way)
        tz = k * cz + c * (wbz - waz)
        w[_TQ, i] -= tx
        w[_TQ + 1, i] -= ty
        w[_TQ + 2, i] -= tz
        if i > 0:
            w[_TQ, i - 1] += tx
            w[_TQ + 1, i - 1] += ty
            w[_TQ + 2, i - 1] += tz


@njit(**JIT)
def _kinematics_and_loads(t, y, p, w):
    n = p.n
    u0 = 3 * n + 1
    cz_, cu_, cv_ = p.current_z, p.current_u, p.current_v
    pos, vel, _ = top_motion(t, y, p)
    for k in range(3):
        w[_P + k, 0] = pos[k]
        w[_V + k, 0] = vel[k]
    for i in range(n):
        li = p.length[i]
        ex, ey, ez = y[3 * i], y[3 * i + 1], y[3 * i + 2]
        ux, uy, uz = y[u0 + 3 * i], y[u0 + 3 * i + 1], y[u0 + 3 * i + 2]
        w[_E, i], w[_E + 1, i], w[_E + 2, i] = ex, ey, ez
        w[_U, i], w[_U + 1, i], w[_U + 2, i] = ux, uy, uz
        w[_P, i + 1] = w[_P, i] + li * ex
        w[_P + 1, i + 1] = w[_P + 1, i] + li * ey
        w[_P + 2, i + 1] = w[_P + 2, i] + li * ez
        w[_V, i + 1] = w[_V, i] + li * ux
        w[_V + 1, i + 1] = w[_V + 1, i] + li * uy
        w[_V + 2, i + 1] = w[_V + 2, i] + li * uz
        zc = w[_P + 2, i] + 0.5 * li * ez
        cu, cv = _current(cz_, cu_, cv_, zc)
        rx = w[_V, i] + 0.5 * li * ux - cu
        ry = w[_V + 1, i] + 0.5 * li * uy - cv
        rz = w[_V + 2, i] + 0.5 * li * uz
        vt = rx * ex + ry * ey + rz * ez
        nx, ny, nz = rx - vt * ex, ry - vt * ey, rz - vt * ez
        vn = math.sqrt(nx * nx + ny * ny + nz * nz)
        cn = -p.drag_normal[i] * vn
        ct = -p.drag_tangential[i] * abs(vt) * vt
        w[_F, i] = cn * nx + ct * ex
        w[_F + 1, i] = cn * ny + ct * ey
        w[_F + 2, i] = cn * nz + ct * ez - p.wet_weight[i]
        wet = _segment_surface(p, w, i)
        if wet < 1.0:
            # (a branch that rewrites the loads: wholly submerged segments compute bitwise as
            # they always did) the drag and the buoyancy of the submerged part
            cn *= wet
            ct *= wet
            w[_F, i] = cn * nx + ct * ex
            w[_F + 1, i] = cn * ny + ct * ey
            w[_F + 2, i] = cn * nz + ct * ez - p.wet_weight[i] + (wet - 1.0) * p.buoyancy[i]
    _joint_torques(y, p, w)
    for i in range(n):
        if w[_SF, i] < 1.0:
            # the buoyancy's moment about the centre: (arm e) x (0, 0, lift)
            w[_TQ, i] += w[_SQ, i] * w[_E + 1, i]
            w[_TQ + 1, i] -= w[_SQ, i] * w[_E, i]
    _hydrostatics(p, w)


@njit(inline="always", **JIT)
def _segment_surface(p, w, i):
    """Rows _SF, _SA, _SJ, _SQ of segment i from its nodes' heights in ``w`` (kernels.surface):
    the added mass of the submerged fraction, spread as the whole segment's (so the rotational
    added inertia scales alike), and the buoyancy's moment arm to the submerged part's centroid.
    Returns the fraction."""
    wet, share_top, _ = segment_submersion(w[_P + 2, i], w[_P + 2, i + 1])
    w[_SF, i] = wet
    if wet < 1.0:
        ma = p.added_mass[i]
        lost = (1.0 - wet) * ma
        w[_SA, i] = ma - lost
        w[_SJ, i] = p.inertia[i] - lost * p.length[i] * p.length[i] / 12.0
        w[_SQ, i] = (0.5 - share_top) * p.length[i] * wet * p.buoyancy[i]
    else:
        w[_SA, i] = p.added_mass[i]
        w[_SJ, i] = p.inertia[i]
        w[_SQ, i] = 0.0
    return wet


@njit(inline="always", **JIT)
def _point_loads(p, k, z, out):
    """Mass (3), apparent weight, drag factor (3) and heave stiffness of the point body at node k
    (the end body at k = n) with its reference point at elevation z: the submerged fraction f
    scales the buoyancy, the added mass and the drag (kernels.surface)."""
    if k == p.n:
        mass, weight = p.body_mass, p.body_wet_weight
        drag0, drag1, drag2 = p.body_drag[0], p.body_drag[1], p.body_drag[2]
    else:
        mass, weight = p.node_mass[k], p.node_wet_weight[k]
        drag0 = drag1 = drag2 = p.node_drag[k]
    if p.node_shape[k, 0] == POINT:  # always submerged: the values as given
        out[0], out[1], out[2], out[3] = mass[0], mass[1], mass[2], weight
        out[4], out[5], out[6], out[7] = drag0, drag1, drag2, 0.0
        return
    f, slope, _ = submersion(z, p.node_shape[k])
    lost = 1.0 - f
    for c in range(3):
        out[c] = mass[c] - lost * p.node_added[k, c]
    out[3] = weight + lost * p.node_buoyancy[k]
    out[4], out[5], out[6] = f * drag0, f * drag1, f * drag2
    out[7] = -slope * p.node_buoyancy[k]


@njit(inline="always", **JIT)
def _hydrostatics(p, w):
    """Rows _BM, _BW, _BD, _BK of every node from its elevation (node 0 carries none)."""
    loads = np.empty(8)
    for k in range(1, p.n + 1):
        _point_loads(p, k, w[_P + 2, k], loads)
        for r in range(8):
            w[_BM + r, k] = loads[r]


@njit(**JIT)
def _point_force(p, k, w, t):
    """Force on the point body at node k (not the cable): weight, drag (and at the bottom,
    applied forces and ties)."""
    vx, vy, vz = w[_V, k], w[_V + 1, k], w[_V + 2, k]
    cu, cv = _current(p.current_z, p.current_u, p.current_v, w[_P + 2, k])
    rx, ry, rz = vx - cu, vy - cv, vz
    speed = math.sqrt(rx * rx + ry * ry + rz * rz)
    dx, dy, dz = w[_BD, k] * speed, w[_BD + 1, k] * speed, w[_BD + 2, k] * speed
    if k < p.n:
        return -dx * rx, -dy * ry, -dz * rz - w[_BW, k]
    fx, _, _ = _tf(p, CH_BODY_FX, t)
    fy, _, _ = _tf(p, CH_BODY_FY, t)
    fz, _, _ = _tf(p, CH_BODY_FZ, t)
    fx -= dx * rx + p.tie_k[0] * (w[_P, k] - p.tie_rest[0]) + p.tie_c[0] * vx
    fy -= dy * ry + p.tie_k[1] * (w[_P + 1, k] - p.tie_rest[1]) + p.tie_c[1] * vy
    fz -= dz * rz + p.tie_k[2] * (w[_P + 2, k] - p.tie_rest[2]) + p.tie_c[2] * vz
    return fx, fy, fz - w[_BW, k]


@njit(**JIT)
def _basis(ex, ey, ez):
    """Orthonormal t1, t2 normal to e (t1 built from the axis least aligned with e)."""
    ax, ay, az = abs(ex), abs(ey), abs(ez)
    if ax <= ay and ax <= az:
        t1x, t1y, t1z = 0.0, ez, -ey  # -(x_hat x e): any vector normal to e will do
    elif ay <= az:
        t1x, t1y, t1z = -ez, 0.0, ex
    else:
        t1x, t1y, t1z = ey, -ex, 0.0
    norm = 1.0 / math.sqrt(t1x * t1x + t1y * t1y + t1z * t1z)
    t1x *= norm
    t1y *= norm
    t1z *= norm
    t2x = ey * t1z - ez * t1y
    t2y = ez * t1x - ex * t1z
    t2z = ex * t1y - ey * t1x
    return t1x, t1y, t1z, t2x, t2y, t2z


@njit(**JIT)
def _store_node(w, k, m, b, s):
    for r in range(6):
        w[_M + r, k] = m[r]
    for r in range(3):
        w[_B + r, k] = b[r]
    for r in range(9):
        w[_S + r, k] = s[r]


@njit(**JIT)
def _sym_mul(m, x0, x1, x2):
    """M x for M stored as (11, 12, 13, 22, 23, 33)."""
    return (
        m[0] * x0 + m[1] * x1 + m[2] * x2,
        m[1] * x0 + m[3] * x1 + m[4] * x2,
        m[2] * x0 + m[4] * x1 + m[5] * x2,
    )


@njit(**JIT)
def _backward_sweep(t, y, p, w):
    n = p.n
    pinned = is_closed(p)
    m = np.zeros(6)
    b = np.zeros(3)
    s = np.zeros(9)
    fx, fy, fz = _point_force(p, n, w, t)
    if p.bottom_kind == BOTTOM_SERVO:
        servo = 6 * n + 2
        fx += y[servo]
        fy += y[servo + 1]
        fz += y[servo + 2]
    m[0], m[3], m[5] = w[_BM, n], w[_BM + 1, n], w[_BM + 2, n]
    b[0], b[1], b[2] = -fx, -fy, -fz
    if pinned:  # the holding force L adds to the force below the end node: S = I
        s[0] = s[4] = s[8] = 1.0
    _store_node(w, n, m, b, s)
    for i in range(n - 1, -1, -1):
        li = p.length[i]
        mi = p.mass[i]
        ma = w[_SA, i]
        mt = mi + ma
        ex, ey, ez = w[_E, i], w[_E + 1, i], w[_E + 2, i]
        u2 = w[_U, i] ** 2 + w[_U + 1, i] ** 2 + w[_U + 2, i] ** 2
        t1x, t1y, t1z, t2x, t2y, t2z = _basis(ex, ey, ez)
        a1x, a1y, a1z = _sym_mul(m, t1x, t1y, t1z)
        a2x, a2y, a2z = _sym_mul(m, t2x, t2y, t2z)
        mex, mey, mez = _sym_mul(m, ex, ey, ez)
        base = w[_SJ, i] + 0.25 * mt * li * li
        d11 = base + li * li * (t1x * a1x + t1y * a1y + t1z * a1z)
        d12 = li * li * (t1x * a2x + t1y * a2y + t1z * a2z)
        d22 = base + li * li * (t2x * a2x + t2y * a2y + t2z * a2z)
        inv_det = 1.0 / (d11 * d22 - d12 * d12)
        i11, i12, i22 = d22 * inv_det, -d12 * inv_det, d11 * inv_det
        h1x, h1y, h1z = (
            li * (0.5 * mt * t1x + a1x),
            li * (0.5 * mt * t1y + a1y),
            li * (0.5 * mt * t1z + a1z),
        )
        h2x, h2y, h2z = (
            li * (0.5 * mt * t2x + a2x),
            li * (0.5 * mt * t2y + a2y),
            li * (0.5 * mt * t2z + a2z),
        )
        # generalised director force G = -e x torque
        tqx, tqy, tqz = w[_TQ, i], w[_TQ + 1, i], w[_TQ + 2, i]
        gx, gy, gz = -(ey * tqz - ez * tqy), -(ez * tqx - ex * tqz), -(ex * tqy - ey * tqx)
        qx = -2.0 * li * u2 * mex + 2.0 * b[0] - w[_F, i]
        qy = -2.0 * li * u2 * mey + 2.0 * b[1] - w[_F + 1, i]
        qz = -2.0 * li * u2 * mez + 2.0 * b[2] - w[_F + 2, i]
        w1 = t1x * gx + t1y * gy + t1z * gz - 0.5 * li * (t1x * qx + t1y * qy + t1z * qz)
        w2 = t2x * gx + t2y * gy + t2z * gz - 0.5 * li * (t2x * qx + t2y * qy + t2z * qz)
        k1x, k1y, k1z = i11 * h1x + i12 * h2x, i11 * h1y + i12 * h2y, i11 * h1z + i12 * h2z
        k2x, k2y, k2z = i12 * h1x + i22 * h2x, i12 * h1y + i22 * h2y, i12 * h1z + i22 * h2z
        if pinned:
            # rows of dw/dL = -l T^T S
            r1 = np.empty(3)
            r2 = np.empty(3)
            for c in range(3):
                r1[c] = -li * (t1x * s[c] + t1y * s[3 + c] + t1z * s[6 + c])
                r2[c] = -li * (t2x * s[c] + t2y * s[3 + c] + t2z * s[6 + c])
                w[_RS + c, i] = r1[c]
                w[_RS + 3 + c, i] = r2[c]
            kk = (k1x, k1y, k1z, k2x, k2y, k2z)
            for r in range(3):
                for c in range(3):
                    s[3 * r + c] += kk[r] * r1[c] + kk[3 + r] * r2[c]
        w[_T1, i], w[_T1 + 1, i], w[_T1 + 2, i] = t1x, t1y, t1z
        w[_T2, i], w[_T2 + 1, i], w[_T2 + 2, i] = t2x, t2y, t2z
        w[_ID11, i], w[_ID12, i], w[_ID22, i] = i11, i12, i22
        w[_H, i], w[_H + 1, i] = h1x, h2x
        w[_H + 2, i], w[_H + 3, i] = h1y, h2y
        w[_H + 4, i], w[_H + 5, i] = h1z, h2z
        w[_W, i], w[_W + 1, i] = w1, w2
        # b <- b - F + K w - l u^2 (m/2 e + M e)
        b[0] += -w[_F, i] + k1x * w1 + k2x * w2 - li * u2 * (0.5 * mi * ex + mex)
        b[1] += -w[_F + 1, i] + k1y * w1 + k2y * w2 - li * u2 * (0.5 * mi * ey + mey)
        b[2] += -w[_F + 2, i] + k1z * w1 + k2z * w2 - li * u2 * (0.5 * mi * ez + mez)
        # M <- m_t I - m_a e e^T + M - K H^T
        m[0] += mt - ma * ex * ex - (k1x * h1x + k2x * h2x)
        m[1] += -ma * ex * ey - (k1x * h1y + k2x * h2y)
        m[2] += -ma * ex * ez - (k1x * h1z + k2x * h2z)
        m[3] += mt - ma * ey * ey - (k1y * h1y + k2y * h2y)
        m[4] += -ma * ey * ez - (k1y * h1z + k2y * h2z)
        m[5] += mt - ma * ez * ez - (k1z * h1z + k2z * h2z)
        if i > 0:  # a point body at the top node of this segment joins the part below it
            nm = p.node_mass[i]
            if nm[0] != 0.0 or nm[1] != 0.0 or nm[2] != 0.0 or p.node_wet_weight[i] != 0.0:
                fx, fy, fz = _point_force(p, i, w, t)
                m[0] += w[_BM, i]
                m[3] += w[_BM + 1, i]
                m[5] += w[_BM + 2, i]
                b[0] -= fx
                b[1] -= fy
                b[2] -= fz
        _store_node(w, i, m, b, s)


@njit(**JIT)
def _solve3(a, r):
    """Solve the 3x3 system a x = r (a row-major, 9 values); returns x and the determinant."""
    c00 = a[4] * a[8] - a[5] * a[7]
    c01 = a[5] * a[6] - a[3] * a[8]
    c02 = a[3] * a[7] - a[4] * a[6]
    det = a[0] * c00 + a[1] * c01 + a[2] * c02
    x = np.zeros(3)
    if det == 0.0:
        return x, det
    inv = 1.0 / det
    x[0] = (
        c00 * r[0] + (a[2] * a[7] - a[1] * a[8]) * r[1] + (a[1] * a[5] - a[2] * a[4]) * r[2]
    ) * inv
    x[1] = (
        c01 * r[0] + (a[0] * a[8] - a[2] * a[6]) * r[1] + (a[2] * a[3] - a[0] * a[5]) * r[2]
    ) * inv
    x[2] = (
        c02 * r[0] + (a[1] * a[6] - a[0] * a[7]) * r[1] + (a[0] * a[4] - a[1] * a[3]) * r[2]
    ) * inv
    return x, det


@njit(**JIT)
def _top_acceleration(t, y, p, w, ac, al):
    """Top node acceleration, affine in the pinned reaction L: A0 = ac + al L (al row-major)."""
    n = p.n
    if p.top_kind == TOP_HEAVE:
        u, _, _ = _tf(p, CH_TOP_FORCE, t)
        f_structure = -p.top_stiffness * (y[3 * n] - p.top_rest_z) - p.top_damping * y[6 * n + 1]
        den = p.top_mass + w[_M + 5, 0]
        ac[2] = (f_structure + u - p.top_net_weight - w[_B + 2, 0]) / den
        for c in range(3):
            al[6 + c] = -w[_S + 6 + c, 0] / den
    else:
        _, _, acc = top_motion(t, y, p)
        ac[:] = acc


@njit(**JIT)
def _forward_sweep(y, p, w, ac, al, pinned):
    """Director accelerations, affine in L; leaves the end acceleration in (ac, al)."""
    n = p.n
    u0 = 3 * n + 1
    for i in range(n):
        li = p.length[i]
        u2 = y[u0 + 3 * i] ** 2 + y[u0 + 3 * i + 1] ** 2 + y[u0 + 3 * i + 2] ** 2
        h1 = (w[_H, i], w[_H + 2, i], w[_H + 4, i])
        h2 = (w[_H + 1, i], w[_H + 3, i], w[_H + 5, i])
        i11, i12, i22 = w[_ID11, i], w[_ID12, i], w[_ID22, i]
        r1 = w[_W, i] - (h1[0] * ac[0] + h1[1] * ac[1] + h1[2] * ac[2])
        r2 = w[_W + 1, i] - (h2[0] * ac[0] + h2[1] * ac[1] + h2[2] * ac[2])
        x1 = i11 * r1 + i12 * r2
        x2 = i12 * r1 + i22 * r2
        w[_XC, i] = x1
        w[_XC + 1, i] = x2
        for k in range(3):
            ac[k] += li * (x1 * w[_T1 + k, i] + x2 * w[_T2 + k, i] - u2 * y[3 * i + k])
        if pinned:
            for c in range(3):
                q1 = w[_RS + c, i] - (h1[0] * al[c] + h1[1] * al[3 + c] + h1[2] * al[6 + c])
                q2 = w[_RS + 3 + c, i] - (h2[0] * al[c] + h2[1] * al[3 + c] + h2[2] * al[6 + c])
                xl1 = i11 * q1 + i12 * q2
                xl2 = i12 * q1 + i22 * q2
                w[_XL + c, i] = xl1
                w[_XL + 3 + c, i] = xl2
                for k in range(3):
                    al[3 * k + c] += li * (xl1 * w[_T1 + k, i] + xl2 * w[_T2 + k, i])


@njit(**JIT)
def _closure(t, y, p, w, ac, al):
    """Holding force L at a closed lower end: on each held axis the end acceleration equals the
    Baumgarte-stabilised target; on a free axis L is zero."""
    n = p.n
    omega = p.stabilization_frequency
    pos, vel, acc = target_motion(t, y, p)
    system = np.zeros(9)
    rhs_ = np.zeros(3)
    for k in range(3):
        if p.constrained[k] != 0.0:
            for c in range(3):
                system[3 * k + c] = al[3 * k + c]
            rhs_[k] = (
                acc[k] - 2.0 * omega * (w[_V + k, n] - vel[k])
                - omega * omega * (w[_P + k, n] - pos[k]) - ac[k]
            )  # fmt: skip
        else:
            system[3 * k + k] = 1.0
    reaction, det = _solve3(system, rhs_)
    scale = 1.0
    for v in al:
        scale = max(scale, abs(v))
    return reaction, abs(det) > 1e-12 * scale**3


@njit(**JIT)
def _final_accelerations(y, p, w, acc_top, al_top, reaction, pinned):
    n = p.n
    u0 = 3 * n + 1
    for k in range(3):
        w[_A + k, 0] = acc_top[k] + (
            al_top[3 * k] * reaction[0] + al_top[3 * k + 1] * reaction[1]
            + al_top[3 * k + 2] * reaction[2]
        )  # fmt: skip
    for i in range(n):
        li = p.length[i]
        u2 = y[u0 + 3 * i] ** 2 + y[u0 + 3 * i + 1] ** 2 + y[u0 + 3 * i + 2] ** 2
        x1 = w[_XC, i]
        x2 = w[_XC + 1, i]
        if pinned:
            for c in range(3):
                x1 += w[_XL + c, i] * reaction[c]
                x2 += w[_XL + 3 + c, i] * reaction[c]
        for k in range(3):
            edd = x1 * w[_T1 + k, i] + x2 * w[_T2 + k, i] - u2 * y[3 * i + k]
            w[_EDD + k, i] = edd
            w[_A + k, i + 1] = w[_A + k, i] + li * edd


@njit(**JIT)
def solve(t, y, p, w):
    """Kinematics, loads and accelerations at (t, y) into ``w``.

    Returns (status, top_heave_acceleration, L) with L the pinned-end reaction (3,).
    """
    n = p.n
    pinned = is_closed(p)
    _kinematics_and_loads(t, y, p, w)
    _backward_sweep(t, y, p, w)
    ac = np.zeros(3)
    al = np.zeros(9)
    _top_acceleration(t, y, p, w, ac, al)
    acc_top = ac.copy()
    al_top = al.copy()
    _forward_sweep(y, p, w, ac, al, pinned)
    reaction = np.zeros(3)
    if pinned:
        reaction, sound = _closure(t, y, p, w, ac, al)
        if not sound:
            return SINGULAR_CLOSURE, 0.0, reaction
    _final_accelerations(y, p, w, acc_top, al_top, reaction, pinned)
    status = OK
    if not math.isfinite(w[_A, n] + w[_A + 1, n] + w[_A + 2, n] + w[_A + 2, 0]):
        status = NON_FINITE
    top_acc = w[_A + 2, 0] if p.top_kind == TOP_HEAVE else 0.0
    return status, top_acc, reaction


@njit(**JIT)
def rhs(t, y, p, w, ydot):
    """Time derivative of the state; returns a status code."""
    n = p.n
    status, top_acc, _ = solve(t, y, p, w)
    u0 = 3 * n + 1
    for i in range(n):
        for k in range(3):
            ydot[3 * i + k] = y[u0 + 3 * i + k]
            ydot[u0 + 3 * i + k] = w[_EDD + k, i]
    ydot[3 * n] = y[6 * n + 1] if p.top_kind == TOP_HEAVE else 0.0
    ydot[6 * n + 1] = top_acc
    servo = 6 * n + 2
    for c in range(3):
        ydot[servo + c] = 0.0
    if p.bottom_kind == BOTTOM_SERVO:
        pos, vel, _ = target_motion(t, y, p)
        servo_rates(p, pos, vel, w[_P : _P + 3, n], w[_V : _V + 3, n], ydot, servo)
    return status


@njit(inline="always", **JIT)  # inlined: a call that passes the parameter tuple copies it
def servo_rates(p, target_pos, target_vel, end_pos, end_vel, ydot, start):
    """ydot[start:start + 3] = dF/dt of the servo's force: the paper's per-step correction
    dF = K (a dE - b dt dE') as a rate over its step dt, dE the target less the end's position
    (shared with the lumped-mass kernel: same field names)."""
    for r in range(3):
        rate = 0.0
        for c in range(3):
            error = target_pos[c] - end_pos[c]
            error_rate = target_vel[c] - end_vel[c]
            rate += p.servo_stiffness[r, c] * (
                p.servo_gain * error / p.servo_step - p.servo_rate_gain * error_rate
            )
        ydot[start + r] = rate


@njit(**JIT)
def project(y, p):
    """Put the state back on its manifold: unit directors, rates normal to them."""
    n = p.n
    u0 = 3 * n + 1
    for i in range(n):
        ex, ey, ez = y[3 * i], y[3 * i + 1], y[3 * i + 2]
        inv = 1.0 / math.sqrt(ex * ex + ey * ey + ez * ez)
        ex *= inv
        ey *= inv
        ez *= inv
        y[3 * i], y[3 * i + 1], y[3 * i + 2] = ex, ey, ez
        dot = y[u0 + 3 * i] * ex + y[u0 + 3 * i + 1] * ey + y[u0 + 3 * i + 2] * ez
        y[u0 + 3 * i] -= dot * ex
        y[u0 + 3 * i + 1] -= dot * ey
        y[u0 + 3 * i + 2] -= dot * ez


@njit(**JIT)
def _node_force(w, k, reaction, pinned):
    m = w[_M : _M + 6, k]
    f = np.empty(3)
    ax, ay, az = w[_A, k], w[_A + 1, k], w[_A + 2, k]
    mx, my, mz = _sym_mul(m, ax, ay, az)
    f[0] = mx + w[_B, k]
    f[1] = my + w[_B + 1, k]
    f[2] = mz + w[_B + 2, k]
    if pinned:
        for r in range(3):
            for c in range(3):
                f[r] += w[_S + 3 * r + c, k] * reaction[c]
    return f


@njit(**JIT)
def _below_point_body(p, w, k, t, force_above):
    """Force on the segment below node k, given the force the part above exerts at node k: the
    point body there (if any) takes its share, m a - F (its inertia less its own loads)."""
    nm = p.node_mass[k]
    if nm[0] == 0.0 and nm[1] == 0.0 and nm[2] == 0.0 and p.node_wet_weight[k] == 0.0:
        return force_above
    fx, fy, fz = _point_force(p, k, w, t)
    out = np.empty(3)
    out[0] = force_above[0] + fx - w[_BM, k] * w[_A, k]
    out[1] = force_above[1] + fy - w[_BM + 1, k] * w[_A + 1, k]
    out[2] = force_above[2] + fz - w[_BM + 2, k] * w[_A + 2, k]
    return out
