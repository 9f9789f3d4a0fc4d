"""The case-file schema of a system's bodies: fixed, imposed (time functions, a ship's track),
point and 6-DOF rigid bodies with their named points and their force models (``case.forces``),
and the ship-simulator document's dynamics block. ``case.system`` holds the lines and the case.

Conventions (docs/conventions.md): SI units, the earth frame z up with z = 0 at the still-water
surface, angles in degrees in the case file (keys end in ``_deg``). A body's pose is its
reference point's position and its orientation (roll, pitch, yaw: rotations about the earth's x,
y and z axes, applied in that order: R = Rz(yaw) Ry(pitch) Rx(roll)); its points and its centre of
gravity are given in the body frame, relative to the reference point.
"""

from typing import Annotated, Literal

import numpy as np
from pydantic import Field, field_validator, model_validator

from seacable.case.base import (
    ORIGIN,
    Constant,
    HullMesh,
    HydroDatabase,
    NonNeg,
    PerAxis,
    Shape,
    ShipTravel,
    TimeFunction,
    Vector,
    _Model,
)
from seacable.case.document import ADDED_MASS, DocumentDynamics, one_way
from seacable.case.forces import DATABASE_MODELS, MESH_MODELS, ForceModel, Matrix6

Name = Annotated[str, Field(min_length=1, pattern=r"^[A-Za-z0-9_\- ]+$")]
DOF_NAMES = ("surge", "sway", "heave", "roll", "pitch", "yaw")
Dof = Literal["surge", "sway", "heave", "roll", "pitch", "yaw"]


# ---- bodies -------------------------------------------------------------------------------------
class _Body(_Model):
    """What every body has: a name and named points."""

    name: Name
    """Name of the body, by which lines, ties and other bodies refer to it."""
    points: dict[Name, Vector] = {}
    """[m] Named points in the body frame, from the reference point, for lines to attach to;
    every body also has ``origin``, its reference point."""

    @field_validator("points")
    @classmethod
    def _no_origin(cls, points):
        if ORIGIN in points:
            raise ValueError(f"'{ORIGIN}' is every body's reference point; choose another name")
        return points


class FixedBody(_Body):
    """Held at rest: an anchor, a pin, a fixed platform."""

    type: Literal["fixed"]
    """Body kind: held at rest."""
    position: Vector
    """[m] Position of the reference point in the earth frame."""
    orientation_deg: Vector = (0.0, 0.0, 0.0)
    """[deg] Roll, pitch, yaw: rotations about the earth's x, y, z axes, applied in that order."""


class Track(ShipTravel):
    """A towing ship's track in the horizontal plane: from ``start`` [x, y] (m) along the
    heading ``heading_deg`` (from +x towards +y), then, from ``turn.start_time``, a turning
    circle tangent to it. The ship travels a constant ``speed`` [m/s] or the ``distance`` [m]
    given as a time function (an acceleration_profile gives speed changes with exact
    accelerations). The track is exempt from the case's build-up: a tow starts in its steady
    state."""

    start: tuple[float, float] = (0.0, 0.0)
    """[m] Point [x, y] of the track at distance 0, in the earth frame."""
    heading_deg: float = 0.0
    """[deg] Heading of the track's straight part, from +x towards +y."""


class ImposedBody(_Body):
    """Moves as its time functions say, whatever the lines pull: a vessel's or a crane's
    motion, a vehicle's trajectory. Position of the reference point [m] and orientation angles
    [deg] (roll, pitch, yaw) as functions of time. Or a ship on a ``track``: x, y and the yaw
    follow the track (the yaw along its heading; ``yaw_deg`` is then an offset from it, a crab
    angle), z, roll and pitch their time functions. With ``relative_to`` (another imposed body,
    itself not relative), x, y, z are offsets in earth axes from that body's reference point: a
    vehicle's trajectory relative to its ship."""

    type: Literal["imposed"]
    """Body kind: moved by its time functions or its track."""
    x: TimeFunction = Constant(value=0.0)
    """[m] x of the reference point in the earth frame (with ``relative_to``, an offset)."""
    y: TimeFunction = Constant(value=0.0)
    """[m] y of the reference point in the earth frame (with ``relative_to``, an offset)."""
    z: TimeFunction = Constant(value=0.0)
    """[m] z of the reference point in the earth frame (with ``relative_to``, an offset)."""
    roll_deg: TimeFunction = Constant(value=0.0)
    """[deg] Roll: rotation about the earth's x axis, applied first."""
    pitch_deg: TimeFunction = Constant(value=0.0)
    """[deg] Pitch: rotation about the earth's y axis, applied after the roll."""
    yaw_deg: TimeFunction = Constant(value=0.0)
    """[deg] Yaw: rotation about the earth's z axis, applied last; on a ``track``, an offset from
    the track's heading (a crab angle)."""
    track: Track | None = None
    """A ship's track that x, y and the yaw follow, instead of the time functions x and y."""
    relative_to: Name | None = None
    """Imposed body (itself not relative) whose reference point x, y, z are offsets from, in
    earth axes; the angles stay absolute."""

    @model_validator(mode="after")
    def _track_or_xy(self):
        if self.track is not None:
            given = [k for k in ("x", "y") if getattr(self, k) != Constant(value=0.0)]
            if given:
                raise ValueError(
                    f"{given} and 'track' both place the body in the horizontal plane; give "
                    "the start of the track as track.start [x, y] and leave out x and y"
                )
        return self


