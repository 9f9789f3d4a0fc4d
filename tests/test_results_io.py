"""Results: NetCDF written as the run goes, units on every variable, status kept on failure."""

from pathlib import Path

import numpy as np
import pytest

import seacable
from helpers import chain_case, upgraded
from seacable import simulation as simulate_module


def _swing(**simulation):
    return chain_case(
        n=10,
        initial={"shape": "arc", "top_angle_deg": 45.0},
        simulation={"duration": 1.0, "output_interval": 0.1, **simulation},
    )


def test_netcdf_has_units_long_names_and_provenance(tmp_path):
    path = tmp_path / "out.nc"
    results = seacable.simulate(upgraded(_swing()), output=path)
    assert results.status == "complete"
    reread = seacable.Results.open(path)
    ds = reread.dataset
    assert dict(ds["lines/cable"].sizes) == {"time": 11, "segment": 10, "node": 11}
    for group in ds.subtree:
        for name, var in group.variables.items():
            assert "units" in var.attrs and "long_name" in var.attrs, (group.path, name)
    assert ds.attrs["status"] == "complete"
    assert ds.attrs["seacable_version"] == seacable.__version__
    assert "segments: 10" in ds.attrs["case"]
    assert ds.attrs["solver_integrator"] == "rk4"
    tension = ds["lines/cable/tension"].values
    np.testing.assert_allclose(tension, results.dataset["lines/cable/tension"].values)


def test_diverging_run_keeps_partial_results_marked(tmp_path, caplog):
    data = _swing(time_step=0.05, duration=5.0, allow_unstable_step=True)
    data["cables"][0]["bottom"] = {
        "type": "free",
        "body": {"mass": 0.01},
        "tie": {"stiffness_x": 1e7, "stiffness_z": 1e7},
    }
    path = tmp_path / "diverged.nc"
    with pytest.raises(seacable.SimulationDiverged) as info:
        seacable.simulate(upgraded(data), output=path)
    message = str(info.value)
    assert "simulation diverged after t =" in message
    assert "reduce simulation.time_step" in message
    assert "fastest motion at component" in message
    assert "beyond rk4's stability limit" in caplog.text  # allowed, and warned before the run
    on_disk = seacable.Results.open(path)
    assert on_disk.status == "diverged"
    assert on_disk.dataset.sizes["time"] >= 1
    assert np.all(np.isfinite(on_disk.dataset["lines/cable/node_x"].values))
    assert info.value.results.status == "diverged"


def test_interrupted_run_keeps_partial_results(tmp_path, monkeypatch):
    original = simulate_module._Run.advance

    def interrupt_later(self, count):  # once two outputs are written (a chunk may hold none)
        if self.done >= 2:
            raise KeyboardInterrupt
        return original(self, count)

    monkeypatch.setattr(simulate_module._Run, "advance", interrupt_later)
    path = tmp_path / "interrupted.nc"
    with pytest.raises(seacable.SimulationInterrupted):
        seacable.simulate(upgraded(_swing(duration=10.0)), output=path)
    on_disk = seacable.Results.open(path)
    assert on_disk.status == "interrupted"
    assert 1 < on_disk.dataset.sizes["time"] < 101


def test_file_is_readable_while_running(tmp_path, monkeypatch):
    """Rows are flushed chunk by chunk: a reader mid-run sees them, status 'incomplete'."""
    seen = []
    original = simulate_module._Run.advance
    path = tmp_path / "live.nc"

    def peek(self, count):
        status = original(self, count)
        if not seen and self.done >= 1:  # a row past t = 0 written (a chunk may hold none)
            seen.append(seacable.Results.open(path))
        return status

    monkeypatch.setattr(simulate_module._Run, "advance", peek)
    seacable.simulate(upgraded(_swing(duration=2.0)), output=path)
    assert seen[0].status == "incomplete"
    assert seen[0].dataset.sizes["time"] >= 2


