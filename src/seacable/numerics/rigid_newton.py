"""Newton's rows of rigid lines in maximal coordinates, and of the bodies they hang from: a
banded block per line, so that an implicit step costs O(n) in the lines' links (derivation:
docs/rigid_newton.md). The layout, the bodies' rows and the planar links' rows are here, the 3D
segments' rows in ``numerics.rigid_newton_3d``.

In the links' angles a rigid line's Newton block is dense (every angular acceleration depends on
every angle). Its Newton correction delta (J delta = r, J = d(residual)/d(a1)) is instead found
from the linearised Newton-Euler equations of the links, whose unknowns are, per planar link i,

    delta_i, dA_(i+1) (2), dlam_i (2), dP_(i+1) (2), dV_(i+1) (2)    (9, in this order)

and dlam_n (2) at the tip (per 3D segment the same in 3D, delta_i its 3 director
accelerations: 15, and 3 at the tip): the change of each node's acceleration A, of the force
lam the part above a node exerts on the part below, and of each node's position P and velocity
V, all scaled by (1 - af). Every row (a link's rotation, its kinematics, its translation, its
node's position and velocity, the tip's) involves one link and its neighbours, so the block is
banded (planar kl = ku = 9, 3D kl = 16, ku = 17, whatever n; ordered by ``Shape.order``) and
``numerics.bordered`` factorises it in O(n). A dynamic body the lines hang from keeps its
unknowns in the border, its rows written in Newton-Euler form too (its own mass and force
models, and each line's dlam_0). Eliminating the auxiliary unknowns gives delta = J^-1 r
exactly: the rows are the exact linearisation of the equations the articulated sweeps solve,
with the loads' derivatives by finite differences of the loads themselves
(``numerics.rigid_derivatives``).

Written so (``eligible``): planar and 3D lines whose base is a fixed or imposed body, or a
dynamic body whose rotations are held and that nothing but such lines (of one model) and its
force models touch; whose tip is free, held (the Baumgarte closure's rows) or carries a point
body nothing else touches (a held end's joint, ``lines.tip_joint``, among its loads). Others
(trees of lines, lines held on a free body, bodies with lumped lines or ties) keep the dense
block of the differences over the accelerations.
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit
from scipy import sparse

from seacable.bodies import dynamics, kinematics
from seacable.kernels import planar_chain as pc
from seacable.kernels.jit import JIT, inner
from seacable.numerics import bordered, lumped_newton
from seacable.numerics import rigid_newton_3d as r3
from seacable.numerics.rigid_derivatives import (
    DERIVATIVES,
    end_joint,
    loads_derivatives,
    point_derivatives,
)
from seacable.system import coordinates, rigid

PER_LINK = 9  # unknowns (and rows) per link; two more at the tip
# where each of a link's unknowns (delta, dA (2), dlam (2), dP (2), dV (2)) stands in the block:
# dlam_i first; the narrowest band of the 9! orders (kl = ku = 9; 11 and 13 in the entries' order)
BLOCK_ORDER = np.array([2, 3, 4, 0, 1, 5, 6, 7, 8])


class Shape(NamedTuple):
    """A line model's rows: unknowns per link, velocity variables per link (the first of its
    unknowns), unknowns at the tip, and the order of a link's unknowns in the block."""

    per: int
    variables: int
    tip: int
    order: np.ndarray


SHAPES = {
    rigid.PLANAR: Shape(PER_LINK, 1, 2, BLOCK_ORDER),
    rigid.SEGMENTS_3D: Shape(r3.PER_SEGMENT, 3, r3.TIP, r3.BLOCK_ORDER),
}


