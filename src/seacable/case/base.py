"""The parts of the case-file schema every case form shares: numbers and points, time functions,
body shapes and the simulation settings (frozen, validated pydantic models; units in every
field); the environment is in ``case.environment``. ``case.schema`` (one cable with its ends)
and ``case.system`` (bodies and lines) build on them.

Conventions (see docs/conventions.md): SI units, z up with z = 0 at the still-water surface,
angles in the case file in degrees (keys end in ``_deg``), radians everywhere inside.
"""

import math
import typing
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    field_validator,
    model_validator,
)
from pydantic_core import PydanticCustomError

from seacable import files

BOOLEAN_ERROR = "boolean_not_number"  # the error type of a true/false where a number is due
MAGNITUDE_ERROR = "number_too_large"  # the error type of a number beyond LARGEST_NUMBER
# no quantity of a marine system is this large in SI units (the heaviest ship, 6e8 kg; its yaw
# inertia, 1e13 kg m^2): a larger number is a slip (a unit, an exponent), and would overflow
LARGEST_NUMBER = 1e15
Pos = Annotated[float, Field(gt=0)]
NonNeg = Annotated[float, Field(ge=0)]
Point = tuple[float, float] | tuple[float, float, float]  # [x, z] (y = 0) or [x, y, z], m
PerAxis = NonNeg | tuple[NonNeg, NonNeg, NonNeg]  # one value, or one per global axis x, y, z
Vector = tuple[float, float, float]
ORIGIN = "origin"  # the point every body has: its reference point


def instances(value, kind: type, where: str = ""):
    """(path, part) of every part of a case (a model, or lists of them) that is a ``kind``,
    in order, the path as the case file writes it (``bodies[1].external forces[0].force_x``)."""
    if isinstance(value, kind):
        yield where, value
    elif isinstance(value, BaseModel):
        for name, field in type(value).model_fields.items():
            key = field.alias or name
            yield from instances(getattr(value, name), kind, f"{where}.{key}" if where else key)
    elif isinstance(value, list | tuple):
        for k, item in enumerate(value):
            yield from instances(item, kind, f"{where}[{k}]")


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
    """Every part of a case: unknown keys refused, frozen; NaN and infinities refused in every
    number, and numbers beyond LARGEST_NUMBER; true/false (yes/no, on/off in YAML) refused
    where a number or a name is expected (pydantic would read true as 1)."""

    model_config = ConfigDict(
        extra="forbid", frozen=True, allow_inf_nan=False, use_attribute_docstrings=True
    )

    @model_validator(mode="before")
    @classmethod
    def _booleans_are_not_numbers(cls, data):
        if not isinstance(data, dict):
            return data
        for name, field in cls.model_fields.items():
            for key in {name, field.alias} - {None}:
                if key in data and _holds_bool(data[key]) and not _admits_bool(field.annotation):
                    raise PydanticCustomError(
                        BOOLEAN_ERROR,
                        "true/false (or yes/no, on/off) is not a number or a name here; write "
                        "a number, or quote the word",
                        {"key": key, "value": data[key]},
                    )
                if key in data and _largest(data[key]) > LARGEST_NUMBER:
                    raise PydanticCustomError(
                        MAGNITUDE_ERROR,
                        f"a number beyond {LARGEST_NUMBER:.0e} is larger than any quantity of a "
                        "marine system in SI units; check its unit and exponent",
                        {"key": key, "value": data[key]},
                    )
        return data


def _largest(value) -> float:
    """The largest magnitude of the numbers in ``value`` (lists included; 0 for none)."""
    if isinstance(value, bool):
        return 0.0
    if isinstance(value, int | float):
        return abs(float(value)) if math.isfinite(value) else 0.0  # NaN, inf: pydantic's
    if isinstance(value, list | tuple):
        return max((_largest(v) for v in value), default=0.0)
    return 0.0


def _holds_bool(value) -> bool:
    """A boolean, or a list of values that holds one (mappings are checked by their model)."""
    if isinstance(value, bool):
        return True
    return isinstance(value, list | tuple) and any(_holds_bool(v) for v in value)


def _admits_bool(annotation) -> bool:
    """Whether a field's type takes a boolean somewhere (bool, Any, or a union holding one)."""
    if annotation is bool or annotation is Any:
        return True
    return any(_admits_bool(arg) for arg in typing.get_args(annotation) if arg is not None)


# ---- time functions ------------------------------------------------------------------------------
class Constant(_Model):
    """f(t) = value."""

    kind: Literal["constant"] = "constant"
    value: float
    """[key's unit] The function's value at every time."""


