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
from seacable.stability import cycles, equilibria
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
    run, end, yaw = _dopri5(case, x0, found.parameter[k], period, 100)
    assert np.abs(end - x0[:2]).max() < 1e-2
    assert abs(math.remainder(yaw - x0[2], 2 * math.pi)) < 1e-4
    swing = np.ptp(np.asarray(run["bodies/shuttle/position_y"]))
    assert swing == pytest.approx(found.amplitude[k][1], rel=1e-3)


def _dopri5(case, x0: np.ndarray, thrust: float, duration: float, rows: int):
    """The shuttle's motion from the state ``x0`` at ``thrust`` [N] under the system's own
    dopri5: the run, and its last place (x, y) and heading [rad]."""
    data = case.model_dump(by_alias=True, exclude_none=True)
    ship = next(b for b in data["bodies"] if b["name"] == "shuttle")
    ship.update(position=[x0[0], x0[1], 0.0], orientation_deg=[0.0, 0.0, math.degrees(x0[2])],
                velocity=[x0[3], x0[4], 0.0], angular_velocity=[0.0, 0.0, x0[5]])  # fmt: skip
    ship["external forces"][1]["force_x"] = {"kind": "constant", "value": thrust}
    data["simulation"] = {"duration": duration, "output_interval": duration / rows,
                          "integrator": "dopri5", "rtol": 1e-10}  # fmt: skip
    run = seacable.simulate(seacable.load_case(data))
    end = np.array([float(np.asarray(run[f"bodies/shuttle/{name}"])[-1])
                    for name in ("position_x", "position_y")])  # fmt: skip
    return run, end, math.radians(float(np.asarray(run["bodies/shuttle/yaw"])[-1]))


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


@SLOW  # seven segments of a 4,000 s orbit, four orbits: about 70 s of one core
def test_cycles_from_a_hopf_point_on_an_unstable_equilibrium_by_multiple_shooting():
    """The shuttle's reversed equilibrium (stern to the hawser) is divergent (a real
    eigenvalue of +0.0033 1/s); at about 67.5 kN of astern thrust a slow pair (period about
    3,900 s) crosses too. Over one period a disturbance grows by exp(13): single shooting's
    Newton diverges. Seven segments (``cycles.segments``) each grow by exp(2) at most, and
    the branch starts: its period tends to 2 pi / omega as the amplitude vanishes, its
    amplitude grows in proportion to the distance from the Hopf point (the |v| v terms), its
    cycles lie where the crossing pair is unstable (supercritical, judged by the branch: no
    simulation can settle beside a divergent equilibrium), each has the multiplier
    exp(lambda T) of the divergent direction and one at 1, and each segment run by the
    system's own dopri5 lands on the next one's start."""
    plane = Plane.of(shuttle_case("short-wing"))
    par = parameter(plane, THRUST)
    par.set(plane, -2e5)
    [reversed_] = [e for e in equilibria.find(plane, None, 12) if not e.stable]
    branch = Continuation(plane, par).run(reversed_.x, -2e5, 0.0)
    [hopf] = [s for s in branch.special if s.kind == "hopf"]
    assert hopf.parameter == pytest.approx(-67538.0, abs=5.0)
    par.set(plane, hopf.parameter)
    lam = np.linalg.eigvals(plane.jacobian(np.concatenate([hopf.x, np.zeros(3)])))
    period = 2 * math.pi / hopf.frequency
    assert cycles.segments(lam, period) == 7
    found, kind = cycles.from_hopf(plane, par, hopf.x, hopf.parameter, hopf.frequency,
                                   (-2e5, 0.0), 4, 1000.0)  # fmt: skip
    assert len(found.parameter) == 4
    assert kind.kind == "supercritical" and kind.by == "branch"
    distance = np.array(found.parameter) - hopf.parameter
    sway = np.array([a[1] for a in found.amplitude])
    assert np.all(distance > 0.0) and np.ptp(sway / distance) < 0.15 * (sway / distance).max()
    # the period, linear in the amplitude here, extrapolated to none: 2 pi / omega
    slope, zero = np.polyfit(sway, found.period, 1)
    assert zero == pytest.approx(period, rel=1e-3)
    growth = math.exp(float(lam.real.max()) * found.period[0])
    assert not any(found.stable)
    multipliers = np.sort(np.abs(found.multipliers[0]))
    assert multipliers[-1] == pytest.approx(growth, rel=0.1)
    assert np.min(np.abs(found.multipliers[0] - 1.0)) < 1e-3
    # the first orbit's segments under the system's dopri5
    starts = found.starts[0]
    case = shuttle_case("short-wing")
    for i in (0, 3):
        x0, x1 = starts[i], starts[(i + 1) % len(starts)]
        _, end, yaw = _dopri5(case, x0, found.parameter[0], found.period[0] / len(starts), 10)
        assert np.abs(end - x1[:2]).max() < 1e-2
        assert abs(math.remainder(yaw - x1[2], 2 * math.pi)) < 1e-4


def test_a_motion_that_has_not_settled_gives_no_verdict():
    """Near a Hopf point the motion settles slowly (its multiplier near 1): cut off after 30
    periods, the runs are still growing, and the criticality says "undecided" rather than
    take an unsettled amplitude for a settled one (which made a subcritical point of the
    shuttle in wind read supercritical)."""
    plane = Plane.of(shuttle_case("short-wing"))
    par = parameter(plane, THRUST)
    branch = Continuation(plane, par).run(np.array([-240.0, 0.0, 0.0]), -2e5, 0.0)
    hopf = next(s for s in branch.special if s.kind == "hopf")
    par.set(plane, hopf.parameter)
    state = np.concatenate([hopf.x, np.zeros(3)])
    lam, vectors = np.linalg.eig(plane.jacobian(state))
    k = int(np.argmin(np.abs(lam.real) + np.abs(np.abs(lam.imag) - hopf.frequency)))
    period = 2 * math.pi / hopf.frequency
    vector = vectors[:, k]
    par.set(plane, hopf.parameter + 1000.0)  # fishtailing, slowly growing
    scale = cycles.orbits._scales(plane)
    push = vector.real / np.abs(vector.real / scale).max() * 0.1
    per = max(400, cycles.orbits._steps(plane, state, period) // 5)
    amplitude, _, settled = cycles._settled(plane, state + push, period, per, 30)
    assert not settled and 0.0 < amplitude < 1.0  # still growing towards its cycle (> 1)
    kind = cycles.criticality(plane, par, state, hopf.parameter, vector, period, 1000.0,
                              most=30)  # fmt: skip
    assert kind.kind == "undecided" and kind.by == "simulation"
