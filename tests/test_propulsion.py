"""A ship's propeller from its open-water curves and its roll-stabilising fins
(forces.propeller, forces.bseries, forces.fin, forces.foil), each against a hand computation
or a closed form: the B-series' polynomials against an independent transcription and the
series' charts; thrust and shaft torque for any pose and motion, on the speed through the water
at the propeller; the speed a constant rate of turn reaches against the hull's resistance
(solved here with brentq from the same curves) and the speed controller's rate of turn; a fin
pair's roll moment as lift times arm; a fin at any span against the foil's law written here;
roll decays at speed without fins, with fins held and with the roll controller, against their
linearised damping ratios."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq
from tests.test_vessel_control import RHO, _loads, _rotation

import seacable
from seacable.case.units import unit_warnings
from seacable.errors import CaseError
from seacable.forces import bseries
from seacable.system import model

# (J, P/D, A_E/A_0, Z, K_T, K_Q) summed from a second transcription of Oosterveld and van
# Oossanen's (1975) tables, independent of forces.bseries' (which follows Bernitsas, Ray and
# Kinley's 1981 report): a single coefficient or power copied wrong moves these points
INDEPENDENT = [
    (0.0, 1.0, 0.7, 4, 0.45473931040000004, 0.06753840263999998),
    (0.37, 0.63, 0.42, 3, 0.13357008635636786, 0.01496562071019357),
    (0.81, 1.17, 0.88, 5, 0.223511754336784, 0.043898141031122224),
    (0.55, 0.74, 1.02, 6, 0.12047446963771985, 0.019320814394687122),
    (1.05, 1.36, 0.31, 2, 0.14093713423430138, 0.029645291081373544),
    (0.2, 0.52, 0.57, 7, 0.17442144723714445, 0.018419669170442916),
]
B4_70 = {"kind": "b_series", "pitch_ratio": 1.0, "area_ratio": 0.7, "blades": 4}
PROPELLER_AT = np.array([-45.0, 2.0, -4.0])
DIAMETER, RPM, WAKE, DEDUCTION = 4.0, 120.0, 0.2, 0.15
Q11 = 2.0e4  # the hull's resistance Q11 u|u| [N s^2/m^2]
SURGE = {"dofs": ["surge"], "added_mass": [1.0e5, 0, 0, 0, 0, 0]}
RESISTANCE = {"model": "quadratic_damping", "diagonal": [Q11, 0, 0, 0, 0, 0]}


def _ship(forces, duration=1.0, interval=1.0, env=None, **body):
    spec = {"name": "ship", "type": "rigid", "position": [0, 0, 0], "mass": 2.0e6,
            "inertia": [7.2e7, 1e9, 1.2e9], "external forces": forces} | body  # fmt: skip
    return seacable.load_case({
        "environment": env or {}, "bodies": [spec], "start": "as_given",
        "simulation": {"duration": duration, "output_interval": interval,
                       "integrator": "dopri5", "rtol": 1e-9},
    })  # fmt: skip


# ---- the B-series' polynomials -------------------------------------------------------------------
def test_the_b_series_polynomials_match_an_independent_transcription():
    """39 terms of K_T and 47 of K_Q, each of a distinct power; their sums and the cubics in J
    they make for one propeller equal a second transcription's at six points across the range
    (to round-off)."""
    assert len(bseries.THRUST) == 39 and len(bseries.TORQUE) == 47
    for terms in (bseries.THRUST, bseries.TORQUE):
        powers = [term[1:] for term in terms]
        assert len(set(powers)) == len(powers) and max(p[0] for p in powers) == 3
    for advance, pitch, area, blades, thrust, torque in INDEPENDENT:
        assert bseries.coefficients(advance, pitch, area, blades) == pytest.approx(
            (thrust, torque), rel=1e-13
        )
        kt, kq = bseries.cubics(pitch, area, blades)
        assert np.polyval(kt[::-1], advance) == pytest.approx(thrust, rel=1e-12)
        assert np.polyval(kq[::-1], advance) == pytest.approx(torque, rel=1e-12)


def test_the_b_series_reads_as_its_charts():
    """A B5-90 of P/D 1.0 at J = 0.83 gives the chart's K_T 0.12 and K_Q 0.023 (within a
    reading); over the series (Z 3 to 6, A_E/A_0 0.4 to 1.0, P/D 0.5 to 1.4), K_T falls with J
    from the bollard pull to zero at J = 0.95 to 1.2 P/D, K_Q stays positive, and the
    open-water efficiency peaks at 0.3 to 0.8 at 0.6 to 0.9 of that J, higher with the pitch."""
    thrust, torque = bseries.coefficients(0.83, 1.0, 0.9, 5)
    assert thrust == pytest.approx(0.12, abs=0.005) and torque == pytest.approx(0.023, abs=0.001)
    for blades in (3, 4, 5, 6):
        for area in (0.4, 0.7, 1.0):
            best = []
            for pitch in (0.5, 0.8, 1.0, 1.2, 1.4):
                kt, kq = bseries.cubics(pitch, area, blades)
                zero = bseries.zero_thrust(kt)
                assert 0.95 < zero / pitch < 1.2
                advance = np.linspace(0.0, zero, 400)
                kts, kqs = np.polyval(kt[::-1], advance), np.polyval(kq[::-1], advance)
                assert np.all(np.diff(kts) < 0.0) and np.all(kqs > 0.0)
                eta = bseries.efficiency(advance, kts, kqs)
                assert 0.3 < eta.max() < 0.8 and 0.6 < advance[eta.argmax()] / zero < 0.9
                best.append(eta.max())
            assert np.all(np.diff(best) > 0.0)


# ---- thrust and torque ---------------------------------------------------------------------------
def _propeller(**extra):
    return {"model": "propeller", "point": PROPELLER_AT.tolist(), "diameter": DIAMETER,
            "rpm": RPM, "open_water": B4_70, "wake_fraction": WAKE,
            "thrust_deduction": DEDUCTION} | extra  # fmt: skip


def test_thrust_and_torque_of_constant_curves_for_any_pose_and_motion():
    """Constant K_T and K_Q: the thrust (1 - t) rho n^2 D^4 K_T along R d at the propeller
    (moment r_P x F) and the shaft's torque rho n^2 D^5 K_Q / eta_R about R d, against the
    propeller's rotation: -Q d right-handed (a negative roll going ahead: heeling to port),
    +Q d left-handed; for random poses, motions and times."""
    rng = np.random.default_rng(11)
    table = {"kind": "table", "coefficients": [[0.0, 0.3, 0.04], [2.0, 0.3, 0.04]]}
    direction = np.array([0.9, 0.1, -0.1])
    unit = direction / np.linalg.norm(direction)
    n = RPM / 60.0
    thrust = (1 - DEDUCTION) * RHO * n**2 * DIAMETER**4 * 0.3
    torque = RHO * n**2 * DIAMETER**5 * 0.04 / 0.98
    for rotation, sign in (("right", -1.0), ("left", 1.0)):
        spec = _propeller(open_water=table, direction=direction.tolist(), rotation=rotation,
                          relative_rotative_efficiency=0.98)  # fmt: skip
        case = _ship([spec])
        for _ in range(4):
            angles = rng.uniform(-0.6, 0.6, 3)
            velocity, omega = rng.uniform(0.0, 4.0, 3), rng.uniform(-0.05, 0.05, 3)
            rot = _rotation(angles)
            load = _loads(case, velocity, omega, angles, t=rng.uniform(0, 10))
            force = rot @ (thrust * unit)
            assert load[:3] == pytest.approx(force, rel=1e-12)
            moment = np.cross(rot @ PROPELLER_AT, force) + sign * torque * (rot @ unit)
            assert load[3:] == pytest.approx(moment, rel=1e-11, abs=1e-6)
    level = _loads(_ship([_propeller(open_water=table)]), velocity=(5.0, 0.0, 0.0))
    assert level[3] == pytest.approx(-torque * 0.98, rel=1e-12)  # right-handed: heel to port


def test_the_advance_ratio_is_on_the_speed_through_the_water_at_the_propeller():
    """Linear curves K_T = 0.5 - 0.4 J, K_Q = 0.06 - 0.03 J: with a sheared current and a
    turning, moving ship, J = (1 - w) u_a / (n D), u_a the propeller's velocity through the
    water at its depth along its shaft; going astern (J < 0) the J = 0 row holds (the bollard
    pull), beyond the last row the last."""
    rows = [[0.0, 0.5, 0.06], [1.25, 0.0, 0.0225]]
    env = {"current": {"profile": [[-20.0, 0.2], [0.0, 1.2]], "direction_deg": 30.0}}
    case = _ship([_propeller(open_water={"kind": "table", "coefficients": rows})], env=env,
                 position=[0.0, 0.0, -2.0])  # fmt: skip
    current = (0.2 + 1.0 * (20.0 - 6.0) / 20.0) * np.array(
        [math.cos(math.radians(30)), math.sin(math.radians(30)), 0.0]
    )  # at z = -6 m
    n = RPM / 60.0
    for speed, expected_advance in ((4.0, None), (-3.0, 0.0), (40.0, 1.25)):
        yaw, omega = 0.3, np.array([0.0, 0.0, 0.02])
        rot = _rotation((0.0, 0.0, yaw))
        velocity = rot @ [speed, 0.5, 0.0]
        load = _loads(case, velocity, omega, (0.0, 0.0, yaw))
        through = rot.T @ (velocity + np.cross(omega, rot @ PROPELLER_AT) - current)
        advance = (1 - WAKE) * through[0] / (n * DIAMETER)
        if expected_advance is not None:
            assert (advance < 0.0) if speed < 0 else (advance > 1.25)
            advance = expected_advance
        thrust = (1 - DEDUCTION) * RHO * n**2 * DIAMETER**4 * (0.5 - 0.4 * advance)
        torque = RHO * n**2 * DIAMETER**5 * (0.06 - 0.03 * advance)
        assert (rot.T @ load[:3]) @ [1, 0, 0] == pytest.approx(thrust, rel=1e-11, abs=1e-6)
        moment = rot.T @ (load[3:] - np.cross(rot @ PROPELLER_AT, load[:3]))
        assert moment == pytest.approx([-torque, 0.0, 0.0], rel=1e-11, abs=1e-5)


def test_a_stopped_propeller_gives_nothing_and_reversing_is_refused():
    """rpm 0: J is undefined, and there is neither thrust nor torque; a rate of turn that
    goes below 0 during the run is refused with its value and time."""
    assert not np.any(_loads(_ship([_propeller(rpm=0.0)]), velocity=(3.0, 0.0, 0.0)))
    backwards = {"kind": "sine", "amplitude": 150.0, "period": 40.0, "offset": 100.0}
    with pytest.raises(CaseError, match=r"rpm: -50 rpm at t = 30 s; the propeller turns ahead"):
        model.build(_ship([_propeller(rpm=backwards)], duration=60.0))


def _steady_speed(rpm, curves=(1.0, 0.7, 4)):
    """The speed where the B-series propeller's thrust meets the resistance Q11 u^2."""
    n = rpm / 60.0

    def excess(speed):
        advance = (1 - WAKE) * speed / (n * DIAMETER)
        thrust = bseries.coefficients(advance, *curves)[0]
        return (1 - DEDUCTION) * RHO * n**2 * DIAMETER**4 * thrust - Q11 * speed**2

    return brentq(excess, 0.1, 15.0, xtol=1e-14)


