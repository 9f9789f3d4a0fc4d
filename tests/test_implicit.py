"""Fixed-step implicit schemes (implicit Euler, theta, Newmark, generalized-alpha) on the
lumped-mass cable: the block-tridiagonal solver, convergence orders on an exact solution,
agreement with an adaptive explicit reference on a mooring line, work counters, errors."""

import dataclasses
import math

import numpy as np
import pytest

import seacable
from seacable.errors import CaseError
from seacable.kernels import lumped as lk
from seacable.numerics import implicit
from seacable.simulation import build_system


def test_block_tridiagonal_solve_matches_a_dense_solve():
    rng = np.random.default_rng(3)
    m = 7
    diag = rng.normal(size=(m, 9)) + 6.0 * np.tile(np.eye(3).ravel(), (m, 1))
    upper = rng.normal(size=(m - 1, 9))
    lower = rng.normal(size=(m - 1, 9))
    dense = np.zeros((3 * m, 3 * m))
    for k in range(m):
        dense[3 * k : 3 * k + 3, 3 * k : 3 * k + 3] = diag[k].reshape(3, 3)
        if k < m - 1:
            dense[3 * k : 3 * k + 3, 3 * k + 3 : 3 * k + 6] = upper[k].reshape(3, 3)
            dense[3 * k + 3 : 3 * k + 6, 3 * k : 3 * k + 3] = lower[k].reshape(3, 3)
    b = rng.normal(size=3 * m)
    x = np.empty(3 * m)
    assert implicit.block_tridiagonal_solve(diag.copy(), upper, lower, b, x)
    np.testing.assert_allclose(x, np.linalg.solve(dense, b), rtol=1e-12, atol=1e-12)


def test_star_solve_matches_a_dense_solve():
    """Three chains of four nodes and a hub: a chain's last node couples to the hub (its upper
    and lower blocks), never to the next chain's first node."""
    rng = np.random.default_rng(5)
    chains, chain = 3, 4
    m = chains * chain + 1
    hub = m - 1
    diag = rng.normal(size=(m, 9)) + 6.0 * np.tile(np.eye(3).ravel(), (m, 1))
    upper = rng.normal(size=(m - 1, 9))
    lower = rng.normal(size=(m - 1, 9))
    dense = np.zeros((3 * m, 3 * m))

    def put(r, c, block):
        dense[3 * r : 3 * r + 3, 3 * c : 3 * c + 3] = block.reshape(3, 3)

    for k in range(m):
        put(k, k, diag[k])
    for k in range(m - 1):
        nxt = hub if k % chain == chain - 1 else k + 1
        put(k, nxt, upper[k])
        put(nxt, k, lower[k])
    b = rng.normal(size=3 * m)
    x = np.empty(3 * m)
    assert implicit.block_tridiagonal_solve(diag.copy(), upper, lower, b, x, chain)
    np.testing.assert_allclose(x, np.linalg.solve(dense, b), rtol=1e-12, atol=1e-12)


# A mass on a massless-ish elastic line, hanging in air from a fixed point, released stretched
# 1.5 times its static stretch: z(t) = -L - d - 0.5 d cos(omega t), omega^2 = k / M, never slack.
LENGTH, EA, BODY, LINE = 10.0, 2.0e5, 50.0, 1.0
G = 9.81


def _bouncing_case(**simulation):
    return seacable.load_case(
        {
            "environment": {"in_air": True, "gravity": G},
            "cables": [
                {
                    "model": "lumped_mass",
                    "links": 1,
                    "length": LENGTH,
                    "diameter": 0.01,
                    "mass_per_length": LINE / LENGTH,
                    "axial_stiffness": EA,
                    "top": {"type": "fixed"},
                    "bottom": {"type": "free", "body": {"mass": BODY}},
                    "initial": {"shape": "arc", "top_angle_deg": 0.0},
                }
            ],
            "simulation": {"duration": 1.0, "output_interval": 1.0, **simulation},
        }
    )


def _bouncing_mass():
    case = _bouncing_case()
    system = build_system(case)
    mass = BODY + 0.5 * LINE
    k = EA / LENGTH
    static = mass * G / k
    y0 = system.y0.copy()
    y0[5] = -LENGTH - 1.5 * static  # the end node
    omega = math.sqrt(k / mass)

    def exact(t):
        return -LENGTH - static - 0.5 * static * math.cos(omega * t)

    return dataclasses.replace(system, y0=y0), exact, static


