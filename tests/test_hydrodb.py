"""Hydrodynamic databases (seacable.hydrodb): retardation functions and Ogilvie's relations
against an analytic kernel whose transforms are known in closed form, a database moved to
another reference point, and Capytaine's NetCDF read back."""

import math
from pathlib import Path

import numpy as np
import pytest

from seacable import hydrodb

ALPHA, BETA = 0.4, 1.1  # K(t) = e^{-alpha t} cos(beta t) times a matrix
SCALE = np.diag([1.0, 2.0, 3.0e3, 4.0e4, 5.0e4, 6.0e4]) * 1e3
DATA = Path(__file__).parent.parent / "examples" / "data"


def _kernel(t):
    return np.exp(-ALPHA * t) * np.cos(BETA * t)


def _damping(w):
    """B(w) = int_0^inf K(t) cos(w t) dt."""
    return 0.5 * (ALPHA / (ALPHA**2 + (w - BETA) ** 2) + ALPHA / (ALPHA**2 + (w + BETA) ** 2))


def _added(w):
    """A(w) - A_inf = -(1/w) int_0^inf K(t) sin(w t) dt (its limit at w = 0)."""
    w = np.asarray(w, dtype=float)
    s = 0.5 * (
        (w - BETA) / (ALPHA**2 + (w - BETA) ** 2) + (w + BETA) / (ALPHA**2 + (w + BETA) ** 2)
    )
    limit = -(ALPHA**2 - BETA**2) / (ALPHA**2 + BETA**2) ** 2
    return np.where(w == 0.0, limit, -s / np.where(w == 0.0, 1.0, w))


def analytic_db(omega=None, infinite=None):
    """A database whose K, B and A are the analytic kernel's, times SCALE."""
    omega = np.linspace(0.02, 30.0, 3000) if omega is None else omega
    infinite = np.diag([1e4, 2e4, 5e6, 1e7, 3e8, 2e8]) if infinite is None else infinite
    n = len(omega)
    zeros = np.zeros((n, 1, 6), complex)
    return hydrodb.HydroDB(
        omega=omega, added_mass=infinite + _added(omega)[:, None, None] * SCALE,
        damping=_damping(omega)[:, None, None] * SCALE, directions=np.zeros(1),
        diffraction=zeros, froude_krylov=zeros, reference_point=np.zeros(3),
    )  # fmt: skip


def _tail(w):
    """int_w^inf B: the part of the damping a database cut at w leaves out."""
    return 0.5 * (math.pi - math.atan((w - BETA) / ALPHA) - math.atan((w + BETA) / ALPHA))


def test_retardation_against_the_analytic_kernel():
    """K(t) from B(w), the exact cosine transform of B piecewise linear on the database's
    frequencies, against e^{-alpha t} cos(beta t): within 15 % above the bound the frequencies
    cut off above 30 rad/s leave, (2/pi) int_30^inf B (B decays only as 1/w^2 here: 0.93 % of
    the peak); and against a quadrature of the same piecewise-linear B to 1e-9."""
    from scipy.integrate import quad

    db = analytic_db(np.linspace(0.0, 30.0, 3001))  # from 0: this B is not zero there
    t = np.linspace(0.0, 40.0, 801)
    k = db.retardation(t)
    expected = _kernel(t)[:, None, None] * SCALE
    bound = 2 / math.pi * _tail(db.omega[-1])  # 0.93 % of the peak
    error = np.abs(k - expected).max(axis=0) / np.abs(SCALE).max()
    assert error.max() <= 1.15 * bound  # the rest: B taken linear between frequencies
    coarse = analytic_db(np.linspace(0.1, 5.0, 12))
    grid = np.concatenate([[0.0], coarse.omega])
    values = np.concatenate([[0.0], coarse.damping[:, 2, 2]])
    for time in (0.0, 0.7, 3.0, 25.0):
        exact = quad(lambda w, time=time: np.interp(w, grid, values) * math.cos(w * time), 0.0,
                     grid[-1], points=grid[1:-1], limit=200, epsabs=0, epsrel=1e-12)[0]  # fmt: skip
        assert coarse.retardation(np.array([time]))[0, 2, 2] == pytest.approx(
            2 / math.pi * exact, rel=1e-9, abs=1e-9 * SCALE[2, 2])  # fmt: skip


