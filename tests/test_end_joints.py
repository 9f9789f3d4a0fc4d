"""Joints at rigid lines' ends. A spring at a line's held end (``tip_joint_stiffness``: a
star's top joint): a rope of two rigid segments hangs in a V between two fixed points A and B
at one height and swings about the chord AB; the spring at B is unloaded with the V turned by
TURN about the chord. Checked against the small-angle period of that one degree of freedom,
against the same rope run from B (the spring at its first joint), against its energy, and, for
the planar model, against the 3D one in a motion in the plane. A spring between two lines
through the body between them (``continues``): against the one line of the same segments and
joints."""

import math

import numpy as np
import pytest

import seacable
from seacable.errors import CaseError

SEGMENT, HALF_SPAN, MASS, SPRING, G = 2.0, 1.2, 2.0, 30.0, 9.81  # m, m, kg each, N m/rad
TURN = 0.01  # rad: the V's turn about the chord at which the spring is unloaded


def _case(lines: list[dict], segments: int, duration: float) -> dict:
    rope = {"name": "rope", "diameter": 0.01, "mass_per_length": MASS / SEGMENT}
    return {
        "name": "skipping rope", "start": "as_given", "environment": {"in_air": True},
        "bodies": [{"name": "a", "type": "fixed", "position": [-HALF_SPAN, 0.0, 0.0]},
                   {"name": "b", "type": "fixed", "position": [HALF_SPAN, 0.0, 0.0]}],
        "line_types": [rope],
        "lines": [{"name": "rope", "model": "rigid_segments_3d", "initial": "catenary",
                   "sections": [{"type": "rope", "length": segments * SEGMENT,
                                 "segments": segments}]} | line for line in lines],
        "simulation": {"duration": duration, "output_interval": 0.01, "time_step": 0.001},
    }  # fmt: skip


def _unloaded(towards_b: bool) -> list[float]:
    """The last (first) segment's direction, the V turned by TURN about the chord: from the
    V's bottom to B (from B to the bottom)."""
    height = math.sqrt(SEGMENT**2 - HALF_SPAN**2)
    down = np.array([0.0, math.sin(TURN), -math.cos(TURN)]) * height
    e = (np.array([HALF_SPAN, 0.0, 0.0]) - down) / SEGMENT
    return [float(v) for v in (e if towards_b else -e)]


def _v_rope(at_tip: bool = True, spring: float = SPRING, duration: float = 5.0) -> dict:
    if at_tip:  # from A to B, the spring at the held end B
        line = {"from": "a", "to": "b", "tip_joint_stiffness": spring,
                "tip_reference": _unloaded(towards_b=True)}  # fmt: skip
    else:  # from B to A, the spring at the first joint, on B
        line = {"from": "b", "to": "a", "base_reference": _unloaded(towards_b=False)}
    data = _case([line], segments=2, duration=duration)
    if not at_tip:  # the spring at the first joint alone
        data["lines"][0]["sections"] = [
            {"type": "rope", "length": SEGMENT, "segments": 1, "joint_stiffness": spring},
            {"type": "rope", "length": SEGMENT, "segments": 1, "joint_stiffness": 0.0},
        ]
    return data


def _run(data: dict):
    tree = seacable.simulate(seacable.load_case(data)).dataset
    return tree["time"].values, tree["lines/rope"].to_dataset(), tree["total_energy"].values


def _period(time: np.ndarray, signal: np.ndarray) -> float:
    """The mean period between the first and the last upward crossing of the signal's middle
    level [s]."""
    x = signal - 0.5 * (signal.max() + signal.min())
    up = np.flatnonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))
    crossing = time[up] - x[up] * (time[up + 1] - time[up]) / (x[up + 1] - x[up])
    return float((crossing[-1] - crossing[0]) / (len(crossing) - 1))


