"""The parts of the case-file schema every case form shares: numbers and points, time functions,
body shapes and the simulation settings (frozen, validated pydantic models; units in every
field); the environment is in ``case.environment``. ``case.schema`` (one cable with its ends)
and ``case.system`` (bodies and lines) build on them.

Conventions (see docs/conventions.md): SI units, z up with z = 0 at the still-water surface,
angles in the case file in degrees (keys end in ``_deg``), radians everywhere inside.
"""

import csv
import io
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

BOOLEAN_ERROR = "boolean_not_number"  # the error type of a true/false where a number is due
MAGNITUDE_ERROR = "number_too_large"  # the error type of a number beyond LARGEST_NUMBER
# no quantity of a marine system is this large in SI units (the heaviest ship, 6e8 kg; its yaw
# inertia, 1e13 kg m^2): a larger number is a slip (a unit, an exponent), and would overflow
LARGEST_NUMBER = 1e15
Pos = Annotated[float, Field(gt=0)]
NonNeg = Annotated[float, Field(ge=0)]
Point = tuple[float, float] | tuple[float, float, float]  # [x, z] (y = 0) or [x, y, z], m
PerAxis = NonNeg | tuple[NonNeg, NonNeg, NonNeg]  # one value, or one per global axis x, y, z


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

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

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


class Turn(_Model):
    """A turning circle: from ``start_time`` [s] the ship follows a circle of ``radius`` [m]
    turning to the ``side`` given (left: towards +y when heading along +x)."""

    start_time: NonNeg
    radius: Pos
    side: Literal["left", "right"] = "left"


LARGEST_TABLE = 50_000_000  # bytes of a table file


class Table(_Model):
    """Values from a CSV file with two columns (time [s], value), interpolated linearly or by a
    clamped cubic spline; held constant outside the table. ``file`` is relative to the case.
    With ``column``, the file's first line names its columns (time first) and the values are
    that column's: one table of a vessel's six motions (time, x, y, z, roll_deg, pitch_deg,
    yaw_deg) moves an imposed body through six channels that name their column."""

    kind: Literal["table"]
    file: str
    interpolation: Literal["linear", "cubic"] = "linear"
    column: str | None = None  # the value's column, by the name in the first line

    def path(self, base_dir=None) -> Path:
        path = Path(self.file)
        if base_dir is not None and not path.is_absolute():
            path = Path(base_dir) / path
        return path

    def text(self, base_dir=None) -> str:
        """The file's text, or a ValueError line: missing, a directory, more than
        LARGEST_TABLE bytes (a device such as /dev/zero is read no further), not UTF-8."""
        path = self.path(base_dir)
        if not path.exists():
            raise ValueError(f"table file '{path}' does not exist")
        if path.is_dir():
            raise ValueError(f"table file '{path}' is a directory")
        with path.open("rb") as f:
            raw = f.read(LARGEST_TABLE + 1)
        if len(raw) > LARGEST_TABLE:
            raise ValueError(f"table file '{path}' is larger than {LARGEST_TABLE:,} bytes")
        try:
            return raw.decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            raise ValueError(
                f"table file '{path}' is not UTF-8 text (byte {raw[exc.start]:#04x} at position "
                f"{exc.start}); save it as UTF-8 CSV"
            ) from None

    def load(self, base_dir=None):
        path = self.path(base_dir)
        rows = []
        at, header = 1, self.column is not None  # the value's column; a header to read
        for row in csv.reader(io.StringIO(self.text(base_dir))):
            if not row or row[0].strip().startswith("#"):
                continue
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

    speed: float | None = None  # [m/s]
    distance: TimeFunction | None = None  # [m]
    turn: Turn | None = None

    @model_validator(mode="after")
    def _one_law(self):
        if (self.speed is None) == (self.distance is None):
            raise ValueError("give exactly one of 'speed' [m/s] or 'distance' [m, time function]")
        return self


# ---- shapes: bodies and the free surface ---------------------------------------------------------
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


class HydroDatabase(_Model):
    """A hull's hydrodynamic database (``file`` relative to the case): Capytaine's NetCDF (as
    ``seacable hydrodb`` writes it), WAMIT's ``.1`` (``.3``, ``.hst`` beside it; dimensional
    with the environment's water density and gravity and WAMIT's ULEN ``length_scale`` [m]) or
    an HDB file (Diodore, AQUA+; its phases in ``phase_unit``). Its frame is the body frame
    moved by ``position`` (its origin in the body frame [m]); its matrices and forces are moved
    from its reference point (Capytaine's rotation centre, WAMIT's body origin, the HDB's
    unstated point: its origin) to the body's reference point (seacable.hydrodb)."""

    file: str
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)  # [m], body frame
    length_scale: Pos = 1.0  # [m] WAMIT's ULEN, for a WAMIT database
    phase_unit: Literal["rad", "deg"] = "rad"  # an HDB file's phases

    def path(self, base_dir=None) -> Path:
        path = Path(self.file)
        if base_dir is not None and not path.is_absolute():
            path = Path(base_dir) / path
        return path


class HullMesh(_Model):
    """A body's hull as a triangle mesh file (``file`` relative to the case): STL (ASCII or
    binary), Wavefront OBJ or WAMIT GDF (``format``, by default from the suffix). The mesh's
    coordinates [m] times ``scale`` are placed in the body frame at ``position`` (the mesh's
    origin) turned by ``orientation_deg`` (roll, pitch, yaw); ``axes: z_down`` reads a mesh
    written in a body frame with z down and y to starboard (the ship-simulator document's and
    NED's), turning it half a turn about x: (x, y, z) -> (x, -y, -z). Its winding is made
    consistent and outward; a mesh not closed below the waterline at the body's start is
    refused."""

    file: str
    format: Literal["stl", "obj", "gdf"] | None = None
    scale: Pos = 1.0
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)  # [m], body frame
    orientation_deg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    axes: Literal["z_up", "z_down"] = "z_up"

    def path(self, base_dir=None) -> Path:
        path = Path(self.file)
        if base_dir is not None and not path.is_absolute():
            path = Path(base_dir) / path
        return path


# ---- simulation ----------------------------------------------------------------------------------
FIXED_STEP_INTEGRATORS = ("rk4", "implicit_euler", "theta", "newmark", "generalized_alpha")
MOST_ROWS = 1e8  # output rows of one run: a hundred million rows of a single number is 800 MB
MOST_STEPS = 1e10  # fixed steps of one run: at a microsecond a step, about three hours


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
    # state's scale (system.model.state_scale: angles 1 rad, coordinates the cable's length
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
    # rk4 at a time_step beyond its stability limit about the start state (the eigenvalues of
    # the linearised system, numerics.stability) is refused, naming the limit; true runs it
    # anyway, with a warning (to show an instability, or when the start is not representative)
    allow_unstable_step: bool = False

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
