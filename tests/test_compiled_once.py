"""Each compiled function of seacable is compiled once per process, whatever the case, the
integrator or the analysis (docs/architecture.md, "Compile time").

The system's parameter and work tuples have one numba type for every case (flat arrays with
offsets), so one compilation serves every system. A second signature of a function means a
second compilation of it and of everything it calls: a read-only state from a solver, a literal
integer argument, a strided view where a contiguous array was expected (not an argument that
switches a kind of component on or leaves its code out: True or None, by design). Before this
test, a CVODE run compiled the whole right-hand side a second time (27 s) for SUNDIALS's
read-only state."""

import sys
from pathlib import Path

import pytest
from numba.core.registry import CPUDispatcher

import seacable
from seacable import analysis
from seacable.kernels import jit, records

EXAMPLES = Path(__file__).parent.parent / "examples"
INTEGRATORS = ["rk4", "dopri5", "theta", "generalized_alpha", "bdf", "lsoda", "cvode"]


def _short(name, integrator, start=None):
    """The example for 0.02 s with the integrator; ``start`` replaces the case's start."""
    case = seacable.load_case(EXAMPLES / name)
    sim = case.simulation
    update = {"duration": 0.02, "output_interval": 0.01, "integrator": integrator,
              "time_step": 1e-4}  # fmt: skip
    case = case.model_copy(update={"simulation": sim.model_copy(update=update)})
    return case if start is None else case.model_copy(update={"start": start})


# the types of an argument that switches a kind of component on (True) or leaves its code out
# (None): compiled apart by design (system.kernel.present, system.rigid's sweeps; ``_switch``)
KIND_SWITCH = {"none", "bool", "Literal[bool](True)"}


def _switch(types: set[str]) -> bool:
    """Whether an argument's types are a kind's switch: True or None, or an array or None (the
    waves' rows, ``None`` where a system has no waves: system.evaluation's WAVES)."""
    return types <= KIND_SWITCH or ("none" in types and len(types) == 2
                                    and any(t.startswith("array(") for t in types))  # fmt: skip


def _dispatchers():
    for module in list(sys.modules.values()):
        if not getattr(module, "__name__", "").startswith("seacable"):
            continue
        for value in vars(module).values():
            if isinstance(value, CPUDispatcher) and value.py_func.__module__ == module.__name__:
                yield value


@pytest.mark.parametrize("name", ["two_buoys_moored_with_hawser.yaml",
                                  "thesis_6_1_sim1_air_12_links.yaml"])  # fmt: skip
def test_every_compiled_function_has_one_signature(name):
    """The first run starts as the case says (the two buoys: from their statics), the others
    as given: the statics are the same compiled code each time (about 4 s of Python-driven
    Newton for the two buoys, warm), and ``analysis.statics`` below runs them once more."""
    for k, integrator in enumerate(INTEGRATORS):
        seacable.simulate(_short(name, integrator, start=None if k == 0 else "as_given"))
    case = _short(name, "dopri5")
    analysis.statics(case)
    analysis.system_modes(case, count=2)
    many = {}
    for d in _dispatchers():
        if d is records._pack and len(d.signatures) <= len(records._FIELDS):
            continue  # by design: once per record class (the parameters, the workspace)
        if len(d.signatures) > 1:  # the arguments whose types differ
            differ = [{str(sig[i]) for sig in d.signatures} for i in range(len(d.signatures[0]))]
            apart = {i: types for i, types in enumerate(differ) if len(types) > 1}
            if any(not _switch(types) for types in apart.values()):
                many[f"{d.py_func.__module__}.{d.py_func.__name__}"] = apart
    assert not many, many


def test_an_inner_function_refuses_a_python_call():
    from seacable.system import energy

    assert isinstance(energy.energies, jit.InnerDispatcher)
    with pytest.raises(TypeError, match="compiled callers only"):
        energy.energies(None, None, None)
