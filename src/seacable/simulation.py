"""Run a case: assemble the system, integrate in compiled chunks, stream results."""

import logging
import signal
import threading
import time as _time
from pathlib import Path
from typing import Any

import numpy as np

from seacable import run_report
from seacable.case import loader, schema
from seacable.case.system import SystemCase, ignored_inputs
from seacable.case.units import unit_warnings
from seacable.errors import CaseError, SimulationDiverged, SimulationInterrupted
from seacable.kernels import jit
from seacable.kernels.status import Status
from seacable.numerics import implicit_setup, integrators, stability, stiff, system_implicit
from seacable.numerics.stability import rk4_step
from seacable.results import (
    STATUS_COMPLETE,
    STATUS_DIVERGED,
    STATUS_INTERRUPTED,
    Results,
    _Sink,
    check_output,
    provenance,
)
from seacable.system import kernel as system_kernel
from seacable.system import model as system_model
from seacable.system import utilisation

log = logging.getLogger(__name__)

ATOL_FLOOR = 1e-3  # default atol: at least rtol times this fraction of each state's scale
# the solver_atol attribute of a run with the default absolute tolerance (absolute_tolerance)
DEFAULT_ATOL = (
    "rtol times each state's largest magnitude (dopri5: so far; stiff integrators: at the start), "
    f"at least {ATOL_FLOOR:g} rtol times the state's scale (system.model.state_scale)"
)
_CHUNK_SECONDS = 0.5  # wall time aimed at per compiled chunk (progress, Ctrl-C, streaming)


# fixed-step implicit schemes of ``numerics.system_implicit``
IMPLICIT = schema.IMPLICIT_INTEGRATORS
FIXED_STEP = ("rk4", *IMPLICIT)


def _solver_settings(sim: schema.Simulation) -> dict:
    settings: dict[str, Any] = {
        "integrator": sim.integrator,
        "duration": sim.duration,
        "output_interval": sim.output_interval,
        "constraint_stabilization_frequency": sim.constraint_stabilization_frequency,
    }
    if sim.integrator in FIXED_STEP:
        settings["time_step"] = rk4_step(sim)[0]
        if sim.integrator in IMPLICIT:
            settings.update(
                newton_tolerance=sim.newton_tolerance,
                max_newton_iterations=sim.max_newton_iterations,
            )
            names = ("pa", "b", "gamma", "alpha_m", "alpha_f")
            settings.update(
                {f"scheme_{k}": float(v) for k, v in zip(names, _scheme(sim), strict=True)}
            )
    else:
        settings.update(rtol=sim.rtol, atol=sim.atol if sim.atol is not None else DEFAULT_ATOL)
        settings["initial_step"] = sim.initial_step
        settings["max_step"] = sim.max_step if sim.max_step is not None else sim.output_interval
    return settings


def _scheme(sim: schema.Simulation) -> np.ndarray:
    return implicit_setup.scheme(
        sim.integrator,
        theta=sim.theta,
        gamma=sim.newmark_gamma,
        beta=sim.newmark_beta,
        spectral_radius=sim.spectral_radius,
    )


def prepare(case: SystemCase) -> tuple[Any, str | None]:
    """Everything a run does before its first step, and ``seacable validate`` with it: the
    case's form, the system built (tables read, geometry checked, the statics it starts from
    solved), the step checked against the fastest motion, values that look like the wrong
    unit (``case.units``), inputs that act on nothing (``case.system.ignored_inputs``), line
    sections whose tension at the start exceeds ``utilisation_limit`` of their breaking
    strength (``system.utilisation``). Returns the built system and the warnings, joined (None
    when there are none). Raises CaseError (or StaticsError)."""
    _check_case(case)
    sim = case.simulation
    axial = stability.axial_bound(case)
    if axial is not None:  # before the build and its statics (100,000 segments: 300 s)
        stability.rk4_early_check(sim, axial)
        stability.cost_check(sim, axial.states, axial)
    system = system_model.build(case, loader.case_base_dir(case))
    stability.cost_check(sim, len(system.y0), axial)
    warnings = [*unit_warnings(case), *ignored_inputs(case), stability.rounded_step(sim),
                _dense_warning(sim, system), stability.rk4_check(sim, system),
                *utilisation.start_warnings(case, system.params, system.y0)]  # fmt: skip
    return system, "; ".join(w for w in warnings if w) or None


