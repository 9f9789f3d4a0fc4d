"""The ship-simulator document's ``dynamics`` block of a rigid body, read as the document
writes it: its keys (``mass``, ``centre of inertia``, ``rigid body inertia matrix at the center
of gravity and projected in the body frame``, ``added mass matrix at the center of buoyancy
projected in the body frame``, ``hydrodynamic forces calculation point in body frame``), its
quantities with their units (``{value: 253.31, unit: tonne}``), its matrices by rows, all in its
body frame: x forward, y to starboard, z down. ``seacable_values`` turns them once into
seacable's body frame (x forward, y to port, z up: half a turn about x, docs/conventions.md,
"Vessels"); the added mass is turned and moved when the system is built (system.hulls), since
its point, the still-water centre of buoyancy, comes from the hull.
"""

from typing import Annotated, Literal

import numpy as np
from pydantic import BeforeValidator, Field, model_validator

from seacable.case.base import NonNeg, _Model

Z_DOWN = np.diag([1.0, -1.0, -1.0])  # the document's body frame (z down) to ours, and back
TURN6 = np.diag([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])  # the same half turn on (v, w)
ADDED_MASS = "added mass matrix at the center of buoyancy projected in the body frame"
RIGID_BODY = "rigid body inertia matrix at the center of gravity and projected in the body frame"
RIGID_AT_BUOYANCY = (
    "rigid body inertia matrix at the center of buoyancy projected in the body frame"
)
CENTRE = "centre of inertia"
HYDRODYNAMIC_POINT = "hydrodynamic forces calculation point in body frame"
MASS_UNITS = {"kg": 1.0, "t": 1000.0, "tonne": 1000.0}
DOFS = "surge, sway, heave, roll, pitch, yaw"
TOLERANCE = 1e-9  # relative: a matrix entry this small beside the largest is zero


def _six(values):
    """A matrix row of six numbers, or a one-line refusal saying how many it has."""
    if isinstance(values, list | tuple) and len(values) != 6:
        raise ValueError(
            f"{len(values)} numbers; a row of the 6x6 matrix has 6 ({DOFS}): complete the row"
        )
    return values


Row6 = Annotated[tuple[float, float, float, float, float, float], BeforeValidator(_six)]
Name = Annotated[str, Field(min_length=1, pattern=r"^[A-Za-z0-9_\- ]+$")]


class DocumentMatrix(_Model):
    """A 6x6 matrix as the ship-simulator document writes it: ``frame`` (the body's own name)
    and ``row 1`` ... ``row 6``, in its body frame (x forward, y to starboard, z down) [kg,
    kg m, kg m^2]."""

    frame: Name
    """Frame the matrix is projected in: the body's own name."""
    row_1: Row6 = Field(alias="row 1")
    """[kg; kg m] Surge row: the first three entries in kg, the last three in kg m."""
    row_2: Row6 = Field(alias="row 2")
    """[kg; kg m] Sway row: the first three entries in kg, the last three in kg m."""
    row_3: Row6 = Field(alias="row 3")
    """[kg; kg m] Heave row: the first three entries in kg, the last three in kg m."""
    row_4: Row6 = Field(alias="row 4")
    """[kg m; kg m^2] Roll row: the first three entries in kg m, the last three in kg m^2."""
    row_5: Row6 = Field(alias="row 5")
    """[kg m; kg m^2] Pitch row: the first three entries in kg m, the last three in kg m^2."""
    row_6: Row6 = Field(alias="row 6")
    """[kg m; kg m^2] Yaw row: the first three entries in kg m, the last three in kg m^2."""

    def rows(self) -> np.ndarray:
        return np.array([self.row_1, self.row_2, self.row_3, self.row_4, self.row_5,
                         self.row_6], dtype=float)  # fmt: skip

    def turned(self) -> np.ndarray:
        """The matrix in seacable's body frame: T M T, T the half turn about x (an entry
        changes sign when exactly one of its two motions is sway, heave, pitch or yaw)."""
        return TURN6 @ self.rows() @ TURN6


class Length(_Model):
    """A length as the document writes it: ``{value: 0.258, unit: m}``."""

    value: float
    """[unit] The length."""
    unit: Literal["m"]
    """Its unit: m."""

    @model_validator(mode="before")
    @classmethod
    def _with_unit(cls, data):
        if not isinstance(data, dict):
            raise ValueError(f"{data!r}: the document writes a length with its unit: write "
                             f"{{value: {data}, unit: m}}")  # fmt: skip
        return data


