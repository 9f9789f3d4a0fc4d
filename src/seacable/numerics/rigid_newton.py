"""Newton's rows of a planar rigid-link line in maximal coordinates: a banded block, so that an
implicit step costs O(n) in the line's links (derivation: docs/rigid_newton.md).

In the links' angles a rigid line's Newton block is dense (every angular acceleration depends on
every angle). Its Newton correction delta (J delta = r, J = d(residual)/d(a1)) is instead found
from the linearised Newton-Euler equations of the links, whose unknowns are, per link i,

    delta_i, dA_(i+1) (2), dlam_i (2), dP_(i+1) (2), dV_(i+1) (2)    (9, in this order)

and dlam_n (2) at the tip: the change of each node's acceleration A, of the force lam the part
above a node exerts on the part below, and of each node's position P and velocity V, all
scaled by (1 - af). Every row (a link's rotation, its kinematics, its translation, its node's
position and velocity, the tip body's equation) involves one link and its neighbours, so the
block is banded (bandwidth about 14, whatever n) and ``numerics.bordered`` factorises it in
O(n). Eliminating the auxiliary unknowns gives delta = J^-1 r exactly: the rows are the exact
linearisation of the equations the articulated sweeps solve, with the loads' derivatives (drag,
weight and the free surface's share, joint springs and dampers, the tip body's force models)
from finite differences of the loads themselves (``kernels.planar_chain.link_loads``,
``forces.table.add_all``), each link's at its own node's position and velocity.

Lines written so (``eligible``): planar, their base on a fixed or imposed body, their tip free,
held (on a fixed or imposed body's point, or on a carried body's held axes: the Baumgarte
closure's rows) or carrying a point body that nothing else touches. Others (3D segments, a base
on a dynamic body, trees of lines) keep the dense block of the differences over the
accelerations.
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from seacable.bodies import kinematics
from seacable.forces import table
from seacable.kernels import planar_chain as pc
from seacable.kernels.timefn import JIT
from seacable.system import kernel as system_kernel
from seacable.system import rigid

PER_LINK = 9  # unknowns (and rows) per link; two more at the tip
FD_STEP = 1.5e-8  # relative change of a position, velocity, angle or rate (difference quotients)
DERIVATIVES = 22  # rows of one line's loads derivatives (``_loads_derivatives``)


class RigidRows(NamedTuple):
    """The planar rigid lines whose Newton block is written in maximal coordinates (flat, with
    offsets; ``line`` may be empty)."""

    line: np.ndarray  # (k,) int: the rigid lines (indices into the rs_* arrays)
    aux: np.ndarray  # (k,) int: each line's first auxiliary unknown (8 n + 2 of them)
    dest_at: np.ndarray  # (k + 1,) int: each line's first entry in ``dest``
    dest: np.ndarray  # every entry's place in Newton's flat matrix (``entries``' order)
    geo: np.ndarray  # (2 total links,) l n of each link when the matrix was built (the
    # right-hand side's transformation must be the matrix's: rewritten with it)
    size: int  # unknowns of Newton's system: the velocity variables, then the auxiliary ones


def eligible(p) -> np.ndarray:
    """The planar rigid lines whose base is on a fixed or imposed body and whose tip is free,
    held, or carries a point body that no other line, tie or string touches."""
    nodes = set(np.asarray(p.point_body)[np.concatenate([p.line_from, p.line_to])].tolist())
    tied = set(np.asarray(p.point_body)[np.concatenate([p.tie_from, p.tie_to])].tolist())
    strings = set(np.asarray(p.nat_tip).tolist()) | set(
        np.asarray(p.point_body)[np.asarray(p.nat_from, dtype=np.int64)].tolist()
    )
    bases = [int(p.point_body[a]) for a in p.rs_from]
    out = []
    for li in range(len(p.rs_n)):
        tip = int(p.rs_tip[li])
        if p.rs_kind[li] != rigid.PLANAR:
            continue
        if p.body_kind[bases[li]] not in (kinematics.FIXED, kinematics.IMPOSED):
            continue
        if tip >= 0 and (tip in nodes or tip in tied or tip in strings or tip in bases):
            continue
        out.append(li)
    return np.array(out, dtype=np.int64)


def local_to_global(n: int, v: int, aux: int) -> np.ndarray:
    """Each local unknown's index in Newton's system: delta_i is velocity variable v + i, the
    auxiliary unknowns follow from ``aux``."""
    local = np.arange(PER_LINK * n + 2)
    link, k = local // PER_LINK, local % PER_LINK
    out = np.where(k == 0, v + link, aux + (PER_LINK - 1) * link + k - 1)
    tip = local >= PER_LINK * n
    out[tip] = aux + (PER_LINK - 1) * n + (local[tip] - PER_LINK * n)
    return out.astype(np.int64)


def entries_pattern(n: int, v: int, aux: int, held: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The rows and columns (Newton's unknowns) of a line's entries, in ``entries``' order
    (``held``: x and z, 1.0 on a held axis)."""
    size = _max_entries(n)
    rows, cols, vals = np.empty(size, np.int64), np.empty(size, np.int64), np.empty(size)
    zero = np.zeros((DERIVATIVES, n))
    count = entries(n, np.ones(n), np.ones(n), np.ones(n), np.zeros(n), np.zeros(n),
                    np.zeros((4, n)), np.zeros((2, n + 1)), zero, np.zeros(4), np.zeros(8),
                    np.asarray(held, dtype=np.float64), 1.0, 1.0, 1.0, 1.0, rows, cols,
                    vals)  # fmt: skip
    glob = local_to_global(n, v, aux)
    return glob[rows[:count]], glob[cols[:count]]


