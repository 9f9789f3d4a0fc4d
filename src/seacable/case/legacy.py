"""The single-cable form (``cables:`` with ``top`` and ``bottom``) written as a system of bodies
and lines (``case.system``): each end becomes a body, the cable a line between them.

``upgrade(case)`` returns the mapping of the system-form case (YAML-ready: plain numbers, lists
and mappings), which ``seacable upgrade old.yaml`` prints. Ends map as:

- ``fixed`` top -> a fixed body ``top``; ``imposed`` -> an imposed body with the same time
  functions; ``floating_structure`` -> a rigid body with ``dofs: [heave]``, its heave spring and
  damper as ``linear_stiffness`` and ``linear_damping`` about its rest elevation, its force and
  net weight as ``applied`` forces;
- ``free`` bottom -> a point body ``end`` carried at the line's end (gravity, buoyancy, drag and
  applied forces as force models, its ties as linear stiffness and damping about their rest
  position, ``hold_axes`` as the axes its ``dofs`` leave out); ``pinned`` -> a fixed body
  ``anchor`` at the end of the initial shape; ``floating_structure`` -> a point body moving in
  surge and heave on its springs, weight equal to buoyancy.

The line keeps the cable's model (``rigid_links`` or ``rigid_segments_3d``), its initial angles
and its joints (a joint stiffness k as the bending stiffness k l of its links). Cables that have
no system form yet (lumped-mass and natural-string cables, towing ships, trajectories, point
bodies along the cable, several cables on one body) are refused, naming what is missing.
"""

import math
from typing import Any

import numpy as np
import yaml

from seacable import timefunctions as tfn
from seacable.case import schema
from seacable.errors import CaseError

RIGID = ("rigid_links", "rigid_segments_3d")
CONVERTED = (*RIGID, "lumped_mass")


def upgrade(case: schema.Case) -> dict[str, Any]:
    """The system-form mapping of a single-cable ``case`` (its table files' names unchanged:
    write it next to the case)."""
    if len(case.cables) != 1 or case.bodies:
        raise CaseError("upgrade: several cables on one body have no system form here yet")
    cable = case.cables[0]
    where = "cables[0]"
    if cable.model not in CONVERTED:
        raise CaseError(f"{where}.model: '{cable.model}' has no system form here yet")
    if cable.model == "lumped_mass":
        return _lumped(case, cable, where)
    for key in ("joint_stiffness", "joint_damping"):
        value = getattr(cable, key)
        if isinstance(value, list) and len(set(value)) > 1:
            raise CaseError(f"{where}.{key}: one value per joint has no system form; give one")
    lengths = cable.lengths()
    if len(set(lengths.tolist())) > 1:
        raise CaseError(f"{where}.link_lengths: unequal links have no system form here yet")
    static = cable.initial.shape == "static"
    if cable.initial.shape not in ("arc", "angles", "static"):
        raise CaseError(f"{where}.initial.shape: '{cable.initial.shape}' has no system form here")
    held = isinstance(cable.bottom, schema.TrajectoryBottom)
    if static and not isinstance(cable.bottom, schema.FreeBottom) and not held:
        raise CaseError(f"{where}.initial.shape: a static start has a system form here with a "
                        "free end or a trajectory only")  # fmt: skip
    # a static start: the statics starts from the line hanging straight down (or, held on a
    # trajectory, on its catenary between its ends)
    angles = [0.0] * cable.links if static else cable.initial.angles(cable.links)
    azimuth = math.radians(cable.initial.azimuth_deg)
    top, start = _top(cable.top, case._base_dir)
    a = np.asarray(angles, dtype=float)
    e = np.column_stack([np.sin(a) * math.cos(azimuth), np.sin(a) * math.sin(azimuth), -np.cos(a)])
    nodes = np.asarray(start) + np.vstack([np.zeros(3), np.cumsum(lengths[:, None] * e, axis=0)])
    if isinstance(cable.bottom, schema.TrajectoryBottom):
        bottom = _trajectory(cable.bottom, top["name"], where)
    else:
        bottom = _bottom(cable, case.environment, [float(v) for v in nodes[-1]])
    line_type = _line_type(cable, lengths)
    joints = _joints(cable, where)
    along = [_point(f"joint {pb.node}", pb, case.environment, [float(v) for v in nodes[pb.node]])
             for pb in sorted(cable.point_bodies, key=lambda pb: pb.node)]  # fmt: skip
    names = [top["name"], *(body["name"] for body in along), bottom["name"]]
    cuts = [0, *(pb.node for pb in sorted(cable.point_bodies, key=lambda pb: pb.node)),
            cable.links]  # fmt: skip
    total = cable.length if cable.length is not None else float(lengths.sum())
    lines = []
    for k in range(len(cuts) - 1):
        count = cuts[k + 1] - cuts[k]
        line: dict[str, Any] = {
            "name": cable.name if len(cuts) == 2 else f"{cable.name} {k + 1}",
            "model": cable.model, "from": names[k], "to": names[k + 1],
            "sections": [{"type": line_type["name"], "segments": count,
                          "length": total if len(cuts) == 2 else total * count / cable.links}],
            "initial": "catenary" if static and held else _initial(cable, static, a,
                                                                   (cuts[k], cuts[k + 1])),
        }  # fmt: skip
        if k == 0:
            reference = math.radians(cable.top_reference_angle_deg)
            line["base_reference"] = [math.sin(reference) * math.cos(azimuth),
                                      math.sin(reference) * math.sin(azimuth),
                                      -math.cos(reference)]  # fmt: skip
        if joints:
            line["joint_damping"] = joints
        lines.append(line)
    out: dict[str, Any] = {"name": case.name}
    if case.description:
        out["description"] = case.description
    out.update(
        environment=_dump(case.environment),
        bodies=[top, bottom, *along],
        line_types=[line_type],
        lines=lines,
        start="static" if static else "as_given",
        simulation=_dump(case.simulation),
    )
    return out


