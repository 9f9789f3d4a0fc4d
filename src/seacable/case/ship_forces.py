"""The force models of a ship manoeuvring in the horizontal plane (``external forces`` of a
rigid body): thrusters and their speed controller, propellers from their open-water curves,
rudders with their autopilot and steering gear, fins with their roll controller, wind and
current loads from coefficient tables, the mean wave drift, a hull's current
loads (``short-wing``, ``cross-flow``) and the tandem compensator. ``case.forces`` gathers them
with the general models into the ``ForceModel`` union.

Conventions (docs/conventions.md): SI units, the body frame x forward, y to port, z up;
angles in degrees in the case file (keys end in ``_deg``), in the horizontal body plane from
the bow (+x) towards port (+y), counter-clockwise seen from above.
"""

from typing import Annotated, Literal

from pydantic import Field, model_validator

from seacable.case.base import ORIGIN, Constant, NonNeg, Pos, TimeFunction, Vector, _Model

BodyPoint = str | Vector  # a point's name (``origin``: the reference point) or its body-frame
# coordinates [m]


# ---- thrusters, propellers, rudders and fins ------------------------------------------------
class SpeedController(_Model):
    """A thruster's surge-speed controller: T = feedforward + gain (target - u) +
    integral_gain I, dI/dt = target - u, u the body's surge speed over ground [m/s]
    (forces.thruster). Proportional alone (integral_gain 0), the speed settles below the
    target unless the feed-forward thrust is the resistance there; the integral removes the
    offset, and is held while ``max_thrust`` limits the thrust (no wind-up)."""

    kind: Literal["surge_speed"]
    target: TimeFunction
    """[m/s] Target surge speed U over ground of the body's reference point."""
    gain: Pos
    """[N s/m] Proportional gain K on the speed error U - u."""
    integral_gain: NonNeg = 0.0
    """[N/m] Integral gain K_i on the time integral I of the speed error."""
    feedforward: TimeFunction = Constant(value=0.0)
    """[N] Feed-forward thrust T_ff, at best the ship's resistance at the target speed."""


class Thruster(_Model):
    """A propeller, tunnel or azimuth thruster (forces.thruster): thrust [N] at ``point`` along
    the body-frame unit ``direction`` (default +x, ahead) or, for an azimuth thruster, along
    ``azimuth_deg`` (a time function: the angle from the bow towards port, in the horizontal
    body plane); from the time function ``thrust`` or the ``controller``, exactly one; |thrust|
    limited to ``max_thrust`` when given."""

    model: Literal["thruster"]
    point: BodyPoint = ORIGIN
    """[m] Where the thrust acts: a point's name (``origin``: the reference point) or [x, y, z]."""
    direction: Vector = (1.0, 0.0, 0.0)
    """[-] Direction of positive thrust in the body frame, of any length (normalised)."""
    azimuth_deg: TimeFunction | None = None
    """[deg] An azimuth thruster's angle from the bow towards port, in the horizontal body plane."""
    thrust: TimeFunction | None = None
    """[N] Thrust along the direction (negative: reversed)."""
    controller: SpeedController | None = None
    """The surge-speed controller that sets the thrust, instead of ``thrust``."""
    max_thrust: Pos | None = None
    """[N] Largest |thrust|. Omitted: unlimited."""

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

    heading_deg: TimeFunction
    """[deg] Target heading of the body's x axis, from +x towards +y."""
    gain: Pos
    """[-] K_p: degrees of rudder angle per degree of heading error."""
    rate_gain: NonNeg = 0.0
    """[s] K_d: rudder angle [rad] per yaw rate [rad/s], against the turn."""
    max_angle_deg: Annotated[float, Field(gt=0, le=90)] = 35.0
    """[deg] Largest rudder angle the autopilot commands, to either side."""


class _Gear(_Model):
    """What turns a foil: its angle follows the command at most at ``max_rate_deg_s``, as a
    first-order lag of ``time_constant`` within that rate, from 0 (forces.foil)."""

    max_rate_deg_s: Pos
    """[deg/s] Fastest rate at which the angle turns towards its command."""
    time_constant: Pos = 0.1
    """[s] Time constant T of the first-order lag towards the command, within that rate."""