def _max_entries(n: int) -> int:
    return 47 * n + 14


@njit(inline="always", **JIT)
def _put(rows, cols, vals, k, r, c, value):
    rows[k], cols[k], vals[k] = r, c, value
    return k + 1


@njit(**JIT)
def entries(n, length, mass, inertia, omega, thdd, geometry, lam, der, tip_mass, tip_der, held,
            stabilization, km, kx, kv, rows, cols, vals):  # fmt: skip
    """One line's entries (local row, local column, value; docs/rigid_newton.md): ``omega`` and
    ``thdd`` the links' rates and angular accelerations, ``geometry`` (4, n) their e and n
    (x, z), ``lam`` (2, n + 1) the node forces, ``der`` the loads' derivatives
    (``_loads_derivatives``), ``tip_mass`` (2x2) and ``tip_der`` (d load / d(P, V), 2x2 each)
    of the tip body; ``held`` (x, z): 1.0 on an axis the tip is held on (Baumgarte, at
    ``stabilization`` rad/s); km = 1 - am, kx = (1 - af) b h^2, kv = (1 - af) g h. Returns the
    count.
    The entries are the same whatever the values: ``entries_pattern`` reads them from here."""
    k = 0
    b = PER_LINK
    for i in range(n):
        li, ex, ez, nx, nz = length[i], geometry[0, i], geometry[1, i], geometry[2, i], geometry[
            3, i]  # fmt: skip
        om, f = omega[i], thdd[i]
        d = b * i  # delta_i; A_(i+1) d+1, d+2; lam_i d+3, d+4; P_(i+1) d+5, d+6; V_(i+1) d+7, d+8
        up = d - b  # link i - 1's (node i's A, P, V)
        lam_next = b * (i + 1) + 3 if i + 1 < n else b * n
        sx, sz = lam[0, i] + lam[0, i + 1], lam[1, i] + lam[1, i + 1]
        # rotation about the centre: J f + l/2 n.(lam_i + lam_(i+1)) - Q = 0
        diag = (inertia[i] * km - 0.5 * li * (ex * sx + ez * sz) * kx - der[16, i] * kx
                - der[17, i] * kv)  # fmt: skip
        k = _put(rows, cols, vals, k, d, d, diag)
        if i > 0:
            k = _put(rows, cols, vals, k, d, up, -(der[18, i] * kx + der[19, i] * kv))
        if i + 1 < n:
            k = _put(rows, cols, vals, k, d, d + b, -(der[20, i] * kx + der[21, i] * kv))
        for c in range(2):
            nc = nx if c == 0 else nz
            k = _put(rows, cols, vals, k, d, d + 3 + c, 0.5 * li * nc)
            k = _put(rows, cols, vals, k, d, lam_next + c, 0.5 * li * nc)
            if i > 0:
                k = _put(rows, cols, vals, k, d, up + 5 + c, -der[8 + c, i])
                k = _put(rows, cols, vals, k, d, up + 7 + c, -der[10 + c, i])
        for c in range(2):
            ec = ex if c == 0 else ez
            nc = nx if c == 0 else nz
            # kinematics: A_(i+1) - A_i - l (f n - omega^2 e) = 0
            r = d + 1 + c
            k = _put(rows, cols, vals, k, r, d + 1 + c, 1.0)
            if i > 0:
                k = _put(rows, cols, vals, k, r, up + 1 + c, -1.0)
            k = _put(rows, cols, vals, k, r, d, -li * nc * km
                     + li * (f * ec * kx + 2.0 * om * ec * kv + om * om * nc * kx))  # fmt: skip
            # translation: m (A_i + A_(i+1)) / 2 - lam_i + lam_(i+1) - F = 0
            r = d + 3 + c
            if i > 0:
                k = _put(rows, cols, vals, k, r, up + 1 + c, 0.5 * mass[i])
            k = _put(rows, cols, vals, k, r, d + 1 + c, 0.5 * mass[i])
            k = _put(rows, cols, vals, k, r, d + 3 + c, -1.0)
            k = _put(rows, cols, vals, k, r, lam_next + c, 1.0)
            if i > 0:
                for e in range(2):
                    k = _put(rows, cols, vals, k, r, up + 5 + e, -der[2 * c + e, i])
                    k = _put(rows, cols, vals, k, r, up + 7 + e, -der[4 + 2 * c + e, i])
            k = _put(rows, cols, vals, k, r, d, -(der[12 + c, i] * kx + der[14 + c, i] * kv))
            # the node's position and velocity: P_(i+1) = P_i + l e, V_(i+1) = V_i + l omega n
            r = d + 5 + c
            k = _put(rows, cols, vals, k, r, d + 5 + c, 1.0)
            if i > 0:
                k = _put(rows, cols, vals, k, r, up + 5 + c, -1.0)
            k = _put(rows, cols, vals, k, r, d, -li * nc * kx)
            r = d + 7 + c
            k = _put(rows, cols, vals, k, r, d + 7 + c, 1.0)
            if i > 0:
                k = _put(rows, cols, vals, k, r, up + 7 + c, -1.0)
            k = _put(rows, cols, vals, k, r, d, -li * (nc * kv - om * ec * kx))
    return _tip_entries(n, tip_mass, tip_der, held, stabilization, rows, cols, vals, k)


