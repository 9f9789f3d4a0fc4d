"""Statics and linearisation of a whole system: every dynamic body free on its degrees of
freedom under its force models, its lines and ties, and the steady current; every lumped line
at its discrete equilibrium (seabed included). Newton iterations on the accelerations of every
free degree of freedom at rest, with a sparse finite-difference Jacobian (columns grouped by a
greedy colouring of the system's known sparsity: each line a chain of nodes, its two end
nodes' neighbours tied to the bodies it hangs from, ties joining bodies), solved by sparse LU.

The coordinates (system.coordinates: body translations and rotations, interior nodes, rigid
segments' turns) carry the linearisation too: ``jacobian`` gives d(rates)/d(increments,
velocities) about any state; ``mooring_stiffness`` the 6x6 stiffness of a body's lines.
"""

from dataclasses import replace

import numpy as np

from seacable.bodies import kinematics
from seacable.errors import SeacableError
from seacable.kernels import surface, waves
from seacable.system import closed_form, kernel, natural_lines, nested, outputs, relax, rigid
from seacable.system.assemble import BuiltSystem
from seacable.system.coordinates import (
    STRAIN,
    TURN,
    Coordinates,
    Residual,
    apply,
    colour,
    coordinates,
    fd_jacobian,
    is_angle,
    pattern,
    rotate,
    tangent_normals,
    tangents,
)
from seacable.system.frequency import fastest_frequency
from seacable.system.initial import towed_hanging, uniform_shapes
from seacable.system.line_balance import settle_each, settle_lines, steady_velocities
from seacable.system.pseudo_time import shifted_step


class StaticsError(SeacableError):
    """The static equilibrium was not found; the message names the body or line at fault."""


def still_water(built: BuiltSystem) -> BuiltSystem:
    """The system without its incident waves (their mean is still water): the statics' and
    the linearisation's."""
    if not built.params.wave.shape[1]:
        return built
    return replace(built, params=built.params._replace(wave=waves.still()))


def equilibrium(built: BuiltSystem, y0: np.ndarray, iterations: int = 60,
                tolerance: float = 1e-9, time: float = 0.0) -> np.ndarray:  # fmt: skip
    """The state at rest in balance, from ``y0``'s positions (velocities set to zero; or, when
    every fixed and imposed body moves at t = 0 with one velocity and without turning, a tow,
    everything moving with it: ``steady_velocities``).

    First Newton over every coordinate at once (sparse Jacobian); when that fails (a stiff
    line's linearised nodes go far astray in a step that moves its ends metres), Newton over
    the free bodies' degrees of freedom (``system.nested``), each lumped line settled at its
    static shape between its ends for every trial pose (``line_balance.settle_lines``, the linear
    axial law: chain lying on a frictionless seabed has one shape): it does not lose its way
    in the kinks of the seabed's contact or of the free surface. Then both again from the
    bodies' balance on the lines' closed-form catenaries (``system.closed_form``: a start near
    the balance when the bodies must travel far, a platform whose lines lie slack); then
    Newton's homotopy; last, dynamic relaxation (``system.relax``: the system let move, its
    kinetic energy taken away, until it rests near a balance Newton then finds), from the start
    and from the closed forms' balance; a tow, which the relaxation does not move, from its
    towed bodies hung below their tow points (``initial.towed_hanging``). Raises StaticsError
    naming the body or line that stays out of balance. In still water: the waves' mean
    position."""
    built = still_water(built)
    p = built.params
    coords = coordinates(p)
    y = y0.copy()
    y[p.n_q : p.n_q + p.n_v] = steady_velocities(p, y, time)
    if not len(coords.kind):
        return y
    y = natural_lines.hanging(p, y)
    residual = Residual(p, coords, time)
    if residual.balanced.any():
        y = _hang(p, y, residual.free, time=time)
    scale = float(np.abs(residual(y)).max()) + 1.0
    structure = pattern(p, coords)
    sparsity = (structure, colour(structure))  # which increments move which residuals
    stages = _Stages(built, coords, sparsity, residual, iterations, tolerance * scale,
                     1e-6 * scale, time)  # fmt: skip
    direct = _direct(built, coords, sparsity, residual, y, iterations, tolerance * scale)
    if stages.balanced(direct):
        return direct
    # the bodies' balance on the lines' closed forms (MoorPy's model; the lines' current and
    # ties as they act), the lumped lines settled on their shapes there: a start near the
    # balance when the bodies must travel far, tried before the nested Newton from the start,
    # which follows the bodies there in steps of the shortest line's tenth
    guess = closed_form.pose(p, coords, y, stages.limit, time)
    if guess is not None:
        guess = settle_each(p, uniform_shapes(p, guess, time), time=time)
        direct = _direct(built, coords, sparsity, residual, guess, iterations, tolerance * scale)
        if stages.balanced(direct):
            return direct
        if (settled := stages.nested_from(guess)) is not None:
            return settled
    if (settled := stages.nested_from(y)) is not None:
        return settled
    followed = _homotopy(built, coords, sparsity, residual, y, tolerance * scale, 1e-6 * scale)
    if stages.balanced(followed):
        return followed
    found, relaxed = stages.relaxed_from(y, scale)
    if found is None and guess is not None:
        found, _ = stages.relaxed_from(guess, scale)
    if found is None and np.any(y[p.n_q : p.n_q + p.n_v]):
        found = stages.towed_from(y)
    if found is not None:
        return found
    r = residual(followed)
    if not relaxed.rested and relaxed.state is not None:
        # it ran away: blame what went farthest, as it was at y, unless it was in balance there
        # (the lines' nodes out of balance on the seabed let it drift): then the worst residual
        moved = np.zeros(len(coords.kind))
        body = coords.kind == 0
        moved[body] = np.abs(relaxed.state[coords.q[body]] - y[coords.q[body]])
        start = residual(y)
        mover = int(np.argmax(moved))
        if moved.max() > 0.0 and not abs(start[mover]) < stages.enough:
            raise StaticsError(_blame(built, coords, start, mover))
    raise StaticsError(_blame(built, coords, r))


