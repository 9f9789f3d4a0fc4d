"""Statics with lines lying slack on the seabed (longer than their span and rise): the laid
start shape, a platform pushed off by a steady force until its upwind line lies slack, and a
platform whose lines all lie slack at the start, against MoorPy's catenaries at the offset
where they balance the force (surge only in both)."""

from pathlib import Path

import numpy as np
import pytest
import yaml

import seacable
from seacable.system import initial

mp = pytest.importorskip("moorpy")
from scipy.optimize import brentq  # noqa: E402

EXAMPLE = Path(__file__).parents[1] / "examples" / "platform_three_catenary_lines.yaml"
FAIRLEADS = ((20.0, 0.0), (-10.0, 17.3205), (-10.0, -17.3205))


def _platform(radius: float, force: float) -> dict:
    """The example's platform in surge only, anchors at ``radius`` [m], a steady ``force``
    along x [N]."""
    case = yaml.safe_load(EXAMPLE.read_text())
    for k, body in enumerate(case["bodies"][:3]):
        angle = 2 * np.pi * k / 3
        body["position"] = [radius * np.cos(angle), radius * np.sin(angle), -200.0]
    platform = case["bodies"][3]
    platform["dofs"] = ["surge"]
    platform["external forces"][-1]["force_x"] = force
    return case


def _moorpy_offset(radius: float, force: float) -> tuple[float, list[float]]:
    """The surge at which MoorPy's three catenaries pull ``force`` back, and the fairlead
    tensions there."""

    def pull(x):
        ms = mp.System(depth=200.0, rho=1025.0, g=9.81)
        ms.setLineType(name="chain", lineType={"d_vol": 0.137, "m": 126.0, "EA": 5.8e8})
        for k, (fx, fy) in enumerate(FAIRLEADS):
            angle = 2 * np.pi * k / 3
            ms.addPoint(1, [radius * np.cos(angle), radius * np.sin(angle), -200.0])
            ms.addPoint(1, [fx + x, fy, -15.0])
            ms.addLine(700.0, "chain", pointA=2 * k + 1, pointB=2 * k + 2)
        ms.initialize()
        return -sum(line.fB[0] for line in ms.lineList), [line.TB for line in ms.lineList]

    x = brentq(lambda x: pull(x)[0] - force, 20.0, 300.0, xtol=1e-6)
    return x, pull(x)[1]


def _ours(case: dict) -> tuple[float, np.ndarray]:
    ds = seacable.statics(seacable.load_case(case)).dataset
    x = float(ds["bodies/platform"].to_dataset().isel(time=0)["position_x"])
    tensions = []
    for k in (1, 2, 3):
        g = ds[f"lines/line_{k}"].to_dataset().isel(time=0)
        tensions.append(np.linalg.norm([float(g[f"to_force_{c}"]) for c in "xyz"]))
    return x, np.array(tensions)


def _tensions_agree(ours: np.ndarray, theirs: list[float]) -> None:
    """The lines that pull (lines 2 and 3) within 0.3 %; the slack line's fairlead holds the
    weight of the chain hanging straight down, within half a 20 m segment's (the lumped
    chain's last hanging segment reaches the seabed aslant)."""
    assert np.abs(ours[1:] / np.array(theirs[1:]) - 1).max() < 3e-3, (ours, theirs)
    assert abs(ours[0] - theirs[0]) < 0.5 * 20.0 * 1087.9, (ours, theirs)


def test_a_line_longer_than_its_span_and_rise_starts_laid_on_the_seabed():
    """Straight down from the upper end, then a polygon on the seabed whose every segment has
    its unstretched length (none pushed, none pulled)."""
    lengths = np.full(35, 20.0)
    low, high = np.array([480.0, 0.0, -200.0]), np.array([20.0, 0.0, -15.0])
    nodes = initial._laid(lengths, low, high)
    assert np.allclose(nodes[0], low) and np.allclose(nodes[-1], high)
    assert np.allclose(np.linalg.norm(np.diff(nodes, axis=0), axis=1), lengths, rtol=1e-9)
    on_seabed = np.isclose(nodes[:, 2], -200.0)
    assert on_seabed[:26].all() and not on_seabed[27:].any()
    assert np.allclose(nodes[27:, :2], high[:2])  # the hanging part straight down
    assert np.abs(nodes[:, 1]).max() > 50.0  # the rest bulges aside on the seabed