def test_a_spring_at_the_held_end_sets_the_small_angle_period():
    """The V's turn psi about the chord: each segment, of mass m and at an angle alpha to the
    chord, turns about it with one end on it (I = 2 m h^2 / 3, h the V's depth); gravity gives
    m g h psi^2 / 2 and the spring k (sin(alpha) psi)^2 / 2 (the last segment turns by
    sin(alpha) psi about B): T = 2 pi sqrt(I / (m g h + k sin^2 alpha)) within 1e-4; the
    energy (the spring's counted) constant to 1e-9 of the spring's; 12 % shorter without."""
    time, rope, energy = _run(_v_rope())
    height = math.sqrt(SEGMENT**2 - HALF_SPAN**2)
    sin_alpha = height / SEGMENT
    inertia = 2.0 * MASS * height**2 / 3.0
    expected = 2.0 * math.pi * math.sqrt(inertia / (MASS * G * height + SPRING * sin_alpha**2))
    swing = rope["node_y"].values[:, 1]  # the V's bottom
    assert _period(time, swing) == pytest.approx(expected, rel=1e-4)
    assert np.ptp(swing) > 0.5 * height * TURN  # it swings about the spring's balance
    free = 2.0 * math.pi * math.sqrt(inertia / (MASS * G * height))
    assert expected < 0.9 * free
    assert np.ptp(energy) < 1e-9 * SPRING * TURN**2


def test_the_held_end_spring_moves_as_the_first_joint_spring():
    """The same rope run from B, the spring at its first joint against the same direction in
    B's frame: the V's bottom moves alike within 1e-9 m."""
    _, tip, _ = _run(_v_rope(at_tip=True, duration=2.0))
    _, base, _ = _run(_v_rope(at_tip=False, duration=2.0))
    for c in "xyz":
        np.testing.assert_allclose(tip[f"node_{c}"].values[:, 1], base[f"node_{c}"].values[:, 1],
                                   rtol=0, atol=1e-9)  # fmt: skip
    assert np.ptp(tip["node_y"].values[:, 1]) > 5e-3


def test_a_planar_held_end_spring_moves_as_the_3d_one():
    """Three links hung between A and B, the spring (and a damper) at B unloaded 0.1 rad off
    the links' start in the plane x-z: the planar model's nodes follow the 3D model's within
    1e-9 m."""
    e = np.array(_unloaded(towards_b=True))
    turned = [float(e[0] * math.cos(0.1) - e[2] * math.sin(0.1)), 0.0,
              float(e[0] * math.sin(0.1) + e[2] * math.cos(0.1))]  # fmt: skip
    line = {"from": "a", "to": "b", "tip_joint_stiffness": SPRING, "tip_joint_damping": 0.5,
            "tip_reference": turned}  # fmt: skip
    runs = {}
    for model in ("rigid_segments_3d", "rigid_links"):
        data = _case([line | {"model": model}], segments=3, duration=2.0)
        runs[model] = _run(data)[1]
    for c in "xz":
        planar, solid = (runs[m][f"node_{c}"].values for m in ("rigid_links", "rigid_segments_3d"))
        np.testing.assert_allclose(planar, solid, rtol=0, atol=1e-9)
    assert np.ptp(runs["rigid_links"]["node_x"].values[:, 1]) > 1e-3


def test_a_tip_joint_on_a_carried_body_is_refused():
    data = _v_rope()
    data["bodies"][1] = {"name": "b", "type": "point", "position": [HALF_SPAN, 0.0, 0.0],
                         "mass": 1.0}  # fmt: skip
    with pytest.raises(CaseError, match=r"rope\)\.tip_joint_stiffness: a joint at the end needs"):
        seacable.simulate(seacable.load_case(data))


def test_a_tip_joint_is_unloaded_at_the_start_by_default():
    """Without ``tip_reference`` the spring is unloaded along the last segment's initial
    direction: the V hanging at rest stays there (its bottom within 1e-12 m)."""
    data = _v_rope(duration=1.0)
    del data["lines"][0]["tip_reference"]
    _, rope, _ = _run(data)
    for c in "xyz":
        assert np.ptp(rope[f"node_{c}"].values[:, 1]) < 1e-12


def test_a_tip_damper_dissipates_c_times_the_relative_rate_squared():
    """With a damper c at B, the energy the V loses is the integral of c |omega|^2, omega the
    last segment's angular velocity (B is fixed; trapezoidal rule on the outputs, 1e-3)."""
    damper = 2.0
    data = _v_rope(duration=3.0)
    data["lines"][0]["tip_joint_damping"] = damper
    time, rope, energy = _run(data)
    rate = rope["angular_rate"].values[:, -1]  # |de/dt| of the last segment [rad/s]
    power = damper * rate**2
    dissipated = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(time))])
    lost = energy[0] - energy
    assert lost[-1] > 0.5 * SPRING * TURN**2 * 0.1  # it does damp
    np.testing.assert_allclose(lost, dissipated, rtol=0, atol=1e-3 * lost[-1])


