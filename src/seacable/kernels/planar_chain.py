"""Planar chain of rigid links: the per-link loads, articulated sweep and energies of the
system's planar rigid lines (``lines.rigid_links``, ``system.rigid``; numba kernels).

Frame: x horizontal, z up. Link ``i`` (0-based) joins node ``i`` (top) to node ``i + 1`` and has the
absolute angle ``theta_i`` measured from the downward vertical, positive towards +x::

    e_i = (sin theta_i, -cos theta_i)     unit vector along the link, top -> bottom
    n_i = (cos theta_i,  sin theta_i)     d e_i / d theta_i

Method (derived from Newton-Euler with the node forces as internal forces, see
``docs/architecture.md``): let ``lam_k`` be the force that the part above node ``k`` exerts on the
part below it. A backward sweep finds, for every node, the articulated relation
``lam_k = M_k A_k + b_k`` between that force and the node acceleration ``A_k`` (``M_k`` a symmetric
2x2 matrix); a forward sweep from the known (or solved) top acceleration then gives every angular
acceleration. A bottom end pinned to the seabed closes the loop: the unknown reaction ``L`` enters
``b`` linearly, its 2x2 sensitivity is carried through both sweeps and ``L`` is fixed by requiring
the end node acceleration to be the Baumgarte-stabilised value. Every sweep is O(n).
"""

import math

from numba import njit

from seacable.kernels.chain3d_layout import profile
from seacable.kernels.jit import JIT, inner
from seacable.kernels.surface import (
    segment_potential,
    segment_submersion,
)

# ---- workspace rows (each of length n + 1) ------------------------------------------------------
_PX, _PZ, _VX, _VZ, _EX, _EZ, _FX, _FZ, _Q = 0, 1, 2, 3, 4, 5, 6, 7, 8
_D, _HX, _HZ, _U, _RSX, _RSZ = 9, 10, 11, 12, 13, 14  # _D holds 1 / D
_M11, _M12, _M22, _BX, _BZ = 15, 16, 17, 18, 19
_S11, _S12, _S21, _S22 = 20, 21, 22, 23
_THC, _THLX, _THLZ, _AX, _AZ, _THDD = 24, 25, 26, 27, 28, 29
N_WORK_ROWS = 30


@inner
def _current(current_z, current_u, z):
    """Current velocity along x at elevation z [m/s].

    Takes the two arrays, not the parameter tuple: passing the whole tuple to a function called
    once per link costs more than the rest of the link's work.
    """
    if current_z.shape[0] == 1:
        return current_u[0]
    return profile(z, current_z, current_u)


@inner
def link_loads(n, y, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
               joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u,
               w):  # fmt: skip
    """Every node's position and velocity from node 0's (rows _PX, _PZ, _VX, _VZ of column 0,
    set by the caller) and the angles ``y[q0 + i]`` and rates ``y[v0 + i]``; every link's
    loads (_FX, _FZ) and torque (_Q): apparent weight, drag on the relative velocity, the free
    surface's share, joint springs and dampers (joint 0 against ``ref_angle`` turning at
    ``ref_rate``). One line's arrays."""
    uniform = current_z.shape[0] == 1  # the current's value, read once: a call per link with
    u_uniform = current_u[0]  # the arrays would take and drop two references each time
    for i in range(n):
        th = y[q0 + i]
        om = y[v0 + i]
        s = math.sin(th)
        c = math.cos(th)
        li = length[i]
        w[_EX, i] = s
        w[_EZ, i] = -c
        w[_PX, i + 1] = w[_PX, i] + li * s
        w[_PZ, i + 1] = w[_PZ, i] - li * c
        w[_VX, i + 1] = w[_VX, i] + li * om * c
        w[_VZ, i + 1] = w[_VZ, i] + li * om * s
        # loads at the link centre: apparent weight and quadratic drag on the relative velocity
        zc = 0.5 * (w[_PZ, i] + w[_PZ, i + 1])
        current = u_uniform if uniform else _current(current_z, current_u, zc)
        vrx = 0.5 * (w[_VX, i] + w[_VX, i + 1]) - current
        vrz = 0.5 * (w[_VZ, i] + w[_VZ, i + 1])
        vn = vrx * c + vrz * s
        vt = vrx * s - vrz * c
        fn = -drag_normal[i] * abs(vn) * vn
        ft = -drag_tangential[i] * abs(vt) * vt
        w[_FX, i] = fn * c + ft * s
        w[_FZ, i] = fn * s - ft * c - wet_weight[i]
        w[_Q, i] = 0.0
        wet, share_top, _ = segment_submersion(w[_PZ, i], w[_PZ, i + 1])
        if wet < 1.0:
            # (a branch that rewrites the loads: wholly submerged links compute bitwise as they
            # always did) the drag of the submerged part and its buoyancy, at its centroid a
            # distance d = (1/2 - share_top) l along e from the centre: a moment d n . F
            fn *= wet
            ft *= wet
            lift = wet * buoyancy[i]
            w[_FX, i] = fn * c + ft * s
            w[_FZ, i] = fn * s - ft * c - wet_weight[i] + (lift - buoyancy[i])
            w[_Q, i] = (0.5 - share_top) * li * s * lift
    # joint springs and dampers: joint i acts between link i-1 (or the top reference) and link i
    for i in range(n):
        if i == 0:
            rel = y[q0] - ref_angle
            rate = y[v0] - ref_rate
        else:
            rel = y[q0 + i] - y[q0 + i - 1]
            rate = y[v0 + i] - y[v0 + i - 1]
        torque = joint_stiffness[i] * rel + joint_damping[i] * rate
        w[_Q, i] -= torque
        if i > 0:
            w[_Q, i - 1] += torque


