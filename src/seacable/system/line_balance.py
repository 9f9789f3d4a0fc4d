"""The static balance of the lumped-mass lines' interior nodes between their ends as they
are: Newton on the nodes' accelerations with a block-banded finite-difference Jacobian (9
evaluations per Jacobian whatever the size), with the linear axial law (smooth; chain lying on
a frictionless seabed has one shape), EA stages and pseudo-transient steps when Newton alone
does not settle (``static_lines``: a run's first shapes), or Newton alone from a nearby state
(``settle_lines``: the statics' trial poses); a tow's steady motion (``steady_velocities``);
how hard the linear law pushes a segment (``pushed``)."""

import logging

import numpy as np
from scipy.linalg import solve_banded

from seacable.bodies import kinematics
from seacable.lines.lumped_mass import T_ROW
from seacable.system import kernel
from seacable.system.pseudo_time import PseudoTime

log = logging.getLogger(__name__)


def _interior(p, at, lines=None):
    """State indices of every interior node position (``at`` = p.line_q) or velocity
    (p.line_v), in line order (of the ``lines`` given, by default all)."""
    lines = range(len(p.line_n)) if lines is None else lines
    parts = [np.arange(at[li], at[li] + 3 * (p.line_n[li] - 1)) for li in lines]
    return np.concatenate(parts) if parts else np.zeros(0, dtype=np.int64)


def steady_velocities(p: kernel.SystemParams, y: np.ndarray, time: float = 0.0) -> np.ndarray:
    """The velocities (``y[n_q:n_q + n_v]``) of a steady motion at ``time``: when every fixed or
    imposed body moves with one velocity V and none turns (a ship towing at constant speed, and
    nothing fixed; a body that holds no line or tie, such as a servo's target, does not count),
    every dynamic body and every lumped line's interior node moves with V, and rigid
    lines do not turn (their nodes move with their bases); otherwise everything at rest.
    The statics then balances the loads of that motion (drag on the velocity relative to the
    current): the steady tow, which stays steady while the kinematic bodies keep V."""
    w = kernel.make_work(p)
    moving = y.copy()
    moving[p.n_q : p.n_q + p.n_v] = 0.0
    kernel.rhs(time, moving, p, w, np.zeros_like(y))
    kinematic = np.intersect1d(np.flatnonzero(np.asarray(p.body_kind) <= kinematics.IMPOSED),
                               _holding(p))  # fmt: skip
    v = np.zeros(p.n_v)
    if not kinematic.size:
        return v
    velocity = w.vel[kinematic]
    common = velocity[0]
    scale = float(np.abs(velocity).max())
    if scale == 0.0 or np.abs(velocity - common).max() > 1e-12 * scale:
        return v
    if np.abs(w.omega[kinematic]).max() > 0.0:
        return v
    for b in np.flatnonzero(np.asarray(p.body_kind) == kinematics.DYNAMIC):
        v[p.body_v[b] - p.n_q : p.body_v[b] - p.n_q + 3] = common
    for li in range(len(p.line_n)):
        first = p.line_v[li] - p.n_q
        v[first : first + 3 * (p.line_n[li] - 1)] = np.tile(common, p.line_n[li] - 1)
    return v


def _holding(p: kernel.SystemParams) -> np.ndarray:
    """The bodies that hold a line or tie end (a body that holds nothing, such as a servo's
    target vehicle, moves as it likes without making a steady motion unsteady)."""
    points = np.concatenate([np.asarray(a, dtype=np.int64) for a in (
        p.line_from, p.line_to, p.tie_from, p.tie_to, p.rs_from, p.rs_to, p.nat_from)])  # fmt: skip
    bodies = np.asarray(p.point_body, dtype=np.int64)[points]
    tips = np.asarray(p.rs_tip, dtype=np.int64)
    return np.union1d(bodies, tips[tips >= 0])


