"""Statistics engineers read from a run's time series (``seacable stats``): largest, least,
mean, standard deviation, the zero-up-crossing period and the most probable largest value
over a storm from a Rayleigh distribution of the peaks or a Weibull fit of them, or from a
Gumbel law fitted to the largest values of several realisations (a sweep's seeds); spectra
(Welch's); rainflow cycles (ASTM E1049-85, by the ``rainflow`` package) and the fatigue
damage they do on a T-N curve N R^m = K.

The most probable largest value (Rayleigh): a narrow-band Gaussian process of standard
deviation sigma has Rayleigh-distributed peaks above its mean, one per zero-up-crossing period
Tz; of the N = D / Tz peaks of a storm of duration D, the most probable largest lies
sigma sqrt(2 ln N) above the mean (the mode of the largest of N Rayleigh variables, for large
N; ``tests/test_stats.py`` checks it against that largest's exact distribution). The most
probable maximum of a 3-hour storm is what mooring design checks commonly take. A
broad-banded or non-Gaussian response (a snatching line) needs a fit to its own peaks: the
Weibull estimate (``weibull_mpm``) fits the cycles' peaks, and its shape says how far they are
from Rayleigh's (2); it needs some tens of peaks to mean anything. The largest values of
several realisations of a sea state (seeds) follow a Gumbel law for any parent of exponential
tail; fitted to them (``gumbel_fit``, maximum likelihood), the mode of the largest over a
storm N times a realisation's duration is mu + beta ln N (``gumbel_mpm``): the common
estimate from the maxima of several simulations of one sea state.
"""

import math
from dataclasses import asdict, dataclass

import numpy as np
import rainflow  # type: ignore[import-untyped]
import yaml


@dataclass(frozen=True)
class Summary:
    """What a time series says at first reading. ``tz`` [s] is NaN when the series crosses
    its mean upwards fewer than twice; ``mpm`` [the series' unit] is NaN without a storm
    duration or a ``tz``."""

    largest: float
    least: float
    mean: float
    std: float
    tz: float
    up_crossings: int
    mpm: float

    def as_dict(self) -> dict:
        return asdict(self)


def steady(t, start: float) -> np.ndarray:
    """The rows of the times ``t`` from ``start`` [s] on (a run's statistics leave out its
    build-up, the ramp that starts its waves); every row when fewer than two are left."""
    t = np.asarray(t, dtype=float)
    kept = t >= start
    return kept if kept.sum() >= 2 else np.ones(t.shape, dtype=bool)


def build_up(attrs) -> float:
    """The build-up [s] of the case a run's results keep (their ``case_resolved``; 0 when
    they keep none)."""
    try:
        case = yaml.safe_load(str(attrs.get("case_resolved", ""))) or {}
        return float(case.get("simulation", {}).get("build_up", 0.0) or 0.0)
    except (yaml.YAMLError, AttributeError, TypeError, ValueError):
        return 0.0


def up_crossing_times(t, x, level: float) -> np.ndarray:
    """The times [s] at which ``x`` crosses ``level`` upwards, linearly interpolated between
    samples (a sample exactly at the level counts once, where the series leaves it upwards)."""
    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float) - level
    at = np.flatnonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))
    share = -x[at] / (x[at + 1] - x[at])
    return t[at] + share * (t[at + 1] - t[at])


def zero_up_crossing_period(t, x) -> tuple[float, int]:
    """The mean time [s] between the up-crossings of the series' mean, and their count (NaN
    below two crossings): Rice's 2 pi sqrt(m0 / m2) for a Gaussian process."""
    times = up_crossing_times(t, x, float(np.mean(x)))
    if len(times) < 2:
        return math.nan, len(times)
    return float((times[-1] - times[0]) / (len(times) - 1)), len(times)


def rayleigh_mpm(mean: float, std: float, tz: float, duration: float) -> float:
    """The most probable largest value over ``duration`` [s] of a narrow-band Gaussian process
    (module docstring): mean + std sqrt(2 ln(duration / tz)); NaN when the storm holds fewer
    than two periods or tz is unknown."""
    if not (math.isfinite(tz) and tz > 0.0 and duration >= 2.0 * tz):
        return math.nan
    return mean + std * math.sqrt(2.0 * math.log(duration / tz))


