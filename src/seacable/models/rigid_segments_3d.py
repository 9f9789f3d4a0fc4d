"""Three-dimensional rigid-segment cable (Jacquot & Marichal 1993): parameters and initial state.

Segments are rigid uniform cylinders (orientation: unit directors, see ``kernels.chain3d``).
Hydrodynamic loads at each segment centre on the velocity relative to the current: Landweber's
normal pressure drag 0.5 rho Cd d l |V_N| V_N (Cd 1.8 by default, as the paper argues from vortex
shedding), Richtmyer's tangential friction f 0.5 rho Cd d l (V cos phi)^2 (plus an optional skin
friction Cd_t on pi d l), normal added mass Ca rho pi d^2/4 l (none axially; Ca = 1 for a
circular cylinder) with its rotational part Ca rho pi d^2/4 l^3/12, and apparent weight.
"""

import math
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np

from seacable import timefunctions as tfn
from seacable.case import schema
from seacable.errors import CaseError
from seacable.kernels import chain3d as c3
from seacable.kernels import chain3d_outputs as c3o
from seacable.kernels import surface
from seacable.models import common, statics
from seacable.models.common import (
    add_total_energy,
    body_loads,
    current_arrays,
    joint_stiffness,
    per_joint,
    section,
    shape_width,
    tangential_drag,
    typed,
    xyz_variables,
)
from seacable.models.common import channel as _channel
from seacable.models.planar_rigid_links import coords, sizes, zigzag_frequency

DEFAULT_DRAG_COEFFICIENT = 1.8  # Jacquot & Marichal: vortex-induced vibration raises Cd


@dataclass(frozen=True)
class System3D:
    params: c3.Chain3DParams
    y0: np.ndarray
    n_links: int
    diameter: float

    @property
    def state_size(self) -> int:
        return c3.state_size(self.n_links)


def directors_from_angles(angles: np.ndarray, azimuth: float) -> np.ndarray:
    """Unit directors of segments at ``angles`` from the downward vertical in the vertical
    plane at ``azimuth`` (from +x towards +y)."""
    s = np.sin(angles)
    return np.column_stack([s * math.cos(azimuth), s * math.sin(azimuth), -np.cos(angles)])


def _track_fields(top: schema.TowingShipTop, base_dir):
    if top.speed is not None:
        spec = schema.AccelerationProfile(
            kind="acceleration_profile",
            initial_velocity=top.speed,
            phases=[schema.AccelerationPhase(duration=1.0, acceleration=0.0)],
        )
        distance = tfn.build(spec)
    else:
        distance = _channel(top.distance, base_dir, "cables[0].top.distance")
    distance = tfn.steady(distance)  # the towed start is the steady state: no build-up
    turn_at, radius = 0.0, 0.0
    if top.turn is not None:
        turn_at = tfn.evaluate(distance, top.turn.start_time)[0]
        radius = top.turn.radius * (1.0 if top.turn.side == "left" else -1.0)
    fields = dict(
        track_origin=np.array(schema.xyz(top.position)),
        track_heading=math.radians(top.heading_deg),
        track_turn_at=turn_at,
        track_radius=radius,
    )
    return fields, distance


def _top(cable: schema.Cable, base_dir):
    """Top kind, fields, channels (x, y, z, force, distance) and the heave state."""
    top = cable.top
    zero = tfn.constant(0.0)
    fields: dict[str, Any] = dict(
        top_x=0.0, top_y=0.0, top_mass=1.0, top_stiffness=0.0, top_damping=0.0
    )
    fields.update(top_rest_z=0.0, top_net_weight=0.0, track_origin=np.zeros(3))
    fields.update(track_heading=0.0, track_turn_at=0.0, track_radius=0.0)
    heave = (0.0, 0.0)
    force = distance = zero
    if isinstance(top, schema.FixedTop):
        kind = c3.TOP_IMPOSED
        channels = tuple(tfn.constant(v) for v in schema.xyz(top.position))
    elif isinstance(top, schema.ImposedTop):
        kind = c3.TOP_IMPOSED
        channels = tuple(
            _channel(getattr(top, axis), base_dir, f"cables[0].top.{axis}") for axis in "xyz"
        )
    elif isinstance(top, schema.TowingShipTop):
        kind = c3.TOP_TRACK
        channels = (zero, zero, zero)
        track, distance = _track_fields(top, base_dir)
        fields.update(track)
    else:
        kind = c3.TOP_HEAVE
        x, y, z = schema.xyz(top.position)
        channels = (tfn.constant(x), tfn.constant(y), tfn.constant(z))
        fields.update(
            top_x=x,
            top_y=y,
            top_mass=top.mass + top.added_mass,
            top_stiffness=top.heave_stiffness,
            top_damping=top.heave_damping,
            top_rest_z=z,
            top_net_weight=top.net_weight,
        )
        heave = (z + top.initial_heave, top.initial_heave_velocity)
        force = _channel(top.force, base_dir, "cables[0].top.force")
    return kind, fields, (*channels, force, distance), heave


