"""Compiled energies of a system at a state (after ``kernel.rhs`` filled the workspace):
kinetic (bodies with their added mass, every line node with its own and its added mass),
the potential of gravity and buoyancy (line segments as ``kernels.lumped`` counts them, each
body's ``gravity``, ``buoyancy`` and ``rod`` force models, the free surface through
``kernels.surface``), and elastic (axial strain, seabed springs, bending, ties, linear
stiffness). Without damping, drag or applied forces their sum is constant: the test of the
coupling between bodies and lines (tests/test_system.py)."""

import math

import numpy as np

from seacable.bodies import dynamics, kinematics
from seacable.bodies.kinematics import turn
from seacable.forces import hydrostatic, linear, rod
from seacable.forces.kinds import (
    BUOYANCY,
    GRAVITY,
    LINEAR_STIFFNESS,
    NON_LINEAR_HYDROSTATIC,
    ROD,
)
from seacable.kernels import waves
from seacable.kernels.chain3d_outputs import segment_energies
from seacable.kernels.jit import inner
from seacable.kernels.lumped_outputs import line_energies
from seacable.kernels.planar_chain import link_energies
from seacable.kernels.surface import POINT, submersion
from seacable.lines import lumped_mass, natural_string, tip_joint
from seacable.system import rigid


@inner
def _lines(y, p, w):
    kinetic = gravity = elastic = 0.0
    for li in range(p.line_n.shape[0]):
        n = p.line_n[li]
        lumped_mass.gather(y, n, p.line_q[li], p.line_v[li], w.ppos, w.pvel, p.line_from[li],
                           p.line_to[li], w.line)  # fmt: skip
        k, g, e = line_energies(
            w.line, n, p.line_seg[li], p.line_node[li], p.node_mass, p.seg_length,
            p.seg_stiffness, p.seg_wet_weight, p.seg_buoyancy, p.seabed_z,
            p.node_seabed_stiffness, p.seabed_band, p.node_bend, p.slack_allowed, w.nodes,
        )  # fmt: skip
        kinetic += k
        gravity += g
        elastic += e
    return kinetic, gravity, elastic


@inner
def _tie_energy(elongation, stiffness, table, first, count):
    """Integral of the tie's tension (damping aside) from 0 to ``elongation`` [J]."""
    if elongation <= 0.0:
        return 0.0
    if stiffness > 0.0:
        return 0.5 * stiffness * elongation * elongation
    total = 0.0
    for k in range(first + 1, first + count):
        e0, t0, e1, t1 = table[k - 1, 0], table[k - 1, 1], table[k, 0], table[k, 1]
        top = elongation if (elongation <= e1 or k == first + count - 1) else e1
        slope = (t1 - t0) / (e1 - e0)
        total += (top - e0) * (t0 + 0.5 * slope * (top - e0))
        if top == elongation:
            break
    return total


@inner
def _bodies(y, p, w, mesh):
    kinetic = gravity = elastic = 0.0
    m6 = np.empty((6, 6))
    bias = np.empty(6)
    for b in range(p.body_kind.shape[0]):
        if not kinematics.has_mass(p.body_kind[b]):
            continue
        scale = w.fraction[b] if p.body_shape[b, 0] != POINT else 1.0
        dynamics.rigid_mass(p.body_mass[b], p.body_cog[b], p.body_inertia[b], p.body_added[b],
                            w.rot[b], w.vel[b], w.omega[b], scale, p.body_coriolis[b], m6,
                            bias)  # fmt: skip
        nu = (w.vel[b, 0], w.vel[b, 1], w.vel[b, 2], w.omega[b, 0], w.omega[b, 1], w.omega[b, 2])
        for i in range(6):
            for j in range(6):
                kinetic += 0.5 * nu[i] * m6[i, j] * nu[j]
    for f in range(p.force_kind.shape[0]):
        b = p.force_body[f]
        kind = p.force_kind[f]
        if kind == GRAVITY:
            arm = turn(w.rot[b], (p.body_cog[b, 0], p.body_cog[b, 1], p.body_cog[b, 2]))
            gravity += p.body_mass[b] * p.gravity * (w.pos[b, 2] + arm[2])
        elif kind == BUOYANCY:
            weight = p.rho * p.gravity * p.body_volume[b]
            if p.body_shape[b, 0] == POINT:
                arm = turn(w.rot[b], (p.body_cob[b, 0], p.body_cob[b, 1], p.body_cob[b, 2]))
                gravity -= weight * (w.pos[b, 2] + arm[2])
            else:
                _, _, integral = submersion(w.pos[b, 2], p.body_shape[b])
                gravity -= weight * integral
        elif kind == NON_LINEAR_HYDROSTATIC:
            if mesh is None:  # no mesh: compiled without the hull's potential
                continue
            row = p.force_data[p.force_at[f] :]
            gravity += hydrostatic.potential(row, b, w.pos[b], w.rot[b], p.rho, p.gravity,
                                             waves.still(), w.hull)  # fmt: skip
        elif kind == LINEAR_STIFFNESS:
            row = p.force_data[p.force_at[f] :]
            elastic += linear.stiffness_energy(row, w.pos[b], w.quat[b])
        elif kind == ROD:
            row = p.force_data[p.force_at[f] :]
            gravity += rod.potential(row, w.pos[b], w.rot[b], p.rho, p.gravity)
    for k in range(p.tie_from.shape[0]):
        a, c = p.tie_from[k], p.tie_to[k]
        d = 0.0
        for i in range(3):
            d += (w.ppos[c, i] - w.ppos[a, i]) ** 2
        elastic += _tie_energy(math.sqrt(d) - p.tie_length[k], p.tie_stiffness[k], p.tie_table,
                               p.tie_first[k], p.tie_count[k])  # fmt: skip
    return kinetic, gravity, elastic


