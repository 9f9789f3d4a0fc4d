"""The seabed's contact law for lumped-mass lines (kernels.lumped.seabed_spring): C1 in the
depth over its ``contact_band``, its energy the integral of its push, its resting depth its
inverse; a chain at rest on the seabed sinks to that depth, and a line that falls onto the
seabed and bounces keeps its energy."""

import numpy as np
import pytest

import seacable
from seacable.kernels import lumped as lk

K, BAND = 3.0e4, 0.005  # [N/m], [m]
# the law's Python source (compiled, they are callable from compiled code only)
spring, potential = lk.seabed_spring.py_func, lk.seabed_potential.py_func


def _derivative(f, x, h=1e-9):
    return (f(x + h) - f(x - h)) / (2 * h)


def test_the_push_is_c1_and_its_energy_is_its_integral():
    """Push and share are continuous with continuous slopes at the seabed and at the band's
    foot (the plain spring's kink is gone), the push is k (depth - band / 2) below the band,
    and the potential's slope is the push at every depth, in and below the band."""

    def push(d):
        return spring(d, K, BAND)[0]

    for at in (0.0, BAND):
        for f in (push, lambda d: spring(d, K, BAND)[1]):
            assert f(at + 1e-12) == pytest.approx(f(at - 1e-12), abs=1e-7)
        # the slope from either side: 0 at the seabed, k at the band's foot
        left = (push(at - 1e-7) - push(at - 2e-7)) / 1e-7
        right = (push(at + 2e-7) - push(at + 1e-7)) / 1e-7
        assert left == pytest.approx(right, abs=1e-3 * K)
        assert right == pytest.approx(K if at else 0.0, abs=1e-3 * K)
    assert push(-0.01) == 0.0 and spring(-0.01, K, BAND)[1] == 0.0
    assert push(0.02) == pytest.approx(K * (0.02 - BAND / 2), rel=1e-15)
    assert spring(0.5 * BAND, K, BAND) == pytest.approx((K * BAND / 8, 0.5))
    for d in (0.2 * BAND, 0.7 * BAND, 1.5 * BAND, 0.05):
        slope = _derivative(lambda x: potential(x, K, BAND), d)
        assert slope == pytest.approx(push(d), rel=1e-6)
    assert potential(-0.01, K, BAND) == 0.0


def test_band_zero_is_the_plain_spring():
    """contact_band 0: k depth below the seabed (MoorDyn's law), k depth^2 / 2 its energy."""
    for d in (1e-6, 0.01, 0.3):
        assert spring(d, K, 0.0) == (K * d, 1.0)
        assert potential(d, K, 0.0) == pytest.approx(0.5 * K * d * d, rel=1e-15)
    assert lk.seabed_resting_depth(150.0, K, 0.0) == 150.0 / K


@pytest.mark.parametrize("weight", [0.01, 0.07, 75.0, 3.0e3])  # in the band and below it [N]
def test_resting_depth_inverts_the_push(weight):
    depth = lk.seabed_resting_depth(weight, K, BAND)
    assert spring(depth, K, BAND)[0] == pytest.approx(weight, rel=1e-12)


def test_frozen_contact_is_the_law_itself_in_the_band():
    """FROZEN (Newton's matrix) on a recorded contact evaluates the same C1 law, so a
    difference quotient across the band's edges is the law's slope, and above the seabed
    it is zero (no pull back, unlike the plain spring's linear continuation)."""
    n = 1
    w = np.zeros((lk.N_WORK_ROWS, n + 1))
    args = (-10.0, np.full(2, K), np.full(2, 50.0), 0.0, 0.01, BAND)  # z, k, c, mu, slip, band
    y = np.array([0.0, 0, -10.002, 1.0, 0, -9.0, 0, 0, -0.1, 0, 0, 0])  # node 0: 2 mm deep

    def normal(state, mode):
        w[lk._F : lk._F + 3] = 0.0
        lk.seabed_loads(state, n, 0, *args, mode, w)
        return w[lk._F + 2, 0]

    law = normal(y, lk.LAW)
    assert list(w[lk._CONTACT]) == [1.0, 0.0]
    push, share = spring(-10.0 - y[2], K, BAND)
    assert law == push + share * 50.0 * 0.1  # sinking at 0.1 m/s: the damping pushes too
    assert normal(y, lk.FROZEN) == law
    lifted = y.copy()
    lifted[2] = -9.999
    assert normal(lifted, lk.FROZEN) == 0.0


def _line_on_the_seabed(**seabed):
    return seacable.load_case(
        {
            "name": "a chain across a flat seabed",
            "environment": {
                "water_density": 1025.0,
                "water_depth": 50.0,
                "seabed": {"stiffness": 3.0e5, "damping": 3.0e3, **seabed},
            },
            "bodies": [
                {"name": "anchor", "type": "fixed", "position": [0.0, 0.0, -50.0]},
                {"name": "fairlead", "type": "fixed", "position": [140.0, 0.0, -10.0]},
            ],
            "line_types": [
                {
                    "name": "chain",
                    "diameter": 0.09,
                    "mass_per_length": 55.0,
                    "axial_stiffness": 2.5e8,
                    "axial_damping_ratio": 0.8,
                }
            ],
            "lines": [
                {
                    "name": "mooring",
                    "model": "lumped_mass",
                    "from": "anchor",
                    "to": "fairlead",
                    "sections": [{"type": "chain", "length": 170.0, "segments": 34}],
                }
            ],
            "simulation": {"duration": 1.0, "output_interval": 0.5, "integrator": "dopri5"},
        }
    )


