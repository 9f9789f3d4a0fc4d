"""Gravity and buoyancy of a body: its weight m g at its centre of gravity, downwards, and
rho g V f(z) at its centre of buoyancy, upwards, f the submerged fraction of its shape
(kernels.surface; 1 for a plain volume)."""

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.kernels.jit import inner


@inner
def add_gravity(mass, cog, rot, gravity, rhs):
    """Weight m g [N] at the centre of gravity ``cog`` (body frame [m])."""
    arm = turn(rot, (cog[0], cog[1], cog[2]))
    add_force(arm, 0.0, 0.0, -mass * gravity, rhs)


@inner
def add_buoyancy(volume, cob, fraction, rot, gravity, rho, rhs):
    """rho g V f [N] at the centre of buoyancy ``cob`` (body frame [m])."""
    arm = turn(rot, (cob[0], cob[1], cob[2]))
    # rho V before g: a body whose weight equals its buoyancy (m = rho V) is balanced exactly
    add_force(arm, 0.0, 0.0, rho * volume * fraction * gravity, rhs)
