"""The case-file schema of a system of bodies and lines: named bodies with named points, the
force models acting on each body (their schemas in ``case.forces``), named line types, and lines
between body points.

Conventions (docs/conventions.md): SI units, the earth frame z up with z = 0 at the still-water
surface, angles in degrees in the case file (keys end in ``_deg``). A body's pose is its
reference point's position and its orientation (roll, pitch, yaw: rotations about the earth's x,
y and z axes, applied in that order: R = Rz(yaw) Ry(pitch) Rx(roll)); its points and its centre of
gravity are given in the body frame, relative to the reference point.
"""

from typing import Annotated, Literal

import numpy as np
from pydantic import Field, PrivateAttr, field_validator, model_validator

from seacable.case.base import (
    Constant,
    HullMesh,
    HydroDatabase,
    NonNeg,
    PerAxis,
    Pos,
    Shape,
    ShipTravel,
    Simulation,
    TimeFunction,
    _Model,
)
from seacable.case.environment import Environment
from seacable.case.forces import DATABASE_MODELS, MESH_MODELS, ORIGIN, ForceModel, Matrix6, Vector

Name = Annotated[str, Field(min_length=1, pattern=r"^[A-Za-z0-9_\- ]+$")]
DOF_NAMES = ("surge", "sway", "heave", "roll", "pitch", "yaw")
Dof = Literal["surge", "sway", "heave", "roll", "pitch", "yaw"]


# ---- bodies -------------------------------------------------------------------------------------
class _Body(_Model):
    name: Name
    points: dict[Name, Vector] = {}  # attachment points in the body frame [m]

    @field_validator("points")
    @classmethod
    def _no_origin(cls, points):
        if ORIGIN in points:
            raise ValueError(f"'{ORIGIN}' is every body's reference point; choose another name")
        return points


class FixedBody(_Body):
    """Held at rest: an anchor, a pin, a fixed platform."""

    type: Literal["fixed"]
    position: Vector  # [m]
    orientation_deg: Vector = (0.0, 0.0, 0.0)  # roll, pitch, yaw [deg]


class Track(ShipTravel):
    """A towing ship's track in the horizontal plane: from ``start`` [x, y] (m) along the
    heading ``heading_deg`` (from +x towards +y), then, from ``turn.start_time``, a turning
    circle tangent to it. The ship travels a constant ``speed`` [m/s] or the ``distance`` [m]
    given as a time function (an acceleration_profile gives speed changes with exact
    accelerations). The track is exempt from the case's build-up: a tow starts in its steady
    state."""

    start: tuple[float, float] = (0.0, 0.0)  # [m]
    heading_deg: float = 0.0


class ImposedBody(_Body):
    """Moves as its time functions say, whatever the lines pull: a vessel's or a crane's
    motion, a vehicle's trajectory. Position of the reference point [m] and orientation angles
    [deg] (roll, pitch, yaw) as functions of time. Or a ship on a ``track``: x, y and the yaw
    follow the track (the yaw along its heading; ``yaw_deg`` is then an offset from it, a crab
    angle), z, roll and pitch their time functions. With ``relative_to`` (another imposed body,
    itself not relative), x, y, z are offsets in earth axes from that body's reference point: a
    vehicle's trajectory relative to its ship."""

    type: Literal["imposed"]
    x: TimeFunction = Constant(value=0.0)  # [m]
    y: TimeFunction = Constant(value=0.0)  # [m]
    z: TimeFunction = Constant(value=0.0)  # [m]
    roll_deg: TimeFunction = Constant(value=0.0)  # [deg]
    pitch_deg: TimeFunction = Constant(value=0.0)  # [deg]
    yaw_deg: TimeFunction = Constant(value=0.0)  # [deg]
    track: Track | None = None
    relative_to: Name | None = None

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
    position: Vector  # initial position of the reference point [m]
    velocity: Vector = (0.0, 0.0, 0.0)  # initial [m/s]
    mass: NonNeg  # [kg]
    volume: NonNeg = 0.0  # displaced volume when wholly submerged [m^3]
    shape: Shape | None = None  # instead of volume: the volume the free surface cuts
    external_forces: list[ForceModel] = Field(default=[], alias="external forces")

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
    added_mass: PerAxis = 0.0  # per earth axis x, y, z [kg] (scaled by a shape's submergence)
    dofs: list[Literal["surge", "sway", "heave"]] = ["surge", "sway", "heave"]

    @field_validator("points")
    @classmethod
    def _at_origin(cls, points):
        off = {k: v for k, v in points.items() if any(v)}
        if off:
            raise ValueError(
                f"a point body's points are its reference point; got {off}: use type 'rigid'"
            )
        return points