def static_lines(p, y0, iterations: int = 30, time: float = 0.0,
                 warn: bool = True) -> np.ndarray:  # fmt: skip
    """Every line's interior nodes at rest in balance (in a tow's steady motion:
    ``steady_velocities``), bodies held where they are at ``time`` [s]: Newton on the nodes'
    accelerations from ``y0`` (a catenary start is near the balance), else with EA raised in
    steps of ten from a thousandth of its value (a nearly inextensible line makes Newton's steps
    erratic from a straight start), each stage from the last one's result, else the first
    Newton continued. When none settles (every node's acceleration below 1e-6 g), the one
    nearest the balance, with a warning (``warn``: a run starts from it; a statics, which
    goes on to the balance, says nothing). Forward differences
    here (``_newton``): with central ones, Newton converges from the catenary start of a lumped
    servo tow (tests/test_upgrade_gaps.py, lumped_servo_tow) to a balance of the linear law
    with segments pushed at 1.9 kN, where the forward one stays near the taut towed shape that
    the statics' Newton then finishes."""
    linear = p._replace(slack_allowed=0)
    if p.seabed_band > 0.0:
        # the whole search on the plain spring first, then continued to the band (see
        # _newton); else each Newton of the search continued so
        plain = _static_lines(linear._replace(seabed_band=0.0), y0, iterations, time)[0]
        continued = _newton_at(linear, plain, iterations, time)
        if _settled(linear, continued, time) and not _pushes(linear, continued, time):
            return continued
    best, left = _static_lines(linear, y0, iterations, time, _newton)
    if left is not None and warn:
        log.warning(
            "the lines' initial static shapes are out of balance by %.3g m/s^2 at some node "
            "(Newton from the catenary start and from EA stages both stopped short)",
            left,
        )
    return best


def _static_lines(linear, y0, iterations, time, newton=None):
    """static_lines' search with the parameters ``linear`` (the linear axial law) by
    ``newton`` (default ``_newton_at``, on one seabed law): the balance, and None; or the
    state nearest it, and its largest node acceleration [m/s^2]."""
    newton = newton or _newton_at

    def balanced(state) -> bool:
        # a balance of the linear law with pushed segments is none of the line's: the EA
        # stages found one of a zigzag chain, its segments 21 to 29 m of 25 m at 208 MN
        # (examples/turret_fpso_catenary_mooring.yaml's chain_3)
        return _settled(linear, state, time) and not _pushes(linear, state, time)

    direct = newton(linear, y0, iterations, time)
    if balanced(direct):
        return direct, None
    y = y0.copy()
    target = linear.seg_stiffness
    for factor in (1e-3, 1e-2, 1e-1, 1.0):
        stage = linear._replace(seg_stiffness=np.ascontiguousarray(target * factor))
        y = newton(stage, y, iterations, time)
    if balanced(y):
        return y, None
    # Newton from the start again, longer (a catenary start can need some 40 iterations; tried
    # last because the stages keep the lines taut where a long Newton may not)
    longer = newton(linear, direct, 2 * iterations, time)
    if balanced(longer):
        return longer, None
    # pseudo-transient steps: chain lying slack (a line longer than its span and rise) holds
    # nothing across it, where Newton's matrix is singular
    relaxed = _newton_at(linear, y0, 10 * iterations, time, pseudo=True)
    if balanced(relaxed):
        return relaxed, None
    tried = [(_pushes(linear, state, time), _unbalance(linear, state, time), k, state)
             for k, state in enumerate((direct, y, longer, relaxed))]  # fmt: skip
    _, left, _, best = min(tried)  # the nearest balance, one that pushes no segment first
    return best, left


def _unbalance(p, y, time: float = 0.0, lines=None) -> float:
    """The largest interior node's acceleration at rest [m/s^2] (of ``lines``, default all)."""
    index = _interior(p, p.line_v, lines)
    if not len(index):
        return 0.0
    ydot = np.zeros_like(y)
    kernel.rhs(time, _at_rest(p, y, time), p, kernel.make_work(p), ydot)
    return float(np.abs(ydot[index]).max())


def _pushes(p, y, time: float = 0.0) -> bool:
    """Whether a lumped segment is pushed at rest (``pushed``): a balance of the linear axial
    law that the physical law has not."""
    w = kernel.make_work(p)
    kernel.rhs(time, _at_rest(p, y, time), p, w, np.zeros_like(y))
    return pushed(p, w) > 0.0


def _at_rest(p, y, time: float = 0.0) -> np.ndarray:
    """A copy of ``y`` at rest: no velocities, or in a tow its steady motion
    (``steady_velocities``), whose drag the lines carry; force models' states zero."""
    at_rest = y.copy()
    at_rest[p.n_q :] = 0.0
    at_rest[p.n_q : p.n_q + p.n_v] = steady_velocities(p, at_rest, time)
    return at_rest


def _settled(p, y, time: float = 0.0) -> bool:
    """True when every interior node's acceleration at rest is below 1e-6 g."""
    return _unbalance(p, y, time) < 1e-6 * p.gravity


def settle_lines(p, y0, iterations: int = 30, slack: int = 0, time: float = 0.0) -> np.ndarray:
    """Every line's interior nodes at rest in balance (in a tow's steady motion) at ``time``
    [s] from a nearby state (no EA stages: the outer loop of the system's statics, whose lines
    start each time from their last balance, their nodes carried along with their moved ends),
    with the axial law ``slack`` (kernels.lumped.segment_loads: 0 linear); Newton with central
    differences."""
    stage = p._replace(slack_allowed=slack)
    return _newton(stage, y0, iterations, time, central=True)


