"""Fatigue damage of a line's tension on its line type's curve (``case.fatigue``): the
rainflow cycles of the tension (seacable.stats) summed by Miner's rule on the curve, an API RP
2SK T-N curve (ranges over the breaking strength; a rope's constant from the mean tension),
a DNV-OS-E301 S-N curve (stress ranges [MPa] on the nominal area) or the user's own."""

import math

import numpy as np

from seacable import stats
from seacable.case.fatigue import API, DNV
from seacable.case.system import LineType

SECONDS_PER_YEAR = 365.25 * 86400.0


def curve(line_type: LineType, mean_tension: float) -> tuple[float, float, float]:
    """The curve of ``line_type`` as N R^m = k with R the range over ``reference`` [N]: (k, m,
    reference); an API rope's k at the mean tension [N] over the breaking strength."""
    given = line_type.fatigue
    if given is None:
        raise ValueError(f"line type '{line_type.name}' has no fatigue curve")
    strength = line_type.breaking_strength
    if given.curve in API:
        constants = API[given.curve]
        assert strength is not None  # the line type's validation asks for it
        if len(constants) == 2:
            return constants[1], constants[0], strength
        m, a, b = constants
        return 10.0 ** (a - b * mean_tension / strength), m, strength
    if given.curve in DNV:
        m, a_d = DNV[given.curve]
        assert given.area is not None
        return a_d, m, given.area * 1e6  # a stress of 1 MPa on the area: 1e6 area newtons
    assert given.k is not None and given.m is not None
    reference = given.reference if given.reference is not None else strength
    assert reference is not None
    return given.k, given.m, reference


def damage(tension, line_type: LineType) -> float:
    """Miner's damage of a tension series [N] on ``line_type``'s curve (NaN without one)."""
    if line_type.fatigue is None:
        return math.nan
    x = np.asarray(tension, dtype=float)
    k, m, reference = curve(line_type, float(np.mean(x)))
    return stats.damage(x, k, m, reference)
