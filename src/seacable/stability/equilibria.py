"""Every static equilibrium of a system in the horizontal plane for a given weather, and the
stability of each from the eigenvalues of the linearised system.

The equilibria are found from many starts: the case's own start, a grid of headings for each
free body,
each body placed by its ties (a tie from a body already placed, or from a fixed one, at its
unstretched length, streaming behind the point; a body without one where the case puts it),
then Newton's method on the accelerations at rest (``plane.balance``). Newton's solutions are
merged when they are within a millimetre and a microradian of each other, and each is kept
only when its force and moment balance holds to round-off (``BALANCED``, relative to the
largest unbalanced load at a start, or a tie's tension there). The linearisation df/dx
(``plane.jacobian``) gives the eigenvalues: an equilibrium is stable when every real part is
below -``STABLE`` |lambda| (or 1e-9 1/s).
"""

import itertools
import math
from dataclasses import dataclass

import numpy as np

from seacable.stability.plane import Plane, Weather, balance

BALANCED = 1e-9  # the weighted residual, relative to the bodies' largest loads
STABLE = 1e-7  # Re(lambda) below -STABLE |lambda| (or 1e-9 1/s): stable
SAME_POSITION, SAME_ANGLE = 1e-3, 1e-6  # [m], [rad]: one equilibrium


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
    def kind(self) -> str:
        """ "stable", or "unstable" with how: "divergent" (a real eigenvalue > 0),
        "oscillatory" (only complex ones), or both."""
        if self.stable:
            return "stable"
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


def _placed_starts(plane: Plane, headings: int) -> list[np.ndarray]:
    """Starts: every combination of ``headings`` headings per body, each body placed by a tie
    to a body placed before it (module docstring)."""
    p = plane.built.params
    n = len(plane.bodies)
    order = list(range(n))
    free_index = {int(b): j for j, b in enumerate(plane.bodies)}
    start = plane.start()[: 3 * n]
    if headings <= 0:
        return []
    grid = np.linspace(-math.pi, math.pi, headings, endpoint=False)
    starts = []
    for combo in itertools.product(grid, repeat=n):
        x = start.copy()
        placed = {int(b) for b in range(p.body_kind.shape[0]) if int(b) not in free_index}
        for j in order:
            x[3 * j + 2] = combo[j]
        for _ in range(n):  # bodies placed in the order their ties allow
            for j in order:
                b = int(plane.bodies[j])
                if b in placed:
                    continue
                tie = _tie_to_placed(p, b, placed)
                if tie is None:
                    continue
                pose = _points(plane, x)
                here, there, length = tie
                ob = p.point_offset[here]
                ab = p.point_body[there]
                oa = p.point_offset[there]
                ca, sa = math.cos(pose[ab, 2]), math.sin(pose[ab, 2])
                anchor = pose[ab, :2] + (ca * oa[0] - sa * oa[1], sa * oa[0] + ca * oa[1])
                psi = x[3 * j + 2]
                c, s = math.cos(psi), math.sin(psi)
                away = -1.0 if ob[0] >= 0.0 else 1.0  # streaming behind the point
                end = anchor + away * length * np.array([c, s])
                x[3 * j : 3 * j + 2] = end - (c * ob[0] - s * ob[1], s * ob[0] + c * ob[1])
                placed.add(b)
        starts.append(x)
    return starts


def _tie_to_placed(p, body: int, placed: set[int]):
    """A tie between ``body`` and a placed body: (its point on ``body``, the other point, the
    unstretched length), or None."""
    for k in range(p.tie_from.shape[0]):
        a, b = int(p.tie_from[k]), int(p.tie_to[k])
        if p.point_body[a] == body and int(p.point_body[b]) in placed:
            return a, b, float(p.tie_length[k])
        if p.point_body[b] == body and int(p.point_body[a]) in placed:
            return b, a, float(p.tie_length[k])
    return None


def find(
    plane: Plane, weather: Weather | None = None, headings: int = 12,
    extra: list[np.ndarray] | None = None, iterations: int = 60,
) -> list[Equilibrium]:  # fmt: skip
    """Every equilibrium reached from the starts (module docstring) and from ``extra`` starts
    (positions), the stable ones first, then the most visited; ``weather`` applied first when
    given."""
    if weather is not None:
        weather.apply(plane.built)
    p = plane.built.params
    n = len(plane.bodies)
    steps = plane.steps()[: 3 * n]
    reach = np.tile([50.0, 50.0, 0.5], n)
    found: list[Equilibrium] = []
    out = np.empty(3 * n)
    starts = [*(extra or []), *_placed_starts(plane, headings)]
    if headings > 0:  # the case's own start too
        starts.append(plane.start()[: 3 * n])
    # the loads' size: the largest unbalanced load of a start, or a tie's tension at one
    scale = 1e-30
    for x0 in starts:
        g, _ = plane.at_rest(np.asarray(x0, dtype=float), jacobian=False)
        tie = np.abs(plane.work.tie_tension).max() if plane.work.tie_tension.size else 0.0
        scale = max(scale, float(np.abs(g).max()), tie)
    for x0 in starts:
        norm, its = balance(0.0, np.asarray(x0, dtype=float), plane.y, plane.q, plane.v, p,
                            plane.work, plane.ydot, plane.weight, steps, reach, iterations,
                            out)  # fmt: skip
        if not np.all(np.isfinite(out)):
            continue  # a stalled Newton (its < 0) is kept when it stalled at round-off
        x = out.copy()
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
                break
        else:
            found.append(Equilibrium(x, np.empty(0), norm / scale, 1))
    for eq in found:
        state = np.concatenate([eq.x, np.zeros(3 * n)])
        eq.eigenvalues = np.linalg.eigvals(plane.jacobian(state))
    found.sort(key=lambda e: (not e.stable, -e.hits))  # the stable ones first
    return found
