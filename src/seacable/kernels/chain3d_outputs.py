"""Outputs of the 3D rigid-segment chain: node positions, tensions, forces on its ends,
energies and the scalar records of ``SCALAR_NAMES`` (numba)."""

import math

import numpy as np
from numba import njit

from seacable.kernels.chain3d import (
    _BM,
    _E,
    _P,
    _SA,
    _SJ,
    _U,
    _V,
    BOTTOM_FREE,
    BOTTOM_SERVO,
    N_SCALARS,
    OK,
    TOP_HEAVE,
    _below_point_body,
    _node_force,
    is_closed,
    solve,
    target_motion,
)
from seacable.kernels.surface import point_potential, segment_potential
from seacable.kernels.timefn import JIT


@njit(**JIT)
def segment_energies(n, length, mass, wet_weight, buoyancy, joint_stiffness, ref, w):
    """Kinetic (own and added mass, translation and rotation), gravity and buoyancy potential
    and joint-spring energy of one line's segments (its workspace ``w`` filled); joint 0 is
    unloaded along ``ref``."""
    kinetic = 0.0
    gravity = 0.0
    elastic = 0.0
    for i in range(n):
        li = length[i]
        ex, ey, ez = w[_E, i], w[_E + 1, i], w[_E + 2, i]
        vx = 0.5 * (w[_V, i] + w[_V, i + 1])
        vy = 0.5 * (w[_V + 1, i] + w[_V + 1, i + 1])
        vz = 0.5 * (w[_V + 2, i] + w[_V + 2, i + 1])
        va = vx * ex + vy * ey + vz * ez
        v2 = vx * vx + vy * vy + vz * vz
        u2 = w[_U, i] ** 2 + w[_U + 1, i] ** 2 + w[_U + 2, i] ** 2
        kinetic += 0.5 * mass[i] * v2 + 0.5 * w[_SA, i] * (v2 - va * va)
        kinetic += 0.5 * w[_SJ, i] * u2
        gravity += segment_potential(wet_weight[i], buoyancy[i], w[_P + 2, i], w[_P + 2, i + 1],
                                     w[_P + 2, i] + 0.5 * li * ez)  # fmt: skip
        if i == 0:
            ax, ay, az = ref[0], ref[1], ref[2]
        else:
            ax, ay, az = w[_E, i - 1], w[_E + 1, i - 1], w[_E + 2, i - 1]
        cx, cy, cz = ay * ez - az * ey, az * ex - ax * ez, ax * ey - ay * ex
        phi = math.atan2(math.sqrt(cx * cx + cy * cy + cz * cz), ax * ex + ay * ey + az * ez)
        elastic += 0.5 * joint_stiffness[i] * phi * phi
    return kinetic, gravity, elastic


@njit(**JIT)
def _energies(y, p, w):
    n = p.n
    kinetic, gravity, elastic = segment_energies(
        n, p.length, p.mass, p.wet_weight, p.buoyancy, p.joint_stiffness, p.top_reference, w
    )
    for k in range(1, n + 1):
        kinetic += 0.5 * (w[_BM, k] * w[_V, k] ** 2 + w[_BM + 1, k] * w[_V + 1, k] ** 2)
        kinetic += 0.5 * w[_BM + 2, k] * w[_V + 2, k] ** 2
        weight = p.body_wet_weight if k == n else p.node_wet_weight[k]
        gravity += point_potential(w[_P + 2, k], weight, p.node_buoyancy[k], p.node_shape[k])
    for k in range(3):
        if p.bottom_kind == BOTTOM_FREE:
            d = w[_P + k, n] - p.tie_rest[k]
            elastic += 0.5 * p.tie_k[k] * d * d
    if p.top_kind == TOP_HEAVE:
        kinetic += 0.5 * p.top_mass * y[6 * n + 1] ** 2
        gravity += p.top_net_weight * y[3 * n]
        d = y[3 * n] - p.top_rest_z
        elastic += 0.5 * p.top_stiffness * d * d
    return kinetic, gravity, elastic


@njit(**JIT)
def outputs(t, y, p, w, node_pos, tension, scalars):
    """Derived outputs at one instant: node_pos (n+1, 3), tension (n,), scalars (N_SCALARS,)."""
    status, _, reaction = solve(t, y, p, w)
    outputs_from_solution(t, y, p, w, reaction, node_pos, tension, scalars)
    return status


@njit(**JIT)
def outputs_from_solution(t, y, p, w, reaction, node_pos, tension, scalars):
    """``outputs`` once ``w`` holds a solution (with ``reaction`` at a closed lower end)."""
    n = p.n
    pinned = is_closed(p)
    for k in range(n + 1):
        for c in range(3):
            node_pos[k, c] = w[_P + c, k]
    f_prev = _node_force(w, 0, reaction, pinned)
    top = -f_prev
    for i in range(n):
        if i > 0:
            f_prev = _below_point_body(p, w, i, t, f_prev)
        f_next = _node_force(w, i + 1, reaction, pinned)
        e0, e1, e2 = w[_E, i], w[_E + 1, i], w[_E + 2, i]
        t_top = -(e0 * f_prev[0] + e1 * f_prev[1] + e2 * f_prev[2])
        t_bottom = -(e0 * f_next[0] + e1 * f_next[1] + e2 * f_next[2])
        tension[i] = 0.5 * (t_top + t_bottom)
        f_prev = f_next
    kinetic, gravity, elastic = _energies(y, p, w)
    for c in range(3):
        scalars[c] = top[c]
        scalars[3 + c] = f_prev[c]
        scalars[6 + c] = w[_V + c, 0]
        scalars[9 + c] = w[_V + c, n]
    scalars[12] = kinetic
    scalars[13] = gravity
    scalars[14] = elastic
    scalars[15] = 0.0
    for k in range(16, N_SCALARS):
        scalars[k] = np.nan
    if pinned or p.bottom_kind == BOTTOM_SERVO:
        pos, _, _ = target_motion(t, y, p)
        d2 = 0.0
        held = 0.0
        for c in range(3):
            scalars[16 + c] = pos[c]
            d2 += (w[_P + c, n] - pos[c]) ** 2
            held += p.constrained[c] * (w[_P + c, n] - pos[c]) ** 2
        scalars[19] = math.sqrt(d2)
        if pinned:
            scalars[15] = math.sqrt(held)
    if p.bottom_kind == BOTTOM_SERVO:
        for c in range(3):
            scalars[20 + c] = y[6 * n + 2 + c]


@njit(**JIT)
def outputs_chunk(times, states, p, w, node_pos, tension, scalars):
    status = OK
    for j in range(times.shape[0]):
        st = outputs(times[j], states[j], p, w, node_pos[j], tension[j], scalars[j])
        if st != OK and status == OK:
            status = st
    return status
