"""The command line: run, validate, plot, animate, statics, modes."""

import logging
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from click.testing import CliRunner
from PIL import Image

from helpers import chain_case, system_data
from seacable.case.loader import load_case
from seacable.cli import main


def _case_file(tmp_path, **kwargs) -> Path:
    """A planar chain of 8 links hanging from a fixed point (the system ``seacable upgrade``
    writes for helpers.chain_case)."""
    path = tmp_path / "case.yaml"
    data = chain_case(n=8, initial={"shape": "arc", "top_angle_deg": 30.0}, **kwargs)
    path.write_text(yaml.safe_dump(system_data(data), sort_keys=False))
    return path


def test_validate_ok_and_bad(tmp_path):
    runner = CliRunner()
    good = _case_file(tmp_path)
    result = runner.invoke(main, ["validate", str(good)])
    assert result.exit_code == 0 and "ok: case" in result.output
    bad = tmp_path / "bad.yaml"
    bad.write_text(good.read_text().replace("segments: 8", "segments: -1"))
    result = runner.invoke(main, ["validate", str(bad)])
    assert result.exit_code == 2
    assert "lines[0].sections[0].segments" in result.output


def test_run_plot_animate(tmp_path):
    runner = CliRunner()
    case = _case_file(tmp_path)
    out = tmp_path / "out.nc"
    result = runner.invoke(main, ["run", str(case), "-o", str(out), "--no-progress"])
    assert result.exit_code == 0, result.output
    assert "complete" in result.output and out.exists()
    png = tmp_path / "out.png"
    result = runner.invoke(main, ["plot", str(out), "-o", str(png), "--every", "0.2"])
    assert result.exit_code == 0, result.output
    assert png.stat().st_size > 10_000
    gif = tmp_path / "cable.gif"
    result = runner.invoke(main, ["animate", str(out), "-o", str(gif), "--fps", "5"])
    assert result.exit_code == 0, result.output
    assert gif.read_bytes()[:3] == b"GIF"
    result = runner.invoke(main, ["animate", str(out), "-o", str(tmp_path / "x.avi")])
    assert result.exit_code == 2 and "'.avi' is not one of its names (.gif)" in result.output


def test_run_reports_divergence(tmp_path):
    data = chain_case(
        n=8,
        initial={"shape": "arc", "top_angle_deg": 30.0},
        simulation={"duration": 3.0, "output_interval": 0.1, "time_step": 0.05,
                    "allow_unstable_step": True},  # refused unless allowed
    )  # fmt: skip
    data["cables"][0]["bottom"] = {"type": "free", "body": {"mass": 0.01},
                                   "tie": {"stiffness_x": 1e7, "stiffness_z": 1e7}}  # fmt: skip
    case = tmp_path / "stiff.yaml"
    case.write_text(yaml.safe_dump(system_data(data)))
    out = tmp_path / "stiff.nc"
    result = CliRunner().invoke(main, ["run", str(case), "-o", str(out), "--no-progress"])
    assert result.exit_code == 3
    assert "diverged" in result.output and "partial results" in result.output
    assert out.exists()


def test_3d_run_plot_animate(tmp_path):
    data = {
        "environment": {"water_density": 1025.0, "current": {"velocity": 0.3, "direction_deg": 90}},
        "cables": [
            {
                "model": "rigid_segments_3d",
                "links": 10,
                "length": 50.0,
                "diameter": 0.02,
                "mass_per_length": 1.47,
                "drag_coefficient_normal": 1.8,
                "top": {"type": "towing_ship", "speed": 1.5,
                        "turn": {"start_time": 1.0, "radius": 30.0, "side": "right"}},
                "bottom": {"type": "free", "body": {"mass": 20.0, "volume": 0.005}},
                "initial": {"shape": "static"},
            }
        ],
        "simulation": {"duration": 3.0, "output_interval": 0.5, "time_step": 0.01},
    }  # fmt: skip
    case = tmp_path / "tow.yaml"
    case.write_text(yaml.safe_dump(system_data(data)))
    runner = CliRunner()
    out = tmp_path / "tow.nc"
    result = runner.invoke(main, ["run", str(case), "-o", str(out), "--no-progress"])
    assert result.exit_code == 0, result.output
    result = runner.invoke(main, ["plot", str(out), "-o", str(tmp_path / "tow.png")])
    assert result.exit_code == 0, result.output
    result = runner.invoke(
        main, ["animate", str(out), "-o", str(tmp_path / "tow.gif"), "--fps", "2"]
    )
    assert result.exit_code == 0, result.output
    result = runner.invoke(main, ["validate", str(case)])
    assert "rigid_segments_3d" in result.output or "ok: case" in result.output


