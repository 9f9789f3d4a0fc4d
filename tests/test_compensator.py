"""The tandem compensator (forces.compensator) against the closed forms its feedback
linearisation promises: unsaturated, the hawser distance's and the heading's errors follow
e'' + 2 z w e' + w^2 e = 0 exactly whatever the hull, wind and hawser loads, so a run from an
offset start gives e0 e^(-z w t) (cos w_d t + z w / w_d sin w_d t); the equilibrium's
linearisation has the law's eigenvalues -z w +- i w sqrt(1 - z^2) among its own. Saturated,
the force applied is the limit while the demand goes beyond it; disabled, the run is the
uncontrolled one to the bit."""

import copy
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import seacable
from seacable.errors import CaseError
from seacable.stability import equilibria
from seacable.stability.plane import Plane

EXAMPLE = Path(__file__).parents[1] / "examples" / "tandem_offloading_fpso_shuttle.yaml"
BASE = yaml.safe_load(EXAMPLE.read_text())
SHUTTLE, COMPENSATOR = 2, 3  # the shuttle's place in bodies, the compensator's in its forces


def _data(yaw_deg=10.0, duration=600.0, **compensator):
    data = copy.deepcopy(BASE)
    shuttle = data["bodies"][SHUTTLE]
    shuttle["orientation_deg"] = [0.0, 0.0, yaw_deg]
    shuttle["external forces"][COMPENSATOR].update({"enabled": True, **compensator})
    for k in ("max_ahead", "max_astern", "max_yaw_moment"):
        if compensator.get(k, 0) is None:
            del shuttle["external forces"][COMPENSATOR][k]
    data["simulation"].update(duration=duration, output_interval=5.0, rtol=1e-10)
    return data


def _law(e0, omega, zeta, t):
    """The free response from e0 at rest of e'' + 2 zeta omega e' + omega^2 e = 0."""
    if zeta == 1.0:
        return e0 * (1.0 + omega * t) * np.exp(-omega * t)
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    return e0 * np.exp(-zeta * omega * t) * (np.cos(wd * t) + zeta * omega / wd * np.sin(wd * t))


def _errors(run, heading):
    """(distance error [m], heading error [rad]) of the run's rows."""
    fx, fy = np.asarray(run["lines/hawser/from_x"]), np.asarray(run["lines/hawser/from_y"])
    tx, ty = np.asarray(run["lines/hawser/to_x"]), np.asarray(run["lines/hawser/to_y"])
    distance = np.hypot(fx - tx, fy - ty)
    own = np.radians(np.asarray(run["bodies/shuttle/yaw"]))
    if heading == "relative":
        reference = np.radians(np.asarray(run["bodies/fpso/yaw"]))
    else:  # the bearing of the FPSO's stern from the shuttle's bow
        reference = np.arctan2(fy - ty, fx - tx)
    e2 = own - reference
    return distance - 95.0, np.arctan2(np.sin(e2), np.cos(e2))


@pytest.mark.parametrize(("heading", "zeta"), [("relative", 1.0), ("line of sight", 0.6)])
def test_the_errors_follow_the_linear_law_exactly(heading, zeta):
    omega, limits = 0.02, {"max_ahead": None, "max_astern": None, "max_yaw_moment": None}
    run = seacable.simulate(seacable.load_case(_data(
        heading=heading, damping_ratio=zeta, frequency=omega, heading_frequency=omega,
        **limits)))  # fmt: skip
    assert run.status == "complete"
    t = np.asarray(run["time"])
    e1, e2 = _errors(run, heading)
    assert abs(e1[0]) > 1.0 and abs(e2[0]) > math.radians(5.0)  # a real offset at the start
    assert np.abs(e1 - _law(e1[0], omega, zeta, t)).max() < 1e-6 * abs(e1[0])
    assert np.abs(e2 - _law(e2[0], omega, zeta, t)).max() < 1e-6 * abs(e2[0])
    # the law's work is real: the loads it cancels are large and change along the run
    demand = np.asarray(run["bodies/shuttle/compensator_surge_force"])
    assert np.ptp(demand) > 1e5
    applied = np.asarray(run["bodies/shuttle/compensator_surge_demand"])
    assert np.array_equal(demand, applied)  # unlimited: what it demands, it applies


