"""Extensible lumped-mass cable (Poth 2002, displacement variables): parameters, initial state,
outputs. See ``kernels.lumped`` for the equations."""

import math
from dataclasses import dataclass

import numpy as np

from seacable import timefunctions as tfn
from seacable.case import schema
from seacable.errors import CaseError
from seacable.kernels import lumped as lk
from seacable.kernels import lumped_newton as lkn
from seacable.kernels import lumped_outputs as lko
from seacable.lines import catenary
from seacable.models import common, planar_rigid_links, statics
from seacable.models import rigid_segments_3d as seg
from seacable.models.common import (
    add_total_energy,
    current_arrays,
    joint_stiffness,
    section,
    shape_width,
    tangential_drag,
    typed,
    xyz_variables,
)
from seacable.numerics import stiff


@dataclass(frozen=True)
class LumpedSystem:
    params: lk.LumpedParams
    y0: np.ndarray
    n_links: int
    diameter: float


def _check(cable: schema.Cable) -> None:
    where = "cables[0]"
    if cable.axial_stiffness is None:
        raise CaseError(f"{where}.axial_stiffness: a lumped-mass cable needs EA [N]")
    bottom = cable.bottom
    if cable.joint_damping:
        raise CaseError(
            f"{where}.joint_damping: the lumped-mass model has bending stiffness but no bending "
            "damping; remove joint_damping (axial_damping_time or axial_damping_ratio damps the "
            "axial law)"
        )
    if cable.initial.shape == "static":
        raise CaseError(f"{where}.initial: use shape 'catenary' for a lumped-mass cable")
    if cable.initial.shape == "catenary" and not isinstance(
        bottom, schema.PinnedBottom | schema.TrajectoryBottom
    ):
        raise CaseError(
            f"{where}.initial: shape 'catenary' needs a pinned bottom with an anchor or a "
            "trajectory (it ends on the target at t = 0)"
        )


def build(case: schema.Case, base_dir=None) -> LumpedSystem:
    cable = case.cables[0]
    _check(cable)
    env = case.environment
    n = cable.links
    props = section(case)
    lengths, mass, rho = props.lengths, props.mass, props.rho
    node_mass = np.zeros(n + 1)
    node_mass[:-1] += 0.5 * mass
    node_mass[1:] += 0.5 * mass
    node_length = np.zeros(n + 1)
    node_length[:-1] += 0.5 * lengths
    node_length[1:] += 0.5 * lengths
    seabed = env.seabed
    depth = env.water_depth
    if seabed is not None and depth is None:
        raise CaseError("environment.seabed: give environment.water_depth [m] for the seabed")
    top_kind, top_fields, channels, heave = seg._top(cable, base_dir)
    # the 3D model's reading of the lower end: its kinds and channels are shared
    width = shape_width(case)
    bottom_kind, fields, bottom_channels = seg._bottom(cable, env, base_dir, width)
    keys = ("body_mass", "body_wet_weight", "body_drag", "tie_k", "tie_c", "constrained")
    servo = ("servo_stiffness", "servo_gain", "servo_rate_gain", "servo_step")
    bottom_fields = {k: fields[k] for k in (*keys, "target_relative", *servo)}
    ordered = [*channels[:4], *bottom_channels[:3], channels[4], *bottom_channels[3:6]]
    current_z, current_u, current_v = current_arrays(env)
    point_mass, point_weight, point_drag, surface_fields = seg._point_bodies(
        cable, env, n, width, fields.get("end_body")
    )
    point_mass[n] += bottom_fields["body_mass"]
    params = typed(
        lk.LumpedParams,
        dict(
            n=n,
            length=lengths,
            node_mass=node_mass,
            added_mass=props.added_mass,
            wet_weight=props.wet_weight,
            buoyancy=props.buoyancy,
            axial_stiffness=cable.axial_stiffness,
            segment_stiffness=np.full(n, cable.axial_stiffness),
            axial_damping=cable.axial_damping_times(),
            slack_allowed=1,
            drag_normal=0.5 * rho * cable.drag_coefficient_normal * cable.diameter * lengths,
            drag_tangential=tangential_drag(cable, rho, lengths),
            current_z=current_z,
            current_u=current_u,
            current_v=current_v,
            seabed_z=-depth if (seabed is not None and depth is not None) else -1e30,
            seabed_stiffness=(seabed.stiffness if seabed else 0.0) * node_length,
            seabed_damping=(seabed.damping if seabed else 0.0) * node_length,
            seabed_friction=seabed.friction_coefficient if seabed else 0.0,
            seabed_slip_speed=seabed.slip_speed if seabed else 0.01,
            top_kind=top_kind,
            **{k: top_fields[k] for k in ("top_x", "top_y", "top_mass", "top_stiffness")},
            **{k: top_fields[k] for k in ("top_damping", "top_rest_z", "top_net_weight")},
            track_origin=top_fields["track_origin"],
            track_heading=top_fields["track_heading"],
            track_turn_at=top_fields["track_turn_at"],
            track_radius=top_fields["track_radius"],
            bottom_kind=bottom_kind,
            pin=np.zeros(3),
            tie_rest=np.zeros(3),
            point_mass=point_mass,
            **surface_fields,
            point_weight=point_weight,
            point_drag=point_drag,
            bend_stiffness=_bend_stiffness(cable, lengths),
            **tfn.kernel_fields(ordered, case.simulation.build_up),
            **bottom_fields,
        ),
    )
    y0, params = _initial_state(case, params, heave)
    return LumpedSystem(params=params, y0=y0, n_links=n, diameter=cable.diameter)


