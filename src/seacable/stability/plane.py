"""A system whose free bodies move in the horizontal plane (surge, sway, yaw), as the vector
field dx/dt = f(x) that the stability analyses work on.

The state is x = (X, V): X the positions (x [m], y [m], psi [rad] of each free body, in the
order of the case), V their rates (the earth-frame velocity of the reference point, v_x and v_y
[m/s], and the yaw rate r [rad/s]). f is the system's own right-hand side
(``system.kernel.rhs``): the force models, ties, current, wind and the bodies' equations are
the ones a time simulation integrates, evaluated here with the states put in place and the
rates read back (``rates``, compiled). The weather is changed in place in the system's
parameters (``Weather``): a uniform current and a constant wind, without rebuilding.

What the analyses accept (``Plane.of``, one line naming the body or line otherwise): every
free body is a rigid body with ``dofs: [surge, sway, yaw]``, level (roll and pitch 0) and
without force models that carry states; lines are ties (massless), or uniform lumped-mass
lines, each taken quasi-static: the tie that pulls its ends as its elastic catenary at rest
does (``quasi_static``; its mass, drag and dynamics left out). Waves act through
their mean drift only (``wave drift``, constant in time once the sea has risen: the plane
takes it risen, without the build-up); the first-order wave loads (``diffraction``,
``non-linear Froude-Krylov``, ``non-linear hydrostatic`` on the waves' surface) oscillate in
time and are refused in waves.
"""

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from seacable import packing
from seacable.case import forces as fm
from seacable.case.environment import Environment, RegularWave
from seacable.case.system import LumpedMassLine, RigidBody, SystemCase, Tie
from seacable.errors import CaseError
from seacable.forces import compensator, kinds
from seacable.kernels import waves
from seacable.kernels.jit import JIT
from seacable.lines import catenary
from seacable.system import assemble, initial, kernel
from seacable.system import model as system_model
from seacable.system.assemble import BuiltSystem

PLANE_DOFS = {"surge", "sway", "yaw"}


@njit(**JIT)
def rates(t, x, y, q, v, p, w, ydot, out):
    """f(x) into ``out`` (module docstring); ``y`` the system's state, its other entries as
    built, ``q`` and ``v`` the bodies' offsets in it, ``ydot`` scratch. The status of the
    system's right-hand side is returned (kernels.status; OK is 0)."""
    n = q.shape[0]
    for j in range(n):
        a, b = q[j], v[j]
        half = 0.5 * x[3 * j + 2]
        y[a], y[a + 1] = x[3 * j], x[3 * j + 1]
        y[a + 3], y[a + 4], y[a + 5], y[a + 6] = math.cos(half), 0.0, 0.0, math.sin(half)
        y[b], y[b + 1], y[b + 2] = x[3 * n + 3 * j], x[3 * n + 3 * j + 1], 0.0
        y[b + 3], y[b + 4], y[b + 5] = 0.0, 0.0, x[3 * n + 3 * j + 2]
    status = kernel.evaluate(t, y, p, w, ydot)
    for j in range(n):
        b = v[j]
        for k in range(3):
            out[3 * j + k] = x[3 * n + 3 * j + k]
        out[3 * n + 3 * j] = ydot[b]
        out[3 * n + 3 * j + 1] = ydot[b + 1]
        out[3 * n + 3 * j + 2] = ydot[b + 5]
    return status


@njit(**JIT)
def jacobian(t, x, y, q, v, p, w, ydot, out, step):
    """df/dx at ``x`` (central differences: ``step`` [m, rad, m/s, rad/s] per entry) into
    ``out`` (n, n); the rates at ``x`` are left in ``ydot``'s scratch."""
    n = x.shape[0]
    up, down = np.empty(n), np.empty(n)
    xx = x.copy()
    for j in range(n):
        h = step[j]
        xx[j] = x[j] + h
        rates(t, xx, y, q, v, p, w, ydot, up)
        xx[j] = x[j] - h
        rates(t, xx, y, q, v, p, w, ydot, down)
        xx[j] = x[j]
        for i in range(n):
            out[i, j] = (up[i] - down[i]) / (2.0 * h)


