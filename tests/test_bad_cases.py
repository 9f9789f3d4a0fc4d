"""A corpus of bad case files (``tests/bad_cases``, written by its ``make_corpus.py``): each is
refused by ``seacable validate`` with exit code 2 and one line that names the field or file
and quotes the value (``expected.yaml``)."""

import re
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from seacable.cli import main

CORPUS = Path(__file__).resolve().parent / "bad_cases"
EXPECTED = yaml.safe_load((CORPUS / "expected.yaml").read_text())


def test_the_corpus_is_what_its_script_writes():
    files = {path.name for path in CORPUS.glob("*.yaml")} - {"expected.yaml"}
    assert files == set(EXPECTED)
    assert len(files) >= 150


@pytest.mark.parametrize("name", sorted(EXPECTED))
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