def _bend_stiffness(cable: schema.Cable, lengths: np.ndarray) -> np.ndarray:
    """k_i = EI / mean span at interior nodes 1..n-1 (joint_stiffness: its entries 1..n-1;
    the top and the end are pins)."""
    k = np.zeros(len(lengths) + 1)
    k[1:-1] = joint_stiffness(cable, lengths)[1:]
    return k


def _initial_state(case, params, heave):
    """The initial state, and the parameters completed from it (the pin, the ties' rest, the
    servo's step and stiffness)."""
    y0, params = _initial_nodes(case, params, heave)
    if params.bottom_kind != lk.BOTTOM_SERVO:
        return y0, params
    params = params._replace(servo_step=seg.servo_step(case))
    stiffness, force = end_stiffness(params, y0, 0.0, seg.end_servo(case).sphere_radius)
    params = params._replace(servo_stiffness=np.ascontiguousarray(stiffness))
    return np.concatenate([y0, force]), params


def _initial_nodes(case, params, heave):
    cable = case.cables[0]
    n = params.n
    y = np.zeros(lk.state_size(n))
    y[2], y[3 * (n + 1) + 2] = heave  # a floating structure's initial heave (else unused)
    top, vel, _ = lk.top_state(0.0, y, params)
    y0 = np.zeros(lk.state_size(n))
    trajectory = isinstance(cable.bottom, schema.TrajectoryBottom)
    target = lk.target_state(0.0, y, params)[0] if trajectory else None
    if cable.initial.shape == "catenary":
        if trajectory:
            anchor = target
        elif cable.bottom.anchor is None:
            raise CaseError("cables[0].bottom.anchor: shape 'catenary' needs the anchor [x, y, z]")
        else:
            anchor = np.array(schema.xyz(cable.bottom.anchor), float)
        nodes = catenary_nodes(params, top, anchor, case.environment)
    else:
        angles = cable.initial.angles(n)
        directors = seg.directors_from_angles(angles, math.radians(cable.initial.azimuth_deg))
        nodes = np.vstack([top, top + np.cumsum(params.length[:, None] * directors, axis=0)])
        if isinstance(cable.bottom, schema.PinnedBottom) and cable.bottom.anchor is not None:
            gap = float(np.linalg.norm(np.array(schema.xyz(cable.bottom.anchor)) - nodes[-1]))
            if gap > 1e-3:
                raise CaseError(
                    f"cables[0].bottom.anchor: {gap:.3f} m from the end of the initial shape; "
                    "use initial: {shape: catenary}"
                )
        if trajectory and np.linalg.norm(target - nodes[-1]) > 1e-3:
            raise CaseError(
                f"cables[0].bottom: the trajectory starts "
                f"{np.linalg.norm(target - nodes[-1]):.3f} m from the end of the initial shape "
                f"at {np.round(nodes[-1], 3).tolist()}; change the shape or use initial: "
                "{shape: catenary} (it ends on the target)"
            )
    y0[: 3 * (n + 1)] = nodes.ravel()
    y0[3 * (n + 1) :] = np.tile(vel, n + 1)
    params = params._replace(pin=np.ascontiguousarray(nodes[-1]))
    if lk.is_held(params):  # the held axes start with their target's velocity
        velocity = lk.target_state(0.0, y0, params)[1]
        held = params.constrained != 0.0
        y0[3 * (n + 1) + 3 * n :][held] = velocity[held]
        _blend_velocities(y0, params)
    rest = seg._explicit_rest(cable)
    params = params._replace(tie_rest=np.ascontiguousarray(nodes[-1] if rest is None else rest))
    if cable.initial.shape == "catenary":
        y0 = discrete_equilibrium(_held(params, 0.0, y0), y0)
    return y0, params


