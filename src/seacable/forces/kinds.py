"""The force models a body's ``external forces`` list may hold, and how each is stored.

The contract every force model follows is ``forces.contract`` (``ForceTable``,
``StatefulForceModel``): a row of floats per model, a force and moment about the body's
reference point in the earth frame, its potential or its dissipation, its states.
"""

from enum import IntEnum


class ForceKind(IntEnum):
    """The compiled code branches on these values; a kind's name is its ``model:`` in capitals
    with spaces and hyphens as underscores (``kind_of``)."""

    GRAVITY = 0
    BUOYANCY = 1
    DRAG = 2
    APPLIED = 3
    LINEAR_STIFFNESS = 4
    LINEAR_DAMPING = 5
    SERVO = 6
    NON_LINEAR_HYDROSTATIC = 7
    QUADRATIC_DAMPING = 8
    NON_LINEAR_FROUDE_KRYLOV = 9
    RADIATION_DAMPING = 10
    DIFFRACTION = 11
    THRUSTER = 12
    RUDDER = 13
    WIND = 14
    CURRENT = 15
    SHORT_WING = 16
    CROSS_FLOW = 17
    COMPENSATOR = 18
    WAVE_DRIFT = 19
    FLUID_INERTIA = 20
    ROD = 21
    PROPELLER = 22
    FIN = 23


GRAVITY = int(ForceKind.GRAVITY)
BUOYANCY = int(ForceKind.BUOYANCY)
DRAG = int(ForceKind.DRAG)
APPLIED = int(ForceKind.APPLIED)
LINEAR_STIFFNESS = int(ForceKind.LINEAR_STIFFNESS)
LINEAR_DAMPING = int(ForceKind.LINEAR_DAMPING)
SERVO = int(ForceKind.SERVO)
NON_LINEAR_HYDROSTATIC = int(ForceKind.NON_LINEAR_HYDROSTATIC)
QUADRATIC_DAMPING = int(ForceKind.QUADRATIC_DAMPING)
NON_LINEAR_FROUDE_KRYLOV = int(ForceKind.NON_LINEAR_FROUDE_KRYLOV)
RADIATION_DAMPING = int(ForceKind.RADIATION_DAMPING)
DIFFRACTION = int(ForceKind.DIFFRACTION)
THRUSTER = int(ForceKind.THRUSTER)
RUDDER = int(ForceKind.RUDDER)
WIND = int(ForceKind.WIND)
CURRENT = int(ForceKind.CURRENT)
SHORT_WING = int(ForceKind.SHORT_WING)
CROSS_FLOW = int(ForceKind.CROSS_FLOW)
COMPENSATOR = int(ForceKind.COMPENSATOR)
WAVE_DRIFT = int(ForceKind.WAVE_DRIFT)
FLUID_INERTIA = int(ForceKind.FLUID_INERTIA)
ROD = int(ForceKind.ROD)
PROPELLER = int(ForceKind.PROPELLER)
FIN = int(ForceKind.FIN)
MESH = (NON_LINEAR_HYDROSTATIC, NON_LINEAR_FROUDE_KRYLOV)  # the kinds whose row holds a mesh


def kind_of(model: str) -> int:
    """The kind of a schema ``model:`` name ("non-linear hydrostatic": NON_LINEAR_HYDROSTATIC)."""
    return int(ForceKind[model.upper().replace("-", "_").replace(" ", "_")])