@njit(inline="always", **JIT)
def _tip_entries(n, tip_mass, tip_der, held, stabilization, rows, cols, vals, k):
    """The tip's rows (``entries``): on a held axis A_n = target - 2 w (V_n - v*) -
    w^2 (P_n - p*) (lam_n's component there is the holding force's), on a free one
    lam_n = M_t A_n + bias - load(P_n, V_n)."""
    b = PER_LINK
    last = b * (n - 1)
    for c in range(2):
        r = b * n + c
        if held[c] != 0.0:
            k = _put(rows, cols, vals, k, r, last + 1 + c, 1.0)
            k = _put(rows, cols, vals, k, r, last + 7 + c, 2.0 * stabilization)
            k = _put(rows, cols, vals, k, r, last + 5 + c, stabilization * stabilization)
            continue
        k = _put(rows, cols, vals, k, r, r, 1.0)
        for e in range(2):
            k = _put(rows, cols, vals, k, r, last + 1 + e, -tip_mass[2 * c + e])
            k = _put(rows, cols, vals, k, r, last + 5 + e, tip_der[2 * c + e])
            k = _put(rows, cols, vals, k, r, last + 7 + e, tip_der[4 + 2 * c + e])
    return k


@njit(**JIT)
def _call_loads(n, y, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u, ws,
                base, out):  # fmt: skip
    """The line's loads with node 0 at ``base`` (P, V in x, z) into ``out`` (3, n: F x, F z,
    Q) and its nodes' positions and velocities into ``ws``."""
    ws[pc._PX, 0], ws[pc._PZ, 0], ws[pc._VX, 0], ws[pc._VZ, 0] = base[0], base[1], base[2], base[3]
    pc.link_loads(n, y, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                  joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u,
                  ws)  # fmt: skip
    for i in range(n):
        out[0, i], out[1, i], out[2, i] = ws[pc._FX, i], ws[pc._FZ, i], ws[pc._Q, i]