@njit(**JIT)
def at_rest(t, x, y, q, v, p, w, ydot, weight, step, g, jac, sides):
    """G(X): the accelerations with the bodies at rest at positions X = ``x`` (3 per body),
    weighted by ``weight`` (``g``), and dG/dX (``jac``, differences of ``step``: central when
    ``sides`` is 2, forward from G when 1, half the cost, for Newton's steps); ``jac`` is
    skipped when it has no rows."""
    m = x.shape[0]
    xx = np.zeros(2 * m)
    f = np.empty(2 * m)
    xx[:m] = x
    rates(t, xx, y, q, v, p, w, ydot, f)
    for i in range(m):
        g[i] = f[m + i] * weight[i]
    if jac.shape[0] == 0:
        return
    up, down = np.empty(2 * m), np.empty(2 * m)
    for j in range(m):
        xx[j] = x[j] + step[j]
        rates(t, xx, y, q, v, p, w, ydot, up)
        if sides == 2:
            xx[j] = x[j] - step[j]
            rates(t, xx, y, q, v, p, w, ydot, down)
        else:
            down[m:] = f[m:]
        xx[j] = x[j]
        for i in range(m):
            jac[i, j] = (up[m + i] - down[m + i]) * weight[i] / (sides * step[j])


@njit(**JIT)
def balance(t, x0, y, q, v, p, w, ydot, weight, step, reach, iterations, tolerance, out):
    """Newton's method for the positions X (3 per body) at which the accelerations vanish with
    the bodies at rest, from ``x0`` (the positions), the residual weighted by ``weight`` (the
    bodies' masses and inertias: forces [N] and moments per metre). Each step is limited to
    ``reach`` (per entry) and halved until the weighted residual's 2-norm falls (Newton's
    step descends on it, not always on the largest entry); its Jacobian is of forward
    differences. It stops when that residual's largest entry is at most ``tolerance``
    or a full step is below 1e-10 of the positions. The solution goes to ``out``; returned:
    the weighted residual's largest entry, the iterations taken (negative when Newton
    stalled)."""
    m = x0.shape[0]
    x = x0.copy()
    g, gt = np.empty(m), np.empty(m)
    jac = np.empty((m, m))
    none = np.empty((0, 0))
    trial = np.empty(m)
    one = np.int64(1)  # forward differences: Newton's steps need no more
    at_rest(t, x, y, q, v, p, w, ydot, weight, step, g, none, one)
    norm = np.abs(g).max()
    before = norm  # the residual five iterations ago: a start that gains under 10 %, stalls
    for it in range(iterations):
        if norm <= tolerance:
            out[:] = x
            return norm, it
        if it % 5 == 0:
            if it > 0 and norm > 0.9 * before:
                out[:] = x
                return norm, -(it + 1)
            before = norm
        at_rest(t, x, y, q, v, p, w, ydot, weight, step, g, jac, one)
        if not np.all(np.isfinite(jac)):
            out[:] = x
            return norm, -(it + 1)
        try:
            dx = np.linalg.solve(jac, -g)
        except Exception:  # singular: a free direction (a body not held)
            out[:] = x
            return norm, -(it + 1)
        scale = 1.0
        for i in range(m):
            if abs(dx[i]) * scale > reach[i]:
                scale = reach[i] / abs(dx[i])
        accepted = False
        nt = norm
        size = np.dot(g, g)
        for _ in range(16):  # down to 1.5e-5 of the step
            trial[:] = x + scale * dx
            at_rest(t, trial, y, q, v, p, w, ydot, weight, step, gt, none, one)
            nt = np.abs(gt).max()
            if np.dot(gt, gt) < size or nt == 0.0:
                accepted = True
                break
            scale *= 0.5
        if not accepted:
            out[:] = x
            return norm, -(it + 1)
        small = scale == 1.0  # a full Newton step, and a small one
        for i in range(m):
            if abs(dx[i]) > 1e-10 * max(1.0, abs(x[i])):
                small = False
        x[:] = trial
        norm = nt
        if small:
            out[:] = x
            return norm, it + 1
    out[:] = x
    return norm, iterations


