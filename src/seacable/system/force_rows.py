"""The rows of a system's force models: each body's ``external forces`` (case.forces) packed
by its model's ``pack`` (src/seacable/forces) into the flat rows and time-function channels of
SystemParams (system.assemble lays them out)."""

import logging
import math
from typing import Any

import numpy as np

from seacable import timefunctions as tfn
from seacable.bodies import kinematics
from seacable.case import forces as fm
from seacable.case import ship_forces as sf
from seacable.case.base import Constant
from seacable.case.system import RigidBody
from seacable.errors import CaseError
from seacable.forces import (
    applied,
    coefficients,
    compensator,
    drag,
    fin,
    foil,
    hull_current,
    hydrostatic,
    linear,
    propeller,
    rod,
    rudder,
    servo,
    table,
    thruster,
    wave_drift,
)
from seacable.forces.kinds import COMPENSATOR, kind_of
from seacable.packing import channel, transported
from seacable.system import hulls

log = logging.getLogger(__name__)
REVOLUTIONS = 1.0 / 60.0  # [rev/s] a revolution a minute


def scaled(function: tfn.Piecewise, k: float) -> tfn.Piecewise:
    """A time function times ``k`` (into the unit the kernels take)."""
    amplitude, omega, phase = function.sine
    return tfn.Piecewise(function.breaks, function.coefs * k, (amplitude * k, omega, phase),
                         function.builds_up)  # fmt: skip


def in_radians(function: tfn.Piecewise) -> tfn.Piecewise:
    """A degree-valued time function in radians."""
    return scaled(function, math.pi / 180.0)


def offset(body, point: str) -> tuple[float, float, float]:
    """A named point's body-frame coordinates [m] (the reference point's: zero)."""
    if point == fm.ORIGIN:
        return (0.0, 0.0, 0.0)
    return body.points[point]


def force_row(case, layout, spec, body, rho, base_dir, channels, where, point) -> list[float]:
    """A force model's row of floats (its ``pack``), its time functions appended to
    ``channels``; ``point(ref, where)`` is the index of the point ``body`` or ``body.point``
    (system.assemble's, created on first use)."""
    if isinstance(spec, fm.Drag | fm.Rod):
        return _morison_row(spec, body, rho, where)
    if isinstance(spec, fm.AppliedForce):
        point(f"{body.name}.{spec.point}" if spec.point != fm.ORIGIN else body.name, where)
        for name in applied.CHANNELS:
            channels.append(channel(getattr(spec, name), base_dir, f"{where}.{name}"))
        return applied.pack(offset(body, spec.point), spec.frame == "body")
    if isinstance(spec, sf.Thruster | sf.Rudder | sf.Propeller | sf.Fin | sf.WindLoad
                  | sf.CurrentLoad):  # fmt: skip
        return _vessel_row(case, layout, spec, body, base_dir, channels, where)
    if isinstance(spec, sf.ShortWing | sf.CrossFlow):
        if not isinstance(body, RigidBody):
            raise CaseError(f"{where}: model '{spec.model}' acts on a ship: a 'rigid' body "
                            f"(this one is '{body.type}')")  # fmt: skip
        given = spec.derivatives.model_dump(exclude_none=True) if spec.derivatives else {}
        return hull_current.pack(
            spec.model, _body_point(body, spec.point, where), spec.length, spec.beam,
            spec.draught, spec.block_coefficient, spec.wetted_area, spec.cross_flow_drag,
            spec.cross_flow_centre, spec.kinematic_viscosity, spec.form_factor, given,
        )  # fmt: skip
    if isinstance(spec, fm.LinearStiffness):
        position: Any = spec.equilibrium_position or body.position
        angles: Any = spec.equilibrium_orientation_deg or getattr(
            body, "orientation_deg", (0.0, 0.0, 0.0)
        )
        roll, pitch, yaw = (math.radians(a) for a in angles)
        quaternion = kinematics.euler_quaternion(roll, pitch, yaw)
        return [*linear.matrix(spec).ravel(), *position, *quaternion]
    if isinstance(spec, fm.LinearDamping | fm.QuadraticDamping):
        matrix = transported(linear.matrix(spec), spec.point)
        form = linear.FORMS[getattr(spec, "frame", "quadratic")]
        return [*matrix.ravel(), float(form)]
    if isinstance(spec, fm.NonLinearHydrostatic | fm.NonLinearFroudeKrylov):
        still = isinstance(spec, fm.NonLinearHydrostatic) and spec.free_surface == "still"
        mesh = hulls.body_mesh(body, base_dir, where.split(".")[0])
        return hydrostatic.pack(mesh.row(), still)
    if isinstance(spec, fm.RadiationDamping | fm.Diffraction):
        return hulls.database_row(case, body, spec, base_dir, where)
    if isinstance(spec, fm.ServoForce):
        target = point(spec.target, f"{where}.target")
        sim = case.simulation
        step = spec.step or sim.time_step or min(0.01, sim.output_interval)
        return servo.pack(spec.gain, spec.rate_gain, step, target)
    if isinstance(spec, sf.Compensator):
        return _compensator_row(spec, body, where, point)
    if isinstance(spec, sf.WaveDrift):
        return _wave_drift_row(case, spec, body, base_dir, where)
    return []  # gravity, buoyancy: the body's own fields