class SteeringGear(_Gear):
    """The rudder's steering gear: the angle follows the command (``angle_deg`` or the
    autopilot's) at most at ``max_rate_deg_s`` [deg/s] (SOLAS II-1/29: 35 deg on one side to
    30 deg on the other within 28 s, 2.3 deg/s), as a first-order lag of ``time_constant``
    [s] within that rate (the default, 0.1 s, is close to the pure rate limit of manoeuvring
    standards and only rounds the arrival on the command). The rudder starts amidships."""


class _Foil(_Model):
    """A foil's lift and drag law (forces.foil): C_L from the ``lift_slope`` up to the stall,
    or C_L and C_D from ``coefficients``."""

    area: Pos
    """[m^2] Area A of the foil, on which C_L and C_D are taken."""
    lift_slope: Pos | None = None
    """[1/rad] Lift slope a of C_L = a alpha up to the stall (or give ``coefficients``)."""
    stall_angle_deg: Annotated[float, Field(gt=0, le=90)] = 35.0
    """[deg] Angle of attack beyond which C_L is held (with ``lift_slope``)."""
    drag_coefficient: NonNeg = 0.0
    """[-] Drag coefficient C_D0 at zero lift (with ``lift_slope``)."""
    aspect_ratio: Pos | None = None
    """[-] Aspect ratio Lambda of the induced drag C_L^2 / (pi Lambda). Omitted: none."""
    coefficients: list[tuple[float, float, NonNeg]] | None = Field(default=None, min_length=2)
    """[deg, -, -] Rows [alpha_deg, C_L, C_D], alpha ascending within [-90, 90], held beyond."""

    @model_validator(mode="after")
    def _one_foil_law(self):
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


class Rudder(_Foil):
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
    """[m] Where the inflow is taken and the force acts: a point's name or body-frame [x, y, z]."""
    slipstream_factor: Pos = 1.0
    """[-] Factor k on the inflow's fore-and-aft component (a propeller's wash)."""
    angle_deg: TimeFunction | None = None
    """[deg] Rudder angle (with a steering gear, its command); positive: trailing edge to port."""
    autopilot: Autopilot | None = None
    """The heading autopilot that sets the rudder angle, instead of ``angle_deg``."""
    steering_gear: SteeringGear | None = None
    """The gear the angle follows its command through. Omitted: the angle is the command."""

    @model_validator(mode="after")
    def _one_law(self):
        if (self.angle_deg is None) == (self.autopilot is None):
            raise ValueError("give exactly one of 'angle_deg' [deg, time function] or "
                             "'autopilot' ({heading_deg, gain, rate_gain})")  # fmt: skip
        return self


class PropellerController(SpeedController):
    """A propeller's surge-speed controller, the thruster's law setting the rate of turn:
    n = feedforward + gain (target - u) + integral_gain I, dI/dt = target - u, u the body's
    surge speed over ground [m/s] (forces.speed_control), n within [0, max_rpm]; the integral
    is held while a limit holds n (no wind-up)."""

    gain: Pos
    """[rpm s/m] Proportional gain K: revolutions per minute per m/s of speed error."""
    integral_gain: NonNeg = 0.0
    """[rpm/m] Integral gain K_i on the time integral I of the speed error."""
    feedforward: TimeFunction = Constant(value=0.0)
    """[rpm] Feed-forward rate n_ff, at best the rate that holds the ship at the target."""


class BSeries(_Model):
    """The Wageningen B-screw series' open-water curves, from Oosterveld and van Oossanen's
    (1975) regression polynomials at a Reynolds number of 2e6 (forces.bseries), over their
    range: J from 0 to where K_T vanishes (held beyond)."""

    kind: Literal["b_series"]
    pitch_ratio: Annotated[float, Field(ge=0.5, le=1.4)]
    """[-] Pitch ratio P/D (at 0.7 of the radius), within the series' 0.5 to 1.4."""
    area_ratio: Annotated[float, Field(ge=0.3, le=1.05)]
    """[-] Expanded blade area ratio A_E/A_0, within the series' 0.30 to 1.05."""
    blades: Annotated[int, Field(ge=2, le=7)]
    """[-] Number of blades Z, within the series' 2 to 7."""


