"""The system of bodies and lines: each body kind, force model and coupling against a closed
form, an invariant or today's single-cable model."""

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation

import seacable
from helpers import turning_body_case
from seacable import viz
from seacable.bodies import kinematics
from seacable.case.loader import derive_case, load_case
from seacable.kernels.timefn import evaluate
from seacable.simulation import simulate
from seacable.system import model

EXAMPLES = Path(__file__).parent.parent / "examples"


def _sim(duration, dt=None, integrator="rk4", interval=0.1, **more):
    out = {"duration": duration, "output_interval": interval, "integrator": integrator, **more}
    if dt is not None:
        out["time_step"] = dt
    return out


def _rigid(**fields):
    body = {"name": "float", "type": "rigid", "position": [0.0, 0.0, 0.0], "mass": 1000.0}
    body.update(fields)
    return body


def _case(bodies, lines, simulation, environment=None, line_types=None, start="as_given"):
    data = {
        "name": "test system",
        "start": start,
        "environment": environment or {"in_air": True},
        "bodies": bodies,
        "lines": lines,
        "simulation": simulation,
    }
    if line_types is not None:
        data["line_types"] = line_types
    return data


ANCHOR = {"name": "ground", "type": "fixed", "position": [0.0, 0.0, -50.0]}


def _tie(name, a, b, length=1.0, stiffness=1.0):
    return {"name": name, "model": "tie", "from": a, "to": b, "unstretched_length": length,
            "stiffness": stiffness}  # fmt: skip


def test_a_body_feels_the_force_its_line_reports_on_it():
    """The anchor of the mooring example (its agreement with the single-cable model is
    test_golden's): the lines' force on the body is the line's force on its 'to' point."""
    case = load_case(EXAMPLES / "catenary_mooring_line_surge.yaml")
    tree = simulate(derive_case(case, {"simulation": {"duration": 1.0}})).dataset
    for c in "xyz":
        np.testing.assert_array_equal(
            tree[f"bodies/anchor/line_force_{c}"].values, tree[f"lines/chain/to_force_{c}"].values
        )


def test_heave_float_decays_at_its_natural_period():
    """A rigid body free in heave only, on a linear spring: z(t) = z0 cos(w t) with
    w = sqrt(K / (m + A33)) (the added mass in its 6x6 matrix); surge and roll stay held."""
    k, mass, added = 4.0e5, 1000.0, 600.0
    body = _rigid(dofs=["heave"], position=[0.0, 0.0, 0.2], added_mass=[0, 0, added, 0, 0, 0],
                  inertia=[100.0, 100.0, 100.0],
                  **{"external forces": [
                      {"model": "linear_stiffness", "diagonal": [1e4, 1e4, k, 1e4, 1e4, 1e4],
                       "equilibrium_position": [0.0, 0.0, 0.0]},
                      {"model": "applied", "force_x": 500.0, "moment_x": 300.0}]})  # fmt: skip
    case = _case([body, ANCHOR], [_tie("soft", "float", "ground", length=100.0)],
                 _sim(2.0, dt=1e-3, interval=0.05))  # fmt: skip
    ds = simulate(load_case(case)).dataset["bodies/float"].to_dataset()
    t = ds["time"].values
    omega = math.sqrt(k / (mass + added))
    np.testing.assert_allclose(ds["position_z"].values, 0.2 * np.cos(omega * t), atol=1e-8)
    assert np.all(ds["position_x"].values == 0.0) and np.all(ds["roll"].values == 0.0)


def test_compound_pendulum_about_a_held_point():
    """A rigid body turning about the earth's x axis only (dofs [roll]) with its centre of
    gravity 2 m below its reference point: the small-angle period of a compound pendulum,
    2 pi sqrt(I_O / (m g d)), I_O = I_G + m d^2; the reaction at the held point is not a force
    model, so the gravity moment alone swings it."""
    mass, d, i_g = 50.0, 2.0, 10.0
    body = _rigid(mass=mass, dofs=["roll"], centre_of_gravity=[0.0, 0.0, -d],
                  inertia=[i_g, i_g, i_g], orientation_deg=[1.0, 0.0, 0.0],
                  **{"external forces": [{"model": "gravity"}]})  # fmt: skip
    case = _case([body, ANCHOR], [_tie("slack", "float", "ground", length=100.0)],
                 _sim(6.0, dt=2e-3, interval=0.01))  # fmt: skip
    ds = simulate(load_case(case)).dataset["bodies/float"].to_dataset()
    roll, t = ds["roll"].values, ds["time"].values
    crossings = t[1:][np.diff(np.sign(roll)) != 0]
    period = 2.0 * np.mean(np.diff(crossings))
    expected = 2 * math.pi * math.sqrt((i_g + mass * d * d) / (mass * 9.81 * d))
    assert abs(period / expected - 1.0) < 2e-3
    assert np.all(ds["position_z"].values == 0.0)


