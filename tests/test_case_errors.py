"""Bad case files give errors that name the path, the value and what is allowed."""

import copy
from pathlib import Path

import pytest

import seacable
from seacable import CaseError
from seacable.case.loader import case_base_dir, derive_case
from seacable.system import model

CHAIN = {
    "name": "test chain",
    "environment": {"in_air": True},
    "bodies": [
        {"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0]},
        {"name": "end", "type": "point", "position": [0.0, 0.0, -10.0], "mass": 1.0,
         "external forces": [{"model": "gravity"}]},
    ],
    "line_types": [{"name": "chain", "diameter": 0.01, "mass_per_length": 1.0}],
    "lines": [
        {"name": "cable", "model": "rigid_links", "from": "top", "to": "end",
         "sections": [{"type": "chain", "segments": 5, "length": 10.0}],
         "initial": {"arc_deg": [0.0, 0.0]}},
    ],
    "start": "as_given",
    "simulation": {"duration": 1.0, "output_interval": 0.1},
}  # fmt: skip


def _load(mutate):
    """A hanging chain of five links (a system of a fixed top, a point body at its end and a
    planar line between them) changed by ``mutate``, loaded."""
    data = copy.deepcopy(CHAIN)
    mutate(data)
    return seacable.load_case(data)


def _top(data, **body):
    data["bodies"][0] = {"name": "top", **body}


def test_unknown_key_lists_valid_keys():
    with pytest.raises(
        CaseError, match=r"lines\[0\]\.sections\[0\]: unknown key 'lenght'\. Valid keys: .*length"
    ):
        _load(lambda d: d["lines"][0]["sections"][0].update(lenght=3.0))


def test_unknown_top_level_key():
    with pytest.raises(CaseError, match=r"\(top level\): unknown key 'solver'.*simulation"):
        _load(lambda d: d.update(solver={}))


def test_value_out_of_range_names_path_and_value():
    with pytest.raises(
        CaseError,
        match=r"lines\[0\]\.sections\[0\]\.segments: .*greater than or equal to 1 \(got 0\)",
    ):
        _load(lambda d: d["lines"][0]["sections"][0].update(segments=0))


def test_negative_build_up_names_path_and_value():
    with pytest.raises(
        CaseError, match=r"simulation\.build_up: .*greater than or equal to 0 \(got -2\.0\)"
    ):
        _load(lambda d: d["simulation"].update(build_up=-2.0))


def test_negative_mass_of_a_body():
    with pytest.raises(
        CaseError, match=r"bodies\[1\]\.mass: .*greater than or equal to 0 \(got -5\)"
    ):
        _load(lambda d: d["bodies"][1].update(mass=-5))


def test_bad_body_type_lists_allowed():
    with pytest.raises(
        CaseError, match=r"bodies\[1\]\.type: value 'glued' is not allowed; allowed: 'fixed'"
    ):
        _load(lambda d: d["bodies"][1].update(type="glued"))


def test_missing_required_key():
    with pytest.raises(CaseError, match=r"line_types\[0\]\.diameter: required key is missing"):
        _load(lambda d: d["line_types"][0].pop("diameter"))


def test_exactly_one_of_the_initial_angle_keys():
    with pytest.raises(
        CaseError,
        match=r"invalid case \(1 problem\):\n- lines\[0\]\.initial: give exactly one of "
        r"'angles_deg' .* or 'arc_deg'",
    ):
        _load(lambda d: d["lines"][0]["initial"].update(angles_deg=[2.0] * 5))


def test_initial_angles_count_must_match():
    case = _load(lambda d: d["lines"][0].update(initial={"angles_deg": [1.0, 2.0]}))
    with pytest.raises(
        CaseError, match=r"lines \(cable\)\.initial\.angles_deg: 2 angles for a line of 5 segments"
    ):
        seacable.simulate(case)


def test_sine_needs_one_frequency():
    with pytest.raises(CaseError, match=r"bodies\[0\]\.x: give exactly one of 'period'"):
        _load(lambda d: _top(d, type="imposed", x={"kind": "sine", "amplitude": 1.0}))


def test_time_function_kind_must_be_known():
    with pytest.raises(
        CaseError, match=r"bodies\[0\]\.x\.kind: value 'cosine' is not allowed.*'sine'"
    ):
        _load(lambda d: _top(d, type="imposed", x={"kind": "cosine", "amplitude": 1.0}))


def test_angle_that_looks_like_radians_mistake():
    with pytest.raises(CaseError, match=r"lines\[0\]\.initial: angles are in degrees"):
        _load(lambda d: d["lines"][0].update(initial={"arc_deg": [700.0, 0.0]}))


def test_anchor_must_match_initial_shape():
    def mutate(d):
        d["bodies"][1] = {"name": "end", "type": "fixed", "position": [3.0, 0.0, -4.0]}
        d["lines"][0]["initial"] = {"arc_deg": [30, 90]}

    case = _load(mutate)
    with pytest.raises(
        CaseError,
        match=r"lines \(cable\)\.initial: the given angles end the line at .* but its 'to' "
        r"point is at \[3\.0, 0\.0, -4\.0\] m \(5\.121 m apart",
    ):
        seacable.simulate(case)


def test_a_line_to_an_unknown_body():
    with pytest.raises(
        CaseError, match=r"lines\[0\] \(cable\)\.to: 'bottom' names no body; bodies are"
    ):
        seacable.simulate(_load(lambda d: d["lines"][0].update(to="bottom")))


def test_output_interval_longer_than_duration():
    with pytest.raises(CaseError, match=r"output_interval \(5\.0 s\) is longer than duration"):
        _load(lambda d: d.update(simulation={"duration": 1.0, "output_interval": 5.0}))


def test_yaml_syntax_error(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text("lines: [\n")
    with pytest.raises(CaseError, match=r"not valid YAML"):
        seacable.load_case(path)


def test_missing_file(tmp_path):
    with pytest.raises(CaseError, match=r"does not exist"):
        seacable.load_case(tmp_path / "nope.yaml")


def test_yaml_is_never_evaluated(tmp_path):
    path = tmp_path / "evil.yaml"
    path.write_text("name: !!python/object/apply:os.system ['echo hacked']\n")
    with pytest.raises(CaseError, match=r"not valid YAML"):
        seacable.load_case(path)


def test_case_is_immutable():
    case = _load(lambda d: None)
    with pytest.raises(Exception, match="frozen"):
        case.lines[0].name = "rope"


def test_derived_case_is_validated_like_a_file():
    case = _load(lambda d: None)
    shorter = derive_case(case, {"simulation": {"duration": 0.5, "output_interval": 0.1}})
    assert shorter.simulation.duration == 0.5
    assert shorter.lines[0] == case.lines[0]
    assert derive_case(case, {"name": None}).name == "case"  # None removes a key
    with pytest.raises(CaseError, match=r"simulation\.duration: .*greater than 0 \(got -1\.0\)"):
        derive_case(case, {"simulation": {"duration": -1.0}})
    with pytest.raises(CaseError, match="not a whole number of output intervals"):
        derive_case(case, {"simulation": {"duration": 0.55, "output_interval": 0.1}})


def test_derived_case_reads_files_from_the_case_folder(monkeypatch, tmp_path):
    examples = Path(__file__).parent.parent / "examples"
    case = seacable.load_case(examples / "crane_tip_lowering_imposed_motion.yaml")
    monkeypatch.chdir(tmp_path)  # the table's relative file name must not depend on this
    derived = derive_case(case, {"simulation": {"duration": 1.0}})
    assert case_base_dir(derived) == case_base_dir(case) == str(examples.resolve())
    assert model.build(derived, case_base_dir(derived)) is not None


def test_duration_must_be_whole_number_of_outputs():
    with pytest.raises(
        CaseError, match=r"not a whole number of output intervals.*use duration 0\.9 or 1\.2"
    ):
        _load(lambda d: d.update(simulation={"duration": 1.0, "output_interval": 0.3}))


def test_missing_table_file_names_the_field():
    case = _load(lambda d: _top(d, type="imposed", x={"kind": "table", "file": "nope.csv"}))
    with pytest.raises(CaseError, match=r"bodies\[0\] \(top\)\.x: table file 'nope.csv' does not"):
        seacable.simulate(case)


def test_the_single_cable_form_is_refused_with_the_command_that_rewrites_it(tmp_path):
    path = tmp_path / "old.yaml"
    path.write_text("cables:\n- {links: 5, length: 10.0, diameter: 0.01, mass_per_length: 1.0}\n")
    with pytest.raises(CaseError, match=rf"^cables: .* seacable upgrade {path} -o system\.yaml$"):
        seacable.load_case(path)
    with pytest.raises(CaseError, match=r"^cables: .* seacable upgrade FILE -o system\.yaml$"):
        seacable.load_case({"cables": []})
