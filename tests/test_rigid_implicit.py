"""Implicit steps for the planar rigid-link cable: the pivoting block solver, the maximal-
coordinate Newton matrix against a dense finite-difference Jacobian of the reduced (link-angle)
residual, agreement with an adaptive reference, convergence orders and Newton's iteration count.
"""

import numpy as np
import pytest

import seacable
from helpers import chain_case, run
from seacable.kernels import chain3d as c3
from seacable.kernels import chain3d_newton as c3n
from seacable.kernels import planar_chain as pc
from seacable.kernels import planar_newton as pn
from seacable.numerics import implicit
from seacable.simulation import build_system


def _dense(diag, upper, lower, bs):
    m = diag.shape[0]
    dense = np.zeros((bs * m, bs * m))
    for k in range(m):
        dense[bs * k : bs * k + bs, bs * k : bs * k + bs] = diag[k].reshape(bs, bs)
        if k < m - 1:
            dense[bs * k : bs * k + bs, bs * k + bs : bs * k + 2 * bs] = upper[k].reshape(bs, bs)
            dense[bs * k + bs : bs * k + 2 * bs, bs * k : bs * k + bs] = lower[k].reshape(bs, bs)
    return dense


def test_pivoting_block_solver_matches_a_dense_solve():
    # saddle-point blocks: zero diagonal entries force row exchanges inside the pivots
    rng = np.random.default_rng(5)
    m, bs = 9, pn.NEWTON_BLOCK
    diag = rng.normal(size=(m, bs * bs))
    diag[:, 0] = 0.0
    diag[:, bs + 1] = 0.0
    upper = rng.normal(size=(m - 1, bs * bs))
    lower = rng.normal(size=(m - 1, bs * bs))
    dense = _dense(diag, upper, lower, bs)
    b = rng.normal(size=bs * m)
    x = np.empty(bs * m)
    factor = np.empty((m - 1, bs * bs))
    piv = np.empty((m, bs), dtype=np.int64)
    work = diag.copy()
    assert implicit.pivoted_factor(work, upper, lower, factor, piv)
    implicit.pivoted_apply(work, lower, factor, piv, b, x)
    np.testing.assert_allclose(x, np.linalg.solve(dense, b), rtol=1e-10, atol=1e-10)


HEAVE_TOP = {
    "type": "floating_structure",
    "position": [0.0, 0.0],
    "mass": 500.0,
    "heave_stiffness": 2000.0,
    "heave_damping": 50.0,
    "force": {"kind": "sine", "amplitude": 300.0, "period": 2.0},
}
BODY = {
    "type": "free",
    "body": {"mass": 5.0, "volume": 0.001, "drag_coefficient": 1.0, "drag_area": 0.02},
    "tie": {"stiffness_x": 30.0, "damping_z": 5.0},
}


def _submerged(n, top, bottom, **simulation):
    # a pinned chain must not start straight (its closure would be singular): start it sagging
    bottom_angle = -40.0 if bottom["type"] == "pinned" else 50.0
    data = chain_case(
        n=n,
        top=top,
        bottom=bottom,
        initial={"shape": "arc", "top_angle_deg": 50.0, "bottom_angle_deg": bottom_angle},
        environment={"water_depth": 100.0, "current": {"velocity": 0.3}},
        simulation={"duration": 2.0, "output_interval": 0.05, **simulation},
        joint_stiffness=20.0,
        joint_damping=0.5,
        drag_coefficient_normal=1.2,
        drag_coefficient_tangential=0.02,
    )
    return data


CASES = {
    "heave top, free body": (HEAVE_TOP, BODY),
    "in air": ({"type": "fixed"}, {"type": "free", "body": {"mass": 5.0}}),
    "moving top, pinned end": (
        {"type": "imposed", "x": {"kind": "sine", "amplitude": 0.5, "period": 3.0}},
        {"type": "pinned"},
    ),
}


def _reduced_state(y0, a, cx, cv, n):
    y = y0.copy()
    y[: n + 1] += cx * a
    y[n + 1 :] += cv * a
    return y


def _dense_newton_step(residual, a, heave_slot, heave):
    """Newton step of the reduced residual with a dense central-difference Jacobian (the heave
    slot pinned to zero when the top does not heave)."""
    size = a.shape[0]
    r0 = residual(a)
    jac = np.empty((size, size))
    for j in range(size):
        e = np.zeros(size)
        e[j] = 1e-6
        jac[:, j] = (residual(a + e) - residual(a - e)) / 2e-6
    if not heave:
        jac[heave_slot, :] = 0.0
        jac[:, heave_slot] = 0.0
        jac[heave_slot, heave_slot] = 1.0
        r0[heave_slot] = 0.0
    return np.linalg.solve(jac, r0)


