"""The tandem compensator: a nonlinear (feedback-linearising) controller that gives a ship the
surge force X and yaw moment N which make two outputs follow linear second-order laws,

    e1'' + 2 z1 w1 e1' + w1^2 e1 = 0,    e1 = d - d*,
    e2'' + 2 z2 w2 e2' + w2^2 e2 = 0,    e2 = psi - psi_ref - h*  (wrapped to (-pi, pi]),

d the horizontal distance from the ship's ``point`` P (its hawser's fairlead) to the ``target``
point Q (the FPSO's stern), psi the ship's heading and psi_ref either the target body's heading
(``relative``) or the bearing of Q from P (``line of sight``: the ship points at Q).

The outputs' second derivatives are affine in the control, y'' = f(x) + G(x) u with
u = (X, N): every load on the ship but the compensator's (hull, wind, hawser, thrust, lines),
its mass matrix and velocity terms give the accelerations without control a0 = M^-1 (F - b);
the target body's accelerations come from its own loads the same way (they do not depend on u:
its forces depend on positions and velocities only); X along the body's x axis at its reference
point and N about its z axis add M^-1 (X e_x, N e_z). With Delta = Q - P (horizontal),

    d'' = (|Delta'|^2 + Delta . Delta'') / d - d'^2 / d,
    beta'' = (Delta_x Delta_y'' - Delta_y Delta_x'' - 2 d d' beta') / d^2   (line of sight),

and a point's acceleration a + alpha x r + omega x (omega x r). The compensator solves
G u = v - f for the laws' v = -2 z w e' - w^2 e: the nonlinear loads are cancelled exactly,
then saturates X to [-max_astern, max_ahead] and N to [-max_yaw_moment, max_yaw_moment]
(each on its own: saturated, the loop is no longer linear). Where G is singular (the hawser
across the ship) it gives nothing. The demand and what is applied are recorded.

Its row: the points' indices, the heading mode, d* [m], h* [rad], w1 [rad/s], z1, w2, z2, the
limits [N, N, N m] (inf: none), and 1 while enabled (0: the ship uncontrolled).
"""

import math

import numpy as np
from numba import njit

from seacable.bodies.dynamics import solve_free
from seacable.bodies.kinematics import DYNAMIC
from seacable.kernels.jit import JIT, inner

POINT, TARGET, LOS, DISTANCE, HEADING, W1, Z1, W2, Z2 = 0, 1, 2, 3, 4, 5, 6, 7, 8
MAX_AHEAD, MAX_ASTERN, MAX_MOMENT, ENABLED = 9, 10, 11, 12
ROW = 13
RECORD = 4  # X and N applied [N, N m], X and N demanded before saturation


def pack(point: int, target: int, line_of_sight: bool, distance: float, heading: float,
         frequencies: tuple[float, float], damping: tuple[float, float],
         limits: tuple[float, float, float], enabled: bool) -> list[float]:  # fmt: skip
    """The row (limits: ahead, astern [N], yaw moment [N m]; inf for none)."""
    return [float(point), float(target), float(line_of_sight), distance, heading,
            frequencies[0], damping[0], frequencies[1], damping[1], *limits,
            float(enabled)]  # fmt: skip


@inner
def _point_acc(acc, omega, arm, quadratic, out):
    """The acceleration (earth frame) of the point at ``arm`` of a body of accelerations
    ``acc`` (a, alpha), with its centripetal part omega x (omega x r) when ``quadratic`` is
    1.0 (a float: literal bools would compile it twice)."""
    ax = acc[4] * arm[2] - acc[5] * arm[1]
    ay = acc[5] * arm[0] - acc[3] * arm[2]
    out[0], out[1] = acc[0] + ax, acc[1] + ay
    if quadratic != 0.0:
        wr0 = omega[1] * arm[2] - omega[2] * arm[1]
        wr1 = omega[2] * arm[0] - omega[0] * arm[2]
        wr2 = omega[0] * arm[1] - omega[1] * arm[0]
        out[0] += omega[1] * wr2 - omega[2] * wr1
        out[1] += omega[2] * wr0 - omega[0] * wr2


@inner
def _second(dx, dy, vx, vy, ax, ay, alpha, alpha_target, los, out):
    """(d'', e2'') from Delta, Delta', Delta'' and the yaw accelerations (module docstring)."""
    d2 = dx * dx + dy * dy
    d = math.sqrt(d2)
    rate = (dx * vx + dy * vy) / d
    out[0] = (vx * vx + vy * vy + dx * ax + dy * ay) / d - rate * rate / d
    if los:
        bearing_rate = (dx * vy - dy * vx) / d2
        out[1] = alpha - (dx * ay - dy * ax - 2.0 * d * rate * bearing_rate) / d2
    else:
        out[1] = alpha - alpha_target