def _morison_row(spec, body, rho: float, where: str) -> list[float]:
    """The row of a body's drag or of a rod fixed to it."""
    if isinstance(spec, fm.Drag):
        return drag.pack(spec, rho)
    if not isinstance(body, RigidBody):
        raise CaseError(f"{where}: a rod turns with its body: give it to a 'rigid' body "
                        f"(this one is '{body.type}')")  # fmt: skip
    return rod.pack(spec)


def rods_added_mass(body, rho: float, pose=None) -> np.ndarray:
    """The added mass (6x6, body frame, at the reference point) of a rigid body's rods on their
    parts under the still water (forces.rod.added_mass) with the body at ``pose`` (its
    position [m] and unit quaternion; by default its start pose); zeros without rods or
    water."""
    total = np.zeros((6, 6))
    specs = [s for s in getattr(body, "external_forces", []) if isinstance(s, fm.Rod)]
    if not specs or rho == 0.0:
        return total
    if pose is None:
        roll, pitch, yaw = (math.radians(a) for a in body.orientation_deg)
        pose = (body.position, kinematics.euler_quaternion(roll, pitch, yaw))
    rot = np.empty((3, 3))
    kinematics.rotation(*(float(c) for c in pose[1]), rot)
    for spec in specs:
        total += rod.added_mass(rod.pack(spec), rho, np.asarray(pose[0], float), rot)
    return total


def rods_at_rest(built, y: np.ndarray) -> None:
    """The rods' part of each rigid body's added mass taken again with the bodies at ``y`` (the
    statics' balance) instead of their start poses: the parts under the still water there."""
    p = built.params
    for b, body in enumerate(built.case.bodies):
        q = int(p.body_q[b])
        if q < 0 or not p.body_rigid[b]:
            continue
        start = rods_added_mass(body, float(p.rho))
        if start.any():
            p.body_added[b] += (
                rods_added_mass(body, float(p.rho), (y[q : q + 3], y[q + 3 : q + 7])) - start
            )


def _compensator_row(spec, body, where: str, point) -> list[float]:
    """The compensator's row: its points' indices, created on first use."""
    if not isinstance(body, RigidBody):
        raise CaseError(f"{where}: model 'compensator' steers a ship: a 'rigid' body (this one "
                        f"is '{body.type}')")  # fmt: skip
    if spec.point != fm.ORIGIN and spec.point not in body.points:
        raise CaseError(f"{where}.point: body '{body.name}' has no point '{spec.point}'; its "
                        f"points are {[fm.ORIGIN, *body.points]}")  # fmt: skip
    own = point(body.name if spec.point == fm.ORIGIN else f"{body.name}.{spec.point}", where)
    target = point(spec.target, f"{where}.target")
    inf = math.inf
    limits = (spec.max_ahead or inf, spec.max_astern or inf, spec.max_yaw_moment or inf)
    return compensator.pack(own, target, spec.heading == "line of sight", spec.distance,
                            math.radians(spec.heading_deg),
                            (spec.frequency, spec.heading_frequency),
                            (spec.damping_ratio, spec.damping_ratio), limits,
                            spec.enabled)  # fmt: skip


def _body_point(body, point, where: str) -> tuple[float, float, float]:
    """A force model's ``point``: a point's name, or body-frame coordinates [m]."""
    if not isinstance(point, str):
        return tuple(float(v) for v in point)  # type: ignore[return-value]
    if point != fm.ORIGIN and point not in body.points:
        raise CaseError(f"{where}.point: body '{body.name}' has no point '{point}'; its points "
                        f"are {[fm.ORIGIN, *body.points]}, or give [x, y, z] in the body "
                        "frame [m]")  # fmt: skip
    return offset(body, point)