def _bottom(cable: schema.Cable, env: schema.Environment, base_dir, width: int):
    """Bottom kind, fields (positions filled in later) and channels (fx, fy, fz, target x, y, z);
    ``width``: of the shape rows."""
    bottom = cable.bottom
    zero = tfn.constant(0.0)
    fields = dict(
        body_mass=np.zeros(3),
        body_wet_weight=0.0,
        body_drag=np.zeros(3),
        tie_k=np.zeros(3),
        tie_c=np.zeros(3),
        constrained=np.ones(3),
        target_relative=0,
        servo_stiffness=np.zeros((3, 3)),
        servo_gain=0.0,
        servo_rate_gain=0.0,
        servo_step=1.0,
    )
    targets: tuple[tfn.Piecewise, ...] = (zero, zero, zero)
    if isinstance(bottom, schema.PinnedBottom):
        return c3.BOTTOM_PINNED, fields, (zero, zero, zero, *targets)
    if isinstance(bottom, schema.TrajectoryBottom):
        targets = tuple(
            _channel(getattr(bottom, a), base_dir, f"cables[0].bottom.{a}") for a in "xyz"
        )
        fields.update(target_relative=int(bottom.relative_to_top))
        if bottom.method == "exact":
            return c3.BOTTOM_TRAJECTORY, fields, (zero, zero, zero, *targets)
        fields.update(servo_gain=bottom.servo.gain, servo_rate_gain=bottom.servo.rate_gain)
        return c3.BOTTOM_SERVO, fields, (zero, zero, zero, *targets)
    if isinstance(bottom, schema.FloatingStructureBottom):
        fields.update(
            body_mass=np.full(3, bottom.mass),
            tie_k=np.array(
                [bottom.surge_stiffness, bottom.surge_stiffness, bottom.heave_stiffness]
            ),
            tie_c=np.array([bottom.surge_damping, bottom.surge_damping, bottom.heave_damping]),
        )
        force = _channel(bottom.force, base_dir, "cables[0].bottom.force")
        return c3.BOTTOM_FREE, fields, (zero, zero, force, *targets)
    # an attached end is built by the star models, which hand this one a pinned end
    assert isinstance(bottom, schema.FreeBottom)
    body = bottom.body
    loads = body_loads(body, env, width)
    fields.update(
        body_mass=loads.mass,
        body_wet_weight=loads.wet_weight,
        body_drag=loads.drag,
        end_body=loads,
    )
    if bottom.tie is not None:
        tie = bottom.tie
        fields.update(
            tie_k=np.array([tie.stiffness_x, tie.stiffness_y, tie.stiffness_z]),
            tie_c=np.array([tie.damping_x, tie.damping_y, tie.damping_z]),
        )
    forces = tuple(
        _channel(getattr(body, f"force_{a}"), base_dir, f"cables[0].bottom.body.force_{a}")
        for a in "xyz"
    )
    if bottom.hold_axes:
        fields.update(constrained=np.array([float(a in bottom.hold_axes) for a in "xyz"]))
        return c3.BOTTOM_PINNED, fields, (*forces, *targets)
    return c3.BOTTOM_FREE, fields, (*forces, *targets)


def _point_bodies(cable: schema.Cable, env: schema.Environment, n: int, width: int, end_body):
    """Per-node fields of the floats and clump weights (the free surface's rows: the end body's
    ``BodyLoads`` at node n, or None)."""
    node_mass = np.zeros((n + 1, 3))
    node_weight = np.zeros(n + 1)
    node_drag = np.zeros(n + 1)
    shapes = np.array([surface.point_row(width) for _ in range(n + 1)])
    node_added = np.zeros((n + 1, 3))
    buoyancy = np.zeros(n + 1)
    for k, body in enumerate(cable.point_bodies):
        if body.node >= n:
            raise CaseError(
                f"cables[0].point_bodies[{k}].node: value {body.node} is not a joint of a cable "
                f"of {n} segments; allowed 1 to {n - 1} (the end body goes in 'bottom')"
            )
        if body.shape is not None and np.any(shapes[body.node] != shapes[0]):
            raise CaseError(
                f"cables[0].point_bodies[{k}].shape: node {body.node} already has a body with "
                "a shape; one shaped body per node (merge them into one)"
            )
        loads = body_loads(body, env, width)
        node_mass[body.node] += loads.mass
        node_weight[body.node] += loads.wet_weight
        node_drag[body.node] += loads.drag[0]
        node_added[body.node] += loads.added
        buoyancy[body.node] += loads.buoyancy
        if body.shape is not None:
            shapes[body.node] = loads.shape
    if end_body is not None:
        shapes[n], node_added[n], buoyancy[n] = end_body.shape, end_body.added, end_body.buoyancy
    surface_fields = dict(node_shape=shapes, node_added=node_added, node_buoyancy=buoyancy)
    return node_mass, node_weight, node_drag, surface_fields


