"""Every example case runs (shortened to keep the suite fast) and ``seacable plot`` draws it."""

import logging
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import seacable
from seacable.case.loader import derive_case
from seacable.cli import main

EXAMPLES = sorted((Path(__file__).parent.parent / "examples").glob("*.yaml"))


def test_there_are_examples():
    assert len(EXAMPLES) >= 16


def _warnings(caplog) -> list[str]:
    return [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_runs_and_plots(path, tmp_path, caplog):
    """Each example runs clean (no warning: an example shows what it means to), and draws."""
    case = derive_case(seacable.load_case(path), {"simulation": {"duration": 1.0}})
    output = tmp_path / "results.nc"
    with caplog.at_level(logging.WARNING, logger="seacable"):
        results = seacable.simulate(case, output=output)
    assert results.status == "complete"
    assert not _warnings(caplog)
    data = results.dataset
    if isinstance(data, xr.DataTree):  # a system: every line's tensions (a ship may have none)
        lines = data["lines"].children.values() if "lines" in data.children else []
        tensions = [node["tension"].values for node in lines]
    else:
        tensions = [data["tension"].values]
    assert all(np.all(np.isfinite(t)) for t in tensions)
    assert data.sizes["time"] == round(1.0 / case.simulation.output_interval) + 1
    # the picture of every kind of result, from the file as a user would draw it
    picture = tmp_path / "results.png"
    outcome = CliRunner().invoke(main, ["plot", str(output), "-o", str(picture)])
    assert outcome.exit_code == 0, outcome.output + repr(outcome.exception)
    assert picture.stat().st_size > 10_000


@pytest.mark.slow
@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_runs_in_full(path, caplog):
    with caplog.at_level(logging.WARNING, logger="seacable"):
        results = seacable.simulate(seacable.load_case(path))
    assert results.status == "complete"
    assert not _warnings(caplog)


def test_the_case_file_in_the_docs_builds():
    """The case-file block of docs/features.md (the README's before) is a valid case whose
    bodies sit where its line ends."""
    from seacable.system import model

    text = (Path(__file__).parent.parent / "docs" / "features.md").read_text()
    start = text.index("```yaml\nenvironment:") + len("```yaml\n")
    case = seacable.load_case(text[start : text.index("```", start)])
    built = model.build(case)
    assert built.params.rs_n[0] == 60
