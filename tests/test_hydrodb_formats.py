"""WAMIT (.1/.3/.3sc/.3fk/.hst) and HDB (Diodore, AQUA+) databases read into seacable's
conventions (seacable.hydrodb_formats), checked against what we did not write:

- WAMIT: Capytaine's own WAMIT writer (tests/data/make_wamit.py) against the same BEM run
  written as our NetCDF, to export precision (six digits), and the Froude-Krylov heave force on
  the box against its closed form (the phase convention: the box is off the origin);
- HDB: a file written by the hand-derived rules (tests/data/make_hdb.py) read back, and its
  excitation against AQUA+'s time-domain formula as xdyn's documentation states it;
- a body in a case runs the same from the WAMIT files as from the NetCDF;
- malformed files give one line naming the file, the line and the fix.
"""

import math
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable import hydrodb
from seacable.errors import CaseError, HydroDBError

DATA = Path(__file__).parent / "data"
EXPORT = 5e-6  # six significant digits, against each array's largest value
KEPT = [0, 3, 6, 9, 12]  # box.hdb's frequencies among box.nc's


def _error(a, b) -> float:
    return float(np.abs(np.asarray(a) - np.asarray(b)).max() / np.abs(b).max())


def _t(m):
    return np.swapaxes(m, -1, -2)


@pytest.fixture(scope="module")
def reference():
    return hydrodb.read(DATA / "box.nc")


# ---- WAMIT ----------------------------------------------------------------------------------
def test_wamit_files_match_the_same_run_in_netcdf(reference):
    """Every array of box.1/.3sc/.3fk/.hst against box.nc to export precision. Capytaine 3.0's
    .1 writer puts the radiating mode in column I (the transpose of WAMIT's A_IJ, the force in
    mode I due to motion in mode J, WAMIT manual 3.2, which the reader follows): A and B are
    compared transposed; their symmetric parts agree either way."""
    db = hydrodb.read(DATA / "box.1")
    assert _error(db.omega, reference.omega) < 1e-6
    assert np.allclose(db.directions, reference.directions)
    for ours, theirs in ((db.added_mass, reference.added_mass), (db.damping, reference.damping),
                         (db.infinite, reference.infinite)):  # fmt: skip
        assert _error(ours, _t(theirs)) < EXPORT
        assert _error(ours + _t(ours), theirs + _t(theirs)) < EXPORT
    assert _error(db.diffraction, reference.diffraction) < EXPORT
    assert _error(db.froude_krylov, reference.froude_krylov) < EXPORT
    assert _error(db.hydrostatic_stiffness, reference.hydrostatic_stiffness) < EXPORT
    assert db.excitation_total is None  # the parts are known: .3 is their sum
    # the test can fail: WAMIT's phase taken as ours would be off by far more
    assert _error(np.conj(db.diffraction), reference.diffraction) > 0.1


def test_wamit_froude_krylov_heave_against_the_closed_form():
    """Deep water, a box of length L, beam B, draft T centred at (xc, yc): the incident pressure
    on its bottom gives F3 = rho g a e^{-kT} L B sinc(k L cos b / 2) sinc(k B sin b / 2)
    e^{i k (xc cos b + yc sin b)} (e^{-i w t}): WAMIT's conjugated phase checked by physics."""
    db = hydrodb.read(DATA / "box.1")
    length, beam, draft, xc, yc = 2.0, 1.2, 0.5, 0.6, 0.25
    k = db.omega**2 / db.gravity
    for m, b in enumerate(db.directions):
        u, v = k * length * math.cos(b) / 2, k * beam * math.sin(b) / 2
        exact = (
            db.rho
            * db.gravity
            * np.exp(-k * draft)
            * length
            * beam
            * np.sinc(u / math.pi)
            * np.sinc(v / math.pi)
            * np.exp(1j * k * (xc * math.cos(b) + yc * math.sin(b)))
        )
        assert _error(db.froude_krylov[:, m, 2], exact) < 0.005, np.degrees(b)  # fmt: skip


def test_wamit_read_from_the_stem_or_any_of_its_files(reference):
    by_stem = hydrodb.read(DATA / "box")
    by_three = hydrodb.read(DATA / "box.3")
    assert np.array_equal(by_stem.added_mass, by_three.added_mass)
    assert np.array_equal(by_stem.diffraction, by_three.diffraction)