FEWEST_PEAKS = 30  # the peaks a Weibull fit of their tail needs


def cycle_peaks(t, x) -> np.ndarray:
    """The largest value of each cycle: between two consecutive up-crossings of the mean
    (one peak a zero-up-crossing period, as the Rayleigh law counts them)."""
    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    level = float(np.mean(x))
    at = np.flatnonzero((x[:-1] < level) & (x[1:] >= level)) + 1
    return np.array([x[a:b].max() for a, b in zip(at[:-1], at[1:], strict=True)])


def weibull_mpm(t, x, duration: float) -> tuple[float, float]:
    """The most probable largest value over ``duration`` [s] from a Weibull law fitted to the
    cycles' peaks above the mean (``cycle_peaks``, maximum likelihood with the location at the
    mean): the value a peak exceeds once in the storm's N = duration / Tz peaks, mean +
    scale (ln N)^(1 / shape); and the fitted shape (2 is Rayleigh's; a snatching line's peaks
    fall off faster or slower). NaN below FEWEST_PEAKS peaks: a tail fitted to fewer says
    little (a 120 s run of a snatching chain, 18 peaks: shape 0.9, twice Rayleigh's extreme)."""
    from scipy.stats import weibull_min

    mean = float(np.mean(x))
    peaks = cycle_peaks(t, x) - mean
    tz, _ = zero_up_crossing_period(t, x)
    peaks = peaks[peaks > 0.0]
    if len(peaks) < FEWEST_PEAKS or not duration >= 2.0 * tz:
        return math.nan, math.nan
    shape, _, scale = weibull_min.fit(peaks, floc=0.0)
    return mean + scale * math.log(duration / tz) ** (1.0 / shape), float(shape)


def summary(t, x, storm: float | None = None) -> Summary:
    """``x`` over the times ``t``; ``storm`` [s]: the duration of the storm whose most
    probable largest value is estimated (``rayleigh_mpm``)."""
    x = np.asarray(x, dtype=float)
    tz, count = zero_up_crossing_period(t, x)
    mean, std = float(np.mean(x)), float(np.std(x))
    return Summary(
        largest=float(np.max(x)), least=float(np.min(x)), mean=mean, std=std, tz=tz,
        up_crossings=count,
        mpm=rayleigh_mpm(mean, std, tz, storm) if storm is not None else math.nan,
    )  # fmt: skip


def cycles(x) -> np.ndarray:
    """Rainflow cycles of a series (ASTM E1049-85, the ``rainflow`` package): rows of (range,
    mean, count), count 0.5 for a half cycle."""
    found = [(r, m, c) for r, m, c, _, _ in rainflow.extract_cycles(np.asarray(x, dtype=float))]
    return np.array(found, dtype=float).reshape(-1, 3)


def damage(x, k: float, m: float, reference: float = 1.0) -> float:
    """Miner's fatigue damage of the series' rainflow cycles on the T-N curve N R^m = k, R the
    cycle's range over ``reference`` (a line's breaking strength for API RP 2SK's curves, 1 for
    a curve in the series' own unit): the sum of count / N(R)."""
    if not (k > 0.0 and m > 0.0 and reference > 0.0):
        raise ValueError(f"a T-N curve needs k > 0, m > 0 and a reference > 0 (got k={k:g}, "
                         f"m={m:g}, reference={reference:g})")  # fmt: skip
    found = cycles(x)
    ranges = found[:, 0] / reference
    return float(np.sum(found[:, 2] * ranges**m / k))