class DocumentPoint(_Model):
    """A point of the body frame as the document writes it: ``x``, ``y``, ``z`` each with its
    unit, from the body frame's origin (the reference point), z down, y to starboard."""

    x: Length
    """Forward of the reference point, with its unit."""
    y: Length
    """To starboard of the reference point (the document's y), with its unit."""
    z: Length
    """Below the reference point (the document's z, down), with its unit."""

    def ours(self) -> tuple[float, float, float]:
        """The point in seacable's body frame (y to port, z up) [m]."""
        x, y, z = Z_DOWN @ np.array([self.x.value, self.y.value, self.z.value])
        return (float(x), float(y), float(z))


class FramedPoint(DocumentPoint):
    """A point with the frame it is given in (the body's own name)."""

    frame: Name
    """Frame the point is given in: the body's own name."""


class Mass(_Model):
    """A mass as the document writes it: ``{value: 253.31, unit: tonne}``."""

    value: NonNeg
    """[unit] The mass."""
    unit: str
    """Its unit: kg, t or tonne (1000 kg)."""

    @model_validator(mode="after")
    def _known_unit(self):
        if self.unit not in MASS_UNITS:
            ton = " ('ton' is the short ton, 907.185 kg, or the long ton, 1016.05 kg)"
            raise ValueError(
                f"unit '{self.unit}' is not a unit of mass seacable reads"
                f"{ton if self.unit == 'ton' else ''}; write kg, t or tonne (1000 kg)"
            )
        return self

    def kilograms(self) -> float:
        return self.value * MASS_UNITS[self.unit]


class DocumentDynamics(_Model):
    """The ship-simulator document's ``dynamics`` block of a body, read as written (each key
    optional; the body's own keys give what it leaves out): its mass, centre of inertia and
    rigid-body inertia at the centre of gravity, its infinite-frequency added mass at the
    centre of buoyancy (the still-water one), the point its hydrodynamic database's forces are
    given at; all in the document's z-down body frame, turned into seacable's once."""

    hydrodynamic_point: DocumentPoint | None = Field(
        None, alias="hydrodynamic forces calculation point in body frame"
    )
    """The point the hydrodynamic database's forces are given at, instead of
    ``hydrodynamics.position``."""
    centre_of_inertia: FramedPoint | None = Field(None, alias="centre of inertia")
    """The centre of gravity, instead of ``centre_of_gravity``."""
    mass: Mass | None = None
    """The body's mass, instead of the body's ``mass``."""
    rigid_body: DocumentMatrix | None = Field(
        None,
        alias="rigid body inertia matrix at the center of gravity and projected in the body frame",
    )
    """The rigid-body inertia at the centre of gravity: m on the first three diagonal entries,
    the inertia about the centre of gravity in the last three rows and columns, the rest zero;
    instead of ``inertia`` (and ``mass``)."""
    added_mass: DocumentMatrix | None = Field(
        None, alias="added mass matrix at the center of buoyancy projected in the body frame"
    )
    """Infinite-frequency added mass at the still-water centre of buoyancy, instead of
    ``added_mass``."""

    @model_validator(mode="before")
    @classmethod
    def _not_at_buoyancy(cls, data):
        if isinstance(data, dict) and RIGID_AT_BUOYANCY in data:
            raise ValueError(
                f"'{RIGID_AT_BUOYANCY}': seacable reads the rigid-body inertia at the centre of "
                f"gravity (the '{CENTRE}'), where its coupling terms are zero; write the matrix "
                f"there, under '{RIGID_BODY}'"
            )
        if isinstance(data, dict) and not data:
            raise ValueError(
                f"empty; give its keys ({ADDED_MASS}, {RIGID_BODY}, mass, {CENTRE}, "
                f"{HYDRODYNAMIC_POINT}) or remove it"
            )
        return data

    @model_validator(mode="after")
    def _rigid_body_at_gravity(self):
        """The rigid-body matrix of a body at its centre of gravity: one mass on the first
        three diagonal entries (the document's ``mass``, when both are given), no coupling."""
        if self.rigid_body is None:
            return self
        rows = self.rigid_body.rows()
        scale = max(float(np.abs(rows).max()), 1e-300)
        mass = rows[0, 0]
        off = np.abs(rows[:3, :3] - mass * np.eye(3)).max()
        if off > TOLERANCE * scale:
            diagonal = ", ".join(f"{v:.6g}" for v in np.diag(rows)[:3])
            raise ValueError(
                f"{RIGID_BODY}: rows 1 to 3 give the masses {diagonal} kg (and off-diagonal "
                f"entries up to {np.abs(rows[:3, :3] - np.diag(np.diag(rows[:3, :3]))).max():.6g}"
                "); a rigid body has one mass, on the three diagonal entries: write m there "
                "and 0 elsewhere in columns 1 to 3"
            )
        coupling = max(np.abs(rows[:3, 3:]).max(), np.abs(rows[3:, :3]).max())
        if coupling > TOLERANCE * scale:
            raise ValueError(
                f"{RIGID_BODY}: coupling terms (rows 1-3 columns 4-6, rows 4-6 columns 1-3) up "
                f"to {coupling:.6g} kg m; at the centre of gravity they are zero: give the "
                f"matrix there, its centre as '{CENTRE}'"
            )
        if self.mass is not None and abs(self.mass.kilograms() - mass) > TOLERANCE * scale:
            raise ValueError(
                f"mass {self.mass.value:g} {self.mass.unit} and {RIGID_BODY} (row 1: {mass:g} kg) "
                "give two masses; keep one of them, or make them agree"
            )
        return self

    def check_frames(self, body: str) -> None:
        """Refuse a matrix or point given in another frame than the body's own (ValueError)."""
        for key, part in ((ADDED_MASS, self.added_mass), (RIGID_BODY, self.rigid_body),
                          (CENTRE, self.centre_of_inertia)):  # fmt: skip
            if part is not None and part.frame != body:
                raise ValueError(
                    f"dynamics.{key}.frame: '{part.frame}' is not this body; it is given in the "
                    f"body's own frame: write frame: {body}"
                )

    def seacable_values(self) -> dict:
        """The body's own keys the block gives, in seacable's body frame (z up, y to port):
        ``mass`` [kg], ``centre_of_gravity`` [m], ``inertia`` [kg m^2, about the centre of
        gravity] and the hydrodynamic database's ``position`` [m]."""
        out: dict = {}
        if self.mass is not None:
            out["mass"] = self.mass.kilograms()
        if self.rigid_body is not None:
            turned = self.rigid_body.turned()
            out["mass"] = float(turned[0, 0])
            out["inertia"] = tuple(tuple(float(v) for v in row) for row in turned[3:, 3:])
        if self.centre_of_inertia is not None:
            out["centre_of_gravity"] = self.centre_of_inertia.ours()
        if self.hydrodynamic_point is not None:
            out["position"] = self.hydrodynamic_point.ours()
        return out


