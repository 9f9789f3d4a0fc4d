"""Periodic orbits (limit cycles: a ship fishtailing on its hawser) of a system in the
horizontal plane: found by shooting, with their Floquet multipliers, period, amplitudes, the
ties' tension peaks and the least clearance between the hulls.

The flow phi_t(x) of dx/dt = f(x) (``plane.rates``) is integrated by the classical Runge-Kutta
method with a fixed step (``flow``, compiled): at least ``STEPS_PER_PERIOD`` a period and
``STEPS_PER_FASTEST`` per period of the linearisation's fastest eigenvalue. Shooting solves
phi_T(x0) = x0 for (x0, T) with the phase condition f(x_r) . (x0 - x_r) = 0 (x0 on the
hyperplane through the guess x_r normal to the flow there) by Newton's method, the monodromy
matrix M = d phi_T / d x0 by central differences of the flow. M's eigenvalues are the Floquet
multipliers: one of them is 1 (along the orbit); the orbit is stable when the others lie
inside the unit circle.

A start for shooting comes from a long integration that settles on an attracting cycle
(``settle``), or from a Hopf point (the equilibrium plus a small multiple of the critical
eigenvector's real part, the period 2 pi / omega).
"""

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from seacable.kernels import roots
from seacable.kernels.jit import JIT, inner
from seacable.stability.plane import Plane, rates

STEPS_PER_PERIOD = 2000
STEPS_PER_FASTEST = 40


@inner
def _rk4(x, h, y, q, v, p, w, ydot, k1, k2, k3, k4, tmp, out):
    """One classical Runge-Kutta step of ``h`` [s] from ``x`` into ``out``."""
    n = x.shape[0]
    rates(0.0, x, y, q, v, p, w, ydot, k1)
    for i in range(n):
        tmp[i] = x[i] + 0.5 * h * k1[i]
    rates(0.0, tmp, y, q, v, p, w, ydot, k2)
    for i in range(n):
        tmp[i] = x[i] + 0.5 * h * k2[i]
    rates(0.0, tmp, y, q, v, p, w, ydot, k3)
    for i in range(n):
        tmp[i] = x[i] + h * k3[i]
    rates(0.0, tmp, y, q, v, p, w, ydot, k4)
    for i in range(n):
        out[i] = x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@inner
def _stretches(x, y, q, v, p, w, ydot, scratch, out):
    """Each tie's d - L0 [m] at state ``x`` (negative: slack)."""
    rates(0.0, x, y, q, v, p, w, ydot, scratch)
    for k in range(p.tie_from.shape[0]):
        a, b = p.tie_from[k], p.tie_to[k]
        d = 0.0
        for c in range(3):
            d += (w.ppos[b, c] - w.ppos[a, c]) ** 2
        out[k] = math.sqrt(d) - p.tie_length[k]


@inner
def _split(x, h, kink, fa, fb, y, q, v, p, w, ydot, k1, k2, k3, k4, tmp, part, scratch, sp,
           out):  # fmt: skip
    """The step of ``h`` from ``x`` in two, where tie ``kink``'s stretch (``fa`` at the start,
    ``fb`` at the end, of opposite signs) crosses zero (the Illinois secant in the fraction of
    the step), into ``out``."""
    a, b = 0.0, 1.0
    side = np.int64(0)  # not the literal 0: numba would compile narrow for Literal[int](0) too
    theta = 0.5
    for _ in range(60):
        theta = roots.trial(a, fa, b, fb)
        _rk4(x, theta * h, y, q, v, p, w, ydot, k1, k2, k3, k4, tmp, part)
        _stretches(part, y, q, v, p, w, ydot, scratch, sp)
        f = sp[kink]
        if f == 0.0 or b - a < 1e-14:
            break
        a, fa, b, fb, side = roots.narrow(a, fa, b, fb, theta, f, side)
    _rk4(x, theta * h, y, q, v, p, w, ydot, k1, k2, k3, k4, tmp, part)
    _rk4(part, (1.0 - theta) * h, y, q, v, p, w, ydot, k1, k2, k3, k4, tmp, out)