Row6 = tuple[float, float, float, float, float, float]
DOCUMENT_ADDED_MASS = "added mass matrix at the center of buoyancy projected in the body frame"


class DocumentMatrix(_Model):
    """A 6x6 matrix as the ship-simulator document writes it: ``frame`` (the body's own name)
    and ``row 1`` ... ``row 6``, in its body frame (x forward, y to starboard, z down) [kg,
    kg m, kg m^2]."""

    frame: Name
    row_1: Row6 = Field(alias="row 1")
    row_2: Row6 = Field(alias="row 2")
    row_3: Row6 = Field(alias="row 3")
    row_4: Row6 = Field(alias="row 4")
    row_5: Row6 = Field(alias="row 5")
    row_6: Row6 = Field(alias="row 6")

    def rows(self) -> np.ndarray:
        return np.array([self.row_1, self.row_2, self.row_3, self.row_4, self.row_5,
                         self.row_6], dtype=float)  # fmt: skip


class DocumentDynamics(_Model):
    """The ship-simulator document's ``dynamics`` block of a body, read as written: the
    infinite-frequency added mass at the centre of buoyancy, in the document's body frame
    (z down, y to starboard), turned into seacable's once (docs/conventions.md, "Vessels") and
    moved to the reference point."""

    added_mass: DocumentMatrix = Field(
        alias="added mass matrix at the center of buoyancy projected in the body frame"
    )


class RigidBody(_Dynamic):
    """Six degrees of freedom (or those of ``dofs``: a heaving buoy is ``[heave]``, a ship in
    the horizontal plane ``[surge, sway, yaw]``; the others are held at their initial values).
    surge, sway, heave move the reference point along the earth's x, y, z; roll, pitch, yaw turn
    the body about the earth's x, y, z axes through the reference point."""

    type: Literal["rigid"]
    orientation_deg: Vector = (0.0, 0.0, 0.0)  # initial roll, pitch, yaw [deg]
    angular_velocity: Vector = (0.0, 0.0, 0.0)  # initial, earth frame [rad/s]
    centre_of_gravity: Vector = (0.0, 0.0, 0.0)  # body frame [m]
    inertia: Vector | tuple[Vector, Vector, Vector] = (0.0, 0.0, 0.0)  # about the CoG,
    # body frame [kg m^2]: the diagonal, or the 3x3 matrix
    added_mass: Matrix6 | tuple[float, float, float, float, float, float] = (0.0,) * 6
    # body frame [kg, kg m, kg m^2]: 6x6, or its diagonal; at ``added_mass_point`` (body frame,
    # default the reference point), moved to the reference point (packing.transported)
    added_mass_point: Vector | None = None
    # the added mass's velocity terms (bodies.dynamics): "rigid_body", the ship-simulator
    # document's body-frame equation with the Coriolis matrix of the rigid-body mass only, or
    # "exact", Kirchhoff's (the fluid's impulse turns with the body too)
    coriolis: Literal["rigid_body", "exact"] = "rigid_body"
    centre_of_buoyancy: Vector = (0.0, 0.0, 0.0)  # body frame [m]
    dofs: list[Dof] = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    mesh: HullMesh | None = None  # the hull, for the mesh force models
    hydrodynamics: HydroDatabase | None = None  # for radiation damping and diffraction
    # the ship-simulator document's block (its added mass at the centre of buoyancy, z down)
    dynamics: DocumentDynamics | None = None

    @model_validator(mode="after")
    def _document_dynamics(self):
        if self.dynamics is None:
            return self
        frame = self.dynamics.added_mass.frame
        if frame != self.name:
            raise ValueError(
                f"dynamics.{DOCUMENT_ADDED_MASS}.frame: '{frame}' is not this body; the matrix "
                f"is projected in the body's own frame: write frame: {self.name}"
            )
        given = [k for k in ("added_mass", "added_mass_point") if k in self.model_fields_set]
        if given:
            raise ValueError(
                f"'{given[0]}' and the document's 'dynamics' block both give the added mass; "
                "keep one of them"
            )
        if "centre_of_buoyancy" not in self.model_fields_set and self.mesh is None:
            raise ValueError(
                "the document's added mass is at the centre of buoyancy: give "
                "'centre_of_buoyancy' [m, body frame, z up] or the hull's 'mesh'"
            )
        return self

    @field_validator("dofs")
    @classmethod
    def _unique(cls, dofs):
        if len(set(dofs)) != len(dofs):
            raise ValueError(f"dofs lists a degree of freedom twice: {dofs}")
        return dofs

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