def test_a_saturated_compensator_applies_its_limit_and_misses_the_law():
    run = seacable.simulate(seacable.load_case(_data(max_ahead=1e5, max_astern=1e5)))
    applied = np.asarray(run["bodies/shuttle/compensator_surge_force"])
    demand = np.asarray(run["bodies/shuttle/compensator_surge_demand"])
    assert np.abs(applied).max() == pytest.approx(1e5, rel=1e-12)
    assert np.abs(demand).max() > 2e5
    assert np.allclose(applied, np.clip(demand, -1e5, 1e5), rtol=0, atol=1e-6)
    e1, _ = _errors(run, "relative")
    t = np.asarray(run["time"])
    assert np.abs(e1 - _law(e1[0], 0.02, 1.0, t)).max() > 0.1


def test_disabled_it_is_the_uncontrolled_ship_to_the_bit():
    off = _data(duration=300.0)
    off["bodies"][SHUTTLE]["external forces"][COMPENSATOR]["enabled"] = False
    without = copy.deepcopy(off)
    del without["bodies"][SHUTTLE]["external forces"][COMPENSATOR]
    a = seacable.simulate(seacable.load_case(off))
    b = seacable.simulate(seacable.load_case(without))
    for name in ("bodies/shuttle/position_x", "bodies/shuttle/yaw", "lines/hawser/tension"):
        assert np.array_equal(np.asarray(a[name]), np.asarray(b[name]))
    assert not np.any(np.asarray(a["bodies/shuttle/compensator_surge_force"]))


def test_the_controlled_equilibrium_holds_the_setpoints_with_the_laws_eigenvalues():
    omega, zeta = 0.02, 0.6
    case = seacable.load_case(_data(yaw_deg=0.0, damping_ratio=zeta, frequency=omega,
                                    heading_frequency=1.5 * omega, max_ahead=None,
                                    max_astern=None, max_yaw_moment=None))  # fmt: skip
    plane = Plane.of(case)
    found = equilibria.find(plane, None, 12)
    assert found[0].stable  # the pair weathervaning (the reversed one: unstable)
    for e in found:
        assert e.residual < 1e-9
        plane.rates(np.concatenate([e.x, np.zeros(6)]))
        ppos = plane.work.ppos
        distance = np.hypot(*(ppos[_point(plane, "fpso.stern")] -
                              ppos[_point(plane, "shuttle.bow")])[:2])  # fmt: skip
        assert distance == pytest.approx(95.0, abs=1e-6)
        assert math.remainder(e.x[5] - e.x[2], 2 * math.pi) == pytest.approx(0.0, abs=1e-8)
        for w in (omega, 1.5 * omega):  # each output's pair of the law's roots
            root = complex(-zeta * w, w * math.sqrt(1 - zeta * zeta))
            assert np.abs(e.eigenvalues - root).min() < 1e-5 * w


def _point(plane, name):
    return plane.built.layout.point_index[name]


@pytest.mark.parametrize(("change", "words"), [
    ({"target": "shuttle.bow"}, "the target point is on the ship itself"),
    ({"point": "stern"}, "has no point 'stern'"),
])  # fmt: skip
def test_the_compensators_refusals(change, words):
    data = _data()
    data["bodies"][SHUTTLE]["external forces"][COMPENSATOR].update(change)
    with pytest.raises(CaseError, match=words):
        seacable.simulate(seacable.load_case(data))


def test_one_compensator_a_pair():
    data = _data()
    data["bodies"][1]["external forces"].append(
        {"model": "compensator", "point": "stern", "target": "shuttle.bow", "distance": 95.0}
    )
    with pytest.raises(CaseError, match="has a compensator too"):
        seacable.simulate(seacable.load_case(data))


