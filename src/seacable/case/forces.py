"""The force models of a system's bodies (their ``external forces``): one schema class per
``model:`` (frozen, validated pydantic models; units in every field), and their union
``ForceModel``, which takes the ship-manoeuvring models (thrusters, rudders, wind, current and
wave drift loads, hull loads in current, the compensator) from ``case.ship_forces``.
``case.bodies`` holds the bodies that carry them.

Conventions (docs/conventions.md): SI units, the earth frame z up with z = 0 at the still-water
surface, angles in degrees in the case file (keys end in ``_deg``); a body's points are in its
body frame, relative to its reference point.
"""

from typing import Annotated, Literal

from pydantic import Field, model_validator

from seacable.case.base import ORIGIN, Constant, NonNeg, PerAxis, Pos, TimeFunction, Vector, _Model
from seacable.case.ship_forces import (
    Compensator,
    CrossFlow,
    CurrentLoad,
    Fin,
    Propeller,
    Rudder,
    ShortWing,
    Thruster,
    WaveDrift,
    WindLoad,
)

Matrix6 = tuple[
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
    tuple[float, float, float, float, float, float],
]
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
    drag_coefficient: NonNeg
    """[-] Drag coefficient Cd, the same on every axis."""
    area: PerAxis
    """[m^2] Projected area A_k facing each body axis x, y, z, or one value for all three."""


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
    end_a: Vector
    """[m] End A of the rod's axis, in the body frame."""
    end_b: Vector
    """[m] End B of the rod's axis, in the body frame."""
    diameter: Pos
    """[m] Diameter d of the cylinder."""
    segments: Annotated[int, Field(ge=1, le=1000)] = 10
    """[-] Number of equal segments the rod is cut into for its loads."""
    drag_coefficient: NonNeg = 0.0
    """[-] Normal drag coefficient Cd, on the diameter."""
    added_mass_coefficient: NonNeg = 0.0
    """[-] Normal added-mass coefficient Ca, of the displaced volume."""
    end_drag_coefficient: NonNeg = 0.0
    """[-] Axial drag coefficient CdEnd of each wetted end, on the section's area."""
    end_added_mass_coefficient: NonNeg = 0.0
    """[-] Axial added-mass coefficient CaEnd of each wetted end, of pi d^3 / 12."""

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
    """The body's point the force acts at, by name (``origin``: the reference point)."""
    frame: Literal["earth", "body"] = "earth"
    """Frame of the force's and moment's components: the earth's, or the body's (turning)."""
    force_x: TimeFunction = Constant(value=0.0)
    """[N] Force along the frame's x axis."""
    force_y: TimeFunction = Constant(value=0.0)
    """[N] Force along the frame's y axis."""
    force_z: TimeFunction = Constant(value=0.0)
    """[N] Force along the frame's z axis (earth frame: positive up)."""
    moment_x: TimeFunction = Constant(value=0.0)
    """[N m] Moment about the frame's x axis, beside the force's own moment."""
    moment_y: TimeFunction = Constant(value=0.0)
    """[N m] Moment about the frame's y axis, beside the force's own moment."""
    moment_z: TimeFunction = Constant(value=0.0)
    """[N m] Moment about the frame's z axis, beside the force's own moment."""


class _MatrixOrDiagonal(_Model):
    """A 6x6 ``matrix`` or its ``diagonal``, exactly one of them."""

    @model_validator(mode="after")
    def _one_form(self):
        if (self.matrix is None) == (self.diagonal is None):
            raise ValueError("give exactly one of 'matrix' (6x6) or 'diagonal' (6 values)")
        return self


class LinearStiffness(_MatrixOrDiagonal):
    """F = -K d: d the body's displacement from its equilibrium pose (x, y, z [m] of the
    reference point from ``equilibrium_position``, then roll, pitch, yaw [rad] as the small
    rotation vector from ``equilibrium_orientation_deg``), K [N/m, N/rad, N m/m, N m/rad] in
    the earth frame at the reference point: a hydrostatic stiffness, a mooring's linearisation,
    elastic ties to the earth. ``matrix`` 6x6, or ``diagonal`` (6 values)."""

    model: Literal["linear_stiffness"]
    matrix: Matrix6 | None = None
    """[N/m, N/rad; N m/m, N m/rad] Stiffness K, 6x6, rows the force then the moment."""
    diagonal: tuple[float, float, float, float, float, float] | None = None
    """[N/m, N/m, N/m, N m/rad, N m/rad, N m/rad] The diagonal of K, the rest zero."""
    equilibrium_position: Vector | None = None
    """[m] Reference point's position where the force vanishes. Omitted: the body's position."""
    equilibrium_orientation_deg: Vector | None = None
    """[deg] Roll, pitch, yaw where the moment vanishes. Omitted: the body's orientation_deg."""


