"""Values that look like the wrong unit: warnings naming the field, the value and the unit
the field takes (a 20 m line diameter was meant as 20 mm; a phase of 90 in a field in radians
was meant in degrees). Warned, not refused: a value can be odd and right."""

import math

from seacable.case.base import Sine, instances
from seacable.case.system import LineType, SystemCase


def unit_warnings(case: SystemCase) -> list[str]:
    """One line per value that looks like the wrong unit."""
    out = []
    for k, kind in enumerate(case.line_types):
        out += _line_type(f"line_types[{k}] ({kind.name})", kind)
    for where, sine in instances(case, Sine):
        if abs(sine.phase) > 2.0 * math.pi:
            out.append(
                f"{where}.phase: {sine.phase:g} rad is more than a turn; phases are in radians "
                f"({sine.phase:g} degrees would be {math.radians(sine.phase):.4g})"
            )
    return out


def _line_type(where: str, kind: LineType) -> list[str]:
    out = []
    if kind.diameter > 1.0:
        out.append(
            f"{where}.diameter: {kind.diameter:g} m is wider than any line; diameters are in "
            f"metres ({kind.diameter:g} mm would be {kind.diameter / 1000:g})"
        )
    if kind.mass_per_length > 2000.0:
        out.append(
            f"{where}.mass_per_length: {kind.mass_per_length:g} kg/m is heavier than any chain; "
            "the unit is kg per metre"
        )
    return out
