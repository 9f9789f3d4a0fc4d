"""The evaluation of a system's rates, compiled for the kinds of component a system holds.

This module is a template. ``system.variants`` writes a copy of it for each set of kinds a
system holds (its line models, ties, compensators, force models' states and force models), with
the flags between the markers below set to what that system needs, imports the copy and
compiles it once (numba caches it on disk under the copy's name). numba prunes the branches of a
flag that is False before typing them, so a system of lumped-mass lines never types, optimises or
generates the rigid lines' sweeps, a hull mesh's integration or a ship's hull loads
(docs/architecture.md, "Compile time"). The package's own copy, with every flag True, is the
template only: nothing calls it.

The copies' compiled functions are reached through their addresses (``system.kernel``'s
``rhs`` and ``body_forces``, ``kernels.indirect``): a caller (an integrator's chunk, the
outputs, the statics) does not link their code into its own, so each copy is optimised and
compiled once however many callers it has.

State: ``y = [Q, V, S]`` (``system.kernel``). One evaluation: (1) every body's pose and twist
(fixed, imposed from its channels, dynamic from the state); (2) every point's position and
velocity; (3) every tie's force and every line's loads, the interior nodes' accelerations, the
end nodes' mass and loads handed to their bodies; (4) every force model; (5) each dynamic
body's 6x6 equation solved on its free degrees of freedom. O(total nodes + bodies).
"""

import math

import numpy as np
from numba import njit

from seacable.bodies import dynamics, kinematics
from seacable.forces import (
    applied,
    coefficients,
    compensator,
    diffraction,
    drag,
    fin,
    fluid_inertia,
    froude_krylov,
    hull_current,
    hydrostatic,
    linear,
    propeller,
    radiation,
    rod,
    rudder,
    servo,
    thruster,
    wave_drift,
    weight,
)
from seacable.forces.kinds import (
    APPLIED,
    BUOYANCY,
    COMPENSATOR,
    CROSS_FLOW,
    CURRENT,
    DIFFRACTION,
    DRAG,
    FIN,
    FLUID_INERTIA,
    GRAVITY,
    LINEAR_DAMPING,
    LINEAR_STIFFNESS,
    NON_LINEAR_FROUDE_KRYLOV,
    NON_LINEAR_HYDROSTATIC,
    PROPELLER,
    QUADRATIC_DAMPING,
    RADIATION_DAMPING,
    ROD,
    RUDDER,
    SERVO,
    SHORT_WING,
    THRUSTER,
    WAVE_DRIFT,
    WIND,
)
from seacable.kernels import chain3d as c3
from seacable.kernels import indirect, memory, natural
from seacable.kernels import lumped as lk
from seacable.kernels.jit import JIT, inner
from seacable.kernels.status import NON_FINITE, OK, SINGULAR_CLOSURE
from seacable.lines import natural_string, tie
from seacable.system import failures, kernel, rigid

# FLAGS: what this copy compiles (system.variants.features names each one; a copy sets them)
LUMPED = True  # lumped-mass lines
SEGMENTS = True  # rigid lines of 3D segments (and the groups rigid lines join)
PLANAR = True  # planar rigid-link lines (and the groups rigid lines join)
GROUPS = True  # free bodies solved together with the rigid lines held on them
TIP_JOINTS = True  # joints at rigid lines' ends
NATURAL = True  # natural-variables strings
TIES = True  # ties (hawsers)
COMPENSATORS = True  # the tandem compensators
STATES = True  # force models with states of their own
WAVES = True  # waves on the lines (their Morison loads and wetted parts)
FAILURES = True  # line ends released during the run (system.failures)
F_DRAG = True  # Morison drag on a body
F_FLUID_INERTIA = True  # Morison's inertia on a body
F_ROD = True  # rods fixed to a body
F_APPLIED = True  # forces and moments of time
F_STIFFNESS = True  # linear stiffness
F_DAMPING = True  # linear and quadratic damping
F_SERVO = True
F_MESH = True  # non-linear hydrostatics and Froude-Krylov on a hull mesh
F_RADIATION_DAMPING = True
F_DIFFRACTION = True
F_WAVE_DRIFT = True
F_THRUSTER = True
F_RUDDER = True
F_PROPELLER = True
F_FIN = True  # fins (roll stabilisers)
F_COEFFICIENTS = True  # wind and current coefficients
F_HULL_CURRENT = True  # short-wing and cross-flow hull loads
# END FLAGS
RIGID = SEGMENTS or PLANAR
# which of the evaluation's parts (kernel.PARTS) this copy calls, and where their addresses are
USED = {"_motions": True, "_masses": True, "_lines": LUMPED or TIES, "_models": True,
        "_backward": RIGID, "_solve": True}  # fmt: skip