class OpenWaterTable(_Model):
    """A propeller's own open-water curves: rows [J, K_T, K_Q], J ascending (from 0, the
    bollard pull, to where K_T vanishes, as an open-water test gives them), or a CSV file of
    those three columns (a header line allowed); linear between rows and held at the first
    and last beyond them, not extrapolated (forces.propeller)."""

    kind: Literal["table"]
    coefficients: list[tuple[float, float, float]] | str
    """[-, -, -] Rows [J, K_T, K_Q], J ascending, or a CSV file's path (relative to the case)."""

    @model_validator(mode="after")
    def _ascending(self):
        if isinstance(self.coefficients, list):
            advances = [row[0] for row in self.coefficients]
            if len(advances) < 2 or any(b <= a for a, b in zip(advances, advances[1:],
                                                               strict=False)):  # fmt: skip
                raise ValueError(f"coefficients: advance ratios {advances} must be 2 or more, "
                                 "increasing strictly; give rows [J, K_T, K_Q] with J "
                                 "ascending")  # fmt: skip
        return self


OpenWater = Annotated[BSeries | OpenWaterTable, Field(discriminator="kind")]


class Propeller(_Model):
    """A ship's propeller from its open-water curves (forces.propeller): at ``point``, along
    the shaft ``direction``, the thrust (1 - t) rho n^2 D^4 K_T(J) and the shaft's torque
    rho n^2 D^5 K_Q(J) / eta_R on the hull about the shaft (its sign by the ``rotation``),
    J = (1 - w) u_a / (n D), u_a the propeller's speed through the water along its shaft
    (the current at its depth taken away). The rate of turn n from the time function ``rpm``
    or the ``controller``, exactly one, in [0, ``max_rpm``]: turning ahead only (a stopped
    propeller gives neither thrust nor torque)."""

    model: Literal["propeller"]
    point: BodyPoint = ORIGIN
    """[m] The propeller's centre: a point's name (``origin``: the reference point) or [x, y, z]."""
    direction: Vector = (1.0, 0.0, 0.0)
    """[-] The shaft's direction in the body frame, of the thrust turning ahead (normalised)."""
    diameter: Pos
    """[m] Diameter D of the propeller."""
    open_water: OpenWater
    """The open-water curves K_T(J), K_Q(J): the B-series' polynomials or a table."""
    rpm: TimeFunction | None = None
    """[rpm] Rate of turn n in revolutions per minute, 0 or more (turning ahead)."""
    controller: PropellerController | None = None
    """The surge-speed controller that sets the rate of turn, instead of ``rpm``."""
    max_rpm: Pos | None = None
    """[rpm] Largest rate of turn. Omitted: unlimited."""
    rotation: Literal["right", "left"] = "right"
    """Right-handed (clockwise seen from astern, turning ahead; heels the ship to port) or left."""
    wake_fraction: Annotated[float, Field(ge=0.0, lt=1.0)] = 0.0
    """[-] Taylor wake fraction w: the speed of advance is (1 - w) times the propeller's speed."""
    thrust_deduction: Annotated[float, Field(ge=0.0, lt=1.0)] = 0.0
    """[-] Thrust deduction t: the hull feels (1 - t) times the open-water thrust."""
    relative_rotative_efficiency: Annotated[float, Field(gt=0.0, le=2.0)] = 1.0
    """[-] eta_R: the torque behind the hull is the open-water torque over it."""

    @model_validator(mode="after")
    def _one_law(self):
        if (self.rpm is None) == (self.controller is None):
            raise ValueError("give exactly one of 'rpm' [rpm, time function] or 'controller' "
                             "({kind: surge_speed, target, gain})")  # fmt: skip
        if not sum(v * v for v in self.direction) > 0.0:
            raise ValueError(f"direction {list(self.direction)} has no length; give the "
                             "shaft's body-frame direction such as [1, 0, 0] (ahead)")  # fmt: skip
        return self


class RollController(_Model):
    """A fin's roll controller: fin angle = -sigma (gain phi + rate_gain p), limited to
    +-max_angle_deg, phi the body's roll [rad], p its roll rate [rad/s], sigma the sign of the
    roll moment a positive angle gives going ahead (forces.fin): positive gains oppose the
    roll, on either side, going ahead (astern the lift reverses)."""

    gain: Pos
    """[-] K_p: degrees of fin angle per degree of roll."""
    rate_gain: NonNeg = 0.0
    """[s] K_d: fin angle [rad] per roll rate [rad/s]."""
    max_angle_deg: Annotated[float, Field(gt=0, le=90)] = 25.0
    """[deg] Largest fin angle the controller commands, to either side."""


