"""Incident waves (kernels.waves, seastate) against linear wave theory: the dispersion
relation, the field equations and boundary conditions of Airy waves at finite and infinite
depth, the stretching under a crest, and the spectra's significant height, peak and
spreading."""

import math

import numpy as np
import pytest

from seacable import seastate
from seacable.case.environment import Environment
from seacable.kernels import waves

G, RHO = 9.81, 1025.0


def _rows(depth, *components):
    """Rows of (amplitude, period, direction [rad], phase) components."""
    out = []
    for amplitude, period, direction, phase in components:
        omega = 2 * math.pi / period
        k = seastate.wave_number(np.array([omega]), depth, G)[0]
        out.append([amplitude, omega, k, math.cos(direction), math.sin(direction), phase, 0.0])
    return waves.table(out, depth)


def test_dispersion_relation():
    omega = np.linspace(0.05, 4.0, 50)
    for depth in (2.0, 30.0, 400.0):
        k = seastate.wave_number(omega, depth, G)
        assert G * k * np.tanh(k * depth) == pytest.approx(omega**2, rel=1e-13)
    assert seastate.wave_number(omega, waves.DEEP, G) == pytest.approx(omega**2 / G)


@pytest.mark.parametrize("depth", [25.0, waves.DEEP])
def test_airy_waves_satisfy_linear_theory(depth):
    """Two crossing components (below the surface, unstretched): the velocity field is
    divergence-free, the acceleration is the velocity's time derivative, the surface rises at
    the vertical velocity there, the bottom is impermeable (stretched or not), and the
    pressure is -rho dphi/dt (checked as its gradient: grad p = -rho du/dt)."""
    rows = _rows(depth, (1.2, 9.0, 0.3, 0.4), (0.5, 6.0, -1.0, 2.0))
    h = 1e-4
    rng = np.random.default_rng(0)
    crests = 0
    for _ in range(20):
        x, y, t = rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(0, 30)
        z = -rng.uniform(2.0, 20.0)

        def vel(xx, yy, zz, tt):
            return np.array(waves.field(rows, tt, xx, yy, zz, depth, waves.VERTICAL)[0:3])

        _, _, _, ax, ay, az = waves.field(rows, t, x, y, z, depth, waves.VERTICAL)
        divergence = ((vel(x + h, y, z, t) - vel(x - h, y, z, t))[0]
                      + (vel(x, y + h, z, t) - vel(x, y - h, z, t))[1]
                      + (vel(x, y, z + h, t) - vel(x, y, z - h, t))[2]) / (2 * h)  # fmt: skip
        speed = np.abs(vel(x, y, z, t)).max()
        assert abs(divergence) < 1e-6 * speed
        dudt = (vel(x, y, z, t + h) - vel(x, y, z, t - h)) / (2 * h)
        assert (ax, ay, az) == pytest.approx(dudt, rel=1e-6, abs=1e-8)
        grad = np.array([
            waves.pressure_at(rows, t, x + h, y, z, depth, waves.VERTICAL, RHO * G)
            - waves.pressure_at(rows, t, x - h, y, z, depth, waves.VERTICAL, RHO * G),
            waves.pressure_at(rows, t, x, y + h, z, depth, waves.VERTICAL, RHO * G)
            - waves.pressure_at(rows, t, x, y - h, z, depth, waves.VERTICAL, RHO * G),
            waves.pressure_at(rows, t, x, y, z + h, depth, waves.VERTICAL, RHO * G)
            - waves.pressure_at(rows, t, x, y, z - h, depth, waves.VERTICAL, RHO * G),
        ]) / (2 * h)  # fmt: skip
        # the dynamic pressure's gradient: -rho du/dt (linearised Euler, gravity in p_static)
        assert grad == pytest.approx(-RHO * np.array([ax, ay, az]), rel=1e-5, abs=1e-4)
        # the kinematic condition at the mean surface, linearised: deta/dt = w(z = 0) (where
        # the mean surface is under water: under a crest)
        if waves.elevation_at(rows, t, x, y) > 0.0:
            deta = waves.elevation_at(rows, t + h, x, y) - waves.elevation_at(rows, t - h, x, y)
            w_top = waves.field(rows, t, x, y, 0.0, depth, waves.VERTICAL)[2]
            assert deta / (2 * h) == pytest.approx(w_top, rel=1e-6, abs=1e-9)
            crests += 1
        if depth < waves.DEEP:
            bottom = waves.field(rows, t, x, y, -depth, depth, waves.WHEELER)
            assert abs(bottom[2]) < 1e-12 and abs(bottom[5]) < 1e-12
    assert crests >= 5