class RigidRows(NamedTuple):
    """The rigid lines (and their dynamic bodies) whose Newton rows are written in maximal
    coordinates (flat, with offsets; ``line`` may be empty)."""

    line: np.ndarray  # (k,) int: the rigid lines (indices into the rs_* arrays)
    aux: np.ndarray  # (k,) int: each line's first auxiliary unknown (8 n + 2 of them planar,
    # 12 n + 3 in 3D)
    base: np.ndarray  # (k,) int: its dynamic base body (-1: fixed or imposed)
    body: np.ndarray  # (kb,) int: the dynamic bodies written
    body_line: np.ndarray  # (k,) int: the lines (of ``line``) hanging from each, body by body
    body_line_at: np.ndarray  # (kb + 1,) int: each body's first in ``body_line``
    dest_at: np.ndarray  # (k + kb + 1,) int: each line's, then each body's first in ``dest``
    dest: np.ndarray  # every entry's place in Newton's flat matrix (``entries``' order)
    geo: np.ndarray  # l n of each planar link (2), r3.GEO of each 3D segment when the
    geo_at: np.ndarray  # (k + 1,) int: each line's first in ``geo``; matrix was built, and
    body_mass: np.ndarray  # (kb, 9) each body's translational mass: the right-hand side's
    # transformation must be the matrix's
    size: int  # unknowns of Newton's system: the velocity variables, then the auxiliary ones
    lumped_line: np.ndarray  # the lumped lines with columns written from their laws, and
    lumped_column: np.ndarray  # (size,) 1 for those columns (numerics.lumped_newton), and
    lumped_dest: np.ndarray  # (size, 9) their entries' places (lumped_newton.destinations)


def eligible(p) -> tuple[list[int], dict[int, list[int]]]:
    """The lines written in maximal coordinates and, for each dynamic body written, the lines
    hanging from it (the module docstring says which)."""
    point_body = np.asarray(p.point_body)
    nodes = set(point_body[np.concatenate([p.line_from, p.line_to])].tolist())
    touched = nodes | set(point_body[np.concatenate([p.tie_from, p.tie_to])].tolist())
    touched |= set(np.asarray(p.nat_tip).tolist())
    touched |= set(point_body[np.asarray(p.nat_from, dtype=np.int64)].tolist())
    bases = [int(point_body[a]) for a in p.rs_from]
    kinds = np.asarray(p.rs_kind)
    lines: list[int] = []
    on_body: dict[int, list[int]] = {}
    for li in range(len(p.rs_n)):
        tip, base = int(p.rs_tip[li]), bases[li]
        if p.rs_port[li] or (tip >= 0 and (tip in touched or tip in bases)):
            continue  # held on a free body (its rows are not written) or a carried body coupled
        if p.body_kind[base] == kinematics.DYNAMIC:
            if base in touched or np.any(p.body_free[base, 3:] != 0.0):
                continue
            if any(
                bases[other] == base and kinds[other] != kinds[li] for other in range(len(bases))
            ):
                continue
            on_body.setdefault(base, []).append(li)
        elif p.body_kind[base] not in (kinematics.FIXED, kinematics.IMPOSED):
            continue
        lines.append(li)
    return lines, on_body


