"""Bad case files give errors that name the path, the value and what is allowed."""

import copy
import re
from pathlib import Path

import numpy as np
import pytest
import yaml

import seacable
from seacable import CaseError
from seacable.case.loader import case_base_dir, case_text, derive_case
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
        match=r"^lines\[0\]\.initial: give exactly one of "
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


# ---- numbers that are not numbers, and files that are not cases ----------------------------------
@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf")])
@pytest.mark.parametrize(
    ("where", "put"),
    [
        ("lines[0].sections[0].length", lambda d, v: d["lines"][0]["sections"][0].update(length=v)),
        ("simulation.duration", lambda d, v: d["simulation"].update(duration=v)),
        ("bodies[1].mass", lambda d, v: d["bodies"][1].update(mass=v)),
        ("bodies[1].position[2]", lambda d, v: d["bodies"][1].update(position=[0.0, 0.0, v])),
        ("line_types[0].diameter", lambda d, v: d["line_types"][0].update(diameter=v)),
    ],
)  # fmt: skip
def test_nan_and_infinities_are_refused_naming_the_field(where, put, bad):
    """Before, an infinite length, diameter or mass was accepted and the run "diverged at
    t = 0" without naming it, and an infinite duration ended in a traceback."""
    with pytest.raises(CaseError, match=re.escape(where) + r".*finite number \(got -?(nan|inf)\)"):
        _load(lambda d: put(d, bad))


@pytest.mark.parametrize(
    ("where", "put"),
    [
        ("simulation.output_interval", lambda d: d["simulation"].update(output_interval=True)),
        ("lines[0].sections[0].segments",
         lambda d: d["lines"][0]["sections"][0].update(segments=True)),
        ("bodies[0].position", lambda d: d["bodies"][0].update(position=[0.0, False, 0.0])),
        ("lines[0].name", lambda d: d["lines"][0].update(name=False)),
    ],
)  # fmt: skip
def test_booleans_are_not_numbers(where, put):
    """YAML reads true, yes and on as booleans, and pydantic would take them for 1: a
    ``links: true`` ran."""
    with pytest.raises(CaseError, match=re.escape(where) + r": true/false .* not a number"):
        _load(put)


def test_a_boolean_field_takes_a_boolean():
    assert _load(lambda d: d["environment"].update(in_air=True)).environment.in_air is True


def _text(case: dict) -> str:
    return yaml.safe_dump(case, sort_keys=False)


def test_a_key_given_twice_is_refused_with_both_lines(tmp_path):
    path = tmp_path / "case.yaml"
    path.write_text(_text(CHAIN) + "name: again\n")
    with pytest.raises(CaseError, match=r"key 'name' is given twice in one mapping \(lines 1 and"):
        seacable.load_case(path)


def test_anchors_aliases_and_merge_keys_still_read(tmp_path):
    """Anchors, aliases and merge keys (a merged key given again overrides, not a duplicate)."""
    text = _text(CHAIN).replace("  mass: 1.0\n", "  mass: &one 1.0\n")
    text = text.replace("  mass_per_length: 1.0\n", "  mass_per_length: *one\n")
    text = text.replace("  sections:\n  - type: chain\n    segments: 5\n    length: 10.0\n",
                        "  sections:\n  - <<: {type: chain, segments: 3, length: 10.0}\n"
                        "    segments: 5\n")  # fmt: skip
    assert "*one" in text and "<<:" in text
    path = tmp_path / "case.yaml"
    path.write_text(text)
    case = seacable.load_case(path)
    assert case.lines[0].sections[0].segments == 5
    assert case.line_types[0].mass_per_length == 1.0


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("# caf\xe9\n".encode("latin-1"), r"not UTF-8 text \(byte 0xe9 at position 5\)"),
        ("name: x\n".encode("utf-16"), r"not UTF-8 text \(byte 0xff at position 0\)"),
        (b"\x89HDF\r\n\x1a\n" + bytes(100), r"is a results file \(NetCDF/HDF5\), not a case"),
        (b"a: " + b"[" * 5000 + b"]" * 5000, r"nested too deeply"),
        (b"a: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n"
         + b"".join(b"%c: &%c [%s]\n" % (98 + i, 98 + i, b", ".join([b"*%c" % (97 + i)] * 10))
                    for i in range(7)),
         r"more than 1,000,000 values once its aliases"),
        (b"name: x\n" + b"#" * 10_000_001, r"larger than 10,000,000 bytes"),
    ],
    ids=["latin-1", "utf-16", "results file", "deep nesting", "billion laughs", "huge"],
)  # fmt: skip
def test_files_that_are_not_cases_get_one_line(tmp_path, content, message):
    """Each was a traceback (UnicodeDecodeError, RecursionError) or a hang before."""
    path = tmp_path / "case.yaml"
    path.write_bytes(content)
    with pytest.raises(CaseError, match=message) as caught:
        seacable.load_case(path)
    assert "\n" not in str(caught.value)


