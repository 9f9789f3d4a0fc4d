"""The environment of a case (every case form's ``environment:``): gravity, the water, its
current, the wind, the seabed and the waves (frozen, validated pydantic models; units in every
field).

Conventions (docs/conventions.md): SI units, z up with z = 0 at the still-water surface,
directions in degrees from +x towards +y (the direction a current, a wind or a wave goes
towards).
"""

from typing import Annotated, Literal

import numpy as np
from pydantic import Field, model_validator

from seacable.case.base import Constant, NonNeg, Pos, TimeFunction, _Model


class Current(_Model):
    """Current flowing towards ``direction_deg`` (from +x towards +y; 0 = along +x): either a
    uniform ``velocity`` [m/s] or a ``profile`` of [elevation z (m, negative below the surface),
    speed (m/s)] pairs, linearly interpolated and held constant beyond the end points."""

    velocity: float | None = None
    """[m/s] Speed of a current uniform over the depth."""
    profile: list[tuple[float, float]] | None = None
    """[m, m/s] Pairs [elevation z (negative below the surface), speed] of a current that varies
    with depth."""
    direction_deg: float = 0.0
    """[deg] Direction the current flows towards, from +x towards +y."""

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


class Wind(_Model):
    """A uniform wind blowing towards ``direction_deg`` (from +x towards +y, as the current;
    not the meteorological "from"), at ``speed`` [m/s]; both time functions (or constants),
    exempt from the build-up as the current is. It acts through the bodies' ``wind`` force
    models, at ``air_density`` [kg/m^3]."""

    speed: TimeFunction
    """[m/s] Wind speed."""
    direction_deg: TimeFunction = Constant(value=0.0)
    """[deg] Direction the wind blows towards, from +x towards +y."""
    air_density: Pos = 1.225
    """[kg/m^3] Density of the air the wind force models use."""


class Seabed(_Model):
    """Seabed contact of lumped-mass cables: per metre of line, a vertical ``stiffness``
    [N/m per m of line] and ``damping`` [N s/m per m] while a node is below the seabed, and
    Coulomb friction along it (``friction_coefficient``, regularised below ``slip_speed``).
    Over the first ``contact_band`` of depth the stiffness (and the share of the damping that
    acts) rises linearly from zero, so that the push is smooth (C1) in the depth and implicit
    steps converge through touchdown; below the band the push is ``stiffness`` (depth -
    band / 2). 0 gives the plain spring, as MoorDyn's. MoorDyn's kBot [Pa/m] and cBot [Pa s/m]
    act on each segment's d l instead: ``stiffness_per_area`` and ``damping_per_area`` give
    them so (each line type's diameter times them per metre of line), in place of
    ``stiffness`` and ``damping``."""

    stiffness: Pos = 1.0e5
    """[N/m^2] Vertical stiffness while a node is below the seabed, per metre of line."""
    damping: NonNeg = 0.0
    """[N s/m^2] Vertical damping while a node is below the seabed, per metre of line."""
    stiffness_per_area: Pos | None = None
    """[Pa/m] MoorDyn's kBot, per m^2 of d l (diameter times length); replaces ``stiffness``."""
    damping_per_area: NonNeg | None = None
    """[Pa s/m] MoorDyn's cBot, per m^2 of d l (diameter times length); replaces ``damping``."""
    friction_coefficient: NonNeg = 0.0
    """[-] Coulomb friction coefficient of a node sliding along the seabed (0: no friction)."""
    slip_speed: Pos = 0.01
    """[m/s] Regularising speed: the friction is mu N v / sqrt(v^2 + slip_speed^2)."""
    contact_band: NonNeg = 0.005
    """[m] Depth below the seabed over which the stiffness rises from zero (0: a plain spring)."""

    @model_validator(mode="after")
    def _one_form(self):
        for per_length, per_area in (("stiffness", "stiffness_per_area"),
                                     ("damping", "damping_per_area")):  # fmt: skip
            if per_length in self.model_fields_set and getattr(self, per_area) is not None:
                raise ValueError(f"give '{per_length}' [per metre of line] or '{per_area}' "
                                 "[per m^2 of the lines' d l, MoorDyn's], not both")  # fmt: skip
        return self

    def per_metre(self, diameter: float) -> tuple[float, float]:
        """Stiffness [N/m per m] and damping [N s/m per m] on a metre of line of ``diameter``
        [m]."""
        k = (
            self.stiffness
            if self.stiffness_per_area is None
            else self.stiffness_per_area * diameter
        )
        c = self.damping if self.damping_per_area is None else self.damping_per_area * diameter
        return k, c


