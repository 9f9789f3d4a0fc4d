"""Rigid-segment lines in a system: planar against 3D lines (a body carried at the end, a
heaving body above an anchored line, a towed body's static shape), an invariant
(energy of a tree of lines and bodies without damping) and the static balance of the bodies
they carry; the cases the sweep cannot carry are refused naming the line."""

import contextlib

import numpy as np
import pytest

import seacable
from seacable.case.loader import load_case
from seacable.errors import CaseError
from seacable.simulation import simulate
from seacable.system import model

ROPE = {"name": "rope", "diameter": 0.02, "mass_per_length": 1.5, "drag_coefficient_normal": 0.0}
WIRE = {"name": "wire", "diameter": 0.03, "mass_per_length": 2.5, "drag_coefficient_normal": 1.8,
        "friction_coefficient": 0.02}  # fmt: skip
PLANAR_WIRE = {**WIRE, "added_mass_coefficient": 0.0}  # Pouzada's links carry no added mass
WATER = {"water_density": 1025.0, "gravity": 9.81}


def _sim(duration, dt, interval=0.1):
    return {"duration": duration, "time_step": dt, "integrator": "rk4",
            "output_interval": interval}  # fmt: skip


def _line(name, a, b, length, segments, kind="rope", model="rigid_segments_3d", **more):
    section = {"type": kind, "length": length, "segments": segments}
    return {"name": name, "model": model, "from": a, "to": b, "sections": [section],
            **more}  # fmt: skip


MODELS = ["rigid_segments_3d", "rigid_links"]


def _system(bodies, lines, simulation, environment=None, start="as_given", types=(ROPE,)):
    return {"name": "rigid lines", "start": start, "environment": environment or
            {"in_air": True, "gravity": 9.81}, "bodies": bodies, "line_types": list(types),
            "lines": lines, "simulation": simulation}  # fmt: skip


def _gap(a, b) -> float:
    return float(np.abs(a - b).max() / np.abs(a).max())


def _body_at_the_end(kind):
    new = _system(
        [{"name": "pin", "type": "fixed", "position": [0, 0, 0]},
         {"name": "ball", "type": "point", "position": [6.0, 0.0, -8.0], "mass": 20.0,
          "external forces": [{"model": "gravity"}]}],
        [_line("chain", "pin", "ball", 10.0, 10, initial="straight", model=kind)],
        _sim(1.0, 1e-3),
    )  # fmt: skip
    return simulate(load_case(new)).dataset


def test_a_body_at_the_end_moves_alike_on_a_planar_and_a_3d_line():
    """A fixed body, a 10-segment line in air and a point body with its weight at the end: the
    planar line (angles) and the 3D line (directors) swinging in their plane give the same
    motion and tensions (two kernels, one physics)."""
    a, b = (_body_at_the_end(kind) for kind in MODELS)
    for name in ("bodies/ball/position_x", "bodies/ball/position_z", "lines/chain/tension",
                 "total_energy"):  # fmt: skip
        assert _gap(a[name].values, b[name].values) < 1e-12, name


def _heaving_body(kind):
    wire = PLANAR_WIRE  # the same added mass (none) on both lines
    sine = {"kind": "sine", "amplitude": 20000.0, "period": 6.0}
    new = _system(
        [{"name": "anchor", "type": "fixed", "position": [7.0, 0.0, -30.0]},
         {"name": "buoy", "type": "rigid", "position": [0, 0, 0], "mass": 5000.0,
          "added_mass": [0, 0, 2000.0, 0, 0, 0], "inertia": [1.0, 1.0, 1.0], "dofs": ["heave"],
          "velocity": [0, 0, 0.5],
          "external forces": [
              {"model": "linear_stiffness", "diagonal": [0, 0, 8e4, 0, 0, 0],
               "equilibrium_position": [0, 0, 0.3]},
              {"model": "linear_damping", "diagonal": [0, 0, 1000.0, 0, 0, 0]},
              {"model": "applied", "force_z": sine}]}],
        [_line("leg", "buoy", "anchor", 32.0, 16, kind="wire", model=kind)], _sim(2.0, 2e-3),
        environment=WATER, types=(wire,),
    )  # fmt: skip
    return simulate(load_case(new)).dataset


