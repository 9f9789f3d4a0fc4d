"""Helpers shared by the cable models: joint properties, current, drag, time-function channels."""

import math
from dataclasses import dataclass

import numpy as np

from seacable.case import schema
from seacable.kernels import surface
from seacable.packing import channel, current_arrays, shape_row, typed  # noqa: F401  (re-exported)

# what a divergence message advises against ringing, per model (only options its schema takes)
JOINT_DAMPING_ADVICE = "add joint damping (cables[k].joint_damping [N m s/rad])"
AXIAL_DAMPING_ADVICE = "add axial damping (cables[k].axial_damping_time [s])"


def per_joint(value, n) -> np.ndarray:
    if isinstance(value, list):
        return np.asarray(value, dtype=float)
    return np.full(n, float(value))


def joint_stiffness(cable: schema.Cable, lengths: np.ndarray) -> np.ndarray:
    n = len(lengths)
    if cable.joint_stiffness is not None:
        return per_joint(cable.joint_stiffness, n)
    if cable.bending_stiffness is not None:
        # a joint stands for the bending of the cable over the mean length of its two links
        spans = np.empty(n)
        spans[0] = lengths[0]
        spans[1:] = 0.5 * (lengths[1:] + lengths[:-1])
        return cable.bending_stiffness / spans
    return np.zeros(n)


def tangential_drag(cable: schema.Cable, rho: float, lengths: np.ndarray) -> np.ndarray:
    """0.5 rho (pi Cd_t + f Cd_n) d l: skin friction on the wetted area plus Richtmyer's law."""
    coefficient = math.pi * cable.drag_coefficient_tangential
    coefficient += cable.friction_coefficient * cable.drag_coefficient_normal
    return 0.5 * rho * coefficient * cable.diameter * lengths


def add_total_energy(rows: dict) -> dict:
    """Add ``total_energy`` = kinetic + gravity potential + elastic to output rows."""
    rows["total_energy"] = (
        rows["kinetic_energy"] + rows["gravity_potential_energy"] + rows["elastic_energy"]
    )
    return rows


@dataclass(frozen=True)
class Section:
    """Per-segment properties of the case's first cable, shared by every cable model (SI)."""

    lengths: np.ndarray  # [m]
    mass: np.ndarray  # [kg]
    rho: float  # water density, 0 in air [kg/m^3]
    area: float  # cross-section pi d^2 / 4 [m^2]
    wet_weight: np.ndarray  # apparent weight, positive down [N]
    buoyancy: np.ndarray  # rho g A l wholly submerged [N]
    added_mass: np.ndarray  # normal added mass Ca rho A l [kg] (Ca default 1)


def section(case: schema.Case) -> Section:
    cable = case.cables[0]
    env = case.environment
    lengths = cable.lengths()
    mass = cable.masses()
    rho = 0.0 if env.in_air else env.water_density
    area = math.pi * cable.diameter**2 / 4
    ca = 1.0 if cable.added_mass_coefficient is None else cable.added_mass_coefficient
    return Section(
        lengths=lengths,
        mass=mass,
        rho=rho,
        area=area,
        wet_weight=(mass - rho * area * lengths) * env.gravity,
        buoyancy=rho * area * lengths * env.gravity,
        added_mass=ca * rho * area * lengths,
    )


def xyz_variables(prefix: str, dims, units: str, what: str) -> dict:
    """Three output variables ``prefix_x``, ``_y``, ``_z`` (dims, units, description)."""
    return {f"{prefix}_{a}": (dims, units, f"{what}, {a}") for a in "xyz"}


# variables a model records only when the case has the end they describe
TRAJECTORY_VARIABLES = ("target_x", "target_y", "target_z", "tracking_error")
SERVO_VARIABLES = ("servo_force_x", "servo_force_y", "servo_force_z")
HELD_VARIABLES = ("constraint_error",)


