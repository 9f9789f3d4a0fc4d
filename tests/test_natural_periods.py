"""The natural periods of vessels (seacable.natural_periods, issue 43): a free-floating box barge
against the closed forms of its hydrostatics, C33 = rho g L B and C44 = rho g V GM_T; its heave
period at its own frequency's added mass A33(w) from the shipped database against an
independent root of w^2 (m + A33(w)) = C33; the linearisation at A(w) against the compiled
kernel's own Jacobian with that added mass; the radiation memory's poles apart."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import seacable
from seacable import analysis, hydrodb, natural_periods
from seacable.system import statics

DATA = Path(__file__).resolve().parents[1] / "examples" / "data"
RHO, G = 1025.0, 9.81
LENGTH, BEAM, DRAFT = 90.0, 24.0, 6.0  # examples/data/barge.stl: KB 3 m, BM B^2 / 12 T = 8 m
MASS = RHO * LENGTH * BEAM * DRAFT  # [kg], KG 6 m (the centre of gravity at the waterline)
INERTIA = (9.4e8, 6.7e9, 7.3e9)  # [kg m^2] about G (the moored barge example's)


def _barge(**given) -> seacable.SystemCase:
    """The example's box barge floating free: no mooring, nothing but its waterplane holds it."""
    barge = {"name": "barge", "type": "rigid", "position": [0.0, 0.0, 0.0], "mass": MASS,
             "centre_of_gravity": [0.0, 0.0, 0.0], "inertia": list(INERTIA),
             "mesh": {"file": str(DATA / "barge.stl")},
             "external forces": [{"model": "gravity"},
                                 {"model": "non-linear hydrostatic", "free_surface": "still"}],
             **given}  # fmt: skip
    return seacable.load_case({
        "environment": {"water_density": RHO, "water_depth": 100.0}, "bodies": [barge],
        "lines": [], "simulation": {"duration": 1.0, "output_interval": 0.5},
    })  # fmt: skip


def _rows(modes) -> dict:
    return {d: (float(p), m) for d, p, m in zip(modes["dominant"].values, modes["period"].values,
                                               modes["method"].values, strict=True)}  # fmt: skip


def test_a_free_floating_barge_has_its_hydrostatic_periods():
    """Heave, roll and pitch of a box barge that nothing holds within 0.1 % of
    2 pi sqrt((M + a) / C), C33 = rho g L B, C44 = rho g V GM_T (GM_T = KB + BM - KG = 5 m),
    C55 = rho g (B L^3 / 12 + V (KB - KG)), with the case's added mass (the centre of gravity
    at the reference point: no coupling); surge, sway and yaw free, without restoring. The
    statics used to refuse the case ("a group that nothing holds")."""
    added = [1.0e6, 2.0e6, 1.5e7, 2.0e8, 5.0e9, 3.0e9]
    rows = _rows(analysis.system_modes(_barge(added_mass=added)))
    volume = LENGTH * BEAM * DRAFT
    stiffness = {
        "heave": RHO * G * LENGTH * BEAM,
        "roll": RHO * G * volume * (DRAFT / 2 + BEAM**2 / (12 * DRAFT) - DRAFT),
        "pitch": RHO * G * (BEAM * LENGTH**3 / 12 - volume * DRAFT / 2),
    }
    inertia = {"heave": MASS + added[2], "roll": INERTIA[0] + added[3],
               "pitch": INERTIA[1] + added[4]}  # fmt: skip
    for dof, c in stiffness.items():
        period, method = rows[f"barge:{dof}"]
        assert period == pytest.approx(2 * math.pi * math.sqrt(inertia[dof] / c), rel=1e-3), dof
        assert method == natural_periods.LINEARISED
    for dof in ("surge", "sway", "yaw"):
        assert rows[f"barge:{dof}"] == (math.inf, natural_periods.FREE)
    assert len(rows) == 6