@dataclass
class Plane:
    """A built system seen as the vector field f (module docstring)."""

    built: BuiltSystem
    bodies: np.ndarray  # the free bodies' indices in the case
    names: list[str]
    q: np.ndarray  # their position offsets in the system's state
    v: np.ndarray  # their velocity offsets
    y: np.ndarray  # the system's state (its other entries as built)
    work: kernel.SystemWork
    ydot: np.ndarray
    weight: np.ndarray  # per position: mass (+ added) [kg], or inertia / length [kg m]
    length: np.ndarray  # per body: a length for its moments [m] (its mesh's or sqrt(I/m))

    @classmethod
    def of(cls, case: SystemCase, base_dir=None) -> "Plane":
        """The plane view of ``case`` (its own start, not its statics); a CaseError line when
        the case is not one the analyses accept (module docstring)."""
        for line in case.lines:
            if not isinstance(line, Tie | LumpedMassLine):
                raise CaseError(f"lines.{line.name}: the horizontal-plane analyses take ties "
                                "(model: tie) and lumped-mass lines (model: lumped_mass, "
                                f"taken quasi-static) between the bodies; '{line.model}' "
                                "lines run in time simulations only")  # fmt: skip
        free = []
        for i, body in enumerate(case.bodies):
            where = f"bodies.{body.name}"
            if body.type == "imposed":
                raise CaseError(f"{where}: an imposed body moves in time; the horizontal-plane "
                                "analyses take fixed bodies and free ships: make it "
                                "type: fixed at the place to analyse")  # fmt: skip
            if body.type == "fixed":
                continue
            if not isinstance(body, RigidBody) or set(body.dofs) != PLANE_DOFS:
                dofs = getattr(body, "dofs", None)
                raise CaseError(f"{where}.dofs: {dofs}; the horizontal-plane analyses need "
                                "rigid bodies with dofs: [surge, sway, yaw]")  # fmt: skip
            if body.orientation_deg[0] != 0.0 or body.orientation_deg[1] != 0.0:
                raise CaseError(f"{where}.orientation_deg: roll and pitch "
                                f"{list(body.orientation_deg[:2])}; the horizontal-plane "
                                "analyses take level bodies: give them 0")  # fmt: skip
            _refuse_first_order_waves(case, body, where)
            free.append(i)
        if not free:
            raise CaseError("bodies: no free body; the horizontal-plane analyses need at least "
                            "one rigid body with dofs: [surge, sway, yaw]")  # fmt: skip
        built = system_model.build(quasi_static(case, base_dir), base_dir)
        p = built.params
        if p.n_s:
            raise CaseError(
                "external forces: a force model with states (a controller's integral, a "
                "steering gear, radiation memory, a servo); the horizontal-plane analyses take "
                "force models without states"
            )
        p.wave[waves.BUILD_UP, :] = 0.0  # the sea risen: its mean drift is constant
        bodies = np.array(free)
        q = p.body_q[bodies].astype(np.int64)
        v = p.body_v[bodies].astype(np.int64)
        weight, length = [], []
        for b in bodies:
            mass = p.body_mass[b]
            izz = p.body_inertia[b, 2, 2] + mass * (p.body_cog[b, 0] ** 2 + p.body_cog[b, 1] ** 2)
            size = math.sqrt(max(izz + p.body_added[b, 5, 5], 1e-30) / max(mass, 1e-30))
            weight += [mass + p.body_added[b, 0, 0], mass + p.body_added[b, 1, 1],
                       (izz + p.body_added[b, 5, 5]) / size]  # fmt: skip
            length.append(size)
        y = built.y0.copy()
        return cls(built, bodies, [case.bodies[b].name for b in bodies], q, v, y,
                   kernel.make_work(p), np.zeros_like(y), np.array(weight),
                   np.array(length))  # fmt: skip

    @property
    def size(self) -> int:
        """Entries of x: 6 per free body."""
        return 6 * len(self.bodies)

    def start(self) -> np.ndarray:
        """The case's own start, x0."""
        y0, n = self.built.y0, len(self.bodies)
        x = np.zeros(6 * n)
        for j, (a, b) in enumerate(zip(self.q, self.v, strict=True)):
            quat = y0[a + 3 : a + 7]
            x[3 * j : 3 * j + 3] = y0[a], y0[a + 1], level_yaw(quat)
            x[3 * n + 3 * j : 3 * n + 3 * j + 3] = y0[b], y0[b + 1], y0[b + 5]
        return x

    def rates(self, x: np.ndarray, t: float = 0.0) -> np.ndarray:
        """f(x)."""
        out = np.empty(self.size)
        rates(t, np.asarray(x, dtype=float), self.y, self.q, self.v, self.built.params,
              self.work, self.ydot, out)  # fmt: skip
        return out

    def steps(self) -> np.ndarray:
        """The differencing steps of x's entries: 0.1 mm and 1e-8 rad, 1e-8 m/s and 1e-10
        rad/s. Small: the hull loads' |v| v terms are C^1 but not C^2 at v = 0, where a central
        difference of step h is off by C_Y h (relative to the linear terms, C_Y h / (pi T/L))."""
        n = len(self.bodies)
        return np.concatenate([np.tile([1e-4, 1e-4, 1e-8], n), np.tile([1e-8, 1e-8, 1e-10], n)])

    def at_rest(self, positions: np.ndarray, jacobian: bool = True, t: float = 0.0):
        """(G, dG/dX) at ``positions`` (``plane.at_rest``; dG/dX None unless ``jacobian``)."""
        m = 3 * len(self.bodies)
        g = np.empty(m)
        jac = np.empty((m, m) if jacobian else (0, 0))
        at_rest(t, np.asarray(positions, dtype=float), self.y, self.q, self.v,
                self.built.params, self.work, self.ydot, self.weight, self.steps()[:m], g,
                jac, np.int64(2))  # fmt: skip
        return g, (jac if jacobian else None)

    def hulls(self) -> list[np.ndarray | None]:
        """Each free body's hull outline in its body frame (4, 2): the L x B rectangle about
        the point of its ``short-wing`` or ``cross-flow`` model (None: no such model)."""
        p = self.built.params
        out: list[np.ndarray | None] = []
        for b in self.bodies:
            rows = [f for f in range(p.force_kind.shape[0]) if p.force_body[f] == b
                    and p.force_kind[f] in (kinds.SHORT_WING, kinds.CROSS_FLOW)]  # fmt: skip
            if not rows:
                out.append(None)
                continue
            row = p.force_data[p.force_at[rows[0]] :]
            half_l, half_b = 0.5 * row[3], 0.5 * row[4]
            out.append(np.array([[half_l, half_b], [-half_l, half_b], [-half_l, -half_b],
                                 [half_l, -half_b]]) + row[:2])  # fmt: skip
        return out

    def outlines(self, positions: np.ndarray) -> list[np.ndarray | None]:
        """Each free body's hull outline (``hulls``) in the earth frame at ``positions`` (3
        per body)."""
        out: list[np.ndarray | None] = []
        for j, corners in enumerate(self.hulls()):
            x, y, psi = positions[3 * j : 3 * j + 3]
            c, s = math.cos(psi), math.sin(psi)
            out.append(None if corners is None else corners @ np.array([[c, s], [-s, c]]) + (x, y))
        return out

    @property
    def controlled(self) -> bool | None:
        """Whether the compensators (forces.compensator) act (None: the case has none)."""
        p = self.built.params
        if not p.compensator.shape[0]:
            return None
        return bool(p.force_data[p.force_at[p.compensator[0]] + compensator.ENABLED] != 0.0)

    def control(self, enabled: bool) -> None:
        """Switch every compensator on or off, in place (the same system otherwise)."""
        p = self.built.params
        for f in p.compensator:
            p.force_data[p.force_at[f] + compensator.ENABLED] = float(enabled)

    def jacobian(self, x: np.ndarray, t: float = 0.0) -> np.ndarray:
        """df/dx at ``x``."""
        out = np.empty((self.size, self.size))
        jacobian(t, np.asarray(x, dtype=float), self.y, self.q, self.v, self.built.params,
                 self.work, self.ydot, out, self.steps())  # fmt: skip
        return out


