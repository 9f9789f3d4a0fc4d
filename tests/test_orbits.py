"""A limit cycle is found, or refused with its reason, wherever the shuttle's astern thrust
puts it (issue 43): near the Hopf point, where the cycle takes months of simulated time to
settle; where the motion never settles on one period; where Newton's step would throw the
ships out of any motion."""

import math

import numpy as np
import pytest

import seacable
from seacable.errors import CaseError
from seacable.stability import orbits
from seacable.stability.api import weather_of
from seacable.stability.plane import Plane
from test_stability import _simulate_from, shuttle_case


@pytest.fixture(scope="module")
def fishtailing():
    """The shuttle without astern thrust, its plane in the case's current, and its cycle."""
    case = shuttle_case("short-wing", thrust=0.0)
    plane = Plane.of(case)
    weather_of(plane.built.case).apply(plane.built)
    return plane, seacable.periodic_orbit(case)


def _ship_state(cycle, k: int) -> np.ndarray:
    """The plane state of the cycle's one ship at its track's row ``k``, velocities by central
    differences along the track."""
    dt = float(cycle["time"][1] - cycle["time"][0])
    x, y = cycle["x"].values[:, 0], cycle["y"].values[:, 0]
    psi = np.unwrap(np.radians(cycle["heading"].values[:, 0]))
    rates = [(v[k + 1] - v[k - 1]) / (2 * dt) for v in (x, y, psi)]
    return np.array([x[k], y[k], psi[k], *rates])


@pytest.mark.slow  # 13 s: make test-all runs it
def test_a_cycle_near_its_hopf_point_is_found_and_is_the_systems_own_motion():
    """At 111 kN astern the equilibrium's oscillation grows at 5.4e-6 1/s (an e-folding every
    two days): 30 periods of motion (the former default) were far too short. The cycle is
    found, and the system's own time simulation (dopri5, another integrator) started on it
    comes back to the same place after one period."""
    case = shuttle_case("short-wing", thrust=111_000.0)
    cycle = seacable.periodic_orbit(case)
    assert bool(cycle["converged"]) and float(cycle["residual"]) < 1e-9
    assert 5.0 < float(cycle["amplitude_y"][0]) < 50.0  # a cycle, not the equilibrium
    period = float(cycle["period"])
    start = _ship_state(cycle, 1)
    plane = Plane.of(case)
    ship = _simulate_from(case, plane, start, period, period / 4)
    back = np.array([float(ship["position_x"][-1]), float(ship["position_y"][-1])])
    assert back == pytest.approx(start[:2], abs=0.02)  # 2 cm on a cycle of 20 m
    quarter = np.array([float(ship["position_y"][2]), float(ship["position_y"][1])])
    assert np.ptp(quarter) > 1.0  # it moved in between


def test_a_motion_that_never_settles_on_one_period_is_refused_with_what_it_did():
    """At 50 kN astern the shuttle swings on an irregular oscillation (the times between its
    swings wander by 6 %): there is no limit cycle to report, and the refusal says so."""
    with pytest.raises(CaseError, match="irregular oscillation, no single periodic orbit"):
        seacable.periodic_orbit(shuttle_case("short-wing", thrust=50_000.0))


@pytest.mark.slow  # its cycle costs 5 s; make test-all
def test_shooting_from_a_bad_guess_damps_its_newton_steps(fishtailing):
    """Started on the cycle with half its period, shooting (undamped, it went to a period of
    -36.6 s or raised FloatingPointError from such guesses) never returns a negative period or
    raises: it converges or says why not."""
    plane, cycle = fishtailing
    guess = _ship_state(cycle, 200)
    orbit = orbits.shoot(plane, guess, 0.5 * float(cycle["period"]), iterations=5)
    assert orbit.period > 0.0 and math.isfinite(orbit.residual)
    assert orbit.converged or orbit.message
    if orbit.converged:  # on a cycle of the system: the one found, or another
        assert orbit.residual < 1e-8


@pytest.mark.slow  # its cycle costs 5 s; make test-all
def test_settle_tells_rest_from_a_cycle(fishtailing):
    """Below the Hopf point (120 kN astern) the equilibrium is stable: a push dies out and
    ``settle`` says "rest" or a vanishing amplitude; above it (the cycle at 0 kN) the amplitude
    settles on the cycle's."""
    plane, cycle = fishtailing
    period = float(cycle["period"])
    went = orbits.settle(plane, _ship_state(cycle, 5), period, 2400, 60 * period)
    assert went.status == "cycle" and went.period == pytest.approx(period, rel=1e-4)
    plane = Plane.of(shuttle_case("short-wing", thrust=120_000.0))
    weather_of(plane.built.case).apply(plane.built)
    rest = seacable.equilibria(shuttle_case("short-wing", thrust=120_000.0))
    stable = int(np.flatnonzero(rest["stable"].values)[0])
    x = np.array([float(rest["x"][stable, 0]), float(rest["y"][stable, 0]),
                  math.radians(float(rest["heading"][stable, 0])), 0.0, 0.0, 0.0])  # fmt: skip
    went = orbits.settle(plane, x + np.array([0.0, 1.0, 0.01, 0, 0, 0]), 2000.0, 400, 4e5)
    assert went.status == "rest" or (went.status == "cycle" and went.amplitude < 1e-2)
