"""The force models of a system's bodies (their ``external forces``): one schema class per
``model:`` (frozen, validated pydantic models; units in every field), and their union
``ForceModel``. ``case.system`` holds the bodies that carry them.

Conventions (docs/conventions.md): SI units, the earth frame z up with z = 0 at the still-water
surface, angles in degrees in the case file (keys end in ``_deg``); a body's points are in its
body frame, relative to its reference point.
"""

from typing import Annotated, Literal

from pydantic import Field, model_validator

from seacable.case.base import Constant, NonNeg, PerAxis, Pos, TimeFunction, _Model

Vector = tuple[float, float, float]
Matrix6 = tuple[
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
]
ORIGIN = "origin"  # the point every body has: its reference point
# force models that need a body's mesh
MESH_MODELS = ("non-linear hydrostatic", "non-linear Froude-Krylov")
DATABASE_MODELS = ("radiation damping", "diffraction")  # those that need its database


# ---- force models (``external forces`` of a body) ------------------------------------------------
class Gravity(_Model):
    """The body's weight m g at its centre of gravity, downwards."""

    model: Literal["gravity"]


class Buoyancy(_Model):
    """rho g V_submerged at the centre of buoyancy, upwards: the body's ``volume`` (wholly
    submerged at any elevation) or its ``shape`` (the submerged part as the free surface cuts
    it). Nothing in air (environment.in_air)."""

    model: Literal["buoyancy"]


class Drag(_Model):
    """Quadratic drag on the velocity of the reference point relative to the water (the
    current's and the waves' there), per body axis k: -0.5 rho Cd A_k |v_r| v_r,k (times the
    submerged fraction of a shaped body)."""

    model: Literal["drag"]
    drag_coefficient: NonNeg  # Cd
    area: PerAxis  # A per body axis [m^2]


class FluidInertia(_Model):
    """The water's acceleration on a body without a hull mesh or database, at its reference
    point (forces.fluid_inertia): Froude-Krylov rho V a on its ``volume`` (or ``shape``) and
    its ``added_mass`` on a, as Morison's inertia term; with ``drag``, Morison's equation."""

    model: Literal["fluid inertia"]


class Rod(_Model):
    """A slender cylinder fixed to a rigid body, from ``end_a`` to ``end_b`` (body frame [m]):
    a spar, a column, a pontoon, a brace (MoorDyn's rod on a body). Its loads on the part under
    the instantaneous surface, cut into ``segments``: buoyancy, normal drag and Morison's
    inertia (Froude-Krylov and the normal added mass) per segment, axial drag and added mass
    at each wetted end, the waterplane's moment when it crosses the surface (forces.rod). Its
    added mass joins the body's; its mass is the body's (give the body's ``mass`` and
    ``inertia`` with its rods)."""

    model: Literal["rod"]
    end_a: Vector  # [m], body frame
    end_b: Vector  # [m], body frame
    diameter: Pos  # [m]
    segments: Annotated[int, Field(ge=1, le=1000)] = 10
    drag_coefficient: NonNeg = 0.0  # normal Cd (on the diameter)
    added_mass_coefficient: NonNeg = 0.0  # normal Ca (of the displaced volume)
    end_drag_coefficient: NonNeg = 0.0  # axial CdEnd (on the section's area), per wetted end
    end_added_mass_coefficient: NonNeg = 0.0  # axial CaEnd (of pi d^3 / 12), per wetted end

    @model_validator(mode="after")
    def _length(self):
        if self.end_a == self.end_b:
            raise ValueError(f"end_a and end_b are the same point {list(self.end_a)}: a rod "
                             "needs a length; give two distinct ends [m]")  # fmt: skip
        return self


class AppliedForce(_Model):
    """A force and a moment given as time functions at a point of the body (its reference
    point by default), in the earth frame or, with ``frame: body``, in the body frame (turning
    with the body: a thruster's thrust): a test load, a thrust."""

    model: Literal["applied"]
    point: str = ORIGIN
    frame: Literal["earth", "body"] = "earth"
    force_x: TimeFunction = Constant(value=0.0)  # [N]
    force_y: TimeFunction = Constant(value=0.0)  # [N]
    force_z: TimeFunction = Constant(value=0.0)  # [N], positive up
    moment_x: TimeFunction = Constant(value=0.0)  # [N m]
    moment_y: TimeFunction = Constant(value=0.0)  # [N m]
    moment_z: TimeFunction = Constant(value=0.0)  # [N m]