class _Stages:
    """The statics' attempts after Newton from the start (``equilibrium``), sharing its
    residual, tolerance (``enough``: the largest residual accepted) and step limits."""

    def __init__(self, built, coords, sparsity, residual, iterations, tolerance, enough, time):
        self.built, self.coords, self.sparsity, self.residual = built, coords, sparsity, residual
        self.iterations, self.tolerance, self.enough, self.time = (
            iterations,
            tolerance,
            enough,
            time,
        )
        p = built.params
        self.bodies = np.flatnonzero(coords.kind <= 1)
        self.limit = _step_limit(built, coords, shortest=True)[self.bodies]
        self.nests = bool(
            (self.bodies.size or len(p.line_n)) and not len(p.rs_n) and not len(p.nat_n)
        )

    def balanced(self, state: np.ndarray) -> bool:
        r = self.residual(state)
        return bool(np.all(np.isfinite(r)) and np.abs(r).max() < self.enough)

    def nested_from(self, state: np.ndarray) -> np.ndarray | None:
        """Newton over the bodies with the lines settled (system.nested), from ``state``: with
        the linear axial law, its balance judged by the nodes' residual of that law; else with
        the physical law (chain laid slack bends at its touchdown, where the linear law pushes
        a segment), from the linear law's last state, judged by the statics' residual. None
        when neither reaches the tolerance."""
        if not self.nests:
            return None
        p, coords = self.built.params, self.coords
        nodes = np.flatnonzero(coords.kind == 2)
        settled = nested.bodies_newton(p, coords, state, self.limit, self.iterations,
                                       self.tolerance, self.time)  # fmt: skip
        if settled is not None:
            r = self.residual(settled)
            r[nodes] = Residual(p._replace(slack_allowed=0), coords, self.time)(settled)[nodes]
            if np.all(np.isfinite(r)) and np.abs(r).max() < self.enough:
                return settled
        if not p.slack_allowed:
            return None
        settled = nested.bodies_newton(p, coords, state if settled is None else settled,
                                       self.limit, self.iterations, self.tolerance, self.time,
                                       law=int(p.slack_allowed))  # fmt: skip
        return settled if settled is not None and self.balanced(settled) else None

    def towed_from(self, state: np.ndarray) -> np.ndarray | None:
        """A tow's balance from its towed bodies hung below their tow points
        (``initial.towed_hanging``: the relaxation does not move a tow), by Newton over every
        coordinate, else over the bodies; None when neither finds it."""
        hung = towed_hanging(self.built.params, state, self.time)
        if hung is None:
            return None
        direct = _direct(self.built, self.coords, self.sparsity, self.residual, hung,
                         self.iterations, self.tolerance)  # fmt: skip
        if self.balanced(direct):
            return direct
        return self.nested_from(hung)

    def relaxed_from(self, state: np.ndarray, scale: float):
        """The dynamic relaxation from ``state`` (``system.relax``), polished by Newton over
        every coordinate or, where that stalls on a soft mode, over the bodies: (the balance
        or None, the relaxation's end)."""
        built, time = self.built, self.time
        relaxed = relax.relax(built, state, self.residual, 1e-3 * scale,
                              fastest_frequency(built, state, time)[0], time)  # fmt: skip
        if relaxed.rested and relaxed.state is not None:
            polished = _direct(built, self.coords, self.sparsity, self.residual, relaxed.state,
                               self.iterations, self.tolerance)  # fmt: skip
            if self.balanced(polished):
                return polished, relaxed
            if (settled := self.nested_from(relaxed.state)) is not None:
                return settled, relaxed
        return None, relaxed


