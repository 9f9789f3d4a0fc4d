"""A real hull in coupled degrees of freedom, time domain against frequency domain (issue 16):
the shipped box barge (examples/data/barge_hydrodb.nc, Capytaine; 90 m x 24 m, draft 6 m) as a
six-degree-of-freedom ``rigid`` body with ``radiation damping`` (convolution), ``diffraction``
(the database's whole excitation, Froude-Krylov included) and linear restoring, in regular Airy
waves at steady state, against the RAO solved from the same database,

    xi = [C - w^2 (M + A(w)) - i w (B(w) + D)]^-1 X(w, b)      (6 x 6, e^{-i w t}),

at frequencies of the database's grid (so A, B and X are the database's own values, nothing
interpolated) below, at and above the resonances: heave 0.83 rad/s, pitch 0.91, roll 0.69.
Head seas (b = 180 deg: surge, heave, pitch), beam seas (90 deg: sway, heave, roll) and oblique
seas (150 deg: all six); the body's reference point at the database's origin (amidships, on the
waterline), and once 20 m forward of it on the keel (the database moved to the reference point,
its excitation's phase referred to the wave there: hulls.body_database).

The body and its restoring: the example's mass (rho times the displaced volume) and inertia,
its centre of gravity on the waterline; C the box's hydrostatics about the waterline (the
database carries none): rho g A_wp in heave, rho g (I_wp - V T / 2) in roll and pitch (GM 5 m);
surge, sway and yaw on soft springs (0.08 rad/s with the database's lowest-frequency added mass)
with half their critical damping, so that the body neither drifts nor rings for long; and a
viscous roll damper of 5 % of critical, D_44, without which the roll resonance (radiation damping
alone: 0.8 % of critical) would take over 1,000 s to settle; 300 s leave every transient
below 0.05 % of the response (200 s: 0.2 % at the roll resonance). The springs and dampers are
``linear_stiffness`` and ``linear_damping`` in the time domain, C and D in the frequency domain.

Criterion, per degree of freedom c, with s the largest |xi| of its kind (translations [m/m] or
rotations [rad/m]) at that frequency and heading:
- every c: |xi_td - xi_fd| <= 1 % of s (small coupled motions against the largest of their kind);
- a dominant c (|xi_fd| >= 30 % of s): |xi_td / xi_fd - 1| <= 1 % (amplitude within 1 % and
  phase within 0.01 rad).

Memory 60 s, not the default 25 s: with the default p = 3 tail the database's kernels are still
0.2 % of their peak at 25 s, 0.03 % at 60 s, and with 25 s the gap to the database's RAO grows
(pitch at 0.9 rad/s in head seas 0.42 -> 0.66 %, roll at 1.4 rad/s in beam seas 0.76 ->
1.8 %). What remains between the two domains is the database's own: the time domain uses B(w)
(through K) and one A_inf (Ogilvie's mean over the frequencies), so its added mass is A(w)
rebuilt from K, which differs from the database's A(w) by up to 1 % in heave (smoothly, -1.3 %
at 0.1 rad/s to +1.0 % at 1.6 rad/s, whatever the tail and the memory: the database's A33 and
B33 are not exactly Kramers-Kronig related), and by up to 2 % in surge, sway and yaw below
1.6 rad/s but 9 to 19 % at 1.8 rad/s (B cut where it is still large; the p = 3 tail stands for
the rest). This moves the heave RAO by up to 0.75 % (at 1.5 rad/s: A33 alone), and above
1.6 rad/s more than 1 %: pitch in head seas by 1.3 and 2.2 % at 1.7 and 1.8 rad/s (the
surge-pitch A15, A51), roll in beam seas by 2.5 % at 1.8 rad/s (the sway-roll A24, A42); there
the run is checked only against the time-domain model's own RAO. The runs' own error is checked
everywhere, tighter: against the RAO of the time-domain model itself (A rebuilt from K,
B = int K cos), within 0.1 % of s (measured: 0.03 %).

Wave amplitude 1 cm: at 10 cm the second-order mean sway on its soft spring (a few cm) shifts
the wave's phase at the body by k y (0.2 % in beam seas), which is not a first-order effect."""

import math
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable import hydrodb

DB = Path(__file__).resolve().parents[1] / "examples" / "data" / "barge_hydrodb.nc"
RHO, G = 1025.0, 9.81
LENGTH, BEAM, DRAFT = 90.0, 24.0, 6.0  # [m]
VOLUME = LENGTH * BEAM * DRAFT  # [m^3]
MASS = RHO * VOLUME  # [kg]
INERTIA = (9.4e8, 6.7e9, 7.3e9)  # about the centre of gravity [kg m^2] (the example's)
AMPLITUDE = 0.01  # [m]
MEMORY, STEP = 60.0, 0.05  # radiation memory and its sampling [s]
DURATION, WINDOW = 300.0, 60.0  # the run, and its last part fitted [s]
SLOW, SLOW_DAMPING, ROLL_DAMPING = 0.08, 0.5, 0.05  # [rad/s], parts of critical
DOMINANT, TOLERANCE, OWN_TOLERANCE = 0.3, 0.01, 0.001
COLUMNS = ("position_x", "position_y", "position_z", "roll", "pitch", "yaw")