def _blend_velocities(y0, params) -> None:
    """A line held at both ends starts with velocities that go linearly, along its unstretched
    length, from the top's to the held end's (in place): a moving top over an anchor would
    otherwise start every node but the anchored one at the top's velocity, a jump in the last
    segment's strain rate that its axial damping turns into a force spike at t = 0."""
    n = params.n
    velocities = y0[3 * (n + 1) : 6 * (n + 1)].reshape(n + 1, 3)
    along = np.concatenate([[0.0], np.cumsum(params.length)]) / np.sum(params.length)
    top, end = velocities[0].copy(), velocities[-1].copy()
    velocities[:] = top + along[:, None] * (end - top)


def _held(params, time, y):
    """A servo end's cable held exactly on its target at ``time`` (its static problems);
    other cables as they are."""
    if params.bottom_kind != lk.BOTTOM_SERVO:
        return params
    held = params._replace(bottom_kind=lk.BOTTOM_PINNED, constrained=np.ones(3))
    target = lk.target_state(time, y, params)[0]
    return held._replace(pin=np.ascontiguousarray(target, dtype=float))


def end_force(params, y, point, time: float = 0.0):
    """Force a holder must apply to the end to keep it at ``point`` with every node moving with
    the top's velocity at ``time`` (the steady state: at rest, or towed), and that state:
    the line's discrete equilibrium from ``y``'s shape, its end moved to ``point`` with a
    displacement that grows along the line (strains stay small)."""
    n = params.n
    nq = 3 * (n + 1)
    held = _held(params, time, y)._replace(pin=np.ascontiguousarray(point, dtype=float))
    if held.bottom_kind != lk.BOTTOM_PINNED:
        held = held._replace(bottom_kind=lk.BOTTOM_PINNED, constrained=np.ones(3))
    start = y[: 2 * nq].copy()
    nodes = start[:nq].reshape(n + 1, 3)
    arc = np.concatenate([[0.0], np.cumsum(params.length)]) / params.length.sum()
    nodes += arc[:, None] * (np.asarray(point, float) - nodes[-1])[None, :]
    start[nq:] = np.tile(lk.top_state(time, start, held)[1], n + 1)
    state = discrete_equilibrium(held, start)
    w = lk.make_workspace(n)
    scalars = np.empty(lk.N_SCALARS)
    lko.outputs(time, state, held, w, np.empty((n + 1, 3)), np.empty(n), scalars)
    return -scalars[3:6], state


def end_stiffness(params, y, time: float, radius: float):
    """Stiffness K [N/m] of the end and the force F0 holding it at its target at ``time``:
    equilibria with the end on a sphere of ``radius`` around the target, linearised by least
    squares (Jacquot & Marichal, section 4; as ``statics.end_stiffness`` for rigid segments)."""
    centre = lk.target_state(time, y, params)[0]
    f0, state = end_force(params, y, centre, time)
    displacements = radius * statics.sphere_directions()
    forces = np.array([end_force(params, state, centre + d, time)[0] for d in displacements])
    k_transposed, *_ = np.linalg.lstsq(displacements, forces - f0, rcond=None)
    return k_transposed.T, f0


def discrete_equilibrium(params, y0, iterations=30):
    """Newton iterations on the node positions until every node is at rest in balance: the
    chords through the continuous catenary are a little short where it bends, so the discrete
    line's equilibrium differs slightly from it. Each iteration solves the block-tridiagonal
    stiffness system of the implicit integrators (O(n)). A nearly inextensible line (a large
    EA) makes Newton's steps erratic, so EA is raised to its value in steps of ten from a
    thousandth of it, each stage starting from the last one's equilibrium."""
    # the linear law (compression allowed) makes the problem smooth; a catenary's equilibrium
    # has every segment in tension, so it is also the equilibrium of the slack law
    target = params.axial_stiffness
    y = y0.copy()
    for stiffness in (1e-3 * target, 1e-2 * target, 1e-1 * target, target):
        stage = params._replace(
            slack_allowed=0,
            axial_stiffness=stiffness,
            segment_stiffness=np.full(params.n, stiffness),
        )
        y = _newton_equilibrium(stage, y, iterations)
    return y


