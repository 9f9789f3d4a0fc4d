"""Analyses built on a case's dynamics: linearised natural modes about a state."""

import numpy as np

from seacable.case import loader, schema
from seacable.errors import CaseError
from seacable.kernels import planar_chain as pc
from seacable.models import planar_rigid_links


def linear_modes(case: schema.Case, state=None, time: float = 0.0, step: float = 1e-7):
    """Natural frequencies [rad/s] and mode shapes of the dynamics linearised about ``state``.

    The Jacobian of the accelerations with respect to positions (stiffness) and velocities
    (damping) is taken by central differences of the compiled right-hand side; the modes are the
    eigenvalues of the first-order system. Without ``state`` the initial state of the case is
    used (which should be an equilibrium for the frequencies to mean anything).

    Returns
    -------
    frequencies : ndarray
        Undamped-equivalent angular frequencies |lambda| of the oscillatory modes, ascending.
    damping_ratios : ndarray
        -Re(lambda) / |lambda| for the same modes.
    shapes : ndarray
        Position part of each mode (columns), normalised to unit largest component.
    """
    if case.cables[0].model != "rigid_links":
        raise CaseError(
            "linear_modes covers the planar rigid-link model; the 3D model's directors need a "
            "tangent-space linearisation that is not implemented yet"
        )
    system = planar_rigid_links.build(case, loader.case_base_dir(case))
    y0 = system.y0.copy() if state is None else np.asarray(state, dtype=float).copy()
    n = system.n_links
    p = system.params
    w = pc.make_workspace(n)
    heave = p.top_kind == pc.TOP_HEAVE
    q_index = list(range(n)) + ([n] if heave else [])
    v_index = [n + 1 + i for i in range(n)] + ([2 * n + 1] if heave else [])
    dof = len(q_index)
    ydot = np.zeros_like(y0)

    def accelerations(y):
        status = pc.rhs(time, y, p, w, ydot)
        if status != pc.OK:
            raise FloatingPointError("the dynamics cannot be evaluated at this state")
        return ydot[v_index].copy()

    jac_q = np.empty((dof, dof))
    jac_v = np.empty((dof, dof))
    for col, (iq, iv) in enumerate(zip(q_index, v_index, strict=True)):
        for jac, index in ((jac_q, iq), (jac_v, iv)):
            yp = y0.copy()
            ym = y0.copy()
            yp[index] += step
            ym[index] -= step
            jac[:, col] = (accelerations(yp) - accelerations(ym)) / (2 * step)
    first_order = np.block([[np.zeros((dof, dof)), np.eye(dof)], [jac_q, jac_v]])
    values, vectors = np.linalg.eig(first_order)
    keep = values.imag > 1e-9
    values = values[keep]
    vectors = vectors[:dof, keep]
    order = np.argsort(np.abs(values))
    values = values[order]
    shapes = np.real(vectors[:, order])
    shapes /= np.where(np.abs(shapes).max(axis=0) > 0, np.abs(shapes).max(axis=0), 1.0)
    frequencies = np.abs(values)
    return frequencies, -values.real / frequencies, shapes
