"""Fixed-step implicit integrators for second-order models with a block-tridiagonal Newton
matrix (the lumped-mass cable): implicit Euler, the theta-method, Newmark (gamma, beta) and the
generalized-alpha method of Chung and Hulbert (1993), as in WHOI Cable.

Every scheme is written for ``M(x) a = F(t, x, v)`` with the acceleration of the step's end,
``a1``, as the unknown:

    x1 = x0 + h v0 + h^2 (pa a0 + b a1),     v1 = v0 + h ((1 - g) a0 + g a1),
    M [(1 - am) a1 + am a0] = F(t0 + (1 - af) h, (1 - af) x1 + af x0, (1 - af) v1 + af v0)

    scheme              pa               b               g                am, af
    implicit Euler      0                1               1                0, 0
    theta-method        theta(1-theta)   theta^2         theta            0, 0
    Newmark             1/2 - beta       beta            gamma            0, 0
    generalized-alpha   1/2 - beta       beta            1/2 - am + af    (2r-1)/(r+1), r/(r+1)

(generalized-alpha: beta = (1 - am + af)^2 / 4, r the spectral radius at infinite frequency).
The theta-method with theta = 1/2 (the trapezoidal rule) and Newmark's average acceleration
(beta = 1/4, gamma = 1/2) are the same scheme here.

Newton's iterations solve for ``a1`` with the model's block-tridiagonal matrix
``(1 - am) M - (1 - af) (b h^2 dF/dx + g h dF/dv)``, factorised by block Thomas elimination
(O(n)) at the first iteration of a step and reused by the next ones (modified Newton). The
integrator follows the contract of ``numerics.integrators``; its work counters add Jacobian
evaluations (matrices built and factorised) and linear solves (Newton iterations).
"""

import math

import numpy as np
from numba import literally, njit

from seacable.kernels.status import NEWTON_FAILED, NON_FINITE, OK
from seacable.kernels.timefn import JIT
from seacable.numerics.dispatch import (
    model_chain,
    model_correct,
    model_keeps_matrix,
    model_newton,
    model_newton_cost,
    model_positions,
    model_prescribe,
    model_project,
    model_rhs,
    model_solver,
)
from seacable.numerics.integrators import step_time

# coefficient vector layout: pa, b, g, am, af
SCHEME_SIZE = 5


def scheme(name: str, theta=0.5, gamma=0.5, beta=0.25, spectral_radius=0.8) -> np.ndarray:
    """The coefficients (pa, b, g, am, af) of a named scheme (see the module docstring)."""
    if name == "implicit_euler":
        return np.array([0.0, 1.0, 1.0, 0.0, 0.0])
    if name == "theta":
        return np.array([theta * (1.0 - theta), theta * theta, theta, 0.0, 0.0])
    if name == "newmark":
        return np.array([0.5 - beta, beta, gamma, 0.0, 0.0])
    if name == "generalized_alpha":
        r = spectral_radius
        am = (2.0 * r - 1.0) / (r + 1.0)
        af = r / (r + 1.0)
        b = 0.25 * (1.0 - am + af) ** 2
        return np.array([0.5 - b, b, 0.5 - am + af, am, af])
    raise ValueError(f"unknown implicit scheme {name!r}")


@njit(**JIT)
def _inverse3(a, out):
    """out = inverse of the 3x3 row-major ``a``; returns the determinant (0: singular)."""
    c00 = a[4] * a[8] - a[5] * a[7]
    c01 = a[5] * a[6] - a[3] * a[8]
    c02 = a[3] * a[7] - a[4] * a[6]
    det = a[0] * c00 + a[1] * c01 + a[2] * c02
    if det == 0.0 or not math.isfinite(det):
        return 0.0
    inv = 1.0 / det
    out[0] = c00 * inv
    out[1] = (a[2] * a[7] - a[1] * a[8]) * inv
    out[2] = (a[1] * a[5] - a[2] * a[4]) * inv
    out[3] = c01 * inv
    out[4] = (a[0] * a[8] - a[2] * a[6]) * inv
    out[5] = (a[2] * a[3] - a[0] * a[5]) * inv
    out[6] = c02 * inv
    out[7] = (a[1] * a[6] - a[0] * a[7]) * inv
    out[8] = (a[0] * a[4] - a[1] * a[3]) * inv
    return det


@njit(**JIT)
def _matmul3(a, b, out):
    for r in range(3):
        for c in range(3):
            out[3 * r + c] = a[3 * r] * b[c] + a[3 * r + 1] * b[3 + c] + a[3 * r + 2] * b[6 + c]


