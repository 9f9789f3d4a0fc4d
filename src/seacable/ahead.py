"""Compile ahead of time (``seacable compile``): what the given cases need, or what every case
shares and the common kinds of system, so that a first run later waits for nothing.

What compiles (docs/architecture.md, "Compile time"): the evaluation of a system's kinds (one
copy per set of kinds: ``system.variants``), each integrator's steps, the outputs and the
Python entries, all cached on disk by numba and shared by every later process. Compiling a
case here is running it for two output intervals in memory (and, with ``every``, with each
integrator family and through the statics and the modes as well).
"""

import copy
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import partial
from pathlib import Path

from seacable import analysis, simulation
from seacable.case import loader
from seacable.case.system import SystemCase
from seacable.errors import SeacableError

# the integrators' families: each compiles steps of its own (the implicit schemes share theirs;
# SciPy's and SUNDIALS' solvers call the evaluation from Python)
FAMILIES = ("rk4", "dopri5", "generalized_alpha")
STEPS = {"rk4": 1e-3, "generalized_alpha": 0.1, "dopri5": None}  # [output intervals]

# small systems of the common kinds, compiled when no case is given (their evaluations are
# those of many everyday cases: a buoy on lumped-mass lines and a hawser, a heaving body on a
# planar rigid-link line, a towed 3D rigid-segment line)
_CHAIN = {
    "name": "chain",
    "diameter": 0.09,
    "mass_per_length": 55.0,
    "axial_stiffness": 2.5e8,
    "axial_damping_ratio": 0.8,
    "drag_coefficient_normal": 2.4,
    "drag_coefficient_tangential": 0.4,
}
_UMBILICAL = {
    "name": "umbilical",
    "diameter": 0.02,
    "mass_per_length": 2.47,
    "bending_stiffness": 523.6,
    "drag_coefficient_normal": 1.2,
    "added_mass_coefficient": 0.0,  # the planar model has none
}
_BUOY_FORCES = [
    {"model": "gravity"},
    {"model": "buoyancy"},
    {"model": "drag", "drag_coefficient": 0.8, "area": [20.0, 20.0, 19.6]},
]


def _buoy(name: str, x: float) -> dict:
    """A moored buoy of the built-in systems at (x, 0, 0)."""
    return {
        "name": name,
        "type": "point",
        "position": [x, 0.0, 0.0],
        "mass": 2.0e4,
        "shape": {"kind": "vertical_cylinder", "radius": 2.5, "height": 4.0},
        "added_mass": [8.0e4, 8.0e4, 4.0e4],
        "external forces": _BUOY_FORCES,
    }