@njit(**JIT)
def flow(x0, duration, steps, y, q, v, p, w, ydot, record, out):
    """phi_duration(x0) into ``out`` by ``steps`` fixed Runge-Kutta steps; with ``record``
    (steps + 1, n) non-empty, every step's state too. A step in which a tie goes slack or
    taut (its tension's kink) is split where it does (the secant method on the stretch along
    the step): without it, the kink's place within a step would make the steps' error depend
    on the start at first order, and the monodromy matrix would not hold f. Returns False
    when a state is not finite."""
    n = x0.shape[0]
    nt = p.tie_from.shape[0]
    h = duration / steps
    x = x0.copy()
    k1, k2, k3, k4, tmp = np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    nxt, part, scratch = np.empty(n), np.empty(n), np.empty(n)
    s0, s1, sp = np.empty(nt), np.empty(nt), np.empty(nt)
    keep = record.shape[0] > 0
    if keep:
        record[0, :] = x
    _stretches(x, y, q, v, p, w, ydot, scratch, s0)
    for s in range(steps):
        _rk4(x, h, y, q, v, p, w, ydot, k1, k2, k3, k4, tmp, nxt)
        _stretches(nxt, y, q, v, p, w, ydot, scratch, s1)
        kink = -1
        for k in range(nt):
            if (s0[k] > 0.0) != (s1[k] > 0.0):
                kink = k
                break
        if kink >= 0:  # split the step at the first tie's kink found
            _split(x, h, kink, s0[kink], s1[kink], y, q, v, p, w, ydot, k1, k2, k3, k4, tmp,
                   part, scratch, sp, nxt)  # fmt: skip
            _stretches(nxt, y, q, v, p, w, ydot, scratch, s1)
        for i in range(n):
            x[i] = nxt[i]
            if not math.isfinite(x[i]):
                out[:] = x
                return False
        for k in range(nt):
            s0[k] = s1[k]
        if keep:
            record[s + 1, :] = x
    out[:] = x
    return True


@dataclass
class Orbit:
    """A periodic orbit: its start x0 (on the phase hyperplane), period [s], Floquet
    multipliers, whether shooting converged and its residual (|phi_T(x0) - x0|, scaled), and
    the states along one period (``path``, a row per step)."""

    x0: np.ndarray
    period: float
    multipliers: np.ndarray
    converged: bool
    residual: float
    path: np.ndarray
    message: str = ""  # why shooting did not converge ("" when it did)

    @property
    def stable(self) -> bool:
        """All multipliers but the one nearest 1 inside the unit circle (meaningful only on a
        converged orbit)."""
        m = self.multipliers
        others = np.delete(m, np.argmin(np.abs(m - 1.0)))
        return bool(np.all(np.abs(others) < 1.0))


def _steps(plane: Plane, x: np.ndarray, period: float) -> int:
    fastest = np.abs(np.linalg.eigvals(plane.jacobian(x))).max()
    return int(
        max(STEPS_PER_PERIOD, math.ceil(period * fastest / (2 * math.pi) * STEPS_PER_FASTEST))
    )


def integrate(plane: Plane, x0: np.ndarray, duration: float, steps: int,
              record: bool = False) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """(phi_duration(x0), the states at every step or an empty array)."""
    n = plane.size
    out = np.empty(n)
    path = np.empty((steps + 1, n) if record else (0, n))
    ok = flow(np.asarray(x0, float), float(duration), int(steps), plane.y, plane.q, plane.v,
              plane.built.params, plane.work, plane.ydot, path, out)  # fmt: skip
    if not ok:
        raise FloatingPointError("the flow left finite values")
    return out, path


def _scales(plane: Plane) -> np.ndarray:
    """The size of each state's typical change (for the residual and differences): 1 m, 1 m,
    1e-3 rad, 1e-3 m/s, 1e-3 m/s, 1e-5 rad/s."""
    n = len(plane.bodies)
    return np.concatenate([np.tile([1.0, 1.0, 1e-3], n), np.tile([1e-3, 1e-3, 1e-5], n)])


