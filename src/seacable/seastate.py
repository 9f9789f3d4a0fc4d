"""Sea states: wave spectra (JONSWAP, Pierson-Moskowitz), directional spreading, the
dispersion relation, and the components of a sea (kernels.waves's rows).

Spectra are one-sided, in angular frequency: S(w) [m^2 s/rad] with int S dw = m0 = Hs^2 / 16.
Pierson-Moskowitz (in the ITTC / DNV form of Hs and the peak frequency w_p = 2 pi / Tp):

    S_PM(w) = 5/16 Hs^2 w_p^4 w^-5 exp(-5/4 (w_p / w)^4)

JONSWAP: S_PM(w) gamma^exp(-(w - w_p)^2 / (2 sigma^2 w_p^2)), sigma 0.07 below w_p and 0.09
above, scaled so that its integral is Hs^2 / 16 (DNV's A_gamma = 1 - 0.287 ln gamma is the same
scaling to about 1 %). The bands kept hold a little less (the tail beyond ``high`` is cut).

A sea is discretised into ``frequencies`` bands of equal width between ``low`` and ``high``
times w_p; each component's frequency is drawn uniformly inside its band (a record does not
repeat after 2 pi / dw) and its phase uniformly, both from the ``seed``; its amplitude is
sqrt(2 S(w) dw). Directional spreading cos^2s((b - b_0) / 2) is discretised into ``directions``
equal sectors over (b_0 - pi, b_0 + pi), weights normalised to one; each frequency is given
every direction (frequencies x directions components).
"""

import math

import numpy as np

from seacable.kernels import waves

GAMMA = 3.3  # JONSWAP's peak enhancement by default


def wave_number(omega: np.ndarray, depth: float, gravity: float) -> np.ndarray:
    """k of w^2 = g k tanh(k h) (Newton from the deep-water root; h = kernels.waves.DEEP:
    k = w^2 / g)."""
    omega = np.asarray(omega, dtype=float)
    k = omega**2 / gravity
    if depth >= waves.DEEP:
        return k
    k = np.maximum(k, omega / math.sqrt(gravity * depth))  # shallow-water root, from above
    for _ in range(100):
        th = np.tanh(k * depth)
        f = gravity * k * th - omega**2
        df = gravity * (th + k * depth * (1.0 - th**2))
        step = f / df
        k = k - step
        if np.all(np.abs(step) <= 1e-15 * np.abs(k)):
            break
    return k


def pierson_moskowitz(omega, hs: float, tp: float) -> np.ndarray:
    wp = 2.0 * math.pi / tp
    omega = np.asarray(omega, dtype=float)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        s = 5.0 / 16.0 * hs**2 * wp**4 * omega**-5.0 * np.exp(-1.25 * (wp / omega) ** 4)
    return np.where(omega > 0.0, s, 0.0)


def jonswap(omega, hs: float, tp: float, gamma: float = 3.3) -> np.ndarray:
    """Unscaled: JONSWAP's peak enhancement on S_PM (``spectrum`` scales it to Hs)."""
    wp = 2.0 * math.pi / tp
    omega = np.asarray(omega, dtype=float)
    sigma = np.where(omega <= wp, 0.07, 0.09)
    peak = gamma ** np.exp(-((omega - wp) ** 2) / (2.0 * sigma**2 * wp**2))
    return pierson_moskowitz(omega, hs, tp) * peak


def spreading(angles, exponent: float) -> np.ndarray:
    """cos^2s(angle / 2) weights of the sectors at ``angles`` [rad from the mean], summing
    to one (one direction: weight one)."""
    angles = np.asarray(angles, dtype=float)
    weights = np.cos(angles / 2.0) ** (2.0 * exponent)
    return weights / weights.sum()


def components(spec, depth: float, gravity: float, build_up: float = 0.0) -> np.ndarray:
    """The rows (n, kernels.waves.GIVEN: a, w, k, cos b, sin b, phase, build-up [s]) of a
    schema wave (``case.environment``'s RegularWave or WaveSpectrum)."""
    rows = _components(spec, depth, gravity)
    return np.column_stack([rows, np.full(len(rows), float(build_up))])


def _components(spec, depth: float, gravity: float) -> np.ndarray:
    direction = math.radians(spec.direction_deg)
    if spec.kind == "airy":
        omega = np.array([2.0 * math.pi / spec.period])
        rows = np.zeros((1, 6))
        rows[0, :2] = spec.height / 2.0, omega[0]
        rows[0, 2] = wave_number(omega, depth, gravity)[0]
        rows[0, 3:] = math.cos(direction), math.sin(direction), math.radians(spec.phase_deg)
        return rows
    rng = np.random.default_rng(spec.seed)
    wp = 2.0 * math.pi / spec.peak_period
    low, high = spec.frequency_range[0] * wp, spec.frequency_range[1] * wp
    edges = np.linspace(low, high, spec.frequencies + 1)
    width = np.diff(edges)
    omega = edges[:-1] + width * rng.random(spec.frequencies)
    density = spectrum(spec, omega)
    m = spec.directions
    sectors = (np.arange(m) - (m - 1) / 2.0) * (2.0 * math.pi / m) if m > 1 else np.zeros(1)
    weights = spreading(sectors, spec.spreading_exponent)
    amp = np.sqrt(2.0 * density[:, None] * width[:, None] * weights[None, :])
    k = wave_number(omega, depth, gravity)
    rows = np.zeros((spec.frequencies * m, 6))
    rows[:, 0] = amp.ravel()
    rows[:, 1] = np.repeat(omega, m)
    rows[:, 2] = np.repeat(k, m)
    angle = direction + np.tile(sectors, spec.frequencies)
    rows[:, 3], rows[:, 4] = np.cos(angle), np.sin(angle)
    rows[:, 5] = rng.uniform(0.0, 2.0 * math.pi, len(rows))
    return rows


def spectrum(spec, omega) -> np.ndarray:
    """S at ``omega`` of a schema spectrum, JONSWAP's scaled so that its whole integral (over
    0.05 to 40 w_p) is Hs^2 / 16."""
    hs, tp = spec.significant_height, spec.peak_period
    if spec.kind == "pierson_moskowitz":
        return pierson_moskowitz(omega, hs, tp)
    wp = 2.0 * math.pi / tp
    gamma = GAMMA if spec.gamma is None else spec.gamma
    grid = np.linspace(0.05 * wp, 40.0 * wp, 200_001)
    whole = np.trapezoid(jonswap(grid, hs, tp, gamma), grid)
    return jonswap(omega, hs, tp, gamma) * (hs**2 / 16.0) / whole
