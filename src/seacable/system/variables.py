"""The output variables of a system's results: each group's variables (``bodies/<name>``,
``lines/<name>``) with its dimensions, unit and meaning, its sizes and coordinates, and
``catalogue()``, every variable a run can write by the kind of part that writes it (the
documentation's list of outputs)."""

from typing import Any

import numpy as np

from seacable.case import system as sch
from seacable.forces.kinds import FIN, PROPELLER, RUDDER, THRUSTER
from seacable.system import rigid as rigid_kind
from seacable.system.assemble import BuiltSystem

AXES = "xyz"


def _body_variables(body, controls) -> dict:
    """A body's variables: those of its kind, then its controls' (``controls``)."""
    out = {}
    for c in AXES:
        out[f"position_{c}"] = (("time",), "m", f"position of the reference point, {c}")
    if not isinstance(body, sch.PointBody):
        for angle in ("roll", "pitch", "yaw"):
            out[angle] = (("time",), "degree", f"{angle} (R = Rz(yaw) Ry(pitch) Rx(roll))")
    if not isinstance(body, sch.FixedBody):
        for c in AXES:
            out[f"velocity_{c}"] = (("time",), "m/s", f"velocity of the reference point, {c}")
    if isinstance(body, sch.RigidBody | sch.ImposedBody):
        for c in AXES:
            out[f"angular_velocity_{c}"] = (("time",), "rad/s", f"angular velocity, {c}")
    for c in AXES:
        out[f"line_force_{c}"] = (
            ("time",), "N", f"force of the lines, ties and joints on the body, {c}",
        )  # fmt: skip
    if not isinstance(body, sch.PointBody):
        for c in AXES:
            out[f"line_moment_{c}"] = (
                ("time",), "N m",
                f"moment of the lines, ties and joints about the reference point, {c}",
            )  # fmt: skip
    return out | _control_variables(body, controls)


def _control_variables(body, controls) -> dict:
    """A body's servo's, controllers' and compensator's variables."""
    out: dict[str, tuple] = {}
    if any(spec.model == "servo" for spec in getattr(body, "external_forces", [])):
        out |= SERVO_VARIABLES
    for _, name, kind in controls:
        out[name] = (("time",), *CONTROL_STATES[kind][1:])
    if any(spec.model == "compensator" for spec in getattr(body, "external_forces", [])):
        for name, unit, text in COMPENSATOR_VARIABLES:
            out[name] = (("time",), unit, text)
    return out


SERVO_VARIABLES = {
    **{f"servo_force_{c}": (("time",), "N", f"force the servo applies to the body, {c}")
       for c in AXES},
    **{f"target_{c}": (("time",), "m", f"the servo's target point, {c}") for c in AXES},
    "tracking_error": (("time",), "m", "distance of the body from its target"),
}  # fmt: skip


# the compensator's record (forces.compensator.RECORD), in its order
COMPENSATOR_VARIABLES = (
    ("compensator_surge_force", "N", "the compensator's surge force, as applied (saturated)"),
    ("compensator_yaw_moment", "N m", "the compensator's yaw moment, as applied (saturated)"),
    ("compensator_surge_demand", "N", "the surge force the compensator's law demands"),
    ("compensator_yaw_demand", "N m", "the yaw moment the compensator's law demands"),
)


# a force model's control state in the results: its variable's name, unit, description
CONTROL_STATES = {
    RUDDER: ("rudder_angle", "degree", "the rudder's angle (its steering gear's state)"),
    THRUSTER: ("speed_integral", "m", "the speed controller's integral of (target - u)"),
    PROPELLER: (
        "propeller_speed_integral",
        "m",
        "the propeller's speed controller's integral of (target - u)",
    ),
    FIN: ("fin_angle", "degree", "the fin's angle (its actuator's state)"),
}
ANGLES = (RUDDER, FIN)  # the control states that are angles (radians inside, degrees out)


def controls(system: BuiltSystem, b: int) -> list[tuple[int, str, int]]:
    """(state, variable, kind) of each of body b's force models with a control state (a
    rudder's steering gear, a fin's actuator, a speed controller's integral:
    forces.table.state_count), in the body's order; the second of a kind is named with
    ``_2``, and so on."""
    p = system.params
    out: list[tuple[int, str, int]] = []
    seen: dict[int, int] = {}
    for f in np.flatnonzero(p.force_body == b):
        kind = int(p.force_kind[f])
        if kind in CONTROL_STATES and p.force_state[f] >= 0:
            seen[kind] = seen.get(kind, 0) + 1
            base = CONTROL_STATES[kind][0]
            out.append((int(p.force_state[f]), base if seen[kind] == 1 else f"{base}_{seen[kind]}",
                        kind))  # fmt: skip
    return out


