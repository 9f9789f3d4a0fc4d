"""The gallery page: every example of examples/, its description (the comment it opens with),
its picture (drawn by docs/pictures.py) and the commands that draw it. docs/conf.py writes it
as docs/gallery.md at each build."""

import json
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
IMAGES = ROOT / "docs" / "images"
# the order of the gallery's sections: an example goes in the first whose words its name holds
SECTIONS = (
    ("Moorings and buoys", ("mooring", "buoy", "catenary", "platform", "clump")),
    ("Vessels and floating structures", ("barge", "fpso", "vessel", "tandem")),
    ("Towed cables and trajectory following", ("jacquot", "towing")),
    ("Rising bodies and lowering", ("rising", "crane")),
    ("Pouzada's planar cable (thesis chapter 6)", ("thesis",)),
    ("Poth's string", ("poth",)),
)


def description(path: Path) -> str:
    """The comment an example opens with, as one paragraph."""
    lines = []
    for line in path.read_text().splitlines():
        if not line.startswith("#"):
            break
        lines.append(line.lstrip("#").strip())
    return " ".join(lines)


def section(stem: str) -> str:
    for title, words in SECTIONS:
        if any(word in stem for word in words):
            return title
    return "Other examples"


def gallery_md() -> str:
    manifest = json.loads((IMAGES / "manifest.json").read_text())
    out = [
        "# Gallery",
        "",
        "Every example of `examples/`, with the picture `seacable plot` draws of its run. Each "
        "runs with `seacable run examples/NAME.yaml -o run.nc`; `seacable plot run.nc -o "
        "run.png` draws it (`docs/pictures.py` draws these).",
        "",
    ]
    examples = sorted((ROOT / "examples").glob("*.yaml"))
    titles = [t for t, _ in SECTIONS] + ["Other examples"]
    for title in titles:
        mine = [p for p in examples if section(p.stem) == title]
        if not mine:
            continue
        out += [f"## {title}", ""]
        for path in mine:
            name = yaml.safe_load(path.read_text()).get("name", path.stem)
            out += [f"### {name}", "", f"`examples/{path.name}`: {description(path)}", ""]
            if path.stem in manifest:
                out += [f"![{name}](images/{path.stem}.png)", ""]
                out += ["```text", *manifest[path.stem]["commands"], "```", ""]
    return "\n".join(out) + "\n"