# ---- line types and lines -----------------------------------------------------------------------
class LineType(_Model):
    """Properties of a cable, rope or chain, per unit length."""

    name: Name
    diameter: Pos  # hydrodynamic and buoyancy diameter [m]
    mass_per_length: Pos  # [kg/m]
    axial_stiffness: Pos | None = None  # EA [N] (extensible models)
    # axial damping, at most one of: alpha [s] in N = EA (eps + alpha d eps/dt), or zeta, the
    # fraction of each segment's critical damping (MoorDyn's negative BA)
    axial_damping_time: NonNeg | None = None  # [s]
    axial_damping_ratio: NonNeg | None = None  # [-]
    bending_stiffness: NonNeg = 0.0  # EI [N m^2]
    drag_coefficient_normal: NonNeg = 1.2  # Cd on the projected area d l
    drag_coefficient_tangential: NonNeg = 0.0  # Cd on the wetted area pi d l
    friction_coefficient: NonNeg = 0.0  # Richtmyer f
    added_mass_coefficient: NonNeg = 1.0  # Ca, normal
    # Ca along the line (MoorDyn's CaAx; lumped-mass lines only)
    added_mass_coefficient_tangential: NonNeg = 0.0
    # minimum breaking load [N]: results give each section's largest tension over it
    breaking_strength: Pos | None = None

    @model_validator(mode="after")
    def _one_damping(self):
        if self.axial_damping_time is not None and self.axial_damping_ratio is not None:
            raise ValueError(
                "give at most one of 'axial_damping_time' [s] or 'axial_damping_ratio'"
            )
        return self


MOST_SEGMENTS = 2_000_000  # segments of all lines of a case
# how far below z = -water_depth a body or node may start [m]: depths written to the centimetre
# (the thesis's 150.19 m under an end at -150.19026 m) are not refused
SEABED_TOLERANCE = 1e-3


class Section(_Model):
    """A stretch of a line: ``length`` [m] of line type ``type`` in ``segments`` equal
    segments. Sections of different lengths, types and joints make a line of unequal segments.

    The joint at the start of each of its segments (between that segment and the one before;
    a rigid line's first joint against ``base_reference``, a lumped line's first node a pin)
    has the spring ``joint_stiffness`` [N m/rad] when given, instead of the line types' EI over
    the mean span of its two segments, and (rigid lines) the damper ``joint_damping``
    [N m s/rad] when given, instead of the line's."""

    type: Name
    length: Pos  # unstretched [m]
    segments: int = Field(ge=1, le=100_000)
    joint_stiffness: NonNeg | None = None  # [N m/rad]
    joint_damping: NonNeg | None = None  # [N m s/rad] (rigid lines)


class LineAngles(_Model):
    """A line's initial shape given by its segments' angles from the downward vertical,
    positive towards +x [deg] (in the vertical plane at ``azimuth_deg`` from +x towards +y for
    a 3D line): ``angles_deg``, one per segment, or ``arc_deg`` [first, last], varying linearly
    along the line, each segment at its unstretched length. The line starts from its ``from``
    point; a body a rigid line carries must be at its end, a held end's point (and a lumped
    line's ``to`` point) within 1 mm of it."""

    angles_deg: list[float] | None = None
    arc_deg: tuple[float, float] | None = None
    azimuth_deg: float = 0.0

    @model_validator(mode="after")
    def _one_form(self):
        if (self.angles_deg is None) == (self.arc_deg is None):
            raise ValueError("give exactly one of 'angles_deg' (one per segment) or 'arc_deg' "
                             "[first, last]")  # fmt: skip
        given = [*(self.angles_deg or []), *(self.arc_deg or []), self.azimuth_deg]
        if any(abs(angle) > 360.0 for angle in given):
            raise ValueError("angles are in degrees and should lie within [-360, 360]")
        return self

    def angles(self, n: int) -> list[float]:
        """The n angles [deg]."""
        if self.angles_deg is not None:
            return list(self.angles_deg)
        assert self.arc_deg is not None  # _one_form
        return [float(a) for a in np.linspace(self.arc_deg[0], self.arc_deg[1], n)]


