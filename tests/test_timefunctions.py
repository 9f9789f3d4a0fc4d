"""Time functions: values and exact derivatives, checked against closed forms and differences."""

import numpy as np
import pytest

from helpers import chain_case, run_rows
from seacable import timefunctions as tfn
from seacable.case import schema
from seacable.kernels.timefn import evaluate


def _eval(spec, times, base_dir=None, build_up=0.0):
    compiled = tfn.stack([tfn.build(spec, base_dir)], build_up)
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


# the build-up ramp r(s) = 10 s^3 - 15 s^4 + 6 s^5 as a numpy polynomial (lowest power first),
# differentiated by numpy rather than by the kernel's hand-written derivatives
_RAMP = np.polynomial.Polynomial([0.0, 0.0, 0.0, 10.0, -15.0, 6.0])


def test_build_up_closed_form_and_continuity():
    """5 m surge sin(2 pi t / 12) + 1 built up over 8 s: F = f(0) + r (f - f(0)) with its exact
    derivatives; at rest at t = 0, equal to the sine itself from t = 8 s on."""
    spec = schema.Sine(kind="sine", amplitude=5.0, period=12.0, phase=0.4, offset=1.0)
    build_up = 8.0
    w = 2 * np.pi / 12.0
    t = np.linspace(0.0, 16.0, 33)
    f = np.column_stack(
        [
            1.0 + 5.0 * np.sin(w * t + 0.4),
            5.0 * w * np.cos(w * t + 0.4),
            -5.0 * w**2 * np.sin(w * t + 0.4),
        ]
    )
    start = 1.0 + 5.0 * np.sin(0.4)
    s = np.minimum(t / build_up, 1.0)
    r, dr, ddr = _RAMP(s), _RAMP.deriv(1)(s) / build_up, _RAMP.deriv(2)(s) / build_up**2
    g = f[:, 0] - start
    expected = np.column_stack(
        [start + r * g, dr * g + r * f[:, 1], ddr * g + 2 * dr * f[:, 1] + r * f[:, 2]]
    )
    ramped = _eval(spec, t, build_up=build_up)
    np.testing.assert_allclose(ramped, expected, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(ramped[0], [start, 0.0, 0.0])  # starts at rest
    after = t >= build_up
    np.testing.assert_array_equal(ramped[after], _eval(spec, t[after]))  # the sine itself


def test_build_up_derivatives_match_differences():
    """Velocity and acceleration of a built-up table and sine against central differences of
    the value and velocity, through the whole build-up and across its end."""
    spec = schema.Sine(kind="sine", amplitude=2.0, period=3.0, phase=-1.0, offset=0.5)
    t = np.linspace(0.07, 6.97, 47)  # not on t = 5 s, where the third derivative jumps
    h = 1e-5
    at = _eval(spec, t, build_up=5.0)
    plus = _eval(spec, t + h, build_up=5.0)
    minus = _eval(spec, t - h, build_up=5.0)
    np.testing.assert_allclose(at[:, 1], (plus[:, 0] - minus[:, 0]) / (2 * h), atol=1e-8)
    np.testing.assert_allclose(at[:, 2], (plus[:, 1] - minus[:, 1]) / (2 * h), atol=1e-7)
    # continuous value, velocity and acceleration where the build-up ends (t = 5 s)
    edge = _eval(spec, [5.0 - 1e-9, 5.0], build_up=5.0)
    np.testing.assert_allclose(edge[0], edge[1], atol=1e-7)


def test_build_up_spares_steady_functions_and_constants():
    """A towing ship's distance (steady) keeps its speed from t = 0; a constant stays put."""
    distance = tfn.build(
        schema.AccelerationProfile(
            kind="acceleration_profile",
            initial_velocity=1.5,
            phases=[{"duration": 1.0, "acceleration": 0.0}],
        )
    )
    compiled = tfn.stack([tfn.steady(distance), distance, tfn.constant(7.0)], build_up=10.0)
    np.testing.assert_array_equal(compiled[4], [[0.0, 0.0], [10.0, 0.0], [10.0, 7.0]])
    np.testing.assert_allclose(evaluate(*compiled, 0, 0.0), [0.0, 1.5, 0.0])
    np.testing.assert_allclose(evaluate(*compiled, 1, 0.0), [0.0, 0.0, 0.0])
    np.testing.assert_allclose(evaluate(*compiled, 2, 3.0), [7.0, 0.0, 0.0])


@pytest.mark.parametrize(
    "cable",
    [
        {},  # rigid_links (planar)
        {"model": "rigid_segments_3d"},
        {"model": "lumped_mass", "axial_stiffness": 1.0e5},
    ],
    ids=["rigid_links", "rigid_segments_3d", "lumped_mass"],
)
def test_models_move_an_imposed_top_through_the_build_up(cable):
    """Every model that imposes a top motion follows the built-up function: the top node at
    every output is f(0) + r (f - f(0)) (the closed form), the sine itself after build_up."""
    sine = {"kind": "sine", "amplitude": 0.5, "period": 2.0, "phase": 0.3}
    simulation = {"duration": 2.0, "output_interval": 0.1, "build_up": 1.5, "time_step": 0.002}
    data = chain_case(n=6, top={"type": "imposed", "x": sine, "z": 0.0}, simulation=simulation,
                      **cable)  # fmt: skip
    results = run_rows(data)
    t = results["time"]
    f = 0.5 * np.sin(np.pi * t + 0.3)
    start = 0.5 * np.sin(0.3)
    expected = start + _RAMP(np.minimum(t / 1.5, 1.0)) * (f - start)
    np.testing.assert_allclose(results["node_x"][:, 0], expected, atol=1e-9)
    assert abs(expected[1] - start) < 0.01 * abs(f[1] - start)  # the ramp holds the top back


def test_towing_ship_keeps_its_speed_through_the_build_up():
    """A towing ship starts at its speed (its towed shape is the steady state): no build-up."""
    data = chain_case(
        n=6,
        model="rigid_segments_3d",
        top={"type": "towing_ship", "speed": 1.5},
        bottom={"type": "free", "body": {"mass": 20.0, "volume": 0.005}},
        initial={"shape": "static"},
        environment={"water_density": 1025.0},
        simulation={"duration": 1.0, "output_interval": 0.1, "build_up": 5.0},
    )
    x = run_rows(data)["node_x"][:, 0]
    np.testing.assert_allclose(np.diff(x) / 0.1, 1.5, rtol=1e-12)