def build(case: schema.Case, base_dir=None) -> System3D:
    """Assemble the 3D system of the (single) cable of ``case``."""
    cable = case.cables[0]
    env = case.environment
    n = cable.links
    props = section(case)
    lengths, mass, rho, added = props.lengths, props.mass, props.rho, props.added_mass
    top_kind, top_fields, channels, heave = _top(cable, base_dir)
    width = shape_width(case)
    bottom_kind, bottom_fields, body_channels = _bottom(cable, env, base_dir, width)
    end_body = bottom_fields.pop("end_body", None)
    node_mass, node_weight, node_drag, surface_fields = _point_bodies(
        cable, env, n, width, end_body
    )
    current_z, current_u, current_v = current_arrays(env)
    ordered = [*channels[:4], *body_channels[:3], channels[4], *body_channels[3:]]
    fields = dict(
        n=n,
        length=lengths,
        mass=mass,
        added_mass=added,
        inertia=(mass + added) * lengths**2 / 12.0,
        wet_weight=props.wet_weight,
        buoyancy=props.buoyancy,
        drag_normal=0.5 * rho * cable.drag_coefficient_normal * cable.diameter * lengths,
        drag_tangential=tangential_drag(cable, rho, lengths),
        joint_stiffness=joint_stiffness(cable, lengths),
        joint_damping=per_joint(cable.joint_damping, n),
        top_reference=_top_reference(cable),
        current_z=current_z,
        current_u=current_u,
        current_v=current_v,
        node_mass=node_mass,
        node_wet_weight=node_weight,
        node_drag=node_drag,
        **surface_fields,
        top_kind=top_kind,
        bottom_kind=bottom_kind,
        tie_rest=np.zeros(3),
        pin=np.zeros(3),
        stabilization_frequency=case.simulation.constraint_stabilization_frequency,
        **tfn.kernel_fields(ordered, case.simulation.build_up),
        **top_fields,
        **bottom_fields,
    )
    params = typed(c3.Chain3DParams, fields)
    y0 = np.zeros(c3.state_size(n))
    y0[3 * n] = heave[0]
    y0[6 * n + 1] = heave[1]
    bottom = cable.bottom
    if isinstance(bottom, schema.PinnedBottom) and bottom.anchor is not None:
        params = params._replace(pin=np.array(schema.xyz(bottom.anchor), dtype=float))
    elif isinstance(bottom, schema.PinnedBottom) and cable.initial.shape == "static":
        raise CaseError(
            "cables[0].bottom.anchor: a pinned end started from initial shape 'static' needs "
            "its 'anchor' [x, y, z] (m)"
        )
    explicit_rest = _explicit_rest(cable)
    if explicit_rest is not None:
        params = params._replace(tie_rest=explicit_rest)
        directors = _initial_directors(case, params, y0)
    else:
        # ties unloaded at the initial end: the static shape is that of a free end
        free = params._replace(tie_k=np.zeros(3))
        directors = _initial_directors(case, free, y0)
    y0[: 3 * n] = directors.ravel()
    params = _fill_rest_positions(cable, params, y0)
    if params.bottom_kind == c3.BOTTOM_SERVO:
        params, y0 = _start_servo(case, params, y0)
    return System3D(params=params, y0=y0, n_links=n, diameter=cable.diameter)


def end_servo(case: schema.Case) -> schema.Servo:
    """The servo of the case's lower end (a trajectory end with method stiffness_servo)."""
    bottom = case.cables[0].bottom
    assert isinstance(bottom, schema.TrajectoryBottom)  # only servo ends ask for their servo
    return bottom.servo


def servo_step(case: schema.Case) -> float:
    servo = end_servo(case)
    if servo.step is not None:
        return servo.step
    sim = case.simulation
    return sim.time_step if sim.time_step is not None else min(0.01, sim.output_interval)