class _MatrixOrDiagonal(_Model):
    """A 6x6 ``matrix`` or its ``diagonal``, exactly one of them."""

    @model_validator(mode="after")
    def _one_form(self):
        if (self.matrix is None) == (self.diagonal is None):
            raise ValueError("give exactly one of 'matrix' (6x6) or 'diagonal' (6 values)")
        return self


class LinearStiffness(_MatrixOrDiagonal):
    """F = -K d: d the body's displacement from ``equilibrium`` (x, y, z [m] of the reference
    point, then roll, pitch, yaw [rad] as the small rotation vector from the equilibrium
    orientation), K [N/m, N/rad, N m/m, N m/rad] in the earth frame at the reference point: a
    hydrostatic stiffness, a mooring's linearisation, elastic ties to the earth. ``matrix``
    6x6, or ``diagonal`` (6 values); ``equilibrium`` defaults to the initial pose."""

    model: Literal["linear_stiffness"]
    matrix: Matrix6 | None = None
    diagonal: tuple[float, float, float, float, float, float] | None = None
    equilibrium_position: Vector | None = None  # [m]
    equilibrium_orientation_deg: Vector | None = None  # roll, pitch, yaw [deg]


class LinearDamping(_MatrixOrDiagonal):
    """F = -B nu, B [N s/m, N s, N m s/m, N m s/rad] 6x6 or ``diagonal``. ``frame: earth``: nu
    the reference point's velocity [m/s] and the angular velocity [rad/s] in the earth frame.
    ``frame: body`` (a vessel's viscous damping): nu the velocity relative to the current and
    the angular velocity in the body frame, B in the body frame at ``point`` (body frame, by
    default the reference point; moved to it), the force turned into the earth frame."""

    model: Literal["linear_damping"]
    matrix: Matrix6 | None = None
    diagonal: tuple[NonNeg, NonNeg, NonNeg, NonNeg, NonNeg, NonNeg] | None = None
    frame: Literal["earth", "body"] = "earth"
    point: Vector | None = None  # [m], body frame (frame: body)

    @model_validator(mode="after")
    def _point_in_body_frame(self):
        if self.point is not None and self.frame == "earth":
            raise ValueError("'point' is for frame: body (the matrix is then at that point)")
        return self


class QuadraticDamping(_MatrixOrDiagonal):
    """A vessel's quadratic viscous damping: F = -B (|nu| nu), |nu_j| nu_j component by
    component, nu the body-frame velocity relative to the current and angular velocity (as
    ``linear_damping`` with ``frame: body``); B [N s^2/m^2, N s^2/rad, N m s^2/m^2,
    N m s^2/rad^2] at ``point`` (body frame, default the reference point)."""

    model: Literal["quadratic_damping"]
    matrix: Matrix6 | None = None
    diagonal: tuple[NonNeg, NonNeg, NonNeg, NonNeg, NonNeg, NonNeg] | None = None
    point: Vector | None = None  # [m], body frame


class ServoForce(_Model):
    """Jacquot & Marichal's trajectory servo (1993, section 4): a force F on the body, at its
    reference point, that brings it to the point ``target`` (``body`` or ``body.point``): the
    correction dF = K (a dE - b dt dE') once per servo step dt (dE the target less the body's
    position, dE' its rate), integrated as a rate, dF/dt = K (a dE / dt - b dE'). F is a state of
    the system. K is the stiffness of the body's lines: static equilibria with the body held
    on a sphere of ``sphere_radius`` around the target (every kinematic body in its steady
    motion), linearised by least squares; F starts as the force that holds the body at the
    target. ``recompute_interval`` refreshes K about the current target during the run. A gain
    and step whose loop would let an error grow by more than e over the run are refused."""

    model: Literal["servo"]
    target: str
    gain: Annotated[float, Field(gt=0, le=2)] = 1.0  # a
    rate_gain: Annotated[float, Field(ge=0, lt=1)] = 0.0  # b
    step: Pos | None = None  # dt [s]; default: the integration step
    sphere_radius: Pos = 1.0  # [m]
    recompute_interval: Pos | None = None  # [s]


