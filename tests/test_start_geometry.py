"""The start state a run cannot honestly take is refused before the first step, by `seacable
validate` too (``system.geometry``): bodies and contact-free nodes below the seabed, a body
without a shape floating above the water, segments stretched beyond what a line takes; a
large stretch is reported with its tension."""

import copy
import logging

import pytest
import yaml

import seacable
from seacable.case.loader import load_case
from seacable.simulation import prepare

UMBILICAL = yaml.safe_load(open("examples/thesis_6_1_sim2_submerged_12_links.yaml"))
BUOYS = yaml.safe_load(open("examples/two_buoys_moored_with_hawser.yaml"))


def _sagging_umbilical(depth):
    """The thesis's 240 m umbilical (rigid links) hung in balance between its top at z = 0 and a
    fixed end at (100, 0, -50) m: its sag reaches z = -128 m."""
    data = copy.deepcopy(UMBILICAL)
    data["environment"]["water_depth"] = depth
    data["bodies"][1] = {"name": "end", "type": "fixed", "position": [100.0, 0.0, -50.0]}
    data["start"] = "static"
    data["lines"][0].pop("initial")
    return load_case(data)


def test_a_rigid_line_whose_balance_passes_below_the_seabed_is_refused():
    prepare(_sagging_umbilical(130.0))  # its lowest node, 128.1 m deep, clears the seabed
    with pytest.raises(seacable.CaseError) as info:
        prepare(_sagging_umbilical(80.0))
    assert str(info.value).startswith(
        "lines (umbilical): node 4 starts at z = -80.8323 m, below the seabed (z = -80 m, "
        "environment.water_depth 80 m) (7 of its 13 nodes); a rigid line has no seabed contact"
    )


def _buoys(change, start=None):
    data = copy.deepcopy(BUOYS)
    change(data)
    if start:
        data["start"] = start
    return load_case(data)


def test_a_body_that_starts_below_the_seabed_is_refused():
    case = _buoys(lambda d: d["bodies"][6].update(position=[0.0, 0.0, -60.0]), "as_given")
    expected = r"^bodies\[6\] \(buoy_a\): starts at z = -60 m, below the seabed \(z = -50 m, "
    with pytest.raises(seacable.CaseError, match=expected + r"environment.water_depth 50 m\)"):
        prepare(case)


def test_a_body_without_a_shape_that_balances_above_the_water_is_refused():
    """Buoy A as a point volume of 78.5 m^3 (no shape): its buoyancy never lessens, so its
    balance lies where its chains hold it, 25 m above the water."""

    def point_volume(d):
        d["bodies"][6].pop("shape")
        d["bodies"][6]["volume"] = 78.5

    with pytest.raises(seacable.CaseError) as info:
        prepare(_buoys(point_volume))
    message = str(info.value)
    assert message.startswith("bodies[6] (buoy_a): its centre of buoyancy starts at z = 24.9")
    assert "wholly submerged; give it a shape (sphere, vertical_cylinder or table)" in message


def test_a_hull_whose_waterplane_is_a_stiffness_may_have_its_reference_above_the_water():
    """The platform example: its reference point at the waterline rises 0.56 m in balance,
    its centre of buoyancy 15 m below stays submerged: accepted."""
    prepare(load_case("examples/platform_three_catenary_lines.yaml"))


def test_a_large_stretch_is_reported_with_its_tension_and_a_larger_one_refused(caplog):
    """The buoys' chains made softer: at EA 1 MN the largest static strain, 5.45 %, is reported
    with its tension (EA times the strain); at 50 kN it would be 46 %: refused."""

    def soft(ea):
        return lambda d: d["line_types"][0].update(axial_stiffness=ea)

    with caplog.at_level(logging.WARNING, logger="seacable"):
        prepare(_buoys(soft(1e6)))
    assert (
        "lines (a_west): its most stretched segment (14) starts at a strain of 5.45 %, a "
        "tension of 5.454e+04 N (EA 1e+06 N)" in caplog.text
    )
    with pytest.raises(seacable.CaseError, match=r"more stretch than a line takes"):
        prepare(_buoys(soft(5e4)))


def test_a_velocity_that_is_not_used_is_reported(caplog):
    """The towed body of the towing example rides at the tip of its rigid cable: a velocity
    given to it cannot be used, and the run says so."""
    data = yaml.safe_load(open("examples/jacquot_marichal_towing_speed_change_and_turn.yaml"))
    data["bodies"][1]["velocity"] = [0.0, 1.0, 0.0]
    with caplog.at_level(logging.WARNING, logger="seacable"):
        prepare(load_case(data))
    assert "bodies[1] (end).velocity [0.0, 1.0, 0.0] m/s is not used: the body rides at the " \
        "tip of a rigid line" in caplog.text  # fmt: skip


