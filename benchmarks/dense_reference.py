"""The thesis's approach, faithfully: form the dense (n+1)x(n+1) inertia matrix I(x), the
Coriolis-centrifugal vector F, the gravity vector G, joint C and K terms and the external vector T
at every evaluation, and solve I xdd = T - C xd - K x - F - G (NumPy, LAPACK).

Generalised coordinates x = (heave of the floating structure, theta_1 .. theta_n) as in the
thesis, with z up. Matrix entries are derived from the Lagrangian (not transcribed from the
thesis, whose printed algorithms have index errors):

    I_zz      = M + sum m_k + m_c
    I_z,i     = l_i sin(theta_i) mu_i,              mu_i = m_i/2 + sum_{k>i} m_k + m_c
    I_i,i     = J_i + l_i^2 (m_i/4 + sum_{k>i} m_k + m_c)
    I_i,j     = l_i l_j cos(theta_i - theta_j) mu_max(i,j)        (i != j)
    F_z       = sum_i l_i cos(theta_i) mu_i thetad_i^2
    F_i       = sum_j I_i,j tan-free form: l_i l_j sin(theta_i - theta_j) mu_max(i,j) thetad_j^2

Loads (apparent weight, drag at link centres, terminal body) enter as generalised forces
l_i n_i . (F_i / 2 + sum_{k>i} F_k + F_body), exactly the physics seacable uses, so both codes
integrate the same equations and can be compared at the same accuracy.
"""

import math
from types import SimpleNamespace

import numpy as np

from seacable.case import system as sch
from seacable.system.assemble import BuiltSystem


def thesis_chain(built: BuiltSystem) -> SimpleNamespace:
    """The thesis's first case read from a system of bodies and lines (as the examples write
    it): a rigid body ``top`` free in heave only on a linear spring and damper, with a sine
    force, a planar rigid-link line from it to a point body ``end`` (gravity, buoyancy, drag),
    in a uniform current. The line's links come from the assembled parameters; the bodies from
    the case (SI units). State layout of the dense model: [theta (n), z_top, omega (n), z_top
    rate]: ``dense_state`` and ``system_rates`` translate."""
    case, p = built.case, built.params
    top, end = case.bodies[0], case.bodies[1]
    if not (
        isinstance(top, sch.RigidBody) and top.dofs == ["heave"]
        and isinstance(end, sch.PointBody) and len(case.lines) == 1
        and case.lines[0].model == "rigid_links"
    ):  # fmt: skip
        raise ValueError("the dense reference covers the thesis's first case only")
    env = case.environment
    forces = {f.model: f for f in top.external_forces}
    end_forces = {f.model: f for f in end.external_forces}
    sine = forces["applied"].force_z if "applied" in forces else None
    drag = end_forces.get("drag")
    buoyancy = env.water_density * end.volume if "buoyancy" in end_forces else 0.0
    current = env.current.velocity if env.current is not None else 0.0
    ref = p.rs_ref[0]
    return SimpleNamespace(
        n=int(p.rs_n[0]), length=p.rs_length, mass=p.rs_mass, inertia=p.rs_inertia,
        wet_weight=p.rs_wet_weight, drag_normal=p.rs_drag_normal,
        drag_tangential=p.rs_drag_tangential, joint_stiffness=p.rs_joint_stiffness,
        joint_damping=p.rs_joint_damping, top_reference_angle=math.atan2(ref[0], -ref[2]),
        current_u=float(current or 0.0), top_mass=top.mass,
        top_stiffness=forces["linear_stiffness"].diagonal[2],
        top_damping=forces["linear_damping"].diagonal[2] if "linear_damping" in forces else 0.0,
        top_rest_z=(forces["linear_stiffness"].equilibrium_position or top.position)[2],
        top_net_weight=0.0,
        body_mass=end.mass + _axis_z(end.added_mass),
        body_wet_weight=(end.mass - buoyancy) * env.gravity,
        body_drag=0.0 if drag is None
        else 0.5 * env.water_density * drag.drag_coefficient * _axis_z(drag.area),
        force=(0.0, 0.0, 0.0, 0.0) if sine is None else (
            sine.offset, sine.amplitude,
            sine.angular_frequency or 2 * math.pi / sine.period, sine.phase),
        rs_q=int(p.rs_q[0]), rs_v=int(p.rs_v[0]), top_q=int(p.body_q[0]) + 2,
        top_v=int(p.body_v[0]) + 2,
    )  # fmt: skip


def _axis_z(value) -> float:
    """The vertical value of a per-axis quantity (one number, or x, y, z)."""
    return float(value) if np.ndim(value) == 0 else float(value[2])


def dense_state(chain: SimpleNamespace, y: np.ndarray) -> np.ndarray:
    """The dense model's state from a system's."""
    n = chain.n
    return np.concatenate([y[chain.rs_q : chain.rs_q + n], [y[chain.top_q]],
                           y[chain.rs_v : chain.rs_v + n], [y[chain.top_v]]])  # fmt: skip


