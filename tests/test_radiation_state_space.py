"""Radiation memory as state spaces (seacable.realization, forces.radiation ``method:
state_space``) against the convolution it replaces and against what neither computes: the
fit of a kernel whose realization is known in closed form, the database's damping B(w) from
the fitted systems' transfer functions, a buoy's steady response in regular waves against
its database's RAO, and free decays with every kind of integrator against the convolution."""

import math

import numpy as np
import pytest

import seacable
from seacable import hydrodb, realization
from seacable.case.system import DOF_NAMES
from seacable.forces.contract import StatefulForceModel
from seacable.system import model
from test_hydrodb import ALPHA, BETA, DATA, analytic_db
from test_radiation import A_INF, MASS, SCALE33, STIFFNESS, _case, _database, _excitation, _steady

STEP, MEMORY = 0.05, 25.0
TIMES = np.arange(int(MEMORY / STEP) + 1) * STEP


def _transfer(fit, omega):
    """int_0^inf C e^{A t} B e^{i w t} dt = -C (A + i w)^{-1} B: B(w) + i w (A_inf - A(w))."""
    eye = np.eye(fit.order)
    return np.array([-fit.c @ np.linalg.solve(fit.a + 1j * w * eye, fit.b) for w in omega])


def _released(case, height=0.5):
    """``case`` with its buoy ``height`` [m] above its stiffness's equilibrium (z = 0)."""
    body = case.bodies[0]
    forces = [f.model_copy(update={"equilibrium_position": (0.0, 0.0, 0.0)})
              if f.model == "linear_stiffness" else f for f in body.external_forces]  # fmt: skip
    body = body.model_copy(update={"position": (0.0, 0.0, height), "external_forces": forces})
    return case.model_copy(update={"bodies": [body]})


def _with(case, **radiation):
    """``case`` with its radiation model's fields replaced (and no diffraction when
    ``waves=False``)."""
    waves = radiation.pop("waves", True)
    body = case.bodies[0]
    forces = [f.model_copy(update=radiation) if f.model == "radiation damping" else f
              for f in body.external_forces if waves or f.model != "diffraction"]  # fmt: skip
    update = {"bodies": [body.model_copy(update={"external_forces": forces})]}
    if not waves:
        update["environment"] = case.environment.model_copy(update={"waves": []})
    return case.model_copy(update=update)


def test_an_order_two_kernel_is_fitted_exactly():
    """K(t) = S e^{-alpha t} cos(beta t) is C e^{A t} B of a system of order 2 with poles
    -alpha +- i beta: the fit finds that order, those poles to 1e-6 and K, through the
    transition matrix e^{A dt} (not the fit's own basis), within 1e-6 of S."""
    scale = 2.8e4
    kernel = scale * np.exp(-ALPHA * TIMES) * np.cos(BETA * TIMES)
    fit = realization.fit(TIMES, kernel)
    assert fit.order == 2
    poles = np.sort_complex(np.linalg.eigvals(fit.a))
    np.testing.assert_allclose(poles, [-ALPHA - 1j * BETA, -ALPHA + 1j * BETA], atol=1e-6)
    assert fit.error < 1e-6
    assert np.abs(fit.response(TIMES) - kernel).max() < 1e-6 * scale


def test_the_hemisphere_kernels_and_damping_are_reproduced():
    """Every non-negligible entry of the shipped hemisphere's K (Capytaine, B up to 5 rad/s)
    fitted within the default 1 % (relative L2 over 25 s, through e^{A dt}) with at most 12
    states and poles in the left half-plane (measured: 18 entries, 8 to 10 states each, the
    worst 0.99 %); the transfer functions' real parts give back the database's B(w) below its
    last frequency (where B drops to zero: K rings as sin(w_max t)/t there, for the
    convolution as much) within 1 % of each translation's peak and 2.5 % of each rotation's,
    whose damping is a few millionths of surge's, the panel method's noise (measured: 0.8 %,
    0.8 %, 0.9 %; 1.6 %, 1.6 %, 1.9 %). The entries left out are below 1e-6 of the
    largest."""
    db = hydrodb.read(DATA / "hemisphere_hydrodb.nc")
    kernel = db.retardation(TIMES)
    fits = realization.fit_matrix(TIMES, kernel)
    peaks = np.abs(kernel).max(axis=0)
    assert {(0, 0), (1, 1), (2, 2), (0, 4), (1, 3)} <= set(fits)
    for (i, j), fit in fits.items():
        k = kernel[:, i, j]
        assert np.linalg.norm(fit.response(TIMES) - k) <= 0.01 * np.linalg.norm(k), (i, j)
        assert fit.order <= 12 and np.linalg.eigvals(fit.a).real.max() < 0.0
    left_out = [peaks[i, j] for i in range(6) for j in range(6) if (i, j) not in fits]
    assert max(left_out) < 1e-6 * peaks.max()
    below = db.omega < db.omega[-1]
    for i in range(6):
        damping = db.damping[below, i, i]
        fitted = _transfer(fits[i, i], db.omega[below]).real
        tolerance = 0.01 if i < 3 else 0.025
        assert np.abs(fitted - damping).max() < tolerance * np.abs(damping).max(), i