class Sine(_Model):
    """f(t) = offset + amplitude sin(omega t + phase); give exactly one of period [s] or
    angular_frequency [rad/s]; phase [rad]."""

    kind: Literal["sine"]
    amplitude: float
    """[key's unit] Amplitude of the oscillation about ``offset``."""
    period: Pos | None = None
    """[s] Period of the oscillation, 2 pi / angular_frequency."""
    angular_frequency: Pos | None = None
    """[rad/s] Angular frequency omega of the oscillation."""
    phase: float = 0.0
    """[rad] Phase of the sine at t = 0."""
    offset: float = 0.0
    """[key's unit] Mean value the function oscillates about."""

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
    """[s] Time the ramp starts from ``start_value``."""
    end_time: float
    """[s] Time the ramp reaches ``end_value``."""
    start_value: float = 0.0
    """[key's unit] Value up to ``start_time``."""
    end_value: float
    """[key's unit] Value from ``end_time`` on."""

    @model_validator(mode="after")
    def _ordered(self):
        if not self.end_time > self.start_time:
            raise ValueError(
                f"end_time ({self.end_time} s) must be later than start_time ({self.start_time} s)"
            )
        return self


class AccelerationPhase(_Model):
    """One phase of an acceleration profile: a constant acceleration for a duration."""

    duration: Pos
    """[s] Length of the phase; the next phase starts when it ends."""
    acceleration: float
    """[m/s^2] Constant acceleration over the phase (for another quantity, its unit per s^2)."""


class AccelerationProfile(_Model):
    """A motion built from phases of constant acceleration; gives position, velocity and
    acceleration exactly. After the last phase the acceleration is zero."""

    kind: Literal["acceleration_profile"]
    initial_position: float = 0.0
    """[m] Value at ``start_time`` (for another quantity, in its unit)."""
    initial_velocity: float = 0.0
    """[m/s] Rate of change at ``start_time``, held before it (for another quantity, its unit/s)."""
    start_time: float = 0.0
    """[s] Time the first phase starts."""
    phases: list[AccelerationPhase] = Field(min_length=1)
    """The phases of constant acceleration, one after the other from ``start_time``."""


class Turn(_Model):
    """A turning circle: from ``start_time`` [s] the ship follows a circle of ``radius`` [m]
    turning to the ``side`` given (left: towards +y when heading along +x)."""

    start_time: NonNeg
    """[s] Time the ship leaves its straight track and starts to turn."""
    radius: Pos
    """[m] Radius of the turning circle, tangent to the straight track."""
    side: Literal["left", "right"] = "left"
    """Side the ship turns to: left turns towards +y when heading along +x."""


LARGEST_TABLE = 50_000_000  # bytes of a table file


class Table(_Model):
    """Values from a CSV file with two columns (time [s], value), interpolated linearly or by a
    clamped cubic spline; held constant outside the table.
    With ``column``, the file's first line names its columns (time first) and the values are
    that column's: one table of a vessel's six motions (time, x, y, z, roll_deg, pitch_deg,
    yaw_deg) moves an imposed body through six channels that name their column."""

    kind: Literal["table"]
    file: str
    """Path of the CSV file, relative to the case file's directory (or absolute)."""
    interpolation: Literal["linear", "cubic"] = "linear"
    """Interpolation between rows: linear, or a clamped cubic spline (zero slope at both ends)."""
    column: str | None = None
    """Name of the value's column in the file's first line. Omitted: the second column."""

    def path(self, base_dir=None) -> Path:
        path = Path(self.file)
        if base_dir is not None and not path.is_absolute():
            path = Path(base_dir) / path
        return path

    def text(self, base_dir=None) -> str:
        """The file's text, or a ValueError line: missing, a directory, more than
        LARGEST_TABLE bytes (a device such as /dev/zero is read no further), not UTF-8."""
        return files.read_text(self.path(base_dir), "table file", LARGEST_TABLE, ValueError,
                               fix="save it as UTF-8 CSV")  # fmt: skip

    def load(self, base_dir=None):
        path = self.path(base_dir)
        rows = []
        at, header = 1, self.column is not None  # the value's column; a header to read
        for _, row in files.csv_rows(self.text(base_dir), f"table file '{path}'", ValueError):
            if header:
                header = False
                names = [name.strip() for name in row]
                if self.column not in names[1:]:
                    raise ValueError(f"table file '{path}' has no column '{self.column}' in its "
                                     f"first line; its columns: {', '.join(names)}")  # fmt: skip
                at = names.index(self.column)
                continue
            try:
                rows.append((float(row[0]), float(row[at])))
            except (ValueError, IndexError):
                if rows:  # a header is allowed only on the first line
                    raise ValueError(f"table file '{path}': bad row {row!r}") from None
        data = np.array(rows, dtype=float)
        if not np.all(np.isfinite(data)):
            raise ValueError(f"table file '{path}': NaN or infinite values")
        if data.size and np.abs(data).max() > LARGEST_NUMBER:
            raise ValueError(
                f"table file '{path}': a value beyond {LARGEST_NUMBER:.0e} "
                f"({np.abs(data).max():.3g}); check its unit and exponent"
            )
        if data.shape[0] < 2 or not np.all(np.diff(data[:, 0]) > 0):
            raise ValueError(
                f"table file '{path}' needs at least 2 rows with strictly increasing times"
            )
        return data[:, 0], data[:, 1]


