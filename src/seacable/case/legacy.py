"""The single-cable form (``cables:`` with ``top`` and ``bottom``) written as a system of bodies
and lines (``case.system``): each end becomes a body, the cable a line between them.

``upgrade(case)`` returns the mapping of the system-form case (YAML-ready: plain numbers, lists
and mappings), which ``seacable upgrade old.yaml`` prints. Ends map as:

- ``fixed`` top -> a fixed body ``top``; ``imposed`` -> an imposed body with the same time
  functions; ``floating_structure`` -> a rigid body with ``dofs: [heave]``, its heave spring and
  damper as ``linear_stiffness`` and ``linear_damping`` about its rest elevation, its force and
  net weight as ``applied`` forces; ``towing_ship`` -> an imposed body on its ``track``;
- ``free`` bottom -> a point body ``end`` carried at the line's end (gravity, buoyancy, drag and
  applied forces as force models, its ties as linear stiffness and damping about their rest
  position, ``hold_axes`` as the axes its ``dofs`` leave out); ``pinned`` -> a fixed body
  ``anchor`` at the end of the initial shape; ``floating_structure`` -> a point body moving in
  surge and heave on its springs, weight equal to buoyancy; ``trajectory`` -> an imposed body
  ``end`` (``relative_to`` the top when the trajectory is) the line is held on (``exact``), or
  the ``vehicle`` a massless ``end`` follows with a ``servo`` force model (``stiffness_servo``).

The line keeps the cable's model (``rigid_links`` or ``rigid_segments_3d``), its initial angles
and its joints (a joint stiffness k as the bending stiffness k l of its links); unequal links,
link masses and one spring or damper per joint become sections (``legacy_sections``); bodies
along the cable (``point_bodies``) cut it into lines, each body carried between two (a spring
or damper at such a body joins the two lines: the second ``continues`` the first); a
static start becomes ``start: static`` (a line held on an anchor or a trajectory starting
on its catenary). Cables on a shared body (a star) become lines from that body back to
each top, the joint at a top the line's tip joint (``tip_joint_stiffness``). A lumped-mass
cable and Poth's natural string have their line models; a lumped-mass cable started on its
catenary to a trajectory (exact or servo), or with bodies along it, starts from the system's
statics (``start: static``: in a tow, its steady motion); a star's lumped-mass cables become
lines from each top to the shared body. What has no system form yet is refused, naming what
is missing.
"""

import math
from typing import Any

import numpy as np
import yaml

from seacable import timefunctions as tfn
from seacable.case import legacy_sections as sections
from seacable.case import schema
from seacable.errors import CaseError

RIGID = ("rigid_links", "rigid_segments_3d")
CONVERTED = (*RIGID, "lumped_mass", "natural_string")


def upgrade(case: schema.Case) -> dict[str, Any]:
    """The system-form mapping of a single-cable ``case`` (its table files' names unchanged:
    write it next to the case)."""
    if case.bodies:
        return _star(case)
    if len(case.cables) != 1:
        raise CaseError("upgrade: several cables need a body they share (bodies:)")
    cable = case.cables[0]
    where = "cables[0]"
    if cable.model not in CONVERTED:
        raise CaseError(f"{where}.model: '{cable.model}' has no system form here yet")
    if cable.model == "lumped_mass":
        return _lumped(case, cable, where)
    if cable.model == "natural_string":
        return _natural(case, cable, where)
    bodies, line_types, lines, static = _rigid(case, cable, where)
    return _case(case, bodies, line_types, lines, "static" if static else "as_given")


def _case(case: schema.Case, bodies, line_types, lines, start: str) -> dict[str, Any]:
    out: dict[str, Any] = {"name": case.name}
    if case.description:
        out["description"] = case.description
    out.update(environment=_dump(case.environment), bodies=bodies, line_types=line_types,
               lines=lines, start=start, simulation=_dump(case.simulation))  # fmt: skip
    return out


