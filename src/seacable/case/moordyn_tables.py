"""A MoorDyn deck's tables row by row (``case.moordyn`` reads the deck): a row by its column
names (``_row``, its count checked), where it is (``_where``: the deck's line, section and
column, which every refusal names), its numbers; and the tables that become seacable bodies and
failures: v2 BODIES (fixed, imposed, or free rigid bodies with MoorDyn's body hydrodynamics),
POINTS / NODE PROPERTIES (fixed bodies, point bodies, coupled points as imposed bodies, points
on the deck's bodies or v1's vessel), ROD TYPES and RODS (``rod`` force models on the deck's
bodies, free rods as rigid bodies, pinned ones as rigid bodies ``pinned_to`` a body or a
coupled point, fixed rods as fixed bodies) and FAILURE (the case's ``failures``).
"""

import math
import re
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from seacable.errors import CaseError


@dataclass
class Section:
    title: str
    line: int  # where its title is (1-based)
    rows: list[tuple[int, list[str]]] = field(default_factory=list)  # (line, fields)


def to_number(text: str, where: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise CaseError(f"{where}: {text!r} is not a number") from None
    if not math.isfinite(value):
        raise CaseError(f"{where}: {text!r} is not a finite number")
    return value


def rounded(value: float) -> float:
    return float(f"{value:.12g}")


COUPLED_PINNED = ("coupledpinned", "cpldpin", "vesselpinned", "vespin")  # MoorDyn's words


def constant(value: float) -> dict[str, Any]:
    return {"kind": "constant", "value": value}


class Tables:
    """The row readers and the body, point and failure tables of a deck (``case.moordyn``'s
    ``_Deck`` gives them its ``name``, ``version``, ``sections`` and ``notes``)."""

    name: str
    version: int
    sections: dict[str, "Section"]
    notes: list[str]

    def _rows(self, key: str) -> list[tuple[int, list[str]]]:
        """A section's rows, none where the deck has no such section."""
        section = self.sections.get(key)
        return section.rows if section else []

    def _where(self, key: str, line: int, column: str | None = None) -> str:
        section = self.sections[key].title
        return f"{self.name} line {line} ({section}{', column ' + column if column else ''})"

    def _bodies(self, options) -> dict[str, dict[str, Any]]:
        """The deck's bodies (v2 BODIES) by their attachment word ``body<ID>``: ``Fixed`` a
        fixed body, ``Coupled`` (``Vessel``) an imposed body held at the deck's pose, ``Free``
        a rigid body with MoorDyn's body hydrodynamics (:meth:`_free_body`), ``CoupledPinned``
        the same pinned to an imposed body ``body<ID>_pin`` at its reference point."""
        columns = ["ID", "Attachment", "X0", "Y0", "Z0", "r0", "p0", "y0", "Mass", "CG", "I",
                   "Volume", "CdA", "Ca"]  # fmt: skip
        bodies: dict[str, dict[str, Any]] = {}
        for number, fields in self._rows("bodies"):
            row = self._row("bodies", number, fields, columns)

            def value(column, row=row, number=number):
                return to_number(row[column], self._where("bodies", number, column))

            def values(column, counts, row=row, number=number):
                parts = row[column].split("|")
                if len(parts) not in counts:
                    raise CaseError(
                        f"{self._where('bodies', number, column)}: {row[column]!r}: give "
                        f"{' or '.join(map(str, counts))} numbers separated by |"
                    )
                return [to_number(v, self._where("bodies", number, column)) for v in parts]

            name, kind = f"body{row['ID']}", row["Attachment"].lower()
            if name in bodies:
                raise CaseError(f"{self._where('bodies', number, 'ID')}: a second body {row['ID']}")
            position = [value("X0"), value("Y0"), value("Z0")]
            angles = [value("r0"), value("p0"), value("y0")]
            body: dict[str, Any]
            if kind in ("fixed", "fix", "anchor"):
                body = {"name": name, "type": "fixed", "position": position}
                if any(angles):
                    body["orientation_deg"] = angles
            elif kind in ("coupled", "cpld", "vessel", "ves"):
                body = {"name": name, "type": "imposed"}
                for key, v in zip(("x", "y", "z", "roll_deg", "pitch_deg", "yaw_deg"),
                                  position + angles, strict=True):  # fmt: skip
                    body[key] = constant(v)
                self.notes.append(
                    f"{name}: a coupled body, held at the deck's pose; give its x, y, z, "
                    "roll_deg, pitch_deg, yaw_deg as time functions to move it, or step it "
                    "from Python (seacable.coupling.Coupling)"
                )
            elif kind in ("free", *COUPLED_PINNED):
                body = self._free_body(name, position, angles, value, values, options["rhow"])
                if kind in COUPLED_PINNED:  # its reference point coupled, turning freely
                    bodies[f"{name}_pin"] = _pin(name, position, self.notes)
                    body["pinned_to"] = f"{name}_pin"
            else:
                raise CaseError(
                    f"{self._where('bodies', number, 'Attachment')}: {row['Attachment']!r}: "
                    "seacable reads Fixed, Coupled (Vessel), CoupledPinned (VesselPinned) and "
                    "Free bodies"
                )
            body["points"] = {}
            bodies[name] = body
        return bodies

    def _free_body(self, name, position, angles, value, values, rho) -> dict[str, Any]:
        """A free body: a rigid body of the deck's mass, CG, inertia about the CG (one value
        for the three axes, or three), its buoyancy at its CG (where MoorDyn puts it), drag
        CdA per body axis on the velocity relative to the water (1, 2, 3 or 6 values as
        MoorDyn's documentation reads them), added mass Ca rho V per axis, and the waves'
        acceleration on its volume (``fluid inertia``; none in still water, MoorDyn's)."""
        mass, volume = value("Mass"), value("Volume")
        cg = values("CG", (1, 3))
        cg = [0.0, 0.0, cg[0]] if len(cg) == 1 else cg
        inertia = values("I", (1, 3))
        cda = values("CdA", (1, 2, 3, 6))
        if len(cda) == 6:
            moving, turning = cda[:3], cda[3:]
        elif len(cda) == 3:
            moving = turning = cda
        else:  # one for all six, or one for the translations and one for the rotations
            moving, turning = [cda[0]] * 3, [cda[-1]] * 3
        ca = values("Ca", (1, 3))
        body: dict[str, Any] = {
            "name": name, "type": "rigid", "position": position, "orientation_deg": angles,
            "mass": mass, "centre_of_gravity": cg,
            "inertia": inertia * 3 if len(inertia) == 1 else inertia,
        }  # fmt: skip
        forces: list[dict[str, Any]] = [{"model": "gravity"}]
        if volume > 0:
            body["volume"] = volume
            body["centre_of_buoyancy"] = cg
            forces += [{"model": "buoyancy"}, {"model": "fluid inertia"}]
            if any(ca):
                added = [rounded(c * rho * volume) for c in (ca * 3 if len(ca) == 1 else ca)]
                body["added_mass"] = [*added, 0.0, 0.0, 0.0]
            self.notes.append(
                f"{name}: its buoyancy acts at its CG (MoorDyn's body); give "
                "centre_of_buoyancy where it is elsewhere"
            )
        if any(moving):
            forces.append({"model": "drag", "drag_coefficient": 1.0, "area": moving})
        if any(turning):
            diagonal = [0.0] * 3 + [rounded(0.5 * rho * c) for c in turning]
            forces.append({"model": "quadratic_damping", "diagonal": diagonal})
            self.notes.append(
                f"{name}: its rotational CdA is a quadratic damping 0.5 rho CdA |w_k| w_k per "
                "body axis (MoorDyn's acts on the whole |w|: the same about one axis)"
            )
        body["external forces"] = forces
        return body

    def _rod_types(self) -> dict[str, dict[str, float]]:
        columns = ["TypeName", "Diam", "Mass/m", "Cd", "Ca", "CdEnd", "CaEnd"]
        types: dict[str, dict[str, float]] = {}
        for number, fields in self._rows("rod_types"):
            row = self._row("rod_types", number, fields, columns)
            if row["TypeName"] in types:
                raise CaseError(f"{self._where('rod_types', number, 'TypeName')}: a second "
                                f"rod type named {row['TypeName']!r}")  # fmt: skip
            types[row["TypeName"]] = {
                c: to_number(row[c], self._where("rod_types", number, c)) for c in columns[1:]
            }
        return types

    def _rods(self, options, held) -> tuple[list[dict[str, Any]], dict[str, str]]:
        """RODS: a rod on a body (``Body<ID>``) becomes a ``rod`` force model of that body, its
        mass, centre and inertia joined to the body's; a ``Free`` rod a rigid body ``rod<ID>``
        (reference point at end A, the rod's mass and inertia, gravity and the rod's loads), a
        ``Pinned`` one the same turning about its end A held still; a ``Fixed`` rod a fixed
        body, a ``Body<ID>Pinned`` one the same pinned at its end A to that body's point
        (``pinned_to``). Its ends are points ``a`` and ``b`` for the lines (R<ID>A, R<ID>B).
        Coupled rods are refused by name."""
        columns = ["ID", "RodType", "Attachment", "Xa", "Ya", "Za", "Xb", "Yb", "Zb", "NumSegs",
                   "RodOutputs"]  # fmt: skip
        types = self._rod_types()
        bodies: list[dict[str, Any]] = []
        ends: dict[str, str] = {}
        for number, fields in self._rows("rods"):
            row = self._row("rods", number, fields, columns, optional=1)

            def where(column, number=number):
                return self._where("rods", number, column)

            a = [to_number(row[c], where(c)) for c in ("Xa", "Ya", "Za")]
            b = [to_number(row[c], where(c)) for c in ("Xb", "Yb", "Zb")]
            segments = to_number(row["NumSegs"], where("NumSegs"))
            kind, name = row["Attachment"].lower(), f"rod{row['ID']}"
            if row["RodType"] not in types:
                raise CaseError(f"{where('RodType')}: {row['RodType']!r} is not a rod type; "
                                f"known: {', '.join(types) or 'none'}")  # fmt: skip
            if a == b or segments < 1 or segments != int(segments):
                raise CaseError(
                    f"{where('NumSegs')}: a rod of length {math.dist(a, b):g} m in "
                    f"{row['NumSegs']} segments: seacable reads rods of a positive length in "
                    "whole segments (a zero-length rod as a joint is not read); give a point "
                    "instead"
                )
            if f"R{row['ID']}A".upper() in ends:
                raise CaseError(f"{where('ID')}: a second rod {row['ID']}")
            kind_of = types[row["RodType"]]
            model = {
                "model": "rod", "end_a": a, "end_b": b, "diameter": kind_of["Diam"],
                "segments": int(segments), "drag_coefficient": kind_of["Cd"],
                "added_mass_coefficient": kind_of["Ca"],
                "end_drag_coefficient": kind_of["CdEnd"],
                "end_added_mass_coefficient": kind_of["CaEnd"],
            }  # fmt: skip
            mass = kind_of["Mass/m"] * math.dist(a, b)
            if kind in held and held[kind]["type"] == "rigid":
                host = held[kind]
                host["external forces"].append(model)
                _join_mass(host, mass, a, b, kind_of["Diam"])
                host["points"][f"{name}_a"], host["points"][f"{name}_b"] = [*a], [*b]
                ref = f"{kind}.{name}_"
            elif kind in ("free", "pinned", "pin", *COUPLED_PINNED) or _pinned_on(kind, held):
                axis = [q - p for p, q in zip(a, b, strict=True)]
                body = {"name": name, "type": "rigid", "position": a, "mass": 0.0,
                        "centre_of_gravity": [0.0, 0.0, 0.0], "inertia": [0.0, 0.0, 0.0],
                        "external forces": [{"model": "gravity"},
                                            {**model, "end_a": [0.0, 0.0, 0.0], "end_b": axis}],
                        "points": {"a": [0.0, 0.0, 0.0], "b": [*axis]}}  # fmt: skip
                _join_mass(body, mass, [0.0, 0.0, 0.0], axis, kind_of["Diam"])
                if _pinned_on(kind, held):  # pinned at end A to a body: it turns about it
                    host = held[_pinned_on(kind, held)]
                    host["points"][f"{name}_pin"] = [*a]
                    body["pinned_to"] = f"{host['name']}.{name}_pin"
                    body["position"], body["orientation_deg"] = _on_body(host, a)
                elif kind in COUPLED_PINNED:  # end A coupled, turning freely
                    bodies.append(_pin(name, a, self.notes))
                    body["pinned_to"] = f"{name}_pin"
                elif kind != "free":  # pinned at end A to the ground: it turns about it
                    body["dofs"] = ["roll", "pitch", "yaw"]
                bodies.append(body)
                ref = f"{name}."
            elif kind in ("fixed", "fix", "anchor") or (kind in held):
                if kind in held:  # on a fixed body: its loads go to the ground
                    host = held[kind]
                    if host["type"] != "fixed":
                        raise CaseError(
                            f"{where('Attachment')}: {row['Attachment']!r} is a coupled body: "
                            "a rod's loads on it would be the coupling's, which seacable does "
                            "not compute for rods; make the body Free, or model the rod's "
                            "loads in the coupled solver"
                        )
                    host["points"][f"{name}_a"], host["points"][f"{name}_b"] = [*a], [*b]
                    ref = f"{kind}.{name}_"
                else:
                    axis = [q - p for p, q in zip(a, b, strict=True)]
                    bodies.append({"name": name, "type": "fixed", "position": a,
                                   "points": {"a": [0.0, 0.0, 0.0], "b": [*axis]}})  # fmt: skip
                    ref = f"{name}."
                self.notes.append(f"{name}: a fixed rod; its own loads go to the ground")
            else:
                raise CaseError(
                    f"{where('Attachment')}: {row['Attachment']!r}: seacable reads rods on the "
                    f"deck's bodies ({', '.join(b for b in held if '_' not in b) or 'none'}, "
                    "or pinned to them: Body<ID>Pinned), Free, Pinned, CoupledPinned and Fixed "
                    "rods; a Coupled rod (its loads would be the coupling's) is not read"
                )
            ends[f"R{row['ID']}A".upper()] = ref + "a"
            ends[f"R{row['ID']}B".upper()] = ref + "b"
        return bodies, ends

    def _row(self, key: str, number: int, fields: list[str], columns: list[str],
             optional: int = 0) -> dict[str, str]:  # fmt: skip
        """A table row by its column names, their count checked (the last ``optional``
        columns may be left out)."""
        if not len(columns) - optional <= len(fields) <= len(columns):
            raise CaseError(
                f"{self._where(key, number)}: {len(fields)} columns; expected {' '.join(columns)}"
            )
        return dict(zip(columns, fields, strict=False))

    def _points(self, options, held) -> tuple[list[dict[str, Any]], dict[str, str]]:

        v2 = self.version == 2
        columns = (
            ["ID", "Attachment", "X", "Y", "Z", "M", "V", "CdA", "CA"]
            if v2
            else ["ID", "Attachment", "X", "Y", "Z", "M", "V", "FX", "FY", "FZ", "CdA", "CA"]
        )
        bodies: list[dict[str, Any]] = []
        names: dict[str, str] = {}
        vessel: dict[str, list[float]] = {}
        for number, fields in self._rows("points"):
            row = self._row("points", number, fields, columns)

            def value(column, row=row, number=number):
                return to_number(row[column], self._where("points", number, column))

            ident, kind = row["ID"], row["Attachment"].lower()
            name = f"point{ident}"
            position = [value("X"), value("Y"), value("Z")]
            if not v2 and any(value(c) != 0.0 for c in ("FX", "FY", "FZ")):
                raise CaseError(
                    f"{self._where('points', number, 'FX')}: a v1 point's steady "
                    "force is not read (its unit is N in MoorDyn's code, kN in its "
                    "sample files); give it as an applied force in the case"
                )
            if ident in names:
                raise CaseError(f"{self._where('points', number, 'ID')}: a second point {ident}")
            if kind in ("fixed", "fix", "anchor"):
                bodies.append({"name": name, "type": "fixed", "position": position})
            elif kind in ("coupled", "cpld") or (kind == "vessel" and v2):
                bodies.append(
                    {
                        "name": name,
                        "type": "imposed",
                        "x": constant(position[0]),
                        "y": constant(position[1]),
                        "z": constant(position[2]),
                    }
                )
            elif kind == "vessel":
                vessel[name] = position
                names[ident] = f"vessel.{name}"
                continue
            elif v2 and kind in held:
                if any(value(c) != 0.0 for c in ("M", "V", "CdA")):
                    raise CaseError(
                        f"{self._where('points', number, 'M')}: a point on {kind} with a mass, "
                        "volume or drag area: seacable's body points carry none; give them "
                        "to the body (its mass, CG, inertia, volume) and set them to 0 here"
                    )
                held[kind]["points"][name] = position
                names[ident] = f"{kind}.{name}"
                continue
            elif kind in ("free", "connect", "con"):
                bodies.append(
                    self._free(
                        name,
                        position,
                        value("M"),
                        value("V"),
                        value("CdA"),
                        value("CA"),
                        options["rhow"],
                    )
                )
            else:
                raise CaseError(
                    f"{self._where('points', number, 'Attachment')}: "
                    f"{row['Attachment']!r}: seacable reads Fixed, Free (Connect), "
                    "Coupled and Vessel points and points on the deck's bodies "
                    f"({', '.join(held) or 'none'}); a point on a turbine is not read"
                )
            names[ident] = name
        bodies = list(held.values()) + bodies
        if vessel:
            bodies.append({"name": "vessel", "type": "imposed", "points": vessel})
            self.notes.append(
                "vessel: the deck's vessel points, held still; give its x, y, z, "
                "roll_deg, pitch_deg, yaw_deg as time functions to move it"
            )
        if any(b["type"] == "imposed" and b["name"] != "vessel" for b in bodies):
            self.notes.append(
                "the coupled points are imposed bodies held where the deck puts "
                "them; give their x, y, z as time functions to move them"
            )
        return bodies, names

    @staticmethod
    def _free(name, position, mass, volume, cda, ca, rho) -> dict[str, Any]:
        body: dict[str, Any] = {"name": name, "type": "point", "position": position, "mass": mass}
        forces: list[dict[str, Any]] = [{"model": "gravity"}]
        if volume > 0:
            body["volume"] = volume
            forces.append({"model": "buoyancy"})
            if ca > 0:
                body["added_mass"] = ca * rho * volume
        if cda > 0:
            forces.append({"model": "drag", "drag_coefficient": 1.0, "area": cda})
        if volume > 0:  # the waves' acceleration on it (none in still water: MoorDyn's)
            forces.append({"model": "fluid inertia"})
        body["external forces"] = forces
        return body

    def _failures(self, names: dict[str, str]) -> list[dict[str, Any]]:
        """FAILURE (MoorDyn's line failures): the lines' ends at a point released at FailTime
        or when one's tension there reaches FailTen (0: none), staying joined by a free point
        (seacable's ``failures``)."""
        columns = ["FailureID", "Point", "Lines", "FailTime", "FailTen"]
        out = []
        for number, fields in self._rows("failures"):
            row = self._row("failures", number, fields, columns)
            point = re.fullmatch(r"(?:P|C|POINT|CON)?(\d+)", row["Point"], re.IGNORECASE)
            if point is None or point.group(1) not in names:
                raise CaseError(
                    f"{self._where('failures', number, 'Point')}: {row['Point']!r}: a point "
                    f"of the deck ({', '.join(names)}); a rod's end is not read"
                )
            lines = [f"line{k}" for k in row["Lines"].split(",") if k]
            time = to_number(row["FailTime"], self._where("failures", number, "FailTime"))
            tension = to_number(row["FailTen"], self._where("failures", number, "FailTen"))
            if time <= 0 and tension <= 0:
                raise CaseError(
                    f"{self._where('failures', number, 'FailTime')}: neither FailTime nor "
                    "FailTen is positive, so the failure never happens; give one of them"
                )
            failure: dict[str, Any] = {
                "name": f"failure{row['FailureID']}",
                "at": names[point.group(1)],
                "lines": lines,
            }
            if time > 0:
                failure["time"] = time
            if tension > 0:
                failure["tension"] = tension
            out.append(failure)
        return out


def _pinned_on(kind: str, held: dict[str, dict[str, Any]]) -> str:
    """The body a rod attachment ``Body<ID>Pinned`` (or ``Body<ID>Pin``) names, when it is one
    of the deck's; else ''."""
    found = re.fullmatch(r"(body\d+)(pinned|pin)", kind)
    return found.group(1) if found and found.group(1) in held else ""


def _pin(name: str, position, notes: list[str]) -> dict[str, Any]:
    """The imposed body ``<name>_pin`` that a coupled pinned body or rod (MoorDyn's
    CoupledPinned) turns about, held at ``position`` [m]."""
    notes.append(
        f"{name}: a coupled pinned {'rod' if name.startswith('rod') else 'body'}: it turns "
        f"freely about the imposed body {name}_pin, held at the deck's position; give its x, "
        "y, z as time functions to move it, or step it from Python (seacable.coupling.Coupling)"
    )
    return {"name": f"{name}_pin", "type": "imposed", "points": {},
            **{k: constant(v) for k, v in zip("xyz", position, strict=True)}}  # fmt: skip


def _on_body(host: dict[str, Any], a) -> tuple[list[float], list[float]]:
    """The earth position of the point ``a`` (body frame) of a deck body at its initial pose,
    and the body's orientation angles [deg] (a rod pinned to it starts turned as it is)."""
    if host["type"] == "imposed":
        keys = ("x", "y", "z", "roll_deg", "pitch_deg", "yaw_deg")
        pose = [host[k]["value"] for k in keys]
        position, angles = pose[:3], pose[3:]
    else:
        position, angles = host["position"], host.get("orientation_deg", [0.0, 0.0, 0.0])
    roll, pitch, yaw = np.radians(angles)
    rx = np.array([[1, 0, 0], [0, np.cos(roll), -np.sin(roll)], [0, np.sin(roll), np.cos(roll)]])
    ry = np.array([[np.cos(pitch), 0, np.sin(pitch)], [0, 1, 0],
                   [-np.sin(pitch), 0, np.cos(pitch)]])  # fmt: skip
    rz = np.array([[np.cos(yaw), -np.sin(yaw), 0], [np.sin(yaw), np.cos(yaw), 0], [0, 0, 1]])
    at = np.array(position, float) + rz @ ry @ rx @ np.array(a, float)
    return [rounded(v) for v in at], [float(v) for v in angles]


def _join_mass(body: dict[str, Any], mass: float, a, b, diameter: float) -> None:
    """Join a rod's mass [kg] (uniform from a to b, body frame [m], a solid cylinder of
    ``diameter``) to a rigid body's ``mass``, ``centre_of_gravity`` and ``inertia`` (about the
    joint centre of gravity; 3 values when diagonal, else 3x3)."""
    if mass <= 0.0:
        return
    m0 = float(body["mass"])
    c0 = np.array(body.get("centre_of_gravity", [0.0, 0.0, 0.0]), float)
    i0 = np.array(body.get("inertia", [0.0, 0.0, 0.0]), float)
    i0 = np.diag(i0) if i0.ndim == 1 else i0
    a, b = np.array(a, float), np.array(b, float)
    c1 = 0.5 * (a + b)
    length = float(np.linalg.norm(b - a))
    t = (b - a) / length
    across = mass * (length**2 / 12.0 + diameter**2 / 16.0)
    i1 = across * (np.eye(3) - np.outer(t, t)) + mass * diameter**2 / 8.0 * np.outer(t, t)
    total = m0 + mass
    centre = (m0 * c0 + mass * c1) / total

    def moved(inertia, m, c):  # parallel axes to the joint centre
        d = c - centre
        return inertia + m * (d @ d * np.eye(3) - np.outer(d, d))

    inertia = moved(i0, m0, c0) + moved(i1, mass, c1)
    inertia = np.where(np.abs(inertia) < 1e-12 * np.abs(inertia).max(), 0.0, inertia)
    body["mass"] = rounded(total)
    body["centre_of_gravity"] = [rounded(v) for v in centre]
    if np.count_nonzero(inertia - np.diag(np.diag(inertia))):
        body["inertia"] = [[rounded(v) for v in r] for r in inertia]
    else:
        body["inertia"] = [rounded(v) for v in np.diag(inertia)]
