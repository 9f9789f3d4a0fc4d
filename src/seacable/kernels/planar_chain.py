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

from seacable.kernels.surface import point_potential, segment_submersion, submersion
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

# status codes returned by the kernels
OK = 0
NON_FINITE = 1
SINGULAR_CLOSURE = 2
NEWTON_FAILED = 4  # an implicit step's Newton iteration did not converge

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
    current_z = p.current_z
    current_u = p.current_u
    x0, z0, vx0, vz0, _, _ = _top_motion(t, y, p)
    w[_PX, 0] = x0
    w[_PZ, 0] = z0
    w[_VX, 0] = vx0
    w[_VZ, 0] = vz0
    for i in range(n):
        th = y[i]
        om = y[n + 1 + i]
        s = math.sin(th)
        c = math.cos(th)
        li = p.length[i]
        w[_EX, i] = s
        w[_EZ, i] = -c
        w[_PX, i + 1] = w[_PX, i] + li * s
        w[_PZ, i + 1] = w[_PZ, i] - li * c
        w[_VX, i + 1] = w[_VX, i] + li * om * c
        w[_VZ, i + 1] = w[_VZ, i] + li * om * s
        # loads at the link centre: apparent weight and quadratic drag on the relative velocity
        zc = 0.5 * (w[_PZ, i] + w[_PZ, i + 1])
        vrx = 0.5 * (w[_VX, i] + w[_VX, i + 1]) - _current(current_z, current_u, zc)
        vrz = 0.5 * (w[_VZ, i] + w[_VZ, i + 1])
        vn = vrx * c + vrz * s
        vt = vrx * s - vrz * c
        fn = -p.drag_normal[i] * abs(vn) * vn
        ft = -p.drag_tangential[i] * abs(vt) * vt
        w[_FX, i] = fn * c + ft * s
        w[_FZ, i] = fn * s - ft * c - p.wet_weight[i]
        w[_Q, i] = 0.0
        wet, share_top, _ = segment_submersion(w[_PZ, i], w[_PZ, i + 1])
        if wet < 1.0:
            # (a branch that rewrites the loads: wholly submerged links compute bitwise as they
            # always did) the drag of the submerged part and its buoyancy, at its centroid a
            # distance d = (1/2 - share_top) l along e from the centre: a moment d n . F
            fn *= wet
            ft *= wet
            lift = wet * p.buoyancy[i]
            w[_FX, i] = fn * c + ft * s
            w[_FZ, i] = fn * s - ft * c - p.wet_weight[i] + (lift - p.buoyancy[i])
            w[_Q, i] = (0.5 - share_top) * li * s * lift
    # joint springs and dampers: joint i acts between link i-1 (or the top reference) and link i
    for i in range(n):
        if i == 0:
            rel = y[0] - p.top_reference_angle
            rate = y[n + 1]
        else:
            rel = y[i] - y[i - 1]
            rate = y[n + 1 + i] - y[n + i]
        torque = p.joint_stiffness[i] * rel + p.joint_damping[i] * rate
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
    for i in range(n - 1, -1, -1):
        li = p.length[i]
        mi = p.mass[i]
        om = y[n + 1 + i]
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
        inv_d = 1.0 / (p.inertia[i] + 0.25 * mi * li * li + li * li * n_m_n)
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
def _energies(y, p, w):
    n = p.n
    kinetic = 0.0
    gravity = 0.0
    elastic = 0.0
    for i in range(n):
        vcx = 0.5 * (w[_VX, i] + w[_VX, i + 1])
        vcz = 0.5 * (w[_VZ, i] + w[_VZ, i + 1])
        om = y[n + 1 + i]
        kinetic += 0.5 * p.mass[i] * (vcx * vcx + vcz * vcz) + 0.5 * p.inertia[i] * om * om
        gravity += p.wet_weight[i] * 0.5 * (w[_PZ, i] + w[_PZ, i + 1])
        wet, _, mean_depth = segment_submersion(w[_PZ, i], w[_PZ, i + 1])
        if wet < 1.0:  # buoyancy's potential -rho g A l mean(min(z, 0)) (kernels.surface)
            gravity += p.buoyancy[i] * (0.5 * (w[_PZ, i] + w[_PZ, i + 1]) - mean_depth)
        rel = y[i] - (p.top_reference_angle if i == 0 else y[i - 1])
        elastic += 0.5 * p.joint_stiffness[i] * rel * rel
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


