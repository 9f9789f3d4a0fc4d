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
from seacable.stability.operability import Limits, clearance_at, grid, operability
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


WAVES = "examples/turret_fpso_wave_drift.yaml"


def _table(tmp_path, text: str):
    path = tmp_path / "states.csv"
    path.write_text(text)
    return path


def test_a_table_of_states_with_waves_maps_each_state_in_its_own_sea(tmp_path):
    """A user's table (current, wind, waves and each state's share of the time): each state's
    equilibrium is the one its own weather gives (the FPSO's turret tension, which the waves'
    drift changes), a state without waves has the case's, and the statuses' shares are
    weighed by the probabilities."""
    from pathlib import Path

    from seacable.stability.operability import shares, table

    path = _table(tmp_path, "# a metocean table\n"
                  "current_speed, current_towards_deg, wind_speed, wind_towards_deg, "
                  "wave_height, wave_towards_deg, probability\n"
                  "0.8, 180, 15, 200, 2.5, 150, 4\n"
                  "0.8, 180, 15, 200, , , 3\n"
                  "0.8, 180, 15, 200, 4.0, 240, 2\n"
                  "0.3, 0, 10, 45, 1.0, 300, 1\n")  # fmt: skip
    states, probability = table(path)
    assert states[1].wave_height is None and states[2].wave_towards_deg == 240.0
    np.testing.assert_allclose(probability, [0.4, 0.3, 0.2, 0.1])
    case = seacable.load_case(Path(__file__).parent.parent / WAVES)
    found = operability(case, states, None, scheduler=None, probability=probability)
    assert found["status"].dims == ("state",)
    np.testing.assert_allclose(found["wave_height"].values, [2.5, 2.5, 4.0, 1.0])
    np.testing.assert_allclose(found["wave_towards"].values, [150.0, 150.0, 240.0, 300.0],
                               atol=1e-9)  # fmt: skip
    plane = Plane.of(case)
    tensions = []
    for state, row in zip(states, found["tension"].values, strict=True):
        stable = [e for e in equilibria.find(plane, state, 12) if e.stable]
        plane.rates(np.concatenate([stable[0].x, np.zeros(3)]))
        tensions.append(float(plane.work.tie_tension.max()))
        assert row == pytest.approx(tensions[-1], rel=1e-9)
    assert tensions[0] == pytest.approx(tensions[1], rel=1e-12)  # the case's own sea
    assert abs(tensions[2] - tensions[0]) > 1e-2 * tensions[0]  # the waves act
    [(label, counts, share)] = shares(found)
    assert label == "" and sum(counts.values()) == 4
    assert sum(share.values()) == pytest.approx(1.0)
    for status, count in counts.items():
        picked = found["probability"].values[found["status"].values == status]
        assert len(picked) == count and share[status] == pytest.approx(picked.sum())


def test_a_bad_table_of_states_is_refused_in_one_line_naming_its_row(tmp_path):
    from seacable.errors import CaseError
    from seacable.stability.operability import table

    header = "current_speed,current_towards_deg,wind_speed,wind_towards_deg"
    for text, words in [
        ("current_speed,current_towards_deg,wind_speed\n0.8,180,15\n", "missing ['wind_towards"),
        (header + ",waves\n0.8,180,15,200,2\n", "unknown ['waves']"),
        (header + "\n0.8,180,15,200\n0.8,north,15,200\n", "line 3: current_towards_deg 'north'"),
        (header + "\n-0.8,180,15,200\n", "line 2: current_speed -0.8 is negative"),
        (header + "\n", "no states"),
    ]:
        with pytest.raises(CaseError) as caught:
            table(_table(tmp_path, text))
        message = str(caught.value)
        assert words in message and "\n" not in message, message


def test_the_operability_command_maps_a_table_of_states(tmp_path):
    from click.testing import CliRunner

    from seacable.cli import main

    root = __import__("pathlib").Path(__file__).parent.parent
    path = _table(tmp_path, "current_speed,current_towards_deg,wind_speed,wind_towards_deg,"
                  "wave_height,wave_towards_deg,probability\n"
                  "0.8,180,15,200,2.5,150,0.75\n0.5,90,20,270,4.0,270,0.25\n")  # fmt: skip
    picture = str(tmp_path / "m.png")
    run = CliRunner().invoke(main, ["operability", str(root / WAVES), "--states", str(path),
                                    "--dask", "none", "--plot", picture])  # fmt: skip
    assert run.exit_code == 0, run.output
    assert "2 weather states: stable 2 (100.0 % of the time)" in run.output
    assert (tmp_path / "m.png").stat().st_size > 10_000
    run = CliRunner().invoke(main, ["operability", str(root / EXAMPLE), "--states", str(path),
                                    "--dask", "none"])  # fmt: skip
    assert run.exit_code != 0 and "environment.waves: none" in run.output
    run = CliRunner().invoke(main, ["operability", str(root / EXAMPLE)])
    assert run.exit_code != 0 and "--current-speed: missing" in run.output


