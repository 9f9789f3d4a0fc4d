"""The fixed step a run takes, and the longest stable step of the classical Runge-Kutta scheme
(rk4) for a system: from the eigenvalues of its fastest motions (``system.frequency``) and the
scheme's stability function. A run beyond it is refused (``rk4_check``).

A step h maps a mode e^(lambda t) to R(h lambda) times itself, R(z) = 1 + z + z^2/2 + z^3/6
+ z^4/24; the exact solution multiplies it by e^(h lambda). The step is stable for a mode
while |R(h lambda)| <= max(1, |e^(h lambda)|): a damped or undamped mode must not grow, a mode
the physics makes grow (a body pushed off an unstable balance) may grow as it does. For an
undamped oscillation (lambda = i omega) the limit is h omega = 2 sqrt 2 = 2.83; for a damped
one on the real axis, 2.79; in between, between 2.7 and 3. (Growth is counted beyond
GROWTH a step, so that a physically growing mode is not refused for rk4's error.)
"""

import math
from typing import NamedTuple

import numpy as np

from seacable.case.base import FIXED_STEP_INTEGRATORS, IMPLICIT_INTEGRATORS, Simulation
from seacable.errors import CaseError
from seacable.system.assemble import BuiltSystem
from seacable.system.frequency import fastest_modes

GRID = 4096  # trial steps per eigenvalue, up to 4 / |lambda|: the limit to 1e-3 of itself
# a step is unstable for a mode that rk4 makes grow this much more per step than time does: a
# mode the physics makes grow (Re lambda > 0) is amplified a little more by any step (the
# scheme's error, O(h^5) a step), which is accuracy, not instability; an undamped mode's
# limit moves by 0.02 % for it
GROWTH = 1e-3
DEFAULT_MAX_STEP = 0.01  # [s] default fixed step bound
# rk4 steps above this fraction of the stability limit about the start are warned: tensions
# that rise in a run (a snatch, a faster tow) raise the fastest frequency
NEAR_LIMIT = 0.6


def rk4_step(sim: Simulation) -> tuple[float, int]:
    """The fixed step actually used (rk4 and the implicit schemes) [s] and the number of steps
    per output interval (1 for an implicit scheme's step of several output intervals:
    ``outputs_per_step``)."""
    outputs = outputs_per_step(sim)
    if outputs > 1:
        return outputs * sim.output_interval, 1
    wanted = (
        sim.time_step if sim.time_step is not None else min(DEFAULT_MAX_STEP, sim.output_interval)
    )
    steps = max(1, math.ceil(sim.output_interval / wanted - 1e-9))
    return sim.output_interval / steps, steps


def outputs_per_step(sim: Simulation) -> int:
    """Output intervals an implicit scheme's step spans (the nearest whole number to its
    time_step over the output interval when that is at least 2; the schema's rule), the outputs
    inside it interpolated (``numerics.dense``); 1 otherwise."""
    if sim.integrator not in IMPLICIT_INTEGRATORS or sim.time_step is None:
        return 1
    return max(1, round(sim.time_step / sim.output_interval))


def rounded_step(sim: Simulation) -> str | None:
    """What the run does with a fixed time_step that divides the output interval (or that
    an implicit scheme's step is a multiple of) only within 1 % (the schema's rule): it takes
    that step, and says so."""
    if sim.integrator not in FIXED_STEP_INTEGRATORS or sim.time_step is None:
        return None
    used, steps = rk4_step(sim)
    if abs(used - sim.time_step) <= 1e-12 * sim.time_step:
        return None
    if outputs_per_step(sim) > 1:
        return (
            f"simulation.time_step {sim.time_step:g} s is taken as {used:.6g} s, "
            f"{outputs_per_step(sim)} output intervals ({sim.output_interval:g} s)"
        )
    return (
        f"simulation.time_step {sim.time_step:g} s is taken as {used:.6g} s, the step that "
        f"divides output_interval ({sim.output_interval:g} s, {steps} per output)"
    )


# the largest h |lambda| at which rk4 is stable, whatever the eigenvalue's direction in the
# left half-plane (2.96, 2.83 on the imaginary axis, 2.79 on the real one), rounded up
RK4_REACH = 3.0