def quasi_static(case: SystemCase, base_dir=None) -> SystemCase:
    """``case`` with each lumped-mass line replaced by the tie that pulls its ends as the line
    at rest does in the horizontal plane: the elastic catenary's horizontal tension H(span)
    (``lines.catenary.horizontal_law``), between the same points, its unstretched length the
    height between them and its tension H d / span at the distance d (the same horizontal
    pull, along the chord). The ends' heights are those the case gives (level ships keep
    them). The line's mass, drag and dynamics are left out; only uniform lines (one stiffness
    and weight per length) have the closed form. The case itself when it has no such line."""
    lumped = [line for line in case.lines if isinstance(line, LumpedMassLine)]
    if not lumped:
        return case
    built = assemble.build(case, base_dir)
    p = built.params
    ppos, _ = initial.end_points(built, built.y0)
    data = case.model_dump(by_alias=True, exclude_none=True)
    for li, line in enumerate(lumped):
        where = f"lines.{line.name}"
        ends = ppos[int(p.line_from[li])], ppos[int(p.line_to[li])]
        low, high = sorted(ends, key=lambda point: float(point[2]))
        uniform = initial.uniform_line(p, li, float(low[2]))
        if uniform is None:
            raise CaseError(f"{where}.sections: segments of different stiffness or weight; "
                            "the horizontal-plane analyses take a lumped-mass line as its "
                            "elastic catenary, which needs a uniform line: give it one line "
                            "type")  # fmt: skip
        length, w, ea, seabed = uniform
        rise = float(high[2] - low[2])
        try:
            law = catenary.horizontal_law(rise, length, w, ea, seabed, count=400)
        except catenary.CatenaryError as exc:
            raise CaseError(f"{where}: {exc}") from None
        chord = np.hypot(law[:, 0], rise)
        pull = law[:, 1] * chord / law[:, 0]  # [N] along the chord
        table = [[0.0, 0.0]] + np.column_stack([chord - rise, pull]).tolist()
        tie = {"name": line.name, "model": "tie", "from": line.from_, "to": line.to,
               "unstretched_length": rise, "tension_table": table}  # fmt: skip
        data["lines"] = [tie if item["name"] == line.name else item for item in data["lines"]]
    return SystemCase.model_validate(data)


