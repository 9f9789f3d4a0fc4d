"""MoorDyn input files (decks) read into a seacable case.

MoorDyn's input file is the open exchange format of mooring models (MoorPy writes it, OpenFAST,
WEC-Sim and others read it). ``read`` turns a deck into the mapping of a seacable case (what
``case.loader.load_case`` validates, and reads a deck as) and ``convert`` into a commented YAML
case as well (``seacable import moordyn``). Both versions of
the format are read:

- v2 (MoorDyn-C 2, MoorDyn-F in OpenFAST): ``LINE TYPES``, ``ROD TYPES``, ``BODIES``,
  ``RODS`` (a rod pinned to a body or coupled pinned: a rigid body ``pinned_to`` it),
  ``POINTS``, ``LINES``, ``FAILURE``, ``OPTIONS``, ``OUTPUTS``;
- v1: ``LINE DICTIONARY`` (or ``LINE TYPES``), ``NODE PROPERTIES`` (``POINT PROPERTIES``,
  ``CONNECTION PROPERTIES``), ``LINE PROPERTIES``, ``SOLVER OPTIONS``, ``OUTPUTS``.

A section starts at a line of dashes around its title; a table's first two lines are its column
names and units; ``!``, ``#`` and ``%`` start a comment (v2). Conventions carried over: z up with
z = 0 at the still water (both codes), the seabed at z = -WtrDpth, a negative BA a damping ratio
(``axial_damping_ratio``) and a positive one a damping coefficient BA [N s]
(``axial_damping_time`` = BA / EA), Cd on d l and CdAx on pi d l (as seacable's), Ca and CaAx
(Can and Cat) the added mass normal to and along the line, kBot [Pa/m] and
cBot [Pa s/m] on the segment's d l (the seabed's ``stiffness_per_area`` and
``damping_per_area``).

Each MoorDyn point becomes a body named ``point<ID>``, each line a lumped-mass line named
``line<ID>`` from its A (anchor) end to its B (fairlead) end: a fixed point a fixed body, a free
(``Connect``) point a point body with its mass, volume (buoyancy, added mass Ca rho V) and drag
(CdA), a coupled point (``Coupled``, ``Vessel``) an imposed body held where the deck puts it
(the motion is the user's to give: its ``x``, ``y``, ``z`` time functions). v1's vessel points
are fixed in the vessel's frame: they become one imposed body ``vessel``, held still the same
way, each point at its deck position.
Each v2 body becomes a body ``body<ID>`` (``_bodies``: fixed, imposed, or a free rigid body
with MoorDyn's body hydrodynamics) holding the points the deck attaches to it (``Body<ID>``),
in its frame. The bodies, points and failures are read in ``case.moordyn_tables``.

What has no equivalent in seacable is refused by name (the section, the row and the column),
never dropped: coupled rods and rods fixed to coupled bodies, a failure at a rod's end, a line
with bending stiffness at a rod's end (MoorDyn clamps it there), a body point's own mass,
volume or drag, vortex-induced vibration (Cl), non-linear or viscoelastic EA, wave and current
kinematics other than WaveKin 7's wave components and Currents 1 and 3's profile, points
attached to turbines, v1 point forces. MoorDyn's own settings that seacable replaces (the
initial-condition solver's: seacable starts from its statics; the output and logging switches:
seacable writes every output) are noted in the written case.
"""

import math
import re
from pathlib import Path
from typing import Any

import yaml

from seacable import files
from seacable.case.moordyn_tables import Section, Tables, rounded, to_number
from seacable.errors import CaseError