def _vessel_row(case, layout, spec, body, base_dir, channels, where) -> list[float]:
    """The row and channels of a thruster, a propeller, a rudder, a fin, or a wind or current
    load."""
    if not isinstance(body, RigidBody):
        raise CaseError(f"{where}: model '{spec.model}' acts on a vessel: a 'rigid' body (this "
                        f"one is '{body.type}')")  # fmt: skip
    if isinstance(spec, sf.Propeller):
        return _propeller_row(case, spec, body, base_dir, channels, where)
    if isinstance(spec, sf.Fin):
        return _fin_row(spec, body, base_dir, channels, where)
    if isinstance(spec, sf.Thruster):
        law = spec.thrust if spec.controller is None else spec.controller.target
        channels.append(channel(law, base_dir, f"{where}.thrust"))
        feed = Constant(value=0.0) if spec.controller is None else spec.controller.feedforward
        channels.append(channel(feed, base_dir, f"{where}.controller.feedforward"))
        channels.append(in_radians(channel(spec.azimuth_deg, base_dir, f"{where}.azimuth_deg")))
        return thruster.pack(_body_point(body, spec.point, where), spec.direction,
                             spec.azimuth_deg is not None, spec.controller is not None,
                             spec.controller.gain if spec.controller else 0.0,
                             spec.max_thrust,
                             spec.controller.integral_gain if spec.controller else 0.0)  # fmt: skip
    if isinstance(spec, sf.Rudder):
        pilot = spec.autopilot
        law = spec.angle_deg if pilot is None else pilot.heading_deg
        channels.append(in_radians(channel(law, base_dir, f"{where}.angle_deg")))
        return rudder.pack(
            _body_point(body, spec.point, where), spec.area, spec.lift_slope,
            spec.stall_angle_deg, spec.drag_coefficient, spec.aspect_ratio,
            spec.slipstream_factor, (pilot.gain, pilot.rate_gain) if pilot else None,
            pilot.max_angle_deg if pilot else None, spec.coefficients,
            (gear.max_rate_deg_s, gear.time_constant) if (gear := spec.steering_gear) else None,
        )  # fmt: skip
    wind = case.environment.wind
    if isinstance(spec, sf.WindLoad) and wind is None:
        raise CaseError(f"{where}: model 'wind' needs environment.wind ({{speed [m/s], "
                        "direction_deg}}); add it, or remove the wind model")  # fmt: skip
    try:
        table = coefficients.table_rows(spec, base_dir)
    except ValueError as exc:
        raise CaseError(f"{where}: {exc}") from None
    is_wind = isinstance(spec, sf.WindLoad)
    return coefficients.pack(
        spec.point, (spec.transverse_area, spec.lateral_area), spec.length,
        wind.air_density if is_wind and wind else 0.0,
        layout.wind_channel if is_wind else -1, table,
    )  # fmt: skip


def _propeller_row(case, spec, body, base_dir, channels, where) -> list[float]:
    """A propeller's row (forces.propeller) and its channels: n [rev/s] (or the target speed)
    and the feed-forward n [rev/s]; a rate of turn below 0 during the run refused, a table of
    curves that does not cover the run warned about."""
    law = spec.controller
    if law is None:
        rate = channel(spec.rpm, base_dir, f"{where}.rpm")
        low, when = tfn.lowest(rate, case.simulation.duration)
        if low < 0.0:
            raise CaseError(f"{where}.rpm: {low:g} rpm at t = {when:g} s; the propeller turns "
                            "ahead only (rpm 0 or more: its curves are the first quadrant's); "
                            "give rpm >= 0 throughout the run")  # fmt: skip
        channels += [scaled(rate, REVOLUTIONS), tfn.constant(0.0)]
    else:
        channels.append(channel(law.target, base_dir, f"{where}.controller.target"))
        feed = channel(law.feedforward, base_dir, f"{where}.controller.feedforward")
        channels.append(scaled(feed, REVOLUTIONS))
    try:
        curves, notes = propeller.open_water(spec, base_dir)
    except ValueError as exc:
        raise CaseError(f"{where}.open_water: {exc}") from None
    for note in notes:
        log.warning(f"{where}.open_water: {note}")
    gains = (law.gain * REVOLUTIONS, law.integral_gain * REVOLUTIONS) if law else None
    return propeller.pack(
        _body_point(body, spec.point, where), spec.direction, spec.diameter,
        spec.wake_fraction, spec.thrust_deduction, spec.rotation == "right",
        spec.relative_rotative_efficiency, gains,
        spec.max_rpm * REVOLUTIONS if spec.max_rpm else None, curves,
    )  # fmt: skip