def _refuse_first_order_waves(case: SystemCase, body: RigidBody, where: str) -> None:
    """A CaseError line for a wave load that oscillates in time, when the case has waves."""
    if not case.environment.waves:
        return
    for k, spec in enumerate(body.external_forces):
        still = isinstance(spec, fm.NonLinearHydrostatic) and spec.free_surface == "still"
        if spec.model in (*fm.MESH_MODELS, "diffraction") and not still:
            raise CaseError(f"{where}.external forces.{k}: '{spec.model}' in waves; its "
                            "load oscillates with them, and the horizontal-plane analyses take "
                            "loads constant in time: remove it (the waves act through 'wave "
                            "drift', their mean) or analyse the case by simulation")  # fmt: skip


def level_yaw(quat) -> float:
    """The yaw [rad] of a level body's quaternion (w, x, y, z)."""
    return 2.0 * math.atan2(float(quat[3]), float(quat[0]))


@dataclass(frozen=True)
class Weather:
    """A uniform current and a constant wind, each a speed [m/s] and the direction it goes
    TOWARDS [deg] (from +x towards +y, as ``environment.current`` and ``environment.wind``);
    and the case's waves (``environment.waves``, as realised for a simulation), which act
    through the ships' ``wave drift``: ``wave_height`` the significant height Hs [m] they are
    scaled to (every component's amplitude by Hs / Hs_case, so the drift by (Hs /
    Hs_case)^2; Hs_case = 4 sqrt(m0) of the case's waves as given, m0 the sum of each
    spectrum's Hs^2 / 16 and each regular wave's H^2 / 8: a regular wave of height H alone has
    Hs_case = sqrt(2) H), ``wave_towards_deg`` the mean direction they are turned to [deg]
    (every component's by the same angle; the mean is the direction of sum a_i^2 (cos b_i,
    sin b_i), the wave's own for one wave or a spread spectrum). None: the case's own."""

    current_speed: float = 0.0
    current_towards_deg: float = 0.0
    wind_speed: float = 0.0
    wind_towards_deg: float = 0.0
    wave_height: float | None = None
    wave_towards_deg: float | None = None

    def apply(self, built: BuiltSystem) -> None:
        """Write this weather into ``built``'s parameters, in place (the case's current must be
        uniform; its wind, if a model needs one, is replaced by constants; its waves scaled
        and turned from the case's own)."""
        p = built.params
        if p.current_z.shape[0] != 1:
            raise CaseError(
                "environment.current: a profile; the horizontal-plane analyses set a uniform "
                "current: give velocity [m/s] instead of profile"
            )
        angle = math.radians(self.current_towards_deg)
        p.current_u[0] = self.current_speed * math.cos(angle)
        p.current_v[0] = self.current_speed * math.sin(angle)
        self._waves(built)
        channel = int(p.wind_channel)
        if channel < 0:
            if self.wind_speed != 0.0:
                raise CaseError("environment.wind: none, and no body has a 'wind' force model; "
                                "add them to analyse a wind")  # fmt: skip
            return
        set_constant(p, channel, self.wind_speed)
        set_constant(p, channel + 1, math.radians(self.wind_towards_deg))

    def calm(self, built: BuiltSystem) -> bool:
        """No current, no wind and no waves (of this weather on ``built``'s case): nothing
        moves water or air past the hulls, so nothing damps or drives the ships."""
        still_sea = self.wave_height == 0.0 or not np.any(built.params.wave[waves.A])
        return self.current_speed == 0.0 and self.wind_speed == 0.0 and still_sea

    def _waves(self, built: BuiltSystem) -> None:
        """The case's waves, scaled to ``wave_height`` and turned to ``wave_towards_deg``."""
        p = built.params
        given = self.wave_height is not None or self.wave_towards_deg is not None
        if p.wave.shape[1] == 0:
            if given:
                raise CaseError("environment.waves: none; the weather's wave_height and "
                                "wave_towards_deg scale and turn the case's sea: add a wave "
                                "(kind: airy) or a spectrum (kind: jonswap) to analyse "
                                "waves")  # fmt: skip
            return
        if self.wave_height and not np.any(p.force_kind == kinds.WAVE_DRIFT):
            raise CaseError("environment.waves: no body has a 'wave drift' force model; add "
                            "them to analyse waves")  # fmt: skip
        sea = case_sea(built.case.environment)
        if sea.shape != p.wave.shape:
            raise CaseError("environment.waves: the built system's sea is not the case's; "
                            "build the plane from this case")  # fmt: skip
        height, mean = case_waves(built.case.environment)
        scale, turn = 1.0, 0.0
        if self.wave_height is not None:
            scale = self.wave_height / height
        if self.wave_towards_deg is not None:
            turn = math.radians(self.wave_towards_deg - mean)
        c, s = math.cos(turn), math.sin(turn)
        p.wave[waves.A] = scale * sea[waves.A]
        p.wave[waves.COS] = c * sea[waves.COS] - s * sea[waves.SIN]
        p.wave[waves.SIN] = s * sea[waves.COS] + c * sea[waves.SIN]


