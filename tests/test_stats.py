"""seacable.stats against closed forms: ASTM E1049-85's worked example of rainflow counting, a
sine's statistics, Rice's zero-up-crossing period of a Gaussian sea, and the most probable
largest value against the exact distribution of the largest of N Rayleigh peaks and a Monte
Carlo of storms."""

import math

import numpy as np
import pytest

from seacable import stats


def test_rainflow_counts_astm_e1049s_example():
    """ASTM E1049-85, section 5.4.4 (its figure 6): the history -2, 1, -3, 5, -1, 3, -4, 4, -2
    holds ranges 3 (half), 4 (one and a half), 6 (half), 8 (one), 9 (half)."""
    found = stats.cycles([-2, 1, -3, 5, -1, 3, -4, 4, -2])
    counted = {r: found[found[:, 0] == r, 2].sum() for r in np.unique(found[:, 0])}
    assert counted == {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}


def test_miners_damage_of_a_sine_is_its_cycles_over_the_curves_life():
    """A sine of range R over n whole periods, trough to trough, does n cycles: damage
    n (R / reference)^m / k."""
    t = np.linspace(0.0, 100.0, 100_001)
    x = 5.0e5 - 2.0e5 * np.cos(2.0 * np.pi * t / 10.0)  # N: a tension of range 4e5 N
    d = stats.damage(x, k=316.0, m=3.36, reference=4.9e6)  # API RP 2SK's studless chain form
    assert d == pytest.approx(10 * (4.0e5 / 4.9e6) ** 3.36 / 316.0, rel=1e-6)
    with pytest.raises(ValueError, match="k > 0"):
        stats.damage(x, k=0.0, m=3.0)


def test_a_sines_summary():
    t = np.arange(0.0, 120.0, 0.01)
    x = 3.0 + 2.0 * np.sin(2.0 * np.pi * t / 8.0 + 0.3)
    s = stats.summary(t, x)
    assert s.largest == pytest.approx(5.0, abs=1e-5) and s.least == pytest.approx(1.0, abs=1e-5)
    assert s.mean == pytest.approx(3.0, abs=1e-9) and s.std == pytest.approx(2.0 / math.sqrt(2))
    assert s.tz == pytest.approx(8.0, rel=1e-6) and s.up_crossings == 15
    assert math.isnan(s.mpm)
    assert math.isnan(stats.summary(t[:100], x[:100]).tz)  # under two crossings


def _sea(spectrum, low, high, count, t, rng):
    """A Gaussian process of one-sided spectrum ``spectrum(omega)``: ``count`` components, one
    at a random frequency in each equal band of [low, high] (a grid of equal steps would repeat
    itself every 2 pi / step seconds), random phases. Its variance m0 and m2."""
    edges = np.linspace(low, high, count + 1)
    omegas = edges[:-1] + rng.uniform(0.0, 1.0, count) * np.diff(edges)
    amplitudes = np.sqrt(2.0 * spectrum(omegas) * np.diff(edges))
    phases = rng.uniform(0.0, 2.0 * np.pi, count)
    x = np.zeros_like(t)
    for a, w, p in zip(amplitudes, omegas, phases, strict=True):
        x += a * np.cos(w * t + p)
    m0 = float(np.sum(amplitudes**2) / 2.0)
    return x, m0, float(np.sum(omegas**2 * amplitudes**2) / 2.0)


def test_the_zero_up_crossing_period_is_rices_for_a_gaussian_sea():
    """A Pierson-Moskowitz sea of 300 components over 3 hours: the counted Tz within 2 % of
    Rice's 2 pi sqrt(m0 / m2), the process's own."""
    rng = np.random.default_rng(3)
    t = np.arange(0.0, 10800.0, 0.2)
    x, m0, m2 = _sea(lambda w: w**-5 * np.exp(-1.25 * (0.7 / w) ** 4), 0.35, 2.5, 300, t, rng)
    s = stats.summary(t, x)
    assert s.tz == pytest.approx(2.0 * math.pi * math.sqrt(m0 / m2), rel=0.02)
    assert s.std == pytest.approx(math.sqrt(m0), rel=0.03)


def test_the_most_probable_largest_of_a_storm():
    """The largest of N independent Rayleigh peaks of scale sigma has the distribution
    F(a)^N: the formula's sigma sqrt(2 ln N) lies within 2 % of that distribution's mode
    (N = 1,000: 3.717 against 3.737). Over 20 three-hour storms of a Gaussian process (a band
    of 0.15 rad/s about 1 rad/s, some 1,700 periods each), the median of their largest values
    lies within 5 % of that distribution's median (measured 2.6 % below it: the peaks of a
    narrow band are not independent) and within 2 % of the formula's most probable largest
    (measured 0.2 %). A Weibull law fitted to each storm's peaks finds a shape of 2 (within
    0.1) and a most probable largest within 3 % of Rayleigh's."""
    n = 1000
    a = np.linspace(2.0, 5.0, 300_001)
    density = n * a * np.exp(-(a**2) / 2.0) * (1.0 - np.exp(-(a**2) / 2.0)) ** (n - 1)
    assert stats.rayleigh_mpm(0.0, 1.0, 10.0, 10.0 * n) == pytest.approx(
        a[np.argmax(density)], rel=0.02
    )
    rng = np.random.default_rng(7)
    t = np.arange(0.0, 10800.0, 0.25)
    largest, mpm, peaks, weibull, shapes = [], [], [], [], []
    for _ in range(20):
        x, _, _ = _sea(lambda w: np.exp(-(((w - 1.0) / 0.15) ** 2)), 0.4, 1.6, 400, t, rng)
        s = stats.summary(t, x, storm=t[-1])
        largest.append((s.largest - s.mean) / s.std)
        mpm.append((s.mpm - s.mean) / s.std)
        peaks.append(t[-1] / s.tz)
        fitted, shape = stats.weibull_mpm(t, x, t[-1])
        weibull.append((fitted - s.mean) / s.std)
        shapes.append(shape)
    exact_median = math.sqrt(-2.0 * math.log(1.0 - 0.5 ** (1.0 / float(np.mean(peaks)))))
    assert float(np.median(largest)) == pytest.approx(exact_median, rel=0.05)
    assert float(np.median(largest)) == pytest.approx(float(np.mean(mpm)), rel=0.02)
    # the Weibull fit of each storm's own peaks finds Rayleigh's shape and its extreme
    assert float(np.mean(shapes)) == pytest.approx(2.0, abs=0.1)
    assert float(np.mean(weibull)) == pytest.approx(float(np.mean(mpm)), rel=0.03)