def _star(case: schema.Case) -> dict[str, Any]:
    """Cables from their tops to bodies they share (a star): each rigid cable becomes lines
    from its shared body to its top (reversed: a rigid line may end held on a fixed or imposed
    body, and several may start on one body), each lumped-mass cable lines from its top to the
    shared body; cut at the bodies along them."""
    bodies = [_point(b.name, b, case.environment, list(schema.xyz(b.position)))
              for b in case.bodies]  # fmt: skip
    line_types: list[dict[str, Any]] = []
    lines: list[dict[str, Any]] = []
    shared = {b.name: b for b in case.bodies}
    for k, cable in enumerate(case.cables):
        where = f"cables[{k}]"
        if not isinstance(cable.bottom, schema.AttachedBottom):
            raise CaseError(f"{where}.bottom: a star's system form here needs every cable "
                            "attached to a shared body")  # fmt: skip
        if cable.model == "lumped_mass":  # lines from the top to the shared body
            more, types, mine, _ = _lumped_parts(case, cable, where, shared[cable.bottom.body])
            bodies, line_types, lines = bodies + more, line_types + types, lines + mine
            continue
        if cable.model not in RIGID:
            raise CaseError(f"{where}.model: '{cable.model}' has no system form in a star")
        if not isinstance(cable.top, schema.FixedTop | schema.ImposedTop):
            raise CaseError(f"{where}.top.type: '{cable.top.type}' has no system form in a star "
                            "(a rigid line held on a moving body's point)")  # fmt: skip
        more, types, mine, _ = _rigid(case, cable, where, shared=cable.bottom.body)
        bodies += more
        line_types += types
        lines += mine
    return _case(case, bodies, line_types, lines, "as_given")


def _rigid(case: schema.Case, cable: schema.Cable, where: str, shared: str | None = None):
    """The bodies, line types and lines of a rigid cable, and whether it starts from its
    statics: from its top to its end (the top body, the end body, those along it); or, ending
    on the body ``shared`` (a star), from that body back to its top (the top body and those
    along it, named after the cable). Unequal links and one value per joint become sections
    (``legacy_sections``)."""
    lengths = cable.lengths()
    static = cable.initial.shape == "static"
    if cable.initial.shape not in ("arc", "angles", "static"):
        raise CaseError(f"{where}.initial.shape: '{cable.initial.shape}' has no system form here")
    held = isinstance(cable.bottom, schema.TrajectoryBottom)
    anchored = isinstance(cable.bottom, schema.PinnedBottom) and cable.bottom.anchor is not None
    if static and not isinstance(cable.bottom, schema.FreeBottom) and not (held or anchored):
        raise CaseError(f"{where}.initial.shape: a static start has a system form here with a "
                        "free end, an anchor or a trajectory only")  # fmt: skip
    # a static start: the statics starts from the line hanging straight down (or, held on a
    # trajectory or an anchor, on its catenary between its ends)
    angles = [0.0] * cable.links if static else cable.initial.angles(cable.links)
    azimuth = math.radians(cable.initial.azimuth_deg)
    top, start = _top(cable.top, case._base_dir)
    a = np.asarray(angles, dtype=float)
    nodes = _nodes(a, azimuth, start, lengths)
    prefix = "" if shared is None else f"{cable.name} "
    if shared is not None:
        top["name"] = f"{cable.name} top"
        bottom = None
    elif isinstance(cable.bottom, schema.TrajectoryBottom):
        bottom = _trajectory(cable.bottom, top["name"])
        if cable.bottom.method == "stiffness_servo":  # the line's end, pulled by the servo
            vehicle, bottom = _servo_end(cable.bottom, bottom, [float(v) for v in nodes[-1]])
            held = False
    else:
        bottom = _bottom(cable, case.environment, [float(v) for v in nodes[-1]])
    ordered = sorted(cable.point_bodies, key=lambda pb: pb.node)
    along = [_point(f"{prefix}joint {pb.node}", pb, case.environment,
                    [float(v) for v in nodes[pb.node]]) for pb in ordered]  # fmt: skip
    end = bottom["name"] if bottom is not None else shared
    names = [top["name"], *(body["name"] for body in along), end]
    cuts = [0, *(pb.node for pb in ordered), cable.links]
    plan = sections.Plan(cable, _line_type(cable), cuts, where, reverse=shared is not None)
    pieces = [(cuts[k], cuts[k + 1], names[k], names[k + 1]) for k in range(len(cuts) - 1)]
    if shared is not None:  # from the shared body back to the top
        pieces = [(first, last, b, a) for first, last, a, b in reversed(pieces)]
    lines: list[dict[str, Any]] = []
    for k, (first, last, start_at, end_at) in enumerate(pieces):
        line: dict[str, Any] = {
            "name": cable.name if len(pieces) == 1 else f"{cable.name} {k + 1}",
            "model": cable.model, "from": start_at, "to": end_at,
            "sections": plan.sections(first, last),
            "initial": "catenary" if static and (held or anchored) else _initial(
                cable, static, a, (first, last), reverse=shared is not None),
        }  # fmt: skip
        reference = math.radians(cable.top_reference_angle_deg)
        down = [math.sin(reference) * math.cos(azimuth), math.sin(reference) * math.sin(azimuth),
                -math.cos(reference)]  # fmt: skip
        if k == 0 and shared is None:
            line["base_reference"] = down
        if shared is not None and first == 0 and (plan.springs[0] or plan.dampers[0]):
            # a star's top joint: the line's last segment, run up to the top, against the top
            line.update(tip_joint_stiffness=float(plan.springs[0]),
                        tip_joint_damping=float(plan.dampers[0]),
                        tip_reference=[-v for v in down])  # fmt: skip
        damping = plan.line_damping(first)
        if damping:
            line["joint_damping"] = damping
        node = last if shared is not None else first  # the body it starts on, along the cable
        if k > 0 and (plan.springs[node] or plan.dampers[node]):
            line["continues"] = lines[-1]["name"]  # the joint there joins the two lines
        lines.append(line)
    bodies = [top, *([bottom] if bottom is not None else []), *along]
    if isinstance(cable.bottom, schema.TrajectoryBottom) and not held:
        bodies.append(vehicle)
    return bodies, plan.types, lines, static