def _lumped(case: schema.Case, cable: schema.Cable, where: str) -> dict[str, Any]:
    """A lumped-mass cable from a top to a pinned anchor, started on its catenary."""
    if not isinstance(cable.bottom, schema.PinnedBottom) or cable.bottom.anchor is None:
        raise CaseError(f"{where}.bottom: a lumped-mass cable's system form needs a pinned end "
                        "with its anchor here")  # fmt: skip
    if cable.initial.shape != "catenary" or cable.point_bodies:
        raise CaseError(f"{where}.initial: only a catenary start has a system form here")
    top, _ = _top(cable.top, case._base_dir)
    anchor = {"name": "anchor", "type": "fixed", "position": list(schema.xyz(cable.bottom.anchor))}
    lengths = cable.lengths()
    line_type: dict[str, Any] = {"name": f"{cable.name} type", "diameter": cable.diameter,
                                 "mass_per_length": float(cable.masses()[0] / lengths[0]),
                                 "axial_stiffness": cable.axial_stiffness}  # fmt: skip
    for key in ("axial_damping_time", "axial_damping_ratio", "bending_stiffness"):
        if getattr(cable, key) is not None:
            line_type[key] = getattr(cable, key)
    line_type["drag_coefficient_normal"] = cable.drag_coefficient_normal
    for key in ("drag_coefficient_tangential", "friction_coefficient", "added_mass_coefficient"):
        if getattr(cable, key):
            line_type[key] = getattr(cable, key)
    total = cable.length if cable.length is not None else float(lengths.sum())
    section = {"type": line_type["name"], "segments": cable.links, "length": total}
    line = {"name": cable.name, "model": "lumped_mass", "from": top["name"], "to": "anchor",
            "sections": [section]}  # fmt: skip
    out: dict[str, Any] = {"name": case.name}
    out.update(environment=_dump(case.environment), bodies=[top, anchor],
               line_types=[line_type], lines=[line], start="as_given",
               simulation=_dump(case.simulation))  # fmt: skip
    return out


