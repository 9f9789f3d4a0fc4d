"""The case-file schema of one cable with its ends (the single-cable form): frozen, validated
pydantic models. Units are given for every field; the parts every case form shares are in
``case.base`` (time functions, shapes, simulation) and ``case.environment``.

Conventions (see docs/conventions.md): SI units, z up with z = 0 at the still-water surface,
angles in the case file in degrees (keys end in ``_deg``), radians everywhere inside.
"""

import math
from typing import Annotated, Literal

import numpy as np
from pydantic import (
    Field,
    PrivateAttr,
    model_validator,
)

from seacable.case.base import (
    FIXED_STEP_INTEGRATORS,
    IMPLICIT_INTEGRATORS,
    AccelerationPhase,
    AccelerationProfile,
    Constant,
    NonNeg,
    PerAxis,
    Point,
    Pos,
    Ramp,
    Shape,
    ShipTravel,
    Simulation,
    Sine,
    Sphere,
    Table,
    TimeFunction,
    Turn,
    VerticalCylinder,
    VolumeTable,
    _Model,
    per_axis,
    xyz,
)
from seacable.case.environment import Current, Environment, Seabed


# ---- cable -------------------------------------------------------------------------------------
class FixedTop(_Model):
    """Top attachment fixed at ``position`` [x, z] (m)."""

    type: Literal["fixed"]
    position: Point = (0.0, 0.0)


class ImposedTop(_Model):
    """Top attachment moved by time functions x(t), z(t) [m]; velocities and accelerations are
    their exact derivatives."""

    type: Literal["imposed"]
    x: TimeFunction = Constant(value=0.0)
    y: TimeFunction = Constant(value=0.0)  # 3D model only
    z: TimeFunction = Constant(value=0.0)


class FloatingStructureTop(_Model):
    """Floating structure moving in heave only: mass-spring-damper with an applied force u(t).

    ``position`` [x, z] (m) is where the heave spring is unloaded; the structure's weight equals
    its buoyancy there unless ``net_weight`` [N] (weight minus buoyancy, positive down) is given.
    """

    type: Literal["floating_structure"]
    position: Point = (0.0, 0.0)
    mass: Pos  # [kg]
    added_mass: NonNeg = 0.0  # heave added mass [kg]
    heave_stiffness: NonNeg  # [N/m]
    heave_damping: NonNeg = 0.0  # [N s/m]
    net_weight: float = 0.0  # [N], positive down
    force: TimeFunction = Constant(value=0.0)  # u(t), vertical, positive up [N]
    initial_heave: float = 0.0  # initial z offset from `position` [m]
    initial_heave_velocity: float = 0.0  # [m/s]


class TowingShipTop(ShipTravel):
    """Tow point on a ship (3D model): starts at ``position`` [x, y, z] (m) heading
    ``heading_deg`` (from +x towards +y) and moves along a straight track, then optionally a
    turning circle. Give a constant ``speed`` [m/s] or the ``distance`` travelled [m] as a time
    function (an acceleration_profile gives speed changes with exact accelerations)."""

    type: Literal["towing_ship"]
    position: Point = (0.0, 0.0, 0.0)
    heading_deg: float = 0.0


class Tie(_Model):
    """Elastic ties holding the bottom body near ``rest_position`` [x, z] (m): spring-dampers
    along x and z. Without rest_position the ties are unloaded at the initial end position."""

    stiffness_x: NonNeg = 0.0  # [N/m]
    damping_x: NonNeg = 0.0  # [N s/m]
    stiffness_y: NonNeg = 0.0  # [N/m] (3D model)
    damping_y: NonNeg = 0.0  # [N s/m] (3D model)
    stiffness_z: NonNeg = 0.0  # [N/m]
    damping_z: NonNeg = 0.0  # [N s/m]
    rest_position: Point | None = None


