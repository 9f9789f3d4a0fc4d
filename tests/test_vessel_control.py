"""A vessel's controlled forces and coefficient loads (forces.thruster, forces.rudder,
forces.coefficients), each alone against a hand computation or a closed form: thrust and its
moment at a point for any pose, the speed a thrust reaches against quadratic damping, the speed
controller, rudder lift and drag for any inflow, a steady turn on a fixed rudder against the
body-frame equations solved here, the heading autopilot, and OCIMF-style wind and current loads
on the flow relative to the ship."""

import math

import numpy as np
import pytest
from scipy.optimize import fsolve
from scipy.spatial.transform import Rotation

import seacable
from seacable.bodies import kinematics
from seacable.errors import CaseError
from seacable.system import kernel, model

RHO = 1025.0
MASS, IZ = 2.0e6, 1.2e9  # a 100 m ship (tests/test_vessel_dynamics.py)
A11, A22, A66 = 0.05 * MASS, 0.9 * MASS, 0.7 * IZ
Q11, Q22, Q66 = 2.0e4, 2.0e5, 5.0e10  # quadratic damping [N s^2/m^2, N m s^2/rad^2]


def _case(forces, env=None, duration=1.0, **body):
    spec = {"name": "ship", "type": "rigid", "position": [0, 0, 0], "mass": MASS,
            "inertia": [1e8, 1e9, IZ], "external forces": forces} | body  # fmt: skip
    return seacable.load_case({
        "environment": env or {}, "bodies": [spec], "start": "as_given",
        "simulation": {"duration": duration, "output_interval": 1.0, "integrator": "dopri5",
                       "rtol": 1e-9},
    })  # fmt: skip


def _loads(case, velocity=(0, 0, 0), omega=(0, 0, 0), angles=(0, 0, 0), t=0.0):
    """The body's force and moment (earth frame, about the reference point) in a pose and
    motion."""
    built = model.build(case)
    p, y = built.params, built.y0.copy()
    y[3:7] = kinematics.euler_quaternion(*(float(a) for a in angles))
    v = int(p.body_v[0])
    y[v : v + 3], y[v + 3 : v + 6] = velocity, omega
    w = kernel.make_work(p)
    kernel.rhs(t, y, p, w, np.zeros_like(y))
    return w.load[0].copy()


def _rotation(angles):
    return Rotation.from_euler("xyz", angles).as_matrix()


def _body_velocities(results):
    ship = results["bodies/ship"]
    yaw = np.radians(ship["yaw"].values)
    vx, vy = ship["velocity_x"].values, ship["velocity_y"].values
    u = np.cos(yaw) * vx + np.sin(yaw) * vy
    v = -np.sin(yaw) * vx + np.cos(yaw) * vy
    return u, v, ship["angular_velocity_z"].values, ship["yaw"].values


HORIZONTAL = {"dofs": ["surge", "sway", "yaw"],
              "added_mass": [A11, A22, 0.0, 0.0, 0.0, A66]}  # fmt: skip
DAMPING = {"model": "quadratic_damping", "diagonal": [Q11, Q22, 0, 0, 0, Q66]}


# ---- thruster ------------------------------------------------------------------------------------
def test_thrust_and_its_moment_at_a_point_for_any_pose():
    """A fixed thruster (a sine thrust along a slanted direction) and an azimuth thruster: force
    R (T d) and moment (R r_P) x (R T d) for random orientations and times."""
    rng = np.random.default_rng(3)
    point, direction = np.array([-40.0, 6.0, -3.0]), np.array([0.8, -0.3, 0.2])
    unit = direction / np.linalg.norm(direction)
    fixed = {
        "model": "thruster",
        "point": point.tolist(),
        "direction": direction.tolist(),
        "thrust": {"kind": "sine", "amplitude": 2e5, "period": 7.0, "offset": 5e5},
    }
    azimuth = {"model": "thruster", "point": "stern", "thrust": 3e5,
               "azimuth_deg": {"kind": "ramp", "start_time": 0, "end_time": 10,
                               "start_value": 0, "end_value": 90}}  # fmt: skip
    cases = (_case([fixed]), _case([azimuth], points={"stern": [-45.0, 0.0, -4.0]}))
    for _ in range(5):
        angles, t = rng.uniform(-1.0, 1.0, 3), rng.uniform(0.0, 10.0)
        rot = _rotation(angles)
        thrust = 5e5 + 2e5 * math.sin(2 * math.pi * t / 7.0)
        a = math.radians(9.0 * t)
        for case, arm, force in (
            (cases[0], rot @ point, rot @ (thrust * unit)),
            (cases[1], rot @ [-45.0, 0.0, -4.0], rot @ (3e5 * np.array([math.cos(a),
                                                                        math.sin(a), 0.0]))),
        ):  # fmt: skip
            load = _loads(case, angles=angles, t=t)
            assert load[:3] == pytest.approx(force, rel=1e-12)
            assert load[3:] == pytest.approx(np.cross(arm, force), rel=1e-12, abs=1e-6)


