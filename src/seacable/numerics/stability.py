"""The longest stable step of the classical Runge-Kutta scheme (rk4) for a system: from the
eigenvalues of its fastest motions (``system.frequency``) and the scheme's stability function.

A step h maps a mode e^(lambda t) to R(h lambda) times itself, R(z) = 1 + z + z^2/2 + z^3/6
+ z^4/24; the exact solution multiplies it by e^(h lambda). The step is stable for a mode
while |R(h lambda)| <= max(1, |e^(h lambda)|): a damped or undamped mode must not grow, a mode
the physics makes grow (a body pushed off an unstable balance) may grow as it does. For an
undamped oscillation (lambda = i omega) the limit is h omega = 2 sqrt 2 = 2.83; for a damped
one on the real axis, 2.79; in between, up to about 3.
"""

from typing import NamedTuple

import numpy as np

from seacable.system.assemble import BuiltSystem
from seacable.system.frequency import fastest_modes

GRID = 4096  # trial steps per eigenvalue, up to 4 / |lambda|: the limit to 1e-3 of itself


def rk4_factor(z: np.ndarray) -> np.ndarray:
    """The classical Runge-Kutta scheme's amplification R(z) of a mode over a step, z = h lambda."""
    return 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0)))


def rk4_stable_step(values: np.ndarray) -> float:
    """The longest step [s] at which no mode of eigenvalues ``values`` [1/s] grows faster under
    rk4 than it does in time (infinite for no eigenvalue, or only zero ones)."""
    limit = np.inf
    for value in np.asarray(values, dtype=complex):
        size = abs(value)
        if size == 0.0:
            continue
        h = np.linspace(4.0 / size / GRID, 4.0 / size, GRID)
        z = h * value
        grows = np.abs(rk4_factor(z)) > np.maximum(1.0, np.abs(np.exp(z))) * (1.0 + 1e-12)
        if grows.any():
            first = int(np.argmax(grows))
            limit = min(limit, float(h[first - 1]) if first else 0.0)
    return limit


class Rk4Limit(NamedTuple):
    """rk4's longest stable step [s] about a system's state, the fastest motion's frequency
    [rad/s] and where it moves most."""

    step: float
    frequency: float
    what: str


def rk4_limit(system: BuiltSystem, y: np.ndarray | None = None, time: float = 0.0) -> Rk4Limit:
    """rk4's stability limit for ``system`` about ``y`` (default: its initial state)."""
    modes = fastest_modes(system, y, time)
    frequency = float(np.abs(modes.values).max()) if modes.values.size else 0.0
    return Rk4Limit(rk4_stable_step(modes.values), frequency, modes.what)