class LumpedMassLine(_Model):
    """An extensible line of lumped masses (Poth's displacement variables, as MoorDyn): its
    end nodes follow the points ``from`` and ``to`` (``body`` or ``body.point``) and give them
    their mass and the line's force."""

    name: Name
    model: Literal["lumped_mass"]
    from_: str = Field(alias="from")
    to: str
    sections: list[Section] = Field(min_length=1)
    # its static shape between its ends (with the seabed), a straight line, or given angles
    initial: Literal["catenary", "straight"] | LineAngles = "catenary"


class RigidLine(_Model):
    """An inextensible line of rigid uniform segments joined by joints with bending springs (the
    line type's EI over the mean span of the two segments; the first joint, at ``from``, against
    ``base_reference``) and dampers: drag on the velocity relative to the current (normal
    pressure drag on d l, Richtmyer's tangential friction), apparent weight, each segment as
    the free surface cuts it. ``rigid_segments_3d``: cylinders in 3D with ball joints and normal
    added mass (Jacquot & Marichal 1993). ``rigid_links``: Pouzada's planar chain (2015), in
    the vertical plane x-z, its bodies kept in that plane, no added mass on its links (its line
    type's added_mass_coefficient must be 0 in water).

    Node 0 follows the point ``from``. The last node either carries ``to``, a point body that no
    other rigid-segment line ends on (the body moves with the line's end: a towed fish, a float,
    a depressor between two cables; on the axes its ``dofs`` leave out it is held where it
    starts), or is held on ``to``, a point of a fixed or imposed body (an anchor, a vehicle's
    trajectory) or of a free body the line does not carry (a rigid body; a point body two
    rigid lines end on): the line then joins the two bodies' motions (two-ports,
    docs/rigid_segment_lines.md)."""

    name: Name
    model: Literal["rigid_segments_3d", "rigid_links"]
    from_: str = Field(alias="from")
    to: str
    sections: list[Section] = Field(min_length=1)
    # initial shape: the inextensible catenary between the ends (hanging in the vertical plane
    # through them; a body carried at the tip moves to the line's end), a straight line from
    # ``from`` towards ``to`` with the whole length, or the segments' angles (LineAngles)
    initial: Literal["catenary", "straight"] | LineAngles = "catenary"
    joint_damping: NonNeg = 0.0  # [N m s/rad], every joint
    # direction the first joint's spring is unloaded at, in the frame of ``from``'s body
    # (unit vector); by default the first segment's initial direction
    base_reference: Vector | None = None
    # a joint at an end held on ``to`` (a star's top joint), between the last segment and the
    # body ``to`` is a point of: spring [N m/rad] and damper [N m s/rad], unloaded along
    # ``tip_reference`` (in that body's frame; by default the last segment's initial direction)
    tip_joint_stiffness: NonNeg = 0.0
    tip_joint_damping: NonNeg = 0.0
    tip_reference: Vector | None = None
    # the rigid line this one continues through the point body between them (that line
    # carries ``from``): the first joint joins that line's last segment, not ``base_reference``
    continues: Name | None = None


class NaturalStringLine(_Model):
    """Poth's extensible string in natural variables (2002): the strain and the tangent's
    direction at each of its nodes (``tangent: angle``, the angle from the downward vertical;
    or ``cartesian``, the tangent's components kept of unit length), in the vertical plane x-z,
    in air. It hangs from a point of a fixed body (``from``) and carries a point body (``to``)
    as its end mass: the body's mass, gravity its only force model. One section of a line type
    with axial_stiffness EA and, optionally, axial_damping_time alpha (N = EA (eps + alpha
    d eps/dt), no compression). It starts unstretched at rest at the angles ``initial`` gives
    (each node between two segments at their mean angle)."""

    name: Name
    model: Literal["natural_string"]
    from_: str = Field(alias="from")
    to: str
    sections: list[Section] = Field(min_length=1, max_length=1)
    tangent: Literal["angle", "cartesian"] = "angle"
    initial: LineAngles


