"""Values that look like the wrong unit are warned, naming the field and the unit it takes
(``case.units``); none of the examples is."""

import copy
from pathlib import Path

import pytest
import yaml

import seacable
from seacable.case.units import unit_warnings

EXAMPLES = sorted(Path("examples").glob("*.yaml"))
BUOYS = yaml.safe_load(Path("examples/two_buoys_moored_with_hawser.yaml").read_text())


def _set(data, keys, value):
    for key in keys[:-1]:
        data = data[key]
    data[keys[-1]] = value


@pytest.mark.parametrize(
    "keys, value, expected",
    [
        (["line_types", 0, "diameter"], 90.0, "line_types[0] (chain50).diameter: 90 m is wider"),
        (["line_types", 0, "mass_per_length"], 55000.0, "mass_per_length: 55000 kg/m is heavier"),
        (["line_types", 0, "axial_stiffness"], 2.5e4,
         "line_types[0] (chain50).axial_stiffness: EA 25000 N over the area of a 0.09 m line is "
         "a modulus of 3.93e+06 Pa, softer than rubber; EA is in N (25000 kN would be 2.5e+07)"),
        (["environment", "water_density"], 1.025,
         "environment.water_density: 1.025 kg/m^3 is far from water's (1025 for sea water)"),
        (["environment", "water_depth"], 50000.0,
         "environment.water_depth: 50000 m is deeper than any ocean"),
        (["environment", "gravity"], 32.2, "environment.gravity: 32.2 m/s^2 is not the earth's"),
        (["bodies", 6, "mass"], 20.0,
         "bodies[6] (buoy_a).mass: 20 kg for 78.54 m^3 is 0.255 kg/m^3, lighter than air-filled "
         "steel; masses are in kg (20 t would be 20000)"),
        (["bodies", 7, "external forces", 3, "force_x", "phase"], 90.0,
         "phase: 90 rad is more than a turn; phases are in radians"),
    ],
)  # fmt: skip
def test_a_value_in_the_wrong_unit_is_warned_naming_the_field(keys, value, expected):
    data = copy.deepcopy(BUOYS)
    _set(data, keys, value)
    warnings = unit_warnings(seacable.load_case(data))
    assert any(expected in w for w in warnings), warnings


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_no_example_is_warned(path):
    assert unit_warnings(seacable.load_case(path)) == []


TURRET = yaml.safe_load(Path("examples/turret_fpso_catenary_mooring.yaml").read_text())


@pytest.mark.parametrize(
    "change, expected",
    [
        (lambda rows: [[r[0] * 3.141592653589793 / 180.0, *r[1:]] for r in rows],
         r"coefficients: its directions run from 0 to 3.14159, within one turn in radians"),
        (lambda rows: [[r[0], *(1000.0 * c for c in r[1:])] for r in rows],
         r"coefficients: a coefficient of 850, where OCIMF's are of order one"),
    ],
)  # fmt: skip
def test_wind_coefficients_in_radians_or_scaled_are_warned(tmp_path, change, expected):
    """Wind directions given in radians, or coefficients a thousand times too large, ran
    without a word (issue 42); as inline rows and as a CSV file."""
    import re

    data = copy.deepcopy(TURRET)
    wind = next(f for b in data["bodies"] for f in b.get("external forces", [])
                if f.get("model") == "wind")  # fmt: skip
    rows = change(wind["coefficients"])
    for given in (rows, "wind.csv"):
        (tmp_path / "wind.csv").write_text(
            "psi_deg,C_X,C_Y,C_N\n" + "".join(",".join(map(str, r)) + "\n" for r in rows)
        )
        wind["coefficients"] = given
        case_file = tmp_path / "case.yaml"
        case_file.write_text(yaml.safe_dump(data, sort_keys=False))
        said = unit_warnings(seacable.load_case(case_file))
        assert len(said) == 1 and re.search(expected, said[0]), said