def test_wamit_total_excitation_alone(tmp_path, reference):
    """Only .1 and .3: the total (FK included) serves froude_krylov: true and is refused
    without it."""
    for suffix in (".1", ".3"):
        shutil.copy(DATA / f"box{suffix}", tmp_path / f"box{suffix}")
    db = hydrodb.read(tmp_path / "box.1")
    assert db.diffraction is None and db.froude_krylov is None and db.hydrostatic_stiffness is None
    total = reference.diffraction + reference.froude_krylov
    assert _error(db.excitation(froude_krylov=True), total) < EXPORT
    with pytest.raises(HydroDBError, match="only the total excitation.*froude_krylov: true"):
        db.excitation(froude_krylov=False)
    moved = db.moved((1.0, 0.0, 0.0))
    assert moved.excitation_total is not None and moved.diffraction is None
    path = tmp_path / "total.nc"
    hydrodb.write(db, path)
    assert _error(hydrodb.read(path).excitation(True), db.excitation(True)) < 1e-15


def test_wamit_length_scale(reference):
    """The same run nondimensionalised with ULEN = 2 m reads back with length_scale=2; read with
    ULEN = 1 it is off by L^k (k = 3 for surge-surge)."""
    db = hydrodb.read(DATA / "box_ulen2.1", length_scale=2.0)
    assert _error(db.added_mass, _t(reference.added_mass)) < EXPORT
    assert _error(db.damping, _t(reference.damping)) < EXPORT
    assert _error(db.excitation(True), reference.excitation(True)) < EXPORT
    wrong = hydrodb.read(DATA / "box_ulen2.1")
    assert wrong.added_mass[0, 0, 0] == pytest.approx(db.added_mass[0, 0, 0] / 8, rel=1e-12)
    assert wrong.added_mass[0, 4, 4] == pytest.approx(db.added_mass[0, 4, 4] / 32, rel=1e-12)


def test_wamit_density_scales_everything():
    light = hydrodb.read(DATA / "box.1", rho=1000.0)
    heavy = hydrodb.read(DATA / "box.1", rho=1025.0)
    assert np.allclose(light.added_mass * 1.025, heavy.added_mass, rtol=1e-12, atol=0)
    assert np.allclose(light.diffraction * 1.025, heavy.diffraction, rtol=1e-12, atol=0)


@pytest.mark.parametrize("suffix, text, message", [
    (".1", "1.0 1 1 2.0\n", r"box\.1', line 1: period 1 s without its damping"),
    (".1", "1.0 1 1 2.0 x3\n", r"box\.1', line 1: 'x3' is not a number"),
    (".1", "1.0 7 1 2.0 3.0\n", r"line 1: mode 7; one body's six rigid-body modes"),
    (".1", "1.0 1 1\n", r"line 1: 3 columns where WAMIT writes 4 or 5"),
    (".1", "-1.0 1 1 2.0\n", r"has no finite period"),
    (".3", "2.0 0.0 1 1 0 1 0\n", r"box\.3': periods \[2\] s, not those of the \.1 file"),
])  # fmt: skip
def test_wamit_malformed(tmp_path, suffix, text, message):
    shutil.copy(DATA / "box.1", tmp_path / "box.1")
    shutil.copy(DATA / "box.3", tmp_path / "box.3")
    (tmp_path / f"box{suffix}").write_text(text)
    with pytest.raises(HydroDBError, match=message):
        hydrodb.read(tmp_path / "box.1")


def test_wamit_without_excitation(tmp_path):
    shutil.copy(DATA / "box.1", tmp_path / "box.1")
    with pytest.raises(HydroDBError, match=r"no excitation beside 'box\.1' \(box\.3, or"):
        hydrodb.read(tmp_path / "box")


def test_unknown_files(tmp_path):
    with pytest.raises(HydroDBError, match="does not exist; check the path"):
        hydrodb.read(tmp_path / "nothing.hdb")
    (tmp_path / "hull.xyz").write_text("1 2 3\n")
    with pytest.raises(HydroDBError, match=r"format '\.xyz' is not known; give Capytaine's"):
        hydrodb.read(tmp_path / "hull.xyz")


# ---- HDB ------------------------------------------------------------------------------------
def test_hdb_reads_back_the_database_it_was_written_from(reference):
    db = hydrodb.read(DATA / "box.hdb")
    assert _error(db.omega, reference.omega[KEPT]) < 1e-6
    assert np.allclose(db.directions, reference.directions)
    for ours, theirs in ((db.added_mass, reference.added_mass), (db.damping, reference.damping),
                         (db.diffraction, reference.diffraction),
                         (db.froude_krylov, reference.froude_krylov)):  # fmt: skip
        assert _error(ours, theirs[KEPT]) < EXPORT
    assert _error(db.hydrostatic_stiffness, reference.hydrostatic_stiffness) < EXPORT
    assert db.infinite is None and db.excitation_total is None


def _blocks(text: str, name: str) -> dict[float, np.ndarray]:
    """The file's own numbers, read without the reader: heading -> (periods, 7) table."""
    out = {}
    for match in re.finditer(rf"\[{name}\]\s+(\S+)\n((?:\s+[-\d.E+]+(?:\s+[-\d.E+]+){{6}}\n)+)",
                             text):  # fmt: skip
        out[float(match.group(1))] = np.loadtxt(match.group(2).splitlines())
    return out