def test_a_heaving_body_over_an_anchored_line_moves_alike_on_a_planar_and_a_3d_line():
    """A rigid body with dofs [heave] (stiffness, damping, a sine force) over a line held on a
    fixed anchor (the holding force eliminated into the body's articulated inertia through the
    tip's map dA_n/dA_0): the planar and the 3D line give the same heave and tensions."""
    a, b = (_heaving_body(kind) for kind in MODELS)
    for name in ("bodies/buoy/position_z", "lines/leg/tension", "lines/leg/to_force_z"):
        assert _gap(a[name].values, b[name].values) < 1e-8, name  # two kernels' round-off


def _tree(start, environment, types, simulation, ship=None):
    """A ship, a main cable to a depressor, a pennant to a towed fish."""
    forces = [{"model": "gravity"}, {"model": "buoyancy"}]
    drag = [] if environment.get("in_air") else [
        {"model": "drag", "drag_coefficient": 1.0, "area": 1.0}]  # fmt: skip
    return _system(
        [ship or {"name": "ship", "type": "fixed", "position": [0, 0, 0]},
         {"name": "depressor", "type": "point", "position": [-60, 0, -150], "mass": 1500.0,
          "volume": 0.2, "added_mass": 300.0, "external forces": forces + drag},
         {"name": "fish", "type": "point", "position": [-160, 0, -160], "mass": 400.0,
          "volume": 0.3, "added_mass": 200.0, "external forces": forces + drag}],
        [_line("main", "ship", "depressor", 200.0, 20, kind=types[0]["name"]),
         _line("pennant", "depressor", "fish", 110.0, 11, kind=types[0]["name"])],
        simulation, environment=environment, start=start, types=types,
    )  # fmt: skip


def test_energy_of_a_tree_of_lines_and_bodies_is_conserved():
    """Ship, main cable, depressor, pennant, fish in air without drag: the depressor carried at
    the main cable's end and carrying the pennant (a tree swept children first); the total
    energy stays constant as the lines swing and fold."""
    ds = simulate(load_case(_tree("as_given", {"in_air": True, "gravity": 9.81}, (ROPE,),
                                  _sim(3.0, 1e-3)))).dataset  # fmt: skip
    energy = ds["total_energy"].values
    assert np.ptp(ds["kinetic_energy"].values) > 1e3  # it moves
    assert np.ptp(energy) < 1e-6 * np.abs(ds["gravity_potential_energy"].values).max()


def test_a_two_stage_tow_starts_in_balance_with_every_segment_pulled():
    """Towing in a 2 m/s current: the statics holds the depressor and the fish where the lines,
    weights, buoyancy and drag balance (each body's forces sum to zero), every segment in
    tension, and a run from it stays there."""
    water = {**WATER, "current": {"velocity": -2.0}}
    ds = simulate(load_case(_tree("static", water, (WIRE,), _sim(1.0, 5e-3, 0.5)))).dataset
    for line in ("main", "pennant"):
        tension = ds[f"lines/{line}/tension"].values
        assert tension.min() > 1e3
        assert np.ptp(tension, axis=0).max() < 1e-6 * tension.max()
    for body in ("depressor", "fish"):
        rows = ds[f"bodies/{body}"]
        assert np.ptp(rows["position_x"].values) < 1e-8
    # the fish: the pennant's pull balances its apparent weight and drag in the current
    pull = [float(ds[f"lines/pennant/to_force_{c}"].values[0]) for c in "xz"]
    weight = (400.0 - 1025.0 * 0.3) * 9.81
    drag = 0.5 * 1025.0 * 1.0 * 1.0 * 2.0**2  # towards -x, the current's way
    np.testing.assert_allclose(pull, [drag, weight], rtol=1e-8)


def _towed_body_start(kind):
    wire = WIRE if kind == "rigid_segments_3d" else PLANAR_WIRE
    water = {**WATER, "current": {"velocity": -2.0}}
    new = _system(
        [{"name": "ship", "type": "fixed", "position": [0, 0, 0]},
         {"name": "fish", "type": "point", "position": [-100, 0, -170], "mass": 400.0,
          "volume": 0.3, "added_mass": [200.0, 200.0, 200.0],
          "external forces": [{"model": "gravity"}, {"model": "buoyancy"},
                              {"model": "drag", "drag_coefficient": 1.0, "area": 1.0}]}],
        [_line("tow", "ship", "fish", 200.0, 20, kind="wire", model=kind)], _sim(0.1, 5e-3),
        environment=water, start="static", types=(wire,),
    )  # fmt: skip
    return simulate(load_case(new)).dataset