def _fin_row(spec, body, base_dir, channels, where) -> list[float]:
    """A fin's row (forces.fin) and its channel: the angle [rad] (zero with the roll
    controller)."""
    pilot = spec.roll_controller
    law = Constant(value=0.0) if pilot else spec.angle_deg
    channels.append(in_radians(channel(law, base_dir, f"{where}.angle_deg")))
    block = foil.pack(spec.area, spec.lift_slope, spec.stall_angle_deg, spec.drag_coefficient,
                      spec.aspect_ratio, spec.coefficients)  # fmt: skip
    gear = (gear.max_rate_deg_s, gear.time_constant) if (gear := spec.actuator) else None
    try:
        return fin.pack(_body_point(body, spec.point, where), spec.span_direction, block,
                        (pilot.gain, pilot.rate_gain) if pilot else None,
                        pilot.max_angle_deg if pilot else None, gear)  # fmt: skip
    except ValueError as exc:
        raise CaseError(f"{where}.{exc}") from None


def _wave_drift_row(case, spec, body, base_dir, where: str) -> list[float]:
    """The mean wave drift's row (forces.wave_drift): its point and tables."""
    if not isinstance(body, RigidBody):
        raise CaseError(f"{where}: model 'wave drift' acts on a ship: a 'rigid' body (this one "
                        f"is '{body.type}')")  # fmt: skip
    if not case.environment.waves:
        raise CaseError(f"{where}: model 'wave drift' needs environment.waves (a regular wave "
                        "{kind: airy, height [m], period [s], direction_deg} or a spectrum "
                        "{kind: jonswap, significant_height [m], peak_period [s], "
                        "direction_deg}); add them, or remove the wave drift model")  # fmt: skip
    try:
        omegas, per = wave_drift.tables(spec, base_dir)
    except ValueError as exc:
        raise CaseError(f"{where}: {exc}") from None
    return wave_drift.pack(_body_point(body, spec.point, where), omegas, per)


def force_table(body, b: int, row_of, own_added, f: dict, data: list, n_s: int,
                 where: str) -> int:  # fmt: skip
    """Body ``b``'s force models into the table ``f`` and the floats ``data`` (``row_of``:
    force_row for this body); ``fluid inertia`` takes the body's own added mass
    ``own_added`` (its rods' apart: they load their own part). Returns the states' count."""
    for k, spec in enumerate(body.external_forces):
        f["kind"].append(kind_of(spec.model))
        f["body"].append(b)
        f["at"].append(len(data))
        f["first"].append(len(row_of.keywords["channels"]))
        row = row_of(spec=spec, where=f"{where}.external forces[{k}]")
        if isinstance(spec, fm.FluidInertia):
            row = [*np.asarray(own_added).ravel()]
        data += row
        states = table.state_count(f["kind"][-1], row)  # its states follow the others'
        f["state"].append(n_s if states else -1)
        n_s += states
    return n_s


def compensator_rows(case, f: dict, fields: dict, points: np.ndarray) -> list[int]:
    """The force rows of the compensators (forces.compensator), refused where their loads would
    not be complete when they act (a rigid line's end, a group) or would depend on each other."""
    rows = [i for i, k in enumerate(f["kind"]) if k == COMPENSATOR]
    controlled = {int(f["body"][i]) for i in rows}
    rigid_ends = {int(points[k]) for k in (*fields["rs_from"], *fields["rs_to"])}
    data = fields["force_data"]
    for i in rows:
        b = int(f["body"][i])
        target = int(points[int(data[f["at"][i] + compensator.TARGET])])
        where = f"bodies ({case.bodies[b].name}).external forces (compensator)"
        for c in (b, target):
            if c in rigid_ends or fields["body_group"][c][0] >= 0:
                raise CaseError(f"{where}: body '{case.bodies[c].name}' carries a rigid line or "
                                "is part of a group; the compensator needs ships moved by their "
                                "own loads and ties or lumped lines")  # fmt: skip
        if sum(1 for j in rows if f["body"][j] == b) > 1:
            raise CaseError(f"{where}: a second compensator on the same ship; give one")
        if target == b:
            raise CaseError(f"{where}: the target point is on the ship itself; give a point "
                            "of the other body ('body.point')")  # fmt: skip
        if target in controlled:
            raise CaseError(f"{where}: its target body '{case.bodies[target].name}' has a "
                            "compensator too; give one ship of a pair the compensator")  # fmt: skip
    return rows