def _run(system, name, dt, duration, **kwargs):
    p = system.params
    y = system.y0.copy()
    w = lk.make_workspace(p.n)
    acc = np.empty(y.size // 2)
    assert implicit.initial_acceleration(0.0, y, p, w, acc) == 0
    work = np.zeros(6, dtype=np.int64)
    steps = int(round(duration / dt))
    states, times = np.empty((1, y.size)), np.empty(1)
    done, status = implicit.newmark_chunk(
        0, y, acc, steps * dt, steps, 1, implicit.scheme(name, **kwargs), 1e-13, 20, p, w, states,
        times, work, implicit.newmark_carry(y, p),
    )  # fmt: skip
    assert (done, status) == (1, 0)
    return y, work


@pytest.mark.parametrize(
    ("name", "kwargs", "order"),
    [
        ("implicit_euler", {}, 1),
        ("theta", {"theta": 0.7}, 1),
        ("theta", {"theta": 0.5}, 2),
        ("newmark", {"gamma": 0.5, "beta": 0.25}, 2),
        ("newmark", {"gamma": 0.6, "beta": 0.3025}, 1),
        ("generalized_alpha", {"spectral_radius": 0.8}, 2),
        ("generalized_alpha", {"spectral_radius": 0.0}, 2),
    ],
)
def test_convergence_order_on_the_exact_bouncing_mass(name, kwargs, order):
    system, exact, static = _bouncing_mass()
    duration = 0.5
    steps = [2e-3, 1e-3, 5e-4]
    errors = [
        abs(_run(system, name, dt, duration, **kwargs)[0][5] - exact(duration)) for dt in steps
    ]
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(rates - order) < 0.15), (errors, rates)
    assert errors[-1] < 0.05 * static


def test_newton_converges_in_few_iterations_and_counts_its_work():
    system, _, _ = _bouncing_mass()
    _, work = _run(system, "generalized_alpha", 1e-3, 0.2)
    accepted, rejected, rhs, failed, jacobians, solves = work
    assert (accepted, rejected, failed) == (200, 0, 0)
    # modified Newton: the lumped model's analytic matrix is built once per step (cheaper than
    # the iterations a stale one would add); a linear spring converges at the first
    # correction, the second confirms it
    assert jacobians == accepted
    assert solves == rhs <= 2 * accepted


def _mooring(integrator, duration=6.0, **simulation):
    case = seacable.load_case("tests/legacy_cases/catenary_mooring_line_surge.yaml")
    sim = case.simulation.model_copy(
        update={"integrator": integrator, "duration": duration, **simulation}
    )
    return seacable.simulate(case.model_copy(update={"simulation": sim})).dataset


def test_implicit_steps_far_beyond_the_explicit_limit_agree_with_dopri5():
    """40-segment chain with part on the seabed, fairlead surging: generalized-alpha at 20 ms
    (six times the rk4 stability limit, omega dt = 2.8) against dopri5 at rtol 1e-6."""
    reference = _mooring("dopri5")
    for integrator, dt in (("generalized_alpha", 0.02), ("newmark", 0.01)):
        ds = _mooring(integrator, time_step=dt)
        tension = np.hypot(ds["top_force_x"], ds["top_force_z"]).values
        expected = np.hypot(reference["top_force_x"], reference["top_force_z"]).values
        assert np.max(np.abs(tension / expected - 1)) < 2e-3, integrator
        attrs = ds.attrs
        assert 0 < attrs["solver_jacobian_evaluations"] <= attrs["solver_linear_solves"]
        assert attrs["solver_rhs_evaluations"] <= 3 * attrs["solver_accepted_steps"]
    # the rk4 warning names the axial waves at that step
    omega, what = seacable.simulation.fastest_frequency(
        build_system(seacable.load_case("tests/legacy_cases/catenary_mooring_line_surge.yaml"))
    )
    assert omega * 0.02 > 6 * 2.8 and "axial" in what


def test_implicit_scheme_needs_a_model_with_a_newton_matrix():
    case = seacable.load_case("tests/legacy_cases/rising_body_four_cables.yaml")  # a star of cables
    sim = case.simulation.model_copy(update={"integrator": "newmark"})
    with pytest.raises(CaseError, match=r"simulation.integrator: 'newmark' needs a model"):
        seacable.simulate(case.model_copy(update={"simulation": sim}))


def test_unstable_newmark_parameters_are_refused():
    case = seacable.load_case("tests/legacy_cases/catenary_mooring_line_surge.yaml")
    data = case.model_dump(mode="json", exclude_unset=True)
    data["simulation"].update(integrator="newmark", newmark_gamma=0.7, newmark_beta=0.25)
    with pytest.raises(CaseError, match=r"newmark_beta \(0.25\) is below"):
        seacable.load_case(data)


