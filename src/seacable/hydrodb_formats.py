"""Readers of hydrodynamic databases in WAMIT's and the HDB (Diodore, AQUA+) text formats, each
turned into seacable's conventions (seacable.hydrodb: angular frequency [rad/s], z up, e^{-i w t},
B itself, matrices [force, motion], excitation per metre of amplitude for waves travelling
towards the heading, from +x towards +y). They return the fields of a ``hydrodb.HydroDB``
(``hydrodb.read`` builds it); every refusal is one line naming the file, the line and the fix.

WAMIT (``stem.1``, ``stem.3``, ``stem.3sc``, ``stem.3fk``, ``stem.hst``; WAMIT User Manual,
chapters 3 and 5):

- the first column is the period [s] (WAMIT's default output, IPEROUT = 1); in ``.1`` the period
  0 is the infinite frequency (A only: ``infinite``) and -1 the zero frequency (A only: not kept);
- values are nondimensional with the density rho, gravity g and WAMIT's length ULEN
  (``length_scale`` [m], 1 unless the run said otherwise): A_ij = Abar rho L^k,
  B_ij = Bbar rho L^k w, with k = 3, 4 or 5 for 0, 1 or 2 rotational indices among i, j;
  X_i = Xbar rho g L^m (per metre of amplitude), m = 2 for a force, 3 for a moment;
  C_ij = Cbar rho g L^k, k = 2, 3 or 4;
- ``.1``: PER I J Abar Bbar, A_ij the force in mode i due to motion in mode j (ours);
  ``.3`` (the whole excitation), ``.3sc`` (scattering: our diffraction), ``.3fk``
  (Froude-Krylov): PER BETA I |X| phase Re Im, BETA [deg] the direction the waves travel to,
  from +x towards +y (ours);
- WAMIT's time dependence is e^{+i w t}: the wave eta = Re(A e^{i w t}) at the origin gives
  F = Re(A X_W e^{i w t}). Ours is e^{-i w t}: F = Re(A conj(X_W) e^{-i w t}), so X = conj(X_W)
  (from Re and Im; the same for the radiation matrices, which are real);
- the body frame of WAMIT's run is z up; matrices and forces are about its origin, the
  database's reference point (0, 0, 0), moved by the case's ``hydrodynamics.position``.

HDB (the text format of Diodore and AQUA+; grammar learned from public readers, its conventions
from xdyn's documentation, which assumes AQUA+'s because the file states none):

- ``[KEY] value`` lines, ``[List_calculated_periods]`` [s] and ``[List_calculated_headings]``
  [deg] one value a line, 6x6 matrices as six rows (``[Hydrostatic_matrix]``), and per period
  rows ``T v1 .. v6``: ``[ADDED_MASS_LINE_i]`` (row i of A [kg, kg m, kg m^2]),
  ``[DAMPING_TERM_i]`` (row i of B itself [N s/m, ...]), and under
  ``[DIFFRACTION_FORCES_AND_MOMENTS]``, ``[FROUDE-KRYLOV_FORCES_AND_MOMENTS]`` or
  ``[EXCITATION_FORCES_AND_MOMENTS]`` (the sum) the blocks ``[INCIDENCE_EFM_MOD_nnn] heading``
  and ``[INCIDENCE_EFM_PH_nnn] heading`` (Diodore's detailed ``INCIDENCE_EFM_DIFF_*`` and
  ``INCIDENCE_EFM_FFK_*`` too): modulus [N/m, N m/m] and phase by period, heading [deg] read
  from the block's header;
- frame: x forward, y to port, z up (AQUA+'s, ours); headings are the direction the waves
  travel to, 0 from stern to bow, 90 towards port (ours);
- phase: AQUA+ writes a wave eta = -a sin(k (x cos b + y sin b) - w t + p) and its force
  F = -|X| a sin(k (x cos b + y sin b) - w t + p - phi). With ours eta = a cos(theta),
  theta = k (...) - w t + p + pi/2, that force is |X| a cos(theta - phi) = Re(|X| e^{-i phi}
  a e^{i theta}): X = |X| e^{-i phi};
- phases in radians (AQUA+'s files, as xdyn reads them) unless ``phase_unit`` is "deg" (some
  writers use degrees): a phase beyond pi in radians is refused as degrees in disguise;
- the file does not say where its matrices and forces are expressed: the database's reference
  point (0, 0, 0), moved by the case's ``hydrodynamics.position``; no A_inf (Ogilvie's relation
  gives it); forward speed 0 only; one structure only.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from seacable import files
from seacable.errors import HydroDBError

WAMIT_SUFFIXES = (".1", ".3", ".3sc", ".3fk", ".hst")
_LIMIT = 50_000_000  # [bytes] larger text is not a database


# ---- shared -------------------------------------------------------------------------------------
def _lines(path: Path) -> list[str]:
    return files.read_text(path, "hydrodynamic database", _LIMIT, HydroDBError,
                           fix="give the file as the solver wrote it").splitlines()  # fmt: skip


def _numbers(path: Path, number: int, words: list[str]) -> list[float]:
    try:
        values = [float(w.replace("D", "E").replace("d", "e")) for w in words]
    except ValueError:
        bad = next(w for w in words if not _is_number(w))
        raise HydroDBError(
            f"hydrodynamic database '{path}', line {number}: '{bad[:30]}' is not a number; "
            "correct that line"
        ) from None
    if not all(math.isfinite(v) for v in values):
        raise HydroDBError(f"hydrodynamic database '{path}', line {number}: a value is not "
                           "finite (NaN or infinity); correct that line")  # fmt: skip
    return values


def _is_number(word: str) -> bool:
    try:
        float(word.replace("D", "E").replace("d", "e"))
    except ValueError:
        return False
    return True


def _rotational(*indices: int) -> int:
    """How many of the 0-based mode indices are rotations."""
    return sum(1 for i in indices if i >= 3)


# ---- WAMIT --------------------------------------------------------------------------------------
def wamit_stem(path: Path) -> Path | None:
    """The stem of a WAMIT run from its ``.1`` (or another of its files, or the stem itself),
    None when ``path`` is none of those."""
    if path.suffix.lower() in WAMIT_SUFFIXES:
        return path.with_suffix("")
    if Path(f"{path}.1").exists():
        return path
    return None


def _wamit_rows(path: Path, columns: tuple[int, ...]) -> list[tuple[int, list[float]]]:
    rows = []
    for number, line in enumerate(_lines(path), start=1):
        words = line.split()
        if not words:
            continue
        values = _numbers(path, number, words)
        if len(values) not in columns:
            raise HydroDBError(
                f"hydrodynamic database '{path}', line {number}: {len(values)} columns where "
                f"WAMIT writes {' or '.join(map(str, columns))}; give the file as WAMIT wrote it"
            )
        rows.append((number, values))
    if not rows:
        raise HydroDBError(f"hydrodynamic database '{path}' holds no values; run WAMIT again")
    return rows


def _mode(path: Path, number: int, value: float) -> int:
    if value != int(value) or not 1 <= value <= 6:
        raise HydroDBError(
            f"hydrodynamic database '{path}', line {number}: mode {value:g}; one body's six "
            "rigid-body modes (1 to 6) are read, not several bodies or generalized modes"
        )
    return int(value) - 1


def _wamit_radiation(path: Path, rho: float, length: float):
    """omega [rad/s] (increasing), A, B (n, 6, 6) and A_inf or None from a ``.1`` file."""
    added: dict[float, np.ndarray] = {}
    damping: dict[float, np.ndarray] = {}
    infinite = None
    for number, row in _wamit_rows(path, (4, 5)):
        period = row[0]
        i, j = _mode(path, number, row[1]), _mode(path, number, row[2])
        scale = rho * length ** (3 + _rotational(i, j))
        if period == 0.0:  # WAMIT: zero period, infinite frequency
            infinite = np.zeros((6, 6)) if infinite is None else infinite
            infinite[i, j] = row[3] * scale
            continue
        if period < 0.0:  # WAMIT: -1, infinite period, zero frequency: not kept
            continue
        if len(row) != 5:
            raise HydroDBError(
                f"hydrodynamic database '{path}', line {number}: period {period:g} s without "
                "its damping (PER I J A B expected); give the file as WAMIT wrote it"
            )
        omega = 2.0 * math.pi / period
        added.setdefault(period, np.zeros((6, 6)))[i, j] = row[3] * scale
        damping.setdefault(period, np.zeros((6, 6)))[i, j] = row[4] * scale * omega
    if not added:
        raise HydroDBError(f"hydrodynamic database '{path}' has no finite period; run WAMIT "
                           "with wave periods")  # fmt: skip
    periods = sorted(added, reverse=True)  # increasing frequency
    frequencies = 2.0 * math.pi / np.array(periods)
    return (periods, frequencies, np.array([added[p] for p in periods]),
            np.array([damping[p] for p in periods]), infinite)  # fmt: skip


def _wamit_excitation(path: Path, periods: list[float], rho: float, gravity: float,
                      length: float):  # fmt: skip
    """(headings [rad] increasing, X (n, m, 6) complex in our convention) from a .3-like file
    whose periods must be those of the .1 file."""
    values: dict[tuple[float, float], np.ndarray] = {}
    for number, row in _wamit_rows(path, (7,)):
        period, heading = row[0], row[1]
        i = _mode(path, number, row[2])
        scale = rho * gravity * length ** (2 + _rotational(i))
        # WAMIT's e^{+i w t} to our e^{-i w t}: the complex conjugate
        values.setdefault((period, heading), np.zeros(6, complex))[i] = (
            complex(row[5], -row[6]) * scale)  # fmt: skip
    headings = sorted({h for _, h in values})
    found = sorted({p for p, _ in values}, reverse=True)
    if len(found) != len(periods) or not np.allclose(found, periods, rtol=1e-5, atol=0.0):
        raise HydroDBError(
            f"hydrodynamic database '{path}': periods {_short(found)} s, not those of the .1 "
            f"file {_short(periods)} s; give both files of the same WAMIT run"
        )
    out = np.zeros((len(found), len(headings), 6), complex)
    for k, p in enumerate(found):
        for m, h in enumerate(headings):
            if (p, h) not in values:
                raise HydroDBError(
                    f"hydrodynamic database '{path}': no line for period {p:g} s and heading "
                    f"{h:g} deg; give the whole table WAMIT wrote"
                )
            out[k, m] = values[(p, h)]
    return np.radians(headings), out


def _short(values) -> str:
    text = ", ".join(f"{v:g}" for v in values[:6])
    return f"[{text}{', ...' if len(values) > 6 else ''}]"


def _wamit_stiffness(path: Path, rho: float, gravity: float, length: float) -> np.ndarray:
    c = np.zeros((6, 6))
    for number, row in _wamit_rows(path, (3,)):
        i, j = _mode(path, number, row[0]), _mode(path, number, row[1])
        c[i, j] = row[2] * rho * gravity * length ** (2 + _rotational(i, j))
    return c


def read_wamit(stem: Path, rho: float = 1025.0, gravity: float = 9.81,
               length_scale: float = 1.0) -> dict:  # fmt: skip
    """The fields of a HydroDB from WAMIT's ``stem.1`` with ``stem.3`` (or ``.3sc`` and
    ``.3fk``) beside it and ``stem.hst`` if there, dimensionalised with ``rho`` [kg/m^3],
    ``gravity`` [m/s^2] and WAMIT's ULEN ``length_scale`` [m]."""
    if not (rho > 0.0 and gravity > 0.0 and length_scale > 0.0):
        raise HydroDBError(f"WAMIT database '{stem}': rho {rho:g}, gravity {gravity:g} and "
                           f"length_scale {length_scale:g} must be positive")  # fmt: skip
    first = Path(f"{stem}.1")
    if not first.exists():
        raise HydroDBError(f"WAMIT database '{stem}': no '{first.name}' (added mass and "
                           "damping); give the stem of a WAMIT run or its .1 file")  # fmt: skip
    periods, omega, added, damping, infinite = _wamit_radiation(first, rho, length_scale)
    parts: dict[str, np.ndarray | None] = {}
    directions = None
    for key, suffix in (("excitation_total", ".3"), ("diffraction", ".3sc"),
                        ("froude_krylov", ".3fk")):  # fmt: skip
        path = Path(f"{stem}{suffix}")
        parts[key] = None
        if path.exists():
            headings, parts[key] = _wamit_excitation(path, periods, rho, gravity, length_scale)
            if directions is not None and (
                len(headings) != len(directions) or not np.allclose(headings, directions)
            ):
                raise HydroDBError(
                    f"WAMIT database '{stem}': '{path.name}' has other headings than the other "
                    "excitation files; give one run's files"
                )
            directions = headings
    if directions is None:
        raise HydroDBError(
            f"WAMIT database '{stem}': no excitation beside '{first.name}' ({stem.name}.3, or "
            f"{stem.name}.3sc and {stem.name}.3fk); run WAMIT's diffraction problem too"
        )
    hst = Path(f"{stem}.hst")
    return dict(
        omega=omega, added_mass=added, damping=damping, directions=directions, **parts,
        reference_point=np.zeros(3), infinite=infinite, rho=rho, gravity=gravity,
        hydrostatic_stiffness=_wamit_stiffness(hst, rho, gravity, length_scale)
        if hst.exists() else None,
        source=f"wamit:{first}",
    )  # fmt: skip