def _hang(p: kernel.SystemParams, y: np.ndarray, free: np.ndarray, time: float = 0.0,
          iterations: int = 30):  # fmt: skip
    """A first shape of the rigid lines of free trees, from which Newton converges to the
    balance with every segment pulled, not to one of the balances with segments folded back
    and pushed.

    For given loads on the bodies the trees carry at their tips, ``_march`` hangs the lines
    along them. Those loads depend on where the lines put the bodies (a tie, a stiffness, the
    free surface): marching with the loads of each new shape is a fixed point whose gain is
    the load's stiffness times the line's length over its tension (500 N/m x 100 m / 700 N,
    about 70, for an end body tied sideways) and runs away. Instead the tip loads F are the
    unknowns (3 per carried body): Newton on G(F) = own loads at the shape hung on F - F,
    with a finite-difference Jacobian (each column a march), each step halved until |G|
    drops. Loads that do not depend on the position give G = 0 at the first march."""
    tips = np.unique(np.asarray(p.rs_tip)[free & (np.asarray(p.rs_tip) >= 0)])
    w = kernel.make_work(p)
    ydot = np.zeros_like(y)

    def gap(state, loads):
        kernel.rhs(time, state, p, w, ydot)
        return w.own_load[tips].ravel() - loads

    kernel.rhs(time, y, p, w, ydot)
    loads = w.own_load[tips].ravel().copy()
    shaped = _march(p, w, y, free, tips, loads, time)
    g = gap(shaped, loads)
    weights = [float(np.abs(p.rs_wet_weight[p.rs_seg[li] : p.rs_seg[li] + p.rs_n[li]]).sum())
               for li in np.flatnonzero(free)]  # fmt: skip
    scale = float(np.abs(loads).max(initial=0.0)) + sum(weights) + 1.0
    for _ in range(iterations):
        if not g.size or np.abs(g).max() < 1e-10 * scale:
            break
        h = 1e-6 * scale
        jac = np.empty((g.size, g.size))
        for j in range(g.size):
            pushed = loads.copy()
            pushed[j] += h
            jac[:, j] = (gap(_march(p, w, shaped, free, tips, pushed, time), pushed) - g) / h
        step = np.linalg.lstsq(jac, -g, rcond=None)[0]
        for fraction in (1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125):
            trial = loads + fraction * step
            hung = _march(p, w, shaped, free, tips, trial, time)
            gt = gap(hung, trial)
            if np.linalg.norm(gt) < np.linalg.norm(g):
                break
        else:
            break
        loads, shaped, g = trial, hung, gt
    return shaped


