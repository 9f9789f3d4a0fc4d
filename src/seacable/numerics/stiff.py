"""Adaptive stiff integrators from PyPI: SciPy's BDF, Radau and LSODA, and SUNDIALS CVODE
(BDF, the successor of DASSL) through scikit-sundae.

They call the system's compiled right-hand side from Python once per evaluation. Their Newton
matrices come from finite differences: SciPy's BDF and Radau get the system's sparse Jacobian
pattern (``system.model.jacobian_sparsity``), group independent columns (coloured finite
differences) and factorise with sparse LU; LSODA and CVODE form a dense Jacobian. One solver
object serves the whole run and steps on its own, the output times being read from its dense
output (SciPy) or asked of CVODE one at a time: the results do not depend on how many output
times a call asks for (``tests/test_reproducible.py``). Work counters follow
``numerics.integrators.WORK_NAMES``; a count the solver does not report (CVODE's steps, SciPy's
rejected steps) is -1.
"""

import numpy as np

STIFF = ("bdf", "radau", "lsoda", "cvode")


class StiffStepper:
    """Advance a model with one of STIFF, hitting output times exactly (dense output)."""

    def __init__(self, name, fun, t0, y0, *, rtol, atol, max_step, first_step, sparsity=None,
                 after=None):  # fmt: skip
        """``atol``: one absolute tolerance, or one per state (in the order of ``y0``).
        ``sparsity``: the Jacobian's pattern as a sparse matrix, used by SciPy's BDF and Radau
        (None: a dense Jacobian). ``after(t, y)``: called after each accepted step of SciPy's
        solvers (SUNDIALS' steps are internal: ``has_steps`` is False for it)."""
        self.sparsity = sparsity
        self.after = after
        self.name = name
        self.fun = fun  # f(t, y) -> ydot (raises FloatingPointError when non-finite)
        self.t = t0
        self.steps = 0
        self.nfev = self.njev = self.nlu = 0
        if name == "cvode":
            self._init_cvode(y0, rtol, atol, max_step, first_step)
        else:
            self._init_scipy(y0, rtol, atol, max_step, first_step)

    # ---- SciPy ----
    def _init_scipy(self, y0, rtol, atol, max_step, first_step):
        from scipy import integrate  # here: its import is slow (docs/architecture.md)

        solver = {"bdf": integrate.BDF, "radau": integrate.Radau, "lsoda": integrate.LSODA}
        options = dict(rtol=rtol, atol=atol, max_step=max_step, first_step=first_step)
        # LSODA takes no sparsity pattern: it uses its dense finite differences
        if self.sparsity is not None and self.name != "lsoda":
            options["jac_sparsity"] = self.sparsity
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
            if self.after is not None and solver.status != "failed":
                self.after(solver.t, np.array(solver.y))
            if solver.status == "failed":
                return done, message or "step failed"
            self._dense = solver.dense_output()
        self.nfev, self.njev, self.nlu = solver.nfev, solver.njev, solver.nlu
        return done, None

    # ---- CVODE ----
    def _init_cvode(self, y0, rtol, atol, max_step, first_step):
        """A dense Jacobian (the system's state is not ordered node by node)."""
        from sksundae.cvode import CVODE

        options = dict(
            method="BDF", rtol=rtol, atol=atol, max_step=max_step, first_step=first_step,
            max_num_steps=100_000, linsolver="dense",
        )  # fmt: skip
        fun = self.fun

        def rhs(t, z, zp):
            zp[:] = fun(t, z)

        self.solver = CVODE(rhs, **options)
        result = self.solver.init_step(self.t, y0.copy())
        if not result.success:
            raise FloatingPointError(result.message)

    def _advance_cvode(self, targets, states):
        for j, target in enumerate(targets):
            result = self.solver.step(float(target))
            if not result.success:
                return j, result.message
            states[j] = np.asarray(result.y)
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
        return np.array([steps, -1, self.nfev, 0, self.njev, solves, 0], dtype=np.int64)