@njit(**JIT)
def _loads_derivatives(n, y, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                       joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u,
                       ws, der):  # fmt: skip
    """Each link's loads (F, Q) differentiated, into ``der`` (22, n): by its top node's
    position (rows 0-3: dF_c/dP_e at 2c + e; 8-9: dQ/dP) and velocity (4-7, 10-11), by its
    angle and rate (12-13, 14-15: F; 16, 17: Q) and, for Q, by its neighbours' (18, 19: the
    link above; 20, 21: below). Forward differences: node 0 moved (the whole line translates),
    then every third link's angle or rate turned (the links below it translate: their share,
    from the first derivatives, is taken off). ``ws`` is the line's workspace after the
    residual's evaluation (node 0's state read, nothing written)."""
    base = np.empty(4)
    for c in range(4):
        base[c] = ws[(pc._PX, pc._PZ, pc._VX, pc._VZ)[c], 0]
    work = np.empty_like(ws)
    y2 = y.copy()
    f0, f1 = np.empty((3, n)), np.empty((3, n))
    nodes = np.empty((4, n + 1))
    der[:, :] = 0.0
    _call_loads(n, y2, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u, work,
                base, f0)  # fmt: skip
    for k in range(n + 1):
        nodes[0, k], nodes[1, k] = work[pc._PX, k], work[pc._PZ, k]
        nodes[2, k], nodes[3, k] = work[pc._VX, k], work[pc._VZ, k]
    moved = base.copy()
    for c in range(4):  # node 0 (and so every node) moved along x, z, then its velocity
        eps = FD_STEP * max(1.0, abs(base[c]))
        moved[:] = base
        moved[c] += eps
        _call_loads(n, y2, q0, v0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                    joint_stiffness, joint_damping, ref_angle, ref_rate, current_z, current_u,
                    work, moved, f1)  # fmt: skip
        row_f, row_q = (0, 8) if c < 2 else (4, 10)
        e = c % 2
        for i in range(n):
            der[row_f + e, i] = (f1[0, i] - f0[0, i]) / eps
            der[row_f + 2 + e, i] = (f1[1, i] - f0[1, i]) / eps
            der[row_q + e, i] = (f1[2, i] - f0[2, i]) / eps
    eps_of = np.empty(n)
    own = np.empty(3)
    for rate in range(2):  # angles, then rates
        at = v0 if rate else q0
        for colour in range(3):
            for j in range(colour, n, 3):
                eps_of[j] = FD_STEP * max(1.0, abs(y[at + j]))
                y2[at + j] = y[at + j] + eps_of[j]
            _call_loads(n, y2, q0, v0, length, wet_weight, buoyancy, drag_normal,
                        drag_tangential, joint_stiffness, joint_damping, ref_angle, ref_rate,
                        current_z, current_u, work, base, f1)  # fmt: skip
            for j in range(colour, n, 3):
                y2[at + j] = y[at + j]
            for i in range(n):
                dpx, dpz = work[pc._PX, i] - nodes[0, i], work[pc._PZ, i] - nodes[1, i]
                dvx, dvz = work[pc._VX, i] - nodes[2, i], work[pc._VZ, i] - nodes[3, i]
                for r in range(3):  # the change less the translation of the link's top node
                    rp = (0, 2, 8)[r]
                    rv = (4, 6, 10)[r]
                    own[r] = (f1[r, i] - f0[r, i] - der[rp, i] * dpx - der[rp + 1, i] * dpz
                              - der[rv, i] * dvx - der[rv + 1, i] * dvz)  # fmt: skip
                if i % 3 == colour:
                    der[12 + 2 * rate, i] = own[0] / eps_of[i]
                    der[13 + 2 * rate, i] = own[1] / eps_of[i]
                    der[16 + rate, i] = own[2] / eps_of[i]
                elif i >= 1 and (i - 1) % 3 == colour:
                    der[18 + rate, i] = own[2] / eps_of[i - 1]
                elif i + 1 < n and (i + 1) % 3 == colour:
                    der[20 + rate, i] = own[2] / eps_of[i + 1]