@pytest.mark.parametrize("band", [0.0, 0.005, 0.05])
def test_a_chain_lies_at_the_depth_that_carries_its_weight(band):
    """At static balance, each node well along the lying part carries its apparent weight
    (55 kg/m less the displaced water, 5 m of chain) at seabed_resting_depth below the seabed:
    W / k + band / 2 for these depths."""
    case = _line_on_the_seabed(contact_band=band)
    tree = seacable.simulate(case).dataset
    z = tree["lines/mooring/node_z"].values[0]
    weight = (55.0 - 1025.0 * np.pi * 0.09**2 / 4) * 9.81  # [N/m]
    expected = -50.0 - lk.seabed_resting_depth(weight, 3.0e5, band)
    np.testing.assert_allclose(z[2:16], expected, atol=1e-9)  # 125 m lie
    assert tree.attrs["status"] == "complete"


def test_a_line_that_falls_onto_the_seabed_keeps_its_energy():
    """No damping, drag, friction or added mass (a node's added mass turns with its segments,
    which the lumped model's equations leave out of the energy: 8e-4 of drift without contact):
    a rope released straight between two points sags onto the seabed, bounces in and out of
    the contact band and below it, and its total energy (the seabed's potential included)
    stays within the integrator's error (measured 2.8e-9 of the kinetic energy's range; 0.5 k
    d^2 for the potential would be off by about 5 %)."""
    case = seacable.load_case(
        {
            "name": "a rope bouncing on the seabed",
            "environment": {
                "water_density": 1025.0,
                "water_depth": 5.5,
                "seabed": {"stiffness": 2.0e3, "contact_band": 0.05},
            },
            "bodies": [
                {"name": "a", "type": "fixed", "position": [0.0, 0.0, -5.0]},
                {"name": "b", "type": "fixed", "position": [10.0, 0.0, -5.0]},
            ],
            "line_types": [
                {
                    "name": "rope",
                    "diameter": 0.01,
                    "mass_per_length": 1.0,
                    "axial_stiffness": 2.0e4,
                    "drag_coefficient_normal": 0.0,
                    "added_mass_coefficient": 0.0,
                }
            ],
            "lines": [
                {
                    "name": "rope",
                    "model": "lumped_mass",
                    "from": "a",
                    "to": "b",
                    "initial": "straight",
                    "sections": [{"type": "rope", "length": 10.0, "segments": 20}],
                }
            ],
            "start": "as_given",  # released straight
            "simulation": {
                "duration": 3.0,
                "output_interval": 0.01,
                "integrator": "dopri5",
                "rtol": 1e-10,
                "atol": 1e-12,
            },
        }
    )
    tree = seacable.simulate(case).dataset
    lowest = tree["lines/rope/node_z"].values.min(axis=-1)
    assert lowest.min() < -5.5 - 0.05  # below the band
    touching = np.mean(lowest < -5.5)
    assert 0.05 < touching < 0.95  # in and out of contact (measured: 13 % of the outputs)
    energy = tree["total_energy"].values
    drift = np.max(np.abs(energy - energy[0])) / np.ptp(tree["kinetic_energy"].values)
    assert drift < 1e-6, drift


@pytest.mark.parametrize(
    "depth, velocity",
    [
        (0.002, (0.0, 0.0, 0.0)),  # in the band, at rest
        (0.003, (0.004, -0.002, -0.05)),  # in the band, sliding slower than slip_speed, sinking
        (0.02, (0.3, 0.1, 0.02)),  # below the band, sliding, rising
        (0.02, (-0.001, 0.0, 0.0)),  # below the band, nearly stuck
        (0.003, (0.0, 0.0, 0.05)),  # in the band, rising: the damping would pull, no contact
    ],
)
def test_the_seabed_gradient_is_the_derivative_of_its_loads(depth, velocity):
    """kernels.lumped.seabed_gradient (Newton's matrix keeps the seabed's terms current with
    it) against central differences of seabed_loads (LAW), friction and damping on."""
    n = 1
    args = (-10.0, np.full(2, K), np.full(2, 2.0e3), 0.6, 0.01, BAND)  # z, k, c, mu, slip, band
    y = np.array([0.0, 0.0, -10.0 - depth, 5.0, 0.0, -2.0, *velocity, 0.0, 0.0, 0.0])

    def force(state):
        w = np.zeros((lk.N_WORK_ROWS, n + 1))
        lk.seabed_loads(state, n, 0, *args, lk.LAW, w)
        return w[lk._F : lk._F + 3, 0].copy()

    numeric = np.empty((3, 4))  # dF/dz, dF/dv_x, dF/dv_y, dF/dv_z
    for col, (index, step) in enumerate([(2, 1e-7), (6, 1e-7), (7, 1e-7), (8, 1e-7)]):
        up, down = y.copy(), y.copy()
        up[index] += step
        down[index] -= step
        numeric[:, col] = (force(up) - force(down)) / (2 * step)
    out = np.empty(12)
    lk.seabed_gradient(y[2], *velocity, *args[:1], K, 2.0e3, *args[3:], out)
    analytic = np.column_stack([out[0:3], out[3:12].reshape(3, 3)])
    scale = np.abs(numeric).max(axis=0)
    np.testing.assert_allclose(analytic, numeric, rtol=1e-5, atol=1e-6 * scale.max())
    assert out[2] < 0.0 or not force(y).any()  # deeper pushes harder: dF_z/dz < 0
