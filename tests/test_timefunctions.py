"""Time functions: values and exact derivatives, checked against closed forms and differences."""

import numpy as np
import pytest

from seacable.case import schema
from seacable.kernels.timefn import evaluate
from seacable.models import timefunctions as tfn


def _eval(spec, times, base_dir=None):
    compiled = tfn.stack([tfn.build(spec, base_dir)])
    return np.array([evaluate(*compiled, 0, t) for t in times])


def test_constant_and_none():
    out = _eval(schema.Constant(value=3.5), [-1.0, 0.0, 100.0])
    np.testing.assert_allclose(out, [[3.5, 0, 0]] * 3)
    np.testing.assert_allclose(_eval(None, [2.0]), [[0.0, 0.0, 0.0]])


def test_sine_with_period_and_phase():
    spec = schema.Sine(kind="sine", amplitude=2.0, period=4.0, phase=0.3, offset=1.0)
    t = np.linspace(0, 10, 7)
    w = 2 * np.pi / 4.0
    expected = np.column_stack(
        [
            1.0 + 2.0 * np.sin(w * t + 0.3),
            2.0 * w * np.cos(w * t + 0.3),
            -2.0 * w**2 * np.sin(w * t + 0.3),
        ]
    )
    np.testing.assert_allclose(_eval(spec, t), expected, atol=1e-12)


def test_ramp_holds_outside():
    spec = schema.Ramp(kind="ramp", start_time=1.0, end_time=3.0, start_value=2.0, end_value=6.0)
    out = _eval(spec, [0.0, 2.0, 5.0])
    np.testing.assert_allclose(out[:, 0], [2.0, 4.0, 6.0])
    np.testing.assert_allclose(out[1, 1], 2.0)


def test_acceleration_profile_is_exact():
    """0-15 s at 0.1 m/s^2, then 30 s at -0.05 m/s^2, then none (the towed-fish manoeuvre)."""
    spec = schema.AccelerationProfile(
        kind="acceleration_profile",
        initial_position=5.0,
        initial_velocity=2.5,
        phases=[{"duration": 15.0, "acceleration": 0.1}, {"duration": 30.0, "acceleration": -0.05}],
    )
    out = _eval(spec, [0.0, 10.0, 15.0, 30.0, 60.0])
    x15 = 5.0 + 2.5 * 15 + 0.5 * 0.1 * 15**2
    v15 = 2.5 + 1.5
    x45 = x15 + v15 * 30 - 0.5 * 0.05 * 30**2
    v45 = v15 - 1.5
    np.testing.assert_allclose(out[0], [5.0, 2.5, 0.1])
    np.testing.assert_allclose(out[1], [5.0 + 25 + 5.0, 3.5, 0.1])
    np.testing.assert_allclose(out[3], [x15 + v15 * 15 - 0.5 * 0.05 * 225, v15 - 0.75, -0.05])
    np.testing.assert_allclose(out[4], [x45 + v45 * 15, v45, 0.0])
    before = _eval(spec, [-2.0])
    np.testing.assert_allclose(before[0], [5.0 - 5.0, 2.5, 0.0])


@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
def test_table_from_csv(tmp_path, interpolation):
    path = tmp_path / "force.csv"
    path.write_text("time,value\n0,0\n1,2\n2,1\n4,1\n")
    spec = schema.Table(kind="table", file="force.csv", interpolation=interpolation)
    out = _eval(spec, [-1.0, 0.0, 1.0, 2.0, 10.0], base_dir=tmp_path)
    np.testing.assert_allclose(out[:, 0], [0.0, 0.0, 2.0, 1.0, 1.0], atol=1e-12)
    t = np.linspace(0.25, 3.75, 8)  # off the breakpoints, where a linear table has kinks
    h = 1e-6
    central = (_eval(spec, t + h, tmp_path)[:, 0] - _eval(spec, t - h, tmp_path)[:, 0]) / (2 * h)
    np.testing.assert_allclose(_eval(spec, t, tmp_path)[:, 1], central, atol=1e-5)


def test_table_rejects_unsorted_times(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("0,1\n2,1\n1,3\n")
    with pytest.raises(ValueError, match="strictly increasing"):
        tfn.build(schema.Table(kind="table", file=str(path)))