# ---- implicit steps: the Newton system in maximal coordinates -----------------------------------
# In link angles the Newton matrix of an implicit step is dense (the inverse mass matrix is), so it
# is written in maximal coordinates instead: node k carries a block of NEWTON_BLOCK unknowns
# [s_k, A_k (2), lam_k (2)], with s_k the angular acceleration of link k - 1 (the link above node
# k; the heave acceleration for k = 0), A_k the node acceleration and lam_k the node force. Each
# link contributes its kinematic relation, its translational and its rotational Newton-Euler
# equation; every equation involves neighbouring blocks only, so the matrix is block-tridiagonal
# and one step costs O(n) (``numerics.implicit.block_lu_factor``).
NEWTON_BLOCK = 5


@njit(inline="always", **JIT)
def put_entry(diag, upper, lower, bs, rb, rl, cb, cl, value):
    """Add ``value`` at row ``rl`` of block row ``rb``, column ``cl`` of block column ``cb`` of a
    block-tridiagonal matrix of bs x bs row-major blocks (``upper[k]`` at (k, k+1), ``lower[k]``
    at (k+1, k)); shared by the rigid-link models' Newton systems."""
    k = rl * bs + cl
    if cb == rb:
        diag[rb, k] += value
    elif cb == rb + 1:
        upper[rb, k] += value
    else:
        lower[cb, k] += value


@njit(**JIT)
def top_rows(diag, bs, s_size, dims, heave, cm, spring, mass):
    """Rows of the top in block 0 of a rigid-link Newton system, whose unknowns are
    [s (s_size), A_0 (dims), lam_0 (dims)]: an imposed top holds s and A_0 (identity rows); a
    heaving structure keeps the unused entries of s and the horizontal axes at zero, ties the
    vertical acceleration to its heave acceleration s[0] (A_0z = cm s_0) and adds its equation
    M A_0z + (k cx + c cv) s_0 + lam_0z = ... (``spring`` = k cx + c cv)."""
    if not heave:
        for r in range(s_size + dims):
            diag[0, r * bs + r] = 1.0
        return
    row = 0
    for r in range(1, s_size):  # unused entries of s
        diag[0, row * bs + r] = 1.0
        row += 1
    for a in range(dims - 1):  # horizontal axes held
        diag[0, row * bs + s_size + a] = 1.0
        row += 1
    z = s_size + dims - 1
    diag[0, row * bs + z] = 1.0  # A_0z = heave acceleration
    diag[0, row * bs + 0] = -cm
    row += 1
    diag[0, row * bs + 0] = spring
    diag[0, row * bs + z] = mass
    diag[0, row * bs + z + dims] = 1.0


@njit(**JIT)
def _drag_jacobian(dn, dt, vn, vt, nx, nz, ex, ez):
    """Derivatives of the link drag F = fn n + ft e: (dF/dv as xx, xz, zx, zz; dF/dtheta)."""
    fn = -dn * abs(vn) * vn
    ft = -dt * abs(vt) * vt
    dfn = -2.0 * dn * abs(vn)
    dft = -2.0 * dt * abs(vt)
    jxx = dfn * nx * nx + dft * ex * ex
    jxz = dfn * nx * nz + dft * ex * ez
    jzz = dfn * nz * nz + dft * ez * ez
    # d n / d theta = -e, d e / d theta = n, d vn / d theta = -vt, d vt / d theta = vn
    ftx = -dfn * vt * nx - fn * ex + dft * vn * ex + ft * nx
    ftz = -dfn * vt * nz - fn * ez + dft * vn * ez + ft * nz
    return jxx, jxz, jzz, ftx, ftz


@njit(**JIT)
def _body_jacobian(p, w):
    """-dF/dV and -dF/dP of the bottom body's force (xx, xz, zz each): drag, ties and the
    free surface's heave stiffness."""
    n = p.n
    cxx, cxz, czz = p.tie_cx, 0.0, p.tie_cz
    _, _, drag, heave = _body_now(p, w[_PZ, n])
    if drag != 0.0:
        vrx = w[_VX, n] - _current(p.current_z, p.current_u, w[_PZ, n])
        vrz = w[_VZ, n]
        speed = math.sqrt(vrx * vrx + vrz * vrz)
        if speed > 0.0:
            cxx += drag * (speed + vrx * vrx / speed)
            cxz += drag * vrx * vrz / speed
            czz += drag * (speed + vrz * vrz / speed)
    return cxx, cxz, czz, p.tie_kx, 0.0, p.tie_kz + heave