# ---- HDB ----------------------------------------------------------------------------------------
_HEADER = re.compile(r"^\s*\[([^\]]+)\]\s*(.*)$")
_SECTIONS = {"DIFFRACTION_FORCES_AND_MOMENTS": "diffraction",
             "FROUDE-KRYLOV_FORCES_AND_MOMENTS": "froude_krylov",
             "EXCITATION_FORCES_AND_MOMENTS": "excitation_total"}  # fmt: skip
_DETAILED = {"DIFF": "diffraction", "FFK": "froude_krylov"}
_EFM = re.compile(r"^INCIDENCE_EFM_(?:(DIFF|FFK)_)?(MOD|PH)_\d+$", re.IGNORECASE)
_MATRIX_ROW = re.compile(r"^(ADDED_MASS_LINE|DAMPING_TERMS?(?:_LINE)?)_([1-6])$", re.IGNORECASE)


class _Block:
    """One ``[NAME] inline`` header, the section it sits in and the lines below it."""

    def __init__(self, name: str, inline: str, number: int, section: str):
        self.name, self.inline, self.number, self.section = name, inline, number, section
        self.rows: list[tuple[int, list[str]]] = []


def _hdb_blocks(path: Path) -> list[_Block]:
    blocks: list[_Block] = []
    section = ""
    for number, line in enumerate(_lines(path), start=1):
        header = _HEADER.match(line)
        if header:
            name = header.group(1).strip()
            if name.upper() in _SECTIONS or name.upper() in (
                "RAO",
                "DRIFT_FORCES_AND_MOMENTS",
                "ADDED_MASS_RADIATION_DAMPING",
            ):
                section = name.upper()
            blocks.append(_Block(name, header.group(2).strip(), number, section))
        elif line.strip():
            if not blocks:
                raise HydroDBError(f"HDB database '{path}', line {number}: values before any "
                                   "[SECTION] header; is this an HDB file?")  # fmt: skip
            blocks[-1].rows.append((number, line.split()))
    return blocks