def _line_variables(tension: str) -> dict:
    out: dict[str, tuple[tuple[str, ...], str, str]] = {
        f"node_{c}": (("time", "node"), "m", f"node position, {c}") for c in AXES
    }
    out["tension"] = (("time", "segment"), "N", tension)
    for end in ("from", "to"):
        for c in AXES:
            out[f"{end}_force_{c}"] = (
                ("time",), "N", f"force of the line on its '{end}' point, {c}",
            )  # fmt: skip
    return out


def _rigid_variables(system: BuiltSystem, li: int) -> dict:
    p = system.params
    return rigid_line_variables(p.rs_kind[li] == rigid_kind.PLANAR, bool(p.rs_held[li].any()))


def rigid_line_variables(planar: bool, held: bool) -> dict:
    """A rigid line's variables: planar (rigid_links) or 3D (rigid_segments_3d), with an end
    held on a constraint or not."""
    out = _line_variables(RIGID_TENSION)
    if planar:
        out["angle"] = (("time", "segment"), "rad",
                        "link angle from the downward vertical, positive towards +x")  # fmt: skip
        out["angular_velocity"] = (("time", "segment"), "rad/s", "link angular velocity")
    else:
        for c in AXES:
            out[f"direction_{c}"] = (
                ("time", "segment"),
                "1",
                f"unit vector along the segment, {c}",
            )
        out["angular_rate"] = (("time", "segment"), "rad/s", "rate of turn of the segment")
    if held:
        out["constraint_error"] = (("time",), "m", "distance of the held end from where it is held")
    return out


LUMPED_TENSION = "axial tension of the segment (no compression)"
RIGID_TENSION = "axial force at the segment's centre (positive pulling, negative compressed)"
TIE_VARIABLES = {
    "tension": (("time",), "N", "tension of the tie (zero when slack)"),
    "distance": (("time",), "m", "distance between the tie's points"),
    **{f"{end}_{c}": (("time",), "m", f"position of the '{end}' point, {c}")
       for end in ("from", "to") for c in AXES},
}  # fmt: skip


ENERGY_VARIABLES = {
    "kinetic_energy": (("time",), "J", "kinetic energy of bodies and line nodes (added mass in)"),
    "gravity_potential_energy": (("time",), "J", "potential of gravity and buoyancy"),
    "elastic_energy": (("time",), "J", "axial, bending, seabed, tie and linear-spring energy"),
    "total_energy": (("time",), "J", "kinetic + gravity potential + elastic energy"),
}


def variables(system: BuiltSystem) -> dict:
    """Every output variable, its name prefixed by its group (the energies at the top)."""
    out: dict[str, tuple] = dict(ENERGY_VARIABLES)
    for b, body in enumerate(system.case.bodies):
        for name, spec in _body_variables(body, controls(system, b)).items():
            out[f"bodies/{body.name}/{name}"] = spec
    for line in system.layout.lines:
        for name, spec in _line_variables(LUMPED_TENSION).items():
            out[f"lines/{line}/{name}"] = spec
    for li, line in enumerate(system.layout.rigid):
        for name, spec in _rigid_variables(system, li).items():
            out[f"lines/{line}/{name}"] = spec
    for line in system.layout.ties:
        for name, spec in TIE_VARIABLES.items():
            out[f"lines/{line}/{name}"] = spec
    for line in system.layout.natural:
        for name, spec in STRING_VARIABLES.items():
            out[f"lines/{line}/{name}"] = spec
    return out


STRING_VARIABLES = {
    **{f"node_{c}": (("time", "node"), "m", f"node position, {c} (trapezoidal integral of the "
                                            "tangent from the pivot)") for c in AXES},
    "strain": (("time", "node"), "1", "axial strain at the node"),
    "tension": (("time", "node"), "N", "axial tension at the node (no compression)"),
}  # fmt: skip