class RegularWave(_Model):
    """An Airy wave: eta = H/2 cos(k (x cos b + y sin b) - 2 pi t / T + phase), k from the
    dispersion relation at the water depth (seastate.wave_number)."""

    kind: Literal["airy"]
    height: Pos
    """[m] Wave height H, crest to trough."""
    period: Pos
    """[s] Wave period T."""
    direction_deg: float = 0.0
    """[deg] Direction b the wave travels towards, from +x towards +y."""
    phase_deg: float = 0.0
    """[deg] Phase of the elevation at the origin at t = 0 (0: a crest there)."""


class WaveSpectrum(_Model):
    """An irregular sea (seastate): a JONSWAP or Pierson-Moskowitz spectrum of significant
    height Hs and peak period Tp, spread over directions as cos^2s((b - direction) / 2),
    discretised into ``frequencies`` x ``directions`` components with random frequencies
    inside equal bands between frequency_range times the peak frequency and random phases,
    from ``seed``."""

    kind: Literal["jonswap", "pierson_moskowitz"]
    significant_height: Pos
    """[m] Significant wave height Hs."""
    peak_period: Pos
    """[s] Peak period Tp of the spectrum."""
    gamma: Annotated[float, Field(ge=1.0, le=20.0)] | None = None
    """[-] JONSWAP's peak enhancement factor. Omitted: 3.3 (jonswap only)."""
    direction_deg: float = 0.0
    """[deg] Mean direction the waves travel towards, from +x towards +y."""
    spreading_exponent: NonNeg = 0.0
    """[-] s of the spreading cos^2s: larger is narrower (about 2 wind sea, 10 or more swell)."""
    directions: Annotated[int, Field(ge=1, le=101)] = 1
    """[-] Number of directions: equal sectors of the whole circle centred on the mean one."""
    frequencies: Annotated[int, Field(ge=1, le=5000)] = 200
    """[-] Number of frequency bands of equal width, one component drawn in each."""
    frequency_range: tuple[Pos, Pos] = (0.5, 3.0)
    """[-] Lowest and highest frequency of the bands, as multiples of the peak 2 pi / Tp."""
    seed: Annotated[int, Field(ge=0)] = 0
    """[-] Seed of the random frequencies and phases: the same seed gives the same sea."""

    @model_validator(mode="after")
    def _consistent(self):
        if self.kind == "pierson_moskowitz" and self.gamma is not None:
            raise ValueError("'gamma' is JONSWAP's peak enhancement; remove it, or use "
                             "kind: jonswap")  # fmt: skip
        if self.directions % 2 == 0:
            raise ValueError(f"directions ({self.directions}) must be odd, so that one is "
                             "the mean direction")  # fmt: skip
        if self.directions > 1 and self.spreading_exponent == 0.0:
            raise ValueError("several directions need a spreading_exponent (s of cos^2s, "
                             "e.g. 2 for wind sea, 10 or more for swell)")  # fmt: skip
        low, high = self.frequency_range
        if not low < high:
            raise ValueError(f"frequency_range [{low:g}, {high:g}] must increase")
        return self


Wave = Annotated[RegularWave | WaveSpectrum, Field(discriminator="kind")]


class Environment(_Model):
    """Gravity, the water and its depth, the current, the wind, the seabed and the waves."""

    gravity: Pos = 9.81
    """[m/s^2] Acceleration of gravity, along -z."""
    water_density: Pos = 1025.0
    """[kg/m^3] Density of the water."""
    water_depth: Pos | None = None
    """[m] Depth of the flat seabed, at z = -water_depth. Omitted: deep water, no seabed."""
    current: Current | None = None
    """Current of the water. Omitted: still water."""
    wind: Wind | None = None
    """Wind for the bodies' ``wind`` force models. Omitted: no wind."""
    in_air: bool = False
    """Whether the system is in air: no buoyancy, drag, added mass or current, and no waves."""
    seabed: Seabed | None = None
    """Contact of lumped-mass lines with the seabed at z = -water_depth. Omitted: no contact."""
    waves: list[Wave] = []
    """Incident waves, regular and irregular, superposed."""
    wave_stretching: Literal["wheeler", "vertical"] = "wheeler"
    """Wave kinematics above z = 0 under a crest: wheeler stretches the water column up to the
    surface, vertical holds them at their value at z = 0."""

    @model_validator(mode="after")
    def _waves_in_water(self):
        if self.waves and self.in_air:
            raise ValueError("waves need water: remove 'waves' or set in_air: false")
        if self.seabed is not None and self.water_depth is None:  # it would touch nothing
            raise ValueError(
                "seabed: a seabed lies at z = -water_depth, and no water_depth is given; give "
                "environment.water_depth [m], or remove seabed (deep water)"
            )
        return self