def test_thrust_against_quadratic_damping_reaches_its_closed_form_speed():
    """A constant thrust T ahead against surge damping Q u|u| settles at u = sqrt(T / Q)."""
    thrust = 8.0e5
    case = _case([{"model": "thruster", "point": [-45, 0, -4], "thrust": thrust}, DAMPING],
                 duration=1500.0, **HORIZONTAL)  # fmt: skip
    u, v, r, _ = _body_velocities(seacable.simulate(case))
    assert u[-1] == pytest.approx(math.sqrt(thrust / Q11), rel=1e-9)
    assert abs(v[-1]) < 1e-9 and abs(r[-1]) < 1e-12


@pytest.mark.parametrize(
    "law", ["feedforward", "proportional", "saturated", "integral", "integral saturated"]
)
def test_the_speed_controller(law):
    """T = T_ff + K (U - u) + K_i I: with the resistance at U as T_ff the ship settles on U;
    proportional alone at K (U - u) = Q u^2; limited to max_thrust below Q U^2 at
    sqrt(max_thrust / Q). With the integral (no feed-forward) it settles on U with
    K_i I = Q U^2; saturated from the start, the integral is held at 0 (without the hold it
    would have grown to about 2,600 m)."""
    target, gain, integral_gain = 6.0, 4.0e5, 2.0e4
    controller = {"kind": "surge_speed", "target": target, "gain": gain}
    thruster = {"model": "thruster", "point": [-45, 0, -4], "controller": controller}
    if law.startswith("integral"):
        controller["integral_gain"] = integral_gain
    if law in ("feedforward", "integral"):
        controller["feedforward"] = Q11 * target**2 if law == "feedforward" else 0.0
        expected = target
    elif law == "proportional":
        expected = (-gain + math.sqrt(gain**2 + 4 * Q11 * gain * target)) / (2 * Q11)
    else:
        thruster["max_thrust"] = 0.5 * Q11 * target**2
        expected = math.sqrt(0.5) * target
    case = _case([thruster, DAMPING], duration=1500.0, **HORIZONTAL)
    results = seacable.simulate(case)
    u, _, _, _ = _body_velocities(results)
    assert u[-1] == pytest.approx(expected, rel=1e-9)
    assert law != "proportional" or u[-1] < 0.9 * target  # the proportional law's offset
    if law == "integral":
        integral = results["bodies/ship"]["speed_integral"].values
        assert integral[-1] == pytest.approx(Q11 * target**2 / integral_gain, rel=1e-9)
    elif law == "integral saturated":
        assert np.array_equal(results["bodies/ship"]["speed_integral"].values, np.zeros(1501))
    else:
        assert "speed_integral" not in results["bodies/ship"]


# ---- rudder --------------------------------------------------------------------------------------
RUDDER_AT = np.array([-48.0, 0.0, -3.0])


def _rudder(**extra):
    return {
        "model": "rudder",
        "point": RUDDER_AT.tolist(),
        "area": 20.0,
        "lift_slope": 3.0,
        "stall_angle_deg": 30.0,
        "drag_coefficient": 0.02,
        "angle_deg": 10.0,
    } | extra


