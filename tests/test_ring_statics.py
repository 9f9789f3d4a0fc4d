"""Statics of a coupled ring of buoys (issue 14): 4 subsurface buoys, each moored by a chain leg
lying partly on the seabed and joined to its neighbours by sagging wires (8 lumped-mass lines),
the small members of ``benchmarks/system_scaling.py``'s family. Newton over the buoys' degrees
of freedom with every line at its static shape (``system.nested``) must find the balance, and
independent checks must agree with it: the force on every buoy recomputed from its lines' end
loads and its own weight and buoyancy, and a damped dynamic run from the case's start that
settles where the statics puts the buoys. Before the nested Newton had its condensed Jacobian
by central differences, the statics failed on this ring at 50 segments per line."""

import sys
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable.system import coordinates, nested, statics
from seacable.system import model as system_model
from seacable.system.assemble import build as assemble
from seacable.system.initial import initial_state

sys.path.insert(0, str(Path(__file__).parent.parent / "benchmarks"))
from system_scaling import system  # noqa: E402

RHO = 1025.0  # [kg/m^3] the case's water density (seacable's default)
EXAMPLES = Path(__file__).parent.parent / "examples"


def _ring(segments: int, **kwargs) -> dict:
    case = system(8, buoys=4, segments=segments, **kwargs)
    # no seabed friction: at rest it is zero (the statics ignores it), but in the damped run
    # regularised Coulomb friction holds the lying chain where it stops, not at the balance
    case["environment"]["seabed"]["friction_coefficient"] = 0.0
    return case


def _buoys(built, y) -> dict[str, np.ndarray]:
    p = built.params
    return {body.name: y[p.body_q[b] : p.body_q[b] + 3].copy()
            for b, body in enumerate(built.case.bodies) if body.type == "point"}  # fmt: skip


def _balanced(segments: int):
    """The ring's statics, every buoy's force from its lines' end loads checked to 1e-7 of its
    net buoyancy; its buoys' positions."""
    built = system_model.build(seacable.load_case(_ring(segments, start="static")))
    given = system_model.build(seacable.load_case(_ring(segments)))
    balanced, start = _buoys(built, built.y0), _buoys(given, given.y0)
    assert max(np.abs(balanced[k] - start[k]).max() for k in start) > 1.0  # it had to move
    loads = statics.line_loads(built, built.y0, at_rest=True)
    g = built.params.gravity
    for b, body in enumerate(built.case.bodies):
        if body.type == "point":
            net = (RHO * body.volume - body.mass) * g
            force = loads[b, :3] + np.array([0.0, 0.0, net])
            assert np.abs(force).max() < 1e-7 * net, (body.name, force)
    return balanced


def test_ring_statics_balances_every_buoy_with_stiff_short_segments():
    _balanced(50)  # 2.6 m wire segments at EA 2e8 N: failed before


def test_a_damped_run_of_the_ring_settles_on_its_statics():
    balanced = _balanced(20)
    duration = 100.0  # from 6 m out of balance, critically damped
    case = _ring(20, damping=5.0e3, duration=duration)
    case["simulation"].update(integrator="generalized_alpha", time_step=0.01)
    tree = seacable.simulate(seacable.load_case(case)).dataset
    for name, position in balanced.items():
        end = np.array([tree[f"bodies/{name}/position_{a}"].values[-1] for a in "xyz"])
        assert np.abs(end - position).max() < 1e-3, (name, end, position)


@pytest.mark.parametrize("source", ["ring", "platform_three_catenary_lines.yaml",
                                    "two_buoys_moored_with_hawser.yaml"])  # fmt: skip
def test_nested_jacobian_matches_central_differences_over_every_column(source):
    """The nested Newton's Jacobian (nodes in colours along every line at once, each line
    end's load read apart; bodies in groups) against plain central differences coloured by
    the system's whole sparsity pattern: a ring, a 6-DOF platform (moments through the arms)
    and two buoys joined by a hawser (a tie)."""
    case = seacable.load_case(_ring(20) if source == "ring" else EXAMPLES / source)
    y, p = initial_state(assemble(case, None))
    p = p._replace(slack_allowed=0)
    coords = coordinates.coordinates(p)
    forces = nested.BodyForces(p, coords)
    r0 = forces(y)
    structure = coordinates.pattern(p, coords)
    colours = coordinates.colour(structure)
    plain = coordinates.fd_jacobian(forces, y, coords, structure, colours, r0, central=True)
    split = nested.jacobian(forces, y)
    # the plain colouring needs more evaluations than the nested one's node colours
    assert colours.max() + 1 > 3 * (2 * nested.reach(p) + 1)
    a, b = split.toarray(), plain.toarray()
    scale = np.abs(b).max(axis=1, keepdims=True)
    assert np.abs(a - b).max(initial=0.0) <= 1e-9 * scale.max()
    assert (np.abs(a - b) / np.maximum(scale, 1e-300)).max() < 1e-9
