"""Curves of folds and Hopf points in two parameters (e.g. the current's direction against the
wind's, or a shuttle's astern thrust against its hawser's length).

A fold or a Hopf point found by a one-parameter continuation (``stability.continuation``) is
followed as both parameters change: the curve is the zero set of the extended system

    G(X, mu1, mu2) = 0,    psi(X, mu1, mu2) = 0,

G the weighted accelerations at rest (``plane.at_rest``), psi the test function of the kind:

- fold: the real eigenvalue of dG/dX nearest zero (a real eigenvalue crosses zero there);
- Hopf: Re lambda / |Im lambda| of the linearised system's complex pair nearest the imaginary
  axis (a pair crosses it there).

m + 1 equations in m + 2 unknowns (X: 3 per free body) make a curve, followed by Keller's
pseudo-arclength method in the scaled variables of ``stability.continuation`` (z = (X / s_X,
mu1 / s1, mu2 / s2)), the extended system's Jacobian by central differences (of 1e-4 in z: the
test functions hold differences of their own, of far smaller steps). Newton stops at steps
under 1e-6 in z: the test functions' own differences leave a noise floor near 1e-7 (measured on
the tandem example) that a tighter tolerance would never pass. A branch point of a
symmetric branch (a pitchfork) is not followed: there the extended system is singular (its
test function is even in the symmetry-breaking direction); its curve is the symmetric
branch's, which a one-parameter continuation in the second parameter gives.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from seacable.stability.continuation import ContinuationError, Parameter
from seacable.stability.plane import Plane

KINDS = ("fold", "hopf")


@dataclass
class Curve:
    """A curve of ``kind`` points: both parameters, the positions, and (Hopf) the crossing
    pair's frequency [rad/s] at each point."""

    kind: str
    first: list[float] = field(default_factory=list)
    second: list[float] = field(default_factory=list)
    x: list[np.ndarray] = field(default_factory=list)
    frequency: list[float] = field(default_factory=list)