def shoot(plane: Plane, x0: np.ndarray, period: float, iterations: int = 20,
          tolerance: float = 1e-9) -> Orbit:  # fmt: skip
    """The periodic orbit through (near) ``x0`` with a period near ``period`` [s] (module
    docstring); ``tolerance`` on the scaled residual and step. Newton's step is damped: halved
    until it lowers the defect (the scaled residual with the phase condition), keeps the
    period positive and the flow finite; when no step of 1/1024 of Newton's does, shooting
    stops, not converged, with the reason in ``message``. A flow that leaves finite values
    from ``x0`` itself raises FloatingPointError."""
    n = plane.size
    scale = _scales(plane)
    ref = np.asarray(x0, float).copy()
    normal = plane.rates(ref) / scale  # in scaled variables
    normal /= np.linalg.norm(normal)
    x, t = ref.copy(), float(period)
    steps = _steps(plane, ref, t)

    def defect(x: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
        end, _ = integrate(plane, x, t, steps)
        return np.concatenate([(end - x) / scale, [normal @ ((x - ref) / scale)]]), end

    r, end = defect(x, t)
    converged, message = False, f"no convergence in {iterations} Newton iterations"
    for k in range(iterations):
        a = np.zeros((n + 1, n + 1))
        a[:n, :n] = _monodromy(plane, x, t, steps, scale) - np.eye(n)
        a[:n, n] = plane.rates(end) / scale
        a[n, :n] = normal
        delta = np.linalg.lstsq(a, -r, rcond=None)[0]
        if np.abs(r[:n]).max() < tolerance and np.abs(delta[:n]).max() < 1e3 * tolerance:
            x, t = x + delta[:n] * scale, t + delta[n]
            converged = True
            break
        damping = 1.0
        while damping >= 1.0 / 1024:
            trial_x, trial_t = x + damping * delta[:n] * scale, t + damping * delta[n]
            if trial_t > 0.0:
                try:
                    trial_r, trial_end = defect(trial_x, trial_t)
                except FloatingPointError:  # the step threw the ships out of any motion
                    trial_r = None
                if trial_r is not None and np.linalg.norm(trial_r) <= (
                    1.0 - 1e-4 * damping) * np.linalg.norm(r):  # fmt: skip
                    break
            damping /= 2.0
        else:
            message = (f"Newton's step stalled after {k} iterations: no step along it lowered "
                       f"the defect (scaled residual {np.abs(r[:n]).max():.2g})")  # fmt: skip
            break
        x, t, r, end = trial_x, trial_t, trial_r, trial_end
    end, path = integrate(plane, x, t, steps, record=True)
    residual = float(np.abs((end - x) / scale).max())
    multipliers = np.linalg.eigvals(_monodromy(plane, x, t, steps, scale))
    converged = converged and residual < 10 * tolerance
    if converged:
        message = ""
    elif message.startswith("no convergence"):
        message += f" (scaled residual {residual:.2g})"
    return Orbit(x, t, multipliers, converged, residual, path, message)


def _monodromy(plane: Plane, x: np.ndarray, period: float, steps: int,
               scale: np.ndarray) -> np.ndarray:  # fmt: skip
    """d phi_T / d x0 in the scaled variables, by central differences (1e-4 of each scale)."""
    n = plane.size
    m = np.empty((n, n))
    for j in range(n):
        h = 1e-4 * scale[j]
        up, down = x.copy(), x.copy()
        up[j] += h
        down[j] -= h
        a, _ = integrate(plane, up, period, steps)
        b, _ = integrate(plane, down, period, steps)
        m[:, j] = (a - b) / (2 * h) * scale[j] / scale
    return m


@dataclass
class Settled:
    """Where a motion went (``settle``). ``status``: "cycle" (its amplitude settled), "rest"
    (it died out), "diverged" (it left finite values), "irregular" (its amplitude stopped
    growing but neither it nor its period settles: no single periodic orbit), or "unsettled"
    (still growing or shrinking when the time ran out). ``amplitude``: the largest scaled peak
    to peak (``_scales``) over the last window of 10 periods, or the limit it approaches
    (Aitken's extrapolation); 0 at rest, inf diverged. ``periods``: the shortest, mean and
    longest time between upward crossings of the coordinate that moves most, over the last
    window (nan: fewer than three)."""

    status: str
    state: np.ndarray
    amplitude: float
    periods: tuple[float, float, float]
    elapsed: float
    amplitudes: list[float]

    @property
    def period(self) -> float:
        return self.periods[1]


def settle(plane: Plane, x0: np.ndarray, period: float, per: int, longest: float,
           center: np.ndarray | None = None, close: float = 0.0) -> Settled:  # fmt: skip
    """Integrate from ``x0`` in windows of 10 ``period`` [s] (``per`` steps a period) until
    the motion's amplitude settles, at most ``longest`` [s] (at least three windows). Near a
    Hopf point the amplitude approaches its limit geometrically and slowly (the multiplier is
    near 1): a window's amplitude that changes by under 1e-4 from the one before, or Aitken's
    limit of the last three that agrees with the previous one to 0.2 %, settles it, once the
    window's crossings come at regular times (within 1 %: a motion whose period wanders is
    no periodic orbit, whatever its amplitude does). Amplitudes falling geometrically to
    nothing (two Aitken limits in a row under 0.1 % of where they started) are a rest. With
    ``close``, a motion whose geometric approach (a ratio under 0.999 a window) leaves under
    that fraction of its amplitude to go is settled too (with ``center``, its offset from it
    scaled to the limit): near enough for shooting to finish.

    With ``center`` (the equilibrium the motion grows from), a slowly growing oscillation is
    sped up: the amplitude a of a motion near a Hopf point follows da/dt = a (sigma - c a^2)
    (the normal form), so the last three windows' growth rates give sigma, c and the cycle's
    amplitude sqrt(sigma / c); the motion's offset from ``center`` is scaled to it (at most
    tenfold, three times at most), and settles from there."""
    scale = _scales(plane)
    seen: list[float] = []
    x, estimate, elapsed = np.asarray(x0, float), math.nan, 0.0
    nothing = (math.nan, math.nan, math.nan)
    periods, since, jumps = nothing, 0, 0
    while elapsed < longest or len(seen) - since < 3:
        try:
            x_end, path = integrate(plane, x, 10 * period, 10 * per, record=True)
        except FloatingPointError:
            return Settled("diverged", np.full_like(x, np.nan), math.inf, nothing, elapsed, seen)
        elapsed += 10 * period
        moves = np.ptp(path, axis=0) / scale
        seen.append(float(moves.max()))
        x = x_end
        if seen[-1] < 1e-6:
            return Settled("rest", x, 0.0, nothing, elapsed, seen)
        periods = _crossing_times(path[:, int(np.argmax(moves))], period / per)
        regular = not periods[2] - periods[0] > 1e-2 * periods[1]  # nan: no crossings
        if len(seen) - since < 3:
            continue
        a0, a1, a2 = seen[-3:]
        step, before = a2 - a1, a1 - a0
        ratio = step / before if before != 0.0 else 0.0
        limit = a2 + step * ratio / (1.0 - ratio) if 0.0 <= ratio < 0.95 else math.nan
        if regular and abs(step) < 1e-4 * a2:
            return Settled("cycle", x, a2, periods, elapsed, seen)
        if regular and math.isfinite(limit) and abs(limit - estimate) < 2e-3 * abs(limit):
            return Settled("cycle", x, limit, periods, elapsed, seen)
        if abs(limit) < 1e-3 * a0 and abs(estimate) < 1e-3 * a0:  # dying out geometrically
            return Settled("rest", x, 0.0, periods, elapsed, seen)
        if close and regular and 0.0 <= ratio < 0.999 and abs(step) / (1.0 - ratio) < close * a2:
            limit = a2 + step * ratio / (1.0 - ratio)
            if center is not None:  # the offset scaled to the limit's amplitude
                x = center + (x - center) * (limit / a2)
            return Settled("cycle", x, limit, periods, elapsed, seen)
        estimate = limit
        target = _normal_form_amplitude(a0, a1, a2, 10 * period)
        if center is not None and regular and jumps < 3 and target > 1.5 * a2:
            x = center + (x - center) * min(target / a2, 10.0)
            since, jumps, estimate = len(seen), jumps + 1, math.nan
    # out of time: still growing or shrinking, or wandering about a level
    last = np.diff(seen[max(since, len(seen) - 5) :])
    wanders = len(last) >= 3 and bool(np.any(last > 0) and np.any(last < 0))
    return Settled("irregular" if wanders else "unsettled", x, seen[-1], periods, elapsed, seen)


def _normal_form_amplitude(a0: float, a1: float, a2: float, window: float) -> float:
    """The limit of amplitudes a0 < a1 < a2 (one a ``window`` [s]) growing as da/dt = a (sigma
    - c a^2): each window's log growth rate against its mean a^2 gives sigma and c; nan unless
    both are positive (the growth slowing as the amplitude grows)."""
    if not 0.0 < a0 < a1 < a2:
        return math.nan
    r1, r2 = math.log(a1 / a0) / window, math.log(a2 / a1) / window
    s1, s2 = 0.5 * (a0 * a0 + a1 * a1), 0.5 * (a1 * a1 + a2 * a2)
    c = (r1 - r2) / (s2 - s1)
    sigma = r1 + c * s1
    return math.sqrt(sigma / c) if c > 0.0 and sigma > 0.0 else math.nan


def _crossing_times(signal: np.ndarray, step: float) -> tuple[float, float, float]:
    """The shortest, mean and longest time between upward crossings of ``signal``'s mean
    (sampled every ``step`` [s]; linear interpolation); nan with fewer than three."""
    s = signal - signal.mean()
    up = np.flatnonzero((s[:-1] < 0.0) & (s[1:] >= 0.0))
    if up.size < 3:
        return (math.nan, math.nan, math.nan)
    crossings = (up - s[up] / (s[up + 1] - s[up])) * step
    gaps = np.diff(crossings)
    return (float(gaps.min()), float(gaps.mean()), float(gaps.max()))


def clearance(outlines: list[np.ndarray]) -> float:
    """The least distance [m] between two convex outlines (earth-frame vertices (k, 2),
    counter-clockwise or not); 0 when they overlap."""
    a, b = (np.asarray(o, dtype=float) for o in outlines)
    if _overlap(a, b):
        return 0.0
    return min(_nearest(a, b), _nearest(b, a))


def _nearest(points: np.ndarray, poly: np.ndarray) -> float:
    """The least distance from ``points`` (p, 2) to the edges of the polygon ``poly`` (k, 2)."""
    start = poly
    edge = np.roll(poly, -1, axis=0) - start  # (k, 2)
    offset = points[:, None, :] - start[None, :, :]  # (p, k, 2)
    share = (offset * edge).sum(axis=-1) / np.maximum((edge * edge).sum(axis=-1), 1e-300)
    gap = offset - np.clip(share, 0.0, 1.0)[..., None] * edge
    return float(np.sqrt((gap * gap).sum(axis=-1)).min())


def _overlap(a: np.ndarray, b: np.ndarray) -> bool:
    """Separating-axis test of two convex polygons."""
    for poly in (a, b):
        for i in range(len(poly)):
            edge = poly[(i + 1) % len(poly)] - poly[i]
            axis = np.array([-edge[1], edge[0]])
            pa, pb = a @ axis, b @ axis
            if pa.max() < pb.min() or pb.max() < pa.min():
                return False
    return True
