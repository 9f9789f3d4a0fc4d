"""seacable sweep: the load cases a sweep plans (crossed and zipped variations, seeds, a table,
probabilities), every load case a row whatever becomes of its run, the summary against the
runs' own files, a sweep run again reusing what ended, the same numbers on a local Dask
cluster as in one process, and the command line."""

import math
from pathlib import Path

import h5py
import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import seacable
from seacable import simulation, stats
from seacable import sweep as batch
from seacable.case import loader
from seacable.case.sweep import Variation
from seacable.cli import main
from seacable.errors import CaseError, OutputError

EXAMPLE = Path(__file__).parent.parent / "examples" / "spread_mooring_in_waves.yaml"
SHORT = ("simulation.duration=1.0", "simulation.build_up=0.5")
HS = "environment.waves[0].significant_height"
TOWARDS = "environment.waves[0].direction_deg"


def _case(*settings):
    return loader.with_settings(seacable.load_case(EXAMPLE), (*SHORT, *settings))


def _vary(path, values, **more):
    return Variation(path=path, values=values, **more)


def test_crossed_and_zipped_variations_with_their_shares():
    case = _case()
    todo = batch.plan(case, [_vary(HS, [2.0, 4.0], probabilities=[0.75, 0.25]),
                             _vary(TOWARDS, "0:360:120", probabilities=[0.5, 0.3, 0.2]),
                             _vary("environment.waves[0].peak_period", [8.0, 10.0, 12.0],
                                   along="direction_deg")])  # fmt: skip
    assert todo.dims == {"significant_height": [2.0, 4.0], "direction_deg": [0.0, 120.0, 240.0]}
    assert todo.along == {"peak_period": ("direction_deg", [8.0, 10.0, 12.0])}
    assert len(todo.cases) == 6 and not any(c.refused for c in todo.cases)
    last = todo.cases[-1]
    assert last.index == (1, 2) and last.label == "significant_height=4, direction_deg=240"
    wave = last.data["environment"]["waves"][0]
    assert (wave["significant_height"], wave["direction_deg"], wave["peak_period"]) == (
        4.0, 240.0, 12.0)  # fmt: skip
    assert "sweep" not in last.data
    np.testing.assert_allclose(todo.probability, np.outer([0.75, 0.25], [0.5, 0.3, 0.2]))
    assert len({c.file for c in todo.cases}) == 6  # each its own run


def test_seeds_and_a_table_of_load_cases(tmp_path):
    table = tmp_path / "cases.csv"
    table.write_text("name,environment.waves[0].significant_height,simulation.integrator,"
                     "probability\nmild,2.5,dopri5,0.9\nstorm,6,rk4,0.1\n")  # fmt: skip
    todo = batch.plan(_case(), seeds=3, load_cases=str(table))
    assert todo.dims == {"load_case": ["mild", "storm"], "seed": [1, 2, 3]}
    storm_seed_3 = todo.cases[-1].data
    assert storm_seed_3["environment"]["waves"][0]["seed"] == 3
    assert storm_seed_3["environment"]["waves"][0]["significant_height"] == 6
    assert storm_seed_3["simulation"]["integrator"] == "rk4"
    np.testing.assert_allclose(todo.probability, np.outer([0.9, 0.1], [1 / 3] * 3))


def test_the_cases_block_and_the_command_lines_variations_join():
    case = _case("sweep={vary: [{path: 'environment.waves[0].significant_height', "
                 "values: [2, 3]}], seeds: 2, storm: 3600}")  # fmt: skip
    todo = batch.plan(case, [_vary(TOWARDS, [0.0, 90.0])], storm=600.0)
    assert list(todo.dims) == ["significant_height", "direction_deg", "seed"]
    assert todo.sweep.storm == 600.0 and len(todo.cases) == 8


