"""Planar chain of rigid links: O(n) forward dynamics, loads and outputs (numba kernels).

Frame: x horizontal, z up. Link ``i`` (0-based) joins node ``i`` (top) to node ``i + 1`` and has the
absolute angle ``theta_i`` measured from the downward vertical, positive towards +x::

    e_i = (sin theta_i, -cos theta_i)     unit vector along the link, top -> bottom
    n_i = (cos theta_i,  sin theta_i)     d e_i / d theta_i

State layout (flat float64, length ``2 (n + 1)``)::

    y = [theta_0 .. theta_{n-1}, z_top, omega_0 .. omega_{n-1}, zdot_top]

``z_top`` is the heave of a floating structure at the top; it is unused (kept at zero) when the
top is fixed or moved by imposed time functions.

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
from typing import NamedTuple

import numpy as np
from numba import njit

from seacable.kernels.status import NON_FINITE, OK, SINGULAR_CLOSURE
from seacable.kernels.surface import (
    point_potential,
    segment_potential,
    segment_submersion,
    submersion,
)
from seacable.kernels.timefn import JIT
from seacable.kernels.timefn import of_params as tf_of_params

# ---- named integer codes shared with the model layer --------------------------------------------
TOP_IMPOSED = 0  # top node moved by time functions (a fixed point is a constant function)
TOP_HEAVE = 1  # floating structure free in heave (mass-spring-damper), fixed in x

BOTTOM_FREE = 0  # free end carrying a point body (mass may be zero), optional elastic ties
BOTTOM_PINNED = 1  # end pinned to a fixed anchor (exact constraint)

CH_TOP_X = 0  # imposed top x(t) [m]
CH_TOP_Z = 1  # imposed top z(t) [m]
CH_TOP_FORCE = 2  # vertical force u(t) on the floating structure [N]
CH_BODY_FX = 3  # applied force on the bottom body, x [N]
CH_BODY_FZ = 4  # applied force on the bottom body, z [N]
N_CHANNELS = 5


# ---- scalar outputs (columns of the ``scalars`` output array) -----------------------------------
SCALAR_NAMES = (
    "top_force_x",
    "top_force_z",
    "bottom_force_x",
    "bottom_force_z",
    "top_heave",
    "top_heave_velocity",
    "kinetic_energy",
    "gravity_potential_energy",
    "elastic_energy",
    "constraint_error",
    "bottom_velocity_x",
    "bottom_velocity_z",
)
N_SCALARS = len(SCALAR_NAMES)

# ---- workspace rows (each of length n + 1) ------------------------------------------------------
_PX, _PZ, _VX, _VZ, _EX, _EZ, _FX, _FZ, _Q = 0, 1, 2, 3, 4, 5, 6, 7, 8
_D, _HX, _HZ, _U, _RSX, _RSZ = 9, 10, 11, 12, 13, 14  # _D holds 1 / D
_M11, _M12, _M22, _BX, _BZ = 15, 16, 17, 18, 19
_S11, _S12, _S21, _S22 = 20, 21, 22, 23
_THC, _THLX, _THLZ, _AX, _AZ, _THDD = 24, 25, 26, 27, 28, 29
N_WORK_ROWS = 30


class ChainParams(NamedTuple):
    """Flat parameters of one planar rigid-link cable and its end conditions (SI units)."""

    n: int
    length: np.ndarray  # (n,) link length [m]
    mass: np.ndarray  # (n,) link mass [kg]
    inertia: np.ndarray  # (n,) link moment of inertia about its centre [kg m^2]
    wet_weight: np.ndarray  # (n,) apparent weight, positive down [N]
    buoyancy: np.ndarray  # (n,) rho g A l of the link wholly submerged [N]
    drag_normal: np.ndarray  # (n,) 0.5 rho Cd_n d l  [N s^2/m^2]
    drag_tangential: np.ndarray  # (n,) 0.5 rho Cd_t pi d l  [N s^2/m^2]
    joint_stiffness: np.ndarray  # (n,) joint i between link i-1 (top: reference) and i [N m/rad]
    joint_damping: np.ndarray  # (n,) [N m s/rad]
    top_reference_angle: float  # angle the top joint spring holds the first link at [rad]
    current_z: np.ndarray  # (K,) ascending elevations of the current profile [m]
    current_u: np.ndarray  # (K,) current velocity along x at those elevations [m/s]
    top_kind: int
    top_x: float  # x of a heaving floating structure [m]
    top_mass: float  # structure mass + heave added mass [kg]
    top_stiffness: float  # heave restoring stiffness [N/m]
    top_damping: float  # heave damping [N s/m]
    top_rest_z: float  # elevation where the heave spring is unloaded [m]
    top_net_weight: float  # structure weight minus buoyancy at rest, positive down [N]
    bottom_kind: int
    body_mass: float  # bottom body mass + added mass [kg]
    body_wet_weight: float  # bottom body apparent weight, positive down [N]
    body_drag: float  # 0.5 rho Cd A of the bottom body [N s^2/m^2]
    # the free surface (kernels.surface): the three above are wholly submerged values
    body_shape: np.ndarray  # (L,) shape row
    body_added: float  # added mass when wholly submerged [kg]
    body_buoyancy: float  # rho g V [N]
    tie_kx: float  # elastic tie of the bottom body, x [N/m]
    tie_cx: float  # [N s/m]
    tie_kz: float  # z [N/m]
    tie_cz: float  # [N s/m]
    tie_x0: float  # unloaded tie position [m]
    tie_z0: float
    pin_x: float  # anchor of a pinned bottom [m]
    pin_z: float
    stabilization_frequency: float  # Baumgarte frequency of the pinned-end closure [rad/s]
    tf_breaks: np.ndarray
    tf_coefs: np.ndarray
    tf_count: np.ndarray
    tf_sine: np.ndarray
    tf_build_up: np.ndarray


def state_size(n):
    """Length of the flat state vector of an n-link chain."""
    return 2 * (n + 1)


def make_workspace(n):
    """Scratch array the kernels fill (allocated once per run, never inside a step)."""
    return np.zeros((N_WORK_ROWS, n + 1))


@njit(**JIT)
def _current(current_z, current_u, z):
    """Current velocity along x at elevation z [m/s].

    Takes the two arrays, not the parameter tuple: passing the whole tuple to a function called
    once per link costs more than the rest of the link's work.
    """
    if current_z.shape[0] == 1:
        return current_u[0]
    return np.interp(z, current_z, current_u)


@njit(**JIT)
def _top_motion(t, y, p):
    """Top node position, velocity and (for imposed motion) acceleration."""
    n = p.n
    if p.top_kind == TOP_HEAVE:
        return p.top_x, y[n], 0.0, y[2 * n + 1], 0.0, 0.0
    x, vx, ax = tf_of_params(p, CH_TOP_X, t)
    z, vz, az = tf_of_params(p, CH_TOP_Z, t)
    return x, z, vx, vz, ax, az


@njit(**JIT)
def _kinematics_and_loads(t, y, p, w):
    """Node positions/velocities, link unit vectors, link forces and torques."""
    n = p.n
    x0, z0, vx0, vz0, _, _ = _top_motion(t, y, p)
    w[_PX, 0] = x0
    w[_PZ, 0] = z0
    w[_VX, 0] = vx0
    w[_VZ, 0] = vz0
    link_loads(
        n, y, 0, n + 1, p.length, p.wet_weight, p.buoyancy, p.drag_normal, p.drag_tangential,
        p.joint_stiffness, p.joint_damping, p.top_reference_angle, 0.0, p.current_z,
        p.current_u, w,
    )  # fmt: skip


@njit(**JIT)
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
def _body_now(p, z):
    """The bottom body at elevation z [m]: mass + submerged added mass [kg], apparent weight
    [N], drag factor [N s^2/m^2] and hydrostatic heave stiffness rho g A_wp [N/m]."""
    fraction, slope, _ = submersion(z, p.body_shape)
    lost = 1.0 - fraction
    return (
        p.body_mass - lost * p.body_added,
        p.body_wet_weight + lost * p.body_buoyancy,
        fraction * p.body_drag,
        -slope * p.body_buoyancy,
    )


@njit(**JIT)
def _bottom_body_force(t, p, w):
    """Force on the bottom point body (excluding the cable): weight, drag, applied, ties."""
    n = p.n
    xn = w[_PX, n]
    zn = w[_PZ, n]
    vx = w[_VX, n]
    vz = w[_VZ, n]
    fx, _, _ = tf_of_params(p, CH_BODY_FX, t)
    fz, _, _ = tf_of_params(p, CH_BODY_FZ, t)
    _, wet_weight, drag, _ = _body_now(p, zn)
    fz -= wet_weight
    if drag != 0.0:
        vrx = vx - _current(p.current_z, p.current_u, zn)
        speed = math.sqrt(vrx * vrx + vz * vz)
        fx -= drag * speed * vrx
        fz -= drag * speed * vz
    fx -= p.tie_kx * (xn - p.tie_x0) + p.tie_cx * vx
    fz -= p.tie_kz * (zn - p.tie_z0) + p.tie_cz * vz
    return fx, fz


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


@njit(**JIT)
def _backward_sweep(t, y, p, w):
    """Articulated 2x2 inertias M_k, biases b_k and (pinned) reaction sensitivities S_k."""
    n = p.n
    pinned = p.bottom_kind == BOTTOM_PINNED
    if pinned:
        m11, m12, m22, bx, bz = 0.0, 0.0, 0.0, 0.0, 0.0
        s11, s12, s21, s22 = 1.0, 0.0, 0.0, 1.0
    else:
        fbx, fbz = _bottom_body_force(t, p, w)
        mass, _, _, _ = _body_now(p, w[_PZ, n])
        m11, m12, m22 = mass, 0.0, mass
        bx, bz = -fbx, -fbz
        s11, s12, s21, s22 = 0.0, 0.0, 0.0, 0.0
    w[_M11, n], w[_M12, n], w[_M22, n], w[_BX, n], w[_BZ, n] = m11, m12, m22, bx, bz
    w[_S11, n], w[_S12, n], w[_S21, n], w[_S22, n] = s11, s12, s21, s22
    st = np.empty(9)
    st[0], st[1], st[2], st[3], st[4] = m11, m12, m22, bx, bz
    st[5], st[6], st[7], st[8] = s11, s12, s21, s22
    for i in range(n - 1, -1, -1):
        link_back(i, p.length[i], p.mass[i], p.inertia[i], y[n + 1 + i], w, st, pinned)


@njit(**JIT)
def _top_acceleration(t, y, p, w):
    """Top node acceleration as an affine function of the pinned reaction L.

    Returns (ax, az, daz_dLx, daz_dLz, zdd_top_const): the top x acceleration never depends on L.
    """
    n = p.n
    if p.top_kind == TOP_HEAVE:
        zs = y[n]
        zsd = y[2 * n + 1]
        u, _, _ = tf_of_params(p, CH_TOP_FORCE, t)
        f_structure = -p.top_stiffness * (zs - p.top_rest_z) - p.top_damping * zsd
        f_structure += u - p.top_net_weight
        den = p.top_mass + w[_M22, 0]
        az = (f_structure - w[_BZ, 0]) / den
        return 0.0, az, -w[_S21, 0] / den, -w[_S22, 0] / den
    _, _, _, _, ax, az = _top_motion(t, y, p)
    return ax, az, 0.0, 0.0


@njit(**JIT)
def solve(t, y, p, w):
    """Fill ``w`` with the kinematics, loads and accelerations at (t, y).

    Returns (status, top_heave_acceleration, reaction_x, reaction_z); the angular accelerations
    are in ``w[_THDD, :n]`` and node accelerations in ``w[_AX]``, ``w[_AZ]``.
    """
    n = p.n
    pinned = p.bottom_kind == BOTTOM_PINNED
    _kinematics_and_loads(t, y, p, w)
    _backward_sweep(t, y, p, w)
    ax, az, azlx, azlz = _top_acceleration(t, y, p, w)
    # forward sweep, affine in L: A = Ac + AL L
    acx, acz = ax, az
    alxx, alxz, alzx, alzz = 0.0, 0.0, azlx, azlz
    for i in range(n):
        li = p.length[i]
        om = y[n + 1 + i]
        ex = w[_EX, i]
        ez = w[_EZ, i]
        nx = -ez
        nz = ex
        inv_d = w[_D, i]
        hx = w[_HX, i]
        hz = w[_HZ, i]
        thc = (w[_U, i] - hx * acx - hz * acz) * inv_d
        w[_THC, i] = thc
        acx += li * (thc * nx - om * om * ex)
        acz += li * (thc * nz - om * om * ez)
        if pinned:
            thlx = (w[_RSX, i] - hx * alxx - hz * alzx) * inv_d
            thlz = (w[_RSZ, i] - hx * alxz - hz * alzz) * inv_d
            w[_THLX, i] = thlx
            w[_THLZ, i] = thlz
            alxx += li * nx * thlx
            alxz += li * nx * thlz
            alzx += li * nz * thlx
            alzz += li * nz * thlz
    lx = 0.0
    lz = 0.0
    if pinned:
        omega = p.stabilization_frequency
        ex_ = w[_PX, n] - p.pin_x
        ez_ = w[_PZ, n] - p.pin_z
        dax = -2.0 * omega * w[_VX, n] - omega * omega * ex_ - acx
        daz = -2.0 * omega * w[_VZ, n] - omega * omega * ez_ - acz
        det = alxx * alzz - alxz * alzx
        scale = abs(alxx) + abs(alxz) + abs(alzx) + abs(alzz)
        if not (abs(det) > 1e-12 * scale * scale):
            return SINGULAR_CLOSURE, 0.0, 0.0, 0.0
        lx = (alzz * dax - alxz * daz) / det
        lz = (-alzx * dax + alxx * daz) / det
    # final accelerations
    topz = az + azlx * lx + azlz * lz
    w[_AX, 0] = ax
    w[_AZ, 0] = topz
    for i in range(n):
        li = p.length[i]
        om = y[n + 1 + i]
        thdd = w[_THC, i]
        if pinned:
            thdd += w[_THLX, i] * lx + w[_THLZ, i] * lz
        w[_THDD, i] = thdd
        nx = -w[_EZ, i]
        nz = w[_EX, i]
        w[_AX, i + 1] = w[_AX, i] + li * (thdd * nx - om * om * w[_EX, i])
        w[_AZ, i + 1] = w[_AZ, i] + li * (thdd * nz - om * om * w[_EZ, i])
    status = OK
    if not math.isfinite(topz + w[_AX, n] + w[_AZ, n]):
        status = NON_FINITE
    top_acc = topz if p.top_kind == TOP_HEAVE else 0.0
    return status, top_acc, lx, lz


@njit(**JIT)
def rhs(t, y, p, w, ydot):
    """Time derivative of the state; returns a status code (0 when the evaluation is sound)."""
    n = p.n
    status, top_acc, _, _ = solve(t, y, p, w)
    for i in range(n):
        ydot[i] = y[n + 1 + i]
        ydot[n + 1 + i] = w[_THDD, i]
    if p.top_kind == TOP_HEAVE:
        ydot[n] = y[2 * n + 1]
    else:
        ydot[n] = 0.0
    ydot[2 * n + 1] = top_acc
    return status


@njit(**JIT)
def _node_force(w, k, lx, lz, pinned):
    """Force lam_k that the part above node k exerts on the part below it [N]."""
    fx = w[_M11, k] * w[_AX, k] + w[_M12, k] * w[_AZ, k] + w[_BX, k]
    fz = w[_M12, k] * w[_AX, k] + w[_M22, k] * w[_AZ, k] + w[_BZ, k]
    if pinned:
        fx += w[_S11, k] * lx + w[_S12, k] * lz
        fz += w[_S21, k] * lx + w[_S22, k] * lz
    return fx, fz


@njit(**JIT)
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


@njit(**JIT)
def _energies(y, p, w):
    n = p.n
    kinetic, gravity, elastic = link_energies(
        n, y, 0, n + 1, p.length, p.mass, p.inertia, p.wet_weight, p.buoyancy,
        p.joint_stiffness, p.top_reference_angle, w,
    )  # fmt: skip
    if p.bottom_kind == BOTTOM_FREE:
        mass, _, _, _ = _body_now(p, w[_PZ, n])
        kinetic += 0.5 * mass * (w[_VX, n] ** 2 + w[_VZ, n] ** 2)
        gravity += point_potential(w[_PZ, n], p.body_wet_weight, p.body_buoyancy, p.body_shape)
        dx = w[_PX, n] - p.tie_x0
        dz = w[_PZ, n] - p.tie_z0
        elastic += 0.5 * (p.tie_kx * dx * dx + p.tie_kz * dz * dz)
    if p.top_kind == TOP_HEAVE:
        kinetic += 0.5 * p.top_mass * y[2 * n + 1] ** 2
        gravity += p.top_net_weight * y[n]
        dz = y[n] - p.top_rest_z
        elastic += 0.5 * p.top_stiffness * dz * dz
    return kinetic, gravity, elastic


@njit(**JIT)
def outputs(t, y, p, w, node_x, node_z, tension, scalars):
    """Derived outputs at one instant, written into the given rows; returns a status code."""
    n = p.n
    pinned = p.bottom_kind == BOTTOM_PINNED
    status, _, lx, lz = solve(t, y, p, w)
    for k in range(n + 1):
        node_x[k] = w[_PX, k]
        node_z[k] = w[_PZ, k]
    fx_prev, fz_prev = _node_force(w, 0, lx, lz, pinned)
    top_fx, top_fz = -fx_prev, -fz_prev
    for i in range(n):
        fx_next, fz_next = _node_force(w, i + 1, lx, lz, pinned)
        ex = w[_EX, i]
        ez = w[_EZ, i]
        # tension at the link ends: the pull along the link, averaged to the link centre
        tension_top = -(ex * fx_prev + ez * fz_prev)
        tension_bottom = -(ex * fx_next + ez * fz_next)
        tension[i] = 0.5 * (tension_top + tension_bottom)
        fx_prev, fz_prev = fx_next, fz_next
    kinetic, gravity, elastic = _energies(y, p, w)
    scalars[0] = top_fx
    scalars[1] = top_fz
    scalars[2] = fx_prev
    scalars[3] = fz_prev
    scalars[4] = y[n] if p.top_kind == TOP_HEAVE else w[_PZ, 0]
    scalars[5] = y[2 * n + 1] if p.top_kind == TOP_HEAVE else w[_VZ, 0]
    scalars[6] = kinetic
    scalars[7] = gravity
    scalars[8] = elastic
    if pinned:
        scalars[9] = math.hypot(w[_PX, n] - p.pin_x, w[_PZ, n] - p.pin_z)
    else:
        scalars[9] = 0.0
    scalars[10] = w[_VX, n]
    scalars[11] = w[_VZ, n]
    return status


@njit(**JIT)
def outputs_chunk(times, states, p, w, node_x, node_z, tension, scalars):
    """``outputs`` for every row of a chunk; returns the first non-zero status (or 0)."""
    status = OK
    for j in range(times.shape[0]):
        st = outputs(times[j], states[j], p, w, node_x[j], node_z[j], tension[j], scalars[j])
        if st != OK and status == OK:
            status = st
    return status