class NonLinearHydrostatic(_Model):
    """The ship-simulator document's non-linear hydrostatics: the still-water pressure
    rho g (-z) integrated exactly on the body's ``mesh`` clipped at the free surface z = 0 at
    every evaluation: buoyancy and its moment at any draft, heel and trim (a rigid body with a
    ``mesh``; instead of ``buoyancy``). In waves the mesh is clipped at their elevation
    (``free_surface: waves``, the document's, with ``non-linear Froude-Krylov``) or at z = 0
    (``still``: with a database's linear excitation, ``diffraction`` with ``froude_krylov``,
    which holds the incident wave's pressure already)."""

    model: Literal["non-linear hydrostatic"]
    free_surface: Literal["waves", "still"] = "waves"


class NonLinearFroudeKrylov(_Model):
    """The ship-simulator document's Froude-Krylov force: the incident waves' dynamic
    pressure (environment.waves) integrated on the body's ``mesh`` under the wave elevation
    at every evaluation (with ``non-linear hydrostatic``, the whole undisturbed pressure)."""

    model: Literal["non-linear Froude-Krylov"]


class RadiationDamping(_Model):
    """The ship-simulator document's radiation damping: the memory force
    -int_0^Tc K(tau) nu(t - tau) d tau on the body-frame velocity history, K(t) = (2/pi)
    int B(w) cos(w t) dw from the body's ``hydrodynamics`` database, over ``memory`` seconds
    (25 s, the document's) sampled every ``memory_step``. The database's infinite-frequency
    added mass (its own, or from Ogilvie's relation) is the body's added mass unless the body
    gives one. A kernel still above 1 % of its peak at the cut-off is reported. The body is
    taken at rest before the run starts.

    Beyond the database's last frequency w_N, B(w) is taken as ``high_frequency_tail: power``
    (the default) B(w_N) (w_N / w)^p, p = ``tail_power`` (3: the radiated wave energy flux of a
    surface-piercing wall moving horizontally falls as rho g^2 / (2 w^3) per metre of
    waterline), or zero (``none``: a database cut where B is still large then gives a K that
    rings as B(w_N) sin(w_N t) / t). The tail is in K, in its state-space fit and in Ogilvie's
    A_inf alike (seacable.hydrodb).

    ``method: convolution`` (the default) integrates over the recorded velocity history;
    ``method: state_space`` replaces each non-negligible K_ij(t) (sampled as above) by a fitted
    stable system of at most ``order`` first-order states, the lowest order whose relative L2
    error over the samples is within ``tolerance`` (seacable.realization; an entry above it is
    reported): a cost independent of ``memory``."""

    model: Literal["radiation damping"]
    memory: Pos = 25.0  # Tc [s]
    memory_step: Pos = 0.05  # [s]
    method: Literal["convolution", "state_space"] = "convolution"
    order: Annotated[int, Field(ge=2, le=40)] = 12  # most states per entry (state_space)
    tolerance: Annotated[float, Field(gt=0, lt=1)] = 0.01  # relative L2 error (state_space)
    high_frequency_tail: Literal["power", "none"] = "power"  # B beyond the last frequency
    tail_power: Annotated[int, Field(ge=2, le=4)] = 3  # p of B(w_N) (w_N / w)^p [-]


class Diffraction(_Model):
    """The ship-simulator document's diffraction force: the body's ``hydrodynamics``
    database's wave excitation for each incident wave component, interpolated in frequency and
    in the wave's direction relative to the body's heading, at the body's place.
    ``froude_krylov: true`` adds the database's linear Froude-Krylov force (the whole linear
    excitation; leave it out with ``non-linear Froude-Krylov``)."""

    model: Literal["diffraction"]
    froude_krylov: bool = False


# ---- controlled forces, wind and current loads (a vessel's) --------------------------------------
BodyPoint = str | Vector  # a point's name (``origin``: the reference point) or its body-frame
# coordinates [m]