MOTIONS, MASSES, LINES, MODELS, BACKWARD, SOLVE = (len(kernel.ENTRIES) + k for k in range(6))
# what system.rigid's sweeps take for a model they leave out: None (pruned before typing)
WITH_PLANAR = True if PLANAR else None
WITH_SEGMENTS = True if SEGMENTS else None


@inner
def evaluate(t, y, p, w, ydot):
    """Fill the workspace and ``ydot``; returns a status (kernels.status codes), the last of its
    parts' that is not OK. A system holding a kind this copy does not compile is refused (a
    ``RuntimeError``), never evaluated without it. Its parts (``PARTS``) take the parameter and
    work tuples, and every call from a part takes the arrays it needs, none the tuples
    (docs/architecture.md, "Calls cost reference counts"); they are compiled apart, in two
    processes at once where the machine has two cores (``system.variants``). SKIPPED: a part
    with nothing to do for this system is not called (each call takes and drops a reference to
    every array of the two tuples, about 0.3 to 0.6 us): the bodies' masses, the force models'
    loads and the bodies' equations when no body has a mass (fixed and imposed bodies) and no
    force model or tie loads one (three lumped lines of two segments between an imposed and
    fixed bodies: 4.8 -> 3.5 us an evaluation, 50 segments 10.8 -> 9.2 us)."""
    if _holds_more(p.line_n, p.rs_kind, p.nat_n, p.tie_from, p.compensator, p.group_member,
                   p.rs_tip_joint, p.n_s, p.wave, p.fail_line):  # fmt: skip
        raise RuntimeError("seacable: a system evaluated by a copy compiled without one of its "
                           "kinds (system.variants.bind gives each system its own)")  # fmt: skip
    massive = _massive(p.body_kind) or RIGID or NATURAL
    models = p.force_kind.shape[0] > 0 or COMPENSATORS or STATES
    status = _part(MOTIONS, t, y, p, w, ydot)
    if massive or models or TIES:  # else no load is added nor read: none to clear (SKIPPED)
        _part(MASSES, t, y, p, w, ydot)
    if LUMPED or TIES:  # USED
        status = _worse(status, _part(LINES, t, y, p, w, ydot))
    if models:
        _part(MODELS, t, y, p, w, ydot)
    if RIGID:
        status = _worse(status, _part(BACKWARD, t, y, p, w, ydot))
    if massive or GROUPS:
        status = _worse(status, _part(SOLVE, t, y, p, w, ydot))
    return status if kernel._finite(ydot) else NON_FINITE


@njit(inline="always", **JIT)
def _massive(kind):
    """Whether any body has a mass that forces accelerate (``kinematics.has_mass``)."""
    for b in range(kind.shape[0]):
        if kinematics.has_mass(kind[b]):
            return True
    return False


@njit(inline="always", **JIT)
def _part(k, t, y, p, w, ydot):
    """Part ``k`` of the evaluation, called by its address (``kernels.indirect``): its code is
    not linked into ``evaluate``'s, so that no part is optimised twice and the parts can be
    compiled in two processes (``system.variants``)."""
    return indirect.call5(p.entries[k], t, y, p, w, ydot)


