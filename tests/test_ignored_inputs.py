"""Inputs that act on nothing are said where a case is checked (case.system.ignored_inputs,
simulation.prepare: seacable validate and every run): waves on a moving body none of whose
force models they act through, wind without any wind model. The examples say nothing."""

from pathlib import Path

import pytest
from click.testing import CliRunner

import seacable
from seacable.case.loader import case_text, derive_case
from seacable.case.system import ignored_inputs
from seacable.cli import main

EXAMPLES = Path(__file__).parent.parent / "examples"
PLATFORM = EXAMPLES / "platform_three_catenary_lines.yaml"
SEA = {"waves": [{"kind": "airy", "height": 6.0, "period": 10.0}]}


def test_waves_on_a_body_without_a_wave_model_are_said():
    case = derive_case(seacable.load_case(PLATFORM), {"environment": SEA})
    said = ignored_inputs(case)
    assert len(said) == 1 and said[0].startswith("bodies[3] (platform): the waves act on none")
    assert "non-linear Froude-Krylov" in said[0]


def test_wind_without_a_wind_model_is_said(tmp_path):
    wind = {"wind": {"speed": {"kind": "constant", "value": 20.0}}}
    case = derive_case(seacable.load_case(PLATFORM), {"environment": wind})
    assert [line.split(":")[0] for line in ignored_inputs(case)] == ["environment.wind"]
    path = tmp_path / "windy.yaml"
    path.write_text(case_text(case))
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 0 and "warning: " in result.stderr
    assert "environment.wind: no moving body has a 'wind' force model" in result.stderr


@pytest.mark.parametrize("example", sorted(EXAMPLES.glob("*.yaml")), ids=lambda p: p.stem)
def test_the_examples_ignore_nothing(example):
    assert ignored_inputs(seacable.load_case(example)) == []
