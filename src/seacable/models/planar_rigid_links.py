"""Planar rigid-link cable: assemble the kernel parameters and initial state from a case.

The cable is n rigid uniform rods (mass m_i, inertia m_i l_i^2 / 12 about the centre) joined by
torsional spring-dampers; the first joint ties the first link to the top attachment. Loads:
apparent weight, quadratic drag at each link centre on the velocity relative to the current
(normal on d l, tangential on pi d l), joint springs and dampers, and the end bodies.
"""

import math
from dataclasses import dataclass

import numpy as np

from seacable import timefunctions as tfn
from seacable.case import schema
from seacable.errors import CaseError
from seacable.kernels import planar_chain as pc
from seacable.kernels import surface
from seacable.models import common
from seacable.models.common import add_total_energy


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
        x, _, z = schema.xyz(top.position)
        channels = (tfn.constant(x), tfn.constant(z))
        position = (x, z)
    elif isinstance(top, schema.ImposedTop):
        kind = pc.TOP_IMPOSED
        channels = (
            common.channel(top.x, base_dir, "cables[0].top.x"),
            common.channel(top.z, base_dir, "cables[0].top.z"),
        )
        position = None
    else:
        assert isinstance(top, schema.FloatingStructureTop)  # Cable._planar_limits: no towing_ship
        kind = pc.TOP_HEAVE
        x, _, z = schema.xyz(top.position)
        channels = (tfn.constant(x), tfn.constant(z))
        fields.update(
            top_x=x,
            top_mass=top.mass + top.added_mass,
            top_stiffness=top.heave_stiffness,
            top_damping=top.heave_damping,
            top_rest_z=z,
            top_net_weight=top.net_weight,
        )
        heave = (z + top.initial_heave, top.initial_heave_velocity)
        position = (x, heave[0])
    force = common.channel(getattr(top, "force", None), base_dir, "cables[0].top.force")
    return kind, fields, channels, force, heave, position


def _bottom(cable: schema.Cable, env: schema.Environment, base_dir, end_xz, width):
    """Bottom-end parameters and channels (fx, fz); ``width``: of the shape row."""
    bottom = cable.bottom
    fields = dict(
        body_mass=0.0,
        body_wet_weight=0.0,
        body_drag=0.0,
        body_shape=surface.point_row(width),
        body_added=0.0,
        body_buoyancy=0.0,
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
            ax, _, az = schema.xyz(bottom.anchor)
            gap = math.hypot(ax - end_xz[0], az - end_xz[1])
            if gap > 1e-3:
                raise CaseError(
                    f"cables[0].bottom.anchor: value {list(bottom.anchor)} is {gap:.3f} m from the "
                    f"end of the initial shape at [{end_xz[0]:.3f}, {end_xz[1]:.3f}]. A pinned end "
                    "must start at its anchor: change initial angles or remove 'anchor'"
                )
        return pc.BOTTOM_PINNED, fields, fx, fz
    if isinstance(bottom, schema.FloatingStructureBottom):
        rest = _xz(bottom.rest_position) or end_xz
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
            common.channel(bottom.force, base_dir, "cables[0].bottom.force"),
        )
    assert isinstance(bottom, schema.FreeBottom)  # Cable._planar_limits: no trajectory, attached
    body = bottom.body
    added = schema.per_axis(body.added_mass)
    area = schema.per_axis(body.drag_area)
    if added[0] != added[2] or area[0] != area[2]:
        raise CaseError(
            "cables[0].bottom.body: the planar model takes one added_mass and one drag_area "
            f"for x and z (got {body.added_mass}, {body.drag_area}); use model: rigid_segments_3d "
            "for direction-dependent values"
        )
    loads = common.body_loads(body, env, width)
    fields.update(
        body_mass=loads.mass[0],
        body_wet_weight=loads.wet_weight,
        body_drag=loads.drag[0],
        body_shape=loads.shape,
        body_added=loads.added[0],
        body_buoyancy=loads.buoyancy,
    )
    if bottom.tie is not None:
        rest = _xz(bottom.tie.rest_position) or end_xz
        fields.update(
            tie_kx=bottom.tie.stiffness_x,
            tie_cx=bottom.tie.damping_x,
            tie_kz=bottom.tie.stiffness_z,
            tie_cz=bottom.tie.damping_z,
            tie_x0=rest[0],
            tie_z0=rest[1],
        )
    fx = common.channel(body.force_x, base_dir, "cables[0].bottom.body.force_x")
    fz = common.channel(body.force_z, base_dir, "cables[0].bottom.body.force_z")
    return pc.BOTTOM_FREE, fields, fx, fz


