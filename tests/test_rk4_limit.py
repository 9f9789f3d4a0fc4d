"""rk4's stability limit: the fastest motions of a system (``system.frequency``) against a
closed form, the scheme's limit (``numerics.stability``) against its stability function, and
the check that refuses a step beyond it against runs on either side of the limit."""

import math
import re

import numpy as np
import pytest

import seacable
import seacable.simulation  # seacable.simulation.prepare below (a lazy attribute otherwise)
from seacable.case.loader import load_case
from seacable.numerics import stability
from seacable.system import frequency, model

MOORING = "examples/catenary_mooring_line_surge.yaml"
N, L0, EA, MU = 10, 10.0, 1e6, 2.0  # the taut rope: segments, length [m], EA [N], [kg/m]


def _taut_rope(**simulation):
    return {
        "name": "taut rope",
        "start": "as_given",
        "environment": {"in_air": True},
        "bodies": [
            {"name": "a", "type": "fixed", "position": [0.0, 0.0, 0.0]},
            {"name": "b", "type": "fixed", "position": [1.01 * L0, 0.0, 0.0]},
        ],
        "line_types": [
            {"name": "rope", "diameter": 0.02, "mass_per_length": MU, "axial_stiffness": EA}
        ],  # fmt: skip
        "lines": [
            {
                "name": "rope",
                "model": "lumped_mass",
                "from": "a",
                "to": "b",
                "sections": [{"type": "rope", "length": L0, "segments": N}],
            }
        ],  # fmt: skip
        "simulation": {"duration": 1.0, "output_interval": 0.01, **simulation},
    }


def test_the_scheme_limit_is_that_of_its_stability_function():
    """An undamped oscillation is stable to omega h = 2 sqrt 2, a damped decay to h lambda =
    2.785 (the real root of |R| = 1), a real growth that the physics makes is never refused,
    and the limit for several modes is the shortest."""
    assert stability.rk4_stable_step([10j]) == pytest.approx(2 * math.sqrt(2) / 10, rel=1e-3)
    assert stability.rk4_stable_step([-10.0]) == pytest.approx(0.2785293, rel=1e-3)
    assert stability.rk4_stable_step([5.0, 0.0]) == math.inf
    assert stability.rk4_stable_step([-1.0, 100j, 3.0]) == pytest.approx(0.0282843, rel=1e-3)
    # a spiral the physics makes grow: rk4's error amplifies it a little more at any step, not
    # a reason to refuse small steps (the limit counts growth beyond GROWTH a step)
    assert stability.rk4_stable_step([1.0 + 1.0j]) > 0.5
    z = 2.7853 * -1.0
    assert abs(stability.rk4_factor(np.array([z]))[0]) == pytest.approx(1.0, abs=1e-3)


def test_the_fastest_motion_of_a_taut_rope_is_its_highest_axial_mode():
    """N - 1 masses mu l between N springs EA / l held at both ends: omega_max =
    2 sqrt(EA / (mu l^2)) sin((N - 1) pi / (2 N)), the dense Jacobian's and ARPACK's alike."""
    built = model.build(load_case(_taut_rope()))
    segment = L0 / N
    closed = 2.0 * math.sqrt(EA / (MU * segment**2)) * math.sin((N - 1) * math.pi / (2 * N))
    dense = frequency.fastest_modes(built)
    assert abs(dense.values[0].imag) == pytest.approx(closed, rel=1e-5)
    assert abs(dense.values[0].real) < 1e-6 * closed  # no damping
    assert dense.what.startswith("node ") and dense.what.endswith("of line 'rope'")
    frequency.DENSE_UP_TO, kept = 0, frequency.DENSE_UP_TO
    try:
        arnoldi = frequency.fastest_modes(built)
    finally:
        frequency.DENSE_UP_TO = kept
    assert abs(arnoldi.values[0]) == pytest.approx(abs(dense.values[0]), rel=1e-6)
    limit = stability.rk4_limit(built)
    assert limit.step == pytest.approx(2 * math.sqrt(2) / closed, rel=1e-3)


def test_a_slack_rope_shows_the_axial_waves_it_has_once_taut():
    """The rope started straight between ends 0.9 of its length apart: every segment slack,
    without axial stiffness in the physical law; the linearisation takes them as taut, and
    finds the taut rope's highest axial mode (before, a slack start gave no fast motion, and
    the check accepted any step)."""
    data = _taut_rope()
    data["bodies"][1]["position"] = [0.9 * L0, 0.0, 0.0]
    data["lines"][0]["initial"] = "straight"
    segment = L0 / N
    closed = 2.0 * math.sqrt(EA / (MU * segment**2)) * math.sin((N - 1) * math.pi / (2 * N))
    limit = stability.rk4_limit(model.build(load_case(data)))
    assert limit.frequency == pytest.approx(closed, rel=1e-6)


def _mooring(**simulation):
    case = seacable.load_case(MOORING)
    return case.model_copy(
        update={"simulation": case.simulation.model_copy(update={"duration": 20.0, **simulation})}
    )


