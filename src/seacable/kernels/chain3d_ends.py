"""Where the 3D chain's ends go: the top's imposed, heaving or towed motion, the target a
held lower end follows, and the stiffness-matrix servo's force rate (numba; shared with the
lumped-mass kernel, whose parameters use the same field names)."""

import math

import numpy as np
from numba import njit

from seacable.kernels.chain3d_layout import (
    BOTTOM_TRAJECTORY,
    CH_TARGET_X,
    CH_TARGET_Y,
    CH_TARGET_Z,
    CH_TOP_X,
    CH_TOP_Y,
    CH_TOP_Z,
    CH_TRACK_S,
    TOP_TRACK,
    _tf,
)
from seacable.kernels.planar_chain import (
    BOTTOM_PINNED,
    TOP_HEAVE,
)
from seacable.kernels.timefn import JIT


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