def test_rudder_lift_and_drag_for_any_inflow():
    """For drift angles beta of the rudder's velocity through the water (with a current), the
    force's component against that velocity is q A C_D and the one perpendicular to it
    (towards starboard of the velocity) q A C_L(alpha), alpha = delta + beta up to the stall;
    its moment is r_P x F; a table of the same lift line gives the same force."""
    current = np.array([0.6, -0.4, 0.0])
    env = {
        "current": {
            "velocity": float(np.hypot(*current[:2])),
            "direction_deg": math.degrees(math.atan2(current[1], current[0])),
        }
    }
    delta = math.radians(10.0)
    table = [[a, 3.0 * math.radians(max(-30.0, min(30.0, a))), 0.02]
             for a in np.arange(-90.0, 91.0, 5.0)]  # fmt: skip
    for model_ in (_rudder(), _rudder(lift_slope=None, coefficients=table)):
        case = _case([model_], env=env)
        for beta_deg in (-60.0, -25.0, -5.0, 0.0, 8.0, 15.0, 40.0, 170.0):
            beta, speed, yaw = math.radians(beta_deg), 4.0, 0.7
            rot = _rotation((0.0, 0.0, yaw))
            s_body = speed * np.array([math.cos(beta), math.sin(beta), 0.0])
            # the body's velocity such that the rudder moves with s_body through the water
            omega = np.array([0.0, 0.0, 0.01])
            arm = rot @ RUDDER_AT
            velocity = rot @ s_body + current - np.cross(omega, arm)
            load = _loads(case, velocity, omega, (0.0, 0.0, yaw))
            force = rot.T @ load[:3]
            alpha = beta + delta
            alpha -= math.pi * round(alpha / math.pi)  # the foil reversed in flow from astern
            cl = 3.0 * max(-math.radians(30.0), min(math.radians(30.0), alpha))
            q_area = 0.5 * RHO * speed**2 * 20.0
            ahead = s_body / speed
            starboard = np.array([ahead[1], -ahead[0], 0.0])
            assert force @ ahead == pytest.approx(-q_area * 0.02, rel=1e-9, abs=1e-6)
            assert force @ starboard == pytest.approx(q_area * cl, rel=1e-9, abs=1e-6)
            assert load[3:] == pytest.approx(np.cross(arm, load[:3]), rel=1e-12, abs=1e-6)


def _turning(rudder, duration=600.0, *extra):
    thruster = {"model": "thruster", "point": [-45, 0, -4], "thrust": 8.0e5}
    return _case([thruster, rudder, DAMPING, *extra], duration=duration, **HORIZONTAL)


def _steady_turn(delta_deg):
    """(u, v, r) of the steady turn from the body-frame equations (the document's form:
    Coriolis of the rigid-body mass), the rudder's force computed here."""
    xr, delta = RUDDER_AT[0], math.radians(delta_deg)

    def residual(x):
        u, v, r = x
        sx, sy = u, v + r * xr
        speed = math.hypot(sx, sy)
        alpha = delta + math.atan2(sy, sx)
        cl = 3.0 * max(-math.radians(30), min(math.radians(30), alpha))
        qa = 0.5 * RHO * speed * 20.0  # q A / V
        fx, fy = qa * (cl * sy - 0.02 * sx), qa * (-cl * sx - 0.02 * sy)
        return [
            8.0e5 + fx - Q11 * u * abs(u) + MASS * v * r,
            fy - Q22 * v * abs(v) - MASS * u * r,
            xr * fy - Q66 * r * abs(r),
        ]

    return fsolve(residual, [6.0, 0.0, 0.01], xtol=1e-12)


def test_a_fixed_rudder_turns_the_ship_to_port_and_settles_on_the_steady_turn():
    """Rudder +10 deg (trailing edge to port) on a ship going ahead: it turns to port (positive
    yaw rate) and settles on the steady turn of its body-frame equations; -10 deg mirrors it."""
    for sign in (1.0, -1.0):
        results = seacable.simulate(_turning(_rudder(angle_deg=10.0 * sign)))
        u, v, r, _ = _body_velocities(results)
        assert sign * r[-1] > 0.0
        assert abs(r[-1] - r[-11]) < 1e-6 * abs(r[-1])  # steady
        expected = _steady_turn(10.0 * sign)
        assert [u[-1], v[-1], r[-1]] == pytest.approx(expected, rel=1e-7)


def test_the_steering_gear_turns_the_rudder_at_its_rate_then_settles_as_a_lag():
    """A 10 deg command through a steering gear of 2.3 deg/s and 0.1 s: the rudder turns at
    2.3 deg/s from amidships until it is rate T from the command (at t1 = (10 - rate T) / rate),
    then closes in as e^{-(t - t1)/T}; the ship ends on the fixed rudder's steady turn."""
    rate, lag = 2.3, 0.1
    rudder = _rudder(steering_gear={"max_rate_deg_s": rate, "time_constant": lag})
    results = seacable.simulate(_turning(rudder))
    time = results["time"].values
    angle = results["bodies/ship"]["rudder_angle"].values
    t1 = (10.0 - rate * lag) / rate
    expected = np.where(time < t1, rate * time,
                        10.0 - rate * lag * np.exp(-np.maximum(time - t1, 0.0) / lag))  # fmt: skip
    assert angle == pytest.approx(expected, abs=1e-7)
    u, v, r, _ = _body_velocities(results)
    assert [u[-1], v[-1], r[-1]] == pytest.approx(_steady_turn(10.0), rel=1e-7)