def build(case: schema.Case, base_dir=None) -> PlanarSystem:
    """Assemble the planar system of the (single) cable of ``case``."""
    cable = case.cables[0]
    env = case.environment
    n = cable.links
    props = common.section(case)
    lengths, mass, rho = props.lengths, props.mass, props.rho
    angles = cable.initial.angles(n)
    top_kind, top_fields, top_channels, top_force, heave, top_pos = _top(cable, base_dir)
    if top_pos is None:  # imposed motion: start where the time functions put the top at t = 0
        top_pos = (tfn.evaluate(top_channels[0], 0.0)[0], tfn.evaluate(top_channels[1], 0.0)[0])
    node_x, node_z = _initial_nodes(top_pos, angles, lengths)
    bottom_kind, bottom_fields, fx, fz = _bottom(
        cable, env, base_dir, (node_x[-1], node_z[-1]), common.shape_width(case)
    )
    current_z, current_u, current_v = common.current_arrays(env)
    if np.any(np.abs(current_v) > 1e-12 * (1.0 + np.abs(current_u))):
        raise CaseError(
            "environment.current.direction_deg: the planar model needs a current along x "
            "(0 or 180 deg); use model: rigid_segments_3d for other directions"
        )
    params = common.typed(
        pc.ChainParams,
        dict(
            n=n,
            length=lengths,
            mass=mass,
            inertia=mass * lengths**2 / 12.0,
            wet_weight=props.wet_weight,
            buoyancy=props.buoyancy,
            drag_normal=0.5 * rho * cable.drag_coefficient_normal * cable.diameter * lengths,
            drag_tangential=common.tangential_drag(cable, rho, lengths),
            joint_stiffness=common.joint_stiffness(cable, lengths),
            joint_damping=common.per_joint(cable.joint_damping, n),
            top_reference_angle=math.radians(cable.top_reference_angle_deg),
            current_z=current_z,
            current_u=current_u,
            top_kind=top_kind,
            bottom_kind=bottom_kind,
            stabilization_frequency=case.simulation.constraint_stabilization_frequency,
            **tfn.kernel_fields([*top_channels, top_force, fx, fz], case.simulation.build_up),
            **top_fields,
            **bottom_fields,
        ),
    )
    y0 = np.zeros(pc.state_size(n))
    y0[:n] = angles
    y0[n] = heave[0]
    y0[2 * n + 1] = heave[1]
    return PlanarSystem(params=params, y0=y0, n_links=n, diameter=cable.diameter)


def _xz(point):
    if point is None:
        return None
    x, _, z = schema.xyz(point)
    return (x, z)


# ---- what a run of this model records (names, dims, units, long names) ---------------------------
VARIABLES = {
    "angle": (("time", "segment"), "rad", "link angle from the downward vertical, positive to +x"),
    "angular_velocity": (("time", "segment"), "rad/s", "link angular velocity"),
    "node_x": (("time", "node"), "m", "node position x"),
    "node_z": (("time", "node"), "m", "node elevation z (up, 0 at the still-water surface)"),
    "tension": (("time", "segment"), "N", "axial tension at the link centre (positive pulling)"),
    "top_force_x": (("time",), "N", "force of the cable on its top attachment, x"),
    "top_force_z": (("time",), "N", "force of the cable on its top attachment, z"),
    "bottom_force_x": (("time",), "N", "force of the cable on its bottom body or anchor, x"),
    "bottom_force_z": (("time",), "N", "force of the cable on its bottom body or anchor, z"),
    "top_heave": (("time",), "m", "elevation of the top attachment (floating structure heave)"),
    "top_heave_velocity": (("time",), "m/s", "vertical velocity of the top attachment"),
    "kinetic_energy": (("time",), "J", "kinetic energy of links, bodies and structure"),
    "gravity_potential_energy": (("time",), "J", "potential energy of apparent weights (z = 0)"),
    "elastic_energy": (("time",), "J", "energy stored in joint springs, heave spring and ties"),
    "total_energy": (("time",), "J", "kinetic + gravity potential + elastic energy"),
    "constraint_error": (("time",), "m", "distance of a pinned end from its anchor"),
    "bottom_velocity_x": (("time",), "m/s", "velocity of the bottom end (its body), x"),
    "bottom_velocity_z": (("time",), "m/s", "velocity of the bottom end (its body), z"),
}


def workspace(system: PlanarSystem):
    """Scratch arrays the compiled kernels fill during a run."""
    return pc.make_workspace(system.n_links)