def test_a_constant_rate_of_turn_reaches_the_speed_where_thrust_meets_resistance():
    """A B4-70 at 120 rpm from rest against the hull's resistance Q11 u|u| settles at the speed
    brentq finds from the same polynomials (3.4 m/s)."""
    results = seacable.simulate(_ship([_propeller(), RESISTANCE], duration=600.0, **SURGE))
    speed = results["bodies/ship"]["velocity_x"].values
    expected = _steady_speed(RPM)
    assert 3.0 < expected < 4.0
    assert speed[-1] == pytest.approx(expected, rel=1e-8)
    assert np.all(np.diff(speed) > -1e-9)  # gathering way, without overshoot


@pytest.mark.slow  # the thruster's controller law, shared (forces.speed_control); test-all
@pytest.mark.parametrize("law", ["integral", "saturated"])
def test_the_speed_controller_sets_the_rate_of_turn(law):
    """n = n_ff + K (U - u) + K_i I [rpm]: with the integral the ship settles on U = 3 m/s with
    K_i I the rate whose thrust meets the resistance there (brentq); limited to 90 rpm below
    it, the ship settles at the speed of a constant 90 rpm and the integral is held at 0
    throughout (without the hold it would grow without end)."""
    controller = {"kind": "surge_speed", "target": 3.0, "gain": 40.0, "integral_gain": 2.0}
    extra = {}
    if law == "saturated":  # n >= 100 rpm until the ship makes 3 m/s: held at 90 throughout
        extra = {"max_rpm": 90.0}
        controller["feedforward"] = 100.0
    case = _ship([_propeller(rpm=None, controller=controller, **extra), RESISTANCE],
                 duration=900.0, **SURGE)  # fmt: skip
    results = seacable.simulate(case)
    speed = results["bodies/ship"]["velocity_x"].values
    integral = results["bodies/ship"]["propeller_speed_integral"].values
    if law == "integral":
        rpm = brentq(lambda r: _steady_speed(r) - 3.0, 30.0, 300.0, xtol=1e-12)
        assert speed[-1] == pytest.approx(3.0, rel=1e-7)
        assert integral[-1] == pytest.approx(rpm / 2.0, rel=1e-6)
    else:
        assert speed[-1] == pytest.approx(_steady_speed(90.0), rel=1e-7)
        assert not np.any(integral)


