"""Every static equilibrium of a system in the horizontal plane for a given weather, and the
stability of each from the eigenvalues of the linearised system.

The equilibria are found by Newton's method on the accelerations at rest (``plane.balance``)
from many starts:

- scanned starts (``_scanned_starts``): each body placed so that its tie balances the loads
  it carries (``_balanced``: its forces balance at any headings), and the roots of the
  moments found body by body, by a scan of ``SCAN`` headings refined by Brent's method. When
  every free body hangs on a chain of ties from a fixed one and the loads at rest depend on
  the headings only, these are every equilibrium (to the scan's resolution); otherwise they
  are starts like any other;
- a grid of headings for each free body, each body placed the same way, unless every scanned
  start balances already (the scan's premise held: ``_settled``);
- the case's own start, and any the caller gives (a map's neighbours).

Newton's solutions are merged when they are within a millimetre and a microradian of each
other, and each is kept only when its force and moment balance holds to round-off
(``BALANCED``, relative to the largest tie tension or force of a force model there).
The linearisation df/dx (``plane.jacobian``) gives the eigenvalues: an equilibrium is stable
when every real part is below -``STABLE`` |lambda| (or 1e-9 1/s).
"""

import itertools
import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from seacable.forces import compensator
from seacable.stability.plane import Plane, Weather, balance

BALANCED = 1e-9  # the weighted residual, relative to the bodies' largest loads
CONVERGED = 1e-11  # Newton stops there (round-off is about 1e-13)
STABLE = 1e-7  # Re(lambda) below -STABLE |lambda| (or 1e-9 1/s): stable
SAME_POSITION, SAME_ANGLE = 1e-3, 1e-6  # [m], [rad]: one equilibrium
SCAN = 72  # headings a body's moment is scanned at (``_scanned_starts``)
SETTLED = 1e-6  # a scanned start's residual, relative to its ties' tensions: the scan held


@dataclass
class Equilibrium:
    """One equilibrium: the positions x (3 per body: x [m], y [m], psi [rad], psi in (-pi,
    pi]), the eigenvalues [1/s] of df/dx, its residual (weighted, relative) and how many starts
    reached it."""

    x: np.ndarray
    eigenvalues: np.ndarray
    residual: float
    hits: int

    @property
    def stable(self) -> bool:
        lam = self.eigenvalues
        return bool(np.all(lam.real < -np.maximum(STABLE * np.abs(lam), 1e-9)))

    @property
    def neutral(self) -> bool:
        """Not stable, but no eigenvalue grows: every real part within the tolerance of zero
        (the ships in still water, with nothing to damp them, and free to lie at any
        heading)."""
        lam = self.eigenvalues
        return not self.stable and bool(np.all(lam.real <= np.maximum(STABLE * np.abs(lam), 1e-9)))

    @property
    def kind(self) -> str:
        """ "stable", "neutral" (``neutral``), or "unstable" with how: "divergent" (a real
        eigenvalue > 0), "oscillatory" (only complex ones), or both."""
        if self.stable:
            return "stable"
        if self.neutral:
            return "neutral"
        lam = self.eigenvalues
        bad = lam[lam.real >= -np.maximum(STABLE * np.abs(lam), 1e-9)]
        real = np.any(np.abs(bad.imag) <= 1e-9 * np.maximum(np.abs(bad), 1e-12))
        complex_ = np.any(np.abs(bad.imag) > 1e-9 * np.maximum(np.abs(bad), 1e-12))
        return "unstable: " + ("divergent and oscillatory" if real and complex_
                               else "divergent" if real else "oscillatory")  # fmt: skip


def _wrap(angle):
    return (np.asarray(angle) + math.pi) % (2.0 * math.pi) - math.pi


