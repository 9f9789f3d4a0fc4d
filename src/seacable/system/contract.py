"""The contract of what the run loop (``simulation``) reaches of a model, as a Protocol with
its rules (``tests/test_contracts.py`` checks ``system.model`` against it)."""

from typing import Any, Protocol, runtime_checkable

import numpy as np


@runtime_checkable
class RunModel(Protocol):
    """What the run loop reaches of a model (a module): the contract every model honours
    (``tests/test_contracts.py`` checks each one).

    1. ``build(case, base_dir) -> system``: flat parameters (``system.params``, a NamedTuple of
       arrays and numbers whose types depend on no count) and the initial state
       (``system.y0``); a case the model cannot run raises CaseError naming the field.
    2. ``workspace(system)``: the scratch its compiled functions share, allocated once per run.
    3. ``rows(times, states, system, w) -> (rows, status)``: output rows (``time`` first), every
       variable the model records, and the worst kernel status met.
    4. ``sizes(system)``, ``coords(system)``: the dimensions and coordinates of its results.
    5. ``rates(system, y)``: the magnitudes a divergence message names (``RATE_WHAT`` says what
       they are), ``fastest_frequency(system, y=None, time=0.0)``: the magnitude of the
       fastest motion about a state [rad/s] and what moves most in it,
       ``state_scale(case, system)``: each state's typical size (the adaptive integrators'
       default tolerance), ``shortest_segment(system)`` [m] (the implicit
       schemes' Newton tolerance), ``DAMPING_ADVICE``: what a divergence message suggests.
    6. ``variables(system)``: what it records, per group; ``jacobian_sparsity(system)``: the
       Jacobian's pattern (SciPy's stiff integrators and the implicit schemes).
    7. ``watch(system)``: an object whose ``see(rows)`` takes every chunk of output rows and
       whose ``warnings()`` lists what they showed that a start would have been refused for
       (``system.geometry.Watch``).
    8. ``start_memory(system, w, t, y)`` at a run's start and ``after_step(system, w, t, y)``
       after each accepted step of an integrator driven from Python (the compiled ones call
       ``system.kernel.after_step`` themselves): what a model keeps of its past (radiation
       memory) is written there only, never by a right-hand side.
    Optional: ``positions`` (the implicit schemes' unknowns), ``refresh_interval``/``refresh``
    (parameters replaced during a run: the servo).
    """

    RATE_WHAT: tuple
    DAMPING_ADVICE: str

    def build(self, case, base_dir=None) -> Any: ...
    def workspace(self, system) -> Any: ...
    def rows(self, times, states, system, w) -> tuple[dict, int]: ...
    def sizes(self, system) -> dict: ...
    def coords(self, system) -> dict: ...
    def rates(self, system, y) -> np.ndarray: ...
    def fastest_frequency(self, system, y=None, time=0.0) -> tuple[float, str]: ...
    def state_scale(self, case, system) -> np.ndarray: ...
    def shortest_segment(self, system) -> float: ...
    def variables(self, system) -> dict: ...
    def jacobian_sparsity(self, system) -> Any: ...
    def watch(self, system) -> Any: ...
    def start_memory(self, system, w, t, y) -> None: ...
    def after_step(self, system, w, t, y) -> None: ...
