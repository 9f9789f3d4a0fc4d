"""The 3D rigid-segment chain's workspace rows and small shared helpers (numba). The chain's
kernels (``chain3d`` and the modules named after it) read their rows from here."""

from seacable.kernels.jit import inner

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


@inner
def _current(current_z, current_u, current_v, z):
    """The current's velocity (east, north) [m/s] at elevation ``z`` [m] from its profile."""
    if current_z.shape[0] == 1:
        return current_u[0], current_v[0]
    return profile(z, current_z, current_u), profile(z, current_z, current_v)


@inner
def profile(x, xp, fp):
    """``np.interp(x, xp, fp)`` for increasing ``xp`` of two points or more: linear between
    them, the end value beyond them, NaN at a NaN ``x``. Written out: numba's ``np.interp``
    serves any shapes and types and costs a second of compile time for each caller's types."""
    last = xp.shape[0] - 1
    if x != x:
        return x
    if x <= xp[0]:
        return fp[0]
    if x >= xp[last]:
        return fp[last]
    j = 0
    while xp[j + 1] <= x:  # xp[j] <= x < xp[j + 1]
        j += 1
    slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j])
    return slope * (x - xp[j]) + fp[j]
