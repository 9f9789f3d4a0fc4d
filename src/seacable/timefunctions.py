"""Turn validated time-function specifications into the compiled piecewise-cubic + sine form.

See ``seacable.kernels.timefn`` for the representation. Every builder returns a
:class:`Piecewise` (breakpoints, cubic coefficients, sine term); :func:`stack` packs several into
the arrays the kernels take, with the case's build-up (``simulation.build_up``) for every function
that follows it.
"""

from dataclasses import dataclass, field, replace

import numpy as np

from seacable.case import base
from seacable.kernels.timefn import evaluate as _evaluate

SENTINEL = -1.0e30  # first breakpoint: a constant piece that covers all earlier times


@dataclass(frozen=True)
class Piecewise:
    """f(t) = sum over pieces of cubic in (t - break) + amplitude sin(omega t + phase)."""

    breaks: np.ndarray
    coefs: np.ndarray  # (K, 4)
    sine: tuple[float, float, float] = field(default=(0.0, 0.0, 0.0))
    # whether the case's build-up applies (every imposed motion and applied force; not a towing
    # ship's distance, whose initial towed shape is already the steady state at its speed)
    builds_up: bool = True


def steady(function: Piecewise) -> Piecewise:
    """``function`` exempt from the case's build-up."""
    return replace(function, builds_up=False)


def constant(value: float) -> Piecewise:
    return Piecewise(np.array([SENTINEL]), np.array([[float(value), 0.0, 0.0, 0.0]]))


def _sine(spec: base.Sine) -> Piecewise:
    if spec.angular_frequency is not None:
        omega = spec.angular_frequency
    else:
        assert spec.period is not None  # Sine._one_frequency: exactly one of the two is given
        omega = 2 * np.pi / spec.period
    base = constant(spec.offset)
    return Piecewise(base.breaks, base.coefs, (spec.amplitude, omega, spec.phase))


def _ramp(spec: base.Ramp) -> Piecewise:
    slope = (spec.end_value - spec.start_value) / (spec.end_time - spec.start_time)
    breaks = np.array([SENTINEL, spec.start_time, spec.end_time])
    coefs = np.array(
        [
            [spec.start_value, 0.0, 0.0, 0.0],
            [spec.start_value, slope, 0.0, 0.0],
            [spec.end_value, 0.0, 0.0, 0.0],
        ]
    )
    return Piecewise(breaks, coefs)


def _acceleration_profile(spec: base.AccelerationProfile) -> Piecewise:
    """Exact position from piecewise-constant accelerations (zero after the last phase)."""
    x = spec.initial_position
    v = spec.initial_velocity
    t = spec.start_time
    # before the profile starts the motion is uniform at the initial velocity (for a million
    # seconds back, then held), so derivatives are exact at the start
    lead = 1.0e6
    breaks = [SENTINEL, t - lead, t]
    coefs = [[x - v * lead, 0.0, 0.0, 0.0], [x - v * lead, v, 0.0, 0.0]]
    for phase in spec.phases:
        coefs.append([x, v, 0.5 * phase.acceleration, 0.0])
        x += v * phase.duration + 0.5 * phase.acceleration * phase.duration**2
        v += phase.acceleration * phase.duration
        t += phase.duration
        breaks.append(t)
    coefs.append([x, v, 0.0, 0.0])
    return Piecewise(np.array(breaks), np.array(coefs))


def _table(spec: base.Table, base_dir) -> Piecewise:
    times, values = spec.load(base_dir)
    first = [values[0], 0.0, 0.0, 0.0]
    last = [values[-1], 0.0, 0.0, 0.0]
    if spec.interpolation == "linear":
        slopes = np.diff(values) / np.diff(times)
        middle = np.column_stack(
            [values[:-1], slopes, np.zeros_like(slopes), np.zeros_like(slopes)]
        )
    else:
        from scipy.interpolate import CubicSpline  # here: its import is slow (docs/architecture.md)

        spline = CubicSpline(times, values, bc_type="clamped")
        c = spline.c  # (4, K) highest power first
        middle = np.column_stack([c[3], c[2], c[1], c[0]])
    breaks = np.concatenate([[SENTINEL], times])
    coefs = np.vstack([first, middle, last])
    return Piecewise(breaks, coefs)


def build(spec, base_dir=None) -> Piecewise:
    """Compile one validated time-function specification (or None for zero)."""
    if spec is None:
        return constant(0.0)
    if isinstance(spec, base.Constant):
        return constant(spec.value)
    if isinstance(spec, base.Sine):
        return _sine(spec)
    if isinstance(spec, base.Ramp):
        return _ramp(spec)
    if isinstance(spec, base.AccelerationProfile):
        return _acceleration_profile(spec)
    if isinstance(spec, base.Table):
        return _table(spec, base_dir)
    raise TypeError(f"unknown time function {type(spec).__name__}")


def stack(functions: list[Piecewise], build_up: float = 0.0):
    """Pack compiled functions into (breaks, coefs, count, sine, build_up) arrays for the
    kernels; ``build_up`` [s] is the case's build-up duration (0: none)."""
    n_channels = len(functions)
    k_max = max(len(f.breaks) for f in functions)
    breaks = np.full((n_channels, k_max), np.inf)
    coefs = np.zeros((n_channels, k_max, 4))
    count = np.zeros(n_channels, dtype=np.int64)
    sine = np.zeros((n_channels, 3))
    ramps = np.zeros((n_channels, 2))
    for c, f in enumerate(functions):
        k = len(f.breaks)
        breaks[c, :k] = f.breaks
        coefs[c, :k] = f.coefs
        count[c] = k
        sine[c] = f.sine
        if f.builds_up and build_up > 0.0:
            ramps[c] = build_up, evaluate(f, 0.0)[0]
    return breaks, coefs, count, sine, ramps


def kernel_fields(functions: list[Piecewise], build_up: float = 0.0) -> dict:
    """The ``tf_*`` fields of a kernel's parameters for these channels, in this order."""
    names = ("tf_breaks", "tf_coefs", "tf_count", "tf_sine", "tf_build_up")
    return dict(zip(names, stack(functions, build_up), strict=True))


def lowest(function: Piecewise, end: float, samples: int = 20001) -> tuple[float, float]:
    """The lowest value of ``function`` over [0, ``end``] [s] and its time: at its breaks
    there and at ``samples`` even times (a cubic piece's or a sine's dip between two samples
    can be missed by a little). Without the build-up, which stays between f(0) and f(t)."""
    breaks = function.breaks
    times = np.union1d(np.linspace(0.0, end, samples), breaks[(breaks >= 0.0) & (breaks <= end)])
    piece = np.searchsorted(breaks, times, side="right") - 1
    step, c = times - breaks[piece], function.coefs[piece]
    amplitude, omega, phase = function.sine
    values = c[:, 0] + step * (c[:, 1] + step * (c[:, 2] + step * c[:, 3]))
    values = values + amplitude * np.sin(omega * times + phase)
    k = int(np.argmin(values))
    return float(values[k]), float(times[k])


def evaluate(function: Piecewise, time: float) -> tuple[float, float, float]:
    """Value and first two derivatives of a compiled time function at ``time`` [s] (no
    build-up: that belongs to the case)."""
    return _evaluate(*stack([function]), 0, float(time))
