"""Radiation memory (the ship-simulator document's ``radiation damping``): the force
-int_0^Tc K(tau) nu(t - tau) d tau of the retardation functions K of a hydrodynamic database
(seacable.hydrodb) on the body-frame velocity history nu of the body's reference point
(kernels.memory), turned into the earth frame. The database's infinite-frequency added mass
is the body's added mass (case.system.RadiationDamping).

The row: kernels.memory's (count, dt, the history block's offset in the workspace, K).
"""

from seacable.kernels import memory
from seacable.kernels.jit import inner


@inner
def body_velocity(rot, vel, omega, out):
    """nu = (R^T v, R^T w) into ``out`` (6)."""
    for c in range(3):
        out[c] = rot[0, c] * vel[0] + rot[1, c] * vel[1] + rot[2, c] * vel[2]
        out[3 + c] = rot[0, c] * omega[0] + rot[1, c] * omega[1] + rot[2, c] * omega[2]


@inner
def add(row, t, rot, vel, omega, history, rhs):
    """``history``: the memory workspace, whose first floats (kernels.memory.SCRATCH) hold nu,
    then the body-frame force."""
    nu = history[0:6]
    body = history[6:12]
    body_velocity(rot, vel, omega, nu)
    memory.force(row, history, t, nu, body)
    for i in range(3):
        rhs[i] += rot[i, 0] * body[0] + rot[i, 1] * body[1] + rot[i, 2] * body[2]
        rhs[3 + i] += rot[i, 0] * body[3] + rot[i, 1] * body[4] + rot[i, 2] * body[5]