def _one(path: Path, blocks: list[_Block], name: str) -> _Block | None:
    found = [b for b in blocks if b.name.upper() == name.upper()]
    if len(found) > 1:
        raise HydroDBError(f"HDB database '{path}', line {found[1].number}: [{name}] given twice; "
                           "keep one")  # fmt: skip
    return found[0] if found else None


def _inline(path: Path, block: _Block) -> float:
    words = block.inline.split()
    if len(words) != 1:
        raise HydroDBError(f"HDB database '{path}', line {block.number}: [{block.name}] needs one "
                           f"number after it, not '{block.inline[:30]}'")  # fmt: skip
    return _numbers(path, block.number, words)[0]


def _table(path: Path, block: _Block, width: int) -> np.ndarray:
    rows = []
    for number, words in block.rows:
        if len(words) != width:
            raise HydroDBError(
                f"HDB database '{path}', line {number}: {len(words)} values under "
                f"[{block.name}] where {width} are expected; correct that line"
            )
        rows.append(_numbers(path, number, words))
    if not rows:
        raise HydroDBError(f"HDB database '{path}', line {block.number}: [{block.name}] has no "
                           "values below it")  # fmt: skip
    return np.array(rows)


def _square(path: Path, block: _Block) -> np.ndarray:
    table = _table(path, block, 6)
    if table.shape != (6, 6):
        raise HydroDBError(f"HDB database '{path}', line {block.number}: [{block.name}] has "
                           f"{len(table)} rows; a 6x6 matrix has six")  # fmt: skip
    return table


