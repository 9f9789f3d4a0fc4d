"""A validated SystemCase turned into the flat SystemParams and the initial state: names
resolved to indices, offsets laid out (system.kernel's state layout), force models packed, line
sections cut into segments, time functions compiled into channels."""

import math
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import numpy as np

from seacable import packing
from seacable import timefunctions as tfn
from seacable.bodies import dynamics, kinematics
from seacable.case import system as sch
from seacable.case.base import ORIGIN, AccelerationPhase, AccelerationProfile, Constant
from seacable.case.schema import VolumeTable, per_axis
from seacable.errors import CaseError
from seacable.kernels import surface
from seacable.packing import channel, current_arrays, shape_row, transported, typed
from seacable.system import failures, hulls, kernel, natural_lines, topology, variants
from seacable.system.force_rows import (
    compensator_rows,
    force_row,
    force_table,
    in_radians,
    offset,
    rods_added_mass,
)
from seacable.system.kernel import SystemParams

KIND = {"fixed": kinematics.FIXED, "imposed": kinematics.IMPOSED}
SEGMENTS_3D, PLANAR = 0, 1  # rigid-line models (SystemParams.rs_kind)
CORIOLIS = {"rigid_body": dynamics.RIGID_BODY, "exact": dynamics.EXACT}
INT_FIELDS = frozenset({
    "body_kind", "body_rigid", "body_coriolis", "body_q", "body_v", "body_channel",
    "body_motion", "body_parent",
    "point_body", "force_kind", "force_body", "force_at", "force_first", "force_state",
    "line_n", "line_seg", "line_node", "line_q", "line_v", "line_from", "line_to", "tie_from",
    "tie_to", "tie_first", "tie_count",
    "rs_n", "rs_seg", "rs_node", "rs_q", "rs_v", "rs_from", "rs_to", "rs_tip", "rs_order",
    "rs_kind", "rs_port", "nat_n", "nat_q", "nat_v", "nat_from", "nat_tip", "nat_cartesian",
    "body_group", "group_first", "group_member", "joint", "compensator", "entries",
    *failures.INT_FIELDS,
})  # fmt: skip


@dataclass
class Layout:
    """Where each component lives: names in case order, state offsets, points."""

    bodies: list[str] = field(default_factory=list)
    lines: list[str] = field(default_factory=list)  # lumped-mass lines
    rigid: list[str] = field(default_factory=list)  # rigid-segment lines
    ties: list[str] = field(default_factory=list)
    natural: list[str] = field(default_factory=list)  # natural-variables strings
    points: list[tuple[int, str]] = field(default_factory=list)  # (body, point name)
    point_index: dict = field(default_factory=dict)  # "body.point" -> index
    wind_channel: int = -1  # the wind's speed channel, its direction [rad] next (-1: none)
    facts: dict = field(default_factory=dict)  # how it was built, for the results' attributes


@dataclass(frozen=True)
class BuiltSystem:
    params: SystemParams
    y0: np.ndarray
    layout: Layout
    case: sch.SystemCase


def _parent(case: sch.SystemCase, body: sch.ImposedBody, where: str) -> int:
    """The index of the imposed body ``body`` moves relative to (-1: none)."""
    if body.relative_to is None:
        return -1
    names = [b.name for b in case.bodies]
    name = body.relative_to
    parent = case.bodies[names.index(name)] if name in names else None
    if parent is None or parent is body or not isinstance(parent, sch.ImposedBody):
        what = "names no body" if parent is None else (
            "is the body itself" if parent is body else f"is a {parent.type} body")  # fmt: skip
        raise CaseError(f"{where}.relative_to: '{name}' {what}; an imposed body moves relative "
                        "to another imposed body: name one")  # fmt: skip
    if parent.relative_to is not None:
        raise CaseError(f"{where}.relative_to: '{name}' moves relative to "
                        f"'{parent.relative_to}' itself; give '{body.name}' relative to "
                        f"'{parent.relative_to}' (one level)")  # fmt: skip
    return names.index(name)