# ---- fins ----------------------------------------------------------------------------------------
FIN_AREA, FIN_SLOPE, FIN_ARM, FIN_DEPTH = 6.0, 3.0, 7.0, -4.0


def _fins(**extra):
    """A pair of fins at x = -10 m, y = +-7 m, z = -4 m, spans outwards."""
    base = {"model": "fin", "area": FIN_AREA, "lift_slope": FIN_SLOPE, "stall_angle_deg": 25.0}
    return [base | {"point": [-10.0, side * FIN_ARM, FIN_DEPTH],
                    "span_direction": [0.0, side, 0.0]} | extra
            for side in (-1.0, 1.0)]  # fmt: skip


def test_a_fin_pair_rolls_the_ship_by_lift_times_arm():
    """A pair at 8 deg, going ahead at 5 m/s (a yawed ship): each fin lifts L = q A a delta,
    the starboard one up and the port one down, a roll moment -2 b L (heeling to port); their
    drags q A (C_D0 + C_L^2 / (pi Lambda)) pull aft and pitch the ship by their depth."""
    speed, delta, yaw = 5.0, math.radians(8.0), 0.4
    case = _ship(_fins(angle_deg=8.0, drag_coefficient=0.01, aspect_ratio=2.0))
    rot = _rotation((0.0, 0.0, yaw))
    load = _loads(case, rot @ [speed, 0.0, 0.0], angles=(0.0, 0.0, yaw))
    q_area = 0.5 * RHO * speed**2 * FIN_AREA
    lift = q_area * FIN_SLOPE * delta
    drag = q_area * (0.01 + (FIN_SLOPE * delta) ** 2 / (math.pi * 2.0))
    body = np.concatenate([rot.T @ load[:3], rot.T @ load[3:]])
    expected = [-2 * drag, 0.0, 0.0, -2 * FIN_ARM * lift, 2 * FIN_DEPTH * -drag, 0.0]
    assert body == pytest.approx(expected, rel=1e-12, abs=1e-6)