def test_a_directory_or_an_endless_file_as_case(tmp_path):
    with pytest.raises(CaseError, match=r"is a directory; give the path of a \.yaml file"):
        seacable.load_case(tmp_path)
    with pytest.raises(CaseError, match=r"'/dev/zero' is not a regular file \(a device"):
        seacable.load_case("/dev/zero")
    big = tmp_path / "big.yaml"
    big.write_bytes(b"#" * 10_000_001)
    with pytest.raises(CaseError, match=r"larger than 10,000,000 bytes"):
        seacable.load_case(big)


def test_a_utf8_file_with_a_byte_order_mark_reads(tmp_path):
    path = tmp_path / "case.yaml"
    path.write_bytes(b"\xef\xbb\xbf" + _text(CHAIN).encode())
    assert seacable.load_case(path).name == "test chain"


def test_a_long_offending_value_is_quoted_shortened():
    with pytest.raises(CaseError, match=r"\.\.\. \(\d+ characters\)\) \(reference: \S+\)$"):
        _load(lambda d: d["lines"][0]["sections"][0].update(segments=list(range(1000))))


def test_a_case_of_numpy_numbers_and_a_changed_case_store_their_own_text():
    """A dict holding NumPy numbers could not be stored (a YAML RepresenterError); a case
    changed with ``model_copy(update=...)`` stored the text it was read from, not the case that
    ran."""
    case = _load(lambda d: d["simulation"].update(duration=np.float64(2.0)))
    assert "duration: 2.0" in case_text(case)
    changed = case.model_copy(update={"name": "changed"})
    assert "name: changed" in case_text(changed)
    assert seacable.load_case(case_text(changed)).name == "changed"


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"duration": 1e12}, r"simulation: .*1e\+13 output rows, more than any run can write"),
        ({"time_step": 1e-12, "output_interval": 1e-4, "duration": 1.0},
         r"simulation: .*1e\+12 steps, more than a run can take in a day"),
    ],
)  # fmt: skip
def test_time_that_cannot_finish_is_refused_up_front(change, message):
    """Before, a duration of 1e12 s ended in a traceback and a step of 1e-12 s ran on."""
    with pytest.raises(CaseError, match=message):
        _load(lambda d: d["simulation"].update(change))


def test_more_segments_than_a_run_can_hold_are_refused():
    sections = [{"type": "chain", "segments": 100_000, "length": 10.0}] * 21
    with pytest.raises(CaseError, match=r"lines: 2,100,000 segments in all, more than a run"):
        _load(lambda d: d["lines"][0].update(sections=sections))