def _march(p, w, y, free, tips, loads, time, sweeps: int = 400, tolerance: float = 1e-12):
    """The rigid lines of free trees turned, again and again, along the pull each segment
    carries (system.rigid.moments' march: the statics of a hanging or towed line as a fixed
    point, tension positive), half a step at a time, until they stop turning, the bodies
    ``tips`` carried at their tips loaded by ``loads`` (3 each, N, earth frame) whatever
    their place."""
    ydot = np.zeros_like(y)
    planar = np.asarray(p.rs_kind) == rigid.PLANAR
    width = np.where(planar, 1, 3)
    index = np.concatenate([
        np.arange(p.rs_q[li], p.rs_q[li] + width[li] * p.rs_n[li]) for li in range(len(p.rs_n))
    ])  # fmt: skip
    turned = np.zeros(len(index))
    line_of = np.repeat(np.arange(len(p.rs_n)), width * np.asarray(p.rs_n))
    y = y.copy()
    for _ in range(sweeps):
        kernel.rhs(time, y, p, w, ydot)
        w.own_load[tips] = loads.reshape(-1, 3)
        rigid.moments(p, w, free, turned, True)
        old = y[index]
        new = old.copy()
        for li in np.flatnonzero(free):
            mine = line_of == li
            if planar[li]:  # angles: half the turn, the short way round
                step = np.angle(np.exp(1j * (turned[mine] - old[mine])))
                new[mine] = old[mine] + 0.5 * step
            else:
                half = 0.5 * (old[mine] + turned[mine]).reshape(-1, 3)
                new[mine] = (half / np.linalg.norm(half, axis=1)[:, None]).ravel()
        y[index] = new
        if np.abs(new - old).max() < tolerance:
            break
    return y


def _homotopy(built, coords, sparsity, residual, y, tolerance, enough, smallest: float = 1e-3):
    """Newton's homotopy: the balance of r(x) - (1 - s) r(x0) followed from s = 0 (where the
    start is one) to s = 1, each s from the last one's balance, the step in s halved when
    Newton fails there: loads that the direct Newton cannot take at once (a platform pushed far
    off by a steady force) are taken in stages. Newton goes on in each stage to ``tolerance``
    or as far as rounding lets it; a stage is taken when its residual is below ``enough`` (a
    tolerance below the rounding floor of large forces must not refuse a converged stage)."""
    start = residual(y)
    s, step = 0.0, 0.1
    while s < 1.0 and step >= smallest:
        target = min(1.0, s + step)

        def staged(state, target=target):  # noqa: B023 (bound by the default)
            return residual(state) - (1.0 - target) * start

        trial = _direct(built, coords, sparsity, staged, y, 20, tolerance)
        rt = staged(trial)
        if np.all(np.isfinite(rt)) and np.abs(rt).max() < max(tolerance, enough):
            y, s = trial, target
            step = min(2.0 * step, 0.25)
        else:
            step *= 0.5
    return y


def _direct(built, coords, sparsity, residual, y, iterations, tolerance):
    """Newton over every coordinate; the best state met."""
    structure, colours = sparsity
    r = residual(y)
    best, best_norm = y, float(np.linalg.norm(r))
    limit = _step_limit(built, coords)
    for _ in range(iterations):
        if not np.all(np.isfinite(r)) or np.abs(r).max() < tolerance:
            break
        jac = fd_jacobian(residual, y, coords, structure, colours, r)
        step = shifted_step(jac, r, limit)  # shifted where nothing holds a coordinate
        if step is None:
            break
        largest = float(np.max(np.abs(step) / limit))
        if largest > 1.0:
            step /= largest
        # the first shorter step that lowers the residual, else the whole step: the seabed's
        # contact makes the residual non-smooth and Newton's path to it not monotone
        for fraction in (1.0, 0.5, 0.25, 0.125, 1.0):
            trial = apply(y, coords, fraction * step)
            rt = residual(trial)
            if np.all(np.isfinite(rt)) and np.linalg.norm(rt) < np.linalg.norm(r):
                break
        y, r = trial, rt
        if np.all(np.isfinite(r)) and np.linalg.norm(r) < best_norm:
            best, best_norm = y, float(np.linalg.norm(r))
    return best