@njit(**JIT)
def _link_rows(p_arrays, n, y, w, i, lam, cm, cx, cv, diag, upper, lower):
    """Matrix rows of link i: kinematics and rotation (block i + 1), translation (block i)."""
    length, mass, inertia, joint_k, joint_c, drag_n, drag_t, current_z, current_u = p_arrays
    li = length[i]
    om = y[n + 1 + i]
    ex, ez = w[_EX, i], w[_EZ, i]
    nx, nz = -ez, ex
    a = w[_THDD, i]  # the Jacobian of the reduced residual linearises about the dynamics
    b = i + 1
    # kinematics A_{i+1} - A_i - l (s n - om^2 e) = 0; d/dtheta = l (s e + om^2 n),
    # d/domega = 2 l om e
    kx = cm * li * nx - cx * li * (a * ex + om * om * nx) - cv * 2.0 * li * om * ex
    kz = cm * li * nz - cx * li * (a * ez + om * om * nz) - cv * 2.0 * li * om * ez
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 0, b, 1, 1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 1, b, 2, 1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 0, i, 1, -1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 1, i, 2, -1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 0, b, 0, -kx)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 1, b, 0, -kz)
    # rotation about the centre: J s + l/2 n.(lam_i + lam_{i+1}) - Q = 0
    k_here, c_here = joint_k[i], joint_c[i]
    k_next = joint_k[i + 1] if i + 1 < n else 0.0
    c_next = joint_c[i + 1] if i + 1 < n else 0.0
    sum_x = lam[0, i] + lam[0, i + 1]
    sum_z = lam[1, i] + lam[1, i + 1]
    geometric = -0.5 * li * (ex * sum_x + ez * sum_z)
    rot = cm * inertia[i] + cx * (geometric + k_here + k_next) + cv * (c_here + c_next)
    put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, b, 0, rot)
    if i > 0:
        put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, i, 0, -(cx * k_here + cv * c_here))
    if i + 1 < n:
        put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, b + 1, 0, -(cx * k_next + cv * c_next))
    for blk in (i, b):
        put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, blk, 3, 0.5 * li * nx)
        put_entry(diag, upper, lower, NEWTON_BLOCK, b, 2, blk, 4, 0.5 * li * nz)
    # translation: m (A_i + A_{i+1}) / 2 - lam_i + lam_{i+1} - F = 0
    zc = 0.5 * (w[_PZ, i] + w[_PZ, b])
    vx = 0.5 * (w[_VX, i] + w[_VX, b]) - _current(current_z, current_u, zc)
    vz = 0.5 * (w[_VZ, i] + w[_VZ, b])
    vn = vx * nx + vz * nz
    vt = vx * ex + vz * ez
    wet, _, _ = segment_submersion(w[_PZ, i], w[_PZ, b])  # the drag of the submerged part
    jxx, jxz, jzz, ftx, ftz = _drag_jacobian(wet * drag_n[i], wet * drag_t[i], vn, vt, nx, nz,
                                             ex, ez)  # fmt: skip
    half_m = 0.5 * mass[i]
    r = 0.5 * cv / cm
    for blk in (i, b):
        put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, blk, 1, half_m - r * jxx)
        put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, blk, 2, -r * jxz)
        put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, blk, 1, -r * jxz)
        put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, blk, 2, half_m - r * jzz)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, i, 3, -1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, i, 4, -1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, b, 3, 1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, b, 4, 1.0)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 3, b, 0, -cx * ftx)
    put_entry(diag, upper, lower, NEWTON_BLOCK, i, 4, b, 0, -cx * ftz)


