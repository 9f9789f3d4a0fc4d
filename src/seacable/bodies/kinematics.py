"""Compiled kinematics of bodies: orientation quaternions, rotation matrices, the pose and twist
of every body at a time, and the position and velocity of a point of a body.

A pose is the reference point's position (3) and the orientation quaternion q = (w, x, y, z),
|q| = 1, rotating body-frame vectors into the earth frame: r_earth = R(q) r_body. A twist is the
reference point's velocity and the angular velocity omega, both in the earth frame;
dq/dt = 1/2 (0, omega) * q (quaternion product, omega in the earth frame).
Euler angles (roll phi, pitch theta, yaw psi) compose as R = Rz(psi) Ry(theta) Rx(phi).
"""

import math

from numba import njit

from seacable.kernels.jit import JIT, inner
from seacable.kernels.timefn import evaluate

FIXED = 0  # held at rest (BodyKind.FIXED)
IMPOSED = 1  # moved by six time functions (BodyKind.IMPOSED)
DYNAMIC = 2  # moved by its equations of motion (BodyKind.DYNAMIC)
TIP = 3  # a point body carried at the tip of a rigid-segment line: its motion is the tip's,
# its mass and loads join the line's (no state of its own; lines.rigid_segments)

# how an imposed body moves (``motion``)
MOVES = 0  # translates only: its angle channels are all zero
TURNS = 1  # translates and turns by its channels
TRACK = 2  # along a ship's track (``track_point``), turning with it


@njit(inline="always", **JIT)
def has_mass(kind):
    """True for a body that forces accelerate (dynamic, or carried at a line's tip)."""
    return kind == DYNAMIC or kind == TIP


@inner
def body_frame_velocity(y, q, v, scratch):
    """A dynamic rigid body's body-frame velocity (R^T v, R^T w) from the state (its pose at
    ``y[q:q + 7]``, its velocity at ``y[v:v + 6]``), into ``scratch[0:6]`` (its rotation in
    ``scratch[12:21]``)."""
    rot = scratch[12:21].reshape((3, 3))
    rotation(y[q + 3], y[q + 4], y[q + 5], y[q + 6], rot)
    for c in range(3):
        scratch[c] = rot[0, c] * y[v] + rot[1, c] * y[v + 1] + rot[2, c] * y[v + 2]
        scratch[3 + c] = rot[0, c] * y[v + 3] + rot[1, c] * y[v + 4] + rot[2, c] * y[v + 5]


@njit(**JIT)
def rotation(qw, qx, qy, qz, out):
    """The rotation matrix of a unit quaternion, into ``out`` (3, 3)."""
    out[0, 0] = 1.0 - 2.0 * (qy * qy + qz * qz)
    out[0, 1] = 2.0 * (qx * qy - qw * qz)
    out[0, 2] = 2.0 * (qx * qz + qw * qy)
    out[1, 0] = 2.0 * (qx * qy + qw * qz)
    out[1, 1] = 1.0 - 2.0 * (qx * qx + qz * qz)
    out[1, 2] = 2.0 * (qy * qz - qw * qx)
    out[2, 0] = 2.0 * (qx * qz - qw * qy)
    out[2, 1] = 2.0 * (qy * qz + qw * qx)
    out[2, 2] = 1.0 - 2.0 * (qx * qx + qy * qy)


@njit(**JIT)
def euler_quaternion(roll, pitch, yaw):
    """The quaternion of R = Rz(yaw) Ry(pitch) Rx(roll) [rad]."""
    cr, sr = math.cos(0.5 * roll), math.sin(0.5 * roll)
    cp, sp = math.cos(0.5 * pitch), math.sin(0.5 * pitch)
    cy, sy = math.cos(0.5 * yaw), math.sin(0.5 * yaw)
    return (
        cy * cp * cr + sy * sp * sr,
        cy * cp * sr - sy * sp * cr,
        cy * sp * cr + sy * cp * sr,
        sy * cp * cr - cy * sp * sr,
    )