def test_a_file_is_in_proportion_to_its_rows(tmp_path):
    """A lumped line of 100,000 segments with two rows (t = 0 and one output): about 36 bytes a
    node a row (its nodes, the segments' tensions, arc lengths), 7.3 MB, where chunks of 1024
    rows made it 4.1 GB; the variables are stored whole, allocated as the run starts."""
    n = 100_000
    case = {"name": "long line", "start": "as_given", "environment": {"water_depth": 5000.0},
            "bodies": [{"name": "a", "type": "fixed", "position": [0.0, 0.0, -4000.0]},
                       {"name": "b", "type": "fixed", "position": [0.99 * n, 0.0, -4000.0]}],
            "line_types": [{"name": "rope", "diameter": 0.02, "mass_per_length": 1.0,
                            "axial_stiffness": 1e6}],
            "lines": [{"name": "line", "model": "lumped_mass", "from": "a", "to": "b",
                       "sections": [{"type": "rope", "length": float(n), "segments": n}],
                       "initial": "straight"}],
            "simulation": {"duration": 1e-4, "output_interval": 1e-4, "integrator": "rk4",
                           "time_step": 1e-4}}  # fmt: skip
    path = tmp_path / "long.nc"
    results = seacable.simulate(seacable.load_case(case), output=path)
    assert results.dataset.sizes["time"] == 2
    assert path.stat().st_size < 50 * 2 * (n + 1)


def test_a_results_file_repeats_its_run(tmp_path):
    """A file keeps how to repeat its run: the case, every setting resolved, the text of the
    files the case read, the software's versions and the platform; ``seacable repeat`` runs it
    again from the file alone (the table file deleted) and gives the same numbers, bit for
    bit."""
    import copy

    import xarray as xr
    import yaml
    from click.testing import CliRunner

    from seacable.cli import main
    from test_case_errors import CHAIN

    data = copy.deepcopy(CHAIN)
    push = {"model": "applied", "force_x": {"kind": "table", "file": "tables/push.csv"}}
    data["bodies"][1]["external forces"].append(push)
    (tmp_path / "tables").mkdir()
    (tmp_path / "tables/push.csv").write_text("time,force\n0,0\n0.5,3\n1,0\n")
    case = tmp_path / "case.yaml"
    case.write_text(yaml.safe_dump(data, sort_keys=False))
    first = tmp_path / "first.nc"
    seacable.simulate(seacable.load_case(case), output=first)
    (tmp_path / "tables/push.csv").unlink()
    again = tmp_path / "again.nc"
    result = CliRunner().invoke(main, ["repeat", str(first), "-o", str(again), "--no-progress"])
    assert result.exit_code == 0, result.output
    with xr.open_datatree(first) as a, xr.open_datatree(again) as b:
        assert yaml.safe_load(a.attrs["input_files"]) == {
            "tables/push.csv": "time,force\n0,0\n0.5,3\n1,0\n"
        }
        assert "numba" in a.attrs["software"] and a.attrs["platform"]
        assert yaml.safe_load(a.attrs["case_resolved"])["simulation"]["integrator"] == "rk4"
        assert np.ptp(a["bodies/end/position_x"].values) > 0.0  # the table's push moved it
        for node in a.subtree:
            for name, values in node.data_vars.items():
                np.testing.assert_array_equal(b[node.path][name].values, values.values)


def test_memory_stays_flat_while_rows_go_to_the_file(tmp_path, monkeypatch):
    """Rows written to a file leave memory: over a run of 20,000 rows (about 10 MB of rows),
    the memory Python and NumPy hold grows by less than 1 MB between the first tenth of the
    run and its end (tracemalloc, after each chunk): 0.18 MB measured, against 9.5 MB for the
    same run kept in memory (no file), as every run was before."""
    import tracemalloc

    from test_case_errors import CHAIN

    data = {**CHAIN, "simulation": {"duration": 200.0, "output_interval": 0.01,
                                    "integrator": "rk4", "time_step": 0.01}}  # fmt: skip
    case = seacable.load_case(data)
    held: list[tuple[int, int]] = []
    original = simulate_module._Run.advance

    def measured(self, count):
        status = original(self, count)
        held.append((self.done, tracemalloc.get_traced_memory()[0]))
        return status

    monkeypatch.setattr(simulate_module._Run, "advance", measured)
    # every chunk's rows written at once (a write slowed by tracemalloc holds them otherwise)
    monkeypatch.setattr(seacable.results, "SLOW_WRITE", float("inf"))
    tracemalloc.start()
    try:
        results = seacable.simulate(case, output=tmp_path / "long.nc", chunk_outputs=500)
    finally:
        tracemalloc.stop()
    size = sum(v.size for node in results.dataset.subtree for v in node.data_vars.values())
    assert size * 8 > 9e6  # the rows are many
    early = next(memory for done, memory in held if done >= 2000)
    assert held[-1][1] - early < 1e6, held[-1][1] - early