def _trajectory(bottom: schema.TrajectoryBottom, top: str, where: str) -> dict[str, Any]:
    """A vehicle's trajectory (the exact end force) as an imposed body the line's end is held
    on, relative to the top body when the trajectory is."""
    if bottom.method != "exact":
        raise CaseError(f"{where}.bottom.method: '{bottom.method}' has no system form here yet "
                        "(the servo as a force model)")  # fmt: skip
    body: dict[str, Any] = {"name": "end", "type": "imposed"}
    for axis in "xyz":
        if getattr(bottom, axis) != schema.Constant(value=0.0):
            body[axis] = _function(getattr(bottom, axis))
    if bottom.relative_to_top:
        body["relative_to"] = top
    return body


def _joints(cable: schema.Cable, where: str) -> float:
    """The joint damping of the line; refused across a point body along the cable (there the
    system's lines meet at a body, with no joint between them)."""
    damping = cable.joint_damping
    damping = float(damping[0] if isinstance(damping, list) else damping)
    stiff = cable.joint_stiffness is not None or cable.bending_stiffness is not None
    if cable.point_bodies and (damping or stiff):
        raise CaseError(f"{where}.point_bodies: a joint's stiffness or damping at a body along "
                        "the cable has no system form (the lines meet at the body, with no "
                        "joint between them)")  # fmt: skip
    return damping


def _initial(cable: schema.Cable, static: bool, angles: np.ndarray, piece: tuple[int, int]):
    """A line's initial shape: the cable's angles as written (its ``arc`` or ``angles_deg``),
    or those of its ``piece`` (first and end segment) between two bodies along it."""
    initial = cable.initial
    if static:
        return "straight"
    if initial.shape == "angles":
        out: dict[str, Any] = {"angles_deg": list(initial.angles_deg or [])[slice(*piece)]}
    elif piece == (0, cable.links):
        last = initial.bottom_angle_deg
        out = {"arc_deg": [initial.top_angle_deg,
                           last if last is not None else initial.top_angle_deg]}  # fmt: skip
    else:
        out = {"angles_deg": [float(v) for v in np.degrees(angles[slice(*piece)])]}
    if initial.azimuth_deg:
        out["azimuth_deg"] = initial.azimuth_deg
    return out


def upgrade_text(case: schema.Case) -> str:
    """The system form of ``case`` as a case file: the comment lines that open the file it was
    read from, then the upgraded case (``upgrade``)."""
    source = case._source_text or ""
    header = []
    for line in source.splitlines():
        if not line.startswith("#"):
            break
        header.append(line)
    note = "# Written in the system form of bodies and lines by `seacable upgrade`."
    body = yaml.safe_dump(upgrade(case), sort_keys=False, default_flow_style=None, width=100)
    return "\n".join([*header, note, body])


def _dump(model) -> dict:
    return model.model_dump(mode="json", by_alias=True, exclude_defaults=True)


def _line_type(cable: schema.Cable, lengths: np.ndarray) -> dict[str, Any]:
    mass = cable.masses()
    out: dict[str, Any] = {"name": f"{cable.name} type", "diameter": cable.diameter}
    if cable.density is not None:  # the same arithmetic as the cable's masses
        out["mass_per_length"] = cable.density * math.pi * cable.diameter**2 / 4
    else:
        out["mass_per_length"] = float(mass[0] / lengths[0])
    if cable.joint_stiffness is not None:
        k = cable.joint_stiffness
        out["bending_stiffness"] = _bending(float(k[0] if isinstance(k, list) else k), lengths[0])
    elif cable.bending_stiffness is not None:
        out["bending_stiffness"] = cable.bending_stiffness
    out["drag_coefficient_normal"] = cable.drag_coefficient_normal
    if cable.drag_coefficient_tangential:
        out["drag_coefficient_tangential"] = cable.drag_coefficient_tangential
    if cable.friction_coefficient:
        out["friction_coefficient"] = cable.friction_coefficient
    if cable.model == "rigid_links":
        out["added_mass_coefficient"] = 0.0  # Pouzada's links carry none
    elif cable.added_mass_coefficient is not None:
        out["added_mass_coefficient"] = cable.added_mass_coefficient
    return out