def _block_newton_step(kernel, state, a, p, w, ydot, cx, cv, t):
    """The Newton step the kernel's block-tridiagonal maximal-coordinate system gives."""
    m, bs = p.n + 1, kernel.NEWTON_BLOCK
    diag = np.empty((m, bs * bs))
    upper = np.empty((m - 1, bs * bs))
    lower = np.empty((m - 1, bs * bs))
    res = np.empty(bs * m)
    status = kernel.newton_system(
        t, state, a, p, w, ydot, 1.0, cx, cv, diag, upper, lower, res, True
    )  # fmt: skip
    assert status == kernel.OK
    factor = np.empty((m - 1, bs * bs))
    piv = np.empty((m, bs), dtype=np.int64)
    da = np.empty(bs * m)
    assert implicit.pivoted_factor(diag, upper, lower, factor, piv)
    implicit.pivoted_apply(diag, lower, factor, piv, res, da)
    corrected = a.copy()
    kernel.newton_correct(p.length, da, corrected)
    return a - corrected


@pytest.mark.parametrize("name", CASES)
def test_newton_step_matches_a_dense_finite_difference_newton_step(name):
    top, bottom = CASES[name]
    data = _submerged(12, top, bottom)
    if name == "in air":
        data["environment"] = {"in_air": True}
    system = build_system(seacable.load_case(data))
    p, n = system.params, system.params.n
    y0 = system.y0.copy()  # the initial arc, set moving
    y0[n + 1 : 2 * n + 1] = 0.2 * np.sin(np.arange(n))  # angular rates [rad/s]
    if top["type"] == "floating_structure":
        y0[2 * n + 1] = 0.1
    w = pc.make_workspace(n)
    ydot = np.empty_like(y0)
    t, h = 0.5, 0.02
    cx, cv = 0.25 * h * h, 0.5 * h
    rng = np.random.default_rng(1)
    pc.rhs(t, y0, p, w, ydot)
    a = ydot[n + 1 :] + rng.normal(scale=0.5, size=n + 1)  # an iterate off the solution
    if top["type"] != "floating_structure":
        a[n] = 0.0

    def residual(acc):
        out = np.empty_like(y0)
        pc.rhs(t, _reduced_state(y0, acc, cx, cv, n), p, w, out)
        return acc - out[n + 1 :]

    dense_step = _dense_newton_step(residual, a, n, top["type"] == "floating_structure")
    step = _block_newton_step(pn, _reduced_state(y0, a, cx, cv, n), a, p, w, ydot, cx, cv, t)
    # exact but for the node velocities and positions in drag, current, ties and the pinned
    # end's Baumgarte terms, which follow the node accelerations by Newmark's rule (terms of
    # relative order h omega dropped): measured 2e-8, 7e-5 and 4e-3 for the three cases
    gap = np.linalg.norm(step - dense_step) / np.linalg.norm(dense_step)
    assert gap < {"in air": 1e-6, "heave top, free body": 1e-3}.get(name, 1e-2), gap


def _end(ds):
    return np.stack([ds["node_x"].values[:, -1], ds["node_z"].values[:, -1]], axis=1)


@pytest.mark.parametrize("name", ["heave top, free body", "moving top, pinned end"])
def test_implicit_runs_agree_with_a_tight_adaptive_reference(name):
    top, bottom = CASES[name]
    ref = run(_submerged(20, top, bottom, integrator="dopri5", rtol=1e-10, atol=1e-10)).dataset
    for scheme in ("newmark", "generalized_alpha"):
        ds = run(_submerged(20, top, bottom, integrator=scheme, time_step=0.005)).dataset
        gap = np.max(np.linalg.norm(_end(ds) - _end(ref), axis=1))
        assert gap < 2e-3, (scheme, gap)  # metres, over a 10 m cable swinging 2 s
        # a good Newton matrix: a handful of iterations per step, few rebuilt matrices
        steps = ds.attrs["solver_accepted_steps"]
        assert ds.attrs["solver_linear_solves"] <= 5 * steps
        assert ds.attrs["solver_jacobian_evaluations"] <= steps


def test_orders_of_implicit_euler_and_newmark_on_the_rigid_chain():
    top, bottom = CASES["heave top, free body"]

    def end_at(scheme, dt):
        data = _submerged(10, top, bottom, integrator=scheme, time_step=dt, duration=1.0)
        data["simulation"]["output_interval"] = 0.5
        data["simulation"]["newton_tolerance"] = 1e-12
        return _end(run(data).dataset)[-1]

    ref = run(
        _submerged(10, top, bottom, integrator="dopri5", rtol=1e-11, atol=1e-11, duration=1.0)
    ).dataset
    exact = _end(ref)[-1]
    for scheme, order in (("implicit_euler", 1.0), ("newmark", 2.0)):
        errors = [np.linalg.norm(end_at(scheme, dt) - exact) for dt in (0.01, 0.005, 0.0025)]
        rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
        assert np.all(rates > order - 0.25), (scheme, errors, rates)


