"""The case-file schema of a system of bodies and lines: its bodies (``case.bodies``, re-exported
here), named line types, lines between body points, line failures, and the case with its
environment and run. Conventions (docs/conventions.md) as ``case.bodies`` states them: SI
units, z up with z = 0 at the still-water surface, angles in degrees.
"""

from typing import Annotated, Literal

import numpy as np
from pydantic import Field, PrivateAttr, model_validator

from seacable.case.base import (
    NonNeg,
    Pos,
    Simulation,
    Vector,
    _Model,
)
from seacable.case.bodies import (  # noqa: F401 (the case's bodies, as ``sch.`` reaches them)
    DOF_NAMES,
    Body,
    Dof,
    FixedBody,
    ImposedBody,
    Name,
    PointBody,
    RigidBody,
    Track,
)
from seacable.case.document import (  # noqa: F401 (the document's dynamics block, as above)
    ADDED_MASS,
    DocumentDynamics,
    DocumentMatrix,
)
from seacable.case.environment import Environment
from seacable.case.fatigue import API, Fatigue
from seacable.case.sweep import Sweep


# ---- line types and lines -----------------------------------------------------------------------
class LineType(_Model):
    """Properties of a cable, rope or chain, per unit length."""

    name: Name
    """Name of the line type, by which sections refer to it."""
    diameter: Pos
    """[m] Hydrodynamic and buoyancy diameter d."""
    mass_per_length: Pos
    """[kg/m] Mass per unit unstretched length, in air (the buoyancy comes from ``diameter``)."""
    axial_stiffness: Pos | None = None
    """[N] Axial stiffness EA, needed by the extensible lines (lumped-mass, natural-string)."""
    axial_damping_time: NonNeg | None = None
    """[s] Axial damping time alpha in N = EA (eps + alpha d eps/dt); or axial_damping_ratio."""
    axial_damping_ratio: NonNeg | None = None
    """[-] Axial damping as the fraction of each segment's critical damping (MoorDyn's negative
    BA); or axial_damping_time."""
    bending_stiffness: NonNeg = 0.0
    """[N m^2] Bending stiffness EI."""
    drag_coefficient_normal: NonNeg = 1.2
    """[-] Drag coefficient Cd across the line, on the projected area d l."""
    drag_coefficient_tangential: NonNeg = 0.0
    """[-] Drag coefficient Cd along the line, on the wetted area pi d l."""
    friction_coefficient: NonNeg = 0.0
    """[-] Richtmyer's friction factor f: a tangential drag f Cd_normal on d l, added to the
    tangential drag."""
    added_mass_coefficient: NonNeg = 1.0
    """[-] Added mass coefficient Ca across the line, on its displaced volume (none in air)."""
    added_mass_coefficient_tangential: NonNeg = 0.0
    """[-] Added mass coefficient Ca along the line (MoorDyn's CaAx); lumped-mass lines only."""
    breaking_strength: Pos | None = None
    """[N] Minimum breaking load; results give each section's largest tension over it."""
    fatigue: Fatigue | None = None
    """The line type's fatigue curve: a sweep gives each line's fatigue damage on it (at the
    line's more loaded end). Omitted: no damage."""

    @model_validator(mode="after")
    def _one_damping(self):
        if self.axial_damping_time is not None and self.axial_damping_ratio is not None:
            raise ValueError(
                "give at most one of 'axial_damping_time' [s] or 'axial_damping_ratio'"
            )
        if self.fatigue is not None and self.breaking_strength is None and (
            self.fatigue.curve in API or (self.fatigue.m is not None and
                                          self.fatigue.reference is None)):  # fmt: skip
            raise ValueError(
                "fatigue: its ranges are taken over the breaking strength; give "
                "'breaking_strength' [N] (or the own curve's 'reference')"
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
    """Name of the section's line type (``line_types``)."""
    length: Pos
    """[m] Unstretched length of the section."""
    segments: int = Field(ge=1, le=100_000)
    """[-] Number of equal segments of the section."""
    joint_stiffness: NonNeg | None = None
    """[N m/rad] Spring of the joint at the start of each segment. Omitted: from the line
    type's EI."""
    joint_damping: NonNeg | None = None
    """[N m s/rad] Damper of each such joint (rigid lines). Omitted: the line's joint_damping."""


class LineAngles(_Model):
    """A line's initial shape given by its segments' angles from the downward vertical,
    positive towards +x [deg] (in the vertical plane at ``azimuth_deg`` from +x towards +y for
    a 3D line): ``angles_deg``, one per segment, or ``arc_deg`` [first, last], varying linearly
    along the line, each segment at its unstretched length. The line starts from its ``from``
    point; a body a rigid line carries must be at its end, a held end's point (and a lumped
    line's ``to`` point) within 1 mm of it."""

    angles_deg: list[float] | None = None
    """[deg] Each segment's angle from the downward vertical, one per segment, from ``from``."""
    arc_deg: tuple[float, float] | None = None
    """[deg] The first and the last segment's angles, varying linearly between them."""
    azimuth_deg: float = 0.0
    """[deg] Direction of the line's vertical plane, from +x towards +y (3D lines)."""

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
    """Name of the line."""
    model: Literal["lumped_mass"]
    from_: str = Field(alias="from")
    """The point the line starts at: ``body`` or ``body.point``."""
    to: str
    """The point the line ends at: ``body`` or ``body.point``."""
    sections: list[Section] = Field(min_length=1)
    """The line's sections, from ``from`` to ``to``."""
    initial: Literal["catenary", "straight"] | LineAngles = "catenary"
    """Initial shape: ``catenary``, its static shape between its ends (with the seabed);
    ``straight``, a straight line; or the segments' angles."""


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
    """Name of the line."""
    model: Literal["rigid_segments_3d", "rigid_links"]
    from_: str = Field(alias="from")
    """The point the line starts at: ``body`` or ``body.point``."""
    to: str
    """The point body the line carries at its end, or the point its end is held on."""
    sections: list[Section] = Field(min_length=1)
    """The line's sections, from ``from`` to ``to``."""
    initial: Literal["catenary", "straight"] | LineAngles = "catenary"
    """Initial shape: ``catenary``, the inextensible catenary hanging in the vertical plane
    through the ends (a body carried at the tip moves to the line's end); ``straight``, from
    ``from`` towards ``to`` with the whole length; or the segments' angles."""
    joint_damping: NonNeg = 0.0
    """[N m s/rad] Damper of every joint a section gives none."""
    base_reference: Vector | None = None
    """[-] Direction, in the frame of ``from``'s body, the first joint's spring is unloaded at
    (normalised). Omitted: the first segment's initial direction."""
    tip_joint_stiffness: NonNeg = 0.0
    """[N m/rad] Spring of the joint between the last segment and the body ``to`` is held on
    (a star's top joint)."""
    tip_joint_damping: NonNeg = 0.0
    """[N m s/rad] Damper of the joint between the last segment and the body ``to`` is held on."""
    tip_reference: Vector | None = None
    """[-] Direction, in the frame of ``to``'s body, the tip joint is unloaded at (normalised).
    Omitted: the last segment's initial direction."""
    continues: Name | None = None
    """The rigid line this one continues through the point body between them (that line
    carries ``from``): the first joint joins that line's last segment, not ``base_reference``."""


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
    """Name of the line."""
    model: Literal["natural_string"]
    from_: str = Field(alias="from")
    """The point of a fixed body the string hangs from: ``body.point`` or ``body``."""
    to: str
    """The point body the string carries as its end mass."""
    sections: list[Section] = Field(min_length=1, max_length=1)
    """The string's one section."""
    tangent: Literal["angle", "cartesian"] = "angle"
    """The tangent's variables: ``angle``, its angle from the downward vertical; ``cartesian``,
    its components, kept of unit length."""
    initial: LineAngles
    """Initial angles of the segments; the string starts unstretched, at rest."""


class Tie(_Model):
    """A massless elastic tie (a hawser, a mooring spring) between two body points: tension
    k (d - L0) + c dd/dt when stretched (d the distance between the points), or from the
    table of (elongation [m], tension [N]) pairs; none in compression (slack)."""

    name: Name
    """Name of the tie."""
    model: Literal["tie"]
    from_: str = Field(alias="from")
    """One end's point: ``body`` or ``body.point``."""
    to: str
    """The other end's point: ``body`` or ``body.point``."""
    unstretched_length: NonNeg
    """[m] Unstretched length L0."""
    stiffness: Pos | None = None
    """[N/m] Stiffness k: tension k (d - L0) when stretched; or ``tension_table``."""
    tension_table: list[tuple[NonNeg, NonNeg]] | None = Field(default=None, min_length=2)
    """[m, N] (elongation, tension) pairs from [0, 0], linear between and beyond them; or
    ``stiffness``."""
    damping: NonNeg = 0.0
    """[N s/m] Damping c on the rate of stretching, while taut."""

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

    name: Name | None = None
    """Name of the failure and of the free point joining the released ends. Omitted:
    failure<k>, k counting the failures from 1."""
    at: str
    """The point the line ends let go at: ``body`` or ``body.point``, as the lines name it."""
    lines: list[Name] = []
    """Lumped-mass lines whose ends at ``at`` let go. Empty: every such line ending there."""
    time: Pos | None = None
    """[s] Time of the release."""
    tension: Pos | None = None
    """[N] End-segment tension at ``at`` that releases the ends when a line first reaches it."""

    @model_validator(mode="after")
    def _a_trigger(self):
        if self.time is None and self.tension is None:
            raise ValueError("give the failure a 'time' [s], a 'tension' [N] or both")
        return self


class SystemCase(_Model):
    """A complete case: bodies, the lines between them, the environment and the run."""

    name: str = "case"
    """Name of the case."""
    description: str = ""
    """Free text describing the case."""
    environment: Environment = Environment()
    """The water, seabed, current, waves and wind."""
    bodies: list[Body] = Field(min_length=1)
    """The bodies, which the lines join."""
    line_types: list[LineType] = []
    """The line types the lines' sections name."""
    lines: list[Line] = []
    """The lines and ties between the bodies' points. Empty: bodies alone (a vessel in free
    decay)."""
    start: Literal["static", "as_given"] = "static"
    """How the run starts: ``static``, every free body and line at rest in balance (steady
    current included; system.statics); ``as_given``, the bodies where the case puts them,
    each lumped-mass line in its static shape between them (a free decay from an offset)."""
    utilisation_limit: Pos = 1.0
    """[-] Share of a line type's breaking strength its tension at the start may reach before
    validate and every run warn (intact moorings commonly keep under 1/5 to 1/3)."""
    failures: list[Failure] = []
    """Line ends released during the run."""
    simulation: Simulation
    """The run: its duration, output interval and integrator."""
    sweep: Sweep | None = None
    """Load cases ``seacable sweep`` runs from this case (``seacable run`` runs the case as
    written). Omitted: a sweep of the command line's ``--vary`` only."""
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
               "fluid inertia", "drag", "rod")  # fmt: skip


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
