"""The project rule for hot code (docs/architecture.md, "Calls cost reference counts"): in a
system's right-hand side only ``system.evaluation.evaluate`` receives the parameter and work
tuples; every call it makes passes arrays or small tuples, never ``p`` or ``w`` themselves
(numba takes and drops a reference to each of the tuples' 124 arrays at every such call, about
1.2 us per evaluation; an inlined helper copies them just the same). Read from the source: no
compilation."""

import ast
import inspect
import textwrap

from seacable.system import evaluation, kernel

TUPLES = {"p", "w"}


def _calls_passing_tuples(function) -> list[str]:
    """Each call in ``function`` that passes one of ``TUPLES`` as an argument, as source text."""
    tree = ast.parse(textwrap.dedent(inspect.getsource(function)))
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        arguments = list(node.args) + [keyword.value for keyword in node.keywords]
        if any(isinstance(a, ast.Name) and a.id in TUPLES for a in arguments):
            found.append(ast.unparse(node))
    return found


def test_rhs_passes_no_whole_tuple():
    """The evaluation passes the tuples only to its parts, by their addresses (``_part``,
    inlined); the parts pass them to nothing; the trampolines the integrators call pass them to
    the evaluation alone (and are inlined into their callers)."""
    calls = _calls_passing_tuples(evaluation.evaluate.py_func)
    assert calls and all(call.startswith("_part(") for call in calls), calls
    calls = _calls_passing_tuples(evaluation._part.py_func)
    assert calls and all(call.startswith("indirect.call") for call in calls), calls
    for name in kernel.PARTS:
        assert _calls_passing_tuples(getattr(evaluation, name).py_func) == [], name
    for trampoline in (kernel.evaluate, kernel.accept):
        calls = _calls_passing_tuples(trampoline.py_func)
        assert calls and all(call.startswith("indirect.call") for call in calls), calls


def test_the_check_finds_a_call_that_passes_a_tuple():
    def breach(t, y, p, w, ydot):
        ok = kernel.project(y, p)
        return ok

    assert _calls_passing_tuples(breach) == ["kernel.project(y, p)"]