class _Dynamic(_Body):
    """What every moving body has: its initial state, mass, volume and force models."""

    position: Vector
    """[m] Initial position of the reference point in the earth frame."""
    velocity: Vector = (0.0, 0.0, 0.0)
    """[m/s] Initial velocity of the reference point in the earth frame."""
    mass: NonNeg
    """[kg] Mass of the body."""
    volume: NonNeg = 0.0
    """[m^3] Displaced volume when wholly submerged, for buoyancy and fluid inertia."""
    shape: Shape | None = None
    """Shape whose part below the free surface gives the displaced volume; instead of
    ``volume``."""
    external_forces: list[ForceModel] = Field(default=[], alias="external forces")
    """Force models acting on the body, besides its lines, ties and joints."""

    @model_validator(mode="after")
    def _volume_or_shape(self):
        if self.shape is not None and self.volume:
            raise ValueError("give 'volume' [m^3] or 'shape', not both")
        needs = [f.model for f in self.external_forces if f.model == "buoyancy"]
        if needs and self.shape is None and not self.volume:
            raise ValueError("force model 'buoyancy' needs the body's 'volume' [m^3] or 'shape'")
        models = {f.model for f in self.external_forces}
        if "fluid inertia" in models:
            added = np.any(np.asarray(getattr(self, "added_mass", 0.0), float)) or any(
                getattr(self, k, None) is not None for k in ("dynamics", "hydrodynamics")
            )
            if self.shape is None and not self.volume and not added:
                raise ValueError(
                    "force model 'fluid inertia' acts on the body's 'volume' [m^3] (or "
                    "'shape') and its 'added_mass' [kg]: give one of them, or remove the model"
                )
            twice = sorted(models & {"non-linear Froude-Krylov", "diffraction"})
            if twice:
                raise ValueError(
                    f"force models 'fluid inertia' and '{twice[0]}' both give the waves' "
                    "Froude-Krylov force; keep one of them"
                )
        return self

    def displaced_volume(self) -> float:
        """Volume wholly submerged [m^3]."""
        return self.shape.volume() if self.shape is not None else self.volume


class PointBody(_Dynamic):
    """Three translational degrees of freedom: a buoy, a clump weight, a towed fish, the
    connection between line sections. Its points are all its reference point."""

    type: Literal["point"]
    """Body kind: free in translation only."""
    added_mass: PerAxis = 0.0
    """[kg] Added mass, one for all or one per earth axis x, y, z (scaled by a shape's
    submergence)."""
    dofs: list[Literal["surge", "sway", "heave"]] = ["surge", "sway", "heave"]
    """Translations along the earth's x, y, z that move; the others keep their initial values."""

    @field_validator("points")
    @classmethod
    def _at_origin(cls, points):
        off = {k: v for k, v in points.items() if any(v)}
        if off:
            raise ValueError(
                f"a point body's points are its reference point; got {off}: use type 'rigid'"
            )
        return points


