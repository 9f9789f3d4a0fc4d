"""Every example matches its golden result (tests/golden/, recorded by tests/golden/record.py):
a 1 s run at the recorded tight settings, every variable within 1e-9 of its scale."""

import numpy as np
import pytest
import yaml

from golden.record import (
    compare_to_golden,
    example_path,
    example_stems,
    golden_changes,
    golden_path,
    load_golden,
    run,
)

STEMS = example_stems()


def test_every_example_has_a_golden_result():
    """Every single-cable example has a golden file, and every golden file its example."""
    examples = {p.stem for p in example_path("x").parent.glob("*.yaml")}
    cables = [s for s in examples if "\ncables:" in example_path(s).read_text()]
    missing = [stem for stem in cables if not golden_path(stem).exists()]
    assert not missing, f"no golden result for {missing}: run tests/golden/record.py {missing}"
    orphans = sorted(set(STEMS) - examples)
    assert not orphans, f"golden files without an example: {orphans}"


@pytest.mark.parametrize("stem", STEMS)  # each under 3 s after compilation (none is slow)
def test_example_matches_its_golden_result(stem):
    golden = load_golden(stem)
    results = run(stem, golden_changes(golden))
    failures = compare_to_golden(golden, results, label=stem)
    for name in golden.coords:
        if name not in results:  # a system names its segments and nodes by arc length
            assert name in ("node", "segment", "link_length", "cable"), name
            continue
        if not np.allclose(np.asarray(results[name]), golden[name].values, rtol=1e-12, atol=0.0):
            failures.append(f"{stem}: coordinate '{name}' differs from the golden one")
    assert not failures, "\n".join(failures)


def test_a_small_change_of_the_physics_is_caught():
    """A cable density 1e-6 larger is seen (the comparison can fail) and named."""
    stem = "thesis_6_1_sim2_submerged_12_links"
    golden = load_golden(stem)
    changes = golden_changes(golden)
    case_changes = dict(changes, line_types=[_heavier_cable(stem)])
    failures = compare_to_golden(golden, run(stem, case_changes), label=stem)
    assert failures
    assert any("'tension' differs by" in line for line in failures), failures


def _heavier_cable(stem):
    data = yaml.safe_load(example_path(stem).read_text())
    line_type = data["line_types"][0]
    line_type["mass_per_length"] *= 1 + 1e-6
    return line_type


def test_comparison_maps_new_names_and_reports_missing_ones():
    golden = load_golden("thesis_6_1_sim1_air_12_links")
    renamed = {f"new_{name}": golden[name].values for name in golden.data_vars}
    mapping = {f"new_{name}": name for name in golden.data_vars}
    assert compare_to_golden(golden, renamed, names=mapping, label="renamed") == []
    del mapping["new_tension"]
    failures = compare_to_golden(golden, renamed, names=mapping, label="renamed")
    assert failures == ["renamed: golden variable 'tension' has no counterpart in the run"]
    shifted = dict(renamed)
    shifted["new_top_force_x"] = renamed["new_top_force_x"].copy()
    shifted["new_top_force_x"][3] *= 1 + 1e-6
    del mapping["new_top_force_x"]
    mapping["new_top_force_x"] = "top_force_x"
    failures = compare_to_golden(golden, shifted, names=mapping, label="renamed")
    assert len(failures) == 2
    scale = np.abs(golden["top_force_x"].values).max()
    error = 1e-6 * abs(golden["top_force_x"].values[3]) / scale
    assert (
        f"renamed: 'top_force_x' differs by {error:.3g} of its scale (allowed 1e-09) at time=3:"
        in ("\n".join(failures))
    )
