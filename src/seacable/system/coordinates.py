"""The coordinates of a system's statics and linearisation ("increments"): per dynamic body
its free translations (earth x, y, z) and its free rotations (a rotation vector in the earth
frame, applied as exp(theta) to its orientation), then every lumped line's interior node
positions, then every rigid segment's turn on the two directions t1, t2 normal to its director
(kernels.chain3d._basis) or a planar link's angle. How an increment moves a state (``apply``),
which increments can change which accelerations (``pattern``, ``colour``), the residual at rest
(``Residual``: accelerations, or the moment balance of rigid trees that hang free) and its
finite-difference Jacobian (``fd_jacobian``). Used by system.statics (equilibrium, Jacobian,
mooring stiffness) and system.model (SciPy's sparsity pattern)."""

from dataclasses import dataclass

import numpy as np
from scipy import sparse

from seacable.bodies import kinematics
from seacable.system import kernel, rigid

# a natural string node's strain; its tangent's angle (angle form: added to it; cartesian
# form: the components (t_x, t_z) turned towards n = (-t_z, t_x))
STRAIN, ANGLE, TURN = 5, 6, 7


@dataclass(frozen=True)
class Coordinates:
    """Where each increment goes: ``kind`` 0 translation, 1 rotation, 2 node, 3 director, 4
    planar link's angle, 5 a natural string node's strain, 6 its tangent's angle, 7 a turn of
    its tangent's components (t_x, t_z) towards n = (-t_z, t_x) (the cartesian form);
    ``body`` its body (-1 for a node or director); ``axis`` 0..2 (a director's: 0 along t1, 1
    along t2); ``q`` its position in y (translation, node), the body's first quaternion entry
    or the director's first entry (a string's tangent: its first component); ``v`` the state
    index of its velocity (a director's first rate); ``line`` (-1 for a body; a lumped line's
    index for a node, a rigid line's for a director, a natural string's for its variables)."""

    kind: np.ndarray
    body: np.ndarray
    axis: np.ndarray
    q: np.ndarray
    v: np.ndarray
    line: np.ndarray


def coordinates(p: kernel.SystemParams) -> Coordinates:
    rows: list[tuple[int, int, int, int, int, int]] = []
    for b in range(len(p.body_kind)):
        if p.body_kind[b] != kinematics.DYNAMIC:
            continue
        q, v = int(p.body_q[b]), int(p.body_v[b])
        for c in range(3):
            if p.body_free[b, c]:
                rows.append((0, b, c, q + c, v + c, -1))
        if p.body_rigid[b]:
            for c in range(3):
                if p.body_free[b, 3 + c]:
                    rows.append((1, b, c, q + 3, v + 3 + c, -1))
    for li in range(len(p.line_n)):
        q, v = int(p.line_q[li]), int(p.line_v[li])
        for k in range(3 * (int(p.line_n[li]) - 1)):
            rows.append((2, -1, k % 3, q + k, v + k, li))
    for li in range(len(p.rs_n)):
        q, v = int(p.rs_q[li]), int(p.rs_v[li])
        for i in range(int(p.rs_n[li])):
            if p.rs_kind[li] == rigid.PLANAR:
                rows.append((4, -1, 0, q + i, v + i, li))
                continue
            for axis in range(2):
                rows.append((3, -1, axis, q + 3 * i, v + 3 * i, li))
    rows += _string_rows(p)
    table = np.array(rows, dtype=np.int64).reshape(-1, 6)
    return Coordinates(*(table[:, c].copy() for c in range(6)))


def _string_rows(p: kernel.SystemParams) -> list[tuple[int, int, int, int, int, int]]:
    """A natural string's coordinates: strain and tangent angle at every node."""
    rows = []
    for li in range(len(p.nat_n)):
        q, v = int(p.nat_q[li]), int(p.nat_v[li])
        width = 3 if p.nat_cartesian[li] else 2
        for i in range(int(p.nat_n[li]) + 1):
            rows.append((STRAIN, -1, 0, q + width * i, v + width * i, li))
            rows.append((TURN if width == 3 else ANGLE, -1, 0, q + width * i + 1,
                         v + width * i + 1, li))  # fmt: skip
    return rows


