"""Compiled explicit time integrators (rk4, dopri5) of a system of bodies and lines.

Contract shared by every integrator (a new one must follow it): ``numerics.contract``'s
``ChunkIntegrator``, points 0 to 5.
"""

import math

import numpy as np
from numba import njit

from seacable.kernels.jit import JIT, inner
from seacable.kernels.status import NON_FINITE, OK
from seacable.system import kernel

WORK_NAMES = (
    "accepted_steps",
    "rejected_steps",
    "rhs_evaluations",
    "failed_evaluations",
    "jacobian_evaluations",
    "linear_solves",
    "matrix_updates",
)


@inner
def _all_finite(y):
    total = 0.0
    for v in y:
        total += v
    return math.isfinite(total)


_RK4_NODES = np.array([0.0, 0.5, 0.5, 1.0])
_RK4_WEIGHTS = np.array([1.0, 2.0, 2.0, 1.0]) / 6.0


@njit(**JIT)
def step_time(first_output, output_interval, steps_per_output, step, dt):
    """Time [s] of the start of fixed step ``step`` of a chunk that begins at output index
    ``first_output``: the global output index times the interval, plus the steps since that
    output, so that a step's time never depends on where a chunk began."""
    done = step // steps_per_output
    return (first_output + done) * output_interval + (step - done * steps_per_output) * dt