def _bending(k: float, length: float) -> float:
    """EI whose joint stiffness EI / l is k to the last bit (k l, or one of its neighbours)."""
    ei = float(k * length)
    for _ in range(8):
        if ei / length == k:
            return ei
        ei = float(np.nextafter(ei, np.inf if ei / length < k else -np.inf))
    return float(k * length)


def _function(f) -> Any:
    return {"kind": f.kind, **f.model_dump(mode="json", exclude_defaults=True)}


def _top(top, base_dir) -> tuple[dict[str, Any], tuple[float, float, float]]:
    if isinstance(top, schema.FixedTop):
        position = schema.xyz(top.position)
        return {"name": "top", "type": "fixed", "position": list(position)}, position
    if isinstance(top, schema.ImposedTop):
        body: dict[str, Any] = {"name": "top", "type": "imposed"}
        for axis in "xyz":
            if getattr(top, axis) != schema.Constant(value=0.0):
                body[axis] = _function(getattr(top, axis))
        x, y, z = (_value_at_zero(getattr(top, a), base_dir) for a in "xyz")
        return body, (x, y, z)
    if isinstance(top, schema.FloatingStructureTop):
        x, y, z = schema.xyz(top.position)
        forces: list[dict[str, Any]] = [
            {"model": "linear_stiffness", "diagonal": [0, 0, top.heave_stiffness, 0, 0, 0],
             "equilibrium_position": [x, y, z]},
        ]  # fmt: skip
        if top.heave_damping:
            forces.append({"model": "linear_damping", "diagonal": [0, 0, top.heave_damping, 0, 0,
                                                                   0]})  # fmt: skip
        if top.force != schema.Constant(value=0.0):
            forces.append({"model": "applied", "force_z": _function(top.force)})
        if top.net_weight:
            forces.append({"model": "applied", "force_z": {"kind": "constant",
                                                           "value": -top.net_weight}})  # fmt: skip
        start = (x, y, z + top.initial_heave)
        body = {"name": "top", "type": "rigid", "position": list(start), "mass": top.mass}
        if top.initial_heave_velocity:
            body["velocity"] = [0.0, 0.0, top.initial_heave_velocity]
        if top.added_mass:
            body["added_mass"] = [0.0, 0.0, top.added_mass, 0.0, 0.0, 0.0]
        body.update({"dofs": ["heave"], "external forces": forces})
        return body, start
    if isinstance(top, schema.TowingShipTop):
        x, y, z = schema.xyz(top.position)
        track: dict[str, Any] = {"start": [x, y], "heading_deg": top.heading_deg}
        if top.speed is not None:
            track["speed"] = top.speed
        else:
            track["distance"] = _function(top.distance)
        if top.turn is not None:
            track["turn"] = _dump(top.turn)
        body = {"name": "top", "type": "imposed", "track": track}
        if z:
            body["z"] = {"kind": "constant", "value": z}
        return body, (x, y, z)
    raise CaseError(f"cables[0].top.type: '{top.type}' has no system form here yet")


def _value_at_zero(function, base_dir) -> float:
    try:
        return float(tfn.evaluate(tfn.build(function, base_dir), 0.0)[0])
    except ValueError as exc:  # a table file that cannot be read
        raise CaseError(f"cables[0].top: {exc}") from None