@njit(inline="always", **JIT)
def _worse(status, part):
    """The evaluation's status after a part's: the part's when it is not OK."""
    return status if part == OK else part


@inner
def _motions(t, y, p, w, ydot):
    """(1)-(2): every body's pose and twist, the rigid lines' and natural strings' nodes and
    loads, every point's position and velocity, the bodies' submerged fractions."""
    sea = p.wave if WAVES else None  # None: the lines' wave code left out
    tf = (p.tf_breaks, p.tf_coefs, p.tf_count, p.tf_sine, p.tf_build_up)
    kinematics.body_states(
        t, y, p.body_kind, p.body_q, p.body_v, p.body_rigid, p.body_pose, p.body_channel,
        p.body_motion, p.body_track, p.body_parent, tf, w.pos, w.rot, w.vel, w.omega, w.acc,
        w.quat, w.imposed,
    )  # fmt: skip
    if RIGID:
        rigid.nodes_and_loads(
            y, p.rs_order, p.rs_kind, p.rs_n, p.rs_seg, p.rs_node, p.rs_q, p.rs_v, p.rs_from,
            p.rs_tip, p.rs_ref, p.rs_length, p.rs_wet_weight, p.rs_buoyancy, p.rs_drag_normal,
            p.rs_drag_tangential, p.rs_added, p.rs_inertia, p.rs_joint_stiffness,
            p.rs_joint_damping, p.current_z, p.current_u, p.current_v, t, p.gravity, sea,
            p.wave_depth, p.wave_stretch, p.point_body, p.point_offset, w.pos, w.rot, w.vel,
            w.omega, w.ppos, w.pvel, w.parm, w.rs, w.scratch[120:123], WITH_PLANAR,
            WITH_SEGMENTS,
        )  # fmt: skip
        if TIP_JOINTS:
            kernel._tip_joints(
                y, p.rs_kind, p.rs_n, p.rs_seg, p.rs_node, p.rs_q, p.rs_v, p.rs_to,
                p.rs_tip_joint, p.point_body, w.rot, w.omega, w.rs, w.scratch[120:123],
            )  # fmt: skip
    if NATURAL:
        for li in range(p.nat_n.shape[0]):
            natural_string.carry(
                y, natural_string.line_params(p.nat_n, p.nat_length, p.nat_mu, p.nat_ea,
                                              p.nat_alpha, p.nat_cartesian, p.gravity, li, 1.0),
                p.nat_q[li], p.nat_v[li], p.nat_from[li], p.nat_tip[li], p.point_body,
                p.point_offset, w.pos, w.rot, w.vel, w.omega, w.ppos, w.pvel, w.parm, w.nat,
                w.nat_work,
            )  # fmt: skip
    kinematics.point_states(
        p.point_body, p.point_offset, w.pos, w.rot, w.vel, w.omega, w.ppos, w.pvel, w.parm
    )
    kernel._fractions(p.body_kind, p.body_shape, w.pos, w.fraction)
    return OK


@inner
def _masses(t, y, p, w, ydot):
    """Every body's mass and velocity terms; the loads cleared."""
    w.load[:, :] = 0.0
    dynamics.body_masses(
        p.body_kind, p.body_rigid, p.body_mass, p.body_cog, p.body_inertia, p.body_added,
        p.body_coriolis, p.body_shape, w.fraction, w.pos, w.rot, w.vel, w.omega, p.current_z,
        p.current_u, p.current_v, w.mass, w.bias,
    )  # fmt: skip
    return OK