class Tie(_Model):
    """A massless elastic tie (a hawser, a mooring spring) between two body points: tension
    k (d - L0) + c dd/dt when stretched (d the distance between the points), or from the
    table of (elongation [m], tension [N]) pairs; none in compression (slack)."""

    name: Name
    model: Literal["tie"]
    from_: str = Field(alias="from")
    to: str
    unstretched_length: NonNeg  # L0 [m]
    stiffness: Pos | None = None  # k [N/m]
    tension_table: list[tuple[NonNeg, NonNeg]] | None = Field(default=None, min_length=2)
    damping: NonNeg = 0.0  # c [N s/m], while taut

    @model_validator(mode="after")
    def _one_law(self):
        if (self.stiffness is None) == (self.tension_table is None):
            raise ValueError(
                "give exactly one of 'stiffness' [N/m] or 'tension_table' "
                "[[elongation m, tension N], ...]"
            )
        if self.tension_table is not None:
            table = self.tension_table
            if table[0] != (0.0, 0.0):
                raise ValueError("tension_table must start at [0, 0] (no tension at L0)")
            if any(b[0] <= a[0] or b[1] < a[1] for a, b in zip(table, table[1:], strict=False)):
                raise ValueError(
                    "tension_table: elongations must increase and tensions must not decrease"
                )
        return self


Line = Annotated[LumpedMassLine | RigidLine | NaturalStringLine | Tie, Field(discriminator="model")]


class Failure(_Model):
    """A line failure (MoorDyn's FAILURE, OrcaFlex's release): the ends of ``lines`` at the
    point ``at`` (``body`` or ``body.point``, as the lines name it) let go at ``time``, or when
    the tension of one of them there first reaches ``tension``, whichever comes first. The
    released ends stay joined to one another by a free massless point, a body named after the
    failure in the results (held where the ends were attached until the release), and the run
    goes on (system.failures). The release comes at the end of the first integration step that
    reaches the time or the tension (within one step: the fixed step of rk4 and the implicit
    schemes, dopri5's adaptive one); the results' attributes give the time it came."""

    name: Name | None = None  # default: failure<k> (k from 1)
    at: str
    lines: list[Name] = []  # lumped-mass lines with an end at ``at``; none: every such line
    time: Pos | None = None  # [s]
    tension: Pos | None = None  # [N], the tension of a line's end segment at ``at``

    @model_validator(mode="after")
    def _a_trigger(self):
        if self.time is None and self.tension is None:
            raise ValueError("give the failure a 'time' [s], a 'tension' [N] or both")
        return self


