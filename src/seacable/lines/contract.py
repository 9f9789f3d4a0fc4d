"""The contract of a rigid line model, as a Protocol with its rules (``tests/test_contracts.py``
checks each model against it, rules included): ``lines.rigid_links`` (planar links, angles)
and ``lines.rigid_segments`` (3D segments, directors). ``system.rigid`` couples either to the
bodies through these functions alone (derivation: docs/rigid_segment_lines.md)."""

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
