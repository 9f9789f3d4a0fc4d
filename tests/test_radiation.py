"""Radiation memory and database excitation in the time domain (forces.radiation,
forces.diffraction, kernels.memory) against the frequency domain: a floating body in regular
waves settles on the response its database's RAO predicts, across frequencies and through
resonance; the history depends on accepted steps only."""

import math

import numpy as np
import pytest

import seacable
from seacable import hydrodb
from test_hydrodb import _added, _damping

MASS, STIFFNESS = 1.0e5, 2.0e5  # heave [kg], [N/m]
SCALE33 = 2.8e4  # K_33(t) = SCALE33 e^{-alpha t} cos(beta t)
A_INF = 3.0e4  # [kg]


def _excitation(omega):
    """A smooth heave excitation per metre of amplitude [N/m] (complex, e^{-i w t})."""
    return 2.0e5 * np.exp(-0.3 * omega**2) * (1.0 + 0.4j * omega)


def _database(path):
    omega = np.linspace(0.02, 30.0, 3000)
    scale = np.zeros((6, 6))
    scale[2, 2] = SCALE33
    infinite = np.diag([1.0, 1.0, A_INF, 1.0, 1.0, 1.0])
    diffraction = np.zeros((len(omega), 1, 6), complex)
    diffraction[:, 0, 2] = _excitation(omega)
    db = hydrodb.HydroDB(
        omega=omega, added_mass=infinite + _added(omega)[:, None, None] * scale,
        damping=_damping(omega)[:, None, None] * scale, directions=np.zeros(1),
        diffraction=diffraction, froude_krylov=np.zeros_like(diffraction),
        reference_point=np.zeros(3), infinite=infinite,
    )  # fmt: skip
    hydrodb.write(db, path)
    return db


def _case(path, omega, amplitude=0.5, integrator="dopri5", duration=160.0):
    return seacable.load_case({
        "environment": {"waves": [{"kind": "airy", "height": 2 * amplitude,
                                   "period": 2 * math.pi / omega}]},
        "bodies": [{"name": "buoy", "type": "rigid", "position": [0, 0, 0], "mass": MASS,
                    "inertia": [1e5, 1e5, 1e5], "dofs": ["heave"],
                    "hydrodynamics": {"file": str(path)},
                    "external forces": [
                        {"model": "linear_stiffness", "diagonal": [0, 0, STIFFNESS, 0, 0, 0]},
                        {"model": "radiation damping"}, {"model": "diffraction"}]}],
        "start": "as_given",
        "simulation": {"duration": duration, "output_interval": 0.05, "integrator": integrator,
                       "rtol": 1e-9, "time_step": 0.01},
    })  # fmt: skip


def _steady(results, omega):
    """Complex amplitude of the heave at omega over the last 40 s (least squares)."""
    t = results["time"].values
    z = results["bodies/buoy"]["position_z"].values
    keep = t > t[-1] - 40.0
    basis = np.stack([np.cos(omega * t[keep]), np.sin(omega * t[keep]), np.ones(keep.sum())], 1)
    (c, s, _), *_ = np.linalg.lstsq(basis, z[keep], rcond=None)
    return c + 1j * s  # z = Re((c + i s) e^{-i w t})


@pytest.mark.parametrize("omega", [0.6, 1.0, 1.15, 1.3, 2.0])
def test_regular_waves_give_the_databases_rao(tmp_path, omega):
    """Heave in regular waves at steady state against X / (C - w^2 (M + A(w)) - i w B(w)),
    amplitude and phase within 1 %, below, at and above resonance (near 1.15 rad/s)."""
    path = tmp_path / "db.nc"
    db = _database(path)
    results = seacable.simulate(_case(path, omega))
    assert results.complete
    a = float(np.interp(omega, db.omega, db.added_mass[:, 2, 2]))
    b = float(np.interp(omega, db.omega, db.damping[:, 2, 2]))
    rao = _excitation(omega) / (STIFFNESS - omega**2 * (MASS + a) - 1j * omega * b)
    measured = _steady(results, omega) / 0.5
    assert abs(measured / rao - 1.0) < 0.01, (measured, rao)


def test_memory_does_not_depend_on_the_chunks(tmp_path):
    """The history is written after accepted steps only: runs cut into chunks of 1 output
    and of all outputs give the same file, bit for bit, with rk4 and dopri5."""
    path = tmp_path / "db.nc"
    _database(path)
    for integrator in ("rk4", "dopri5"):
        case = _case(path, 1.0, integrator=integrator, duration=5.0)
        one = seacable.simulate(case, chunk_outputs=1)
        whole = seacable.simulate(case, chunk_outputs=1000)
        z1 = one["bodies/buoy"]["position_z"].values
        z2 = whole["bodies/buoy"]["position_z"].values
        assert np.array_equal(z1, z2)
        assert np.abs(z1).max() > 0.01


def test_the_infinite_added_mass_comes_from_the_database(tmp_path):
    """A body without added mass takes the database's A_inf; without A_inf in the database,
    Ogilvie's estimate (here within 1 % of the true value)."""
    from seacable.system import model

    path = tmp_path / "db.nc"
    db = _database(path)
    built = model.build(_case(path, 1.0))
    assert built.params.body_added[0, 2, 2] == pytest.approx(A_INF)
    hydrodb.write(hydrodb.HydroDB(**{**db.__dict__, "infinite": None}), path)
    built = model.build(_case(path, 1.0))
    assert built.params.body_added[0, 2, 2] == pytest.approx(A_INF, rel=1e-2)


def test_a_short_memory_is_reported_and_cvode_refused(tmp_path, caplog):
    """A kernel cut while still above 1 % of its peak is reported with the fix; SUNDIALS
    (whose steps are its own) is refused for radiation memory."""
    from seacable.errors import CaseError
    from seacable.system import model

    path = tmp_path / "db.nc"
    _database(path)
    case = _case(path, 1.0)
    forces = list(case.bodies[0].external_forces)
    forces[1] = forces[1].model_copy(update={"memory": 3.0})
    short = case.model_copy(update={"bodies": [case.bodies[0].model_copy(
        update={"external_forces": forces})]})  # fmt: skip
    with caplog.at_level("WARNING", logger="seacable"):
        model.build(short)
    assert "still" in caplog.text and "lengthen 'memory'" in caplog.text
    with pytest.raises(CaseError, match="SUNDIALS"):
        model.build(_case(path, 1.0, integrator="cvode"))


def test_waves_outside_the_databases_frequencies_are_said_at_build(tmp_path, caplog):
    """A wave beyond the database's frequencies (0.02 to 30 rad/s here) gets no excitation:
    before, silently; now the build says so, naming the file, its range and the share of the
    waves' energy. A wave inside says nothing."""
    from seacable.system import model

    path = tmp_path / "db.nc"
    _database(path)
    with caplog.at_level("WARNING", logger="seacable"):
        model.build(_case(path, 1.0))
    assert "get no excitation" not in caplog.text
    with caplog.at_level("WARNING", logger="seacable"):
        model.build(_case(path, 40.0, amplitude=0.01))
    assert f"database '{path}' covers 0.02 to 30 rad/s" in caplog.text
    assert "1 of the 1 wave components (100.0 % of the waves' energy" in caplog.text
