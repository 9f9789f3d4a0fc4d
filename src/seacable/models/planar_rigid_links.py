"""Planar rigid-link cable: assemble the kernel parameters and initial state from a case.

The cable is n rigid uniform rods (mass m_i, inertia m_i l_i^2 / 12 about the centre) joined by
torsional spring-dampers; the first joint ties the first link to the top attachment. Loads:
apparent weight, quadratic drag at each link centre on the velocity relative to the current
(normal on d l, tangential on pi d l), joint springs and dampers, and the end bodies.
"""

import math
from dataclasses import dataclass

import numpy as np

from seacable.case import schema
from seacable.errors import CaseError
from seacable.kernels import planar_chain as pc
from seacable.models import timefunctions as tfn


@dataclass(frozen=True)
class PlanarSystem:
    """Everything a run needs: kernel parameters, initial state and a description of both."""

    params: pc.ChainParams
    y0: np.ndarray
    n_links: int
    diameter: float

    @property
    def state_size(self) -> int:
        return pc.state_size(self.n_links)


def _per_joint(value, n) -> np.ndarray:
    if isinstance(value, list):
        return np.asarray(value, dtype=float)
    return np.full(n, float(value))


def _joint_stiffness(cable: schema.Cable, lengths: np.ndarray) -> np.ndarray:
    n = len(lengths)
    if cable.joint_stiffness is not None:
        return _per_joint(cable.joint_stiffness, n)
    if cable.bending_stiffness is not None:
        # a joint stands for the bending of the cable over the mean length of its two links
        spans = np.empty(n)
        spans[0] = lengths[0]
        spans[1:] = 0.5 * (lengths[1:] + lengths[:-1])
        return cable.bending_stiffness / spans
    return np.zeros(n)


def _initial_nodes(top: tuple[float, float], angles: np.ndarray, lengths: np.ndarray):
    x = top[0] + np.concatenate([[0.0], np.cumsum(lengths * np.sin(angles))])
    z = top[1] + np.concatenate([[0.0], np.cumsum(-lengths * np.cos(angles))])
    return x, z


def _top(cable: schema.Cable, base_dir):
    """Top-end parameters, channels and the initial top position/heave state."""
    top = cable.top
    fields = dict(top_x=0.0, top_mass=1.0, top_stiffness=0.0, top_damping=0.0, top_rest_z=0.0)
    fields["top_net_weight"] = 0.0
    heave = (0.0, 0.0)
    if isinstance(top, schema.FixedTop):
        kind = pc.TOP_IMPOSED
        channels = (tfn.constant(top.position[0]), tfn.constant(top.position[1]))
        position = top.position
    elif isinstance(top, schema.ImposedTop):
        kind = pc.TOP_IMPOSED
        channels = (
            _channel(top.x, base_dir, "cables[0].top.x"),
            _channel(top.z, base_dir, "cables[0].top.z"),
        )
        position = None
    else:
        kind = pc.TOP_HEAVE
        channels = (tfn.constant(top.position[0]), tfn.constant(top.position[1]))
        fields.update(
            top_x=top.position[0],
            top_mass=top.mass + top.added_mass,
            top_stiffness=top.heave_stiffness,
            top_damping=top.heave_damping,
            top_rest_z=top.position[1],
            top_net_weight=top.net_weight,
        )
        heave = (top.position[1] + top.initial_heave, top.initial_heave_velocity)
        position = (top.position[0], heave[0])
    force = _channel(getattr(top, "force", None), base_dir, "cables[0].top.force")
    return kind, fields, channels, force, heave, position


def _bottom(cable: schema.Cable, env: schema.Environment, base_dir, end_xz):
    """Bottom-end parameters and channels (fx, fz)."""
    bottom = cable.bottom
    rho = 0.0 if env.in_air else env.water_density
    fields = dict(
        body_mass=0.0,
        body_wet_weight=0.0,
        body_drag=0.0,
        tie_kx=0.0,
        tie_cx=0.0,
        tie_kz=0.0,
        tie_cz=0.0,
        tie_x0=end_xz[0],
        tie_z0=end_xz[1],
        pin_x=end_xz[0],
        pin_z=end_xz[1],
    )
    fx = fz = tfn.constant(0.0)
    if isinstance(bottom, schema.PinnedBottom):
        if bottom.anchor is not None:
            gap = math.hypot(bottom.anchor[0] - end_xz[0], bottom.anchor[1] - end_xz[1])
            if gap > 1e-3:
                raise CaseError(
                    f"cables[0].bottom.anchor: value {list(bottom.anchor)} is {gap:.3f} m from the "
                    f"end of the initial shape at [{end_xz[0]:.3f}, {end_xz[1]:.3f}]. A pinned end "
                    "must start at its anchor: change initial angles or remove 'anchor'"
                )
        return pc.BOTTOM_PINNED, fields, fx, fz
    if isinstance(bottom, schema.FloatingStructureBottom):
        rest = bottom.rest_position or end_xz
        fields.update(
            body_mass=bottom.mass,
            tie_kx=bottom.surge_stiffness,
            tie_cx=bottom.surge_damping,
            tie_kz=bottom.heave_stiffness,
            tie_cz=bottom.heave_damping,
            tie_x0=rest[0],
            tie_z0=rest[1],
        )
        return (
            pc.BOTTOM_FREE,
            fields,
            fx,
            _channel(bottom.force, base_dir, "cables[0].bottom.force"),
        )
    body = bottom.body
    fields.update(
        body_mass=body.mass + (0.0 if env.in_air else body.added_mass),
        body_wet_weight=(body.mass - rho * body.volume) * env.gravity,
        body_drag=0.5 * rho * body.drag_coefficient * body.drag_area,
    )
    if bottom.tie is not None:
        rest = bottom.tie.rest_position or end_xz
        fields.update(
            tie_kx=bottom.tie.stiffness_x,
            tie_cx=bottom.tie.damping_x,
            tie_kz=bottom.tie.stiffness_z,
            tie_cz=bottom.tie.damping_z,
            tie_x0=rest[0],
            tie_z0=rest[1],
        )
    fx = _channel(body.force_x, base_dir, "cables[0].bottom.body.force_x")
    fz = _channel(body.force_z, base_dir, "cables[0].bottom.body.force_z")
    return pc.BOTTOM_FREE, fields, fx, fz