def case_variables(variables: dict, case: schema.Case) -> dict:
    """The entries of a model's ``VARIABLES`` that ``case`` really has: the target and the
    tracking error with a trajectory end or a guided end (``hold_axes``), the servo's force with
    a servo end, the constraint error with an end held exactly (pinned, exact trajectory,
    guided). The one filter every model's records go through (``simulation.simulate``)."""
    bottoms = [cable.bottom for cable in case.cables]
    trajectory = [b for b in bottoms if isinstance(b, schema.TrajectoryBottom)]
    guided = any(getattr(b, "hold_axes", []) for b in bottoms)
    servo = any(b.method == "stiffness_servo" for b in trajectory)
    pinned = any(isinstance(b, schema.PinnedBottom) for b in bottoms)
    held = pinned or guided or any(b.method == "exact" for b in trajectory)
    absent: set[str] = set()
    if not (trajectory or guided):
        absent.update(TRAJECTORY_VARIABLES)
    if not servo:
        absent.update(SERVO_VARIABLES)
    if not held:
        absent.update(HELD_VARIABLES)
    return {name: v for name, v in variables.items() if name not in absent}


def cable_length(cable: schema.Cable) -> float:
    """Unstretched length of the cable [m]."""
    return float(np.sum(cable.lengths()))


def state_scale(
    cable: schema.Cable, env: schema.Environment, positions: np.ndarray, forces: int = 0
) -> np.ndarray:
    """Typical magnitude of each state of a cable's block ``[positions, their rates, forces]``,
    the unit of the floor of the adaptive integrators' default absolute tolerance (see
    ``schema.Simulation.atol``): ``positions`` the models give (1 for
    angles [rad] and unit directors, the cable's length L [m] for coordinates); their rates
    that times the pendulum frequency sqrt(g / L) [1/s] (a cable of length L swinging through
    a radian: sqrt(g L) [m/s], sqrt(g / L) [rad/s]); then ``forces`` forces (the cable's weight
    in air [N])."""
    length = cable_length(cable)
    weight = float(np.sum(cable.masses())) * env.gravity
    positions = np.asarray(positions, dtype=float)
    return np.concatenate(
        [positions, positions * math.sqrt(env.gravity / length), np.full(forces, weight)]
    )


# ---- bodies and the free surface -----------------------------------------------------------------
def _case_bodies(case: schema.Case) -> list[schema.SharedBody | schema.PointBody | schema.Body]:
    bodies: list[schema.SharedBody | schema.PointBody | schema.Body] = list(case.bodies)
    for cable in case.cables:
        bodies += list(cable.point_bodies)
        body = getattr(cable.bottom, "body", None)
        if isinstance(body, schema.Body):
            bodies.append(body)
    return bodies


def shape_width(case: schema.Case) -> int:
    """Width of the shape rows of ``case`` (kernels.surface): room for its longest table."""
    width = surface.HEADER
    for body in _case_bodies(case):
        if isinstance(body.shape, schema.VolumeTable):
            width = max(width, surface.HEADER + 2 * len(body.shape.submerged_volume))
    return width


@dataclass(frozen=True)
class BodyLoads:
    """A point body's loads when wholly submerged, and what the free surface scales (SI)."""

    mass: np.ndarray  # (3,) mass + added mass per axis [kg]
    wet_weight: float  # apparent weight (m - rho V) g, positive down [N]
    drag: np.ndarray  # (3,) 0.5 rho Cd A per axis [N s^2/m^2]
    added: np.ndarray  # (3,) added mass per axis [kg]
    buoyancy: float  # rho g V [N]
    shape: np.ndarray  # shape row (kernels.surface)


def body_loads(body, env: schema.Environment, width: int) -> BodyLoads:
    """Loads of a Body, SharedBody or PointBody (one drag area for a PointBody); no water, no
    buoyancy, added mass or drag in air."""
    rho = 0.0 if env.in_air else env.water_density
    added = np.zeros(3) if env.in_air else np.array(schema.per_axis(body.added_mass), float)
    buoyancy = rho * body.displaced_volume() * env.gravity
    return BodyLoads(
        mass=body.mass + added,
        wet_weight=(body.mass - rho * body.displaced_volume()) * env.gravity,
        drag=0.5 * rho * body.drag_coefficient * np.array(schema.per_axis(body.drag_area), float),
        added=added,
        buoyancy=buoyancy,
        shape=shape_row(body.shape, width),
    )