def test_stretching_keeps_the_total_pressure_zero_at_the_surface():
    """Wheeler's stretching gives a dynamic pressure of rho g eta at the free surface (the
    hydrostatic -rho g eta cancels it), under a crest as under a trough; above the surface,
    the surface's value (callers integrate over the wetted part)."""
    rows = _rows(30.0, (2.0, 8.0, 0.0, 0.0), (0.7, 5.0, 0.8, 1.0))
    for x in np.linspace(0, 100, 21):
        eta = waves.elevation_at(rows, 3.0, x, 2.0)
        p = waves.pressure_at(rows, 3.0, x, 2.0, eta, 30.0, waves.WHEELER, RHO * G)
        assert p == pytest.approx(RHO * G * eta, rel=1e-12, abs=1e-9)
        above = waves.pressure_at(rows, 3.0, x, 2.0, eta + 0.01, 30.0, waves.WHEELER, RHO * G)
        assert above == p  # continuous: the surface's value


def _sea(**spec):
    return Environment.model_validate({"waves": [spec]}).waves[0]


@pytest.mark.parametrize("kind", ["jonswap", "pierson_moskowitz"])
def test_a_spectrum_gives_its_significant_height_and_peak(kind):
    """The components of a sea: 4 sqrt(m0) within 1 % of Hs (the tail beyond 3 w_p is cut);
    the spectrum's whole integral Hs^2 / 16; its peak at 2 pi / Tp."""
    hs, tp = 4.0, 10.0
    spec = _sea(kind=kind, significant_height=hs, peak_period=tp, frequencies=400, seed=3)
    rows = seastate.components(spec, waves.DEEP, G)
    m0 = np.sum(rows[:, 0] ** 2) / 2
    assert 4 * math.sqrt(m0) == pytest.approx(hs, rel=1e-2)
    wp = 2 * math.pi / tp
    grid = np.linspace(0.05 * wp, 40 * wp, 400_001)
    density = seastate.spectrum(spec, grid)
    assert np.trapezoid(density, grid) == pytest.approx(hs**2 / 16, rel=1e-4)
    assert grid[np.argmax(density)] == pytest.approx(wp, rel=1e-3)
    # the same seed, the same sea; another seed, other phases
    again = seastate.components(spec, waves.DEEP, G)
    assert np.array_equal(rows, again)
    other = seastate.components(spec.model_copy(update={"seed": 4}), waves.DEEP, G)
    assert not np.array_equal(rows[:, 5], other[:, 5])


def test_directional_spreading():
    spec = _sea(kind="jonswap", significant_height=3.0, peak_period=8.0, direction_deg=30.0,
                spreading_exponent=4.0, directions=9, frequencies=50)  # fmt: skip
    rows = seastate.components(spec, waves.DEEP, G)
    assert len(rows) == 50 * 9
    # energy is kept across directions and centred on the mean direction
    m0 = np.sum(rows[:, 0] ** 2) / 2
    long = seastate.components(spec.model_copy(update={"directions": 1}), waves.DEEP, G)
    assert m0 == pytest.approx(np.sum(long[:, 0] ** 2) / 2, rel=1e-12)
    mean = math.atan2(np.sum(rows[:, 0] ** 2 * rows[:, 4]), np.sum(rows[:, 0] ** 2 * rows[:, 3]))
    assert math.degrees(mean) == pytest.approx(30.0, abs=1e-9)


def test_bad_seas_are_refused():
    with pytest.raises(ValueError, match="directions"):
        _sea(kind="jonswap", significant_height=3.0, peak_period=8.0, directions=4)
    with pytest.raises(ValueError, match="gamma"):
        _sea(kind="pierson_moskowitz", significant_height=3.0, peak_period=8.0, gamma=2.0)
    with pytest.raises(ValueError, match="frequency_range"):
        _sea(kind="jonswap", significant_height=3.0, peak_period=8.0, frequency_range=[2, 1])