def _number_is_constant(value: Any) -> Any:
    """Allow a plain number where a time function is expected."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return {"kind": "constant", "value": value}
    return value


TimeFunction = Annotated[
    Constant | Sine | Ramp | AccelerationProfile | Table,
    Field(discriminator="kind"),
    BeforeValidator(_number_is_constant),
]


class ShipTravel(_Model):
    """How far a towing ship has gone along its track: a constant ``speed`` [m/s] or the
    ``distance`` [m] as a time function (an acceleration_profile gives speed changes with
    exact accelerations), exactly one; then optionally a turning circle (``turn``)."""

    speed: float | None = None
    """[m/s] Constant speed of the ship along its track."""
    distance: TimeFunction | None = None
    """[m] Distance travelled along the track as a function of time."""
    turn: Turn | None = None
    """Turning circle the ship follows from ``turn.start_time``. Omitted: a straight track."""

    @model_validator(mode="after")
    def _one_law(self):
        if (self.speed is None) == (self.distance is None):
            raise ValueError("give exactly one of 'speed' [m/s] or 'distance' [m, time function]")
        return self


# ---- shapes: bodies and the free surface ---------------------------------------------------------
class Sphere(_Model):
    """A sphere of ``radius`` [m] centred on the body's position."""

    kind: Literal["sphere"]
    radius: Pos
    """[m] Radius of the sphere; its centre is the body's position."""

    def volume(self) -> float:
        return 4.0 / 3.0 * math.pi * self.radius**3


class VerticalCylinder(_Model):
    """A vertical cylinder of ``radius`` and ``height`` [m] centred on the body's position."""

    kind: Literal["vertical_cylinder"]
    radius: Pos
    """[m] Radius of the cylinder."""
    height: Pos
    """[m] Height of the cylinder, half above and half below the body's position."""

    def volume(self) -> float:
        return math.pi * self.radius**2 * self.height


class VolumeTable(_Model):
    """Any hull: its submerged volume tabulated against the elevation of the body's position,
    linearly interpolated."""

    kind: Literal["table"]
    submerged_volume: list[tuple[float, NonNeg]] = Field(min_length=2)
    """[m, m^3] Pairs [z of the body's position, submerged volume], z ascending, from the whole
    volume (the first z and below) down to 0 (clear of the water, the last z and above)."""

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


class HydroDatabase(_Model):
    """A hull's hydrodynamic database (``file`` relative to the case): Capytaine's NetCDF (as
    ``seacable hydrodb`` writes it), WAMIT's ``.1`` (``.3``, ``.hst`` beside it; dimensional
    with the environment's water density and gravity and WAMIT's ULEN ``length_scale`` [m]) or
    an HDB file (Diodore, AQUA+; its phases in ``phase_unit``). Its frame is the body frame
    moved by ``position``; its matrices and forces are moved
    from its reference point (Capytaine's rotation centre, WAMIT's body origin, the HDB's
    unstated point: its origin) to the body's reference point (seacable.hydrodb)."""

    file: str
    """Path of the database file, relative to the case file's directory (or absolute)."""
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """[m] Origin of the database's frame in the body frame (its axes are the body's)."""
    length_scale: Pos = 1.0
    """[m] WAMIT's ULEN, that makes a WAMIT database dimensional; ignored for other formats."""
    phase_unit: Literal["rad", "deg"] = "rad"
    """Unit of the phases in an HDB file; ignored for other formats."""

    def path(self, base_dir=None) -> Path:
        path = Path(self.file)
        if base_dir is not None and not path.is_absolute():
            path = Path(base_dir) / path
        return path