# ---- bodies and the free surface -----------------------------------------------------------------
class _Displacing(_Model):
    """A body's displaced volume: a ``volume`` [m^3], a point that is always wholly submerged
    (its buoyancy rho g V everywhere, even above z = 0), or a ``shape`` whose submerged part
    follows the free surface z = 0: buoyancy rho g V_sub, added mass and drag area times the
    submerged fraction V_sub / V (docs/conventions.md, "The free surface")."""

    volume: NonNeg = 0.0  # displaced volume of a point body [m^3]
    shape: Shape | None = None  # instead of volume: the body's extent about its position

    @model_validator(mode="after")
    def _volume_or_shape(self):
        if self.shape is not None and self.volume != 0.0:
            raise ValueError(
                f"volume: value {self.volume}; a body with a shape takes its volume from it "
                f"({self.shape.volume():.6g} m^3): remove 'volume'"
            )
        return self

    def displaced_volume(self) -> float:
        """Wholly submerged volume [m^3]."""
        return self.volume if self.shape is None else self.shape.volume()


class Body(_Displacing):
    """Point body at the free end (a terminal mass, towed body, clump weight or buoy).

    Added mass and drag area take one value or one per global axis [x, y, z]: a very large
    added mass along an axis restrains the body's motion along it (as Jacquot & Marichal do).
    With a ``shape`` they are the wholly submerged values, scaled by the submerged fraction."""

    mass: NonNeg = 0.0  # [kg]
    added_mass: PerAxis = 0.0  # [kg]
    drag_coefficient: NonNeg = 0.0  # Cd on drag_area (force 0.5 rho Cd A |v| v_k per axis k)
    drag_area: PerAxis = 0.0  # [m^2]
    force_x: TimeFunction = Constant(value=0.0)  # applied force (a thrust) [N]
    force_y: TimeFunction = Constant(value=0.0)  # [N], 3D model only
    force_z: TimeFunction = Constant(value=0.0)  # [N], positive up


class FreeBottom(_Model):
    """Free end, optionally carrying a body and held by elastic ties. ``hold_axes`` (3D model)
    holds the end exactly at its initial coordinate along the axes listed: ``[x, y]`` is a
    vertical guide (the exact alternative to a very large added mass across the guide)."""

    type: Literal["free"]
    body: Body = Body()
    tie: Tie | None = None
    hold_axes: list[Literal["x", "y", "z"]] = []


class FloatingStructureBottom(_Model):
    """Second floating structure at the lower end: a body of ``mass`` held by heave and surge
    spring-dampers around ``rest_position`` (default: initial end position); weight equals
    buoyancy. ``force`` is a vertical applied force u(t) [N]."""

    type: Literal["floating_structure"]
    mass: Pos  # [kg]
    heave_stiffness: NonNeg  # [N/m]
    heave_damping: NonNeg = 0.0  # [N s/m]
    surge_stiffness: NonNeg  # [N/m]
    surge_damping: NonNeg = 0.0  # [N s/m]
    force: TimeFunction = Constant(value=0.0)
    rest_position: Point | None = None


class Servo(_Model):
    """Jacquot & Marichal's trajectory servo: the force on the cable end is corrected every
    ``step`` [s] by dF = K (a dE - b dt dE'), with dE the target minus the end position and K the
    stiffness of the cable end from static equilibria with the end on a sphere of
    ``sphere_radius`` [m] around its nominal position. ``recompute_interval`` [s] refreshes K
    about the current target during the motion (the paper suggests it)."""

    gain: Annotated[float, Field(gt=0, le=2)] = 1.0  # a
    rate_gain: Annotated[float, Field(ge=0, lt=1)] = 0.0  # b
    step: Pos | None = None  # dt of the correction; default: the integration step
    sphere_radius: Pos = 1.0  # [m]
    recompute_interval: Pos | None = None  # [s]


