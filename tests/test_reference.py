"""The case file's reference, generated from the schema (docs/reference/case_file.rst): every
key documented with its unit, every entry an error line links to present."""

import copy
import re

import pytest
from tests.test_case_errors import CHAIN

import seacable
from seacable import CaseError
from seacable.case import reference
from seacable.case.system import SystemCase

PAGE = reference.case_file_rst()
LABELS = set(re.findall(r"^\.\. _([a-z0-9-]+):$", PAGE, flags=re.M))


def _entries():
    for model in reference.parts(SystemCase):
        for key in reference.keys(model):
            yield model, key


def test_every_part_has_a_docstring_and_every_key_a_meaning():
    missing = [m.__name__ for m in reference.parts(SystemCase) if not (m.__doc__ or "").strip()]
    missing += [f"{m.__name__}.{k.name}" for m, k in _entries() if not k.meaning]
    assert not missing, f"{len(missing)} without a docstring: {missing}"


def test_every_number_has_its_unit():
    """A key that holds numbers says their unit ([-] for a pure number); one that holds none
    says none."""
    numeric = re.compile(r"\b(number|integer)s?\b")
    wrong = [f"{m.__name__}.{k.name} ({k.type})" for m, k in _entries()
             if bool(numeric.search(k.type)) != bool(k.unit)]  # fmt: skip
    assert not wrong, f"{len(wrong)} keys: {wrong}"


def test_every_part_and_key_has_its_entry_once():
    anchors = [reference.anchor(m) for m in reference.parts(SystemCase)]
    anchors += [k.anchor for _, k in _entries()]
    assert len(anchors) == len(set(anchors))
    assert set(anchors) <= LABELS
    for model in reference.parts(SystemCase):  # placed once, in one group
        assert sum(model in group for _, group in reference.sections()) == 1


def test_entry_shows_type_unit_limits_and_default():
    text = PAGE.split(".. _case-linetype-diameter:")[1].split(".. _")[0]
    assert "``diameter``" in text and "number" in text and "[m]" in text and "> 0" in text
    text = PAGE.split(".. _case-simulation-integrator:")[1].split(".. _")[0]
    assert "one of ``rk4``" in text and 'default "' in text


def _bad(mutate):
    data = copy.deepcopy(CHAIN)
    mutate(data)
    with pytest.raises(CaseError) as caught:
        seacable.load_case(data)
    return str(caught.value)


@pytest.mark.parametrize(
    ("mutate", "fragment"),
    [
        (lambda d: d["line_types"][0].update(diameter=-1.0), "case-linetype-diameter"),
        (lambda d: d["line_types"][0].update(colour="red"), "case-linetype"),
        (lambda d: d["bodies"][1].update(mass=True), "case-pointbody-mass"),
        (lambda d: d["bodies"][1].update(type="wobbly"), "case-systemcase-bodies"),
        (lambda d: d["simulation"].pop("duration"), "case-simulation-duration"),
        (lambda d: d["lines"][0]["sections"][0].update(segments=0), "case-section-segments"),
        (lambda d: d["bodies"][1]["external forces"][0].update(colour=1), "case-gravity"),
    ],
)
def test_error_lines_link_to_their_entries(mutate, fragment):
    message = _bad(mutate)
    links = re.findall(r"\(reference: (\S+)\)", message)
    assert links, message
    assert all(link.startswith(reference.DOCS_URL + reference.PAGE + ".html#") for link in links)
    assert {link.split("#")[1] for link in links} <= LABELS
    assert fragment in {link.split("#")[1] for link in links}, message
    assert "Valid keys: ?" not in message  # a key with a space (external forces) is walked


def test_every_variable_a_run_writes_is_in_the_catalogue_of_outputs():
    """docs/reference/outputs.md lists seacable.system.variables.catalogue(): the variables of
    built systems (a rigid-link chain, the same as a lumped-mass line, a tie) are all there,
    with the same dimensions, unit and meaning."""
    from seacable.system import model, variables

    listed = {(name, spec) for _, _, found in variables.catalogue() for name, spec in found.items()}
    lumped = copy.deepcopy(CHAIN)
    lumped["line_types"][0]["axial_stiffness"] = 1e6
    lumped["lines"][0] = {
        "name": "cable",
        "model": "lumped_mass",
        "from": "top",
        "to": "end",
        "sections": [{"type": "chain", "segments": 5, "length": 10.0}],
    }
    tie = copy.deepcopy(lumped)
    tie["lines"][0] = {"name": "cable", "model": "tie", "from": "top", "to": "end",
                       "unstretched_length": 10.0, "stiffness": 1e5}  # fmt: skip
    for data in (CHAIN, lumped, tie):
        built = model.build(seacable.load_case(data))
        written = model.variables(built)
        coords = model.coords(built)
        missing = [path for path, spec in written.items()
                   if (path.rsplit("/", 1)[-1], spec) not in listed]  # fmt: skip
        missing += [path for path, (dim, _, unit, text) in coords.items()
                    if (path.rsplit("/", 1)[-1], ((dim,), unit, text)) not in listed]  # fmt: skip
        assert not missing, missing


def test_an_error_found_after_the_schema_links_to_the_key_it_names(tmp_path):
    """A check of the built system (a lumped-mass line on a line type without EA) names the
    key in its own words; the command line adds the address of its entry."""
    import yaml
    from click.testing import CliRunner

    from seacable.cli import main

    data = copy.deepcopy(CHAIN)
    data["lines"][0] = {"name": "cable", "model": "lumped_mass", "from": "top", "to": "end",
                        "sections": [{"type": "chain", "segments": 5, "length": 10.0}]}  # fmt: skip
    case = tmp_path / "case.yaml"
    case.write_text(yaml.safe_dump(data))
    outcome = CliRunner().invoke(main, ["validate", str(case)])
    assert outcome.exit_code == 2
    assert "has no axial_stiffness" in outcome.output
    assert outcome.output.strip().endswith(f"(reference: {reference.DOCS_URL}{reference.PAGE}"
                                           ".html#case-section-type)")  # fmt: skip
