"""Values that look like the wrong unit: warnings naming the field, the value and the unit
the field takes (a 20 m line diameter was meant as 20 mm; a phase of 90 in a field in radians
was meant in degrees). Warned, not refused: a value can be odd and right."""

import math

from seacable.case.base import Sine, instances
from seacable.case.system import LineType, PointBody, RigidBody, SystemCase

LIGHTEST_BODY = 10.0  # [kg/m^3] a body's mass over its volume below this: tonnes given as kg?
SOFTEST_LINE = 1e7  # [Pa] EA over the line's area pi d^2 / 4 below this: EA given in kN?
DEEPEST_SEA = 11000.0  # [m] the deepest ocean


def unit_warnings(case: SystemCase) -> list[str]:
    """One line per value that looks like the wrong unit."""
    out = _environment(case)
    for k, kind in enumerate(case.line_types):
        out += _line_type(f"line_types[{k}] ({kind.name})", kind)
    for k, body in enumerate(case.bodies):
        if not isinstance(body, (PointBody, RigidBody)):
            continue
        volume = body.displaced_volume()
        if volume > 0.0 and body.mass / volume < LIGHTEST_BODY:
            out.append(
                f"bodies[{k}] ({body.name}).mass: {body.mass:g} kg for {volume:.4g} m^3 is "
                f"{body.mass / volume:.3g} kg/m^3, lighter than air-filled steel; masses are "
                f"in kg ({body.mass:g} t would be {1000 * body.mass:g})"
            )
    for where, sine in instances(case, Sine):
        if abs(sine.phase) > 2.0 * math.pi:
            out.append(
                f"{where}.phase: {sine.phase:g} rad is more than a turn; phases are in radians "
                f"({sine.phase:g} degrees would be {math.radians(sine.phase):.4g})"
            )
    return out


def _environment(case: SystemCase) -> list[str]:
    env, out = case.environment, []
    if not env.in_air and not 500.0 <= env.water_density <= 2000.0:
        out.append(
            f"environment.water_density: {env.water_density:g} kg/m^3 is far from water's "
            f"(1025 for sea water); the unit is kg/m^3 ({env.water_density:g} t/m^3 would be "
            f"{1000 * env.water_density:g})"
        )
    if env.water_depth is not None and env.water_depth > DEEPEST_SEA:
        out.append(
            f"environment.water_depth: {env.water_depth:g} m is deeper than any ocean "
            f"({DEEPEST_SEA:g} m); depths are in metres"
        )
    if not 9.7 <= env.gravity <= 9.9:
        out.append(
            f"environment.gravity: {env.gravity:g} m/s^2 is not the earth's (9.81); the unit is "
            "m/s^2"
        )
    return out


def _line_type(where: str, kind: LineType) -> list[str]:
    out = []
    area = math.pi * kind.diameter**2 / 4.0
    if kind.axial_stiffness is not None and kind.axial_stiffness / area < SOFTEST_LINE:
        out.append(
            f"{where}.axial_stiffness: EA {kind.axial_stiffness:g} N over the area of a "
            f"{kind.diameter:g} m line is a modulus of {kind.axial_stiffness / area:.3g} Pa, "
            f"softer than rubber; EA is in N ({kind.axial_stiffness:g} kN would be "
            f"{1000 * kind.axial_stiffness:g})"
        )
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