@inner
def _lines(t, y, p, w, ydot):
    """(3): every tie's force and every lumped-mass line's loads, its interior nodes'
    accelerations, its end nodes' mass and loads handed to their bodies."""
    status = OK
    if TIES:
        tie.forces(
            w.ppos, w.pvel, p.tie_from, p.tie_to, p.tie_length, p.tie_stiffness, p.tie_damping,
            p.tie_table, p.tie_first, p.tie_count, w.tie_tension, w.tie_force,
        )  # fmt: skip
        for k in range(p.tie_from.shape[0]):
            f = w.tie_force[k]
            a, b = p.tie_from[k], p.tie_to[k]
            dynamics.add_force(w.parm[a], f[0], f[1], f[2], w.load[p.point_body[a]])
            dynamics.add_force(w.parm[b], -f[0], -f[1], -f[2], w.load[p.point_body[b]])
    sea = p.wave if WAVES else None
    if LUMPED and not kernel._lumped_lines(
        y, p.line_n, p.line_seg, p.line_node, p.line_q, p.line_v, p.line_from, p.line_to,
        p.seg_length, p.seg_stiffness, p.seg_damping, p.slack_allowed, p.seg_drag_normal,
        p.seg_drag_tangential, p.seg_wet_weight, p.seg_buoyancy, p.seg_added_mass, p.node_bend,
        p.node_mass, p.node_seabed_stiffness, p.node_seabed_damping, p.seabed_z,
        p.seabed_friction, p.seabed_slip_speed, p.seabed_band, p.current_z, p.current_u,
        p.current_v, t, p.gravity, sea, p.wave_depth, p.wave_stretch, p.point_body,
        p.body_kind, w.ppos, w.pvel, w.parm, w.omega, w.line, w.nodes, w.end_mass, w.end_load,
        w.mass, w.load, ydot,
    ):  # fmt: skip
        status = NON_FINITE
    return status


@inner
def _models(t, y, p, w, ydot):
    """(4): every force model's load (kept from the last evaluation where it holds), the
    compensators' after them all, the models' states' rates."""
    tf = (p.tf_breaks, p.tf_coefs, p.tf_count, p.tf_sine, p.tf_build_up)
    if not kernel._models_kept(t, y, p.n_q + p.n_v, p.slack_allowed == lk.FROZEN, w.pos,
                               w.quat, w.vel, w.omega, w.models_key):  # fmt: skip
        w.models[:, :] = 0.0
        add_all(
            t, y, p.force_kind, p.force_body, p.force_at, p.force_first, p.force_state,
            p.force_data, p.body_mass, p.body_cog, p.body_volume, p.body_cob, w.fraction, w.quat,
            w.pos, w.rot, w.vel, w.omega, p.gravity, p.rho, p.current_z, p.current_u,
            p.current_v, p.wave, p.wave_depth, p.wave_stretch, w.hull, w.memory, w.trig, tf,
            w.models,
        )  # fmt: skip
    for b in range(w.load.shape[0]):  # a loop: an array expression compiles slowly
        for c in range(6):
            w.load[b, c] += w.models[b, c]
    if COMPENSATORS:
        compensator.apply_all(  # after every other load: it cancels them
            p.compensator, p.force_body, p.force_at, p.force_data, p.point_body, p.body_kind,
            p.body_free, w.mass, w.bias, w.load, w.acc, w.ppos, w.pvel, w.parm, w.rot, w.omega,
            w.control,
        )  # fmt: skip
    if STATES:
        state_rates(t, y, p.force_kind, p.force_body, p.force_at, p.force_first, p.force_state,
                    p.force_data, w.pos, w.rot, w.vel, w.omega, w.ppos, w.pvel, tf,
                    ydot)  # fmt: skip
    return OK


@inner
def _backward(t, y, p, w, ydot):
    """The rigid lines' backward sweeps: their base bodies' articulated inertias."""
    for b in range(w.load.shape[0]):  # for the statics' moment balance of rigid lines
        for c in range(3):
            w.own_load[b, c] = w.load[b, c]
    if not rigid.backward(
        p.rs_order, p.rs_kind, p.rs_n, p.rs_seg, p.rs_node, p.rs_v, p.rs_from, p.rs_to,
        p.rs_tip, p.rs_held, p.rs_port, p.rs_length, p.rs_mass, p.rs_inertia,
        p.stabilization_frequency, p.point_body, p.point_offset, p.body_kind, p.body_pose,
        y, w.pos, w.rot, w.vel, w.omega, w.acc, w.ppos, w.pvel, w.parm, w.mass, w.bias,
        w.load, w.rs, w.rs_force, w.rs_la, w.scratch, WITH_PLANAR, WITH_SEGMENTS,
    ):  # fmt: skip
        return SINGULAR_CLOSURE
    return OK