def test_torque_free_rigid_body_keeps_its_angular_momentum_and_energy():
    """An asymmetric body spinning freely: the angular momentum R I R^T w (earth frame) and the
    kinetic energy stay constant (quaternion rates, gyroscopic terms, projection)."""
    inertia = np.array([1.0, 2.0, 3.0])
    body = _rigid(mass=1.0, inertia=inertia.tolist(), angular_velocity=[0.1, 2.0, 0.3])
    other = {"name": "far", "type": "fixed", "position": [500.0, 0.0, 0.0]}
    case = _case([body, other], [_tie("slack", "float", "far", length=1000.0)],
                 _sim(5.0, dt=1e-3, interval=0.05))  # fmt: skip
    ds = simulate(load_case(case)).dataset["bodies/float"].to_dataset()
    angles = np.radians(np.stack([ds[a].values for a in ("roll", "pitch", "yaw")], axis=1))
    rotations = Rotation.from_euler("xyz", angles).as_matrix()
    omega = np.stack([ds[f"angular_velocity_{c}"].values for c in "xyz"], axis=1)
    momentum = np.einsum("tij,j,tkj,tk->ti", rotations, inertia, rotations, omega)
    energy = 0.5 * np.einsum("ti,ti->t", omega, momentum)
    np.testing.assert_allclose(momentum, momentum[:1].repeat(len(momentum), 0), atol=1e-9)
    np.testing.assert_allclose(energy, energy[0], rtol=1e-9)
    assert np.ptp(omega[:, 1]) > 0.1  # it does tumble (the intermediate axis)


def test_tie_between_two_free_bodies_conserves_momentum_and_goes_slack():
    """Two point bodies pulled apart then together by a linear tie (no other force): total
    momentum is constant; the tie carries tension only while longer than its length."""
    a = {"name": "a", "type": "point", "position": [0.0, 0.0, 0.0], "mass": 2.0,
         "velocity": [-1.0, 0.5, 0.0]}  # fmt: skip
    b = {"name": "b", "type": "point", "position": [3.0, 0.0, 0.0], "mass": 1.0,
         "velocity": [2.0, 0.0, 0.0]}  # fmt: skip
    case = _case([a, b], [_tie("hawser", "a", "b", length=3.0, stiffness=50.0)],
                 _sim(3.0, dt=1e-3, interval=0.01))  # fmt: skip
    tree = simulate(load_case(case)).dataset
    va = np.stack([tree[f"bodies/a/velocity_{c}"].values for c in "xyz"])
    vb = np.stack([tree[f"bodies/b/velocity_{c}"].values for c in "xyz"])
    momentum = 2.0 * va + vb
    np.testing.assert_allclose(momentum, momentum[:, :1].repeat(momentum.shape[1], 1), atol=1e-12)
    tension = tree["lines/hawser/tension"].values
    distance = tree["lines/hawser/distance"].values
    np.testing.assert_array_equal(tension[distance <= 3.0], 0.0)
    np.testing.assert_allclose(tension[distance > 3.0], 50.0 * (distance[distance > 3.0] - 3.0))
    assert tension.max() > 10.0 and np.any(distance < 3.0)


def test_euler_angles_match_scipy_and_rates_give_the_angular_velocity():
    roll, pitch, yaw = 0.3, -0.4, 1.2
    q = kinematics.euler_quaternion(roll, pitch, yaw)
    rot = np.empty((3, 3))
    kinematics.rotation(*q, rot)
    np.testing.assert_allclose(rot, Rotation.from_euler("xyz", [roll, pitch, yaw]).as_matrix(),
                               atol=1e-14)  # fmt: skip
    np.testing.assert_allclose(kinematics.quaternion_euler(*q), (roll, pitch, yaw), atol=1e-14)
    rates = np.array([0.2, -0.1, 0.5])
    omega = np.empty(3)
    kinematics.euler_rates_omega(roll, pitch, yaw, *rates, omega)
    h = 1e-6
    a = Rotation.from_euler("xyz", np.array([roll, pitch, yaw]) + h * rates).as_matrix()
    b = Rotation.from_euler("xyz", np.array([roll, pitch, yaw]) - h * rates).as_matrix()
    skew = (a - b) / (2 * h) @ rot.T  # dR/dt R^T = [omega]
    np.testing.assert_allclose(omega, [skew[2, 1], skew[0, 2], skew[1, 0]], atol=1e-8)


