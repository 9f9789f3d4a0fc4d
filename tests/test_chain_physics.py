"""Physics checks of the planar rigid-link line: invariants, analytic limits, agreement of
three models of a seabed-fixed end. Each case is written in the single-cable form and run as
the system ``seacable upgrade`` writes (a line between a top body and an end body)."""

import numpy as np
import pytest
from scipy.special import jn_zeros

import seacable
from helpers import chain_case, run_rows, system_data, upgraded
from seacable.analysis import system_modes


def _energy_drift(results):
    energy = results["total_energy"]
    swing = np.ptp(results["kinetic_energy"])
    return np.max(np.abs(energy - energy[0])) / swing


def _modes(n, count=3):
    """Frequencies [rad/s] and damping ratios of the hanging chain's slowest modes (the system
    linearised about its statics)."""
    modes = system_modes(upgraded(chain_case(n=n)), count=count)
    return modes["frequency"].values, modes["damping_ratio"].values


def test_energy_is_conserved_without_damping_or_water():
    data = chain_case(
        n=30,
        initial={"shape": "arc", "top_angle_deg": 60.0},
        bottom={"type": "free", "body": {"mass": 2.0}},
        joint_stiffness=5.0,
        simulation={"duration": 5.0, "output_interval": 0.05, "time_step": 0.0005},
    )
    drift = _energy_drift(run_rows(data))
    assert drift < 1e-6, f"relative energy drift {drift:.2e}"


def test_energy_is_conserved_with_heaving_structure_and_ties():
    data = chain_case(
        n=12,
        top={"type": "floating_structure", "mass": 20.0, "heave_stiffness": 300.0},
        bottom={
            "type": "floating_structure",
            "mass": 3.0,
            "heave_stiffness": 50.0,
            "surge_stiffness": 80.0,
        },  # fmt: skip
        initial={"shape": "arc", "top_angle_deg": 30.0, "bottom_angle_deg": 120.0},
        joint_stiffness=2.0,
        simulation={"duration": 4.0, "output_interval": 0.05, "time_step": 0.0005},
    )
    drift = _energy_drift(run_rows(data))
    assert drift < 1e-6, f"relative energy drift {drift:.2e}"


def test_dissipation_only_removes_energy():
    data = chain_case(
        n=20,
        environment={"water_density": 1025.0},
        initial={"shape": "arc", "top_angle_deg": 60.0},
        joint_damping=0.5,
        joint_stiffness=1.0,
        simulation={"duration": 3.0, "output_interval": 0.05, "time_step": 0.001},
    )
    energy = run_rows(data)["total_energy"]
    assert np.all(np.diff(energy) <= 1e-9 * np.abs(energy).max())
    assert energy[-1] < energy[0]


@pytest.mark.parametrize("n", [50, 100])
def test_hanging_chain_frequencies_approach_heavy_chain(n):
    """Small oscillations of a hanging chain: omega_k = (j_0k / 2) sqrt(g / L)."""
    frequencies, damping = _modes(n)
    exact = jn_zeros(0, 3) / 2 * np.sqrt(9.81 / 10.0)
    error = np.abs(frequencies[:3] / exact - 1)
    assert np.all(error < 2.0 / n**2 * np.array([1, 10, 30])), error
    assert np.allclose(damping[:3], 0.0, atol=1e-9)


def test_frequency_error_falls_as_n_squared():
    errors = []
    for n in (25, 50, 100):
        frequencies, _ = _modes(n, count=2)
        errors.append(abs(frequencies[1] / (jn_zeros(0, 2)[1] / 2 * np.sqrt(0.981)) - 1))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 2.0) < 0.1), orders


@pytest.mark.parametrize("n", [10, 400])
def test_static_tension_of_hanging_chain_is_weight_below(n):
    """At rest, hanging: tension at a link centre = weight below it (exact for any n); holds
    for hundreds of links, where the thesis's dense mass matrix became nearly singular."""
    data = chain_case(n=n, bottom={"type": "free", "body": {"mass": 3.0}})
    simulation = {"duration": 0.2, "output_interval": 0.1, "time_step": 0.001}  # rk4 stable
    results = run_rows(data | {"simulation": simulation})
    centre = results["arc_length"][:-1] + 5.0 / n
    expected = 9.81 * (3.0 + (10.0 - centre) * 1.0)
    np.testing.assert_allclose(results["tension"][-1], expected, rtol=1e-9)
    np.testing.assert_allclose(results["top_force_z"], -9.81 * 13.0, rtol=1e-9)
    assert np.max(np.abs(results["angle"])) < 1e-12