def test_the_sea_rises_over_the_build_up():
    """With a build-up of T: still water at t = 0, every quantity times the quintic ramp
    r(t/T) = s^3 (10 - 15 s + 6 s^2) before T and the full sea after it; the acceleration is
    still the velocity's time derivative (the ramp's rate included)."""
    rows = _rows(40.0, (1.5, 8.0, 0.3, 0.4), (0.7, 5.0, -1.0, 2.0))
    ramped = rows.copy()
    ramped[waves.BUILD_UP] = 20.0
    x, y, z = 3.0, -2.0, -4.0
    assert waves.elevation_at(ramped, 0.0, x, y) == 0.0
    assert waves.field(ramped, 0.0, x, y, z, 40.0, waves.WHEELER) == (0.0,) * 6
    for t in (5.0, 13.0, 20.0, 31.0):
        s = min(t / 20.0, 1.0)
        r = s**3 * (10 - 15 * s + 6 * s * s)
        assert waves.elevation_at(ramped, t, x, y) == pytest.approx(
            r * waves.elevation_at(rows, t, x, y), rel=1e-13, abs=1e-15)  # fmt: skip
        # held at z (vertical stretching): Wheeler's stretches with the raised elevation
        assert waves.pressure_at(ramped, t, x, y, z, 40.0, waves.VERTICAL, RHO * G) == (
            pytest.approx(r * waves.pressure_at(rows, t, x, y, z, 40.0, waves.VERTICAL,
                                                RHO * G), rel=1e-12))  # fmt: skip
        h = 1e-4
        ahead = np.array(waves.field(ramped, t + h, x, y, z, 40.0, waves.VERTICAL)[:3])
        behind = np.array(waves.field(ramped, t - h, x, y, z, 40.0, waves.VERTICAL)[:3])
        acceleration = np.array(waves.field(ramped, t, x, y, z, 40.0, waves.VERTICAL)[3:])
        assert acceleration == pytest.approx((ahead - behind) / (2 * h), rel=1e-6, abs=1e-9)


@pytest.mark.parametrize("limit", [0.7, 3.0, 3e4, 1e6])
def test_vectorised_cos_sin_agree_with_the_c_library(limit):
    """kernels.trig's cosines and sines (the components' phases, a vectorised loop) against
    numpy's, at angles up to ``limit`` [rad] (3e4: 180 components over three hours), to the
    last bit or so; exact at the quarter turns' zeros and ones."""
    from seacable.kernels import trig

    angles = np.random.default_rng(3).uniform(-limit, limit, 100_001)
    c, s = trig.cos_sin_at(angles)
    assert np.abs(c - np.cos(angles)).max() <= 2.3e-16
    assert np.abs(s - np.sin(angles)).max() <= 2.3e-16
    c, s = trig.cos_sin_at(np.array([0.0, -0.0, math.pi, 2.0 * math.pi, 1e-300]))
    assert np.array_equal(c, np.cos([0.0, -0.0, math.pi, 2.0 * math.pi, 1e-300]))
    assert s[0] == 0.0 and s[4] == 1e-300


def test_vectorised_exp_agrees_with_the_c_library():
    """kernels.trig's exponentials (the components' depth factors, a vectorised loop) against
    numpy's over the range the waves use (k z <= 0) and beyond, to two roundings; 0 below the
    normal doubles (e^-708)."""
    from seacable.kernels import trig

    rng = np.random.default_rng(5)
    x = np.concatenate([rng.uniform(-708.0, 0.0, 100_000), rng.uniform(-1.0, 1.0, 100_000),
                        rng.uniform(0.0, 709.0, 10_000), [0.0, -0.0, 1.0, -1e-300]])  # fmt: skip
    assert np.abs(trig.exp_at(x) / np.exp(x) - 1.0).max() <= 4.5e-16
    assert np.array_equal(trig.exp_at(np.array([-709.0, -1e4, -1e30, -np.inf])), np.zeros(4))


@pytest.mark.parametrize("depth", [3.0, 60.0, 2000.0, waves.DEEP])
def test_the_depth_factors_are_the_hyperbolic_ones(depth):
    """The pressure and the kinematics of one component against the textbook's cosh and sinh
    (shallow, intermediate, deep and infinite depth; from the surface to the seabed)."""
    a, period, phase = 0.8, 7.0, 0.3
    rows = _rows(depth, (a, period, 0.0, phase))
    omega, k = rows[waves.W, 0], rows[waves.K, 0]
    bottom = min(depth, 150.0)
    for z in np.linspace(-bottom, 0.0, 13):
        x, t = 2.0, 1.3
        theta = k * x - omega * t + phase
        if depth < waves.DEEP:
            c = math.cosh(k * (z + depth)) / math.cosh(k * depth)
            d = math.cosh(k * (z + depth)) / math.sinh(k * depth)
            e = math.sinh(k * (z + depth)) / math.sinh(k * depth)
        else:
            c = d = e = math.exp(k * z)
        p = waves.pressure_at(rows, t, x, 0.0, z, depth, waves.VERTICAL, RHO * G)
        assert p == pytest.approx(RHO * G * a * c * math.cos(theta), rel=1e-13, abs=1e-9)
        ux, uy, uz, ax, ay, az = waves.field(rows, t, x, 0.0, z, depth, waves.VERTICAL)
        expected = (
            a * omega * d * math.cos(theta),
            0.0,
            a * omega * e * math.sin(theta),
            a * omega**2 * d * math.sin(theta),
            0.0,
            -a * omega**2 * e * math.cos(theta),
        )
        assert (ux, uy, uz, ax, ay, az) == pytest.approx(expected, rel=1e-13, abs=1e-13)
