"""The statics of random spread moorings (benchmarks/statics_success.py) whose platform must
travel hundreds of metres before its lines hold it: found from the lines' closed forms, each
lumped line settled by itself on its closed-form shape (system.initial.uniform_shapes,
line_balance.settle_each)."""

import importlib.util
import os
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable.system import closed_form, model, natural_lines, statics
from seacable.system.coordinates import Residual, coordinates
from seacable.system.initial import uniform_shapes
from seacable.system.line_balance import settle_each

BENCHMARK = Path(__file__).resolve().parents[1] / "benchmarks" / "statics_success.py"


def _mooring(seed: int, k: int) -> dict:
    spec = importlib.util.spec_from_file_location("statics_success", BENCHMARK)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    rng = np.random.default_rng(seed)
    for i in range(k + 1):
        case = module.mooring(rng, i)
    return case


def _built(case: dict):
    loaded = seacable.load_case(case)
    built = model.build(loaded.model_copy(update={"start": "as_given"}))
    return statics.still_water(built)


def test_far_travelling_platform_balanced():
    """Seed 39, mooring 1: four wire lines, two laid slack; the platform travels 470 m. Its
    balance: every coordinate's acceleration below 1e-6 m/s^2 (the platform's force off by
    10 N of its 1e7 kg, the nodes' by 1e-7 of their weight)."""
    built = _built(_mooring(39, 1))
    found = statics.equilibrium(built, built.y0)
    p = built.params
    r = Residual(p, coordinates(p))(found)
    assert np.all(np.isfinite(r)) and np.abs(r).max() < 1e-6
    assert abs(found[p.body_q[-1]]) > 100.0  # it did travel (surge)


@pytest.mark.parametrize(
    ("k", "travel"),
    [
        pytest.param(3, 210.0, marks=pytest.mark.slow),
        (31, 1100.0),
        pytest.param(42, 1230.0, marks=pytest.mark.slow),
        (127, 61.0),
    ],  # fmt: skip
)
def test_platforms_on_lines_lying_slack_balance(k, travel):
    """Seed 39, moorings 3, 31 and 42, which failed: mooring 3's longest line lies in a heap
    below its fairlead (its last hanging segments started pushed, the drop shortened by the
    hanging part's stretch: now each hanging segment starts stretched by the line below it);
    moorings 31 and 42 lie slack on all three lines, 3.5 to 6.2 km long, so the closed forms'
    Newton found no force change to follow (it now steps along the force while none changes);
    mooring 127's polyester line, 3.2 m short of its span and rise, has a touchdown its 25.5 m
    segments cut: they lie slack (``initial._laid`` where it fits). Balanced to 1e-6 m/s^2,
    the platform 210, 1,100, 1,230 and 61 m from its start (within 5 %)."""
    built = _built(_mooring(39, k))
    found = statics.equilibrium(built, built.y0)
    p = built.params
    r = Residual(p, coordinates(p))(found)
    assert np.all(np.isfinite(r)) and np.abs(r).max() < 1e-6
    offset = np.hypot(*found[p.body_q[-1] : p.body_q[-1] + 2])
    assert offset == pytest.approx(travel, rel=0.05), offset


def test_closed_form_shapes_settle_each_line():
    """At the closed forms' pose, every lumped line settles by itself from its closed-form
    shape to 1e-6 g under the linear axial law."""
    built = _built(_mooring(39, 1))
    p = built.params
    coords = coordinates(p)
    y = natural_lines.hanging(p, built.y0.copy())
    limit = statics._step_limit(built, coords, shortest=True)[np.flatnonzero(coords.kind <= 1)]
    pose = closed_form.pose(p, coords, y, limit)
    assert pose is not None
    settled = settle_each(p, uniform_shapes(p, pose))
    r = Residual(p._replace(slack_allowed=0), coordinates(p))(settled)
    assert np.abs(r[coords.kind == 2]).max() < 1e-6 * p.gravity


def test_a_lumped_tow_balances_whatever_its_towed_bodys_first_guess():
    """Jacquot and Marichal's tow as a lumped-mass line (benchmarks' ``--family shapes``): its
    towed body given 300 m ahead of the ship and 200 m down, or hanging 500 m below it, the
    statics find one balance (the body 470.3 m astern and 164.7 m down: 1e-6 m apart), and
    the first guess ahead of the ship is found only from the bodies hung below their tow
    points (``towed_from``; it failed before)."""
    spec = importlib.util.spec_from_file_location("statics_success", BENCHMARK)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    found = []
    for guess in ([0.0, 0.0, -500.0], [300.0, 0.0, -200.0]):
        ds = seacable.statics(seacable.load_case(module._tow(guess))).dataset
        body = ds["bodies/end"].to_dataset().isel(time=0)
        found.append([float(body[f"position_{c}"]) for c in "xyz"])
    assert np.abs(np.subtract(*found)).max() < 1e-6, found
    assert found[0][0] == pytest.approx(-470.28, abs=0.01)
    assert found[0][2] == pytest.approx(-164.66, abs=0.01)


def test_superlus_blas_complaints_are_held_back_and_other_output_kept(capfd):
    """On a nearly singular matrix SuperLU's BLAS writes "** On entry to DGEMV parameter
    number 2 had an illegal value" (OpenBLAS's xerbla, on the standard output; seed 40's
    moorings 18 and 41 printed it during their statics); the solves hold such lines back and
    pass anything else on. A singular matrix is None, a regular one solved."""
    from scipy import sparse

    from seacable.system import pseudo_time

    with pseudo_time._held_blas_errors():
        os.write(1, b" ** On entry to DGEMV  parameter number  2 had an illegal value\n")
        os.write(2, b" ** On entry to DTRSV  parameter number  6 had an illegal value\n")
        os.write(2, b"something else\n")
    seen = capfd.readouterr()
    assert seen.out == "" and seen.err == "something else\n"
    assert pseudo_time.sparse_solve(sparse.csc_matrix(np.zeros((2, 2))), np.ones(2)) is None
    solved = pseudo_time.sparse_solve(sparse.diags([2.0, 4.0]), np.ones(2))
    assert np.allclose(solved, [0.5, 0.25])


def test_a_u_lying_slack_between_buoys_on_tethers_balances():
    """``--family shapes``' U of 500 m of chain between two buoys on vertical 45 m tethers in
    60 m of water, which failed: the closed forms took the U for a catenary hanging clear
    (through the seabed), pulling the buoys 14 m together. With its middle on the seabed it is
    two arms tangent to it (here slack: no H), the buoys stay above their anchors (to 1e-6 m)
    on their taut tethers, 15 m below the surface less the tethers' stretch (within 1 cm);
    balanced to 1e-6 m/s^2."""
    spec = importlib.util.spec_from_file_location("statics_success", BENCHMARK)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    case = dict(module.shapes())["a U of 500 m lying slack between buoys on vertical tethers"]
    built = _built(case)
    found = statics.equilibrium(built, built.y0)
    p = built.params
    r = Residual(p, coordinates(p))(found)
    assert np.all(np.isfinite(r)) and np.abs(r).max() < 1e-6
    buoys = [found[p.body_q[b] : p.body_q[b] + 3] for b in range(2)]
    assert np.abs(np.abs([b[0] for b in buoys]) - 60.0).max() < 1e-6
    assert all(b[2] == pytest.approx(-14.97, abs=0.01) for b in buoys), buoys
