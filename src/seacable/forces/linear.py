"""Linear stiffness, and linear and quadratic damping matrices (at the reference point).

Stiffness (earth frame): F = -K d, d = (x - x_eq, theta), theta the rotation vector of
R R_eq^T (the small rotation from the equilibrium orientation; exactly roll, pitch, yaw for
small angles).
Damping: in the earth frame F = -B (v, omega); in the body frame (a vessel's viscous damping)
on the body-frame velocity relative to the current at the reference point,
nu_r = (R^T (v - c), R^T omega): F_body = -B nu_r (linear) or -B (|nu_r| nu_r), component by
component (quadratic), turned into the earth frame."""

import math

import numpy as np
from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels.jit import JIT, inner

STIFFNESS_ROW = 36 + 3 + 4  # K row-major, equilibrium position, equilibrium quaternion
DAMPING_ROW = 36 + 1  # B row-major, then the form (EARTH, BODY, QUADRATIC)
EARTH, BODY, QUADRATIC = 0, 1, 2
FORMS = {"earth": EARTH, "body": BODY, "quadratic": QUADRATIC}


def matrix(spec) -> np.ndarray:
    """The 6x6 matrix of a spec with ``matrix`` or ``diagonal``."""
    if spec.matrix is not None:
        return np.array(spec.matrix, dtype=float)
    return np.diag(np.array(spec.diagonal, dtype=float))


@inner
def rotation_vector(qw, qx, qy, qz):
    """The rotation vector [rad] of a unit quaternion (the shorter way round)."""
    if qw < 0.0:
        qw, qx, qy, qz = -qw, -qx, -qy, -qz
    s = math.sqrt(qx * qx + qy * qy + qz * qz)
    if s < 1e-12:
        return 2.0 * qx, 2.0 * qy, 2.0 * qz
    angle = 2.0 * math.atan2(s, qw)
    return angle * qx / s, angle * qy / s, angle * qz / s


@inner
def _displacement(row, pos, quat):
    """d = (x - x_eq, theta) of the stiffness row; ``quat`` the orientation (w, x, y, z)."""
    ew, ex, ey, ez = row[39], -row[40], -row[41], -row[42]  # conjugate of q_eq
    qw, qx, qy, qz = quat[0], quat[1], quat[2], quat[3]
    # q q_eq^*
    dw = qw * ew - qx * ex - qy * ey - qz * ez
    dx = qw * ex + qx * ew + qy * ez - qz * ey
    dy = qw * ey - qx * ez + qy * ew + qz * ex
    dz = qw * ez + qx * ey - qy * ex + qz * ew
    tx, ty, tz = rotation_vector(dw, dx, dy, dz)
    return (pos[0] - row[36], pos[1] - row[37], pos[2] - row[38], tx, ty, tz)


@inner
def add_stiffness(row, pos, quat, rhs):
    """-K d added to the body's force and moment."""
    d = _displacement(row, pos, quat)
    for i in range(6):
        total = 0.0
        for j in range(6):
            total += row[6 * i + j] * d[j]
        rhs[i] -= total


@inner
def stiffness_energy(row, pos, quat):
    """1/2 d^T K d [J] (the potential of -K d when K is symmetric)."""
    d = _displacement(row, pos, quat)
    total = 0.0
    for i in range(6):
        for j in range(6):
            total += 0.5 * d[i] * row[6 * i + j] * d[j]
    return total


@inner
def add_damping(row, pos, rot, vel, omega, current_z, current_u, current_v, rhs):
    form = int(row[36])
    if form == EARTH:
        v = (vel[0], vel[1], vel[2], omega[0], omega[1], omega[2])
        for i in range(6):
            total = 0.0
            for j in range(6):
                total += row[6 * i + j] * v[j]
            rhs[i] -= total
        return
    cu, cv = c3._current(current_z, current_u, current_v, pos[2])
    rx, ry, rz = vel[0] - cu, vel[1] - cv, vel[2]
    nu = (
        rot[0, 0] * rx + rot[1, 0] * ry + rot[2, 0] * rz,
        rot[0, 1] * rx + rot[1, 1] * ry + rot[2, 1] * rz,
        rot[0, 2] * rx + rot[1, 2] * ry + rot[2, 2] * rz,
        rot[0, 0] * omega[0] + rot[1, 0] * omega[1] + rot[2, 0] * omega[2],
        rot[0, 1] * omega[0] + rot[1, 1] * omega[1] + rot[2, 1] * omega[2],
        rot[0, 2] * omega[0] + rot[1, 2] * omega[1] + rot[2, 2] * omega[2],
    )
    if form == QUADRATIC:
        nu = (abs(nu[0]) * nu[0], abs(nu[1]) * nu[1], abs(nu[2]) * nu[2], abs(nu[3]) * nu[3],
              abs(nu[4]) * nu[4], abs(nu[5]) * nu[5])  # fmt: skip
    body = (_row_times(row, 0, nu), _row_times(row, 1, nu), _row_times(row, 2, nu),
            _row_times(row, 3, nu), _row_times(row, 4, nu), _row_times(row, 5, nu))  # fmt: skip
    for i in range(3):
        rhs[i] -= rot[i, 0] * body[0] + rot[i, 1] * body[1] + rot[i, 2] * body[2]
        rhs[3 + i] -= rot[i, 0] * body[3] + rot[i, 1] * body[4] + rot[i, 2] * body[5]


@njit(inline="always", **JIT)
def _row_times(row, i, v):
    return (row[6 * i] * v[0] + row[6 * i + 1] * v[1] + row[6 * i + 2] * v[2]
            + row[6 * i + 3] * v[3] + row[6 * i + 4] * v[4] + row[6 * i + 5] * v[5])  # fmt: skip