def test_hdb_excitation_against_aqua_plus_formula():
    """xdyn's documentation of AQUA+: eta = -a sin(k x - w t + p), F = -|X| a sin(k x - w t + p
    - phi). Our force Re(X a e^{i (k x - w t + p')}) for the same wave (p' = p + pi/2) must be
    the same function of time, for every period, heading and mode."""
    text = (DATA / "box.hdb").read_text()
    section = text[text.index("[FROUDE-KRYLOV") :]
    modulus, phase = (
        _blocks(section, "INCIDENCE_EFM_MOD_001"),
        _blocks(section, "INCIDENCE_EFM_PH_001"),
    )
    db = hydrodb.read(DATA / "box.hdb")
    t = np.linspace(0.0, 20.0, 201)
    a, p = 0.7, 0.4
    for m, heading in enumerate(np.degrees(db.directions)):
        for n, period in enumerate(modulus[heading][:, 0]):
            w = 2 * math.pi / period
            k = db.omega.tolist().index(db.omega[np.argmin(abs(db.omega - w))])
            for c in range(6):
                size, phi = modulus[heading][n, c + 1], phase[heading][n, c + 1]
                theirs = -size * a * np.sin(-w * t + p - phi)
                ours = np.real(db.froude_krylov[k, m, c] * a * np.exp(1j * (-w * t + p + math.pi
                                                                              / 2)))  # fmt: skip
                assert np.abs(ours - theirs).max() <= 1e-6 * max(size * a, 1e-9)


def test_hdb_phases_in_degrees(tmp_path):
    """Degrees refused as radians, read with phase_unit deg."""
    text = (DATA / "box.hdb").read_text()
    lines = text.splitlines()
    out, in_phase = [], False
    for line in lines:
        if line.strip().startswith("["):
            in_phase = "_PH_" in line
        elif in_phase:
            values = line.split()
            line = "  " + values[0] + "".join(f"  {math.degrees(float(v)): .9E}"
                                              for v in values[1:])  # fmt: skip
        out.append(line)
    path = tmp_path / "deg.hdb"
    path.write_text("\n".join(out))
    with pytest.raises(HydroDBError, match=r"deg\.hdb', line \d+: phases up to .* in degrees"):
        hydrodb.read(path)
    deg = hydrodb.read(path, phase_unit="deg")
    assert _error(deg.diffraction, hydrodb.read(DATA / "box.hdb").diffraction) < 1e-8


def _edited(tmp_path, old, new, count=1) -> Path:
    text = (DATA / "box.hdb").read_text()
    assert old in text
    path = tmp_path / "bad.hdb"
    path.write_text(text.replace(old, new, count))
    return path


def _line_of(text: str, needle: str) -> int:
    return text[: text.index(needle)].count("\n") + 1


def test_hdb_malformed(tmp_path):
    text = (DATA / "box.hdb").read_text()
    start = text.index(" [ADDED_MASS_LINE_3]")
    end = text.index(" [ADDED_MASS_LINE_4]")
    with pytest.raises(HydroDBError, match=r"bad\.hdb': no \[ADDED_MASS_LINE_3\] section"):
        hydrodb.read(_edited(tmp_path, text[start:end], ""))
    row = text[start:end].splitlines()[1]
    number = _line_of(text, row)
    broken = row.replace("E", "Q", 1)
    with pytest.raises(HydroDBError, match=rf"bad\.hdb', line {number}: '.*Q.*' is not a number"):
        hydrodb.read(_edited(tmp_path, row, broken))
    with pytest.raises(HydroDBError, match=rf"line {number}: 6 values under \[ADDED_MASS_LINE_3\]"):
        hydrodb.read(_edited(tmp_path, row, row.rsplit(maxsplit=1)[0]))
    with pytest.raises(HydroDBError, match=r"\[PERIODS_NUMBER\] says 6 but"):
        hydrodb.read(_edited(tmp_path, "[PERIODS_NUMBER]  5", "[PERIODS_NUMBER]  6"))
    with pytest.raises(HydroDBError, match=r"line 2: forward speed 3.00; only .* zero speed"):
        hydrodb.read(_edited(tmp_path, "[FORWARD_SPEED]   0.00", "[FORWARD_SPEED]   3.00"))
    with pytest.raises(HydroDBError, match=r"no \[List_calculated_headings\] section"):
        hydrodb.read(_edited(tmp_path, "[List_calculated_headings]", "[Headings]"))
    with pytest.raises(HydroDBError, match=r"no excitation forces"):
        hydrodb.read(_edited(tmp_path, "INCIDENCE_EFM", "INCIDENCE_XFM", count=-1))
    with pytest.raises(HydroDBError, match=r"no \[INCIDENCE_EFM_PH_...\] 90 block"):
        hydrodb.read(_edited(tmp_path, "[INCIDENCE_EFM_PH_001]   90.000000",
                             "[INCIDENCE_EFM_PH_001]   80.000000"))  # fmt: skip


