"""The 3D rigid-segment cable against MoorPy (an independent quasi-static catenary code) for a
line hanging between two points: static shape and a very slow dynamic motion, drag off."""

import math

import numpy as np
import pytest

from helpers import rows, upgraded

moorpy_catenary = pytest.importorskip("moorpy.Catenary").catenary

RHO = 1025.0
MASS = 20.0  # kg/m
DIAMETER = 0.1  # m
LENGTH = 130.0  # m
ANCHOR = (0.0, 0.0, -100.0)
WET = (MASS - RHO * math.pi * DIAMETER**2 / 4) * 9.81  # N/m


def _case(n, top=None, duration=1.0):
    """The cable as ``seacable upgrade`` writes it: a system of one line between two bodies."""
    return upgraded(
        {
            "environment": {"water_density": RHO},
            "cables": [
                {
                    "model": "rigid_segments_3d",
                    "links": n,
                    "length": LENGTH,
                    "diameter": DIAMETER,
                    "mass_per_length": MASS,
                    "drag_coefficient_normal": 0.0,
                    "added_mass_coefficient": 0.0,
                    "top": top or {"type": "fixed", "position": [60.0, 20.0, -10.0]},
                    "bottom": {"type": "pinned", "anchor": list(ANCHOR)},
                    "initial": {"shape": "static"},
                }
            ],
            "simulation": {
                "duration": duration,
                "output_interval": duration / 10,
                "time_step": 0.002,
            },  # fmt: skip
        }
    )


def _moorpy(top):
    span = math.hypot(top[0] - ANCHOR[0], top[1] - ANCHOR[1])
    rise = top[2] - ANCHOR[2]
    fa_h, fa_v, fb_h, fb_v, _ = moorpy_catenary(span, rise, LENGTH, 1e13, WET, CB=-1000.0)
    return np.array([fa_h, fa_v, fb_h, fb_v])


def _ours(ds, index=-1):
    bottom = np.array([ds[f"bottom_force_{a}"][index] for a in "xyz"])
    top = np.array([ds[f"top_force_{a}"][index] for a in "xyz"])
    # MoorPy: end A (anchor) and end B (fairlead) horizontal and vertical tension magnitudes
    return np.array([np.hypot(*bottom[:2]), abs(bottom[2]), np.hypot(*top[:2]), abs(top[2])])


def test_static_catenary_matches_moorpy_and_converges():
    expected = np.abs(_moorpy((60.0, 20.0, -10.0)))
    errors = []
    for n in (25, 50, 100):
        results = rows(_case(n))
        errors.append(np.max(np.abs(_ours(results) / expected - 1)))
    assert errors[-1] < 2e-4, errors
    assert errors[0] > errors[1] > errors[2]


def test_static_shape_passes_through_both_ends():
    start = rows(_case(60, duration=0.02))
    first = np.array([start[f"node_{a}"][0, 0] for a in "xyz"])
    last = np.array([start[f"node_{a}"][0, -1] for a in "xyz"])
    np.testing.assert_allclose(first, [60.0, 20.0, -10.0], atol=1e-8)
    np.testing.assert_allclose(last, ANCHOR, atol=1e-8)


@pytest.mark.slow  # 16 s; the system's lines against MoorPy: tests/test_system_moorpy.py
def test_slow_motion_is_quasi_static_like_moorpy():
    """The fairlead moves 10 m in x over 200 s (smooth start): the tensions follow MoorPy's
    static catenary at the instantaneous position."""
    motion = {
        "kind": "sine",
        "amplitude": -5.0,
        "angular_frequency": math.pi / 200.0,
        "phase": -math.pi / 2,
        "offset": 65.0,
    }  # x = 60 -> 70 m, zero initial velocity
    top = {"type": "imposed", "x": motion, "y": 20.0, "z": -10.0}
    results = rows(_case(60, top=top, duration=200.0))
    for index in (5, 10):
        x = results["node_x"][index, 0]
        expected = np.abs(_moorpy((x, 20.0, -10.0)))
        np.testing.assert_allclose(_ours(results, index), expected, rtol=3e-3)