EARLY_STATES = 6_000  # the lines' states (1,000 nodes) from which a step is judged early


def rk4_early_check(sim: Simulation, axial: "Axial | None") -> None:
    """rk4 certainly beyond its stability limit, told from the case before the build and its
    statics (``axial_bound``: a lower bound of the fastest motion), for a system of at least
    EARLY_STATES lines' states, whose statics may take a minute (a MoorDyn deck of 1,200
    segments took 67 s before ``rk4_check`` refused its step): refused unless the case allows
    it. A smaller system is left to ``rk4_check``, which names the exact limit, the node that
    moves and a step to take."""
    if sim.integrator != "rk4" or axial is None or sim.allow_unstable_step:
        return
    if axial.states < EARLY_STATES:
        return
    dt, _ = rk4_step(sim)
    if dt * axial.frequency <= RK4_REACH:
        return
    raise CaseError(
        f"simulation.time_step: {dt:.4g} s is beyond rk4's stability limit: the fastest axial "
        f"motion of {axial.where} is {axial.frequency:.4g} rad/s or faster, which makes rk4 "
        f"unstable above time_step {RK4_REACH / axial.frequency:.3g} s at most. Use a shorter "
        "time_step (validate then checks it against the built system), or integrator: dopri5 "
        "(it adapts its step), or set simulation.allow_unstable_step: true to run anyway"
    )


def rk4_check(sim: Simulation, system: BuiltSystem) -> str | None:
    """rk4 beyond its stability limit about the start: refused (CaseError) unless the case
    allows it (then a warning); within NEAR_LIMIT of it, a warning; else None."""
    if sim.integrator != "rk4":
        return None
    dt, _ = rk4_step(sim)
    limit = rk4_limit(system)  # about the start: the linearised system's eigenvalues
    if dt <= NEAR_LIMIT * limit.step:
        return None
    wanted = max(NEAR_LIMIT * limit.step, 1e-300)
    step = sim.output_interval / math.ceil(sim.output_interval / wanted - 1e-9)
    motion = (
        f"the fastest motion about the start ({limit.frequency:.4g} rad/s, moving {limit.what} "
        f"most) makes rk4 unstable above time_step {limit.step:.3g} s"
    )
    if dt <= limit.step:  # tensions that rise in the run (a snatch, a faster tow) raise it
        return (
            f"simulation.time_step {dt:.4g} s is close to rk4's stability limit: {motion}. A "
            f"shorter time_step (about {step:.4g} s) or integrator: dopri5 is safer"
        )
    if sim.allow_unstable_step:
        return f"simulation.time_step {dt:.4g} s is beyond rk4's stability limit: {motion}"
    raise CaseError(
        f"simulation.time_step: {dt:.4g} s is beyond rk4's stability limit: {motion}. Use "
        f"time_step {step:.4g} s or less (it divides output_interval), or integrator: dopri5 "
        "(it adapts its step), or set simulation.allow_unstable_step: true to run anyway"
    )


WORK_BUDGET = 2e10  # states x steps a run may take without asking: about an hour at 0.2 us


def cost_check(sim: Simulation, states: int, axial: "Axial | None" = None) -> None:
    """A run whose work can be estimated before it starts (its fixed steps, or at least
    ``duration / max_step`` adaptive ones, or for dopri5 at least the steps its stability
    allows on the lines' fastest axial motion ``axial``; times its states) and exceeds
    WORK_BUDGET is refused with the estimate unless the case allows it
    (``simulation.allow_long_run``)."""
    fixed = sim.integrator in FIXED_STEP_INTEGRATORS
    step = rk4_step(sim)[0] if fixed else sim.max_step
    bounded = not fixed and sim.integrator == "dopri5" and axial is not None
    if bounded and axial is not None and (step is None or DOPRI5_REACH / axial.frequency < step):
        step = DOPRI5_REACH / axial.frequency
    else:
        bounded = False
    if step is None or sim.allow_long_run:
        return
    steps = sim.duration / step
    work = steps * states
    if work > WORK_BUDGET:
        why = fix = ""
        if bounded and axial is not None:
            why = (f" (dopri5's steps are at most {DOPRI5_REACH:g} / {axial.frequency:.3g} rad/s, "
                   f"the fastest axial motion of {axial.where})")  # fmt: skip
            fix = "use fewer, longer segments, "
        raise CaseError(
            f"simulation: about {steps:.3g} steps of {states:,} states ({work:.2g} state-steps, "
            f"more than the {WORK_BUDGET:.0e} that run in about an hour){why}; {fix}lengthen "
            "simulation.time_step (or max_step), shorten duration, or set "
            "simulation.allow_long_run: true (seacable run --yes) to run it anyway"
        )