class FinActuator(_Gear):
    """The fin's actuator: its angle follows the command (``angle_deg`` or the roll
    controller's) at most at ``max_rate_deg_s`` [deg/s] (a stabiliser's fins turn at 20 to 40
    deg/s), as a first-order lag of ``time_constant`` [s] within that rate, from 0."""


class Fin(_Foil):
    """A fin (forces.fin): a roll stabiliser's fin, or any foil fixed to the hull and turned
    about its span, of ``area`` [m^2] at ``point``: lift and drag (the rudder's law: C_L from
    ``lift_slope`` up to ``stall_angle_deg``, or ``coefficients``) on its velocity through the
    water in the plane normal to ``span_direction``, rotation included. Angle 0: the chord
    along the body's x; positive: turned about the span direction by the right-hand rule (a
    starboard fin, span [0, -1, 0], leading edge up). The angle from ``angle_deg`` or the
    ``roll_controller``, exactly one, through the ``actuator`` when given."""

    model: Literal["fin"]
    point: BodyPoint = ORIGIN
    """[m] Where the inflow is taken and the force acts: a point's name or body-frame [x, y, z]."""
    span_direction: Vector
    """[-] From the fin's root to its tip, body frame: [0, -1, 0] starboard, [0, 1, 0] port."""
    angle_deg: TimeFunction | None = None
    """[deg] Fin angle (with an actuator, its command), about the span direction."""
    roll_controller: RollController | None = None
    """The roll controller that sets the fin angle, instead of ``angle_deg``."""
    actuator: FinActuator | None = None
    """What turns the fin at a limited rate. Omitted: the angle is the command."""

    @model_validator(mode="after")
    def _one_law(self):
        if (self.angle_deg is None) == (self.roll_controller is None):
            raise ValueError("give exactly one of 'angle_deg' [deg, time function] or "
                             "'roll_controller' ({gain, rate_gain, max_angle_deg})")  # fmt: skip
        x, y, z = self.span_direction
        if not y * y + z * z > 1e-12 * (x * x + y * y + z * z):
            raise ValueError(f"span_direction {list(self.span_direction)} has no length or "
                             "lies along the body's x axis (the flow going ahead would run "
                             "along the span); give the direction from the fin's root to "
                             "its tip across the flow, such as [0, -1, 0] for a starboard "
                             "fin")  # fmt: skip
        return self


# ---- wind, current and wave drift loads from tables ----------------------------------------
class _CoefficientLoad(_Model):
    """OCIMF-style loads from coefficient tables (forces.coefficients): F_x = q A_T C_X(psi),
    F_y = q A_L C_Y(psi), M_z = q A_L L C_N(psi) at ``point``, q = 1/2 rho V^2, V the flow's
    speed relative to the point, psi the direction it comes from (from the bow towards port);
    the coefficients dimensionless, [[psi_deg, C_X, C_Y, C_N], ...] or a CSV file of those
    four columns (a header line allowed), psi ascending over less than 360 deg, interpolated
    linearly and periodically. ``symmetric``: the table covers 0 to 180 deg and the other side
    mirrors it (C_X even, C_Y and C_N odd in psi)."""

    point: Vector = (0.0, 0.0, 0.0)
    """[m] Body-frame point where the force acts, about which C_N's moment is taken."""
    transverse_area: Pos
    """[m^2] Transverse projected area A_T (seen from ahead), of F_x."""
    lateral_area: Pos
    """[m^2] Lateral projected area A_L (seen from the side), of F_y and M_z."""
    length: Pos
    """[m] Length L of the moment M_z = q A_L L C_N."""
    coefficients: list[tuple[float, float, float, float]] | str
    """[deg, -, -, -] Rows [psi_deg, C_X, C_Y, C_N], or a CSV file's path (relative to the case)."""
    symmetric: bool = False
    """The table covers 0 to 180 deg; the other side mirrors it (C_X even, C_Y and C_N odd)."""


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
    point: BodyPoint = ORIGIN
    """[m] Where the force acts, D_N's moment about it: a point's name or body-frame [x, y, z]."""
    coefficients: (
        list[tuple[float, float, float, float] | tuple[float, float, float, float, float]] | str
    )
    """[rad/s, deg, N/m^2, N/m^2, N m/m^2] Rows [omega, beta_deg, D_X, D_Y, D_N] (omega left
    out: the same at every frequency), or a CSV file's path (relative to the case)."""
    symmetric: bool = False
    """The table covers 0 to 180 deg; the other side mirrors it (D_X even, D_Y and D_N odd)."""


