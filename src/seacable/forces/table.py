"""Every force model of every body, evaluated from one flat table (``forces.kinds``): row f
acts on body ``body[f]``, reads its floats from ``data[at[f]:]`` and its channels from
``first[f]`` on."""

from numba import njit

from seacable.forces import (
    applied,
    coefficients,
    diffraction,
    drag,
    froude_krylov,
    hull_current,
    hydrostatic,
    linear,
    radiation,
    rudder,
    servo,
    thruster,
    wave_drift,
    weight,
)
from seacable.forces.kinds import (
    APPLIED,
    BUOYANCY,
    COMPENSATOR,
    CROSS_FLOW,
    CURRENT,
    DIFFRACTION,
    DRAG,
    GRAVITY,
    LINEAR_DAMPING,
    LINEAR_STIFFNESS,
    NON_LINEAR_FROUDE_KRYLOV,
    NON_LINEAR_HYDROSTATIC,
    QUADRATIC_DAMPING,
    RADIATION_DAMPING,
    RUDDER,
    SERVO,
    SHORT_WING,
    THRUSTER,
    WAVE_DRIFT,
    WIND,
)
from seacable.kernels import memory
from seacable.kernels.jit import JIT, inner


@inner  # compiled once: inlined, its body was compiled again into each caller
def add_all(
    t, y, kind, body, at, first, state, data, mass, cog, volume, cob, fraction, quat, pos, rot,
    vel, omega, gravity, rho, current_z, current_u, current_v, wave, wave_depth, wave_stretch,
    hull, history, tf, rhs,
):  # fmt: skip
    """Add every force model's force and moment to its body's row of ``rhs`` (nb, 6); a model
    with states reads them from ``y`` at ``state[f]``; the mesh models share the workspace
    ``hull`` (kernels.hull.place), the radiation models read their velocity ``history``
    (kernels.memory; its first floats are a model's scratch)."""
    for f in range(kind.shape[0]):
        b = body[f]
        row = data[at[f] :]
        k = kind[f]
        if k == GRAVITY:
            weight.add_gravity(mass[b], cog[b], rot[b], gravity, rhs[b])
        elif k == BUOYANCY:
            weight.add_buoyancy(volume[b], cob[b], fraction[b], rot[b], gravity, rho, rhs[b])
        elif k == DRAG:
            drag.add(row, fraction[b], pos[b], rot[b], vel[b], current_z, current_u, current_v,
                     rhs[b])  # fmt: skip
        elif k == APPLIED:
            applied.add(row, first[f], t, rot[b], tf, rhs[b])
        elif k == LINEAR_STIFFNESS:
            linear.add_stiffness(row, pos[b], quat[b], rhs[b])
        elif k == LINEAR_DAMPING or k == QUADRATIC_DAMPING:
            linear.add_damping(row, pos[b], rot[b], vel[b], omega[b], current_z, current_u,
                               current_v, rhs[b])  # fmt: skip
        elif k == SERVO:
            servo.add(row, y, state[f], rhs[b])
        elif k == NON_LINEAR_HYDROSTATIC:
            hydrostatic.add(row, pos[b], rot[b], rho, gravity, wave, t, hull, rhs[b])
        elif k == RADIATION_DAMPING:
            radiation.add(row, t, y, state[f], rot[b], vel[b], omega[b], history, rhs[b])
        elif k == DIFFRACTION:
            diffraction.add(row, t, wave, pos[b], rot[b], history[0 : memory.SCRATCH], rhs[b])
        elif k == NON_LINEAR_FROUDE_KRYLOV:
            froude_krylov.add(row, pos[b], rot[b], rho, gravity, wave, t, wave_depth,
                              wave_stretch, hull, rhs[b])  # fmt: skip
        elif k == WAVE_DRIFT:
            wave_drift.add(row, t, wave, rot[b], rhs[b])
        elif (
            k == THRUSTER
            or k == RUDDER
            or k == WIND
            or k == CURRENT
            or k == SHORT_WING
            or (k == CROSS_FLOW)
        ):
            _vessel(k, row, first[f], t, y, state[f], rho, pos[b], rot[b], vel[b], omega[b],
                    current_z, current_u, current_v, tf, rhs[b])  # fmt: skip


@njit(inline="always", **JIT)
def _vessel(k, row, first, t, y, state, rho, pos, rot, vel, omega, current_z, current_u,
            current_v, tf, rhs):  # fmt: skip
    """A vessel's controlled forces (thruster, rudder; ``state``: their controller's or
    gear's, -1: none), coefficient loads (wind, current) and hull loads (short-wing,
    cross-flow)."""
    if k == THRUSTER:
        thruster.add(row, first, t, rot, vel, tf, y, state, rhs)
    elif k == RUDDER:
        rudder.add(row, first, t, rho, pos, rot, vel, omega, current_z, current_u, current_v,
                   tf, y, state, rhs)  # fmt: skip
    elif k == WIND or k == CURRENT:
        coefficients.add(row, t, tf, rho, pos, rot, vel, omega, current_z, current_u,
                         current_v, rhs)  # fmt: skip
    else:
        hull_current.add(row, rho, pos, rot, vel, omega, current_z, current_u, current_v, rhs)


@njit(inline="always", **JIT)
def state_rates(t, y, kind, body, at, first, state, data, pos, rot, vel, omega, ppos, pvel, tf,
                ydot):  # fmt: skip
    """The rates of every force model's states (read from ``y``) into ``ydot``."""
    for f in range(kind.shape[0]):
        if state[f] < 0:
            continue
        b = body[f]
        row = data[at[f] :]
        if kind[f] == SERVO:
            servo.rates(row, pos[b], vel[b], ppos, pvel, state[f], ydot)
        elif kind[f] == RADIATION_DAMPING:
            radiation.rates(row, y, state[f], rot[b], vel[b], omega[b], ydot)
        elif kind[f] == THRUSTER:
            thruster.rates(row, first[f], t, rot[b], vel[b], tf, y, state[f], ydot)
        elif kind[f] == RUDDER:
            rudder.rates(row, first[f], t, rot[b], omega[b], tf, y, state[f], ydot)


# kinds evaluated after every other load of the system, which they need (system.kernel.rhs:
# forces.compensator.apply_all), not by add_all, whatever their value (a kind added after
# them, as WAVE_DRIFT, is still a load they see)
LAST = (COMPENSATOR,)

STATEFUL = {
    SERVO: servo.state_count,
    RADIATION_DAMPING: radiation.state_count,
    THRUSTER: thruster.state_count,
    RUDDER: rudder.state_count,
}


def state_count(kind: int, row) -> int:
    """The first-order states of a force model of ``kind`` with its packed ``row`` (a
    ``StatefulForceModel``'s ``state_count``; none for the others)."""
    count = STATEFUL.get(kind)
    return 0 if count is None else count(row)
