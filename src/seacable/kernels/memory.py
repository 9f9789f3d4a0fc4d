"""Radiation memory: the convolution -int_0^Tc K(tau) nu(t - tau) d tau of a retardation
function K (6x6, sampled every ``dt`` from 0 to Tc = (count - 1) dt) with a body's body-frame
velocity history (numba).

The history is a ring of velocities at the times k dt (k = 0, 1, ...), kept in a workspace
block that the integrators write after each accepted step only (``record``): a step that
jumps over several of these times fills them by linear interpolation between its two ends.
Nothing before the run's start: the body was at rest. The right-hand side reads the history
(``force``): the trapezoidal rule over the current velocity (tau = 0) and the recorded
samples, K interpolated linearly between its own samples. Since the history depends only on
accepted steps, a run's results do not depend on how it is cut into chunks.

A block: [t_prev, last index written, nu_prev (6), ring ((count) x 6)]; ``BLOCK`` + 6 count
floats, laid out after the workspace's first ``SCRATCH`` floats (which the force models use as
scratch). The kernel row: [count, dt, the block's offset, K (count x 36, row-major)].
"""

import math

from numba import njit

from seacable.kernels.jit import JIT, inner

BLOCK = 8  # t_prev, last index, nu_prev
SCRATCH = 24  # the workspace's first floats: a force model's small vectors, before the blocks
ROW = 3  # count, dt, offset before K


def block_size(count: int) -> int:
    return BLOCK + 6 * count


@njit(inline="always", **JIT)
def _slot(block_at, count, index):
    return block_at + BLOCK + 6 * (index % count)


@inner
def start(row, memory, t, nu):
    """A fresh history at the run's start ``t`` with velocity ``nu``: at rest before."""
    count = int(row[0])
    at = int(row[2])
    for i in range(BLOCK + 6 * count):
        memory[at + i] = 0.0
    memory[at] = t
    index = int(math.floor(t / row[1] + 1e-9))
    memory[at + 1] = index
    s = _slot(at, count, index)
    for c in range(6):
        memory[at + 2 + c] = nu[c]
        memory[s + c] = nu[c]


@inner
def record(row, memory, t, nu):
    """An accepted step ending at ``t`` with velocity ``nu``: every sample time passed since
    the last step, filled by linear interpolation."""
    count = int(row[0])
    dt = row[1]
    at = int(row[2])
    t0 = memory[at]
    index = int(memory[at + 1])
    while (index + 1) * dt <= t + 1e-12 * dt:
        index += 1
        s = _slot(at, count, index)
        span = t - t0
        f = 1.0 if span <= 0.0 else (index * dt - t0) / span
        for c in range(6):
            memory[s + c] = memory[at + 2 + c] + f * (nu[c] - memory[at + 2 + c])
    memory[at] = t
    memory[at + 1] = index
    for c in range(6):
        memory[at + 2 + c] = nu[c]


@njit(inline="always", **JIT)
def _add_k(row, k, f, weight, nu, s, memory, out):
    """out += weight K(tau) nu_sample, K(tau) = (1 - f) K_k + f K_{k+1}."""
    count = int(row[0])
    a = ROW + 36 * k
    b = a + 36 if k + 1 < count else a
    for i in range(6):
        total = 0.0
        for j in range(6):
            kij = (1.0 - f) * row[a + 6 * i + j] + f * row[b + 6 * i + j]
            value = nu[j] if s < 0 else memory[s + j]
            total += kij * value
        out[i] += weight * total


@inner
def force(row, memory, t, nu, out):
    """``out`` (6, zeroed here): -int_0^Tc K(tau) nu(t - tau) d tau, body frame."""
    for i in range(6):
        out[i] = 0.0
    count = int(row[0])
    dt = row[1]
    at = int(row[2])
    last = int(memory[at + 1])
    ahead = (t - last * dt) / dt  # the newest sample's tau, in samples
    if ahead < 0.0:  # an evaluation before the newest sample (statics at t = 0)
        ahead = 0.0
    shift = int(math.floor(ahead))
    f = ahead - shift
    tau_newest = ahead * dt
    # [0, tau_newest]: the current velocity (tau = 0) and the newest sample
    if tau_newest > 0.0:
        _add_k(row, 0, 0.0, 0.5 * tau_newest, nu, -1, memory, out)
        if shift < count:
            _add_k(row, shift, f, 0.5 * tau_newest, nu, _slot(at, count, last), memory, out)
    # then sample by sample: tau = (shift + f + j) dt for the sample last - j
    for j in range(count - 1):
        k = shift + j
        if k + 1 >= count or last - j - 1 < 0:
            break
        _add_k(row, k, f, 0.5 * dt, nu, _slot(at, count, last - j), memory, out)
        _add_k(row, k + 1, f, 0.5 * dt, nu, _slot(at, count, last - j - 1), memory, out)
    for i in range(6):
        out[i] = -out[i]
