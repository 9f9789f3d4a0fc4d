"""The global search for equilibria (seacable.stability.equilibria): the scanned starts, on the
placement where each tie balances the loads it carries, find every equilibrium that a brute
force of 256 starts finds, and more, where the brute force misses some; with a compensator
on, every equilibrium where it does not saturate."""

import math
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable.stability import equilibria
from seacable.stability.plane import Plane, Weather

EXAMPLE = Path(__file__).parent.parent / "examples" / "tandem_offloading_fpso_shuttle.yaml"


@pytest.fixture(scope="module")
def plane():
    return Plane.of(seacable.load_case(EXAMPLE))


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    d = np.abs(a - b)
    d[2::3] = np.abs((d[2::3] + math.pi) % (2 * math.pi) - math.pi)
    return bool(np.all(d[0::3] < 1e-2) and np.all(d[1::3] < 1e-2) and np.all(d[2::3] < 1e-4))


def test_on_the_balanced_placement_only_the_moments_are_left(plane):
    """Each body placed so that its tie carries what it holds: its force balances to
    round-off at any headings; its moment does not."""
    Weather(0.8, 150.0, 16.0, 330.0).apply(plane.built)
    order = equilibria._tie_order(plane)
    assert [tie is not None for _, tie in order] == [True, True]
    rng = np.random.default_rng(3)
    for _ in range(5):
        x = plane.start()[:6]
        x[2::3] = rng.uniform(-math.pi, math.pi, 2)
        equilibria._balanced(plane, x, order)
        plane.at_rest(x, jacobian=False)
        load = plane.work.load[plane.bodies]
        tension = plane.work.tie_tension.max()
        assert tension > 1e5
        assert np.abs(load[:, :2]).max() < 1e-9 * tension
        assert np.abs(load[:, 5]).max() > 1e3  # [N m]: the moments are what the scan solves


@pytest.mark.parametrize("weather", [Weather(0.8, 152.4, 16.0, 330.2),
                                     Weather(0.8, 180.0, 24.0, 0.0)])  # fmt: skip
def test_the_search_finds_what_a_brute_force_finds(plane, weather):
    """256 starts (16 headings a body, placed, without the scan) against the search of the
    scan and one placed start: no equilibrium of the brute force missed, each balanced to
    round-off; the scanned starts alone are equilibria already (the premise holds: loads at
    rest depend on the headings only)."""
    brute = equilibria.find(plane, weather, 16, scan=0)
    found = equilibria.find(plane, weather, 1)
    assert len(brute) >= 4
    for e in brute:
        assert any(_same(e.x, f.x) for f in found), f"missed {np.round(e.x, 2)}"
    assert len(found) >= len(brute)
    assert sum(e.stable for e in found) >= 1
    for e in found:
        assert e.residual < equilibria.BALANCED
    scanned = equilibria._scanned_starts(plane, equilibria.SCAN)
    assert len(scanned) == len(found)
    for x in scanned:
        g, _ = plane.at_rest(x, jacobian=False)
        assert np.abs(g).max() < 1e-6 * plane.work.tie_tension.max()


@pytest.mark.parametrize("weather", [Weather(0.8, 180.0, 15.0, 200.0),
                                     Weather(0.8, 120.0, 24.0, 250.0)])  # fmt: skip
def test_the_controlled_scan_finds_every_equilibrium_where_the_compensator_holds(plane, weather):
    """With the compensator on, the shuttle's loads depend on where it is, but where the
    compensator does not saturate its errors are zero at rest: the hawser 95 m long, the
    shuttle on the FPSO's heading. The scanned starts are then equilibria already, and they
    are every unsaturated equilibrium of a brute force of 256 starts. The placed starts
    (``every``) look for the saturated ones too, without a guarantee."""
    plane.control(True)
    try:
        brute = equilibria.find(plane, weather, 16, scan=0)
        scanned = equilibria._scanned_starts(plane, equilibria.SCAN)
        p = plane.built.params
        for x in scanned:
            g, _ = plane.at_rest(x, jacobian=False)
            assert np.abs(g).max() < 1e-6 * plane.work.tie_tension.max()
            pose = equilibria._points(plane, x)
            stern, bow = (pose[p.point_body[k], :2]
                          + equilibria._turn(pose[p.point_body[k], 2], p.point_offset[k])
                          for k in _hawser_points(plane))  # fmt: skip
            assert abs(float(np.hypot(*(bow - stern))) - 95.0) < 1e-6
            assert abs(x[5] - x[2]) < 1e-9
        some = equilibria.find(plane, weather, 4, every=False)
        every = equilibria.find(plane, weather)  # 12 headings a body
        assert sum(e.stable for e in some) >= 1
        saturated = 0
        for e in brute:
            plane.rates(np.concatenate([e.x, np.zeros(6)]))
            record = plane.work.control[0]
            held = record[0] == record[2] and record[1] == record[3]
            saturated += not held
            if held:
                assert any(_same(e.x, x) for x in scanned), f"not scanned {np.round(e.x, 2)}"
                assert any(_same(e.x, f.x) for f in some), f"missed {np.round(e.x, 2)}"
        for e in some:
            assert any(_same(e.x, f.x) for f in every)
        assert len(scanned) >= 4
        # the yaw moment saturated: not of the scan's kind (the grid may find them, or not)
        assert (saturated > 0) == (weather.wind_speed == 24.0)
    finally:
        plane.control(False)


def _hawser_points(plane) -> tuple[int, int]:
    p = plane.built.params
    k = list(plane.built.layout.ties).index("hawser")
    return int(p.tie_from[k]), int(p.tie_to[k])
