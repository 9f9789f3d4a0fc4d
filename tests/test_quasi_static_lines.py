"""Lumped-mass lines in the horizontal-plane analyses (seacable.stability.plane.quasi_static):
each taken as the tie that pulls its ends as its elastic catenary does at rest. The catenary's
horizontal law against its closed form, and the turret-moored FPSO's equilibrium on three
chains against the whole system's statics with the lines' nodes (the discrete lines converge
on the plane's as their segments shrink)."""

import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import seacable
from seacable.errors import CaseError
from seacable.lines import catenary
from seacable.stability import equilibria
from seacable.stability.plane import Plane
from seacable.system import model as system_model

EXAMPLE = Path(__file__).parent.parent / "examples" / "turret_fpso_catenary_mooring.yaml"
W = 286.6 * 9.80665 * (1.0 - 1025.0 / 7850.0)  # a chain's apparent weight [N/m] (about)


@pytest.mark.parametrize("seabed", [True, False])
def test_the_horizontal_law_is_the_catenary_s(seabed):
    """Each row (span, H) of the law is the closed-form catenary's H at that span, and the
    law's linear interpolation between rows is within 3e-4 of it (where it is steepest,
    nearly taut: a span error of micrometres)."""
    rise, length, ea = 185.0, 1000.0, 1.23e9
    law = catenary.horizontal_law(rise, length, W, ea, seabed, count=400)
    assert np.all(np.diff(law[:, 0]) > 0.0) and np.all(np.diff(law[:, 1]) > 0.0)
    for k in (0, 57, 200, 399):
        h, _ = catenary.solve(float(law[k, 0]), rise, length, W, ea, seabed)
        assert h == pytest.approx(law[k, 1], rel=1e-6)
    for span in np.linspace(law[5, 0], law[-5, 0], 7):
        h, _ = catenary.solve(float(span), rise, length, W, ea, seabed)
        assert np.interp(span, law[:, 0], law[:, 1]) == pytest.approx(h, rel=3e-4)


def _case(segments: int, start: str = "as_given", pose=None) -> dict:
    data = yaml.safe_load(EXAMPLE.read_text())
    for kind in data["line_types"]:  # no current on the lines: the statics' nodes feel none
        kind["drag_coefficient_normal"] = kind["drag_coefficient_tangential"] = 0.0
    for line in data["lines"]:
        line["sections"][0]["segments"] = segments
    data["start"] = start
    if pose is not None:
        [fpso] = [b for b in data["bodies"] if b["name"] == "fpso"]
        fpso["position"] = [float(pose[0]), float(pose[1]), 0.0]
        fpso["orientation_deg"] = [0.0, 0.0, math.degrees(pose[2])]
    return data


def test_the_fpso_on_three_chains_balances_as_the_whole_system_does():
    """The plane's stable equilibrium (the chains quasi-static, closed form) against the
    whole system's statics with the chains' nodes (40, 80 and 160 segments, started there):
    the same heading (the chains pull at the turret, so the heading balances the hull's
    moment about it alone), and turret places that converge on the plane's, within 3 cm at 160
    segments (what is left is the nodes' sinking into the elastic seabed)."""
    plane = Plane.of(seacable.load_case(_case(40)))
    found = equilibria.find(plane, None, 6)
    [stable] = [e for e in found if e.stable]
    assert len(found) == 2  # and the reversed heading, unstable
    offsets = []
    for segments in (40, 80, 160):
        built = system_model.build(seacable.load_case(_case(segments, "static", stable.x)))
        q = int(built.params.body_q[[i for i, b in enumerate(built.case.bodies)
                                     if b.name == "fpso"][0]])  # fmt: skip
        y = built.y0
        heading = 2.0 * math.atan2(y[q + 6], y[q + 3])
        assert heading == pytest.approx(stable.x[2], abs=1e-9)
        offsets.append(math.hypot(y[q] - stable.x[0], y[q + 1] - stable.x[1]))
    assert offsets[0] > offsets[1] > offsets[2]
    assert offsets[2] < 0.03
    assert offsets[0] < 0.5


def test_a_line_the_plane_cannot_take_is_refused_in_one_line():
    data = _case(40)
    data["line_types"].append({**data["line_types"][0], "name": "wire",
                               "mass_per_length": 40.0})  # fmt: skip
    data["lines"][0]["sections"] = [{"type": "chain120", "length": 500.0, "segments": 20},
                                    {"type": "wire", "length": 500.0, "segments": 20}]  # fmt: skip
    with pytest.raises(CaseError) as caught:
        Plane.of(seacable.load_case(data))
    message = str(caught.value)
    assert message.startswith("lines.chain_1.sections: segments of different")
    assert "\n" not in message
