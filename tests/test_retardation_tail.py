"""The damping's high-frequency tail beyond a database's last frequency (seacable.hydrodb's
``tail_power``, ``radiation damping``'s ``high_frequency_tail``): its closed-form cosine
transform against quadrature; analytic dampings whose retardation functions are known in closed
form, cut where they are still large, give kernels and Ogilvie's A_inf closer to the exact ones
with the tail than without; the shipped barge database follows the power the tail assumes, and
its kernel falls below 1 % of its peak within the example's 25 s only with the tail."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

import seacable
from seacable import hydrodb, realization
from seacable.case.forces import RadiationDamping
from seacable.system import hulls

DATA = Path(__file__).parent.parent / "examples" / "data"
RHO, G = 1025.0, 9.81


def _reference(power: int, a: float) -> float:
    """a^(p-1) int_a^inf x^-p cos x dx by scipy's quadrature: adaptive on [a, a + 40], then
    QUADPACK's Fourier integral (QAWF) beyond."""
    near = quad(lambda x: x**-power * math.cos(x), a, a + 40.0, limit=400, epsabs=1e-15,
                epsrel=1e-13)[0]  # fmt: skip
    far = quad(lambda x: x**-power, a + 40.0, np.inf, weight="cos", wvar=1.0, epsabs=1e-15)[0]
    return a ** (power - 1) * (near + far)


@pytest.mark.parametrize("power", [2, 3, 4])
def test_the_tail_transform_against_quadrature(power):
    """F_p(a) = a^(p-1) int_a^inf x^-p cos x dx from the Ci/Si recurrence against quadrature
    within 1e-11 up to a = 72 (w_N T: 1.8 rad/s over 40 s; measured 6e-15, 3e-15 and 5e-12
    for p = 2, 3 and 4, as against mpmath), its limit 1 / (p - 1) at a = 0 and continuity
    towards it; other powers refused."""
    for a in (0.5, 1.0, 3.7, 20.0, 72.0):
        assert float(hydrodb.tail_transform(power, a)) == pytest.approx(
            _reference(power, a), abs=1e-11)  # fmt: skip
    at = hydrodb.tail_transform(power, np.array([0.0, 1e-6]))
    assert at[0] == 1.0 / (power - 1)
    assert at[1] == pytest.approx(at[0], abs=1e-5)
    for other in (1, 5, 2.5):
        with pytest.raises(ValueError, match="2, 3 or 4"):
            hydrodb.tail_transform(other, 1.0)


def _database(omega, damping, added=None):
    """A database of heave only: B(w) and A(w) (zero when not given) at ``omega``."""
    n = len(omega)
    b, a, z = np.zeros((n, 6, 6)), np.zeros((n, 6, 6)), np.zeros((n, 1, 6), complex)
    b[:, 2, 2] = damping
    a[:, 2, 2] = 0.0 if added is None else added
    return hydrodb.HydroDB(omega=omega, added_mass=a, damping=b, directions=np.zeros(1),
                           diffraction=z, froude_krylov=z, reference_point=np.zeros(3))  # fmt: skip


# B(w) (the damping), K(t) = (2/pi) int_0^inf B cos(w t) dw in closed form, B's power at w -> inf
LORENTZ2 = (lambda w: w**2 / (1 + w**2) ** 2, lambda t: 0.5 * (1 - t) * np.exp(-t), 2)
LORENTZ3 = (lambda w: w**2 / (1 + w**2) ** 3, lambda t: (1 + t - t**2) * np.exp(-t) / 8, 4)