@inner
def _solve(t, y, p, w, ydot):
    """(5): each dynamic body's equation solved on its free degrees of freedom (with the rigid
    lines held on it, in groups), the rigid lines' forward sweeps, the natural strings'
    rates."""
    status = OK
    if not kernel._solve_bodies(y, p.body_kind, p.body_free, p.body_q, p.body_v, p.body_rigid,
                                p.body_group, w.load, w.bias, w.mass, w.acc, w.rhs6,
                                ydot):  # fmt: skip
        status = NON_FINITE
    if GROUPS:
        if not rigid.solve_groups(
            y, p.body_kind, p.body_free, p.body_q, p.body_v, p.body_rigid, p.body_group,
            p.group_first, p.group_member, p.joint, p.rs_from, p.rs_to, p.rs_held,
            p.point_body, w.acc, w.omega, w.parm, w.ppos, w.pvel, p.stabilization_frequency,
            w.rs_la, w.rs_force, w.load, w.bias, w.mass, w.group, w.scratch, ydot,
        ):  # fmt: skip
            status = SINGULAR_CLOSURE
    if RIGID:
        rigid.forward(
            p.rs_order, p.rs_kind, p.rs_n, p.rs_seg, p.rs_node, p.rs_q, p.rs_v, p.rs_from,
            p.rs_tip, p.rs_held, p.rs_port, p.rs_length, p.point_body, p.body_kind, y, w.omega,
            w.acc, w.parm, w.rs, w.rs_force, w.rs_la, w.scratch, ydot, WITH_PLANAR,
            WITH_SEGMENTS,
        )  # fmt: skip
    if NATURAL:
        for li in range(p.nat_n.shape[0]):
            params = natural_string.line_params(p.nat_n, p.nat_length, p.nat_mu, p.nat_ea,
                                                p.nat_alpha, p.nat_cartesian, p.gravity, li,
                                                p.body_mass[p.nat_tip[li]])  # fmt: skip
            if natural_string.rates(t, y, params, p.nat_q[li], p.nat_v[li], w.nat, w.nat_work,
                                    w.nat_dot, ydot) != OK:  # fmt: skip
                status = NON_FINITE
    return status


@inner
def _holds_more(line_n, rs_kind, nat_n, tie_from, compensators, group_member, tip_joints, n_s,
                wave, failures):  # fmt: skip
    """Whether the system holds a kind of line, tie, compensator, stateful force model or waves
    this copy does not compile (its force models: ``add_all``). The arrays come one by one."""
    more = line_n.shape[0] > 0 and not LUMPED
    for li in range(rs_kind.shape[0]):
        planar = rs_kind[li] == rigid.PLANAR
        more = more or (planar and not PLANAR) or (not planar and not SEGMENTS)
    more = more or (nat_n.shape[0] > 0 and not NATURAL)
    more = more or (tie_from.shape[0] > 0 and not TIES)
    more = more or (compensators.shape[0] > 0 and not COMPENSATORS)
    more = more or (group_member.shape[0] > 0 and not GROUPS)
    more = more or (tip_joints.shape[0] > 0 and not TIP_JOINTS)
    more = more or (wave.shape[1] > 0 and not WAVES)
    more = more or (failures.shape[0] > 0 and not FAILURES)
    return more or (n_s > 0 and not STATES)


