"""Pseudo-transient continuation (Kelley and Keyes, SIAM J. Numer. Anal. 35, 1998) for static
balances whose Jacobian is singular where nothing holds a coordinate: chain lying slack on a
frictionless seabed has no stiffness across itself, a platform on slack lines none in surge.

The balance r(x) = 0 of accelerations r is the rest point of the flow dx/dtau = r(x); one
implicit Euler step of it in pseudo-time tau is the Newton step of the shifted matrix,
(J - sigma I) dx = -r with sigma = 1 / dtau [1/s^2]. A coordinate on which nothing acts has
J = 0 and r = 0 there, so it stays put, where plain Newton divides by zero. ``sigma`` starts
where a step moves the worst coordinate by ``reach`` and follows the residual (switched
evolution relaxation: sigma times |r_new| / |r_old|), so the steps become Newton's as the
balance nears, down to ``floor``; a step that raises the residual is taken back and sigma
raised tenfold."""

import ctypes
import functools
import os
import sys
import tempfile
from contextlib import contextmanager

import numpy as np
from scipy import sparse
from scipy.sparse.linalg import splu


class PseudoTime:
    """The shift sigma [1/s^2] of the next step."""

    def __init__(self, residual: np.ndarray, reach: float, floor: float):
        self.shift = max(float(np.abs(residual).max()) / reach, floor)
        self.floor = floor

    def accepted(self, before: float, after: float) -> None:
        """A step took the residual's norm from ``before`` to ``after``."""
        self.shift = max(self.floor, self.shift * after / max(before, 1e-300))

    def rejected(self) -> None:
        self.shift *= 10.0


@functools.cache
def _libc() -> ctypes.CDLL:
    """The C library (its ``fflush``), loaded once: the solves run at every Newton step."""
    return ctypes.CDLL(None)


@contextmanager
def _held_blas_errors():
    """SuperLU's BLAS, on a nearly singular matrix, reports an argument it was wrongly given
    ("** On entry to DGEMV parameter number 2 had an illegal value", OpenBLAS's xerbla, by
    C's printf on the process's standard output), where a user reads it as a fault; the
    solve then fails or gives a step the caller checks. Such lines are held back, anything
    else written to the standard output or error meanwhile passed on."""
    libc = _libc()
    sys.stdout.flush()
    sys.stderr.flush()
    saved = {fd: os.dup(fd) for fd in (1, 2)}
    with tempfile.TemporaryFile() as held:
        for fd in saved:
            os.dup2(held.fileno(), fd)
        try:
            yield
        finally:
            libc.fflush(None)  # C's buffered output, before the streams are given back
            for fd, copy in saved.items():
                os.dup2(copy, fd)
                os.close(copy)
            held.seek(0)
            text = held.read().decode(errors="replace")
            kept = [line for line in text.splitlines()
                    if not ("On entry to" in line and "illegal value" in line)]  # fmt: skip
            if kept:
                sys.stderr.write("\n".join(kept) + "\n")


def sparse_solve(matrix, rhs: np.ndarray) -> np.ndarray | None:
    """The solution of ``matrix`` x = ``rhs`` (sparse LU, SuperLU), None when the matrix is
    singular or the solution not finite."""
    try:
        with _held_blas_errors():
            x = splu(sparse.csc_matrix(matrix)).solve(rhs)
    except RuntimeError:
        return None
    return x if np.all(np.isfinite(x)) else None


def shifted_step(jac, r: np.ndarray, limit: np.ndarray,
                 along: bool = False) -> np.ndarray | None:  # fmt: skip
    """Newton's step of J dx = -r (J sparse or dense); where J is singular or nearly (a step
    beyond a hundred of each coordinate's ``limit``), one step of the shifted matrix with
    sigma per coordinate its residual over its limit (at least 1e-9 of J's largest diagonal
    entry, or of the largest such ratio where J is zero): a coordinate nothing holds moves along
    its force, the others nearly as Newton's. ``along``: one sigma for all, the largest of
    those, so that a step where J is zero follows the force (scaled by the limits), none
    beyond its limit. None when even that fails."""
    jac = sparse.csc_matrix(jac)
    step = sparse_solve(jac, -r)
    if step is not None and np.all(np.abs(step) < 100.0 * limit):
        return step
    diagonal = np.abs(jac.diagonal())
    pull = np.abs(r) / limit
    # at least 1e-9 of J's largest diagonal entry, or of the largest pull where J is nothing
    # (lines that all lie slack): a coordinate neither holds nor pulls then stays put
    least = max(float(diagonal.max(initial=0.0)), float(pull.max(initial=0.0)), 1e-300)
    shift = np.maximum(np.full_like(pull, pull.max(initial=0.0)) if along else pull,
                       1e-9 * least)  # fmt: skip
    return sparse_solve(jac - sparse.diags(shift), -r)
