"""Several lumped-mass cables whose lower ends share one point body (a "star" of extensible
cables): a buoy on four mooring legs, a clump weight on several lines.

The body is one node shared by every cable: its last node. Each cable is a ``kernels.lumped``
chain with a free end; the body's mass, added mass, apparent weight and drag ride on chain 0's
end (its ``body_*`` fields), so chain 0's end-node equation is the body's own and every other
chain adds its end node's mass and force to it:

    (sum_k M_end,k) A_B = sum_k F_end,k.

Every chain's nodes but the last keep their own 3x3 equations: the step is O(total nodes).

State: ``[x, v]`` with x the positions of chain 0's nodes 0..n-1, chain 1's, ..., then the
body's (3), and v the velocities in the same order. Each kernel gathers a chain's own lumped
state (its nodes, then the body) into the workspace and calls ``kernels.lumped`` on it.
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from seacable.kernels import chain3d as c3
from seacable.kernels import lumped as lk
from seacable.kernels import lumped_outputs as lko
from seacable.kernels.status import NON_FINITE, OK
from seacable.kernels.timefn import JIT


class LumpedStarParams(NamedTuple):
    chains: tuple  # LumpedParams, one per cable, free ends; chain 0 carries the body
    n: int  # segments per cable (all equal)


class StarWork(NamedTuple):
    """Workspace: per chain, its lumped workspace, its gathered state and derivative, and the
    scratch of its Newton system."""

    w: np.ndarray  # (k, lumped.N_WORK_ROWS, n + 1)
    y: np.ndarray  # (k, 6 (n + 1))
    ydot: np.ndarray  # (k, 6 (n + 1))
    acc: np.ndarray  # (k, 3 (n + 1))
    res: np.ndarray  # (k, 3 (n + 1))
    diag: np.ndarray  # (k, n + 1, 9)
    upper: np.ndarray  # (k, n, 9)
    lower: np.ndarray  # (k, n, 9)


def state_size(cables: int, n: int) -> int:
    return 6 * (cables * n + 1)


def make_workspace(cables: int, n: int) -> StarWork:
    m = n + 1
    return StarWork(
        w=np.zeros((cables, lk.N_WORK_ROWS, m)),
        y=np.zeros((cables, 6 * m)),
        ydot=np.zeros((cables, 6 * m)),
        acc=np.zeros((cables, 3 * m)),
        res=np.zeros((cables, 3 * m)),
        diag=np.zeros((cables, m, 9)),
        upper=np.zeros((cables, n, 9)),
        lower=np.zeros((cables, n, 9)),
    )


@njit(inline="always", **JIT)
def _gather(x, k, n, cables, stride, out):
    """Chain k's own entries of the star's ``x`` (its n nodes, then the body's), for each of
    the ``stride``-long halves of ``x`` (positions, velocities; or accelerations only)."""
    parts = x.shape[0] // stride
    m = 3 * (n + 1)
    o = 3 * n * k
    hub = 3 * n * cables
    for h in range(parts):
        for i in range(3 * n):
            out[h * m + i] = x[h * stride + o + i]
        for c in range(3):
            out[h * m + 3 * n + c] = x[h * stride + hub + c]


@njit(inline="always", **JIT)
def _scatter(chain, k, n, cables, stride, x):
    """Chain k's own nodes (not the body) back into the star's ``x`` (the inverse of
    ``_gather``)."""
    parts = x.shape[0] // stride
    m = 3 * (n + 1)
    o = 3 * n * k
    for h in range(parts):
        for i in range(3 * n):
            x[h * stride + o + i] = chain[h * m + i]


@njit(**JIT)
def rhs(t, y, p, ws, ydot):
    cables = len(p.chains)
    n = p.n
    nq = 3 * (cables * n + 1)
    hub = 3 * n * cables
    system = np.zeros(9)
    force = np.zeros(3)
    status = OK
    for k in range(cables):
        pk = p.chains[k]
        wk, yk, dk = ws.w[k], ws.y[k], ws.ydot[k]
        _gather(y, k, n, cables, nq, yk)
        st = lk.rhs(t, yk, pk, wk, dk)  # the end's own acceleration is not used
        if st != OK:
            status = st
        _scatter(dk, k, n, cables, nq, ydot)
        mass = lk._node_mass(pk, wk, n)  # chain 0's includes the body's
        for c in range(9):
            system[c] += mass[c]
        for c in range(3):
            force[c] += wk[lk._F + c, n]
    acc, det = c3._solve3(system, force)
    for c in range(3):
        ydot[hub + c] = y[nq + hub + c]
        ydot[nq + hub + c] = acc[c]
    if det == 0.0 or not math.isfinite(acc[0] + acc[1] + acc[2]):
        status = NON_FINITE
    return status


@njit(**JIT)
def outputs_chunk(times, states, p, ws, node_pos, tension, scalars, body_acc):
    """Per time: node positions (k, n+1, 3), tensions (k, n), each chain's ``lumped`` scalars
    (k, S) (chain 0's energies include the body's; a chain's bottom force is its pull on the
    body) and the body's acceleration (3)."""
    status = OK
    cables = len(p.chains)
    n = p.n
    ny = states.shape[1]
    nq = ny // 2
    ydot = np.empty(ny)
    for j in range(times.shape[0]):
        st = rhs(times[j], states[j], p, ws, ydot)
        if st != OK and status == OK:
            status = st
        for c in range(3):
            body_acc[j, c] = ydot[nq + 3 * n * cables + c]
        for k in range(cables):
            _gather(states[j], k, n, cables, nq, ws.y[k])
            st = lko.outputs(times[j], ws.y[k], p.chains[k], ws.w[k], node_pos[j, k],
                            tension[j, k], scalars[j, k])  # fmt: skip
            if st != OK and status == OK:
                status = st
    return status
