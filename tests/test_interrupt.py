"""A run stopped from outside keeps its rows: SIGTERM and SIGINT (Ctrl-C) end it after the
chunk under way with status ``interrupted``, the rows on disk readable by xarray, and exit codes
143 and 130 (128 + the signal)."""

import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

EXAMPLE = (
    Path(__file__).resolve().parent.parent / "examples/thesis_6_1_sim2_submerged_12_links.yaml"
)


def _long_case(tmp_path: Path) -> Path:
    """The 12-link thesis case run for an hour of simulated time (a few minutes of wall
    time): it is still running when the signal comes."""
    data = yaml.safe_load(EXAMPLE.read_text())
    data["simulation"]["duration"] = 3600.0
    path = tmp_path / "long.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


@pytest.mark.parametrize(("sig", "code"), [(signal.SIGTERM, 143), (signal.SIGINT, 130)],
                         ids=["SIGTERM", "SIGINT"])  # fmt: skip
def test_a_signalled_run_keeps_its_rows_and_says_it_was_interrupted(tmp_path, sig, code):
    case, out = _long_case(tmp_path), tmp_path / "long.nc"
    command = [sys.executable, "-c", "from seacable.cli import main; main()", "run", str(case),
               "-o", str(out), "--progress"]  # fmt: skip
    process = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    assert process.stderr is not None
    seen = ""
    while "simulating" not in seen:  # its progress bar: past the compilation, rows written
        line = process.stderr.read(80)
        assert line, f"the run ended before the signal: {seen[-500:]}"
        seen += line
    time.sleep(1.0)
    sent = time.perf_counter()
    process.send_signal(sig)
    rest = process.communicate(timeout=60)[1]
    answered = time.perf_counter() - sent
    assert process.returncode == code, rest[-500:]
    assert "partial results (status 'interrupted')" in rest
    assert answered < 5.0  # a chunk lasts about 0.5 s
    with xr.open_datatree(out, engine="h5netcdf") as tree:
        assert tree.attrs["status"] == "interrupted"
        who = "by SIGTERM" if sig == signal.SIGTERM else "by the user (Ctrl-C)"
        assert tree.attrs["status_message"].startswith(f"interrupted {who} at t = ")
        times = tree["time"].values
        assert len(times) > 10
        assert times[-1] < 3600.0
        angles = tree["lines/umbilical/node_z"].values
        assert np.all(np.isfinite(angles))
