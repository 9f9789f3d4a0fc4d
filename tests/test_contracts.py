"""Every implementation honours its contract (the Protocol or enumeration that states it)."""

import ast
import inspect
import typing

from seacable.case import system as sch
from seacable.forces import kinds, table
from seacable.system import model as system_model
from seacable.system.contract import RunModel


def test_the_system_model_is_a_run_model():
    members = {n for n in vars(RunModel) if not n.startswith("_")}
    members |= set(RunModel.__annotations__)
    missing = sorted(name for name in members if not hasattr(system_model, name))
    assert not missing, f"system.model lacks {missing} of RunModel"
    assert isinstance(system_model, RunModel)
    assert hasattr(system_model, "variables")


def _schema_force_models() -> list[str]:
    union = typing.get_args(typing.get_args(sch.ForceModel)[0])
    return [typing.get_args(cls.model_fields["model"].annotation)[0] for cls in union]


def test_every_force_model_in_the_schema_has_a_kind_and_a_branch():
    """Each ``model:`` of ``external forces`` has a ForceKind, and forces.table evaluates each
    kind (a kind nobody evaluates would be accepted and silently do nothing)."""
    names = _schema_force_models()
    assert sorted(names) == sorted(kind.name.lower() for kind in kinds.ForceKind)
    source = inspect.getsource(table.add_all)
    branches = {node.id for node in ast.walk(ast.parse(source)) if isinstance(node, ast.Name)}
    for kind in kinds.ForceKind:
        assert kind.name in branches, f"forces.table.add_all has no branch for {kind.name}"
