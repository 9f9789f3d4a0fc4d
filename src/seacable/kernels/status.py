"""What a compiled evaluation or step reports: one enumeration shared by every kernel,
integrator and the run loop (``Status``), and its values as plain integers for compiled code
(numba reads module-level integers as constants)."""

from enum import IntEnum


class Status(IntEnum):
    OK = 0  # sound
    NON_FINITE = 1  # a state or rate became NaN or infinite, or a mass matrix was singular
    SINGULAR_CLOSURE = 2  # a pinned end could not be closed (a rigid-link line pulled straight)
    NEWTON_FAILED = 4  # an implicit step's Newton iteration did not converge


OK = int(Status.OK)
NON_FINITE = int(Status.NON_FINITE)
SINGULAR_CLOSURE = int(Status.SINGULAR_CLOSURE)
NEWTON_FAILED = int(Status.NEWTON_FAILED)
