"""The contract of a time integrator, as a Protocol with its rules (``tests/test_contracts.py``
and ``tests/test_reproducible.py`` check them, numerically)."""

from typing import Any, Protocol, runtime_checkable

import numpy as np


@runtime_checkable
class ChunkIntegrator(Protocol):
    """A compiled integrator's chunk: ``numerics.integrators.rk4_chunk`` and ``dopri5_chunk``,
    ``numerics.system_implicit.chunk`` (the implicit family); SciPy's and SUNDIALS' stiff
    methods follow the same rules from Python (``numerics.stiff.StiffStepper.advance``). Its
    arguments start with ``first_output`` (the fixed-step ones: ``first_step``), ``y`` and
    ``output_interval`` [s] and end with ``states``, ``times`` and ``work`` (and the arrays it
    carries from chunk to chunk).

    0. It calls the system only through ``system.kernel`` (``rhs``, ``project``, ``projects``),
       and projects the state after every accepted step.
    1. It advances the flat state ``y`` in place over a *chunk* of ``n_outputs`` output
       intervals of length ``output_interval``, starting at the global output index
       ``first_output``, and writes the state at the end of each interval in ``states[j]`` and
       its time, ``(first_output + j + 1) * output_interval``, in ``times[j]``; the whole chunk
       runs in compiled code. A fixed-step chunk counts steps instead: ``n_steps`` from the
       global step ``first_step``, either of which may fall inside an output interval (a row at
       each output reached), so that the run loop can cut a long interval short (a signal is
       answered within about a second whatever the output interval); an implicit chunk's
       step may instead span ``outputs_per_step`` whole intervals, each step then writing that
       many rows, those inside it interpolated (``numerics.dense``; the run drops the rows a
       last step writes past the duration); dopri5's takes a budget
       of steps, ``max_steps``, and stops inside an interval past it, its time in ``clock``
       for the next chunk to resume from.
    2. It returns ``(completed, status, ...)`` where ``completed`` is the number of output rows
       written and ``status`` a kernel status code (0 = sound); ``work`` is an int64 array of
       the counters of ``numerics.integrators.WORK_NAMES``, added to in place: accepted steps,
       rejected steps, right-hand-side evaluations, failed (non-finite) evaluations, Jacobians,
       linear solves.
    3. On a non-finite or singular evaluation it stops at once, leaves ``y`` at the last sound
       state of the completed rows and reports the status; it never raises.
    4. Output times are hit exactly (fixed-step: an integer number of steps per interval, or
       of intervals per implicit step; adaptive: the step is clipped at each output time).
    5. Its results and work counters do not depend on how a run is cut into chunks (the run
       loop sizes chunks from wall time, so they would otherwise depend on machine load): every
       time is computed from global indices (output index times the interval, plus steps since
       that output times the step), never accumulated from a chunk's start, and every state
       carried from step to step (the step size proposal, a first-same-as-last derivative, the
       last acceleration, a predictor, kept Newton factors) lives in arrays the caller
       allocates once per run and passes to every chunk. ``tests/test_reproducible.py`` checks
       it for every integrator.
    """

    def __call__(self, first_output: int, y: np.ndarray, output_interval: float,
                 *args: Any) -> tuple: ...  # fmt: skip