def test_hdb_total_excitation_section(tmp_path, reference):
    """An EXCITATION section (the sum) with a FROUDE-KRYLOV one gives the diffraction part."""
    path = _edited(tmp_path, "[DIFFRACTION_FORCES_AND_MOMENTS]", "[EXCITATION_FORCES_AND_MOMENTS]")
    db = hydrodb.read(path)
    # the file's diffraction numbers now read as the total: diffraction = them - FK
    assert _error(db.diffraction + db.froude_krylov, reference.diffraction[KEPT]) < EXPORT


def test_hdb_parts_missing_and_damping_names(tmp_path, reference):
    """xdyn's name variants are read alike; a file with Froude-Krylov forces only (as xdyn's
    test ship's) cannot give the diffraction part, and says so."""
    same = hydrodb.read(_edited(tmp_path, "[DAMPING_TERM_", "[DAMPING_TERMS_LINE_", count=-1))
    assert np.array_equal(same.damping, hydrodb.read(DATA / "box.hdb").damping)
    text = (DATA / "box.hdb").read_text()
    start = text.index(" [DIFFRACTION_FORCES_AND_MOMENTS]")
    end = text.index(" [FROUDE-KRYLOV_FORCES_AND_MOMENTS]")
    db = hydrodb.read(_edited(tmp_path, text[start:end], ""))
    assert _error(db.froude_krylov, reference.froude_krylov[KEPT]) < EXPORT
    for froude_krylov in (True, False):
        with pytest.raises(HydroDBError, match="has no diffraction forces .Froude-Krylov only"):
            db.excitation(froude_krylov)


# ---- in a case --------------------------------------------------------------------------------
def _case(path, **hydrodynamics):
    return seacable.load_case({
        "environment": {"waves": [{"kind": "airy", "height": 0.4, "period": 2 * math.pi / 2.2,
                                   "direction_deg": 45.0}]},
        "bodies": [{"name": "box", "type": "rigid", "position": [0, 0, 0], "mass": 1230.0,
                    "inertia": [200.0, 400.0, 500.0], "dofs": ["heave"],
                    "hydrodynamics": {"file": str(path), **hydrodynamics},
                    "external forces": [
                        {"model": "linear_stiffness", "diagonal": [0, 0, 24132.6, 0, 0, 0]},
                        {"model": "radiation damping", "memory": 8.0, "memory_step": 0.05},
                        {"model": "diffraction", "froude_krylov": True}]}],
        "start": "as_given",
        "simulation": {"duration": 12.0, "output_interval": 0.1, "integrator": "rk4",
                       "time_step": 0.01},
    })  # fmt: skip


def test_a_body_runs_the_same_from_wamit_files_as_from_netcdf(tmp_path, caplog):
    """The box heaving in a regular wave at 45 deg: its motion from box.1 (with .3sc and .3fk)
    as from box.nc, to export precision; the HDB file as the NetCDF written from it."""
    z = {}
    for name, path in (("nc", DATA / "box.nc"), ("wamit", DATA / "box.1")):
        z[name] = seacable.simulate(_case(path))["bodies/box"]["position_z"].values
    assert np.abs(z["nc"]).max() > 0.05  # it moves
    assert _error(z["wamit"], z["nc"]) < 5e-6
    hdb = tmp_path / "box.nc"
    hydrodb.write(hydrodb.read(DATA / "box.hdb"), hdb)
    from_hdb = seacable.simulate(_case(DATA / "box.hdb"))["bodies/box"]["position_z"].values
    from_nc = seacable.simulate(_case(hdb))["bodies/box"]["position_z"].values
    assert _error(from_hdb, from_nc) < 1e-12


def test_a_case_refuses_a_bad_database_with_its_field(tmp_path):
    for suffix in (".1", ".3"):
        shutil.copy(DATA / f"box{suffix}", tmp_path / f"box{suffix}")
    case = _case(tmp_path / "box.1")
    spec = case.bodies[0].external_forces[2]
    case = case.model_copy(update={"bodies": [case.bodies[0].model_copy(update={
        "external_forces": [*case.bodies[0].external_forces[:2],
                            spec.model_copy(update={"froude_krylov": False})]})]})  # fmt: skip
    with pytest.raises(CaseError, match=r"box.*only the total excitation"):
        seacable.simulate(case)
