"""Adaptive stiff integrators from PyPI: SciPy's BDF, Radau and LSODA, and SUNDIALS CVODE
(BDF, the successor of DASSL) through scikit-sundae.

They call the model's compiled right-hand side from Python once per evaluation. Their Newton
matrices come from finite differences that exploit the Jacobian's structure: for the cable
models whose nodes only talk to their neighbours a Jacobian costs a fixed number of right-hand
sides (O(n) work) and its factorisation is O(n):

* SciPy: ``jac_sparsity`` (the node-neighbour pattern) makes SciPy group independent columns
  (coloured finite differences) and factorise with sparse LU;
* CVODE: the state is interleaved node by node ([x_i, v_i] per node), which makes the Jacobian
  banded with half-bandwidth 2B (r + 1) - 1 (B variables per node, r the reach of a node's
  coupling: 1, or 2 with bending), and CVODE's banded difference quotients and banded LU are
  O(n). A star of cables (the shared body couples every chain's end) is not banded: dense.

Models without that structure (rigid links: the inverse mass matrix couples every link) get a
dense Jacobian. One solver object serves the whole run and steps on its own, the output times
being read from its dense output (SciPy) or asked of CVODE one at a time: the results do
not depend on how many output times a call asks for (``tests/test_reproducible.py``). Work
counters follow ``numerics.integrators.WORK_NAMES``; a count the solver does not report
(CVODE's steps, SciPy's rejected steps) is -1.
"""

import numpy as np
from scipy import integrate, sparse

STIFF = ("bdf", "radau", "lsoda", "cvode")


def chain_graph(nodes: int, reach: int = 1) -> list[np.ndarray]:
    """Node neighbours along one chain: each node's acceleration depends on the nodes within
    ``reach`` of it (1: axial forces and drag; 2 with bending, whose force on a node comes from
    the angles at its neighbours)."""
    return [np.arange(max(0, i - reach), min(nodes, i + reach + 1)) for i in range(nodes)]


def graph_sparsity(neighbours, block: int):
    """Jacobian pattern of ``y = [x (block per node), v (block per node)]``: ``neighbours[i]``
    the nodes (itself included) whose positions and velocities node i's acceleration depends on
    (``chain_graph``; a star: each chain's last node and the shared body couple too)."""
    nodes = len(neighbours)
    nq = nodes * block
    rows: list[int] = []
    cols: list[int] = []
    for i, near_nodes in enumerate(neighbours):
        own = np.arange(i * block, (i + 1) * block)
        near = (np.asarray(near_nodes)[:, None] * block + np.arange(block)[None, :]).ravel()
        # dx/dt = v
        rows.extend(own)
        cols.extend(nq + own)
        # dv/dt = a(x, v of the neighbours)
        rr, cc = np.meshgrid(nq + own, np.concatenate([near, nq + near]), indexing="ij")
        rows.extend(rr.ravel())
        cols.extend(cc.ravel())
    n = 2 * nq
    return sparse.csc_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))


def interleave(nodes: int, block: int) -> np.ndarray:
    """Permutation p with z = y[p] ordered node by node: [x_0, v_0, x_1, v_1, ...]."""
    nq = nodes * block
    order: list[int] = []
    for i in range(nodes):
        order.extend(range(i * block, (i + 1) * block))
        order.extend(range(nq + i * block, nq + (i + 1) * block))
    return np.array(order)


MAX_BANDED_REACH = 4  # CVODE: a graph reaching further (a star's body) gets a dense Jacobian


def _reach(graph) -> int:
    """The largest index distance between coupled nodes."""
    return max(int(np.max(np.abs(np.asarray(near) - i))) for i, near in enumerate(graph))


def banded(graph) -> bool:
    """True when CVODE gets a banded Jacobian for this node graph."""
    return _reach(graph) <= MAX_BANDED_REACH


