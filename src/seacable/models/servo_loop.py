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

import numpy as np

from seacable.case import schema
from seacable.errors import CaseError
from seacable.numerics import integrators
from seacable.system.servo import ServoLoop, loop_of


def servo_loop(params, y0: np.ndarray, workspace) -> ServoLoop:
    """Linearise the model (any whose parameters carry ``servo_gain``, ``servo_rate_gain`` and
    ``servo_step``) with its servo about ``y0`` at t = 0: central differences of its compiled
    right-hand side, one Jacobian per term of J (``system.servo.loop_of``; 6 ny evaluations:
    0.16 s for the published case at 50 links, 1.8 s at 200 links with the dense eigenvalues
    of the check)."""

    def rates(gain, rate_gain, y, out):
        p = params._replace(servo_gain=gain, servo_rate_gain=rate_gain, servo_step=1.0)
        integrators.evaluate_rhs(0.0, y, p, workspace, out)

    return loop_of(rates, y0)


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