def _position(local: int, n: int, shape: Shape) -> int:
    """Where local unknown ``local`` of a line of n links stands in its block (``shape.order``;
    the tip's last)."""
    if local >= shape.per * n:
        return local
    return shape.per * (local // shape.per) + int(shape.order[local % shape.per])


def local_to_global(n: int, v: int, aux: int, base_v: int, shape: Shape) -> np.ndarray:
    """Each local unknown's index in Newton's system: link i's first ``shape.variables`` are
    its velocity variables (from v), the auxiliary unknowns follow from ``aux``, then
    (``base_v`` >= 0) the base body's three translations."""
    per, nv = shape.per, shape.variables
    local = np.arange(per * n + shape.tip + 3)
    link, k = local // per, local % per
    out = np.where(k < nv, v + nv * link + k, aux + (per - nv) * link + k - nv)
    tip = local >= per * n
    out[tip] = aux + (per - nv) * n + (local[tip] - per * n)
    out[per * n + shape.tip :] = base_v + np.arange(3)
    return out.astype(np.int64)


def entries_pattern(
    kind: int, n: int, v: int, aux: int, held: np.ndarray, base_v: int
) -> tuple[np.ndarray, np.ndarray]:
    """The rows and columns (Newton's unknowns) of a line's entries, in ``entries``' (or
    ``rigid_newton_3d.entries``') order (``held``: x, y, z, 1.0 on a held axis; ``base_v``: the
    first velocity variable of its dynamic base body, -1 for none)."""
    if kind == rigid.PLANAR:
        size = 47 * n + 34
        rows, cols, vals = np.empty(size, np.int64), np.empty(size, np.int64), np.empty(size)
        zero = np.zeros((DERIVATIVES, n))
        count = entries(n, np.ones(n), np.ones(n), np.ones(n), np.zeros(n), np.zeros(n),
                        np.zeros((4, n)), np.zeros((2, n + 1)), zero, np.zeros(9), np.zeros(18),
                        np.asarray(held, dtype=np.float64)[[0, 2]], 1.0,
                        np.ones(3 if base_v >= 0 else 0), 1.0, 1.0, 1.0, rows, cols,
                        vals)  # fmt: skip
        rows, cols = rows[:count], cols[:count]
    else:
        rows, cols = r3.entries_pattern(n, held, base_v >= 0)
    glob = local_to_global(n, v, aux, base_v, SHAPES[kind])
    return glob[rows], glob[cols]


def body_pattern(
    size: int, v: int, auxes: list[int], free: np.ndarray, shape: Shape
) -> tuple[np.ndarray, np.ndarray]:
    """The rows and columns of a body's entries (``body_entries``' order): ``size`` velocity
    variables from ``v``, the lines (of ``shape``) hanging from it with auxiliary unknowns from
    ``auxes``, ``free`` its translations' flags."""
    dims = shape.tip
    rows, cols, vals = np.empty(96, np.int64), np.empty(96, np.int64), np.empty(96)
    count = body_entries(size, np.asarray(free, dtype=np.float64), np.zeros(9), np.zeros(18),
                         len(auxes), dims, 1.0, 1.0, 1.0, rows, cols, vals)  # fmt: skip
    glob = np.arange(size + dims * len(auxes))
    glob[:size] += v
    for j, aux in enumerate(auxes):  # link 0's dlam_0: its auxiliary unknowns after dA_1
        glob[size + dims * j : size + dims * (j + 1)] = aux + dims + np.arange(dims)
    return glob[rows[:count]], glob[cols[:count]]


def layout(
    p,
    pattern,
    border: np.ndarray,
    maximal: bool,
    lumped: tuple[np.ndarray, np.ndarray],
    triple: np.ndarray,
) -> tuple[bordered.Bordered, RigidRows]:
    """The layout of Newton's system with the eligible rigid lines (and the dynamic bodies
    they hang from) in maximal coordinates: their entries placed by ``entries`` and
    ``body_entries`` and left out of the differences (colour -1), each line's block ordered
    link by link; ``maximal=False``: none. ``lumped``: the lumped lines and the columns
    (over the velocity variables) written from their laws (``lumped_newton.eligible``), left
    out of the differences too; ``triple``: the velocity variables whose blocks may be
    factorised as 3 x 3 blocks (``bordered.structure``)."""
    nv, nq = pattern.shape[0], int(p.n_q)
    row, col = pattern.row, pattern.col
    lines, on_body = eligible(p) if maximal else ([], {})
    groups = [[li] for li in lines if int(p.point_body[p.rs_from[li]]) not in on_body]
    groups += [[-1 - b, *members] for b, members in on_body.items()]  # a body, its lines
    written = np.zeros(nv, dtype=bool)
    parts: list[tuple[np.ndarray, np.ndarray]] = []
    kept_lines: list[int] = []
    auxes: list[int] = []
    bases: list[int] = []
    bodies: list[int] = []
    body_lines: list[list[int]] = []
    size = nv
    geo_at = [0]
    key = list(range(nv))
    for group in groups:
        own = np.zeros(nv, dtype=bool)
        for member in group:
            v, count = _unknowns(p, member)
            own[v : v + count] = True
        if np.any(own[row] != own[col]):
            continue  # coupled to some other unknown: the differences keep it
        written |= own
        base_v = int(p.body_v[-1 - group[0]]) - nq if group[0] < 0 else -1
        first = len(kept_lines)
        for li in group[1:] if group[0] < 0 else group:
            n, v, kind = int(p.rs_n[li]), int(p.rs_v[li]) - nq, int(p.rs_kind[li])
            shape = SHAPES[kind]
            glob = local_to_global(n, v, size, base_v, shape)[: shape.per * n + shape.tip]
            parts.append(entries_pattern(kind, n, v, size, p.rs_held[li], base_v))
            kept_lines.append(li)
            auxes.append(size)
            bases.append(-1 - group[0] if group[0] < 0 else -1)
            size += len(glob) - shape.variables * n
            key.extend([0] * (len(glob) - shape.variables * n))
            for local, g in enumerate(glob):
                key[g] = _position(local, n, shape)
            geo_at.append(geo_at[-1] + (2 if kind == rigid.PLANAR else r3.GEO) * n)
        if group[0] < 0:
            bodies.append(-1 - group[0])
            body_lines.append(list(range(first, len(kept_lines))))
    for b, members in zip(bodies, body_lines, strict=True):
        v, count = _unknowns(p, -1 - b)
        shape = SHAPES[int(p.rs_kind[kept_lines[members[0]]])]
        parts.append(body_pattern(count, v, [auxes[m] for m in members], p.body_free[b, :3], shape))
    kept = ~written[row]
    rows_all = np.concatenate([row[kept], *[r for r, _ in parts]]).astype(np.int64)
    cols_all = np.concatenate([col[kept], *[c for _, c in parts]]).astype(np.int64)
    full = sparse.coo_matrix((np.ones(len(rows_all)), (rows_all, cols_all)), shape=(size, size))
    lumped_line, lumped_column = lumped
    differenced = kept & (lumped_column[col] == 0)
    rest = sparse.csr_matrix(
        (np.ones(int(differenced.sum())), (row[differenced], col[differenced])), shape=(nv, nv)
    )
    colours = np.full(size, -1, dtype=np.int64)
    colours[:nv] = np.where(written | (lumped_column != 0), -1, coordinates.colour(rest))
    border_all = np.zeros(size, dtype=bool)
    border_all[:nv] = border
    triple_all = np.zeros(size, dtype=bool)
    triple_all[:nv] = triple
    lay = bordered.structure(
        full, border_all, colours, np.array(key, dtype=np.int64), triple_all & ~border_all
    )
    col_of = np.repeat(np.arange(size), np.diff(lay.nz_ptr))
    place = sparse.csr_matrix((lay.nz_dest + 1, (lay.nz_row, col_of)), shape=(size, size))
    dest = [np.asarray(place[r, c]).ravel() - 1 for r, c in parts]

    def ints(values) -> np.ndarray:
        return np.array(values, dtype=np.int64)

    rows = RigidRows(
        line=ints(kept_lines), aux=ints(auxes), base=ints(bases), body=ints(bodies),
        body_line=ints([m for members in body_lines for m in members]),
        body_line_at=np.concatenate([[0], np.cumsum([len(m) for m in body_lines])]).astype(
            np.int64),
        dest_at=np.concatenate([[0], np.cumsum([len(r) for r, _ in parts])]).astype(np.int64),
        dest=np.concatenate([np.zeros(0, np.int64), *dest]).astype(np.int64),
        geo=np.zeros(geo_at[-1]), geo_at=ints(geo_at), body_mass=np.zeros((len(bodies), 9)),
        size=size, lumped_line=ints(lumped_line),
        lumped_column=np.concatenate([lumped_column, np.zeros(size - nv, np.int64)]),
        lumped_dest=np.concatenate([
            lumped_newton.destinations(p, lumped_line, lumped_column, lay),
            np.full((size - nv, 9), -1, np.int64),
        ]),
    )  # fmt: skip
    return lay, rows


def _unknowns(p, member: int) -> tuple[int, int]:
    """The first velocity variable (relative to V's start) and the count of a rigid line
    (``member`` >= 0) or of the body -1 - member."""
    nq = int(p.n_q)
    if member >= 0:
        return int(p.rs_v[member]) - nq, SHAPES[int(p.rs_kind[member])].variables * int(
            p.rs_n[member]
        )
    b = -1 - member
    return int(p.body_v[b]) - nq, 6 if p.body_rigid[b] else 3


@njit(**JIT)
def body_entries(size, free, mass3, der, lines, dims, km, kx, kv, rows, cols, vals):
    """A dynamic body's rows (local: its ``size`` unknowns, then each line's dlam_0 in x and
    z, ``dims`` 2, or in x, y, z, ``dims`` 3): on a free translation c, its Newton-Euler row
    sum_e M_ce (km delta_e - r_e) (free e) - dF_c + dlam_0,c = 0 with dF from its force models
    (``der``: ``point_derivatives``) and the body's own mass ``mass3`` (3x3); on a held axis or
    a rotation, km delta_c = r_c.
    Returns the count."""
    k = 0
    for c in range(size):
        if c >= 3 or free[c] == 0.0:
            k = r3.put(rows, cols, vals, k, c, c, km)
            continue
        for e in range(3):
            value = mass3[3 * c + e] * km * free[e] - der[3 * c + e] * kx - der[9 + 3 * c + e] * kv
            k = r3.put(rows, cols, vals, k, c, e, value)
        if dims == 3 or c != 1:  # every axis, or the plane's x and z
            for j in range(lines):
                k = r3.put(rows, cols, vals, k, c, size + dims * j + (c if dims == 3 else c // 2),
                         1.0)  # fmt: skip
    return k


@njit(**JIT)
def entries(n, length, mass, inertia, omega, thdd, geometry, lam, der, tip_mass, tip_der, held,
            stabilization, base_free, km, kx, kv, rows, cols, vals):  # fmt: skip
    """One line's entries (local row, local column, value; docs/rigid_newton.md): ``omega`` and
    ``thdd`` the links' rates and angular accelerations, ``geometry`` (4, n) their e and n
    (x, z), ``lam`` (2, n + 1) the node forces, ``der`` the loads' derivatives
    (``rigid_derivatives.loads_derivatives``), ``tip_mass`` (3x3) and ``tip_der``
    (``point_derivatives``) of the tip body; ``held`` (x, z): 1.0 on an axis the tip is held on
    (Baumgarte, at ``stabilization`` rad/s); ``base_free`` (3, or empty for a base on a fixed
    or imposed body): the free translations of the dynamic body the line hangs from (its
    columns local 9 n + 2 + axis); km = 1 - am, kx = (1 - af) b h^2, kv = (1 - af) g h.
    Returns the count. The entries are the same whatever the values: ``entries_pattern`` reads
    them from here."""
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
        k = r3.put(rows, cols, vals, k, d, d, diag)
        if i > 0:
            k = r3.put(rows, cols, vals, k, d, up, -(der[18, i] * kx + der[19, i] * kv))
        if i + 1 < n:
            k = r3.put(rows, cols, vals, k, d, d + b, -(der[20, i] * kx + der[21, i] * kv))
        for c in range(2):
            nc = nx if c == 0 else nz
            k = r3.put(rows, cols, vals, k, d, d + 3 + c, 0.5 * li * nc)
            k = r3.put(rows, cols, vals, k, d, lam_next + c, 0.5 * li * nc)
            if i > 0:
                k = r3.put(rows, cols, vals, k, d, up + 5 + c, -der[8 + c, i])
                k = r3.put(rows, cols, vals, k, d, up + 7 + c, -der[10 + c, i])
        for c in range(2):
            ec = ex if c == 0 else ez
            nc = nx if c == 0 else nz
            # kinematics: A_(i+1) - A_i - l (f n - omega^2 e) = 0
            r = d + 1 + c
            k = r3.put(rows, cols, vals, k, r, d + 1 + c, 1.0)
            if i > 0:
                k = r3.put(rows, cols, vals, k, r, up + 1 + c, -1.0)
            k = r3.put(rows, cols, vals, k, r, d, -li * nc * km
                     + li * (f * ec * kx + 2.0 * om * ec * kv + om * om * nc * kx))  # fmt: skip
            # translation: m (A_i + A_(i+1)) / 2 - lam_i + lam_(i+1) - F = 0
            r = d + 3 + c
            if i > 0:
                k = r3.put(rows, cols, vals, k, r, up + 1 + c, 0.5 * mass[i])
            k = r3.put(rows, cols, vals, k, r, d + 1 + c, 0.5 * mass[i])
            k = r3.put(rows, cols, vals, k, r, d + 3 + c, -1.0)
            k = r3.put(rows, cols, vals, k, r, lam_next + c, 1.0)
            if i > 0:
                for e in range(2):
                    k = r3.put(rows, cols, vals, k, r, up + 5 + e, -der[2 * c + e, i])
                    k = r3.put(rows, cols, vals, k, r, up + 7 + e, -der[4 + 2 * c + e, i])
            k = r3.put(rows, cols, vals, k, r, d, -(der[12 + c, i] * kx + der[14 + c, i] * kv))
            # the node's position and velocity: P_(i+1) = P_i + l e, V_(i+1) = V_i + l omega n
            r = d + 5 + c
            k = r3.put(rows, cols, vals, k, r, d + 5 + c, 1.0)
            if i > 0:
                k = r3.put(rows, cols, vals, k, r, up + 5 + c, -1.0)
            k = r3.put(rows, cols, vals, k, r, d, -li * nc * kx)
            r = d + 7 + c
            k = r3.put(rows, cols, vals, k, r, d + 7 + c, 1.0)
            if i > 0:
                k = r3.put(rows, cols, vals, k, r, up + 7 + c, -1.0)
            k = r3.put(rows, cols, vals, k, r, d, -li * (nc * kv - om * ec * kx))
    k = r3.tip_entries(n, PER_LINK, 2, (1, 5, 7), tip_mass, tip_der, held, stabilization, rows,
                       cols, vals, k)  # fmt: skip
    if base_free.shape[0] > 0:
        k = _base_entries(n, mass[0], der, base_free, km, kx, kv, rows, cols, vals, k)
    return k


@njit(inline="always", **JIT)
def _base_entries(n, mass0, der, free, km, kx, kv, rows, cols, vals, k):
    """Link 0's entries in the columns of a dynamic base body's translations (``entries``):
    dA_0 = km delta_b - r_b on its free axes, dP_0 = kx delta_b, dV_0 = kv delta_b."""
    body = PER_LINK * n + 2
    for c in range(2):
        bc = 2 * c  # x, z of the plane: the body's axes 0 and 2
        k = r3.put(rows, cols, vals, k, 1 + c, body + bc, -km * free[bc])  # kinematics
        k = r3.put(rows, cols, vals, k, 3 + c, body + bc, 0.5 * mass0 * km * free[bc])
        k = r3.put(rows, cols, vals, k, 5 + c, body + bc, -kx)  # node 1's position, velocity
        k = r3.put(rows, cols, vals, k, 7 + c, body + bc, -kv)
        for e in range(2):
            k = r3.put(rows, cols, vals, k, 3 + c, body + 2 * e,
                     -(der[2 * c + e, 0] * kx + der[4 + 2 * c + e, 0] * kv))  # fmt: skip
    for e in range(2):  # rotation
        k = r3.put(rows, cols, vals, k, 0, body + 2 * e,
                 -(der[8 + e, 0] * kx + der[10 + e, 0] * kv))  # fmt: skip
    return k


@inner
def fill(t, y, h, coef, p, w, rows, mat):
    """Add every written line's and body's entries to Newton's flat matrix ``mat`` (places
    ``rows.dest``) at the state ``y`` and time ``t`` of the residual just evaluated (``w``
    holds its workspace), and keep what the right-hand side needs (``rhs``). False when an
    entry is not finite."""
    km = 1.0 - coef[3]
    kx = (1.0 - coef[4]) * coef[1] * h * h
    kv = (1.0 - coef[4]) * coef[2] * h
    point = np.zeros(18)
    ok = True
    for k in range(rows.line.shape[0]):
        li = rows.line[k]
        geo = rows.geo[rows.geo_at[k] : rows.geo_at[k + 1]]
        r_loc, c_loc, vals = _scratch(rows, k)
        if p.rs_kind[li] == rigid.PLANAR:
            count = _planar_line(t, y, p, w, li, rows.base[k], km, kx, kv, geo, r_loc, c_loc,
                                 vals)  # fmt: skip
        else:
            count = r3.fill_line(t, y, p, w, li, rows.base[k] >= 0, km, kx, kv, geo, r_loc,
                                 c_loc, vals)  # fmt: skip
        ok = _add(rows, k, mat, vals, count) and ok
    if rows.body.shape[0] == 0:
        return ok
    masses, bias = np.empty_like(w.mass), np.empty_like(w.bias)  # the bodies' own
    dynamics.body_masses(
        p.body_kind, p.body_rigid, p.body_mass, p.body_cog, p.body_inertia, p.body_added,
        p.body_coriolis, p.body_shape, w.fraction, w.pos, w.rot, w.vel, w.omega, p.current_z,
        p.current_u, p.current_v, masses, bias,
    )  # fmt: skip
    for j in range(rows.body.shape[0]):
        b = rows.body[j]
        for c in range(3):
            for e in range(3):
                rows.body_mass[j, 3 * c + e] = masses[b, c, e]
        point_derivatives(t, y, p, w, b, point)
        size = 6 if p.body_rigid[b] else 3
        first = rows.body_line_at[j]
        lines = rows.body_line_at[j + 1] - first
        dims = 2 if p.rs_kind[rows.line[rows.body_line[first]]] == rigid.PLANAR else 3
        k = rows.line.shape[0] + j
        r_loc, c_loc, vals = _scratch(rows, k)
        count = body_entries(size, p.body_free[b, :3], rows.body_mass[j], point, lines, dims, km,
                             kx, kv, r_loc, c_loc, vals)  # fmt: skip
        ok = _add(rows, k, mat, vals, count) and ok
    return ok


@inner
def _planar_line(t, y, p, w, li, base, km, kx, kv, geo, r_loc, c_loc, vals):
    """A planar line's entries (``entries``) at the evaluation ``w`` holds, and the l n of its
    links into ``geo``. Returns the count."""
    n, s0 = p.rs_n[li], p.rs_seg[li]
    e = s0 + n
    ws = rigid.workspace(p, w, li)
    der = _line_derivatives(p, w, y, li, ws)
    geometry = np.empty((4, n))
    omega, thdd = np.empty(n), np.empty(n)
    for i in range(n):
        geometry[0, i], geometry[1, i] = ws[pc._EX, i], ws[pc._EZ, i]
        geometry[2, i], geometry[3, i] = -ws[pc._EZ, i], ws[pc._EX, i]
        omega[i], thdd[i] = y[p.rs_v[li] + i], ws[pc._THDD, i]
        geo[2 * i] = p.rs_length[s0 + i] * geometry[2, i]
        geo[2 * i + 1] = p.rs_length[s0 + i] * geometry[3, i]
    held = np.array([p.rs_held[li, 0], p.rs_held[li, 2]])
    pinned = held[0] != 0.0 or held[1] != 0.0
    lam = np.empty((2, n + 1))
    for node in range(n + 1):
        lam[0, node], lam[1, node] = pc._node_force(ws, node, w.rs_force[li, 0],
                                                    w.rs_force[li, 2], pinned)  # fmt: skip
    tip_mass, point = r3.tip_body(t, y, p, w, p.rs_tip[li])
    base_free = p.body_free[base, :3] if base >= 0 else np.zeros(0)
    return entries(
        n, p.rs_length[s0:e], p.rs_mass[s0:e], p.rs_inertia[s0:e], omega, thdd, geometry, lam,
        der, tip_mass, point, held, p.stabilization_frequency, base_free, km, kx, kv, r_loc,
        c_loc, vals,
    )  # fmt: skip


@njit(inline="always", **JIT)
def _scratch(rows, k):
    """Rows, columns and values of the entries of ``rows.dest``'s part k."""
    size = rows.dest_at[k + 1] - rows.dest_at[k]
    return np.empty(size, np.int64), np.empty(size, np.int64), np.empty(size)


@njit(inline="always", **JIT)
def _add(rows, k, mat, vals, count):
    """mat at the places of part k (a line, then the bodies) += ``vals``; False when one is
    not finite."""
    at = rows.dest_at[k]
    total = 0.0
    for j in range(count):
        mat[rows.dest[at + j]] += vals[j]
        total += vals[j]
    return math.isfinite(total)


@inner
def _line_derivatives(p, w, y, li, ws):
    """``rigid_derivatives.loads_derivatives`` of line ``li`` (its joint 0 against its base's
    reference direction, and its held end's joint)."""
    n, s0 = p.rs_n[li], p.rs_seg[li]
    e = s0 + n
    base = p.point_body[p.rs_from[li]]
    der = np.empty((DERIVATIVES, n))
    loads_derivatives(
        n, y, p.rs_q[li], p.rs_v[li], p.rs_length[s0:e], p.rs_wet_weight[s0:e],
        p.rs_buoyancy[s0:e], p.rs_drag_normal[s0:e], p.rs_drag_tangential[s0:e],
        p.rs_joint_stiffness[s0:e], p.rs_joint_damping[s0:e],
        rigid.planar_reference(w.rot[base], p.rs_ref[li]), -w.omega[base, 1], p.current_z,
        p.current_u, end_joint(p, w, li), ws, der,
    )  # fmt: skip
    return der


@njit(**JIT)
def rhs(rows, p, res, big):
    """Newton's right-hand side over every unknown (``big``, ``rows.size``) from the residual
    ``res`` of the accelerations: a written line's rotation rows get J r, its kinematics rows
    -l n r (with the l n the matrix was built with), link 0's kinematics and translation rows
    -r_b and m r_b / 2 from a dynamic base's residual r_b (a 3D line's rows:
    ``rigid_newton_3d.rhs_line``); a written body's free rows M r; every other auxiliary row 0."""
    nv = res.shape[0]
    big[:nv] = res
    big[nv:] = 0.0
    for k in range(rows.line.shape[0]):
        li = rows.line[k]
        geo = rows.geo[rows.geo_at[k] : rows.geo_at[k + 1]]
        if p.rs_kind[li] != rigid.PLANAR:
            r3.rhs_line(p, li, rows.aux[k], geo, res, big, rows.base[k])
            continue
        n, s0, v = p.rs_n[li], p.rs_seg[li], p.rs_v[li] - p.n_q
        aux = rows.aux[k]
        for i in range(n):
            r = res[v + i]
            big[v + i] = p.rs_inertia[s0 + i] * r
            big[aux + (PER_LINK - 1) * i] = -geo[2 * i] * r
            big[aux + (PER_LINK - 1) * i + 1] = -geo[2 * i + 1] * r
        base = rows.base[k]
        if base >= 0:
            bv = p.body_v[base] - p.n_q
            for c in range(2):
                rb = p.body_free[base, 2 * c] * res[bv + 2 * c]
                big[aux + c] -= rb
                big[aux + 2 + c] += 0.5 * p.rs_mass[s0] * rb
    for j in range(rows.body.shape[0]):
        b = rows.body[j]
        bv = p.body_v[b] - p.n_q
        for c in range(3):
            if p.body_free[b, c] != 0.0:
                total = 0.0
                for e in range(3):
                    total += rows.body_mass[j, 3 * c + e] * p.body_free[b, e] * res[bv + e]
                big[bv + c] = total
