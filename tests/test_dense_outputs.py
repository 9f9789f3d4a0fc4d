"""An implicit scheme's step of several output intervals (numerics.dense): the outputs inside a
step interpolated from its two ends, those at its ends the steps' own states."""

import math

import numpy as np
import pytest
from numba import njit

import seacable
from helpers import turning_body_case
from seacable.errors import CaseError
from seacable.numerics import dense


@njit
def _between(y0, y1, s, h, q_of_v, quat_q, quat_v, nq, out):
    dense.between(y0, y1, s, h, q_of_v, quat_q, quat_v, nq, out)


def _quaternion(axis, angle):
    return np.r_[math.cos(angle / 2), math.sin(angle / 2) * np.asarray(axis)]


def _product(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    ])  # fmt: skip


def test_interpolation_is_exact_on_cubic_motion_and_steady_turning():
    """State [x (3), q (4), v (3), omega (3), s]: positions on cubics of time and a body
    turning at a steady rate about a fixed axis (earth frame, q = exp(omega t / 2) q0) come
    back exactly inside the step, velocities too; a force model's state linearly."""
    rng = np.random.default_rng(4)
    c = rng.normal(size=(4, 3))  # x(t) = c0 + c1 t + c2 t^2 + c3 t^3
    axis = np.array([1.0, -2.0, 0.5]) / np.linalg.norm([1.0, -2.0, 0.5])
    rate = 0.7  # rad/s
    q0 = _quaternion([0.0, 0.6, 0.8], 0.4)

    def state(t):
        x = c[0] + c[1] * t + c[2] * t**2 + c[3] * t**3
        v = c[1] + 2 * c[2] * t + 3 * c[3] * t**2
        q = _product(_quaternion(axis, rate * t), q0)
        return np.r_[x, q, v, rate * axis, 10.0 + 4.0 * t]

    t0, h = 1.3, 0.4
    q_of_v = np.array([0, 1, 2, -1, -1, -1])
    quat_q, quat_v = np.array([3]), np.array([3])
    out = np.empty(14)
    for s in (0.25, 0.5, 2 / 3):
        _between(state(t0), state(t0 + h), s, h, q_of_v, quat_q, quat_v, 7, out)
        np.testing.assert_allclose(out, state(t0 + s * h), rtol=0, atol=1e-13)


def _platform_case(**simulation):
    """examples/platform_three_catenary_lines.yaml with 10 segments a line, its wind load
    brought on over 10 s (the platform drifts, heels and turns), 18 s of it."""
    case = seacable.load_case("examples/platform_three_catenary_lines.yaml")
    data = case.model_dump(mode="json", by_alias=True, exclude_unset=True)
    for line in data["lines"]:
        line["sections"][0]["segments"] = 10
    for force in data["bodies"][3]["external forces"]:
        if force["model"] == "applied":
            force["force_x"]["end_time"] = 10.0
    data["simulation"] = {"duration": 18.0, "integrator": "generalized_alpha"} | simulation
    return seacable.load_case(data)


def _platform(**simulation):
    return seacable.simulate(_platform_case(**simulation)).dataset


VARIABLES = ("bodies/platform/position_x", "bodies/platform/pitch",
             "bodies/platform/angular_velocity_y", "bodies/platform/velocity_x",
             "lines/line_1/from_force_x", "lines/line_2/tension")  # fmt: skip


def _values(ds, name):
    return np.asarray(ds[name].values)


def test_long_steps_end_on_their_own_states_and_interpolate_between():
    """A moored platform heeling under wind (``_platform``) at steps of three output intervals:
    the rows at the steps' ends are, bit for bit, those of the run whose output interval is
    the step; the rows between them come within a few times the steps' own error of a run
    ten times finer, and no larger than the steps' ends are off."""
    # times exact in binary: the steps' ends are the same numbers in both runs
    long = _platform(time_step=0.375, output_interval=0.125)
    coarse = _platform(time_step=0.375, output_interval=0.375)
    fine = _platform(time_step=0.025, output_interval=0.125)
    assert len(long["time"]) == 145 and long.attrs["solver_accepted_steps"] == 48
    assert long.attrs["solver_time_step"] == 0.375
    np.testing.assert_array_equal(long["time"].values[::3], coarse["time"].values)
    for node in long.subtree:
        other = coarse if node.is_root else coarse[node.path]
        for name in node.data_vars:
            if "time" in node[name].dims:
                np.testing.assert_array_equal(node[name].values[::3], other[name].values, name)
    for name in VARIABLES:
        off = np.abs(_values(long, name) - _values(fine, name))
        ends, inside = off[::3].max(), np.delete(off, np.s_[::3]).max()
        assert 0.0 < inside <= 2.0 * ends, (name, inside, ends)  # measured: 1.0 to 1.5 times


def test_long_steps_past_the_end_and_in_any_chunks():
    """A duration that is not a whole number of steps: the last step runs past it and its rows
    beyond are dropped; the rows do not depend on the chunks (tests/test_reproducible.py)."""
    case = _platform_case(duration=2.0, output_interval=0.1, time_step=0.3)
    runs = [seacable.simulate(case, chunk_outputs=c).dataset for c in (1, 7, None, 10**9)]
    assert len(runs[0]["time"]) == 21 and runs[0]["time"].values[-1] == pytest.approx(2.0)
    assert runs[0].attrs["solver_accepted_steps"] == 7
    for other in runs[1:]:
        for name in VARIABLES:
            np.testing.assert_array_equal(_values(other, name), _values(runs[0], name))


@pytest.mark.parametrize(
    ("integrator", "step", "message"),
    [
        ("generalized_alpha", 0.25, r"0\.25 s is not a whole number of output intervals "
         r"\(0\.1 s\): use time_step 0\.2 or 0\.3 s"),
        ("rk4", 0.2, r"0\.2 s does not divide output_interval \(0\.1 s\).*an implicit "
         r"integrator's step may span whole output intervals"),
    ],
)  # fmt: skip
def test_a_step_of_no_whole_number_of_outputs_is_refused(integrator, step, message):
    data = turning_body_case({"duration": 1.0, "output_interval": 0.1, "integrator": integrator,
                              "time_step": step})  # fmt: skip
    with pytest.raises(CaseError, match=rf"simulation\.time_step: {message}"):
        seacable.load_case(data)