@inner
def apply(row, b, point_body, body_kind, free, mass, bias, load, acc, ppos, pvel, parm, rot,
          omega, record):  # fmt: skip
    """Add the compensator's X and N to ``load[b]`` (earth frame, about the reference point),
    ``record`` (RECORD) what it applied and demanded; ``load`` holds every other load."""
    for i in range(RECORD):
        record[i] = 0.0
    if row[ENABLED] == 0.0:
        return
    p, q = int(row[POINT]), int(row[TARGET])
    c = point_body[q]
    rhs = np.empty(6)
    own = np.empty(6)
    target = np.zeros(6)
    unit_x = np.empty(6)
    unit_n = np.empty(6)
    for i in range(6):
        rhs[i] = load[b, i] - bias[b, i]
    solve_free(mass[b], rhs, free[b], own)
    if body_kind[c] == DYNAMIC:
        for i in range(6):
            rhs[i] = load[c, i] - bias[c, i]
        solve_free(mass[c], rhs, free[c], target)
    else:
        target[:] = acc[c]
    for i in range(3):  # X e_x, then N e_z, each of unit size
        rhs[i], rhs[3 + i] = rot[b, i, 0], 0.0
    solve_free(mass[b], rhs, free[b], unit_x)
    for i in range(3):
        rhs[i], rhs[3 + i] = 0.0, rot[b, i, 2]
    solve_free(mass[b], rhs, free[b], unit_n)
    dx, dy = ppos[q, 0] - ppos[p, 0], ppos[q, 1] - ppos[p, 1]
    vx, vy = pvel[q, 0] - pvel[p, 0], pvel[q, 1] - pvel[p, 1]
    if dx * dx + dy * dy == 0.0:
        return
    los = row[LOS] != 0.0
    a_p, a_q, f, gx, gn = np.empty(2), np.empty(2), np.empty(2), np.empty(2), np.empty(2)
    _point_acc(own, omega[b], parm[p], 1.0, a_p)
    _point_acc(target, omega[c], parm[q], 1.0, a_q)
    _second(dx, dy, vx, vy, a_q[0] - a_p[0], a_q[1] - a_p[1], own[5], target[5], los, f)
    _point_acc(unit_x, omega[b], parm[p], 0.0, a_p)
    _second(dx, dy, 0.0, 0.0, -a_p[0], -a_p[1], unit_x[5], 0.0, los, gx)
    _point_acc(unit_n, omega[b], parm[p], 0.0, a_p)
    _second(dx, dy, 0.0, 0.0, -a_p[0], -a_p[1], unit_n[5], 0.0, los, gn)
    d = math.sqrt(dx * dx + dy * dy)
    e1, e1_rate = d - row[DISTANCE], (dx * vx + dy * vy) / d
    heading = math.atan2(rot[b, 1, 0], rot[b, 0, 0])
    if los:
        reference = math.atan2(dy, dx)
        reference_rate = (dx * vy - dy * vx) / (d * d)
    else:
        reference = math.atan2(rot[c, 1, 0], rot[c, 0, 0])
        reference_rate = omega[c, 2]
    e2 = heading - reference - row[HEADING]
    e2 = math.atan2(math.sin(e2), math.cos(e2))
    e2_rate = omega[b, 2] - reference_rate
    v1 = -2.0 * row[Z1] * row[W1] * e1_rate - row[W1] * row[W1] * e1 - f[0]
    v2 = -2.0 * row[Z2] * row[W2] * e2_rate - row[W2] * row[W2] * e2 - f[1]
    det = gx[0] * gn[1] - gn[0] * gx[1]
    if not (abs(det) > 0.0 and math.isfinite(det)):
        return
    demand_x = (v1 * gn[1] - gn[0] * v2) / det
    demand_n = (gx[0] * v2 - v1 * gx[1]) / det
    x = min(max(demand_x, -row[MAX_ASTERN]), row[MAX_AHEAD])
    n = min(max(demand_n, -row[MAX_MOMENT]), row[MAX_MOMENT])
    for i in range(3):
        load[b, i] += x * rot[b, i, 0]
        load[b, 3 + i] += n * rot[b, i, 2]
    record[0], record[1], record[2], record[3] = x, n, demand_x, demand_n


@njit(inline="always", **JIT)  # inlined: no call where a case has none
def apply_all(rows, force_body, force_at, data, point_body, body_kind, free, mass, bias, load,
              acc, ppos, pvel, parm, rot, omega, record):  # fmt: skip
    """Every compensator (force rows ``rows``), in order, into ``load`` and ``record``."""
    for k in range(rows.shape[0]):
        f = rows[k]
        apply(data[force_at[f] :], force_body[f], point_body, body_kind, free, mass, bias, load,
              acc, ppos, pvel, parm, rot, omega, record[k])  # fmt: skip