def test_an_output_in_a_missing_folder_is_refused(tmp_path):
    """A mistyped folder is named, not created silently."""
    from test_case_errors import CHAIN

    with pytest.raises(
        seacable.OutputError, match=r"output '.*typo/run.nc': its folder '.*typo' does not exist"
    ):
        seacable.simulate(seacable.load_case(CHAIN), output=tmp_path / "typo" / "run.nc")


def _chain_with_table(tmp_path, name: str):
    """The chain case pushed by a table file ``name`` (relative to the case, or absolute)."""
    import copy

    import yaml

    from test_case_errors import CHAIN

    data = copy.deepcopy(CHAIN)
    push = {"model": "applied", "force_x": {"kind": "table", "file": name}}
    data["bodies"][1]["external forces"].append(push)
    table = Path(name) if Path(name).is_absolute() else tmp_path / name
    table.write_text("time,force\n0,0\n0.5,3\n1,0\n")
    case = tmp_path / "case.yaml"
    case.write_text(yaml.safe_dump(data, sort_keys=False))
    return case, table


def test_a_run_refuses_to_write_over_a_file_it_reads_or_one_that_is_not_results(tmp_path):
    """The case's own file, its table file (whatever its suffix), and an existing file that is
    not a results file are refused as outputs, naming them; nothing is written over."""
    case, table = _chain_with_table(tmp_path, "push.dat")
    loaded = seacable.load_case(case)
    with pytest.raises(
        seacable.OutputError, match=r"output '.*push\.dat' is a file this command reads"
    ):
        seacable.simulate(loaded, output=table)
    notes = tmp_path / "notes.nc"
    notes.write_bytes(b"%PDF-1.4 not results")
    with pytest.raises(seacable.OutputError, match=r"'.*notes\.nc' exists and is not a 'seacable "
                       "simulation results' file"):  # fmt: skip
        seacable.simulate(loaded, output=notes)
    with pytest.raises(seacable.OutputError, match=r"'\.pdf' is not one of its names"):
        seacable.simulate(loaded, output=tmp_path / "notes.pdf")
    assert table.read_text().startswith("time,force") and notes.read_bytes().startswith(b"%PDF")


def test_a_run_refuses_to_write_over_its_hydrodynamic_database(tmp_path):
    """``seacable run ... -o data/barge_hydrodb.nc`` replaced the case's database (issue 42's
    first example): the databases are among the files a run reads, and a WAMIT database's
    side files beside its .1 too."""
    import shutil

    from seacable.case import loader

    examples = Path(__file__).parent.parent / "examples"
    shutil.copytree(examples / "data", tmp_path / "data")
    shutil.copy(examples / "moored_barge_irregular_sea.yaml", tmp_path)
    case = seacable.load_case(tmp_path / "moored_barge_irregular_sea.yaml")
    database = tmp_path / "data" / "barge_hydrodb.nc"
    assert database.resolve() in loader.files_read(case)
    before = database.read_bytes()
    with pytest.raises(
        seacable.OutputError, match=r"barge_hydrodb\.nc' is a file this command reads"
    ):
        seacable.simulate(case, output=database)
    assert database.read_bytes() == before
    wamit = case.model_copy(
        update={
            "bodies": [
                b.model_copy(
                    update={"hydrodynamics": b.hydrodynamics.model_copy(update={"file": "h.1"})}
                )
                if getattr(b, "hydrodynamics", None) is not None
                else b
                for b in case.bodies
            ]
        }
    )
    wamit._base_dir = case._base_dir
    side = {p.name for p in loader.files_read(wamit)}
    assert {"h.1", "h.3", "h.3sc", "h.3fk", "h.hst"} <= side