def refresh_interval(case: schema.Case) -> float | None:
    """How often [s] the run must call :func:`refresh` between compiled chunks (None: never)."""
    bottom = case.cables[0].bottom
    if isinstance(bottom, schema.TrajectoryBottom) and bottom.method == "stiffness_servo":
        return bottom.servo.recompute_interval
    return None


def refresh(case: schema.Case, params, time: float, y):
    """Parameters for the next stretch of the run: the servo's stiffness K recomputed about the
    target at ``time`` (the top's current velocity taken as steady)."""
    radius = end_servo(case).sphere_radius
    stiffness, _ = statics.end_stiffness(params, y, time, radius)
    return params._replace(servo_stiffness=np.ascontiguousarray(stiffness))


def _start_servo(case, params, y0):
    servo = end_servo(case)
    stiffness, force = statics.end_stiffness(params, y0, 0.0, servo.sphere_radius)
    y0 = y0.copy()
    y0[6 * params.n + 2 :] = force
    params = params._replace(
        servo_stiffness=np.ascontiguousarray(stiffness), servo_step=servo_step(case)
    )
    return params, y0


def _initial_directors(case, params, y0) -> np.ndarray:
    cable = case.cables[0]
    if cable.initial.shape == "static":
        return statics.static_directors(params, y0, time=0.0)
    angles = cable.initial.angles(cable.links)
    return directors_from_angles(angles, math.radians(cable.initial.azimuth_deg))


def end_position(params: c3.Chain3DParams, y: np.ndarray, time: float = 0.0) -> np.ndarray:
    """Position of the bottom node of state ``y`` [m]."""
    n = params.n
    top, _, _ = c3.top_motion(time, y, params)
    directors = y[: 3 * n].reshape(n, 3)
    return top + (params.length[:, None] * directors).sum(axis=0)


def _explicit_rest(cable: schema.Cable):
    """Rest position of the bottom ties when the case gives one (else None)."""
    bottom = cable.bottom
    if isinstance(bottom, schema.FloatingStructureBottom) and bottom.rest_position is not None:
        return np.array(schema.xyz(bottom.rest_position), dtype=float)
    tie = getattr(bottom, "tie", None)
    if tie is not None and tie.rest_position is not None:
        return np.array(schema.xyz(tie.rest_position), dtype=float)
    return None


def _fill_rest_positions(cable: schema.Cable, params, y0):
    end = end_position(params, y0)
    bottom = cable.bottom
    rest = _explicit_rest(cable)
    if rest is None:
        rest = end
    if isinstance(bottom, schema.TrajectoryBottom):
        target = np.asarray(c3.target_motion(0.0, y0, params)[0], float)
        gap = float(np.linalg.norm(target - end))
        if gap > 1e-3:
            raise CaseError(
                f"cables[0].bottom: the trajectory starts {gap:.3f} m from the end of the initial "
                "shape; use initial: {shape: static} (the steady shape ending on the target)"
            )
        end = target
    if isinstance(bottom, schema.PinnedBottom) and bottom.anchor is not None:
        anchor = np.array(schema.xyz(bottom.anchor))
        gap = float(np.linalg.norm(anchor - end))
        if gap > 1e-3:
            raise CaseError(
                f"cables[0].bottom.anchor: value {list(bottom.anchor)} is {gap:.3f} m from the end "
                f"of the initial shape at {np.round(end, 3).tolist()}. A pinned end must start at "
                "its anchor: change the initial shape, use initial: {shape: static}, or remove "
                "'anchor'"
            )
        end = anchor
    return params._replace(tie_rest=np.asarray(rest, float), pin=np.asarray(end, float))


def _top_reference(cable: schema.Cable) -> np.ndarray:
    angle = math.radians(cable.top_reference_angle_deg)
    azimuth = math.radians(cable.initial.azimuth_deg)
    return directors_from_angles(np.array([angle]), azimuth)[0]


# ---- what a run of this model records ------------------------------------------------------------
VARIABLES = {
    **xyz_variables("direction", ("time", "segment"), "1", "unit vector along the segment"),
    **xyz_variables("node", ("time", "node"), "m", "node position (z up, 0 at the surface)"),
    "tension": (("time", "segment"), "N", "axial tension at the segment centre (positive pulling)"),
    **xyz_variables(
        "top_force",
        ("time",),
        "N",
        "force of the cable on its top attachment "
        "(the tow force needed at the tow point is its opposite)",
    ),  # fmt: skip
    **xyz_variables(
        "bottom_force", ("time",), "N", "force of the cable on its bottom body or anchor"
    ),
    **xyz_variables("top_velocity", ("time",), "m/s", "velocity of the top attachment"),
    **xyz_variables("bottom_velocity", ("time",), "m/s", "velocity of the bottom end (its body)"),
    "angular_rate": (("time", "segment"), "rad/s", "rate of turn of the segment"),
    "kinetic_energy": (("time",), "J", "kinetic energy (added mass included)"),
    "gravity_potential_energy": (("time",), "J", "potential energy of apparent weights (z = 0)"),
    "elastic_energy": (("time",), "J", "energy stored in joint springs, heave spring and ties"),
    "total_energy": (("time",), "J", "kinetic + gravity potential + elastic energy"),
    "constraint_error": (("time",), "m", "distance of a held end from its target (held axes)"),
    **xyz_variables("target", ("time",), "m", "target of the lower end (trajectory, guide)"),
    "tracking_error": (("time",), "m", "distance of the lower end from its target"),
    **xyz_variables("servo_force", ("time",), "N", "force the servo applies to the cable end"),
}