@njit(**JIT)
def block_tridiagonal_factor(diag, upper, lower, factor, chain=0):
    """Block LU (Thomas) of the block-tridiagonal matrix with 3x3 blocks (row-major, 9 values
    each): ``diag[k]`` on the diagonal, ``upper[k]`` at (k, k+1), ``lower[k]`` at (k+1, k).
    Overwrites ``diag`` with the inverted pivots and fills ``factor[k] = lower[k] pivot[k]^-1``
    (``factor`` as long as ``lower``); O(n). Returns False when a pivot is singular.

    With ``chain`` > 0 the matrix is a star (``kernels.lumped_star``): chains of ``chain`` nodes
    one after another, then one hub node (the last) coupled to each chain's last node, whose
    ``upper``/``lower`` entries hold that coupling; chains do not couple to each other. Each
    chain is eliminated towards the hub, then the hub. ``chain`` = 0: one chain (the plain
    block-tridiagonal matrix)."""
    m = diag.shape[0]
    hub = m - 1
    if chain <= 0:
        chain = max(hub, 1)
    inv = np.empty(9)
    tmp = np.empty(9)
    for k in range(hub):
        if _inverse3(diag[k], inv) == 0.0:
            return False
        for c in range(9):
            diag[k, c] = inv[c]
        # eliminate node k from the next one's rows (a chain's last node: the hub's)
        following = hub if k % chain == chain - 1 else k + 1
        _matmul3(lower[k], diag[k], factor[k])
        _matmul3(factor[k], upper[k], tmp)
        for c in range(9):
            diag[following, c] -= tmp[c]
    if _inverse3(diag[hub], inv) == 0.0:
        return False
    for c in range(9):
        diag[hub, c] = inv[c]
    return True


@njit(inline="always", **JIT)
def _less_product(x, k, g, v, j):
    """x[k] -= g v[j] for 3-vectors at block k of x and j of v and the 3x3 block g."""
    p0, p1, p2 = v[3 * j], v[3 * j + 1], v[3 * j + 2]
    x[3 * k] -= g[0] * p0 + g[1] * p1 + g[2] * p2
    x[3 * k + 1] -= g[3] * p0 + g[4] * p1 + g[5] * p2
    x[3 * k + 2] -= g[6] * p0 + g[7] * p1 + g[8] * p2


@njit(**JIT)
def block_tridiagonal_apply(diag, upper, factor, rhs, x, chain=0):
    """Solve with the factors of ``block_tridiagonal_factor`` (forward, then back
    substitution); O(n). ``chain`` as given to the factorisation."""
    m = diag.shape[0]
    hub = m - 1
    if chain <= 0:
        chain = max(hub, 1)
    x[: 3 * m] = rhs[: 3 * m]
    for k in range(hub):
        _less_product(x, hub if k % chain == chain - 1 else k + 1, factor[k], x, k)
    for k in range(m - 1, -1, -1):
        if k < hub:
            _less_product(x, k, upper[k], x, hub if k % chain == chain - 1 else k + 1)
        d = diag[k]
        r0, r1, r2 = x[3 * k], x[3 * k + 1], x[3 * k + 2]
        x[3 * k] = d[0] * r0 + d[1] * r1 + d[2] * r2
        x[3 * k + 1] = d[3] * r0 + d[4] * r1 + d[5] * r2
        x[3 * k + 2] = d[6] * r0 + d[7] * r1 + d[8] * r2


@njit(**JIT)
def block_tridiagonal_solve(diag, upper, lower, rhs, x, chain=0):
    """Solve the block-tridiagonal (or, with ``chain``, star) system (see
    ``block_tridiagonal_factor``; ``diag`` is overwritten). Returns False when a pivot is
    singular."""
    factor = np.empty((max(diag.shape[0] - 1, 1), 9))
    if not block_tridiagonal_factor(diag, upper, lower, factor, chain):
        return False
    block_tridiagonal_apply(diag, upper, factor, rhs, x, chain)
    return True


@njit(**JIT)
def _lu(a, piv, bs):
    """In-place LU with partial pivoting of the bs x bs row-major block ``a`` (row swaps in
    ``piv``); returns False when it is singular."""
    literally(bs)
    for c in range(bs):
        best = c
        for r in range(c + 1, bs):
            if abs(a[r * bs + c]) > abs(a[best * bs + c]):
                best = r
        piv[c] = best
        if best != c:
            for k in range(bs):
                tmp = a[c * bs + k]
                a[c * bs + k] = a[best * bs + k]
                a[best * bs + k] = tmp
        pivot = a[c * bs + c]
        if pivot == 0.0 or not math.isfinite(pivot):
            return False
        for r in range(c + 1, bs):
            f = a[r * bs + c] / pivot
            a[r * bs + c] = f
            for k in range(c + 1, bs):
                a[r * bs + k] -= f * a[c * bs + k]
    return True