@pytest.mark.parametrize(
    ("form", "power", "whole", "late"),
    [
        # measured: none 46.2 % and 1.41 %, the tail 8.3 % and 0.032 %
        (LORENTZ2, 2, (0.10, 0.30), (1e-3, 0.1)),
        # measured: none 8.3 % and 0.77 %, the tail 2.1 % and 0.0062 %
        (LORENTZ3, 3, (0.03, 0.5), (1e-3, 0.01)),
    ],
)
def test_the_tail_brings_a_cut_kernel_closer_to_the_exact_one(form, power, whole, late):
    """B = w^2 / (1 + w^2)^2 (K = (1 - t) e^-t / 2, B ~ w^-2) and w^2 / (1 + w^2)^3
    (K = (1 + t - t^2) e^-t / 8, B ~ w^-4) cut at w_N = 2.5 rad/s, where B is still 48 % and
    11 % of its peak: the error of K over 0-40 s, relative to K's peak, with a power tail
    (p = 2, and the default 3 against a B that falls as w^-4, steeper) against without. The
    whole error (at t = 0 mostly: the area beyond w_N) is below ``whole[0]`` and that much
    below the error without the tail times ``whole[1]``; after 10 s (the ringing
    B(w_N) sin(w_N t) / t) below ``late[0]`` and that without times ``late[1]``."""
    damping, kernel, _ = form
    omega = np.linspace(0.0, 2.5, 4001)  # fine: the rest of the error is the cut alone
    db = _database(omega, damping(omega))
    t = np.linspace(0.0, 40.0, 4001)
    exact = kernel(t)
    peak = np.abs(exact).max()
    error = {p: np.abs(db.retardation(t, p)[:, 2, 2] - exact) / peak for p in (None, power)}
    assert error[power].max() < whole[0]
    assert error[power].max() < whole[1] * error[None].max()
    after = t > 10.0
    assert error[power][after].max() < late[0]
    assert error[power][after].max() < late[1] * error[None][after].max()


def test_the_tail_matches_the_same_damping_tabulated_far_beyond():
    """K with the closed-form tail against K of the same B tabulated (piecewise linear) out
    to 400 rad/s without a tail: equal within 2e-5 of the peak, what the far table's linear
    pieces and its own cut leave (measured 9.7e-6, at t = 0)."""
    damping, _, _ = LORENTZ2
    near = np.linspace(0.0, 2.5, 501)
    far = np.concatenate([near, 2.5 * np.geomspace(1.0, 160.0, 4001)[1:]])
    b_far = damping(2.5) * (2.5 / np.maximum(far, 2.5)) ** 3
    b_far[: len(near)] = damping(near)
    t = np.linspace(0.0, 30.0, 301)
    tail = _database(near, damping(near)).retardation(t, 3)[:, 2, 2]
    tabulated = _database(far, b_far).retardation(t)[:, 2, 2]
    assert np.abs(tail - tabulated).max() < 2e-5 * np.abs(tail).max()


def test_ogilvie_infinite_added_mass_with_the_tail():
    """B = w^2 / (1 + w^2)^2, A(w) = A_inf - (w^2 - 1) / (2 (1 + w^2)^2) cut at 2.5 rad/s:
    Ogilvie's A_inf (K over 60 s) off by 0.0166 without a tail, 0.0016 with p = 2 and 0.0047
    with p = 3 (A(w) - A_inf spans 0.5)."""
    omega = np.linspace(0.01, 2.5, 500)
    infinite = 10.0
    added = infinite - (omega**2 - 1) / (2 * (1 + omega**2) ** 2)
    db = _database(omega, LORENTZ2[0](omega), added)
    t = np.arange(3001) * 0.02
    error = {p: abs(db.ogilvie(t, tail_power=p)[0][2, 2] - infinite) for p in (None, 2, 3)}
    assert error[None] > 0.012
    assert error[2] < 0.003 and error[3] < 0.007


