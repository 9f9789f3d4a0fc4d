"""Outputs inside an implicit scheme's step that spans several output intervals: the state
interpolated between the step's two ends.

An implicit scheme's accurate step can be longer than the interval at which a user wants the
results (a spread mooring's generalized-alpha step of 0.3 s against outputs every 0.1 s;
benchmarks/vs_moordyn_spread.py): ``simulation.time_step`` may then be a whole number m of
output intervals, and the m - 1 outputs inside each step are read from the cubic Hermite
interpolant of its ends. Each position x with its velocity v (``Increments.q_of_v``), over
the step h from (x0, v0) to (x1, v1), at t0 + s h:

    x(s) = h00 x0 + h01 x1 + h (h10 v0 + h11 v1),
    v(s) = x'(s) = 6 s (1 - s) (x1 - x0) / h + (1 - 4 s + 3 s^2) v0 + (3 s^2 - 2 s) v1,

h00 = 2 s^3 - 3 s^2 + 1, h01 = 3 s^2 - 2 s^3, h10 = s^3 - 2 s^2 + s, h11 = s^3 - s^2: the
positions to O(h^4), the velocities, the interpolant's derivative, to O(h^3), both exact at
the ends, with no evaluation of the forces. A rigid body's orientation turns alike by the
rotation vector d(s) = h01 d + h (h10 w0 + h11 w1) from q0 (earth frame, as the schemes move
it: q = exp(d / 2) q0, ``system_implicit._advance``), d the step's whole rotation from q0 to
q1, its angular velocity the same derivative; the force models' states S linearly. The
state is then projected as after a step (unit quaternions, directors), not accepted: no
history (radiation's convolutions) records it. The rows at the steps' ends are the steps'
states themselves: bit for bit those of a run whose output interval is the step, where the
two intervals' multiples are the same numbers (k 0.125 and k/3 0.375 are; k 0.1 and k/3 0.3
differ in the last bit, and so do the steps' times). The interpolated rows of a moored
platform heeling under wind at 0.375 s steps are as far from a run ten times finer as the
steps' ends are (1.0 to 1.5 times, tests/test_dense_outputs.py).
"""

import math

from numba import njit

from seacable.kernels.jit import JIT, inner
from seacable.system import kernel as system_kernel


@njit(inline="always", **JIT)
def _weights(s):
    """The cubic Hermite basis at s in [0, 1]: h00, h01, h10, h11, and the velocity's weights
    of (x1 - x0) / h, v0 and v1."""
    s2, s3 = s * s, s * s * s
    return (2.0 * s3 - 3.0 * s2 + 1.0, 3.0 * s2 - 2.0 * s3, s3 - 2.0 * s2 + s, s3 - s2,
            6.0 * s * (1.0 - s), 1.0 - 4.0 * s + 3.0 * s2, 3.0 * s2 - 2.0 * s)  # fmt: skip


@inner
def _rotation(y0, y1, q):
    """The rotation vector d (earth frame) with q1 = exp(d / 2) q0, the shorter way, of the
    quaternions at ``y0[q:q + 4]`` and ``y1[q:q + 4]``."""
    w0, x0, v0, z0 = y0[q], y0[q + 1], y0[q + 2], y0[q + 3]
    w1, x1, v1, z1 = y1[q], y1[q + 1], y1[q + 2], y1[q + 3]
    # dq = q1 conj(q0)
    dw = w1 * w0 + x1 * x0 + v1 * v0 + z1 * z0
    dx = -w1 * x0 + x1 * w0 - v1 * z0 + z1 * v0
    dy = -w1 * v0 + x1 * z0 + v1 * w0 - z1 * x0
    dz = -w1 * z0 - x1 * v0 + v1 * x0 + z1 * w0
    if dw < 0.0:  # q and -q are one rotation
        dw, dx, dy, dz = -dw, -dx, -dy, -dz
    sine = math.sqrt(dx * dx + dy * dy + dz * dz)
    if sine < 1e-300:
        return 0.0, 0.0, 0.0
    angle = 2.0 * math.atan2(sine, dw)
    return angle * dx / sine, angle * dy / sine, angle * dz / sine


@inner
def between(y0, y1, s, h, q_of_v, quat_q, quat_v, nq, out):
    """``out``: the state at t0 + s h between the step's ends y0 (t0) and y1 (t0 + h), before
    its projection (module docstring). ``q_of_v``, ``quat_q``, ``quat_v``: the schemes'
    ``Increments``; ``nq`` the positions' count."""
    h00, h01, h10, h11, dx, dv0, dv1 = _weights(s)
    nv = q_of_v.shape[0]
    for i in range(nv):
        q = q_of_v[i]
        v0, v1 = y0[nq + i], y1[nq + i]
        if q >= 0:
            x0, x1 = y0[q], y1[q]
            out[q] = h00 * x0 + h01 * x1 + h * (h10 * v0 + h11 * v1)
            out[nq + i] = dx * (x1 - x0) / h + dv0 * v0 + dv1 * v1
    for k in range(quat_q.shape[0]):
        q, v = quat_q[k], nq + quat_v[k]
        d0, d1, d2 = _rotation(y0, y1, q)
        tx = h01 * d0 + h * (h10 * y0[v] + h11 * y1[v])
        ty = h01 * d1 + h * (h10 * y0[v + 1] + h11 * y1[v + 1])
        tz = h01 * d2 + h * (h10 * y0[v + 2] + h11 * y1[v + 2])
        out[v] = dx * d0 / h + dv0 * y0[v] + dv1 * y1[v]
        out[v + 1] = dx * d1 / h + dv0 * y0[v + 1] + dv1 * y1[v + 1]
        out[v + 2] = dx * d2 / h + dv0 * y0[v + 2] + dv1 * y1[v + 2]
        angle = math.sqrt(tx * tx + ty * ty + tz * tz)
        sw, sx, sy, sz = 1.0, 0.0, 0.0, 0.0
        if angle > 1e-300:
            f = math.sin(0.5 * angle) / angle
            sw, sx, sy, sz = math.cos(0.5 * angle), f * tx, f * ty, f * tz
        qw, qx, qy, qz = y0[q], y0[q + 1], y0[q + 2], y0[q + 3]
        out[q] = sw * qw - sx * qx - sy * qy - sz * qz
        out[q + 1] = sw * qx + sx * qw + sy * qz - sz * qy
        out[q + 2] = sw * qy - sx * qz + sy * qw + sz * qx
        out[q + 3] = sw * qz + sx * qy - sy * qx + sz * qw
    for i in range(nq + nv, y0.shape[0]):  # the force models' states
        out[i] = (1.0 - s) * y0[i] + s * y1[i]


@inner
def record(y0, y1, h, step, outputs, output_interval, q_of_v, quat_q, quat_v, p, states, times,
           j):  # fmt: skip
    """After global step ``step`` from y0 to y1 spanning ``outputs`` output intervals: its
    rows from row ``j`` of ``states`` and ``times``, the ``outputs`` - 1 inside it
    interpolated and projected, then y1 at its end; the next row's index."""
    first = step * outputs
    for k in range(1, outputs):
        row = states[j]
        between(y0, y1, k / outputs, h, q_of_v, quat_q, quat_v, p.n_q, row)
        system_kernel.projected(row, p)
        times[j] = (first + k) * output_interval
        j += 1
    states[j, :] = y1
    times[j] = (first + outputs) * output_interval
    return j + 1
