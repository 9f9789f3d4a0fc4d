"""A force and a moment from time functions at a point of a body, in the earth frame or in
the body frame (turning with it: a thruster's thrust): a test load, a thrust. Six channels
from the model's first: force x, y, z [N], moment x, y, z [N m]."""

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.kernels.jit import inner
from seacable.kernels.timefn import evaluate

CHANNELS = ("force_x", "force_y", "force_z", "moment_x", "moment_y", "moment_z")


def pack(offset, body_frame: bool) -> list[float]:
    """The row: the point's position in the body frame [m], 1 when the force and moment are
    given in the body frame."""
    return [*(float(v) for v in offset), float(body_frame)]


@inner
def add(row, first, t, rot, tf, rhs):
    breaks, coefs, count, sine, build_up = tf
    arm = turn(rot, (row[0], row[1], row[2]))
    f0, _, _ = evaluate(breaks, coefs, count, sine, build_up, first, t)
    f1, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 1, t)
    f2, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 2, t)
    m0, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 3, t)
    m1, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 4, t)
    m2, _, _ = evaluate(breaks, coefs, count, sine, build_up, first + 5, t)
    if row[3] != 0.0:
        f0, f1, f2 = turn(rot, (f0, f1, f2))
        m0, m1, m2 = turn(rot, (m0, m1, m2))
    add_force(arm, f0, f1, f2, rhs)
    rhs[3] += m0
    rhs[4] += m1
    rhs[5] += m2