@njit(**JIT)
def quaternion_euler(qw, qx, qy, qz):
    """Roll, pitch, yaw [rad] of a unit quaternion (pitch within [-pi/2, pi/2])."""
    roll = math.atan2(2.0 * (qw * qx + qy * qz), 1.0 - 2.0 * (qx * qx + qy * qy))
    sine = max(-1.0, min(1.0, 2.0 * (qw * qy - qz * qx)))
    pitch = math.asin(sine)
    yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
    return roll, pitch, yaw


@njit(**JIT)
def euler_rates_omega(roll, pitch, yaw, droll, dpitch, dyaw, out):
    """Earth-frame angular velocity of R = Rz(yaw) Ry(pitch) Rx(roll) with angle rates:
    omega = dyaw e_z + dpitch Rz e_y + droll Rz Ry e_x."""
    cy, sy = math.cos(yaw), math.sin(yaw)
    cp, sp = math.cos(pitch), math.sin(pitch)
    out[0] = -dpitch * sy + droll * cp * cy
    out[1] = dpitch * cy + droll * cp * sy
    out[2] = dyaw - droll * sp


@inner
def body_states(t, y, kind, q_at, v_at, rigid, pose0, channel, motion, track, parent, tf, pos,
                rot, vel, omega, acc, quat, work):  # fmt: skip
    """Pose and twist of every body at time t from the state y: ``pos`` (nb, 3), ``rot``
    (nb, 3, 3), ``quat`` (nb, 4), ``vel`` and ``omega`` (nb, 3); and an imposed body's
    acceleration and angular acceleration (``acc`` (nb, 6), earth frame; a fixed body's zero).
    An imposed body moves by its channels (``imposed_channels``: ``channel[b]``, ``motion[b]``,
    ``track[b]``), its position offset, in earth axes, from the reference point of the imposed
    body ``parent[b]`` when that is not -1 (``parent`` names no body that has a parent itself);
    ``tf`` is the tuple of time-function arrays (breaks, coefs, count, sine, build_up); ``work``
    (18) is scratch."""
    for b in range(kind.shape[0]):
        if kind[b] == DYNAMIC:
            q, v = q_at[b], v_at[b]
            for c in range(3):
                pos[b, c] = y[q + c]
                vel[b, c] = y[v + c]
            if rigid[b] == 1:
                rotation(y[q + 3], y[q + 4], y[q + 5], y[q + 6], rot[b])
                for c in range(4):
                    quat[b, c] = y[q + 3 + c]
                for c in range(3):
                    omega[b, c] = y[v + 3 + c]
            else:
                _still(b, rot, omega, quat)
        elif kind[b] == IMPOSED:
            imposed_channels(t, channel[b], motion[b], track[b], tf, work)
            _imposed_state(b, motion[b], work, pos, rot, vel, omega, acc, quat)
        elif kind[b] == FIXED:
            for c in range(3):
                pos[b, c] = pose0[b, c]
                vel[b, c] = 0.0
                omega[b, c] = 0.0
            for c in range(6):
                acc[b, c] = 0.0
            rotation(pose0[b, 3], pose0[b, 4], pose0[b, 5], pose0[b, 6], rot[b])
            for c in range(4):
                quat[b, c] = pose0[b, 3 + c]
        else:  # TIP: its position and velocity come from its line (lines.rigid_segments)
            _still(b, rot, omega, quat)
    for b in range(kind.shape[0]):  # offsets from another imposed body, once it is placed
        a = parent[b]
        if a >= 0:
            for c in range(3):
                pos[b, c] += pos[a, c]
                vel[b, c] += vel[a, c]
                acc[b, c] += acc[a, c]


@njit(inline="always", **JIT)
def _imposed_state(b, motion, work, pos, rot, vel, omega, acc, quat):
    """Body b's pose, twist and acceleration from its channels (``imposed_channels``)."""
    imposed_acceleration(work, acc[b])
    for c in range(3):
        pos[b, c] = work[c]
        vel[b, c] = work[6 + c]
    if motion == MOVES:
        _still(b, rot, omega, quat)
        return
    qw, qx, qy, qz = euler_quaternion(work[3], work[4], work[5])
    rotation(qw, qx, qy, qz, rot[b])
    quat[b, 0], quat[b, 1], quat[b, 2], quat[b, 3] = qw, qx, qy, qz
    euler_rates_omega(work[3], work[4], work[5], work[9], work[10], work[11], omega[b])