def test_a_step_beyond_the_limit_is_refused_with_the_limit_and_a_step_to_use():
    """The mooring example's chain (axial waves near 686 rad/s) at rk4's 0.01 s: refused before
    the run, naming the limit, the node that moves, a step that divides the output interval,
    the adaptive integrator and the way to go ahead."""
    case = _mooring(integrator="rk4", time_step=0.01)
    with pytest.raises(seacable.CaseError) as info:
        seacable.simulation.prepare(case)
    message = str(info.value)
    assert message.startswith("simulation.time_step: 0.01 s is beyond rk4's stability limit")
    assert re.search(r"\(685\.\d rad/s, moving node \d+ of line .chain. most\)", message)
    assert "unstable above time_step 0.00392 s" in message
    assert "Use time_step 0.002326 s or less" in message  # 0.1 s / 43, 0.6 of the limit
    assert "integrator: dopri5" in message and "allow_unstable_step: true" in message


def test_the_limit_is_sharp_and_a_run_allowed_beyond_it_is_warned(caplog):
    """The refusal guards against what rk4 does beyond the limit: the mooring example at 98 %
    of the limit gives dopri5's largest tension (to 1e-4); at 106 %, allowed, the run
    finishes 'complete' with a largest tension more than twice too large."""
    ds = seacable.simulate(_mooring()).dataset
    reference = float(ds["lines/chain/tension"].max())
    limit = stability.rk4_limit(model.build(_mooring())).step
    below, above = 0.1 / 26, 0.1 / 24  # steps that divide the output interval, 0.1 s
    assert below / limit == pytest.approx(0.982, abs=1e-3)
    assert above / limit == pytest.approx(1.064, abs=1e-3)
    near = seacable.simulate(_mooring(integrator="rk4", time_step=below)).dataset
    assert float(near["lines/chain/tension"].max()) == pytest.approx(reference, rel=1e-4)
    assert "close to rk4's stability limit" in caplog.text
    far = seacable.simulate(_mooring(integrator="rk4", time_step=above, allow_unstable_step=True))
    assert far.status == "complete"
    assert float(far.dataset["lines/chain/tension"].max()) > 2.0 * reference
    assert "is beyond rk4's stability limit" in caplog.text


def test_a_step_taken_as_the_divisor_of_the_output_interval_is_reported():
    """The schema takes a fixed step within 1 % above a divisor of the output interval as that
    divisor: the run says so."""
    data = load_case(MOORING).model_dump(mode="json", by_alias=True, exclude_unset=True)
    data["simulation"].update(integrator="rk4", time_step=0.002002)
    _, warnings = seacable.simulation.prepare(load_case(data))
    assert (
        "simulation.time_step 0.002002 s is taken as 0.002 s, the step that divides "
        "output_interval (0.1 s, 50 per output)" in warnings
    )


@pytest.mark.parametrize("segments", [1, 2, 10, 40])
def test_the_axial_bound_read_off_the_case_lies_below_the_fastest_motion(segments):
    """``stability.axial_bound`` (what refuses a dopri5 run of 100,000 segments before its
    300 s of statics) is a lower bound of the fastest motion that the built system's
    eigenvalues give (Arnoldi, ``system.frequency``): the catenary chain in water (added mass,
    axial damping, seabed) and the taut rope in air, within a factor 8 (a line of one segment
    has none); and dopri5's steps on
    the chain are at least the duration over the step the bound allows."""
    import yaml

    root = __import__("pathlib").Path(__file__).parent.parent
    chain = yaml.safe_load((root / MOORING).read_text())
    for data in (chain, _taut_rope()):
        data["lines"][0]["sections"][0]["segments"] = segments
        case = load_case(data)
        bound = stability.axial_bound(case)
        if segments == 1:  # no node inside: nothing to bound
            assert bound is None
            continue
        fastest = frequency.fastest_frequency(model.build(case))[0]
        assert bound is not None and bound.frequency <= fastest < 8.0 * bound.frequency
    if segments == 40:
        case = load_case({**chain, "simulation": {**chain["simulation"], "duration": 2.0}})
        run = seacable.simulate(case)
        least = 2.0 * stability.axial_bound(case).frequency / stability.DOPRI5_REACH
        assert run.dataset.attrs["solver_accepted_steps"] >= least


def test_a_step_certainly_beyond_the_limit_of_a_large_system_is_refused_before_its_statics(
    monkeypatch,
):
    """The mooring example's chain in 2,000 segments at rk4's 0.002 s: the lines' axial bound
    (``stability.axial_bound``: 6,470 rad/s or faster) makes that step unstable whatever the
    statics find, so the case is refused before the build (which would raise here); the same
    chain in 40 segments is left to the exact check after the build."""
    import yaml

    from seacable import simulation

    root = __import__("pathlib").Path(__file__).parent.parent
    chain = yaml.safe_load((root / MOORING).read_text())
    chain["lines"][0]["sections"][0]["segments"] = 2000
    chain["simulation"] = {"duration": 1.0, "output_interval": 0.1, "integrator": "rk4",
                           "time_step": 0.002}  # fmt: skip

    def not_built(*args, **kwargs):
        raise AssertionError("built")

    monkeypatch.setattr(simulation.system_model, "build", not_built)
    with pytest.raises(seacable.CaseError) as info:
        simulation.prepare(load_case(chain))
    message = str(info.value)
    assert message.startswith("simulation.time_step: 0.002 s is beyond rk4's stability limit")
    assert "line 'chain' (sections[0]: segments of 0.125 m" in message
    assert "rad/s or faster" in message and "allow_unstable_step: true" in message
    chain["lines"][0]["sections"][0]["segments"] = 40
    with pytest.raises(AssertionError, match="built"):
        simulation.prepare(load_case(chain))