def _foil_force(s, span, delta, lift_slope=3.0, stall_deg=35.0, drag=0.02):
    """The foil's law, written here: lift along a x s_p and drag against s_p, s_p the inflow
    normal to the span, alpha from the inflow to the chord (body x made normal to the span,
    turned by delta about it), folded into [-90, 90] deg."""
    span = np.asarray(span, float) / np.linalg.norm(span)
    plane = s - (s @ span) * span
    chord0 = np.array([1.0, 0.0, 0.0]) - span[0] * span
    chord0 /= np.linalg.norm(chord0)
    chord = math.cos(delta) * chord0 + math.sin(delta) * np.cross(span, chord0)
    alpha = math.atan2(np.cross(plane, chord) @ span, chord @ plane)
    alpha -= math.pi * round(alpha / math.pi)
    stall = math.radians(stall_deg)
    cl = lift_slope * max(-stall, min(stall, alpha))
    speed = np.linalg.norm(plane)
    return 0.5 * RHO * speed * 4.0 * (cl * np.cross(span, plane) - drag * plane)


@pytest.mark.slow  # the foil law at any span; the fin pair's closed form stays
def test_a_fin_at_any_span_lifts_normal_to_its_inflow_and_a_rudder_is_one():
    """A fin slanted 45 deg down to starboard, moving and turning through a current: its force
    is the foil's law written here on its velocity through the water in the plane normal to
    its span, its moment r_P x F; a fin hanging down (span -z) at the rudder's angle gives the
    rudder's force."""
    rng = np.random.default_rng(4)
    env = {"current": {"velocity": 0.7, "direction_deg": -50.0}}
    current = 0.7 * np.array([math.cos(math.radians(-50)), math.sin(math.radians(-50)), 0.0])
    point = np.array([-30.0, -6.0, -5.0])
    foil = {"point": point.tolist(), "area": 4.0, "lift_slope": 3.0, "drag_coefficient": 0.02}
    slanted = _ship([foil | {"model": "fin", "span_direction": [0, -1, -1], "angle_deg": 12.0}],
                    env=env)  # fmt: skip
    fin = _ship([foil | {"model": "fin", "span_direction": [0, 0, -1], "angle_deg": 12.0}],
                env=env)  # fmt: skip
    rudder = _ship([foil | {"model": "rudder", "angle_deg": 12.0}], env=env)
    for _ in range(6):
        angles = rng.uniform(-0.3, 0.3, 3)
        velocity, omega = rng.uniform(-3.0, 3.0, 3), rng.uniform(-0.05, 0.05, 3)
        rot = _rotation(angles)
        load = _loads(slanted, velocity, omega, angles)
        inflow = rot.T @ (velocity + np.cross(omega, rot @ point) - current)
        force = rot @ _foil_force(inflow, [0, -1, -1], math.radians(12.0))
        assert load[:3] == pytest.approx(force, rel=1e-10, abs=1e-6)
        assert load[3:] == pytest.approx(np.cross(rot @ point, force), rel=1e-10, abs=1e-5)
        assert _loads(fin, velocity, omega, angles) == pytest.approx(
            _loads(rudder, velocity, omega, angles), rel=1e-12, abs=1e-6
        )