def test_values_the_case_refuses_are_rows_and_a_key_that_leads_nowhere_is_refused():
    todo = batch.plan(_case(), [_vary(HS, [2.0, -1.0])])
    assert not todo.cases[0].refused
    assert "significant_height" in todo.cases[1].refused and todo.cases[1].data is None
    with pytest.raises(CaseError, match="refuses every load case"):
        batch.plan(_case(), [_vary(HS, [-2.0, -1.0])])
    with pytest.raises(CaseError, match=r"sweep.vary 'environment.wave\[0\]\.x'.* no key 'wave'"):
        batch.plan(_case(), [_vary("environment.wave[0].x", [1.0])])
    with pytest.raises(CaseError, match="nothing varies"):
        batch.plan(_case())
    with pytest.raises(CaseError, match="the case has none"):
        batch.plan(_case("environment.waves=[]"), seeds=2)
    with pytest.raises(CaseError, match="2 values along 'significant_height', which has 3"):
        batch.plan(
            _case(),
            [_vary(HS, [1.0, 2.0, 3.0]), _vary(TOWARDS, [0, 1], along="significant_height")],
        )
    with pytest.raises(CaseError, match="at most 100,000"):
        batch.plan(_case(), [_vary(HS, "1:1000:1"), _vary(TOWARDS, "0:360:1")])


@pytest.mark.parametrize(
    ("text", "values"),
    [("a.b=2,4,6", [2, 4, 6]), ("a.b=[1, x]", [1, "x"]), ("a.b=5", [5]),
     ("a.b=0:360:90", [0.0, 90.0, 180.0, 270.0]), ("a.b = 1:2:0.25 ", [1.0, 1.25, 1.5, 1.75])],
)  # fmt: skip
def test_vary_on_the_command_line(text, values):
    assert batch.parse_vary(text).listed() == values


@pytest.mark.parametrize(
    ("text", "said"),
    [("a.b", "write PATH=VALUES"), ("a.b=", "write PATH=VALUES"),
     ("a.b=1:0:1", "the step must be positive"), ("a.b=1:x:2", "first:stop:step"),
     ("a.b=[1, ", "not a list")],
)  # fmt: skip
def test_vary_refused_in_one_line(text, said):
    with pytest.raises(CaseError, match=said) as found:
        batch.parse_vary(text)
    assert "\n" not in str(found.value)


def _rows(todo, output, **kw):
    seen = []
    found = batch.execute(todo, output, None, lambda d, n, lc, row: seen.append((lc, row)), **kw)
    return found, seen


def test_every_load_case_is_a_row_whatever_its_run_does(tmp_path, monkeypatch):
    """Complete, refused, diverged (its partial file kept) and failed (a bug in one run)."""
    todo = batch.plan(_case(), [_vary(HS, [2.0, -1.0, 3.0, 4.0])])
    real = simulation.simulate

    def simulate(case, output=None, **kw):
        height = case.environment.waves[0].significant_height
        if height == 3.0:
            results = real(case.model_copy(update={"simulation": case.simulation.model_copy(
                update={"duration": 0.5})}), output=output)  # fmt: skip
            with h5py.File(output, "r+") as f:  # as a run that diverged writes it
                f.attrs["status"] = results.dataset.attrs["status"] = "diverged"
            raise seacable.SimulationDiverged("the state became non-finite at t = 0.5 s",
                                              results)  # fmt: skip
        if height == 4.0:
            raise ZeroDivisionError("a bug")
        return real(case, output=output, **kw)

    monkeypatch.setattr(simulation, "simulate", simulate)
    found, seen = _rows(todo, tmp_path / "s.nc")
    assert list(found["status"].values) == ["complete", "refused", "diverged", "failed"]
    assert "significant_height" in str(found["message"].values[1])
    assert "internal error, a bug in seacable (ZeroDivisionError" in str(found["message"][3].values)
    assert np.isfinite(found["tension_max"].values[0]).all()
    assert np.isnan(found["tension_max"].values[1:]).all()  # no figures of an unfinished run
    runs = tmp_path / "s.runs"
    assert seacable.Results.open(runs / str(found["file"].values[2])).status == "diverged"
    assert len(seen) == 4 and found.attrs["counts"] == (
        "complete 1; diverged 1; failed 1; refused 1")  # fmt: skip
    assert xr.open_dataset(tmp_path / "s.nc")["status"].values.tolist() == found[
        "status"].values.tolist()  # fmt: skip