class TrajectoryBottom(_Model):
    """Lower end carried by a vehicle along a prescribed path (3D models): x(t), y(t), z(t) [m],
    offsets from the top attachment when ``relative_to_top`` (the vehicle's motion relative to
    the ship) or absolute. ``method`` exact: the end force that imposes the path exactly;
    stiffness_servo: the paper's servo (see Servo). Outputs the force of the cable on the vehicle
    and the tracking error."""

    type: Literal["trajectory"]
    x: TimeFunction = Constant(value=0.0)
    y: TimeFunction = Constant(value=0.0)
    z: TimeFunction = Constant(value=0.0)
    relative_to_top: bool = True
    method: Literal["exact", "stiffness_servo"] = "exact"
    servo: Servo = Servo()


class AttachedBottom(_Model):
    """Lower end attached to a body of the case's ``bodies`` list, by name (3D models:
    rigid_segments_3d or lumped_mass, the same for every cable): several cables attached to one
    body form a star, e.g. a buoy held by four anchored cables."""

    type: Literal["attached"]
    body: str


class SharedBody(_Displacing):
    """A point body that several cables attach to (3D models). ``position`` [x, y, z] (m) is
    where it starts: every attached cable's initial shape must end there (within 1 mm; a
    lumped-mass cable's catenary does). Added mass and drag area take one value or one per
    global axis (with a ``shape``: wholly submerged values, scaled by the submerged fraction)."""

    name: str
    position: Point
    mass: Pos  # [kg]
    added_mass: PerAxis = 0.0  # [kg]
    drag_coefficient: NonNeg = 0.0
    drag_area: PerAxis = 0.0  # [m^2]


class PointBody(_Displacing):
    """A float or clump weight at a joint (3D model): ``node`` counts joints from the top
    (1 = between the first and second segments). Drag as a sphere: 0.5 rho Cd A |v| v (with a
    ``shape``: added mass and drag area scaled by the submerged fraction)."""

    node: int = Field(ge=1)
    mass: NonNeg = 0.0  # [kg]
    added_mass: PerAxis = 0.0  # [kg]
    drag_coefficient: NonNeg = 0.5
    drag_area: NonNeg = 0.0  # [m^2]


class PinnedBottom(_Model):
    """End pinned to an anchor (exact constraint). The anchor is the end of the initial shape;
    if ``anchor`` [x, z] (m) is given it must agree with that end within 1 mm."""

    type: Literal["pinned"]
    anchor: Point | None = None


class InitialShape(_Model):
    """Initial link angles from the downward vertical, positive towards +x [deg]:
    ``arc`` varies linearly from top_angle_deg (first link) to bottom_angle_deg (last link);
    ``angles`` gives one angle per link; ``static`` (3D model) starts from the static
    equilibrium for the motion the top has at t = 0 (towing at constant speed, or hanging).
    The cable starts at rest (or, from ``static``, moving steadily with the top).
    ``catenary`` (lumped-mass model, pinned lower end): the elastic catenary between the top and
    the anchor, lying on the seabed where it reaches it."""

    shape: Literal["arc", "angles", "static", "catenary"] = "arc"
    top_angle_deg: float = 0.0
    bottom_angle_deg: float | None = None
    angles_deg: list[float] | None = None
    azimuth_deg: float = 0.0  # 3D: plane of the initial shape, from +x towards +y

    @model_validator(mode="after")
    def _consistent(self):
        if self.shape == "angles" and self.angles_deg is None:
            raise ValueError("shape 'angles' needs 'angles_deg': one angle per link [deg]")
        if self.shape == "arc" and self.angles_deg is not None:
            raise ValueError("'angles_deg' goes with shape 'angles', not 'arc'")
        return self

    def angles(self, n: int) -> np.ndarray:
        if self.shape == "angles":
            assert self.angles_deg is not None  # _consistent: shape 'angles' needs them
            if len(self.angles_deg) != n:
                raise ValueError(f"angles_deg has {len(self.angles_deg)} values; the cable has {n}")
            return np.radians(np.asarray(self.angles_deg, dtype=float))
        bottom = self.top_angle_deg if self.bottom_angle_deg is None else self.bottom_angle_deg
        return np.radians(np.linspace(self.top_angle_deg, bottom, n))