def _bottom(cable: schema.Cable, env: schema.Environment, end: list[float]) -> dict[str, Any]:
    bottom = cable.bottom
    if isinstance(bottom, schema.PinnedBottom):
        # the planar model pins the end of its initial shape, the 3D model the anchor given
        anchor = end
        if cable.model == "rigid_segments_3d" and bottom.anchor is not None:
            anchor = list(schema.xyz(bottom.anchor))
        return {"name": "anchor", "type": "fixed", "position": list(anchor)}
    if isinstance(bottom, schema.FloatingStructureBottom):
        rest = list(schema.xyz(bottom.rest_position) if bottom.rest_position else end)
        forces: list[dict[str, Any]] = [
            {"model": "linear_stiffness", "equilibrium_position": rest,
             "diagonal": [bottom.surge_stiffness, bottom.surge_stiffness, bottom.heave_stiffness,
                          0, 0, 0]},
            {"model": "linear_damping",
             "diagonal": [bottom.surge_damping, bottom.surge_damping, bottom.heave_damping, 0, 0,
                          0]},
        ]  # fmt: skip
        if bottom.force != schema.Constant(value=0.0):
            forces.append({"model": "applied", "force_z": _function(bottom.force)})
        dofs = ["surge", "heave"] if cable.model == "rigid_links" else ["surge", "sway", "heave"]
        return {"name": "end", "type": "point", "position": list(end), "mass": bottom.mass,
                "dofs": dofs, "external forces": forces}  # fmt: skip
    if isinstance(bottom, schema.FreeBottom):
        return _free_end(cable, bottom, env, end)
    raise CaseError(f"cables[0].bottom.type: '{bottom.type}' has no system form here yet")


def _free_end(cable, bottom: schema.FreeBottom, env, end: list[float]) -> dict[str, Any]:
    out = _point("end", bottom.body, env, end)
    forces = out.pop("external forces")
    if bottom.tie is not None:
        tie = bottom.tie
        rest = list(schema.xyz(tie.rest_position) if tie.rest_position else end)
        forces.append({"model": "linear_stiffness", "equilibrium_position": rest, "diagonal": [
            tie.stiffness_x, tie.stiffness_y, tie.stiffness_z, 0, 0, 0]})  # fmt: skip
        forces.append({"model": "linear_damping", "diagonal": [
            tie.damping_x, tie.damping_y, tie.damping_z, 0, 0, 0]})  # fmt: skip
    if bottom.hold_axes:
        out["dofs"] = [dof for axis, dof in zip("xyz", ("surge", "sway", "heave"), strict=True)
                       if axis not in bottom.hold_axes]  # fmt: skip
    out["external forces"] = forces
    return out


def _point(name: str, body: schema.Body | schema.PointBody, env, at: list[float]) -> dict:
    """A point body of the system form: the free end's body, or a float or clump weight along
    the cable (``point_bodies``), at ``at``."""
    out: dict[str, Any] = {"name": name, "type": "point", "position": list(at),
                           "mass": body.mass}  # fmt: skip
    forces: list[dict[str, Any]] = [{"model": "gravity"}]
    if body.shape is not None:
        out["shape"] = _dump(body.shape)
    elif body.volume:
        out["volume"] = body.volume
    if body.displaced_volume() and not env.in_air:
        forces.append({"model": "buoyancy"})
    added = schema.per_axis(body.added_mass)
    if any(added) and not env.in_air:
        out["added_mass"] = list(added)
    area = schema.per_axis(body.drag_area)
    if body.drag_coefficient and any(area) and not env.in_air:
        forces.append({"model": "drag", "drag_coefficient": body.drag_coefficient,
                       "area": list(area)})  # fmt: skip
    zero = schema.Constant(value=0.0)
    applied = {f"force_{a}": _function(getattr(body, f"force_{a}")) for a in "xyz"
               if getattr(body, f"force_{a}", zero) != zero}  # fmt: skip
    if applied:
        forces.append({"model": "applied", **applied})
    out["external forces"] = forces
    return out