def test_a_towed_body_hangs_alike_on_a_planar_and_a_3d_line():
    """One cable and a towed body in a current: the system's statics (Newton on the moment
    balance) puts a planar and a 3D line in the same shape (added mass plays no part at rest)."""
    a, b = (_towed_body_start(kind) for kind in MODELS)
    for c in "xz":
        np.testing.assert_allclose(b[f"lines/tow/node_{c}"].values[0],
                                   a[f"lines/tow/node_{c}"].values[0], rtol=0,
                                   atol=1e-6)  # fmt: skip


ANCHOR = {"name": "anchor", "type": "fixed", "position": [0, 0, -20]}


@pytest.mark.parametrize(
    ("bodies", "lines", "message"),
    [
        ([ANCHOR, {"name": "a", "type": "point", "position": [5, 0, -5], "mass": 0.0},
          {"name": "hull", "type": "rigid", "position": [9, 0, -5], "mass": 1.0}],
         [_line("leg", "anchor", "a", 30.0, 5), _line("tether", "a", "hull", 8.0, 5)],
         r"lines\[0\] \(leg\)\.to: body 'a' is massless, and line 'tether' starts on it"),
        ([ANCHOR, {"name": "a", "type": "point", "position": [5, 0, -5], "mass": 1.0},
          {"name": "b", "type": "point", "position": [9, 0, -5], "mass": 0.0}],
         [_line("one", "a", "b", 5.0, 5), _line("two", "b", "a", 5.0, 5)],
         r"body 'b' is massless, and lines \['one', 'two'\] would close a ring"),
        ([ANCHOR, {"name": "top", "type": "fixed", "position": [0, 0, 0]}],
         [_line("leg", "top", "anchor", 10.0, 5)], r"lines \(leg\): its ends are 20 m apart"),
        ([ANCHOR, {"name": "b", "type": "point", "position": [5, 0, -5], "mass": 1.0}],
         [_line("leg", "b", "anchor", 30.0, 5, model="rigid_links")],
         r"lines\[0\] \(leg\)\.from: a planar rigid_links line .* dofs include sway"),
        ([ANCHOR, {"name": "top", "type": "fixed", "position": [0, 3, 0]}],
         [_line("leg", "top", "anchor", 30.0, 5, model="rigid_links")],
         r"lines \(leg\): a planar rigid_links line lies in an x-z plane"),
    ],
)  # fmt: skip
def test_what_a_sweep_cannot_carry_is_refused_naming_the_line(bodies, lines, message):
    case = load_case(_system(bodies, lines, _sim(1.0, 1e-3)))
    with pytest.raises(CaseError, match=message):
        model.build(case)


def test_a_too_long_rk4_step_on_rigid_lines_is_refused_naming_a_segment(caplog):
    """The thesis umbilical (a system with one rigid-link line): its zigzag about the start,
    27.6 rad/s, sets rk4's limit near 0.104 s; 0.125 s is refused naming a segment, 0.1 s is
    warned as close to it."""
    case = load_case("examples/thesis_6_1_sim4_submerged_60_links.yaml")
    omega, what = model.fastest_frequency(model.build(case))
    assert omega == pytest.approx(27.6, rel=0.01) and what.startswith("segment ")
    sim = case.simulation.model_copy(update={"time_step": 0.125, "output_interval": 0.25,
                                             "duration": 0.5})  # fmt: skip
    with pytest.raises(seacable.CaseError, match=r"beyond rk4's stability limit.*segment \d+ of"):
        seacable.simulation.prepare(case.model_copy(update={"simulation": sim}))
    sim = case.simulation.model_copy(update={"time_step": 0.1, "duration": 0.2})
    with contextlib.suppress(seacable.SimulationDiverged):
        seacable.simulate(case.model_copy(update={"simulation": sim}))
    assert "close to rk4's stability limit" in caplog.text and "segment" in caplog.text
