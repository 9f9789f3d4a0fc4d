"""Line failures (the case's ``failures``, system.failures): a rope released at its top falls
with its centre of mass at exactly g whatever the integrator (momentum: only gravity acts on it
once free), a tension threshold releases the line at the step its tension crosses it in an
intact run, the released end leaves moving as the point it left, two lines released together
stay joined, a built system runs again from intact lines, and what a failure cannot be is
refused by name."""

import numpy as np
import pytest

import seacable
from seacable.coupling import Coupling
from seacable.errors import CaseError

G = 9.81
ROPE = {"name": "rope", "diameter": 0.05, "mass_per_length": 2.0, "axial_stiffness": 1.0e6,
        "axial_damping_ratio": 0.2}  # fmt: skip


def _hanging(failures, simulation):
    """A 20 m rope of 10 segments hanging in air from a fixed point, a 50 kg clump at its end."""
    return seacable.load_case({
        "environment": {"in_air": True, "gravity": G},
        "bodies": [{"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0]},
                   {"name": "clump", "type": "point", "position": [0.0, 0.0, -20.0],
                    "mass": 50.0, "external forces": [{"model": "gravity"}]}],
        "line_types": [ROPE],
        "lines": [{"name": "rope", "model": "lumped_mass", "from": "top", "to": "clump",
                   "sections": [{"type": "rope", "length": 20.0, "segments": 10}]}],
        "failures": failures, "simulation": simulation,
    })  # fmt: skip


@pytest.mark.parametrize(
    "simulation",
    [{"integrator": "rk4", "time_step": 0.001},
     {"integrator": "dopri5", "rtol": 1e-9, "atol": 1e-11},
     {"integrator": "generalized_alpha", "time_step": 0.005}],
    ids=["rk4", "dopri5", "generalized_alpha"],
)  # fmt: skip
def test_a_rope_released_at_its_top_falls_with_its_centre_of_mass_at_g(simulation):
    """Released at t = 1 s from its static hang, the rope (40 kg, node masses 2, 4, ..., 4, 2)
    and its clump (50 kg) fall: the centre of mass is at rest before and on the parabola of
    acceleration -g after, to round-off (the stretched rope's recoil is internal); the released
    end, the failure's point body, sits at the top until then and falls below it after."""
    ds = seacable.simulate(_hanging([{"at": "top", "time": 1.0}],
                                    {"duration": 2.0, "output_interval": 0.01,
                                     **simulation})).dataset  # fmt: skip
    assert ds.attrs["failure_failure1_time"] == pytest.approx(1.0, abs=1e-9)
    assert ds.attrs["failures"] == "failure1: rope released at t = 1 s"
    line = ds["lines/rope"].to_dataset()
    t = line["time"].values
    mass = np.full(11, 4.0)
    mass[[0, -1]] = 2.0
    clump = ds["bodies/clump"].to_dataset()["position_z"].values
    centre = (line["node_z"].values @ mass + 50.0 * clump) / 90.0
    after = t > 1.0 + 1e-9
    fit = np.polyfit(t[after] - 1.0, centre[after], 2)
    assert 2 * fit[0] == pytest.approx(-G, rel=1e-9)
    assert np.abs(np.polyval(fit, t[after] - 1.0) - centre[after]).max() < 1e-9
    assert abs(fit[1]) < 0.01  # from rest (the implicit schemes release a step late: 0.002)
    assert np.ptp(centre[~after]) < 1e-9
    end = ds["bodies/failure1"].to_dataset()["position_z"].values
    assert np.abs(end[~after]).max() < 1e-9 and end[-1] < -4.0
    # the rows before the release (evaluated after the chunk that released it) see the rope
    # attached: its top segment carries the 88 kg below it
    top = line["tension"].values[:, 0]
    np.testing.assert_allclose(top[~after], 88.0 * G, rtol=1e-6)


def _towed(failures, duration=4.0):
    """A 20 m rope in air from an anchor to a tug pulling it taut at 0.5 m/s."""
    return {
        "environment": {"in_air": True, "gravity": G},
        "bodies": [{"name": "anchor", "type": "fixed", "position": [0.0, 0.0, 0.0]},
                   {"name": "tug", "type": "imposed",
                    "x": {"kind": "ramp", "start_time": 0.0, "end_time": 4.0,
                          "start_value": 19.0, "end_value": 21.0}}],
        "line_types": [ROPE],
        "lines": [{"name": "rope", "model": "lumped_mass", "from": "anchor", "to": "tug",
                   "sections": [{"type": "rope", "length": 20.0, "segments": 10}]}],
        "failures": failures,
        "simulation": {"duration": duration, "output_interval": 0.001, "integrator": "rk4",
                       "time_step": 0.001},
    }  # fmt: skip


def test_a_released_chain_end_comes_to_rest_on_the_seabed():
    """A chain from an anchor to a fairlead 30 m up, released at its fairlead at 1 s: its
    free end falls and comes to rest on the seabed, held by its end node's contact at the
    depth the lying nodes rest at (1.8 mm, to 1e-6 m), and the run says nothing of a body
    below the seabed."""
    chain = {"name": "chain", "diameter": 0.08, "mass_per_length": 40.0,
             "axial_stiffness": 1.0e8, "axial_damping_ratio": 0.5,
             "drag_coefficient_normal": 1.2}  # fmt: skip
    case = seacable.load_case({
        "environment": {"water_depth": 50.0, "seabed": {"stiffness": 1.0e6, "damping": 1.0e4}},
        "bodies": [{"name": "anchor", "type": "fixed", "position": [-60.0, 0.0, -50.0]},
                   {"name": "fairlead", "type": "fixed", "position": [0.0, 0.0, -20.0]}],
        "line_types": [chain],
        "lines": [{"name": "chain", "model": "lumped_mass", "from": "anchor", "to": "fairlead",
                   "sections": [{"type": "chain", "length": 80.0, "segments": 16}]}],
        "failures": [{"at": "fairlead", "lines": ["chain"], "time": 1.0}],
        "simulation": {"duration": 40.0, "output_interval": 1.0, "integrator": "dopri5"},
    })  # fmt: skip
    ds = seacable.simulate(case).dataset
    end = ds["bodies/failure1"].to_dataset()["position_z"].values
    lying = ds["lines/chain"].to_dataset()["node_z"].values[-1, -4:-1]  # its last nodes
    assert end[0] == pytest.approx(-20.0) and -50.01 < end.min()
    assert np.abs(lying - end[-1]).max() < 1e-6, (lying, end[-1])
    assert "run_warnings" not in ds.attrs, ds.attrs.get("run_warnings")


def test_a_tension_threshold_releases_the_line_where_the_intact_one_crosses_it():
    """The tug pulls the sagging rope taut: the intact run's tension at the tug first reaches
    20 kN at some step; with a failure at 20 kN the rope is released at that same step, its
    end leaves with the tug's 0.5 m/s, and the tug feels nothing after."""
    intact = seacable.simulate(seacable.load_case(_towed([]))).dataset
    tension = intact["lines/rope"].to_dataset()["tension"].values[:, -1]
    crossing = intact["time"].values[np.argmax(tension >= 2.0e4)]
    assert 1.0 < crossing < 3.5
    ds = seacable.simulate(seacable.load_case(_towed(
        [{"name": "snap", "at": "tug", "tension": 2.0e4}]))).dataset  # fmt: skip
    released = ds.attrs["failure_snap_time"]
    assert released == pytest.approx(crossing, abs=1e-9)
    t = ds["time"].values
    end = ds["bodies/snap"].to_dataset()
    k = int(np.argmin(abs(t - released)))
    assert end["velocity_x"].values[k] == pytest.approx(0.5, rel=1e-9)
    assert end["position_x"].values[k] == pytest.approx(19.0 + 0.5 * released, rel=1e-12)
    pull = ds["bodies/tug"].to_dataset()["line_force_x"].values
    assert np.abs(pull[t < released - 1e-9]).max() > 1.0e4
    assert np.abs(pull[t > released + 1e-9]).max() == 0.0


def test_two_lines_released_together_stay_joined():
    """A Y of two ropes from a hub held by an imposed body to two fixed anchors: released at the
    hub, both ends move with the failure's point body (MoorDyn's free point joining them)."""
    data = _towed([], duration=1.5)
    data["bodies"].append({"name": "anchor2", "type": "fixed", "position": [0.0, 15.0, 0.0]})
    data["lines"].append({"name": "rope2", "model": "lumped_mass", "from": "anchor2",
                          "to": "tug", "sections": [{"type": "rope", "length": 25.0,
                                                     "segments": 10}]})  # fmt: skip
    data["failures"] = [{"name": "hub", "at": "tug", "time": 0.5}]
    ds = seacable.simulate(seacable.load_case(data)).dataset
    assert ds.attrs["failures"] == "hub: rope, rope2 released at t = 0.5 s"
    t = ds["time"].values
    hub = ds["bodies/hub"].to_dataset()
    for name in ("rope", "rope2"):
        line = ds[f"lines/{name}"].to_dataset()
        for c in "xyz":
            gap = line[f"node_{c}"].values[:, -1] - hub[f"position_{c}"].values
            assert np.abs(gap[t > 0.5 + 1e-9]).max() < 1e-12
    assert hub["position_z"].values[-1] < -1.0  # falling


def test_a_coupled_run_starts_again_from_intact_lines():
    """The stepping interface (seacable.coupling) across a failure at 0.5 s, twice: the second
    init attaches the line again and gives the first init's forces, and it is released again."""
    case = seacable.load_case(_towed([{"at": "tug", "time": 0.5}], duration=1.0))
    coupling = Coupling(case)
    x0 = np.array([19.0, 0.0, 0.0])
    runs = []
    for _ in range(2):
        forces = [coupling.init(x0, np.zeros(3))]
        for k in range(10):
            forces.append(coupling.step(x0, np.zeros(3), 0.1 * k, 0.1))
        runs.append(np.array(forces))
    np.testing.assert_array_equal(runs[0], runs[1])
    assert np.abs(runs[0][0]).max() > 100.0 and np.abs(runs[0][-1]).max() < 1e-9


@pytest.mark.parametrize(
    ("failure", "message"),
    [({"at": "tug"}, "give the failure a 'time'"),
     ({"at": "tug", "time": 1.0, "lines": ["nothing"]}, "'nothing' has no end at 'tug'"),
     ({"at": "boat", "time": 1.0}, "'boat' is not a body"),
     ({"name": "anchor", "at": "tug", "time": 1.0}, "'anchor' is already a body's"),
     ({"at": "anchor.pad", "time": 1.0}, "no lumped_mass line ends at 'anchor.pad'")],
)  # fmt: skip
def test_what_a_failure_cannot_be_is_refused_by_name(failure, message):
    with pytest.raises(CaseError, match=message):
        seacable.load_case(_towed([failure]))


def test_a_scipy_solver_cannot_follow_a_release():
    data = _towed([{"at": "tug", "time": 1.0}])
    data["simulation"] = {"duration": 1.0, "output_interval": 0.1, "integrator": "bdf"}
    with pytest.raises(CaseError, match="simulation.integrator bdf"):
        seacable.load_case(data)
