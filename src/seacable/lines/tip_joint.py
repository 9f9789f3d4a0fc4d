"""The joint at a rigid line's held end: a bending spring and damper between its last segment
and the body it is held on (a star's top joint: cables from a shared body, each ended on its
own top). As the line's other joints (kernels.chain3d_loads.joint_torques,
kernels.planar_chain.link_loads): the moment k phi about the axis that turns the last segment
towards its unloaded direction ``ref`` (earth frame; the reference turns with the body) plus
c times the relative angular velocity, on the last segment; its reaction acts on the held
body, whose motion is imposed. Energy k phi^2 / 2."""

import math

from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels import planar_chain as pc
from seacable.kernels.timefn import JIT


@njit(inline="always", **JIT)
def planar_angle_gap(y, q, n, ref):
    """The planar reference's angle (from the downward vertical towards +x) less the last
    link's, in (-pi, pi] [rad]."""
    gap = math.atan2(ref[0], -ref[2]) - y[q + n - 1]
    return (gap + math.pi) % (2.0 * math.pi) - math.pi


@njit(inline="always", **JIT)
def _bend(y, q, n, ref):
    """The last segment's director (3D) e, e x ``ref`` and the angle phi [rad] between them."""
    at = q + 3 * (n - 1)
    ax, ay, az = y[at], y[at + 1], y[at + 2]
    cx, cy, cz = ay * ref[2] - az * ref[1], az * ref[0] - ax * ref[2], ax * ref[1] - ay * ref[0]
    phi = math.atan2(math.sqrt(cx * cx + cy * cy + cz * cz),
                     ax * ref[0] + ay * ref[1] + az * ref[2])  # fmt: skip
    return ax, ay, az, cx, cy, cz, phi


@njit(**JIT)
def add_torque(planar, n, y, q, v, ref, omega, stiffness, damping, ws):
    """Add the joint's moment on the last segment to the line's workspace ``ws`` (its joint
    and buoyancy moments: chain3d_layout's _TQ rows in 3D, planar_chain's _Q row in the plane).
    ``ref``: the unloaded direction (3, earth frame); ``omega``: the held body's angular
    velocity (3, earth frame)."""
    if planar:
        gap = planar_angle_gap(y, q, n, ref)
        ws[pc._Q, n - 1] += stiffness * gap + damping * (-omega[1] - y[v + n - 1])
        return
    ax, ay, az, cx, cy, cz, phi = _bend(y, q, n, ref)
    at = v + 3 * (n - 1)
    ux, uy, uz = y[at], y[at + 1], y[at + 2]
    wax, way, waz = ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux
    sin_phi = math.sqrt(cx * cx + cy * cy + cz * cz)
    k = stiffness * (phi / sin_phi if sin_phi > 1e-12 else 1.0)
    ws[c3._TQ, n - 1] += k * cx + damping * (omega[0] - wax)
    ws[c3._TQ + 1, n - 1] += k * cy + damping * (omega[1] - way)
    ws[c3._TQ + 2, n - 1] += k * cz + damping * (omega[2] - waz)


@njit(**JIT)
def energy(planar, n, y, q, ref, stiffness):
    """k phi^2 / 2 [J], phi the last segment's angle from ``ref``."""
    if stiffness == 0.0:
        return 0.0
    if planar:
        gap = planar_angle_gap(y, q, n, ref)
    else:
        gap = _bend(y, q, n, ref)[6]
    return 0.5 * stiffness * gap * gap