def test_compare_side_by_side_agrees_with_the_simulation_and_judges_the_limits(tmp_path):
    from click.testing import CliRunner

    from seacable.cli import main
    from seacable.stability.operability import Limits

    case = seacable.load_case(EXAMPLE)
    found = seacable.compare(case, duration=1200.0, limits=Limits(20.0, (("hawser", 1e6),)),
                             start="case")  # fmt: skip
    off, on = found.sel(control="uncontrolled"), found.sel(control="controlled")
    assert off["verdict"].item() == "limit exceeded" and "hawser" in off["message"].item()
    assert on["verdict"].item() == "safe"
    assert float(off["peak_surge_force"]) == 0.0 and float(on["peak_surge_force"]) > 1e5
    hawser = on["distance"].sel(tie="hawser").values
    assert abs(hawser[-1] - 95.0) < 1e-3 and np.ptp(off["distance"].sel(tie="hawser").values) > 5.0
    # the analyses' RK4 flow (1 s steps, split at the kinks) against the simulation's dopri5
    data = copy.deepcopy(BASE)
    data["bodies"][SHUTTLE]["external forces"][COMPENSATOR]["enabled"] = True
    data["simulation"].update(duration=1200.0, output_interval=10.0, rtol=1e-9)
    run = seacable.simulate(seacable.load_case(data))
    for name, ours in (("bodies/shuttle/position_x", on["x"].sel(body="shuttle")),
                       ("bodies/fpso/yaw", on["heading"].sel(body="fpso")),
                       ("lines/hawser/tension", on["tension"].sel(tie="hawser")),
                       ("bodies/shuttle/compensator_surge_force", on["surge_force"])):  # fmt: skip
        theirs = np.asarray(run[name])
        assert np.abs(ours.values - theirs).max() < 1e-3 * max(np.abs(theirs).max(), 1.0), name
    out = CliRunner().invoke(main, ["compare", str(EXAMPLE), "--duration", "600",
                                    "--plot", str(tmp_path / "c.png")])  # fmt: skip
    assert out.exit_code == 0, out.output
    assert "uncontrolled: " in out.output and "controlled: safe" in out.output
    assert (tmp_path / "c.png").stat().st_size > 10_000


def test_a_map_of_both_settings(tmp_path):
    from click.testing import CliRunner

    from seacable.cli import main
    from seacable.stability import operability as op

    case = seacable.load_case(EXAMPLE)
    states, shape = op.grid(0.8, np.array([180.0, 200.0]), np.array([200.0]), np.array([18.75]))
    found = op.operability(case, states, shape, scheduler=None, control="both")
    assert list(found["control"].values) == ["uncontrolled", "controlled"]
    assert not found["surge_force"].sel(control="uncontrolled").any()
    held = found.sel(control="controlled")
    assert (held["status"] != "failed").all() and (np.abs(held["surge_force"]) > 0).all()
    with pytest.raises(CaseError, match="control 'sometimes'"):
        op.operability(case, states, shape, scheduler=None, control="sometimes")
    out = CliRunner().invoke(main, ["operability", str(EXAMPLE), "--current-speed", "0.8",
                                    "--current-towards", "180", "--wind-towards", "200",
                                    "--ratios", "18.75", "--control", "both", "--dask", "none",
                                    "--plot", str(tmp_path / "m.png")])  # fmt: skip
    assert out.exit_code == 0, out.output
    assert "uncontrolled: 1 weather states" in out.output
    assert "controlled: 1 weather states" in out.output


def test_its_settings_are_parameters_of_the_analyses():
    from seacable.stability.parameters import parameter

    plane = Plane.of(seacable.load_case(_data(yaw_deg=0.0)))
    parameter(plane, "bodies.shuttle.external forces.3.distance").set(plane, 97.0)
    parameter(plane, "bodies.shuttle.external forces.3.heading_deg").set(plane, 5.0)
    e = equilibria.find(plane, None, 12)[0]
    assert e.stable
    plane.rates(np.concatenate([e.x, np.zeros(6)]))
    ppos = plane.work.ppos
    gap = ppos[_point(plane, "fpso.stern")] - ppos[_point(plane, "shuttle.bow")]
    assert np.hypot(*gap[:2]) == pytest.approx(97.0, abs=1e-6)
    assert math.degrees(math.remainder(e.x[5] - e.x[2], 2 * math.pi)) == pytest.approx(5.0)
    with pytest.raises(CaseError, match="no 'distance' there"):
        parameter(plane, "bodies.shuttle.external forces.2.distance")