@njit(**JIT)
def imposed_channels(t, first, motion, track, tf, work):
    """An imposed body's x, y, z [m], roll, pitch, yaw [rad] at time t (``work[0:6]``), their
    rates (``work[6:12]``) and second derivatives (``work[12:18]``), from its six channels
    starting at ``first``. ``motion`` MOVES: the angles are zero (not evaluated); TURNS: from
    their channels; TRACK: x, y and the yaw's heading from the distance travelled along the
    track (the x channel; ``track_point``), the yaw channel an offset from that heading."""
    breaks, coefs, count, sine, build_up = tf
    used = 3 if motion == MOVES else 6
    for c in range(used):
        work[c], work[6 + c], work[12 + c] = evaluate(breaks, coefs, count, sine, build_up,
                                                      first + c, t)  # fmt: skip
    for c in range(used, 6):
        work[c] = work[6 + c] = work[12 + c] = 0.0
    if motion == TRACK:
        track_point(track, work)


@njit(inline="always", **JIT)
def track_point(track, work):
    """x, y and yaw (``work`` as ``imposed_channels`` fills it) on a ship's track from the
    distance s travelled along it (in place of x): ``track`` = (x0, y0, heading [rad], distance
    where the turn starts [m], signed radius [m]: positive turns towards the left, 0 no turn).
    A straight line from (x0, y0) along the heading, then a circle tangent to it."""
    s, sd, sdd = work[0], work[6], work[12]
    x0, y0, h0, turn_at, r = track[0], track[1], track[2], track[3], track[4]
    c0, s0 = math.cos(h0), math.sin(h0)
    if r == 0.0 or s <= turn_at:
        work[0], work[6], work[12] = x0 + s * c0, sd * c0, sdd * c0
        work[1], work[7], work[13] = y0 + s * s0, sd * s0, sdd * s0
        work[5] += h0
        return
    heading = h0 + (s - turn_at) / r
    ch, sh = math.cos(heading), math.sin(heading)
    cx = x0 + turn_at * c0 - r * s0  # the circle's centre, left of the track for r > 0
    cy = y0 + turn_at * s0 + r * c0
    kappa = sd * sd / r
    work[0], work[6], work[12] = cx + r * sh, sd * ch, sdd * ch - kappa * sh
    work[1], work[7], work[13] = cy - r * ch, sd * sh, sdd * sh + kappa * ch
    work[5] += heading
    work[11] += sd / r
    work[17] += sdd / r


@njit(inline="always", **JIT)
def _still(b, rot, omega, quat):
    """No rotation: the identity orientation, no angular velocity."""
    rotation(1.0, 0.0, 0.0, 0.0, rot[b])
    omega[b, :] = 0.0
    quat[b, 0] = 1.0
    quat[b, 1] = quat[b, 2] = quat[b, 3] = 0.0


@inner
def point_states(body, offset, pos, rot, vel, omega, ppos, pvel, parm):
    """Earth-frame position and velocity of every point (``ppos``, ``pvel`` (np, 3)) and its
    arm from its body's reference point (``parm``): r = R r_body, p = x + r,
    v = v_ref + omega x r."""
    for k in range(body.shape[0]):
        point_state(k, body, offset, pos, rot, vel, omega, ppos, pvel, parm)


@njit(inline="always", **JIT)
def point_state(k, body, offset, pos, rot, vel, omega, ppos, pvel, parm):
    """``point_states`` of point k alone."""
    b = body[k]
    for c in range(3):
        parm[k, c] = (
            rot[b, c, 0] * offset[k, 0] + rot[b, c, 1] * offset[k, 1] + rot[b, c, 2] * offset[k, 2]
        )
    rx, ry, rz = parm[k, 0], parm[k, 1], parm[k, 2]
    wx, wy, wz = omega[b, 0], omega[b, 1], omega[b, 2]
    ppos[k, 0] = pos[b, 0] + rx
    ppos[k, 1] = pos[b, 1] + ry
    ppos[k, 2] = pos[b, 2] + rz
    pvel[k, 0] = vel[b, 0] + wy * rz - wz * ry
    pvel[k, 1] = vel[b, 1] + wz * rx - wx * rz
    pvel[k, 2] = vel[b, 2] + wx * ry - wy * rx