def test_the_summary_holds_what_the_runs_files_say(tmp_path):
    """From the end of the build-up (0.5 s) on; the offsets from where the buoy starts."""
    case = _case("simulation.duration=4.0")
    todo = batch.plan(case, [_vary(HS, [2.5, 5.0])], storm=3600.0)
    found, _ = _rows(todo, tmp_path / "s.nc")
    for k in range(2):
        results = seacable.Results.open(tmp_path / "s.runs" / str(found["file"].values[k]))
        whole = results["time"].values
        kept = whole >= 0.5
        assert kept.sum() == 8 and not kept[0]
        t = whole[kept]
        for line in case.lines:
            tension = results[f"lines/{line.name}/tension"].values[kept]
            row = found.isel(significant_height=k).sel(line=line.name)
            assert float(row["tension_max"]) == tension.max()
            assert float(row["tension_min"]) == tension.min()
            end = tension[:, 0] if tension[:, 0].mean() > tension[:, -1].mean() else tension[:, -1]
            assert float(row["tension_mean"]) == pytest.approx(end.mean(), rel=1e-12)
            s = stats.summary(t, end, storm=3600.0)
            assert float(row["tension_mpm"]) == pytest.approx(s.mpm, rel=1e-12, nan_ok=True)
            assert float(row["utilisation"]) == pytest.approx(tension.max() / 4.9e6, rel=1e-12)
        x, y = (results[f"bodies/buoy/position_{c}"].values for c in "xy")
        offset = np.hypot(x[kept] - x[0], y[kept] - y[0]).max()
        assert float(found["offset_max"].isel(significant_height=k, body=0)) == offset
    assert found["tension_max"].attrs["units"] == "N"
    assert found["significant_height"].attrs["path"] == HS


def test_run_again_it_reuses_what_ended_and_runs_the_rest(tmp_path):
    output = tmp_path / "s.nc"
    first, _ = _rows(batch.plan(_case(), [_vary(HS, [2.0, 4.0])]), output)
    runs = tmp_path / "s.runs"
    kept = {p.name: p.stat().st_mtime_ns for p in runs.iterdir()}
    # a run killed mid-way (its file 'incomplete') is run again; a grown sweep runs its new cases
    killed = runs / str(first["file"].values[1])
    with h5py.File(killed, "r+") as f:
        f.attrs["status"] = "incomplete"
    again, seen = _rows(batch.plan(_case(), [_vary(HS, [2.0, 4.0, 6.0])]), output)
    reused = [lc.label for lc, row in seen if row.get("reused")]
    assert reused == ["significant_height=2"]
    assert (runs / str(again["file"].values[0])).stat().st_mtime_ns == kept[
        str(first["file"].values[0])]  # fmt: skip
    assert list(again["status"].values) == ["complete"] * 3
    np.testing.assert_array_equal(again["tension_max"].values[:2], first["tension_max"].values)


def test_a_local_dask_cluster_gives_the_same_numbers_as_this_process(tmp_path):
    pytest.importorskip("distributed")
    todo = batch.plan(_case(), [_vary(HS, [2.0, 4.0])])
    here, _ = _rows(todo, tmp_path / "here.nc")
    there = batch.execute(todo, tmp_path / "there.zarr", "local")
    assert list(there["status"].values) == ["complete", "complete"]
    np.testing.assert_array_equal(there["tension_max"].values, here["tension_max"].values)
    np.testing.assert_array_equal(there["motion_std"].values, here["motion_std"].values)
    assert xr.open_zarr(tmp_path / "there.zarr")["status"].values.tolist() == ["complete"] * 2