class Cable(_Model):
    """A planar cable of rigid links joined by torsional spring-dampers."""

    name: str = "cable"
    model: Literal["rigid_links", "rigid_segments_3d", "lumped_mass", "natural_string"] = (
        "rigid_links"
    )
    # natural_string: how the tangent is parametrised, (eps, phi) or (eps, t_x, t_z)
    tangent: Literal["angle", "cartesian"] = "angle"
    links: int = Field(ge=1, le=100_000)  # number of rigid links
    length: Pos | None = None  # total length [m], equal links
    link_lengths: list[Pos] | None = None  # [m], one per link
    diameter: Pos  # hydrodynamic and buoyancy diameter [m]
    mass_per_length: Pos | None = None  # [kg/m]
    density: Pos | None = None  # material density [kg/m^3]: mass = density * pi d^2/4 * l
    link_masses: list[Pos] | None = None  # [kg], one per link (instead of the two above)
    joint_stiffness: NonNeg | list[NonNeg] | None = None  # [N m/rad], scalar or one per joint
    bending_stiffness: NonNeg | None = None  # EI [N m^2] -> joint stiffness EI / l
    joint_damping: NonNeg | list[NonNeg] = 0.0  # [N m s/rad], scalar or one per joint
    drag_coefficient_normal: NonNeg = 1.2  # Cd on the projected area d l
    drag_coefficient_tangential: NonNeg = 0.0  # Cd on the wetted area pi d l
    friction_coefficient: NonNeg = 0.0  # Richtmyer f: 0.5 rho f Cd_n d l (V cos phi)^2
    added_mass_coefficient: NonNeg | None = None  # Ca, normal only; 3D default 1.0
    axial_stiffness: Pos | None = None  # EA [N] (lumped_mass: required)
    # axial damping, at most one of (none: undamped): alpha [s] in N = EA (eps + alpha d eps/dt),
    # or (lumped_mass) zeta, the fraction of each segment's critical damping, MoorDyn's negative
    # BA: alpha_i = zeta l_i sqrt(mu_i / EA), mu_i = m_i / l_i its mass per length [kg/m]
    axial_damping_time: NonNeg | None = None  # alpha [s]
    axial_damping_ratio: NonNeg | None = None  # zeta [-]
    point_bodies: list[PointBody] = []  # floats and clump weights at joints (3D)
    top_reference_angle_deg: float = 0.0  # angle the first joint spring is unloaded at [deg]
    top: FixedTop | ImposedTop | FloatingStructureTop | TowingShipTop = Field(discriminator="type")
    bottom: (
        FreeBottom | FloatingStructureBottom | PinnedBottom | TrajectoryBottom | AttachedBottom
    ) = Field(discriminator="type")
    initial: InitialShape = InitialShape()

    @model_validator(mode="after")
    def _exactly_one_each(self):
        if (self.length is None) == (self.link_lengths is None):
            raise ValueError("give exactly one of 'length' [m] or 'link_lengths' [m, one per link]")
        if self.link_lengths is not None and len(self.link_lengths) != self.links:
            raise ValueError(
                f"link_lengths has {len(self.link_lengths)} values but links = {self.links}"
            )
        given = [k for k in ("mass_per_length", "density", "link_masses") if getattr(self, k)]
        if len(given) != 1:
            raise ValueError(
                "give exactly one of 'mass_per_length' [kg/m], 'density' [kg/m^3] or "
                f"'link_masses' [kg, one per link] (got {given or 'none'})"
            )
        if self.link_masses is not None and len(self.link_masses) != self.links:
            raise ValueError(
                f"link_masses has {len(self.link_masses)} values but links = {self.links}"
            )
        if self.joint_stiffness is not None and self.bending_stiffness is not None:
            raise ValueError("give at most one of 'joint_stiffness' or 'bending_stiffness'")
        if self.axial_damping_time is not None and self.axial_damping_ratio is not None:
            raise ValueError(
                "give at most one of 'axial_damping_time' [s] or 'axial_damping_ratio' "
                "[fraction of each segment's critical damping]"
            )
        if self.axial_damping_ratio is not None and self.model != "lumped_mass":
            raise ValueError(
                f"axial_damping_ratio is for model 'lumped_mass' (got model '{self.model}'); "
                "give axial_damping_time [s] instead"
            )
        for key in ("joint_stiffness", "joint_damping"):
            value = getattr(self, key)
            if isinstance(value, list) and len(value) != self.links:
                raise ValueError(f"{key} has {len(value)} values but links = {self.links}")
        if self.initial.shape == "angles" and len(self.initial.angles_deg) != self.links:
            raise ValueError(
                f"initial.angles_deg has {len(self.initial.angles_deg)} values "
                f"but links = {self.links}"
            )
        if abs(self.top_reference_angle_deg) > 360 or abs(self.initial.top_angle_deg) > 360:
            raise ValueError("angles are in degrees and should lie within [-360, 360]")
        return self

    @model_validator(mode="after")
    def _planar_limits(self):
        if self.model != "rigid_links":
            return self
        fix = "use model: rigid_segments_3d"
        if isinstance(self.top, TowingShipTop):
            raise ValueError(f"top type 'towing_ship' needs the 3D model: {fix}")
        points = [getattr(self.top, "position", None)]
        points += [
            getattr(self.bottom, "anchor", None),
            getattr(self.bottom, "rest_position", None),
        ]
        tie = getattr(self.bottom, "tie", None)
        points.append(tie.rest_position if tie is not None else None)
        for point in points:
            if point is not None and len(point) == 3 and point[1] != 0.0:
                raise ValueError(
                    f"the planar model lies in the x-z plane; got y = {point[1]}: {fix}"
                )
        if isinstance(self.top, ImposedTop) and self.top.y != Constant(value=0.0):
            raise ValueError(f"the planar model has no y motion (top.y): {fix}")
        body = getattr(self.bottom, "body", None)
        if body is not None and body.force_y != Constant(value=0.0):
            raise ValueError(f"the planar model has no y force (bottom.body.force_y): {fix}")
        if self.point_bodies:
            raise ValueError(f"point_bodies are supported by the 3D model only: {fix}")
        if isinstance(self.bottom, TrajectoryBottom | AttachedBottom):
            raise ValueError(f"bottom type '{self.bottom.type}' needs the 3D model: {fix}")
        if getattr(self.bottom, "hold_axes", []):
            raise ValueError(f"bottom.hold_axes needs the 3D model: {fix}")
        if self.added_mass_coefficient:
            raise ValueError(
                f"the planar model has no link added mass (added_mass_coefficient): {fix}"
            )
        if self.initial.shape == "static":
            raise ValueError(f"initial shape 'static' is computed by the 3D model: {fix}")
        return self

    def lengths(self) -> np.ndarray:
        if self.link_lengths is not None:
            return np.asarray(self.link_lengths, dtype=float)
        assert self.length is not None  # _exactly_one_each: length or link_lengths
        return np.full(self.links, self.length / self.links)

    def masses(self) -> np.ndarray:
        """Mass of each link [kg]."""
        if self.link_masses is not None:
            return np.asarray(self.link_masses, dtype=float)
        if self.mass_per_length is not None:
            return self.mass_per_length * self.lengths()
        assert self.density is not None  # _exactly_one_each: one of the three is given
        return self.density * math.pi * self.diameter**2 / 4 * self.lengths()

    def axial_damping_times(self) -> np.ndarray:
        """alpha of each segment [s] (N = EA (eps + alpha d eps/dt)). From axial_damping_ratio
        zeta: a segment of stiffness EA / l with half of its mass m at each end vibrates (its
        ends in opposition) at omega = 2 sqrt(EA / (m l)); its critical damping is
        m omega / 2 = sqrt(EA m / l) [N s/m], that is alpha_crit = l sqrt(m / (l EA))
        = l sqrt(mu / EA) [s] (the segment's length over the axial wave speed), and
        alpha = zeta alpha_crit. The fastest mode of a uniform line's interior nodes (each of
        mass m between two half segments) has the same omega and ratio; MoorDyn's BA = -zeta:
        BA = zeta l sqrt(EA mu) [N s] = EA alpha."""
        if self.axial_damping_ratio is None:
            return np.full(self.links, self.axial_damping_time or 0.0)
        if self.axial_stiffness is None:
            return np.zeros(self.links)  # the model refuses the cable (EA is required)
        lengths = self.lengths()
        return self.axial_damping_ratio * np.sqrt(self.masses() * lengths / self.axial_stiffness)


