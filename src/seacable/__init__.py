"""seacable: dynamics of marine cables and the bodies they connect.

Public API::

    case = seacable.load_case("examples/thesis_6_1_sim6_submerged_60_links_forced.yaml")
    results = seacable.simulate(case, output="run.nc")
    results.dataset["lines/umbilical/tension"]  # a DataTree: a group per body and per line
    seacable.equilibria(case)  # ships on turrets and hawsers: every equilibrium, its stability
"""

import importlib
from typing import TYPE_CHECKING, Any

from seacable.errors import (
    CaseError,
    InputError,
    OutputError,
    SeacableError,
    SimulationDiverged,
    SimulationInterrupted,
)

if TYPE_CHECKING:
    from seacable.analysis import statics
    from seacable.case.loader import load_case
    from seacable.case.system import SystemCase
    from seacable.results import Results
    from seacable.simulation import simulate
    from seacable.stability.api import compare, continuation, curves, equilibria, periodic_orbit
    from seacable.stability.plane import Weather
    from seacable.system.statics import StaticsError

# the public names imported on first use: a run does not import the analyses (SciPy's
# optimisers, the stability package), a command imports what it uses
_LAZY = {
    "statics": "seacable.analysis",
    "load_case": "seacable.case.loader",
    "SystemCase": "seacable.case.system",
    "Results": "seacable.results",
    "simulate": "seacable.simulation",
    "compare": "seacable.stability.api",
    "continuation": "seacable.stability.api",
    "curves": "seacable.stability.api",
    "equilibria": "seacable.stability.api",
    "periodic_orbit": "seacable.stability.api",
    "Weather": "seacable.stability.plane",
    "StaticsError": "seacable.system.statics",
}


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'seacable' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


__version__ = "0.1.0"

__all__ = [
    "CaseError",
    "InputError",
    "OutputError",
    "Results",
    "SeacableError",
    "SimulationDiverged",
    "SimulationInterrupted",
    "StaticsError",
    "SystemCase",
    "Weather",
    "__version__",
    "compare",
    "continuation",
    "curves",
    "equilibria",
    "load_case",
    "periodic_orbit",
    "simulate",
    "statics",
]