def test_mirror_symmetry():
    base = {"shape": "arc", "top_angle_deg": 40.0, "bottom_angle_deg": -20.0}
    mirror = {"shape": "arc", "top_angle_deg": -40.0, "bottom_angle_deg": 20.0}
    common = dict(n=15, environment={"water_density": 1025.0}, joint_stiffness=1.0,
                  simulation={"duration": 2.0, "output_interval": 0.1})  # fmt: skip
    a = run_rows(chain_case(initial=base, **common))
    b = run_rows(chain_case(initial=mirror, **common))
    np.testing.assert_allclose(a["node_x"], -b["node_x"], atol=1e-10)
    np.testing.assert_allclose(a["node_z"], b["node_z"], atol=1e-10)
    np.testing.assert_allclose(a["tension"], b["tension"], rtol=1e-9, atol=1e-9)


def _seabed_case(bottom):
    return {
        "environment": {"water_density": 1000.0},
        "cables": [
            {
                "links": 30,
                "length": 100.0,
                "diameter": 0.02,
                "density": 7850.0,
                "joint_stiffness": 50.0,
                "joint_damping": 2.8,
                "top": {
                    "type": "floating_structure",
                    "mass": 6000.0,
                    "heave_stiffness": 1200.0,
                    "heave_damping": 237.6,
                    "force": {"kind": "sine", "amplitude": 25000.0, "period": 4.0},
                },
                "bottom": bottom,
                "initial": {"shape": "arc", "top_angle_deg": 20.0, "bottom_angle_deg": 80.0},
            }
        ],
        "simulation": {"duration": 8.0, "output_interval": 0.1, "time_step": 0.002},
    }


# the seabed-fixed end three ways: exact pin, the thesis's huge mass, the thesis's stiff ties
SEABED_BOTTOMS = {
    "pinned": {"type": "pinned"},
    "huge mass": {"type": "free", "body": {"mass": 8e8, "volume": 8e5}},
    "stiff ties": {
        "type": "free",
        "body": {"mass": 60.0},
        "tie": {"stiffness_x": 1.2e6, "damping_x": 2e4, "stiffness_z": 1.2e6, "damping_z": 2e4},
    },
}


def test_seabed_fixed_end_three_ways_agree():
    """Exact pin, huge terminal mass (the thesis's first way) and stiff ties (its second)."""
    pinned, huge, ties = (run_rows(_seabed_case(bottom)) for bottom in SEABED_BOTTOMS.values())
    scale = 100.0
    gap_huge = np.max(np.abs(pinned["node_z"] - huge["node_z"])) / scale
    gap_ties = np.max(np.abs(pinned["node_z"] - ties["node_z"])) / scale
    assert gap_huge < 1e-4, gap_huge
    assert gap_ties < 5e-3, gap_ties
    assert np.max(pinned["constraint_error"]) < 1e-6
    t_pin = pinned["bottom_force_z"]
    t_huge = huge["bottom_force_z"]
    assert np.max(np.abs(t_pin - t_huge)) < 1e-3 * np.max(np.abs(t_pin)) + 1.0


def test_static_tension_with_unequal_links_and_masses():
    """Links of different lengths and masses (sections of one segment each): tension at rest =
    weight hanging below; a body carried off the end of the given shape is refused."""
    lengths = [1.0, 2.5, 0.5, 3.0, 1.5]
    masses = [2.0, 0.5, 4.0, 1.0, 3.0]
    data = chain_case(n=5, bottom={"type": "free", "body": {"mass": 1.5}})
    cable = data["cables"][0]
    cable.pop("length")
    cable.pop("mass_per_length")
    cable.update(link_lengths=lengths, link_masses=masses)
    simulation = {"duration": 0.2, "output_interval": 0.1, "time_step": 0.001}  # rk4 stable
    results = run_rows(data | {"simulation": simulation})
    below = np.concatenate([np.cumsum(masses[::-1])[::-1][1:], [0.0]])
    expected = 9.81 * (1.5 + below + 0.5 * np.array(masses))
    np.testing.assert_allclose(results["tension"][-1], expected, rtol=1e-9)
    np.testing.assert_allclose(results["node_z"][-1, -1], -sum(lengths), rtol=1e-12)
    system = system_data(data)
    system["bodies"][1]["position"] = [10.0, 0.0, -20.0]
    refusal = (
        r"lines \(cable\)\.initial: the given angles end the line at \[0\.0, 0\.0, -8\.5\] m but "
        r"the body it carries is at \[10\.0, 0\.0, -20\.0\] m \(15\.24 m apart"
    )
    with pytest.raises(seacable.CaseError, match=refusal):
        seacable.simulate(seacable.load_case(system))