@pytest.mark.slow  # the same run and picture as test_examples' rising_body_four_cables, by the CLI
def test_star_run_and_plot(tmp_path):
    text = (Path(__file__).parent.parent / "examples" / "rising_body_four_cables.yaml").read_text()
    case = tmp_path / "four.yaml"
    case.write_text(text.replace("duration: 28.0", "duration: 1.0"))
    runner = CliRunner()
    out = tmp_path / "four.nc"
    result = runner.invoke(main, ["run", str(case), "-o", str(out), "--no-progress"])
    assert result.exit_code == 0, result.output
    result = runner.invoke(main, ["plot", str(out), "-o", str(tmp_path / "four.png")])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "four.png").stat().st_size > 10_000


def _long_result(path, steps: int, nodes: int = 11):
    """A system's result of ``steps`` output times (0.05 s apart): a straight 10 m line
    swinging in 3D."""
    times = 0.05 * np.arange(steps)
    angle = 0.5 * np.sin(0.3 * times)[:, None]
    s = np.linspace(0.0, 10.0, nodes)[None, :]
    line = xr.Dataset(
        {
            "node_x": (("time", "node"), s * np.sin(angle)),
            "node_y": (("time", "node"), 0.1 * s * np.cos(angle)),
            "node_z": (("time", "node"), -s * np.cos(angle)),
        },
        coords={"time": times},
    )
    root = xr.Dataset(coords={"time": times},
                      attrs={"case": "name: swinging line", "status": "complete"})  # fmt: skip
    xr.DataTree.from_dict({"/": root, "/lines/line": line}).to_netcdf(path, engine="h5netcdf")


def test_animate_caps_frames_and_streams(tmp_path, caplog):
    """12,001 outputs (600 s at 20 fps asks 12,000 frames): the GIF holds --max-frames frames
    spread over the whole run, written one at a time, and a log line says so."""
    result_file = tmp_path / "long.nc"
    _long_result(result_file, 12_001)
    gif = tmp_path / "long.gif"
    runner = CliRunner()
    with caplog.at_level(logging.INFO, logger="seacable.viz"):
        result = runner.invoke(
            main,
            ["animate", str(result_file), "-o", str(gif), "--max-frames", "7", "--no-progress"],
        )
    assert result.exit_code == 0, result.output + repr(result.exception)
    assert "animating 7 frames of the 12001 asked (one every 100 s" in caplog.text
    with Image.open(gif) as picture:
        assert picture.n_frames == 7
        first = np.asarray(picture.convert("RGB"))
        picture.seek(3)
        middle = np.asarray(picture.convert("RGB"))
    assert first.shape == (480, 1120, 3)  # plan and elevation, 14 x 6 in at 80 dpi
    assert np.any(first != middle)  # the line moves from frame to frame
    # --every below the cap: one frame per 150 s of the 600 s run, no cap
    result = runner.invoke(
        main, ["animate", str(result_file), "-o", str(gif), "--every", "150", "--no-progress"]
    )
    assert result.exit_code == 0, result.output
    with Image.open(gif) as picture:
        assert picture.n_frames == 5
    result = runner.invoke(main, ["animate", str(result_file), "-o", str(gif), "--fps", "0"])
    assert result.exit_code == 2 and "'--fps': 0 is not in the range" in result.output


def test_system_validate_statics_and_modes(tmp_path):
    """A system case: validate names its bodies and lines, statics prints every body's pose
    and every line's end tensions and writes them as a DataTree, modes prints the periods."""
    example = Path(__file__).parent.parent / "examples" / "buoy_three_lines_clump_weight.yaml"
    runner = CliRunner()
    result = runner.invoke(main, ["validate", str(example)])
    assert result.exit_code == 0 and "buoy (point)" in result.output
    assert "leg_c_upper (lumped_mass)" in result.output
    output = tmp_path / "statics.nc"
    result = runner.invoke(main, ["statics", str(example), "-o", str(output)])
    assert result.exit_code == 0, result.output
    assert "body buoy: at (4.438, -7.596, -20.41) m" in result.output
    assert "line leg_a: end tensions" in result.output
    tree = xr.open_datatree(output, engine="h5netcdf")
    assert abs(tree["bodies/buoy/position_z"].values[0] + 20.41) < 0.005
    result = runner.invoke(main, ["modes", str(example), "--count", "4"])
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    assert lines[0].startswith("mode  period [s]") and len(lines) == 5
    assert lines[0].endswith("found by") and lines[1].endswith("linearised")
    single = tmp_path / "single.yaml"
    single.write_text(yaml.safe_dump(chain_case(n=8)))
    result = runner.invoke(main, ["statics", str(single)])
    assert result.exit_code == 2 and f"seacable upgrade {single} -o system.yaml" in result.output


