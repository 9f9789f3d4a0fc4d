"""A run stopped from outside keeps its rows: SIGTERM and SIGINT (Ctrl-C) end it after the
chunk under way with status ``interrupted``, the rows on disk readable by xarray (those never
written NaN), and exit codes 143 and 130 (128 + the signal)."""

import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

import seacable

EXAMPLE = (
    Path(__file__).resolve().parent.parent / "examples/thesis_6_1_sim2_submerged_12_links.yaml"
)
MOORING = Path(__file__).resolve().parent.parent / "examples/catenary_mooring_line_surge.yaml"


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
        written = int(np.count_nonzero(np.isfinite(times)))
        assert 10 < written < len(times)
        assert np.all(np.isfinite(times[:written]))  # the rows written, then NaN
        nodes = tree["lines/umbilical/node_z"].values
        assert np.all(np.isfinite(nodes[:written])) and np.all(np.isnan(nodes[written:]))


def test_a_run_killed_at_any_moment_leaves_a_file_that_opens(tmp_path):
    """SIGKILL, which no program can catch, at moments spread over a run's start and its
    writing (seeded): the file, when it exists yet, opens with xarray and holds a prefix of
    whole rows (those whose time is written), status 'incomplete', and ``Results.open`` reads
    exactly those. Before, the file's structure stayed in HDF5's memory (h5netcdf's flush does
    not flush HDF5) and 0 of 10 files killed so opened."""
    case = _long_case(tmp_path)
    moments = np.random.default_rng(7).uniform(0.0, 3.0, 3)  # before and while writing
    for k, after in enumerate(moments):
        out = tmp_path / f"killed{k}.nc"
        command = [sys.executable, "-c", "from seacable.cli import main; main()", "run",
                   str(case), "-o", str(out), "--progress"]  # fmt: skip
        process = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
        assert process.stderr is not None
        if k % 2:  # every other one once its rows are being written
            seen = ""
            while "simulating" not in seen:
                chunk = process.stderr.read(80)
                assert chunk, seen[-500:]
                seen += chunk
        time.sleep(after)
        process.kill()
        process.communicate(timeout=60)
        if not out.exists():
            assert k % 2 == 0  # killed before the file was made
            continue
        with xr.open_datatree(out, engine="h5netcdf") as tree:
            assert tree.attrs["status"] == "incomplete"
            times = tree["time"].values
            written = int(np.count_nonzero(np.isfinite(times)))
            assert np.all(np.isfinite(times[:written]))
            nodes = tree["lines/umbilical/node_z"].values
            # the rows whose time is written are whole (time is written last); past them the
            # values of a chunk killed while being written may be there or NaN
            assert np.all(np.isfinite(nodes[:written]))
            if k % 2:
                assert written > 0
        assert seacable.Results.open(out).dataset.sizes["time"] == written


def test_a_second_run_does_not_write_over_a_file_being_written(tmp_path):
    """Another process writing the output file (HDF5 holds a lock on it): the run refuses,
    naming the file, instead of replacing it under that process."""
    import seacable

    out = tmp_path / "shared.nc"
    holder = subprocess.Popen(
        [sys.executable, "-c", "import h5py, sys, time; f = h5py.File(sys.argv[1], 'w'); "
         "print('open', flush=True); time.sleep(60)", str(out)],
        stdout=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        assert holder.stdout is not None and holder.stdout.readline().strip() == "open"
        case = seacable.load_case(EXAMPLE)
        with pytest.raises(seacable.OutputError, match=r"'.*shared\.nc' is being written by"):
            seacable.simulate(case, output=out)
    finally:
        holder.kill()
        holder.communicate()


@pytest.mark.parametrize("integrator", ["rk4", "dopri5", "bdf"])
def test_a_signal_is_answered_within_a_second_however_long_the_output_interval(
    tmp_path, integrator
):
    """One output interval of an hour (1.8 million rk4 steps, minutes): the run cuts it
    short (a fixed-step chunk counts steps, a dopri5 chunk tries a budget of steps sized to
    half a second, and SciPy's steps call Python, where the signal acts at once); SIGTERM is
    answered in about a second, the first row kept, status 'interrupted'. Before, a chunk was
    at least one output interval, and the signal waited for its end."""
    data = yaml.safe_load(MOORING.read_text())  # a catenary chain, its fairlead moved by a table
    data["simulation"] = {"duration": 3600.0, "output_interval": 3600.0, "integrator": integrator,
                          "time_step": 0.002} if integrator == "rk4" else {
        "duration": 3600.0, "output_interval": 3600.0, "integrator": integrator}  # fmt: skip
    text = yaml.safe_dump(data, sort_keys=False).replace("data/", f"{MOORING.parent}/data/")
    case, out = tmp_path / "one_row.yaml", tmp_path / "one_row.nc"
    case.write_text(text)
    command = [sys.executable, "-c", "from seacable.cli import main; main()", "run", str(case),
               "-o", str(out), "--progress"]  # fmt: skip
    process = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    waited = time.perf_counter()
    while not out.exists():  # made as the run starts (a stiff run's bar shows only at its end)
        assert process.poll() is None and time.perf_counter() - waited < 120
        time.sleep(0.1)
    time.sleep(3.0)
    assert process.poll() is None, "the run ended before the signal"
    sent = time.perf_counter()
    process.send_signal(signal.SIGTERM)
    rest = process.communicate(timeout=120)[1]
    answered = time.perf_counter() - sent
    assert process.returncode == 143, rest[-500:]
    assert answered < 3.0, answered
    with xr.open_datatree(out, engine="h5netcdf") as tree:
        assert tree.attrs["status"] == "interrupted"
        assert np.isfinite(tree["time"].values).tolist() == [True, False]