def _points(plane: Plane, x: np.ndarray):
    """Every point's earth-frame (x, y) with the free bodies at positions ``x``."""
    p = plane.built.params
    pose = np.zeros((p.body_kind.shape[0], 3))  # x, y, psi
    for b in range(p.body_kind.shape[0]):
        quat = p.body_pose[b, 3:7]
        pose[b] = p.body_pose[b, 0], p.body_pose[b, 1], 2 * math.atan2(quat[3], quat[0])
    for j, b in enumerate(plane.bodies):
        pose[b] = x[3 * j : 3 * j + 3]
    return pose


def _turn(psi: float, vector) -> np.ndarray:
    """``vector`` (x, y) turned by ``psi`` [rad] about z."""
    c, s = math.cos(psi), math.sin(psi)
    return np.array([c * vector[0] - s * vector[1], s * vector[0] + c * vector[1]])


def relative(plane: Plane, x: np.ndarray) -> np.ndarray:
    """Each free body's pose (3 per body: x, y [m], psi [rad] in (-pi, pi]) relative to the
    body its tie holds it by (``_tie_order``), in that body's frame; a body held by none, its
    own. Two equilibria of ships that weathervane together compare by these: how the ships
    lie to each other, not where the weather turned them."""
    pose = _points(plane, x)
    p = plane.built.params
    out = np.asarray(x, dtype=float)[: 3 * len(plane.bodies)].copy()
    for j, tie in _tie_order(plane):
        if tie is None:
            continue
        b, a = int(plane.bodies[j]), int(p.point_body[tie[1]])
        out[3 * j : 3 * j + 2] = _turn(-pose[a, 2], pose[b, :2] - pose[a, :2])
        out[3 * j + 2] = _wrap(pose[b, 2] - pose[a, 2])
    return out


