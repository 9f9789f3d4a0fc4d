"""Poth's string pendulum in natural variables: the (eps, phi) and (eps, t) parametrisations
agree, they agree with the displacement form (lumped mass) as the grid is refined, the stiff
integrators agree with the compiled ones, and the model refuses what it does not describe."""

import numpy as np
import pytest

import seacable
from golden.record import system_rows
from helpers import system_data, upgraded
from seacable import analysis
from seacable.errors import CaseError


def _pendulum(model="natural_string", tangent="angle", k=20, ea=1e5, **simulation):
    cable = {
        "model": model,
        "links": k,
        "length": 10.0,
        "diameter": 0.01,
        "mass_per_length": 1.0,
        "axial_stiffness": ea,
        "axial_damping_time": 1e-3,
        "top": {"type": "fixed"},
        "bottom": {"type": "free", "body": {"mass": 10.0}},
        "initial": {"shape": "arc", "top_angle_deg": 90.0, "bottom_angle_deg": 90.0},
    }
    if model == "natural_string":
        cable["tangent"] = tangent
    sim = {"duration": 1.0, "output_interval": 0.1, "integrator": "dopri5", "rtol": 1e-9}
    sim["atol"] = 1e-9
    sim.update(simulation)
    return {"environment": {"in_air": True}, "cables": [cable], "simulation": sim}


def _run(data) -> tuple[dict, dict]:
    """The upgraded pendulum's rows (single-cable names) and the results' attributes."""
    case = upgraded(data)
    ds = seacable.simulate(case).dataset
    return system_rows(ds, case), ds.attrs


def _end(rows):
    return np.array([rows["node_x"][-1, -1], rows["node_z"][-1, -1]])


def test_angle_and_cartesian_tangents_give_the_same_motion():
    angle, _ = _run(_pendulum(tangent="angle"))
    cartesian, _ = _run(_pendulum(tangent="cartesian"))
    assert np.max(np.abs(angle["node_x"] - cartesian["node_x"])) < 1e-6
    np.testing.assert_allclose(angle["tension"], cartesian["tension"], rtol=1e-5, atol=1e-3)
    assert np.allclose(_end(angle), [angle["end_x"][-1], angle["end_z"][-1]])


def test_natural_and_displacement_forms_converge_to_each_other():
    """The two space discretisations differ at O(1/k^2): the gap of the end mass shrinks about
    fourfold per doubling of k."""
    gaps = []
    for k in (10, 20, 40):
        natural = _end(_run(_pendulum(k=k))[0])
        displacement = _end(_run(_pendulum(model="lumped_mass", k=k))[0])
        gaps.append(float(np.linalg.norm(natural - displacement)))
    rates = np.log2(np.array(gaps[:-1]) / np.array(gaps[1:]))
    assert gaps[-1] < 5e-3, gaps
    assert np.all(rates > 1.6), (gaps, rates)


def test_the_string_falls_like_a_pendulum_at_first():
    """Released horizontal, the whole string first falls freely: the end mass drops g t^2 / 2
    while the string is slack."""
    drop = _run(_pendulum(duration=0.1, output_interval=0.05))[0]["end_z"][1]
    assert abs(drop + 0.5 * 9.81 * 0.05**2) < 1e-3


# CVODE factorises the system's Jacobian densely (the single-cable string's was banded): 20 s
@pytest.mark.parametrize(
    "integrator", [pytest.param("cvode", marks=pytest.mark.slow), "bdf", "radau", "lsoda"]
)
def test_stiff_integrators_agree_with_dopri5(integrator):
    reference = _end(_run(_pendulum(ea=1e6))[0])
    ends, attrs = _run(_pendulum(ea=1e6, integrator=integrator, rtol=1e-8, atol=1e-8))
    assert np.linalg.norm(_end(ends) - reference) < 1e-4
    assert attrs["solver_rhs_evaluations"] > 0
    assert attrs["solver_jacobian_evaluations"] > 0


@pytest.mark.parametrize("integrator", ["newmark", "generalized_alpha"])
@pytest.mark.parametrize("tangent", ["angle", "cartesian"])
def test_fixed_step_schemes_on_natural_variables(integrator, tangent):
    """Second order in time through the system's finite-difference Newton matrix (the string
    written as a system by seacable upgrade)."""

    def end(data):
        ends = _run(data)[0]
        return np.array([ends["end_x"][-1], ends["end_z"][-1]])

    reference = end(_pendulum(tangent=tangent))
    errors = []
    for dt in (0.01, 0.005, 0.0025):
        at = end(_pendulum(tangent=tangent, integrator=integrator, time_step=dt,
                           newton_tolerance=1e-10))  # fmt: skip
        errors.append(float(np.linalg.norm(at - reference)))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(rates > 1.6), (errors, rates)


