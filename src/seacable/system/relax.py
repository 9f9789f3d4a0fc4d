"""Dynamic relaxation: the statics' last resort, the system let move from its start until it
rests.

Newton (``system.statics``) finds a balance near its start, and none when the balance lies
far away and the way there turns the system a lot (a body hung off its centre of gravity,
which must turn 60 degrees under its eye; a ball between two rigid lines written as a tree).
Letting the system move and taking its kinetic energy away finds a balance from any start,
as form-finding codes do (and, with damping instead, MoorDyn's initialisation). Here with
kinetic damping (Barnes): the motion is integrated as it is (classical Runge-Kutta, at the
statics' time: imposed motions and time functions stay where they are), and every time the
kinetic energy stops growing every velocity is set back to zero. A reset takes kinetic
energy away and leaves the potential, so without other sources of energy the system comes to
rest in a minimum of its potential: a stable balance. Each step is checked against two
half-steps (an unstable step disagrees with them by far more than its error), shortened
when they disagree and lengthened when they agree closely, from a first step of one over the
fastest natural frequency (``system.frequency``). The relaxation stops near the balance;
Newton then finds it to the statics' tolerance.
"""

from typing import NamedTuple

import numpy as np

from seacable.system import kernel, outputs
from seacable.system.assemble import BuiltSystem


class Relaxed(NamedTuple):
    """What the relaxation ended with: its last state (None when it did not start: a tow, no
    step that stays finite), and whether that state rests near a balance."""

    state: np.ndarray | None
    rested: bool


RUNAWAY = 5000  # steps without a reset (the kinetic energy growing all along): no balance


class _Kinetic:
    """The kinetic energy [J] of a state (``system.energy`` through the compiled outputs)."""

    def __init__(self, p: kernel.SystemParams, time: float):
        self.p, self.w, self.times = p, kernel.make_work(p), np.full(1, time)
        self.rows = outputs.allocate(p, 1)

    def __call__(self, y: np.ndarray) -> float:
        outputs.fill(self.times, y[None, :], self.p, self.w, self.rows)
        return float(self.rows.energy[0, 0])


def relax(built: BuiltSystem, y: np.ndarray, residual, target: float, fastest: float,
          time: float = 0.0, steps: int = 20000) -> Relaxed:  # fmt: skip
    """A state near a stable balance, from ``y`` at rest (``rested``), or the last state met
    when the system does not rest within ``steps`` steps. ``residual``: the statics' residual
    of a state (system.coordinates.Residual), small enough once its largest entry is below
    ``target``; ``fastest``: the system's fastest natural frequency [rad/s] (steps at most
    2.5 / fastest, within the scheme's stability). It stops as well when the kinetic energy
    grows for ``RUNAWAY`` steps without a reset (a body pushed that nothing holds runs away:
    the last state shows which). A tow (bodies moving at t = ``time``) is not relaxed: its
    balance is in motion."""
    p = built.params
    n = p.n_q + p.n_v
    if not np.isfinite(fastest) or fastest <= 0.0 or np.any(y[p.n_q : n] != 0.0):
        return Relaxed(None, False)
    w = kernel.make_work(p)
    kinetic = _Kinetic(p, time)
    k = np.empty((4, len(y)))
    y = y.copy()
    h = 1.0 / fastest  # the classical Runge-Kutta scheme is stable to 2.8 / omega
    previous = 0.0
    reset = 0
    for step in range(steps):
        if step - reset > RUNAWAY:
            return Relaxed(y, False)  # nothing stops it: no balance to rest in
        trial, h = _step(time, y, h, p, w, k, 2.5 / fastest)
        if trial is None:
            return Relaxed(None, False)
        trial[n:] = y[n:]  # force models' states stay as they are
        energy = kinetic(trial)
        if energy < previous:  # past the peak of the kinetic energy: take it all away
            trial[p.n_q : n] = 0.0
            energy = 0.0
            reset = step
        y, previous = trial, energy
        if energy == 0.0:  # at every reset (a tenth of them missed a soft mode's balance)
            r = residual(y)
            if np.all(np.isfinite(r)) and np.abs(r).max() < target:
                return Relaxed(y, True)
    return Relaxed(y, False)


def _step(time, y, h, p, w, k, longest: float, smallest: float = 1e-9):
    """A step from ``y`` and the length for the next one: a step of ``h`` and two of h / 2
    that agree to 1e-3 of the state (relative, or absolute below 1), else h halved and tried
    again (an unstable step disagrees with its halves by far more), h grown by a quarter up to
    ``longest`` when they agree to 1e-5. (None, h) when h falls below ``smallest`` [s]."""
    while h >= smallest:
        whole = _rk4(time, y, h, p, w, k)
        halves = _rk4(time, _rk4(time, y, 0.5 * h, p, w, k), 0.5 * h, p, w, k)
        error = np.abs(whole - halves) / (1.0 + np.abs(halves))
        largest = float(error.max()) if np.all(np.isfinite(error)) else np.inf
        if largest <= 1e-3:
            return halves, (min(1.25 * h, longest) if largest < 1e-5 else h)
        h *= 0.5
    return None, h


def _rk4(time, y, h, p, w, k):
    """One classical Runge-Kutta step of length ``h`` at the frozen time ``time``, projected
    (unit quaternions and directors)."""
    kernel.rhs(time, y, p, w, k[0])
    kernel.rhs(time, y + 0.5 * h * k[0], p, w, k[1])
    kernel.rhs(time, y + 0.5 * h * k[1], p, w, k[2])
    kernel.rhs(time, y + h * k[2], p, w, k[3])
    out = y + (h / 6.0) * (k[0] + 2.0 * k[1] + 2.0 * k[2] + k[3])
    kernel.project(out, p, w)
    return out