class HullMesh(_Model):
    """A body's hull as a triangle mesh file (STL, ASCII or binary; OBJ; GDF) placed in the body
    frame: its coordinates times ``scale``, turned half a turn about x for ``axes: z_down`` (the
    ship-simulator document's and NED's frame), then by ``orientation_deg``, its origin moved to
    ``position``. Its winding is made consistent and outward; a mesh not closed below the
    waterline at the body's start is refused."""

    file: str
    """Path of the mesh file, relative to the case file's directory (or absolute)."""
    format: Literal["stl", "obj", "gdf"] | None = None
    """File format: STL, Wavefront OBJ or WAMIT GDF. Omitted: from the file's suffix."""
    scale: Pos = 1.0
    """[-] Factor the mesh's coordinates are multiplied by to give metres."""
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """[m] Position of the mesh's origin in the body frame."""
    orientation_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """[deg] Roll, pitch, yaw turning the mesh in the body frame (Rz Ry Rx, as a body's)."""
    axes: Literal["z_up", "z_down"] = "z_up"
    """Mesh frame: z_up as seacable's; z_down (z down, y to starboard) is turned (x, -y, -z)."""

    def path(self, base_dir=None) -> Path:
        path = Path(self.file)
        if base_dir is not None and not path.is_absolute():
            path = Path(base_dir) / path
        return path


# ---- simulation ----------------------------------------------------------------------------------
IMPLICIT_INTEGRATORS = ("implicit_euler", "theta", "newmark", "generalized_alpha")
FIXED_STEP_INTEGRATORS = ("rk4", *IMPLICIT_INTEGRATORS)
MOST_ROWS = 1e8  # output rows of one run: a hundred million rows of a single number is 800 MB
MOST_STEPS = 1e10  # fixed steps of one run: at a microsecond a step, about three hours


