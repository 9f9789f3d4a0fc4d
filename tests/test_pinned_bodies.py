"""Bodies pinned to another body's point (``pinned_to``: a spherical joint solved with the
bodies, system.rigid.solve_groups): a pendulum on a free cart against Lagrange's equations
integrated here, its centre of mass held still, a pendulum pinned to a fixed body against the
same pendulum held in translation, the case's checks, the pin's force returned by a coupling;
MoorDyn's ``Body<ID>Pinned`` rod read from a deck (seacable's statics against the exact
hydrostatics of the arm's wetted part and against MoorDyn holding the body at seacable's pose)
and its ``CoupledPinned`` body (a bar on an accelerated point against its exact swing, run and
stepped through a coupling as MoorDyn's own test steps it, and against MoorDyn)."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import seacable
from helpers import quiet_stdout
from seacable.bodies import kinematics
from seacable.case import moordyn as deck_reader
from seacable.coupling import Coupling
from seacable.errors import CaseError
from test_rod import _submerged

G, MASS, LENGTH, CART = 9.81, 100.0, 4.0, 50.0
ARM = Path(__file__).parent / "data" / "moordyn_v2_spar_arm.txt"


def _case(parent: dict, pendulum: dict | None = None, duration: float = 20.0) -> dict:
    """A uniform bar of MASS and LENGTH hanging from its end (the reference point) at the
    point ``pin`` of ``parent``, let go 10 deg off the vertical, in air."""
    bar = {"name": "bar", "type": "rigid", "position": [0.0, 0.0, 0.0],
           "orientation_deg": [0.0, 10.0, 0.0], "mass": MASS,
           "inertia": [MASS * LENGTH**2 / 12, MASS * LENGTH**2 / 12, 1.0],
           "centre_of_gravity": [0.0, 0.0, -LENGTH / 2], "pinned_to": "top.pin",
           "external forces": [{"model": "gravity"}], **(pendulum or {})}  # fmt: skip
    return {"environment": {"gravity": G, "water_depth": 1000.0}, "bodies": [parent, bar],
            "lines": [], "start": "as_given",
            "simulation": {"duration": duration, "output_interval": 0.01}}  # fmt: skip


def _cart() -> dict:
    return {
        "name": "top",
        "type": "rigid",
        "position": [0.0, 0.0, 0.0],
        "mass": CART,
        "inertia": [1.0, 1.0, 1.0],
        "dofs": ["surge"],
        "points": {"pin": [0.0, 0.0, 0.0]},
    }


def _lagrange(duration: float, step: float) -> np.ndarray:
    """The cart's x and the bar's angle of a pendulum on a cart, from Lagrange's equations:
    T = (M + m) X'^2 / 2 - m d cos(th) X' th' + I_A th'^2 / 2, V = -m g d cos(th)."""
    d = LENGTH / 2
    inertia = MASS * LENGTH**2 / 3

    def rates(_, s):
        _, th, v, om = s
        coupling = -MASS * d * math.cos(th)
        a = np.array([[CART + MASS, coupling], [coupling, inertia]])
        b = [-MASS * d * math.sin(th) * om * om, -MASS * G * d * math.sin(th)]
        return [v, om, *np.linalg.solve(a, b)]

    times = np.arange(0.0, duration + step / 2, step)
    out = solve_ivp(rates, (0.0, duration), [0.0, math.radians(10.0), 0.0, 0.0],
                    t_eval=times, rtol=1e-12, atol=1e-12, method="DOP853")  # fmt: skip
    return out.y[:2]


@pytest.mark.parametrize(
    "integrator",
    ["rk4", pytest.param("dopri5", marks=pytest.mark.slow)],  # its own compile
)
def test_a_pendulum_on_a_free_cart_swings_as_lagranges_equations(integrator):
    """The joint's force moves the cart (surge only) as the bar swings: over 20 s (8.5
    periods of 10 deg) the bar's angle within 1e-4 deg of Lagrange's equations integrated
    here (2.2e-6 measured with rk4), the cart within 1e-6 m (5e-8), the pin on the cart
    within 1e-9 m, and the centre of mass of cart and bar still within 1e-8 m (8e-11)."""
    case = _case(_cart())
    case["simulation"]["integrator"] = integrator
    dataset = seacable.simulate(seacable.load_case(case)).dataset
    bar, cart = dataset["bodies/bar"].to_dataset(), dataset["bodies/top"].to_dataset()
    x_cart, angle = _lagrange(20.0, 0.01)
    assert np.abs(bar["pitch"].values - np.degrees(angle)).max() < 1e-4
    assert np.abs(cart["position_x"].values - x_cart).max() < 1e-6
    gap = np.hypot(bar["position_x"].values - cart["position_x"].values,
                   bar["position_z"].values)  # fmt: skip
    assert gap.max() < 1e-9
    x_bar = bar["position_x"].values - LENGTH / 2 * np.sin(np.radians(bar["pitch"].values))
    centre = (CART * cart["position_x"].values + MASS * x_bar) / (CART + MASS)
    assert np.ptp(centre) < 1e-8


def test_a_body_pinned_to_a_fixed_point_swings_as_one_held_in_translation():
    """The same bar pinned to a fixed body's point, and held in translation instead (dofs
    roll, pitch, yaw): the same swing to 1e-9 deg, at the period of a 10 deg compound
    pendulum (its small-angle one times 1 + th^2/16, within 1e-4)."""
    fixed = {"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0],
             "points": {"pin": [0.0, 0.0, 0.0]}}  # fmt: skip
    pinned = seacable.simulate(seacable.load_case(_case(fixed, duration=10.0))).dataset
    held = _case(fixed, {"pinned_to": None, "dofs": ["roll", "pitch", "yaw"]}, duration=10.0)
    held = seacable.simulate(seacable.load_case(held)).dataset
    a, b = (d["bodies/bar"].to_dataset() for d in (pinned, held))
    assert np.abs(a["pitch"].values - b["pitch"].values).max() < 1e-9
    pitch, time = a["pitch"].values, a["time"].values
    down = np.flatnonzero((pitch[:-1] > 0) & (pitch[1:] <= 0))
    crossing = time[down] - pitch[down] * 0.01 / (pitch[down + 1] - pitch[down])
    small = 2 * math.pi * math.sqrt(LENGTH**2 / 3 / (G * LENGTH / 2))
    assert np.diff(crossing).mean() == pytest.approx(small * (1 + math.radians(10) ** 2 / 16),
                                                     rel=1e-4)  # fmt: skip


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"dofs": ["surge", "pitch"]}, "dofs ['surge']: a body pinned to 'top.pin' moves"),
        ({"velocity": [1.0, 0.0, 0.0]}, "starts with that point's velocity"),
        ({"pinned_to": "nowhere"}, "'nowhere' names no other body"),
        ({"pinned_to": "bar"}, "'bar' names no other body"),
        ({"pinned_to": "top.elsewhere"}, "body 'top' has no point 'elsewhere'"),
        ({"position": [0.0, 0.0, -0.5]}, "is 0.5 m from 'top.pin' at the start"),
    ],
)
def test_a_pin_the_case_cannot_hold_is_refused_by_name(change, message):
    case = _case(_cart(), change)
    with pytest.raises(CaseError, match=message.replace("[", r"\[").replace("]", r"\]")):
        seacable.simulate(seacable.load_case(case))


def _pose(dataset, name: str) -> tuple[np.ndarray, np.ndarray, list[float]]:
    """A body's rotation matrix, position and angles [rad] in a statics' results."""
    body = dataset[f"bodies/{name}"].to_dataset().isel(time=0)
    angles = [math.radians(float(body[k])) for k in ("roll", "pitch", "yaw")]
    rot = np.zeros((3, 3))
    kinematics.rotation(*kinematics.euler_quaternion(*angles), rot)
    return rot, np.array([float(body[f"position_{c}"]) for c in "xyz"]), angles


def test_an_arm_pinned_to_a_spar_floats_where_its_wetted_part_balances_it(tmp_path):
    """The spar deck with an arm (20 m, 1 m across, 600 kg/m) pinned to its column 5 m above
    the water (MoorDyn's ``Body1Pinned``) floats at an angle: in seacable's statics the
    moment about the pin of the arm's weight and of the buoyancy of its wetted part (Gauss
    quadrature of the cut cylinder, tests/test_rod.py) balance within 1e-9 of the weight's
    (6e-16 measured); MoorDyn holding the spar at seacable's pose (Coupled; its
    initial-condition solve swings the arm) puts the arm within 0.2 deg of seacable's (0.09:
    its rod hydrostatics, tests/test_moordyn_peer.py) and pulls at the fairleads within 0.5 %
    of seacable (6e-5), the spar's vertical load its weight within 1e-5 of the buoyancy.
    MoorDyn's dynamics of such an arm are not compared: MoorDyn 2.7 hands a body-pinned rod's
    whole moment and 6x6 mass to the body (Rod::getNetForceAndMass), as if it were fixed."""
    md = pytest.importorskip("moordyn")
    case = deck_reader.read(ARM)
    arm = next(b for b in case["bodies"] if b["name"] == "rod3")
    assert arm["pinned_to"] == "body1.rod3_pin"
    dataset = seacable.statics(seacable.load_case(case)).dataset
    rot_arm, pin, _ = _pose(dataset, "rod3")
    rot_spar, position, angles = _pose(dataset, "body1")
    assert np.linalg.norm(pin - (position + rot_spar @ [4.0, 0.0, 5.0])) < 1e-9
    axis = rot_arm @ [12.0, 0.0, -16.0]
    length, radius, mass = 20.0, 0.5, 600.0 * 20.0
    volume, centre = _submerged(pin + axis, -axis / length, length, radius)
    weight_moment = np.cross(axis / 2, [0.0, 0.0, -mass * G])
    buoyancy_moment = np.cross(centre - pin, [0.0, 0.0, 1025.0 * G * volume])
    assert np.linalg.norm(weight_moment + buoyancy_moment) < 1e-9 * np.linalg.norm(weight_moment)

    text = ARM.read_text().replace("1    Free       0.0", "1    Coupled    0.0")
    end_b = np.array([4.0, 0.0, 5.0]) + rot_spar.T @ axis
    deck = tmp_path / ARM.name
    deck.write_text(
        text.replace(
            "4    0     5      16    0    -11 ",
            "4    0     5      " + " ".join(f"{v:.9f}" for v in end_b),
        )
    )
    pose = np.array([*position, *angles])
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, pose, np.zeros(6))
        rod = md.GetRod(system, 3)
        tip = np.array(md.GetRodNodePos(rod, md.GetRodN(rod)))
        load = np.array(md.Step(system, pose, np.zeros(6), 0.0, 0.001))
        theirs = [np.linalg.norm(md.GetPointForce(md.GetPoint(system, k))) for k in (4, 5, 6)]
        md.Close(system)
    theirs_axis = tip - pin
    angle = math.degrees(math.acos(theirs_axis @ axis / np.linalg.norm(theirs_axis) / length))
    assert angle < 0.2, angle
    ours = [np.linalg.norm([float(dataset[f"lines/line{k}"].to_dataset().isel(time=0)[
        f"to_force_{c}"]) for c in "xyz"]) for k in (1, 2, 3)]  # fmt: skip
    assert np.abs(np.array(ours) / theirs - 1).max() < 5e-3, (ours, theirs)
    buoyancy = 1025.0 * G * (math.pi * 16 * (40 - position[2]) + math.pi * 49 * 2)
    assert abs(load[2] - 1.78e6 * G) < 1e-5 * buoyancy, load


def test_a_coupling_returns_the_pins_force_on_its_coupled_body():
    """A coupled body's forces include the joints of the bodies pinned to it: the bar hanging
    at rest below a coupled point pulls it down with its weight (to 1e-9), as a line would;
    a deck's rod pinned to a coupled body is read as such."""
    imposed = {"name": "top", "type": "imposed", "points": {"pin": [0.0, 0.0, 0.0]}}
    case = _case(imposed, {"orientation_deg": [0.0, 0.0, 0.0]})
    case["simulation"].update(integrator="rk4", time_step=0.01)
    coupling = Coupling(case)
    forces = coupling.init(np.zeros(3))
    assert np.abs(forces - [0.0, 0.0, -MASS * G]).max() < 1e-9 * MASS * G, forces
    text = ARM.read_text().replace("1    Free       0.0", "1    Coupled    0.0")
    text = "".join(
        row for row in text.splitlines(True) if "    Body1      0     0    -4" not in row
    )
    arm = next(b for b in deck_reader.read(text)["bodies"] if b["name"] == "rod3")
    assert arm["pinned_to"] == "body1.rod3_pin"


