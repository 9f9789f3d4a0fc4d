"""Implicit steps of rigid-link and rigid-segment lines in systems (planar links and 3D
segments from a heaving body, to a free body tied to the earth, or held at both ends):
agreement with a tight adaptive reference, convergence orders and Newton's iteration count.
The cases are written in the single-cable form and converted by ``seacable upgrade``."""

import numpy as np
import pytest

import seacable
from helpers import chain_case
from seacable.case import legacy
from seacable.case.loader import load_single_cable

HEAVE_TOP = {
    "type": "floating_structure",
    "position": [0.0, 0.0],
    "mass": 500.0,
    "heave_stiffness": 2000.0,
    "heave_damping": 50.0,
    "force": {"kind": "sine", "amplitude": 300.0, "period": 2.0},
}
BODY = {
    "type": "free",
    "body": {"mass": 5.0, "volume": 0.001, "drag_coefficient": 1.0, "drag_area": 0.02},
    "tie": {"stiffness_x": 30.0, "damping_z": 5.0},
}


def _submerged(n, top, bottom, **simulation):
    # a pinned chain must not start straight (its closure would be singular): start it sagging
    bottom_angle = -40.0 if bottom["type"] == "pinned" else 50.0
    data = chain_case(
        n=n,
        top=top,
        bottom=bottom,
        initial={"shape": "arc", "top_angle_deg": 50.0, "bottom_angle_deg": bottom_angle},
        environment={"water_depth": 100.0, "current": {"velocity": 0.3}},
        simulation={"duration": 2.0, "output_interval": 0.05, **simulation},
        joint_stiffness=20.0,
        joint_damping=0.5,
        drag_coefficient_normal=1.2,
        drag_coefficient_tangential=0.02,
    )
    return data


CASES = {
    "heave top, free body": (HEAVE_TOP, BODY),
    "in air": ({"type": "fixed"}, {"type": "free", "body": {"mass": 5.0}}),
    "moving top, pinned end": (
        {"type": "imposed", "x": {"kind": "sine", "amplitude": 0.5, "period": 3.0}},
        {"type": "pinned"},
    ),
}


def _run(data):
    """The single-cable case ``data`` run as a system; the last line's end node (x, z) or
    (x, y, z) over time and the run's attributes."""
    system = legacy.upgrade(load_single_cable(data))
    ds = seacable.simulate(seacable.load_case(system)).dataset
    line = ds[f"lines/{system['lines'][-1]['name']}"]
    axes = "xyz" if "node_y" in line else "xz"
    return np.stack([line[f"node_{a}"].values[:, -1] for a in axes], axis=1), ds.attrs


@pytest.mark.parametrize("name", ["heave top, free body", "moving top, pinned end"])
def test_implicit_runs_agree_with_a_tight_adaptive_reference(name):
    top, bottom = CASES[name]
    ref, _ = _run(_submerged(20, top, bottom, integrator="dopri5", rtol=1e-10, atol=1e-10))
    for scheme in ("newmark", "generalized_alpha"):
        end, attrs = _run(_submerged(20, top, bottom, integrator=scheme, time_step=0.005))
        gap = np.max(np.linalg.norm(end - ref, axis=1))
        assert gap < 2e-3, (scheme, gap)  # metres, over a 10 m cable swinging 2 s
        # a good Newton matrix: a handful of iterations per step, few rebuilt matrices
        steps = attrs["solver_accepted_steps"]
        assert attrs["solver_linear_solves"] <= 5 * steps
        assert attrs["solver_jacobian_evaluations"] <= steps


def test_orders_of_implicit_euler_and_newmark_on_the_rigid_chain():
    top, bottom = CASES["heave top, free body"]

    def end_at(scheme, dt):
        data = _submerged(10, top, bottom, integrator=scheme, time_step=dt, duration=1.0)
        data["simulation"]["output_interval"] = 0.5
        data["simulation"]["newton_tolerance"] = 1e-12
        return _run(data)[0][-1]

    exact = _run(
        _submerged(10, top, bottom, integrator="dopri5", rtol=1e-11, atol=1e-11, duration=1.0)
    )[0][-1]
    for scheme, order in (("implicit_euler", 1.0), ("newmark", 2.0)):
        errors = [np.linalg.norm(end_at(scheme, dt) - exact) for dt in (0.01, 0.005, 0.0025)]
        rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
        assert np.all(rates > order - 0.25), (scheme, errors, rates)


# ---- the 3D chain ---------------------------------------------------------------------------
def _case_3d(n, top, bottom, **simulation):
    data = chain_case(
        n=n,
        top=top,
        bottom=bottom,
        initial={"shape": "arc", "top_angle_deg": 50.0, "bottom_angle_deg": -30.0},
        environment={
            "water_depth": 100.0,
            "current": {"velocity": 0.4, "direction_deg": 30.0},
        },
        simulation={"duration": 2.0, "output_interval": 0.05, **simulation},
        model="rigid_segments_3d",  # no joint stiffness: the lines meet at the point body
        drag_coefficient_normal=1.2,
        drag_coefficient_tangential=0.02,
        added_mass_coefficient=1.0,
        point_bodies=[{"node": n // 2, "mass": 0.5, "volume": 0.004, "drag_area": 0.03}],
    )
    return data


CASES_3D = {
    "heave top, free body": (
        {**HEAVE_TOP, "position": [0.0, 0.0, 0.0]},
        {
            "type": "free",
            "body": {"mass": 5.0, "volume": 0.001, "drag_coefficient": 1.0, "drag_area": 0.02},
            "tie": {"stiffness_x": 30.0, "stiffness_y": 10.0, "damping_z": 5.0},
        },
    ),
    "moving top, pinned end": (
        {"type": "imposed", "y": {"kind": "sine", "amplitude": 0.5, "period": 3.0}},
        {"type": "pinned"},
    ),
    "guided end": (
        {"type": "fixed"},
        {"type": "free", "body": {"mass": 2.0, "volume": 0.004}, "hold_axes": ["x", "y"]},
    ),
}


@pytest.mark.parametrize("name", CASES_3D)
def test_3d_implicit_runs_agree_with_a_tight_adaptive_reference(name):
    top, bottom = CASES_3D[name]
    ref, _ = _run(_case_3d(12, top, bottom, integrator="dopri5", rtol=1e-10, atol=1e-10))
    for scheme in ("newmark", "generalized_alpha"):
        end, attrs = _run(_case_3d(12, top, bottom, integrator=scheme, time_step=0.005))
        gap = np.max(np.linalg.norm(end - ref, axis=1))
        assert gap < 3e-3, (scheme, gap)
        steps = attrs["solver_accepted_steps"]
        assert attrs["solver_linear_solves"] <= 5 * steps
        assert attrs["solver_jacobian_evaluations"] <= steps
