"""A hydrodynamic database of one frequency (seacable hydrodb --omega W W 1): read, and used by a
case where one frequency makes sense, the wave excitation at it: a heaving body in a regular
wave at W settles on X / (C - W^2 (M + A_inf) - i W B_lin). Where it does not, one line naming
the file and what is needed: the radiation memory (at least two frequencies), Ogilvie's A_inf
(a database without A_inf), waves at other frequencies."""

import math

import numpy as np
import pytest
from click.testing import CliRunner

import seacable
from seacable import hydrodb
from seacable.cli import main
from seacable.errors import CaseError
from test_radiation import _steady

W0 = 0.8  # [rad/s]
MASS, STIFFNESS, DAMPING = 1.0e5, 2.0e5, 4.0e4  # heave [kg], [N/m], [N s/m]
A_INF = 3.0e4  # [kg]
X = 1.5e5 * (1.0 + 0.5j)  # heave excitation per metre of amplitude [N/m] (e^{-i w t})


def _database(path, infinite=True):
    diffraction = np.zeros((1, 1, 6), complex)
    diffraction[0, 0, 2] = X
    db = hydrodb.HydroDB(
        omega=np.array([W0]), added_mass=np.diag([1.0, 1.0, 4.0e4, 1.0, 1.0, 1.0])[None],
        damping=np.diag([0.0, 0.0, 2.0e4, 0.0, 0.0, 0.0])[None], directions=np.zeros(1),
        diffraction=diffraction, froude_krylov=np.zeros_like(diffraction),
        reference_point=np.zeros(3),
        infinite=np.diag([1.0, 1.0, A_INF, 1.0, 1.0, 1.0]) if infinite else None,
    )  # fmt: skip
    hydrodb.write(db, path)
    return db


def _case(path, omega=W0, forces=("diffraction",), added_mass=None):
    body = {"name": "buoy", "type": "rigid", "position": [0, 0, 0], "mass": MASS,
            "inertia": [1e5, 1e5, 1e5], "dofs": ["heave"], "hydrodynamics": {"file": str(path)},
            "external forces": [
                {"model": "linear_stiffness", "diagonal": [0, 0, STIFFNESS, 0, 0, 0]},
                {"model": "linear_damping", "diagonal": [0, 0, DAMPING, 0, 0, 0]},
                *({"model": f} for f in forces)]}  # fmt: skip
    if added_mass is not None:
        body["added_mass"] = added_mass
    return seacable.load_case({
        "environment": {"waves": [{"kind": "airy", "height": 1.0, "period": 2 * math.pi / omega}]},
        "bodies": [body], "start": "as_given",
        "simulation": {"duration": 100.0, "output_interval": 0.05, "integrator": "dopri5",
                       "rtol": 1e-9},
    })  # fmt: skip


def test_a_one_frequency_database_is_read_and_excites_a_body_at_its_frequency(tmp_path):
    """Read back as written (A_inf too); a heaving body in a regular wave of the database's
    period settles on the RAO of its excitation with A_inf and the linear damping, amplitude
    and phase within 1 %; a period rounded to 4 digits (7.854 s, 3e-5 off) is taken as it."""
    from seacable.system import model

    path = tmp_path / "one.nc"
    _database(path)
    db = hydrodb.read(path)
    assert db.omega.tolist() == [W0] and db.infinite[2, 2] == A_INF
    for omega in (W0, 2 * math.pi / 7.854):
        case = _case(path, omega=omega)
        assert model.build(case).params.body_added[0, 2, 2] == A_INF  # not estimated
        results = seacable.simulate(case)
        assert results.complete
        rao = X / (STIFFNESS - omega**2 * (MASS + A_INF) - 1j * omega * DAMPING)
        measured = _steady(results, omega) / 0.5
        assert abs(measured / rao - 1.0) < 0.01, (omega, measured, rao)


def test_what_one_frequency_cannot_give_is_refused_naming_the_file(tmp_path):
    """Waves at another frequency (their excitation would be zero), radiation memory (a
    retardation function needs the damping over frequencies), Ogilvie's A_inf (a database
    without one, a body without added mass): each one line with the file and the fix; a body
    that gives its added mass needs no A_inf."""
    from seacable.system import model

    path = tmp_path / "one.nc"
    _database(path)
    with pytest.raises(
        CaseError,
        match=r"'.*one.nc' holds one frequency, 0.8 rad/s \(period "
        r"7.853981634 s\), and the waves have components at 0.7 rad/s",
    ):
        model.build(_case(path, omega=0.7))
    with pytest.raises(
        CaseError,
        match=r"at least two, and hydrodynamic database '.*one.nc' "
        r"has one \(0.8 rad/s\)",
    ):
        model.build(_case(path, forces=("diffraction", "radiation damping")))
    bare = tmp_path / "bare.nc"
    _database(bare, infinite=False)
    with pytest.raises(
        CaseError,
        match=r"hydrodynamics.file: hydrodynamic database '.*bare.nc' "
        r"has no added mass at infinite frequency.*one frequency",
    ):
        model.build(_case(bare))
    built = model.build(_case(bare, added_mass=[0, 0, 2.5e4, 0, 0, 0]))
    assert built.params.body_added[0, 2, 2] == 2.5e4


@pytest.mark.parametrize("omega,expected", [
    (["0.8", "0.9", "1"], "one frequency is first = last (--omega 0.8 0.8 1)"),
    (["0.9", "0.8", "3"], "give first < last for 3 frequencies"),
    (["0.8", "0.8", "2"], "give first < last for 2 frequencies"),
])  # fmt: skip
def test_hydrodb_frequencies_that_are_no_range_are_refused_in_one_line(tmp_path, omega, expected):
    """A count of 1 with first < last used to drop the last frequency silently."""
    mesh = tmp_path / "hull.stl"
    mesh.write_text("solid x\nendsolid x\n")
    result = CliRunner().invoke(main, ["hydrodb", str(mesh), "--omega", *omega])
    assert result.exit_code == 2
    assert result.output.count("error:") == 1 and expected in result.output, result.output