def test_a_laid_line_hangs_stretched_by_the_line_below_and_pushes_no_segment():
    """With its weight in water and EA, a laid line's hanging segments start stretched by the
    weight of the hanging line below each (to 1e-12), and the foot's segment, which takes up
    what the drop leaves, is at least its unstretched length: no segment pushed (the hanging
    part's stretch used to shorten it)."""
    lengths = np.full(40, 10.0)
    w, ea = 1.0e3, 1.0e8  # a stretch of 1e-5 per 1 m of line below
    low, high = np.array([150.0, 0.0, -200.0]), np.array([0.0, 0.0, -15.0])
    nodes = initial._laid(lengths, low, high, w, ea)
    assert np.allclose(nodes[0], low) and np.allclose(nodes[-1], high)
    segments = np.linalg.norm(np.diff(nodes, axis=0), axis=1)
    hanging = np.flatnonzero(nodes[1:, 2] > -200.0 + 1e-9)  # segments whose upper node hangs
    foot = hanging[0]
    assert segments[foot] >= lengths[foot] * (1 - 1e-12)
    upper = hanging[1:]
    below = (upper - foot - 0.5) * 10.0  # hanging line under each segment's middle
    expected = 10.0 * (1.0 + w * (below + 10.0) / ea)  # the foot's segment below too
    assert np.allclose(segments[upper], expected, rtol=1e-12), segments[upper] - expected
    assert np.allclose(segments[:foot], lengths[:foot], rtol=1e-9)  # lying: unstretched


def test_a_line_a_little_short_of_its_span_and_rise_lies_slack_where_its_segments_fit():
    """561.3 m of polyester in 22 segments from an anchor 243.6 m off and 320.9 m below the
    fairlead: 3.2 m short of its span and rise, its catenary has H = 151 N and a touchdown
    bent within 0.5 m, which its 25.5 m segments cut: they lie slack (every lying segment at
    its length, none pushed), as the statics then find it (seed 39, mooring 127, failed
    before). 20 segments of 25.5 m, 10 m short of 240 m and 280 m: they cannot (None)."""
    lengths = np.full(22, 561.3208085 / 22)
    low, high = np.array([0.0, 0.0, -337.436]), np.array([243.599, 0.0, -16.545])
    nodes = initial._laid(lengths, low, high, 297.5, 3.253e8)
    assert nodes is not None
    segments = np.linalg.norm(np.diff(nodes, axis=0), axis=1)
    assert np.all(segments >= lengths * (1 - 1e-12))
    lying = np.isclose(nodes[1:, 2], -337.436) & np.isclose(nodes[:-1, 2], -337.436)
    assert lying.sum() >= 8 and np.allclose(segments[lying], lengths[lying], rtol=1e-9)
    short = np.full(20, 25.5)
    assert initial._laid(short, np.array([0.0, 0.0, -300.0]), np.array([240.0, 0.0, -20.0]),
                         297.5, 3.253e8) is None  # fmt: skip


@pytest.mark.parametrize("length", [200.0, 400.0])
def test_a_line_hanging_between_two_buoys_starts_with_its_middle_on_the_seabed(length):
    """Ends 40 m and 25 m above the seabed, 120 m apart: the free catenary would dip below
    the seabed, so each arm hangs as a catenary tangent to the seabed where it touches down
    (the same horizontal tension: the arms' heights and slopes agree with it) and the middle
    lies on it; a line longer than its span and both heights lies slack in an arc. Every node
    at or above the seabed, every segment at most its length (a chord of the curve), the
    lying ones exactly."""
    lengths = np.full(40, length / 40)
    start, end = np.array([-60.0, 0.0, -60.0]), np.array([60.0, 0.0, -75.0])
    nodes = initial._touching_down(lengths, start, end, 1000.0, -100.0)
    assert np.allclose(nodes[0], start) and np.allclose(nodes[-1], end)
    gaps = np.linalg.norm(np.diff(nodes, axis=0), axis=1)
    assert np.all(gaps <= lengths * (1 + 1e-12)) and np.all(gaps > 0.99 * lengths)
    lying = np.isclose(nodes[:, 2], -100.0)
    assert lying.sum() >= 5 and nodes[:, 2].min() > -100.0 - 1e-9
    both = lying[:-1] & lying[1:]
    assert np.allclose(gaps[both], lengths[both], rtol=1e-9)
    if length > 120.0 + 40.0 + 25.0:
        assert np.abs(nodes[:, 1]).max() > 10.0  # slack: the laid part bulges aside
    else:  # taut: both arms are catenaries z = a (cosh(x / a) - 1) from their feet, one a
        hanging = ~lying
        heights = nodes[hanging, 2] + 100.0
        beyond = np.abs(nodes[hanging, 0] - np.where(nodes[hanging, 0] < 0, start[0], end[0]))

        def offset(a, h, top):  # horizontal distance from the end at height top down to h
            return a * (np.arccosh(1 + top / a) - np.arccosh(1 + h / a))

        tops = np.where(nodes[hanging, 0] < 0, 40.0, 25.0)
        a = brentq(lambda a: offset(a, heights[2], tops[2]) - beyond[2], 1.0, 1e6)
        assert np.abs(offset(a, heights, tops) - beyond).max() < 1e-6 * 120.0
        assert np.abs(nodes[:, 1]).max() < 1e-9