@inner
def body_forces(t, y, p, w, pos, vel, fraction, load):
    """Every force model's load into ``load`` (nb, 6) with the bodies at ``pos``, moving at
    ``vel`` and submerged by ``fraction`` (the rest as ``w`` holds it): the rigid lines' point
    derivatives (numerics.rigid_derivatives). Returns 0."""
    tf = (p.tf_breaks, p.tf_coefs, p.tf_count, p.tf_sine, p.tf_build_up)
    add_all(
        t, y, p.force_kind, p.force_body, p.force_at, p.force_first, p.force_state, p.force_data,
        p.body_mass, p.body_cog, p.body_volume, p.body_cob, fraction, w.quat, pos,
        w.rot, vel, w.omega, p.gravity, p.rho, p.current_z, p.current_u, p.current_v, p.wave,
        p.wave_depth, p.wave_stretch, w.hull, w.memory, w.trig, tf, load,
    )  # fmt: skip
    return np.int64(0)


@inner
def add_all(
    t, y, kind, body, at, first, state, data, mass, cog, volume, cob, fraction, quat, pos,
    rot, vel, omega, gravity, rho, current_z, current_u, current_v, wave, wave_depth,
    wave_stretch, hull, history, trig, tf, rhs,
):  # fmt: skip
    """Add every force model's force and moment to its body's row of ``rhs`` (nb, 6); a model
    with states reads them from ``y`` at ``state[f]``; the mesh models share the workspace
    ``hull`` (kernels.hull.place), the radiation models read their velocity ``history``
    (kernels.memory; its first floats are a model's scratch), the models on the waves'
    kinematics their scratch ``trig`` (kernels.waves.scratch, as wide as the waves). The
    compensators act later (``evaluate``); a kind this copy does not compile is refused (a
    ``RuntimeError``)."""
    if trig.shape[1] < wave.shape[1]:
        raise RuntimeError("seacable: a workspace made for fewer wave components")
    for f in range(kind.shape[0]):
        b = body[f]
        row = data[at[f] :]
        k = kind[f]
        if k == GRAVITY:
            weight.add_gravity(mass[b], cog[b], rot[b], gravity, rhs[b])
        elif k == BUOYANCY:
            weight.add_buoyancy(volume[b], cob[b], fraction[b], rot[b], gravity, rho, rhs[b])
        elif F_DRAG and k == DRAG:
            drag.add(row, fraction[b], pos[b], rot[b], vel[b], current_z, current_u, current_v,
                     t, wave, wave_depth, wave_stretch, trig, rhs[b])  # fmt: skip
        elif F_FLUID_INERTIA and k == FLUID_INERTIA:
            fluid_inertia.add(volume[b], cob[b], row, fraction[b], pos[b], rot[b], rho, t, wave,
                              wave_depth, wave_stretch, trig, rhs[b])  # fmt: skip
        elif F_ROD and k == ROD:
            rod.add(row, pos[b], rot[b], vel[b], omega[b], rho, gravity, current_z, current_u,
                    current_v, t, wave, wave_depth, wave_stretch, trig, rhs[b])  # fmt: skip
        elif F_APPLIED and k == APPLIED:
            applied.add(row, first[f], t, rot[b], tf, rhs[b])
        elif F_STIFFNESS and k == LINEAR_STIFFNESS:
            linear.add_stiffness(row, pos[b], quat[b], rhs[b])
        elif F_DAMPING and (k == LINEAR_DAMPING or k == QUADRATIC_DAMPING):
            linear.add_damping(row, pos[b], rot[b], vel[b], omega[b], current_z, current_u,
                               current_v, rhs[b])  # fmt: skip
        elif F_SERVO and k == SERVO:
            servo.add(row, y, state[f], rhs[b])
        elif F_MESH and k == NON_LINEAR_HYDROSTATIC:
            hydrostatic.add(row, b, pos[b], rot[b], rho, gravity, wave, t, hull, rhs[b])
        elif F_RADIATION_DAMPING and k == RADIATION_DAMPING:
            radiation.add(row, t, y, state[f], rot[b], vel[b], omega[b], history, rhs[b])
        elif F_DIFFRACTION and k == DIFFRACTION:
            diffraction.add(row, t, wave, pos[b], rot[b], history[0 : memory.SCRATCH], rhs[b])
        elif F_MESH and k == NON_LINEAR_FROUDE_KRYLOV:
            froude_krylov.add(row, b, pos[b], rot[b], rho, gravity, wave, t, wave_depth,
                              wave_stretch, hull, rhs[b])  # fmt: skip
        elif F_WAVE_DRIFT and k == WAVE_DRIFT:
            wave_drift.add(row, t, wave, rot[b], rhs[b])
        elif F_THRUSTER and k == THRUSTER:
            thruster.add(row, first[f], t, rot[b], vel[b], tf, y, state[f], rhs[b])
        elif F_RUDDER and k == RUDDER:
            rudder.add(row, first[f], t, rho, pos[b], rot[b], vel[b], omega[b], current_z,
                       current_u, current_v, tf, y, state[f], rhs[b])  # fmt: skip
        elif F_PROPELLER and k == PROPELLER:
            propeller.add(row, first[f], t, rho, pos[b], rot[b], vel[b], omega[b], current_z,
                          current_u, current_v, tf, y, state[f], rhs[b])  # fmt: skip
        elif F_FIN and k == FIN:
            fin.add(row, first[f], t, rho, pos[b], rot[b], vel[b], omega[b], current_z,
                    current_u, current_v, tf, y, state[f], rhs[b])  # fmt: skip
        elif F_COEFFICIENTS and (k == WIND or k == CURRENT):
            coefficients.add(row, t, tf, rho, pos[b], rot[b], vel[b], omega[b], current_z,
                             current_u, current_v, rhs[b])  # fmt: skip
        elif F_HULL_CURRENT and (k == SHORT_WING or k == CROSS_FLOW):
            hull_current.add(row, rho, pos[b], rot[b], vel[b], omega[b], current_z, current_u,
                             current_v, rhs[b])  # fmt: skip
        elif k != COMPENSATOR:
            raise RuntimeError(
                "seacable: a force model evaluated by a copy compiled without "
                "its kind (system.variants.bind gives each its own)"
            )


