"""Make the documentation's pictures: run each example (examples/*.yaml) and draw it with
``seacable plot`` into docs/images/<example>.png, as a user would (OPTIONS: the plot's options
where its defaults do not suit), then shrink it to WIDTH pixels and 128 colours.

usage: .venv/bin/python docs/pictures.py [EXAMPLE ...]     (every example by default)

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
WIDTH = 1200  # pixels: the pages show it at most this wide


def digest(example: str) -> str:
    return hashlib.sha256((ROOT / "examples" / f"{example}.yaml").read_bytes()).hexdigest()


def draw(example: str) -> dict:
    case = ROOT / "examples" / f"{example}.yaml"
    picture = IMAGES / f"{example}.png"
    with tempfile.TemporaryDirectory() as folder:
        results = Path(folder) / "results.nc"
        run = [*SEACABLE, "run", str(case), "-o", str(results), "--no-progress"]
        plot = [*SEACABLE, "plot", str(results), "-o", str(picture), *OPTIONS.get(example, [])]
        for command in (run, plot):
            subprocess.run(command, check=True, cwd=ROOT)
    shrink(picture)
    return {
        "example_sha256": digest(example),
        "commands": [
            f"seacable run examples/{example}.yaml -o results.nc",
            " ".join(
                [
                    "seacable plot results.nc -o",
                    f"docs/images/{example}.png",
                    *OPTIONS.get(example, []),
                ]
            ),
        ],
    }


def shrink(picture: Path) -> None:
    """The picture at WIDTH pixels in 128 colours: a tenth of the bytes, as legible."""
    from PIL import Image

    image = Image.open(picture).convert("RGB")
    if image.width > WIDTH:
        height = round(image.height * WIDTH / image.width)
        image = image.resize((WIDTH, height), Image.Resampling.LANCZOS)
    image.quantize(colors=128, method=Image.Quantize.MEDIANCUT).save(picture, optimize=True)


def main(names: list[str]) -> None:
    unknown = sorted(set(names) - set(PICTURES))
    if unknown:
        sys.exit(f"no picture of {unknown}; the pictures: {', '.join(PICTURES)}")
    manifest = json.loads(MANIFEST.read_text()) if MANIFEST.exists() else {}
    for name in names or list(PICTURES):
        manifest[name] = draw(name)
        print(f"docs/images/{name}.png drawn")
    MANIFEST.write_text(json.dumps(manifest, indent=2, sort_keys=True) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