def _newton_equilibrium(params, y0, iterations):
    n = params.n
    w = lk.make_workspace(n)
    ydot = np.zeros_like(y0)
    nq = 3 * (n + 1)
    at_rest = np.zeros(nq)
    diag, upper, lower = np.empty((n + 1, 9)), np.empty((n, 9)), np.empty((n, 9))
    res, step = np.empty(nq), np.empty(nq)

    def residual(y):
        # with zero wanted acceleration, res = -F per node (prescribed nodes: 0); the matrix
        # (cm = 0, cx = 1, cv = 0) is -dF/dx
        lkn.newton_system(0.0, y, at_rest, params, w, ydot, 0.0, 1.0, 0.0, diag, upper, lower, res)
        return res.copy()

    def stretched(y):
        # the linear law has folded equilibria (a compressed segment between two pulling
        # ones): a step into compression is not taken
        chords = np.diff(y[:nq].reshape(n + 1, 3), axis=0)
        return bool(np.all(np.linalg.norm(chords, axis=1) >= params.length))

    y = y0.copy()
    r = residual(y)
    scale = float(np.abs(r).max()) + 1.0
    best, best_norm = y, np.linalg.norm(r)
    for _ in range(iterations):
        if np.abs(r).max() < 1e-9 * scale:
            break
        if not lkn.block_tridiagonal_solve(diag, upper, lower, r, step):
            break
        candidates = [(d, True) for d in (1.0, 0.5, 0.25, 0.1)]
        # when no shorter step lowers the residual (erratic Newton steps on a stiff line), the
        # longest one that keeps every segment stretched is taken anyway
        candidates += [(0.5**k, False) for k in range(12)]
        for damping, must_lower in candidates:
            trial = y.copy()
            trial[:nq] -= damping * step
            if not stretched(trial):
                continue
            rt = residual(trial)
            if not must_lower or np.linalg.norm(rt) < np.linalg.norm(r):
                break
        else:
            break
        y, r = trial, rt
        if np.linalg.norm(r) < best_norm:
            best, best_norm = y, np.linalg.norm(r)
        residual(y)  # the matrix at the accepted point
    return best


def catenary_nodes(params, top, anchor, env) -> np.ndarray:
    """Node positions (top first) on the elastic catenary from ``anchor`` to ``top``."""
    length = float(params.length.sum())
    w = float(params.wet_weight.sum()) / length
    seabed = env.seabed is not None and env.water_depth is not None
    on_seabed = seabed and abs(anchor[2] + env.water_depth) < 1e-6
    span_vector = top[:2] - anchor[:2]
    span = float(np.hypot(*span_vector))
    rise = float(top[2] - anchor[2])
    try:
        h, v_f = catenary.solve(span, rise, length, w, params.axial_stiffness, on_seabed)
    except catenary.CatenaryError as exc:
        raise CaseError(f"cables[0].initial: {exc}") from None
    s_top = np.concatenate([[0.0], np.cumsum(params.length)])
    x, z = catenary.profile(length - s_top, h, v_f, length, w, params.axial_stiffness, on_seabed)
    direction = span_vector / span if span > 0 else np.zeros(2)
    nodes = np.empty((params.n + 1, 3))
    nodes[:, 0] = anchor[0] + x * direction[0]
    nodes[:, 1] = anchor[1] + x * direction[1]
    nodes[:, 2] = anchor[2] + z
    if on_seabed:
        # nodes lying on the seabed start at the penetration that carries their weight
        sink = w / env.seabed.stiffness
        lying = (np.abs(z) < 1e-9) & (np.arange(params.n + 1) < params.n)
        nodes[lying, 2] -= sink
    return nodes