def test_heave_period_at_its_own_frequency_from_the_database():
    """The free barge with its database (examples/data/barge_hydrodb.nc) and no added mass of
    its own: heave at A33(w) of its own w, within 1e-6 of brentq's root of
    w^2 (M + A33(w)) = rho g L B (A33 linear between the database's frequencies: 7.5796 s),
    about 9 % under the period at A_inf that the linearisation alone gives (8.2 s)."""
    modes = analysis.system_modes(_barge(hydrodynamics={"file": str(DATA / "barge_hydrodb.nc")}))
    period, method = _rows(modes)["barge:heave"]
    db = hydrodb.read(DATA / "barge_hydrodb.nc")
    stiffness = RHO * G * LENGTH * BEAM

    def unbalanced(w: float) -> float:
        return w**2 * (MASS + np.interp(w, db.omega, db.added_mass[:, 2, 2])) - stiffness

    expected = 2 * math.pi / brentq(unbalanced, db.omega[0], db.omega[-1], xtol=1e-14)
    assert method == natural_periods.ITERATED
    assert period == pytest.approx(expected, rel=1e-6)
    infinite = db.ogilvie(np.arange(251) * 0.1, tail_power=3)[0][2, 2]
    assert abs(2 * math.pi * math.sqrt((MASS + infinite) / stiffness) / expected - 1) > 0.02
    heave = list(modes["dominant"].values).index("barge:heave")
    assert 0.0 < float(modes["damping_ratio"][heave]) < 0.5  # B33(w): radiation damps heave


@pytest.mark.slow  # the rescaling's consistency; the periods' physics is tested above
def test_the_linearisation_at_a_frequency_is_the_kernels_with_that_added_mass():
    """``_Frequency.matrix(w)``'s stiffness rows (M + A(w) - A_inf)^-1 M J equal the
    compiled Jacobian of the system whose added mass is A(w) (to 1e-6 of the largest)."""
    case = _barge(hydrodynamics={"file": str(DATA / "barge_hydrodb.nc")})
    state = natural_periods.equilibrium(case)
    a, coords = statics.jacobian(state.built, state.y)
    n = len(coords.kind)
    (body,) = natural_periods.databases(state.built)
    frequency = natural_periods._Frequency(state, a, coords, [body], np.ones(n))
    w = 0.7
    p = state.built.params
    added = p.body_added.copy()
    added[body.index] += body.at(w)[0]
    changed = type(state.built)(p._replace(body_added=added), state.y, state.built.layout,
                                state.built.case)  # fmt: skip
    exact, _ = statics.jacobian(changed, state.y)
    ours = frequency.matrix(w)[n : 2 * n, :n]
    assert np.abs(ours - exact[n : 2 * n, :n]).max() < 1e-6 * np.abs(exact[n : 2 * n, :n]).max()
    assert np.abs(ours - a[n : 2 * n, :n]).max() > 0.1 * np.abs(a[n : 2 * n, :n]).max()


@pytest.mark.slow  # a state-space fit's own compile; make test-all
def test_the_radiation_memorys_poles_are_listed_apart():
    """With the radiation memory as a state space, its states' poles are listed as memory
    poles (the eigenvalues of the fitted matrices), and the vessel's periods are those of the
    convolution (whose memory adds no state)."""
    spec = {"model": "radiation damping", "memory": 25.0, "memory_step": 0.1}
    found = {}
    hull = [{"model": "gravity"}, {"model": "non-linear hydrostatic", "free_surface": "still"}]
    for method in ("convolution", "state_space"):
        forces = [*hull, {**spec, "method": method}]
        found[method] = analysis.system_modes(_barge(**{
            "hydrodynamics": {"file": str(DATA / "barge_hydrodb.nc")}, "external forces": forces,
        }))  # fmt: skip
    kinds = list(found["state_space"]["method"].values)
    assert natural_periods.MEMORY_POLE in kinds and natural_periods.MEMORY_POLE not in list(
        found["convolution"]["method"].values
    )
    vessel = [k != natural_periods.MEMORY_POLE for k in kinds]
    np.testing.assert_allclose(
        found["state_space"]["period"].values[vessel],
        found["convolution"]["period"].values,
        rtol=1e-9,
    )