def _step_limit(built: BuiltSystem, coords: Coordinates, shortest: bool = False) -> np.ndarray:
    """Largest increment of each coordinate in one Newton step: a tenth of all lines' and
    ties' length (of the ``shortest`` one) for positions (at least 1 m), 0.1 rad for
    rotations, and a quarter of its size
    for a body the free surface cuts (a step must not lift it clear of the water, where
    nothing tells Newton the way back)."""
    p = built.params
    lengths = (
        [
            float(p.seg_length[p.line_seg[i] : p.line_seg[i] + p.line_n[i]].sum())
            for i in range(len(p.line_n))
        ]
        + [float(v) for v in p.tie_length if v > 0]
        + [
            float(p.rs_length[p.rs_seg[i] : p.rs_seg[i] + p.rs_n[i]].sum())
            for i in range(len(p.rs_n))
        ]
    )
    metres = max(1.0, 0.1 * (min(lengths) if shortest else sum(lengths))) if lengths else 1.0
    limit = np.where(is_angle(coords.kind), 0.1, metres)
    for i in np.flatnonzero((coords.kind == 0) & (coords.axis == 2)):
        shape = p.body_shape[coords.body[i]]
        if shape[0] != surface.POINT:
            size = shape[1] if shape[0] == surface.SPHERE else (
                0.5 * shape[2] if shape[0] == surface.CYLINDER else 1.0)  # fmt: skip
            limit[i] = min(limit[i], 0.25 * size)
    return limit


def _blame(built: BuiltSystem, coords: Coordinates, r: np.ndarray, worst: int = -1) -> str:
    """The message that names the body or line out of balance: coordinate ``worst``, by
    default the one whose residual ``r`` is largest."""
    if worst < 0:
        worst = int(np.nanargmax(np.where(np.isfinite(r), np.abs(r), np.inf)))
    if coords.body[worst] >= 0:
        name = built.case.bodies[int(coords.body[worst])].name
        what = ("x", "y", "z")[int(coords.axis[worst])]
        dof = "rotation about" if coords.kind[worst] == 1 else "force along"
        where = f"body '{name}' ({dof} {what}: acceleration {r[worst]:.3g} at rest)"
    elif coords.kind[worst] >= STRAIN:
        where = f"line '{built.layout.natural[int(coords.line[worst])]}'"
    elif coords.kind[worst] >= 3:
        where = f"line '{built.layout.rigid[int(coords.line[worst])]}'"
    else:
        where = f"line '{built.layout.lines[int(coords.line[worst])]}'"
    return (
        f"statics: no equilibrium found; {where} stays out of balance. Check that something "
        "holds every free degree of freedom (a line, a tie, a stiffness or buoyancy against "
        "gravity), that the lines can reach their bodies, or start the run as given "
        "(start: as_given)"
    )


def jacobian(
    built: BuiltSystem, y: np.ndarray, time: float = 0.0
) -> tuple[np.ndarray, Coordinates]:
    """A = d(rates)/d(increments, velocities, force models' states) of the free degrees of
    freedom about ``y`` (dense, central differences): the linearised system dz/dt = A z with
    z = (dx, dv, ds), ds the force models' first-order states (a servo's force; n_s of them,
    last)."""
    built = still_water(built)
    p = built.params
    coords = coordinates(p)
    n, ns, s0 = len(coords.kind), int(p.n_s), int(p.n_q + p.n_v)
    residual = Residual(p, coords, time, balance=False)  # accelerations: dynamics

    def rates(state: np.ndarray) -> np.ndarray:
        return np.concatenate([residual(state), residual.ydot[s0 : s0 + ns]])

    a = np.zeros((2 * n + ns, 2 * n + ns))
    a[:n, n : 2 * n] = np.eye(n)
    for j in range(n):
        h = 1e-6 * (1.0 if is_angle(coords.kind[j : j + 1])[0] else max(1.0, abs(y[coords.q[j]])))
        dx = np.zeros(n)
        dx[j] = h
        a[n:, j] = (rates(apply(y, coords, dx)) - rates(apply(y, coords, -dx))) / (2 * h)
        hv = 1e-6 * max(1.0, abs(y[coords.v[j]]))
        up, down = y.copy(), y.copy()
        if coords.kind[j] == 3:  # the director's rate along its turn's direction
            at = coords.v[j] + np.arange(3)
            step = hv * tangents(y, coords, np.array([j]))[0]
            up[at] += step
            down[at] -= step
        elif coords.kind[j] == TURN:  # a string's tangent's rate along n
            at = coords.v[j] + np.arange(2)
            step = hv * tangent_normals(y, coords, np.array([j]))[0]
            up[at] += step
            down[at] -= step
        else:
            up[coords.v[j]] += hv
            down[coords.v[j]] -= hv
        a[n:, n + j] = (rates(up) - rates(down)) / (2 * hv)
    for k in range(ns):
        hs = 1e-6 * max(1.0, abs(y[s0 + k]))
        up, down = y.copy(), y.copy()
        up[s0 + k] += hs
        down[s0 + k] -= hs
        a[n:, 2 * n + k] = (rates(up) - rates(down)) / (2 * hs)
    return a, coords