@njit(**JIT)
def _end_rows(p, w, cm, cx, cv, diag):
    """Rows of the top (block 0, rows 0-2) and bottom (block n, rows 3-4) conditions."""
    n = p.n
    heave = p.top_kind == TOP_HEAVE
    spring = p.top_stiffness * cx + p.top_damping * cv
    top_rows(diag, NEWTON_BLOCK, 1, 2, heave, cm, spring, p.top_mass)
    rx, rz = 3 * NEWTON_BLOCK, 4 * NEWTON_BLOCK
    if p.bottom_kind == BOTTOM_PINNED:
        om = p.stabilization_frequency
        c = 1.0 + (2.0 * om * cv + om * om * cx) / cm
        diag[n, rx + 1] += c
        diag[n, rz + 2] += c
    else:
        # m_b A_n - lam_n - F_body = 0
        dxx, dxz, dzz, kxx, kxz, kzz = _body_jacobian(p, w)
        mass, _, _, _ = _body_now(p, w[_PZ, n])
        diag[n, rx + 1] += mass + (cv * dxx + cx * kxx) / cm
        diag[n, rx + 2] += (cv * dxz + cx * kxz) / cm
        diag[n, rz + 1] += (cv * dxz + cx * kxz) / cm
        diag[n, rz + 2] += mass + (cv * dzz + cx * kzz) / cm
        diag[n, rx + 3] -= 1.0
        diag[n, rz + 4] -= 1.0


@njit(**JIT)
def newton_system(t, y, a_alpha, p, w, ydot, cm, cx, cv, diag, upper, lower, res, matrix):
    """Residual (and, when ``matrix``, the block-tridiagonal matrix) of an implicit step's
    Newton iteration at the alpha point (t, y) with accelerations ``a_alpha``; see
    ``numerics.implicit`` for cm, cx, cv. Returns the status.

    The residual is built from the mismatch g = a_alpha - f(t, y) between the iterate and the
    O(n) forward dynamics: the node accelerations the iterate implies differ from the dynamic
    ones by E (E_{k+1} = E_k + l n g), so the translational rows get m E at the link centre,
    the rotational rows J g and the bottom body m_b E_n; a converged iterate (g = 0) zeroes
    every row whatever approximation the matrix makes. The matrix is the exact linearisation
    of the Newton-Euler equations except that node positions and velocities follow the node
    accelerations as (cx / cm) dA and (cv / cm) dA (Newmark's update applied to the nodes),
    which drops terms of order h^2 omega^2 relative to the kept ones."""
    n = p.n
    pinned = p.bottom_kind == BOTTOM_PINNED
    status, top_acc, lx, lz = solve(t, y, p, w)
    if status != OK:
        return status
    bs = NEWTON_BLOCK
    for k in range(res.shape[0]):
        res[k] = 0.0
    # the node forces of the dynamic solution, kept in the scratch rows of ydot
    lam = ydot[: 2 * (n + 1)].reshape((2, n + 1))
    for k in range(n + 1):
        lam[0, k], lam[1, k] = _node_force(w, k, lx, lz, pinned)
    ex_, ez_ = 0.0, 0.0
    if p.top_kind == TOP_HEAVE:
        ez_ = a_alpha[n] - top_acc
        res[2] = p.top_mass * ez_
    for i in range(n):
        g = a_alpha[i] - w[_THDD, i]
        li = p.length[i]
        nx, nz = -w[_EZ, i], w[_EX, i]
        ex_next = ex_ + li * nx * g
        ez_next = ez_ + li * nz * g
        res[bs * i + 3] = 0.5 * p.mass[i] * (ex_ + ex_next)
        res[bs * i + 4] = 0.5 * p.mass[i] * (ez_ + ez_next)
        res[bs * (i + 1) + 2] = p.inertia[i] * g
        ex_, ez_ = ex_next, ez_next
    scale = 1.0 if pinned else _body_now(p, w[_PZ, n])[0]
    res[bs * n + 3] = scale * ex_
    res[bs * n + 4] = scale * ez_
    if not matrix:
        return OK
    diag[:, :] = 0.0
    upper[:, :] = 0.0
    lower[:, :] = 0.0
    arrays = (
        p.length, p.mass, p.inertia, p.joint_stiffness, p.joint_damping, p.drag_normal,
        p.drag_tangential, p.current_z, p.current_u,
    )  # fmt: skip
    for i in range(n):
        _link_rows(arrays, n, y, w, i, lam, cm, cx, cv, diag, upper, lower)
    _end_rows(p, w, cm, cx, cv, diag)
    return OK


@njit(**JIT)
def newton_correct(length, da, a1):
    """Subtract the Newton correction (the s entries of the solver's blocks) from the
    accelerations; returns the largest as a node acceleration (angle correction x length)."""
    n = length.shape[0]
    bs = NEWTON_BLOCK
    largest = abs(da[0])
    a1[n] -= da[0]
    for i in range(n):
        d = da[bs * (i + 1)]
        a1[i] -= d
        largest = max(largest, abs(d) * length[i])
    return largest