@njit(**JIT)
def _lu_solve(a, piv, bs, x, stride, columns):
    """Solve with the factors of ``_lu`` for ``columns`` right-hand sides stored row-major in
    ``x`` (row r, column j at x[r * stride + j]), in place."""
    literally(bs)
    for j in range(columns):
        for c in range(bs):
            r = piv[c]
            if r != c:
                tmp = x[c * stride + j]
                x[c * stride + j] = x[r * stride + j]
                x[r * stride + j] = tmp
        for r in range(1, bs):
            acc = x[r * stride + j]
            for k in range(r):
                acc -= a[r * bs + k] * x[k * stride + j]
            x[r * stride + j] = acc
        for r in range(bs - 1, -1, -1):
            acc = x[r * stride + j]
            for k in range(r + 1, bs):
                acc -= a[r * bs + k] * x[k * stride + j]
            x[r * stride + j] = acc / a[r * bs + r]


@njit(**JIT)
def block_lu_factor(diag, upper, lower, factor, piv, bs):
    """Block Thomas elimination for any block size bs (``diag`` of shape (m, bs * bs), blocks
    row-major; ``upper[k]`` at (k, k+1), ``lower[k]`` at (k+1, k)), for systems whose pivot
    blocks need row pivoting (saddle points: accelerations with constraint forces).
    ``diag[k]`` becomes the LU factors of the k-th Schur complement (row swaps in ``piv[k]``)
    and ``factor[k] = pivot[k]^-1 upper[k]``; O(m bs^3). Returns False on a singular pivot.
    ``bs`` is compiled as a constant (``numba.literally``): the loops unroll, twice as fast."""
    literally(bs)
    m = diag.shape[0]
    for k in range(m):
        if k > 0:
            g = factor[k - 1]
            low = lower[k - 1]
            for r in range(bs):
                for c in range(bs):
                    acc = 0.0
                    for j in range(bs):
                        acc += low[r * bs + j] * g[j * bs + c]
                    diag[k, r * bs + c] -= acc
        if not _lu(diag[k], piv[k], bs):
            return False
        if k < m - 1:
            factor[k, :] = upper[k]
            _lu_solve(diag[k], piv[k], bs, factor[k], bs, bs)
    return True


@njit(**JIT)
def block_lu_apply(diag, lower, factor, piv, rhs, x, bs):
    """Solve with the factors of ``block_lu_factor``; O(m bs^2)."""
    literally(bs)
    m = diag.shape[0]
    for k in range(m):
        for r in range(bs):
            acc = rhs[k * bs + r]
            if k > 0:
                low = lower[k - 1]
                for j in range(bs):
                    acc -= low[r * bs + j] * x[(k - 1) * bs + j]
            x[k * bs + r] = acc
        _lu_solve(diag[k], piv[k], bs, x[k * bs : (k + 1) * bs], 1, 1)
    for k in range(m - 2, -1, -1):
        g = factor[k]
        for r in range(bs):
            acc = 0.0
            for j in range(bs):
                acc += g[r * bs + j] * x[(k + 1) * bs + j]
            x[k * bs + r] -= acc


PIVOTED_SIZES = (5, 9)  # block sizes compiled for the pivoting solver (rigid links: 2D, 3D)


@njit(**JIT)
def pivoted_factor(diag, upper, lower, factor, piv):
    """``block_lu_factor`` for the block size of ``piv``; False when it is not compiled."""
    if piv.shape[1] == 5:
        return block_lu_factor(diag, upper, lower, factor, piv, 5)
    if piv.shape[1] == 9:
        return block_lu_factor(diag, upper, lower, factor, piv, 9)
    return False


@njit(**JIT)
def pivoted_apply(diag, lower, factor, piv, rhs, x):
    """``block_lu_apply`` for the block size of ``piv``."""
    if piv.shape[1] == 5:
        block_lu_apply(diag, lower, factor, piv, rhs, x, 5)
    elif piv.shape[1] == 9:
        block_lu_apply(diag, lower, factor, piv, rhs, x, 9)


