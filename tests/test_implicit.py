"""Fixed-step implicit schemes (implicit Euler, theta, Newmark, generalized-alpha) on systems of
bodies and lines: convergence orders on an exact solution, work counters, errors, the adaptive
and stiff integrators on the same exact solution."""

import math

import numpy as np
import pytest

import seacable

# A mass on an elastic tie, hanging in air from a fixed point, released stretched 1.5 times its
# static stretch: z(t) = -L - d - 0.5 d cos(omega t), omega^2 = k / M, never slack.
LENGTH, STIFFNESS, MASS = 10.0, 2.0e4, 50.0
G = 9.81
STATIC = MASS * G / STIFFNESS
OMEGA = math.sqrt(STIFFNESS / MASS)


def _bouncing(stretch=1.5, **simulation):
    """The bouncing mass released at ``stretch`` times its static stretch; its height."""
    case = {
        "name": "bouncing mass",
        "start": "as_given",
        "environment": {"in_air": True, "gravity": G},
        "bodies": [
            {"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0]},
            {"name": "mass", "type": "point", "mass": MASS,
             "position": [0.0, 0.0, -LENGTH - stretch * STATIC],
             "external forces": [{"model": "gravity"}]},
        ],
        "lines": [{"name": "tie", "model": "tie", "from": "top", "to": "mass",
                   "unstretched_length": LENGTH, "stiffness": STIFFNESS}],
        "simulation": {"duration": 1.0, "output_interval": 1.0, **simulation},
    }  # fmt: skip
    ds = seacable.simulate(seacable.load_case(case)).dataset
    return ds["bodies/mass/position_z"].values, ds.attrs


def _exact(t):
    return -LENGTH - STATIC - 0.5 * STATIC * math.cos(OMEGA * t)


@pytest.mark.parametrize(
    ("name", "kwargs", "order"),
    [
        ("implicit_euler", {}, 1),
        ("theta", {"theta": 0.7}, 1),
        ("theta", {"theta": 0.5}, 2),
        ("newmark", {"newmark_gamma": 0.5, "newmark_beta": 0.25}, 2),
        ("newmark", {"newmark_gamma": 0.6, "newmark_beta": 0.3025}, 1),
        ("generalized_alpha", {"spectral_radius": 0.8}, 2),
        ("generalized_alpha", {"spectral_radius": 0.0}, 2),
    ],
)
def test_convergence_order_on_the_exact_bouncing_mass(name, kwargs, order):
    duration = 0.5
    errors = []
    for dt in (2e-3, 1e-3, 5e-4):
        z, _ = _bouncing(integrator=name, time_step=dt, duration=duration,
                         output_interval=duration, newton_tolerance=1e-13, **kwargs)  # fmt: skip
        errors.append(abs(z[-1] - _exact(duration)))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(rates - order) < 0.15), (errors, rates)
    assert errors[-1] < 0.05 * STATIC


def test_newton_converges_in_few_iterations_and_counts_its_work():
    _, attrs = _bouncing(integrator="generalized_alpha", time_step=1e-3, duration=0.2,
                         output_interval=0.2)  # fmt: skip
    assert attrs["solver_accepted_steps"] == 200
    assert attrs["solver_rejected_steps"] == attrs["solver_failed_evaluations"] == 0
    # modified Newton: the matrix (finite differences) is built once and kept; a linear spring
    # converges at the first correction, the second confirms it
    assert attrs["solver_jacobian_evaluations"] == 1
    assert attrs["solver_linear_solves"] <= 2 * 200
    assert attrs["solver_rhs_evaluations"] <= 2 * 200 + 5


MOORING = "examples/catenary_mooring_line_surge.yaml"


def _mooring(**simulation):
    case = seacable.load_case(MOORING)
    sim = case.simulation.model_copy(update=simulation)
    return case.model_copy(update={"simulation": sim})


def test_the_rk4_limit_names_the_axial_waves_an_implicit_step_steps_over():
    """The mooring example's 0.02 s implicit step (tests/test_system_implicit.py) is five times
    beyond rk4's limit, set by the chain's axial waves (a node moves most)."""
    system = seacable.system.model.build(seacable.load_case(MOORING))
    limit = seacable.numerics.stability.rk4_limit(system)
    assert 0.02 > 5 * limit.step and "node" in limit.what and "'chain'" in limit.what