def test_the_controlled_map_keeps_the_shuttle_astern_where_it_is_stable_alongside_too():
    """With the compensator on, in a strong wind 100 deg off the current, the shuttle is held
    at 95 m both astern of the FPSO and beside its stern quarter, each stable: the map keeps
    the one where the ships lie to each other as at their nominal places, whichever way the
    weather turned them."""
    case = _example()
    plane = Plane.of(case)
    plane.control(True)
    weather = Weather(0.8, 110.0, 24.0, 10.0)
    found = [e for e in equilibria.find(plane, weather, 6, every=False) if e.stable]
    clearances = sorted(clearance_at(plane, e.x) for e in found)
    assert len(found) >= 2 and 0.0 < clearances[0] < 30.0 < clearances[-1]
    row = operability(case, [weather], None, Limits(30.0), scheduler=None, control="on")
    assert row["status"].values.ravel()[0] == "stable"
    assert row["clearance"].values.ravel()[0] == pytest.approx(clearances[-1], rel=1e-6)
    # in the FPSO's frame, the shuttle's midship 405 m astern at the nominal places; at the
    # equilibria, on the FPSO's heading, astern of it or beside its stern quarter
    assert equilibria.relative(plane, plane.start()[:6])[3] == pytest.approx(-405.0)
    poses = sorted((equilibria.relative(plane, e.x)[3:] for e in found), key=lambda q: q[0])
    assert poses[0][0] < -350.0 < -300.0 < poses[-1][0]
    assert all(abs(q[2]) < 1e-9 for q in poses)


def test_simulations_from_the_nominal_places_turn_with_the_weather():
    """``start="nominal"``: the shuttle at rest at its nominal place relative to the FPSO,
    the FPSO at its equilibrium. The turret's restoring is the same in every direction, so
    the weather turned by 90 deg gives the same motion turned: the same clearance and
    tension to round-off, and a motion that differs from the one from the equilibrium."""
    case = _example()
    limits = Limits(30.0, (("hawser", 3.0e6),))
    weathers = [Weather(0.8, 150.0, 16.0, 190.0), Weather(0.8, 240.0, 16.0, 280.0)]
    nominal = operability(case, weathers, None, limits, 600.0, scheduler=None, headings=6,
                          start="nominal")  # fmt: skip
    pushed = operability(case, weathers[:1], None, limits, 600.0, scheduler=None, headings=6)
    clearance, tension = nominal["clearance"].values, nominal["tension"].values
    assert clearance[0] == pytest.approx(clearance[1], rel=1e-6)
    assert tension[0] == pytest.approx(tension[1], rel=1e-6)
    assert abs(clearance[0] - pushed["clearance"].values[0]) > 1.0
    assert nominal.attrs["simulated_from"] == "nominal"
    with pytest.raises(seacable.CaseError, match="start 'anywhere'"):
        operability(case, weathers, None, limits, 600.0, scheduler=None, start="anywhere")


@pytest.mark.parametrize("currents", [[180.0], [150.0, 180.0]])
def test_a_map_of_one_current_direction_draws_its_cells(tmp_path, currents):
    """A grid of one current direction drew an empty map (matplotlib's cells around a single
    coordinate have no height): each status now fills its cell, one direction or several."""
    import matplotlib.image
    import xarray as xr

    from seacable.viz.operability import COLOURS, plot_operability

    statuses = ["stable", "limit exceeded", "cycling"]
    status = np.array([[[s] for s in statuses]] * len(currents), dtype=object)
    ds = xr.Dataset({"status": (("current_towards_deg", "wind_towards_deg",
                                 "wind_current_ratio"), status)},
                    coords={"current_towards_deg": currents,
                            "wind_towards_deg": [0.0, 90.0, 180.0],
                            "wind_current_ratio": [15.0]})  # fmt: skip
    picture = matplotlib.image.imread(plot_operability(ds, tmp_path / "map.png"))[..., :3]
    for name in statuses:
        colour = np.array([int(COLOURS[name][k : k + 2], 16) / 255 for k in (1, 3, 5)])
        share = np.mean(np.all(np.abs(picture - colour) < 0.02, axis=-1))
        assert share > 0.05, (name, share)  # each of three cells: a sixth of the picture