def _nodes(angles: np.ndarray, azimuth: float, start, lengths: np.ndarray) -> np.ndarray:
    """The nodes (n + 1, 3) of segments at ``angles`` [rad] from the downward vertical, in the
    vertical plane at ``azimuth`` [rad], from ``start``."""
    e = np.column_stack([np.sin(angles) * math.cos(azimuth), np.sin(angles) * math.sin(azimuth),
                         -np.cos(angles)])  # fmt: skip
    return np.asarray(start) + np.vstack([np.zeros(3), np.cumsum(lengths[:, None] * e, axis=0)])


def _natural(case: schema.Case, cable: schema.Cable, where: str) -> dict[str, Any]:
    """Poth's string pendulum: a natural_string line from a fixed pivot to its end mass."""
    if not isinstance(cable.top, schema.FixedTop) or not isinstance(
        cable.bottom, schema.FreeBottom
    ):
        raise CaseError(f"{where}: a natural_string's system form needs a fixed top and a free "
                        "end")  # fmt: skip
    top, start = _top(cable.top, case._base_dir)
    a = cable.initial.angles(cable.links)  # the end of the links' shape (the body is carried)
    tip = np.asarray(start) + (cable.lengths()[:, None] * np.column_stack(
        [np.sin(a), np.zeros_like(a), -np.cos(a)])).sum(axis=0)  # fmt: skip
    end = {
        "name": "end",
        "type": "point",
        "position": [float(v) for v in tip],
        "mass": cable.bottom.body.mass,
        "external forces": [{"model": "gravity"}],
    }
    length = float(cable.lengths().sum())
    line_type: dict[str, Any] = {"name": f"{cable.name} type", "diameter": cable.diameter,
                                 "mass_per_length": float(cable.masses().sum()) / length,
                                 "axial_stiffness": cable.axial_stiffness}  # fmt: skip
    if cable.axial_damping_time is not None:
        line_type["axial_damping_time"] = cable.axial_damping_time
    initial = cable.initial
    shape: dict[str, Any] = (
        {"angles_deg": list(initial.angles_deg or [])} if initial.shape == "angles" else
        {"arc_deg": [initial.top_angle_deg, initial.bottom_angle_deg
                     if initial.bottom_angle_deg is not None else initial.top_angle_deg]}
    )  # fmt: skip
    line = {"name": cable.name, "model": "natural_string", "from": "top", "to": "end",
            "tangent": cable.tangent, "initial": shape,
            "sections": [{"type": line_type["name"], "segments": cable.links,
                          "length": length}]}  # fmt: skip
    return _case(case, [top, end], [line_type], [line], "as_given")


def _lumped(case: schema.Case, cable: schema.Cable, where: str) -> dict[str, Any]:
    """A lumped-mass cable as a system (``_lumped_parts``)."""
    bodies, line_types, lines, start = _lumped_parts(case, cable, where)
    return _case(case, bodies, line_types, lines, start)


