"""The force models' table on the Python side: which kinds act last (``LAST``) and which have
states of their own (``STATEFUL``, ``state_count``). Every force model of every body is
evaluated from one flat table (``forces.kinds``: row f acts on body ``body[f]``, reads its floats
from ``data[at[f]:]`` and its channels from ``first[f]`` on) by ``system.evaluation``'s
``add_all`` and ``state_rates``, compiled for the kinds a system holds."""

from seacable.forces import fin, propeller, radiation, rudder, servo, thruster
from seacable.forces.kinds import (
    COMPENSATOR,
    FIN,
    PROPELLER,
    RADIATION_DAMPING,
    RUDDER,
    SERVO,
    THRUSTER,
)

# kinds evaluated after every other load of the system, which they need (system.kernel.rhs:
# forces.compensator.apply_all), not by add_all, whatever their value (a kind added after
# them, as WAVE_DRIFT, is still a load they see)
LAST = (COMPENSATOR,)

STATEFUL = {
    SERVO: servo.state_count,
    RADIATION_DAMPING: radiation.state_count,
    THRUSTER: thruster.state_count,
    RUDDER: rudder.state_count,
    PROPELLER: propeller.state_count,
    FIN: fin.state_count,
}


def state_count(kind: int, row) -> int:
    """The first-order states of a force model of ``kind`` with its packed ``row`` (a
    ``StatefulForceModel``'s ``state_count``; none for the others)."""
    count = STATEFUL.get(kind)
    return 0 if count is None else count(row)
