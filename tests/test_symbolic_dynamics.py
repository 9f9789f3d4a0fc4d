"""The compiled O(n) dynamics against an independent sympy Euler-Lagrange derivation."""

import itertools

import numpy as np
import pytest
import sympy as sp

from seacable.case import schema
from seacable.kernels import planar_chain as pc
from seacable.models import planar_rigid_links
from symbolic_chain import SymbolicChain

TOPS = ("fixed", "imposed", "floating_structure")
BOTTOMS = ("free_end", "body", "tied_structure", "pinned")


def _case(n, top, bottom):
    tops = {
        "fixed": {"type": "fixed", "position": [1.0, -2.0]},
        "imposed": {
            "type": "imposed",
            "x": {"kind": "sine", "amplitude": 0.7, "period": 3.0, "phase": 0.3},
            "z": {"kind": "sine", "amplitude": 0.4, "angular_frequency": 1.3, "offset": -1.0},
        },
        "floating_structure": {
            "type": "floating_structure",
            # under water (the links point down from it): the derivation has no free surface
            "position": [0.0, -2.0],
            "mass": 30.0,
            "heave_stiffness": 400.0,
            "heave_damping": 20.0,
            "net_weight": 15.0,
            "force": {"kind": "sine", "amplitude": 50.0, "period": 2.0},
        },
    }
    bottoms = {
        "free_end": {"type": "free"},
        "body": {
            "type": "free",
            "body": {
                "mass": 3.0,
                "volume": 0.001,
                "added_mass": 0.5,
                "drag_coefficient": 0.8,
                "drag_area": 0.05,
                "force_x": {"kind": "sine", "amplitude": 5.0, "period": 1.7},
                "force_z": 2.0,
            },
        },
        "tied_structure": {
            "type": "floating_structure",
            "mass": 8.0,
            "heave_stiffness": 90.0,
            "heave_damping": 4.0,
            "surge_stiffness": 150.0,
            "surge_damping": 6.0,
            "force": {"kind": "sine", "amplitude": 3.0, "period": 2.5},
            "rest_position": [1.5, -3.0],
        },
        "pinned": {"type": "pinned"},
    }
    return schema.Case.model_validate(
        {
            "environment": {"current": {"profile": [[-1000.0, 0.1], [1000.0, 0.9]]}},
            "cables": [
                {
                    "links": n,
                    "length": 2.0 * n,
                    "diameter": 0.05,
                    "mass_per_length": 2.0,
                    "drag_coefficient_tangential": 0.3,
                    "top": tops[top],
                    "bottom": bottoms[bottom],
                    "initial": {"shape": "arc", "top_angle_deg": 10, "bottom_angle_deg": 40},
                }
            ],
            "simulation": {"duration": 1.0, "output_interval": 0.1},
        }
    )


def _sym_sine(spec, t):
    omega = spec.angular_frequency or 2 * np.pi / spec.period
    return spec.offset + spec.amplitude * sp.sin(omega * t + spec.phase)


def _randomise(p, rng):
    n = p.n
    return p._replace(
        length=rng.uniform(0.5, 2.0, n),
        mass=rng.uniform(0.5, 3.0, n),
        inertia=rng.uniform(0.05, 1.0, n),
        wet_weight=rng.uniform(-5.0, 20.0, n),
        drag_normal=rng.uniform(0.0, 2.0, n),
        drag_tangential=rng.uniform(0.0, 0.5, n),
        joint_stiffness=rng.uniform(0.0, 30.0, n),
        joint_damping=rng.uniform(0.0, 3.0, n),
        top_reference_angle=0.2,
    )


CONFIGS = [
    # four links (several seconds of symbolic algebra each) run with the slow tests; one to
    # three links already give every top and bottom interior joints
    pytest.param(n, top, bottom, marks=pytest.mark.slow) if n == 4 else (n, top, bottom)
    for n, top, bottom in itertools.product(range(1, 5), TOPS, BOTTOMS)
    # a pinned end needs at least one degree of freedom left
    if not (bottom == "pinned" and n + (top == "floating_structure") < 3)
]


@pytest.mark.parametrize("n,top,bottom", CONFIGS)
def test_accelerations_match_symbolic_euler_lagrange(n, top, bottom):
    rng = np.random.default_rng(1000 * n + 10 * TOPS.index(top) + BOTTOMS.index(bottom))
    case = _case(n, top, bottom)
    system = planar_rigid_links.build(case)
    p = _randomise(system.params, rng)
    t_sym = sp.Symbol("t")
    cable = case.cables[0]
    top_motion = None
    forces = {}
    if top == "fixed":
        top_motion = tuple(sp.Float(v) for v in cable.top.position)
    if top == "imposed":
        top_motion = (_sym_sine(cable.top.x, t_sym), _sym_sine(cable.top.z, t_sym))
    if top == "floating_structure":
        forces["top_force"] = _sym_sine(cable.top.force, t_sym)
    if bottom == "body":
        forces["body_fx"] = _sym_sine(cable.bottom.body.force_x, t_sym)
        forces["body_fz"] = cable.bottom.body.force_z.value
    if bottom == "tied_structure":
        forces["body_fz"] = _sym_sine(cable.bottom.force, t_sym)
    sym = SymbolicChain(p, top_motion=top_motion, forces=forces)
    w = pc.make_workspace(n)
    ydot = np.zeros(pc.state_size(n))
    for trial in range(3):
        t = rng.uniform(0.0, 5.0)
        q = np.concatenate([rng.uniform(-1.2, 1.2, n), rng.uniform(-0.5, 0.5, sym.nq - n)])
        if sym.heave:  # about the structure's rest elevation
            q[n] += p.top_rest_z
        v = rng.uniform(-1.5, 1.5, sym.nq)
        if sym.pinned:
            end = sym.end_position(t, q, v)
            p = p._replace(pin_x=float(end[0]), pin_z=float(end[1]))
            v = sym.consistent_velocity(t, q, v)
        expected = sym.accelerations(t, q, v)
        y = np.zeros(pc.state_size(n))
        y[:n] = q[:n]
        y[n + 1 : 2 * n + 1] = v[:n]
        if sym.heave:
            y[n] = q[n]
            y[2 * n + 1] = v[n]
        status = pc.rhs(t, y, p, w, ydot)
        assert status == pc.OK
        got = ydot[n + 1 : 2 * n + 1]
        if sym.heave:
            got = np.append(got, ydot[2 * n + 1])
        scale = np.max(np.abs(expected)) + 1e-300
        np.testing.assert_allclose(
            got, expected, rtol=0, atol=1e-9 * scale, err_msg=f"trial {trial}"
        )