@njit(**JIT)
def _tip_derivatives(t, y, p, w, tip, out):
    """d load / d P and d load / d V (x, z; 2x2 each, row-major) of the point body ``tip``'s
    force models, by forward differences (its submerged fraction followed)."""
    pos, vel, fraction = w.pos.copy(), w.vel.copy(), w.fraction.copy()
    load0, load1 = np.zeros_like(w.load), np.zeros_like(w.load)
    tf = (p.tf_breaks, p.tf_coefs, p.tf_count, p.tf_sine, p.tf_build_up)
    for case in range(5):
        pos[:, :] = w.pos
        vel[:, :] = w.vel
        eps = 1.0
        if case > 0:
            axis = 0 if case % 2 == 1 else 2
            target = pos if case <= 2 else vel
            eps = FD_STEP * max(1.0, abs(target[tip, axis]))
            target[tip, axis] += eps
        system_kernel._fractions(p.body_kind, p.body_shape, pos, fraction)
        load = load0 if case == 0 else load1
        load[:, :] = 0.0
        table.add_all(
            t, y, p.force_kind, p.force_body, p.force_at, p.force_first, p.force_state,
            p.force_data, p.body_mass, p.body_cog, p.body_volume, p.body_cob, fraction, w.quat,
            pos, w.rot, vel, w.omega, p.gravity, p.rho, p.current_z, p.current_u, p.current_v,
            tf, load,
        )  # fmt: skip
        if case > 0:
            e = 0 if case % 2 == 1 else 1
            first = 0 if case <= 2 else 4
            out[first + e] = (load1[tip, 0] - load0[tip, 0]) / eps
            out[first + 2 + e] = (load1[tip, 2] - load0[tip, 2]) / eps


