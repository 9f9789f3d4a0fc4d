"""Every code block of the README and of docs/ runs, so the documentation cannot go stale.

The blocks of one page run in order, in a folder holding a copy of ``examples/`` (a block may
read what an earlier one wrote, as a reader would go). ``python`` blocks are executed;
``bash`` blocks run each ``seacable`` command through the command line (a ``make`` target must
exist in the Makefile: those are CI's own commands); a command ending ``# exits with code N``
must exit with N; ``yaml`` blocks that hold a ``simulation`` are loaded as cases. In the default
suite each ``seacable run`` and ``sweep`` is shortened to two output intervals (``--set
simulation.duration=...``); the slow suite runs them as written. Blocks without a language are
output or diagrams, and MyST's ``{directive}`` blocks are Sphinx's.

Also: the pictures the docs show were drawn from their examples as they are now
(docs/pictures.py).
"""

import contextlib
import hashlib
import io
import json
import os
import re
import shlex
import shutil
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

import seacable
from seacable.cli import main

ROOT = Path(__file__).parent.parent
GENERATED = {"gallery.md"}  # written by docs/conf.py from the examples: no code of its own
PAGES = [
    ROOT / "README.md",
    *sorted(p for p in (ROOT / "docs").glob("*.md") if p.name not in GENERATED),
    *sorted((ROOT / "docs" / "tutorials").glob("*.md")),
]
FENCE = re.compile(r"^```([^\n`]*)\n(.*?)^```\s*$", re.S | re.M)
EXIT = re.compile(r"#\s*exits with code (\d+)")
MAKE_TARGETS = set(re.findall(r"^([a-z][a-z-]*):", (ROOT / "Makefile").read_text(), re.M))


def blocks(page: Path) -> list[tuple[str, str]]:
    """(language, text) of each fenced block of a page, in order."""
    return [(lang.strip(), text) for lang, text in FENCE.findall(page.read_text())]


def _pages_with_code():
    return [p for p in PAGES if any(lang in ("python", "bash", "yaml") for lang, _ in blocks(p))]


def test_the_pages_have_their_code_blocks_found():
    assert len(blocks(ROOT / "README.md")) >= 2
    assert any(p.name == "getting_started.md" for p in _pages_with_code())


def _seacable(args: list[str], expected: int, short: bool) -> str:
    if short and args[0] in ("run", "sweep"):
        case = seacable.load_case(args[1])
        args = [*args, "--set", f"simulation.duration={2 * case.simulation.output_interval!r}"]
    if args[0] in ("run", "animate"):
        args = [*args, "--no-progress"]
    outcome = CliRunner().invoke(main, args)
    assert outcome.exit_code == expected, (
        f"seacable {shlex.join(args)}: exit {outcome.exit_code}\n{outcome.output}"
        f"{outcome.exception!r}"
    )
    return outcome.output


def _bash(text: str, short: bool) -> None:
    for line in text.splitlines():
        expected = int(EXIT.search(line).group(1)) if EXIT.search(line) else 0
        words = shlex.split(line, comments=True)
        if not words:
            continue
        if words[0] == "make":
            assert set(words[1:]) <= MAKE_TARGETS, f"{line}: no such target in the Makefile"
            continue
        assert Path(words[0]).name == "seacable", f"{line}: only seacable commands run here"
        _seacable(words[1:], expected, short)


def _python(text: str) -> None:
    with contextlib.redirect_stdout(io.StringIO()):
        exec(compile(text, "<docs block>", "exec"), {"__name__": "__docs__"})  # noqa: S102


def _yaml(text: str) -> None:
    data = yaml.safe_load(text)
    if isinstance(data, dict) and "simulation" in data:
        seacable.load_case(data)


def _run_page(page: Path, tmp_path: Path, short: bool) -> None:
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        for k, (lang, text) in enumerate(blocks(page)):
            try:
                if lang == "python":
                    _python(text)
                elif lang in ("bash", "sh", "console"):
                    _bash(text, short)
                elif lang == "yaml":
                    _yaml(text)
            except Exception as exc:
                raise AssertionError(f"{page.name}, block {k + 1} ({lang}):\n{text}") from exc
    finally:
        os.chdir(here)


@pytest.mark.parametrize("page", _pages_with_code(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_the_code_blocks_run(page, tmp_path):
    _run_page(page, tmp_path, short=True)


@pytest.mark.slow
@pytest.mark.parametrize("page", _pages_with_code(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_the_code_blocks_run_in_full(page, tmp_path):
    _run_page(page, tmp_path, short=False)


def test_the_pictures_were_drawn_from_the_examples_as_they_are():
    """The gallery (docs/gallery.py) shows every example with its picture."""
    manifest = json.loads((ROOT / "docs" / "images" / "manifest.json").read_text())
    examples = {p.stem for p in (ROOT / "examples").glob("*.yaml")}
    assert examples <= set(manifest), (
        f"no picture of {sorted(examples - set(manifest))}: draw them with "
        ".venv/bin/python docs/pictures.py NAME ..."
    )
    for name, entry in manifest.items():
        example = entry.get("example", f"{name}.yaml")  # a tutorial's picture names its case
        text = (ROOT / "examples" / example).read_bytes()
        assert hashlib.sha256(text).hexdigest() == entry["example_sha256"], (
            f"examples/{example} changed: draw its picture again with "
            f".venv/bin/python docs/pictures.py {name}"
        )
        assert (ROOT / "docs" / "images" / f"{name}.png").stat().st_size > 20_000


def test_every_picture_the_pages_show_exists():
    for page in PAGES:
        for target in re.findall(r"!\[[^\]]*\]\(([^)]+\.png)\)", page.read_text()):
            assert (page.parent / target).exists(), f"{page.name} shows {target}: missing"