@pytest.mark.parametrize("omega", [0.6, 1.15, 2.0])
def test_regular_waves_give_the_convolutions_response_and_the_rao(tmp_path, omega):
    """The buoy of tests/test_radiation.py in regular waves, below, at and above resonance:
    its steady heave with state spaces within 1 % of the convolution's and of the database's
    RAO, amplitude and phase (measured: 0.04 %, 0.09 %, 0.02 % from the convolution's; 0.03 %,
    0.10 %, 0.02 % from the RAO)."""
    path = tmp_path / "db.nc"
    db = _database(path)
    case = _case(path, omega)
    a = float(np.interp(omega, db.omega, db.added_mass[:, 2, 2]))
    b = float(np.interp(omega, db.omega, db.damping[:, 2, 2]))
    rao = _excitation(omega) / (STIFFNESS - omega**2 * (MASS + a) - 1j * omega * b)
    fitted = seacable.simulate(_with(case, method="state_space"))
    convolved = seacable.simulate(case)
    assert fitted.complete and convolved.complete
    measured = _steady(fitted, omega) / 0.5
    assert abs(measured / rao - 1.0) < 0.01, (measured, rao)
    assert abs(measured / (_steady(convolved, omega) / 0.5) - 1.0) < 0.01


@pytest.mark.parametrize("integrator", ["rk4", "dopri5", "generalized_alpha", "bdf"])
def test_a_free_decay_follows_the_convolution(tmp_path, integrator):
    """Released 0.5 m above its equilibrium, the buoy's heave with state spaces follows the
    convolution's within 0.1 % of the offset over 20 s (measured 0.022 % with each), with
    each kind of integrator (explicit, adaptive, implicit, SciPy's), and radiation does damp
    it (below 25 % of the offset after 16 s, measured 12.7 %: without it nothing would)."""
    path = tmp_path / "db.nc"
    _database(path)
    case = _case(path, 1.0, integrator=integrator, duration=20.0)
    case = _released(case.model_copy(update={"simulation": case.simulation.model_copy(
        update={"rtol": 1e-8})}))  # fmt: skip
    runs = [seacable.simulate(_with(case, method=m, waves=False))
            for m in ("convolution", "state_space")]  # fmt: skip
    z = [r["bodies/buoy"]["position_z"].values for r in runs]
    assert all(r.complete for r in runs)
    assert np.abs(z[1] - z[0]).max() < 0.001 * 0.5
    late = runs[0]["time"].values > 16.0
    assert np.abs(z[1][late]).max() < 0.25 * 0.5


def test_sundials_runs_a_state_space(tmp_path):
    """A state space keeps no history, so cvode may run it (refused for a convolution): its
    free decay follows dopri5's convolution within 0.2 % of the offset."""
    path = tmp_path / "db.nc"
    _database(path)
    results = {}
    for integrator, method in (("cvode", "state_space"), ("dopri5", "convolution")):
        case = _released(_case(path, 1.0, integrator=integrator, duration=10.0))
        case = _with(case, method=method, waves=False)
        results[integrator] = seacable.simulate(case)["bodies/buoy"]["position_z"].values
    assert np.abs(results["cvode"] - results["dopri5"]).max() < 0.002 * 0.5