@pytest.mark.parametrize(
    ("content", "message"),
    [(None, r"table file '/dev/zero' is not a regular file \(a device"),
     (b"0,1\n1,nan\n", r"NaN or infinite values"),
     ("0,caf\xe9\n".encode("latin-1"), r"not UTF-8 text \(byte 0xe9 at position 5\)")],
    ids=["endless", "nan", "latin-1"],
)  # fmt: skip
def test_bad_table_files_name_the_field(tmp_path, content, message):
    """A table file that never ends (/dev/zero) was read until memory ran out."""
    name = "/dev/zero"
    if content is not None:
        name = str(tmp_path / "table.csv")
        Path(name).write_bytes(content)
    case = _load(lambda d: _top(d, type="imposed", x={"kind": "table", "file": name}))
    with pytest.raises(CaseError, match=r"bodies\[0\] \(top\)\.x: .*" + message):
        seacable.simulate(case)


def test_the_tension_a_stretched_lines_ends_imply_is_reported(caplog):
    """A lumped line of 100 m between two anchors 110 m apart: 10 % strain, about EA / 10 of
    tension, said before the run (beyond 30 % it is refused: the corpus's stretched line)."""
    data = {
        "name": "stretched", "start": "as_given", "environment": {"water_depth": 50.0},
        "bodies": [{"name": "a", "type": "fixed", "position": [0.0, 0.0, -40.0]},
                   {"name": "b", "type": "fixed", "position": [110.0, 0.0, -40.0]}],
        "line_types": [{"name": "rope", "diameter": 0.05, "mass_per_length": 5.0,
                        "axial_stiffness": 1e7}],
        "lines": [{"name": "rope", "model": "lumped_mass", "from": "a", "to": "b",
                   "sections": [{"type": "rope", "length": 100.0, "segments": 10}]}],
        "simulation": {"duration": 0.1, "output_interval": 0.1},
    }  # fmt: skip
    from seacable.simulation import prepare

    with caplog.at_level("WARNING"):
        prepare(seacable.load_case(data))
    assert "lines (rope): its most stretched segment (" in caplog.text
    assert "starts at a strain of 10 %, a tension of 1e+06 N (EA 1e+07 N)" in caplog.text


def test_a_seabed_without_a_water_depth_is_refused():
    """A seabed lies at z = -water_depth: without a depth it touched nothing, silently."""
    with pytest.raises(CaseError, match=r"environment: seabed: .* no water_depth is given"):
        _load(lambda d: d["environment"].update(in_air=False, seabed={"stiffness": 1e5}))


def test_settings_change_one_key_as_the_file_nests_it():
    """The command line's ``--set PATH=VALUE`` (``loader.with_settings``): a key, a list's
    item by index (``[1]`` or ``.1.``) or by name, a value read as YAML; a path that leads
    nowhere, a value that is not YAML or a setting without ``=`` refused in one line."""
    from seacable.case.loader import with_settings

    case = _load(lambda d: None)
    changed = with_settings(case, ("simulation.duration=2", "bodies.end.mass=2.5",
                                   "lines[0].sections.0.segments=7",
                                   "bodies[1].position=[0, 0, -12]"))  # fmt: skip
    assert changed.simulation.duration == 2.0 and changed.bodies[1].mass == 2.5
    assert changed.lines[0].sections[0].segments == 7
    assert changed.bodies[1].position == (0.0, 0.0, -12.0)
    with pytest.raises(CaseError, match=r"simulation\.output_interval: required key is missing"):
        with_settings(case, ("simulation.output_interval=",))  # an empty value removes the key
    for setting, match in (
        (
            "bodies.boat.mass=1",
            r"bodies has no item 'boat'; its items: 0 to 1 or by name: top, end",
        ),
        ("simulation.lenght.x=1", r"simulation has no key 'lenght'; its keys: .*duration"),
        ("simulation.duration=[1, ", r"the value is not YAML"),
        ("simulation.duration", r"write PATH=VALUE"),
        ("simulation.duration=-1", r"simulation\.duration: Input should be greater than 0"),
    ):
        with pytest.raises(CaseError, match=match):
            with_settings(case, (setting,))
