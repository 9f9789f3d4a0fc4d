"""Jacquot & Marichal's trajectory servo (1993, section 4) as a force model with a state.

The servo's force F (3, earth frame, at the body's reference point) is a state of the system;
its rate is the paper's correction dF = K (a dE - b dt dE') spread over the servo step dt:

    dF/dt = K (a (r - x) / dt - b (r' - x')),

x and x' the body's position and velocity, r and r' the target point's, K (3x3, N/m) the
stiffness of the body's lines (``system.servo.stiffness`` fills it), a the gain, b the rate gain.
Its row: K (9, row-major), a, b, dt, the target point's index.
"""

from numba import njit

from seacable.kernels.jit import JIT

ROW = 9 + 4
GAIN, RATE_GAIN, STEP, TARGET = 9, 10, 11, 12
STATES = 3  # the force F


def state_count(row) -> int:
    """The model's first-order states: the force (3)."""
    return STATES


def pack(gain: float, rate_gain: float, step: float, target: int) -> list[float]:
    """The row with K zero (``system.servo`` computes it once the system is built)."""
    return [0.0] * 9 + [gain, rate_gain, step, float(target)]


@njit(inline="always", **JIT)
def add(row, y, state, rhs):
    """The force F (the state at ``state``) on the body's reference point."""
    for c in range(3):
        rhs[c] += y[state + c]


@njit(inline="always", **JIT)
def rates(row, pos, vel, ppos, pvel, state, ydot):
    """dF/dt into ``ydot[state:state + 3]`` from the body's ``pos`` and ``vel`` and the points'
    positions and velocities (the target's at ``row[TARGET]``)."""
    k = int(row[TARGET])
    a, b, dt = row[GAIN], row[RATE_GAIN], row[STEP]
    for r in range(3):
        rate = 0.0
        for c in range(3):
            rate += row[3 * r + c] * (a * (ppos[k, c] - pos[c]) / dt - b * (pvel[k, c] - vel[c]))
        ydot[state + r] = rate
