"""Added mass along a lumped-mass line (``added_mass_coefficient_tangential``, MoorDyn's CaAx):
a body pulled along a straight submerged line at rest accelerates at F / (M + m/2 + m_at/2)
(the end node carries half the last segment's mass and half its added mass along it, none of
the normal one); the water's acceleration along a segment acts through it (Morison's inertia);
the rigid-segment models refuse it."""

import math

import numpy as np
import pytest

import seacable
from seacable.kernels import morison
from seacable.system import kernel, model

RHO, D, MASS_PER_LENGTH, LENGTH, SEGMENTS = 1025.0, 0.2, 50.0, 40.0, 4
BODY, FORCE = 1000.0, 5000.0


def _case(ca_along: float, line_model: str = "lumped_mass"):
    return seacable.load_case({
        "environment": {"water_density": RHO},
        "bodies": [
            {"name": "wall", "type": "fixed", "position": [0.0, 0.0, -50.0]},
            {"name": "pulled", "type": "point", "position": [LENGTH, 0.0, -50.0], "mass": BODY,
             "external forces": [{"model": "applied", "force_x": {"kind": "constant",
                                                                   "value": FORCE}}]},
        ],
        "line_types": [{"name": "rope", "diameter": D, "mass_per_length": MASS_PER_LENGTH,
                        "axial_stiffness": 1.0e8, "added_mass_coefficient": 1.0,
                        "added_mass_coefficient_tangential": ca_along,
                        "drag_coefficient_normal": 0.0}],
        "lines": [{"name": "line", "model": line_model, "from": "wall", "to": "pulled",
                   "initial": "straight",
                   "sections": [{"type": "rope", "length": LENGTH, "segments": SEGMENTS}]}],
        "start": "as_given",
        "simulation": {"duration": 1.0, "output_interval": 0.1, "integrator": "rk4",
                       "time_step": 0.001},
    })  # fmt: skip


@pytest.mark.parametrize("ca_along", [0.0, 0.5, 1.0])
def test_a_body_pulled_along_the_line_carries_half_a_segment_of_added_mass(ca_along):
    system = model.build(_case(ca_along))
    p = system.params
    ydot = np.empty_like(system.y0)
    kernel.rhs(0.0, system.y0, p, kernel.make_work(p), ydot)
    segment = LENGTH / SEGMENTS
    along = ca_along * RHO * math.pi * D**2 / 4 * segment
    expected = FORCE / (BODY + 0.5 * MASS_PER_LENGTH * segment + 0.5 * along)
    assert ydot[p.body_v[1]] == pytest.approx(expected, rel=1e-9)


def test_the_waters_acceleration_along_a_segment_acts_through_it():
    force = morison.inertia(0.0, 3.0, 2.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0)  # tangent x
    assert force == pytest.approx((2.0, 3.0, 0.0))


def test_the_rigid_segment_models_refuse_it():
    with pytest.raises(seacable.CaseError, match="no added mass along its segments"):
        model.build(_case(0.5, "rigid_segments_3d"))