def _list(path: Path, blocks: list[_Block], name: str, count: str) -> np.ndarray:
    block = _one(path, blocks, name)
    if block is None:
        raise HydroDBError(f"HDB database '{path}': no [{name}] section; an HDB file lists its "
                           f"calculated periods and headings")  # fmt: skip
    values = _table(path, block, 1)[:, 0]
    declared = _one(path, blocks, count)
    if declared is not None and int(_inline(path, declared)) != len(values):
        raise HydroDBError(
            f"HDB database '{path}', line {declared.number}: [{count}] says "
            f"{declared.inline} but [{name}] lists {len(values)}; make them agree"
        )
    return values


def _check_periods(path: Path, block: _Block, column: np.ndarray, periods: np.ndarray) -> None:
    if len(column) != len(periods) or not np.allclose(column, periods, rtol=1e-4, atol=1e-6):
        raise HydroDBError(
            f"HDB database '{path}', line {block.number}: [{block.name}] is given at periods "
            f"{_short(column)} s, not those of [List_calculated_periods] {_short(periods)} s; "
            "give one row per calculated period, in the list's order"
        )


def _hdb_matrices(path: Path, blocks: list[_Block], periods: np.ndarray):
    """A and B (n periods, 6, 6) from the [ADDED_MASS_LINE_i] and [DAMPING_TERM_i] rows."""
    out = {"ADDED": np.zeros((len(periods), 6, 6)), "DAMPING": np.zeros((len(periods), 6, 6))}
    seen: dict[str, set[int]] = {"ADDED": set(), "DAMPING": set()}
    for block in blocks:
        match = _MATRIX_ROW.match(block.name)
        if not match or block.section not in ("", "ADDED_MASS_RADIATION_DAMPING"):
            continue
        kind = "ADDED" if match.group(1).upper().startswith("ADDED") else "DAMPING"
        row = int(match.group(2)) - 1
        if row in seen[kind]:
            raise HydroDBError(f"HDB database '{path}', line {block.number}: [{block.name}] given "
                               "twice; keep one (several structures are not read)")  # fmt: skip
        table = _table(path, block, 7)
        _check_periods(path, block, table[:, 0], periods)
        out[kind][:, row, :] = table[:, 1:]
        seen[kind].add(row)
    for kind, name in (("ADDED", "ADDED_MASS_LINE"), ("DAMPING", "DAMPING_TERM")):
        missing = sorted(set(range(6)) - seen[kind])
        if missing:
            raise HydroDBError(
                f"HDB database '{path}': no [{name}_{missing[0] + 1}] section (rows 1 to 6 of "
                "the matrix by period under [Added_mass_Radiation_Damping]); give all six rows"
            )
    return out["ADDED"], out["DAMPING"]


