"""The 3D rigid-segment chain's layout: kinds of ends, time-function channels, scalar records,
workspace rows, the parameter tuple and the small shared helpers (numba). The chain's kernels
(``chain3d`` and the modules named after it) read their rows and fields from here."""

from typing import NamedTuple

import numpy as np
from numba import njit

from seacable.kernels.timefn import JIT
from seacable.kernels.timefn import of_params as tf_of_params

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
