"""Linear stiffness and damping matrices (earth frame, at the reference point).

Stiffness: F = -K d, d = (x - x_eq, theta), theta the rotation vector of R R_eq^T (the small
rotation from the equilibrium orientation; exactly roll, pitch, yaw for small angles).
Damping: F = -B (v, omega)."""

import math

import numpy as np

from seacable.kernels.jit import inner

STIFFNESS_ROW = 36 + 3 + 4  # K row-major, equilibrium position, equilibrium quaternion
DAMPING_ROW = 36


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
def add_damping(row, vel, omega, rhs):
    v = (vel[0], vel[1], vel[2], omega[0], omega[1], omega[2])
    for i in range(6):
        total = 0.0
        for j in range(6):
            total += row[6 * i + j] * v[j]
        rhs[i] -= total