def _track(track: sch.Track, base_dir, where: str) -> tuple[tfn.Piecewise, list[float]]:
    """The distance travelled along a track (a channel exempt from the build-up) and its
    kinematics.track_point row."""
    if track.speed is not None:
        distance = tfn.build(AccelerationProfile(
            kind="acceleration_profile", initial_velocity=track.speed,
            phases=[AccelerationPhase(duration=1.0, acceleration=0.0)],
        ))  # fmt: skip
    else:
        distance = channel(track.distance, base_dir, f"{where}.track.distance")
    distance = tfn.steady(distance)
    turn_at, radius = 0.0, 0.0
    if track.turn is not None:
        turn_at = float(tfn.evaluate(distance, track.turn.start_time)[0])
        radius = track.turn.radius * (1.0 if track.turn.side == "left" else -1.0)
    row = [*track.start, math.radians(track.heading_deg), turn_at, radius]
    return distance, row


def _point(case: sch.SystemCase, layout: Layout, ref: str, where: str) -> int:
    """Index of the point ``body`` or ``body.point`` (created on first use)."""
    if ref in layout.point_index:
        return layout.point_index[ref]
    body_name, _, point_name = ref.partition(".")
    names = layout.bodies
    if body_name not in names:
        raise CaseError(
            f"{where}: '{ref}' names no body; bodies are {names} (write 'body' or 'body.point')"
        )
    b = names.index(body_name)
    body = case.bodies[b]
    point_name = point_name or ORIGIN
    if point_name != ORIGIN and point_name not in body.points:
        raise CaseError(
            f"{where}: body '{body_name}' has no point '{point_name}'; its points are "
            f"{[ORIGIN, *body.points]}"
        )
    layout.point_index[ref] = len(layout.points)
    layout.points.append((b, point_name))
    return layout.point_index[ref]


def _orientation(body) -> tuple[float, float, float, float]:
    roll, pitch, yaw = (math.radians(a) for a in getattr(body, "orientation_deg", (0, 0, 0)))
    return kinematics.euler_quaternion(roll, pitch, yaw)