class SpeedController(_Model):
    """A thruster's surge-speed controller: T = feedforward + gain (target - u) +
    integral_gain I, dI/dt = target - u, u the body's surge speed over ground [m/s]
    (forces.thruster). Proportional alone (integral_gain 0), the speed settles below the
    target unless the feed-forward thrust is the resistance there; the integral removes the
    offset, and is held while ``max_thrust`` limits the thrust (no wind-up)."""

    kind: Literal["surge_speed"]
    target: TimeFunction  # U [m/s]
    gain: Pos  # K [N s/m]
    integral_gain: NonNeg = 0.0  # K_i [N/m]
    feedforward: TimeFunction = Constant(value=0.0)  # T_ff [N]


class Thruster(_Model):
    """A propeller, tunnel or azimuth thruster (forces.thruster): thrust [N] at ``point`` along
    the body-frame unit ``direction`` (default +x, ahead) or, for an azimuth thruster, along
    ``azimuth_deg`` (a time function: the angle from the bow towards port, in the horizontal
    body plane); from the time function ``thrust`` or the ``controller``, exactly one; |thrust|
    limited to ``max_thrust`` when given."""

    model: Literal["thruster"]
    point: BodyPoint = ORIGIN
    direction: Vector = (1.0, 0.0, 0.0)  # body frame
    azimuth_deg: TimeFunction | None = None  # [deg]
    thrust: TimeFunction | None = None  # [N]
    controller: SpeedController | None = None
    max_thrust: Pos | None = None  # [N]

    @model_validator(mode="after")
    def _one_law(self):
        if (self.thrust is None) == (self.controller is None):
            raise ValueError("give exactly one of 'thrust' [N, time function] or 'controller' "
                             "({kind: surge_speed, target, gain})")  # fmt: skip
        if not sum(v * v for v in self.direction) > 0.0:
            raise ValueError(f"direction {list(self.direction)} has no length; give a non-zero "
                             "body-frame vector such as [1, 0, 0] (ahead)")  # fmt: skip
        if self.azimuth_deg is not None and self.direction != (1.0, 0.0, 0.0):
            raise ValueError("give 'direction' (a fixed thruster) or 'azimuth_deg' (an azimuth "
                             "thruster), not both")  # fmt: skip
        return self


class Autopilot(_Model):
    """A heading autopilot: rudder angle = gain (heading - psi) - rate_gain r, limited to
    +-max_angle_deg (psi the body's heading, r its yaw rate [rad/s]; forces.rudder)."""

    heading_deg: TimeFunction  # target, from +x towards +y [deg]
    gain: Pos  # K_p [deg of rudder per deg of heading error]
    rate_gain: NonNeg = 0.0  # K_d [s]
    max_angle_deg: Annotated[float, Field(gt=0, le=90)] = 35.0


class SteeringGear(_Model):
    """The rudder's steering gear: the angle follows the command (``angle_deg`` or the
    autopilot's) at most at ``max_rate_deg_s`` [deg/s] (SOLAS II-1/29: 35 deg on one side to
    30 deg on the other within 28 s, 2.3 deg/s), as a first-order lag of ``time_constant``
    [s] within that rate (the default, 0.1 s, is close to the pure rate limit of manoeuvring
    standards and only rounds the arrival on the command). The rudder starts amidships."""

    max_rate_deg_s: Pos
    time_constant: Pos = 0.1  # [s]