def test_a_summary_replaces_nothing_but_a_summary(tmp_path):
    case = _case()
    (tmp_path / "notes.nc").write_text("mine")
    for name, said in [("notes.nc", "is not a 'seacable sweep summary' file"), ("s.csv", "NetCDF"),
                       ("none/s.nc", "does not exist")]:  # fmt: skip
        with pytest.raises(OutputError, match=said):
            batch.check_summary_output(tmp_path / name, case)
    (tmp_path / "mine.zarr").mkdir()
    (tmp_path / "mine.zarr" / "data").write_text("mine")
    with pytest.raises(OutputError, match="exists and is not a Zarr store"):
        batch.check_summary_output(tmp_path / "mine.zarr", case)
    (tmp_path / "mine.zarr" / ".zgroup").write_text("{}")
    with pytest.raises(OutputError, match="exists and is not a sweep's summary"):
        batch.check_summary_output(tmp_path / "mine.zarr", case)
    with pytest.raises(OutputError, match="is a file this command reads"):
        batch.check_summary_output(EXAMPLE, case)


def test_the_command_line(tmp_path):
    runner = CliRunner()
    output = tmp_path / "s.nc"
    args = ["sweep", str(EXAMPLE), *(f"--set={s}" for s in SHORT), "--dask", "none", "-o",
            str(output)]  # fmt: skip
    result = runner.invoke(main, [*args, "--vary", f"{HS}=2,4", "--storm", "600"])
    assert result.exit_code == 0, result.output
    assert "2 load cases (2 significant_height); runs in" in result.output
    assert "[2/2] significant_height=4: complete in" in result.output
    assert "largest tension of each line over the sweep:" in result.output
    assert "line_1: " in result.output and "at significant_height=" in result.output
    assert xr.open_dataset(output).attrs["storm"] == 600.0
    again = runner.invoke(main, [*args, "--vary", f"{HS}=2,4"])
    assert again.output.count("(ended before, reused)") == 2
    before = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "s.runs").iterdir()}
    rerun = runner.invoke(main, [*args, "--vary", f"{HS}=2,4", "--rerun"])
    assert rerun.exit_code == 0 and "reused" not in rerun.output
    after = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "s.runs").iterdir()}
    assert set(after) == set(before) and all(after[n] > before[n] for n in before)
    bad = runner.invoke(main, [*args, "--vary", f"{HS}=4:2:1"])
    assert bad.exit_code == 2 and "the step must be positive" in bad.output
    block = runner.invoke(main, ["validate", str(EXAMPLE), "--set", "sweep={seeds: 2}"])
    assert block.exit_code == 0 and "its sweep: block is for seacable sweep" in block.output
    nothing = runner.invoke(main, args)
    assert nothing.exit_code == 2 and "nothing varies" in nothing.output
    assert math.isfinite(float(xr.open_dataset(output)["tension_max"].max()))


@pytest.mark.slow
def test_a_scheduler_and_two_workers_one_killed_mid_sweep(tmp_path):
    """A scheduler and two workers started as their own processes on the loopback address;
    one worker killed (SIGKILL) while it runs: the sweep ends with every row accounted for
    (Dask gives the killed worker's run to the other)."""
    pytest.importorskip("distributed")
    import json
    import os
    import signal
    import subprocess
    import sys
    import time

    bin_dir = Path(sys.executable).parent
    address_file = tmp_path / "scheduler.json"
    started = [subprocess.Popen([bin_dir / "dask", "scheduler", "--host", "127.0.0.1",
                                 "--port", "0", "--no-dashboard", "--scheduler-file",
                                 address_file], stderr=subprocess.DEVNULL)]  # fmt: skip
    try:
        for _ in range(300):
            if address_file.exists() and address_file.stat().st_size:
                break
            time.sleep(0.1)
        address = json.loads(address_file.read_text())["address"]
        for _ in range(2):
            started.append(subprocess.Popen(
                [bin_dir / "dask", "worker", address, "--nthreads", "1", "--no-nanny",
                 "--no-dashboard", "--host", "127.0.0.1"], stderr=subprocess.DEVNULL))  # fmt: skip
        sweep = subprocess.Popen(
            [bin_dir / "seacable", "sweep", EXAMPLE, "--set", "simulation.duration=6",
             "--vary", f"{HS}=1:5:0.5", "--dask", address, "-o", tmp_path / "s.nc"],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)  # fmt: skip
        assert sweep.stdout is not None
        lines = []
        for line in sweep.stdout:
            lines.append(line)
            if line.startswith("[1/"):  # a run ended: both workers are busy with the next
                os.kill(started[1].pid, signal.SIGKILL)
                break
        rest, _ = sweep.communicate(timeout=900)
        output = "".join(lines) + rest
        assert sweep.returncode == 0, output
        found = xr.open_dataset(tmp_path / "s.nc")
        status = found["status"].values.tolist()
        assert len(status) == 8 and "not run" not in status, output
        assert status.count("complete") >= 7, output
        assert output.count("] significant_height=") == 8
    finally:
        for process in started:
            process.kill()
            process.wait()