def system_rates(chain: SimpleNamespace, ydot: np.ndarray) -> np.ndarray:
    """A system's rates in the dense model's layout."""
    return dense_state(chain, ydot)


class DenseThesisModel:
    """Floating structure in heave at the top, free end with a point body (the thesis's case 1),
    described by :func:`thesis_chain`."""

    def __init__(self, p: SimpleNamespace):
        self.p = p
        n = p.n
        m = p.mass
        # mass below each link (exclusive) plus the terminal body
        below = np.concatenate([np.cumsum(m[::-1])[::-1][1:], [0.0]]) + p.body_mass
        self.mu = 0.5 * m + below  # mu_i
        self.diag = p.inertia + p.length**2 * (0.25 * m + below)
        index = np.arange(n)
        self.mu_pair = self.mu[np.maximum.outer(index, index)]
        self.ll = np.outer(p.length, p.length)
        self.total_mass = p.top_mass + m.sum() + p.body_mass
        self.u_const, self.u_amp, self.u_omega, self.u_phase = p.force

    def rhs(self, t, y):
        p = self.p
        n = p.n
        th = y[:n]
        zs = y[n]
        om = y[n + 1 : 2 * n + 1]
        zsd = y[2 * n + 1]
        s = np.sin(th)
        c = np.cos(th)
        lengths = p.length
        # dense inertia matrix I(x) (n+1)x(n+1), heave first
        inertia = np.empty((n + 1, n + 1))
        inertia[0, 0] = self.total_mass
        inertia[0, 1:] = inertia[1:, 0] = lengths * s * self.mu
        cos_diff = np.cos(th[:, None] - th[None, :])
        block = self.ll * cos_diff * self.mu_pair
        np.fill_diagonal(block, self.diag)
        inertia[1:, 1:] = block
        # Coriolis-centrifugal vector
        sin_diff = np.sin(th[:, None] - th[None, :])
        coriolis = np.empty(n + 1)
        coriolis[0] = np.sum(lengths * c * self.mu * om**2)
        coriolis[1:] = (self.ll * sin_diff * self.mu_pair) @ (om**2)
        # node velocities and link loads (the same loads as seacable's kernel)
        vx_nodes = np.concatenate([[0.0], np.cumsum(lengths * om * c)])
        vz_nodes = zsd + np.concatenate([[0.0], np.cumsum(lengths * om * s)])
        vcx = 0.5 * (vx_nodes[:-1] + vx_nodes[1:]) - p.current_u
        vcz = 0.5 * (vz_nodes[:-1] + vz_nodes[1:])
        vn = vcx * c + vcz * s
        vt = vcx * s - vcz * c
        fn = -p.drag_normal * np.abs(vn) * vn
        ft = -p.drag_tangential * np.abs(vt) * vt
        fx = fn * c + ft * s
        fz = fn * s - ft * c - p.wet_weight
        bvx = vx_nodes[-1] - p.current_u
        bvz = vz_nodes[-1]
        speed = np.hypot(bvx, bvz)
        bfx = -p.body_drag * speed * bvx
        bfz = -p.body_drag * speed * bvz - p.body_wet_weight
        sum_below_x = np.concatenate([np.cumsum(fx[::-1])[::-1][1:], [0.0]]) + bfx
        sum_below_z = np.concatenate([np.cumsum(fz[::-1])[::-1][1:], [0.0]]) + bfz
        external = np.empty(n + 1)
        external[1:] = lengths * (c * (0.5 * fx + sum_below_x) + s * (0.5 * fz + sum_below_z))
        u = self.u_const + self.u_amp * np.sin(self.u_omega * t + self.u_phase)
        external[0] = (
            fz.sum() + bfz + u - p.top_net_weight
            - p.top_stiffness * (zs - p.top_rest_z) - p.top_damping * zsd
        )  # fmt: skip
        # joint springs and dampers (the thesis's tridiagonal K and C)
        rel = np.diff(np.concatenate([[p.top_reference_angle], th]))
        rate = np.diff(np.concatenate([[0.0], om]))
        joint = p.joint_stiffness * rel + p.joint_damping * rate
        torque = -joint
        torque[:-1] += joint[1:]
        external[1:] += torque
        acc = np.linalg.solve(inertia, external - coriolis)
        ydot = np.empty_like(y)
        ydot[:n] = om
        ydot[n] = zsd
        ydot[n + 1 : 2 * n + 1] = acc[1:]
        ydot[2 * n + 1] = acc[0]
        return ydot

    def run_rk4(self, y0, dt, steps):
        y = y0.copy()
        t = 0.0
        for _ in range(steps):
            k1 = self.rhs(t, y)
            k2 = self.rhs(t + 0.5 * dt, y + 0.5 * dt * k1)
            k3 = self.rhs(t + 0.5 * dt, y + 0.5 * dt * k2)
            k4 = self.rhs(t + dt, y + dt * k3)
            y = y + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
            t += dt
        return y
