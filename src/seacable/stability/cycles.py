"""Branches of periodic orbits born at a Hopf point, continued in a parameter, and the Hopf
point's criticality settled by simulation.

**The branch.** A periodic orbit is a zero of R(x0, T, mu) = (phi_T(x0; mu) - x0, p . (x0 -
x_r)): the flow of the system (``orbits.flow``, RK4 split at the ties' kinks) returns to its
start after the period T, and x0 lies on the hyperplane through the last orbit's start x_r
normal to the flow there (p). In scaled variables z = (x0 / s_x, T / T_H, mu / s_mu) the orbits
form a curve, followed by pseudo-arclength (Keller) as the equilibria are
(``stability.continuation``): predictor z_k + ds t_k, Newton on R = 0 with t_k . (z - z_k) = ds,
the Jacobian [M - I, f(phi_T) T_H, d phi / d mu s_mu; p, 0, 0] (M the monodromy matrix by
central differences, d phi / d mu by a central difference). At the Hopf point (x_H, mu_H, the
critical pair i omega with eigenvector q) the branch starts along Re q with T = 2 pi / omega;
the first phase condition is normal to Im q (the small orbit's velocity at its start). The
Floquet multipliers are M's eigenvalues; an orbit is stable when all but the one at 1 lie
inside the unit circle. A fold of cycles is where the parameter turns back along the branch.

**Multiple shooting** beside an unstable equilibrium: where another eigenvalue grows by
exp(Re lambda T) over a period (e^13 at the shuttle's reversed equilibrium), single shooting's
Newton diverges. The orbit is then cut into m segments (``segments``: each growing by e^2 at
most), its unknowns every segment's start x_i, T and mu, its residual phi_{T/m}(x_i) -
x_{i+1} (cyclically) and the phase condition on x_0; the Jacobian has the segments'
monodromies M_i on its diagonal and -I beside them, the monodromy is M_{m-1} ... M_0. The
arclength is measured on x_0, T and mu (the other starts follow), so that one segment is
single shooting, as before. The predictor puts the starts on the small orbit x_H + e Re(q
exp(2 pi i k / m)).

**Criticality by simulation.** The hull forces' |v| v terms are not smooth enough for the usual
normal-form coefficient, so the Hopf point's kind is judged from the motion itself: on the
side where the equilibrium is unstable, at mu_H + delta and mu_H + delta / 4, the motion from
the equilibrium pushed along Re q is integrated, 10 periods at a time, until its amplitude
settles (``_settled``; a motion still growing or shrinking after ``most`` periods gives no
verdict: "undecided"). A supercritical point's cycles shrink to nothing at the Hopf point
(their amplitude falls by at least 30 % from delta to delta / 4: by half for a smooth field,
as sqrt(delta), by three quarters for a |v| v one, as delta); a subcritical point's motion
leaves for a distant cycle (or diverges) however close to mu_H. For a subcritical point the
motion is then started from that distant cycle on the stable side, at mu_H - delta: if it
keeps cycling there, the equilibrium and the large cycle coexist (hysteresis). A Hopf point
where a second pair crosses (the equilibrium already unstable on both sides) no simulation
can judge, and where the simulations are undecided, the branch does (``by`` "branch"):
supercritical when its first (smallest) cycle lies on the side where the crossing pair is
unstable, subcritical on the other.
"""

import math
from dataclasses import dataclass, field, replace

import numpy as np

from seacable.stability import equilibria, orbits
from seacable.stability.continuation import ContinuationError, Parameter
from seacable.stability.plane import Plane