V2_SECTIONS = {
    "LINE TYPES": "line_types",
    "LINE DICTIONARY": "line_types",
    "POINTS": "points",
    "POINT PROPERTIES": "points",
    "NODE PROPERTIES": "points",
    "CONNECTION PROPERTIES": "points",
    "POINT LIST": "points",
    "LINES": "lines",
    "LINE PROPERTIES": "lines",
    "LINE LIST": "lines",
    "OPTIONS": "options",
    "SOLVER OPTIONS": "options",
    "OUTPUTS": "outputs",
    "OUTPUT LIST": "outputs",
    "BODIES": "bodies",
    "BODY LIST": "bodies",
    "BODY PROPERTIES": "bodies",
    "FAILURE": "failures",
    "FAILURE CONDITIONS": "failures",
    "ROD TYPES": "rod_types",
    "ROD DICTIONARY": "rod_types",
    "RODS": "rods",
    "ROD LIST": "rods",
    "ROD PROPERTIES": "rods",
}
NOT_YET = (
    "EXTERNAL LOADS",
    "CONTROL",
    "CONTROL VARIABLES",
)
END_TITLES = ("NEED THIS LINE", "END")
# options seacable takes, and what each becomes
DEFAULTS = {
    "dtm": 0.001,
    "g": 9.80665,
    "rhow": 1025.0,
    "wtrdpth": 0.0,
    "kbot": 3.0e6,
    "cbot": 3.0e5,
    "frictioncoefficient": 0.0,
}
ALIASES = {
    "gravity": "g",
    "rho": "rhow",
    "waterdepth": "wtrdpth",
    "depth": "wtrdpth",
    "kb": "kbot",
    "cb": "cbot",
    "wtrdnsty": "rhow",
    "mu": "frictioncoefficient",
    "tscheme": "timescheme",
}
REPLACED = {  # MoorDyn's settings that seacable replaces, with what replaces them
    "dtic": "seacable starts from its statics (start: static)",
    "tmaxic": "seacable starts from its statics (start: static)",
    "cdscaleic": "seacable starts from its statics (start: static)",
    "threshic": "seacable starts from its statics (start: static)",
    "icdfac": "seacable starts from its statics (start: static)",
    "icthresh": "seacable starts from its statics (start: static)",
    "ictmax": "seacable starts from its statics (start: static)",
    "icgendynamic": "seacable starts from its statics (start: static)",
    "echo": "an output switch of MoorDyn's (seacable writes every output)",
    "writelog": "an output switch of MoorDyn's (seacable writes every output)",
    "writeunits": "an output switch of MoorDyn's (seacable writes every output)",
    "disableoutput": "an output switch of MoorDyn's (seacable writes every output)",
    "disableouttime": "an output switch of MoorDyn's (seacable writes every output)",
    "fileic": "seacable starts from its statics (start: static)",
    "timescheme": "seacable's own integrators (rk4 at dtM in the written case)",
    "dtwave": "a wave kinematics setting (give the waves in the case's environment.waves)",
    "dtout": "simulation.output_interval",
    "tmax": "simulation.duration",
}
AT_DEFAULT = {  # MoorDyn's settings seacable takes at their MoorDyn default only
    "fricdamp": (
        200.0,
        "MoorDyn's friction smoothing (seacable regularises below the seabed's slip_speed)",
    ),
    "statdynfricscale": (1.0, "a static friction above the dynamic one"),
    "inertialf": (0.0, "the coupled bodies' inertial reaction"),
}
ZERO_ONLY = {  # options seacable takes at 0 (their MoorDyn default) only
    "wavekin": "wave kinematics other than 7 (wave components in wave_frequencies.txt beside "
    "the deck); give the waves in the case's environment.waves instead",
    "currents": "current kinematics other than a steady profile (1 or 3, current_profile.txt "
    "beside the deck); give the current in the case's environment.current",
    "seafloorfile": "a 3D seafloor (seacable's seabed is flat)",
}
DURATION = 60.0  # [s] a deck carries no duration (the program MoorDyn is coupled to decides)
OUTPUT_INTERVAL = 0.1  # [s] unless the deck gives dtOut
LARGEST_DECK = 50_000_000  # [bytes] a deck, or a side file it reads (wave elevations, currents)


