"""A corpus of bad input (``tests/bad_cases``, written by its ``make_corpus.py``): case files
that ``seacable validate`` refuses, and command lines (``args``: every command's output paths,
options and side files) that their command refuses; each with exit code 2 and one line that
names the field, option or file and quotes the value (``expected.yaml``), and without
changing any file of the corpus."""

import hashlib
import re
import sys
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from seacable.cli import main

CORPUS = Path(__file__).resolve().parent / "bad_cases"
EXPECTED = yaml.safe_load((CORPUS / "expected.yaml").read_text())
COMMANDS = {name: entry for name, entry in EXPECTED.items() if "args" in entry}
CASES = {name: entry for name, entry in EXPECTED.items() if "args" not in entry}


def test_the_corpus_is_what_its_script_writes():
    files = {path.name for path in CORPUS.glob("*.yaml")} - {"expected.yaml"}
    assert files == set(CASES)
    assert len(files) >= 150 and len(EXPECTED) >= 500
    assert {entry["args"][0] for entry in COMMANDS.values()} >= set(main.commands)


def _files(folder: Path) -> dict:
    """Every file and link under ``folder``: its content's hash, or where the link points."""
    return {
        str(path.relative_to(folder)): (
            f"-> {path.readlink()}" if path.is_symlink()
            else "dir" if path.is_dir() else hashlib.sha256(path.read_bytes()).hexdigest()
        )
        for path in sorted(folder.rglob("*"))
    }  # fmt: skip


@pytest.fixture(scope="module")
def inputs(tmp_path_factory) -> Path:
    """The commands' input files, good and bad (``corpus_commands.write_inputs``)."""
    sys.path.insert(0, str(CORPUS))
    try:
        import corpus_commands
        import make_corpus
    finally:
        sys.path.remove(str(CORPUS))
    here = tmp_path_factory.mktemp("corpus")
    corpus_commands.write_inputs(here, make_corpus.BASE, make_corpus.PUSH)
    return here


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_a_command_refuses_bad_input_in_one_line_and_writes_nothing(name, inputs):
    """Every command, given a bad output path, option or side file, exits 2 with one line
    that names it; no file of the corpus changes, none is added."""
    entry = COMMANDS[name]
    args = [arg.replace("{here}", str(inputs)) for arg in entry["args"]]
    before = _files(inputs)
    result = CliRunner().invoke(main, args)
    assert _files(inputs) == before
    errors = [line for line in result.output.splitlines() if line.startswith("error:")]
    assert result.exit_code == 2, result.output
    assert len(errors) == 1 and "Traceback" not in result.output, result.output
    said = result.output[result.output.index("error:") :]  # one line, or one a problem
    assert re.search(entry["expect"], said), said


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_bad_case_is_refused_with_one_line_naming_it(name):
    """``seacable validate`` refuses the case; one with an ``output`` is a good case whose
    output path ``seacable run`` refuses, writing nothing."""
    output = EXPECTED[name].get("output")
    if output is None:
        result = CliRunner().invoke(main, ["validate", str(CORPUS / name)])
    else:
        target = CORPUS / output
        before = target.read_bytes() if target.is_file() else None
        result = CliRunner().invoke(
            main, ["run", str(CORPUS / name), "-o", str(target), "--no-progress"]
        )
        assert (target.read_bytes() if target.is_file() else None) == before
    assert result.exit_code == 2, result.output
    message = result.output.strip()
    assert re.search(EXPECTED[name]["expect"], message, re.DOTALL), message
    assert "Traceback" not in message