def test_the_states_rest_at_rest_and_follow_their_system(tmp_path):
    """StatefulForceModel rule 3: at rest with its states zero the model's rates and force
    vanish (a static start stays at rest); off rest its rates are A x + B nu_j of each entry,
    nu the body-frame velocity, and its force -C x turned into the earth frame."""
    from seacable.forces import radiation
    from seacable.system import kernel

    assert isinstance(radiation, StatefulForceModel)
    path = tmp_path / "db.nc"
    db = analytic_db(np.linspace(0.02, 30.0, 3000))
    hydrodb.write(db, path)
    case = _with(_case(path, 1.0), method="state_space", waves=False)
    body = case.bodies[0].model_copy(update={"dofs": list(DOF_NAMES)})
    built = model.build(case.model_copy(update={"bodies": [body]}))
    p, y = built.params, built.y0.copy()
    w = kernel.make_work(p)
    ydot = np.zeros_like(y)
    kernel.rhs(0.0, y, p, w, ydot)
    assert p.n_s >= 12 and not ydot[p.n_q + p.n_v :].any()
    assert np.abs(w.load[0]).max() == 0.0
    rng = np.random.default_rng(5)
    angles = rng.normal(size=3) * 0.3
    y[p.n_q : p.n_q + 6] = rng.normal(size=6)
    y[p.n_q + p.n_v :] = rng.normal(size=p.n_s)
    y[3:7] = _quaternion(angles)
    kernel.rhs(0.0, y, p, w, ydot)
    rot = w.rot[0]
    nu = np.concatenate([rot.T @ y[p.n_q : p.n_q + 3], rot.T @ y[p.n_q + 3 : p.n_q + 6]])
    force, s = np.zeros(6), p.n_q + p.n_v
    fits = realization.fit_matrix(TIMES, db.retardation(TIMES, 3))  # the case's: tail p = 3
    assert sum(fit.order for fit in fits.values()) == p.n_s
    for (i, j), fit in fits.items():  # in the row's order
        x = y[s : s + fit.order]
        expected_rates = fit.a @ x + fit.b * nu[j]
        np.testing.assert_allclose(ydot[s : s + fit.order], expected_rates, rtol=1e-12,
                                   atol=1e-12 * np.abs(expected_rates).max())  # fmt: skip
        force[i] -= fit.c @ x
        s += fit.order
    expected = np.concatenate([rot @ force[:3], rot @ force[3:]])
    stiffness = np.zeros(6)  # the case's other force model: its linear stiffness
    w2 = kernel.make_work(p)
    y_still = y.copy()
    y_still[p.n_q + p.n_v :] = 0.0
    kernel.rhs(0.0, y_still, p, w2, np.zeros_like(y))
    stiffness[:] = w2.load[0]
    np.testing.assert_allclose(w.load[0] - stiffness, expected, rtol=1e-10,
                               atol=1e-10 * np.abs(expected).max())  # fmt: skip


def _quaternion(angles):
    from seacable.bodies import kinematics

    return np.array(kinematics.euler_quaternion(*(float(a) for a in angles)))


def test_a_poor_fit_is_reported(caplog):
    """An entry whose fit stays above the tolerance with the states allowed is reported with
    its name, its error and the fix; the run still builds."""
    path = DATA / "hemisphere_hydrodb.nc"
    case = _case(path, 1.0)
    with caplog.at_level("WARNING", logger="seacable"):
        built = model.build(_with(case, method="state_space", order=2, waves=False))
    assert "K_33 (Heave on Heave)" in caplog.text and "raise 'order'" in caplog.text
    assert built.params.n_s == 2 * len(realization.fit_matrix(
        TIMES, hydrodb.read(path).retardation(TIMES), 2, 0.01))  # fmt: skip
    assert math.isfinite(built.y0.sum())


def test_the_linearised_heave_has_the_closed_form_modes(tmp_path):
    """The radiation states enter the linearisation (statics.jacobian, seacable modes): the
    buoy's heave with K(t) = S e^{-alpha t} cos(beta t) has the modes lambda of
    lambda^2 (M + A_inf) + lambda S (lambda + alpha) / ((lambda + alpha)^2 + beta^2) + C = 0
    (the Laplace transform of K in the equation of motion): the four roots of that quartic
    are eigenvalues of the linearised system within 0.1 % (measured 0.03 %; its database's B
    is cut at 30 rad/s, and the fit has three states)."""
    from seacable.system import statics

    path = tmp_path / "db.nc"
    _database(path)
    built = model.build(_with(_case(path, 1.0), method="state_space", waves=False))
    eigenvalues = np.linalg.eigvals(statics.jacobian(built, built.y0)[0])
    mass = MASS + A_INF
    quartic = np.polyadd(np.polymul([mass, 0.0, STIFFNESS], [1.0, 2 * ALPHA, ALPHA**2 + BETA**2]),
                         np.polymul([SCALE33, 0.0], [1.0, ALPHA]))  # fmt: skip
    for root in np.roots(quartic):
        assert np.abs(eigenvalues - root).min() < 1e-3 * abs(root), (root, eigenvalues)