def output_count(sim: schema.Simulation) -> int:
    """The output intervals of a run (its rows but the first, at t = 0)."""
    return max(1, int(round(sim.duration / sim.output_interval)))


def _check_case(case: SystemCase) -> None:
    if not isinstance(case, SystemCase):
        raise CaseError(
            "the case is in the single-cable form (cables:), which does not run any more; write "
            "it as a system of bodies and lines: seacable upgrade case.yaml -o system.yaml"
        )


def absolute_tolerance(case: SystemCase, model, system) -> tuple[np.ndarray, np.ndarray]:
    """The adaptive integrators' absolute tolerance of each state and, for dopri5's default,
    the largest magnitude of each state so far (empty when not tracked).

    ``simulation.atol`` given: that value for every state, no tracking. Default: a floor of
    rtol times ATOL_FLOOR times the model's scale of each state (``state_scale``), and dopri5
    raises state i's tolerance to rtol times the largest |y_i| reached so far, so that each
    state's error is measured against its own amplitude (small angles and rates included)
    and rtol alone sets the accuracy. SciPy's and SUNDIALS' integrators take a fixed
    tolerance: rtol times the larger of |y_i| at the start and the floor."""
    sim = case.simulation
    size = len(system.y0)
    if sim.atol is not None:
        return np.full(size, sim.atol), np.empty(0)
    floor = sim.rtol * ATOL_FLOOR * model.state_scale(case, system)
    if sim.integrator in stiff.STIFF:
        return np.maximum(floor, sim.rtol * np.abs(system.y0)), np.empty(0)
    return floor, np.abs(system.y0)