VARIABLES = {
    **{f"node_{a}": (("time", "node"), "m", f"node position, {a}") for a in "xyz"},
    "tension": (("time", "segment"), "N", "axial tension of the segment (no compression)"),
    **{
        f"top_force_{a}": (("time",), "N", f"force of the cable on its top attachment, {a}")
        for a in "xyz"
    },  # fmt: skip
    **{
        f"bottom_force_{a}": (
            ("time",),
            "N",
            f"force of the cable on its bottom body or anchor, {a}",
        )
        for a in "xyz"
    },  # fmt: skip
    "kinetic_energy": (("time",), "J", "kinetic energy (added mass included)"),
    "gravity_potential_energy": (("time",), "J", "potential energy of apparent weights"),
    "elastic_energy": (("time",), "J", "axial strain energy and seabed springs"),
    "total_energy": (("time",), "J", "kinetic + gravity potential + elastic energy"),
    "tracking_error": (("time",), "m", "distance of a trajectory end from its target"),
    **xyz_variables("target", ("time",), "m", "target of the lower end (trajectory)"),
    **xyz_variables("servo_force", ("time",), "N", "force the servo applies to the cable end"),
}


RATE_WHAT = ("node", "speed", "m/s", 1)  # what ``rates`` measures (divergence messages)
NEWTON = False  # the implicit schemes run systems of bodies and lines only


def shortest_segment(system: LumpedSystem) -> float:
    return float(system.params.length.min())


sizes = planar_rigid_links.sizes  # the same dimensions: segment, node


def workspace(system: LumpedSystem):
    return lk.make_workspace(system.n_links)


def coords(system) -> dict:
    return seg.coords(system)


def rows(times, states, system: LumpedSystem, w) -> tuple[dict, int]:
    n = system.n_links
    m = len(times)
    nodes = np.empty((m, n + 1, 3))
    tension = np.empty((m, n))
    scalars = np.empty((m, lk.N_SCALARS))
    status = lko.outputs_chunk(times, states, system.params, w, nodes, tension, scalars)
    out = {"time": times, "tension": tension}
    for c, a in enumerate("xyz"):
        out[f"node_{a}"] = nodes[:, :, c]
    for k, name in enumerate(lk.SCALAR_NAMES):
        out[name] = scalars[:, k]
    return add_total_energy(out), status


DAMPING_ADVICE = common.AXIAL_DAMPING_ADVICE  # divergence messages


def state_scale(case: schema.Case, system: LumpedSystem) -> np.ndarray:
    """Typical magnitude of each state (``common.state_scale``): node coordinates the cable's
    length, a servo force the cable's weight."""
    cable = case.cables[0]
    nodes = 3 * (system.n_links + 1)
    positions = np.full(nodes, common.cable_length(cable))
    return common.state_scale(cable, case.environment, positions, len(system.y0) - 2 * nodes)


def rates(system: LumpedSystem, y) -> np.ndarray:
    """Speed of every node but the top [m/s] (the 'where' of a divergence message)."""
    n = system.n_links
    return np.linalg.norm(y[3 * (n + 1) : 6 * (n + 1)].reshape(n + 1, 3), axis=1)[1:]


def fastest_frequency(system: LumpedSystem) -> tuple[float, str]:
    """Fastest axial mode of the shortest segment between two nodes: 2 sqrt(EA / (m l))."""
    p = system.params
    mass = np.minimum(p.node_mass[:-1], p.node_mass[1:]) + 0.5 * p.added_mass
    omega = 2.0 * np.sqrt(p.axial_stiffness / (mass * p.length))
    i = int(np.argmax(omega))
    return float(
        omega[i]
    ), f"axial waves on segment {i} ({p.length[i]:.3g} m, EA {p.axial_stiffness:.3g} N)"


def node_block(system: LumpedSystem) -> int | None:
    """Variables per node: the stiff integrators' Jacobian is node-neighbour structured (not
    with a servo's force, which couples to the end: a dense Jacobian)."""
    return None if system.params.bottom_kind == lk.BOTTOM_SERVO else 3


def node_graph(system: LumpedSystem) -> list[np.ndarray]:
    """Node neighbours of the stiff integrators' Jacobian: one chain, reaching two nodes with
    bending (a node's bending force comes from the angles at its neighbours)."""
    reach = 2 if np.any(system.params.bend_stiffness > 0.0) else 1
    return stiff.chain_graph(system.n_links + 1, reach)


def positions(system: LumpedSystem) -> int:
    """Position variables of the state; the velocities follow, then a servo's force."""
    return 3 * (system.n_links + 1)


refresh_interval = seg.refresh_interval


def refresh(case: schema.Case, params, time: float, y):
    """Parameters for the next stretch of the run: the servo's stiffness K recomputed about the
    target at ``time``, from the line's current shape."""
    radius = seg.end_servo(case).sphere_radius
    stiffness, _ = end_stiffness(params, y, time, radius)
    return params._replace(servo_stiffness=np.ascontiguousarray(stiffness))
