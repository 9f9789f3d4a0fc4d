"""seacable report: a run's page and a sweep's page hold every plot with data, the statistics
and the case (escaped: a case's text is never markup); opened in a real browser (headless
Chromium, when installed: `.ci/run` installs it), the pages run their script without an error
(uncaught, or said on the console),
draw every plot, and show something that is not blank."""

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import seacable
from seacable import report, stats
from seacable import sweep as batch
from seacable.case import loader
from seacable.cli import main
from seacable.errors import SeacableError

pytest.importorskip("plotly")
EXAMPLE = Path(__file__).parent.parent / "examples" / "spread_mooring_in_waves.yaml"
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """A run of the CALM buoy (named with markup) and a sweep of two load cases."""
    folder = tmp_path_factory.mktemp("report")
    case = loader.with_settings(
        seacable.load_case(EXAMPLE),
        ["simulation.duration=10", "simulation.build_up=2", "name=<b>buoy</b> & <script>"],
    )
    seacable.simulate(case, output=folder / "run.nc")
    todo = batch.plan(case, [batch.parse_vary("environment.waves[0].significant_height=2,4")])
    batch.execute(todo, folder / "sweep.nc", None)
    for name in ("run", "sweep"):
        result = CliRunner().invoke(main, ["report", str(folder / f"{name}.nc")])
        assert result.exit_code == 0, result.output
    return folder


def _figures(page: str) -> list[dict]:
    found = re.search(r'<script type="application/json" id="figures">(.*?)</script>', page, re.S)
    assert found is not None
    return json.loads(found.group(1))


def test_a_runs_page(made):
    page = (made / "run.html").read_text()
    figures = _figures(page)
    assert [f["id"] for f in figures] == ["tensions", "spectra", "bodies_m", "bodies_degree",
                                          "ranges", "system"]  # fmt: skip
    by_id = {f["id"]: f for f in figures}
    for figure in figures:
        assert figure["data"] and all(len(t.get("x") or []) > 1 for t in figure["data"])
    results = seacable.Results.open(made / "run.nc")
    tension = results["lines/line_3/tension"].values
    largest = next(t for t in by_id["ranges"]["data"] if t["name"] == "line_3 largest")
    np.testing.assert_allclose(largest["y"], tension.max(axis=0) / 1e3, rtol=1e-6)
    assert len(by_id["system"]["frames"]) == len(results["time"])  # every output time, to 60
    spectrum = by_id["spectra"]["data"][0]  # line_1's 'from' end: Welch's, as stats gives it
    kept = results["time"].values >= 2.0  # from the end of the build-up
    f, density = stats.spectrum(
        results["time"].values[kept], results["lines/line_1/tension"].values[kept, 0] / 1e3
    )
    np.testing.assert_allclose(spectrum["y"], density, rtol=1e-6)
    assert "&lt;b&gt;buoy&lt;/b&gt; &amp; &lt;script&gt;" in page and "<b>buoy</b>" not in page
    assert "MPM Rayleigh" in page and "lines/line_3 tension, &#x27;to&#x27; end" in page
    assert "https://" not in page.split("<script>", 2)[0]  # nothing fetched: no link in head


def test_a_sweeps_page(made):
    page = (made / "sweep.html").read_text()
    figures = _figures(page)
    assert [f["id"] for f in figures] == ["utilisation"]
    assert figures[0]["data"][0]["x"] == ["2", "4"]
    assert "Envelope of each line" in page and page.count("<td>complete</td>") == 2
    assert "<td>seacable_version</td>" in page  # the provenance


def test_a_report_replaces_only_a_report(made, tmp_path):
    mine = tmp_path / "mine.html"
    mine.write_text("<!DOCTYPE html><html>my notes</html>")
    with pytest.raises(SeacableError, match="not a seacable report"):
        report.write(made / "run.nc", mine)
    with pytest.raises(SeacableError, match="ending in .html"):
        report.write(made / "run.nc", tmp_path / "run.nc")
    report.write(made / "run.nc", made / "run.html")  # its own page again