def significant_height(environment: Environment) -> float:
    """Hs = 4 sqrt(m0) [m] of the waves as given: m0 the sum of each spectrum's Hs^2 / 16
    and each regular wave's H^2 / 8 (its a^2 / 2)."""
    m0 = sum(w.height**2 / 8.0 if isinstance(w, RegularWave) else w.significant_height**2 / 16.0
             for w in environment.waves)  # fmt: skip
    return 4.0 * math.sqrt(m0)


_SEAS: dict[str, np.ndarray] = {}  # case_sea's, by the environment's JSON


def case_waves(environment: Environment) -> tuple[float, float]:
    """The case's waves as ``Weather`` sees them: their significant height Hs [m]
    (``significant_height``) and their mean direction [deg], towards (the direction of
    sum a_i^2 (cos b_i, sin b_i) over the realised components)."""
    sea = case_sea(environment)
    energy = sea[waves.A] ** 2
    mean = math.atan2((energy * sea[waves.SIN]).sum(), (energy * sea[waves.COS]).sum())
    return significant_height(environment), math.degrees(mean)


def case_sea(environment: Environment) -> np.ndarray:
    """The sea (kernels.waves table) ``environment`` realises, without build-up: the one
    ``system.assemble`` builds, the same components in the same order (kept, read-only, for
    the next weather)."""
    key = environment.model_dump_json()
    if key not in _SEAS:
        if len(_SEAS) >= 8:
            _SEAS.clear()
        table = packing.wave_fields(environment)["wave"]
        table.setflags(write=False)
        _SEAS[key] = table
    return _SEAS[key]


def set_constant(p: kernel.SystemParams, channel: int, value: float) -> None:
    """Make time-function channel ``channel`` the constant ``value``, in place."""
    p.tf_coefs[channel, :, :] = 0.0
    p.tf_coefs[channel, :, 0] = value
    p.tf_sine[channel, :] = 0.0
    p.tf_build_up[channel, :] = 0.0


__all__ = ["Plane", "Weather", "at_rest", "balance", "case_sea", "case_waves", "jacobian", "rates",
           "set_constant", "significant_height"]  # fmt: skip