def test_the_barge_database_follows_the_tails_power():
    """The shipped barge (90 x 24 m, draft 6 m; Capytaine, lid at z = 0): no negative
    damping, and above 1.4 rad/s its surge and sway damping within 10 % of the strip law of a
    wall moving horizontally in deep water, 2 rho g^2 (1 - e^-kd)^2 / w^3 per metre of
    waterline (the far wave of a piston of draft d: amplitude 2 (1 - e^-kd) its stroke's),
    whose w^-3 is the default tail's power (measured ratios 0.96-1.09 and 1.00-1.02)."""
    db = hydrodb.read(DATA / "barge_hydrodb.nc")
    diagonal = np.einsum("nii->ni", db.damping)
    assert diagonal.min() >= 0.0
    w = db.omega[db.omega >= 1.4]
    k = w**2 / G
    strip = 2 * RHO * G**2 * (1 - np.exp(-k * 6.0)) ** 2 / w**3  # [N s/m per m]
    for dof, waterline in ((0, 2 * 24.0), (1, 2 * 90.0)):
        ratio = diagonal[db.omega >= 1.4, dof] / (waterline * strip)
        assert np.all(np.abs(ratio - 1.0) < 0.10), (hydrodb.DOFS[dof], ratio)


def test_the_barge_kernel_dies_out_within_the_memory_with_the_tail(caplog):
    """The example's radiation damping (25 s every 0.1 s): |K| at the cut-off is 2.6 % of its
    peak without a tail (reported) and 0.20 % with the default tail (not reported); Ogilvie's
    A_inf, which should not depend on the frequency it is taken at, spreads over the
    frequencies by 14, 13 and 14 % (standard deviation over mean; surge, sway, yaw) without
    the tail and by 2.3, 1.0 and 2.6 % with it."""
    db = hydrodb.read(DATA / "barge_hydrodb.nc")
    t = np.arange(251) * 0.1
    cut = {}
    for p in (None, 3):
        k = db.retardation(t, p)
        cut[p] = np.abs(k[-1]).max() / np.abs(k).max()
        mean, each = db.ogilvie(t, tail_power=p)
        spread = np.array([each[:, i, i].std() / abs(mean[i, i]) for i in (0, 1, 5)])
        assert np.all(spread > 0.10) if p is None else np.all(spread < 0.04), (p, spread)
    assert cut[None] > 0.02 and cut[3] < 0.005
    for tail, reported in (("none", True), ("power", False)):
        spec = RadiationDamping(model="radiation damping", memory=25.0, memory_step=0.1,
                                high_frequency_tail=tail)  # fmt: skip
        caplog.clear()
        with caplog.at_level("WARNING", logger="seacable"):
            hulls.radiation_row(db, spec, "barge.radiation")
        assert ("still" in caplog.text) is reported


def test_the_tail_reaches_the_state_space_fit_and_the_added_mass(monkeypatch):
    """``method: state_space`` fits the kernel with the tail, and a body's A_inf from
    Ogilvie's relation (a database without one) uses the same tail."""
    db = hydrodb.read(DATA / "barge_hydrodb.nc")
    spec = RadiationDamping(model="radiation damping", memory=25.0, memory_step=0.1,
                            method="state_space", tail_power=4)  # fmt: skip
    seen = []
    monkeypatch.setattr(realization, "fit_matrix",
                        lambda t, k, *_: seen.append((t, k)) or {})  # fmt: skip
    hulls.radiation_row(db, spec, "barge.radiation")
    t, kernel = seen[0]
    assert np.array_equal(kernel, db.retardation(t, 4))
    case = seacable.load_case({
        "bodies": [{"name": "barge", "type": "rigid", "position": [0, 0, 0], "mass": 1.3e7,
                    "inertia": [1e9, 7e9, 7e9], "hydrodynamics": {"file": "barge_hydrodb.nc"},
                    "external forces": [{"model": "radiation damping", "memory": 25.0,
                                         "memory_step": 0.1}]}],
        "simulation": {"duration": 1.0, "output_interval": 0.5},
    })  # fmt: skip
    body = case.bodies[0]
    added = hulls.database_added_mass(body, DATA, "barge", case.environment)
    assert np.allclose(added, db.ogilvie(t, tail_power=3)[0], rtol=1e-12)
    assert not np.allclose(added, db.ogilvie(t)[0], rtol=1e-3)