def test_a_run_whose_table_lies_outside_its_folder_is_repeated(tmp_path):
    """A table given by an absolute path is kept in the results file too; ``seacable repeat``
    puts it beside the case it runs again and gives the same numbers, bit for bit."""
    import xarray as xr
    from click.testing import CliRunner

    from seacable.cli import main

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    folder = tmp_path / "case"
    folder.mkdir()
    case, table = _chain_with_table(folder, str(elsewhere / "push.csv"))
    first = tmp_path / "first.nc"
    seacable.simulate(seacable.load_case(case), output=first)
    table.unlink()
    again = tmp_path / "again.nc"
    result = CliRunner().invoke(main, ["repeat", str(first), "-o", str(again), "--no-progress"])
    assert result.exit_code == 0, result.output
    with xr.open_datatree(first) as a, xr.open_datatree(again) as b:
        assert np.ptp(a["bodies/end/position_x"].values) > 0.0
        np.testing.assert_array_equal(
            b["bodies/end/position_x"].values, a["bodies/end/position_x"].values
        )


def test_a_file_the_disk_cannot_hold_is_refused_with_its_size(tmp_path, monkeypatch):
    """The file is allocated whole when it is created: with too little room on its disk the run
    is refused before it starts, naming the size it needs and the room there is, an estimate
    within 5 % of the size the run writes."""
    import collections

    from seacable import results as results_module
    from test_case_errors import CHAIN

    data = {**CHAIN, "simulation": {"duration": 20.0, "output_interval": 0.01,
                                    "integrator": "rk4", "time_step": 0.01}}  # fmt: skip
    case = seacable.load_case(data)
    written = tmp_path / "fits.nc"
    seacable.simulate(case, output=written)
    usage = collections.namedtuple("usage", "total used free")
    monkeypatch.setattr(results_module.shutil, "disk_usage", lambda _: usage(1e9, 1e9, 1000))
    with pytest.raises(seacable.OutputError) as info:
        seacable.simulate(case, output=tmp_path / "full.nc")
    message = str(info.value)
    assert "needs about" in message and "its disk has 1e-06 GB free" in message
    needed = float(message.split("needs about ")[1].split(" GB")[0]) * 1e9
    assert abs(needed - written.stat().st_size) < 0.05 * written.stat().st_size
    assert not (tmp_path / "full.nc").exists()


def test_a_large_file_is_read_back_lazily_so_memory_stays_bounded_to_the_end(tmp_path, monkeypatch):
    """Beyond ``EAGER_BYTES`` the results a run returns are read from its file as used: here
    (the bound set to 0) a 20,000-row run ends with less than 1 MB of rows held (tracemalloc),
    against 10.7 MB read back whole; the rows read lazily are those in the file. Before, every
    run read its whole file back at its end: a 2-million-row run of 1.04 GB peaked at 1.3 GB
    of memory, flat at 0.31 GB while it ran; now 0.34 GB."""
    import tracemalloc

    from seacable import results as results_module
    from test_case_errors import CHAIN

    data = {**CHAIN, "simulation": {"duration": 200.0, "output_interval": 0.01,
                                    "integrator": "rk4", "time_step": 0.01}}  # fmt: skip
    case = seacable.load_case(data)
    whole = seacable.simulate(case, output=tmp_path / "whole.nc")
    monkeypatch.setattr(results_module, "EAGER_BYTES", 0)
    tracemalloc.start()
    lazy = seacable.simulate(case, output=tmp_path / "lazy.nc")
    held = tracemalloc.get_traced_memory()[0]
    tracemalloc.stop()
    assert held < 1e6, held
    end = lazy["bodies/end/position_x"].values
    np.testing.assert_array_equal(end, whole["bodies/end/position_x"].values)
    assert lazy.status == "complete" and len(end) == 20001
    lazy.close()