def test_energy_decreases_with_damping_and_is_nearly_kept_without():
    damped = _run(_pendulum())[0]["total_energy"]
    assert damped[-1] < damped[0]
    data = _pendulum(ea=1e4)
    data["cables"][0]["axial_damping_time"] = 0.0
    energy = _run(data)[0]["total_energy"]
    swing = 10.0 * 9.81 * 10.0  # the end mass falls about its string's length
    assert np.max(np.abs(energy - energy[0])) < 0.02 * swing


def test_natural_string_refuses_water_and_a_missing_end_mass():
    data = _pendulum()
    data["environment"]["in_air"] = False
    with pytest.raises(CaseError, match="in air"):
        seacable.simulate(upgraded(data))
    data = _pendulum()
    data["cables"][0]["bottom"] = {"type": "free"}
    with pytest.raises(CaseError, match="end mass"):
        seacable.simulate(upgraded(data))


# ---- the same string as a line of a system of bodies and lines ----------------------------------
def _system(tangent="angle", **changes):
    """The pendulum in the system form (seacable upgrade of the single-cable case)."""
    data = system_data(_pendulum(tangent=tangent))
    for key, value in changes.items():
        data[key] = value
    return seacable.load_case(data)


def test_a_system_string_hangs_in_air_only():
    with pytest.raises(CaseError, match=r"string pendulum in air"):
        seacable.simulate(_system(environment={"water_density": 1025.0}))


def test_a_string_end_mass_holding_another_line_is_refused():
    """Its end mass takes gravity alone: a tie there was once ignored (490 kN, no effect)."""
    data = system_data(_pendulum())
    end = data["lines"][0]["to"]
    data["bodies"].append({"name": "anchor", "type": "fixed", "position": [10.0, 0.0, -5.0]})
    data["lines"].append({"name": "spring", "model": "tie", "from": "anchor", "to": end,
                          "unstretched_length": 0.1, "stiffness": 1e5})  # fmt: skip
    with pytest.raises(CaseError, match=r"lines\[0\] \(cable\)\.to: .* also holds \['spring'\]"):
        seacable.simulate(seacable.load_case(data))


@pytest.mark.parametrize("tangent", ["angle", "cartesian"])
def test_a_string_hangs_with_the_weight_below_each_node_over_ea(tangent):
    """``start: static``: the string hangs straight down, each node's strain the weight below
    it (10 kg at the end, 1 kg/m over 10 m) over EA = 1e5 N, to 1e-12; a run from there stays
    at rest (the released string swings 10 m)."""
    ds = seacable.simulate(_system(tangent, start="static")).dataset
    strain = ds["lines/cable/strain"].values
    s = np.linspace(0.0, 10.0, strain.shape[1])
    exact = 9.81 * (1.0 * (10.0 - s) + 10.0) / 1e5
    np.testing.assert_allclose(strain[0], exact, rtol=0, atol=1e-12)
    assert np.abs(strain - strain[:1]).max() < 1e-10
    assert np.abs(ds["lines/cable/node_x"].values).max() < 1e-9


def _bessel_periods(count, g=9.81, length=10.0, mu=1.0, end_mass=10.0):
    """The small swings of an inextensible uniform chain of ``length`` [m] and ``mu`` [kg/m]
    with ``end_mass`` [kg] at its free end: with xi = l - s + m/mu (tension mu g xi), the
    displacement U solves g (xi U')' + w^2 U = 0, so U = A J0(x) + B Y0(x), x = 2 w sqrt(xi / g);
    U = 0 at the pivot, and at the end mass -w^2 m U = mu g xi U'. Periods 2 pi / w [s]."""
    from scipy import optimize, special

    a = end_mass / mu

    def det(w):
        xa, xp = 2 * w * np.sqrt(a / g), 2 * w * np.sqrt((length + a) / g)
        return (special.j0(xp) * (special.y1(xa) - 0.5 * xa * special.y0(xa))
                - special.y0(xp) * (special.j1(xa) - 0.5 * xa * special.j0(xa)))  # fmt: skip

    grid = np.linspace(0.05, 20.0, 4000)
    values = det(grid)
    sign = np.flatnonzero(values[:-1] * values[1:] < 0)[:count]
    return np.array([2 * np.pi / optimize.brentq(det, grid[i], grid[i + 1]) for i in sign])


@pytest.mark.parametrize("tangent", ["angle", "cartesian"])
def test_string_modes_converge_to_the_hanging_chains_bessel_modes(tangent):
    """``seacable modes`` on the string (EA 1e9 N: nearly inextensible): its three slowest
    periods approach the hanging chain's (Bessel functions, with the end mass) at second order
    in the element length: within 1.1e-3 at 40 elements, each error at least 3.5 times
    smaller than at 20."""
    exact = _bessel_periods(3)
    errors = []
    for k in (20, 40):
        data = system_data(_pendulum(tangent=tangent, k=k, ea=1e9))
        periods = analysis.system_modes(seacable.load_case(data), count=3)["period"].values
        errors.append(np.abs(periods / exact - 1.0))
    assert np.all(errors[1] < 1.1e-3)
    assert np.all(errors[0] > 3.5 * errors[1])