def test_imposed_angular_acceleration_is_the_rate_of_the_angular_velocity():
    """alpha of an imposed body against central differences of its angular velocity."""
    case = _case(
        [{"name": "ship", "type": "imposed", "x": {"kind": "sine", "amplitude": 1.0, "period": 7.0},
          "roll_deg": {"kind": "sine", "amplitude": 10.0, "period": 5.0},
          "pitch_deg": {"kind": "sine", "amplitude": 4.0, "period": 6.0, "phase": 0.3},
          "yaw_deg": {"kind": "ramp", "start_time": 0.0, "end_time": 10.0, "end_value": 30.0}},
         ANCHOR],
        [_tie("t", "ship", "ground", length=100.0)], _sim(1.0),
    )  # fmt: skip
    built = model.build(load_case(case))
    p = built.params
    tf = (p.tf_breaks, p.tf_coefs, p.tf_count, p.tf_sine, p.tf_build_up)

    def omega(t):
        angle = [evaluate(*tf, 3 + c, t)[0] for c in range(3)]
        rate = [evaluate(*tf, 3 + c, t)[1] for c in range(3)]
        out = np.empty(3)
        kinematics.euler_rates_omega(*angle, *rate, out)
        return out

    t, h = 1.3, 1e-5
    acc, work = np.empty(6), np.empty(18)
    kinematics.imposed_channels(t, 0, kinematics.TURNS, p.body_track[0], tf, work)
    kinematics.imposed_acceleration(work, acc)
    np.testing.assert_allclose(acc[3:], (omega(t + h) - omega(t - h)) / (2 * h), atol=1e-8)
    assert acc[0] == pytest.approx(-((2 * math.pi / 7) ** 2) * math.sin(2 * math.pi * t / 7))


def test_a_ship_on_its_track_turns_on_its_circle_with_its_rates():
    """A track at 30 deg, speeding up, turning right on a 200 m circle from t = 40 s: the
    straight line, then the circle tangent to it; velocity, acceleration and yaw rate are the
    derivatives of position and yaw; the yaw is the direction of travel."""
    distance = {
        "kind": "acceleration_profile",
        "initial_velocity": 2.0,
        "phases": [{"duration": 60.0, "acceleration": 0.02}],
    }
    track = {
        "start": [10.0, -5.0],
        "heading_deg": 30.0,
        "distance": distance,
        "turn": {"start_time": 40.0, "radius": 200.0, "side": "right"},
    }
    case = _case([{"name": "ship", "type": "imposed", "track": track}, ANCHOR],
                 [_tie("t", "ship", "ground", length=100.0)], _sim(1.0))  # fmt: skip
    p = model.build(load_case(case)).params
    tf = (p.tf_breaks, p.tf_coefs, p.tf_count, p.tf_sine, p.tf_build_up)
    assert p.body_motion[0] == kinematics.TRACK

    def state(t):
        work = np.empty(18)
        kinematics.imposed_channels(t, p.body_channel[0], p.body_motion[0], p.body_track[0], tf,
                                    work)  # fmt: skip
        return work

    h0 = math.radians(30.0)
    s_turn = 2.0 * 40.0 + 0.01 * 40.0**2
    for t in (20.0, 39.0, 70.0, 130.0):
        w, h = state(t), 1e-4
        ahead, behind = state(t + h), state(t - h)
        np.testing.assert_allclose(w[6:12], (ahead[:6] - behind[:6]) / (2 * h), atol=1e-7)
        np.testing.assert_allclose(w[12:18], (ahead[6:12] - behind[6:12]) / (2 * h), atol=1e-7)
        assert math.atan2(w[7], w[6]) == pytest.approx(w[5], abs=1e-12)
        s = 2.0 * t + 0.01 * min(t, 60.0) ** 2 + 1.2 * max(t - 60.0, 0.0)
        assert np.hypot(w[6], w[7]) == pytest.approx(2.0 + 0.02 * min(t, 60.0), rel=1e-12)
        if t <= 40.0:
            np.testing.assert_allclose(w[:2], [10 + s * math.cos(h0), -5 + s * math.sin(h0)])
            assert w[5] == pytest.approx(h0, abs=1e-14)
            continue
        centre = np.array([10.0, -5.0]) + s_turn * np.array([math.cos(h0), math.sin(h0)])
        centre += 200.0 * np.array([math.sin(h0), -math.cos(h0)])  # to the right
        assert np.hypot(*(w[:2] - centre)) == pytest.approx(200.0, rel=1e-12)
        assert w[5] == pytest.approx(h0 - (s - s_turn) / 200.0, abs=1e-12)