def line_loads(built: BuiltSystem, y: np.ndarray, at_rest: bool = False,
               time: float = 0.0) -> np.ndarray:  # fmt: skip
    """(bodies, 6): force [N] and moment about the reference point [N m] of every body's lines
    and ties at the state ``y``, earth frame.

    By default as the results report them (``line_force_*``, ``line_moment_*``): each lumped
    line's end force is its end node's loads less the node's mass times its point's
    acceleration (the node moves with the body). ``at_rest``: the static loads of the lines
    held at ``y``, without that inertia: each lumped line's end-node loads (its end segment's
    tension, half the segment's weight and buoyancy, the seabed's) and each tie's force (a
    rigid-segment line's end forces as in the results). A held body's acceleration at a pose
    out of balance comes from its own force models, and must not enter its lines' loads."""
    p = built.params
    w = kernel.make_work(p)
    row = outputs.at(p, y, time, w)
    bodies, rigid = row.bodies, row.rigid
    if not at_rest:
        return bodies[0, :, 12:18].copy()
    # every end force on a point (N, earth frame): lumped lines' from and to ends, ties'
    # from (+) and to (-) ends, rigid lines' from and to ends
    points = np.concatenate([p.line_from, p.line_to, p.tie_from, p.tie_to, p.rs_from, p.rs_to])
    forces = np.concatenate([w.end_load[:, 0], w.end_load[:, 1], w.tie_force, -w.tie_force,
                             rigid[2][0, :, 0], rigid[2][0, :, 1]])  # fmt: skip
    points = np.asarray(points, dtype=np.int64)
    loads = np.zeros((len(p.body_kind), 6))
    on = np.asarray(p.point_body)[points]
    np.add.at(loads[:, :3], on, forces)
    np.add.at(loads[:, 3:], on, np.cross(w.parm[points], forces))
    return loads