def placed(plane: Plane, x: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """Positions with each free body that a tie holds to another free body at its pose in
    ``poses`` (``relative``'s) relative to that body, the others as in ``x``: the ships as
    at their nominal places, for instance, around the FPSO where the weather turned it."""
    out = np.asarray(x, dtype=float)[: 3 * len(plane.bodies)].copy()
    p = plane.built.params
    free = {int(b) for b in plane.bodies}
    for j, tie in _tie_order(plane):  # the bodies holding others first
        if tie is None or int(p.point_body[tie[1]]) not in free:
            continue
        parent = _points(plane, out)[int(p.point_body[tie[1]])]
        out[3 * j : 3 * j + 2] = parent[:2] + _turn(parent[2], poses[3 * j : 3 * j + 2])
        out[3 * j + 2] = _wrap(parent[2] + poses[3 * j + 2])
    return out


def _tie_order(plane: Plane) -> list[tuple[int, tuple[int, int, int] | None]]:
    """The free bodies (their index j) in an order their ties allow: each with its tie to a
    body placed before it (its point, the other point, the tie's index), or None (a body not
    tied to one: it stays where the case puts it)."""
    p = plane.built.params
    free = {int(b): j for j, b in enumerate(plane.bodies)}
    placed = {b for b in range(p.body_kind.shape[0]) if b not in free}
    order: list[tuple[int, tuple[int, int, int] | None]] = []
    while len(order) < len(free):
        for b, j in free.items():
            if b in placed:
                continue
            tie = _tie_to_placed(p, b, placed)
            if tie is not None:
                order.append((j, tie))
                placed.add(b)
                break
        else:  # the rest are not tied to a placed body
            order += [(j, None) for b, j in free.items() if b not in placed]
            break
    return order


def _stretch(p, k: int, tension: float) -> float:
    """The elongation [m] of tie ``k`` at ``tension`` [N] (its table's or its stiffness's; its
    last slope beyond its table)."""
    count = int(p.tie_count[k])
    if count == 0:
        return tension / p.tie_stiffness[k] if p.tie_stiffness[k] > 0.0 else 0.0
    rows = p.tie_table[int(p.tie_first[k]) : int(p.tie_first[k]) + count]
    if tension <= rows[-1, 1] or count < 2:
        return float(np.interp(tension, rows[:, 1], rows[:, 0]))
    slope = (rows[-1, 0] - rows[-2, 0]) / max(rows[-1, 1] - rows[-2, 1], 1e-30)
    return float(rows[-1, 0] + slope * (tension - rows[-1, 1]))


def _tension(p, k: int, elongation: float) -> float:
    """The tension [N] of tie ``k`` at ``elongation`` [m], at rest (``lines.tie.tension``'s
    law: its table's, or its stiffness's; its last slope beyond its table)."""
    if elongation <= 0.0:
        return 0.0
    count = int(p.tie_count[k])
    if count == 0:
        return float(p.tie_stiffness[k] * elongation)
    rows = p.tie_table[int(p.tie_first[k]) : int(p.tie_first[k]) + count]
    if elongation <= rows[-1, 0] or count < 2:
        return max(float(np.interp(elongation, rows[:, 0], rows[:, 1])), 0.0)
    slope = (rows[-1, 1] - rows[-2, 1]) / (rows[-1, 0] - rows[-2, 0])
    return float(rows[-1, 1] + slope * (elongation - rows[-1, 0]))


@dataclass(frozen=True)
class _Held:
    """A free body that an enabled compensator holds on the tie it hangs by (its ``point`` and
    ``target`` the tie's two ends): at an equilibrium where it does not saturate, the
    compensator's errors are zero, so the tie is ``distance`` [m] long and carries
    ``tension`` [N], and the body's heading is ``offset`` [rad] off the target body's
    (``line_of_sight`` False) or off the bearing of the target point (True)."""

    line_of_sight: bool
    distance: float
    offset: float
    tension: float


def _held(plane: Plane, order) -> dict[int, _Held]:
    """The free bodies (by j) held by an enabled compensator on the tie they hang by."""
    p = plane.built.params
    ties = {j: tie for j, tie in order if tie is not None}
    index = {int(b): j for j, b in enumerate(plane.bodies)}
    out = {}
    for f in p.compensator:
        row = p.force_data[p.force_at[f] : p.force_at[f] + compensator.ROW]
        j = index.get(int(p.force_body[f]), -1)
        tie = ties.get(j)
        if row[compensator.ENABLED] == 0.0 or tie is None:
            continue
        if (int(row[compensator.POINT]), int(row[compensator.TARGET])) != tie[:2]:
            continue
        distance = float(row[compensator.DISTANCE])
        tension = _tension(p, tie[2], distance - float(p.tie_length[tie[2]]))
        if tension > 0.0:
            out[j] = _Held(bool(row[compensator.LOS]), distance, float(row[compensator.HEADING]),
                           tension)  # fmt: skip
    return out


def _place(plane: Plane, x: np.ndarray, j: int, tie, direction) -> None:
    """Put body j (in ``x``, at its heading there) with its tie point ``tie[0]`` at the other
    point plus ``direction`` (a vector [m], earth frame)."""
    p = plane.built.params
    here, there, _ = tie
    pose = _points(plane, x)
    ab = p.point_body[there]
    anchor = pose[ab, :2] + _turn(pose[ab, 2], p.point_offset[there])
    x[3 * j : 3 * j + 2] = anchor + direction - _turn(x[3 * j + 2], p.point_offset[here])


def _balanced(plane: Plane, x: np.ndarray, order, held: dict[int, _Held] | None = None,
              branch: dict[int, int] | None = None) -> bool:  # fmt: skip
    """Place the tied bodies in ``x`` (in place, at their headings there; ``order``:
    ``_tie_order``) so that each tie balances the loads it carries: with every tie slack, each
    body's own load at rest (current, wind, thrust at its heading) is summed over the bodies it
    holds up the chain of ties, and the tie is laid along that sum, stretched to carry it. A
    body's forces then balance; only its moment is left (module docstring).

    A body ``held`` by its compensator (``_held``) is put where the compensator's errors are
    zero instead: its heading the target's plus the offset (or, line of sight, its own), its
    tie at the compensator's distance, turned so that the tie's pull balances the body's own
    sway force (the compensator gives the surge force and the yaw moment): sin(theta - psi) =
    F_sway / T, of two roots, ``branch`` 0 (asin) or 1 (pi - asin, the default: the body
    behind its target point when F_sway is small); line of sight, theta = psi - pi - offset.
    Returns False where no such place exists (|F_sway| > T)."""
    p = plane.built.params
    held = held or {}
    branch = branch or {}
    parent = {j: int(p.point_body[tie[1]]) for j, tie in order if tie is not None}
    index = {int(b): j for j, b in enumerate(plane.bodies)}
    for j, tie in order:  # every tie slack: each body's point on its anchor (parents first)
        h = held.get(j)
        if h is not None and not h.line_of_sight:  # on its target's heading
            x[3 * j + 2] = _points(plane, x)[parent[j], 2] + h.offset
        if tie is not None:
            _place(plane, x, j, tie, np.zeros(2))
    controlled = plane.controlled
    if controlled:  # the bodies' own loads, without the compensators'
        plane.control(False)
    try:
        plane.at_rest(x, jacobian=False)
    finally:
        if controlled:
            plane.control(True)
    load = {j: plane.work.load[b, :2].copy() for j, b in enumerate(plane.bodies)}  # [N]
    turned: dict[int, float] = {}  # a held body's tie direction theta [rad]
    for j, _tie in order[::-1]:  # each tie carries its body's load and what it holds
        h = held.get(j)
        if h is not None:
            psi = x[3 * j + 2]
            if h.line_of_sight:
                theta = psi - math.pi - h.offset
            else:
                sway = (-math.sin(psi) * load[j][0] + math.cos(psi) * load[j][1]) / h.tension
                if abs(sway) > 1.0:
                    return False
                theta = psi + (math.asin(sway) if branch.get(j, 1) == 0
                               else math.pi - math.asin(sway))  # fmt: skip
            turned[j] = theta
            load[j] = h.tension * np.array([math.cos(theta), math.sin(theta)])
        up = index.get(parent.get(j, -1), -1)
        if up >= 0:
            load[up] += load[j]
    for j, tie in order:
        if tie is None:
            continue
        size = float(np.hypot(*load[j]))
        if j in turned:
            along = held[j].distance * np.array([math.cos(turned[j]), math.sin(turned[j])])
        elif size > 0.0:
            along = load[j] / size * (p.tie_length[tie[2]] + _stretch(p, tie[2], size))
        else:  # no load: streaming behind the point at its length
            away = -1.0 if p.point_offset[tie[0]][0] >= 0.0 else 1.0
            psi = x[3 * j + 2]
            along = away * p.tie_length[tie[2]] * np.array([math.cos(psi), math.sin(psi)])
        _place(plane, x, j, tie, along)
    return True


def _placed_starts(plane: Plane, headings: int) -> list[np.ndarray]:
    """Starts: every combination of ``headings`` headings per body, the bodies placed by their
    ties (``_balanced``)."""
    n = len(plane.bodies)
    if headings <= 0:
        return []
    order = _tie_order(plane)
    start = plane.start()[: 3 * n]
    starts = []
    for combo in itertools.product(np.linspace(-math.pi, math.pi, headings, endpoint=False),
                                   repeat=n):  # fmt: skip
        x = start.copy()
        x[2::3] = combo
        _balanced(plane, x, order)
        starts.append(x)
    return starts


def _scanned_starts(plane: Plane, count: int) -> list[np.ndarray]:
    """Starts on the balanced placement (``_balanced``), where only the bodies' yaw moments
    are left: when every free body hangs on a chain of ties from a fixed one and the loads at
    rest depend on the headings only (a uniform current and wind, thrust fixed to the hull),
    a body's moment depends on its own heading and on those of the bodies it holds, not on
    the others'. Its roots are then found body by body from the ends of the chains: a scan
    of ``count`` headings, each change of sign refined by Brent's method, for every
    combination of roots of the bodies it holds.

    A body held by its compensator (``_held``) has, where the compensator does not saturate,
    its heading and its tie's length given, and its tie's direction from its sway force: it
    adds its two branches (heading relative to its target's), or the roots of its sway force
    over its heading (line of sight), and its target's moment is scanned with it in place.
    Where the premise fails (a saturated compensator, a restoring force model), these are
    starts like any other."""
    order = _tie_order(plane)
    n = len(plane.bodies)
    if count <= 0 or any(tie is None for _, tie in order):
        return []
    held = _held(plane, order)
    base = plane.start()[: 3 * n]
    # half a step off the headings that symmetric weather makes roots of (0, +-90, 180 deg),
    # so that no root falls on the seam where the scan closes on itself
    grid = np.linspace(-math.pi, math.pi, count + 1) + math.pi / count
    partial: list[tuple[dict[int, float], dict[int, int]]] = [({}, {})]  # headings, branches
    for j, _tie in order[::-1]:  # the ends of the chains first
        h = held.get(j)
        if h is not None and not h.line_of_sight:  # its heading follows its target's
            partial = [(fixed, {**branch, j: side}) for fixed, branch in partial
                       for side in (0, 1)]  # fmt: skip
            continue

        def residual(psi: float, fixed: dict[int, float], branch: dict[int, int], j: int = j,
                     sway: bool = h is not None) -> float:  # fmt: skip
            """The body's moment [N m] (held, line of sight: its sway force [N])."""
            x = base.copy()
            for k, value in fixed.items():
                x[3 * k + 2] = value
            x[3 * j + 2] = psi
            if not _balanced(plane, x, order, held, branch):
                return math.nan
            plane.at_rest(x, jacobian=False)
            load = plane.work.load[plane.bodies[j]]
            if sway:
                return float(-math.sin(psi) * load[0] + math.cos(psi) * load[1])
            return float(load[5])  # about z

        more = []
        for fixed, branch in partial:
            values = [residual(psi, fixed, branch) for psi in grid]  # the ends: round-off apart
            for k in range(count):
                fa, fb = values[k], values[k + 1]
                if fa == 0.0:
                    more.append(({**fixed, j: float(grid[k])}, branch))
                elif fa * fb < 0.0:  # False where either is nan (no place there)
                    psi = optimize.brentq(residual, grid[k], grid[k + 1], args=(fixed, branch),
                                          xtol=1e-9)  # fmt: skip
                    more.append(({**fixed, j: float(psi)}, branch))
        partial = more
    starts = []
    for headings, branch in partial:
        x = base.copy()
        for k, value in headings.items():
            x[3 * k + 2] = value
        if _balanced(plane, x, order, held, branch):
            starts.append(x)
    return starts


def _scale(plane: Plane, x: np.ndarray) -> float:
    """The size of the loads at positions ``x`` [N]: the largest tie tension or force of a
    force model on a free body (what a balance there is relative to)."""
    plane.at_rest(x, jacobian=False)
    work = plane.work
    tie = float(np.abs(work.tie_tension).max()) if work.tie_tension.size else 0.0
    return max(tie, float(np.abs(work.models[plane.bodies, :2]).max()), 1e-30)


def _settled(plane: Plane, scanned: list[np.ndarray]) -> bool:
    """Whether every scanned start balances already, to ``SETTLED`` of its ties' tensions
    (Brent's method leaves the moments near 1e-9 of their slopes): the scan's premise held,
    and its starts are every equilibrium."""
    for x in scanned:
        g, _ = plane.at_rest(x, jacobian=False)
        if np.abs(g).max() > SETTLED * max(np.abs(plane.work.tie_tension).max(), 1e-30):
            return False
    return True


def _tie_to_placed(p, body: int, placed: set[int]):
    """A tie between ``body`` and a placed body: (its point on ``body``, the other point, the
    tie's index), or None."""
    for k in range(p.tie_from.shape[0]):
        a, b = int(p.tie_from[k]), int(p.tie_to[k])
        if p.point_body[a] == body and int(p.point_body[b]) in placed:
            return a, b, k
        if p.point_body[b] == body and int(p.point_body[a]) in placed:
            return b, a, k
    return None


def find(
    plane: Plane, weather: Weather | None = None, headings: int = 12,
    extra: list[np.ndarray] | None = None, iterations: int = 60, scan: int = SCAN,
    every: bool = True,
) -> list[Equilibrium]:  # fmt: skip
    """Every equilibrium reached by Newton from the starts (module docstring: ``extra``
    positions, the scanned starts of ``scan`` headings, the placed starts of ``headings`` a
    body unless every scanned start balances already, the case's own; with ``headings`` 0
    only ``extra``), the stable ones first, then the most visited; ``weather`` applied first
    when given. With a compensator the scan finds the equilibria where it does not saturate;
    the placed starts run too, for those where it does, unless ``every`` is False and the
    others include a stable one (what a map needs)."""
    if weather is not None:
        weather.apply(plane.built)
    n = len(plane.bodies)
    found: list[Equilibrium] = []
    starts = [np.asarray(x, dtype=float) for x in (extra or [])]
    grid = False
    if headings > 0:
        scanned = _scanned_starts(plane, scan)
        starts += scanned
        grid = not (scanned and _settled(plane, scanned))  # unless the scan settles it
        if grid:
            starts += _placed_starts(plane, headings)
        starts.append(plane.start()[: 3 * n])  # the case's own start too
    _solve(plane, starts, iterations, found)
    if headings > 0 and not grid and _held(plane, _tie_order(plane)):
        if every or not any(_stable(plane, eq) for eq in found):  # saturated ones
            _solve(plane, _placed_starts(plane, headings), iterations, found)
    for eq in found:
        _stable(plane, eq)
    found.sort(key=lambda e: (not e.stable, -e.hits))  # the stable ones first
    return found


def _stable(plane: Plane, eq: Equilibrium) -> bool:
    """Whether ``eq`` is stable, its eigenvalues computed first if they are not yet."""
    if not eq.eigenvalues.size:
        state = np.concatenate([eq.x, np.zeros_like(eq.x)])
        eq.eigenvalues = np.linalg.eigvals(plane.jacobian(state))
    return eq.stable


def _solve(plane: Plane, starts: list[np.ndarray], iterations: int,
           found: list[Equilibrium]) -> None:  # fmt: skip
    """Newton from each start; each equilibrium reached added to ``found``, or counted as a
    hit of the one it repeats (module docstring)."""
    p = plane.built.params
    n = len(plane.bodies)
    steps = plane.steps()[: 3 * n]
    reach = np.tile([50.0, 50.0, 0.5], n)
    out = np.empty(3 * n)
    for x0 in starts:
        scale = _scale(plane, x0)
        norm, _ = balance(0.0, x0, plane.y, plane.q, plane.v, p, plane.work, plane.ydot,
                          plane.weight, steps, reach, iterations, CONVERGED * scale,
                          out)  # fmt: skip
        if not np.all(np.isfinite(out)):
            continue  # a stalled Newton is kept when it stalled at round-off
        x = out.copy()
        scale = _scale(plane, x)
        if CONVERGED * scale < norm < 1e-3 * scale:  # stopped on a wild start's loads: polish
            norm, _ = balance(0.0, x, plane.y, plane.q, plane.v, p, plane.work, plane.ydot,
                              plane.weight, steps, reach, iterations, CONVERGED * scale,
                              out)  # fmt: skip
            x = out.copy()
            scale = _scale(plane, x)
        x[2::3] = _wrap(x[2::3])
        if norm > BALANCED * scale:
            continue
        for eq in found:
            d = np.abs(eq.x - x)
            d[2::3] = np.abs(_wrap(d[2::3]))
            if (
                np.all(d[0::3] < SAME_POSITION)
                and np.all(d[1::3] < SAME_POSITION)
                and np.all(d[2::3] < SAME_ANGLE)
            ):
                eq.hits += 1
                if norm / scale < eq.residual:  # keep the best converged
                    eq.x, eq.residual = x, norm / scale
                    eq.eigenvalues = np.empty(0)
                break
        else:
            found.append(Equilibrium(x, np.empty(0), norm / scale, 1))