def workspace(system: System3D):
    """Scratch arrays the compiled kernels fill during a run."""
    return c3.make_workspace(system.n_links)


def rows(times, states, system: System3D, w) -> tuple[dict, int]:
    """Output rows for the given states (compiled), and the first non-zero kernel status."""
    n = system.n_links
    m = len(times)
    nodes = np.empty((m, n + 1, 3))
    tension = np.empty((m, n))
    scalars = np.empty((m, c3.N_SCALARS))
    status = c3o.outputs_chunk(times, states, system.params, w, nodes, tension, scalars)
    directors = states[:, : 3 * n].reshape(m, n, 3)
    rates_ = states[:, 3 * n + 1 : 6 * n + 1].reshape(m, n, 3)
    out = {"time": times, "tension": tension}
    for k, a in enumerate("xyz"):
        out[f"direction_{a}"] = directors[:, :, k]
        out[f"node_{a}"] = nodes[:, :, k]
    for k, name in enumerate(c3.SCALAR_NAMES):
        out[name] = scalars[:, k]
    out["angular_rate"] = np.linalg.norm(rates_, axis=2)
    return add_total_energy(out), status


NEWTON = False  # the implicit schemes run systems of bodies and lines only


def shortest_segment(system: System3D) -> float:
    """Shortest segment [m]: scales the Newton tolerance of implicit steps."""
    return float(np.min(system.params.length))


def positions(system: System3D) -> int:
    """Position variables of the state (directors and heave); the servo force follows."""
    return 3 * system.n_links + 1


DAMPING_ADVICE = common.JOINT_DAMPING_ADVICE  # divergence messages


class _Segmented(Protocol):
    """What ``state_scale`` reads of a system: its segments per cable (a star's too)."""

    @property
    def n_links(self) -> int: ...


def state_scale(case: schema.Case, system: _Segmented) -> np.ndarray:
    """Typical magnitude of each state (``common.state_scale``): unit directors 1, the heave
    of a floating end the cable's length, the servo force the cable's weight."""
    cable = case.cables[0]
    positions = np.append(np.ones(3 * system.n_links), common.cable_length(cable))
    return common.state_scale(cable, case.environment, positions, c3.SERVO_STATES)


RATE_WHAT = ("segment", "angular rate", "rad/s", 0)  # |de/dt| of each segment (messages)


def rates(system: System3D, y) -> np.ndarray:
    n = system.n_links
    return np.linalg.norm(y[3 * n + 1 : 6 * n + 1].reshape(n, 3), axis=1)


def fastest_frequency(system: System3D) -> tuple[float, str]:
    """The zigzag estimate of the planar model (see its docstring), with added inertia."""
    p = system.params
    tension = float(np.sum(np.abs(p.wet_weight)) + np.sum(np.abs(p.node_wet_weight)))
    tension += abs(p.body_wet_weight)
    tension += 0.5 * float(np.sum(p.drag_normal)) * _speed_scale(p) ** 2
    tie_k = float(p.tie_k.max()) if p.bottom_kind == c3.BOTTOM_FREE else 0.0
    heave = p.top_stiffness / p.top_mass if p.top_kind == c3.TOP_HEAVE else 0.0
    return zigzag_frequency(p, tension, tie_k, float(p.body_mass.min()), heave)


def _speed_scale(p) -> float:
    """A speed for the drag part of the tension bound: current plus tow speed at t = 0."""
    speed = float(np.max(np.hypot(p.current_u, p.current_v)))
    if p.top_kind == c3.TOP_TRACK:
        speed += abs(c3.top_motion(0.0, np.zeros(c3.state_size(p.n)), p)[1]).max()
    return speed


__all__ = [
    "System3D",
    "build",
    "coords",
    "fastest_frequency",
    "rates",
    "rows",
    "sizes",
    "workspace",
]