MISTAKES = [
    ({"lines": {"from": "nowhere"}}, r"lines\[0\] \(t\)\.from: 'nowhere' names no body"),
    ({"lines": {"to": "ground.hook"}}, r"body 'ground' has no point 'hook'"),
    ({"bodies": {"name": "ground"}}, r"bodies: names must be unique; \['ground'\]"),
    ({"bodies": {"dofs": ["heave", "heave"]}}, r"lists a degree of freedom twice"),
    ({"lines": {"tension_table": [[0, 0], [1, 5]]}}, r"exactly one of 'stiffness'"),
]


@pytest.mark.parametrize(("change", "message"), MISTAKES)
def test_a_mistake_names_the_body_or_line_at_fault(change, message):
    case = _case([_rigid(), ANCHOR], [_tie("t", "float", "ground")], _sim(1.0))
    for key, fields in change.items():
        case[key][0].update(fields)
    with pytest.raises(seacable.CaseError, match=message):
        model.build(load_case(case))


@pytest.mark.parametrize(
    ("relative_to", "message"),
    [
        ("float", r"bodies\[2\] \(vehicle\)\.relative_to: 'float' is a rigid body"),
        ("nobody", r"'nobody' names no body"),
        ("vehicle", r"'vehicle' is the body itself"),
        ("ship", r"'ship' moves relative to 'tug' itself; give 'vehicle' relative to 'tug'"),
    ],
)
def test_an_imposed_body_moves_relative_to_one_imposed_body(relative_to, message):
    tug = {"name": "tug", "type": "imposed", "track": {"speed": 1.0}}
    ship = {"name": "ship", "type": "imposed", "relative_to": "tug"}
    vehicle = {"name": "vehicle", "type": "imposed", "relative_to": relative_to}
    case = _case([tug, _rigid(), vehicle, ship], [_tie("t", "float", "vehicle")], _sim(1.0))
    with pytest.raises(seacable.CaseError, match=message):
        model.build(load_case(case))


def test_a_lumped_line_needs_a_known_line_type():
    case = _case(
        [ANCHOR, {"name": "top", "type": "fixed", "position": [10.0, 0.0, -40.0]}],
        [{"name": "leg", "model": "lumped_mass", "from": "top", "to": "ground",
          "sections": [{"type": "rope", "length": 20.0, "segments": 4}]}],
        _sim(1.0), line_types=[{"name": "chain", "diameter": 0.1, "mass_per_length": 50.0,
                                "axial_stiffness": 1e8}],
    )  # fmt: skip
    with pytest.raises(seacable.CaseError, match=r"sections\[0\]\.type: no line type 'rope'"):
        model.build(load_case(case))


def test_system_results_are_a_datatree_on_disk_and_in_pictures(tmp_path):
    """Groups per body and line with units and long names; plot and animate draw them."""
    a = {"name": "buoy", "type": "point", "position": [0.0, 0.0, -10.0], "mass": 100.0,
         "volume": 0.2, "added_mass": 50.0,
         "external forces": [{"model": "gravity"}, {"model": "buoyancy"},
                             {"model": "drag", "drag_coefficient": 1.0, "area": 0.5}]}  # fmt: skip
    case = _case(
        [a, ANCHOR],
        [{"name": "rope", "model": "lumped_mass", "from": "ground", "to": "buoy",
          "sections": [{"type": "rope", "length": 40.0, "segments": 6}], "initial": "straight"}],
        _sim(2.0, dt=5e-4, interval=0.1),
        environment={"water_depth": 50.0},
        line_types=[{"name": "rope", "diameter": 0.05, "mass_per_length": 2.0,
                     "axial_stiffness": 2e6, "axial_damping_ratio": 1.0}],
    )  # fmt: skip
    path = tmp_path / "buoy.nc"
    simulate(load_case(case), output=path)
    tree = xr.open_datatree(path, engine="h5netcdf")
    assert set(tree["bodies"].children) == {"buoy", "ground"}
    for node in tree.subtree:
        for name, variable in node.to_dataset().data_vars.items():
            assert variable.attrs.get("units") and variable.attrs.get("long_name"), name
    z = tree["bodies/buoy/position_z"].values
    # net buoyancy (0.2 m^3 of water for 100 kg: 1030 N) stretches the nearly neutral 40 m rope
    # (EA / L = 5e4 N/m) by about 2.1 cm, about which the buoy still swings after 2 s
    assert 0.015 < z[-10:].mean() + 10.0 < 0.03
    assert "angular_velocity_x" not in tree["bodies/buoy"].to_dataset()  # a point body
    results = seacable.Results.open(path)
    assert viz.plot_results(results.dataset, tmp_path / "p.png").stat().st_size > 10_000
    gif = viz.animate_results(results.dataset, tmp_path / "a.gif", max_frames=3, progress=False)
    assert gif.stat().st_size > 1_000