class Rudder(_Model):
    """A rudder (forces.rudder): a foil of ``area`` [m^2] at ``point``, its lift perpendicular to
    the water's flow past it and its drag along it, in the horizontal body plane; C_L from the
    ``lift_slope`` [1/rad] up to ``stall_angle_deg`` (held beyond) with C_D = drag_coefficient
    + C_L^2 / (pi aspect_ratio), or both from ``coefficients`` [[alpha_deg, C_L, C_D], ...].
    The rudder angle (positive: trailing edge to port, turning the ship to port) from
    ``angle_deg`` or the ``autopilot``, exactly one, through the ``steering_gear`` when given
    (else at once). ``slipstream_factor`` multiplies the inflow's fore-and-aft component (a
    propeller's wash)."""

    model: Literal["rudder"]
    point: BodyPoint = ORIGIN
    area: Pos  # [m^2]
    lift_slope: Pos | None = None  # [1/rad]
    stall_angle_deg: Annotated[float, Field(gt=0, le=90)] = 35.0
    drag_coefficient: NonNeg = 0.0  # C_D0
    aspect_ratio: Pos | None = None  # Lambda, for the induced drag
    coefficients: list[tuple[float, float, NonNeg]] | None = Field(default=None, min_length=2)
    slipstream_factor: Pos = 1.0
    angle_deg: TimeFunction | None = None  # [deg]
    autopilot: Autopilot | None = None
    steering_gear: SteeringGear | None = None

    @model_validator(mode="after")
    def _one_of_each(self):
        if (self.angle_deg is None) == (self.autopilot is None):
            raise ValueError("give exactly one of 'angle_deg' [deg, time function] or "
                             "'autopilot' ({heading_deg, gain, rate_gain})")  # fmt: skip
        if (self.lift_slope is None) == (self.coefficients is None):
            raise ValueError("give exactly one of 'lift_slope' [1/rad] or 'coefficients' "
                             "[[alpha_deg, C_L, C_D], ...]")  # fmt: skip
        if self.coefficients is not None:
            alphas = [row[0] for row in self.coefficients]
            if any(b <= a for a, b in zip(alphas, alphas[1:], strict=False)) or any(
                    abs(a) > 90.0 for a in alphas):  # fmt: skip
                raise ValueError(f"coefficients: angles of attack {alphas} must increase "
                                 "strictly within [-90, 90] deg")  # fmt: skip
        return self


class _CoefficientLoad(_Model):
    """OCIMF-style loads from coefficient tables (forces.coefficients): F_x = q A_T C_X(psi),
    F_y = q A_L C_Y(psi), M_z = q A_L L C_N(psi) at ``point``, q = 1/2 rho V^2, V the flow's
    speed relative to the point, psi the direction it comes from (from the bow towards port);
    the coefficients dimensionless, [[psi_deg, C_X, C_Y, C_N], ...] or a CSV file of those
    four columns (a header line allowed), psi ascending over less than 360 deg, interpolated
    linearly and periodically. ``symmetric``: the table covers 0 to 180 deg and the other side
    mirrors it (C_X even, C_Y and C_N odd in psi)."""

    point: Vector = (0.0, 0.0, 0.0)  # where the force acts and C_N refers to, body frame [m]
    transverse_area: Pos  # A_T [m^2]
    lateral_area: Pos  # A_L [m^2]
    length: Pos  # L [m]
    coefficients: list[tuple[float, float, float, float]] | str
    symmetric: bool = False


class WindLoad(_CoefficientLoad):
    """The wind's load (environment.wind, air_density)."""

    model: Literal["wind"]


class CurrentLoad(_CoefficientLoad):
    """The current's load (environment.current at the point's elevation, water_density)."""

    model: Literal["current"]


class WaveDrift(_Model):
    """The mean wave drift force (forces.wave_drift) of the case's ``environment.waves``:
    F = sum_i a_i^2 D(w_i, beta_i) at ``point``, a_i [m] and w_i [rad/s] the sea's
    components, beta_i the direction each comes from, from the bow towards port (0: head
    seas). ``coefficients``: [[beta_deg, D_X, D_Y, D_N], ...] (independent of frequency) or
    [[omega, beta_deg, D_X, D_Y, D_N], ...] (omega [rad/s] ascending, the same headings at
    each), or a CSV file of those columns; D_X, D_Y in N/m^2, D_N in N m/m^2 (per unit
    squared amplitude); beta ascending over less than 360 deg, interpolated linearly and
    periodically, omega linearly (held at its ends). ``symmetric``: 0 to 180 deg given, the
    other side mirrored (D_X even, D_Y and D_N odd in beta)."""

    model: Literal["wave drift"]
    point: BodyPoint = ORIGIN  # where the force acts and D_N refers to
    coefficients: (
        list[tuple[float, float, float, float] | tuple[float, float, float, float, float]] | str
    )
    symmetric: bool = False