class SystemCase(_Model):
    """A complete case: bodies, the lines between them, the environment and the run."""

    name: str = "case"
    description: str = ""
    environment: Environment = Environment()
    bodies: list[Body] = Field(min_length=1)
    line_types: list[LineType] = []
    lines: list[Line] = []  # none: bodies alone (a vessel in free decay)
    # how the run starts: "static", every free body and line at rest in balance (steady current
    # included; system.statics), or "as_given", bodies where the case puts them, each lumped
    # line at its static shape between them (a free decay from an offset)
    start: Literal["static", "as_given"] = "static"
    # the share of a line type's breaking strength that its tension at the start may reach
    # before validate and every run warn (an intact mooring's static tensions are commonly
    # kept under a fifth to a third of it)
    utilisation_limit: Pos = 1.0
    failures: list[Failure] = []  # line ends released during the run
    simulation: Simulation
    _source_text: str | None = PrivateAttr(default=None)  # YAML the case was read from
    _source_dump: dict | None = PrivateAttr(default=None)  # the case as read (text still true?)
    _base_dir: str | None = PrivateAttr(default=None)  # folder relative file names refer to
    _source_file: str | None = PrivateAttr(default=None)  # the case file it was read from

    @model_validator(mode="after")
    def _failures(self):
        taken = {body.name for body in self.bodies}
        released: dict[tuple[str, str], str] = {}
        lines = {line.name: line for line in self.lines}
        for k, failure in enumerate(self.failures):
            where = f"failures[{k}]"
            name = failure.name or f"failure{k + 1}"
            if name in taken:
                raise ValueError(
                    f"{where}.name: '{name}' is already a body's or a failure's "
                    "name (the released ends' point is a body of that name)"
                )
            taken.add(name)
            if failure.at.partition(".")[0] not in {body.name for body in self.bodies}:
                raise ValueError(
                    f"{where}.at: '{failure.at}' is not a body or a body's point "
                    "('body' or 'body.point', as the lines name their ends)"
                )
            at_it = [n for n, line in lines.items() if failure.at in (line.from_, line.to)]
            for line_name in failure.lines or at_it:
                line = lines.get(line_name)
                if line is None or line_name not in at_it:
                    raise ValueError(
                        f"{where}.lines: '{line_name}' has no end at "
                        f"'{failure.at}'; the lines there: {at_it or 'none'}"
                    )
                if not isinstance(line, LumpedMassLine):
                    raise ValueError(
                        f"{where}.lines: '{line_name}' is a {line.model} line; a "
                        "failure releases lumped_mass lines"
                    )
                if line.from_ == line.to:
                    raise ValueError(
                        f"{where}.lines: both ends of '{line_name}' are at '{failure.at}'"
                    )
                if (line_name, failure.at) in released:
                    raise ValueError(
                        f"{where}.lines: the end of '{line_name}' at "
                        f"'{failure.at}' is already released by "
                        f"{released[line_name, failure.at]}"
                    )
                released[line_name, failure.at] = name
            if not at_it:
                raise ValueError(f"{where}.at: no lumped_mass line ends at '{failure.at}'")
        if self.failures and self.simulation.integrator in ("bdf", "radau", "lsoda", "cvode"):
            raise ValueError(
                f"failures: a line's release changes the system during the run, which "
                f"simulation.integrator {self.simulation.integrator} (a SciPy solver stepping "
                "on its own) cannot follow; use rk4, dopri5, implicit_euler, theta, newmark or "
                "generalized_alpha"
            )
        return self

    @model_validator(mode="after")
    def _unique_names(self):
        for what, items in (
            ("bodies", self.bodies),
            ("line_types", self.line_types),
            ("lines", self.lines),
        ):
            names = [item.name for item in items]
            twice = sorted({n for n in names if names.count(n) > 1})
            if twice:
                raise ValueError(f"{what}: names must be unique; {twice} appear more than once")
        depth = self.environment.water_depth
        for k, body in enumerate(self.bodies):
            if (
                depth is not None
                and isinstance(body, FixedBody)
                and body.position[2] < -depth - SEABED_TOLERANCE
            ):
                raise ValueError(
                    f"bodies[{k}] ({body.name}).position: z = {body.position[2]:g} m is below the "
                    f"seabed (z = {-depth:g} m, environment.water_depth {depth:g} m); put it on "
                    "or above the seabed, or deepen the water"
                )
        segments = sum(section.segments for line in self.lines
                       for section in getattr(line, "sections", None) or [])  # fmt: skip
        if segments > MOST_SEGMENTS:
            raise ValueError(
                f"lines: {segments:,} segments in all, more than a run can hold in memory and "
                f"finish ({MOST_SEGMENTS:,}); use fewer, longer segments"
            )
        return self


# the force models the waves act through (the lines feel the waves in their own loads)
WAVE_MODELS = ("non-linear hydrostatic", "non-linear Froude-Krylov", "diffraction", "wave drift",
               "fluid inertia", "drag")  # fmt: skip


def ignored_inputs(case: SystemCase) -> list[str]:
    """One line per part of the environment that acts on nothing a case holds, said where
    the case is checked (``simulation.prepare``: ``seacable validate`` and every run): waves on
    a moving body none of whose force models they act through (the lines still feel them),
    wind without any body's ``wind`` model."""
    out = []
    env = case.environment
    if env.waves:
        for k, body in enumerate(case.bodies):
            if not isinstance(body, (PointBody, RigidBody)):
                continue
            models = {force.model for force in body.external_forces}
            if not models & set(WAVE_MODELS):
                out.append(
                    f"bodies[{k}] ({body.name}): the waves act on none of its force models "
                    f"({', '.join(sorted(models)) or 'none'}): only its lines feel them; give "
                    f"it one of {', '.join(WAVE_MODELS)} (a hull mesh, a hydrodynamic "
                    "database, or Morison's fluid inertia and drag at its reference point), "
                    "or ignore this for a body the waves do not reach"
                )
    moving = [body for body in case.bodies if isinstance(body, (PointBody, RigidBody))]
    winds = [force for body in moving for force in body.external_forces if force.model == "wind"]
    if env.wind is not None and not winds:
        out.append(
            "environment.wind: no moving body has a 'wind' force model, so the wind acts on "
            "nothing; add one (its coefficients) or remove the wind"
        )
    return out
