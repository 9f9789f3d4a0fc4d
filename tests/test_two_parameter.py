"""Curves of Hopf points in two parameters (seacable.stability.two_parameter): the shuttle's
Hopf point in astern thrust, followed as its hawser lengthens, against the Routh-Hurwitz
condition derived by hand at every point (tests/test_stability.py); the tandem example's Hopf
points in the current's direction, followed as the wind turns, against one-parameter
continuations run at fixed wind directions taken from the curves."""

from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import seacable
from seacable.stability.api import weather_of
from seacable.stability.continuation import Continuation
from seacable.stability.parameters import parameter
from seacable.stability.plane import Plane
from seacable.stability.two_parameter import CurveContinuation
from test_stability import _routh_hurwitz, shuttle_case

EXAMPLE = Path(__file__).parents[1] / "examples" / "tandem_offloading_fpso_shuttle.yaml"


def test_the_shuttles_hopf_curve_in_thrust_and_hawser_length_is_routh_hurwitzs():
    plane = Plane.of(shuttle_case("cross-flow"))
    thrust = parameter(plane, "bodies.shuttle.external forces.1.force_x")
    hawser = parameter(plane, "lines.hawser.unstretched_length")
    branch = Continuation(plane, thrust).run(np.array([-240.0, 0.0, 0.0]), -2e5, 0.0)
    hopf = next(s for s in branch.special if s.kind == "hopf")
    curve = CurveContinuation(plane, thrust, hawser, "hopf").run(
        hopf.x, hopf.parameter, 80.0, 160.0, (-1e6, 0.0), hopf.frequency
    )
    assert len(curve.first) > 10 and curve.second[-1] >= 160.0
    for mu, length in zip(curve.first, curve.second, strict=True):
        exact = brentq(_routh_hurwitz, 1e4, 1e6, args=(length,), xtol=1e-9)
        assert -mu == pytest.approx(exact, rel=1e-6)
    assert curve.first[-1] < -1.4e5  # a longer hawser needs more astern thrust


def test_the_tandems_hopf_curves_in_current_and_wind_directions(tmp_path):
    case = seacable.load_case(EXAMPLE)
    found = seacable.curves(case, "current.towards_deg", 90.0, 270.0, "wind.towards_deg",
                            200.0, 215.0, headings=6)  # fmt: skip
    assert found.sizes["curve"] >= 4 and set(found["kind"].values) == {"hopf"}
    checked = 0
    for k in range(found.sizes["curve"]):
        on = found.where(found["curve"] == k, drop=True)
        if on.sizes["curve_point"] < 3:
            continue
        i = on.sizes["curve_point"] // 2  # a point inside the curve: the wind fixed there
        current, wind = float(on["first"][i]), float(on["second"][i])
        plane = Plane.of(case)
        weather = weather_of(case)
        shared = {"weather": weather}
        parameter(plane, "wind.towards_deg", weather, shared).set(plane, wind)
        towards = parameter(plane, "current.towards_deg", weather, shared)
        x = np.stack([on["x"].values[i], on["y"].values[i], np.radians(on["heading"].values[i])],
                     axis=1).ravel()  # fmt: skip
        branch = Continuation(plane, towards).run(x, current - 0.5, current + 0.5)
        located = [s.parameter for s in branch.special if s.kind == "hopf"]
        assert located and min(abs(m - current) for m in located) < 1e-4, (k, located)
        checked += 1
    assert checked >= 3
    out = _cli(tmp_path)
    assert out.exit_code == 0, out.output
    assert "hopf:" in out.output and (tmp_path / "c.png").stat().st_size > 10_000


def _cli(tmp_path):
    from click.testing import CliRunner

    from seacable.cli import main

    return CliRunner().invoke(main, ["curves", str(EXAMPLE), "--parameter",
                                     "current.towards_deg", "--from", "170", "--to", "190",
                                     "--second", "wind.towards_deg", "--second-from", "200",
                                     "--second-to", "205", "--headings", "6", "--plot",
                                     str(tmp_path / "c.png")])  # fmt: skip