PINNED_BODY = Path(__file__).parent / "data" / "moordyn_v2_coupled_pinned_body.txt"
PUSH = 0.5  # [m/s^2] the coupled point's steady acceleration along y


def _swing(duration: float, step: float) -> tuple[np.ndarray, float]:
    """The exact roll [rad] of the deck's bar (50 t, 10 m, its centre 10 m below the pin)
    at ``step``, 2 ``step``, ... when its pin accelerates at PUSH along y from rest: a compound
    pendulum let go at rest in the gravity tilted by theta = atan(-PUSH / g), swinging between
    0 and 2 theta; and the period of that swing (elliptic integral)."""
    from scipy.special import ellipk

    g = 9.80665
    mass, distance = 5.0e4, 10.0
    inertia = mass * (10.0**2 / 12 + 2.0**2 / 16) + mass * distance**2
    omega2 = mass * math.hypot(g, PUSH) * distance / inertia
    theta = math.atan(-PUSH / g)
    times = np.arange(1, round(duration / step) + 1) * step
    swing = solve_ivp(lambda _, s: [s[1], -omega2 * math.sin(s[0] - theta)], (0.0, duration),
                      [0.0, 0.0], t_eval=times, rtol=1e-12, atol=1e-12)  # fmt: skip
    return swing.y[0], 4.0 * ellipk(math.sin(theta / 2) ** 2) / math.sqrt(omega2)