def test_the_autopilot_brings_the_heading_to_its_target():
    """A PD heading autopilot takes the ship from 0 to 30 deg, then at 300 s to -20 deg, and
    holds each without steady error (nothing pulls it off its heading once the sway has died
    out: linear damping added, as quadratic damping alone lets a drift decay as 1/t) and
    without overshoot (gains of an overdamped loop)."""
    pilot = {"heading_deg": {"kind": "ramp", "start_time": 300, "end_time": 301,
                             "start_value": 30, "end_value": -20},
             "gain": 3.0, "rate_gain": 40.0, "max_angle_deg": 25.0}  # fmt: skip
    linear = {"model": "linear_damping", "frame": "body", "diagonal": [0, 6e5, 0, 0, 0, 1.5e9]}
    results = seacable.simulate(_turning(_rudder(angle_deg=None, autopilot=pilot), 700.0,
                                         linear))  # fmt: skip
    _, _, r, yaw = _body_velocities(results)
    time = results["time"].values
    assert yaw[time == 295.0][0] == pytest.approx(30.0, abs=0.01)
    assert yaw[-1] == pytest.approx(-20.0, abs=1e-3)
    assert abs(r[-1]) < 1e-6
    assert yaw.max() < 30.0 and yaw[time > 300.0].min() > -20.0


# ---- wind and current loads ----------------------------------------------------------------------
AT, AL, LENGTH = 300.0, 1500.0, 100.0
POINT = [5.0, 1.0, 0.0]


def _shape(psi):
    """The test table's coefficients: C_X = -0.7 cos psi, C_Y = -0.9 sin psi,
    C_N = 0.1 sin 2 psi (psi [rad], the direction the flow comes from)."""
    return -0.7 * np.cos(psi), -0.9 * np.sin(psi), 0.1 * np.sin(2 * psi)


def _coefficient_model(model_, step=1.0, symmetric=False):
    psi = np.arange(0.0, 180.0 + step / 2, step) if symmetric else np.arange(-180.0, 180.0, step)
    cx, cy, cn = _shape(np.radians(psi))
    rows = np.column_stack([psi, cx, cy, cn]).tolist()
    return {"model": model_, "point": POINT, "transverse_area": AT, "lateral_area": AL,
            "length": LENGTH, "coefficients": rows, "symmetric": symmetric}  # fmt: skip


def _expected(flow_body, rho, rot):
    """Force and moment (earth frame, about the reference point) of the closed-form table for
    the flow ``flow_body`` relative to the point, in the body frame."""
    psi = math.atan2(-flow_body[1], -flow_body[0])
    q = 0.5 * rho * (flow_body[0] ** 2 + flow_body[1] ** 2)
    cx, cy, cn = _shape(psi)
    force = np.array([q * AT * cx, q * AL * cy, 0.0])
    moment = np.array([0.0, 0.0, q * AL * LENGTH * cn]) + np.cross(POINT, force)
    return np.concatenate([rot @ force, rot @ moment])


def test_a_closed_form_coefficient_table_gives_the_closed_form_load():
    """A table sampled every degree from C_X = -a cos psi, C_Y = -b sin psi, C_N = c sin 2psi
    gives the closed form at any relative angle (to the linear interpolation's 4e-5), the
    symmetric half-table the same; a ship held still in a current gets that load, one drifting
    with the current none."""
    rng = np.random.default_rng(5)
    for symmetric in (False, True):
        for _ in range(6):
            towards, speed, yaw = rng.uniform(-math.pi, math.pi), rng.uniform(0.3, 2.0), \
                rng.uniform(-math.pi, math.pi)  # fmt: skip
            current = speed * np.array([math.cos(towards), math.sin(towards), 0.0])
            env = {"current": {"velocity": speed, "direction_deg": math.degrees(towards)}}
            case = _case([_coefficient_model("current", symmetric=symmetric)], env=env)
            rot = _rotation((0.0, 0.0, yaw))
            load = _loads(case, angles=(0.0, 0.0, yaw))
            expected = _expected(rot.T @ current, RHO, rot)
            scale = 0.5 * RHO * speed**2 * AL * LENGTH
            assert load == pytest.approx(expected, abs=4e-5 * scale)
            drifting = _loads(case, velocity=current, angles=(0.0, 0.0, yaw))
            assert np.abs(drifting).max() < 1e-9 * scale


