"""Fatigue of mooring lines: the curves of API RP 2SK and DNV-OS-E301 as the case names them
(their constants written out here from the documents' forms), Miner's damage of a sine's
cycles on each against the closed form n (R / reference)^m / k, the refusals of incomplete
curves, and a sweep's damage per run and a year over its load cases' shares of the time."""

import math
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable import fatigue
from seacable import sweep as batch
from seacable.case import loader
from seacable.case.system import LineType
from seacable.errors import CaseError

CHAIN = {"name": "chain", "diameter": 0.137, "mass_per_length": 126.0, "axial_stiffness": 5.8e8,
         "breaking_strength": 4.9e6}  # fmt: skip
EXAMPLE = Path(__file__).parent.parent / "examples" / "spread_mooring_in_waves.yaml"


def _type(**fatigue_curve) -> LineType:
    return LineType(**CHAIN, fatigue=fatigue_curve)


def _sine(mean: float, tension_range: float, cycles: int = 10) -> np.ndarray:
    t = np.linspace(0.0, 10.0 * cycles, 2000 * cycles + 1)
    return mean - 0.5 * tension_range * np.cos(2.0 * np.pi * t / 10.0)


@pytest.mark.parametrize(
    ("given", "k", "m", "reference"),
    [({"curve": "api_studless_chain"}, lambda lm: 316.0, 3.36, 4.9e6),
     ({"curve": "api_studlink_chain"}, lambda lm: 1000.0, 3.36, 4.9e6),
     ({"curve": "api_six_strand_rope"}, lambda lm: 10 ** (3.20 - 2.79 * lm), 4.09, 4.9e6),
     ({"curve": "api_spiral_strand_rope"}, lambda lm: 10 ** (3.25 - 3.43 * lm), 5.05, 4.9e6),
     ({"curve": "dnv_studless_chain", "area": 0.0295}, lambda lm: 6.0e10, 3.0, 0.0295e6),
     ({"curve": "dnv_studlink_chain", "area": 0.0295}, lambda lm: 1.2e11, 3.0, 0.0295e6),
     ({"curve": "dnv_stranded_rope", "area": 0.01}, lambda lm: 3.4e14, 4.0, 1e4),
     ({"curve": "dnv_spiral_rope", "area": 0.01}, lambda lm: 1.7e17, 4.8, 1e4),
     ({"m": 3.0, "k": 1e12, "reference": 1e3}, lambda lm: 1e12, 3.0, 1e3),
     ({"m": 3.0, "k": 500.0}, lambda lm: 500.0, 3.0, 4.9e6)],
)  # fmt: skip
def test_each_curve_and_the_damage_of_a_sines_cycles(given, k, m, reference):
    """A rope's constant from its mean load over the breaking strength, Lm."""
    kind = _type(**given)
    assert fatigue.curve(kind, 0.2 * 4.9e6) == pytest.approx((k(0.2), m, reference))
    tension = _sine(0.2 * 4.9e6, 4.0e5)
    lm = tension.mean() / 4.9e6
    expected = 10 * (4.0e5 / reference) ** m / k(lm)  # ten whole cycles of range 400 kN
    assert fatigue.damage(tension, kind) == pytest.approx(expected, rel=1e-6)


@pytest.mark.parametrize(
    ("given", "said"),
    [({}, "give a 'curve'"), ({"curve": "api_studless_chain", "m": 3.0}, "own constants"),
     ({"curve": "dnv_studless_chain"}, "'area'"), ({"curve": "api_studless_chain",
                                                    "area": 0.01}, "'area'"),
     ({"curve": "iso_chain"}, "api_studless_chain")],
)  # fmt: skip
def test_incomplete_curves_are_refused(given, said):
    with pytest.raises(ValueError, match=said):
        _type(**given)
    with pytest.raises(ValueError, match="breaking_strength"):
        LineType(**{**CHAIN, "breaking_strength": None}, fatigue={"curve": "api_studless_chain"})


def test_a_sweeps_damage_and_its_damage_a_year(tmp_path):
    case = loader.with_settings(seacable.load_case(EXAMPLE), [
        "simulation.duration=4", "simulation.build_up=1",
        "line_types[0].fatigue={curve: api_studless_chain}"])  # fmt: skip
    heights = batch.parse_vary("environment.waves[0].significant_height=2,5")
    todo = batch.plan(case, [heights.model_copy(update={"probabilities": [0.7, 0.3]})])
    found = batch.execute(todo, tmp_path / "s.nc", None)
    year = 365.25 * 86400.0
    expected = np.zeros(4)
    for k in range(2):
        results = seacable.Results.open(tmp_path / "s.runs" / str(found["file"].values[k]))
        kept = results["time"].values >= 1.0  # from the end of the build-up
        t = results["time"].values[kept]
        for j, line in enumerate(case.lines):
            tension = results[f"lines/{line.name}/tension"].values[kept]
            ends = tension[:, [0, -1]]
            end = ends[:, int(np.argmax(ends.mean(axis=0)))]
            d = fatigue.damage(end, case.line_types[0])
            assert float(found["damage"].values[k, j]) == pytest.approx(d, rel=1e-12)
            expected[j] += [0.7, 0.3][k] * d * year / (t[-1] - t[0])
    np.testing.assert_allclose(found["annual_damage"].values, expected, rtol=1e-12)
    np.testing.assert_allclose(found["fatigue_life"].values, 1.0 / expected, rtol=1e-12)
    assert all(math.isfinite(v) and v > 0 for v in found["annual_damage"].values)


def test_a_curve_in_a_case_file_is_checked_as_the_file_is():
    with pytest.raises(CaseError, match=r"line_types\[0\]\.fatigue"):
        loader.with_settings(seacable.load_case(EXAMPLE),
                             ["line_types[0].fatigue={curve: dnv_studless_chain}"])  # fmt: skip


def test_a_yearly_damage_is_unknown_where_a_load_case_of_some_share_has_none():
    """Two load cases, half the year each, of 100 s: the yearly damage is the shares' sum of
    damage x year / 100 s; a line without damage in a load case of some share (no curve, or a
    run that did not complete) has neither a yearly damage nor a life (NaN, not infinity), and
    a load case of no share does not count."""
    from seacable import sweep_summary

    damage = np.array([[1e-6, np.nan, 0.0], [3e-6, 1e-6, 0.0], [np.nan, np.nan, np.nan]])
    found = sweep_summary._lives(np.array([0.5, 0.5, 0.0]), damage, np.full(3, 100.0))
    year = 365.25 * 86400.0
    annual, life = found["annual_damage"][1], found["fatigue_life"][1]
    assert annual[0] == pytest.approx(0.5 * 4e-6 * year / 100.0)
    assert life[0] == pytest.approx(1.0 / annual[0])
    assert math.isnan(annual[1]) and math.isnan(life[1])
    assert annual[2] == 0.0 and life[2] == math.inf  # no cycles at all: no fatigue