def read(source: str | Path, name: str | None = None,
         folder: Path | None = None) -> dict[str, Any]:  # fmt: skip
    """The case mapping of the MoorDyn deck ``source`` (a path, or the deck's text when it
    holds a newline; ``name``: what messages call it; ``folder``: where its side files are,
    by default the deck's). Raises ``CaseError`` naming the section, row and column of
    anything with no equivalent (the module's docstring)."""
    return _Deck(source, name, folder).case()


def convert(source: str | Path, name: str | None = None,
            folder: Path | None = None) -> tuple[dict[str, Any], str]:  # fmt: skip
    """``read(source)`` and the same case as commented YAML text (what the import did, then
    the case)."""
    deck = _Deck(source, name, folder)
    case = deck.case()
    return case, deck.commented(case)


def looks_like_deck(text: str) -> bool:
    """Whether ``text`` is a MoorDyn deck: a line of dashes around a MoorDyn section's title."""
    return any(_title(line) in V2_SECTIONS for line in text.splitlines()[:400])


def _title(line: str) -> str | None:
    match = re.match(r"^\s*-{3,}\s*(.*?)\s*-{3,}\s*$", line)
    return " ".join(match.group(1).upper().split()) if match else None


class _Deck(Tables):
    def __init__(self, source: str | Path, name: str | None = None,
                 folder: Path | None = None):  # fmt: skip
        self.folder = folder  # where the deck's side files are
        if isinstance(source, Path) or "\n" not in str(source):
            self.name = str(source)
            self.folder = folder or Path(source).parent
            raw = files.read_bytes(source, "MoorDyn deck", LARGEST_DECK, CaseError)
            text = raw.decode(errors="replace")  # a comment's stray byte is no matter
        else:
            self.name, text = name or "the deck", str(source)
        self.sections: dict[str, Section] = {}
        self.notes: list[str] = []
        self._split(text)
        titles = {s.title for s in self.sections.values()}
        self.version = 2 if titles & {"POINTS", "RODS", "ROD TYPES", "BODIES", "OPTIONS"} else 1
        if "line_types" in self.sections and self.sections["line_types"].rows:
            self.version = 2 if len(self.sections["line_types"].rows[0][1]) >= 10 else 1

    def _split(self, text: str) -> None:
        current: Section | None = None
        skip = 0
        for number, raw in enumerate(text.splitlines(), start=1):
            title = _title(raw)
            if title is not None:
                if title in V2_SECTIONS:
                    key = V2_SECTIONS[title]
                    if key in self.sections:
                        raise CaseError(f"{self.name} line {number}: a second {title} section")
                    current = self.sections[key] = Section(title, number)
                    skip = 0 if key in ("options", "outputs") else 2
                elif title in NOT_YET:
                    raise CaseError(
                        f"{self.name} line {number}: section {title} is not read yet (seacable "
                        "reads MoorDyn's line types, rod types, bodies, rods, points, lines, "
                        "failures, options and outputs); model it in the seacable case instead"
                    )
                elif current is not None and any(t in title for t in END_TITLES):
                    current = None
                elif current is not None:
                    raise CaseError(
                        f"{self.name} line {number}: {title!r} is not a MoorDyn "
                        f"section; known: {', '.join(V2_SECTIONS)}"
                    )
                continue  # before the first section: the deck's free-form heading
            if current is None:
                continue
            fields = re.split(r"[!#%]", raw, maxsplit=1)[0].split()
            if not fields:
                continue
            if skip:
                skip -= 1  # the table's column names and units
                continue
            if current.title == "OUTPUTS" or fields[0].upper() == "END":
                if fields[0].upper() == "END":
                    current = None
                else:
                    current.rows.append((number, fields))
                continue
            current.rows.append((number, fields))

    # -- the case --------------------------------------------------------------------------
    def case(self) -> dict[str, Any]:
        if not any(self._rows(k) for k in ("lines", "rods", "bodies")):
            raise CaseError(f"{self.name}: no lines, rods or bodies (a MoorDyn deck needs "
                            "one of them)")  # fmt: skip
        if self._rows("lines") and not self._rows("line_types"):
            raise CaseError(f"{self.name}: lines and no line types (a MoorDyn deck's lines "
                            "need their LINE TYPES)")  # fmt: skip
        options = self._options()
        types = self._line_types()
        held = self._bodies(options)
        rods, ends = self._rods(options, held)
        bodies, names = self._points(options, held)
        bodies += rods
        names.update(ends)
        lines = self._lines(types, names)
        failures = self._failures(names)
        environment: dict[str, Any] = {"gravity": options["g"], "water_density": options["rhow"]}
        if options["rhow"] == 0.0:  # MoorDyn's vacuum
            environment = {"gravity": options["g"], "in_air": True}
            self.notes.append("water density 0: in_air (no buoyancy, drag or added mass)")
        if options["wtrdpth"] > 0:
            environment["water_depth"] = options["wtrdpth"]
            environment["seabed"] = {  # on each segment's d l, as MoorDyn's
                "stiffness_per_area": options["kbot"],
                "damping_per_area": options["cbot"],
                "contact_band": 0.0,
            }
            if options["frictioncoefficient"] > 0:  # along and across the line alike
                environment["seabed"]["friction_coefficient"] = options["frictioncoefficient"]
        if options.get("wavekin") == 7.0:
            environment["waves"] = self._wave_components(options)
            environment["wave_stretching"] = "wheeler"
        if options.get("currents") == 1.0:
            environment["current"] = self._current_profile()
        outputs = self.sections.get("outputs")
        if outputs is not None and outputs.rows:
            channels = ", ".join(fields[0] for _, fields in outputs.rows)
            self.notes.append(
                f"OUTPUTS ({channels}): seacable's results hold every body's "
                "motion and every line's tensions and end forces"
            )
        step = options["dtm"]
        if "cfl" in options and not any(f[1].lower() == "dtm" for _, f in self._option_rows()):
            step = rounded(options["cfl"] * _transit(types, lines))
            self.notes.append(
                f"CFL {options['cfl']:g}: time_step {step:g} s, the CFL number times the axial "
                "wave's transit time over the shortest segment, sqrt(m / EA) l"
            )
        interval = options.get("dtout", OUTPUT_INTERVAL)
        whole = interval / math.ceil(interval / step * (1 - 1e-12))  # at most the step asked
        if abs(whole - step) > 1e-12 * step:
            self.notes.append(
                f"time_step {rounded(whole):g} s: {step:g} s made a whole fraction of the "
                f"{interval:g} s output interval"
            )
        simulation = {
            "duration": options.get("tmax", DURATION),
            "output_interval": interval,
            "integrator": "rk4",
            "time_step": rounded(whole),
        }
        if "tmax" not in options:
            self.notes.append(f"simulation.duration: {DURATION:g} s (a deck carries none)")
        return {
            "name": f"MoorDyn deck {Path(self.name).name}",
            "description": f"imported from the MoorDyn v{self.version} deck {self.name}",
            "environment": environment,
            "bodies": bodies,
            "line_types": list(types.values()),
            "lines": lines,
            **({"failures": failures} if failures else {}),
            "start": "static",
            "simulation": simulation,
        }

    def _wave_components(self, options) -> list[dict[str, Any]]:
        """WaveKin 7: the wave components of ``wave_frequencies.txt`` beside the deck (rows of
        omega [rad/s], then the real and imaginary parts of the complex amplitude A [m], the
        first at omega 0), each an Airy wave towards +x: MoorDyn's eta = |A| sin(omega t - k x
        + arg A) is seacable's H/2 cos(k x - omega t + phase) with H = 2 |A| and phase =
        90 deg - arg A; kinematics stretched as MoorDyn's (Wheeler)."""
        if options["wtrdpth"] <= 0:
            raise CaseError(f"{self.name} (OPTIONS, WaveKin 7): waves need the water depth; "
                            "give WtrDpth")  # fmt: skip
        path, lines = self._side_file("wave_frequencies.txt", "WaveKin 7")
        waves = []
        for number, raw in enumerate(lines, start=1):
            fields = raw.split()
            if not fields:
                continue
            at = f"{path} line {number}"
            if len(fields) != 3:
                raise CaseError(f"{at}: {raw.strip()!r}: give omega [rad/s], then the real and "
                                "imaginary parts of the amplitude [m]")  # fmt: skip
            omega, real, imaginary = (to_number(v, at) for v in fields)
            if omega < 0 or (number == 1 and omega != 0):
                raise CaseError(f"{at}: omega {omega:g}: the frequencies start at 0 rad/s "
                                "(MoorDyn's first row) and are not negative")  # fmt: skip
            amplitude = math.hypot(real, imaginary)
            if omega == 0 or amplitude == 0:
                continue
            phase = 90.0 - math.degrees(math.atan2(imaginary, real))
            waves.append({"kind": "airy", "height": rounded(2 * amplitude),
                          "period": rounded(2 * math.pi / omega),
                          "phase_deg": rounded(phase), "direction_deg": 0.0})  # fmt: skip
        if not waves:
            raise CaseError(f"{path}: no wave component with a frequency and an amplitude")
        self.notes.append(f"WaveKin 7: {len(waves)} wave components from {path.name}, towards "
                          "+x, Wheeler's stretching as MoorDyn's")  # fmt: skip
        return waves

    def _side_file(self, name: str, option: str) -> tuple[Path, list[str]]:
        """A side file of the deck (``option`` needs it) and its lines."""
        where = f"{self.name} (OPTIONS, {option})"
        if self.folder is None:
            raise CaseError(f"{where}: it is read from {name} beside the deck; read the deck "
                            "from its file")  # fmt: skip
        path = self.folder / name
        raw = files.read_bytes(path, f"{where}: side file", LARGEST_DECK, CaseError)
        return path, raw.decode(errors="replace").splitlines()

    def _current_profile(self) -> dict[str, Any]:
        """Currents 1 or 3: the steady profile of ``current_profile.txt`` beside the deck (three
        heading lines, then rows of z [m], ux, uy and uz [m/s]; uy and uz may be left out), as
        the case's current ``profile`` towards one direction (MoorDyn interpolates it in z as
        seacable does, and holds the end values beyond)."""
        path, lines = self._side_file("current_profile.txt", "Currents")
        rows = []
        for number, raw in enumerate(lines[3:], start=4):
            fields = raw.split()
            if not fields:
                continue
            at = f"{path} line {number}"
            if not 2 <= len(fields) <= 4:
                raise CaseError(f"{at}: {raw.strip()!r}: give z [m], then ux, uy, uz [m/s]")
            z, ux, uy, uz = (*(to_number(v, at) for v in fields), 0.0, 0.0)[:4]
            if uz != 0.0:
                raise CaseError(f"{at}: uz {uz:g} m/s: a vertical current is not modelled; "
                                "set it to 0")  # fmt: skip
            rows.append((number, z, ux, uy))
        if len(rows) < 2:
            raise CaseError(f"{path}: a current profile needs at least 2 rows after its three "
                            "heading lines")  # fmt: skip
        flowing = [(math.atan2(uy, ux), n) for n, _, ux, uy in rows if math.hypot(ux, uy) > 0]
        heading = flowing[0][0] if flowing else 0.0
        for angle, number in flowing:
            if abs(math.remainder(angle - heading, 2 * math.pi)) > 1e-9:
                raise CaseError(
                    f"{path} line {number}: the current turns with depth ({math.degrees(angle):g}"
                    f" deg here, {math.degrees(heading):g} deg above); seacable's profile has "
                    "one direction: give the rows one direction"
                )
        profile = [[rounded(z), rounded(math.hypot(ux, uy))] for _, z, ux, uy in rows]
        self.notes.append(f"Currents: the steady profile of {path.name}, {len(rows)} rows")
        return {"profile": profile, "direction_deg": rounded(math.degrees(heading))}

    def _option_rows(self) -> list[tuple[int, list[str]]]:
        return self._rows("options")

    def _options(self) -> dict[str, float]:
        options = dict(DEFAULTS)
        for number, fields in self._rows("options"):
            if len(fields) < 2:
                raise CaseError(
                    f"{self._where('options', number)}: an option is a value then "
                    f"its name; got {' '.join(fields)!r}"
                )
            value, name = fields[0], fields[1]
            key = ALIASES.get(name.lower(), name.lower())
            where = self._where("options", number, name)
            if key in DEFAULTS or key in ("dtout", "tmax", "cfl"):
                options[key] = to_number(value, where)
                if key in ("dtm", "dtout", "tmax", "cfl") and options[key] <= 0:
                    raise CaseError(f"{where}: {value} must be positive")
                if key in ("dtout", "tmax"):
                    self.notes.append(f"{name} {value}: {REPLACED[key]}")
            elif key in REPLACED:
                self.notes.append(f"{name} {value}: not used ({REPLACED[key]})")
            elif key in AT_DEFAULT:
                default, what = AT_DEFAULT[key]
                if to_number(value, where) != default:
                    raise CaseError(
                        f"{where}: {value}: {what} is not modelled; remove it or "
                        f"set MoorDyn's default {default:g}"
                    )
                self.notes.append(f"{name} {value}: MoorDyn's default, nothing to carry over")
            elif key == "wavekin" and value == "7":
                options["wavekin"] = 7.0
            elif key == "currents" and value in ("1", "3"):
                options["currents"] = 1.0
            elif key in ZERO_ONLY:
                if value not in ("0", "0.0", "-"):
                    raise CaseError(
                        f"{where}: {value!r}: {ZERO_ONLY[key]} is not read; set it to 0"
                    )
            else:
                raise CaseError(
                    f"{where}: option {name!r} has no equivalent in seacable; the options read: "
                    "dtM, g, rhoW (WtrDnsty), WtrDpth, kBot, cBot, FrictionCoefficient, dtOut, "
                    "TMax "
                    "(and MoorDyn's initial-condition and output settings, noted); remove it"
                )
        return options

    def _line_types(self) -> dict[str, dict[str, Any]]:
        v2 = self.version == 2
        columns = (
            ["Name", "Diam", "MassDen", "EA", "BA", "EI", "Cd", "Ca", "CdAx", "CaAx"]
            if v2
            else ["Name", "Diam", "MassDen", "EA", "BA", "Can", "Cat", "Cdn", "Cdt"]
        )
        types: dict[str, dict[str, Any]] = {}
        for number, fields in self._rows("line_types"):
            if len(fields) < len(columns) or len(fields) > (13 if v2 else len(columns)):
                raise CaseError(
                    f"{self._where('line_types', number)}: {len(fields)} columns; "
                    f"expected {' '.join(columns)}"
                )
            row = dict(zip(columns, fields, strict=False))
            name = row["Name"]

            def value(column, row=row, number=number):
                return to_number(row[column], self._where("line_types", number, column))

            if not re.fullmatch(r"[-+0-9.eE]+", row["EA"]):
                raise CaseError(
                    f"{self._where('line_types', number, 'EA')}: {row['EA']!r}: a "
                    "non-linear or viscoelastic EA is not read; give one number"
                )
            tangential = "CaAx" if v2 else "Cat"
            if v2 and len(fields) > 10 and to_number(fields[10], "Cl") != 0.0:
                raise CaseError(
                    f"{self._where('line_types', number, 'Cl')}: {fields[10]}: "
                    "vortex-induced vibration is not modelled; set Cl to 0"
                )
            ea, ba = value("EA"), value("BA")
            line_type: dict[str, Any] = {
                "name": name,
                "diameter": value("Diam"),
                "mass_per_length": value("MassDen"),
                "axial_stiffness": ea,
                "drag_coefficient_normal": value("Cd" if v2 else "Cdn"),
                "drag_coefficient_tangential": value("CdAx" if v2 else "Cdt"),
                "added_mass_coefficient": value("Ca" if v2 else "Can"),
            }
            if value(tangential) > 0:
                line_type["added_mass_coefficient_tangential"] = value(tangential)
            if ba < 0:
                line_type["axial_damping_ratio"] = -ba
            elif ba > 0:
                line_type["axial_damping_time"] = ba / ea
            if v2 and value("EI") > 0:
                line_type["bending_stiffness"] = value("EI")
            if name in types:
                raise CaseError(
                    f"{self._where('line_types', number)}: a second line type named {name!r}"
                )
            types[name] = line_type
        return types

    def _lines(self, types, names) -> list[dict[str, Any]]:
        v2 = self.version == 2
        columns = (
            ["ID", "LineType", "AttachA", "AttachB", "UnstrLen", "NumSegs", "Outputs"]
            if v2
            else ["ID", "LineType", "UnstrLen", "NumSegs", "AttachA", "AttachB", "Outputs"]
        )
        lines = []
        for number, fields in self._rows("lines"):
            row = self._row("lines", number, fields, columns, optional=1)
            if row["LineType"] not in types:
                raise CaseError(
                    f"{self._where('lines', number, 'LineType')}: "
                    f"{row['LineType']!r} is not a line type; known: "
                    f"{', '.join(types)}"
                )
            ends = []
            for column in ("AttachA", "AttachB"):
                if row[column].upper() not in names:
                    raise CaseError(
                        f"{self._where('lines', number, column)}: {row[column]!r} "
                        "is not a point or rod end of the deck (a point's ID, or R<ID>A, "
                        "R<ID>B)"
                    )
                ends.append(names[row[column].upper()])
                clamped = re.fullmatch(r"R\d+[AB]", row[column].upper())
                if clamped and types[row["LineType"]].get("bending_stiffness"):
                    raise CaseError(
                        f"{self._where('lines', number, column)}: {row[column]!r}: a line with "
                        "bending stiffness (EI > 0) at a rod's end, which MoorDyn clamps along "
                        "the rod's axis (a cantilever); seacable's line ends turn freely, so "
                        "it is not read: give the line type EI 0 to hinge it there"
                    )
            length = to_number(row["UnstrLen"], self._where("lines", number, "UnstrLen"))
            segments = to_number(row["NumSegs"], self._where("lines", number, "NumSegs"))
            if segments != int(segments) or segments < 1:
                raise CaseError(
                    f"{self._where('lines', number, 'NumSegs')}: {row['NumSegs']} "
                    "must be a positive whole number"
                )
            lines.append(
                {
                    "name": f"line{row['ID']}",
                    "model": "lumped_mass",
                    "from": ends[0],
                    "to": ends[1],
                    "sections": [
                        {"type": row["LineType"], "length": length, "segments": int(segments)}
                    ],
                }
            )
        return lines

    def commented(self, case: dict[str, Any]) -> str:
        """The case as YAML, headed by what the import did."""
        head = [
            f"# seacable case imported from the MoorDyn v{self.version} deck {self.name}",
            "# (seacable import moordyn). Points are bodies point<ID>, lines line<ID>;",
            "# z up, z = 0 at the still water, SI units, as in the deck.",
        ]
        head += [f"# - {note}" for note in self.notes]
        body = yaml.safe_dump(case, sort_keys=False, default_flow_style=None, width=100)
        return "\n".join(head) + "\n" + body


def _transit(types: dict[str, dict[str, Any]], lines: list[dict[str, Any]]) -> float:
    """The shortest time [s] an axial wave takes along a segment of ``lines``."""
    times = []
    for line in lines:
        section = line["sections"][0]
        kind = types[section["type"]]
        length = section["length"] / section["segments"]
        times.append(length * math.sqrt(kind["mass_per_length"] / kind["axial_stiffness"]))
    return min(times)
