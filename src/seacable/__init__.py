"""seacable: dynamics of marine cables and the bodies they connect.

Public API::

    case = seacable.load_case("examples/thesis_6_1_sim6_submerged_60_links_forced.yaml")
    results = seacable.simulate(case, output="run.nc")
    results.dataset["lines/umbilical/tension"]  # a DataTree: a group per body and per line
    seacable.equilibria(case)  # ships on turrets and hawsers: every equilibrium, its stability
"""

from seacable.analysis import statics
from seacable.case.loader import load_case
from seacable.case.system import SystemCase
from seacable.errors import (
    CaseError,
    OutputError,
    SeacableError,
    SimulationDiverged,
    SimulationInterrupted,
)
from seacable.results import Results
from seacable.simulation import simulate
from seacable.stability.api import compare, continuation, curves, equilibria, periodic_orbit
from seacable.stability.plane import Weather
from seacable.system.statics import StaticsError

__version__ = "0.1.0"

__all__ = [
    "CaseError",
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