def build(case: sch.SystemCase, base_dir=None) -> BuiltSystem:
    """The parameters and start state of ``case``; the built system's case holds a point body
    per failure (system.failures)."""
    case = failures.derived(case)
    env = case.environment
    rho = 0.0 if env.in_air else env.water_density
    layout = Layout(bodies=[b.name for b in case.bodies])
    point = partial(_point, case, layout)  # (ref, where) -> the point's index
    channels: list[tfn.Piecewise] = []
    nb = len(case.bodies)
    tables = [
        len(b.shape.submerged_volume) for b in case.bodies
        if isinstance(b, sch.PointBody | sch.RigidBody) and isinstance(b.shape, VolumeTable)
    ]  # fmt: skip
    width = surface.HEADER + 2 * max(tables or [0])
    f: dict[str, list] = {k: [] for k in ("kind", "body", "at", "first", "state")}
    data: list[float] = []
    arrays = {
        "body_kind": np.zeros(nb), "body_rigid": np.zeros(nb), "body_q": -np.ones(nb),
        "body_v": -np.ones(nb), "body_channel": -np.ones(nb), "body_motion": np.zeros(nb),
        "body_track": np.zeros((nb, 5)), "body_parent": -np.ones(nb),
        "body_pose": np.zeros((nb, 7)),
        "body_mass": np.zeros(nb), "body_cog": np.zeros((nb, 3)),
        "body_inertia": np.zeros((nb, 3, 3)), "body_added": np.zeros((nb, 6, 6)),
        "body_coriolis": np.zeros(nb), "body_free": np.zeros((nb, 6)), "body_volume": np.zeros(nb),
        "body_cob": np.zeros((nb, 3)), "body_shape": np.zeros((nb, width)),
    }  # fmt: skip
    if env.wind is not None:  # exempt from the build-up, as the current
        layout.wind_channel = len(channels)
        channels.append(tfn.steady(channel(env.wind.speed, base_dir, "environment.wind.speed")))
        channels.append(tfn.steady(in_radians(channel(env.wind.direction_deg, base_dir,
                                                "environment.wind.direction_deg"))))  # fmt: skip
    tips = topology.rigid_tips(case)
    carried = set(tips) | natural_lines.tips(case)  # no state: a line's end carries them
    q_at = v_at = n_s = 0  # n_s: the force models' states
    y_q: list[float] = []
    y_v: list[float] = []
    for b, body in enumerate(case.bodies):
        where = f"bodies[{b}] ({body.name})"
        arrays["body_shape"][b] = shape_row(getattr(body, "shape", None), width)
        arrays["body_pose"][b, 3] = 1.0
        if isinstance(body, sch.FixedBody):
            arrays["body_pose"][b] = [*body.position, *_orientation(body)]
            continue
        if isinstance(body, sch.ImposedBody):
            arrays["body_kind"][b] = kinematics.IMPOSED
            arrays["body_channel"][b] = len(channels)
            for axis in ("x", "y", "z"):
                channels.append(channel(getattr(body, axis), base_dir, f"{where}.{axis}"))
            for angle in ("roll_deg", "pitch_deg", "yaw_deg"):
                channels.append(
                    in_radians(channel(getattr(body, angle), base_dir, f"{where}.{angle}"))
                )
                if getattr(body, angle) != Constant(value=0.0):
                    arrays["body_motion"][b] = kinematics.TURNS
            arrays["body_parent"][b] = _parent(case, body, where)
            if body.track is not None:
                arrays["body_motion"][b] = kinematics.TRACK
                distance, arrays["body_track"][b] = _track(body.track, base_dir, where)
                channels[int(arrays["body_channel"][b])] = distance
            continue
        rigid = isinstance(body, sch.RigidBody)
        arrays["body_kind"][b] = kinematics.TIP if b in carried else kinematics.DYNAMIC
        arrays["body_rigid"][b] = 1 if rigid else 0
        if b not in carried:
            arrays["body_q"][b], arrays["body_v"][b] = q_at, v_at
        arrays["body_mass"][b] = body.mass
        arrays["body_volume"][b] = body.displaced_volume()
        free = [1.0 if name in body.dofs else 0.0 for name in sch.DOF_NAMES]
        if getattr(body, "pinned_to", None) is not None:  # its joint moves it
            free[:3] = [1.0, 1.0, 1.0]
        arrays["body_free"][b] = free
        velocity = [v * free[c] for c, v in enumerate(body.velocity)]
        if isinstance(body, sch.RigidBody):
            quaternion = _orientation(body)
            y_q += [*body.position, *quaternion]
            omega = [w * free[3 + c] for c, w in enumerate(body.angular_velocity)]
            y_v += [*velocity, *omega]
            arrays["body_cog"][b] = body.centre_of_gravity
            arrays["body_cob"][b] = body.centre_of_buoyancy
            inertia = np.array(body.inertia, dtype=float)
            arrays["body_inertia"][b] = np.diag(inertia) if inertia.ndim == 1 else inertia
            added = np.array(body.added_mass, dtype=float)
            added = np.diag(added) if added.ndim == 1 else added
            arrays["body_added"][b] = transported(added, body.added_mass_point)
            if body.dynamics is not None:  # the ship-simulator document's block
                arrays["body_added"][b], note = hulls.document_added_mass(
                    body, base_dir, where, env.water_density
                )
                points = layout.facts.get("added_mass_point")
                layout.facts["added_mass_point"] = f"{points}\n{note}" if points else note
            if body.hydrodynamics is not None and not np.any(added):  # the database's A_inf
                arrays["body_added"][b] = hulls.database_added_mass(body, base_dir, where, env)
            arrays["body_coriolis"][b] = CORIOLIS[body.coriolis]
            q_at, v_at = q_at + 7, v_at + 6
        else:
            arrays["body_added"][b, :3, :3] = np.diag(
                np.zeros(3) if env.in_air else np.array(per_axis(body.added_mass), float)
            )
            if b in carried:  # no state: the line's tip carries it; held axes stay here
                arrays["body_pose"][b, :3] = body.position
            else:
                y_q += list(body.position)
                y_v += velocity
                q_at, v_at = q_at + 3, v_at + 3
        row_of = partial(force_row, case, layout, body=body, rho=rho, base_dir=base_dir,
                         channels=channels, point=point)  # fmt: skip
        n_s = force_table(body, b, row_of, arrays["body_added"][b], f, data, n_s, where)
        arrays["body_added"][b] += rods_added_mass(body, rho)
    hulls.memory_offsets(f["kind"], f["at"], data)
    bodies_q, bodies_v = q_at, v_at
    lines = _lines(case, layout, rho, q_at, v_at)
    q_at += lines.pop("interior_q")
    v_at += lines.pop("interior_v")
    rigid_lines = _rigid_lines(case, layout, rho, q_at, v_at, tips, arrays["body_free"])
    n_q = q_at + rigid_lines.pop("directors")
    n_v = v_at + rigid_lines.pop("rates")
    strings, string_q = natural_lines.table(case, layout, point, n_q, n_v)
    strings["nat_v"] = strings["nat_v"] + n_q + len(string_q)  # absolute, as below
    first_string = n_q
    n_q, n_v = n_q + len(string_q), n_v + len(string_q)
    # velocity offsets are absolute: after every position
    arrays["body_v"] = np.where(arrays["body_v"] >= 0, arrays["body_v"] + n_q, -1)
    lines["line_v"] = lines["line_v"] + n_q
    rigid_lines["rs_v"] = rigid_lines["rs_v"] + n_q
    f["state"] = [s + n_q + n_v if s >= 0 else -1 for s in f["state"]]
    ties = _ties(case, layout)
    released = failures.fields(case, point)  # creates the failures' points
    joint = topology.joint_points(case, tips, point)  # and the joints'
    points = np.array([b for b, _ in layout.points], dtype=np.int64)
    offsets = np.array([offset(case.bodies[b], name) for b, name in layout.points]).reshape(-1, 3)
    current_z, current_u, current_v = current_arrays(env)
    seabed = env.seabed
    fields: dict[str, Any] = dict(
        n_q=n_q, n_v=n_v, n_s=n_s, **arrays, point_body=points, point_offset=offsets,
        force_kind=f["kind"], force_body=f["body"], force_at=f["at"], force_first=f["first"],
        force_state=f["state"], **strings,
        force_data=np.array(data + [0.0]), **lines, **rigid_lines, **ties, slack_allowed=1,
        stabilization_frequency=case.simulation.constraint_stabilization_frequency,
        gravity=env.gravity, rho=rho,
        seabed_z=-env.water_depth if (seabed and env.water_depth) else -1e30,
        seabed_friction=seabed.friction_coefficient if seabed else 0.0,
        seabed_slip_speed=seabed.slip_speed if seabed else 0.01,
        seabed_band=seabed.contact_band if seabed else 0.0,
        current_z=current_z, current_u=current_u, current_v=current_v,
        **packing.wave_fields(env, case.simulation.build_up), wind_channel=layout.wind_channel,
        **tfn.kernel_fields(channels or [tfn.constant(0.0)], case.simulation.build_up),
        **released, joint=joint,
    )  # fmt: skip
    fields.update(topology.group_arrays(case, tips, nb))
    fields["compensator"] = compensator_rows(case, f, fields, points)
    fields["entries"] = np.zeros(len(kernel.ENTRIES), dtype=np.int64)
    params = variants.bind(typed(SystemParams, fields, INT_FIELDS))
    y0 = np.zeros(n_q + n_v + n_s)
    y0[:bodies_q] = y_q
    y0[n_q : n_q + bodies_v] = y_v
    y0[first_string : first_string + len(string_q)] = string_q
    built = BuiltSystem(params=params, y0=y0, layout=layout, case=case)
    return built


