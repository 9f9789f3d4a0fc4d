"""The command line: run, validate, plot, animate."""

from pathlib import Path

import yaml
from click.testing import CliRunner

from helpers import chain_case
from seacable.cli import main


def _case_file(tmp_path, **kwargs) -> Path:
    path = tmp_path / "case.yaml"
    data = chain_case(n=8, initial={"shape": "arc", "top_angle_deg": 30.0}, **kwargs)
    path.write_text(yaml.safe_dump(data))
    return path


def test_validate_ok_and_bad(tmp_path):
    runner = CliRunner()
    good = _case_file(tmp_path)
    result = runner.invoke(main, ["validate", str(good)])
    assert result.exit_code == 0 and "ok: case" in result.output
    bad = tmp_path / "bad.yaml"
    bad.write_text(good.read_text().replace("links: 8", "links: -1"))
    result = runner.invoke(main, ["validate", str(bad)])
    assert result.exit_code == 2
    assert "cables[0].links" in result.output


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
    assert result.exit_code == 2 and "use a .gif or .mp4" in result.output


def test_run_reports_divergence(tmp_path):
    data = chain_case(
        n=8,
        initial={"shape": "arc", "top_angle_deg": 30.0},
        simulation={"duration": 3.0, "output_interval": 0.1, "time_step": 0.05},
    )
    data["cables"][0]["bottom"] = {"type": "free", "body": {"mass": 0.01},
                                   "tie": {"stiffness_x": 1e7, "stiffness_z": 1e7}}  # fmt: skip
    case = tmp_path / "stiff.yaml"
    case.write_text(yaml.safe_dump(data))
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
    case.write_text(yaml.safe_dump(data))
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
