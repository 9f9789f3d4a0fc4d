"""Integrators: convergence order on a problem with a known solution, work budgets, agreement."""

import numpy as np
import pytest

import seacable
from golden.record import system_rows
from helpers import chain_case, run_rows, upgraded

M_TOP, K_TOP, N_LINKS, BODY = 50.0, 800.0, 8, 5.0


def _heave_case(simulation):
    """A straight hanging chain under a heaving structure stays vertical: the whole system is a
    mass-spring with z(t) = z_eq + (z0 - z_eq) cos(omega t)."""
    return chain_case(
        n=N_LINKS,
        top={
            "type": "floating_structure",
            "mass": M_TOP,
            "heave_stiffness": K_TOP,
            "initial_heave": 0.3,
        },  # fmt: skip
        bottom={"type": "free", "body": {"mass": BODY}},
        simulation=simulation,
    )


def _run(data) -> tuple[dict, dict]:
    """The upgraded case's rows (single-cable names) and the results' attributes."""
    case = upgraded(data)
    results = seacable.simulate(case)
    return system_rows(results.dataset, case), results.dataset.attrs


def _heave_exact(t):
    total = M_TOP + 10.0 + BODY
    z_eq = -(10.0 + BODY) * 9.81 / K_TOP  # the structure's weight equals its buoyancy
    return z_eq + (0.3 - z_eq) * np.cos(np.sqrt(K_TOP / total) * t)


def test_heave_solution_is_exact_shape():
    res = run_rows(_heave_case({"duration": 2.0, "output_interval": 0.1, "time_step": 0.001}))
    np.testing.assert_allclose(res["top_heave"], _heave_exact(res["time"]), atol=1e-9)
    assert np.max(np.abs(res["angle"])) < 1e-12


def test_rk4_converges_at_fourth_order():
    errors = []
    for dt in (0.04, 0.02, 0.01):
        res = run_rows(_heave_case({"duration": 2.0, "output_interval": 0.4, "time_step": dt}))
        errors.append(np.max(np.abs(res["top_heave"] - _heave_exact(res["time"]))))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 4.0) < 0.3), (errors, orders)


def test_rk4_work_budget_is_four_evaluations_per_step():
    _, attrs = _run(_heave_case({"duration": 1.0, "output_interval": 0.1, "time_step": 0.01}))
    assert attrs["solver_accepted_steps"] == 100
    assert attrs["solver_rhs_evaluations"] == 400
    assert attrs["solver_rejected_steps"] == 0


@pytest.mark.parametrize("rtol", [1e-5, 1e-7, 1e-9])
def test_dopri5_error_follows_tolerance(rtol):
    sim = {"duration": 2.0, "output_interval": 0.1, "integrator": "dopri5", "rtol": rtol,
           "atol": rtol * 1e-2}  # fmt: skip
    res, attrs = _run(_heave_case(sim))
    error = np.max(np.abs(res["top_heave"] - _heave_exact(res["time"])))
    assert error < 50 * rtol, error
    assert attrs["solver_rhs_evaluations"] >= 6 * attrs["solver_accepted_steps"]


def test_dopri5_is_fifth_order_in_its_step():
    """Error against the exact solution shrinks like tolerance^(5/5): 100x tighter -> ~100x."""
    errors = []
    for rtol in (1e-6, 1e-8):
        sim = {"duration": 2.0, "output_interval": 0.1, "integrator": "dopri5", "rtol": rtol,
               "atol": rtol * 1e-2}  # fmt: skip
        res = run_rows(_heave_case(sim))
        errors.append(np.max(np.abs(res["top_heave"] - _heave_exact(res["time"]))))
    assert 10 < errors[0] / errors[1] < 1000, errors


def test_rk4_and_dopri5_agree_on_a_swinging_submerged_chain():
    common = dict(n=25, environment={"water_density": 1025.0}, joint_stiffness=2.0,
                  joint_damping=0.1, initial={"shape": "arc", "top_angle_deg": 50.0},
                  bottom={"type": "free", "body": {"mass": 2.0, "volume": 0.0005}})  # fmt: skip
    a = run_rows(chain_case(simulation={"duration": 3.0, "output_interval": 0.1, "time_step": 5e-4},
                       **common))  # fmt: skip
    b = run_rows(chain_case(simulation={"duration": 3.0, "output_interval": 0.1,
                                   "integrator": "dopri5", "rtol": 1e-9, "atol": 1e-11},
                       **common))  # fmt: skip
    np.testing.assert_allclose(a["node_x"], b["node_x"], atol=1e-6)
    np.testing.assert_allclose(a["tension"], b["tension"], rtol=1e-5, atol=1e-4)