def test_upgrade_writes_a_single_cable_case_as_a_system(tmp_path):
    """`seacable upgrade` writes the system form (keeping the file's opening comments); a case
    it cannot write yet, or one already a system, gets one line naming why."""
    legacy = Path(__file__).parent / "legacy_cases"
    out = tmp_path / "upgraded.yaml"
    result = CliRunner().invoke(
        main, ["upgrade", str(legacy / "thesis_6_2_pinned_exact_60_links.yaml"), "-o", str(out)]
    )
    assert result.exit_code == 0, result.output
    text = out.read_text()
    assert text.startswith("# Pouzada (2015)") and "\nlines:\n" in text
    case = load_case(out)
    assert [b.type for b in case.bodies] == ["rigid", "fixed"]
    assert case.lines[0].model == "rigid_links"
    lumped = tmp_path / "lumped.yaml"  # ending free, started on a catenary: no system form
    data = yaml.safe_load((legacy / "catenary_mooring_line_surge.yaml").read_text())
    data["cables"][0]["bottom"] = {"type": "free", "body": {"mass": 100.0}}
    lumped.write_text(yaml.safe_dump(data))
    result = CliRunner().invoke(main, ["upgrade", str(lumped)])
    assert result.exit_code == 2 and "a catenary start needs the end's anchor or its" in (
        result.output
    )
    data["cables"][0]["initial"] = {"shape": "arc", "top_angle_deg": 10.0}  # at given angles
    lumped.write_text(yaml.safe_dump(data))
    result = CliRunner().invoke(main, ["upgrade", str(lumped)])
    assert result.exit_code == 0, result.output
    result = CliRunner().invoke(main, ["upgrade", str(out)])
    assert result.exit_code == 2 and "already a system" in result.output
    star = tmp_path / "star.yaml"  # cables on a shared body: lines from it back to the anchors
    result = CliRunner().invoke(
        main, ["upgrade", str(legacy / "rising_body_four_cables.yaml"), "-o", str(star)]
    )
    assert result.exit_code == 0, result.output
    case = load_case(star)
    assert [line.from_ for line in case.lines[:2]] == ["buoy", "cable 1 joint 13"]
    assert [line.to for line in case.lines[:2]] == ["cable 1 joint 13", "cable 1 top"]
    assert case.lines[0].initial.angles_deg[:6] == [-180.0] * 5 + [10.59 - 180.0]


def test_every_failure_is_one_line_and_its_exit_code(tmp_path, monkeypatch):
    """The command line's one error boundary: input errors exit 2, a bug exits 1 with one
    line saying so (``--debug`` shows the traceback), never a traceback for a user's mistake."""
    runner = CliRunner()
    case = _case_file(tmp_path)
    result = runner.invoke(main, ["run", str(case), "-o", str(case)])  # over the case itself
    assert result.exit_code == 2
    assert "is a file this command reads" in result.output and "would replace" in result.output
    other = tmp_path / "other.yaml"  # a case-like name the run does not read: refused too
    result = runner.invoke(main, ["run", str(case), "-o", str(other)])
    assert result.exit_code == 2
    assert "'.yaml' is not one of its names (.nc, .nc4, .h5, .hdf5)" in result.output
    unreadable = tmp_path / "latin1.yaml"
    unreadable.write_bytes("name: caf\xe9\n".encode("latin-1"))
    for command in ("run", "validate", "statics", "modes"):
        result = runner.invoke(main, [command, str(unreadable)])
        assert result.exit_code == 2, (command, result.output)
        assert result.output.count("\n") == 1 and "not UTF-8 text" in result.output

    def broken(*args, **kwargs):
        raise RuntimeError("something impossible")

    monkeypatch.setattr("seacable.simulate", broken)
    result = runner.invoke(main, ["run", str(case)])
    assert result.exit_code == 1
    assert "internal error, a bug in seacable (RuntimeError: something impossible)" in (
        result.output
    )
    assert "--debug" in result.output and "Traceback" not in result.output
    result = runner.invoke(main, ["--debug", "run", str(case)])
    assert isinstance(result.exception, RuntimeError)


def test_validate_checks_what_a_run_checks_before_its_first_step(tmp_path):
    """A line too short to reach its ends is only found when the system is built: validate
    builds it, as the run does (before, such a case passed validate and failed in run)."""
    import copy

    from test_case_errors import CHAIN

    data = copy.deepcopy(CHAIN)
    data["bodies"][1] = {"name": "end", "type": "fixed", "position": [0.0, 0.0, -10.0]}
    data["lines"][0]["sections"][0]["length"] = 5.0
    path = tmp_path / "short.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 2
    assert "farther than its length" in result.output


def test_values_that_look_like_the_wrong_unit_are_warned(tmp_path):
    """A 20 m line diameter (meant as 20 mm) and a phase of 90 in radians (meant in degrees):
    validate says so, naming the fields, and still accepts the case (an odd value may be
    right)."""
    import copy

    from test_case_errors import CHAIN

    data = copy.deepcopy(CHAIN)
    data["line_types"][0]["diameter"] = 20.0
    push = {"kind": "sine", "amplitude": 1.0, "period": 5.0, "phase": 90.0}
    data["bodies"][1]["external forces"].append({"model": "applied", "force_x": push})
    path = tmp_path / "units.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    result = CliRunner().invoke(main, ["validate", str(path)])
    assert result.exit_code == 0, result.output
    assert "line_types[0] (chain).diameter: 20 m is wider than any line" in result.output
    assert "bodies[1].external forces[1].force_x.phase: 90 rad is more than a turn" in (
        result.output
    )