def rotate(quaternion: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """exp(theta / 2) * q: the orientation turned by the rotation vector theta (earth)."""
    angle = float(np.linalg.norm(theta))
    if angle < 1e-300:
        return quaternion.copy()
    axis = theta / angle
    s = float(np.sin(0.5 * angle))
    dw = float(np.cos(0.5 * angle))
    dx, dy, dz = (s * float(a) for a in axis)
    qw, qx, qy, qz = (float(v) for v in quaternion)
    out = np.array([
        dw * qw - dx * qx - dy * qy - dz * qz,
        dw * qx + dx * qw + dy * qz - dz * qy,
        dw * qy - dx * qz + dy * qw + dz * qx,
        dw * qz + dx * qy - dy * qx + dz * qw,
    ])  # fmt: skip
    return out / np.linalg.norm(out)


def normal_basis(e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """t1, t2 (m, 3) normal to the unit vectors e (m, 3), as kernels.chain3d._basis builds
    them."""
    a = np.abs(e)
    smallest = np.where((a[:, 0] <= a[:, 1]) & (a[:, 0] <= a[:, 2]), 0,
                        np.where(a[:, 1] <= a[:, 2], 1, 2))  # fmt: skip
    t1 = np.zeros_like(e)  # e x (the axis of its smallest component), as chain3d._basis
    rows = np.arange(len(e))
    after, before = (smallest + 1) % 3, (smallest + 2) % 3
    t1[rows, after] = e[rows, before]
    t1[rows, before] = -e[rows, after]
    t1 /= np.sqrt((t1 * t1).sum(axis=1))[:, None]
    t2 = np.empty_like(e)
    t2[:, 0] = e[:, 1] * t1[:, 2] - e[:, 2] * t1[:, 1]
    t2[:, 1] = e[:, 2] * t1[:, 0] - e[:, 0] * t1[:, 2]
    t2[:, 2] = e[:, 0] * t1[:, 1] - e[:, 1] * t1[:, 0]
    return t1, t2


def tangents(y: np.ndarray, coords: Coordinates, which: np.ndarray) -> np.ndarray:
    """The direction (m, 3) each director increment of ``which`` turns its director along."""
    index = coords.q[which][:, None] + np.arange(3)[None, :]
    t1, t2 = normal_basis(y[index])
    return np.where((coords.axis[which] == 0)[:, None], t1, t2)


def apply(y: np.ndarray, coords: Coordinates, dx: np.ndarray) -> np.ndarray:
    """The state moved by the increments ``dx``."""
    out = y.copy()
    plain = np.isin(coords.kind, (0, 2, 4, STRAIN, ANGLE))
    np.add.at(out, coords.q[plain], dx[plain])
    turned = np.flatnonzero((coords.kind == TURN) & (dx != 0.0))
    if turned.size:  # (t_x, t_z) turned by the angle: t cos + n sin, n = (-t_z, t_x)
        tx, tz = y[coords.q[turned]], y[coords.q[turned] + 1]
        c, s = np.cos(dx[turned]), np.sin(dx[turned])
        out[coords.q[turned]] = tx * c - tz * s
        out[coords.q[turned] + 1] = tz * c + tx * s
    turned = np.flatnonzero((coords.kind == 3) & (dx != 0.0))  # the directors that turn
    if turned.size:
        index = coords.q[turned][:, None] + np.arange(3)[None, :]
        np.add.at(out, index, dx[turned][:, None] * tangents(y, coords, turned))
        first = np.unique(coords.q[turned])
        rows = first[:, None] + np.arange(3)[None, :]
        out[rows] /= np.linalg.norm(out[rows], axis=1)[:, None]
    for b in np.unique(coords.body[coords.kind == 1]):
        mine = (coords.kind == 1) & (coords.body == b)
        theta = np.zeros(3)
        theta[coords.axis[mine]] = dx[mine]
        q = coords.q[mine][0]
        out[q : q + 4] = rotate(out[q : q + 4], theta)
    return out


def pattern(p: kernel.SystemParams, coords: Coordinates) -> sparse.csr_matrix:
    """Which increments can change which accelerations (a superset)."""
    n = len(coords.kind)
    body_cols: dict[int, list[int]] = {}
    for i in range(n):
        if coords.body[i] >= 0:
            body_cols.setdefault(int(coords.body[i]), []).append(i)
    node_index: dict[tuple[int, int], list[int]] = {}
    for i in (int(k) for k in np.flatnonzero(coords.kind == 2)):
        li = int(coords.line[i])
        local = int(coords.q[i] - p.line_q[li]) // 3
        node_index.setdefault((li, local), []).append(i)
    links: list[tuple[list[int], list[int]]] = []
    for cols in _rigid_groups(p, coords, body_cols):
        links.append((cols, cols))
    links += _string_links(coords)
    moving = set(body_cols)
    # bodies that share a line or tie are coupled; every body to itself
    groups: list[list[int]] = [[b] for b in moving]
    for li in range(len(p.line_n)):
        ends_all = (int(p.point_body[p.line_from[li]]), int(p.point_body[p.line_to[li]]))
        ends = [b for b in ends_all if b in moving]
        groups.append(ends)
        ends_cols = [body_cols[b] if b in moving else None for b in ends_all]
        c0, segments = int(p.line_node[li]), int(p.line_n[li])
        bends = bool(np.any(p.node_bend[c0 + 1 : c0 + segments] != 0.0))
        links += _lumped_links(li, segments - 1, node_index, ends_cols, 2 if bends else 1)
    for k in range(len(p.tie_from)):
        groups.append([b for b in (int(p.point_body[p.tie_from[k]]),
                                   int(p.point_body[p.tie_to[k]])) if b in moving])  # fmt: skip
    for group in groups:
        for a in group:
            for b in group:
                links.append((body_cols[a], body_cols[b]))
    rows, cols = [], []
    for r, c in links:
        for i in r:
            rows.extend([i] * len(c))
            cols.extend(c)
    data = np.ones(len(rows))
    out = sparse.csr_matrix((data, (rows, cols)), shape=(n, n))
    return _solved_together(p, body_cols, out)


def _solved_together(p, body_cols: dict[int, list[int]], out: sparse.csr_matrix):
    """``out`` with the rows of the bodies solved together (a group of ``rigid.solve_groups``:
    joints, rigid lines held on free bodies) each holding every column that any of them
    holds: a load on one of them accelerates them all."""
    groups: dict[int, list[int]] = {}
    for b, cols in body_cols.items():
        if p.body_group[b, 0] >= 0:
            groups.setdefault(int(p.body_group[b, 0]), []).extend(cols)
    rows, cols = [], []
    for members in groups.values():
        union = np.unique(out[members].indices)
        for i in members:
            rows.extend([i] * len(union))
            cols.extend(union.tolist())
    if not rows:
        return out
    extra = sparse.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=out.shape)
    return ((out + extra) != 0).astype(float).tocsr()


def _lumped_links(li: int, n_int: int, node_index: dict, ends_cols: list, reach: int) -> list:
    """A lumped line's links: each of its ``n_int`` interior nodes to the nodes within
    ``reach`` along it (a node's loads come from its two segments, 1; bending at a node moves
    its two neighbours too, 2), and the nodes within reach of each end to and from that end's
    body's columns (``ends_cols``: from and to; None for a body that does not move). A reach
    of 1 narrows each line's band in Newton's matrix from 8 to 5 diagonals on either side:
    its factorisation 2.5 times, its solve 1.6 times fewer operations."""
    links = []
    for j in range(n_int):
        near = [node_index[(li, k)] for k in range(max(0, j - reach), min(n_int, j + reach + 1))]
        links.append((node_index[(li, j)], [c for cols in near for c in cols]))
    first, last = range(min(reach, n_int)), range(max(0, n_int - reach), n_int)
    for cols, nodes in zip(ends_cols, (first, last), strict=True):  # each end its own nodes
        if cols is None:
            continue
        for j in nodes:
            links.append((node_index[(li, j)], cols))
            links.append((cols, node_index[(li, j)]))
    return links


def _string_links(coords: Coordinates) -> list[tuple[list[int], list[int]]]:
    """A natural string's node (its strain and tangent) with its neighbours': the discrete
    equations (kernels.natural) couple nothing farther, the end mass folded into the last
    node's."""
    links = []
    string = coords.kind >= STRAIN
    for li in np.unique(coords.line[string]):
        cols = np.flatnonzero(string & (coords.line == li)).reshape(-1, 2)
        for i in range(len(cols)):
            near = cols[max(0, i - 1) : i + 2].ravel()
            links.append(([int(c) for c in cols[i]], [int(c) for c in near]))
    return links


def _rigid_groups(p, coords: Coordinates, body_cols: dict[int, list[int]]) -> list[list[int]]:
    """The columns of each tree of rigid lines and the bodies they join (coupled densely: a
    sweep couples every segment of a line; a line held on a free body couples it too); a body
    carried at a tip gets its tree's columns in ``body_cols`` (its motion is its line's)."""
    parent: dict[tuple[str, int], tuple[str, int]] = {}

    def root(x):
        parent.setdefault(x, x)
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    def ends(li: int) -> tuple[int, ...]:  # its base; the body carried or held at its end
        held = int(p.point_body[p.rs_to[li]]) if p.rs_port[li] else -1
        return int(p.point_body[p.rs_from[li]]), int(p.rs_tip[li]), held

    for li in range(len(p.rs_n)):
        parent[root(("line", li))] = root(("body", int(p.point_body[p.rs_from[li]])))
        for b in ends(li)[1:]:
            if b >= 0:
                parent[root(("body", b))] = root(("line", li))
    members: dict[tuple[str, int], list[int]] = {}
    for i in np.flatnonzero((coords.kind == 3) | (coords.kind == 4)):
        members.setdefault(root(("line", int(coords.line[i]))), []).append(int(i))
    for li in range(len(p.rs_n)):
        for b in ends(li):
            if b >= 0 and b in body_cols and p.body_kind[b] != kinematics.TIP:
                group = members.setdefault(root(("body", b)), [])
                group.extend(c for c in body_cols[b] if c not in group)
    for li in range(len(p.rs_n)):
        if p.rs_tip[li] >= 0:
            body_cols[int(p.rs_tip[li])] = members[root(("line", li))]
    return list(members.values())


def colour(structure: sparse.csr_matrix) -> np.ndarray:
    """Groups of columns that share no row, for finite differences: greedy, the columns with
    the most entries first (Welsh and Powell's order; ties in column order). Columns coupled
    through a body (a line's nodes next to its fairleads, the body's own) each need a colour
    of their own but can share it with nodes far along other lines: in natural order they
    were coloured last and alone (the moored barge with three 40-segment chains: 42 colours,
    the body's and its fairlead nodes' 24 of them alone; in this order 21)."""
    csc = structure.tocsc()
    n = structure.shape[1]
    colours = -np.ones(n, dtype=np.int64)
    row_colours: list[set[int]] = [set() for _ in range(structure.shape[0])]
    shared = (abs(csc).T @ abs(csc)).tocsc()  # columns that share a row with each column
    for j in np.argsort(-np.diff(shared.indptr), kind="stable"):
        rows = csc.indices[csc.indptr[j] : csc.indptr[j + 1]]
        used = set().union(*(row_colours[r] for r in rows)) if len(rows) else set()
        c = 0
        while c in used:
            c += 1
        colours[j] = c
        for r in rows:
            row_colours[r].add(c)
    return colours


class Residual:
    """Accelerations of every increment's degree of freedom at a state (with ``balance``, the
    segments of rigid trees that hang free give their moment balance instead: statics; without,
    every coordinate its acceleration: linearised dynamics)."""

    def __init__(self, p: kernel.SystemParams, coords: Coordinates, time: float = 0.0,
                 balance: bool = True):  # fmt: skip
        self.p, self.coords, self.time = p, coords, time
        self.w = kernel.make_work(p)
        self.ydot = np.zeros(p.n_q + p.n_v + p.n_s)

        # rigid lines whose trees hang free (no held tip) balance moments (N m) rather than
        # accelerations: the residual of the segments' statics, well scaled whatever the
        # masses carried below them
        self.free = free_trees(p)
        self.directors = np.flatnonzero((coords.kind == 3) | (coords.kind == 4))
        self.moments = np.zeros(len(self.directors))
        per_line = np.where(np.asarray(p.rs_kind) == rigid.PLANAR, 1, 2) * np.asarray(p.rs_n)
        per_segment = np.repeat(np.arange(len(p.rs_n)), per_line)
        self.balanced = self.free[per_segment] if len(p.rs_n) else np.zeros(0, bool)
        self.balanced &= balance

    def __call__(self, y: np.ndarray) -> np.ndarray:
        kernel.rhs(self.time, y, self.p, self.w, self.ydot)
        out = accelerations(y, self.coords, self.ydot)
        if self.balanced.any():
            rigid.moments(self.p, self.w, self.free, self.moments, False)
            out[self.directors[self.balanced]] = self.moments[self.balanced]
        return out


def free_trees(p: kernel.SystemParams) -> np.ndarray:
    """Per rigid line: True when no line of its tree (the lines joined through the bodies
    carried at their tips) is held at its tip."""
    nr = len(p.rs_n)
    tree = np.arange(nr)
    carried_by = {int(p.rs_tip[li]): li for li in range(nr) if p.rs_tip[li] >= 0}
    for li in range(nr):  # the root of each line: follow its base up while a line carries it
        at = li
        while int(p.point_body[p.rs_from[at]]) in carried_by:
            at = carried_by[int(p.point_body[p.rs_from[at]])]
        tree[li] = at
    held = np.asarray(np.asarray(p.rs_held).reshape(-1, 3).sum(axis=1) > 0)
    return np.array([not held[tree == tree[li]].any() for li in range(nr)], dtype=bool)


def accelerations(y: np.ndarray, coords: Coordinates, ydot: np.ndarray) -> np.ndarray:
    """The acceleration of each coordinate in the rates ``ydot`` (a director's on its turn's
    direction, a string's cartesian tangent's on n)."""
    out = ydot[coords.v].copy()
    turned = np.flatnonzero(coords.kind == 3)
    if turned.size:
        index = coords.v[turned][:, None] + np.arange(3)[None, :]
        out[turned] = np.einsum("ij,ij->i", ydot[index], tangents(y, coords, turned))
    turned = np.flatnonzero(coords.kind == TURN)
    if turned.size:
        n = tangent_normals(y, coords, turned)
        out[turned] = ydot[coords.v[turned]] * n[:, 0] + ydot[coords.v[turned] + 1] * n[:, 1]
    return out


def tangent_normals(y: np.ndarray, coords: Coordinates, which: np.ndarray) -> np.ndarray:
    """n = (-t_z, t_x) (m, 2) of the cartesian string tangents ``which``: the direction their
    increment turns them along."""
    return np.stack([-y[coords.q[which] + 1], y[coords.q[which]]], axis=1)


def is_angle(kind: np.ndarray) -> np.ndarray:
    """True for a coordinate that is an angle [rad] (a body's turn, a director's, a string's
    tangent)."""
    return (kind == 1) | (kind == 3) | (kind == 4) | (kind == ANGLE) | (kind == TURN)


def fd_jacobian(residual, y, coords, structure, colours, r0,
                central: bool = False) -> sparse.csc_matrix:  # fmt: skip
    """The Jacobian of ``residual`` about ``y`` on ``structure``, a residual evaluation per
    colour of columns: forward differences (steps 1e-7 of each coordinate's size), or with
    ``central`` two per colour (steps 1e-6). Forward differences err by the second
    derivative: moving a node of a taut lumped line by h across it stretches its segments by
    h^2 / (2 l), which adds EA h / (2 l^2) to the geometric stiffness T / l of a transverse
    column, a relative error EA h / (2 l T): 17 % for a 2e8 N wire at 9 kN in 1.3 m segments
    (h = 2e-5 m), enough to stall Newton; central differences cancel it."""
    rows_of = structure.tocsc()
    n = len(coords.kind)
    data_r, data_c, data_v = [], [], []
    for c in range(int(colours.max()) + 1 if n else 0):
        columns = np.flatnonzero(colours == c)
        scale = np.where(
            is_angle(coords.kind[columns]), 1.0, np.maximum(1.0, np.abs(y[coords.q[columns]]))
        )
        step = (1e-6 if central else 1e-7) * scale
        dx = np.zeros(n)
        dx[columns] = step
        if central:
            dr = 0.5 * (residual(apply(y, coords, dx)) - residual(apply(y, coords, -dx)))
        else:
            dr = residual(apply(y, coords, dx)) - r0
        first, counts = rows_of.indptr[columns], np.diff(rows_of.indptr)[columns]
        at = np.repeat(first - np.cumsum(counts) + counts, counts) + np.arange(counts.sum())
        rows = rows_of.indices[at]
        data_r.append(rows)
        data_c.append(np.repeat(columns, counts))
        data_v.append(dr[rows] / np.repeat(step, counts))
    if not data_r:
        return sparse.csc_matrix((n, n))
    values, rows, cols = (np.concatenate(d) for d in (data_v, data_r, data_c))
    return sparse.csc_matrix((values, (rows, cols)), shape=(n, n))