def _buoy_on_tie(**buoy):
    body = {"name": "buoy", "type": "point", "position": [1.0, 0.5, -30.0], "mass": 400.0,
            "volume": 1.0, "external forces": [{"model": "gravity"}, {"model": "buoyancy"}],
            **buoy}  # fmt: skip
    return _case([body, ANCHOR], [_tie("tether", "ground", "buoy", length=12.0, stiffness=2e4)],
                 _sim(1.0), environment={"water_depth": 50.0}, start="static")  # fmt: skip


def test_statics_of_a_buoy_on_a_tether_is_the_closed_form():
    """A buoy of net buoyancy (rho V - m) g on a linear tether from a fixed anchor: it floats
    straight above the anchor, the tether stretched by that force over its stiffness."""
    results = seacable.statics(load_case(_buoy_on_tie()))
    ds = results.dataset["bodies/buoy"].to_dataset().isel(time=0)
    lift = (1025.0 * 1.0 - 400.0) * 9.81
    assert ds["position_x"].item() == pytest.approx(0.0, abs=1e-9)
    assert ds["position_y"].item() == pytest.approx(0.0, abs=1e-9)
    assert ds["position_z"].item() == pytest.approx(-50.0 + 12.0 + lift / 2e4, abs=1e-9)
    assert results.dataset["lines/tether/tension"].values[0] == pytest.approx(lift, rel=1e-9)


def test_statics_finds_the_balance_a_tie_only_gives_once_stretched():
    """A constant push of 100 N along x on a buoy free in surge only, its 12 m tie exactly
    vertical and unstretched: at the start nothing resists along x (the tie's stiffness there
    is zero, and Newton finds no balance), but the tie stretched sideways holds it where
    k (L - L0) x / L = 100 N, L = sqrt(L0^2 + x^2) (about 1.13 m off; closed form to 1e-9 m).
    The dynamic relaxation finds it (system.relax)."""
    push = {"model": "applied", "force_x": 100.0}
    case = _buoy_on_tie(dofs=["surge"], position=[0.0, 0.0, -38.0])
    case["bodies"][0]["external forces"].append(push)
    results = seacable.statics(load_case(case))
    x = results.dataset["bodies/buoy/position_x"].values[0]

    def held(x):
        length = np.hypot(12.0, x)
        return 2e4 * (length - 12.0) * x / length - 100.0

    assert x == pytest.approx(brentq(held, 0.1, 5.0, xtol=1e-14), abs=1e-9)
    assert 1.0 < x < 1.3


def test_statics_names_the_body_nothing_holds():
    """A constant push along x on a buoy free in surge and heave, held by a stiffness in heave
    only: nothing resists along x, and the statics names the body and the axis (after the
    dynamic relaxation found it running away)."""
    push = {"model": "applied", "force_x": 100.0}
    spring = {"model": "linear_stiffness", "diagonal": [0.0, 0.0, 1e4, 0.0, 0.0, 0.0]}
    case = _buoy_on_tie()  # a second buoy, on the tie, besides it
    buoy = {**case["bodies"][0], "name": "free", "dofs": ["surge", "heave"]}
    buoy["external forces"] = [*buoy["external forces"], push, spring]
    case["bodies"].append(buoy)
    with pytest.raises(seacable.SeacableError, match=r"body 'free' \(force along x"):
        seacable.statics(load_case(case))


