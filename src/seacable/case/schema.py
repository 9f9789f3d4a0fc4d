"""The case-file schema: frozen, validated pydantic models. Units are given for every field.

Conventions (see docs/conventions.md): SI units, z up with z = 0 at the still-water surface,
angles in the case file in degrees (keys end in ``_deg``), radians everywhere inside.
"""

import csv
import math
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    PrivateAttr,
    field_validator,
    model_validator,
)

Pos = Annotated[float, Field(gt=0)]
NonNeg = Annotated[float, Field(ge=0)]
Point = tuple[float, float] | tuple[float, float, float]  # [x, z] (y = 0) or [x, y, z], m
PerAxis = NonNeg | tuple[NonNeg, NonNeg, NonNeg]  # one value, or one per global axis x, y, z


def xyz(point) -> tuple[float, float, float]:
    """(x, y, z) of a point given as [x, z] or [x, y, z]."""
    if len(point) == 2:
        return (float(point[0]), 0.0, float(point[1]))
    return (float(point[0]), float(point[1]), float(point[2]))


def per_axis(value) -> tuple[float, float, float]:
    if isinstance(value, tuple | list):
        x, y, z = value
        return (float(x), float(y), float(z))
    return (float(value), float(value), float(value))


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


# ---- time functions ------------------------------------------------------------------------------
class Constant(_Model):
    """f(t) = value."""

    kind: Literal["constant"] = "constant"
    value: float


class Sine(_Model):
    """f(t) = offset + amplitude sin(omega t + phase); give exactly one of period [s] or
    angular_frequency [rad/s]; phase [rad]."""

    kind: Literal["sine"]
    amplitude: float
    period: Pos | None = None
    angular_frequency: Pos | None = None
    phase: float = 0.0
    offset: float = 0.0

    @model_validator(mode="after")
    def _one_frequency(self):
        if (self.period is None) == (self.angular_frequency is None):
            raise ValueError(
                "give exactly one of 'period' [s] or 'angular_frequency' [rad/s] "
                f"(got period={self.period}, angular_frequency={self.angular_frequency})"
            )
        return self


class Ramp(_Model):
    """Linear from start_value at start_time [s] to end_value at end_time, constant outside."""

    kind: Literal["ramp"]
    start_time: float
    end_time: float
    start_value: float = 0.0
    end_value: float

    @model_validator(mode="after")
    def _ordered(self):
        if not self.end_time > self.start_time:
            raise ValueError(
                f"end_time ({self.end_time} s) must be later than start_time ({self.start_time} s)"
            )
        return self


class AccelerationPhase(_Model):
    duration: Pos  # [s]
    acceleration: float  # [m/s^2] (or the unit of the quantity per s^2)


class AccelerationProfile(_Model):
    """A motion built from phases of constant acceleration; gives position, velocity and
    acceleration exactly. After the last phase the acceleration is zero."""

    kind: Literal["acceleration_profile"]
    initial_position: float = 0.0  # [m]
    initial_velocity: float = 0.0  # [m/s]
    start_time: float = 0.0  # [s]
    phases: list[AccelerationPhase] = Field(min_length=1)


class Table(_Model):
    """Values from a CSV file with two columns (time [s], value), interpolated linearly or by a
    clamped cubic spline; held constant outside the table. ``file`` is relative to the case."""

    kind: Literal["table"]
    file: str
    interpolation: Literal["linear", "cubic"] = "linear"

    def load(self, base_dir=None):
        path = Path(self.file)
        if base_dir is not None and not path.is_absolute():
            path = Path(base_dir) / path
        if not path.exists():
            raise ValueError(f"table file '{path}' does not exist")
        rows = []
        with open(path, newline="") as fh:
            for row in csv.reader(fh):
                if not row or row[0].strip().startswith("#"):
                    continue
                try:
                    rows.append((float(row[0]), float(row[1])))
                except (ValueError, IndexError):
                    if rows:  # a header is allowed only on the first line
                        raise ValueError(f"table file '{path}': bad row {row!r}") from None
        data = np.array(rows, dtype=float)
        if data.shape[0] < 2 or not np.all(np.diff(data[:, 0]) > 0):
            raise ValueError(
                f"table file '{path}' needs at least 2 rows with strictly increasing times"
            )
        return data[:, 0], data[:, 1]