def _mass() -> np.ndarray:
    return np.diag([MASS, MASS, MASS, *INERTIA])


def _restoring(db) -> tuple[np.ndarray, np.ndarray]:
    """(C, D) at the database's origin: the box's hydrostatics (no term of the weight's: the
    centre of gravity is on the waterline), soft springs and dampers in surge, sway and yaw,
    and the viscous roll damper."""
    stiffness, damping = np.zeros((6, 6)), np.zeros((6, 6))
    stiffness[2, 2] = RHO * G * LENGTH * BEAM
    stiffness[3, 3] = RHO * G * (LENGTH * BEAM**3 / 12.0 - VOLUME * DRAFT / 2.0)
    stiffness[4, 4] = RHO * G * (BEAM * LENGTH**3 / 12.0 - VOLUME * DRAFT / 2.0)
    inertia = _mass() + db.added_mass[0]
    for c in (0, 1, 5):
        stiffness[c, c] = SLOW**2 * inertia[c, c]
        damping[c, c] = 2.0 * SLOW_DAMPING * SLOW * inertia[c, c]
    damping[3, 3] = 2.0 * ROLL_DAMPING * math.sqrt(stiffness[3, 3] * inertia[3, 3])
    return stiffness, damping


def _transport(arm) -> np.ndarray:
    """H with nu_P = H nu_O for a point P at ``arm`` = P - O (body frame [m])."""
    h = np.eye(6)
    x, y, z = arm
    h[:3, 3:] = -np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return h


def _rao(omega, heading_deg, added, damping, db) -> np.ndarray:
    """xi (6) [m/m, rad/m] at the database's origin from the 6 x 6 frequency-domain equation."""
    i = int(np.flatnonzero(np.isclose(db.omega, omega))[0])
    j = int(np.flatnonzero(np.isclose(np.degrees(db.directions), heading_deg))[0])
    stiffness, extra = _restoring(db)
    impedance = stiffness - omega**2 * (_mass() + added) - 1j * omega * (damping + extra)
    return np.linalg.solve(impedance, db.excitation(froude_krylov=True)[i, j])


def _expected(omega, heading_deg, db) -> np.ndarray:
    """The RAO of the database's A(w), B(w), X(w, b)."""
    i = int(np.flatnonzero(np.isclose(db.omega, omega))[0])
    return _rao(omega, heading_deg, db.added_mass[i], db.damping[i], db)


def _own_model(omega, heading_deg, db) -> np.ndarray:
    """The RAO of what the time domain is given: K(t) (the default p = 3 tail) over MEMORY,
    A_inf by Ogilvie (its mean over the frequencies), so A(w) = A_inf - int K sin(w t) dt / w
    and B(w) = int K cos(w t) dt."""
    t = np.arange(int(round(MEMORY / STEP)) + 1) * STEP
    kernel = db.retardation(t, 3)
    infinite = db.ogilvie(t, tail_power=3)[0]
    added = infinite - np.trapezoid(kernel * np.sin(omega * t)[:, None, None], t, axis=0) / omega
    damping = np.trapezoid(kernel * np.cos(omega * t)[:, None, None], t, axis=0)
    return _rao(omega, heading_deg, added, damping, db)


def _case(omega, heading_deg, db, arm=(0.0, 0.0, 0.0)):
    """The barge with its reference point at ``arm`` from the database's origin (body frame
    [m]), that origin on the earth's origin; the matrices moved to the reference point
    (H^-T C H^-1)."""
    arm = np.asarray(arm, dtype=float)
    back = np.linalg.inv(_transport(arm))
    stiffness, damping = (back.T @ m @ back for m in _restoring(db))
    return seacable.load_case({
        "environment": {"waves": [{"kind": "airy", "height": 2 * AMPLITUDE,
                                   "period": 2 * math.pi / omega, "direction_deg": heading_deg}]},
        "bodies": [{"name": "barge", "type": "rigid", "position": arm.tolist(), "mass": MASS,
                    "inertia": list(INERTIA), "centre_of_gravity": (-arm).tolist(),
                    "hydrodynamics": {"file": str(DB), "position": (-arm).tolist()},
                    "external forces": [
                        {"model": "linear_stiffness", "matrix": stiffness.tolist()},
                        {"model": "linear_damping", "matrix": damping.tolist()},
                        {"model": "radiation damping", "memory": MEMORY, "memory_step": STEP},
                        {"model": "diffraction", "froude_krylov": True}]}],
        "start": "as_given",
        "simulation": {"duration": DURATION, "output_interval": 0.1, "integrator": "rk4",
                       "time_step": 0.05, "build_up": 20.0},
    })  # fmt: skip


