"""Outputs of the extensible lumped-mass cable: node positions, tensions, the forces on its
ends, energies and the scalar records of ``kernels.lumped.SCALAR_NAMES`` (numba)."""

import math

import numpy as np
from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels.lumped import (
    _F,
    _SF,
    _T,
    _TX,
    BOTTOM_SERVO,
    BOTTOM_TRAJECTORY,
    N_SCALARS,
    _bend_angle,
    _body_load,
    _free_axes,
    _node_mass,
    _node_mass_into,
    is_held,
    rhs,
    target_state,
)
from seacable.kernels.status import OK
from seacable.kernels.surface import point_potential, segment_potential
from seacable.kernels.timefn import JIT


@njit(**JIT)
def line_energies(
    yl, n, s0, c0, node_mass, length, stiffness, wet_weight, buoyancy, seabed_z, seabed_k,
    bend, slack, w,
):  # fmt: skip
    """Kinetic (added mass included), gravity potential (apparent weight and the buoyancy of
    the submerged part) and elastic (axial, seabed, bending) energies of one line's nodes
    ``yl = [r_0 .. r_n, v_0 .. v_n]`` [J]: segment arrays at ``[s0 + i]``, node arrays and
    workspace columns at ``[c0 + k]`` (filled by the rates), ``slack`` as in segment_loads.
    Every lumped line, alone or in a system, counts its energies here."""
    v0 = 3 * (n + 1)
    kinetic = gravity = elastic = 0.0
    m3 = np.empty(9)
    for j in range(n + 1):
        k = c0 + j
        _node_mass_into(node_mass[k], w, k, m3)
        vx, vy, vz = yl[v0 + 3 * j], yl[v0 + 3 * j + 1], yl[v0 + 3 * j + 2]
        kinetic += 0.5 * (
            vx * (m3[0] * vx + m3[1] * vy + m3[2] * vz)
            + vy * (m3[3] * vx + m3[4] * vy + m3[5] * vz)
            + vz * (m3[6] * vx + m3[7] * vy + m3[8] * vz)
        )
        depth = seabed_z - yl[3 * j + 2]
        if depth > 0.0:
            elastic += 0.5 * seabed_k[k] * depth * depth
        if 0 < j < n and bend[k] > 0.0:
            phi, _, _ = _bend_angle(w, k)
            elastic += 0.5 * bend[k] * phi * phi
    for i in range(n):
        s = s0 + i
        za, zb = yl[3 * i + 2], yl[3 * i + 5]
        gravity += segment_potential(wet_weight[s], buoyancy[s], za, zb, 0.5 * (za + zb))
        dx = yl[3 * i + 3] - yl[3 * i]
        dy = yl[3 * i + 4] - yl[3 * i + 1]
        dz = yl[3 * i + 5] - yl[3 * i + 2]
        strain = math.sqrt(dx * dx + dy * dy + dz * dz) / length[s] - 1.0
        if strain > 0.0 or slack == 0:
            elastic += 0.5 * stiffness[s] * length[s] * strain * strain
    return kinetic, gravity, elastic


@njit(**JIT)
def _energies(y, p, w):
    """The cable's energies (line_energies) with its end body, point bodies, ties and a
    floating structure's spring and mass (w filled by rhs)."""
    n = p.n
    v0 = 3 * (n + 1)
    kinetic, gravity, elastic = line_energies(
        y, n, 0, 0, p.node_mass, p.length, p.segment_stiffness, p.wet_weight, p.buoyancy,
        p.seabed_z, p.seabed_stiffness, p.bend_stiffness, p.slack_allowed, w,
    )  # fmt: skip
    for k in range(n + 1):  # the end body (zero without one) at n, point bodies before it
        weight = p.body_wet_weight if k == n else p.point_weight[k]
        gravity += point_potential(y[3 * k + 2], weight, p.node_buoyancy[k], p.node_shape[k])
    for c in range(3):  # ties: zero without them
        d = y[3 * n + c] - p.tie_rest[c]
        elastic += 0.5 * p.tie_k[c] * d * d
    if p.top_kind == c3.TOP_HEAVE:
        vz = y[v0 + 2]
        kinetic += 0.5 * p.top_mass * vz * vz
        gravity += p.top_net_weight * y[2]
        d = y[2] - p.top_rest_z
        elastic += 0.5 * p.top_stiffness * d * d
    return kinetic, gravity, elastic


@njit(**JIT)
def outputs(t, y, p, w, node_pos, tension, scalars):
    n = p.n
    v0 = 3 * (n + 1)
    ydot = np.empty_like(y)
    status = rhs(t, y, p, w, ydot)
    for k in range(n + 1):
        for c in range(3):
            node_pos[k, c] = y[3 * k + c]
    for i in range(n):
        tension[i] = w[_T, i]
    # force of the cable on the top attachment: the node's loads less its inertia (the node's
    # own mass only: a floating structure's mass and spring are not the cable's)
    a0 = _node_mass(p, w, 0)
    for c in range(3):
        inertia = a0[3 * c] * ydot[v0] + a0[3 * c + 1] * ydot[v0 + 1] + a0[3 * c + 2] * ydot[v0 + 2]
        scalars[c] = w[_F + c, 0] - inertia
    an = _node_mass(p, w, n)
    body = _body_load(t, y, p) if _free_axes(p) else np.zeros(3)  # what rhs added
    for c in range(3):
        if is_held(p) and p.constrained[c] != 0.0:
            # on a held axis, the cable's share of what holds the end: the end node's loads
            # less its inertia, the body's excluded
            inertia = 0.0
            for k in range(3):
                inertia += an[3 * c + k] * ydot[v0 + 3 * n + k]
            body_mass = p.body_mass[c] - (1.0 - w[_SF, n]) * p.node_added[n, c]
            inertia -= body_mass * ydot[v0 + 3 * n + c]
            scalars[3 + c] = w[_F + c, n] - body[c] - inertia
        else:
            # the pull of the last segment on the body
            scalars[3 + c] = -w[_T, n - 1] * w[_TX + c, n - 1]
    kinetic, gravity, elastic = _energies(y, p, w)
    scalars[6] = kinetic
    scalars[7] = gravity
    scalars[8] = elastic
    for k in range(9, N_SCALARS):  # trajectory and servo variables: recorded only with one
        scalars[k] = np.nan
    if p.bottom_kind == BOTTOM_SERVO or p.bottom_kind == BOTTOM_TRAJECTORY:
        target, _, _ = target_state(t, y, p)
        error = 0.0
        for c in range(3):
            error += (target[c] - y[3 * n + c]) ** 2
            scalars[10 + c] = target[c]
            if p.bottom_kind == BOTTOM_SERVO:
                scalars[13 + c] = y[2 * v0 + c]
        scalars[9] = math.sqrt(error)
    return status


@njit(**JIT)
def outputs_chunk(times, states, p, w, node_pos, tension, scalars):
    status = OK
    for j in range(times.shape[0]):
        st = outputs(times[j], states[j], p, w, node_pos[j], tension[j], scalars[j])
        if st != OK and status == OK:
            status = st
    return status