@inner
def record(step, steps_per_output, first_output, output_interval, y, states, times, j):
    """After fixed step ``step`` (counted from output ``first_output``): at an output, the row
    ``j`` of ``states`` and ``times`` written; the next row's index."""
    if step % steps_per_output != 0:
        return j
    states[j, :] = y
    times[j] = (first_output + step // steps_per_output) * output_interval
    return j + 1


@njit(**JIT)
def rk4_chunk(first_step, y, output_interval, steps_per_output, n_steps, p, w, states, times, work):
    """Classical 4th-order Runge-Kutta with a fixed step ``output_interval / steps_per_output``
    [s]: ``n_steps`` steps from global step ``first_step`` (which may lie inside an output
    interval: a chunk need not end at an output, so that a long interval can be cut short by a
    signal), a row in ``states`` at each output reached. Returns (outputs reached, status).

    The stages run in a loop with a single call of the right-hand side: four inlined copies of
    it made the compiled step twice as slow (instruction-cache pressure).
    """
    ny = y.shape[0]
    dt = output_interval / steps_per_output
    k = np.empty((4, ny))
    stage = np.empty(ny)
    acc = np.empty(ny)
    first_output = first_step // steps_per_output
    step = first_step - first_output * steps_per_output  # into its output interval
    j = np.int64(0)  # not a literal: record compiles once
    for _ in range(n_steps):
        t = step_time(first_output, output_interval, steps_per_output, step, dt)
        status = OK
        for s in range(4):
            if s == 0:
                stage[:] = y
            else:
                h = _RK4_NODES[s] * dt
                for i in range(ny):
                    stage[i] = y[i] + h * k[s - 1, i]
            status |= kernel.evaluate(t + _RK4_NODES[s] * dt, stage, p, w, k[s])
        work[2] += 4
        for i in range(ny):
            acc[i] = y[i] + dt * (
                _RK4_WEIGHTS[0] * k[0, i]
                + _RK4_WEIGHTS[1] * k[1, i]
                + _RK4_WEIGHTS[2] * k[2, i]
                + _RK4_WEIGHTS[3] * k[3, i]
            )
        if status != OK or not _all_finite(acc):
            work[3] += 1
            return j, (status if status != OK else NON_FINITE)
        kernel.accept(t + dt, acc, p, w)
        y[:] = acc
        work[0] += 1
        step += 1
        j = record(step, steps_per_output, first_output, output_interval, y, states, times, j)
    return j, OK


# Dormand-Prince 5(4) coefficients
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1 / 5, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3 / 40, 9 / 40, 0.0, 0.0, 0.0, 0.0],
        [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0, 0.0],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0, 0.0],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0.0],
        [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
    ]
)
_E = np.array([71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


@njit(inline="always", **JIT)
def _dopri_step(t, y, h, p, w, k, ytmp, ynew):
    """One Dormand-Prince step from (t, y) with k[0] = f(t, y) given; fills k[1..6], ynew."""
    ny = y.shape[0]
    status = OK
    for s in range(1, 7):
        for i in range(ny):
            acc = 0.0
            for r in range(s):
                acc += _A[s, r] * k[r, i]
            ytmp[i] = y[i] + h * acc
        if s == 6:
            ynew[:] = ytmp
        status |= kernel.evaluate(t + _C[s] * h, ytmp, p, w, k[s])
    return status


@inner
def _error_norm(k, y, ynew, h, rtol, atol, magnitude):
    """RMS of the embedded error estimate over atol_i + rtol max(|y_i|, |ynew_i|), where atol_i
    is at least rtol times ``magnitude[i]`` when ``magnitude`` is given (not empty)."""
    ny = y.shape[0]
    tracked = magnitude.shape[0] > 0
    err = 0.0
    for i in range(ny):
        e = 0.0
        for r in range(7):
            e += _E[r] * k[r, i]
        a = max(atol[i], rtol * magnitude[i]) if tracked else atol[i]
        sc = a + rtol * max(abs(y[i]), abs(ynew[i]))
        err += (h * e / sc) ** 2
    return math.sqrt(err / ny)


@inner
def _accept(t, y, ynew, p, w, k, magnitude, work):
    """An accepted step to ``ynew`` (projected) at ``t``: ``y`` and the largest magnitudes
    updated, ``k[0]`` the derivative there (the last stage's, or evaluated again after a
    projection); the evaluation's status."""
    changed = kernel.accept(t, ynew, p, w)  # a line's failure: the last stage is stale
    y[:] = ynew
    for i in range(magnitude.shape[0]):
        magnitude[i] = max(magnitude[i], abs(y[i]))
    if kernel.projects(p) or changed != 0:
        work[2] += 1
        if kernel.evaluate(t, y, p, w, k[0]) != OK:
            work[3] += 1
            return NON_FINITE
    else:
        k[0, :] = k[6, :]
    work[0] += 1
    return OK


@njit(**JIT)
def dopri5_chunk(
    first_output, y, output_interval, n_outputs, h, rtol, atol, magnitude, max_step, p, w,
    states, times, work, k, fsal, clock, max_steps,
):  # fmt: skip
    """Adaptive Dormand-Prince 5(4) with error control, from output index ``first_output``
    (time ``first_output * output_interval`` [s]); returns (completed, status, next_h).

    ``atol`` holds one absolute tolerance per state; when ``magnitude`` is not empty it holds
    the largest |y_i| reached so far, updated after every accepted step, and the absolute
    tolerance of state i is at least rtol times it (``schema.Simulation.atol``'s default: each
    state's error measured against its own amplitude). ``k`` (7 x len(y)) are the stages, carried
    from chunk to chunk with ``fsal[0]`` = 1 while ``k[0]`` is the derivative at (t, y) (first
    same as last): a chunk then starts exactly as the step after an output inside a chunk
    would, so neither the results nor the work counters depend on where chunks begin.

    ``max_steps`` bounds the steps tried in the chunk: past it the chunk stops inside an output
    interval, its time kept in ``clock`` (``clock[1]`` = 1: the next chunk, from the same
    ``first_output``, resumes at ``clock[0]`` as the step would have gone on), so that a long
    interval can be cut short by a signal; it returns then with fewer outputs than asked and
    a sound status."""
    ny = y.shape[0]
    ytmp = np.empty(ny)
    ynew = np.empty(ny)
    t = clock[0] if clock[1] == 1.0 else first_output * output_interval
    clock[1] = 0.0
    tried = 0
    if n_outputs > 0 and fsal[0] == 0:
        status = kernel.evaluate(t, y, p, w, k[0])
        work[2] += 1
        if status != OK:
            work[3] += 1
            return 0, status, h
        fsal[0] = 1
    min_step = 1e-12 * max(1.0, output_interval)
    for j in range(n_outputs):
        t_target = (first_output + j + 1) * output_interval
        while t < t_target:
            if tried >= max_steps:
                clock[0], clock[1] = t, 1.0
                return j, OK, h
            tried += 1
            h = min(h, max_step)
            h_try = h
            last = False
            if t + h_try >= t_target - 1e-12 * output_interval:
                h_try = t_target - t
                last = True
            st = _dopri_step(t, y, h_try, p, w, k, ytmp, ynew)
            work[2] += 6
            err = _error_norm(k, y, ynew, h_try, rtol, atol, magnitude)
            if st != OK or not math.isfinite(err):
                work[3] += 1
                h = 0.25 * h_try
                if h < min_step:
                    return j, (st if st != OK else NON_FINITE), h
                continue
            if err <= 1.0:
                t = t_target if last else t + h_try
                if _accept(t, y, ynew, p, w, k, magnitude, work) != OK:
                    fsal[0] = 0
                    return j, NON_FINITE, h
                if last:
                    # a step clipped at an output time keeps the unclipped proposal unless the
                    # (unclamped) error estimate says it is too long
                    if err > 0.0:
                        h = min(h, 0.9 * h_try * err ** (-0.2))
                else:
                    h = h_try * (5.0 if err == 0.0 else min(5.0, 0.9 * err ** (-0.2)))
            else:
                work[1] += 1
                h = h_try * max(0.2, 0.9 * err ** (-0.2))
                if h < min_step:
                    return j, NON_FINITE, h
        states[j, :] = y
        times[j] = t
    return n_outputs, OK, h