def _hdb_excitation(path: Path, blocks: list[_Block], periods: np.ndarray,
                    headings: np.ndarray, radians: bool) -> dict:  # fmt: skip
    """The excitation parts found, each (n periods, m headings, 6) complex, ours."""
    tables: dict[str, dict[str, dict[float, tuple[_Block, np.ndarray]]]] = {}
    for block in blocks:
        match = _EFM.match(block.name)
        if not match:
            continue
        part = _DETAILED.get((match.group(1) or "").upper()) or _SECTIONS.get(block.section)
        if part is None:
            continue
        table = _table(path, block, 7)
        _check_periods(path, block, table[:, 0], periods)
        heading = _inline(path, block)
        kind = match.group(2).upper()
        slot = tables.setdefault(part, {}).setdefault(kind, {})
        if heading in slot:
            raise HydroDBError(f"HDB database '{path}', line {block.number}: heading {heading:g} "
                               f"deg given twice in [{block.section}]; keep one")  # fmt: skip
        slot[heading] = (block, table[:, 1:])
    parts = {}
    for part, kinds in tables.items():
        values = np.zeros((len(periods), len(headings), 6), complex)
        for m, heading in enumerate(headings):
            got = {kind: kinds.get(kind, {}).get(_near(kinds.get(kind, {}), heading))
                   for kind in ("MOD", "PH")}  # fmt: skip
            if got["MOD"] is None or got["PH"] is None:
                kind = "MOD" if got["MOD"] is None else "PH"
                raise HydroDBError(
                    f"HDB database '{path}': no [INCIDENCE_EFM_{kind}_...] {heading:g} block for "
                    f"the {part.replace('_', ' ')} forces; give modulus and phase at every "
                    "calculated heading"
                )
            modulus, phase = got["MOD"][1], got["PH"][1]
            if radians and np.abs(phase).max() > math.pi * (1.0 + 1e-6):
                raise HydroDBError(
                    f"HDB database '{path}', line {got['PH'][0].number}: phases up to "
                    f"{np.abs(phase).max():.4g} beyond pi: they are in degrees; say phase_unit: "
                    "deg in the body's hydrodynamics"
                )
            # AQUA+'s F = -|X| a sin(theta - phi), theta = k x - w t + p; ours: X = |X| e^{-i phi}
            values[:, m, :] = modulus * np.exp(-1j * (phase if radians else np.radians(phase)))
        parts[part] = values
    return parts


