"""A line type's fatigue curve (``line_types[].fatigue``): a curve of a standard by its name,
or the user's own, for the damage ``seacable sweep`` and ``seacable.fatigue`` give."""

from typing import Literal

from pydantic import model_validator

from seacable.case.base import Pos, _Model

# API RP 2SK (3rd edition, 2005), its T-N curves N R^M = K, R the tension range over the
# reference breaking strength: (M, K) or, for ropes, (M, a, b) with log10 K = a - b Lm, Lm the
# mean tension over the breaking strength
API = {
    "api_studless_chain": (3.36, 316.0),
    "api_studlink_chain": (3.36, 1000.0),
    "api_six_strand_rope": (4.09, 3.20, 2.79),
    "api_spiral_strand_rope": (5.05, 3.25, 3.43),
}
# DNV-OS-E301, its S-N curves n = a_D s^-m, s the stress range [MPa] on the component's
# nominal area: (m, a_D)
DNV = {
    "dnv_studlink_chain": (3.0, 1.2e11),
    "dnv_studless_chain": (3.0, 6.0e10),
    "dnv_stranded_rope": (4.0, 3.4e14),
    "dnv_spiral_rope": (4.8, 1.7e17),
}
Curve = Literal["api_studless_chain", "api_studlink_chain", "api_six_strand_rope",
                "api_spiral_strand_rope", "dnv_studlink_chain", "dnv_studless_chain",
                "dnv_stranded_rope", "dnv_spiral_rope"]  # fmt: skip


class Fatigue(_Model):
    """A fatigue curve: ``curve``, one of API RP 2SK's T-N curves (their ranges over the line
    type's ``breaking_strength``) or DNV-OS-E301's S-N curves (their stress ranges on the
    nominal ``area``), with the constants those documents give (check them against your
    edition); or the user's own N R^m = k, R the tension range over ``reference``."""

    curve: Curve | None = None
    """The standard's curve. Omitted: the own curve of ``m`` and ``k``."""
    m: Pos | None = None
    """[-] The own curve's exponent m of N R^m = k."""
    k: Pos | None = None
    """[-] The own curve's constant k of N R^m = k."""
    reference: Pos | None = None
    """[N] The own curve's unit of range: R is the tension range over it. Omitted: the line
    type's breaking strength (as API RP 2SK's curves)."""
    area: Pos | None = None
    """[m^2] Nominal area of a DNV curve's component, on which the stress range is taken (as
    DNV-OS-E301 defines it for the component)."""

    @model_validator(mode="after")
    def _complete(self):
        own = self.m is not None or self.k is not None or self.reference is not None
        if self.curve is None and (self.m is None or self.k is None):
            raise ValueError("give a 'curve' (one of " + ", ".join([*API, *DNV]) + ") or an "
                             "own curve's 'm' and 'k' (N R^m = k)")  # fmt: skip
        if self.curve is not None and own:
            raise ValueError(f"curve '{self.curve}' has its own constants; remove m, k and "
                             "reference, or the curve")  # fmt: skip
        if (self.curve in DNV) != (self.area is not None):
            raise ValueError("'area' [m^2] is a DNV curve's nominal area: give it with a dnv_ "
                             "curve, and only there")  # fmt: skip
        return self