class RigidBody(_Dynamic):
    """Six degrees of freedom (or those of ``dofs``: a heaving buoy is ``[heave]``, a ship in
    the horizontal plane ``[surge, sway, yaw]``; the others are held at their initial values).
    surge, sway, heave move the reference point along the earth's x, y, z; roll, pitch, yaw turn
    the body about the earth's x, y, z axes through the reference point."""

    type: Literal["rigid"]
    """Body kind: free in translation and rotation."""
    orientation_deg: Vector = (0.0, 0.0, 0.0)
    """[deg] Initial roll, pitch, yaw: rotations about the earth's x, y, z axes, in that order."""
    angular_velocity: Vector = (0.0, 0.0, 0.0)
    """[rad/s] Initial angular velocity in the earth frame."""
    centre_of_gravity: Vector = (0.0, 0.0, 0.0)
    """[m] Centre of gravity in the body frame, from the reference point."""
    inertia: Vector | tuple[Vector, Vector, Vector] = (0.0, 0.0, 0.0)
    """[kg m^2] Inertia about the centre of gravity in the body frame: the diagonal or the 3x3
    matrix."""
    added_mass: Matrix6 | tuple[float, float, float, float, float, float] = (0.0,) * 6
    """[kg, kg m, kg m^2] Added mass in the body frame at ``added_mass_point``: the 6x6 matrix or
    its diagonal; moved to the reference point."""
    added_mass_point: Vector | None = None
    """[m] Point, in the body frame, the added mass is given at. Omitted: the reference point."""
    coriolis: Literal["rigid_body", "exact"] = "rigid_body"
    """The added mass's velocity terms: ``rigid_body``, the ship-simulator document's body-frame
    equation with the Coriolis matrix of the rigid-body mass only; ``exact``, Kirchhoff's (the
    fluid's impulse turns with the body too)."""
    centre_of_buoyancy: Vector = (0.0, 0.0, 0.0)
    """[m] Centre of buoyancy in the body frame, where buoyancy and fluid inertia act and the
    document's added mass is given."""
    dofs: list[Dof] = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    """Degrees of freedom that move; the others keep their initial values. With ``pinned_to``:
    rotations only, all three by default."""
    pinned_to: str | None = None
    """A spherical joint: the reference point held at another body's point (``body.point``, or
    ``body`` for its reference point), the body turning freely about it. The joint's force
    acts on both bodies (in their results' line_force and line_moment)."""
    mesh: HullMesh | None = None
    """The hull, for the mesh force models."""
    hydrodynamics: HydroDatabase | None = None
    """Hydrodynamic database, for radiation damping and diffraction."""
    dynamics: DocumentDynamics | None = None
    """The ship-simulator document's ``dynamics`` block, read as written (z down): its mass,
    centre of inertia, rigid-body inertia and added mass instead of the body's own keys."""

    @model_validator(mode="before")
    @classmethod
    def _one_way(cls, data):
        return one_way(data) if isinstance(data, dict) else data

    @model_validator(mode="after")
    def _document_dynamics(self):
        """The document's block read: its values set in the body's own keys (frozen: set once,
        here), its frames the body's own, its added mass's centre of buoyancy found."""
        if self.dynamics is None:
            return self
        self.dynamics.check_frames(self.name)
        values = self.dynamics.seacable_values()
        position = values.pop("position", None)
        if position is not None:
            assert self.hydrodynamics is not None  # document.one_way
            object.__setattr__(
                self, "hydrodynamics", self.hydrodynamics.model_copy(update={"position": position})
            )
        for key, value in values.items():
            object.__setattr__(self, key, value)
        if self.dynamics.added_mass is not None and not self.hull_floats():
            raise ValueError(
                f"dynamics.{ADDED_MASS}: the matrix is at the still-water centre of buoyancy, "
                "found from the hull: give the hull's 'mesh', or the point as "
                "'centre_of_buoyancy' [m, body frame, z up]"
            )
        return self

    def hull_floats(self) -> bool:
        """True when the still-water centre of buoyancy is known: given, or the mesh's."""
        return "centre_of_buoyancy" in self.model_fields_set or self.mesh is not None

    @field_validator("dofs")
    @classmethod
    def _unique(cls, dofs):
        if len(set(dofs)) != len(dofs):
            raise ValueError(f"dofs lists a degree of freedom twice: {dofs}")
        return dofs

    @model_validator(mode="after")
    def _pinned_rotations(self):
        if self.pinned_to is None:
            return self
        if "dofs" not in self.model_fields_set:  # frozen: the default set once, here
            object.__setattr__(self, "dofs", ["roll", "pitch", "yaw"])
        moved = [d for d in self.dofs if d in DOF_NAMES[:3]]
        if moved:
            raise ValueError(
                f"dofs {moved}: a body pinned to '{self.pinned_to}' moves with that point; its "
                "dofs are its rotations (roll, pitch, yaw): remove the translations"
            )
        if self.velocity != (0.0, 0.0, 0.0):
            raise ValueError(
                f"velocity {list(self.velocity)}: a body pinned to '{self.pinned_to}' starts "
                "with that point's velocity; leave the velocity out"
            )
        return self

    @model_validator(mode="after")
    def _physical_inertia(self):
        """A mass that moves, an inertia matrix a body can have (symmetric, positive), an
        added mass that is not negative (its symmetric part)."""
        added = np.asarray(self.added_mass, dtype=float)
        added = np.diag(added) if added.ndim == 1 else added
        document_added = self.dynamics is not None and self.dynamics.added_mass is not None
        if self.dofs and self.mass <= 0.0 and not document_added and not np.any(added[:3, :3]):
            raise ValueError(
                f"mass {self.mass:g} kg: a rigid body that moves needs a mass (or an added "
                "mass); give it in kg"
            )
        inertia = np.asarray(self.inertia, dtype=float)
        inertia = np.diag(inertia) if inertia.ndim == 1 else inertia
        full = np.any(inertia - np.diag(np.diag(inertia)))
        shown = inertia.tolist() if full else np.diag(inertia).tolist()
        scale = max(float(np.abs(inertia).max()), 1e-300)
        if np.abs(inertia - inertia.T).max() > 1e-9 * scale:
            raise ValueError(
                f"inertia {shown}: not symmetric, as every inertia matrix is (I_xy = I_yx, ...); "
                "check its rows (kg m^2, about the centre of gravity, body frame)"
            )
        moments = np.linalg.eigvalsh(inertia)
        if moments[0] < -1e-9 * scale:
            raise ValueError(
                f"inertia {shown}: not positive (its principal moments are "
                f"{', '.join(f'{m:.4g}' for m in moments)} kg m^2), which no body has; check "
                "the signs (products of inertia are -sum m x y in some conventions)"
            )
        # (the largest principal moment above the sum of the two others is no mass
        # distribution either, but ships' usual radii of gyration, 0.35 B, 0.25 L, 0.26 L,
        # exceed it by a few per cent: not refused)
        symmetric = 0.5 * (added + added.T)
        low = float(np.linalg.eigvalsh(symmetric)[0])
        if low < -1e-9 * max(float(np.abs(added).max()), 1e-300):
            raise ValueError(
                f"added_mass: negative (the least eigenvalue of its symmetric part is "
                f"{low:.4g}), which would make the body lighter than itself when it "
                "accelerates; check the signs and the matrix's layout (kg, kg m, kg m^2)"
            )
        return self

    @model_validator(mode="after")
    def _mesh_models(self):
        needs = [f.model for f in self.external_forces if f.model in MESH_MODELS]
        if needs and self.mesh is None:
            raise ValueError(
                f"force model '{needs[0]}' needs the body's hull: give 'mesh' "
                "(file: hull.stl, and its placement)"
            )
        needs = [f.model for f in self.external_forces if f.model in DATABASE_MODELS]
        if needs and self.hydrodynamics is None:
            raise ValueError(
                f"force model '{needs[0]}' needs the body's hydrodynamic database: give "
                "'hydrodynamics' (file: hull.nc, from seacable hydrodb)"
            )
        _one_incident_pressure(self.external_forces)
        both = {"buoyancy", "non-linear hydrostatic"} <= {f.model for f in self.external_forces}
        if both:
            raise ValueError(
                "'buoyancy' and 'non-linear hydrostatic' both give the body its buoyancy; "
                "keep one of them"
            )
        return self


def _one_incident_pressure(forces) -> None:
    """The incident wave's pressure counted once: a database's linear Froude-Krylov force
    (``diffraction`` with ``froude_krylov``) holds its rho g eta at the waterline and its
    dynamic part, as the mesh models clipped at the wave elevation do."""
    linear = [f for f in forces if f.model == "diffraction" and f.froude_krylov]
    if not linear:
        return
    for f in forces:
        if f.model == "non-linear Froude-Krylov":
            raise ValueError(
                "'diffraction' with froude_krylov: true and 'non-linear Froude-Krylov' both "
                "give the incident wave's pressure; keep one of them"
            )
        if f.model == "non-linear hydrostatic" and f.free_surface == "waves":
            raise ValueError(
                "'non-linear hydrostatic' clipped at the wave elevation and 'diffraction' with "
                "froude_krylov: true both count the incident wave's rho g eta; give the "
                "hydrostatics free_surface: still"
            )


Body = Annotated[FixedBody | ImposedBody | PointBody | RigidBody, Field(discriminator="type")]
