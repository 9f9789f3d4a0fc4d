"""Branches of equilibria in a parameter, by pseudo-arclength continuation, with their folds,
branch points (pitchforks) and Hopf points located.

With X the positions (3 per free body) and mu the parameter, the equilibria are the curve
G(X, mu) = 0, G the weighted accelerations at rest (``plane.at_rest``). In the scaled variables
z = (X / s_X, mu / s_mu) (s_X: a body's length for its x and y, 1 for its heading; s_mu the
parameter's scale), a step of length ds goes from z_k along the unit tangent t_k (the null
vector of [G_z], oriented as t_{k-1}) to the predictor z_k + ds t_k, and Newton's method
corrects it on G(z) = 0 with t_k . (z - z_k) = ds (Keller's pseudo-arclength). The step grows
by 1.5 after an easy correction (at most 3 iterations) and halves after a failed one.

Along the branch, two test functions:
- det(dG/dX) changes sign at a fold (the parameter turns back: the tangent's mu component
  changes sign too) or at a branch point (it does not: a pitchfork or a transcritical point);
- the largest real part among the complex eigenvalues of the linearised system changes sign
  at a Hopf point (a pair crosses the imaginary axis).
Each sign change is located by the secant method on the test function along the arc between
the two points, to ``tolerance`` in the parameter.
"""

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from seacable.errors import SeacableError
from seacable.kernels import roots
from seacable.stability.plane import Plane


class ContinuationError(SeacableError):
    """A branch could not be started or continued."""


@dataclass
class Parameter:
    """A parameter of the system: ``name`` (with its unit), ``set(plane, value)`` writing it
    into the system's parameters in place, and its ``scale`` (a typical change)."""

    name: str
    set: Callable[[Plane, float], None]
    scale: float = 1.0


@dataclass
class SpecialPoint:
    """A fold, a branch point or a Hopf point on a branch: its kind, the parameter, the
    positions, and for a Hopf point the crossing pair's frequency [rad/s]."""

    kind: str  # "fold", "branch point", "hopf"
    parameter: float
    x: np.ndarray
    frequency: float = math.nan


@dataclass
class Branch:
    """A branch of equilibria: the parameter and the positions at each point, the number of
    eigenvalues with a positive real part there, and the special points found."""

    parameter: list[float] = field(default_factory=list)
    x: list[np.ndarray] = field(default_factory=list)
    unstable: list[int] = field(default_factory=list)
    eigenvalues: list[np.ndarray] = field(default_factory=list)
    special: list[SpecialPoint] = field(default_factory=list)


def _complex_margin(lam: np.ndarray) -> float:
    """The largest real part among the complex eigenvalues (-inf: none)."""
    pairs = lam[np.abs(lam.imag) > 1e-9 * np.maximum(np.abs(lam), 1e-12)]
    return float(pairs.real.max()) if pairs.size else -math.inf


def _unstable(lam: np.ndarray) -> int:
    return int(np.sum(lam.real > 1e-9 * np.maximum(np.abs(lam), 1.0)))