@dataclass
class CycleBranch:
    """Periodic orbits along a parameter: at each point the parameter, period [s], start x0
    (and its segments' starts, ``starts``, with multiple shooting), amplitudes (peak to peak
    of each free body's x, y [m] and heading [rad]) and the least and largest of each along
    the orbit (``low``, ``high``), Floquet multipliers and stability; the folds of cycles
    found (parameter values)."""

    parameter: list[float] = field(default_factory=list)
    period: list[float] = field(default_factory=list)
    x0: list[np.ndarray] = field(default_factory=list)
    amplitude: list[np.ndarray] = field(default_factory=list)
    low: list[np.ndarray] = field(default_factory=list)
    high: list[np.ndarray] = field(default_factory=list)
    multipliers: list[np.ndarray] = field(default_factory=list)
    stable: list[bool] = field(default_factory=list)
    folds: list[float] = field(default_factory=list)
    starts: list[np.ndarray] = field(default_factory=list)  # each orbit's segments' (m, n)


@dataclass
class Criticality:
    """A Hopf point's kind judged by simulation (module docstring): ``kind`` (supercritical,
    subcritical, undecided; "not judged" when the equilibrium is unstable on both sides of
    it: a second pair crossing, whose cycles no simulation can settle on), the parameter
    values tried on the unstable side and the settled amplitudes there (the largest scaled
    peak to peak), and for a subcritical point whether the large cycle persists on the
    stable side (``hysteresis``)."""

    kind: str
    parameters: tuple[float, float]
    amplitudes: tuple[float, float]
    hysteresis: bool | None = None
    by: str = "simulation"  # or "branch": the side its cycles lie on (``from_hopf``)


def _stable(multipliers: np.ndarray) -> bool:
    others = np.delete(multipliers, np.argmin(np.abs(multipliers - 1.0)))
    return bool(np.all(np.abs(others) < 1.0))


