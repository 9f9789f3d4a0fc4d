"""Limit cycles born at a Hopf point (seacable.stability.cycles): the shuttle tanker on its
hawser fishtails once its astern thrust falls below the Routh-Hurwitz value (about 112 kN,
tests/test_stability.py). The branch of periodic orbits from that Hopf point starts at the
period 2 pi / omega of the crossing pair, lies on the side where the equilibrium is unstable,
and its orbits are stable: a supercritical point. Simulation says so on its own (the settled
amplitude shrinks in proportion to the distance from the Hopf point, as the |v| v terms make
it), and the settled amplitudes agree with the branch's orbits; an orbit of the branch, run by
the system's own dopri5 for one period, returns to its start."""

import math

import numpy as np
import pytest
import yaml

import seacable
from seacable.stability import cycles
from seacable.stability.continuation import Continuation
from seacable.stability.parameters import parameter
from seacable.stability.plane import Plane
from test_stability import shuttle_case

THRUST = "bodies.shuttle.external forces.1.force_x"


# the branch and the runs that judge the Hopf point take about 100 s: run by make test-all
SLOW = pytest.mark.slow


@pytest.fixture(scope="module")
def hopf_cycles():
    case = shuttle_case("short-wing")
    plane = Plane.of(case)
    par = parameter(plane, THRUST)
    branch = Continuation(plane, par).run(np.array([-240.0, 0.0, 0.0]), -2e5, 0.0)
    hopf = next(s for s in branch.special if s.kind == "hopf")
    found, kind = cycles.from_hopf(plane, par, hopf.x, hopf.parameter, hopf.frequency,
                                   (-2e5, 0.0), 7, 1000.0)  # fmt: skip
    return case, hopf, found, kind


@SLOW
def test_the_branch_starts_at_the_hopf_period_on_the_unstable_side_with_stable_orbits(
    hopf_cycles,
):
    _, hopf, found, _ = hopf_cycles
    assert len(found.parameter) == 7
    assert found.period[0] == pytest.approx(2 * math.pi / hopf.frequency, rel=1e-3)
    # less astern thrust than at the Hopf point: where the equilibrium fishtails
    assert all(mu > hopf.parameter for mu in found.parameter)
    assert all(found.stable) and not found.folds
    sway = [a[1] for a in found.amplitude]
    assert np.all(np.diff(sway) > 0) and sway[-1] > 10.0
    # the |v| v terms: amplitude nearly in proportion to the distance from the Hopf point
    slope = np.array(sway) / (np.array(found.parameter) - hopf.parameter)
    assert np.ptp(slope[2:]) < 0.2 * slope[-1]


@SLOW
def test_simulation_says_supercritical_and_settles_on_the_branchs_orbits(hopf_cycles):
    _, hopf, found, kind = hopf_cycles
    assert kind.kind == "supercritical" and kind.hysteresis is None
    big, small = kind.amplitudes
    assert 0.15 < small / big < 0.4  # as the distance (1/4), not its square root (1/2)
    order = np.argsort(found.parameter)
    mu = np.array(found.parameter)[order]
    heading = np.array([a[2] for a in found.amplitude])[order] * 1e3  # scaled: 1e-3 rad
    # Aitken's limit of a slow approach (multipliers 0.999 a period near the Hopf point): the
    # nearer run is 2.5 % off the branch, the farther 0.4 % (measured)
    for tried, settled in zip(kind.parameters, kind.amplitudes, strict=True):
        assert np.interp(tried, mu, heading) == pytest.approx(settled, rel=0.05)


@SLOW
def test_an_orbit_of_the_branch_returns_to_its_start_under_dopri5(hopf_cycles):
    case, _, found, _ = hopf_cycles
    k = len(found.parameter) - 1
    x0, period = found.x0[k], found.period[k]
    data = case.model_dump(by_alias=True, exclude_none=True)
    ship = next(b for b in data["bodies"] if b["name"] == "shuttle")
    ship.update(position=[x0[0], x0[1], 0.0], orientation_deg=[0.0, 0.0, math.degrees(x0[2])],
                velocity=[x0[3], x0[4], 0.0], angular_velocity=[0.0, 0.0, x0[5]])  # fmt: skip
    ship["external forces"][1]["force_x"] = {"kind": "constant", "value": found.parameter[k]}
    data["simulation"] = {"duration": period, "output_interval": period / 100,
                          "integrator": "dopri5", "rtol": 1e-10}  # fmt: skip
    run = seacable.simulate(seacable.load_case(data))
    end = [float(np.asarray(run[f"bodies/shuttle/{name}"])[-1])
           for name in ("position_x", "position_y")]  # fmt: skip
    yaw = math.radians(float(np.asarray(run["bodies/shuttle/yaw"])[-1]))
    assert np.abs(np.array(end) - x0[:2]).max() < 1e-2
    assert abs(math.remainder(yaw - x0[2], 2 * math.pi)) < 1e-4
    swing = np.ptp(np.asarray(run["bodies/shuttle/position_y"]))
    assert swing == pytest.approx(found.amplitude[k][1], rel=1e-3)


@SLOW  # the criticality's simulations: about 110 s of one core
def test_the_command_line_reports_the_cycles_and_their_kind(tmp_path):
    from click.testing import CliRunner

    from seacable.cli import main

    data = shuttle_case("short-wing").model_dump(by_alias=True, exclude_none=True)
    case_file = tmp_path / "shuttle.yaml"
    case_file.write_text(yaml.safe_dump(data))
    out = CliRunner().invoke(main, ["continuation", str(case_file), "--parameter", THRUST,
                                    "--from", "-1.3e5", "--to", "-1.0e5", "--headings", "2",
                                    "--cycles", "3", "--plot", str(tmp_path / "b.png"),
                                    "-o", str(tmp_path / "b.nc")])  # fmt: skip
    assert out.exit_code == 0, out.output
    assert "supercritical by simulation" in out.output
    assert "cycles from the Hopf point 1: 3 orbits" in out.output
    assert (tmp_path / "b.png").stat().st_size > 10_000