def series(tree) -> list[tuple[str, str, np.ndarray]]:
    """What ``seacable stats`` reads first in a system's results (an xarray DataTree): each
    line's tension at its two ends (its first and last segment or node; a tie's one tension)
    and each moving body's position and angles, as (name, unit, values over time)."""
    out: list[tuple[str, str, np.ndarray]] = []
    for name, node in tree["lines"].children.items() if "lines" in tree.children else []:
        tension = node["tension"]
        unit = str(tension.attrs.get("units", ""))
        if tension.ndim == 1:
            out.append((f"lines/{name} tension", unit, tension.values))
            continue
        out.append((f"lines/{name} tension, 'from' end", unit, tension.values[:, 0]))
        out.append((f"lines/{name} tension, 'to' end", unit, tension.values[:, -1]))
    for name, node in tree["bodies"].children.items() if "bodies" in tree.children else []:
        for key in ("position_x", "position_y", "position_z", "roll", "pitch", "yaw"):
            values = node[key].values if key in node else np.zeros(1)
            if np.ptp(values) > 1e-6 * max(1.0, float(np.abs(values).max())):  # it moves
                out.append((f"bodies/{name} {key}", str(node[key].attrs.get("units", "")),
                            values))  # fmt: skip
    return out


EULER_GAMMA = 0.5772156649015329


def gumbel_fit(maxima) -> tuple[float, float]:
    """The location mu and scale beta of the Gumbel law F(x) = exp(-exp(-(x - mu) / beta))
    fitted by maximum likelihood to ``maxima`` (each the largest value of one realisation, e.g.
    of one seed), from the method of moments' start (beta = s sqrt(6) / pi, mu = mean - gamma
    beta); (NaN, NaN) below three maxima or when they are all equal."""
    x = np.asarray(maxima, dtype=float)
    x = x[np.isfinite(x)]
    if x.size < 3 or np.ptp(x) == 0.0:
        return math.nan, math.nan
    beta = float(np.std(x, ddof=1)) * math.sqrt(6.0) / math.pi
    for _ in range(100):  # the likelihood's equation in beta (Newton's method)
        shifted = x - x.max()
        w = np.exp(-shifted / beta)
        s0, s1, s2 = w.sum(), (x * w).sum(), (x * x * w).sum()
        g = x.mean() - beta - s1 / s0
        dg = -1.0 - (s2 * s0 - s1 * s1) / (s0 * s0 * beta * beta)
        step = g / dg
        beta = max(beta - step, 0.5 * beta)
        if abs(step) < 1e-12 * beta:
            break
    w = np.exp(-(x - x.max()) / beta)
    mu = float(x.max() - beta * math.log(w.mean()))
    return mu, float(beta)


def gumbel_mpm(maxima, duration: float, storm: float) -> float:
    """The most probable largest value over a ``storm`` [s] from the largest values of
    realisations of ``duration`` [s] each (``gumbel_fit``): the mode of the largest of
    storm / duration Gumbel variables, mu + beta ln(storm / duration)."""
    mu, beta = gumbel_fit(maxima)
    return mu + beta * math.log(storm / duration)


def spectrum(t, x, segments: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """The one-sided power spectral density of a series sampled evenly (frequencies [Hz] and
    density [unit^2/Hz]) by Welch's method (SciPy's: Hann windows over ``segments`` halves
    overlapping, the mean removed): it integrates to the series' variance."""
    from scipy.signal import welch

    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    dt = np.diff(t)
    if len(t) < 16 or not np.allclose(dt, dt[0], rtol=1e-6):
        raise ValueError("a spectrum needs at least 16 samples at an even interval")
    per = max(16, int(2 * len(x) / (segments + 1)))
    return welch(x, fs=1.0 / dt[0], nperseg=min(per, len(x)), detrend="constant")


def table(t, found: list[tuple[str, str, np.ndarray]], storm: float,
          start: float) -> tuple[np.ndarray, list[tuple]]:  # fmt: skip
    """What ``seacable stats`` and the report give of the series ``found`` (``series``) from
    ``start`` [s] on (``steady``): the times kept, and per series (name, unit shown: forces in
    kN, its Summary over a ``storm`` [s], the Weibull estimate and its shape)."""
    t = np.asarray(t, dtype=float)
    kept = steady(t, start)
    rows = []
    for name, unit, values in found:
        scale, shown = (1e3, "kN") if unit == "N" else (1.0, unit)
        x = np.asarray(values, dtype=float)[kept] / scale
        fitted, shape = weibull_mpm(t[kept], x, storm)
        rows.append((name, shown, summary(t[kept], x, storm=storm), fitted, shape))
    return t[kept], rows