@inner
def state_rates(t, y, kind, body, at, first, state, data, pos, rot, vel, omega, ppos, pvel, tf,
                ydot):  # fmt: skip
    """The rates of every force model's states (read from ``y``) into ``ydot``."""
    for f in range(kind.shape[0]):
        if state[f] < 0:
            continue
        b = body[f]
        row = data[at[f] :]
        k = kind[f]
        if F_SERVO and k == SERVO:
            servo.rates(row, pos[b], vel[b], ppos, pvel, state[f], ydot)
        elif F_RADIATION_DAMPING and k == RADIATION_DAMPING:
            radiation.rates(row, y, state[f], rot[b], vel[b], omega[b], ydot)
        elif F_THRUSTER and k == THRUSTER:
            thruster.rates(row, first[f], t, rot[b], vel[b], tf, y, state[f], ydot)
        elif F_RUDDER and k == RUDDER:
            rudder.rates(row, first[f], t, rot[b], omega[b], tf, y, state[f], ydot)
        elif F_PROPELLER and k == PROPELLER:
            propeller.rates(row, first[f], t, rot[b], vel[b], tf, y, state[f], ydot)
        elif F_FIN and k == FIN:
            fin.rates(row, first[f], t, rot[b], omega[b], tf, y, state[f], ydot)