def test_the_command_reads_a_runs_tensions_and_motions(tmp_path):
    """``seacable stats``: a row per line end and per moving body's motion, in kN for
    tensions; a storm of no length refused by the option's name."""
    import copy

    from click.testing import CliRunner
    from tests.test_case_errors import CHAIN

    import seacable
    from seacable.cli import main

    output = tmp_path / "chain.nc"
    data = copy.deepcopy(CHAIN)
    data["lines"][0]["initial"] = {"arc_deg": [30.0, 30.0]}  # swinging
    data["bodies"][1]["position"] = [5.0, 0.0, -8.660254037844387]
    seacable.simulate(seacable.load_case(data), output=output)
    outcome = CliRunner().invoke(main, ["stats", str(output), "--storm", "3600"])
    assert outcome.exit_code == 0, outcome.output
    rows = {line[:44].strip(): line[44:].split() for line in outcome.output.splitlines()[1:-1]}
    assert set(rows) >= {"lines/cable tension, 'from' end", "lines/cable tension, 'to' end",
                         "bodies/end position_x", "bodies/end position_z"}  # fmt: skip
    assert rows["lines/cable tension, 'from' end"][0] == "kN"
    tree = seacable.Results.open(output).dataset
    x = tree["bodies/end/position_x"].values
    assert float(rows["bodies/end position_x"][1]) == pytest.approx(x.max(), rel=1e-3)
    assert "rows from 0 s to" in outcome.output  # no build-up: every row
    middle = float(tree["time"].values[len(tree["time"]) // 2])
    late = CliRunner().invoke(main, ["stats", str(output), "--from", f"{middle!r}"])
    kept = tree["time"].values >= middle
    late_rows = {line[:44].strip(): line[44:].split() for line in late.output.splitlines()[1:-1]}
    assert float(late_rows["bodies/end position_x"][2]) == pytest.approx(x[kept].min(), rel=1e-3)
    assert f"{kept.sum()} rows from {middle:g} s to" in late.output and kept.sum() >= 2
    refused = CliRunner().invoke(main, ["stats", str(output), "--storm", "0"])
    assert refused.exit_code == 2 and "--storm" in refused.output


def test_a_gumbel_fit_finds_the_law_it_was_drawn_from():
    """Maximum likelihood on 2,000 draws of Gumbel(mu 10, beta 2): within 3 % of each (its
    standard errors are about 1 % and 2 %); and its likelihood equation holds at the fit."""
    rng = np.random.default_rng(7)
    x = rng.gumbel(10.0, 2.0, 2000)
    mu, beta = stats.gumbel_fit(x)
    assert mu == pytest.approx(10.0, rel=0.03) and beta == pytest.approx(2.0, rel=0.03)
    w = np.exp(-x / beta)
    assert x.mean() - beta - (x * w).sum() / w.sum() == pytest.approx(0.0, abs=1e-9)
    assert math.isnan(stats.gumbel_fit([1.0, 2.0])[0]) and math.isnan(stats.gumbel_fit([3] * 5)[1])


def test_the_gumbel_estimate_of_a_storms_largest_from_short_realisations():
    """Two hundred realisations of 20 minutes of a narrow-band Gaussian response (120 Rayleigh
    peaks each), each's largest value fitted: the mode of the largest over 3 hours (1,080
    peaks) lands within 3 % of the exact one, the mode of (1 - exp(-x^2 / 2))^1080 (the
    estimate's own scatter: about 1.5 % with 200 realisations, 5 % with 30)."""
    rng = np.random.default_rng(11)
    peaks = np.sqrt(-2.0 * np.log(rng.random((200, 120))))  # sigma 1
    found = stats.gumbel_mpm(peaks.max(axis=1), duration=1200.0, storm=10800.0)
    x = np.linspace(2.0, 6.0, 400_001)
    density = (1.0 - np.exp(-(x**2) / 2.0)) ** 1079 * x * np.exp(-(x**2) / 2.0)
    assert found == pytest.approx(x[np.argmax(density)], rel=0.03)


def test_a_spectrum_integrates_to_the_variance_and_peaks_at_a_sines_frequency():
    t = np.arange(0.0, 1200.0, 0.1)
    rng = np.random.default_rng(3)
    x = 2.0 * np.sin(2 * np.pi * 0.125 * t) + rng.normal(0.0, 0.5, t.size) + 7.0
    f, density = stats.spectrum(t, x)
    assert f[np.argmax(density)] == pytest.approx(0.125, abs=f[1])
    assert np.trapezoid(density, f) == pytest.approx(np.var(x), rel=0.02)
    with pytest.raises(ValueError, match="even interval"):
        stats.spectrum(np.r_[t[:100], t[101:200]], x[:199])