ROLL_INERTIA, ROLL_STIFFNESS, ROLL_DAMPING = 8.64e7, 1.96e7, 1.65e6  # [kg m^2, N m/rad, N m s]
SPEED = 6.0  # [m/s] the ship's speed through the water (a current astern of a ship held)


def _roll_decay(fins):
    """A ship free in roll only, from 3 deg, going ahead at 6 m/s through the water (a current
    running aft past it), with ``fins``: the damping ratio of its decay, from the ratio of
    successive maxima (the start, then peaks refined by parabolas) over three periods."""
    case = _ship([{"model": "linear_stiffness", "diagonal": [0, 0, 0, ROLL_STIFFNESS, 0, 0],
                   "equilibrium_orientation_deg": [0, 0, 0]},
                  {"model": "linear_damping", "diagonal": [0, 0, 0, ROLL_DAMPING, 0, 0]},
                  *fins], duration=55.0, interval=0.05,
                 env={"current": {"velocity": SPEED, "direction_deg": 180.0}},
                 dofs=["roll"], orientation_deg=[3.0, 0.0, 0.0],
                 inertia=[0.8 * ROLL_INERTIA, 1e9, 1.2e9],
                 added_mass=[0, 0, 0, 0.2 * ROLL_INERTIA, 0, 0])  # fmt: skip
    roll = seacable.simulate(case)["bodies/ship"]["roll"].values
    peaks = [roll[0]]  # at rest: a maximum of the decay, as the later ones
    for k in np.flatnonzero((roll[1:-1] > roll[:-2]) & (roll[1:-1] >= roll[2:])) + 1:
        a, b, c = roll[k - 1 : k + 2]
        peaks.append(b + (a - c) ** 2 / (8.0 * (2.0 * b - a - c)))
    decrement = np.log(np.array(peaks[:3]) / np.array(peaks[1:4]))
    return decrement / np.sqrt(4.0 * math.pi**2 + decrement**2)


def test_a_roll_decay_at_speed_damps_faster_with_the_roll_controller():
    """The damping ratio of a roll decay at 6 m/s: hull alone 0.020; fins held at 0 add the
    lift of their heave velocity 2 b q A a b / U (0.086); the roll controller (K_p 0.5, K_d
    2 s) adds 2 b q A a K_d and stiffens the roll by 2 b q A a K_p (0.19); each measured from
    the decay within 0.2 % of its linearised value."""
    gain = 2 * FIN_ARM * 0.5 * RHO * SPEED**2 * FIN_AREA * FIN_SLOPE  # the pair's dM/d alpha
    held = _fins(angle_deg=0.0)
    controlled = _fins(roll_controller={"gain": 0.5, "rate_gain": 2.0})
    found = []
    for fins, damping, stiffness in (
        ([], ROLL_DAMPING, ROLL_STIFFNESS),
        (held, ROLL_DAMPING + gain * FIN_ARM / SPEED, ROLL_STIFFNESS),
        (controlled, ROLL_DAMPING + gain * (2.0 + FIN_ARM / SPEED), ROLL_STIFFNESS + 0.5 * gain),
    ):
        ratios = _roll_decay(fins)
        expected = damping / (2.0 * math.sqrt(stiffness * ROLL_INERTIA))
        assert ratios == pytest.approx(np.full(3, expected), rel=2e-3)
        found.append(ratios.mean())
    assert found[0] < found[1] < found[2]
    assert found[2] > 2.0 * found[1]


