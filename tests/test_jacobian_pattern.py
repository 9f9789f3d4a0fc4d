"""The sparsity pattern of a moored body's Jacobian and its colouring: the pattern holds every
entry of the Jacobian, couples a line's nodes to the body at their own end only (before, the
nodes next to a fixed anchor were taken as coupled to the moored body too), and the colouring
reaches the fewest colours the pattern allows."""

from pathlib import Path

import numpy as np
import pytest
import yaml

import seacable
from helpers import dense_jacobian
from seacable.bodies import kinematics
from seacable.numerics import implicit_setup
from seacable.system import coordinates, kernel, model

EXAMPLE = Path(__file__).parent.parent / "examples" / "platform_three_catenary_lines.yaml"
SEGMENTS = 8


def _platform(bending=0.0):
    """The platform on three catenary lines, 8 segments each, the third line written from
    the platform to its anchor (both orientations of a line); ``bending``: the lines'
    bending stiffness [N m^2]."""
    raw = yaml.safe_load(EXAMPLE.read_text())
    for line in raw["lines"]:
        line["sections"][0]["segments"] = SEGMENTS
    for kind in raw["line_types"]:
        kind["bending_stiffness"] = bending
    third = raw["lines"][2]
    third["from"], third["to"] = third["to"], third["from"]
    return model.build(seacable.load_case(raw))


@pytest.mark.parametrize("bending, reach", [(0.0, 1), (2e5, 2)])
def test_moored_body_jacobian_lies_in_its_pattern_and_anchor_nodes_are_apart(bending, reach):
    """A line's node reaches its neighbours (its two segments' loads), and two nodes on
    either side where the line bends (the bending at a node moves its neighbours)."""
    system = _platform(bending)
    p = system.params
    jac = dense_jacobian(system, 1.0, 0.3, 2)
    pattern = model.jacobian_sparsity(system).toarray() != 0
    assert np.abs(jac).max() > 1.0
    assert np.abs(jac[~pattern]).max() == 0.0
    # the body's accelerations (its velocity rows come first) reach ``reach`` nodes at each
    # fairlead: 6 + 3 lines x reach nodes x 3 coordinates velocity columns, none at the anchors
    nq = int(p.n_q)
    body_rows = pattern[nq : nq + 6, nq : p.n_q + p.n_v]
    assert body_rows.any(axis=0).sum() == 6 + 3 * reach * 3
    # an interior node's accelerations reach the positions of the nodes within reach
    row, q0 = int(p.line_v[0]) + 9, int(p.line_q[0])  # interior node 3 of the first line
    middle = pattern[row, q0 : q0 + 3 * (SEGMENTS - 1)]
    assert middle.reshape(-1, 3).any(axis=1).sum() == 2 * reach + 1
    far = np.abs(jac[row : row + 3, q0 + 3 : q0 + 6]).max()  # node 1's position
    assert (far > 0.0) == (reach == 2)  # bending does couple nodes two apart


def test_colouring_reaches_the_clique_of_the_body_and_its_fairlead_nodes():
    """The 15 velocity columns the body's rows share (its own and its fairlead nodes') need a
    colour each; every other column fits among them (natural order needed 27 colours here, and
    42 for the moored barge's 40-segment chains, when each node was taken to reach two nodes
    on either side)."""
    system = _platform()
    p = system.params
    nq, nv = int(p.n_q), int(p.n_v)
    velocities = model.jacobian_sparsity(system).tocsr()[nq : nq + nv, nq : nq + nv]
    colours = coordinates.colour(velocities)
    assert colours.max() + 1 == 6 + 3 * 3
    for c in range(colours.max() + 1):  # no two columns of a colour share a row
        members = velocities[:, colours == c]
        assert np.asarray(abs(members).sum(axis=1)).max() <= 1


def test_newtons_matrix_keeps_the_force_models_loads_only_where_nothing_they_read_moved():
    """system.kernel._models_kept: a frozen residual (Newton's matrix) whose difference
    quotient moves only a line's nodes takes the force models' loads of the evaluation before
    it (shown by marking them); one that moves the body, or any residual not frozen, or one
    after an accepted step (after_step) evaluates them again, bitwise as a fresh workspace."""
    system = _platform()
    p, y = system.params, system.y0.copy()
    assert p.force_kind.shape[0] > 0
    frozen = implicit_setup.frozen(p)

    def after_law(state):
        w = kernel.make_work(p)
        kernel.rhs(2.0, state, p, w, np.zeros_like(state))
        return w

    def frozen_rhs(state, w):
        ydot = np.zeros_like(state)
        kernel.rhs(2.0, state, frozen, w, ydot)
        return ydot

    node = int(p.line_q[0]) + 3  # a line's second interior node, x
    moved = y.copy()
    moved[node] += 1e-6
    marked = after_law(y)
    marked.models[:, 0] += 1.0  # [N]: a mark only a kept load carries into the rates
    assert not np.array_equal(frozen_rhs(moved, marked), frozen_rhs(moved, after_law(y)))
    body = y.copy()
    body[int(p.body_q[np.flatnonzero(p.body_kind == kinematics.DYNAMIC)[0]])] += 1e-6
    marked = after_law(y)
    marked.models[:, 0] += 1.0
    np.testing.assert_array_equal(frozen_rhs(body, marked), frozen_rhs(body, after_law(y)))
    marked = after_law(y)
    marked.models[:, 0] += 1.0
    kernel.after_step(2.0, y, p, marked)
    np.testing.assert_array_equal(frozen_rhs(moved, marked), frozen_rhs(moved, after_law(y)))
    marked = after_law(y)
    marked.models[:, 0] += 1.0
    ydot, fresh = np.zeros_like(y), np.zeros_like(y)
    kernel.rhs(2.0, moved, p, marked, ydot)
    kernel.rhs(2.0, moved, p, after_law(y), fresh)
    np.testing.assert_array_equal(ydot, fresh)