def _number_is_constant(value: Any) -> Any:
    """Allow a plain number where a time function is expected (also one YAML 1.1 reads as text,
    such as ``1.0e6``, which pydantic takes as a number everywhere else: the same here)."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return {"kind": "constant", "value": value}
    if isinstance(value, str):
        try:
            number = float(value)
        except ValueError:
            return value
        # text that reads as nan or inf stays text (refused): a finite number only
        return {"kind": "constant", "value": number} if math.isfinite(number) else value
    return value


TimeFunction = Annotated[
    Constant | Sine | Ramp | AccelerationProfile | Table,
    Field(discriminator="kind"),
    BeforeValidator(_number_is_constant),
]


# ---- environment ---------------------------------------------------------------------------------
class Current(_Model):
    """Current flowing towards ``direction_deg`` (from +x towards +y; 0 = along +x): either a
    uniform ``velocity`` [m/s] or a ``profile`` of [elevation z (m, negative below the surface),
    speed (m/s)] pairs, linearly interpolated and held constant beyond the end points."""

    velocity: float | None = None
    profile: list[tuple[float, float]] | None = None
    direction_deg: float = 0.0

    @model_validator(mode="after")
    def _one(self):
        if (self.velocity is None) == (self.profile is None):
            raise ValueError("give exactly one of 'velocity' [m/s] or 'profile' [[z, u], ...]")
        if self.profile is not None:
            if len(self.profile) < 2:
                raise ValueError("a current profile needs at least 2 points")
        return self

    def arrays(self):
        if self.profile is None:
            return np.array([0.0]), np.array([float(self.velocity)])
        data = np.array(sorted(self.profile), dtype=float)
        if np.any(np.diff(data[:, 0]) <= 0):
            raise ValueError("current profile elevations must be distinct")
        return data[:, 0].copy(), data[:, 1].copy()


class Seabed(_Model):
    """Seabed contact of lumped-mass cables: per metre of line, a vertical ``stiffness``
    [N/m per m of line] and ``damping`` [N s/m per m] while a node is below the seabed, and
    Coulomb friction along it (``friction_coefficient``, regularised below ``slip_speed``)."""

    stiffness: Pos = 1.0e5
    damping: NonNeg = 0.0
    friction_coefficient: NonNeg = 0.0
    slip_speed: Pos = 0.01  # [m/s]


class Environment(_Model):
    gravity: Pos = 9.81  # [m/s^2]
    water_density: Pos = 1025.0  # [kg/m^3]
    water_depth: Pos | None = None  # [m]; seabed at z = -water_depth (None: deep water)
    current: Current | None = None
    in_air: bool = False  # true: no buoyancy, no drag, no added mass
    seabed: Seabed | None = None  # contact at z = -water_depth (lumped-mass cables)


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


class Turn(_Model):
    """A turning circle: from ``start_time`` [s] the ship follows a circle of ``radius`` [m]
    turning to the ``side`` given (left: towards +y when heading along +x)."""

    start_time: NonNeg
    radius: Pos
    side: Literal["left", "right"] = "left"


class TowingShipTop(_Model):
    """Tow point on a ship (3D model): starts at ``position`` [x, y, z] (m) heading
    ``heading_deg`` (from +x towards +y) and moves along a straight track, then optionally a
    turning circle. Give a constant ``speed`` [m/s] or the ``distance`` travelled [m] as a time
    function (an acceleration_profile gives speed changes with exact accelerations)."""

    type: Literal["towing_ship"]
    position: Point = (0.0, 0.0, 0.0)
    heading_deg: float = 0.0
    speed: float | None = None
    distance: TimeFunction | None = None
    turn: Turn | None = None

    @model_validator(mode="after")
    def _one_law(self):
        if (self.speed is None) == (self.distance is None):
            raise ValueError("give exactly one of 'speed' [m/s] or 'distance' [m, time function]")
        return self


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
class Sphere(_Model):
    """A sphere of ``radius`` [m] centred on the body's position."""

    kind: Literal["sphere"]
    radius: Pos  # [m]

    def volume(self) -> float:
        return 4.0 / 3.0 * math.pi * self.radius**3