def sizes(system: BuiltSystem) -> dict:
    p = system.params
    out = {}
    for li, line in enumerate(system.layout.lines):
        out[f"lines/{line}/segment"] = int(p.line_n[li])
        out[f"lines/{line}/node"] = int(p.line_n[li]) + 1
    for li, line in enumerate(system.layout.rigid):
        out[f"lines/{line}/segment"] = int(p.rs_n[li])
        out[f"lines/{line}/node"] = int(p.rs_n[li]) + 1
    for li, line in enumerate(system.layout.natural):
        out[f"lines/{line}/node"] = int(p.nat_n[li]) + 1
    return out


def coords(system: BuiltSystem) -> dict:
    p = system.params
    out = {}
    for li, line in enumerate(system.layout.lines):
        n, s0 = int(p.line_n[li]), int(p.line_seg[li])
        arc = np.concatenate([[0.0], np.cumsum(p.seg_length[s0 : s0 + n])])
        out[f"lines/{line}/arc_length"] = ("node", arc, "m", ARC_LENGTH["lumped_mass"])
    for li, line in enumerate(system.layout.rigid):
        n, s0 = int(p.rs_n[li]), int(p.rs_seg[li])
        arc = np.concatenate([[0.0], np.cumsum(p.rs_length[s0 : s0 + n])])
        out[f"lines/{line}/arc_length"] = ("node", arc, "m", ARC_LENGTH["rigid"])
    for li, line in enumerate(system.layout.natural):
        arc = np.linspace(0.0, float(p.nat_length[li]), int(p.nat_n[li]) + 1)
        out[f"lines/{line}/arc_length"] = ("node", arc, "m", ARC_LENGTH["natural_string"])
    return out


BODY_NAMES = (
    *(f"position_{c}" for c in AXES), "roll", "pitch", "yaw",
    *(f"velocity_{c}" for c in AXES), *(f"angular_velocity_{c}" for c in AXES),
    *(f"line_force_{c}" for c in AXES), *(f"line_moment_{c}" for c in AXES),
)  # fmt: skip


# a line's arc-length coordinate, by its model (``coords``)
ARC_LENGTH = {
    "lumped_mass": "unstretched arc length from the 'from' end",
    "rigid": "arc length from the 'from' end",
    "natural_string": "unstretched arc length from the pivot",
}


def catalogue() -> list[tuple[str, str, dict]]:
    """Every variable a run can write, by the part that writes it: (what writes them, the
    group they go in, {name: (dims, unit, meaning)}), as the documentation lists them."""
    bodies: list[tuple[str, Any]] = [
        ("a fixed body", sch.FixedBody), ("an imposed body", sch.ImposedBody),
        ("a point body", sch.PointBody), ("a rigid body", sch.RigidBody),
    ]  # fmt: skip
    arc = {k: {"arc_length": (("node",), "m", text)} for k, text in ARC_LENGTH.items()}
    rudder, thruster, propeller, fin = (
        {CONTROL_STATES[k][0]: (("time",), *CONTROL_STATES[k][1:])}
        for k in (RUDDER, THRUSTER, PROPELLER, FIN)
    )
    return [
        ("the system", "/", dict(ENERGY_VARIABLES)),
        *[(what, "bodies/<name>", _body_variables(kind.model_construct(), []))
          for what, kind in bodies],
        ("a body with a servo force", "bodies/<name>", dict(SERVO_VARIABLES)),
        ("a body with a rudder (its steering gear)", "bodies/<name>", rudder),
        ("a body with a thruster's speed controller", "bodies/<name>", thruster),
        ("a body with a propeller's speed controller", "bodies/<name>", propeller),
        ("a body with a fin (its actuator)", "bodies/<name>", fin),
        ("a body with a compensator", "bodies/<name>",
         {name: (("time",), unit, text) for name, unit, text in COMPENSATOR_VARIABLES}),
        ("a lumped-mass line", "lines/<name>",
         _line_variables(LUMPED_TENSION) | arc["lumped_mass"]),
        ("a rigid_links line (planar)", "lines/<name>",
         rigid_line_variables(True, True) | arc["rigid"]),
        ("a rigid_segments_3d line", "lines/<name>",
         rigid_line_variables(False, True) | arc["rigid"]),
        ("a tie", "lines/<name>", dict(TIE_VARIABLES)),
        ("a natural_string line", "lines/<name>",
         dict(STRING_VARIABLES) | arc["natural_string"]),
    ]  # fmt: skip