def _sections(case, line, rho, extensible=True):
    """Per-segment arrays of a line from its sections (``extensible``: EA and its damping)."""
    types = {t.name: t for t in case.line_types}
    env = case.environment
    out: dict[str, list] = {k: [] for k in (
        "length", "mass", "stiffness", "damping", "drag_normal", "drag_tangential",
        "wet_weight", "buoyancy", "added_mass", "added_mass_tangential", "bend", "joint_stiffness",
        "joint_damping")}  # fmt: skip
    for k, section in enumerate(line.sections):
        where = f"lines ({line.name}).sections[{k}]"
        if section.type not in types:
            raise CaseError(
                f"{where}.type: no line type '{section.type}'; line_types are {list(types)}"
            )
        t = types[section.type]
        if extensible and t.axial_stiffness is None:
            raise CaseError(
                f"{where}.type: line type '{t.name}' has no axial_stiffness; a lumped-mass line "
                "needs EA [N]"
            )
        n = section.segments
        length = np.full(n, section.length / n)
        mass = t.mass_per_length * length
        area = math.pi * t.diameter**2 / 4
        ea = t.axial_stiffness or math.inf
        if t.axial_damping_ratio is not None:
            alpha = t.axial_damping_ratio * np.sqrt(mass * length / ea)
        else:
            alpha = np.full(n, t.axial_damping_time or 0.0)
        ca = 0.0 if env.in_air else t.added_mass_coefficient
        tangential = math.pi * t.drag_coefficient_tangential
        tangential += t.friction_coefficient * t.drag_coefficient_normal
        out["length"].append(length)
        out["mass"].append(mass)
        out["stiffness"].append(np.full(n, ea))
        out["damping"].append(alpha)
        out["drag_normal"].append(0.5 * rho * t.drag_coefficient_normal * t.diameter * length)
        out["drag_tangential"].append(0.5 * rho * tangential * t.diameter * length)
        out["wet_weight"].append((mass - rho * area * length) * env.gravity)
        out["buoyancy"].append(rho * area * length * env.gravity)
        out["added_mass"].append(ca * rho * area * length)
        along = 0.0 if env.in_air else t.added_mass_coefficient_tangential
        out["added_mass_tangential"].append(along * rho * area * length)
        out["bend"].append(np.full(n, t.bending_stiffness))
        # the section's own joints (NaN: from EI, and the line's damping)
        for key in ("joint_stiffness", "joint_damping"):
            value = getattr(section, key)
            out[key].append(np.full(n, math.nan if value is None else value))
    return {k: np.concatenate(v) for k, v in out.items()}


