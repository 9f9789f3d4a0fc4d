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
from seacable.kernels.timefn import JIT


@njit(inline="always", **JIT)
def line_params(p, li, end_mass):
    """The kernel's parameters of line li (``end_mass`` 0: the string alone, its energies)."""
    return nk.NaturalParams(
        n=p.nat_n[li], length=p.nat_length[li], mu=p.nat_mu[li], end_mass=end_mass,
        axial_stiffness=p.nat_ea[li], axial_damping=p.nat_alpha[li], slack_allowed=1,
        gravity=p.gravity, cartesian=p.nat_cartesian[li],
    )  # fmt: skip


@njit(inline="always", **JIT)
def gather(y, p, li, buf):
    """The line's state in the kernel's layout, [node variables, their rates], into ``buf``;
    returns its size."""
    size = (3 if p.nat_cartesian[li] == 1 else 2) * (p.nat_n[li] + 1)
    q, v = p.nat_q[li], p.nat_v[li]
    for i in range(size):
        buf[i] = y[q + i]
        buf[size + i] = y[v + i]
    return size


@njit(**JIT)
def rates(t, y, p, w, li, ydot):
    """The line's rates into ``ydot``; returns the kernel's status."""
    tip = p.nat_tip[li]
    size = gather(y, p, li, w.nat)
    status = nk.rhs(t, w.nat, line_params(p, li, p.body_mass[tip]), w.nat_work, w.nat_dot)
    q, v = p.nat_q[li], p.nat_v[li]
    for i in range(size):
        ydot[q + i] = w.nat_dot[i]
        ydot[v + i] = w.nat_dot[size + i]
    return status


@njit(**JIT)
def carry(y, p, w, li):
    """The pivot's point and the position and velocity of the body at the string's end (the
    workspace's fields filled for the line)."""
    k = p.nat_from[li]
    kinematics.point_state(k, p.point_body, p.point_offset, w.pos, w.rot, w.vel, w.omega,
                           w.ppos, w.pvel, w.parm)  # fmt: skip
    gather(y, p, li, w.nat)
    n = p.nat_n[li]
    nk.fields(w.nat, line_params(p, li, 1.0), w.nat_work)
    h = p.nat_length[li] / n
    x = z = vx = vz = 0.0
    for i in range(1, n + 1):
        dx, dz, dvx, dvz = nk.trapezoid(w.nat_work, h, i)
        x, z, vx, vz = x + dx, z + dz, vx + dvx, vz + dvz
    tip = p.nat_tip[li]
    w.pos[tip, 0] = w.ppos[k, 0] + x
    w.pos[tip, 1] = w.ppos[k, 1]
    w.pos[tip, 2] = w.ppos[k, 2] + z
    w.vel[tip, 0], w.vel[tip, 1], w.vel[tip, 2] = vx, 0.0, vz


@njit(**JIT)
def own(y, p, w, li):
    """The string alone (its end mass aside): ``w.nat_out[:n + 1]`` gets each node's x and z
    from the pivot, strain and tension; returns its kinetic energy, its potential of gravity
    (from z = 0) and its elastic energy [J] (kernels.natural.outputs)."""
    n = p.nat_n[li]
    gather(y, p, li, w.nat)
    out = w.nat_out
    scalars = w.nat_dot[:5]  # scratch
    nk.outputs(0.0, w.nat, line_params(p, li, 0.0), w.nat_work, out[: n + 1, 0:2],
               out[: n + 1, 2], out[: n + 1, 3], scalars)  # fmt: skip
    pivot = w.ppos[p.nat_from[li], 2]
    weight = p.nat_mu[li] * p.nat_length[li] * p.gravity
    return scalars[2], scalars[3] + weight * pivot, scalars[4]