class _Run:
    """One integration: holds the compiled state and writes rows to the sink."""

    def __init__(self, case: SystemCase, model, system, sink: _Sink):
        self.case = case
        self.sim = case.simulation
        self.model = model
        self.system = system
        self.p = system.params
        self.sink = sink
        self.y = system.y0.copy()
        self.t = 0.0
        self.w = model.workspace(system)
        model.start_memory(system, self.w, self.t, self.y)
        self.work = np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
        self.h = self.sim.initial_step
        positions = getattr(model, "positions", lambda system: len(system.y0) // 2)(system)
        self.acc = np.zeros(positions)  # implicit schemes: the acceleration a0
        self.stepper = None  # SciPy / SUNDIALS integrators
        self.stiff_failure = None
        self.n_outputs = output_count(self.sim)
        self.done = 0
        self.into = 0  # fixed steps taken into the output interval under way
        self.each = stability.outputs_per_step(self.sim)  # output intervals a step spans
        # state carried from chunk to chunk (numerics.contract, point 5): dopri5's
        # stages with a flag saying whether k[0] is the derivative at (t, y); the implicit
        # schemes' predictor and Newton factors
        self.stages = np.zeros((7, len(self.y)))
        self.fsal = np.zeros(1, dtype=np.int64)
        # dopri5's time inside an output interval where a chunk stopped (and a flag), and the
        # steps a chunk may try (sized by _loop to about _CHUNK_SECONDS: a long interval is cut
        # short, so that a signal is answered)
        self.clock = np.zeros(2)
        self.budget = 10
        self.carry = None
        self.newton = None  # a system's implicit steps: how increments move, the matrix layout
        if self.sim.integrator in IMPLICIT:
            self.newton = implicit_setup.newton(case, system)
            self.carry = implicit_setup.carry(system, self.newton[1])
        self.atol, self.magnitude = absolute_tolerance(case, model, system)
        self.watch = model.watch(system)  # what the rows must not show (system.geometry)
        # adaptive integrators: state values at output times whose error weight atol set
        # (above rtol |y|, and above rtol times the largest |y| so far when that is tracked),
        # out of all
        self.seen = np.zeros(len(self.y))
        self.absolute_governed = 0
        self.samples = 0

    def emit(self, times, states) -> int:
        if self.sim.integrator not in FIXED_STEP:
            size = np.abs(states)
            if self.magnitude.size:
                size = np.maximum.accumulate(np.vstack([self.seen, size]))[1:]
                self.seen = size[-1].copy()
            self.absolute_governed += int(np.count_nonzero(self.atol > self.sim.rtol * size))
            self.samples += states.size
        rows, status = self.model.rows(times, states, self.system, self.w)
        self.sink.write(rows)
        self.watch.see(rows)
        return status

    def refresh_every(self) -> int:
        """Output intervals between calls of the model's ``refresh`` (0: never)."""
        interval = getattr(self.model, "refresh_interval", lambda case: None)(self.case)
        if not interval:
            return 0
        return max(1, round(interval / self.sim.output_interval))

    def compile(self) -> None:
        """Compile (or load from the cache) the kernels this run uses, before any timing or
        progress display: a zero-length chunk does nothing but dispatch (on copies: the run's
        carried state stays as it is)."""
        empty = np.empty((0, self.y.shape[0]))
        y, work, sim = self.y.copy(), np.zeros_like(self.work), self.sim
        if sim.integrator == "rk4":
            integrators.rk4_chunk(0, y, 1.0, 1, 0, self.p, self.w, empty, np.empty(0), work)
        elif sim.integrator in stiff.STIFF:  # the solvers' steps call these from Python
            system_kernel.rhs(0.0, y, self.p, self.w, np.empty_like(y))
            system_kernel.project(y, self.p, self.w)
            system_kernel.after_step(0.0, y, self.p, system_kernel.make_work(self.p))
        elif sim.integrator in IMPLICIT and self.newton is not None:
            if implicit_setup.initial_acceleration(0.0, y, self.p, self.w, self.acc) != Status.OK:
                self.acc[:] = 0.0
            carry = implicit_setup.carry(self.system, self.newton[1])
            self._newmark(y, 1, 0, empty, np.empty(0), work, carry)
        else:
            integrators.dopri5_chunk(
                0, y, 1.0, 0, 1.0, 1.0, self.atol, self.magnitude.copy(), 1.0, self.p, self.w,
                empty, np.empty(0), work,
                self.stages.copy(), self.fsal.copy(), np.zeros(2), 1,
            )  # fmt: skip
        self.model.rows(np.empty(0), empty, self.system, self.w)

    def refresh(self) -> None:
        """Let the model replace its parameters (at output-interval multiples, always at a
        chunk boundary whatever the chunk sizes); what was derived from the old parameters is
        dropped: dopri5's first-same-as-last derivative, the implicit schemes' kept factors."""
        self.p = self.model.refresh(self.case, self.p, self.t, self.y)
        self.fsal[0] = 0
        if self.carry is not None:
            self.carry[1][0] = 0.0
            self.carry[1][3] = 0.0  # the forces the last step ended with

    def _stiff_stepper(self) -> stiff.StiffStepper:
        sim = self.sim
        p, w = self.p, self.w
        ydot = np.empty_like(self.y)
        state = np.empty_like(self.y)

        def fun(t, y):
            # the solvers may pass a read-only or strided view: a copy into one writable
            # C-contiguous array keeps the compiled signature (a read-only y would compile the
            # whole right-hand side again, 27 s)
            np.copyto(state, y)
            status = system_kernel.rhs(t, state, p, w, ydot)
            if status != Status.OK or not np.isfinite(ydot).all():
                raise FloatingPointError(f"status {status} at t = {t:.6g} s")
            return ydot.copy()

        return stiff.StiffStepper(
            sim.integrator, fun, self.t, self.y,
            rtol=sim.rtol, atol=self.atol,
            max_step=sim.max_step if sim.max_step is not None else sim.output_interval,
            first_step=sim.initial_step, sparsity=self.model.jacobian_sparsity(self.system),
            after=lambda t, y: self.model.after_step(self.system, w, t, y),
        )  # fmt: skip

    def _advance_stiff(self, count, states, times):
        if self.stepper is None:
            self.stepper = self._stiff_stepper()
        targets = (self.done + 1 + np.arange(count)) * self.sim.output_interval
        done, failure = self.stepper.advance(targets, states)
        times[:done] = targets[:done]
        if done:
            self.y = states[done - 1].copy()
        self.work[:] = self.stepper.work()
        self.stiff_failure = failure
        return done, (Status.OK if failure is None else Status.NON_FINITE)

    def _newmark(self, y, steps, count, states, times, work, carry, first_step=0):
        sim = self.sim
        tol = sim.newton_tolerance * self.model.shortest_segment(self.system)
        return system_implicit.chunk(
            first_step, y, self.acc, sim.output_interval, steps, self.each, count, _scheme(sim),
            tol,
            sim.max_newton_iterations, implicit_setup.lagged(self.p),
            implicit_setup.frozen(self.p), self.w, *self.newton, carry, states, times, work,
            True if self.newton[2].line.shape[0] > 0 else None,
        )  # fmt: skip

    def units(self) -> int:
        """What ``advance`` counts, per output interval: fixed steps for rk4 and the implicit
        schemes (a chunk may end inside an output interval, so a signal is answered within
        about a second however long the interval), output intervals for the others."""
        return rk4_step(self.sim)[1] if self.sim.integrator in FIXED_STEP else 1

    def covering(self, outputs: int) -> int:
        """The units (``units``) that reach ``outputs`` output intervals from the start: an
        implicit step may span several (``each``), the last one past the run's end."""
        return -(-outputs // self.each) * self.units()

    def position(self) -> int:
        """The units done."""
        return self.covering(self.done) + self.into

    def advance(self, count: int) -> int:
        """Integrate ``count`` units (``units``: fixed steps, or output intervals); returns the
        kernel status."""
        ny = self.y.shape[0]
        sim = self.sim
        per = self.units()
        outputs = (self.into + count) // per * self.each  # the outputs this chunk reaches
        states = np.empty((outputs, ny))
        times = np.empty(outputs)
        if sim.integrator in FIXED_STEP:
            first = self.position()  # the global step
            if sim.integrator == "rk4":
                completed, status = integrators.rk4_chunk(
                    first, self.y, sim.output_interval, per, count, self.p, self.w, states,
                    times, self.work,
                )  # fmt: skip
            else:
                completed, status = self._newmark(
                    self.y, per, count, states, times, self.work, self.carry, first
                )
            if status == Status.OK:
                self.into = (self.into + count) % per
        elif sim.integrator in stiff.STIFF:
            completed, status = self._advance_stiff(count, states, times)
        else:
            max_step = sim.max_step if sim.max_step is not None else sim.output_interval
            completed, status, self.h = integrators.dopri5_chunk(
                self.done, self.y, sim.output_interval, count, self.h, sim.rtol, self.atol,
                self.magnitude, max_step, self.p, self.w, states, times, self.work, self.stages,
                self.fsal, self.clock, self.budget,
            )  # fmt: skip
        completed = min(completed, self.n_outputs - self.done)  # a last step past the end
        if completed:
            self.t = times[completed - 1]
            self.done += completed
            out_status = self.emit(times[:completed], states[:completed])
            status = status or out_status
        return status


def simulate(
    case: SystemCase,
    output=None,
    progress: bool = False,
    chunk_outputs: int | None = None,
) -> Results:
    """Run ``case`` and return its :class:`Results`.

    Parameters
    ----------
    case
        A validated case (:func:`seacable.load_case`).
    output
        Optional NetCDF path; results are appended to it as the run goes, so a run that diverges
        or is interrupted leaves a readable file whose ``status`` attribute says so.
    progress
        Show a progress bar when the run lasts more than about two seconds.
    chunk_outputs
        Output intervals per compiled chunk (the rows written, the progress bar moved and
        Ctrl-C honoured between chunks); None: chunks of about half a second of wall time.
        The results do not depend on it (bit for bit); tests use it to force chunk sizes.

    Raises
    ------
    SimulationDiverged
        The state became non-finite (or a pinned end could not be closed); the exception's
        ``results`` hold everything computed before.
    SimulationInterrupted
        Ctrl-C; ``results`` hold everything computed before.
    """
    model = system_model
    _check_case(case)
    if output is not None:  # refused before the statics and the compiling, not after
        check_output(Path(output), loader.files_read(case))
    system, warning = prepare(case)
    sim = case.simulation
    settings = _solver_settings(sim)
    if warning:
        log.warning(warning)
        settings["warning"] = warning
    attrs = provenance(loader.case_text(case), settings)
    attrs.update(loader.record(case))
    attrs.update(system.layout.facts)  # how the system was built (the added mass's point)
    variables = model.variables(system)
    sink = _Sink(output, model.sizes(system), model.coords(system), variables, attrs,
                 rows=1 + output_count(sim), inputs=loader.files_read(case))  # fmt: skip
    run = _Run(case, model, system, sink)
    stop = _Stop()
    previous = stop.install()
    bar = None
    try:
        _compile(run)
        bar = _progress_bar(progress, run.n_outputs, sim.output_interval)
        run.emit(np.array([0.0]), system.y0[None, :].copy())
        stop.armed = True  # from here a signal is acted on between chunks
        status = _loop(run, bar, chunk_outputs, stop)
    except KeyboardInterrupt:
        signum = stop.signum or signal.SIGINT
        who = (
            "by the user (Ctrl-C)"
            if signum == signal.SIGINT
            else f"by {signal.Signals(signum).name}"
        )
        results = sink.finish(
            STATUS_INTERRUPTED,
            f"interrupted {who} at t = {run.t:.6g} s; results up to that time are kept",
            run_report.attributes(run, run.sim.integrator in FIXED_STEP),
        )
        raise SimulationInterrupted(results.message, results, int(signum)) from None
    finally:
        stop.restore(previous)
        if bar is not None:
            bar.close()
    if status != Status.OK:
        message = _divergence_message(run, status, settings)
        results = sink.finish(
            STATUS_DIVERGED, message, run_report.attributes(run, run.sim.integrator in FIXED_STEP)
        )
        raise SimulationDiverged(message, results)
    return sink.finish(
        STATUS_COMPLETE,
        "the run reached its duration",
        run_report.attributes(run, run.sim.integrator in FIXED_STEP),
    )


class _Stop:
    """SIGINT (Ctrl-C) and SIGTERM during a run: before its loop they interrupt at once
    (nothing computed yet); in it they are noted and acted on after the chunk under way (about
    _CHUNK_SECONDS of wall time), so that the rows written are whole; during a stiff
    integrator's chunk (SciPy's and SUNDIALS' steps call the Python right-hand side, where the
    handler runs) at once: that chunk's rows are not written yet, and are dropped."""

    def __init__(self):
        self.signum = 0
        self.armed = False
        self.immediate = False  # a stiff integrator's chunk: its rows are not written yet

    def __call__(self, signum, frame):
        self.signum = signum
        if not self.armed or self.immediate:
            raise KeyboardInterrupt

    def install(self) -> dict:
        """Handle both signals (only the main thread may); returns the handlers replaced."""
        if threading.current_thread() is not threading.main_thread():
            return {}
        return {sig: signal.signal(sig, self) for sig in (signal.SIGINT, signal.SIGTERM)}

    def restore(self, previous: dict) -> None:
        for sig, handler in previous.items():
            signal.signal(sig, handler)


def _loop(run: _Run, bar, chunk_outputs: int | None = None, stop: _Stop | None = None) -> int:
    """Advance the run in compiled chunks of ``chunk_outputs`` output intervals (None: sized
    to about _CHUNK_SECONDS of wall time), stopping at each model refresh, and after the
    chunk in which ``stop`` noted a signal (KeyboardInterrupt)."""
    if chunk_outputs is not None and chunk_outputs < 1:
        raise ValueError(f"chunk_outputs must be a positive integer or None, not {chunk_outputs}")
    # a chunk counts fixed steps, or output intervals (_Run.units)
    chunk = run.covering(chunk_outputs) if chunk_outputs else 1
    refresh = run.covering(run.refresh_every())  # at a step's end (an implicit step may span
    total = run.covering(run.n_outputs)  # several output intervals)
    while run.position() < total:
        at = run.position()
        count = min(chunk, total - at)
        if refresh:
            count = min(count, refresh - at % refresh)
        start = _time.perf_counter()
        before, tried = run.done, int(run.work[0] + run.work[1])
        if stop is not None:  # SciPy's and SUNDIALS' steps call Python: a signal acts at once
            stop.immediate = run.sim.integrator in stiff.STIFF
        status = run.advance(count)
        if stop is not None:
            stop.immediate = False
        if bar is not None:
            bar.update(run.done - before)
        if status != Status.OK:
            return status
        if stop is not None and stop.signum:
            raise KeyboardInterrupt
        reached = run.position()
        if refresh and reached > at and reached % refresh == 0 and reached < total:
            run.refresh()  # once, as the chunk reaches the boundary (a cut dopri5 chunk may not)
        if chunk_outputs is None:
            took = max(_time.perf_counter() - start, 1e-6)
            chunk = int(min(max(1, count / took * _CHUNK_SECONDS), 4 * chunk + 1))
            steps = int(run.work[0] + run.work[1]) - tried
            run.budget = int(min(max(10, steps / took * _CHUNK_SECONDS), 4 * run.budget + 1))
        else:
            run.budget = 2**62  # a chunk of the outputs asked, however many steps
    return Status.OK


def _compile(run: _Run) -> None:
    """Compile (or load from numba's cache) the run's kernels, announced when it lasts
    (kernels.jit.announced)."""
    with jit.announced(f"the {run.sim.integrator} integrator's steps and the outputs",
                       "about 5 to 30 s"):  # fmt: skip
        run.compile()


def _progress_bar(progress: bool, total: int, interval: float):
    if not progress:
        return None
    from tqdm import tqdm

    return tqdm(total=total, unit="out", delay=2.0, desc=f"simulating ({interval:g} s per output)")


def _dense_warning(sim: schema.Simulation, system) -> str | None:
    """A warning when the integrator builds a dense Jacobian of a large system."""
    size = len(system.y0)
    dense = sim.integrator in ("cvode", "lsoda")  # bdf and radau colour the sparse pattern
    if dense and size > 200:
        return (
            f"simulation.integrator {sim.integrator} builds a dense Jacobian for this model "
            f"({size} states: {size} right-hand sides and a dense factorisation per Jacobian); "
            "it is slow beyond a few dozen links. Use dopri5 or rk4 (or, for the planar "
            "rigid_links model, newmark or generalized_alpha, which solve in O(n))"
        )
    return None


def _divergence_message(run: _Run, status: int, settings: dict) -> str:
    rates = run.model.rates(run.system, run.y)
    worst = int(np.nanargmax(rates)) if np.any(np.isfinite(rates)) else 0
    if status == Status.SINGULAR_CLOSURE:
        what = (
            "the pinned end could not be closed (the cable is pulled straight between its ends, "
            "where a rigid-link model has no unique tension)"
        )
    elif status == Status.NEWTON_FAILED:
        what = (
            f"the implicit step's Newton iteration did not converge in "
            f"{settings['max_newton_iterations']} iterations"
        )
    elif run.stiff_failure is not None:
        what = f"the {settings['integrator']} solver failed ({run.stiff_failure})"
    else:
        what = "the state became non-finite"
    thing, rate, unit, first = run.model.RATE_WHAT
    where = f"{thing} {worst + first} ({rate} {rates[worst]:.4g} {unit} in the last sound state)"
    if settings["integrator"] in IMPLICIT:
        advice = (
            f"reduce simulation.time_step (now {settings['time_step']:.4g} s), raise "
            "max_newton_iterations or loosen newton_tolerance"
        )
    elif settings["integrator"] == "rk4":
        advice = (
            f"reduce simulation.time_step (now {settings['time_step']:.4g} s) or use "
            "integrator: dopri5"
        )
    else:
        advice = "tighten rtol/atol or set max_step"
    damping = getattr(run.model, "damping_advice", lambda system: run.model.DAMPING_ADVICE)
    return (
        f"simulation diverged after t = {run.t:.6g} s: {what}; fastest motion at {where}. Try: "
        f"{advice}; {damping(run.system)}; check very stiff ties or springs. Results up to "
        f"t = {run.t:.6g} s are kept."
    )