class Continuation:
    """Pseudo-arclength continuation of ``plane``'s equilibria in ``parameter``."""

    def __init__(self, plane: Plane, parameter: Parameter):
        self.plane = plane
        self.parameter = parameter
        n = len(plane.bodies)
        self.scale = np.concatenate([np.tile([1.0, 1.0, 0.0], n) * np.repeat(plane.length, 3)
                                     + np.tile([0.0, 0.0, 1.0], n), [parameter.scale]])  # fmt: skip
        self.m = 3 * n

    # ---- G and its derivatives in the scaled variables -------------------------------------
    def _g(self, z: np.ndarray, jacobian: bool = True):
        """G and [dG/dz] (m x (m + 1)) at the scaled point z."""
        x, mu = z[: self.m] * self.scale[: self.m], z[self.m] * self.scale[self.m]
        self.parameter.set(self.plane, mu)
        g, gx = self.plane.at_rest(x, jacobian)
        if not jacobian:
            return g, None
        h = 1e-6 * max(1.0, abs(mu)) if self.parameter.scale >= 1.0 else 1e-6 * self.parameter.scale
        self.parameter.set(self.plane, mu + h)
        up, _ = self.plane.at_rest(x, False)
        self.parameter.set(self.plane, mu - h)
        down, _ = self.plane.at_rest(x, False)
        self.parameter.set(self.plane, mu)
        jac = np.empty((self.m, self.m + 1))
        jac[:, : self.m] = gx * self.scale[: self.m]
        jac[:, self.m] = (up - down) / (2 * h) * self.scale[self.m]
        return g, jac

    def _tangent(self, jac: np.ndarray, previous: np.ndarray) -> np.ndarray:
        a = np.vstack([jac, previous])
        rhs = np.zeros(self.m + 1)
        rhs[-1] = 1.0
        t = np.linalg.solve(a, rhs)
        return t / np.linalg.norm(t)

    def _correct(self, z0: np.ndarray, t: np.ndarray, ds: float, iterations: int = 12,
                 tolerance: float = 1e-10):  # fmt: skip
        """Newton on G(z) = 0, t . (z - z0) = ds from the predictor; (z, iterations) or
        (None, iterations)."""
        z = z0 + ds * t
        g0 = None
        for it in range(iterations):
            g, jac = self._g(z)
            if g0 is None:
                g0 = max(np.abs(g).max(), 1e-300)
            r = np.concatenate([g, [t @ (z - z0) - ds]])
            a = np.vstack([jac, t])
            try:
                dz = np.linalg.solve(a, -r)
            except np.linalg.LinAlgError:
                return None, it
            z = z + dz
            if not np.all(np.isfinite(z)):
                return None, it
            if np.abs(dz).max() < tolerance:
                return z, it + 1
        return None, iterations

    def _eigenvalues(self, z: np.ndarray) -> np.ndarray:
        x, mu = z[: self.m] * self.scale[: self.m], z[self.m] * self.scale[self.m]
        self.parameter.set(self.plane, mu)
        return np.linalg.eigvals(self.plane.jacobian(np.concatenate([x, np.zeros(self.m)])))

    def _tests(self, z: np.ndarray):
        """(det dG/dX (scaled, its sign), the complex margin, the eigenvalues) at z."""
        _, jac = self._g(z)
        lam = self._eigenvalues(z)
        return np.linalg.det(jac[:, : self.m]), _complex_margin(lam), lam

    # ---- the branch ---------------------------------------------------------------------------
    def run(self, x0: np.ndarray, mu0: float, mu_end: float, step: float = 0.02,
            largest: float = 0.1, points: int = 2000, tolerance: float = 1e-9,
            direction: np.ndarray | None = None) -> Branch:  # fmt: skip
        """The branch through the equilibrium ``x0`` (positions, corrected first) at ``mu0``,
        towards ``mu_end``, until the parameter passes ``mu_end`` or leaves the range between
        them by more than their distance, or ``points`` points; steps of ``step`` (scaled
        arclength) up to ``largest``. ``direction``: the first tangent (scaled; for branch
        switching), else towards ``mu_end``. Special points located to ``tolerance`` times the
        parameter's scale."""
        lo, hi = sorted((mu0, mu_end))
        span = hi - lo
        z = np.concatenate([np.asarray(x0, float) / self.scale[: self.m],
                            [mu0 / self.scale[self.m]]])  # fmt: skip
        fixed = np.zeros(self.m + 1)
        fixed[self.m] = 1.0
        z, _ = self._correct(z, fixed, 0.0)  # the equilibrium at mu0
        if z is None:
            raise ContinuationError(f"continuation in {self.parameter.name}: no equilibrium "
                                    f"near the start at {mu0:g}")  # fmt: skip
        if direction is None:
            _, jac = self._g(z)
            sign = 1.0 if mu_end >= mu0 else -1.0
            t = self._tangent(jac, sign * fixed)
        else:  # off a branch point: one step across the other branch, then along it
            t = np.asarray(direction, float) / np.linalg.norm(direction)
            z, _ = self._correct(z, t, step)
            if z is None:
                raise ContinuationError(f"continuation in {self.parameter.name}: no other "
                                        f"branch from the branch point at {mu0:g}")  # fmt: skip
            _, jac = self._g(z)
            t = self._tangent(jac, t)
        branch = Branch()
        det, margin, lam = self._tests(z)
        self._record(branch, z, lam)
        ds = step
        for _ in range(points):
            z1, its = self._correct(z, t, ds)
            if z1 is None:
                ds *= 0.5
                if ds < 1e-8:
                    break
                continue
            _, jac = self._g(z1)
            t1 = self._tangent(jac, t)
            det1, margin1, lam1 = self._tests(z1)
            if np.sign(det1) != np.sign(det) and det != 0.0:
                kind = "fold" if np.sign(t1[self.m]) != np.sign(t[self.m]) else "branch point"
                self._locate(branch, kind, z, t, ds, tolerance, lambda zz: self._tests(zz)[0])
            if math.isfinite(margin) and math.isfinite(margin1) and (margin < 0) != (margin1 < 0):
                self._locate(branch, "hopf", z, t, ds, tolerance, lambda zz: self._tests(zz)[1])
            z, t, det, margin = z1, t1, det1, margin1
            self._record(branch, z, lam1)
            mu = z[self.m] * self.scale[self.m]
            if (mu - mu0) * (mu_end - mu0) >= (mu_end - mu0) ** 2 or not (
                lo - span <= mu <= hi + span
            ):
                break
            if its <= 3:
                ds = min(1.5 * ds, largest)
        return branch

    def _record(self, branch: Branch, z: np.ndarray, lam: np.ndarray) -> None:
        branch.parameter.append(float(z[self.m] * self.scale[self.m]))
        branch.x.append(z[: self.m] * self.scale[: self.m])
        branch.unstable.append(_unstable(lam))
        branch.eigenvalues.append(lam)

    def _locate(self, branch, kind, z, t, ds, tolerance, test) -> None:
        """The special point between z (arclength 0) and arclength ds along t: the secant
        (Illinois) method on ``test`` in the arclength."""
        a, b = 0.0, ds
        fa, fb = test(z), test(self._correct(z, t, ds)[0])
        za = z
        point = None
        side = 0
        for _ in range(60):
            s = roots.trial(a, fa, b, fb)
            zs, _ = self._correct(za, t, s)
            if zs is None:
                return
            fs = test(zs)
            point = zs
            if abs(b - a) * max(abs(t[self.m]), 1e-3) < tolerance or fs == 0.0:
                break
            a, fa, b, fb, side = roots.narrow(a, fa, b, fb, s, fs, side)
            if abs(b - a) < tolerance * 1e-3:
                break
        if point is None:
            return
        lam = self._eigenvalues(point)
        pairs = lam[np.abs(lam.imag) > 1e-9 * np.maximum(np.abs(lam), 1e-12)]
        frequency = math.nan
        if kind == "hopf" and pairs.size:
            frequency = float(np.abs(pairs[np.argmin(np.abs(pairs.real))].imag))
        mu = float(point[self.m] * self.scale[self.m])
        branch.special.append(SpecialPoint(kind, mu, point[: self.m] * self.scale[: self.m],
                                           frequency))  # fmt: skip

    def null_direction(self, x: np.ndarray, mu: float) -> np.ndarray:
        """The scaled direction (phi, 0) of dG/dX's null vector at a branch point: the other
        branch's tangent at a symmetric pitchfork."""
        z = np.concatenate([x / self.scale[: self.m], [mu / self.scale[self.m]]])
        _, jac = self._g(z)
        _, _, vt = np.linalg.svd(jac[:, : self.m])
        return np.concatenate([vt[-1], [0.0]])