def _joint_springs(from_bending, given):
    """Each joint's spring [N m/rad]: its section's ``joint_stiffness`` where given, else
    ``from_bending`` (EI over the mean span)."""
    return np.where(np.isnan(given), from_bending, given)


def _lines(case, layout, rho, q_at, v_at) -> dict:
    env = case.environment
    seabed = env.seabed
    keys = ("line_n", "line_seg", "line_node", "line_q", "line_v", "line_from", "line_to")
    out: dict[str, list] = {k: [] for k in keys}
    segs: dict[str, list] = {}
    nodes: dict[str, list] = {k: [] for k in ("mass", "k", "c", "bend")}
    seg_count = node_count = interior_q = interior_v = 0
    for k, line in enumerate(case.lines):
        if not isinstance(line, sch.LumpedMassLine):
            continue
        where = f"lines[{k}] ({line.name})"
        layout.lines.append(line.name)
        props = _sections(case, line, rho)
        n = len(props["length"])
        out["line_n"].append(n)
        out["line_seg"].append(seg_count)
        out["line_node"].append(node_count)
        out["line_q"].append(q_at + interior_q)
        out["line_v"].append(v_at + interior_v)
        out["line_from"].append(_point(case, layout, line.from_, f"{where}.from"))
        out["line_to"].append(_point(case, layout, line.to, f"{where}.to"))
        for name, values in props.items():
            segs.setdefault(name, []).append(values)
        mass = np.zeros(n + 1)
        mass[:-1] += 0.5 * props["mass"]
        mass[1:] += 0.5 * props["mass"]
        span = np.zeros(n + 1)
        span[:-1] += 0.5 * props["length"]
        span[1:] += 0.5 * props["length"]
        bend = np.zeros(n + 1)
        # EI over the mean span of the two segments at each interior node
        mean = 0.5 * (props["length"][1:] + props["length"][:-1])
        bend[1:-1] = _joint_springs(props["bend"][1:] / mean, props["joint_stiffness"][1:])
        if not np.all(np.isnan(props["joint_damping"])):
            raise CaseError(f"{where}.sections: joint_damping is for rigid lines; a "
                            "lumped-mass line's bending has no damper (axial damping damps "
                            "it)")  # fmt: skip
        nodes["mass"].append(mass)
        # the seabed's stiffness and damping on each node's half segments, per metre of line
        # (per its diameter with MoorDyn's per-area form: case.environment.Seabed)
        types = {t.name: t for t in case.line_types}
        per_metre = np.array([
            seabed.per_metre(types[s.type].diameter) if seabed else (0.0, 0.0)
            for s in line.sections for _ in range(s.segments)
        ])  # fmt: skip
        for column, key in enumerate(("k", "c")):
            share = 0.5 * props["length"] * per_metre[:, column]
            on_node = np.zeros(n + 1)
            on_node[:-1] += share
            on_node[1:] += share
            nodes[key].append(on_node)
        nodes["bend"].append(bend)
        seg_count += n
        node_count += n + 1
        interior_q += 3 * (n - 1)
        interior_v += 3 * (n - 1)

    def cat(parts):
        return np.concatenate(parts) if parts else np.zeros(1)

    fields: dict[str, Any] = {k: np.array(v, dtype=np.int64) for k, v in out.items()}
    names = {"length": "seg_length", "stiffness": "seg_stiffness", "damping": "seg_damping",
             "drag_normal": "seg_drag_normal", "drag_tangential": "seg_drag_tangential",
             "wet_weight": "seg_wet_weight", "buoyancy": "seg_buoyancy",
             "added_mass": "seg_added_mass"}  # fmt: skip
    for key, name in names.items():
        fields[name] = cat(segs.get(key, []))
    # (segments, 2): normal and tangential added mass; one row when there is no segment
    tangential = cat(segs.get("added_mass_tangential", []))
    fields["seg_added_mass"] = np.column_stack([fields["seg_added_mass"], tangential])
    fields.update(
        node_mass=cat(nodes["mass"]), node_seabed_stiffness=cat(nodes["k"]),
        node_seabed_damping=cat(nodes["c"]), node_bend=cat(nodes["bend"]),
        interior_q=interior_q, interior_v=interior_v,
    )  # fmt: skip
    return fields


