"""Several 3D rigid-segment cables whose lower ends hold one shared point body (a "star"):
a buoy retained by four anchored cables, a clump weight on several legs.

Each cable is a ``chain3d`` chain whose lower end is closed on the body. For chain k the sweeps
give its end acceleration as an affine function of the force L_k it exerts on the body,
A_end = a_k + G_k L_k; requiring the end to follow the body (Baumgarte-stabilised)
makes L_k affine in the body's acceleration A_B, and the body's equation
m_B A_B = F_B + sum_k L_k closes the system with one 3x3 solve. O(total segments).

State: the chains' states one after another (each ``chain3d.state_size(n_k)`` long), then the
body's position (3) and velocity (3).
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels import chain3d_outputs as c3o
from seacable.kernels.status import NON_FINITE, OK, SINGULAR_CLOSURE
from seacable.kernels.surface import submersion
from seacable.kernels.timefn import JIT

N_BODY_STATES = 6


class StarParams(NamedTuple):
    chains: tuple  # Chain3DParams, one per cable (lower ends closed on the body)
    offsets: np.ndarray  # (k + 1,) start of each chain's state; offsets[k] = the body's
    body_mass: np.ndarray  # (3,) mass + added mass per axis [kg]
    body_wet_weight: float  # [N], positive down
    body_drag: np.ndarray  # (3,) 0.5 rho Cd A per axis [N s^2/m^2]
    # the free surface (kernels.surface): the three above are wholly submerged values
    body_shape: np.ndarray  # (L,) shape row
    body_added: np.ndarray  # (3,) added mass when wholly submerged [kg]
    body_buoyancy: float  # rho g V [N]
    current_z: np.ndarray
    current_u: np.ndarray
    current_v: np.ndarray
    stabilization_frequency: float


def state_size(counts) -> int:
    return sum(c3.state_size(n) for n in counts) + N_BODY_STATES


@njit(**JIT)
def _inverse3(a):
    """Inverse of a row-major 3x3 matrix (9 values); (inverse, determinant)."""
    inv = np.zeros(9)
    det = (
        a[0] * (a[4] * a[8] - a[5] * a[7])
        - a[1] * (a[3] * a[8] - a[5] * a[6])
        + a[2] * (a[3] * a[7] - a[4] * a[6])
    )
    if det == 0.0:
        return inv, det
    d = 1.0 / det
    inv[0] = (a[4] * a[8] - a[5] * a[7]) * d
    inv[1] = (a[2] * a[7] - a[1] * a[8]) * d
    inv[2] = (a[1] * a[5] - a[2] * a[4]) * d
    inv[3] = (a[5] * a[6] - a[3] * a[8]) * d
    inv[4] = (a[0] * a[8] - a[2] * a[6]) * d
    inv[5] = (a[2] * a[3] - a[0] * a[5]) * d
    inv[6] = (a[3] * a[7] - a[4] * a[6]) * d
    inv[7] = (a[1] * a[6] - a[0] * a[7]) * d
    inv[8] = (a[0] * a[4] - a[1] * a[3]) * d
    return inv, det


@njit(**JIT)
def _body_force(p, pos, vel, fraction):
    """Drag and apparent weight of the body with ``fraction`` of it submerged."""
    cu, cv = c3._current(p.current_z, p.current_u, p.current_v, pos[2])
    r = np.array([vel[0] - cu, vel[1] - cv, vel[2]])
    speed = math.sqrt(r[0] ** 2 + r[1] ** 2 + r[2] ** 2)
    force = -(fraction * p.body_drag) * speed * r
    force[2] -= p.body_wet_weight + (1.0 - fraction) * p.body_buoyancy
    return force


@njit(**JIT)
def solve(t, y, p, workspaces, reactions):
    """Accelerations of every chain and of the body; fills ``reactions`` (k, 3) with the force
    of each cable on the body. Returns (status, body acceleration (3,))."""
    k_count = len(p.chains)
    b0 = p.offsets[k_count]
    pos = y[b0 : b0 + 3]
    vel = y[b0 + 3 : b0 + 6]
    omega = p.stabilization_frequency
    system = np.zeros(9)
    fraction, _, _ = submersion(pos[2], p.body_shape)
    for r in range(3):
        system[4 * r] = p.body_mass[r] - (1.0 - fraction) * p.body_added[r]
    rhs_ = _body_force(p, pos, vel, fraction)
    inverses = np.zeros((k_count, 9))
    offsets_ = np.zeros((k_count, 3))
    tops = np.zeros((k_count, 3))
    top_gains = np.zeros((k_count, 9))
    for k in range(k_count):
        pk = p.chains[k]
        yk = y[p.offsets[k] : p.offsets[k + 1]]
        w = workspaces[k]
        n = pk.n
        c3._kinematics_and_loads(t, yk, pk, w)
        c3._backward_sweep(t, yk, pk, w)
        ac = np.zeros(3)
        al = np.zeros(9)
        c3._top_acceleration(t, yk, pk, w, ac, al)
        tops[k] = ac
        top_gains[k] = al
        c3._forward_sweep(yk, pk, w, ac, al, True)
        inv, det = _inverse3(al)
        if det == 0.0:
            return SINGULAR_CLOSURE, np.zeros(3)
        inverses[k] = inv
        # the chain end must follow the body: A_end = A_B + stab
        for r in range(3):
            stab = -2.0 * omega * (w[c3._V + r, n] - vel[r])
            stab -= omega * omega * (w[c3._P + r, n] - pos[r])
            offsets_[k, r] = stab - ac[r]
        # L_k = G_k^-1 (A_B + offset_k): the body gets L_k
        for r in range(3):
            for c in range(3):
                system[3 * r + c] -= inv[3 * r + c]
                rhs_[r] += inv[3 * r + c] * offsets_[k, c]
    body_acc, det = c3._solve3(system, rhs_)
    if det == 0.0:
        return SINGULAR_CLOSURE, body_acc
    for k in range(k_count):
        pk = p.chains[k]
        yk = y[p.offsets[k] : p.offsets[k + 1]]
        inv = inverses[k]
        for r in range(3):
            value = 0.0
            for c in range(3):
                value += inv[3 * r + c] * (body_acc[c] + offsets_[k, c])
            reactions[k, r] = value
        c3._final_accelerations(yk, pk, workspaces[k], tops[k], top_gains[k], reactions[k], True)
    status = OK
    if not (math.isfinite(body_acc[0]) and math.isfinite(body_acc[1])
            and math.isfinite(body_acc[2])):  # fmt: skip
        status = NON_FINITE
    return status, body_acc


@njit(**JIT)
def rhs(t, y, p, workspaces, ydot):
    k_count = len(p.chains)
    reactions = np.zeros((k_count, 3))
    status, body_acc = solve(t, y, p, workspaces, reactions)
    for k in range(k_count):
        pk = p.chains[k]
        n = pk.n
        o = p.offsets[k]
        u0 = 3 * n + 1
        w = workspaces[k]
        for i in range(n):
            for c in range(3):
                ydot[o + 3 * i + c] = y[o + u0 + 3 * i + c]
                ydot[o + u0 + 3 * i + c] = w[c3._EDD + c, i]
        top_acc = w[c3._A + 2, 0] if pk.top_kind == c3.TOP_HEAVE else 0.0
        ydot[o + 3 * n] = y[o + 6 * n + 1] if pk.top_kind == c3.TOP_HEAVE else 0.0
        ydot[o + 6 * n + 1] = top_acc
        for c in range(3):
            ydot[o + 6 * n + 2 + c] = 0.0
    b0 = p.offsets[k_count]
    for c in range(3):
        ydot[b0 + c] = y[b0 + 3 + c]
        ydot[b0 + 3 + c] = body_acc[c]
    return status


@njit(**JIT)
def project(y, p):
    for k in range(len(p.chains)):
        c3.project(y[p.offsets[k] : p.offsets[k + 1]], p.chains[k])


@njit(**JIT)
def outputs_chunk(times, states, p, workspaces, node_pos, tension, scalars, anchor_force):
    """Per time: node positions (k, n+1, 3), tension (k, n), chain scalars (k, S) and the force
    of each cable on its top attachment (k, 3)."""
    status = OK
    k_count = len(p.chains)
    reactions = np.zeros((k_count, 3))
    for j in range(times.shape[0]):
        st, _ = solve(times[j], states[j], p, workspaces, reactions)
        if st != OK and status == OK:
            status = st
        for k in range(k_count):
            pk = p.chains[k]
            yk = states[j, p.offsets[k] : p.offsets[k + 1]]
            c3o.outputs_from_solution(times[j], yk, pk, workspaces[k], reactions[k],
                                     node_pos[j, k], tension[j, k], scalars[j, k])  # fmt: skip
            for c in range(3):
                anchor_force[j, k, c] = scalars[j, k, c]
    return status
