"""Trajectory following (Jacquot & Marichal, section 4): exact end force and stiffness servo."""

from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable.models import statics
from seacable.simulation import build_system

EXAMPLES = Path(__file__).parent.parent / "examples"


def _load(name, **servo):
    case = seacable.load_case(EXAMPLES / f"{name}.yaml")
    if servo:
        cable = case.cables[0]
        bottom = cable.bottom.model_copy(
            update={"servo": cable.bottom.servo.model_copy(update=servo)}
        )
        case = case.model_copy(update={"cables": [cable.model_copy(update={"bottom": bottom})]})
    return case


@pytest.fixture(scope="module")
def exact():
    return seacable.simulate(_load("jacquot_marichal_trajectory_exact")).dataset


@pytest.fixture(scope="module")
def servo():
    return seacable.simulate(_load("jacquot_marichal_trajectory_servo")).dataset


def _largest_displacement(ds):
    relative = np.stack([ds[f"target_{a}"].values - ds[f"node_{a}"].values[:, 0] for a in "xyz"])
    return np.max(np.linalg.norm(relative - relative[:, :1], axis=0))


def test_exact_method_follows_the_published_path(exact):
    error = exact["tracking_error"].values
    assert _largest_displacement(exact) > 50.0
    assert error.max() < 1e-4  # m; the paper's servo stays under 2.5 cm


def test_force_before_the_manoeuvre_is_the_static_end_force(exact):
    case = _load("jacquot_marichal_trajectory_exact")
    system = build_system(case)
    holding = statics.end_force(system.params, system.y0, [300.0, 0.0, -300.0])
    before = exact["time"].values < 10.0  # the manoeuvre starts at 10 s
    for k, a in enumerate("xyz"):
        np.testing.assert_allclose(exact[f"bottom_force_{a}"].values[before], -holding[k],
                                   rtol=1e-6, atol=1e-3)  # fmt: skip


def test_servo_tracks_and_agrees_with_the_exact_force(exact, servo):
    error = servo["tracking_error"].values
    assert 1e-3 < error.max() < 2.0  # m, over a 60 m excursion (see the note on a and b)
    assert np.max(servo["tracking_error"].values[servo["time"].values <= 10.0]) < 1e-6
    during = (servo["time"].values > 12) & (servo["time"].values < 50)
    force_exact = exact["bottom_force_x"].values[during]
    force_servo = servo["bottom_force_x"].values[during]
    assert np.max(np.abs(force_servo - force_exact)) < 0.15 * np.max(np.abs(force_exact))


def test_servo_error_shrinks_with_a_refreshed_stiffness(servo):
    refreshed = seacable.simulate(
        _load("jacquot_marichal_trajectory_servo", recompute_interval=5.0)
    )
    assert refreshed["tracking_error"].values.max() < 0.8 * servo["tracking_error"].values.max()


def test_lateral_excursion_needs_a_sideways_force():
    ds = seacable.simulate(_load("jacquot_marichal_trajectory_lateral")).dataset
    assert ds["tracking_error"].values.max() < 1e-4
    assert np.max(np.abs(ds["bottom_force_y"].values)) > 1000.0
    np.testing.assert_allclose(ds["node_y"].values[-1, -1], -30.0, atol=1e-4)


def test_trajectory_needs_the_static_start():
    data = {
        "cables": [
            {
                "model": "rigid_segments_3d",
                "links": 5,
                "length": 50.0,
                "diameter": 0.02,
                "mass_per_length": 1.0,
                "top": {"type": "fixed"},
                "bottom": {"type": "trajectory", "x": 10.0, "z": -20.0},
                "initial": {"shape": "arc", "top_angle_deg": 10.0},
            }
        ],
        "simulation": {"duration": 1.0, "output_interval": 0.5},
    }
    with pytest.raises(seacable.CaseError, match=r"trajectory starts .* m from the end .* static"):
        seacable.simulate(seacable.load_case(data))