def test_a_newton_failure_stops_with_advice_and_keeps_results(tmp_path):
    case = seacable.load_case("tests/legacy_cases/catenary_mooring_line_surge.yaml")
    sim = case.simulation.model_copy(
        update={
            "integrator": "newmark",
            "time_step": 0.05,
            "max_newton_iterations": 1,
            "newton_tolerance": 1e-30,
            "duration": 1.0,
        }  # fmt: skip
    )
    with pytest.raises(seacable.SimulationDiverged, match="Newton iteration did not converge") as e:
        seacable.simulate(case.model_copy(update={"simulation": sim}), output=tmp_path / "r.nc")
    assert "max_newton_iterations" in str(e.value)
    ds = e.value.results.dataset
    assert ds.attrs["status"] == "diverged"
    assert ds.attrs["solver_rejected_steps"] == 7  # retried in 2, 4, ... 64 parts first


@pytest.mark.parametrize("integrator", ["cvode", "bdf", "radau", "lsoda", "dopri5"])
def test_adaptive_integrators_converge_with_their_tolerance(integrator):
    """The bouncing mass released unstretched, z(t) = -L - d (1 - cos omega t): the error at the
    end falls with the tolerance (by 100 or more for 1000 times tighter), and the work is
    counted."""
    mass = BODY + 0.5 * LINE
    k = EA / LENGTH
    static = mass * G / k
    omega = math.sqrt(k / mass)
    errors = []
    for tol in (1e-5, 1e-8):
        case = _bouncing_case(
            output_interval=0.5, integrator=integrator, rtol=tol, atol=tol * 1e-2, max_step=0.05
        )
        ds = seacable.simulate(case).dataset
        exact = -LENGTH - static * (1 - math.cos(omega * 1.0))
        errors.append(abs(ds["node_z"].values[-1, -1] - exact))
        assert ds.attrs["solver_rhs_evaluations"] > 0
    assert errors[1] < 1e-2 * errors[0] or errors[1] < 1e-9, errors
    assert errors[1] < 1e-5 * static


@pytest.mark.parametrize("integrator", ["cvode", "bdf"])
def test_stiff_integrators_run_rigid_link_models_with_a_dense_jacobian(integrator):
    case = seacable.load_case("tests/legacy_cases/thesis_6_1_sim2_submerged_12_links.yaml")
    reference = case.simulation.model_copy(
        update={"integrator": "dopri5", "duration": 2.0, "rtol": 1e-9, "atol": 1e-11}
    )
    expected = seacable.simulate(case.model_copy(update={"simulation": reference})).dataset
    sim = reference.model_copy(update={"integrator": integrator, "rtol": 1e-8, "atol": 1e-10})
    ds = seacable.simulate(case.model_copy(update={"simulation": sim})).dataset
    gap = np.abs(ds["node_x"].values - expected["node_x"].values).max()
    assert gap < 1e-5, gap
    assert ds.attrs["solver_jacobian_evaluations"] > 0


def test_default_generalized_alpha_survives_snapping_slack_segments():
    """The rising body on a stiff line (EA 1e8 N) whose lower segments go slack and snap taut:
    at 5 ms steps the default generalized-alpha keeps the energy bounded and rises like rk4 at
    its stable step (with rho_infinity 0.8 the energy grew 25 times and the body rose twice
    as far)."""
    data = seacable.load_case("tests/legacy_cases/rising_body_single_cable_guided.yaml").model_dump(
        mode="json", exclude_unset=True
    )
    data["cables"][0].update(model="lumped_mass", axial_stiffness=1e8)
    runs = {}
    for integrator, step in (("rk4", 0.0002), ("generalized_alpha", 0.005)):
        data["simulation"].update(duration=2.5, integrator=integrator, time_step=step)
        runs[integrator] = seacable.simulate(seacable.load_case(data)).dataset
    implicit, explicit = runs["generalized_alpha"], runs["rk4"]
    energy = implicit["total_energy"].values
    assert energy.max() <= energy[0] * (1 + 1e-6)  # drag only takes energy out
    rise = explicit["node_z"].values[-1, -1] - explicit["node_z"].values[0, -1]
    assert rise > 5.0
    assert abs(implicit["node_z"].values[-1, -1] - explicit["node_z"].values[-1, -1]) < 0.01 * rise