# the longest step [s] times |lambda| at which dopri5 is stable (its region reaches 3.3 along
# the negative real axis, less along the imaginary one)
DOPRI5_REACH = 3.5


class Axial(NamedTuple):
    """A lower bound of the fastest axial motion of a case's lumped lines [rad/s], where it
    is, and the lines' interior nodes' states (a lower bound of the system's)."""

    frequency: float
    where: str
    states: int


def axial_bound(case) -> Axial | None:
    """``Axial`` from the case alone, before anything is built: an interior node of a lumped
    line, between segments of length l, axial stiffness EA and mass m a metre (with the whole
    normal added mass in water: more than it has along the line), has a stiffness of at least
    k = EA / l along a segment against a mass of m l: by Rayleigh's quotient the system holds
    a mode at sqrt(EA / (m l^2)) or faster (taut segments: more; 2 sqrt(k / (m l)) for a long
    straight chain). None without a lumped line of two segments or more."""
    types = {t.name: t for t in case.line_types}
    env = case.environment
    best: Axial | None = None
    states = 0
    for line in case.lines:
        if getattr(line, "model", None) != "lumped_mass":
            continue
        interior = sum(section.segments for section in line.sections) - 1
        states += 6 * interior
        for k, section in enumerate(line.sections if interior else ()):
            kind = types.get(section.type)
            if kind is None or kind.axial_stiffness is None:
                continue
            water = 0.0 if env.in_air else env.water_density
            mass = kind.mass_per_length + water * kind.added_mass_coefficient * (
                math.pi * kind.diameter**2 / 4.0
            )
            length = section.length / section.segments
            frequency = math.sqrt(kind.axial_stiffness / mass) / length
            if best is None or frequency > best.frequency:
                where = (f"line '{line.name}' (sections[{k}]: segments of {length:.3g} m, "
                         f"EA {kind.axial_stiffness:.3g} N)")  # fmt: skip
                best = Axial(frequency, where, 0)
    return None if best is None else best._replace(states=states)


def rk4_factor(z: np.ndarray) -> np.ndarray:
    """The classical Runge-Kutta scheme's amplification R(z) of a mode over a step, z = h lambda."""
    return 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0)))


def rk4_stable_step(values: np.ndarray) -> float:
    """The longest step [s] at which no mode of eigenvalues ``values`` [1/s] grows faster under
    rk4 than it does in time (infinite for no eigenvalue, or only zero ones)."""
    limit = np.inf
    for value in np.asarray(values, dtype=complex):
        size = abs(value)
        if size == 0.0:
            continue
        h = np.linspace(4.0 / size / GRID, 4.0 / size, GRID)
        z = h * value
        grows = np.abs(rk4_factor(z)) > np.maximum(1.0, np.abs(np.exp(z))) * (1.0 + GROWTH)
        if grows.any():
            first = int(np.argmax(grows))
            limit = min(limit, float(h[first - 1]) if first else 0.0)
    return limit


class Rk4Limit(NamedTuple):
    """rk4's longest stable step [s] about a system's state, the fastest motion's frequency
    [rad/s] and where it moves most."""

    step: float
    frequency: float
    what: str


def rk4_limit(system: BuiltSystem, y: np.ndarray | None = None, time: float = 0.0) -> Rk4Limit:
    """rk4's stability limit for ``system`` about ``y`` (default: its initial state)."""
    modes = fastest_modes(system, y, time)
    frequency = float(np.abs(modes.values).max()) if modes.values.size else 0.0
    return Rk4Limit(rk4_stable_step(modes.values), frequency, modes.what)
