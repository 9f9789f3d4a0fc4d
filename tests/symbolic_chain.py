"""An independent symbolic Euler-Lagrange derivation of the planar rigid-link cable (sympy).

Written from the Lagrangian, not from the kernel: generalised coordinates are the absolute link
angles (and the heave of a floating structure at the top); kinetic and potential energy, a
Rayleigh dissipation function for the dampers and the virtual work of drag and applied forces give
M(q, t) qdd = f(q, qd, t). A pinned end adds the holonomic constraint r_n(q, t) = anchor with a
Lagrange multiplier.
"""

from types import SimpleNamespace

import numpy as np
import sympy as sp


class SymbolicChain:
    """Accelerations of the chain from sympy, for its description ``p`` and the top motion
    given as sympy expressions of ``t`` (used when the top is neither fixed nor heaving).

    ``p`` (SI units): ``n`` links; ``heave`` (a floating structure at the top, ``top_x``,
    ``top_mass``, ``top_stiffness``, ``top_damping``, ``top_rest_z``, ``top_net_weight``
    positive down); ``pinned`` (the end held where it is); per link ``length``, ``mass``,
    ``inertia`` (about its centre), ``wet_weight`` (positive down), ``drag_normal`` and
    ``drag_tangential`` (0.5 rho Cd d l), ``joint_stiffness`` and ``joint_damping`` (joint i
    between links i-1 and i, the first against ``top_reference_angle``); the current's profile
    ``current_z``, ``current_u``; the end body's ``body_mass`` (added mass in), ``body_wet_weight``,
    ``body_drag`` (0.5 rho Cd A) and its ties ``tie_kx``, ``tie_kz``, ``tie_cx``, ``tie_cz``
    about ``tie_x0``, ``tie_z0``."""

    def __init__(self, p: SimpleNamespace, top_motion=None, forces=None):
        t = sp.Symbol("t")
        n = p.n
        heave = p.heave
        pinned = p.pinned
        forces = forces or {}
        nq = n + (1 if heave else 0)
        qf = [sp.Function(f"q{j}")(t) for j in range(nq)]
        th = qf[:n]
        if heave:
            x0, z0 = sp.Float(float(p.top_x)), qf[n]
        else:
            x0, z0 = top_motion
        nodes = [(x0, z0)]
        for i in range(n):
            xi, zi = nodes[-1]
            nodes.append(
                (xi + float(p.length[i]) * sp.sin(th[i]), zi - float(p.length[i]) * sp.cos(th[i]))
            )
        centres = [
            ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
            for a, b in zip(nodes[:-1], nodes[1:], strict=True)
        ]

        def vel(point):
            return (sp.diff(point[0], t), sp.diff(point[1], t))

        kinetic = 0
        potential = 0
        dissipation = 0
        virtual = [0] * nq
        u0 = float(p.current_u[0] - p.current_z[0] * _slope(p))
        u1 = float(_slope(p))
        for i in range(n):
            vc = vel(centres[i])
            om = sp.diff(th[i], t)
            kinetic += sp.Rational(1, 2) * float(p.mass[i]) * (vc[0] ** 2 + vc[1] ** 2)
            kinetic += sp.Rational(1, 2) * float(p.inertia[i]) * om**2
            potential += float(p.wet_weight[i]) * centres[i][1]
            prev = float(p.top_reference_angle) if i == 0 else th[i - 1]
            prev_rate = 0 if i == 0 else sp.diff(th[i - 1], t)
            potential += sp.Rational(1, 2) * float(p.joint_stiffness[i]) * (th[i] - prev) ** 2
            dissipation += sp.Rational(1, 2) * float(p.joint_damping[i]) * (om - prev_rate) ** 2
            # drag at the link centre on the velocity relative to a linear current profile
            vrx = vc[0] - (u0 + u1 * centres[i][1])
            vrz = vc[1]
            nx, nz = sp.cos(th[i]), sp.sin(th[i])
            ex, ez = sp.sin(th[i]), -sp.cos(th[i])
            vn = vrx * nx + vrz * nz
            vt = vrx * ex + vrz * ez
            fn = -float(p.drag_normal[i]) * sp.Abs(vn) * vn
            ft = -float(p.drag_tangential[i]) * sp.Abs(vt) * vt
            force = (fn * nx + ft * ex, fn * nz + ft * ez)
            for j in range(nq):
                virtual[j] += force[0] * sp.diff(centres[i][0], qf[j])
                virtual[j] += force[1] * sp.diff(centres[i][1], qf[j])
        end = nodes[-1]
        if not pinned:
            ve = vel(end)
            kinetic += sp.Rational(1, 2) * float(p.body_mass) * (ve[0] ** 2 + ve[1] ** 2)
            potential += float(p.body_wet_weight) * end[1]
            potential += sp.Rational(1, 2) * float(p.tie_kx) * (end[0] - float(p.tie_x0)) ** 2
            potential += sp.Rational(1, 2) * float(p.tie_kz) * (end[1] - float(p.tie_z0)) ** 2
            dissipation += sp.Rational(1, 2) * (
                float(p.tie_cx) * ve[0] ** 2 + float(p.tie_cz) * ve[1] ** 2
            )
            vrx = ve[0] - (u0 + u1 * end[1])
            speed = sp.sqrt(vrx**2 + ve[1] ** 2)
            fx = -float(p.body_drag) * speed * vrx + forces.get("body_fx", 0)
            fz = -float(p.body_drag) * speed * ve[1] + forces.get("body_fz", 0)
            for j in range(nq):
                virtual[j] += fx * sp.diff(end[0], qf[j]) + fz * sp.diff(end[1], qf[j])
        if heave:
            zs = qf[n]
            kinetic += sp.Rational(1, 2) * float(p.top_mass) * sp.diff(zs, t) ** 2
            potential += (
                sp.Rational(1, 2) * float(p.top_stiffness) * (zs - float(p.top_rest_z)) ** 2
            )
            potential += float(p.top_net_weight) * zs
            dissipation += sp.Rational(1, 2) * float(p.top_damping) * sp.diff(zs, t) ** 2
            virtual[n] += forces.get("top_force", 0)

        lagrangian = kinetic - potential
        qs = sp.symbols(f"x0:{nq}")
        vs = sp.symbols(f"v0:{nq}")
        accs = sp.symbols(f"a0:{nq}")
        subs = {}
        for j in range(nq):
            subs[sp.diff(qf[j], t, 2)] = accs[j]
        for j in range(nq):
            subs[sp.diff(qf[j], t)] = vs[j]
        for j in range(nq):
            subs[qf[j]] = qs[j]

        def plain(expr):
            return sp.sympify(expr).subs(subs)

        equations = []
        for j in range(nq):
            dq = sp.diff(qf[j], t)
            eq = sp.diff(sp.diff(lagrangian, dq), t) - sp.diff(lagrangian, qf[j])
            eq += sp.diff(dissipation, dq) - virtual[j]
            equations.append(plain(eq))
        mass = sp.Matrix([[sp.diff(eq, a) for a in accs] for eq in equations])
        rest = sp.Matrix([eq.subs({a: 0 for a in accs}) for eq in equations])
        args = (t, qs, vs)
        self._mass = sp.lambdify(args, mass, "numpy")
        self._rest = sp.lambdify(args, rest, "numpy")
        self.nq = nq
        self.n = n
        self.heave = heave
        self.pinned = pinned
        self._end = sp.lambdify(args, sp.Matrix([plain(end[0]), plain(end[1])]), "numpy")
        if pinned:
            phi = sp.Matrix([end[0], end[1]])
            jac = sp.Matrix([[plain(sp.diff(c, qf[j])) for j in range(nq)] for c in phi])
            phi_t = sp.Matrix(
                [plain(sp.diff(c, t)) - (jac * sp.Matrix(vs))[k] for k, c in enumerate(phi)]
            )
            gamma = sp.Matrix([plain(sp.diff(c, t, 2)).subs({a: 0 for a in accs}) for c in phi])
            self._jac = sp.lambdify(args, jac, "numpy")
            self._phi_t = sp.lambdify(args, phi_t, "numpy")
            self._gamma = sp.lambdify(args, gamma, "numpy")

    def end_position(self, t, q, v):
        return np.asarray(self._end(t, q, v), dtype=float).ravel()

    def consistent_velocity(self, t, q, v):
        """Project v so the pinned end does not move (J v + phi_t = 0)."""
        jac = np.asarray(self._jac(t, q, v), dtype=float)
        phi_t = np.asarray(self._phi_t(t, q, v), dtype=float).ravel()
        residual = jac @ v + phi_t
        return v - np.linalg.pinv(jac) @ residual

    def accelerations(self, t, q, v):
        mass = np.asarray(self._mass(t, q, v), dtype=float)
        rest = np.asarray(self._rest(t, q, v), dtype=float).ravel()
        if not self.pinned:
            return np.linalg.solve(mass, -rest)
        jac = np.asarray(self._jac(t, q, v), dtype=float)
        gamma = np.asarray(self._gamma(t, q, v), dtype=float).ravel()
        k = self.nq
        system = np.zeros((k + 2, k + 2))
        system[:k, :k] = mass
        system[:k, k:] = -jac.T
        system[k:, :k] = jac
        rhs = np.concatenate([-rest, -gamma])
        return np.linalg.solve(system, rhs)[:k]


def _slope(p):
    if p.current_z.shape[0] < 2:
        return 0.0
    return (p.current_u[1] - p.current_u[0]) / (p.current_z[1] - p.current_z[0])
