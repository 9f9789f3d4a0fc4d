"""Breaking strength and utilisation: each line section's largest tension and its share of
its line type's breaking strength, from a statics and from a run, printed by the command line;
the warning at validate when the start already exceeds the case's utilisation limit."""

from pathlib import Path

import numpy as np
import pytest
import yaml
from click.testing import CliRunner

import seacable
from seacable import analysis
from seacable.cli import main

BUOY = Path(__file__).parents[1] / "examples" / "buoy_three_lines_clump_weight.yaml"
STRENGTH = {"wire": 2.0e5, "polyester": 1.5e6, "chain": 6.0e6}  # [N]


def _case(limit: float | None = None, duration: float = 2.0) -> dict:
    case = yaml.safe_load(BUOY.read_text())
    for kind in case["line_types"]:
        kind["breaking_strength"] = STRENGTH[kind["name"]]
    if limit is not None:
        case["utilisation_limit"] = limit
    case["simulation"]["duration"] = duration
    return case


def test_each_section_against_its_own_breaking_strength():
    """A line of polyester then chain: two sections, each its segments' largest tension over
    its own type's strength."""
    case = seacable.load_case(_case())
    results = seacable.statics(case)
    loads = analysis.line_utilisation(results, case)
    two = [load for load in loads if load.line == case.lines[3].name]
    assert [(load.section, load.line_type) for load in two] == [(0, "polyester"), (1, "chain")]
    tension = results.dataset[f"lines/{case.lines[3].name}"].to_dataset()["tension"].values[0]
    assert two[0].largest_tension == pytest.approx(tension[:15].max(), rel=1e-12)
    assert two[1].largest_tension == pytest.approx(tension[15:].max(), rel=1e-12)
    assert two[1].utilisation == pytest.approx(tension[15:].max() / 6.0e6, rel=1e-12)
    assert len(loads) == sum(len(line.sections) for line in case.lines)


def test_a_run_takes_the_largest_tension_over_its_times(tmp_path):
    case = seacable.load_case(_case(duration=3.0))
    results = seacable.simulate(case)
    loads = analysis.line_utilisation(results)  # the case read back from the results
    tension = results.dataset[f"lines/{case.lines[0].name}"].to_dataset()["tension"].values
    assert loads[0].largest_tension == pytest.approx(np.nanmax(tension), rel=1e-12)
    assert loads[0].utilisation == pytest.approx(np.nanmax(tension) / 2.0e5, rel=1e-12)


def test_the_command_line_prints_it_and_validate_warns_over_the_limit(tmp_path):
    statics = analysis.line_utilisation(seacable.statics(seacable.load_case(_case())))
    worst = max(load.utilisation for load in statics)
    below, above = tmp_path / "below.yaml", tmp_path / "above.yaml"
    below.write_text(yaml.safe_dump(_case(limit=1.01 * worst)))
    above.write_text(yaml.safe_dump(_case(limit=0.99 * worst)))
    quiet = CliRunner().invoke(main, ["validate", str(below)])
    assert quiet.exit_code == 0 and "breaking strength" not in quiet.output, quiet.output
    warned = CliRunner().invoke(main, ["validate", str(above)])
    assert warned.exit_code == 0, warned.output
    assert "% of its breaking strength, above utilisation_limit" in warned.output
    printed = CliRunner().invoke(main, ["statics", str(below), "-o", str(tmp_path / "s.nc")])
    assert printed.exit_code == 0, printed.output
    assert printed.output.count("of its breaking strength") == len(statics)