def test_a_results_file_reads_as_xarray_reads_it_in_either_mode(tmp_path):
    """``Results.open`` reads seacable's grouped files itself (``results._tree``: h5netcdf's
    dimension lookup is quadratic in the variables, 270 s for a run of 800 anchors): the tree
    is the one ``xarray.open_datatree`` gives, attributes, coordinates and units included,
    whole or read lazily, for a rigid body, a point body and lines; an unfinished run's rows
    never written are left out alike."""
    import xarray as xr

    from helpers import turning_body_case

    run = {"duration": 0.4, "output_interval": 0.1, "integrator": "rk4", "time_step": 0.001}
    case = seacable.load_case(turning_body_case(run))
    path = tmp_path / "turning.nc"
    seacable.simulate(case, output=path)
    with xr.open_datatree(path, engine="h5netcdf") as expected:
        expected = expected.load()
    whole = seacable.Results.open(path).dataset
    xr.testing.assert_identical(whole, expected)
    lazy = seacable.Results.open(path, lazy=True)
    xr.testing.assert_identical(lazy.dataset.load(), expected)
    rope = lazy["lines/rope/tension"]
    np.testing.assert_array_equal(rope[1:3, ::2].values, expected["lines/rope/tension"][1:3, ::2])
    lazy.close()  # the file closed: a run may replace it
    import h5py

    assert not [f for f in h5py.h5f.get_obj_ids(h5py.h5f.OBJ_ALL, h5py.h5f.OBJ_FILE)
                if Path(f.name.decode()).resolve() == path.resolve()]  # fmt: skip
    assert set(whole["bodies"].children) == {"top", "float", "weight"}


def test_rows_held_while_writing_is_slow_all_reach_the_file(tmp_path, monkeypatch):
    """Where a write takes longer than ``SLOW_WRITE`` (a system of thousands of bodies) the
    next chunks' rows are held and written together: with every write taken as slow, the file
    holds every row, equal to those of a run that writes each chunk at once, and a reader
    mid-run finds a file that opens."""
    import xarray as xr

    from seacable import results as results_module

    case = upgraded(_swing(duration=2.0))
    at_once = seacable.simulate(case, output=tmp_path / "at_once.nc", chunk_outputs=2)
    # a clock that moves a second each time it is read: a write "takes" a second, and the
    # rows of the next chunks are held until nine more have passed
    ticks = iter(range(1_000_000))
    monkeypatch.setattr(results_module, "monotonic", lambda: float(next(ticks)))
    monkeypatch.setattr(results_module, "SLOW_WRITE", 0.5)
    seen = []
    original = simulate_module._Run.advance

    def peek(self, count):
        status = original(self, count)
        found = seacable.Results.open(tmp_path / "held.nc")
        seen.append((found.status, found.dataset.sizes["time"], self.done + 1))
        return status

    monkeypatch.setattr(simulate_module._Run, "advance", peek)
    held = seacable.simulate(case, output=tmp_path / "held.nc", chunk_outputs=2)
    assert {status for status, _, _ in seen} == {"incomplete"}
    assert any(in_file < done for _, in_file, done in seen)  # some rows were held
    assert any(in_file == done for _, in_file, done in seen[1:])  # and written later
    reread = seacable.Results.open(tmp_path / "held.nc").dataset
    for ds in (reread, held.dataset):
        assert ds.sizes["time"] == 21
        xr.testing.assert_equal(
            ds["lines/cable"].to_dataset(), at_once.dataset["lines/cable"].to_dataset()
        )


def test_a_changed_results_file_is_refused_as_damaged_not_as_a_bug(tmp_path):
    """A seacable results file whose dimensions were tampered with (a group's time no longer
    a dimension scale) is refused in one line naming the file, not an internal error."""
    import h5py

    path = tmp_path / "changed.nc"
    seacable.simulate(upgraded(_swing()), output=path)
    with h5py.File(path, "r+") as f:
        del f["lines/cable/time"].attrs["CLASS"]
    with pytest.raises(seacable.InputError, match=r"changed\.nc' cannot be read as seacable's"):
        seacable.Results.open(path)