def _measured(results, omega) -> np.ndarray:
    """The complex amplitude of each degree of freedom per metre of wave amplitude, fitted by
    least squares over the last WINDOW seconds (with a constant): x = Re(xi a e^{-i w t})."""
    t = results["time"].values
    keep = t > t[-1] - WINDOW
    basis = np.stack([np.cos(omega * t[keep]), np.sin(omega * t[keep]), np.ones(keep.sum())], 1)
    body = results["bodies/barge"]
    out = np.zeros(6, complex)
    for c, name in enumerate(COLUMNS):
        x = body[name].values[keep] * (math.pi / 180.0 if c >= 3 else 1.0)
        (cos, sin, _), *_ = np.linalg.lstsq(basis, x, rcond=None)
        out[c] = (cos + 1j * sin) / AMPLITUDE
    return out


def _errors(found, reference) -> tuple[np.ndarray, np.ndarray]:
    """(|found - reference| / s, |found / reference - 1|) per degree of freedom, s the largest
    |reference| of its kind (translations, rotations)."""
    scale = np.repeat([np.abs(reference[:3]).max(), np.abs(reference[3:]).max()], 3)
    return np.abs(found - reference) / scale, np.abs(found / reference - 1.0)


def _check(found, reference, tolerance, own=False):
    against_largest, relative = _errors(found, reference)
    scale = np.repeat([np.abs(reference[:3]).max(), np.abs(reference[3:]).max()], 3)
    dominant = np.abs(reference) >= DOMINANT * scale
    assert np.all(against_largest <= tolerance), (against_largest, found, reference)
    if not own:
        assert np.all(relative[dominant] <= tolerance), (relative, dominant, found, reference)


@pytest.fixture(scope="module")
def db():
    return hydrodb.read(DB)


# make test keeps the resonances (heave and pitch in head seas, roll in beam seas) and the
# oblique sea that moves all six; the frequencies around them are `slow` (make test-all)
LONG = pytest.mark.slow
CASES = [
    pytest.param(180.0, 0.5, marks=LONG), pytest.param(180.0, 0.85, marks=LONG), (180.0, 0.9),
    pytest.param(180.0, 1.2, marks=LONG), pytest.param(180.0, 1.5, marks=LONG),
    pytest.param(90.0, 0.5, marks=LONG), (90.0, 0.7), pytest.param(90.0, 0.8, marks=LONG),
    pytest.param(90.0, 1.0, marks=LONG), pytest.param(90.0, 1.2, marks=LONG),
    (150.0, 0.6), (150.0, 0.9), (150.0, 1.2),
]  # fmt: skip


@pytest.mark.parametrize(("heading", "omega"), CASES)
def test_regular_waves_give_the_databases_rao(db, heading, omega):
    """Every degree of freedom at steady state within 1 % of the largest of its kind, the
    dominant ones within 1 % of themselves, against the database's RAO; within 0.1 % of the
    largest against the RAO of the time-domain model's own A and B (module docstring)."""
    results = seacable.simulate(_case(omega, heading, db))
    assert results.complete
    found = _measured(results, omega)
    _check(found, _expected(omega, heading, db), TOLERANCE)
    _check(found, _own_model(omega, heading, db), OWN_TOLERANCE, own=True)


def test_a_reference_point_away_from_the_databases_origin(db):
    """The reference point 20 m forward of and 6 m below the database's origin (centre of
    gravity, database and matrices given from there): the hull moves as with the reference
    point at the origin, xi_P = H xi_O. The database's excitation refers to the wave's phase at
    its origin; taken at the reference point without moving that phase, every motion was off
    by e^{i k (20 m) cos b} (a phase of -82 deg here)."""
    arm = np.array([20.0, 0.0, -6.0])
    omega, heading = 0.9, 150.0
    results = seacable.simulate(_case(omega, heading, db, arm))
    assert results.complete
    h = _transport(arm)
    _check(_measured(results, omega), h @ _expected(omega, heading, db), TOLERANCE)


@pytest.mark.parametrize("heading", [180.0, 90.0])
def test_the_last_frequency_against_the_time_domain_models_own_rao(db, heading):
    """At 1.8 rad/s, the database's last frequency: within 0.1 % of the largest of its kind
    against the RAO of the A and B the time domain is given (A rebuilt from K by Ogilvie, B =
    int K cos). Against the database's own A, pitch in head seas is 2.2 % off and roll in beam
    seas 2.5 %, nearly all from the coupling added masses A15 and A24 rebuilt from a damping cut
    at 1.8 rad/s where it is still large (module docstring): a limit of the database, not of
    the run."""
    omega = 1.8
    results = seacable.simulate(_case(omega, heading, db))
    assert results.complete
    _check(_measured(results, omega), _own_model(omega, heading, db), OWN_TOLERANCE, own=True)
