"""The compiled O(n) dynamics of a system's planar rigid-link line (between the bodies
``seacable upgrade`` writes for a single cable's ends) against an independent sympy
Euler-Lagrange derivation."""

import itertools
import math
from types import SimpleNamespace

import numpy as np
import pytest
import sympy as sp

from helpers import upgraded
from seacable.kernels.status import Status
from seacable.system import kernel, model
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
    return {
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


def _sym_sine(spec, t):
    omega = spec.get("angular_frequency") or 2 * np.pi / spec["period"]
    return spec.get("offset", 0.0) + spec["amplitude"] * sp.sin(omega * t + spec.get("phase", 0.0))


RHO, G = 1025.0, 9.81  # the environment's defaults


def _description(cable, n, rng):
    """The chain for the derivation: random links (the same go into the system's line), the
    ends from the single-cable case's values."""
    top, bottom = cable["top"], cable["bottom"]
    chain = SimpleNamespace(
        n=n, heave=top["type"] == "floating_structure", pinned=bottom["type"] == "pinned",
        top_x=0.0, top_mass=0.0, top_stiffness=0.0, top_damping=0.0, top_rest_z=0.0,
        top_net_weight=0.0, body_mass=0.0, body_wet_weight=0.0, body_drag=0.0, tie_kx=0.0,
        tie_kz=0.0, tie_cx=0.0, tie_cz=0.0, tie_x0=0.0, tie_z0=0.0,
        current_z=np.array([-1000.0, 1000.0]), current_u=np.array([0.1, 0.9]),
        length=rng.uniform(0.5, 2.0, n), mass=rng.uniform(0.5, 3.0, n),
        inertia=rng.uniform(0.05, 1.0, n), wet_weight=rng.uniform(-5.0, 20.0, n),
        drag_normal=rng.uniform(0.0, 2.0, n), drag_tangential=rng.uniform(0.0, 0.5, n),
        joint_stiffness=rng.uniform(0.0, 30.0, n), joint_damping=rng.uniform(0.0, 3.0, n),
        top_reference_angle=0.2,
    )  # fmt: skip
    if chain.heave:
        chain.top_x, chain.top_rest_z = top["position"]
        chain.top_mass, chain.top_stiffness = top["mass"], top["heave_stiffness"]
        chain.top_damping, chain.top_net_weight = top["heave_damping"], top["net_weight"]
    body = bottom.get("body")
    if body is not None:
        chain.body_mass = body["mass"] + body["added_mass"]
        chain.body_wet_weight = (body["mass"] - RHO * body["volume"]) * G
        chain.body_drag = 0.5 * RHO * body["drag_coefficient"] * body["drag_area"]
    if bottom["type"] == "floating_structure":  # its weight equals its buoyancy
        chain.body_mass = bottom["mass"]
        chain.tie_kx, chain.tie_kz = bottom["surge_stiffness"], bottom["heave_stiffness"]
        chain.tie_cx, chain.tie_cz = bottom["surge_damping"], bottom["heave_damping"]
        chain.tie_x0, chain.tie_z0 = bottom["rest_position"]
    return chain


def _with_links(p: kernel.SystemParams, chain) -> kernel.SystemParams:
    """The system's parameters with the line's links and first joint's reference of ``chain``
    (a planar line has no added mass: its inertia is its own)."""
    angle = chain.top_reference_angle
    return p._replace(
        rs_length=chain.length.copy(), rs_mass=chain.mass.copy(), rs_inertia=chain.inertia.copy(),
        rs_wet_weight=chain.wet_weight.copy(), rs_drag_normal=chain.drag_normal.copy(),
        rs_drag_tangential=chain.drag_tangential.copy(),
        rs_joint_stiffness=chain.joint_stiffness.copy(),
        rs_joint_damping=chain.joint_damping.copy(),
        rs_ref=np.array([[math.sin(angle), 0.0, -math.cos(angle)]]),
    )  # fmt: skip


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
    data = _case(n, top, bottom)
    cable = data["cables"][0]
    built = model.build(upgraded(data))
    chain = _description(cable, n, rng)
    p = _with_links(built.params, chain)
    assert not np.any(p.rs_added)
    t_sym = sp.Symbol("t")
    top_motion = None
    forces = {}
    if top == "fixed":
        top_motion = (sp.Float(cable["top"]["position"][0]), sp.Float(cable["top"]["position"][1]))
    if top == "imposed":
        top_motion = (_sym_sine(cable["top"]["x"], t_sym), _sym_sine(cable["top"]["z"], t_sym))
    if top == "floating_structure":
        forces["top_force"] = _sym_sine(cable["top"]["force"], t_sym)
    if bottom == "body":
        forces["body_fx"] = _sym_sine(cable["bottom"]["body"]["force_x"], t_sym)
        forces["body_fz"] = cable["bottom"]["body"]["force_z"]
    if bottom == "tied_structure":
        forces["body_fz"] = _sym_sine(cable["bottom"]["force"], t_sym)
    sym = SymbolicChain(chain, top_motion=top_motion, forces=forces)
    angles, rates = int(p.rs_q[0]), int(p.rs_v[0])
    heave, heave_rate = int(p.body_q[0]) + 2, int(p.body_v[0]) + 2  # the top's z
    w = model.workspace(built)
    ydot = np.zeros_like(built.y0)
    for trial in range(3):
        t = rng.uniform(0.0, 5.0)
        q = np.concatenate([rng.uniform(-1.2, 1.2, n), rng.uniform(-0.5, 0.5, sym.nq - n)])
        if sym.heave:  # about the structure's rest elevation
            q[n] += chain.top_rest_z
        v = rng.uniform(-1.5, 1.5, sym.nq)
        if sym.pinned:  # the anchor (the end's body, fixed) where the end is
            end = sym.end_position(t, q, v)
            pose = p.body_pose.copy()
            pose[1, [0, 2]] = end
            p = p._replace(body_pose=pose)
            v = sym.consistent_velocity(t, q, v)
        expected = sym.accelerations(t, q, v)
        y = built.y0.copy()
        y[angles : angles + n] = q[:n]
        y[rates : rates + n] = v[:n]
        if sym.heave:
            y[heave] = q[n]
            y[heave_rate] = v[n]
        assert kernel.rhs(t, y, p, w, ydot) == Status.OK
        got = ydot[rates : rates + n]
        if sym.heave:
            got = np.append(got, ydot[heave_rate])
        scale = np.max(np.abs(expected)) + 1e-300
        np.testing.assert_allclose(
            got, expected, rtol=0, atol=1e-9 * scale, err_msg=f"trial {trial}"
        )
