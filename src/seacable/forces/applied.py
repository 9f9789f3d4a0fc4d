"""A force and a moment from time functions (earth frame) at a point of a body: thrust, a
test load. Six channels from the model's first: force x, y, z [N], moment x, y, z [N m]."""

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.kernels.jit import inner
from seacable.kernels.timefn import evaluate

CHANNELS = ("force_x", "force_y", "force_z", "moment_x", "moment_y", "moment_z")


def pack(offset) -> list[float]:
    """The row: the point's position in the body frame [m]."""
    return [float(v) for v in offset]


@inner
def add(row, first, t, rot, tf, rhs):
    breaks, coefs, count, sine, build_up = tf
    arm = turn(rot, (row[0], row[1], row[2]))
    f0, _, _ = evaluate(breaks, coefs, count, sine, build_up, first, t)
    f1, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 1, t)
    f2, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 2, t)
    add_force(arm, f0, f1, f2, rhs)
    for c in range(3):
        m, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 3 + c, t)
        rhs[3 + c] += m