class HullDerivatives(_Model):
    """Clarke's linear derivatives (non-dimensional, prime: Y_v per 1/2 rho L^2 U, Y_r and N_v
    per 1/2 rho L^3 U, N_r per 1/2 rho L^4 U) replacing the values Clarke, Gedling and Hine's
    regression gives for the hull's L, B, T and C_B; any of them."""

    Y_v: float | None = None
    Y_r: float | None = None
    N_v: float | None = None
    N_r: float | None = None


class _HullCurrent(_Model):
    """A ship hull's forces in the horizontal plane from the water flowing past it, at any
    drift angle, with yaw-rate terms (forces.hull_current): on the velocity relative to the
    water at ``point`` (midship), the loads acting there."""

    point: Vector = (0.0, 0.0, 0.0)  # midship, body frame [m]
    length: Pos  # L, between perpendiculars [m]
    beam: Pos  # B [m]
    draught: Pos  # T [m]
    block_coefficient: Annotated[float, Field(gt=0.0, le=1.0)]  # C_B [-]
    wetted_area: Pos | None = None  # S [m^2]; default Denny-Mumford's 1.7 L T + C_B L B
    cross_flow_drag: Pos  # C_Y, the drag coefficient in beam flow, on L T [-] (0.6 to 1.1
    # for tankers; higher in shallow water)
    cross_flow_centre: float = 0.0  # x_Y, where the beam flow's force acts, forward of
    # ``point`` [m]
    form_factor: NonNeg = 0.25  # k in (1 + k) C_F, the friction's form factor [-]
    kinematic_viscosity: Pos = 1.19e-6  # nu of the water [m^2/s] (sea water at 15 C)
    derivatives: HullDerivatives | None = None  # Clarke's, replaced


class ShortWing(_HullCurrent):
    """Leite, Aranha, Umeda and de Conti's (1998) short-wing model; its yaw-rate terms:
    Clarke's Y_r, N_r times |u| and the cross-flow drag of each station."""

    model: Literal["short-wing"]

    @model_validator(mode="after")
    def _static_terms_are_the_models(self):
        d = self.derivatives
        if d is not None and (d.Y_v is not None or d.N_v is not None):
            raise ValueError(
                "derivatives: the short-wing model's drift terms come from its own formula; "
                "give only Y_r and N_r, or use model: cross-flow to set Y_v and N_v"
            )
        return self


class CrossFlow(_HullCurrent):
    """The low-speed manoeuvring model of the MMG kind: Clarke's linear lift terms, which
    vanish in beam flow, plus the cross-flow drag integrated along the hull."""

    model: Literal["cross-flow"]


class Compensator(_Model):
    """The tandem compensator (forces.compensator): the surge force and yaw moment, by feedback
    linearisation, that hold the horizontal distance from this body's ``point`` (its hawser's
    fairlead) to the ``target`` point (``body.point``, the FPSO's stern) at ``distance`` and
    the ship's heading at ``heading_deg`` from the target body's heading (``relative``) or from
    the bearing of the target point (``line of sight``), each error then obeying
    e'' + 2 z w e' + w^2 e = 0; the force and moment limited to the ship's thrust."""

    model: Literal["compensator"]
    point: str  # this body's point [name]
    target: str  # "body.point"
    distance: Pos  # d* [m]
    heading: Literal["relative", "line of sight"] = "relative"
    heading_deg: float = 0.0  # h* [deg]
    frequency: Pos = 0.02  # w1 of the distance [rad/s]
    heading_frequency: Pos = 0.02  # w2 [rad/s]
    damping_ratio: Pos = 1.0  # z1 = z2
    max_ahead: Pos | None = None  # [N]; none: unlimited
    max_astern: Pos | None = None  # [N]
    max_yaw_moment: Pos | None = None  # [N m]
    enabled: bool = True  # false: the ship uncontrolled (the same case, for comparison)


ForceModel = Annotated[
    Gravity
    | Buoyancy
    | Drag
    | AppliedForce
    | LinearStiffness
    | LinearDamping
    | ServoForce
    | NonLinearHydrostatic
    | QuadraticDamping
    | NonLinearFroudeKrylov
    | RadiationDamping
    | Diffraction
    | Thruster
    | Rudder
    | WindLoad
    | CurrentLoad
    | ShortWing
    | CrossFlow
    | Compensator
    | WaveDrift
    | FluidInertia
    | Rod,
    Field(discriminator="model"),
]