def settle_each(p, y0, iterations: int = 30, slack: int = 0, time: float = 0.0,
                tolerance: float = 1e-6) -> np.ndarray:  # fmt: skip
    """``settle_lines`` line by line (a line whose Newton stalls does not hold back the
    others' line search), each line that Newton leaves above ``tolerance`` g (as
    ``static_lines``: each node's force off by that share of its weight; a hanging part
    at zero tension, chain lying slack: Newton's matrix singular across it) continued by
    pseudo-transient steps (system.pseudo_time), from where Newton stopped and, when that does
    not reach it, from the line's start; its nodes as they were when those do not get nearer
    the balance either."""
    stage = p._replace(slack_allowed=slack)
    y = y0.copy()
    allowed = tolerance * p.gravity
    for li in range(len(p.line_n)):
        start = y
        y = _newton(stage, start, iterations, time, central=True, lines=[li])
        left = _unbalance(stage, y, time, [li])
        # from where Newton stopped, else from the line's start: Newton's long steps may
        # fold the line where the pseudo-time steps stall (a nearly slack line whose
        # touchdown bends within a segment)
        for origin in (y, start):
            if left < allowed:
                break
            relaxed = _newton_at(stage, origin, 10 * iterations, time, pseudo=True, lines=[li])
            relaxed = _newton_at(stage, relaxed, iterations, time, central=True, lines=[li])
            if (unbalance := _unbalance(stage, relaxed, time, [li])) < left:
                y, left = relaxed, unbalance
    return y


def pushed(p, w, share: float = 1e-6) -> float:
    """How hard [N] the most compressed segment of the lumped lines is pushed at the last
    evaluation into the workspace ``w`` under the linear axial law (0 when none is, or by no
    more than a strain of 1e-8 or 1e-6 of the largest tension). That law, which the static
    solves use (smooth; chain lying on a frictionless seabed has one shape), has balances the
    physical law has not: chain laid straight and pushed, on the seabed or in a tow's bight."""
    if not len(p.line_n):
        return 0.0
    segments = np.concatenate([np.arange(p.line_node[li], p.line_node[li] + p.line_n[li])
                               for li in range(len(p.line_n))])  # fmt: skip
    tension = w.nodes[T_ROW, segments]
    allowed = max(1e-8 * float(np.max(p.seg_stiffness)), share * float(tension.max()))
    compression = -float(tension.min())
    return compression if compression > allowed else 0.0


def _newton(p, y0, iterations, time: float = 0.0, central: bool = False, lines=None):
    """``_newton_at``; with a seabed contact band (kernels.lumped.seabed_spring), first with
    the plain spring and then from its balance with the band: the band's soft foot makes
    Newton's long first steps wander where the plain spring's did not (two moored buoys'
    statics found no balance with a 5 mm band); from the plain spring's balance the lying
    nodes sink by about half the band, where the law is linear, and Newton takes a step or
    two. ``static_lines`` continues its whole search so (an eight-segment chain from its
    catenary start, whose first Newton fails, folded into a zigzag of the linear law on the
    band, at 63 MN)."""
    if p.seabed_band > 0.0:
        y0 = _newton_at(p._replace(seabed_band=0.0), y0, iterations, time, central, lines=lines)
    return _newton_at(p, y0, iterations, time, central, lines=lines)


