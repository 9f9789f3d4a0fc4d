"""Sphinx configuration of seacable's documentation (``make docs``; warnings are errors).

The case-file reference, the output variables, the command line and the gallery are generated
here, from the schema (``seacable.case.reference``), the results' declarations
(docs/outputs.py), the commands (docs/cli.py) and the examples with their pictures
(docs/gallery.py), so they cannot drift from the code."""

import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))

import cli  # noqa: E402 (docs/cli.py)
import gallery  # noqa: E402 (docs/gallery.py)
import outputs  # noqa: E402 (docs/outputs.py)

import seacable  # noqa: E402
from seacable.case import reference  # noqa: E402

project = "seacable"
author = "the seacable developers"
copyright = "2026, the seacable developers"
release = version = seacable.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "README.md", "pictures.py", "gallery.py", "outputs.py", "cli.py"]
myst_enable_extensions = ["dollarmath", "deflist"]
myst_heading_anchors = 3
nitpicky = False
suppress_warnings = ["myst.xref_missing"]

html_theme = "furo"
html_title = f"seacable {release}"

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "undoc-members": False}


def _generate(app) -> None:
    """Write the generated pages before Sphinx reads the sources (a page unchanged is not
    written again, so that Sphinx keeps its cache)."""
    pages = {
        HERE / "reference" / "case_file.rst": reference.case_file_rst(),
        HERE / "gallery.md": gallery.gallery_md(),
        HERE / "reference" / "outputs.md": outputs.outputs_md(),
        HERE / "reference" / "cli.md": cli.cli_md(),
    }
    for target, text in pages.items():
        if not target.exists() or target.read_text() != text:
            target.parent.mkdir(parents=True, exist_ok=True)  # reference/: generated pages only
            target.write_text(text)


def setup(app) -> None:
    app.connect("builder-inited", _generate)