def test_a_coupled_pinned_body_swings_as_a_pendulum_in_tilted_gravity():
    """MoorDyn's CoupledPinned body (a bar hanging from its coupled point, in a vacuum) read
    as a rigid body pinned to an imposed one, the point pushed at a steady 0.5 m/s^2 (an
    ``acceleration_profile``): the roll swings between 0 and 2 atan(-a / g) within 1e-6 rad
    (1.3e-8 measured) as the exact swing does (within 1e-5 rad), and the joint pulls the
    point with the bar's weight and inertia, m (g - a_G) from the bar's own motion, within
    1e-3 of its weight."""
    case = deck_reader.read(PINNED_BODY)
    bodies = {b["name"]: b for b in case["bodies"]}
    assert bodies["body1"]["pinned_to"] == "body1_pin" and "in_air" in case["environment"]
    bodies["body1_pin"]["y"] = {"kind": "acceleration_profile",
                                "phases": [{"duration": 100.0, "acceleration": PUSH}]}  # fmt: skip
    case["start"] = "as_given"
    case["simulation"].update(duration=20.0, output_interval=0.01, build_up=0.0)
    dataset = seacable.simulate(seacable.load_case(case)).dataset
    bar, pin = dataset["bodies/body1"].to_dataset(), dataset["bodies/body1_pin"].to_dataset()
    roll = np.radians(bar["roll"].values)
    exact, _ = _swing(20.0, 0.01)
    theta = math.atan(-PUSH / 9.80665)
    assert abs(roll.min() - 2 * theta) < 1e-6 and abs(roll.max()) < 1e-6
    assert np.abs(roll[1:] - exact).max() < 1e-5
    centre = np.column_stack([pin["position_y"].values + 10.0 * np.sin(roll),
                              -5.0 - 10.0 * np.cos(roll)])  # fmt: skip
    acceleration = (centre[2:] - 2 * centre[1:-1] + centre[:-2]) / 0.01**2
    pull = np.column_stack([pin[f"line_force_{c}"].values[1:-1] for c in "yz"])
    expected = -5.0e4 * (acceleration + [0.0, 9.80665])
    assert np.abs(pull - expected).max() < 1e-3 * 5.0e4 * 9.80665