# the document's keys -> the body's own keys that give the same (one way to give each)
SAME_AS = {
    "mass": ("mass",),
    RIGID_BODY: ("inertia", "mass"),
    CENTRE: ("centre_of_gravity",),
    ADDED_MASS: ("added_mass", "added_mass_point"),
}


def one_way(body: dict) -> dict:
    """A raw body (the case file's mapping) whose ``dynamics`` block and own keys give each
    quantity once, with a placeholder ``mass`` when the block gives it (set from the block once
    it is read); a ValueError naming both keys otherwise."""
    block = body.get("dynamics")
    if not isinstance(block, dict):
        return body
    for key, ours in SAME_AS.items():
        both = [k for k in ours if k in body] if key in block else []
        if both:
            raise ValueError(
                f"'{both[0]}' and the document's 'dynamics.{key}' both give the body's "
                f"{both[0].replace('_', ' ')}; keep one of them"
            )
    hydro = body.get("hydrodynamics")
    if HYDRODYNAMIC_POINT in block:
        if not isinstance(hydro, dict):
            raise ValueError(
                f"'dynamics.{HYDRODYNAMIC_POINT}' is where the hydrodynamic database's forces are "
                "given, and the body has no 'hydrodynamics': give it (file: hull.nc) or remove "
                "the point"
            )
        if "position" in hydro:
            raise ValueError(
                f"'hydrodynamics.position' and the document's 'dynamics.{HYDRODYNAMIC_POINT}' "
                "both give the database's point; keep one of them"
            )
    if ("mass" in block or RIGID_BODY in block) and "mass" not in body:
        body = {**body, "mass": 0.0}  # the block's, once read (RigidBody._document_dynamics)
    return body
