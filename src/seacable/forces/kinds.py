"""The force models a body's ``external forces`` list may hold, and how each is stored.

Contract of a force model (every module of this package follows it):

1. Its schema class (``case.system``) validates its inputs; its ``pack(spec, ...)`` turns them
   into one row of floats (``data``) and, for time functions, channels; nothing of it depends on
   how many bodies or forces a case has (flat arrays with offsets: compiled types stay the same).
2. Its compiled ``add(...)`` adds a force and a moment about the body's reference point, both in
   the earth frame, to the body's 6-vector; it reads only its row, the body's pose and twist,
   the time and the environment, and never allocates.
3. It is tested alone against a closed form (tests/test_system_forces.py).
4. A model with internal states (the servo's force; radiation memory next) declares how many
   in ``STATES``; they follow the velocities in the state vector (``SystemParams.force_state``:
   the first, -1 for none), first-order, with their rates from its compiled ``rates(...)``.
"""

from enum import IntEnum


class ForceKind(IntEnum):
    """The compiled code branches on these values."""

    GRAVITY = 0
    BUOYANCY = 1
    DRAG = 2
    APPLIED = 3
    LINEAR_STIFFNESS = 4
    LINEAR_DAMPING = 5
    SERVO = 6


GRAVITY = int(ForceKind.GRAVITY)
BUOYANCY = int(ForceKind.BUOYANCY)
DRAG = int(ForceKind.DRAG)
APPLIED = int(ForceKind.APPLIED)
LINEAR_STIFFNESS = int(ForceKind.LINEAR_STIFFNESS)
LINEAR_DAMPING = int(ForceKind.LINEAR_DAMPING)
SERVO = int(ForceKind.SERVO)
STATES = {SERVO: 3}  # states of the models that have some