class Simulation(_Model):
    """How long a run lasts, how often it writes its results and how it integrates in time."""

    duration: Pos
    """[s] Simulated time, from t = 0; a whole number of output intervals."""
    output_interval: Pos
    """[s] Time between two rows of the results."""
    integrator: Literal[
        "rk4", "dopri5", "implicit_euler", "theta", "newmark", "generalized_alpha",
        "bdf", "radau", "lsoda", "cvode",
    ] = "rk4"  # fmt: skip
    """Time integrator: rk4 (fixed step) and dopri5 (adaptive) explicit; implicit_euler, theta,
    newmark, generalized_alpha implicit, fixed step; bdf, radau, lsoda (SciPy) and cvode
    (SUNDIALS) adaptive, for stiff systems."""
    time_step: Pos | None = None
    """[s] Fixed step of rk4 and the implicit schemes; it must divide ``output_interval``, or,
    for an implicit scheme, be a whole number of output intervals (the outputs inside a step
    are interpolated from its two ends: cubic in positions, their derivative the velocities).
    Omitted: the longest step of at most 0.01 s that divides it."""
    theta: float = Field(0.5, ge=0.5, le=1.0)
    """[-] Weight of the theta method: 1/2 the trapezoidal rule, 1 implicit Euler."""
    newmark_gamma: float = Field(0.5, ge=0.5, le=1.0)
    """[-] Newmark's gamma: 1/2 adds no numerical damping, more damps the high frequencies."""
    newmark_beta: float = Field(0.25, gt=0.0, le=0.5)
    """[-] Newmark's beta; at least (gamma + 1/2)^2 / 4, 1/4 with gamma 1/2 the average
    acceleration rule."""
    spectral_radius: float = Field(0.5, ge=0.0, le=1.0)
    """[-] Generalized-alpha's rho_infinity: the share of the highest frequencies that survives
    a step (1: no damping, 0: damped in one step)."""
    # 0.5 damps axial ringing enough that a slack segment snapping taut does not feed energy back
    # (a rising body on a line of EA 1e8 N at 5 ms steps: with 0.8 or Newmark's 1 the energy
    # grew 25 to 30 times; with 0.5 or less it decays, as in rk4)
    newton_tolerance: Pos = 1e-9
    """[-] Newton's stop in an implicit step: every node's last correction below this fraction of
    the shortest segment."""
    max_newton_iterations: int = Field(10, ge=1, le=100)
    """[-] Most Newton iterations of one implicit step; the run stops with an error beyond."""
    rtol: float = Field(1e-6, gt=0.0, le=1e-2)
    """[-] Relative tolerance of the adaptive integrators (at most 0.01: looser, a run can end
    far from the motion it integrates)."""
    atol: Pos | None = None
    """[state's unit] Absolute tolerance of the adaptive integrators, one value for every state.
    Omitted: rtol alone sets the accuracy, against each state's magnitude and scale."""
    # dopri5 measures each state's error against rtol times the largest magnitude that state has
    # reached (small angles and rates are followed to rtol of their own amplitude), with a floor
    # of 1e-3 rtol times the state's scale (system.model.state_scale: angles 1 rad, coordinates
    # the cable's length L, rates those times sqrt(g / L), forces the cable's weight); bdf,
    # radau, lsoda and cvode take rtol times the larger of the state's start value and that
    # floor. The results' attribute solver_tolerance_governing says which tolerance governed
    max_step: Pos | None = None
    """[s] Longest step of the adaptive integrators. Omitted: ``output_interval``."""
    initial_step: Pos = 1e-3
    """[s] First step the adaptive integrators try."""
    constraint_stabilization_frequency: Pos = 10.0
    """[rad/s] Baumgarte frequency that pulls a pinned end or a joint back onto its constraint."""
    build_up: NonNeg = 0.0
    """[s] Build-up period: imposed motions, applied forces, trajectory targets and waves rise
    smoothly from their value at t = 0 to their own from this time on (0: none). A ship's track
    and the wind are not ramped; one to two periods of the motion is usual."""
    # as OrcaFlex's: f(t) is replaced by f(0) + r(t/T) (f(t) - f(0)), r(s) = s^3 (10 - 15 s
    # + 6 s^2) up to T and 1 after: it starts at rest, with zero acceleration. A towing ship's
    # initial towed shape is already the steady state at its speed
    allow_unstable_step: bool = False
    """Run rk4 at a ``time_step`` beyond its stability limit about the start, with a warning
    (false: such a step is refused, naming the limit)."""
    allow_long_run: bool = False
    """Run a case whose estimated work (its steps times its states) exceeds what runs in about
    an hour (false: such a run is refused before it starts, with the estimate; ``seacable run
    --yes`` sets it)."""

    @field_validator("time_step")
    @classmethod
    def _step_divides_output_interval(cls, time_step, info):
        """A fixed step must divide the output interval (outputs fall on steps): one that does
        within 1 % is rounded to the divisor, another is refused with the two nearest divisors
        (running silently at a step more than 1 % shorter would cost time the user did not ask
        for, and a longer one could not be stable or accurate as they chose). An implicit
        scheme's step may instead span whole output intervals (two or more), within 1 % too."""
        interval = info.data.get("output_interval")
        integrator = info.data.get("integrator")
        if time_step is None or interval is None:
            return time_step
        if integrator not in FIXED_STEP_INTEGRATORS:
            return time_step
        if time_step > 1.5 * interval and integrator in IMPLICIT_INTEGRATORS:
            spans = round(time_step / interval)
            if abs(spans * interval - time_step) <= 0.01 * time_step:
                return time_step
            raise ValueError(
                f"{time_step} s is not a whole number of output intervals ({interval} s): use "
                f"time_step {math.floor(time_step / interval) * interval:.6g} or "
                f"{math.ceil(time_step / interval) * interval:.6g} s (the outputs between a "
                "step's ends are interpolated), or an output_interval that divides time_step"
            )
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
            + (" (an implicit integrator's step may span whole output intervals)"
               if time_step > interval else "")
        )  # fmt: skip

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
        if count > MOST_ROWS:
            raise ValueError(
                f"duration / output_interval = {count:.3g} output rows, more than any run can "
                f"write ({MOST_ROWS:.0e}); lengthen output_interval or shorten duration"
            )
        step = self.time_step if self.integrator in FIXED_STEP_INTEGRATORS else None
        if step is not None and self.duration / step > MOST_STEPS:
            raise ValueError(
                f"duration / time_step = {self.duration / step:.3g} steps, more than a run can "
                f"take in a day on any machine ({MOST_STEPS:.0e}); lengthen time_step (or use "
                "an implicit integrator) or shorten duration"
            )
        if abs(count - round(count)) > 1e-6 * count:
            below = math.floor(count) * self.output_interval
            raise ValueError(
                f"duration ({self.duration} s) is not a whole number of output intervals "
                f"({self.output_interval} s): use duration {below:g} or "
                f"{below + self.output_interval:g}, or another output_interval"
            )
        return self