@njit(inline="always", **JIT)
def link_back(i, li, mi, inertia, om, w, st, pinned):
    """One link of the backward sweep: the articulated inertia, bias and (``pinned``) reaction
    map ``st`` = (m11, m12, m22, bx, bz, s11, s12, s21, s22) at the link's lower node turned into
    those at its upper node, in place, and stored in column i with the link's rows _D, _HX,
    _HZ, _U (_RSX, _RSZ) for the forward sweep. Reads _EX, _EZ, _FX, _FZ, _Q of column i; the
    link's length, mass, inertia about its centre and angular rate."""
    m11, m12, m22, bx, bz = st[0], st[1], st[2], st[3], st[4]
    s11, s12, s21, s22 = st[5], st[6], st[7], st[8]
    ex = w[_EX, i]
    ez = w[_EZ, i]
    nx = -ez
    nz = ex
    mnx = m11 * nx + m12 * nz
    mnz = m12 * nx + m22 * nz
    mex = m11 * ex + m12 * ez
    mez = m12 * ex + m22 * ez
    n_m_n = nx * mnx + nz * mnz
    n_m_e = nx * mex + nz * mez
    inv_d = 1.0 / (inertia + 0.25 * mi * li * li + li * li * n_m_n)
    hx = li * (0.5 * mi * nx + mnx)
    hz = li * (0.5 * mi * nz + mnz)
    n_f = nx * w[_FX, i] + nz * w[_FZ, i]
    u = w[_Q, i] - 0.5 * li * (-2.0 * li * om * om * n_m_e + 2.0 * (nx * bx + nz * bz) - n_f)
    w[_D, i] = inv_d  # stored as the reciprocal of D
    w[_HX, i] = hx
    w[_HZ, i] = hz
    w[_U, i] = u
    w2 = li * om * om
    hx_d = hx * inv_d
    hz_d = hz * inv_d
    new_bx = bx - w[_FX, i] + hx_d * u - w2 * (0.5 * mi * ex + mex)
    new_bz = bz - w[_FZ, i] + hz_d * u - w2 * (0.5 * mi * ez + mez)
    m11 = mi + m11 - hx * hx_d
    m12 = m12 - hx * hz_d
    m22 = mi + m22 - hz * hz_d
    bx = new_bx
    bz = new_bz
    if pinned:
        # d u / d L = -l n^T S  (row vector)
        rsx = -li * (nx * s11 + nz * s21)
        rsz = -li * (nx * s12 + nz * s22)
        w[_RSX, i] = rsx
        w[_RSZ, i] = rsz
        s11 += hx_d * rsx
        s12 += hx_d * rsz
        s21 += hz_d * rsx
        s22 += hz_d * rsz
    w[_M11, i], w[_M12, i], w[_M22, i], w[_BX, i], w[_BZ, i] = m11, m12, m22, bx, bz
    w[_S11, i], w[_S12, i], w[_S21, i], w[_S22, i] = s11, s12, s21, s22
    st[0], st[1], st[2], st[3], st[4] = m11, m12, m22, bx, bz
    st[5], st[6], st[7], st[8] = s11, s12, s21, s22


@inner
def _node_force(w, k, lx, lz, pinned):
    """Force lam_k that the part above node k exerts on the part below it [N]."""
    fx = w[_M11, k] * w[_AX, k] + w[_M12, k] * w[_AZ, k] + w[_BX, k]
    fz = w[_M12, k] * w[_AX, k] + w[_M22, k] * w[_AZ, k] + w[_BZ, k]
    if pinned:
        fx += w[_S11, k] * lx + w[_S12, k] * lz
        fz += w[_S21, k] * lx + w[_S22, k] * lz
    return fx, fz


@inner
def link_energies(n, y, q0, v0, length, mass, inertia, wet_weight, buoyancy, joint_stiffness,
                  ref_angle, w):  # fmt: skip
    """Kinetic, gravity and buoyancy potential and joint-spring energy of one line's links
    (its workspace filled); joint 0 is unloaded at ``ref_angle``."""
    kinetic = 0.0
    gravity = 0.0
    elastic = 0.0
    for i in range(n):
        vcx = 0.5 * (w[_VX, i] + w[_VX, i + 1])
        vcz = 0.5 * (w[_VZ, i] + w[_VZ, i + 1])
        om = y[v0 + i]
        kinetic += 0.5 * mass[i] * (vcx * vcx + vcz * vcz) + 0.5 * inertia[i] * om * om
        gravity += segment_potential(wet_weight[i], buoyancy[i], w[_PZ, i], w[_PZ, i + 1],
                                     0.5 * (w[_PZ, i] + w[_PZ, i + 1]))  # fmt: skip
        rel = y[q0 + i] - (ref_angle if i == 0 else y[q0 + i - 1])
        elastic += 0.5 * joint_stiffness[i] * rel * rel
    return kinetic, gravity, elastic