@inner
def project(y, p):
    """Every rigid body's quaternion back to unit length, every rigid segment's director too and
    its rate normal to it, every natural string's cartesian tangents (after each accepted step;
    from Python too: system.relax). Returns 0."""
    if SEGMENTS:
        for li in range(p.rs_n.shape[0]):
            if p.rs_kind[li] == rigid.SEGMENTS_3D:
                c3.project_directors(y, p.rs_n[li], p.rs_q[li], p.rs_v[li])
    if NATURAL:
        for li in range(p.nat_n.shape[0]):
            if p.nat_cartesian[li] == 1:
                natural.project_tangents(y, p.nat_n[li], p.nat_q[li], p.nat_v[li])
    for b in range(p.body_kind.shape[0]):
        if p.body_kind[b] == kinematics.DYNAMIC and p.body_rigid[b] == 1:
            q = p.body_q[b] + 3
            norm = np.sqrt(y[q] ** 2 + y[q + 1] ** 2 + y[q + 2] ** 2 + y[q + 3] ** 2)
            for c in range(4):
                y[q + c] /= norm
    return np.int64(0)


@inner
def after_step(t, y, p, w):
    """An accepted step ending at (t, y): the radiation convolutions record their body's
    velocity (kernels.memory), and the line ends whose failure comes are released in ``y``
    and the parameters (system.failures). Every integrator calls it where it projects the
    state. Returns 1 when a release changed the system (the integrator's derivatives at
    (t, y) are stale), else 0."""
    _histories(t, y, p, w, False)
    if FAILURES:
        return _failures(t, y, p, w)
    return np.int64(0)


@inner
def start_memory(t, y, p, w):
    """The radiation convolutions' histories at the run's start (at rest before it), and every
    line end attached again (system.failures: a built system runs again from intact lines).
    Returns 0."""
    if FAILURES:
        for k in range(p.fail_line.shape[0]):
            p.fail_state[k] = np.nan
            for c in range(3):
                p.body_free[p.fail_body[k], c] = 0.0
            failures.attach(p, k, p.fail_orig[k])
    return _histories(t, y, p, w, True)


@inner
def _failures(t, y, p, w):
    """Release every failure whose time has come or one of whose lines' end segments at its
    point has reached its tension (the tension of the last evaluation, the step's end or its
    last stage) after the run's start: its point body takes the position and velocity of the
    point the ends were attached to at (t, y), its degrees of freedom are freed and the ends
    moved onto it (system.failures). Returns 1 when it released one, else 0."""
    changed = np.int64(0)
    if t <= 0.0:
        return changed
    for k in range(p.fail_line.shape[0]):
        if not math.isnan(p.fail_state[k]):
            continue
        li = p.fail_line[k]
        column = p.line_node[li] + (0 if p.fail_end[k] == 0 else p.line_n[li] - 1)
        if t >= p.fail_time[k] or w.nodes[lk._T, column] >= p.fail_tension[k]:
            if changed == 0:  # every point at (t, y) (the motions part writes no rate)
                _part(MOTIONS, t, y, p, w, w.rhs6)
            for j in range(p.fail_line.shape[0]):
                if p.fail_group[j] == p.fail_group[k] and math.isnan(p.fail_state[j]):
                    failures.release(t, y, p, w, j)
            changed = np.int64(1)
    if changed:
        w.models_key[0] = np.nan  # the kept force models' loads are not this system's
    return changed


@njit(inline="always", **JIT)
def _histories(t, y, p, w, start):
    """Each radiation convolution's history started (``start``) or extended at (t, y); the
    force models' kept loads forgotten (the histories change them)."""
    w.models_key[0] = np.nan
    if F_RADIATION_DAMPING:
        for f in range(p.force_kind.shape[0]):
            if _convolves(p, f):
                b = p.force_body[f]
                kinematics.body_frame_velocity(y, p.body_q[b], p.body_v[b], w.memory)
                row = p.force_data[p.force_at[f] + radiation.MEMORY :]
                if start:
                    memory.start(row, w.memory, t, w.memory[0:6])
                else:
                    memory.record(row, w.memory, t, w.memory[0:6])
    return np.int64(0)


@njit(inline="always", **JIT)
def _convolves(p, f):
    """Force model f is a radiation convolution (forces.radiation), which keeps a history."""
    return (p.force_kind[f] == RADIATION_DAMPING
            and p.force_data[p.force_at[f]] == radiation.CONVOLUTION)  # fmt: skip
