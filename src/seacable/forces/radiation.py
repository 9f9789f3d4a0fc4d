"""Radiation memory (the ship-simulator document's ``radiation damping``): the force
-int_0^Tc K(tau) nu(t - tau) d tau of the retardation functions K of a hydrodynamic database
(seacable.hydrodb) on the body-frame velocity history nu of the body's reference point, turned
into the earth frame. The database's infinite-frequency added mass is the body's added mass
(case.forces.RadiationDamping). Two methods:

- ``convolution``: the integral over a recorded velocity history (kernels.memory);
- ``state_space``: each non-negligible entry K_ij(t) ~ C e^{A t} B (seacable.realization), its
  part of the force -C x with x' = A x + B nu_j: first-order states of the model
  (``StatefulForceModel``), zero at rest, whose rates vanish there.

The row: the method, then for a convolution kernels.memory's row (count, dt, the history
block's offset in the workspace, K); for a state space the entries, the states, then per entry
i, j, m, A's three diagonals (m each: A[r, r-1], A[r, r], A[r, r+1], zero off the matrix), B
(m), C (m). A is tridiagonal: the fit's modal form (1x1 and 2x2 blocks) is, and the rates
then cost 5 m products an entry, not m^2.
"""

import numpy as np

from seacable.kernels import memory
from seacable.kernels.jit import inner

CONVOLUTION, STATE_SPACE = 0.0, 1.0  # row[0]
MEMORY = 1  # the convolution's kernels.memory row starts here
ENTRIES, STATES, FIRST = 1, 2, 3  # a state space's entries, states, first entry


def pack_convolution(count: int, step: float, kernel) -> list[float]:
    """The convolution's row: ``count`` samples of K (count, 6, 6) every ``step`` [s]; the
    history block's offset zero (``system.hulls.memory_offsets`` sets it)."""
    return [CONVOLUTION, float(count), float(step), 0.0, *kernel.reshape(-1)]


def pack_state_space(entries) -> list[float]:
    """The state space's row from ``entries``: (i, j, A, B, C) for each entry K_ij, A (m, m)
    tridiagonal (a ValueError otherwise)."""
    row = [STATE_SPACE, float(len(entries)), float(sum(len(b) for _, _, _, b, _ in entries))]
    for i, j, a, b, c in entries:
        m = len(b)
        lower = np.concatenate([[0.0], np.diag(a, -1)])
        upper = np.concatenate([np.diag(a, 1), [0.0]])
        if np.any(np.triu(a, 2)) or np.any(np.tril(a, -2)):
            raise ValueError(f"the state space of K_{i + 1}{j + 1}: A is not tridiagonal")
        row += [float(i), float(j), float(m), *lower, *np.diag(a), *upper, *b, *c]
    return row


def state_count(row) -> int:
    """The model's first-order states (none for a convolution)."""
    return int(row[STATES]) if row[0] == STATE_SPACE else 0


def uses_history(row) -> bool:
    """Whether the model reads a velocity history (a convolution)."""
    return bool(row[0] == CONVOLUTION)


@inner
def body_velocity(rot, vel, omega, out):
    """nu = (R^T v, R^T w) into ``out`` (6)."""
    for c in range(3):
        out[c] = rot[0, c] * vel[0] + rot[1, c] * vel[1] + rot[2, c] * vel[2]
        out[3 + c] = rot[0, c] * omega[0] + rot[1, c] * omega[1] + rot[2, c] * omega[2]


@inner
def _state_space_force(row, y, state, out):
    """``out`` (6, body frame): -sum over the entries of C x."""
    for i in range(6):
        out[i] = 0.0
    at, s = FIRST, state
    for _ in range(int(row[ENTRIES])):
        i, m = int(row[at]), int(row[at + 2])
        c = at + 3 + 4 * m
        total = 0.0
        for k in range(m):
            total += row[c + k] * y[s + k]
        out[i] -= total
        at, s = c + m, s + m


@inner
def add(row, t, y, state, rot, vel, omega, history, rhs):
    """The force and moment on the body's reference point (earth frame) into ``rhs``.
    ``history``: the memory workspace, whose first floats (kernels.memory.SCRATCH) hold nu,
    then the body-frame force; a state space reads its states from ``y`` at ``state``."""
    nu = history[0:6]
    body = history[6:12]
    if row[0] == STATE_SPACE:
        _state_space_force(row, y, state, body)
    else:
        body_velocity(rot, vel, omega, nu)
        memory.force(row[MEMORY:], history, t, nu, body)
    for i in range(3):
        rhs[i] += rot[i, 0] * body[0] + rot[i, 1] * body[1] + rot[i, 2] * body[2]
        rhs[3 + i] += rot[i, 0] * body[3] + rot[i, 1] * body[4] + rot[i, 2] * body[5]


@inner
def rates(row, y, state, rot, vel, omega, ydot):
    """A state space's x' = A x + B nu_j of every entry into ``ydot`` from ``state`` on, nu
    the body-frame velocity (R^T v, R^T w) [m/s, rad/s]; zero at rest (x = 0, nu = 0)."""
    at, s = FIRST, state
    for _ in range(int(row[ENTRIES])):
        j, m = int(row[at + 1]), int(row[at + 2])
        turn = vel if j < 3 else omega
        c = j % 3
        nu = rot[0, c] * turn[0] + rot[1, c] * turn[1] + rot[2, c] * turn[2]
        low, b = at + 3, at + 3 + 3 * m  # the three diagonals, then B
        for r in range(m):
            total = row[b + r] * nu + row[low + m + r] * y[s + r]
            if r > 0:
                total += row[low + r] * y[s + r - 1]
            if r + 1 < m:
                total += row[low + 2 * m + r] * y[s + r + 1]
            ydot[s + r] = total
        at, s = b + 2 * m, s + m