def test_seeds_give_a_gumbel_estimate_of_the_storms_largest(tmp_path):
    todo = batch.plan(_case("simulation.duration=2.0"), seeds=3, storm=3600.0)
    found, _ = _rows(todo, tmp_path / "s.nc")
    assert found["tension_gumbel_mpm"].dims == ("line",)
    for line in ("line_1", "line_3"):
        maxima = found["tension_max"].sel(line=line).values
        expected = stats.gumbel_mpm(maxima, duration=1.5, storm=3600.0)  # 2 s, less 0.5 s
        assert float(found["tension_gumbel_mpm"].sel(line=line)) == pytest.approx(expected)
        assert float(found["tension_gumbel_mpm"].sel(line=line)) > maxima.max()


def test_the_weather_by_continuations_paths():
    """waves.height scales every wave to that significant height (a spectrum and a regular
    wave together: Hs = 4 sqrt(Hs1^2 / 16 + H2^2 / 8)); waves.towards_deg turns them all to
    that mean direction; current.speed and current.towards_deg give a uniform current."""
    from seacable.case.environment import Environment
    from seacable.stability.plane import significant_height

    case = _case(
        "environment.waves=[{kind: jonswap, significant_height: 3.0, peak_period: 9.0},"
        " {kind: airy, height: 2.0, period: 8.0}]"
    )
    todo = batch.plan(case, [batch.parse_vary("waves.height=1,6"),
                             batch.parse_vary("waves.towards_deg=90"),
                             batch.parse_vary("current.speed=0.5"),
                             batch.parse_vary("current.towards_deg=30")])  # fmt: skip
    assert list(todo.dims) == ["waves_height", "waves_towards_deg", "current_speed",
                               "current_towards_deg"]  # fmt: skip
    for load, height in zip(todo.cases, (1.0, 6.0), strict=True):
        environment = load.data["environment"]
        sea = Environment.model_validate(environment)
        assert significant_height(sea) == pytest.approx(height, rel=1e-12)
        ratio = environment["waves"][0]["significant_height"] / environment["waves"][1]["height"]
        assert ratio == pytest.approx(3.0 / 2.0)  # scaled together
        assert [w["direction_deg"] for w in environment["waves"]] == [90.0, 90.0]
        assert environment["current"] == {"velocity": 0.5, "direction_deg": 30.0}
    with pytest.raises(CaseError, match="the case has no wind"):
        batch.plan(case, [batch.parse_vary("wind.speed=10")])
    with pytest.raises(CaseError, match="not a weather path; the weather's are current.speed"):
        batch.plan(case, [batch.parse_vary("waves.hs=2:8:2")])
    with pytest.raises(CaseError, match="the weather takes numbers"):
        batch.plan(case, [batch.parse_vary("waves.height=[high]")])


def test_ctrl_c_keeps_the_summary_so_far_and_the_same_sweep_runs_the_rest(tmp_path):
    todo = batch.plan(_case(), [_vary(HS, [2.0, 4.0])])
    output = tmp_path / "s.nc"

    def stop(done, total, load, row):
        raise KeyboardInterrupt  # Ctrl-C as the first run ends

    with pytest.raises(KeyboardInterrupt):
        batch.execute(todo, output, None, stop)
    assert xr.open_dataset(output)["status"].values.tolist() == ["complete", "not run"]
    again, seen = _rows(todo, output)
    assert [bool(row.get("reused")) for _, row in seen] == [True, False]
    assert again["status"].values.tolist() == ["complete", "complete"]