def _near(table: dict, heading: float):
    for key in table:
        if abs(key - heading) < 1e-6 * max(1.0, abs(heading)):
            return key
    return None


def read_hdb(path: Path, rho: float = 1025.0, gravity: float = 9.81,
             phase_unit: str = "rad") -> dict:  # fmt: skip
    """The fields of a HydroDB from an HDB file (Diodore, AQUA+): conventions in the module's
    docstring. ``rho`` [kg/m^3] and ``gravity`` [m/s^2] are recorded only (the file is
    dimensional); ``phase_unit``: "rad" or "deg", the unit of the file's phases."""
    if phase_unit not in ("rad", "deg"):
        raise HydroDBError(f"HDB database '{path}': phase_unit '{phase_unit}'; give rad or deg")
    blocks = _hdb_blocks(path)
    structures = _one(path, blocks, "STRUCTURES_NUMBER")
    if structures is not None and _inline(path, structures) != 1:
        raise HydroDBError(
            f"HDB database '{path}', line {structures.number}: {structures.inline} structures; "
            "one structure's file is read"
        )
    speed = _one(path, blocks, "FORWARD_SPEED")
    if speed is not None and _inline(path, speed) != 0.0:
        raise HydroDBError(f"HDB database '{path}', line {speed.number}: forward speed "
                           f"{speed.inline}; only a database at zero speed is read")  # fmt: skip
    periods = _list(path, blocks, "List_calculated_periods", "PERIODS_NUMBER")
    headings = _list(path, blocks, "List_calculated_headings", "HEADINGS_NUMBER")
    if np.any(periods <= 0.0):
        raise HydroDBError(f"HDB database '{path}': a calculated period is not positive "
                           f"{_short(periods)}; periods are in seconds")  # fmt: skip
    added, damping = _hdb_matrices(path, blocks, periods)
    parts = _hdb_excitation(path, blocks, periods, headings, phase_unit == "rad")
    if not parts:
        raise HydroDBError(
            f"HDB database '{path}': no excitation forces ([DIFFRACTION_FORCES_AND_MOMENTS], "
            "[FROUDE-KRYLOV_FORCES_AND_MOMENTS] or [EXCITATION_FORCES_AND_MOMENTS] with "
            "[INCIDENCE_EFM_MOD_...] and [INCIDENCE_EFM_PH_...] blocks); add them"
        )
    stiffness = _one(path, blocks, "Hydrostatic_matrix")
    freq = np.argsort(2.0 * math.pi / periods)
    direction = np.argsort(headings)
    return dict(
        omega=(2.0 * math.pi / periods)[freq], added_mass=added[freq], damping=damping[freq],
        directions=np.radians(headings[direction]),
        **{key: parts[key][freq][:, direction] if key in parts else None
           for key in ("diffraction", "froude_krylov", "excitation_total")},
        reference_point=np.zeros(3), infinite=None, rho=rho, gravity=gravity,
        hydrostatic_stiffness=None if stiffness is None else _square(path, stiffness),
        source=f"hdb:{path}",
    )  # fmt: skip