def test_a_calm_state_is_stable_not_cycling():
    """In a calm (no current, wind or waves) nothing damps the ships or holds their heading:
    the equilibrium's eigenvalues lie on the imaginary axis or left of it (to 1e-8 of their
    size, the heading a free direction), and no energy comes in to feed a motion; the state is
    stable, said so in its message, not "cycling" as any state without a stable equilibrium
    was. A current of 0.1 m/s gives the ordinary stable equilibrium."""
    case = _example()
    plane = Plane.of(case)
    calm = [e for e in equilibria.find(plane, Weather(), 6) if clearance_at(plane, e.x) > 0.0]
    assert calm and all(not e.stable for e in calm)
    neutral = [e for e in calm if e.neutral]
    assert neutral and all(e.kind == "neutral" for e in neutral)
    lam = neutral[0].eigenvalues
    size = np.abs(lam).max()
    assert np.all(lam.real < 1e-8 * size)  # nothing grows ...
    assert np.sum(np.abs(lam.real) < 1e-8 * size) >= 4  # ... nor decays, in most modes
    assert np.abs(lam).min() < 1e-6 * size  # the free heading
    rows = operability(case, [Weather(), Weather(0.1, 180.0)], None, Limits(30.0),
                       scheduler=None, headings=6)  # fmt: skip
    assert list(rows["status"].values) == ["stable", "stable"]
    assert rows["message"].values[0].startswith("calm:") and rows["message"].values[1] == ""
    assert not Weather(0.1, 180.0).calm(plane.built) and Weather().calm(plane.built)


def test_an_equilibrium_the_ships_do_not_reach_does_not_decide_and_compare_agrees():
    """Controlled, in a 24 m/s wind 120 deg off a 0.8 m/s current, the only stable equilibrium
    holds the shuttle 4.6 m from the FPSO, but from their nominal places the ships never
    reach it: the map said "limit exceeded, hulls 4.6 m apart" where ``compare`` found the
    run safe. The motion from the nominal places (the map's and compare's same start) decides
    the state now, and both give the same least clearance and tension peak."""
    from seacable.stability.operability import REACH

    case = _example()
    weather = Weather(0.8, 180.0, 24.0, 60.0)
    limits = Limits(30.0)
    row = operability(case, [weather], None, limits, scheduler=None, control="on", headings=6)
    row = row.isel(control=0, state=0)
    assert int(row["reached"]) == 0 and row["status"].item() in ("stable", "cycling")
    assert "hulls 4.6 m apart) is not reached" in row["message"].item()
    runs = seacable.compare(case, weather, REACH, every=5.0, limits=limits, headings=6)
    on = runs.sel(control="controlled")
    assert on["verdict"].item() == "safe"
    assert float(on["least_clearance"]) == pytest.approx(float(row["clearance"]), rel=1e-9)
    assert float(on["peak_tension"].max()) == pytest.approx(float(row["tension"]), rel=1e-9)


def test_a_reached_equilibrium_is_simulated_from_itself_when_asked():
    """With ``simulate`` from the equilibrium, a state whose equilibrium breaks a limit (here
    the hawser's tension, over a 200 kN limit) and is reached from the nominal places is judged
    by the motion from that equilibrium pushed by 1 m and 1 deg, as asked, not by the hour from
    the nominal places that checked it was reached."""
    from seacable.stability import operability as op

    case = _example()
    weather = Weather(0.8, 180.0, 15.0, 200.0)
    limits = Limits(30.0, (("hawser", 2.0e5),))
    row = operability(case, [weather], None, limits, 300.0, scheduler=None, headings=6)
    assert int(row["reached"].values[0]) == 1 and row["status"].values[0] == "limit exceeded"
    plane = Plane.of(case)
    weather.apply(plane.built)
    nominal = equilibria.relative(plane, plane.start()[:6])
    best, _ = op.kept(plane, op.search(plane, 6), nominal)
    push = np.concatenate([best.x, np.zeros(6)])
    push[0:6:3] += 1.0
    push[2:6:3] += np.radians(1.0)
    least = op._motion(plane, push, 300.0, limits)[0]
    assert float(row["clearance"].values[0]) == pytest.approx(least, rel=1e-12)
