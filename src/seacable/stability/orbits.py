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

    @property
    def stable(self) -> bool:
        """All multipliers but the one nearest 1 inside the unit circle."""
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
    docstring); ``tolerance`` on the scaled residual and step."""
    n = plane.size
    scale = _scales(plane)
    ref = np.asarray(x0, float).copy()
    normal = plane.rates(ref) / scale  # in scaled variables
    normal /= np.linalg.norm(normal)
    x, t = ref.copy(), float(period)
    steps = _steps(plane, ref, t)
    residual, converged = math.inf, False
    monodromy = np.eye(n)
    for _ in range(iterations):
        end, _ = integrate(plane, x, t, steps)
        r = (end - x) / scale
        residual = float(np.abs(r).max())
        monodromy = _monodromy(plane, x, t, steps, scale)
        a = np.zeros((n + 1, n + 1))
        a[:n, :n] = monodromy - np.eye(n)
        a[:n, n] = plane.rates(end) / scale
        a[n, :n] = normal
        rhs = np.concatenate([-r, [-(normal @ ((x - ref) / scale))]])
        delta = np.linalg.lstsq(a, rhs, rcond=None)[0]
        x = x + delta[:n] * scale
        t = t + delta[n]
        if residual < tolerance and np.abs(delta[:n]).max() < 1e3 * tolerance:
            converged = True
            break
        if not (t > 0.0 and np.all(np.isfinite(x))):
            break
    end, path = integrate(plane, x, t, steps, record=True)
    residual = float(np.abs((end - x) / scale).max())
    monodromy = _monodromy(plane, x, t, steps, scale)
    multipliers = np.linalg.eigvals(monodromy)
    return Orbit(x, t, multipliers, converged and residual < 10 * tolerance, residual, path)


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


def settle(
    plane: Plane, x0: np.ndarray, duration: float, step: float = 1.0
) -> tuple[np.ndarray, float]:
    """Integrate from ``x0`` for ``duration`` [s] (``step`` [s]); return the last state and the
    period of the motion over the last third (the mean time between upward crossings of the
    coordinate that moves most; nan when it does not oscillate or comes to rest)."""
    steps = int(math.ceil(duration / step))
    _, path = integrate(plane, x0, duration, steps, record=True)
    tail = path[2 * steps // 3 :]
    times = np.arange(tail.shape[0]) * (duration / steps)
    spread = np.ptp(tail, axis=0) / _scales(plane)
    if spread.max() < 1e-2:  # at rest: under 1 cm and 1e-5 rad (settled on an equilibrium)
        return path[-1], math.nan
    k = int(np.argmax(spread))
    third = tail.shape[0] // 3
    early, late = np.ptp(tail[:third, k]), np.ptp(tail[-third:, k])
    if late < 0.9 * early:  # still dying out: coming to rest, not a cycle
        return path[-1], math.nan
    signal = tail[:, k] - tail[:, k].mean()
    up = np.flatnonzero((signal[:-1] < 0.0) & (signal[1:] >= 0.0))
    if up.size < 3:
        return path[-1], math.nan
    # crossing times by linear interpolation
    crossings = times[up] - signal[up] / (signal[up + 1] - signal[up]) * (times[1] - times[0])
    return path[-1], float(np.mean(np.diff(crossings)))


def clearance(outlines: list[np.ndarray]) -> float:
    """The least distance [m] between two convex outlines (earth-frame vertices (k, 2),
    counter-clockwise or not); 0 when they overlap."""
    a, b = outlines
    if _overlap(a, b):
        return 0.0
    best = math.inf
    for p_, poly in ((a, b), (b, a)):
        for point in p_:
            for i in range(len(poly)):
                best = min(best, _segment_distance(point, poly[i], poly[(i + 1) % len(poly)]))
    return best


def _segment_distance(p_, a, b) -> float:
    d = b - a
    s = np.clip(np.dot(p_ - a, d) / max(np.dot(d, d), 1e-300), 0.0, 1.0)
    return float(np.linalg.norm(p_ - (a + s * d)))


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
