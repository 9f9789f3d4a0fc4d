"""Adaptive stiff integrators from PyPI: SciPy's BDF, Radau and LSODA, and SUNDIALS CVODE
(BDF, the successor of DASSL) through scikit-sundae.

They call the model's compiled right-hand side from Python once per evaluation. Their Newton
matrices come from finite differences that exploit the Jacobian's structure: for the cable
models whose nodes only talk to their neighbours a Jacobian costs a fixed number of right-hand
sides (O(n) work) and its factorisation is O(n):

* SciPy: ``jac_sparsity`` (the node-neighbour pattern) makes SciPy group independent columns
  (coloured finite differences) and factorise with sparse LU;
* CVODE: the state is interleaved node by node ([x_i, v_i] per node), which makes the Jacobian
  banded with half-bandwidth 4B - 1 (B variables per node), and CVODE's banded difference
  quotients and banded LU are O(n).

Models without that structure (rigid links: the inverse mass matrix couples every link) get a
dense Jacobian. Work counters follow ``numerics.integrators.WORK_NAMES``; a count the solver
does not report (CVODE's steps, SciPy's rejected steps) is -1.
"""

import numpy as np
from scipy import integrate, sparse

STIFF = ("bdf", "radau", "lsoda", "cvode")


def neighbour_sparsity(nodes: int, block: int):
    """Jacobian pattern of ``y = [x (block per node), v (block per node)]`` when each node's
    acceleration depends on its own and its neighbours' positions and velocities."""
    nq = nodes * block
    rows, cols = [], []
    for i in range(nodes):
        own = np.arange(i * block, (i + 1) * block)
        near = np.arange(max(0, i - 1) * block, min(nodes, i + 2) * block)
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
    order = []
    for i in range(nodes):
        order.extend(range(i * block, (i + 1) * block))
        order.extend(range(nq + i * block, nq + (i + 1) * block))
    return np.array(order)


class StiffStepper:
    """Advance a model with one of STIFF, hitting output times exactly (dense output)."""

    def __init__(self, name, fun, t0, y0, *, rtol, atol, max_step, first_step, block, nodes):
        self.name = name
        self.fun = fun  # f(t, y) -> ydot (raises FloatingPointError when non-finite)
        self.t = t0
        self.steps = 0
        self.nfev = self.njev = self.nlu = 0
        if name == "cvode":
            self._init_cvode(y0, rtol, atol, max_step, first_step, block, nodes)
        else:
            self._init_scipy(y0, rtol, atol, max_step, first_step, block, nodes)

    # ---- SciPy ----
    def _init_scipy(self, y0, rtol, atol, max_step, first_step, block, nodes):
        solver = {"bdf": integrate.BDF, "radau": integrate.Radau, "lsoda": integrate.LSODA}
        options = dict(rtol=rtol, atol=atol, max_step=max_step, first_step=first_step)
        if block is not None:
            sparsity = neighbour_sparsity(nodes, block)
            if self.name == "lsoda":
                # LSODA takes a banded Jacobian through lband/uband only for its own FD; the
                # [x, v] layout is not banded, so it uses its dense finite differences
                sparsity = None
            if sparsity is not None:
                options["jac_sparsity"] = sparsity
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
    def _init_cvode(self, y0, rtol, atol, max_step, first_step, block, nodes):
        from sksundae.cvode import CVODE

        options = dict(
            method="BDF", rtol=rtol, atol=atol, max_step=max_step, first_step=first_step,
            max_num_steps=100_000,
        )  # fmt: skip
        fun = self.fun
        if block is not None:
            order = interleave(nodes, block)
            inverse = np.argsort(order)
            self._order, self._inverse = order, inverse
            half = 4 * block - 1
            options.update(linsolver="band", lband=half, uband=half)

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