BUILT_IN: dict[str, dict] = {
    "moored buoys (lumped-mass lines, a hawser)": {
        "name": "moored buoys",
        "environment": {
            "water_density": 1025.0,
            "water_depth": 50.0,
            "seabed": {"stiffness": 3.0e5, "damping": 3.0e3, "friction_coefficient": 0.5},
        },
        "bodies": [
            {"name": "anchor_a", "type": "fixed", "position": [-130.0, 0.0, -50.0]},
            {"name": "anchor_b", "type": "fixed", "position": [210.0, 0.0, -50.0]},
            _buoy("buoy_a", 0.0),
            _buoy("buoy_b", 80.0),
        ],
        "line_types": [_CHAIN],
        "lines": [
            {
                "name": "a",
                "model": "lumped_mass",
                "from": "anchor_a",
                "to": "buoy_a",
                "sections": [{"type": "chain", "length": 150.0, "segments": 10}],
            },
            {
                "name": "b",
                "model": "lumped_mass",
                "from": "anchor_b",
                "to": "buoy_b",
                "sections": [{"type": "chain", "length": 150.0, "segments": 10}],
            },
            {
                "name": "hawser",
                "model": "tie",
                "from": "buoy_a",
                "to": "buoy_b",
                "unstretched_length": 78.0,
                "stiffness": 2.0e4,
                "damping": 2.0e3,
            },
        ],
        "start": "as_given",
        # rk4's step below its limit on the chain (0.0038 s)
        "simulation": {"duration": 1.0, "output_interval": 0.5, "time_step": 0.001},
    },
    "heaving body on a planar rigid-link line": {
        "name": "heaving body",
        "environment": {"water_density": 1000.0, "water_depth": 300.0},
        "bodies": [
            {
                "name": "top",
                "type": "rigid",
                "position": [0.0, 0.0, -7.0],
                "mass": 6000.0,
                "dofs": ["heave"],
                "external forces": [
                    {
                        "model": "linear_stiffness",
                        "diagonal": [0, 0, 1200.0, 0, 0, 0],
                        "equilibrium_position": [0.0, 0.0, -7.0],
                    },
                    {"model": "linear_damping", "diagonal": [0, 0, 237.6, 0, 0, 0]},
                    {
                        "model": "applied",
                        "force_z": {"kind": "sine", "amplitude": 2.5e4, "angular_frequency": 1.57},
                    },
                ],
            },
            {
                "name": "end",
                "type": "point",
                "position": [207.84609690826542, 0.0, -127.0],
                "mass": 60.0,
                "volume": 0.00764,
                "external forces": _BUOY_FORCES[:2]
                + [{"model": "drag", "drag_coefficient": 0.5, "area": 0.047}],
            },
        ],
        "line_types": [_UMBILICAL],
        "lines": [
            {
                "name": "umbilical",
                "model": "rigid_links",
                "from": "top",
                "to": "end",
                "sections": [{"type": "umbilical", "segments": 12, "length": 240.0}],
                "initial": {"arc_deg": [60.0, 60.0]},
                "base_reference": [0.0, 0.0, -1.0],
            }
        ],
        "start": "as_given",
        "simulation": {"duration": 0.2, "output_interval": 0.1},
    },
    "towed 3D rigid-segment line": {
        "name": "towed line",
        "environment": {"water_density": 1025.0},
        "bodies": [
            {
                "name": "ship",
                "type": "imposed",
                "track": {"start": [0.0, 0.0], "heading_deg": 0.0, "speed": 2.5},
            },
            {
                "name": "fish",
                "type": "point",
                "position": [-200.0, 0.0, -100.0],
                "mass": 500.0,
                "volume": 0.2,
                "external forces": _BUOY_FORCES[:2]
                + [{"model": "drag", "drag_coefficient": 1.0, "area": 0.5}],
            },
        ],
        "line_types": [_UMBILICAL],
        "lines": [
            {
                "name": "tow",
                "model": "rigid_segments_3d",
                "from": "ship",
                "to": "fish",
                "sections": [{"type": "umbilical", "segments": 20, "length": 240.0}],
                "initial": "catenary",
            }
        ],
        "start": "as_given",
        "simulation": {"duration": 0.2, "output_interval": 0.1},
    },
}


@dataclass
class Item:
    """One thing to compile: a case with an integrator, or a case's statics and modes."""

    label: str
    run: Callable[[], None]


def _short(case: SystemCase, integrator: str | None) -> SystemCase:
    """``case`` run for two output intervals (with ``integrator`` and a step it accepts)."""
    sim = case.simulation
    update: dict = {"duration": 2 * sim.output_interval}
    if integrator is not None:
        update["integrator"] = integrator
        step = STEPS[integrator]
        if step is not None:  # short enough for rk4's limit on any of these systems
            update["time_step"] = step * sim.output_interval
    return case.model_copy(update={"simulation": sim.model_copy(update=update)})


def items(cases: list[tuple[str, SystemCase]], every: bool) -> Iterator[Item]:
    """What compiling ``cases`` (name, case) means: each run briefly with its integrator and,
    with ``every``, with each integrator family and through its statics and modes."""
    for name, case in cases:
        families = FAMILIES if every else (None,)
        for integrator in families:
            short = _short(case, integrator)
            label = f"{name}, {short.simulation.integrator}"
            yield Item(label, partial(_run, short))
        if every:
            yield Item(f"{name}, statics and modes", partial(_analyses, case))


def _run(case: SystemCase) -> None:
    simulation.simulate(case)


def _analyses(case: SystemCase) -> None:
    analysis.statics(case)
    analysis.system_modes(case, count=1)


def built_in() -> list[tuple[str, SystemCase]]:
    """The small systems of the common kinds (``BUILT_IN``), validated."""
    return [(name, loader.load_case(copy.deepcopy(data))) for name, data in BUILT_IN.items()]


def compile_ahead(
    paths: list[str], every: bool, report: Callable[[int, int, str, float | None], None]
) -> float:
    """Compile what the case files ``paths`` need (none: the built-in systems), reporting
    ``report(done, total, label, seconds)`` before (seconds None) and after each item; the
    total time [s]."""
    cases = [(Path(p).name, loader.load_case(p)) for p in paths] if paths else built_in()
    todo = list(items(cases, every))
    start = time.perf_counter()
    for k, item in enumerate(todo):
        report(k, len(todo), item.label, None)
        began = time.perf_counter()
        try:
            item.run()
        except SeacableError as exc:  # a case that cannot run: its own error, named
            raise SeacableError(f"compiling {item.label}: {exc}") from exc
        report(k + 1, len(todo), item.label, time.perf_counter() - began)
    return time.perf_counter() - start
