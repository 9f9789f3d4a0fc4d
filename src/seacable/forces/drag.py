"""Quadratic drag of a body on the velocity of its reference point relative to the water (the
current's and the waves' velocity there, kernels.waves with the environment's stretching): per
body axis k, f_k = -c_k |v_r| (R^T v_r)_k, c_k = 0.5 rho Cd A_k [N s^2/m^2], times the
submerged fraction of a shaped body; applied at the reference point (MoorDyn's CdA per axis of
a body or point; with ``fluid inertia``, Morison's equation at that point)."""

import math

from seacable.bodies.dynamics import add_force
from seacable.case.schema import per_axis
from seacable.kernels import chain3d as c3
from seacable.kernels import waves
from seacable.kernels.jit import inner


def pack(spec, rho: float) -> list[float]:
    """The row: c_x, c_y, c_z [N s^2/m^2]."""
    area = per_axis(spec.area)
    return [0.5 * rho * spec.drag_coefficient * a for a in area]


@inner
def add(row, fraction, pos, rot, vel, current_z, current_u, current_v, t, wave, depth, stretch,
        trig, rhs):  # fmt: skip
    """``trig``: kernels.waves' scratch."""
    cu, cv = c3._current(current_z, current_u, current_v, pos[2])
    rx, ry, rz = vel[0] - cu, vel[1] - cv, vel[2]
    if wave.shape[1] > 0:
        u, _ = waves.kinematics(wave, t, pos[0], pos[1], pos[2], depth, stretch, trig)
        rx, ry, rz = rx - u[0], ry - u[1], rz - u[2]
    speed = math.sqrt(rx * rx + ry * ry + rz * rz) * fraction
    # body-frame components R^T v_r, their drag, back to the earth frame
    fb = (
        -row[0] * speed * (rot[0, 0] * rx + rot[1, 0] * ry + rot[2, 0] * rz),
        -row[1] * speed * (rot[0, 1] * rx + rot[1, 1] * ry + rot[2, 1] * rz),
        -row[2] * speed * (rot[0, 2] * rx + rot[1, 2] * ry + rot[2, 2] * rz),
    )
    fx = rot[0, 0] * fb[0] + rot[0, 1] * fb[1] + rot[0, 2] * fb[2]
    fy = rot[1, 0] * fb[0] + rot[1, 1] * fb[1] + rot[1, 2] * fb[2]
    fz = rot[2, 0] * fb[0] + rot[2, 1] * fb[1] + rot[2, 2] * fb[2]
    add_force((0.0, 0.0, 0.0), fx, fy, fz, rhs)