# ---- the 3D chain ---------------------------------------------------------------------------
def _case_3d(n, top, bottom, **simulation):
    data = chain_case(
        n=n,
        top=top,
        bottom=bottom,
        initial={"shape": "arc", "top_angle_deg": 50.0, "bottom_angle_deg": -30.0},
        environment={
            "water_depth": 100.0,
            "current": {"velocity": 0.4, "direction_deg": 30.0},
        },
        simulation={"duration": 2.0, "output_interval": 0.05, **simulation},
        model="rigid_segments_3d",
        joint_stiffness=15.0,
        joint_damping=0.4,
        drag_coefficient_normal=1.2,
        drag_coefficient_tangential=0.02,
        added_mass_coefficient=1.0,
        point_bodies=[{"node": n // 2, "mass": 0.5, "volume": 0.004, "drag_area": 0.03}],
    )
    return data


CASES_3D = {
    "heave top, free body": (
        {**HEAVE_TOP, "position": [0.0, 0.0, 0.0]},
        {
            "type": "free",
            "body": {"mass": 5.0, "volume": 0.001, "drag_coefficient": 1.0, "drag_area": 0.02},
            "tie": {"stiffness_x": 30.0, "stiffness_y": 10.0, "damping_z": 5.0},
        },
    ),
    "moving top, pinned end": (
        {"type": "imposed", "y": {"kind": "sine", "amplitude": 0.5, "period": 3.0}},
        {"type": "pinned"},
    ),
    "guided end": (
        {"type": "fixed"},
        {"type": "free", "body": {"mass": 2.0, "volume": 0.004}, "hold_axes": ["x", "y"]},
    ),
}


@pytest.mark.parametrize("name", CASES_3D)
def test_3d_newton_step_matches_a_dense_finite_difference_newton_step(name):
    top, bottom = CASES_3D[name]
    system = build_system(seacable.load_case(_case_3d(8, top, bottom)))
    p, n = system.params, system.params.n
    y0 = system.y0.copy()
    u0 = 3 * n + 1
    rng = np.random.default_rng(2)
    for i in range(n):  # rates normal to the directors
        e = y0[3 * i : 3 * i + 3]
        r = rng.normal(scale=0.2, size=3)
        y0[u0 + 3 * i : u0 + 3 * i + 3] = r - (r @ e) * e
    heave = top["type"] == "floating_structure"
    if heave:
        y0[6 * n + 1] = 0.1
    w = c3.make_workspace(n)
    ydot = np.empty_like(y0)
    t, h = 0.5, 0.02
    cx, cv = 0.25 * h * h, 0.5 * h
    nq = 3 * n + 1
    assert c3.rhs(t, y0, p, w, ydot) == c3.OK
    a = ydot[nq : 2 * nq] + rng.normal(scale=0.5, size=nq)
    if not heave:
        a[3 * n] = 0.0

    def state(acc):
        y = y0.copy()
        y[:nq] += cx * acc
        y[nq : 2 * nq] += cv * acc
        return y

    def residual(acc):
        out = np.empty_like(y0)
        c3.rhs(t, state(acc), p, w, out)
        return acc - out[nq : 2 * nq]

    dense_step = _dense_newton_step(residual, a, 3 * n, heave)
    step = _block_newton_step(c3n, state(a), a, p, w, ydot, cx, cv, t)
    gap = np.linalg.norm(step - dense_step) / np.linalg.norm(dense_step)
    assert gap < 5e-3, gap  # measured 3e-4, 1.4e-3 and 3e-4


@pytest.mark.parametrize("name", CASES_3D)
def test_3d_implicit_runs_agree_with_a_tight_adaptive_reference(name):
    top, bottom = CASES_3D[name]
    ref = run(_case_3d(12, top, bottom, integrator="dopri5", rtol=1e-10, atol=1e-10)).dataset

    def end(ds):
        return np.stack([ds[f"node_{a}"].values[:, -1] for a in "xyz"], axis=1)

    for scheme in ("newmark", "generalized_alpha"):
        ds = run(_case_3d(12, top, bottom, integrator=scheme, time_step=0.005)).dataset
        gap = np.max(np.linalg.norm(end(ds) - end(ref), axis=1))
        assert gap < 3e-3, (scheme, gap)
        steps = ds.attrs["solver_accepted_steps"]
        assert ds.attrs["solver_linear_solves"] <= 5 * steps
        assert ds.attrs["solver_jacobian_evaluations"] <= steps


def test_servo_end_is_refused_by_the_implicit_schemes():
    case = seacable.load_case("tests/legacy_cases/jacquot_marichal_trajectory_servo.yaml")
    sim = case.simulation.model_copy(update={"integrator": "newmark"})
    with pytest.raises(seacable.CaseError, match="servo"):
        seacable.simulate(case.model_copy(update={"simulation": sim}))
