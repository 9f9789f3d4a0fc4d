"""What a run tells its user: which tolerance governed dopri5, a time step that does not divide
the output interval, divergence advice that names only options the model takes, the compile
notice, and the command line's -v showing seacable's own log only."""

import logging

import numpy as np
import pytest
import yaml
from click.testing import CliRunner

import seacable
from helpers import chain_case, system_data, upgraded
from seacable import simulation
from seacable.cli import main
from seacable.errors import CaseError
from seacable.kernels import jit
from seacable.system import model
from test_reproducible import _lumped_line, _rigid_chain


def _small_swing(**sim):
    """Five links in air released on a small arc (amplitude 0.017 rad): the results' attributes
    and the links' angles [rad]."""
    data = chain_case(
        n=5,
        initial={"shape": "arc", "top_angle_deg": 0.5},
        simulation={"duration": 4.0, "output_interval": 0.1, "integrator": "dopri5", **sim},
    )
    tree = seacable.simulate(upgraded(data)).dataset
    return tree.attrs, tree["lines/cable/angle"].values


def test_dopri5_default_atol_lets_rtol_set_the_accuracy_of_a_small_swing():
    """With atol fixed at 1e-8 (the old default) rtol 1e-7 gave 1.5e-6 of the amplitude; by
    default each state's error is measured against its own amplitude, so the error follows
    rtol and the results say the relative tolerance governed."""
    reference = _small_swing(rtol=1e-12, atol=1e-14)[1]
    amplitude = np.abs(reference).max()
    errors = {}
    for rtol in (1e-5, 1e-7):
        attrs, angle = _small_swing(rtol=rtol)
        errors[rtol] = np.abs(angle - reference).max() / amplitude
        assert attrs["solver_atol"] == simulation.DEFAULT_ATOL
        assert attrs["solver_tolerance_governing"].startswith("relative")
        assert attrs["solver_atol_smallest"] > 0.0
    assert errors[1e-7] < 1e-6, errors
    assert errors[1e-5] > 10.0 * errors[1e-7], errors
    attrs, _ = _small_swing(rtol=1e-7, atol=1e-8)
    assert attrs["solver_atol"] == 1e-8
    assert attrs["solver_tolerance_governing"].startswith("absolute")


def test_default_atol_floor_follows_each_state_scale():
    """The floor is rtol x 1e-3 x the model's scale: the line's length L for the position of
    the heaving top, 1 for its quaternion and the links' angles [rad], those times sqrt(g / L)
    for their rates (the top's three velocities, its three angular velocities, the four links'
    rates)."""
    sim = {"duration": 1.0, "output_interval": 0.1, "integrator": "dopri5", "rtol": 1e-6}
    heaving = {"type": "floating_structure", "mass": 20.0, "heave_stiffness": 300.0}
    case = upgraded(chain_case(n=4, simulation=sim, top=heaving))
    system = model.build(case)
    floor, magnitude = simulation.absolute_tolerance(case, model, system)
    omega = np.sqrt(9.81 / 10.0)
    expected = 1e-9 * np.array([10] * 3 + [1] * 8 + [10 * omega] * 3 + [omega] * 7)
    np.testing.assert_allclose(floor, expected, rtol=1e-12)
    np.testing.assert_array_equal(magnitude, np.abs(system.y0))


@pytest.mark.parametrize(
    ("step", "advice"),
    [
        (0.0125, r"0\.01 s \(1 per output\)"),
        (0.003, r"0\.00333333 s \(3 per output\) or 0\.0025 s"),
    ],
)
def test_time_step_not_dividing_the_output_interval_is_refused(step, advice):
    data = system_data(chain_case())
    data["simulation"] = {"duration": 1.0, "output_interval": 0.01, "time_step": step}
    with pytest.raises(
        CaseError,
        match=rf"simulation\.time_step: {step} s does not divide output_interval.*{advice}",
    ):
        seacable.load_case(data)


def test_time_step_within_one_percent_of_a_divisor_is_used_as_that_divisor():
    data = chain_case(simulation={"duration": 0.1, "output_interval": 0.01, "time_step": 0.00334})
    results = seacable.simulate(upgraded(data))
    assert results.dataset.attrs["solver_time_step"] == pytest.approx(0.01 / 3, rel=1e-15)


def _diverge(data):
    data["simulation"].update(max_newton_iterations=1, newton_tolerance=1e-15)
    with pytest.raises(seacable.SimulationDiverged) as raised:
        seacable.simulate(seacable.load_case(data))
    return str(raised.value)


def test_divergence_advice_names_only_options_the_model_takes():
    lumped = _diverge(_lumped_line("newmark", time_step=0.01))
    assert "joint damping" not in lumped and "joint_damping" not in lumped
    assert "axial_damping_ratio" in lumped
    rigid = _diverge(_rigid_chain("newmark", time_step=0.01))
    assert "joint_damping" in rigid and "axial_damping" not in rigid


def test_a_slow_compilation_is_announced(caplog, monkeypatch):
    monkeypatch.setattr(jit, "NOTICE_SECONDS", 0.0)
    case = seacable.load_case(_rigid_chain("rk4", time_step=0.002))
    with caplog.at_level(logging.INFO, logger="seacable"):
        seacable.simulate(case)
    notices = [r for r in caplog.records if "compiling the rk4 integrator" in r.getMessage()]
    assert len(notices) == 1 and notices[0].levelno == logging.INFO
    assert "first run only" in notices[0].getMessage() and " s)" in notices[0].getMessage()


def test_verbose_command_line_shows_seacable_debug_and_no_numba_debug(tmp_path):
    path = tmp_path / "case.yaml"
    path.write_text(yaml.safe_dump(_rigid_chain("rk4", time_step=0.002)))
    numba_log = logging.getLogger("numba.core.ssa")
    result = CliRunner().invoke(
        main, ["-v", "run", str(path), "-o", str(tmp_path / "out.nc"), "--no-progress"]
    )
    assert result.exit_code == 0, result.output
    assert "DEBUG: the rk4 integrator's steps and the outputs ready in" in result.stderr
    assert not numba_log.isEnabledFor(logging.DEBUG)
    assert not numba_log.isEnabledFor(logging.INFO)
    quiet = CliRunner().invoke(main, ["run", str(path), "-o", str(tmp_path / "out.nc"),
                                      "--no-progress"])  # fmt: skip
    assert quiet.exit_code == 0 and "DEBUG" not in quiet.stderr