# ---- a hull's loads in current ---------------------------------------------------------------
class HullDerivatives(_Model):
    """Clarke's linear derivatives (non-dimensional, prime: Y_v per 1/2 rho L^2 U, Y_r and N_v
    per 1/2 rho L^3 U, N_r per 1/2 rho L^4 U) replacing the values Clarke, Gedling and Hine's
    regression gives for the hull's L, B, T and C_B; any of them."""

    Y_v: float | None = None
    """[-] Y'_v, the sway force per sway velocity. Omitted: the regression's."""
    Y_r: float | None = None
    """[-] Y'_r, the sway force per yaw rate. Omitted: the regression's."""
    N_v: float | None = None
    """[-] N'_v, the yaw moment per sway velocity. Omitted: the regression's."""
    N_r: float | None = None
    """[-] N'_r, the yaw moment per yaw rate. Omitted: the regression's."""


class _HullCurrent(_Model):
    """A ship hull's forces in the horizontal plane from the water flowing past it, at any
    drift angle, with yaw-rate terms (forces.hull_current): on the velocity relative to the
    water at ``point`` (midship), the loads acting there."""

    point: Vector = (0.0, 0.0, 0.0)
    """[m] Midship in the body frame: where the velocity is taken and the loads act."""
    length: Pos
    """[m] Length L between perpendiculars."""
    beam: Pos
    """[m] Beam B of the hull."""
    draught: Pos
    """[m] Draught T of the hull."""
    block_coefficient: Annotated[float, Field(gt=0.0, le=1.0)]
    """[-] Block coefficient C_B of the hull."""
    wetted_area: Pos | None = None
    """[m^2] Wetted area S of the friction. Omitted: Denny-Mumford's 1.7 L T + C_B L B."""
    cross_flow_drag: Pos
    """[-] Drag coefficient C_Y in beam flow, on L T (0.6 to 1.1 for tankers; more in shallow
    water)."""
    cross_flow_centre: float = 0.0
    """[m] x_Y, where the beam flow's force acts, forward of ``point``."""
    form_factor: NonNeg = 0.25
    """[-] Form factor k of the friction (1 + k) C_F."""
    kinematic_viscosity: Pos = 1.19e-6
    """[m^2/s] Kinematic viscosity nu of the water (the default: sea water at 15 C)."""
    derivatives: HullDerivatives | None = None
    """Clarke's linear derivatives to use instead of the regression's."""


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


# ---- the tandem compensator ----------------------------------------------------------------
class Compensator(_Model):
    """The tandem compensator (forces.compensator): the surge force and yaw moment, by feedback
    linearisation, that hold the horizontal distance from this body's ``point`` (its hawser's
    fairlead) to the ``target`` point (``body.point``, the FPSO's stern) at ``distance`` and
    the ship's heading at ``heading_deg`` from the target body's heading (``relative``) or from
    the bearing of the target point (``line of sight``), each error then obeying
    e'' + 2 z w e' + w^2 e = 0; the force and moment limited to the ship's thrust."""

    model: Literal["compensator"]
    point: str
    """This body's point the distance is measured from, by name (``origin``: reference point)."""
    target: str
    """The other body's point to hold the distance to: ``body`` or ``body.point``."""
    distance: Pos
    """[m] Horizontal distance d* to hold between ``point`` and ``target``."""
    heading: Literal["relative", "line of sight"] = "relative"
    """What ``heading_deg`` is measured from: the target body's heading, or the target's bearing."""
    heading_deg: float = 0.0
    """[deg] Heading h* to hold from that reference, counter-clockwise seen from above."""
    frequency: Pos = 0.02
    """[rad/s] Natural frequency w1 of the distance error's law."""
    heading_frequency: Pos = 0.02
    """[rad/s] Natural frequency w2 of the heading error's law."""
    damping_ratio: Pos = 1.0
    """[-] Damping ratio z of both laws."""
    max_ahead: Pos | None = None
    """[N] Largest surge force ahead. Omitted: unlimited."""
    max_astern: Pos | None = None
    """[N] Largest surge force astern, given positive. Omitted: unlimited."""
    max_yaw_moment: Pos | None = None
    """[N m] Largest yaw moment, either way. Omitted: unlimited."""
    enabled: bool = True
    """False: no force or moment, the ship uncontrolled (the same case, for comparison)."""