def test_a_free_decay_has_the_period_of_the_linearised_modes():
    """The platform example (coarser lines), displaced 0.5 m in heave from its equilibrium and
    released: the damped heave period of the run within 1 % of the linearised system's
    (system_modes), whose pitch period is the closed form of its hydrostatics within 2 %."""
    from seacable.analysis import system_modes

    path = EXAMPLES / "platform_three_catenary_lines.yaml"
    coarse = {"lines": [
        {**line, "sections": [{**line["sections"][0], "segments": 10}]}
        for line in yaml.safe_load(path.read_text())["lines"]
    ]}  # fmt: skip
    case = seacable.case.loader.derive_case(load_case(path), coarse)
    modes = system_modes(case)
    heave = float(modes["period"][list(modes["dominant"].values).index("platform:heave")])
    pitch = float(modes["period"][list(modes["dominant"].values).index("platform:pitch")])
    stiffness = 1.00553e9 + 1025 * 9.81 * 1e4 * (-15 + 10)  # waterplane + rho g V (z_B - z_G)
    inertia = 8.0e9 + 1e7 * 10.0**2 + 4.0e9  # about the reference point, added inertia included
    assert pitch == pytest.approx(2 * math.pi * math.sqrt(inertia / stiffness), rel=0.02)
    still = seacable.statics(case).dataset["bodies/platform"].to_dataset().isel(time=0)
    start = [still[f"position_{c}"].item() for c in "xy"] + [still["position_z"].item() + 0.5]
    released = seacable.case.loader.derive_case(case, {
        "start": "as_given",
        "bodies": [*yaml.safe_load(path.read_text())["bodies"][:3],
                   {**yaml.safe_load(path.read_text())["bodies"][3], "position": start,
                    "external forces": yaml.safe_load(path.read_text())["bodies"][3][
                        "external forces"][:4]}],
        "simulation": {"duration": 80.0, "output_interval": 0.05},
    })  # fmt: skip
    ds = simulate(released).dataset["bodies/platform"].to_dataset()
    z = ds["position_z"].values - still["position_z"].item()
    t = ds["time"].values
    upward = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))
    crossings = t[upward] - z[upward] * (t[upward + 1] - t[upward]) / (z[upward + 1] - z[upward])
    measured = float(np.mean(np.diff(crossings)))
    assert measured == pytest.approx(heave, rel=0.01)


def test_energy_of_bodies_on_lines_is_conserved_without_damping():
    """A rigid body (off-centre points, turning) hung in air from a fixed point by a lumped
    line and tied to a point body by a spring tie, swinging in 3D: no drag, no axial damping,
    so kinetic + gravity potential + elastic energy is constant (rk4, small step). It checks
    the coupling: an end node's mass and loads carried by a turning body."""
    case = turning_body_case(_sim(2.0, dt=2e-5, interval=0.1))
    tree = simulate(load_case(case)).dataset
    total = tree["total_energy"].values
    kinetic = tree["kinetic_energy"].values
    assert np.ptp(kinetic) > 100.0  # the swing exchanges energies
    assert np.ptp(total) < 1e-6 * np.abs(kinetic).max()


def test_a_group_of_bodies_nothing_holds_is_named():
    """Two buoys joined by a tie and to nothing else: no static equilibrium, refused."""
    a = {"name": "a", "type": "point", "position": [0.0, 0.0, -5.0], "mass": 1.0}
    b = {"name": "b", "type": "point", "position": [3.0, 0.0, -5.0], "mass": 1.0}
    case = _case([a, b, ANCHOR], [_tie("t", "a", "b")], _sim(1.0), start="static")
    with pytest.raises(
        seacable.CaseError, match=r"bodies \['a', 'b'\]: a group that nothing holds"
    ):
        model.build(load_case(case))


def test_a_number_yaml_reads_as_text_is_a_constant_but_nan_is_refused():
    """YAML 1.1 reads 1.0e6 as text; the case loader reads it as the number it is, but not
    text that reads as nan."""
    text = "\n".join([
        "bodies:",
        "  - {name: a, type: fixed, position: [0, 0, 0]}",
        "  - {name: b, type: imposed, x: 1.0e3}",
        "lines: [{name: t, model: tie, from: a, to: b, unstretched_length: 1, stiffness: 1}]",
        "simulation: {duration: 1, output_interval: 0.1}",
    ])  # fmt: skip
    assert load_case(text).bodies[1].x.value == 1000.0
    with pytest.raises(seacable.CaseError, match=r"bodies\[1\]\.x"):
        load_case(text.replace("x: 1.0e3", "x: nan"))
