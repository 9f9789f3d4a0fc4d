"""Every example case runs (shortened to keep the suite fast)."""

from pathlib import Path

import numpy as np
import pytest

import seacable

EXAMPLES = sorted((Path(__file__).parent.parent / "examples").glob("*.yaml"))


def test_there_are_examples():
    assert len(EXAMPLES) >= 16


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_runs(path):
    case = seacable.load_case(path)
    short = case.simulation.model_copy(update={"duration": 1.0})
    case = case.model_copy(update={"simulation": short})
    results = seacable.simulate(case)
    assert results.status == "complete"
    assert np.all(np.isfinite(results["tension"].values))
    assert results.dataset.sizes["time"] == round(1.0 / short.output_interval) + 1


@pytest.mark.slow
@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_runs_in_full(path):
    results = seacable.simulate(seacable.load_case(path))
    assert results.status == "complete"