def test_the_current_load_is_on_the_velocity_relative_to_the_current_at_the_point():
    """A ship moving and turning in a sheared current: the flow relative to the point is the
    current at the point's elevation less the point's velocity."""
    env = {"current": {"profile": [[-20.0, 0.2], [0.0, 1.2]], "direction_deg": 30.0}}
    case = _case([_coefficient_model("current")], env=env, position=[0.0, 0.0, -6.0])
    yaw, velocity, omega = 0.4, np.array([1.5, -0.3, 0.0]), np.array([0.0, 0.0, 0.02])
    rot = _rotation((0.0, 0.0, yaw))
    arm = rot @ POINT
    c = (0.2 + (1.2 - 0.2) * (20.0 - 6.0) / 20.0) * np.array(
        [math.cos(math.radians(30)), math.sin(math.radians(30)), 0]
    )
    flow = rot.T @ (c - velocity - np.cross(omega, arm))
    load = _loads(case, velocity, omega, (0.0, 0.0, yaw))
    assert load == pytest.approx(_expected(flow, RHO, rot), rel=1e-4, abs=1e-4 * np.abs(load).max())


def test_wind_load_grows_as_the_square_of_the_wind_speed():
    """The wind load at air density from environment.wind: the closed form at 5, 10 and 20 m/s
    (proportional to V^2), the wind blowing towards its direction_deg (here it comes from
    astern of a ship heading the same way: C_X(180 deg) pushes it ahead)."""
    loads = []
    for speed in (5.0, 10.0, 20.0):
        env = {"wind": {"speed": speed, "direction_deg": 20.0}}
        case = _case([_coefficient_model("wind")], env=env)
        rot = _rotation((0.0, 0.0, math.radians(20.0)))
        load = _loads(case, angles=(0.0, 0.0, math.radians(20.0)))
        flow = rot.T @ (speed * np.array([math.cos(math.radians(20)),
                                          math.sin(math.radians(20)), 0.0]))  # fmt: skip
        assert load == pytest.approx(_expected(flow, 1.225, rot), rel=1e-6, abs=1e-6)
        assert rot.T @ load[:3] @ [1, 0, 0] > 0.0  # pushed ahead
        loads.append(load)
    assert loads[1] == pytest.approx(4.0 * loads[0], rel=1e-12)
    assert loads[2] == pytest.approx(16.0 * loads[0], rel=1e-12)


def test_coefficients_from_a_csv_file_and_bad_input(tmp_path):
    """A CSV table (with a header) gives the inline table's load; a wind model without
    environment.wind and a table over 360 deg are refused with the field named."""
    spec = _coefficient_model("current", step=10.0)
    rows = spec["coefficients"]
    text = "psi_deg,cx,cy,cn\n" + "\n".join(",".join(f"{v!r}" for v in r) for r in rows)
    (tmp_path / "current.csv").write_text(text)
    env = {"current": {"velocity": 1.0, "direction_deg": 50.0}}
    inline = _loads(_case([spec], env=env))
    from_file = _case([spec | {"coefficients": "current.csv"}], env=env)
    built = model.build(from_file, base_dir=tmp_path)
    p, y = built.params, built.y0.copy()
    w = kernel.make_work(p)
    kernel.rhs(0.0, y, p, w, np.zeros_like(y))
    assert w.load[0] == pytest.approx(inline, rel=1e-12)
    with pytest.raises(CaseError, match="environment.wind"):
        model.build(_case([_coefficient_model("wind")]))
    with pytest.raises(CaseError, match="span less than 360"):
        model.build(_case([spec | {"coefficients": [*rows, [180.0, 0, 0, 0]]}], env=env))


def test_bad_thruster_and_rudder_input_is_refused_with_the_field_named():
    """Both or neither of thrust and controller, a direction of no length, an unknown point,
    neither angle nor autopilot, and a rudder on a point body are refused."""
    for bad, match in (
        ({"model": "thruster", "thrust": 1.0,
          "controller": {"kind": "surge_speed", "target": 1.0, "gain": 1.0}}, "exactly one"),
        ({"model": "thruster"}, "exactly one"),
        ({"model": "thruster", "thrust": 1.0, "direction": [0, 0, 0]}, "no length"),
        ({"model": "rudder", "area": 1.0, "lift_slope": 3.0}, "exactly one"),
    ):  # fmt: skip
        with pytest.raises(CaseError, match=match):
            _case([bad])
    with pytest.raises(CaseError, match="has no point 'bow'"):
        model.build(_case([{"model": "thruster", "thrust": 1.0, "point": "bow"}]))
    point_body = seacable.load_case({
        "bodies": [{"name": "buoy", "type": "point", "position": [0, 0, -5], "mass": 1.0,
                    "external forces": [_rudder()]}],
        "start": "as_given", "simulation": {"duration": 1.0, "output_interval": 1.0},
    })  # fmt: skip
    with pytest.raises(CaseError, match="'rigid' body"):
        model.build(point_body)
