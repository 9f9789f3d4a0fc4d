"""Every implementation honours its contract (the Protocol or enumeration that states it)."""

import ast
import inspect
import typing
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable.case import system as sch
from seacable.forces import kinds, table
from seacable.kernels import chain3d as c3
from seacable.kernels import planar_chain as pc
from seacable.lines import rigid_links, rigid_segments
from seacable.lines.contract import RigidLineModel
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


def _rigid_line_at_a_moving_state(example: str, seed: int):
    """A system's first rigid line with its workspace filled by one right-hand side at the
    example's start with random segment rates: (params, state, workspace, line index)."""
    from seacable.case.loader import derive_case
    from seacable.system import kernel
    from seacable.system import rigid as system_rigid

    case = seacable.load_case(Path(__file__).parent.parent / "examples" / f"{example}.yaml")
    built = system_model.build(derive_case(case, {"simulation": {"duration": 0.1}}))
    p, y = built.params, built.y0.copy()
    li = 0
    per = 1 if p.rs_kind[li] == system_rigid.PLANAR else 3
    v, n = int(p.rs_v[li]), int(p.rs_n[li])
    y[v : v + per * n] += np.random.default_rng(seed).normal(scale=0.05, size=per * n)
    w = kernel.make_work(p)
    kernel.rhs(0.0, y, p, w, np.zeros_like(y))
    return p, y, system_rigid.workspace(p, w, li).copy(), li


@pytest.mark.parametrize(
    ("model", "example"),
    [(rigid_links, "thesis_6_1_sim2_submerged_12_links"),
     (rigid_segments, "rising_body_single_cable_added_mass")],
)  # fmt: skip
def test_every_rigid_line_model_honours_its_contract(model, example):
    """Each rigid line model has the contract's functions, and its tip map is the forward
    sweep's (rule 2): for random node-0 accelerations A_0 and holding forces L on a held tip,
    the tip's acceleration from ``forward`` is ac + ga A_0 + al L from ``tip_map``."""
    assert isinstance(model, RigidLineModel)
    p, y, ws, li = _rigid_line_at_a_moving_state(example, seed=3)
    n, s0 = int(p.rs_n[li]), int(p.rs_seg[li])
    q, v = int(p.rs_q[li]), int(p.rs_v[li])
    length, mass = p.rs_length[s0 : s0 + n], p.rs_mass[s0 : s0 + n]
    rng = np.random.default_rng(7)
    planar = model is rigid_links
    dims = 2 if planar else 3
    if planar:
        st = np.array([5.0, 0.3, 7.0, *rng.normal(size=2), 1.0, 0.0, 0.0, 1.0])
        model.backward(n, length, mass, p.rs_inertia[s0 : s0 + n], y, v, ws, st, True)
        ac, ga, al = np.empty(2), np.empty(4), np.empty(4)
        model.tip_map(n, length, y, v, ws, ac, ga, al)
    else:
        m = np.array([5.0, 0.3, 0.1, 6.0, 0.2, 7.0])
        model.backward(n, length, mass, ws, m, rng.normal(size=3), np.eye(3).ravel(), True)
        ac, ga, al = np.empty(3), np.empty(9), np.empty(9)
        model.tip_map(n, length, ws, ac, ga, al)
    for _ in range(3):
        a0, force = rng.normal(size=dims), rng.normal(size=dims) * 100.0
        ydot = np.zeros_like(y)
        if planar:
            model.forward(n, length, ws, a0[0], a0[1], force[0], force[1], True, y, q, v, ydot)
            tip = ws[[pc._AX, pc._AZ], n]
        else:
            model.forward(n, length, ws, a0, force, True, y, q, v, ydot)
            tip = ws[c3._A : c3._A + 3, n]
        mapped = ac + ga.reshape(dims, dims) @ a0 + al.reshape(dims, dims) @ force
        np.testing.assert_allclose(tip, mapped, rtol=1e-10, atol=1e-10 * np.abs(mapped).max())
