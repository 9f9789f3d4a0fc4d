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


def shifted_step(jac, r: np.ndarray, limit: np.ndarray) -> np.ndarray | None:
    """Newton's step of J dx = -r (J sparse or dense); where J is singular or nearly (a step
    beyond a hundred of each coordinate's ``limit``), one step of the shifted matrix with
    sigma per coordinate its residual over its limit (at least 1e-9 of J's largest diagonal
    entry): a coordinate nothing holds moves along its force, the others nearly as Newton's.
    None when even that fails."""
    jac = sparse.csc_matrix(jac)
    try:
        step = splu(jac).solve(-r)
        if np.all(np.isfinite(step)) and np.all(np.abs(step) < 100.0 * limit):
            return step
    except RuntimeError:
        pass
    diagonal = np.abs(jac.diagonal())
    shift = np.maximum(np.abs(r) / limit, 1e-9 * max(float(diagonal.max(initial=0.0)), 1e-300))
    try:
        step = splu((jac - sparse.diags(shift)).tocsc()).solve(-r)
    except RuntimeError:
        return None
    return step if np.all(np.isfinite(step)) else None
