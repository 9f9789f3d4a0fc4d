"""A string in natural variables (Poth 2002; ``kernels.natural``) as a line of a system: its
nodes' variables (strain and tangent angle, or strain and tangent components) sit in the
system's positions, their rates in its velocities (``nat_q``, ``nat_v``); each evaluation copies
them into one contiguous block of the kernel's layout, evaluates it there and copies the rates
back. It hangs from a fixed point (``nat_from``) and carries a point body (``nat_tip``, no
state of its own) whose mass is its end mass: the body's position and velocity are the
string's end, the trapezoidal integral of its tangent field from the pivot, in the plane of
the pivot (y constant)."""

from numba import njit

from seacable.bodies import kinematics
from seacable.kernels import natural as nk
from seacable.kernels.jit import JIT, inner


@njit(inline="always", **JIT)
def line_params(nat_n, nat_length, nat_mu, nat_ea, nat_alpha, nat_cartesian, gravity, li,
                end_mass):  # fmt: skip
    """The kernel's parameters of line li (scalars only; ``end_mass`` [kg] 0: the string
    alone, its energies), from the system's ``nat_*`` arrays and ``gravity`` [m/s^2]."""
    return nk.NaturalParams(
        n=nat_n[li], length=nat_length[li], mu=nat_mu[li], end_mass=end_mass,
        axial_stiffness=nat_ea[li], axial_damping=nat_alpha[li], slack_allowed=1,
        gravity=gravity, cartesian=nat_cartesian[li],
    )  # fmt: skip


@njit(inline="always", **JIT)
def gather(y, params, q, v, buf):
    """The line's state in the kernel's layout, [node variables, their rates], into ``buf``
    (``q``, ``v``: its first position and velocity in ``y``); returns its size."""
    size = (3 if params.cartesian == 1 else 2) * (params.n + 1)
    for i in range(size):
        buf[i] = y[q + i]
        buf[size + i] = y[v + i]
    return size


@inner
def rates(t, y, params, q, v, nat, nat_work, nat_dot, ydot):
    """The line's rates into ``ydot`` (``params``: ``line_params`` with the end body's mass;
    ``nat``, ``nat_work``, ``nat_dot``: the workspace's fields); returns the kernel's status.
    Arrays, not the system's tuples, as arguments (docs/architecture.md)."""
    size = gather(y, params, q, v, nat)
    status = nk.rhs(t, nat, params, nat_work, nat_dot)
    for i in range(size):
        ydot[q + i] = nat_dot[i]
        ydot[v + i] = nat_dot[size + i]
    return status


@inner
def carry(y, params, q, v, pivot, tip, point_body, point_offset, pos, rot, vel, omega, ppos,
          pvel, parm, nat, nat_work):  # fmt: skip
    """The pivot's point and the position and velocity of the body at the string's end (the
    workspace's fields filled for the line; ``params``: ``line_params``, ``pivot``: the point
    ``nat_from``, ``tip``: the body ``nat_tip``)."""
    kinematics.point_state(pivot, point_body, point_offset, pos, rot, vel, omega, ppos, pvel,
                           parm)  # fmt: skip
    gather(y, params, q, v, nat)
    n = params.n
    nk.fields(nat, params, nat_work)
    h = params.length / n
    x = z = vx = vz = 0.0
    for i in range(1, n + 1):
        dx, dz, dvx, dvz = nk.trapezoid(nat_work, h, i)
        x, z, vx, vz = x + dx, z + dz, vx + dvx, vz + dvz
    pos[tip, 0] = ppos[pivot, 0] + x
    pos[tip, 1] = ppos[pivot, 1]
    pos[tip, 2] = ppos[pivot, 2] + z
    vel[tip, 0], vel[tip, 1], vel[tip, 2] = vx, 0.0, vz


@inner
def own(y, p, w, li):
    """The string alone (its end mass aside): ``w.nat_out[:n + 1]`` gets each node's x and z
    from the pivot, strain and tension; returns its kinetic energy, its potential of gravity
    (from z = 0) and its elastic energy [J] (kernels.natural.outputs)."""
    n = p.nat_n[li]
    params = line_params(p.nat_n, p.nat_length, p.nat_mu, p.nat_ea, p.nat_alpha,
                         p.nat_cartesian, p.gravity, li, 0.0)  # fmt: skip
    gather(y, params, p.nat_q[li], p.nat_v[li], w.nat)
    out = w.nat_out
    scalars = w.nat_dot[:5]  # scratch
    nk.outputs(0.0, w.nat, params, w.nat_work, out[: n + 1, 0:2],
               out[: n + 1, 2], out[: n + 1, 3], scalars)  # fmt: skip
    pivot = w.ppos[p.nat_from[li], 2]
    weight = p.nat_mu[li] * p.nat_length[li] * p.gravity
    return scalars[2], scalars[3] + weight * pivot, scalars[4]