def test_a_velocity_a_tow_start_replaces_is_reported(caplog):
    """A free buoy given a velocity, started static in a tow (its anchor towed at 1 m/s): it
    starts in the tow's steady motion, and the run says it replaced the velocity given."""
    data = {
        "name": "towed buoy", "environment": {"water_depth": 100.0},
        "bodies": [
            {"name": "ship", "type": "imposed", "x": {"kind": "ramp", "start_time": 0.0,
             "end_time": 100.0, "start_value": 0.0, "end_value": 100.0}},
            {"name": "buoy", "type": "point", "position": [-20.0, 0.0, -10.0], "mass": 100.0,
             "velocity": [0.0, 0.5, 0.0], "external forces": [{"model": "gravity"}]},
        ],
        "lines": [{"name": "tie", "model": "tie", "from": "ship", "to": "buoy",
                   "unstretched_length": 20.0, "stiffness": 1e5}],
        "simulation": {"duration": 0.1, "output_interval": 0.1},
    }  # fmt: skip
    with caplog.at_level(logging.WARNING, logger="seacable"):
        prepare(load_case(data))
    assert "bodies[1] (buoy).velocity [0.0, 0.5, 0.0] m/s is replaced by the tow's steady " \
        "motion, [1.0, 0.0, 0.0] m/s" in caplog.text  # fmt: skip


def test_a_run_that_goes_where_a_start_would_be_refused_says_when(caplog, tmp_path):
    """The thesis umbilical in water 130 m deep: it starts above the seabed (its end at -120
    m) and swings down through it, where nothing holds it; the run finishes, and says from
    when, in the log and in the file (``run_warnings``)."""
    data = copy.deepcopy(UMBILICAL)
    data["environment"]["water_depth"] = 130.0
    data["simulation"].update(duration=6.0)
    with caplog.at_level(logging.WARNING, logger="seacable"):
        results = seacable.simulate(load_case(data), output=tmp_path / "through.nc")
    assert results.status == "complete"
    said = results.dataset.attrs["run_warnings"]
    assert said.startswith("body 'end' below the seabed from t = ")
    assert "line 'umbilical' below the seabed from t = " in said
    assert "where no seabed contact holds it" in caplog.text
    end = results.dataset["bodies/end/position_z"].values
    first = float(said.split("from t = ")[1].split(" s")[0])
    assert end[results.dataset["time"].values < first].min() >= -130.001 > end.min()


def test_a_body_without_a_shape_that_rises_above_the_water_is_said(caplog):
    """Buoy A as a point volume started 5 m deep, as given: its buoyancy, never lessened,
    lifts it out of the water; the run says from when."""

    def point_volume(d):
        d["bodies"][6].pop("shape")
        d["bodies"][6].update(volume=78.5, position=[0.0, 0.0, -5.0])
        d["simulation"].update(duration=20.0)

    with caplog.at_level(logging.WARNING, logger="seacable"):
        results = seacable.simulate(_buoys(point_volume, "as_given"))
    assert "body 'buoy_a' above the water from t = " in results.dataset.attrs["run_warnings"]
    assert "its volume still counts as wholly submerged: give it a shape" in caplog.text


def test_mirrored_lines_start_in_mirrored_shapes_with_no_segment_pushed(caplog):
    """The turret FPSO's chains 2 and 3 mirror each other about the x axis. Their start shapes
    (``start: as_given``: each line settled between its ends) were not mirrored: the EA stages
    of ``line_balance`` had put chain 3 in a balance of the linear axial law with its segments
    zigzagging, 21 to 29 m of 25 m, at 208 MN; such a balance, which pushes segments, is no
    longer taken."""
    import numpy as np

    from seacable.system import model

    case = load_case("examples/turret_fpso_catenary_mooring.yaml")
    with caplog.at_level(logging.WARNING, logger="seacable"):
        built = model.build(case)
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]
    rows, _ = model.rows(np.array([0.0]), built.y0[None, :], built, model.workspace(built))
    chain_2, chain_3 = (rows[f"lines/{name}/tension"][0] for name in ("chain_2", "chain_3"))
    np.testing.assert_allclose(chain_3, chain_2, rtol=1e-6)
    assert chain_3.max() < 1e6  # [N] a fairlead tension of hundreds of kN