@njit(**JIT)
def initial_acceleration(t, y, p, w, acc):
    """The model's acceleration at (t, y): the a0 a run starts from. Returns the status."""
    ydot = np.empty_like(y)
    status = model_rhs(t, y, p, w, ydot)
    nq = acc.shape[0]
    acc[:] = ydot[nq : 2 * nq]
    return status


@njit(**JIT)
def _stage(y0, a0, a1, h, coef, y1, nq):
    """End state y1 = (x1, v1) of the step from the end acceleration a1."""
    pa, b, g = coef[0], coef[1], coef[2]
    for i in range(nq):
        x1 = y0[i] + h * y0[nq + i] + h * h * (pa * a0[i] + b * a1[i])
        v1 = y0[nq + i] + h * ((1.0 - g) * a0[i] + g * a1[i])
        y1[i] = x1
        y1[nq + i] = v1


@njit(**JIT)
def _alpha_point(y0, y1, a0, a1, coef, ya, aa, nq):
    am, af = coef[3], coef[4]
    for i in range(nq):
        ya[i] = (1.0 - af) * y1[i] + af * y0[i]
        ya[nq + i] = (1.0 - af) * y1[nq + i] + af * y0[nq + i]
        aa[i] = (1.0 - am) * a1[i] + am * a0[i]


MAX_SUBSTEPS = 64  # a step whose Newton iteration fails is retried in up to this many parts


REFRESH = 3  # modified Newton: the matrix is rebuilt after REFRESH iterations without converging
SLOW = 0.5  # ... or as soon as a correction is larger than SLOW times the one before


@njit(**JIT)
def _step(
    t, y, acc, h, coef, tol, max_iter, p, w, vec, q, da, res, diag, upper, lower, factor, piv,
    fresh, work,
):  # fmt: skip
    """One implicit step of length h from (t, y, acc); updates y and acc only when it succeeds.
    Returns the status (NEWTON_FAILED when Newton's iteration does not converge).

    A modified Newton iteration: models whose matrix is costly (``model_keeps_matrix``: the
    rigid-link ones) keep the factorised matrix from step to step while it serves (``fresh`` =
    [1, h] while the factors belong to the step length h); the others build it at each step's
    first iteration, which saves iterations. Either way it is rebuilt when the iteration takes
    REFRESH iterations on one matrix or contracts slower than SLOW; the other iterations only
    evaluate the residual and reuse the factors.
    ``da`` and ``res`` hold three entries per node whatever the model's variables per node
    (the solver's blocks are 3x3) or, for the rigid-link models, the solver's own unknowns
    (``model_correct`` maps them back onto the accelerations)."""
    nq = q.shape[1]
    pivoted = diag.shape[1] != 9
    y1, ya, ydot = vec[0], vec[1], vec[2]
    aa, a1, trend = q[0], q[1], q[2]
    b, g, am, af = coef[1], coef[2], coef[3], coef[4]
    t1 = t + h
    ta = t + (1.0 - af) * h
    # predictor: the last acceleration, extrapolated by the last step's change when that step
    # had the same length (on a smooth motion the first correction is then often the last)
    a1[:] = acc
    if fresh[2] == h:
        for i in range(nq):
            a1[i] += trend[i]
    y1[:] = y  # first-order states past the velocities (if any) stay as they are
    ya[:] = y
    uses = 0  # iterations on the current factors in this step
    previous = math.inf
    for it in range(max_iter):
        _stage(y, acc, a1, h, coef, y1, nq)
        model_prescribe(t1, y1, a1, p, w)
        _alpha_point(y, y1, acc, a1, coef, ya, aa, nq)
        matrix = fresh[0] == 0.0 or fresh[1] != h or uses >= REFRESH
        matrix = matrix or (it == 0 and not model_keeps_matrix(p))
        status = model_newton(
            ta, ya, aa, p, w, ydot, 1.0 - am, (1.0 - af) * b * h * h, (1.0 - af) * g * h,
            diag, upper, lower, res, matrix,
        )  # fmt: skip
        work[2] += model_newton_cost(p) if matrix else 1
        if status != OK:
            work[3] += 1
            return status
        if matrix:
            work[4] += 1
            if pivoted:
                factored = pivoted_factor(diag, upper, lower, factor, piv)
            else:
                factored = block_tridiagonal_factor(diag, upper, lower, factor, model_chain(p))
            if not factored:
                work[3] += 1
                fresh[0] = 0.0
                return NON_FINITE
            fresh[0], fresh[1] = 1.0, h
            uses = 0
            previous = math.inf
        uses += 1
        work[5] += 1
        if pivoted:
            pivoted_apply(diag, lower, factor, piv, res, da)
        else:
            block_tridiagonal_apply(diag, upper, factor, res, da, model_chain(p))
        largest = model_correct(p, da, a1)
        if not math.isfinite(largest):
            work[3] += 1
            fresh[0] = 0.0
            return NON_FINITE
        if largest > SLOW * previous:
            uses = REFRESH  # factors that no longer serve: rebuild at the next iteration
        previous = largest
        if b * h * h * largest <= tol:
            _stage(y, acc, a1, h, coef, y1, nq)
            model_prescribe(t1, y1, a1, p, w)
            model_project(y1, p)
            y[:] = y1
            for i in range(nq):
                trend[i] = a1[i] - acc[i]
            fresh[2] = h
            acc[:] = a1
            work[0] += 1
            return OK
    fresh[0] = 0.0
    fresh[2] = 0.0
    return NEWTON_FAILED