@pytest.mark.slow  # the rudder's steering gear law, shared (forces.foil); test-all
def test_the_fin_actuator_turns_at_its_rate():
    """A 10 deg command through an actuator of 4 deg/s and 0.1 s: the fin turns at 4 deg/s from
    0 until it is rate T from the command, then closes in as its lag (the rudder's gear);
    the output ``fin_angle`` in degrees, one for each fin of the pair."""
    gear = {"max_rate_deg_s": 4.0, "time_constant": 0.1}
    results = seacable.simulate(_ship(_fins(angle_deg=10.0, actuator=gear), duration=5.0,
                                      interval=0.25, dofs=["surge"]))  # fmt: skip
    time = results["time"].values
    t1 = (10.0 - 0.4) / 4.0
    expected = np.where(time < t1, 4.0 * time,
                        10.0 - 0.4 * np.exp(-np.maximum(time - t1, 0.0) / 0.1))  # fmt: skip
    ship = results["bodies/ship"]
    for name in ("fin_angle", "fin_angle_2"):
        assert ship[name].values == pytest.approx(expected, abs=1e-5)


# ---- bad input -----------------------------------------------------------------------------------
def test_bad_propeller_and_fin_input_is_refused_with_the_field_named():
    """Each refusal names the field and the value and says what is allowed."""
    for bad, match in (
        (_propeller(wake_fraction=1.2), r"wake_fraction: Input should be less than 1 \(got 1.2"),
        (_propeller(open_water=B4_70 | {"pitch_ratio": 1.6}),
         r"open_water.pitch_ratio: Input should be less than or equal to 1.4 \(got 1.6"),
        (_propeller(open_water=B4_70 | {"blades": 8}), r"open_water.blades: .* 7 \(got 8"),
        (_propeller(controller={"kind": "surge_speed", "target": 3.0, "gain": 10.0}),
         "exactly one of 'rpm'"),
        (_propeller(open_water={"kind": "table", "coefficients": [[0.5, 0.3, 0.04],
                                                                  [0.2, 0.4, 0.05]]}),
         r"advance ratios \[0.5, 0.2\] must be 2 or more, increasing"),
        (_propeller(rotation="clockwise"), r"rotation: Input should be 'right' or 'left'"),
        (_fins(angle_deg=3.0, span_direction=[1.0, 0.0, 0.0])[0],
         r"span_direction \[1.0, 0.0, 0.0\] .* lies along the body's x axis"),
        (_fins()[0], "exactly one of 'angle_deg'"),
    ):  # fmt: skip
        with pytest.raises(CaseError, match=match):
            _ship([bad])
    centred = _fins(point=[0.0, 0.0, 0.0], roll_controller={"gain": 1.0})[0]
    with pytest.raises(CaseError, match=r"roll_controller: the fin's lift has no roll moment"):
        model.build(_ship([centred]))


def test_a_rate_of_turn_or_a_diameter_in_the_wrong_unit_is_warned_about():
    """2 rpm (meant as rev/s) and a diameter of 4000 m (meant in mm) are each named with
    what they would be; the ship's own values give no warning."""
    said = " ".join(unit_warnings(_ship([_propeller(rpm=2.0, diameter=4000.0)])))
    assert "rpm: 2 rpm is slower than a ship's propeller turns" in said
    assert "(2 rev/s would be 120)" in said and "(4000 mm would be 4)" in said
    assert not unit_warnings(_ship([_propeller()]))


def test_a_table_that_does_not_cover_the_run_is_warned_about(caplog):
    """A table from J = 0.2 to where K_T is still 0.1: both ends named in a warning (the
    values held beyond them); the B-series' curves, which cover it, give none."""
    short = {"kind": "table", "coefficients": [[0.2, 0.4, 0.05], [0.8, 0.1, 0.03]]}
    with caplog.at_level("WARNING", logger="seacable"):
        model.build(_ship([_propeller()]))
        assert not caplog.records
        model.build(_ship([_propeller(open_water=short)]))
    said = " ".join(r.getMessage() for r in caplog.records)
    assert "its first row is at J = 0.2" in said and "K_T = 0.1 > 0" in said