class CycleContinuation:
    """Pseudo-arclength continuation of ``plane``'s periodic orbits in ``parameter``."""

    def __init__(self, plane: Plane, parameter: Parameter, period: float, segments: int = 1):
        self.plane = plane
        self.parameter = parameter
        self.n = plane.size
        self.scale = orbits._scales(plane)
        self.period = period  # T_H: the period's scale
        self.steps = 0  # RK4 steps a period
        self.segments = segments  # m: multiple shooting's (module docstring)
        # the arclength's metric: the first start, the period and the parameter
        self.mask = np.zeros(segments * self.n + 2)
        self.mask[: self.n] = self.mask[-2:] = 1.0

    def _unpack(self, z: np.ndarray) -> tuple[np.ndarray, float, float]:
        """The segments' starts (m, n), the period and the parameter."""
        n, m = self.n, self.segments
        starts = z[: m * n].reshape(m, n) * self.scale
        return starts, z[m * n] * self.period, z[m * n + 1] * self.parameter.scale

    def _residual(self, z: np.ndarray, ref: np.ndarray, normal: np.ndarray, jacobian: bool):
        """R and its Jacobian ((m n + 1) x (m n + 2), scaled) at z; the monodromy matrix (the
        product of the segments')."""
        n, m = self.n, self.segments
        starts, t, mu = self._unpack(z)
        steps = -(-self.steps // m)
        self.parameter.set(self.plane, mu)
        ends = [orbits.integrate(self.plane, x, t / m, steps)[0] for x in starts]
        gaps = [(ends[i] - starts[(i + 1) % m]) / self.scale for i in range(m)]
        r = np.concatenate([*gaps, [normal @ ((starts[0] - ref) / self.scale)]])
        if not jacobian:
            return r, None, None
        jac = np.zeros((m * n + 1, m * n + 2))
        monodromy = np.eye(n)
        h = 1e-4 * self.parameter.scale
        for i, x in enumerate(starts):
            rows = slice(i * n, (i + 1) * n)
            part = orbits._monodromy(self.plane, x, t / m, steps, self.scale)
            monodromy = part @ monodromy
            jac[rows, i * n : (i + 1) * n] = part
            jac[rows, (i + 1) % m * n : ((i + 1) % m + 1) * n] -= np.eye(n)
            jac[rows, m * n] = self.plane.rates(ends[i]) / self.scale * self.period / m
            self.parameter.set(self.plane, mu + h)
            up, _ = orbits.integrate(self.plane, x, t / m, steps)
            self.parameter.set(self.plane, mu - h)
            down, _ = orbits.integrate(self.plane, x, t / m, steps)
            self.parameter.set(self.plane, mu)
            jac[rows, m * n + 1] = (up - down) / (2 * h) / self.scale * self.parameter.scale
        jac[m * n, :n] = normal
        return r, jac, monodromy

    def _correct(self, z0, t, ds, ref, normal, iterations=8, tolerance=1e-8):
        """Newton from the predictor: (z, its, monodromy) or (None, its, None)."""
        z = z0 + ds * t
        along = t * self.mask
        for it in range(iterations):
            try:
                r, jac, monodromy = self._residual(z, ref, normal, True)
            except FloatingPointError:
                return None, it, None
            a = np.vstack([jac, along])
            rhs = -np.concatenate([r, [along @ (z - z0) - ds]])
            try:
                dz = np.linalg.solve(a, rhs)
            except np.linalg.LinAlgError:
                return None, it, None
            z = z + dz
            if not (np.all(np.isfinite(z)) and z[self.segments * self.n] > 0.0):
                return None, it, None
            if np.abs(dz).max() < tolerance and np.abs(r).max() < 1e3 * tolerance:
                return z, it + 1, monodromy
        return None, iterations, None

    def _norm(self, t: np.ndarray) -> np.ndarray:
        """``t`` of unit length in the arclength's metric (``mask``)."""
        return t / math.sqrt(float(t @ (t * self.mask)))

    def _tangent(self, jac: np.ndarray, previous: np.ndarray) -> np.ndarray:
        a = np.vstack([jac, previous * self.mask])
        rhs = np.zeros(jac.shape[1])
        rhs[-1] = 1.0
        t = self._norm(np.linalg.solve(a, rhs))
        return t if t @ (previous * self.mask) > 0 else -t

    def from_hopf(self, x_hopf: np.ndarray, mu_hopf: float, vector: np.ndarray,
                  bounds: tuple[float, float], step: float = 0.5, largest: float = 20.0,
                  points: int = 40) -> CycleBranch:  # fmt: skip
        """The branch from the Hopf point (the state ``x_hopf``, velocities zero; ``vector``
        the critical eigenvector, complex) until the parameter leaves ``bounds``, the period
        grows beyond 20 T_H, or ``points`` orbits; steps of ``step`` up to ``largest``
        (scaled arclength: about metres of amplitude)."""
        n, m = self.n, self.segments
        self.steps = orbits._steps(self.plane, x_hopf, self.period)
        # the small orbit x_H + e Re(q exp(i w t)) at the segments' starts, t = i T_H / m
        phases = np.exp(2j * math.pi * np.arange(m) / m)
        z = np.concatenate([np.tile(x_hopf / self.scale, m), [1.0, mu_hopf / self.parameter.scale]])
        along = np.concatenate([*((vector * c).real / self.scale for c in phases), [0.0, 0.0]])
        t = self._norm(along)
        normal = -vector.imag / self.scale
        normal /= np.linalg.norm(normal)
        ref = x_hopf.copy()
        branch = CycleBranch()
        ds, points_z = step, [z]
        for _ in range(points):
            z1, its, monodromy = self._correct(z, t, ds, ref, normal)
            if z1 is None:  # a first orbit that will not come gives up sooner
                ds *= 0.5
                if ds < (1e-3 if branch.parameter else 0.1) * step:
                    break
                continue
            starts, period, mu = self._unpack(z1)
            x = starts[0]
            _, jac, _ = self._residual(z1, ref, normal, True)
            t1 = self._tangent(jac, t)
            points_z.append(z1)
            if branch.parameter and np.sign(t1[m * n + 1]) != np.sign(t[m * n + 1]):
                branch.folds.append(_vertex(points_z, m * n + 1) * self.parameter.scale)
            self._record(branch, starts, period, mu, monodromy)
            z, t = z1, t1
            ref = x.copy()  # the next phase condition: normal to the flow at this start
            normal = self.plane.rates(x) / self.scale
            normal /= max(np.linalg.norm(normal), 1e-300)
            if not (bounds[0] <= mu <= bounds[1]) or period > 20 * self.period:
                break
            if its <= 3:
                ds = min(1.5 * ds, largest)
        return branch

    def _record(self, branch, starts, period, mu, monodromy) -> None:
        steps = -(-self.steps // self.segments)
        path = np.vstack([orbits.integrate(self.plane, x, period / self.segments, steps,
                                           record=True)[1] for x in starts])  # fmt: skip
        x = starts[0]
        m = 3 * len(self.plane.bodies)
        multipliers = np.linalg.eigvals(monodromy)
        branch.parameter.append(float(mu))
        branch.period.append(float(period))
        branch.x0.append(x.copy())
        branch.starts.append(np.array(starts))
        branch.amplitude.append(np.ptp(path[:, :m], axis=0))
        branch.low.append(path[:, :m].min(axis=0))
        branch.high.append(path[:, :m].max(axis=0))
        branch.multipliers.append(multipliers)
        branch.stable.append(_stable(multipliers))


def _vertex(zs: list[np.ndarray], k: int) -> float:
    """The parameter's extremum (a fold of cycles) near the last of the scaled points ``zs``:
    the vertex of the parabola through the last three in the arclength between them (the
    extreme point of the last two when there are only two)."""
    pts = zs[-3:]
    mus = [z[k] for z in pts]
    if len(pts) < 3:
        return max(mus, key=abs)
    gaps = [np.linalg.norm(pts[i + 1] - pts[i]) for i in range(2)]
    s = np.concatenate([[0.0], np.cumsum(gaps)])
    c = np.polyfit(s, mus, 2)
    if c[0] == 0.0:
        return max(mus, key=abs)
    top = -c[1] / (2 * c[0])
    return float(np.polyval(c, min(max(top, s[0]), s[-1])))


def criticality(plane: Plane, parameter: Parameter, x_hopf: np.ndarray, mu_hopf: float,
                vector: np.ndarray, period: float, delta: float,
                most: int = 3000) -> Criticality:  # fmt: skip
    """The Hopf point's kind by simulation (module docstring): ``delta`` the parameter's
    offset, each run at most ``most`` periods."""
    scale = orbits._scales(plane)
    push = vector.real / np.abs(vector.real / scale).max() * 0.1  # 10 cm (or 1e-4 rad) at most
    n = plane.size
    start = np.concatenate([x_hopf[: n // 2], np.zeros(n // 2)])
    side, judged = unstable_side(plane, parameter, start, mu_hopf, delta)
    if not judged:  # its cycles live beside an unstable equilibrium: no run settles on them
        return Criticality("not judged", (math.nan, math.nan), (math.nan, math.nan))
    per = max(400, orbits._steps(plane, start, period) // 5)
    trials = (mu_hopf + side * delta, mu_hopf + side * delta / 4)
    amplitudes, far, settled = [], None, True
    for mu in trials:
        parameter.set(plane, mu)
        amplitude, state, done = _settled(plane, _rest(plane, start) + push, period, per, most)
        amplitudes.append(amplitude)
        settled = settled and done
        far = state if far is None else far
    big, small = amplitudes
    if not math.isfinite(small) or (settled and small > 0.85 * big):
        kind = "subcritical"
    elif not settled:  # still growing or shrinking after ``most`` periods: no verdict
        kind = "undecided"
    elif small < 0.7 * big:
        kind = "supercritical"
    else:
        kind = "undecided"
    hysteresis = None
    if kind == "subcritical" and far is not None and np.all(np.isfinite(far)):
        parameter.set(plane, mu_hopf - side * delta)
        stays, _, _ = _settled(plane, far, period, per, most)
        hysteresis = bool(math.isfinite(stays) and stays > 0.5 * big)
    parameter.set(plane, mu_hopf)
    return Criticality(kind, trials, (big, small), hysteresis)


def unstable_side(plane: Plane, parameter: Parameter, start: np.ndarray, mu: float,
                  delta: float) -> tuple[float, bool]:  # fmt: skip
    """(+1 when the equilibrium has more unstable eigenvalues above the Hopf point's parameter
    ``mu`` (at mu + delta) than below, else -1; whether the other side is stable, so that a
    simulation can tell the Hopf point's kind)."""
    counts = []
    for mu_side in (mu + delta, mu - delta):
        parameter.set(plane, mu_side)
        lam = np.linalg.eigvals(plane.jacobian(_rest(plane, start)))
        counts.append(int(np.sum(lam.real > 0.0)))
    parameter.set(plane, mu)
    return (1.0 if counts[0] > counts[1] else -1.0), min(counts) == 0


def _rest(plane: Plane, start: np.ndarray) -> np.ndarray:
    """The equilibrium nearest ``start`` (positions, then zero velocities)."""
    m = plane.size // 2
    found = equilibria.find(plane, None, 0, extra=[start[:m]])
    if not found:
        raise ContinuationError("criticality: no equilibrium near the Hopf point's")
    x = min(found, key=lambda e: float(np.abs(e.x - start[:m]).sum())).x
    return np.concatenate([x, np.zeros(m)])


def _settled(plane: Plane, x0: np.ndarray, period: float, per: int,
             most: int) -> tuple[float, np.ndarray, bool]:  # fmt: skip
    """The settled amplitude of the motion from ``x0`` (0 at rest, inf when it diverges), the
    last state, and whether it settled within ``most`` periods (else the last amplitude):
    ``orbits.settle``'s, in runs of 10 periods (``per`` steps a period)."""
    windows = max(3, most // 10)
    went = orbits.settle(plane, x0, period, per, (windows - 0.5) * 10 * period)
    return went.amplitude, went.state, went.status in ("cycle", "rest", "diverged")


def from_hopf(plane: Plane, parameter: Parameter, x_hopf: np.ndarray, mu_hopf: float,
              frequency: float, bounds: tuple[float, float], points: int,
              delta: float) -> tuple[CycleBranch, Criticality]:  # fmt: skip
    """The branch of periodic orbits from the Hopf point (positions ``x_hopf`` at ``mu_hopf``,
    the pair +- i ``frequency``) and its criticality by simulation (offset ``delta``)."""
    n = plane.size
    parameter.set(plane, mu_hopf)
    state = np.concatenate([x_hopf, np.zeros(n // 2)])
    lam, vectors = np.linalg.eig(plane.jacobian(state))
    k = int(np.argmin(np.abs(lam.real) + np.abs(np.abs(lam.imag) - frequency)))
    vector = vectors[:, k] if lam[k].imag > 0 else vectors[:, k].conj()
    period = 2 * math.pi / frequency
    kind = criticality(plane, parameter, state, mu_hopf, vector, period, delta)
    branch = CycleContinuation(plane, parameter, period, segments(lam, period)).from_hopf(
        state, mu_hopf, vector, bounds, points=points
    )
    parameter.set(plane, mu_hopf)
    if kind.kind in ("not judged", "undecided") and branch.parameter:  # its cycles' side says
        side, _ = unstable_side(plane, parameter, state, mu_hopf, delta)
        first = branch.parameter[0] - mu_hopf  # the smallest cycle: the point's own side
        if abs(first) > 1e-9 * parameter.scale:
            kind = replace(kind, kind="supercritical" if np.sign(first) == side
                           else "subcritical", by="branch")  # fmt: skip
    return branch, kind


def segments(eigenvalues: np.ndarray, period: float) -> int:
    """Multiple shooting's segments for orbits near an equilibrium of ``eigenvalues``: each
    short enough that its fastest growth, exp(Re lambda T / m), stays below exp(2) (one
    segment, single shooting, beside a stable equilibrium)."""
    growth = max(float(np.max(eigenvalues.real)), 0.0) * period
    return max(1, math.ceil(growth / 2.0))


__all__ = [
    "segments",
    "CycleBranch",
    "CycleContinuation",
    "Criticality",
    "criticality",
    "from_hopf",
    "unstable_side",
]