@inner
def energies(y, p, w, lumped, planar, segments, natural, mesh):
    """(kinetic, gravity potential, elastic) [J] at y, the workspace filled by kernel.rhs.
    ``lumped``, ``planar``, ``segments``, ``natural``, ``mesh``: True, or None where the system
    holds none of that kind (compiled apart, the kind left out: ``kernel.present``)."""
    k1 = g1 = e1 = k3 = g3 = e3 = 0.0
    if lumped is not None:
        k1, g1, e1 = _lines(y, p, w)
    k2, g2, e2 = _bodies(y, p, w, mesh)
    if planar is not None or segments is not None:
        k3, g3, e3 = _rigid(y, p, w, planar, segments)
    if natural is not None:
        for li in range(p.nat_n.shape[0]):  # natural strings
            k, g, e = natural_string.own(y, p, w, li)
            k3, g3, e3 = k3 + k, g3 + g, e3 + e
    return k1 + k2 + k3, g1 + g2 + g3, e1 + e2 + e3


@inner
def _rigid(y, p, w, planar, segments):
    """The rigid lines' segments (kernels.chain3d_outputs.segment_energies, kernels.planar_chain
    .link_energies; ``planar``, ``segments``: as ``energies``')."""
    kinetic = gravity = elastic = 0.0
    ref = np.empty(3)
    for li in range(p.rs_n.shape[0]):
        n, s0 = p.rs_n[li], p.rs_seg[li]
        base = p.point_body[p.rs_from[li]]
        for c in range(3):
            ref[c] = (w.rot[base, c, 0] * p.rs_ref[li, 0] + w.rot[base, c, 1] * p.rs_ref[li, 1]
                      + w.rot[base, c, 2] * p.rs_ref[li, 2])  # fmt: skip
        e = s0 + n
        ws = rigid.workspace(p, w, li)
        k = g = el = 0.0
        if p.rs_kind[li] == 1:  # planar
            if planar is None:
                continue
            k, g, el = link_energies(
                n, y, p.rs_q[li], p.rs_v[li], p.rs_length[s0:e], p.rs_mass[s0:e],
                p.rs_inertia[s0:e], p.rs_wet_weight[s0:e], p.rs_buoyancy[s0:e],
                p.rs_joint_stiffness[s0:e], math.atan2(ref[0], -ref[2]), ws,
            )  # fmt: skip
        elif segments is not None:
            k, g, el = segment_energies(
                n, p.rs_length[s0:e], p.rs_mass[s0:e], p.rs_wet_weight[s0:e],
                p.rs_buoyancy[s0:e], p.rs_joint_stiffness[s0:e], ref, ws,
            )  # fmt: skip
        kinetic += k
        gravity += g
        elastic += el
    for j in range(p.rs_tip_joint.shape[0]):  # the joints at lines' ends
        li, nxt = int(p.rs_tip_joint[j, 0]), int(p.rs_tip_joint[j, 1])
        b = p.point_body[p.rs_to[li]]
        for c in range(3):
            ref[c] = (w.rot[b, c, 0] * p.rs_tip_joint[j, 2] + w.rot[b, c, 1] * p.rs_tip_joint[j, 3]
                      + w.rot[b, c, 2] * p.rs_tip_joint[j, 4])  # fmt: skip
        at = p.rs_q[nxt] if nxt >= 0 else -1
        elastic += tip_joint.energy(p.rs_kind[li] == 1, p.rs_n[li], y, p.rs_q[li], ref,
                                    p.rs_tip_joint[j, 5], at)  # fmt: skip
    return kinetic, gravity, elastic