def test_ogilvie_gives_back_the_added_mass_and_its_infinite_limit():
    """A_inf from Ogilvie's relation (K over 60 s, averaged over the frequencies) within 0.5 %
    of the kernel's scale (measured 0.41 %), and A(w) rebuilt from K within 1.2 % above
    0.5 rad/s and 0.4 % above 1 rad/s (measured 1.04 % and 0.29 %): what limits both is B cut
    at 30 rad/s, whose Lorentzian tail falls only as 1/w^2."""
    infinite = np.diag([1e4, 2e4, 5e6, 1e7, 3e8, 2e8])
    db = analytic_db(infinite=infinite)
    t = np.linspace(0.0, 60.0, 6001)
    estimate, _ = db.ogilvie(t)
    scale = np.abs(SCALE).max()
    assert np.abs(estimate - infinite).max() < 5e-3 * scale
    rebuilt = db.added_mass_from_kernel(t, infinite)
    for lowest, tolerance in ((0.5, 1.2e-2), (1.0, 4e-3)):
        at = db.omega >= lowest
        assert np.abs(rebuilt[at] - db.added_mass[at]).max() < tolerance * scale


def test_a_database_moved_keeps_energy_and_work():
    """Moved to another point: 1/2 nu^T A nu and the power F . nu are unchanged for motions
    described at either point."""
    rng = np.random.default_rng(0)
    db = analytic_db(np.linspace(0.5, 2.0, 4))
    forces = rng.normal(size=(4, 1, 6)) + 1j * rng.normal(size=(4, 1, 6))
    db = hydrodb.HydroDB(**{**db.__dict__, "diffraction": forces,
                            "reference_point": np.array([1.0, 0.5, -2.0])})  # fmt: skip
    point = np.array([-3.0, 0.2, 1.0])
    moved = db.moved(point)
    r = db.reference_point - point
    for _ in range(5):
        v, w = rng.normal(size=3), rng.normal(size=3)
        at_new = np.concatenate([v, w])
        at_old = np.concatenate([v + np.cross(w, r), w])
        for k in range(4):
            assert at_old @ db.added_mass[k] @ at_old == pytest.approx(
                at_new @ moved.added_mass[k] @ at_new, rel=1e-12)  # fmt: skip
            assert db.diffraction[k, 0] @ at_old == pytest.approx(
                moved.diffraction[k, 0] @ at_new, rel=1e-12)  # fmt: skip


def test_the_excitations_phase_moved_to_another_point():
    """X refers to the wave's phase at the database's origin; phase_moved(P, k) to its phase
    at P: the same wave gives the same force, Re(X a e^{i p_O}) = Re(X_P a e^{i p_P}) with
    p_P = p_O + k (x_P cos b + y_P sin b), at every frequency and direction; the matrices
    stay. A body's reference point away from the database's origin needs it
    (tests/test_rao_barge.py)."""
    db = hydrodb.read(DATA / "barge_hydrodb.nc")
    point = np.array([20.0, -7.0, -6.0])
    k = db.omega**2 / db.gravity
    moved = db.phase_moved(point, k)
    shift = k[:, None] * (point[0] * np.cos(db.directions) + point[1] * np.sin(db.directions))
    for p_origin in (0.0, 1.3, -2.9):
        for part in ("diffraction", "froude_krylov"):
            at_origin = getattr(db, part) * np.exp(1j * p_origin)
            at_point = getattr(moved, part) * np.exp(1j * (p_origin + shift))[:, :, None]
            assert np.allclose(at_point.real, at_origin.real, rtol=0.0,
                               atol=1e-12 * np.abs(at_origin).max())  # fmt: skip
    assert moved.added_mass is db.added_mass and moved.damping is db.damping


def test_capytaine_output_is_read():
    """The example's database (a hemisphere of radius 2.5 m, computed with Capytaine through
    seacable.bem): six degrees of freedom in order, symmetric matrices, a heave damping that
    vanishes at both ends of the frequency range."""
    db = hydrodb.read(DATA / "hemisphere_hydrodb.nc")
    assert db.added_mass.shape == (len(db.omega), 6, 6)
    # symmetric to the panel method's accuracy (its small couplings of a symmetric body)
    asymmetry = np.abs(db.added_mass - np.swapaxes(db.added_mass, 1, 2)).max()
    assert asymmetry < 1e-3 * np.abs(db.added_mass).max()
    heave = db.damping[:, 2, 2]
    assert heave.max() > 10 * max(heave[0], heave[-1])
    assert np.all(np.diff(db.omega) > 0)
    assert db.diffraction.shape == (len(db.omega), len(db.directions), 6)
    assert math.isfinite(db.rho) and db.rho > 0