def _lumped_parts(case: schema.Case, cable: schema.Cable, where: str,
                  shared: schema.SharedBody | None = None):  # fmt: skip
    """The bodies, line types and lines of a lumped-mass cable from its top to its end, and
    how the system starts: started on its catenary to a pinned anchor, a trajectory or the
    body ``shared`` with other cables (a star; its bodies named after the cable), or at its
    given angles (``arc``, ``angles``) to whatever its end is (an anchor, a free body, a guided
    one, a floating structure, a trajectory); cut into lines at the bodies along it (each
    line keeps at least two segments)."""
    shape = cable.initial.shape
    anchor = cable.bottom.anchor if isinstance(cable.bottom, schema.PinnedBottom) else None
    trajectory = isinstance(cable.bottom, schema.TrajectoryBottom)
    if shape == "catenary" and anchor is None and not trajectory and shared is None:
        raise CaseError(f"{where}.initial: a catenary start needs the end's anchor or its "
                        "trajectory; give the start as angles (arc or angles)")  # fmt: skip
    if shape not in ("catenary", "arc", "angles"):
        raise CaseError(f"{where}.initial.shape: '{shape}' has no system form for a lumped-mass "
                        "cable")  # fmt: skip
    top, start = _top(cable.top, case._base_dir)
    prefix = "" if shared is None else f"{cable.name} "
    top["name"] = f"{prefix}{top['name']}"
    lengths = cable.lengths()
    nodes = None
    if anchor is not None and shape == "catenary":
        end = list(schema.xyz(anchor))
    elif shared is not None and shape == "catenary":
        end = list(schema.xyz(shared.position))
    elif isinstance(cable.bottom, schema.TrajectoryBottom) and shape == "catenary":
        # to the trajectory's start (the line at its static shape to it)
        end = _trajectory_start(cable.bottom, start, case._base_dir)
    else:
        a = np.asarray(cable.initial.angles(cable.links), dtype=float)  # [rad]
        nodes = _nodes(a, math.radians(cable.initial.azimuth_deg), start, lengths)
        end = [float(v) for v in nodes[-1]]
    vehicle = None
    bottom: dict[str, Any] | None = None
    if shared is not None:  # the shared body (the star's)
        pass
    elif isinstance(cable.bottom, schema.TrajectoryBottom):
        bottom = _trajectory(cable.bottom, top["name"])
        if cable.bottom.method == "stiffness_servo":
            vehicle, bottom = _servo_end(cable.bottom, bottom, end)
    elif anchor is not None:
        bottom = {"name": "anchor", "type": "fixed", "position": list(schema.xyz(anchor))}
    else:
        bottom = _bottom(cable, case.environment, end)
    ordered = sorted(cable.point_bodies, key=lambda pb: pb.node)
    along = []
    arc = np.concatenate([[0.0], np.cumsum(lengths)]) / lengths.sum()
    for pb in ordered:
        if nodes is None:  # a first guess on the chord: the statics places it
            at = [float(a + arc[pb.node] * (b - a)) for a, b in zip(start, end, strict=True)]
        else:
            at = [float(v) for v in nodes[pb.node]]
        along.append(_point(f"{prefix}joint {pb.node}", pb, case.environment, at))
    end_name = shared.name if shared is not None else bottom["name"]  # type: ignore[index]
    names = [top["name"], *(body["name"] for body in along), end_name]
    cuts = [0, *(pb.node for pb in ordered), cable.links]
    plan = sections.Plan(cable, _lumped_type(cable), cuts, where)
    lines = []
    for k in range(len(cuts) - 1):
        count = cuts[k + 1] - cuts[k]
        if count < 2:
            raise CaseError(f"{where}.point_bodies: a lumped-mass line between bodies needs at "
                            f"least two segments (nodes {cuts[k]} to {cuts[k + 1]})")  # fmt: skip
        line: dict[str, Any] = {
            "name": cable.name if len(cuts) == 2 else f"{cable.name} {k + 1}",
            "model": "lumped_mass", "from": names[k], "to": names[k + 1],
            "sections": plan.sections(cuts[k], cuts[k + 1]),
        }  # fmt: skip
        if nodes is not None:
            line["initial"] = _initial(cable, False, np.asarray(cable.initial.angles(
                cable.links), dtype=float), (cuts[k], cuts[k + 1]))  # fmt: skip
        lines.append(line)
    bodies = [top, *([bottom] if bottom is not None else []), *along,
              *([vehicle] if vehicle is not None else [])]  # fmt: skip
    # a catenary start on a trajectory (the towed equilibrium through the target) or with
    # bodies along the cable (the equilibrium of the lines and those bodies)
    balanced = shape == "catenary" and (trajectory or bool(along))
    return bodies, plan.types, lines, "static" if balanced else "as_given"