class LinearDamping(_MatrixOrDiagonal):
    """F = -B nu, B [N s/m, N s, N m s/m, N m s/rad] 6x6 or ``diagonal``. ``frame: earth``: nu
    the reference point's velocity [m/s] and the angular velocity [rad/s] in the earth frame.
    ``frame: body`` (a vessel's viscous damping): nu the velocity relative to the current and
    the angular velocity in the body frame, B in the body frame at ``point`` (body frame, by
    default the reference point; moved to it), the force turned into the earth frame."""

    model: Literal["linear_damping"]
    matrix: Matrix6 | None = None
    """[N s/m, N s; N m s/m, N m s/rad] Damping B, 6x6, rows the force then the moment."""
    diagonal: tuple[NonNeg, NonNeg, NonNeg, NonNeg, NonNeg, NonNeg] | None = None
    """[N s/m, N s/m, N s/m, N m s/rad, N m s/rad, N m s/rad] The diagonal of B, the rest zero."""
    frame: Literal["earth", "body"] = "earth"
    """earth: on the velocity over ground; body: on the body-frame velocity through the current."""
    point: Vector | None = None
    """[m] Body-frame point where B is given (frame: body). Omitted: the reference point."""

    @model_validator(mode="after")
    def _point_in_body_frame(self):
        if self.point is not None and self.frame == "earth":
            raise ValueError("'point' is for frame: body (the matrix is then at that point)")
        return self


class QuadraticDamping(_MatrixOrDiagonal):
    """A vessel's quadratic viscous damping: F = -B (|nu| nu), |nu_j| nu_j component by
    component, nu the body-frame velocity relative to the current and angular velocity (as
    ``linear_damping`` with ``frame: body``); B [N s^2/m^2, N s^2/rad^2, N m s^2/m^2,
    N m s^2/rad^2] at ``point`` (body frame, default the reference point)."""

    model: Literal["quadratic_damping"]
    matrix: Matrix6 | None = None
    """[N s^2/m^2, N s^2/rad^2; N m s^2/m^2, N m s^2/rad^2] B, 6x6, rows the force, the moment."""
    diagonal: tuple[NonNeg, NonNeg, NonNeg, NonNeg, NonNeg, NonNeg] | None = None
    """[N s^2/m^2 (3), N m s^2/rad^2 (3)] The diagonal of B, the rest zero."""
    point: Vector | None = None
    """[m] Body-frame point where B is given. Omitted: the reference point."""


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
    """The point the body is brought to: ``body`` (its reference point) or ``body.point``."""
    gain: Annotated[float, Field(gt=0, le=2)] = 1.0
    """[-] a, the share of the position error dE corrected per servo step."""
    rate_gain: Annotated[float, Field(ge=0, lt=1)] = 0.0
    """[-] b, the weight of the error's rate dE' (times dt) in each correction."""
    step: Pos | None = None
    """[s] Servo step dt. Omitted: the simulation's time_step (else 0.01 s or output_interval)."""
    sphere_radius: Pos = 1.0
    """[m] Radius of the sphere of held positions around the target that K is fitted on."""
    recompute_interval: Pos | None = None
    """[s] Interval at which K is recomputed about the current target. Omitted: never."""


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
    """Where the mesh is clipped: at the incident waves' elevation, or at z = 0."""


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
    memory: Pos = 25.0
    """[s] Length Tc of the velocity history the memory force integrates over."""
    memory_step: Pos = 0.05
    """[s] Step at which the kernel K(t) is sampled over ``memory``."""
    method: Literal["convolution", "state_space"] = "convolution"
    """How the memory force is computed: on the recorded history, or by fitted state spaces."""
    order: Annotated[int, Field(ge=2, le=40)] = 12
    """[-] Most first-order states of each entry's fit (method: state_space)."""
    tolerance: Annotated[float, Field(gt=0, lt=1)] = 0.01
    """[-] Largest relative L2 error of each entry's fit (method: state_space)."""
    high_frequency_tail: Literal["power", "none"] = "power"
    """B(w) beyond the database's last frequency w_N: B(w_N) (w_N / w)^p, or zero."""
    tail_power: Annotated[int, Field(ge=2, le=4)] = 3
    """[-] Exponent p of the tail B(w_N) (w_N / w)^p."""

    @model_validator(mode="after")
    def _samples(self):
        if self.memory < 2.0 * self.memory_step:
            raise ValueError(
                f"memory {self.memory:g} s holds less than two samples of memory_step "
                f"{self.memory_step:g} s: the memory force would be none; lengthen memory (25 s "
                "is usual) or shorten memory_step"
            )
        return self


class Diffraction(_Model):
    """The ship-simulator document's diffraction force: the body's ``hydrodynamics``
    database's wave excitation for each incident wave component, interpolated in frequency and
    in the wave's direction relative to the body's heading, at the body's place.
    ``froude_krylov: true`` adds the database's linear Froude-Krylov force (the whole linear
    excitation; leave it out with ``non-linear Froude-Krylov``)."""

    model: Literal["diffraction"]
    froude_krylov: bool = False
    """Adds the database's linear Froude-Krylov force (not with ``non-linear Froude-Krylov``)."""


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
    | Propeller
    | Fin
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