class VerticalCylinder(_Model):
    """A vertical cylinder of ``radius`` and ``height`` [m] centred on the body's position."""

    kind: Literal["vertical_cylinder"]
    radius: Pos  # [m]
    height: Pos  # [m]

    def volume(self) -> float:
        return math.pi * self.radius**2 * self.height


class VolumeTable(_Model):
    """Any hull: ``submerged_volume`` pairs [elevation z of the body's position (m, negative
    below the surface), submerged volume (m^3)], z ascending, the volume not increasing, from
    the whole volume (wholly submerged, at the first z and below) to 0 (clear of the water, at
    the last z and above); linearly interpolated."""

    kind: Literal["table"]
    submerged_volume: list[tuple[float, NonNeg]] = Field(min_length=2)

    @model_validator(mode="after")
    def _monotone(self):
        z = [pair[0] for pair in self.submerged_volume]
        v = [pair[1] for pair in self.submerged_volume]
        if np.any(np.diff(z) <= 0.0):
            raise ValueError(f"submerged_volume: elevations {z} must be strictly ascending [m]")
        if np.any(np.diff(v) > 0.0) or v[0] <= 0.0 or v[-1] != 0.0:
            raise ValueError(
                f"submerged_volume: volumes {v} must not increase with z, from the whole "
                "volume (> 0 m^3, at the lowest z) to 0 (at the highest z)"
            )
        return self

    def volume(self) -> float:
        return float(self.submerged_volume[0][1])


Shape = Annotated[Sphere | VerticalCylinder | VolumeTable, Field(discriminator="kind")]


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


# ---- simulation ----------------------------------------------------------------------------------
FIXED_STEP_INTEGRATORS = ("rk4", "implicit_euler", "theta", "newmark", "generalized_alpha")