def _lumped_type(cable: schema.Cable) -> dict[str, Any]:
    """A lumped-mass cable's line type but its name, mass per length and EI: EA and axial
    damping (its joints' springs: ``legacy_sections.Plan``; the top joint is a pin in a
    lumped line)."""
    out = _line_type(cable)
    out["axial_stiffness"] = cable.axial_stiffness
    for key in ("axial_damping_time", "axial_damping_ratio"):
        if getattr(cable, key) is not None:
            out[key] = getattr(cable, key)
    return out


def _trajectory(bottom: schema.TrajectoryBottom, top: str) -> dict[str, Any]:
    """A vehicle's trajectory as an imposed body (the line's end held on it with the exact end
    force; the servo's target), relative to the top body when the trajectory is."""
    body: dict[str, Any] = {"name": "end", "type": "imposed"}
    for axis in "xyz":
        if getattr(bottom, axis) != schema.Constant(value=0.0):
            body[axis] = _function(getattr(bottom, axis))
    if bottom.relative_to_top:
        body["relative_to"] = top
    return body


def _servo_end(bottom: schema.TrajectoryBottom, path: dict[str, Any], at: list[float]):
    """The vehicle (the trajectory ``path`` as an imposed body, the servo's target) and the
    line's end it pulls: a point body of no mass at ``at`` with the servo force model."""
    vehicle = dict(path, name="vehicle")
    end = {"name": "end", "type": "point", "position": list(at), "mass": 0.0,
           "external forces": [{"model": "servo", "target": "vehicle",
                                **_dump(bottom.servo)}]}  # fmt: skip
    return vehicle, end


def _trajectory_start(bottom: schema.TrajectoryBottom, top, base_dir) -> list[float]:
    """Where the trajectory starts [m] (from the top's start ``top`` when relative to it)."""
    offset = [_value_at_zero(getattr(bottom, axis), base_dir) for axis in "xyz"]
    origin = top if bottom.relative_to_top else (0.0, 0.0, 0.0)
    return [float(o + d) for o, d in zip(origin, offset, strict=True)]


def _turned(angle: float) -> float:
    """A segment's angle [deg] turned by 180 deg, kept within the schema's [-360, 360]."""
    turned = angle - 180.0
    return turned + 360.0 if turned < -360.0 else turned


def _initial(cable: schema.Cable, static: bool, angles: np.ndarray, piece: tuple[int, int],
             reverse: bool = False):  # fmt: skip
    """A line's initial shape: the cable's angles as written (its ``arc`` or ``angles_deg``),
    or those of its ``piece`` (first and end segment) between two bodies along it; ``reverse``:
    the piece run from its end to its start (each segment turned by 180 deg)."""
    initial = cable.initial
    if static:
        return "straight"
    if reverse:
        written = initial.angles_deg if initial.shape == "angles" else np.degrees(angles)
        out: dict[str, Any] = {
            "angles_deg": [
                _turned(float(v))
                for v in list(written if written is not None else [])[slice(*piece)][::-1]
            ]
        }
    elif initial.shape == "angles":
        out = {"angles_deg": list(initial.angles_deg or [])[slice(*piece)]}
    elif piece == (0, cable.links):
        last = initial.bottom_angle_deg
        out = {"arc_deg": [initial.top_angle_deg,
                           last if last is not None else initial.top_angle_deg]}  # fmt: skip
    else:
        out = {"angles_deg": [float(v) for v in np.degrees(angles[slice(*piece)])]}
    if initial.azimuth_deg:  # the schema's [-360, 360]: the single-cable form took any
        az = initial.azimuth_deg
        out["azimuth_deg"] = math.fmod(az, 360.0) if abs(az) > 360.0 else az
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


def _line_type(cable: schema.Cable) -> dict[str, Any]:
    """A cable's line type but its name, mass per length and EI (``legacy_sections.Plan``)."""
    out: dict[str, Any] = {"diameter": cable.diameter}
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


def _point(name: str, body: schema.Body | schema.PointBody | schema.SharedBody, env,
           at: list[float]) -> dict:  # fmt: skip
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