def test_a_platform_pushed_until_its_upwind_line_lies_slack_matches_moorpy():
    """1 MN on the example's platform: its upwind line, 700 m, ends 600 m from its anchor's
    foot at 135 m of offset, lying slack; Newton over the bodies reshapes it at each pose."""
    x, tensions = _ours(_platform(600.0, 1.0e6))
    x_mp, tensions_mp = _moorpy_offset(600.0, 1.0e6)
    assert abs(x - x_mp) < 0.05, (x, x_mp)
    _tensions_agree(tensions, tensions_mp)


def test_a_platform_on_lines_that_all_lie_slack_matches_moorpy():
    """Anchors 480 m out: every 700 m line lies slack at the start, nothing holds the platform
    in surge until it has gone some 100 m; 100 kN pushes it 204 m."""
    x, tensions = _ours(_platform(480.0, 1.0e5))
    x_mp, tensions_mp = _moorpy_offset(480.0, 1.0e5)
    assert abs(x - x_mp) < 0.35, (x, x_mp)  # 0.28 m at 35 segments a line, 0.06 m at 70
    _tensions_agree(tensions, tensions_mp)


BUOY = Path(__file__).parents[1] / "examples" / "buoy_three_lines_clump_weight.yaml"


@pytest.mark.parametrize("segment", [3.0, 2.0])
def test_the_three_line_buoy_at_short_segments(segment):
    """The buoy's statics failed at 3 m and 2 m segments (and converged at 2.5, 4, 5 and 10):
    now found at both, the buoy within 5 cm of where 10 m segments put it."""

    def buoy(length: float) -> np.ndarray:
        case = yaml.safe_load(BUOY.read_text())
        for line in case["lines"]:
            for section in line["sections"]:
                section["segments"] = max(1, round(section["length"] / length))
        ds = seacable.statics(seacable.load_case(case)).dataset["bodies/buoy"].to_dataset()
        return np.array([float(ds[f"position_{c}"].isel(time=0)) for c in "xyz"])

    assert np.abs(buoy(segment) - buoy(10.0)).max() < 0.05


@pytest.mark.parametrize(("radius", "force"), [(600.0, 1.0e6), (480.0, 1.0e5)])
def test_the_bodies_balance_on_the_closed_forms_is_moorpys(radius, force):
    """system.closed_form, the statics' first guess: the platform's balance on its lines'
    closed forms (elastic catenaries with seabed contact, or laid slack) is MoorPy's balance of
    the same continuous catenaries, within 1 mm, from the upright start (135 m and 204 m
    away; the second with every line lying slack there, nothing holding the platform)."""
    from seacable.system import closed_form, model, statics
    from seacable.system.coordinates import coordinates

    built = model.build(seacable.load_case({**_platform(radius, force), "start": "as_given"}))
    p = statics.still_water(built).params
    coords = coordinates(p)
    bodies = np.flatnonzero(coords.kind <= 1)
    limit = statics._step_limit(built, coords, shortest=True)[bodies]
    found = closed_form.pose(p, coords, built.y0, limit)
    assert found is not None
    x = found[int(p.body_q[built.layout.bodies.index("platform")])]
    assert abs(x - _moorpy_offset(radius, force)[0]) < 1e-3, x
