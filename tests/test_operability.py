"""The operability map (seacable.stability.operability): its statuses against the equilibria
found state by state, the same rows in this process and on Dask (a scheduler and two workers
started here as separate processes on the loopback address), and a failing state kept as a
row with its message."""

import socket
import subprocess
import sys
import time

import numpy as np
import pytest

import seacable
from seacable.stability import equilibria
from seacable.stability.operability import Limits, grid, operability
from seacable.stability.plane import Plane, Weather

EXAMPLE = "examples/tandem_offloading_fpso_shuttle.yaml"


def _example():
    from pathlib import Path

    return seacable.load_case(Path(__file__).parent.parent / EXAMPLE)


def test_a_small_map_in_this_process_agrees_with_the_equilibria_state_by_state():
    """(The search is not exhaustive: seeded by its neighbours, the map finds stable
    equilibria that a search from 12 headings per body misses; not the other way round.)"""
    case = _example()
    states, shape = grid(
        0.8, np.array([180.0, 90.0]), np.array([200.0, 0.0]), np.array([10.0, 25.0])
    )
    limits = Limits(30.0, (("hawser", 3.0e6),))
    found = operability(case, states, shape, limits, scheduler=None, headings=6)
    assert found["status"].shape == (2, 2, 2)
    assert set(found["status"].values.ravel()) <= {"stable", "limit exceeded", "cycling",
                                                    "collision risk", "no equilibrium"}  # fmt: skip
    # the example's own weather (current towards 180, wind 15 m/s towards 200: ratio 18.75
    # is not on the grid; 10 is): a stable tandem with the hawser in its limit
    first = found.isel(current_towards_deg=0, wind_towards_deg=0, wind_current_ratio=0)
    assert first["status"].item() == "stable" and first["clearance"].item() > 30.0
    plane = Plane.of(case)
    for state, status in zip(states, found["status"].values.ravel(), strict=True):
        stable = [e for e in equilibria.find(plane, state, 12) if e.stable]
        if stable:  # the map, seeded by its neighbours, misses no stable state the search finds
            assert status in ("stable", "limit exceeded", "collision risk")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def dask_cluster():
    """A scheduler and two single-threaded workers, each its own process, on 127.0.0.1."""
    pytest.importorskip("distributed")
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    dask = [sys.executable, "-m", "distributed.cli.dask_scheduler"]
    procs = [subprocess.Popen([*dask, "--host", "127.0.0.1", "--port", str(port),
                               "--dashboard-address", ":0"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]  # fmt: skip
    time.sleep(2.0)
    for _ in range(2):
        procs.append(subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_worker", address, "--nthreads", "1",
             "--nworkers", "1", "--no-dashboard"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))  # fmt: skip
    from distributed import Client

    with Client(address, timeout=60) as client:
        client.wait_for_workers(2, timeout=120)
    yield address
    for p in procs[::-1]:
        p.terminate()
    for p in procs:
        p.wait(timeout=30)


def test_a_map_on_a_running_scheduler_gives_the_same_rows_and_keeps_a_failed_state(dask_cluster):
    case = _example()
    states, shape = grid(0.8, np.array([180.0, 150.0]), np.array([200.0, 260.0]), np.array([12.0]))
    limits = Limits(30.0, (("hawser", 3.0e6),))
    here = operability(case, states, shape, limits, scheduler=None, headings=6)
    there = operability(case, states, shape, limits, scheduler=dask_cluster, chunk=1, headings=6)
    assert (here["status"].values == there["status"].values).all()
    np.testing.assert_allclose(here["tension"].values, there["tension"].values, rtol=1e-9)
    # a state that cannot run (a wind on a case whose ships have no wind model) is a row
    bad = [states[0], Weather(float("nan"), 180.0, 12.0, 200.0)]
    found = operability(case, bad, None, limits, scheduler=dask_cluster, chunk=1, headings=6)
    assert list(found["status"].values[:1]) == [here["status"].values.ravel()[0]]
    assert found["status"].values[1] in ("failed", "no equilibrium")


def test_the_operability_command_writes_the_map_and_its_picture(tmp_path):
    import xarray as xr
    from click.testing import CliRunner

    from seacable.cli import main

    root = __import__("pathlib").Path(__file__).parent.parent
    run = CliRunner().invoke(main, [
        "operability", str(root / EXAMPLE), "--current-speed", "0.8",
        "--current-towards", "180,150", "--wind-towards", "0:360:180", "--ratios", "15",
        "--clearance", "30", "--tension-limit", "hawser", "3e6", "--dask", "none",
        "-o", str(tmp_path / "m.nc"), "--plot", str(tmp_path / "m.png"),
    ])  # fmt: skip
    assert run.exit_code == 0, run.output
    assert "4 weather states:" in run.output
    found = xr.open_dataset(tmp_path / "m.nc")
    assert found["status"].shape == (2, 2, 1)
    assert (tmp_path / "m.png").stat().st_size > 20_000
    run = CliRunner().invoke(main, ["operability", str(root / EXAMPLE), "--current-speed", "1",
                                    "--wind-towards", "0:x:1"])  # fmt: skip
    assert run.exit_code != 0 and "--wind-towards '0:x:1'" in run.output