class StiffStepper:
    """Advance a model with one of STIFF, hitting output times exactly (dense output)."""

    def __init__(
        self, name, fun, t0, y0, *, rtol, atol, max_step, first_step, block, graph, sparsity=None
    ):
        """``atol``: one absolute tolerance, or one per state (in the order of ``y0``).
        ``sparsity``: the Jacobian's pattern as a sparse matrix (a system of bodies and lines),
        used by SciPy's integrators instead of a node graph; CVODE then factorises densely."""
        self.sparsity = sparsity
        self.name = name
        self.fun = fun  # f(t, y) -> ydot (raises FloatingPointError when non-finite)
        self.t = t0
        self.steps = 0
        self.nfev = self.njev = self.nlu = 0
        if name == "cvode":
            self._init_cvode(y0, rtol, atol, max_step, first_step, block, graph)
        else:
            self._init_scipy(y0, rtol, atol, max_step, first_step, block, graph)

    # ---- SciPy ----
    def _init_scipy(self, y0, rtol, atol, max_step, first_step, block, graph):
        """``graph``: the node neighbours of ``graph_sparsity`` (``block`` variables per node);
        None: a dense Jacobian."""
        solver = {"bdf": integrate.BDF, "radau": integrate.Radau, "lsoda": integrate.LSODA}
        options = dict(rtol=rtol, atol=atol, max_step=max_step, first_step=first_step)
        # LSODA takes a banded Jacobian through lband/uband only for its own FD; the [x, v]
        # layout is not banded, so it uses its dense finite differences
        if self.sparsity is not None and self.name != "lsoda":
            options["jac_sparsity"] = self.sparsity
        elif graph is not None and self.name != "lsoda":
            options["jac_sparsity"] = graph_sparsity(graph, block)
        self.solver = solver[self.name](self.fun, self.t, y0.copy(), np.inf, **options)

    def _advance_scipy(self, targets, states):
        solver = self.solver
        done = 0
        while done < len(targets):
            if solver.t >= targets[done]:
                dense = self._dense
                while done < len(targets) and targets[done] <= solver.t:
                    states[done] = dense(targets[done])
                    done += 1
                continue
            message = solver.step()
            self.steps += 1
            if solver.status == "failed":
                return done, message or "step failed"
            self._dense = solver.dense_output()
        self.nfev, self.njev, self.nlu = solver.nfev, solver.njev, solver.nlu
        return done, None

    # ---- CVODE ----
    def _init_cvode(self, y0, rtol, atol, max_step, first_step, block, graph):
        """Banded when the graph is a chain (interleaved node by node: half-bandwidth
        2 B (reach + 1) - 1); dense otherwise (a star, or no structure)."""
        from sksundae.cvode import CVODE

        options = dict(
            method="BDF", rtol=rtol, atol=atol, max_step=max_step, first_step=first_step,
            max_num_steps=100_000,
        )  # fmt: skip
        fun = self.fun
        if graph is not None and banded(graph):
            reach = _reach(graph)
            nodes = len(graph)
            order = interleave(nodes, block)
            inverse = np.argsort(order)
            self._order, self._inverse = order, inverse
            half = 2 * block * (reach + 1) - 1
            options.update(linsolver="band", lband=half, uband=half)
            options["atol"] = np.broadcast_to(np.asarray(atol, dtype=float), y0.shape)[order]

            def rhs(t, z, zp):
                zp[:] = fun(t, z[inverse])[order]
        else:
            self._order = self._inverse = None
            options.update(linsolver="dense")

            def rhs(t, z, zp):
                zp[:] = fun(t, z)

        self.solver = CVODE(rhs, **options)
        z0 = y0[self._order] if self._order is not None else y0
        result = self.solver.init_step(self.t, z0.copy())
        if not result.success:
            raise FloatingPointError(result.message)

    def _advance_cvode(self, targets, states):
        for j, target in enumerate(targets):
            result = self.solver.step(float(target))
            if not result.success:
                return j, result.message
            z = np.asarray(result.y)
            states[j] = z[self._inverse] if self._inverse is not None else z
            self.nfev, self.njev = int(result.nfev), int(result.njev)
        return len(targets), None

    def advance(self, targets, states):
        """Fill ``states`` at ``targets``; returns (rows done, failure message or None)."""
        try:
            if self.name == "cvode":
                done, failure = self._advance_cvode(targets, states)
            else:
                done, failure = self._advance_scipy(targets, states)
        except FloatingPointError as exc:
            return 0, f"the right-hand side became non-finite ({exc})"
        if done:
            self.t = float(targets[done - 1])
        return done, failure

    def work(self) -> np.ndarray:
        """Counters in the order of ``integrators.WORK_NAMES``."""
        steps = -1 if self.name == "cvode" else self.steps
        solves = -1 if self.name == "cvode" else self.nlu
        return np.array([steps, -1, self.nfev, 0, self.njev, solves], dtype=np.int64)
