"""The contract of a force model (the ``external forces`` of a body), as Protocols with its
rules (``tests/test_contracts.py`` checks them, numerically). ``system.kernel`` reaches every
force model through one table (``ForceTable``: ``system.evaluation``'s ``add_all`` and
``state_rates``, compiled for the kinds a system holds); a model with states of its own is
also a ``StatefulForceModel``."""

from collections.abc import Callable
from typing import Any, Protocol, runtime_checkable


@runtime_checkable
class ForceTable(Protocol):
    """Every force model of every body from one flat table (``system.evaluation``): row f acts on
    body ``body[f]``, its kind ``kind[f]`` (``forces.kinds.ForceKind``), its floats from
    ``data[at[f]:]``, its time-function channels from ``first[f]``, its states from
    ``state[f]`` (-1: none). The rules every force model honours:

    1. Its schema class (``case.forces``) validates its inputs, and its ``pack`` turns them into
       one row of floats (and channels for time functions); nothing of it depends on how many
       bodies or forces a case has (compiled types stay the same).
    2. ``add_all``: it adds a force and its moment about the body's reference point, both in the
       earth frame, to the body's 6-vector (a force f at an arm r adds f and r x f:
       ``bodies.dynamics.add_force``); it reads only its row, the body's pose and twist, the
       time, the environment and its own states, and never allocates.
    3. A conservative model is minus the gradient of the potential the results report
       (``system.energy``): the virtual work of its force and moment along any small motion
       of the body is minus the change of that potential. Gravity and buoyancy exactly; the
       linear stiffness exactly in translation and to first order in rotation (its rotation
       vector of R R_eq^T is not the gradient of a potential at finite angles).
    4. A dissipative model (drag without current, linear damping with a positive semi-definite
       matrix) never does positive work: F . v + M . omega <= 0.
    5. A model with states (``table.STATEFUL``) follows ``StatefulForceModel``;
       ``state_rates`` gives their rates, ``state_count`` their number from its row.
    6. A new model is a ``ForceKind`` value with a branch in ``add_all`` (and in
       ``state_rates`` when it has states) and a schema class: the schema's models and the
       kinds are checked to match one to one.
    """

    add_all: Callable[..., Any]
    state_rates: Callable[..., Any]


@runtime_checkable
class StatefulForceModel(Protocol):
    """A force model with states of its own (the trajectory servo's force; radiation memory
    as a state space; a speed controller's integral; a steering gear's rudder angle):
    ``state_count(row)`` first-order states, read from its packed row (so that a model's
    states may vary in number from one row to the next: a state space's order), laid out
    after the velocities in the state vector (``system.assemble``: ``force_state``).

    1. ``pack`` (or ``pack_*``): its row (the parts computed once the system is built may
       start at zero).
    2. ``add``: its force and moment from its states (and its row, the body's pose and twist).
    3. ``rates``: the rates of its states; they vanish at the model's equilibrium (the servo's
       body on its target and moving with it; radiation's at rest with its states zero), so
       that a static start stays at rest.
    """

    state_count: Callable[..., int]
    add: Callable[..., Any]
    rates: Callable[..., Any]