def test_a_coupled_pinned_body_steps_as_in_moordyn(tmp_path):
    """The same bar stepped through ``Coupling`` as MoorDyn's own pinned-body test steps it
    (x = a t^2 / 2 and v = a t given at each 0.01 s step's start; three values, the pin's):
    within 1e-4 rad of the exact swing (1.9e-5 measured: the coupling takes the acceleration
    (v - v_last) / dt over each step, as MoorDyn does); MoorDyn's swing, one coupling step
    behind, within 1e-4 rad of seacable's shifted by that step (1.9e-5) and over its whole
    periods its mean within MoorDyn's test's 1e-3 rad of theta."""
    md = pytest.importorskip("moordyn")
    step, duration = 0.01, 20.0
    count = round(duration / step)
    ours, theirs = [], []
    deck = tmp_path / PINNED_BODY.name  # MoorDyn writes its outputs beside the deck
    deck.write_text(PINNED_BODY.read_text())
    coupling = Coupling(deck)
    assert coupling.bodies == ["body1_pin"] and coupling.size == 3
    with quiet_stdout():
        coupling.init(np.array([0.0, 0.0, -5.0]))
        system = md.Create(str(deck))
        md.Init(system, np.array([0.0, 0.0, -5.0, 0.0, 0.0, 0.0]), np.zeros(6))
        body = md.GetBody(system, 1)
        for k in range(count):
            t = k * step
            x = np.array([0.0, 0.5 * PUSH * t * t, -5.0, 0.0, 0.0, 0.0])
            v = np.array([0.0, PUSH * t, 0.0, 0.0, 0.0, 0.0])
            coupling.step(x[:3], v[:3], t, step)
            ours.append(math.radians(coupling.state()["bodies/body1/roll"]))
            md.Step(system, x, v, t, step)
            theirs.append(md.GetBodyState(body)[0][3])
        md.Close(system)
    ours, theirs = np.array(ours), np.array(theirs)
    exact, period = _swing(duration, step)
    assert np.abs(ours - exact).max() < 1e-4
    assert np.abs(theirs[1:] - ours[:-1]).max() < 1e-4
    whole = round(2 * period / step)
    assert abs(theirs[:whole].mean() - math.atan(-PUSH / 9.80665)) < 1e-3