def _chain(model: str, cut: bool, joint: float = 40.0, damping: float = 0.3) -> dict:
    """A chain of four rigid segments (1 m, 2 kg each, a spring and damper at every joint)
    hung from a fixed point, released 0.4 rad from the vertical with a 5 kg end body: one line,
    or (``cut``) two lines of two segments through a massless point body, the second line
    ``continues`` the first."""
    rope = {"name": "rope", "diameter": 0.01, "mass_per_length": 2.0}
    section = {"type": "rope", "length": 2.0, "segments": 2, "joint_stiffness": joint}
    angles = {"angles_deg": [23.0, 23.0, 23.0, 23.0]}
    tip = 4.0 * np.array([math.sin(math.radians(23.0)), 0.0, -math.cos(math.radians(23.0))])
    end = {"name": "end", "type": "point", "position": [float(v) for v in tip], "mass": 5.0,
           "external forces": [{"model": "gravity"}]}  # fmt: skip
    bodies = [{"name": "pin", "type": "fixed", "position": [0.0, 0.0, 0.0]}, end]
    base = {"model": model, "joint_damping": damping}
    if cut:
        middle = [float(v) for v in tip / 2.0]
        knot = {"name": "knot", "type": "point", "position": middle, "mass": 0.0}
        if model == "rigid_links":
            knot["dofs"] = ["surge", "heave"]  # in the plane
        bodies.append(knot)
        half = {"angles_deg": [23.0, 23.0]}
        lines = [base | {"name": "upper", "from": "pin", "to": "knot", "sections": [section],
                         "initial": half},
                 base | {"name": "lower", "from": "knot", "to": "end", "sections": [section],
                         "initial": half, "continues": "upper"}]  # fmt: skip
    else:
        lines = [base | {"name": "upper", "from": "pin", "to": "end", "initial": angles,
                         "sections": [section | {"length": 4.0, "segments": 4}]}]  # fmt: skip
    lines[0]["base_reference"] = [0.0, 0.0, -1.0]
    simulation = {"duration": 2.0, "output_interval": 0.02, "time_step": 0.001}
    return {"name": "chain", "start": "as_given", "environment": {"in_air": True},
            "bodies": bodies, "line_types": [rope], "lines": lines,
            "simulation": simulation}  # fmt: skip


def _nodes(data: dict) -> np.ndarray:
    tree = seacable.simulate(seacable.load_case(data)).dataset
    parts = [tree[f"lines/{line['name']}"] for line in data["lines"]]
    xyz = [np.concatenate([p[f"node_{c}"].values[:, (1 if k else 0):] for k, p in enumerate(parts)],
                          axis=1) for c in "xz"]  # fmt: skip
    return np.stack(xyz), tree["total_energy"].values


@pytest.mark.parametrize("model", ["rigid_segments_3d", "rigid_links"])
def test_a_line_that_continues_another_moves_as_one_line(model):
    """Two lines joined through a massless body, the joint there a spring and damper between
    them (``continues``), swing as the one line of the same four segments and joints (nodes
    within 1e-9 m over 2 s); without the joint's spring they do not."""
    whole, _ = _nodes(_chain(model, cut=False))
    joined, _ = _nodes(_chain(model, cut=True))
    np.testing.assert_allclose(joined, whole, rtol=0, atol=1e-9)
    loose = _chain(model, cut=True)
    del loose["lines"][1]["continues"]  # the spring against the vertical instead
    assert np.abs(_nodes(loose)[0] - whole).max() > 1e-3


def test_a_joint_between_lines_keeps_the_energy():
    """Without dampers the joined chain's energy (the joint's spring counted) is constant
    (1e-9 of its swing's)."""
    _, energy = _nodes(_chain("rigid_segments_3d", cut=True, damping=0.0))
    assert np.ptp(energy) < 1e-9 * 5.0 * 9.81 * 4.0


@pytest.mark.parametrize(
    ("change", "message"),
    [({"continues": "nothing"}, r"lines\[1\] \(lower\)\.continues: no rigid line 'nothing'"),
     ({"continues": "lower"}, r"lines\[1\] \(lower\)\.continues: line 'lower' does not carry"),
     ({"base_reference": [0, 0, -1]}, r"\(lower\)\.base_reference: a line that continues")],
)  # fmt: skip
def test_a_line_continues_only_the_line_that_carries_its_start(change, message):
    data = _chain("rigid_segments_3d", cut=True)
    data["lines"][1] |= change
    with pytest.raises(CaseError, match=message):
        seacable.simulate(seacable.load_case(data))
