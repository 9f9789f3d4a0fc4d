"""Values that look like the wrong unit: warnings naming the field, the value and the unit
the field takes (a 20 m line diameter was meant as 20 mm; a phase of 90 in a field in radians
was meant in degrees). Warned, not refused: a value can be odd and right."""

import math
from pathlib import Path

from seacable import files
from seacable.case.base import LARGEST_TABLE, Constant, Sine, instances
from seacable.case.ship_forces import CurrentLoad, Propeller, WindLoad
from seacable.case.system import LineType, PointBody, RigidBody, SystemCase
from seacable.errors import SeacableError

LIGHTEST_BODY = 10.0  # [kg/m^3] a body's mass over its volume below this: tonnes given as kg?
SOFTEST_LINE = 1e7  # [Pa] EA over the line's area pi d^2 / 4 below this: EA given in kN?
DEEPEST_SEA = 11000.0  # [m] the deepest ocean
LARGEST_COEFFICIENT = 20.0  # [-] OCIMF's wind and current coefficients are of order one
SLOWEST_PROPELLER = 10.0  # [rpm] a ship's propeller turns faster (rev/s given as rpm?)
WIDEST_PROPELLER = 15.0  # [m] the largest ships' propellers are about 11 m across (mm as m?)


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
    for cls in (WindLoad, CurrentLoad):
        for where, load in instances(case, cls):
            out += _coefficients(where, load, case._base_dir)
    out += _propellers(case)
    for where, sine in instances(case, Sine):
        if abs(sine.phase) > 2.0 * math.pi:
            out.append(
                f"{where}.phase: {sine.phase:g} rad is more than a turn; phases are in radians "
                f"({sine.phase:g} degrees would be {math.radians(sine.phase):.4g})"
            )
    return out


def _propellers(case: SystemCase) -> list[str]:
    """A propeller's constant rpm slower than a ship's propeller turns, its diameter wider."""
    out = []
    for where, spec in instances(case, Propeller):
        if isinstance(spec.rpm, Constant) and 0.0 < spec.rpm.value < SLOWEST_PROPELLER:
            value = spec.rpm.value
            out.append(f"{where}.rpm: {value:g} rpm is slower than a ship's propeller turns; "
                       f"the unit is revolutions per minute ({value:g} rev/s would be "
                       f"{60 * value:g})")  # fmt: skip
        if spec.diameter > WIDEST_PROPELLER:
            out.append(f"{where}.diameter: {spec.diameter:g} m is wider than any ship's "
                       "propeller (about 11 m at most); diameters are in m "
                       f"({spec.diameter:g} mm would be {spec.diameter / 1000:g})")  # fmt: skip
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


def _coefficients(where: str, load, base_dir) -> list[str]:
    """A wind or current load's table whose directions look like radians (all within one
    turn's radians, over several rows) or whose coefficients look scaled (beyond
    LARGEST_COEFFICIENT, where OCIMF's are of order one)."""
    rows = load.coefficients
    if isinstance(rows, str):
        path = Path(base_dir or ".") / rows
        try:
            text = files.read_text(path, "coefficients file", LARGEST_TABLE)
            rows = []
            for _, cells in files.csv_rows(text, f"coefficients file '{path}'"):
                try:
                    rows.append([float(c) for c in cells])
                except ValueError:
                    continue  # a header line
        except SeacableError:
            return []  # the force model refuses the file, naming it
    if len(rows) < 3 or any(len(row) < 4 for row in rows):
        return []
    out = []
    angles = [row[0] for row in rows]
    if max(abs(a) for a in angles) <= 2.0 * math.pi + 1e-9 and max(angles) > min(angles):
        out.append(
            f"{where}.coefficients: its directions run from {min(angles):g} to {max(angles):g}, "
            "within one turn in radians; they are in degrees (psi_deg)"
        )
    largest = max(abs(c) for row in rows for c in row[1:4])
    if largest > LARGEST_COEFFICIENT:
        out.append(
            f"{where}.coefficients: a coefficient of {largest:g}, where OCIMF's are of order one; "
            "they are dimensionless (C_X, C_Y, C_N), the force q A C"
        )
    return out
