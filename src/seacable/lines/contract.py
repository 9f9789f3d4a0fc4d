"""The contracts of the line models, each a Protocol with its rules (``tests/test_contracts.py``
checks every model against its contract, rules included, numerically):

- ``RigidLineModel``: ``lines.rigid_links`` (planar links, angles) and ``lines.rigid_segments``
  (3D segments, directors); ``system.rigid`` couples either to the bodies through these
  functions alone (derivation: docs/rigid_segment_lines.md);
- ``LumpedLineModel``: ``lines.lumped_mass``, reached by ``system.kernel``;
- ``NaturalStringModel``: ``lines.natural_string``, reached by ``system.kernel``.

A new line model of one of these kinds provides the same functions under the same rules; a new
kind of line writes its contract here."""

from collections.abc import Callable
from typing import Any, Protocol, runtime_checkable


@runtime_checkable
class RigidLineModel(Protocol):
    """What ``system.rigid`` reaches of a rigid line model (a module of compiled functions on
    one line's workspace ``w``, (rows, n + 1), filled by the model's loads for the state).

    1. ``backward``: the backward sweep from the tip's articulated inertia, bias and reaction
       map (the identity on a held tip) to node 0's, every node's rows stored; node 0's are
       what the base body receives.
    2. ``tip_map``: the tip's acceleration as an affine map A_n = ac + ga A_0 + al L of node
       0's acceleration A_0 and of the holding force L on the tip, exactly as ``forward``
       computes it (the closures rely on it).
    3. ``closure``: the holding force L = l0 + la A_0 that gives a held tip its target's
       acceleration (Baumgarte-stabilised) on the held axes, zero on the free ones; False when
       singular (the line pulled straight between held ends).
    4. ``forward``: from A_0 (and L on a held tip), every node's acceleration and the line's
       rates into ``ydot``.
    5. ``node_force``: the force the part above node k exerts on node k and below it.
    6. ``march`` and ``moment_balance`` (statics): at rest, each segment turned along the pull
       it carries; each segment's moment balance, zero when it is in balance.
    """

    backward: Callable[..., Any]
    tip_map: Callable[..., Any]
    closure: Callable[..., Any]
    forward: Callable[..., Any]
    node_force: Callable[..., Any]
    march: Callable[..., Any]
    moment_balance: Callable[..., Any]


@runtime_checkable
class LumpedLineModel(Protocol):
    """What ``system.kernel`` reaches of the lumped-mass line model (a module of compiled
    functions; a line of n segments has nodes 0..n in the columns c0..c0 + n of the shared
    workspace ``w.nodes``; its n - 1 interior nodes are states, its two end nodes are not).

    1. ``gather``: the line's nodes as ``[r_0 .. r_n, v_0 .. v_n]``: the end nodes are the points
       ``from`` and ``to`` (position and velocity), the interior ones the state.
    2. ``loads``: every load on every node, ends included, from those nodes alone (axial
       tension and damping, drag and the added mass of the relative flow, apparent weight,
       bending, seabed): an end node's loads are computed as an interior node's would be.
    3. ``interior_rates``: each interior node's position rate is its velocity and its
       acceleration M_j^-1 F_j, M_j its 3x3 mass (its share of the segments' mass, the added
       mass normal to them) and F_j its loads; False when an M_j is singular.
    4. ``end_mass_force``: an end node's M and F, the same M and F that rule 3 solves at an
       interior node. The body carrying the end node adds them to its own (its point moves
       rigidly with it: ``bodies.dynamics.add_point_mass``), as MoorDyn's coupled points do, so
       the body and the node move as one rigid whole: no spring couples them.
    5. Nothing allocates; every array is flat with offsets, so that compiled types depend on no
       count of lines or nodes.
    """

    gather: Callable[..., Any]
    loads: Callable[..., Any]
    interior_rates: Callable[..., Any]
    end_mass_force: Callable[..., Any]


@runtime_checkable
class NaturalStringModel(Protocol):
    """What ``system.kernel`` reaches of the natural-variables string model (Poth 2002;
    ``kernels.natural``): a planar string from a fixed pivot carrying a point body at its end,
    its node variables (strain and tangent) in the system's positions and their rates in its
    velocities.

    1. ``line_params``: the kernel's parameters of one string from the system's flat ``nat_*``
       arrays and the end body's mass (scalars only; 0: the string alone).
    2. ``gather``: the string's variables and rates, in the kernel's layout, from the state.
    3. ``rates``: the rates of every node variable into the system's ``ydot``; at a static
       balance (hanging still, each node's strain the weight below it over EA) they vanish.
    4. ``carry``: the end body has no state of its own: its position and velocity are the
       pivot's plus the trapezoidal integral of the tangent field (1 + eps) t over the
       string (its rate for the velocity), in the pivot's x-z plane.
    5. ``own``: the string's own outputs and energies (its end body's counted with the bodies).
    """

    line_params: Callable[..., Any]
    gather: Callable[..., Any]
    rates: Callable[..., Any]
    carry: Callable[..., Any]
    own: Callable[..., Any]