class CurveContinuation:
    """Pseudo-arclength continuation of ``kind`` points of ``plane`` in ``first`` and
    ``second``."""

    def __init__(self, plane: Plane, first: Parameter, second: Parameter, kind: str):
        if kind not in KINDS:
            raise ContinuationError(f"two-parameter curves follow {KINDS}, not '{kind}'")
        self.plane, self.first, self.second, self.kind = plane, first, second, kind
        self.omega = 0.0  # the crossing pair's frequency at the last point (Hopf) [rad/s]
        n = len(plane.bodies)
        self.m = 3 * n
        self.scale = np.concatenate([np.tile([1.0, 1.0, 0.0], n) * np.repeat(plane.length, 3)
                                     + np.tile([0.0, 0.0, 1.0], n),
                                     [first.scale, second.scale]])  # fmt: skip

    def _set(self, z: np.ndarray) -> np.ndarray:
        """Both parameters written from z; the positions returned."""
        v = z * self.scale
        self.first.set(self.plane, v[self.m])
        self.second.set(self.plane, v[self.m + 1])
        return v[: self.m]

    def _psi(self, x: np.ndarray, gx: np.ndarray) -> tuple[float, float]:
        """The test function and (Hopf) the pair's frequency at positions x."""
        if self.kind == "fold":
            lam = np.linalg.eigvals(gx)
            real = lam[np.abs(lam.imag) <= 1e-9 * np.maximum(np.abs(lam), 1e-300)].real
            return (float(real[np.argmin(np.abs(real))]) if real.size else math.inf), math.nan
        lam = np.linalg.eigvals(self.plane.jacobian(np.concatenate([x, np.zeros(self.m)])))
        pairs = lam[lam.imag > 1e-9 * np.maximum(np.abs(lam), 1e-300)]
        if not pairs.size:
            return math.inf, math.nan
        # the pair that crosses: the one nearest the axis and the last point's frequency
        # (another pair may come nearer the axis elsewhere on the curve)
        near = np.abs(pairs.real) + np.abs(pairs.imag - self.omega) if self.omega > 0 else (
            np.abs(pairs.real))  # fmt: skip
        pair = pairs[np.argmin(near)]
        return float(pair.real / pair.imag), float(pair.imag)

    def residual(self, z: np.ndarray) -> tuple[np.ndarray, float]:
        """(G, psi) at z, and the frequency."""
        x = self._set(z)
        g, gx = self.plane.at_rest(x, True)
        psi, omega = self._psi(x, gx)
        return np.concatenate([g, [psi]]), omega

    def _jacobian(self, z: np.ndarray) -> np.ndarray:
        h = 1e-4
        jac = np.empty((self.m + 1, self.m + 2))
        for j in range(self.m + 2):
            up, down = z.copy(), z.copy()
            up[j] += h
            down[j] -= h
            jac[:, j] = (self.residual(up)[0] - self.residual(down)[0]) / (2 * h)
        return jac

    def _correct(self, z0, t, ds, iterations=10, tolerance=1e-6):
        z = z0 + ds * t
        for it in range(iterations):
            r, _ = self.residual(z)
            if not np.all(np.isfinite(r)):
                return None, it
            a = np.vstack([self._jacobian(z), t])
            try:
                dz = np.linalg.solve(a, -np.concatenate([r, [t @ (z - z0) - ds]]))
            except np.linalg.LinAlgError:
                return None, it
            z = z + dz
            if np.abs(dz).max() < tolerance:
                return z, it + 1
        return None, iterations

    def _tangent(self, z: np.ndarray, previous: np.ndarray) -> np.ndarray:
        a = np.vstack([self._jacobian(z), previous])
        rhs = np.zeros(self.m + 2)
        rhs[-1] = 1.0
        t = np.linalg.solve(a, rhs)
        return t / np.linalg.norm(t)

    def run(self, x0: np.ndarray, mu1: float, mu2: float, second_end: float,
            box: tuple[float, float], frequency: float = 0.0, step: float = 0.02,
            largest: float = 0.5, points: int = 400) -> Curve:  # fmt: skip
        """The curve through the ``kind`` point at positions ``x0`` and (``mu1``, ``mu2``)
        (a Hopf point's pair at ``frequency``), corrected first, setting out towards
        ``second_end``, until the second parameter passes it, the first leaves ``box``, or
        ``points`` points."""
        self.omega = frequency
        z = np.concatenate([np.asarray(x0, float), [mu1, mu2]]) / self.scale
        fixed = np.zeros(self.m + 2)
        fixed[self.m + 1] = 1.0
        z, _ = self._correct(z, fixed, 0.0)
        if z is None:
            raise ContinuationError(
                f"the {self.kind} point at {self.first.name} = {mu1:g}, {self.second.name} = "
                f"{mu2:g} could not be corrected"
            )
        sign = 1.0 if second_end >= mu2 else -1.0
        t = self._tangent(z, sign * fixed)
        curve = Curve(self.kind)
        self._record(curve, z)
        ds = step
        for _ in range(points):
            z1, its = self._correct(z, t, ds)
            if z1 is None:
                ds *= 0.5
                if ds < 1e-6:
                    break
                continue
            t = self._tangent(z1, t)
            z = z1
            self._record(curve, z)
            first, second = curve.first[-1], curve.second[-1]
            if (second - mu2) * (second_end - mu2) >= (second_end - mu2) ** 2 or not (
                box[0] <= first <= box[1]
            ):
                break
            if its <= 4:
                ds = min(1.5 * ds, largest)
        self._set(np.concatenate([np.asarray(x0, float), [mu1, mu2]]) / self.scale)
        return curve

    def _record(self, curve: Curve, z: np.ndarray) -> None:
        _, omega = self.residual(z)
        if math.isfinite(omega):
            self.omega = omega
        v = z * self.scale
        curve.first.append(float(v[self.m]))
        curve.second.append(float(v[self.m + 1]))
        curve.x.append(v[: self.m].copy())
        curve.frequency.append(omega)


__all__ = ["KINDS", "Curve", "CurveContinuation"]