def _banded_jacobian(residual, y, index, r, central: bool, half: int) -> np.ndarray:
    """The lines' interior nodes' block-tridiagonal Jacobian in banded storage, by forward or
    ``central`` differences in 9 colours of columns (see ``_newton_at``)."""
    m = len(index)
    ab = np.zeros((2 * half + 1, m))
    for colour in range(9):
        columns = np.arange(colour, m, 9)
        if central:  # in metres (see _newton_at)
            step = np.full(len(columns), 1e-6)
        else:
            step = 1e-7 * np.maximum(1.0, np.abs(y[index[columns]]))
        trial = y.copy()
        trial[index[columns]] += step
        if central:
            dr = residual(trial)
            trial[index[columns]] -= 2.0 * step
            dr = 0.5 * (dr - residual(trial))
        else:
            dr = residual(trial) - r
        # each column's rows: its node's and its two neighbours' (9, those inside)
        rows = 3 * (columns // 3 - 1)[:, None] + np.arange(9)[None, :]
        cols = np.broadcast_to(columns[:, None], rows.shape)
        inside = (rows >= 0) & (rows < m)
        rows, cols = rows[inside], cols[inside]
        steps = np.broadcast_to(step[:, None], inside.shape)[inside]
        ab[half + rows - cols, cols] = dr[rows] / steps
    return ab


def _newton_at(p, y0, iterations, time: float = 0.0, central: bool = False,
               pseudo: bool = False, lines=None):  # fmt: skip
    """The lines' interior nodes in balance by Newton, its block-tridiagonal Jacobian by forward
    differences (steps 1e-7 of each coordinate) or ``central`` ones (1e-6 m; two residuals per
    colour), either stopping once the step is at the positions' rounding, the residual's floor
    (forward ones went on to the last iteration there: the spread mooring of
    benchmarks/vs_moordyn_spread.py, 50 segments a line, settled to 2e-9 m/s^2 in 4 and 6
    iterations of its two Newtons, above the 1e-10 g asked, and ran 30 each; its start took
    45.8 ms and now 9.3, the nodes within 1e-13 m). The
    central steps are in metres, not shares of the coordinates: a node 400 m from the origin
    moved by 4e-4 m, a share of 1e-6, crossed the seabed's contact of light line (polyester
    lying on a 3e5 Pa seabed sinks by 0.1 mm) and Newton lost its way
    (benchmarks/statics_success.py); the forward ones stay shares (with steps of 1e-7 m,
    ``static_lines`` found the pushed balance of a lumped tow, tests/test_upgrade_gaps.py).
    Forward differences err by EA h / (2 l^2) on a taut segment's transverse stiffness T / l
    (17 % for a 2e8 N wire at 9 kN in 1.3 m segments) and Newton then creeps; ``static_lines``
    keeps them (see there), ``settle_lines`` takes central ones. ``pseudo``: the steps of
    pseudo-transient continuation (system.pseudo_time), for chain lying slack on the seabed,
    which holds nothing across it (Newton's matrix is singular there). ``lines``: the lines
    solved (default all), the others held as they are."""
    index = _interior(p, p.line_q, lines)
    m = len(index)
    if m == 0:
        return y0.copy()
    w = kernel.make_work(p)
    ydot = np.zeros_like(y0)
    velocity = _interior(p, p.line_v, lines)  # the accelerations sit at the velocities' offsets

    def residual(y):
        kernel.rhs(time, y, p, w, ydot)
        return ydot[velocity].copy()

    y = _at_rest(p, y0, time)
    r = residual(y)
    best, best_norm = y, np.linalg.norm(r)
    scale = float(np.abs(r).max()) + 1e-6
    half = 5  # block-tridiagonal with 3 x 3 blocks: 5 diagonals either side
    clock: PseudoTime | None = None
    for _ in range(iterations):
        if np.abs(r).max() < max(1e-12 * scale, 1e-10 * p.gravity):
            break
        ab = _banded_jacobian(residual, y, index, r, central, half)
        if not np.isfinite(ab).all():
            break  # the lines went where their loads are not finite: keep the best state met
        if pseudo:
            if clock is None:  # a step moves a node by a metre at most, at first
                clock = PseudoTime(r, 1.0, 1e-10 * float(np.abs(ab[half]).max()))
            ab[half] -= clock.shift
        try:
            delta = solve_banded((half, half), ab, -r)
        except np.linalg.LinAlgError:
            break  # singular: chain lying slack holds nothing across it; keep the best state
        damping = 1.0
        if clock is not None:
            trial = y.copy()
            trial[index] += delta
            rt = residual(trial)
            if not np.all(np.isfinite(rt)) or np.linalg.norm(rt) > np.linalg.norm(r):
                clock.rejected()
                continue
            clock.accepted(float(np.linalg.norm(r)), float(np.linalg.norm(rt)))
        else:
            # the seabed's contact is not smooth: when no shorter step lowers the residual,
            # the full step is taken anyway, and the best state met is kept
            for damping in (1.0, 0.5, 0.25, 0.1, 1.0):
                trial = y.copy()
                trial[index] += damping * delta
                rt = residual(trial)
                if np.linalg.norm(rt) < np.linalg.norm(r):
                    break
        y, r = trial, rt
        if np.linalg.norm(r) < best_norm:
            best, best_norm = y, np.linalg.norm(r)
        moved = damping * np.abs(delta).max()
        if not pseudo and moved <= 1e-12 * (1.0 + np.abs(y[index]).max()):
            break  # the residual is at its rounding floor: no step moves a node any more
    best = best.copy()
    best[p.n_q :] = y0[p.n_q :]
    return best