class Simulation(_Model):
    duration: Pos  # [s]
    output_interval: Pos  # [s]
    # rk4, dopri5: compiled explicit; implicit_euler, theta, newmark, generalized_alpha:
    # compiled fixed-step implicit (models with a node-block Newton matrix); bdf, radau, lsoda
    # (SciPy) and cvode (SUNDIALS): adaptive stiff, with structured finite-difference Jacobians
    integrator: Literal[
        "rk4", "dopri5", "implicit_euler", "theta", "newmark", "generalized_alpha",
        "bdf", "radau", "lsoda", "cvode",
    ] = "rk4"  # fmt: skip
    # fixed step [s] of rk4 and the implicit schemes (default: output_interval / ceil(...) <=
    # 0.01 s)
    time_step: Pos | None = None
    theta: float = Field(0.5, ge=0.5, le=1.0)  # theta-method weight (1/2: trapezoidal, 1: Euler)
    newmark_gamma: float = Field(0.5, ge=0.5, le=1.0)  # Newmark gamma
    newmark_beta: float = Field(0.25, gt=0.0, le=0.5)  # Newmark beta
    # generalized-alpha rho_infinity: how much of the highest frequencies survives a step. 0.5
    # damps axial ringing enough that a slack segment snapping taut does not feed energy back
    # (a rising body on a line of EA 1e8 N at 5 ms steps: with 0.8 or Newmark's 1 the energy
    # grew 25 to 30 times; with 0.5 or less it decays, as in rk4)
    spectral_radius: float = Field(0.5, ge=0.0, le=1.0)
    # implicit schemes: Newton stops when its last correction of every node position is below
    # this fraction of the shortest segment (a strain)
    newton_tolerance: Pos = 1e-9
    max_newton_iterations: int = Field(10, ge=1, le=100)
    rtol: Pos = 1e-6  # adaptive integrators' relative tolerance
    # adaptive integrators' absolute tolerance, in each state's own unit (one value for every
    # state). Default (None): rtol alone sets the accuracy: dopri5 measures each state's error
    # against rtol times the largest magnitude that state has reached (so small angles and
    # rates are followed to rtol of their own amplitude), with a floor of 1e-3 rtol times the
    # state's scale (models.common.state_scale: angles 1 rad, coordinates the cable's length
    # L, rates those times sqrt(g / L), forces the cable's weight); bdf, radau, lsoda and cvode
    # take a fixed tolerance, rtol times the larger of the state's start value and that floor.
    # The results' attribute solver_tolerance_governing says which tolerance governed
    atol: Pos | None = None
    max_step: Pos | None = None  # adaptive integrators' largest step [s]
    initial_step: Pos = 1e-3  # adaptive integrators' first step [s]
    constraint_stabilization_frequency: Pos = 10.0  # pinned end, Baumgarte [rad/s]
    # build-up period T [s] (0: none), as OrcaFlex's: every imposed motion (imposed top and
    # bottom positions), applied force (floating-structure top force, body and end forces) and
    # trajectory target f(t) is replaced by f(0) + r(t/T) (f(t) - f(0)), r(s) = s^3 (10 - 15 s
    # + 6 s^2) up to T and 1 after, so it starts from its value at t = 0 at rest, with zero
    # acceleration, and equals its own time function from T on (no sudden start against a line
    # started still). A towing ship's speed or distance is not ramped: its initial towed shape
    # is already the steady state at that speed. One to two periods of the motion is usual.
    build_up: NonNeg = 0.0

    @field_validator("time_step")
    @classmethod
    def _step_divides_output_interval(cls, time_step, info):
        """A fixed step must divide the output interval (outputs fall on steps): one that does
        within 1 % is rounded to the divisor, another is refused with the two nearest divisors
        (running silently at a step more than 1 % shorter would cost time the user did not ask
        for, and a longer one could not be stable or accurate as they chose)."""
        interval = info.data.get("output_interval")
        if time_step is None or interval is None:
            return time_step
        if info.data.get("integrator") not in FIXED_STEP_INTEGRATORS:
            return time_step
        steps = max(1, math.ceil(interval / time_step - 1e-9))
        used = interval / steps
        if abs(used - time_step) <= 0.01 * time_step:
            return time_step
        valid = f"{used:.6g} s ({steps} per output)"
        if steps > 1:
            valid = f"{interval / (steps - 1):.6g} s ({steps - 1} per output) or " + valid
        raise ValueError(
            f"{time_step} s does not divide output_interval ({interval} s): the run would use "
            f"{used:.6g} s, {100 * (1 - used / time_step):.3g} % shorter. Use time_step "
            f"{valid}, or an output_interval that is a whole number of time steps"
        )

    @model_validator(mode="after")
    def _ordered(self):
        if (
            self.integrator == "newmark"
            and self.newmark_beta < 0.25 * (self.newmark_gamma + 0.5) ** 2 - 1e-12
        ):
            raise ValueError(
                f"newmark_beta ({self.newmark_beta}) is below (gamma + 1/2)^2 / 4 = "
                f"{0.25 * (self.newmark_gamma + 0.5) ** 2:g} for newmark_gamma "
                f"{self.newmark_gamma}: the scheme would not be unconditionally stable; raise "
                "newmark_beta (0.25 with gamma 0.5 is the average-acceleration rule)"
            )
        if self.output_interval > self.duration:
            raise ValueError(
                f"output_interval ({self.output_interval} s) is longer than duration "
                f"({self.duration} s)"
            )
        count = self.duration / self.output_interval
        if abs(count - round(count)) > 1e-6 * count:
            below = math.floor(count) * self.output_interval
            raise ValueError(
                f"duration ({self.duration} s) is not a whole number of output intervals "
                f"({self.output_interval} s): use duration {below:g} or "
                f"{below + self.output_interval:g}, or another output_interval"
            )
        return self


class Case(_Model):
    """A complete simulation case."""

    name: str = "case"
    description: str = ""
    environment: Environment = Environment()
    cables: list[Cable] = Field(min_length=1)
    bodies: list[SharedBody] = []
    simulation: Simulation
    _source_text: str | None = PrivateAttr(default=None)  # YAML the case was read from
    _base_dir: str | None = PrivateAttr(default=None)  # folder relative file names refer to

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