def test_unstable_newmark_parameters_are_refused():
    data = _mooring().model_dump(mode="json", by_alias=True, exclude_unset=True)
    data["simulation"].update(integrator="newmark", newmark_gamma=0.7, newmark_beta=0.25)
    with pytest.raises(seacable.CaseError, match=r"newmark_beta \(0.25\) is below"):
        seacable.load_case(data)


def test_a_newton_failure_stops_with_advice_and_keeps_results(tmp_path):
    case = _mooring(integrator="newmark", time_step=0.05, max_newton_iterations=1,
                    newton_tolerance=1e-30, duration=1.0)  # fmt: skip
    with pytest.raises(seacable.SimulationDiverged, match="Newton iteration did not converge") as e:
        seacable.simulate(case, output=tmp_path / "r.nc")
    assert "max_newton_iterations" in str(e.value)
    ds = e.value.results.dataset
    assert ds.attrs["status"] == "diverged"
    assert ds.attrs["solver_rejected_steps"] == 7  # retried in 2, 4, ... 64 parts first


@pytest.mark.parametrize("integrator", ["cvode", "bdf", "radau", "lsoda", "dopri5"])
def test_adaptive_integrators_converge_with_their_tolerance(integrator):
    """The bouncing mass released unstretched, z(t) = -L - d (1 - cos omega t): the error at the
    end falls with the tolerance (by 100 or more for 1000 times tighter), and the work is
    counted."""
    errors = []
    for tol in (1e-5, 1e-8):
        z, attrs = _bouncing(stretch=0.0, output_interval=0.5, integrator=integrator, rtol=tol,
                             atol=tol * 1e-2, max_step=0.05)  # fmt: skip
        errors.append(abs(z[-1] + LENGTH + STATIC * (1 - math.cos(OMEGA * 1.0))))
        assert attrs["solver_rhs_evaluations"] > 0
    assert errors[1] < 1e-2 * errors[0] or errors[1] < 1e-9, errors
    assert errors[1] < 1e-5 * STATIC


@pytest.mark.parametrize("integrator", ["cvode", "bdf"])
def test_stiff_integrators_run_rigid_link_lines_with_their_jacobian(integrator):
    case = seacable.load_case("examples/thesis_6_1_sim2_submerged_12_links.yaml")
    reference = case.simulation.model_copy(
        update={"integrator": "dopri5", "duration": 2.0, "rtol": 1e-9, "atol": 1e-11}
    )
    expected = seacable.simulate(case.model_copy(update={"simulation": reference})).dataset
    sim = reference.model_copy(update={"integrator": integrator, "rtol": 1e-8, "atol": 1e-10})
    ds = seacable.simulate(case.model_copy(update={"simulation": sim})).dataset
    name = "lines/umbilical/node_x"
    gap = np.abs(ds[name].values - expected[name].values).max()
    assert gap < 1e-5, gap
    assert ds.attrs["solver_jacobian_evaluations"] > 0


def test_default_generalized_alpha_takes_long_steps_on_stiff_lines():
    """The guided rising body on stiff lumped lines (EA 1e8 N), partly on the seabed (its
    contact given: without it the lines would start through the seabed), its float
    between them: at 5 ms steps (25 times rk4's stable step) the default generalized-alpha
    keeps the energy from growing and rises as rk4 does."""
    case = seacable.load_case("examples/rising_body_single_cable_guided.yaml")
    system = case.model_dump(mode="json", by_alias=True, exclude_unset=True)
    system["line_types"][0]["axial_stiffness"] = 1e8
    system["environment"]["seabed"] = {"stiffness": 1e5}  # the lumped lines' contact
    for line in system["lines"]:  # lumped, each at its static shape between its bodies
        line.update(model="lumped_mass")
        del line["initial"]
    body = "bodies/body/position_z"
    runs = {}
    for integrator, step in (("rk4", 0.0002), ("generalized_alpha", 0.005)):
        system["simulation"].update(duration=2.5, integrator=integrator, time_step=step)
        runs[integrator] = seacable.simulate(seacable.load_case(system)).dataset
    implicit, explicit = runs["generalized_alpha"], runs["rk4"]
    energy = implicit["total_energy"].values
    assert energy.max() <= energy[0] * (1 + 1e-6)  # drag only takes energy out
    rise = explicit[body].values[-1] - explicit[body].values[0]
    assert rise > 5.0
    assert abs(implicit[body].values[-1] - explicit[body].values[-1]) < 1e-4 * rise  # 5e-7