def sizes(system) -> dict:
    return {"segment": system.n_links, "node": system.n_links + 1}


def rows(times, states, system: PlanarSystem, w) -> tuple[dict, int]:
    """Output rows for the given states (compiled), and the first non-zero kernel status."""
    n = system.n_links
    m = len(times)
    node_x = np.empty((m, n + 1))
    node_z = np.empty((m, n + 1))
    tension = np.empty((m, n))
    scalars = np.empty((m, pc.N_SCALARS))
    status = pc.outputs_chunk(times, states, system.params, w, node_x, node_z, tension, scalars)
    out = {
        "time": times,
        "angle": states[:, :n],
        "angular_velocity": states[:, n + 1 : 2 * n + 1],
        "node_x": node_x,
        "node_z": node_z,
        "tension": tension,
    }
    for k, name in enumerate(pc.SCALAR_NAMES):
        out[name] = scalars[:, k]
    return add_total_energy(out), status


NEWTON = False  # the implicit schemes run systems of bodies and lines only


def shortest_segment(system: PlanarSystem) -> float:
    """Shortest link [m]: scales the Newton tolerance of implicit steps."""
    return float(np.min(system.params.length))


DAMPING_ADVICE = common.JOINT_DAMPING_ADVICE  # divergence messages


def state_scale(case: schema.Case, system: PlanarSystem) -> np.ndarray:
    """Typical magnitude of each state (``common.state_scale``): link angles 1 rad, the heave
    of a floating end the cable's length."""
    cable = case.cables[0]
    positions = np.append(np.ones(system.n_links), common.cable_length(cable))
    return common.state_scale(cable, case.environment, positions)


RATE_WHAT = ("link", "angular rate", "rad/s", 0)  # what ``rates`` measures (divergence messages)


def rates(system: PlanarSystem, y) -> np.ndarray:
    """Angular rate of every link [rad/s]."""
    n = system.n_links
    return np.abs(y[n + 1 : 2 * n + 1])


def fastest_frequency(system: PlanarSystem) -> tuple[float, str]:
    """An estimate of the fastest natural frequency [rad/s] and what sets it.

    The fastest motion of a rigid-link chain is the zigzag mode, each link turning about its
    centre against its two joint springs and the tension: omega_i^2 = (2 (k_i + k_{i+1})
    + T l_i) / J_i, with T bounded by the whole apparent weight. Used to warn before an explicit
    run whose step cannot follow it (RK4 is stable up to about 2.8 / omega).
    """
    p = system.params
    tension = float(np.sum(np.abs(p.wet_weight))) + abs(p.body_wet_weight)
    if p.top_kind == pc.TOP_HEAVE:
        tension += abs(p.top_net_weight)
    ties = (p.tie_kx, p.tie_kz) if p.bottom_kind == pc.BOTTOM_FREE else (0.0, 0.0)
    heave = p.top_stiffness / p.top_mass if p.top_kind == pc.TOP_HEAVE else 0.0
    return zigzag_frequency(p, tension, max(ties), p.body_mass, heave)


def zigzag_frequency(p, tension, tie_k, body_mass, heave_rate) -> tuple[float, str]:
    """Shared by the cable models: the zigzag estimate plus ties and heave."""
    joint_k = p.joint_stiffness
    k_next = np.append(joint_k[1:], 0.0)
    w = np.sqrt((2.0 * (joint_k + k_next) + tension * p.length) / p.inertia)
    i = int(np.argmax(w))
    what = f"zigzag of link {i} ({p.length[i]:.3g} m, joint springs and tension)"
    candidates = [(float(w[i]), what)]
    if tie_k > 0 and body_mass > 0:
        candidates.append((math.sqrt(tie_k / body_mass), f"bottom ties ({tie_k:.4g} N/m)"))
    if heave_rate > 0:
        candidates.append((math.sqrt(heave_rate), "floating structure heave"))
    return max(candidates)


def coords(system: PlanarSystem) -> dict:
    lengths = system.params.length
    arc = np.concatenate([[0.0], np.cumsum(lengths)])
    return {
        "segment": (
            "segment",
            np.arange(system.n_links, dtype=float),
            "1",
            "link index (0 at the top)",
        ),
        "node": (
            "node",
            np.arange(system.n_links + 1, dtype=float),
            "1",
            "node index (0 at the top)",
        ),
        "arc_length": ("node", arc, "m", "unstretched arc length of the node from the top"),
        "link_length": ("segment", lengths.copy(), "m", "link length"),
    }
