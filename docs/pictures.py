"""Make the documentation's pictures: run each example (examples/*.yaml) and draw it with
``seacable plot`` into docs/images/<example>.png, as a user would (OPTIONS: the plot's options
where its defaults do not suit), then shrink it to WIDTH pixels and 128 colours.

usage: .venv/bin/python docs/pictures.py [NAME ...]     (every picture by default)

docs/images/manifest.json keeps, for each picture, the SHA-256 of the example's text and the
commands that drew it: tests/test_docs.py fails when an example changes and its picture was not
drawn again.
"""

import hashlib
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
IMAGES = ROOT / "docs" / "images"
MANIFEST = IMAGES / "manifest.json"
SEACABLE = [sys.executable, "-m", "seacable.cli"]
PICTURES = sorted(p.stem for p in (ROOT / "examples").glob("*.yaml"))
OPTIONS = {"spread_mooring_in_waves": ["--every", "20"]}  # example -> its plot's options
# pictures the tutorials show beyond the gallery's: name -> (the case, in examples/; the
# commands that draw it, the case written CASE, the picture PICTURE and a results file RESULTS)
OTHERS = {
    "tandem_operability_map": ("tandem_offloading_fpso_shuttle.yaml", [[
        "operability", "CASE", "--current-speed", "0.8", "--control", "both",
        "--clearance", "30", "--tension-limit", "hawser", "3e6", "--dask", "none",
        "--plot", "PICTURE", "-o", "RESULTS",
    ]]),
    "moordyn_buoy_three_chains": ("moordyn/buoy_three_chains.txt", [
        ["run", "CASE", "-o", "RESULTS", "--no-progress", "--set", "start=as_given"],
        ["plot", "RESULTS", "-o", "PICTURE"],
    ]),
}  # fmt: skip
WIDTH = 1200  # pixels: the pages show it at most this wide


def recipe(name: str) -> tuple[str, list[list[str]]]:
    """The case (in examples/) and the commands of a picture: an example's run and plot, or
    one of OTHERS."""
    if name in OTHERS:
        return OTHERS[name]
    run = ["run", "CASE", "-o", "RESULTS", "--no-progress"]
    return f"{name}.yaml", [run, ["plot", "RESULTS", "-o", "PICTURE", *OPTIONS.get(name, [])]]


def draw(name: str) -> dict:
    """Draw one picture by its commands, shrink it; its manifest entry."""
    example, commands = recipe(name)
    picture = IMAGES / f"{name}.png"
    with tempfile.TemporaryDirectory() as folder:
        given = {"CASE": str(ROOT / "examples" / example), "PICTURE": str(picture),
                 "RESULTS": f"{folder}/results.nc"}  # fmt: skip
        for words in commands:
            subprocess.run([*SEACABLE, *(given.get(w, w) for w in words)], check=True, cwd=ROOT)
    shrink(picture)
    shown = {"CASE": f"examples/{example}", "PICTURE": f"docs/images/{name}.png",
             "RESULTS": "results.nc"}  # fmt: skip
    entry = {
        "example_sha256": hashlib.sha256((ROOT / "examples" / example).read_bytes()).hexdigest(),
        "commands": [
            " ".join(["seacable", *(shown.get(w, w) for w in words)]) for words in commands
        ],  # fmt: skip
    }
    return entry if example == f"{name}.yaml" else {"example": example, **entry}


def shrink(picture: Path) -> None:
    """The picture at WIDTH pixels in 128 colours: a tenth of the bytes, as legible."""
    from PIL import Image

    image = Image.open(picture).convert("RGB")
    if image.width > WIDTH:
        height = round(image.height * WIDTH / image.width)
        image = image.resize((WIDTH, height), Image.Resampling.LANCZOS)
    image.quantize(colors=128, method=Image.Quantize.MEDIANCUT).save(picture, optimize=True)


def main(names: list[str]) -> None:
    unknown = sorted(set(names) - set(PICTURES) - set(OTHERS))
    if unknown:
        sys.exit(f"no picture of {unknown}; the pictures: {', '.join([*PICTURES, *OTHERS])}")
    manifest = json.loads(MANIFEST.read_text()) if MANIFEST.exists() else {}
    for name in names or [*PICTURES, *OTHERS]:
        manifest[name] = draw(name)
        MANIFEST.write_text(json.dumps(manifest, indent=2, sort_keys=True) + "\n")
        print(f"docs/images/{name}.png drawn", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