def build(case: schema.Case, base_dir=None) -> PlanarSystem:
    """Assemble the planar system of the (single) cable of ``case``."""
    cable = case.cables[0]
    env = case.environment
    n = cable.links
    lengths = cable.lengths()
    mass = cable.masses()
    rho = 0.0 if env.in_air else env.water_density
    area = math.pi * cable.diameter**2 / 4
    angles = cable.initial.angles(n)
    top_kind, top_fields, top_channels, top_force, heave, top_pos = _top(cable, base_dir)
    if top_pos is None:  # imposed motion: start where the time functions put the top at t = 0
        top_pos = (float(_eval0(top_channels[0])), float(_eval0(top_channels[1])))
    node_x, node_z = _initial_nodes(top_pos, angles, lengths)
    bottom_kind, bottom_fields, fx, fz = _bottom(cable, env, base_dir, (node_x[-1], node_z[-1]))
    current_z, current_u = (
        env.current.arrays() if env.current is not None else (np.zeros(1), np.zeros(1))
    )
    if env.in_air:
        current_u = np.zeros_like(current_u)
    breaks, coefs, count, sine = tfn.stack([*top_channels, top_force, fx, fz])
    params = _typed(
        n=n,
        length=lengths,
        mass=mass,
        inertia=mass * lengths**2 / 12.0,
        wet_weight=(mass - rho * area * lengths) * env.gravity,
        drag_normal=0.5 * rho * cable.drag_coefficient_normal * cable.diameter * lengths,
        drag_tangential=0.5
        * rho
        * cable.drag_coefficient_tangential
        * math.pi
        * cable.diameter
        * lengths,
        joint_stiffness=_joint_stiffness(cable, lengths),
        joint_damping=_per_joint(cable.joint_damping, n),
        top_reference_angle=math.radians(cable.top_reference_angle_deg),
        current_z=current_z,
        current_u=current_u,
        top_kind=top_kind,
        bottom_kind=bottom_kind,
        stabilization_frequency=case.simulation.constraint_stabilization_frequency,
        tf_breaks=breaks,
        tf_coefs=coefs,
        tf_count=count,
        tf_sine=sine,
        **top_fields,
        **bottom_fields,
    )
    y0 = np.zeros(pc.state_size(n))
    y0[:n] = angles
    y0[n] = heave[0]
    y0[2 * n + 1] = heave[1]
    return PlanarSystem(params=params, y0=y0, n_links=n, diameter=cable.diameter)


def _channel(spec, base_dir, where: str) -> tfn.Piecewise:
    """Compile a time function; a table that cannot be read becomes a CaseError naming it."""
    try:
        return tfn.build(spec, base_dir)
    except ValueError as exc:
        raise CaseError(f"{where}: {exc}") from None


def _eval0(piecewise: tfn.Piecewise) -> float:
    breaks, coefs, count, sine = tfn.stack([piecewise])
    return pc.tf_evaluate(breaks, coefs, count, sine, 0, 0.0)[0]


def _typed(**fields) -> pc.ChainParams:
    """ChainParams with every field of the exact type the compiled kernels were built for
    (a float given as int would trigger a new compilation)."""
    typed = {}
    for name, annotation in pc.ChainParams.__annotations__.items():
        value = fields[name]
        if annotation is int:
            typed[name] = int(value)
        elif annotation is float:
            typed[name] = float(value)
        elif name == "tf_count":
            typed[name] = np.ascontiguousarray(value, dtype=np.int64)
        else:
            typed[name] = np.ascontiguousarray(value, dtype=np.float64)
    return pc.ChainParams(**typed)
