"""Joints at rigid lines' ends: a bending spring and damper between a line's last segment and
either the body its end is held on (a star's top joint: cables from a shared body, each ended
on its own top) or the first segment of the line that continues it through the point body
between them (a cable cut at a body along it). As the line's own joints
(kernels.chain3d_loads.joint_torques, kernels.planar_chain.link_loads): the moment k phi about
the axis that turns the last segment towards the other direction, plus c times their relative
angular velocity, on the last segment, and its opposite on the next line's first segment; a
held body's reaction is not needed (its motion is imposed). Energy k phi^2 / 2."""

import math

from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels import planar_chain as pc
from seacable.kernels.jit import JIT, inner


@njit(inline="always", **JIT)
def planar_angle_gap(y, q, n, ref):
    """The planar reference's angle (from the downward vertical towards +x) less the last
    link's, in (-pi, pi] [rad]."""
    gap = math.atan2(ref[0], -ref[2]) - y[q + n - 1]
    return (gap + math.pi) % (2.0 * math.pi) - math.pi


@njit(inline="always", **JIT)
def _bend(ax, ay, az, bx, by, bz):
    """a x b and the angle phi [rad] between the unit vectors a and b."""
    cx, cy, cz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
    phi = math.atan2(math.sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz)
    return cx, cy, cz, phi


@njit(inline="always", **JIT)
def _moment(ax, ay, az, bx, by, bz, wax, way, waz, wbx, wby, wbz, stiffness, damping, ws, i):
    """Add the joint's moment on segment a (column i of its line's workspace ``ws``, rows _TQ)
    and return it: k phi about a x b, c (w_b - w_a)."""
    cx, cy, cz, phi = _bend(ax, ay, az, bx, by, bz)
    sin_phi = math.sqrt(cx * cx + cy * cy + cz * cz)
    k = stiffness * (phi / sin_phi if sin_phi > 1e-12 else 1.0)
    tx = k * cx + damping * (wbx - wax)
    ty = k * cy + damping * (wby - way)
    tz = k * cz + damping * (wbz - waz)
    ws[c3._TQ, i] += tx
    ws[c3._TQ + 1, i] += ty
    ws[c3._TQ + 2, i] += tz
    return tx, ty, tz


@njit(inline="always", **JIT)
def _director(y, q, v, i):
    """Segment i's director and its angular velocity e x de/dt (3D)."""
    at, rt = q + 3 * i, v + 3 * i
    ax, ay, az = y[at], y[at + 1], y[at + 2]
    ux, uy, uz = y[rt], y[rt + 1], y[rt + 2]
    return ax, ay, az, ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux


@inner
def add_torque(planar, n, y, q, v, ref, omega, stiffness, damping, ws):
    """Add a held end's joint moment on the last segment to the line's workspace ``ws`` (its
    joint and buoyancy moments: chain3d_layout's _TQ rows in 3D, planar_chain's _Q row in the
    plane). ``ref``: the unloaded direction (3, earth frame); ``omega``: the held body's
    angular velocity (3, earth frame)."""
    if planar:
        gap = planar_angle_gap(y, q, n, ref)
        ws[pc._Q, n - 1] += stiffness * gap + damping * (-omega[1] - y[v + n - 1])
        return
    ax, ay, az, wax, way, waz = _director(y, q, v, n - 1)
    _moment(ax, ay, az, ref[0], ref[1], ref[2], wax, way, waz, omega[0], omega[1], omega[2],
            stiffness, damping, ws, n - 1)  # fmt: skip


@inner
def add_between(planar, n, y, q, v, q_next, v_next, stiffness, damping, ws, ws_next):
    """Add the joint between a line's last segment (n segments, directors or angles at ``q``,
    rates at ``v``, workspace ``ws``) and the first segment of the line that continues it
    (``q_next``, ``v_next``, ``ws_next``): the moment on the one, its opposite on the other."""
    if planar:
        torque = stiffness * (y[q_next] - y[q + n - 1]) + damping * (y[v_next] - y[v + n - 1])
        ws[pc._Q, n - 1] += torque
        ws_next[pc._Q, 0] -= torque
        return
    ax, ay, az, wax, way, waz = _director(y, q, v, n - 1)
    bx, by, bz, wbx, wby, wbz = _director(y, q_next, v_next, 0)
    tx, ty, tz = _moment(ax, ay, az, bx, by, bz, wax, way, waz, wbx, wby, wbz, stiffness,
                         damping, ws, n - 1)  # fmt: skip
    ws_next[c3._TQ, 0] -= tx
    ws_next[c3._TQ + 1, 0] -= ty
    ws_next[c3._TQ + 2, 0] -= tz


@inner
def energy(planar, n, y, q, ref, stiffness, q_next):
    """k phi^2 / 2 [J], phi the last segment's angle from ``ref`` (a held end: ``q_next`` -1)
    or from the first segment of the line that continues it (its first director or angle at
    ``q_next``)."""
    if stiffness == 0.0:
        return 0.0
    if planar:
        gap = planar_angle_gap(y, q, n, ref) if q_next < 0 else y[q_next] - y[q + n - 1]
    else:
        at = q + 3 * (n - 1)
        if q_next >= 0:
            bx, by, bz = y[q_next], y[q_next + 1], y[q_next + 2]
        else:
            bx, by, bz = ref[0], ref[1], ref[2]
        gap = _bend(y[at], y[at + 1], y[at + 2], bx, by, bz)[3]
    return 0.5 * stiffness * gap * gap