@njit(**JIT)
def fill(t, y, h, coef, p, w, rows, mat):
    """Add every written line's entries to Newton's flat matrix ``mat`` (places ``rows.dest``)
    at the state ``y`` and time ``t`` of the residual just evaluated (``w`` holds its
    workspace), and keep each link's l n for the right-hand side (``rhs``)."""
    km = 1.0 - coef[3]
    kx = (1.0 - coef[4]) * coef[1] * h * h
    kv = (1.0 - coef[4]) * coef[2] * h
    geo_at = 0
    for k in range(rows.line.shape[0]):
        li = rows.line[k]
        n, s0, q0, v0 = p.rs_n[li], p.rs_seg[li], p.rs_q[li], p.rs_v[li]
        e = s0 + n
        ws = rigid.workspace(p, w, li)
        base = p.point_body[p.rs_from[li]]
        ref_angle = rigid.planar_reference(w.rot[base], p.rs_ref[li])
        der = np.empty((DERIVATIVES, n))
        _loads_derivatives(
            n, y, q0, v0, p.rs_length[s0:e], p.rs_wet_weight[s0:e], p.rs_buoyancy[s0:e],
            p.rs_drag_normal[s0:e], p.rs_drag_tangential[s0:e], p.rs_joint_stiffness[s0:e],
            p.rs_joint_damping[s0:e], ref_angle, -w.omega[base, 1], p.current_z, p.current_u,
            ws, der,
        )  # fmt: skip
        geometry = np.empty((4, n))
        omega, thdd = np.empty(n), np.empty(n)
        for i in range(n):
            geometry[0, i], geometry[1, i] = ws[pc._EX, i], ws[pc._EZ, i]
            geometry[2, i], geometry[3, i] = -ws[pc._EZ, i], ws[pc._EX, i]
            omega[i], thdd[i] = y[v0 + i], ws[pc._THDD, i]
            rows.geo[geo_at + 2 * i] = p.rs_length[s0 + i] * geometry[2, i]
            rows.geo[geo_at + 2 * i + 1] = p.rs_length[s0 + i] * geometry[3, i]
        geo_at += 2 * n
        held = np.array([p.rs_held[li, 0], p.rs_held[li, 2]])
        pinned = held[0] != 0.0 or held[1] != 0.0
        lam = np.empty((2, n + 1))
        for node in range(n + 1):
            lam[0, node], lam[1, node] = pc._node_force(ws, node, w.rs_force[li, 0],
                                                        w.rs_force[li, 2], pinned)  # fmt: skip
        tip_mass, tip_der = np.zeros(4), np.zeros(8)
        tip = p.rs_tip[li]
        if tip >= 0:
            mt = w.mass[tip]
            tip_mass[0], tip_mass[1], tip_mass[2], tip_mass[3] = mt[0, 0], mt[0, 2], mt[2, 0], mt[
                2, 2]  # fmt: skip
            _tip_derivatives(t, y, p, w, tip, tip_der)
        size = rows.dest_at[k + 1] - rows.dest_at[k]
        r_loc, c_loc, vals = np.empty(size, np.int64), np.empty(size, np.int64), np.empty(size)
        count = entries(n, p.rs_length[s0:e], p.rs_mass[s0:e], p.rs_inertia[s0:e], omega, thdd,
                        geometry, lam, der, tip_mass, tip_der, held, p.stabilization_frequency,
                        km, kx, kv, r_loc, c_loc, vals)  # fmt: skip
        at = rows.dest_at[k]
        for j in range(count):
            mat[rows.dest[at + j]] += vals[j]
        if not math.isfinite(vals[:count].sum()):
            return False
    return True


@njit(**JIT)
def rhs(rows, p, res, big):
    """Newton's right-hand side over every unknown (``big``, ``rows.size``) from the residual
    ``res`` of the accelerations: the written lines' rows get J r (rotation) and -l n r
    (kinematics, with the l n the matrix was built with), every auxiliary row 0."""
    nv = res.shape[0]
    big[:nv] = res
    big[nv:] = 0.0
    geo_at = 0
    for k in range(rows.line.shape[0]):
        li = rows.line[k]
        n, s0, v = p.rs_n[li], p.rs_seg[li], p.rs_v[li] - p.n_q
        aux = rows.aux[k]
        for i in range(n):
            r = res[v + i]
            big[v + i] = p.rs_inertia[s0 + i] * r
            big[aux + (PER_LINK - 1) * i] = -rows.geo[geo_at + 2 * i] * r
            big[aux + (PER_LINK - 1) * i + 1] = -rows.geo[geo_at + 2 * i + 1] * r
        geo_at += 2 * n