def _browse(page: Path, tmp_path: Path) -> tuple[str, str, Path]:
    """The page's DOM after its scripts ran, Chromium's log, and a screenshot."""
    flags = [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
             "--no-first-run", "--disable-background-networking", "--disable-component-update",
             "--disable-sync", f"--user-data-dir={tmp_path / 'profile'}",
             "--virtual-time-budget=20000", "--window-size=1280,3000",
             "--enable-logging=stderr", "--v=0"]  # fmt: skip
    dom = subprocess.run([*flags, "--dump-dom", page.as_uri()], capture_output=True, text=True,
                         timeout=300)  # fmt: skip
    picture = tmp_path / f"{page.stem}.png"
    subprocess.run([*flags, f"--screenshot={picture}", page.as_uri()], capture_output=True,
                   timeout=300, check=True)  # fmt: skip
    return dom.stdout, dom.stderr, picture


@pytest.mark.parametrize("name", ["run", "sweep"])
def test_the_pages_in_a_real_browser(made, tmp_path, name):
    from PIL import Image

    if CHROMIUM is None:
        if os.environ.get("SEACABLE_BROWSER_TESTS") == "required":
            pytest.fail("no Chromium, and .ci/run requires the browser tests")
        pytest.skip("no Chromium here (.ci/run installs it)")

    page = made / f"{name}.html"
    dom, log, picture = _browse(page, tmp_path)
    body = re.search(r"<body([^>]*)>", dom)
    assert body is not None, dom[:500]
    assert "data-errors" not in body.group(1), body.group(1)
    assert f'data-plots="{len(_figures(page.read_text()))}"' in body.group(1), body.group(1)
    assert "Uncaught" not in log, log[-2000:]  # an exception the page's watch missed
    pixels = np.asarray(Image.open(picture).convert("L"), dtype=float)
    assert pixels.std() > 10.0 and (pixels < 128).mean() > 0.002  # text and plots, not blank


def test_curvature_along_a_line_bent_on_a_circle():
    """Nodes on a circle of radius R, 1 m chords: every inner node's curvature is the chords'
    turning angle over their length, 2 arcsin(1 / 2R) (1/R to 1/(24 R^2)); the line bends
    twice as much at the second output time."""
    import xarray as xr

    from seacable.viz import system as vs

    def arc(radius: float) -> np.ndarray:
        step = 2.0 * np.arcsin(0.5 / radius)
        angles = step * np.arange(11)
        return np.stack([radius * np.sin(angles), np.zeros(11), radius * (1 - np.cos(angles))])

    nodes = np.stack([arc(20.0), arc(10.0)])  # (time, xyz, node)
    line = xr.Dataset(
        {f"node_{c}": (("time", "node"), nodes[:, k]) for k, c in enumerate("xyz")},
        coords={"arc_length": ("node", np.arange(11.0))},
    )
    tree = xr.DataTree.from_dict({"/": xr.Dataset(coords={"time": [0.0, 1.0]}),
                                  "/lines/bent": line})  # fmt: skip
    arcs, least, mean, largest = vs.curvature_ranges(tree, 2, ["bent"])["bent"]
    np.testing.assert_array_equal(arcs, np.arange(1.0, 10.0))
    np.testing.assert_allclose(least, 2.0 * np.arcsin(0.5 / 20.0), rtol=1e-9)
    np.testing.assert_allclose(largest, 2.0 * np.arcsin(0.5 / 10.0), rtol=1e-9)
    assert largest[0] == pytest.approx(0.1, rel=1e-3)
    assert vs.bending_lines({"case_resolved": (
        "line_types: [{name: a, bending_stiffness: 1000.0}, {name: b, bending_stiffness: 0.0}]\n"
        "lines: [{name: stiff, sections: [{type: b}, {type: a}]}, "
        "{name: limp, sections: [{type: b}]}]\n")}) == ["stiff"]  # fmt: skip