def _ties(case, layout) -> dict:
    out: dict[str, list] = {k: [] for k in (
        "tie_from", "tie_to", "tie_first", "tie_count", "tie_length", "tie_stiffness",
        "tie_damping")}  # fmt: skip
    rows: list = []
    for k, line in enumerate(case.lines):
        if not isinstance(line, sch.Tie):
            continue
        where = f"lines[{k}] ({line.name})"
        layout.ties.append(line.name)
        out["tie_from"].append(_point(case, layout, line.from_, f"{where}.from"))
        out["tie_to"].append(_point(case, layout, line.to, f"{where}.to"))
        table = line.tension_table or []
        out["tie_first"].append(len(rows))
        out["tie_count"].append(len(table))
        rows += table
        out["tie_length"].append(line.unstretched_length)
        out["tie_stiffness"].append(line.stiffness or 0.0)
        out["tie_damping"].append(line.damping)
    fields: dict = {k: np.array(v) for k, v in out.items()}
    fields["tie_table"] = np.array(rows, dtype=float).reshape(-1, 2) if rows else np.zeros((1, 2))
    return fields


def _rigid_lines(case, layout, rho, q_at, v_at, tips, body_free) -> dict:
    """Flat arrays of the rigid-segment lines (system.kernel's ``rs_`` fields); the order of
    their sweeps, children first (a line carried at another's tip before that one)."""
    keys = ("rs_n", "rs_seg", "rs_node", "rs_q", "rs_v", "rs_from", "rs_to", "rs_tip", "rs_kind",
            "rs_port")  # fmt: skip
    ported = {r for r, _, _ in topology.ports(case, tips)}
    out: dict[str, list] = {k: [] for k in keys}
    held: list = []
    ref: list = []
    tip_joints: list = []
    joined: list = []
    segs: dict[str, list] = {k: [] for k in (
        "length", "mass", "added", "inertia", "wet_weight", "buoyancy", "drag_normal",
        "drag_tangential", "joint_stiffness", "joint_damping")}  # fmt: skip
    seg_count = node_count = directors = 0
    for r, (k, line) in enumerate(topology.rigid_lines(case)):
        where = f"lines[{k}] ({line.name})"
        layout.rigid.append(line.name)
        props = _sections(case, line, rho, extensible=False)
        n = len(props["length"])
        lengths = props["length"]
        out["rs_n"].append(n)
        out["rs_seg"].append(seg_count)
        out["rs_node"].append(node_count)
        out["rs_q"].append(q_at + directors)
        out["rs_v"].append(v_at + directors)
        out["rs_from"].append(_point(case, layout, line.from_, f"{where}.from"))
        out["rs_to"].append(_point(case, layout, line.to, f"{where}.to"))
        tip = next((b for b, rr in tips.items() if rr == r), -1)
        out["rs_tip"].append(tip)
        out["rs_port"].append(1 if r in ported else 0)
        planar = line.model == "rigid_links"
        out["rs_kind"].append(PLANAR if planar else SEGMENTS_3D)
        if planar:
            topology.planar_ends(case, line, where, tip)
        held.append(np.ones(3) if tip < 0 else 1.0 - body_free[tip, :3])
        if line.model == "rigid_links":
            held[-1][1] = 0.0  # the plane holds y
        ref.append(
            np.full(3, np.nan)
            if line.base_reference is None
            else np.asarray(line.base_reference, float) / np.linalg.norm(line.base_reference)
        )
        if line.base_reference is not None and not np.linalg.norm(line.base_reference) > 0:
            raise CaseError(f"{where}.base_reference: a direction needs a non-zero length")
        joint = _tip_joint(line, where, -2 if r in ported else tip, r)
        if joint is not None:
            tip_joints.append(joint)
        if line.continues is not None:
            joined.append((r, line, where))
        mass, added = props["mass"], props["added_mass"]
        if np.any(props["added_mass_tangential"] > 0):
            raise CaseError(
                f"{where}.sections: line type of added_mass_coefficient_tangential > 0; the "
                f"{line.model} model has no added mass along its segments: set it to 0, or "
                "use model: lumped_mass"
            )
        if planar and np.any(added > 0):
            raise CaseError(
                f"{where}.sections: line type of added_mass_coefficient > 0 in water; the planar "
                "rigid_links model has no added mass on its links: set the line type's "
                "added_mass_coefficient to 0, or use model: rigid_segments_3d"
            )
        # a joint stands for the bending over the mean span of its two segments; the first
        # joint over the first segment
        span = np.concatenate([[lengths[0]], 0.5 * (lengths[1:] + lengths[:-1])])
        bend = np.concatenate([[props["bend"][0]], 0.5 * (props["bend"][1:] + props["bend"][:-1])])
        damping = props["joint_damping"]
        values = {
            "length": lengths, "mass": mass, "added": added,
            "inertia": (mass + added) * lengths**2 / 12.0, "wet_weight": props["wet_weight"],
            "buoyancy": props["buoyancy"], "drag_normal": props["drag_normal"],
            "drag_tangential": props["drag_tangential"],
            "joint_stiffness": _joint_springs(bend / span, props["joint_stiffness"]),
            "joint_damping": np.where(np.isnan(damping), line.joint_damping, damping),
        }  # fmt: skip
        for key, value in values.items():
            segs[key].append(value)
        seg_count += n
        node_count += n + 1
        directors += (1 if planar else 3) * n
    nr = len(out["rs_n"])
    depth = [topology.depth(case, tips, r) for r in range(nr)]
    order = sorted(range(nr), key=lambda r: -depth[r])  # children first
    fields: dict[str, Any] = {k: np.array(v, dtype=np.int64) for k, v in out.items()}
    fields["rs_order"] = np.array(order, dtype=np.int64)
    fields["rs_held"] = np.array(held, dtype=float).reshape(-1, 3)
    fields["rs_ref"] = np.array(ref, dtype=float).reshape(-1, 3)
    for key, parts in segs.items():
        fields[f"rs_{key}"] = np.concatenate(parts) if parts else np.zeros(1)
    topology.joined(case, layout, joined, tips, fields, tip_joints)
    fields["rs_tip_joint"] = np.array(tip_joints, dtype=float).reshape(-1, 7)
    fields.update(directors=directors, rates=directors)
    return fields


