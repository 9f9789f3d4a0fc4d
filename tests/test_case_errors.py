"""Bad case files give errors that name the path, the value and what is allowed."""

from pathlib import Path

import pytest

import seacable
from helpers import chain_case
from seacable import CaseError
from seacable.case.loader import case_base_dir, derive_case
from seacable.simulation import build_system


def _load(mutate):
    data = chain_case(n=5)
    mutate(data)
    return seacable.load_case(data)


def test_unknown_key_lists_valid_keys():
    with pytest.raises(
        CaseError, match=r"cables\[0\]: unknown key 'lenght'\. Valid keys: .*length"
    ):
        _load(lambda d: d["cables"][0].update(lenght=3.0))


def test_unknown_top_level_key():
    with pytest.raises(CaseError, match=r"\(top level\): unknown key 'solver'.*simulation"):
        _load(lambda d: d.update(solver={}))


def test_value_out_of_range_names_path_and_value():
    with pytest.raises(
        CaseError, match=r"cables\[0\]\.links: .*greater than or equal to 1 \(got 0\)"
    ):
        _load(lambda d: d["cables"][0].update(links=0))


def test_negative_build_up_names_path_and_value():
    with pytest.raises(
        CaseError, match=r"simulation\.build_up: .*greater than or equal to 0 \(got -2\.0\)"
    ):
        _load(lambda d: d["simulation"].update(build_up=-2.0))


def test_negative_mass_of_floating_structure():
    def mutate(d):
        d["cables"][0]["top"] = {"type": "floating_structure", "mass": -5, "heave_stiffness": 1}

    with pytest.raises(CaseError, match=r"cables\[0\]\.top\.mass: .*greater than 0 \(got -5\)"):
        _load(mutate)


def test_bad_end_type_lists_allowed():
    with pytest.raises(
        CaseError, match=r"bottom\.type: value 'glued' is not allowed; allowed: 'free'"
    ):
        _load(lambda d: d["cables"][0].update(bottom={"type": "glued"}))


def test_missing_required_key():
    with pytest.raises(CaseError, match=r"cables\[0\]\.diameter: required key is missing"):
        _load(lambda d: d["cables"][0].pop("diameter"))


def test_exactly_one_of_length_keys():
    with pytest.raises(CaseError, match=r"exactly one of 'length' \[m\] or 'link_lengths'"):
        _load(lambda d: d["cables"][0].update(link_lengths=[2.0] * 5))


def test_link_lengths_count_must_match():
    def mutate(d):
        d["cables"][0].pop("length")
        d["cables"][0]["link_lengths"] = [1.0, 2.0]

    with pytest.raises(CaseError, match=r"link_lengths has 2 values but links = 5"):
        _load(mutate)


def test_sine_needs_one_frequency():
    def mutate(d):
        d["cables"][0]["top"] = {"type": "imposed", "x": {"kind": "sine", "amplitude": 1.0}}

    with pytest.raises(CaseError, match=r"top\.x.*exactly one of 'period'"):
        _load(mutate)


def test_time_function_kind_must_be_known():
    def mutate(d):
        d["cables"][0]["top"] = {"type": "imposed", "x": {"kind": "cosine", "amplitude": 1.0}}

    with pytest.raises(CaseError, match=r"top\.x\.kind: value 'cosine' is not allowed.*'sine'"):
        _load(mutate)


def test_angle_that_looks_like_radians_mistake():
    with pytest.raises(CaseError, match=r"degrees"):
        _load(lambda d: d["cables"][0].update(initial={"shape": "arc", "top_angle_deg": 700.0}))


def test_pinned_anchor_must_match_initial_shape():
    def mutate(d):
        d["cables"][0]["bottom"] = {"type": "pinned", "anchor": [3.0, -4.0]}
        d["cables"][0]["initial"] = {"shape": "arc", "top_angle_deg": 30, "bottom_angle_deg": 90}

    case = _load(mutate)
    with pytest.raises(
        CaseError, match=r"bottom\.anchor: value \[3\.0, -4\.0\] is .* m from the end"
    ):
        seacable.simulate(case)


def test_several_cables_need_a_shared_body():
    with pytest.raises(
        CaseError, match=r"several cables \(2\) must all be attached to one shared body"
    ):
        _load(lambda d: d["cables"].append(d["cables"][0]))


def test_output_interval_longer_than_duration():
    with pytest.raises(CaseError, match=r"output_interval \(5\.0 s\) is longer than duration"):
        _load(lambda d: d.update(simulation={"duration": 1.0, "output_interval": 5.0}))


def test_yaml_syntax_error(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text("cables: [\n")
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
        case.cables[0].links = 3


def test_derived_case_is_validated_like_a_file():
    case = _load(lambda d: None)
    shorter = derive_case(case, {"simulation": {"duration": 0.5, "output_interval": 0.1}})
    assert shorter.simulation.duration == 0.5
    assert shorter.cables[0] == case.cables[0]
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
    assert build_system(derived) is not None


def test_mass_keys_are_exclusive_and_counted():
    with pytest.raises(
        CaseError,
        match=r"exactly one of 'mass_per_length'.*got \['mass_per_length', 'link_masses'\]",
    ):
        _load(lambda d: d["cables"][0].update(link_masses=[1.0] * 5))

    def mutate(d):
        d["cables"][0].pop("mass_per_length")
        d["cables"][0]["link_masses"] = [1.0, 2.0]

    with pytest.raises(CaseError, match=r"link_masses has 2 values but links = 5"):
        _load(mutate)


def test_duration_must_be_whole_number_of_outputs():
    with pytest.raises(
        CaseError, match=r"not a whole number of output intervals.*use duration 0\.9 or 1\.2"
    ):
        _load(lambda d: d.update(simulation={"duration": 1.0, "output_interval": 0.3}))


def test_missing_table_file_names_the_field(tmp_path):
    def mutate(d):
        d["cables"][0]["top"] = {"type": "imposed", "x": {"kind": "table", "file": "nope.csv"}}

    case = _load(mutate)
    with pytest.raises(
        CaseError, match=r"cables\[0\]\.top\.x: table file 'nope.csv' does not exist"
    ):
        seacable.simulate(case)
