"""The closed loop of the trajectory servo (Jacquot & Marichal's stiffness-matrix law on a free
cable end): its linearisation about the initial state, its growth rate, and the gains it allows.

The servo's force F is a state with dF/dt = K (a/dt (r - x) - b (r' - x')) (``chain3d.
servo_rates``): x the end, r its target, K the end's stiffness, a the gain, b the rate gain, dt
the servo step. Linearised about the initial (steady) state y0, the whole model with the servo
obeys dy/dt = J y with

    J(a/dt, b) = J0 + (a/dt) G + b H,

J0 the cable with the servo's force frozen, G and H the servo's rows per unit a/dt and b (the
law is linear in both). The loop's modes are the eigenvalues of J: the largest real part sigma
[1/s] is the rate at which a small error grows (sigma = 0: the neutral modes of the constraints).
The loop depends on a and dt only through a/dt (for dt much shorter than its periods): a shorter
servo step needs a proportionally smaller gain. The paper's sampled form (a correction once per
step, the force held in between; ``sampled_growth_rate``) has the same growth rates within
0.1 % on the published case for a <= 2 and dt <= 0.1 s: the loop's modes (0.6 and 30 rad/s)
are slow against the step, so the continuous form integrated here is the paper's law. Checked
against runs at rest: at a/dt = 1500 and 2000 /s the predicted growth (2.20 and 5.21 /s) is the
measured one within 0.3 and 3 % (``benchmarks/trajectory_servo_scan.py``)."""

from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from seacable.case import schema
from seacable.errors import CaseError
from seacable.numerics import integrators

_GAIN_LIMIT = 2.0  # the schema's largest gain a


@dataclass(frozen=True)
class ServoLoop:
    """The linearised closed loop of a servo end: ``J0``, ``G`` (per unit a/dt [1/s]) and ``H``
    (per unit b), all (ny, ny)."""

    J0: np.ndarray
    G: np.ndarray
    H: np.ndarray

    def growth_rate(self, gain: float, rate_gain: float, step: float) -> float:
        """Largest real part [1/s] of the loop's eigenvalues with gain a, rate gain b and servo
        step dt [s]."""
        jacobian = self.J0 + (gain / step) * self.G + rate_gain * self.H
        return float(np.max(np.linalg.eigvals(jacobian).real))

    def sampled_growth_rate(self, gain: float, rate_gain: float, step: float) -> float:
        """The same [1/s] for the law as the paper writes it, a correction once per servo step
        (the force held in between): y -> (I + a G + b dt H) expm(J0 dt) y per step, the growth
        rate ln(largest |eigenvalue|) / dt."""
        size = self.J0.shape[0]
        jump = np.eye(size) + gain * self.G + rate_gain * step * self.H
        largest = np.max(np.abs(np.linalg.eigvals(jump @ expm(self.J0 * step))))
        return float(np.log(largest) / step)

    def largest_stable_gain(self, rate_gain: float, step: float, growth: float) -> float:
        """The largest gain a <= 2 whose growth rate stays at or below ``growth`` [1/s]
        (bisection; 0 if none)."""
        if self.growth_rate(_GAIN_LIMIT, rate_gain, step) <= growth:
            return _GAIN_LIMIT
        low, high = 0.0, _GAIN_LIMIT
        for _ in range(20):
            middle = 0.5 * (low + high)
            if self.growth_rate(middle, rate_gain, step) <= growth:
                low = middle
            else:
                high = middle
        return low


def servo_loop(params, y0: np.ndarray, workspace) -> ServoLoop:
    """Linearise the model (any whose parameters carry ``servo_gain``, ``servo_rate_gain`` and
    ``servo_step``) with its servo about ``y0`` at t = 0: central differences of its compiled
    right-hand side, one Jacobian per term of J (6 ny evaluations: 0.16 s for the published
    case at 50 links, 1.8 s at 200 links with the dense eigenvalues of the check)."""

    def jacobian(gain, rate_gain):
        p = params._replace(servo_gain=gain, servo_rate_gain=rate_gain, servo_step=1.0)
        size = y0.shape[0]
        result = np.empty((size, size))
        plus, minus = np.empty(size), np.empty(size)
        for i in range(size):
            h = 1e-6 * max(1.0, abs(y0[i]))
            y = y0.copy()
            y[i] += h
            integrators.evaluate_rhs(0.0, y, p, workspace, plus)
            y[i] -= 2.0 * h
            integrators.evaluate_rhs(0.0, y, p, workspace, minus)
            result[:, i] = (plus - minus) / (2.0 * h)
        return result

    frozen = jacobian(0.0, 0.0)
    return ServoLoop(frozen, jacobian(1.0, 0.0) - frozen, jacobian(0.0, 1.0) - frozen)


def check_servo_loop(case: schema.Case, params, y0: np.ndarray, workspace) -> float | None:
    """Refuse a servo gain and step that make the loop unstable: an error growing by more than
    a factor e over the run (growth rate above 1 / duration). Returns the growth rate [1/s]
    (None without a servo end)."""
    bottom = case.cables[0].bottom
    if not (isinstance(bottom, schema.TrajectoryBottom) and bottom.method == "stiffness_servo"):
        return None
    loop = servo_loop(params, y0, workspace)
    servo, duration = bottom.servo, case.simulation.duration
    gain, rate_gain, step = params.servo_gain, params.servo_rate_gain, params.servo_step
    growth = loop.growth_rate(gain, rate_gain, step)
    allowed = 1.0 / duration
    if growth <= allowed:
        return growth
    largest = loop.largest_stable_gain(rate_gain, step, allowed)
    if largest == 0.0:
        raise CaseError(
            f"cables[0].bottom.servo: no gain is stable with rate_gain {rate_gain:g} and servo "
            f"step {step:g} s (growth {growth:.3g} /s at gain {gain:g}); use method: exact"
        )
    given = "" if servo.step is not None else " (the integration step)"
    raise CaseError(
        f"cables[0].bottom.servo.gain: value {servo.gain:g} with servo step {step:g} s{given} "
        f"makes the servo loop unstable: an error grows as exp({growth:.3g} t), by a factor "
        f"exp({growth * duration:.3g}) over the {duration:g} s run. The stable gains with this "
        f"step are 0 < gain <= {largest:.3g} (gain / step <= {largest / step:.3g} /s, growth "
        f"below 1 / duration). Lower servo.gain to at most {largest:.3g}, or lengthen "
        f"servo.step in proportion; or use method: exact"
    )