def _tip_joint(line, where: str, tip: int, index: int) -> list[float] | None:
    """The row of ``rs_tip_joint`` of rigid line ``index`` (None without a joint at its held
    end): refused on a line whose end carries a body (``tip`` >= 0), which has no joint there,
    or is held on a free body (-2)."""
    given = line.tip_joint_stiffness or line.tip_joint_damping or line.tip_reference is not None
    if not given:
        return None
    if tip != -1:
        field = "tip_joint_stiffness" if line.tip_joint_stiffness else (
            "tip_joint_damping" if line.tip_joint_damping else "tip_reference")  # fmt: skip
        what = ("a point body the line carries (it moves with the last node, with no joint "
                "there)" if tip >= 0 else "on a free body (the joint's moment on it is not "
                "modelled)")  # fmt: skip
        raise CaseError(
            f"{where}.{field}: a joint at the end needs the end held on a point of a fixed or "
            f"imposed body, but '{line.to}' is {what}: leave the tip joint out, or hold the "
            "end on a fixed or imposed body"
        )
    reference = line.tip_reference
    if reference is not None and not np.linalg.norm(reference) > 0:
        raise CaseError(f"{where}.tip_reference: a direction needs a non-zero length")
    unit = (np.full(3, np.nan) if reference is None
            else np.asarray(reference, float) / np.linalg.norm(reference))  # fmt: skip
    return [float(index), -1.0, *unit, line.tip_joint_stiffness, line.tip_joint_damping]