def mooring_stiffness(
    built: BuiltSystem, y: np.ndarray, body: str, translation: float = 1e-2,
    rotation: float = 1e-4, span: float | None = None, symmetric: bool = True,
) -> np.ndarray:  # fmt: skip
    """The 6x6 stiffness of the lines and ties on ``body`` about the state ``y`` (a static
    equilibrium) [N/m, N/rad; N m/m, N m/rad]: the Hessian of the lines' and ties' potential
    energy in the coordinates x (the reference point's position, earth frame) and theta (the
    rotation vector of R R_y^T, earth frame) at theta = 0, symmetric. With F the force and M
    the moment about the reference point of the lines and ties at rest (``line_loads(...,
    at_rest=True)``, earth frame): K[:, x] = -d(F, M)/dx, K[x, theta] = -dF/dtheta (equal to
    -dM/dx transposed), and K[theta, theta] = -dM/dtheta - [M x] / 2: the moment's own tangent
    under a rotation is not symmetric where the lines exert a moment M on the body (the
    generalized force of theta is J(theta)^T M, J the rotation's Jacobian, whose derivative
    adds half the skew matrix of M); ``symmetric=False`` returns that tangent, -d(F, M)/d(x,
    theta), instead. The two are equal at a pose where the lines exert no moment. The body's
    pose is moved by +-``translation`` [m] and +-``rotation`` [rad]
    in turn, every line's interior nodes re-solved at rest with every body held (the other
    bodies do not follow: their own stiffness is not included), and the loads differenced
    (central differences). The body's own force models (hydrostatics, weight) are not in K;
    MoorPy's ``lines_only`` stiffness is its analogue.

    ``span`` [m]: the translation columns as secants over +-``span`` instead (the pose moved
    there in steps of at most 0.25 m, the lines re-solved at each). A lumped line's tangent
    stiffness is a sawtooth along the pose: each time a node lifts off (or lands on) the
    seabed the slope drops (or jumps), by up to +-20 % of the heave stiffness for 10 m
    segments, about a continuous catenary's (-3 % in surge and -7 % in heave at the platform
    example's balance); a span of about one node spacing of touchdown travel averages it out
    (+-5 m: the platform example's surge and heave within 0.05 % of MoorPy's secants over the
    same poses at 70 segments, 0.2 % at 140). Rotations stay tangent (``rotation``).

    Raises StaticsError when a line's interior nodes are not in balance after re-solving
    (their largest acceleration above 1e-7 g) or when a rigid-segment line is on ``body``
    (not re-solved here)."""
    p = built.params
    b = built.layout.bodies.index(body)
    if p.body_kind[b] != kinematics.DYNAMIC or not p.body_rigid[b]:
        raise ValueError(f"mooring_stiffness: body '{body}' is not a rigid (6-DOF) body")
    for li in range(len(p.rs_n)):
        if b in (p.point_body[p.rs_from[li]], p.point_body[p.rs_to[li]]):
            raise StaticsError(
                f"mooring_stiffness: body '{body}' carries the rigid-segment line "
                f"'{built.layout.rigid[li]}', whose segments are not re-solved at the moved "
                "poses; compute the stiffness of a body whose lines are lumped_mass lines"
            )
    q = int(p.body_q[b])
    y = y.copy()
    y[p.n_q :] = 0.0
    stiffness = np.zeros((6, 6))
    for j in range(6):
        h = rotation if j >= 3 else (translation if span is None else span)
        steps = 1 if j >= 3 else max(1, int(np.ceil(h / 0.25 - 1e-9)))  # of 0.25 m at most
        loads = []
        for sign in (1.0, -1.0):
            moved = y.copy()
            for _ in range(steps):
                if j < 3:
                    moved[q + j] += sign * h / steps
                else:
                    theta = np.zeros(3)
                    theta[j - 3] = sign * h / steps
                    moved[q + 3 : q + 7] = rotate(moved[q + 3 : q + 7], theta)
                moved = _settle(built, moved, body)
            loads.append(line_loads(built, moved, at_rest=True)[b])
        stiffness[:, j] = -(loads[0] - loads[1]) / (2.0 * h)
    if symmetric:
        m = line_loads(built, _settle(built, y, body), at_rest=True)[b][3:]
        stiffness[3:, 3:] -= 0.5 * np.array([[0.0, -m[2], m[1]], [m[2], 0.0, -m[0]],
                                             [-m[1], m[0], 0.0]])  # fmt: skip
    return stiffness


def _settle(built: BuiltSystem, y: np.ndarray, body: str, attempts: int = 3) -> np.ndarray:
    """``y`` with every lumped line's interior nodes in balance at rest (``settle_lines``, the
    linear axial law), their largest acceleration at most 1e-7 g: each line's end loads then
    err by at most about 1e-7 of its weight. Newton is run again from its last state when it
    stopped short (it can stall where a node sits on the seabed's kink); StaticsError naming
    the line when it does not get there."""
    p = built.params
    allowed = 1e-7 * p.gravity
    ydot = np.zeros_like(y)
    worst = np.zeros(len(p.line_n))
    for _ in range(attempts):
        y = settle_lines(p, y)
        kernel.rhs(0.0, y, p._replace(slack_allowed=0), kernel.make_work(p), ydot)
        for li in range(len(p.line_n)):
            v = int(p.line_v[li])
            worst[li] = np.abs(ydot[v : v + 3 * (int(p.line_n[li]) - 1)]).max(initial=0.0)
        if np.all(worst <= allowed):
            return y
    li = int(np.argmax(np.where(np.isfinite(worst), worst, np.inf)))
    raise StaticsError(
        f"mooring_stiffness: line '{built.layout.lines[li]}' not in balance at a moved pose of "
        f"body '{body}' (interior node acceleration {worst[li]:.3g} m/s^2 after {attempts} "
        f"solves, allowed {allowed:.3g}); use fewer segments, or another translation or span"
    )
