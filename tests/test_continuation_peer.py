"""seacable's pseudo-arclength continuation (seacable.stability.continuation) against bice, an
independent continuation and bifurcation package (PyPI "bice"; a test extra only), on the
shuttle tanker of tests/test_stability.py: a hawser from a fixed point, the current from ahead,
the parameter the astern thrust (the applied force_x, negative).

The two share only the vector field f(x, mu) (``plane.rates``, all six states of the free body:
x, y, psi, vx, vy, r). bice finds the start's equilibrium with its own Newton solver, follows the
branch with its own pseudo-arclength stepper, differentiates f with its own finite differences,
counts the unstable eigenvalues with its own eigensolver and locates the Hopf point by its own
bisection; seacable works on the positions at rest (G = 0) with its own Jacobian and locates the
Hopf point by the secant method on the complex eigenvalues' largest real part.

bice works in scaled variables: u = x / SCALE, tau = t / TIME and mu = force_x / FORCE are all
near 1, since its tolerances and difference steps are absolute. Its bisection stops where the
real part is below ``tolerance`` or the interval is 1e-4 of the continuation step (1e-5 in mu
here, 1 N): the two Hopf points agree to 9e-7 (0.1 N; the assertion leaves a factor of ten)."""

import numpy as np
import pytest

from seacable.stability.continuation import Continuation
from seacable.stability.parameters import parameter
from seacable.stability.plane import Plane, Weather
from test_stability import FORMS, KH, XB, U, shuttle_case

bice = pytest.importorskip("bice")

LENGTH, TIME, FORCE = 100.0, 100.0, 1e5  # m, s, N
SCALE = np.array([LENGTH, LENGTH, 1.0, LENGTH / TIME, LENGTH / TIME, 1.0 / TIME])
START, END = -4e5, 0.0  # the astern thrust's force_x [N]: stable at the start, not at the end


class _Shuttle(bice.Equation):
    """du/dtau = TIME f(u SCALE, mu FORCE) / SCALE, the parameter ``mu`` an attribute (bice's
    continuation parameter); the Jacobian is bice's own (forward differences)."""

    def __init__(self, plane, thrust, mu):
        super().__init__(shape=(6,))
        self.plane, self.thrust, self.mu = plane, thrust, mu

    def rhs(self, u):
        self.thrust.set(self.plane, self.mu * FORCE)
        return TIME * self.plane.rates(u * SCALE) / SCALE


class _Newton(bice.MyNewtonSolver):
    """bice's textbook Newton, its convergence judged on max |residual| (bice 0.4.6 takes the
    signed max(residual), which stops at once where every residual is negative)."""

    def norm(self, residuals):
        return float(np.abs(residuals).max())


def _bice_branch(plane, thrust):
    """bice's branch from the equilibrium at START to END and its Hopf points: (parameter [N],
    the state, the eigenvalues [1/s]) at each."""
    problem = bice.Problem()
    problem.add_equation(_Shuttle(plane, thrust, START / FORCE))
    problem.continuation_parameter = (problem.eq, "mu")
    # the hawser stretched by the thrust alone (Newton adds the current's drag)
    problem.u = np.array([-(80.0 + XB - START / KH), 0.0, 0.0, 0.0, 0.0, 0.0]) / SCALE
    problem.newton_solver = _Newton()
    problem.newton_solver.convergence_tolerance = 1e-13
    problem.newton_solve()
    problem.settings.neigs = None  # every eigenvalue, by a dense solver
    stepper = problem.continuation_stepper
    stepper.ds, stepper.ds_max = 0.05, 0.1
    hopf = []
    for _ in range(400):
        if problem.get_continuation_parameter() >= END / FORCE:
            break
        problem.continuation_step()
        if problem.bifurcation_diagram.current_solution().bifurcation_type() == "HP":
            u, mu = problem.u.copy(), problem.get_continuation_parameter()
            # ev_index 0: the largest real part (bice's default, the smallest |real part|,
            # could take the weakly damped surge pair, Re -8.5e-5 1/s, instead)
            assert problem.locate_bifurcation(ev_index=0, tolerance=1e-8)
            lam = problem.eigen_solver.latest_eigenvalues / TIME
            hopf.append((problem.get_continuation_parameter() * FORCE, problem.u * SCALE, lam))
            problem.u = u  # on from the step's end, as bice itself does
            problem.set_continuation_parameter(mu)
    return problem.bifurcation_diagram.active_branch, hopf


@pytest.mark.parametrize("form", FORMS)
def test_the_shuttles_hopf_point_agrees_with_bice(form):
    plane = Plane.of(shuttle_case(form))
    Weather(U, 180.0).apply(plane.built)
    thrust = parameter(plane, "bodies.shuttle.external forces.1.force_x")
    ours = Continuation(plane, thrust).run(np.array([-(80.0 + XB), 0.0, 0.0]), START, END)
    (hopf,) = [s for s in ours.special if s.kind == "hopf"]

    branch, found = _bice_branch(plane, thrust)
    assert len(found) == 1
    mu, state, lam = found[0]
    assert mu == pytest.approx(hopf.parameter, rel=1e-5)  # about 1e-6 (module docstring)
    assert state[:3] == pytest.approx(hopf.x, abs=1e-4)  # [m, m, rad]; dx/dmu = 1/KH
    assert np.abs(state[3:]).max() < 1e-12  # at rest
    assert lam[0].real == pytest.approx(0.0, abs=1e-8)  # the crossing pair, largest real part
    assert abs(lam[0].imag) == pytest.approx(hopf.frequency, rel=1e-5)  # about 4e-7

    # stable before the Hopf point, a pair unstable after it, as seacable's branch
    parameters = FORCE * branch.parameter_vals()
    unstable = np.array([s.nunstable_eigenvalues for s in branch.solutions])
    assert parameters[-1] >= END and len(parameters) > 20
    assert np.all(unstable[parameters < mu] == 0)
    assert np.all(unstable[parameters > mu] == 2)
    assert ours.unstable[0] == 0 and ours.unstable[-1] == 2