@njit(**JIT)
def newmark_carry(y, p):
    """The arrays an implicit run carries from step to step, allocated once per run and given
    to every chunk (``numerics.integrators``, contract point 5): ``q`` (the acceleration at the
    alpha point, the step's end acceleration a1, the last step's change of acceleration, the
    predictor's trend), ``fresh`` ([factors valid, their step length, the step length of the
    change in q[2]]) and the Newton matrix's factors (diag, upper, lower, factor, piv), which
    the rigid-link models keep from step to step."""
    ny = y.shape[0]
    nq = model_positions(p, ny)
    blocks, bs = model_solver(p, nq)
    q = np.zeros((3, nq))
    fresh = np.zeros(3)
    diag = np.zeros((blocks, bs * bs))
    upper = np.zeros((max(blocks - 1, 1), bs * bs))
    lower = np.zeros((max(blocks - 1, 1), bs * bs))
    factor = np.zeros((max(blocks - 1, 1), bs * bs))
    piv = np.zeros((blocks, bs), dtype=np.int64)
    return q, fresh, diag, upper, lower, factor, piv


@njit(**JIT)
def newmark_chunk(
    first_output, y, acc, output_interval, steps_per_output, n_outputs, coef, tol, max_iter, p,
    w, states, times, work, carry,
):  # fmt: skip
    """Advance ``n_outputs`` output intervals of ``steps_per_output`` implicit steps
    ``output_interval / steps_per_output`` [s], from output index ``first_output``.

    ``acc`` holds the scheme's acceleration a0 at the start (the model's acceleration at the
    first call; the algorithmic one after), and is updated; ``carry`` is ``newmark_carry``'s
    tuple, updated. ``tol`` [m] bounds the last Newton correction of the positions
    (b h^2 |da|). A step whose iteration fails (regularised seabed friction can make Newton
    cycle at long steps) is retried in 2, 4, ... MAX_SUBSTEPS equal parts, each retry counted
    as a rejected step. Returns (completed, status); ``work`` gets [accepted, rejected, rhs
    evaluations, failed evaluations, Jacobian evaluations, linear solves] (a Jacobian costs one
    rhs when analytic, more with finite differences; accepted counts substeps)."""
    ny = y.shape[0]
    q, fresh, diag, upper, lower, factor, piv = carry
    nq = q.shape[1]
    bs = piv.shape[1]
    blocks = piv.shape[0]
    dt = output_interval / steps_per_output
    vec = np.empty((3, ny))
    da = np.empty(bs * blocks)
    res = np.empty(bs * blocks)
    y_saved = np.empty(ny)
    acc_saved = np.empty(nq)
    step = 0
    for j in range(n_outputs):
        for _ in range(steps_per_output):
            t = step_time(first_output, output_interval, steps_per_output, step, dt)
            y_saved[:] = y
            acc_saved[:] = acc
            parts = 1
            while True:
                status = OK
                h = dt / parts
                for k in range(parts):
                    status = _step(
                        t + k * h, y, acc, h, coef, tol, max_iter, p, w, vec, q, da, res, diag,
                        upper, lower, factor, piv, fresh, work,
                    )  # fmt: skip
                    if status != OK:
                        break
                if status == OK:
                    break
                work[1] += 1
                y[:] = y_saved
                acc[:] = acc_saved
                if parts >= MAX_SUBSTEPS:
                    return j, status
                parts *= 2
            step += 1
        states[j, :] = y
        times[j] = (first_output + j + 1) * output_interval
    return n_outputs, OK