@njit(inline="always", **JIT)
def point_acceleration(kind, acc, arm, omega, out):
    """Acceleration (3) of a point at ``arm`` (earth frame) from its body's reference point:
    a + alpha x r + w x (w x r), with the body's ``acc`` (6: solved for a dynamic or tip body,
    from its channels for an imposed one: ``body_states``), zero for a fixed body."""
    if kind == FIXED:
        out[0] = out[1] = out[2] = 0.0
    else:
        _carried(acc, arm, omega, out)


@njit(inline="always", **JIT)
def _carried(a, r, om, out):
    """a + alpha x r + w x (w x r) of a body's twist rates ``a`` (6)."""
    ax, ay, az = (
        om[1] * r[2] - om[2] * r[1],
        om[2] * r[0] - om[0] * r[2],
        om[0] * r[1] - om[1] * r[0],
    )
    out[0] = a[0] + a[4] * r[2] - a[5] * r[1] + om[1] * az - om[2] * ay
    out[1] = a[1] + a[5] * r[0] - a[3] * r[2] + om[2] * ax - om[0] * az
    out[2] = a[2] + a[3] * r[1] - a[4] * r[0] + om[0] * ay - om[1] * ax


@njit(inline="always", **JIT)
def turn(rot, v):
    """R v for a 3-vector v (a tuple)."""
    return (
        rot[0, 0] * v[0] + rot[0, 1] * v[1] + rot[0, 2] * v[2],
        rot[1, 0] * v[0] + rot[1, 1] * v[1] + rot[1, 2] * v[2],
        rot[2, 0] * v[0] + rot[2, 1] * v[1] + rot[2, 2] * v[2],
    )


@njit(inline="always", **JIT)
def turn_back(rot, v):
    """R^T v for a 3-vector v (a tuple): an earth-frame vector in the body frame."""
    return (
        rot[0, 0] * v[0] + rot[1, 0] * v[1] + rot[2, 0] * v[2],
        rot[0, 1] * v[0] + rot[1, 1] * v[1] + rot[2, 1] * v[2],
        rot[0, 2] * v[0] + rot[1, 2] * v[1] + rot[2, 2] * v[2],
    )


@njit(**JIT)
def imposed_acceleration(work, out):
    """Acceleration (3) and angular acceleration (3, earth frame) of an imposed body from its
    channels (``work`` as ``imposed_channels`` fills it):
    alpha = d/dt (dyaw e_z + dpitch Rz e_y + droll Rz Ry e_x)."""
    for c in range(3):
        out[c] = work[12 + c]
    pitch, yaw = work[4], work[5]
    dr, dp, dy = work[9], work[10], work[11]
    ar, ap, ay = work[15], work[16], work[17]
    cy, sy, cp, sp = math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch)
    ey = (-sy, cy, 0.0)  # Rz e_y
    ex = (cp * cy, cp * sy, -sp)  # Rz Ry e_x
    w1 = (dp * ey[0], dp * ey[1], dy + dp * ey[2])  # angular velocity of Rz Ry
    # d(Rz e_y)/dt = dyaw e_z x Rz e_y; d(Rz Ry e_x)/dt = w1 x Rz Ry e_x
    dey = (-dy * ey[1], dy * ey[0], 0.0)
    dex = (
        w1[1] * ex[2] - w1[2] * ex[1],
        w1[2] * ex[0] - w1[0] * ex[2],
        w1[0] * ex[1] - w1[1] * ex[0],
    )
    for c in range(3):
        out[3 + c] = ap * ey[c] + dp * dey[c] + ar * ex[c] + dr * dex[c]
    out[5] += ay