class Case(_Model):
    """A complete simulation case."""

    name: str = "case"
    description: str = ""
    environment: Environment = Environment()
    cables: list[Cable] = Field(min_length=1)
    bodies: list[SharedBody] = []
    simulation: Simulation
    _source_text: str | None = PrivateAttr(default=None)  # YAML the case was read from
    _source_dump: dict | None = PrivateAttr(default=None)  # the case as read (text still true?)
    _base_dir: str | None = PrivateAttr(default=None)  # folder relative file names refer to
    _source_file: str | None = PrivateAttr(default=None)  # the case file it was read from

    @model_validator(mode="after")
    def _cables_and_bodies(self):
        attached = [c for c in self.cables if isinstance(c.bottom, AttachedBottom)]
        names = [b.name for b in self.bodies]
        if len(set(names)) != len(names):
            raise ValueError(f"bodies: names must be unique (got {names})")
        for k, cable in enumerate(attached):
            if cable.bottom.body not in names:
                raise ValueError(
                    f"cables[{k}].bottom.body: no body named '{cable.bottom.body}'; "
                    f"bodies are {names or 'none'}"
                )
        if attached and len(attached) != len(self.cables):
            raise ValueError(
                "either every cable is attached to the shared body (a star) or there is one cable"
            )
        if len({c.bottom.body for c in attached}) > 1:
            raise ValueError("all attached cables must share one body (several bodies: not yet)")
        if not attached and len(self.cables) != 1:
            raise ValueError(
                f"several cables ({len(self.cables)}) must all be attached to one shared body "
                "(bottom: {type: attached, body: NAME}); otherwise split them into one case each"
            )
        if attached and len({c.links for c in self.cables}) != 1:
            raise ValueError("cables attached to one body must have the same number of links")
        if self.bodies and not attached:
            raise ValueError("bodies are given but no cable is attached to them")
        return self


# the shared parts (case.base, case.environment) are re-exported: ``schema.Sine`` etc. keep working
__all__ = [
    "AccelerationPhase",
    "AccelerationProfile",
    "AttachedBottom",
    "Body",
    "Cable",
    "Case",
    "Constant",
    "Current",
    "Environment",
    "FIXED_STEP_INTEGRATORS",
    "IMPLICIT_INTEGRATORS",
    "FixedTop",
    "FloatingStructureBottom",
    "FloatingStructureTop",
    "FreeBottom",
    "ImposedTop",
    "InitialShape",
    "NonNeg",
    "PerAxis",
    "PinnedBottom",
    "Point",
    "PointBody",
    "Pos",
    "Ramp",
    "Seabed",
    "Servo",
    "Shape",
    "SharedBody",
    "Simulation",
    "Sine",
    "Sphere",
    "Table",
    "Tie",
    "TimeFunction",
    "TowingShipTop",
    "TrajectoryBottom",
    "Turn",
    "VerticalCylinder",
    "VolumeTable",
    "per_axis",
    "xyz",
]
