"""Statics and linearisation of a whole system: every dynamic body free on its degrees of
freedom under its force models, its lines and ties, and the steady current; every lumped line
at its discrete equilibrium (seabed included). Newton iterations on the accelerations of every
free degree of freedom at rest, with a sparse finite-difference Jacobian (columns grouped by a
greedy colouring of the system's known sparsity: each line a chain of nodes, its two end
nodes' neighbours tied to the bodies it hangs from, ties joining bodies), solved by sparse LU.

Coordinates ("increments"): per dynamic body its free translations (earth x, y, z) and its
free rotations (a rotation vector in the earth frame, applied as exp(theta) to its
orientation), then every interior node's position, then every rigid segment's turn on the two
directions t1, t2 normal to its director (kernels.chain3d._basis; the residual is the
director's acceleration on them). The same coordinates carry the
linearisation: ``jacobian`` gives d(rates)/d(increments, velocities) about any state.
"""

from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.sparse.linalg import splu

from seacable.bodies import kinematics
from seacable.errors import SeacableError
from seacable.kernels import surface
from seacable.system import kernel, outputs, rigid
from seacable.system.assemble import BuiltSystem
from seacable.system.initial import settle_lines


class StaticsError(SeacableError):
    """The static equilibrium was not found; the message names the body or line at fault."""


@dataclass(frozen=True)
class Coordinates:
    """Where each increment goes: ``kind`` 0 translation, 1 rotation, 2 node, 3 director, 4
    planar link's angle;
    ``body`` its body (-1 for a node or director); ``axis`` 0..2 (a director's: 0 along t1, 1
    along t2); ``q`` its position in y (translation, node), the body's first quaternion entry
    or the director's first entry; ``v`` the state index of its velocity (a director's first
    rate); ``line`` (-1 for a body; a lumped line's index for a node, a rigid line's for a
    director)."""

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
    table = np.array(rows, dtype=np.int64).reshape(-1, 6)
    return Coordinates(*(table[:, c].copy() for c in range(6)))


def _rotate(quaternion: np.ndarray, theta: np.ndarray) -> np.ndarray:
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
    t1 = np.where(
        ((a[:, 0] <= a[:, 1]) & (a[:, 0] <= a[:, 2]))[:, None],
        np.column_stack([np.zeros(len(e)), e[:, 2], -e[:, 1]]),
        np.where(
            (a[:, 1] <= a[:, 2])[:, None],
            np.column_stack([-e[:, 2], np.zeros(len(e)), e[:, 0]]),
            np.column_stack([e[:, 1], -e[:, 0], np.zeros(len(e))]),
        ),
    )
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    return t1, np.cross(e, t1)


def _tangents(y: np.ndarray, coords: Coordinates, which: np.ndarray) -> np.ndarray:
    """The direction (m, 3) each director increment of ``which`` turns its director along."""
    index = coords.q[which][:, None] + np.arange(3)[None, :]
    t1, t2 = normal_basis(y[index])
    return np.where((coords.axis[which] == 0)[:, None], t1, t2)


def apply(y: np.ndarray, coords: Coordinates, dx: np.ndarray) -> np.ndarray:
    """The state moved by the increments ``dx``."""
    out = y.copy()
    plain = (coords.kind == 0) | (coords.kind == 2) | (coords.kind == 4)
    np.add.at(out, coords.q[plain], dx[plain])
    turned = np.flatnonzero(coords.kind == 3)
    if turned.size:
        index = coords.q[turned][:, None] + np.arange(3)[None, :]
        np.add.at(out, index, dx[turned][:, None] * _tangents(y, coords, turned))
        first = np.unique(coords.q[turned])
        rows = first[:, None] + np.arange(3)[None, :]
        out[rows] /= np.linalg.norm(out[rows], axis=1)[:, None]
    for b in np.unique(coords.body[coords.kind == 1]):
        mine = (coords.kind == 1) & (coords.body == b)
        theta = np.zeros(3)
        theta[coords.axis[mine]] = dx[mine]
        q = coords.q[mine][0]
        out[q : q + 4] = _rotate(out[q : q + 4], theta)
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
    moving = set(body_cols)
    # bodies that share a line or tie are coupled; every body to itself
    groups: list[list[int]] = [[b] for b in moving]
    for li in range(len(p.line_n)):
        ends = [int(p.point_body[p.line_from[li]]), int(p.point_body[p.line_to[li]])]
        ends = [b for b in ends if b in moving]
        groups.append(ends)
        n_int = int(p.line_n[li]) - 1
        reach = 2  # bending couples nodes two apart
        for j in range(n_int):
            near = [
                node_index[(li, k)] for k in range(max(0, j - reach), min(n_int, j + reach + 1))
            ]
            links.append((node_index[(li, j)], [c for cols in near for c in cols]))
        for j in (*range(min(reach, n_int)), *range(max(0, n_int - reach), n_int)):
            for b in ends:
                links.append((node_index[(li, j)], body_cols[b]))
                links.append((body_cols[b], node_index[(li, j)]))
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
    return sparse.csr_matrix((data, (rows, cols)), shape=(n, n))


def _rigid_groups(p, coords: Coordinates, body_cols: dict[int, list[int]]) -> list[list[int]]:
    """The columns of each tree of rigid lines and the bodies they join (coupled densely: a
    sweep couples every segment of a line); a body carried at a tip gets its tree's columns
    in ``body_cols`` (its motion is its line's)."""
    parent: dict[tuple[str, int], tuple[str, int]] = {}

    def root(x):
        parent.setdefault(x, x)
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for li in range(len(p.rs_n)):
        parent[root(("line", li))] = root(("body", int(p.point_body[p.rs_from[li]])))
        if p.rs_tip[li] >= 0:
            parent[root(("body", int(p.rs_tip[li])))] = root(("line", li))
    members: dict[tuple[str, int], list[int]] = {}
    for i in np.flatnonzero(coords.kind >= 3):
        members.setdefault(root(("line", int(coords.line[i]))), []).append(int(i))
    for li in range(len(p.rs_n)):
        for b in (int(p.point_body[p.rs_from[li]]), int(p.rs_tip[li])):
            if b >= 0 and b in body_cols and p.body_kind[b] != kinematics.TIP:
                group = members.setdefault(root(("body", b)), [])
                group.extend(c for c in body_cols[b] if c not in group)
    for li in range(len(p.rs_n)):
        if p.rs_tip[li] >= 0:
            body_cols[int(p.rs_tip[li])] = members[root(("line", li))]
    return list(members.values())


def colour(structure: sparse.csr_matrix) -> np.ndarray:
    """Groups of columns that share no row (greedy), for finite differences."""
    csc = structure.tocsc()
    n = structure.shape[1]
    colours = -np.ones(n, dtype=np.int64)
    row_colours: list[set[int]] = [set() for _ in range(structure.shape[0])]
    for j in range(n):
        rows = csc.indices[csc.indptr[j] : csc.indptr[j + 1]]
        used = set().union(*(row_colours[r] for r in rows)) if len(rows) else set()
        c = 0
        while c in used:
            c += 1
        colours[j] = c
        for r in rows:
            row_colours[r].add(c)
    return colours


class _Residual:
    """Accelerations of every increment's degree of freedom at a state."""

    def __init__(self, p: kernel.SystemParams, coords: Coordinates, time: float = 0.0):
        self.p, self.coords, self.time = p, coords, time
        self.w = kernel.make_work(p)
        self.ydot = np.zeros(p.n_q + p.n_v)

        # rigid lines whose trees hang free (no held tip) balance moments (N m) rather than
        # accelerations: the residual of the segments' statics, well scaled whatever the
        # masses carried below them
        self.free = free_trees(p)
        self.directors = np.flatnonzero((coords.kind == 3) | (coords.kind == 4))
        self.moments = np.zeros(len(self.directors))
        per_line = np.where(np.asarray(p.rs_kind) == rigid.PLANAR, 1, 2) * np.asarray(p.rs_n)
        per_segment = np.repeat(np.arange(len(p.rs_n)), per_line)
        self.balanced = self.free[per_segment] if len(p.rs_n) else np.zeros(0, bool)

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
    direction)."""
    out = ydot[coords.v].copy()
    turned = np.flatnonzero(coords.kind == 3)
    if turned.size:
        index = coords.v[turned][:, None] + np.arange(3)[None, :]
        out[turned] = np.einsum("ij,ij->i", ydot[index], _tangents(y, coords, turned))
    return out


def _angle(kind: np.ndarray) -> np.ndarray:
    """True for a coordinate that is an angle [rad] (a body's turn, a director's)."""
    return (kind == 1) | (kind == 3) | (kind == 4)


def _fd_jacobian(residual, y, coords, structure, colours, r0) -> sparse.csc_matrix:
    rows_of = structure.tocsc()
    n = len(coords.kind)
    data_r, data_c, data_v = [], [], []
    for c in range(int(colours.max()) + 1 if n else 0):
        columns = np.flatnonzero(colours == c)
        scale = np.where(
            _angle(coords.kind[columns]), 1.0, np.maximum(1.0, np.abs(y[coords.q[columns]]))
        )
        step = 1e-7 * scale
        dx = np.zeros(n)
        dx[columns] = step
        dr = residual(apply(y, coords, dx)) - r0
        for j, h in zip(columns, step, strict=True):
            rows = rows_of.indices[rows_of.indptr[j] : rows_of.indptr[j + 1]]
            data_r.extend(rows)
            data_c.extend([j] * len(rows))
            data_v.extend(dr[rows] / h)
    return sparse.csc_matrix((data_v, (data_r, data_c)), shape=(n, n))


def equilibrium(built: BuiltSystem, y0: np.ndarray, iterations: int = 60,
                tolerance: float = 1e-9) -> np.ndarray:  # fmt: skip
    """The state at rest in balance, from ``y0``'s positions (velocities set to zero).

    First Newton over every coordinate at once (sparse Jacobian); when that fails, Newton over
    the free bodies' degrees of freedom alone (a small dense system), each line settled at its
    static shape between its ends for every trial pose (``initial.settle_lines``, the linear
    axial law: chain lying on a frictionless seabed has one shape) — slower, but it does not
    lose its way in the kinks of the seabed's contact or of the free surface. Raises
    StaticsError naming the body or line that stays out of balance."""
    p = built.params
    coords = coordinates(p)
    y = y0.copy()
    y[p.n_q :] = 0.0
    if not len(coords.kind):
        return y
    residual = _Residual(p, coords)
    if residual.balanced.any():
        y = _hang(p, y, residual.free)
    scale = float(np.abs(residual(y)).max()) + 1.0
    direct = _direct(built, coords, residual, y, iterations, tolerance * scale)
    r = residual(direct)
    if np.all(np.isfinite(r)) and np.abs(r).max() < 1e-6 * scale:
        return direct
    bodies = np.flatnonzero(coords.kind <= 1)
    if bodies.size and not len(p.rs_n):
        nested = _bodies_newton(built, coords, residual, y, bodies, iterations, tolerance * scale)
        r = residual(nested)
        nodes = np.flatnonzero(coords.kind == 2)
        r[nodes] = _Residual(p._replace(slack_allowed=0), coords)(nested)[nodes]
        if np.all(np.isfinite(r)) and np.abs(r).max() < 1e-6 * scale:
            return nested
    followed = _homotopy(built, coords, residual, y, tolerance * scale)
    r = residual(followed)
    if np.all(np.isfinite(r)) and np.abs(r).max() < 1e-6 * scale:
        return followed
    raise StaticsError(_blame(built, coords, r))


def _hang(p: kernel.SystemParams, y: np.ndarray, free: np.ndarray, sweeps: int = 200):
    """The rigid lines of free trees turned, again and again, along the pull each segment
    carries (system.rigid.moments' march: the statics of a hanging or towed line as a fixed
    point, tension positive), half a step at a time, until they stop turning: a first shape
    from which Newton converges to the balance with every segment pulled, not to one of the
    balances with segments folded back and pushed."""
    w = kernel.make_work(p)
    ydot = np.zeros_like(y)
    planar = np.asarray(p.rs_kind) == rigid.PLANAR
    width = np.where(planar, 1, 3)
    index = np.concatenate([
        np.arange(p.rs_q[li], p.rs_q[li] + width[li] * p.rs_n[li]) for li in range(len(p.rs_n))
    ])  # fmt: skip
    turned = np.zeros(len(index))
    line_of = np.repeat(np.arange(len(p.rs_n)), width * np.asarray(p.rs_n))
    y = y.copy()
    for _ in range(sweeps):
        kernel.rhs(0.0, y, p, w, ydot)
        rigid.moments(p, w, free, turned, True)
        old = y[index]
        new = old.copy()
        for li in np.flatnonzero(free):
            mine = line_of == li
            if planar[li]:  # angles: half the turn, the short way round
                step = np.angle(np.exp(1j * (turned[mine] - old[mine])))
                new[mine] = old[mine] + 0.5 * step
            else:
                half = 0.5 * (old[mine] + turned[mine]).reshape(-1, 3)
                new[mine] = (half / np.linalg.norm(half, axis=1)[:, None]).ravel()
        y[index] = new
        if np.abs(new - old).max() < 1e-9:
            break
    return y


def _homotopy(built, coords, residual, y, tolerance, smallest: float = 1e-3):
    """Newton's homotopy: the balance of r(x) - (1 - s) r(x0) followed from s = 0 (where the
    start is one) to s = 1, each s from the last one's balance, the step in s halved when
    Newton fails there: loads that the direct Newton cannot take at once (a platform pushed far
    off by a steady force) are taken in stages."""
    start = residual(y)
    s, step = 0.0, 0.1
    while s < 1.0 and step >= smallest:
        target = min(1.0, s + step)

        def staged(state, target=target):  # noqa: B023 (bound by the default)
            return residual(state) - (1.0 - target) * start

        trial = _direct(built, coords, staged, y, 20, tolerance)
        rt = staged(trial)
        if np.all(np.isfinite(rt)) and np.abs(rt).max() < max(tolerance, 1e-9):
            y, s = trial, target
            step = min(2.0 * step, 0.25)
        else:
            step *= 0.5
    return y


def _direct(built, coords, residual, y, iterations, tolerance):
    """Newton over every coordinate; the best state met."""
    p = built.params
    structure = pattern(p, coords)
    colours = colour(structure)
    r = residual(y)
    best, best_norm = y, float(np.linalg.norm(r))
    limit = _step_limit(built, coords)
    for _ in range(iterations):
        if not np.all(np.isfinite(r)) or np.abs(r).max() < tolerance:
            break
        jac = _fd_jacobian(residual, y, coords, structure, colours, r)
        try:
            step = splu(jac).solve(-r)
        except RuntimeError:
            break
        largest = float(np.max(np.abs(step) / limit))
        if largest > 1.0:
            step /= largest
        # the first shorter step that lowers the residual, else the whole step: the seabed's
        # contact makes the residual non-smooth and Newton's path to it not monotone
        for fraction in (1.0, 0.5, 0.25, 0.125, 1.0):
            trial = apply(y, coords, fraction * step)
            rt = residual(trial)
            if np.all(np.isfinite(rt)) and np.linalg.norm(rt) < np.linalg.norm(r):
                break
        y, r = trial, rt
        if np.all(np.isfinite(r)) and np.linalg.norm(r) < best_norm:
            best, best_norm = y, float(np.linalg.norm(r))
    return best


def _moved(p, coords: Coordinates, y, bodies, dx):
    """``y`` with the bodies moved by ``dx`` and each line's interior nodes carried along,
    each by the displacement of its two ends weighted by its place along the line."""
    full = np.zeros(len(coords.kind))
    full[bodies] = dx
    before = _point_positions(p, y)
    out = apply(y, coords, full)
    after = _point_positions(p, out)
    for li in range(len(p.line_n)):
        n, s0, q = int(p.line_n[li]), int(p.line_seg[li]), int(p.line_q[li])
        arc = np.cumsum(p.seg_length[s0 : s0 + n])[:-1] / p.seg_length[s0 : s0 + n].sum()
        da = after[p.line_from[li]] - before[p.line_from[li]]
        db = after[p.line_to[li]] - before[p.line_to[li]]
        shift = da[None, :] + arc[:, None] * (db - da)[None, :]
        out[q : q + 3 * (n - 1)] += shift.ravel()
    return out


def _point_positions(p, y) -> np.ndarray:
    w = kernel.make_work(p)
    kernel.rhs(0.0, y, p, w, np.zeros_like(y))
    return w.ppos.copy()


def _bodies_newton(built, coords, residual, y, bodies, iterations, tolerance):
    p = built.params
    limit = _step_limit(built, coords, shortest=True)[bodies]

    def settled(state):
        out = settle_lines(p, state, slack=0)
        return out, residual(out)[bodies]

    y, r = settled(y)
    for _ in range(iterations):
        if not np.all(np.isfinite(r)) or np.abs(r).max() < tolerance:
            break
        jac = np.empty((len(bodies), len(bodies)))
        for j in range(len(bodies)):
            h = (
                1e-6
                if coords.kind[bodies[j]] == 1
                else 1e-6 * max(1.0, abs(y[coords.q[bodies[j]]]))
            )
            dx = np.zeros(len(bodies))
            dx[j] = h
            jac[:, j] = (settled(_moved(p, coords, y, bodies, dx))[1] - r) / h
        try:
            step = np.linalg.solve(jac, -r)
        except np.linalg.LinAlgError:
            step = np.linalg.lstsq(jac, -r, rcond=None)[0]
        largest = float(np.max(np.abs(step) / limit))
        if largest > 1.0:
            step /= largest
        for fraction in (1.0, 0.5, 0.25, 0.125, 0.0625):
            trial, rt = settled(_moved(p, coords, y, bodies, fraction * step))
            if np.all(np.isfinite(rt)) and np.linalg.norm(rt) < np.linalg.norm(r):
                break
        else:
            break
        y, r = trial, rt
    return y


def _step_limit(built: BuiltSystem, coords: Coordinates, shortest: bool = False) -> np.ndarray:
    """Largest increment of each coordinate in one Newton step: a tenth of all lines' and
    ties' length (of the ``shortest`` one) for positions (at least 1 m), 0.1 rad for
    rotations, and a quarter of its size
    for a body the free surface cuts (a step must not lift it clear of the water, where
    nothing tells Newton the way back)."""
    p = built.params
    lengths = (
        [
            float(p.seg_length[p.line_seg[i] : p.line_seg[i] + p.line_n[i]].sum())
            for i in range(len(p.line_n))
        ]
        + [float(v) for v in p.tie_length if v > 0]
        + [
            float(p.rs_length[p.rs_seg[i] : p.rs_seg[i] + p.rs_n[i]].sum())
            for i in range(len(p.rs_n))
        ]
    )
    metres = max(1.0, 0.1 * (min(lengths) if shortest else sum(lengths))) if lengths else 1.0
    limit = np.where(_angle(coords.kind), 0.1, metres)
    for i in np.flatnonzero((coords.kind == 0) & (coords.axis == 2)):
        shape = p.body_shape[coords.body[i]]
        if shape[0] != surface.POINT:
            size = shape[1] if shape[0] == surface.SPHERE else (
                0.5 * shape[2] if shape[0] == surface.CYLINDER else 1.0)  # fmt: skip
            limit[i] = min(limit[i], 0.25 * size)
    return limit


def _blame(built: BuiltSystem, coords: Coordinates, r: np.ndarray) -> str:
    worst = int(np.nanargmax(np.where(np.isfinite(r), np.abs(r), np.inf)))
    if coords.body[worst] >= 0:
        name = built.case.bodies[int(coords.body[worst])].name
        what = ("x", "y", "z")[int(coords.axis[worst])]
        dof = "rotation about" if coords.kind[worst] == 1 else "force along"
        where = f"body '{name}' ({dof} {what}: acceleration {r[worst]:.3g} at rest)"
    elif coords.kind[worst] >= 3:
        where = f"line '{built.layout.rigid[int(coords.line[worst])]}'"
    else:
        where = f"line '{built.layout.lines[int(coords.line[worst])]}'"
    return (
        f"statics: no equilibrium found; {where} stays out of balance. Check that something "
        "holds every free degree of freedom (a line, a tie, a stiffness or buoyancy against "
        "gravity), that the lines can reach their bodies, or start the run as given "
        "(start: as_given)"
    )


def jacobian(
    built: BuiltSystem, y: np.ndarray, time: float = 0.0
) -> tuple[np.ndarray, Coordinates]:
    """A = d(rates)/d(increments, velocities) of the free degrees of freedom about ``y``
    (dense, central differences): the linearised system dz/dt = A z with z = (dx, dv)."""
    p = built.params
    coords = coordinates(p)
    n = len(coords.kind)
    residual = _Residual(p, coords, time)
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    for j in range(n):
        h = 1e-6 * (1.0 if _angle(coords.kind[j : j + 1])[0] else max(1.0, abs(y[coords.q[j]])))
        dx = np.zeros(n)
        dx[j] = h
        a[n:, j] = (residual(apply(y, coords, dx)) - residual(apply(y, coords, -dx))) / (2 * h)
        hv = 1e-6 * max(1.0, abs(y[coords.v[j]]))
        up, down = y.copy(), y.copy()
        if coords.kind[j] == 3:  # the director's rate along its turn's direction
            at = coords.v[j] + np.arange(3)
            step = hv * _tangents(y, coords, np.array([j]))[0]
            up[at] += step
            down[at] -= step
        else:
            up[coords.v[j]] += hv
            down[coords.v[j]] -= hv
        a[n:, n + j] = (residual(up) - residual(down)) / (2 * hv)
    return a, coords


def line_loads(built: BuiltSystem, y: np.ndarray, at_rest: bool = False) -> np.ndarray:
    """(bodies, 6): force [N] and moment about the reference point [N m] of every body's lines
    and ties at the state ``y``, earth frame.

    By default as the results report them (``line_force_*``, ``line_moment_*``): each lumped
    line's end force is its end node's loads less the node's mass times its point's
    acceleration (the node moves with the body). ``at_rest``: the static loads of the lines
    held at ``y``, without that inertia: each lumped line's end-node loads (its end segment's
    tension, half the segment's weight and buoyancy, the seabed's) and each tie's force (a
    rigid-segment line's end forces as in the results). A held body's acceleration at a pose
    out of balance comes from its own force models, and must not enter its lines' loads."""
    p = built.params
    nb, nl, nt = len(p.body_kind), len(p.line_n), len(p.tie_from)
    bodies = np.empty((1, nb, outputs.BODY_COLUMNS))
    w = kernel.make_work(p)
    rigid = outputs.rigid_rows(p, 1)
    outputs.outputs_chunk(
        np.zeros(1), y[None, :], p, w, bodies,
        np.empty((1, len(p.node_mass), 3)), np.empty((1, len(p.seg_length))),
        np.empty((1, nl, 2, 3)), np.empty((1, nt, 8)), np.empty((1, 3)), rigid,
    )  # fmt: skip
    if not at_rest:
        return bodies[0, :, 12:18].copy()
    # every end force on a point (N, earth frame): lumped lines' from and to ends, ties'
    # from (+) and to (-) ends, rigid lines' from and to ends
    points = np.concatenate([p.line_from, p.line_to, p.tie_from, p.tie_to, p.rs_from, p.rs_to])
    forces = np.concatenate([w.end_load[:, 0], w.end_load[:, 1], w.tie_force, -w.tie_force,
                             rigid[2][0, :, 0], rigid[2][0, :, 1]])  # fmt: skip
    points = np.asarray(points, dtype=np.int64)
    loads = np.zeros((nb, 6))
    on = np.asarray(p.point_body)[points]
    np.add.at(loads[:, :3], on, forces)
    np.add.at(loads[:, 3:], on, np.cross(w.parm[points], forces))
    return loads


def mooring_stiffness(
    built: BuiltSystem, y: np.ndarray, body: str, translation: float = 1e-2,
    rotation: float = 1e-4, span: float | None = None,
) -> np.ndarray:  # fmt: skip
    """The 6x6 stiffness of the lines and ties on ``body`` about the state ``y`` (a static
    equilibrium): K[i, j] = -dF_i/dx_j [N/m, N/rad; N m/m, N m/rad], F the force and the moment
    about the body's reference point of its lines and ties at rest (``line_loads(...,
    at_rest=True)``, earth frame), x the reference point's position and the rotation vector
    (earth frame). The body's pose is moved by +-``translation`` [m] and +-``rotation`` [rad]
    in turn, every line's interior nodes re-solved at rest with every body held (the other
    bodies do not follow: their own stiffness is not included), and the loads differenced
    (central differences). The body's own force models (hydrostatics, weight) are not in K;
    MoorPy's ``lines_only`` stiffness is its analogue.

    ``span`` [m]: the translation columns as secants over +-``span`` instead (the pose moved
    there in steps of at most 0.25 m, the lines re-solved at each). A lumped line's tangent
    stiffness is a sawtooth along the pose: each time a node lifts off (or lands on) the
    seabed the slope drops (or jumps), by up to +-20 % of the heave stiffness for 10 m
    segments, about a continuous catenary's (-3 % in surge and -7 % in heave at the platform
    example's balance); a span of about one node spacing of touchdown travel averages it out
    (+-5 m: the platform example's surge and heave within 0.05 % of MoorPy's secants over the
    same poses at 70 segments, 0.2 % at 140). Rotations stay tangent (``rotation``).

    Raises StaticsError when a line's interior nodes are not in balance after re-solving
    (their largest acceleration above 1e-7 g) or when a rigid-segment line is on ``body``
    (not re-solved here)."""
    p = built.params
    b = built.layout.bodies.index(body)
    if p.body_kind[b] != kinematics.DYNAMIC or not p.body_rigid[b]:
        raise ValueError(f"mooring_stiffness: body '{body}' is not a rigid (6-DOF) body")
    for li in range(len(p.rs_n)):
        if b in (p.point_body[p.rs_from[li]], p.point_body[p.rs_to[li]]):
            raise StaticsError(
                f"mooring_stiffness: body '{body}' carries the rigid-segment line "
                f"'{built.layout.rigid[li]}', whose segments are not re-solved at the moved "
                "poses; compute the stiffness of a body whose lines are lumped_mass lines"
            )
    q = int(p.body_q[b])
    y = y.copy()
    y[p.n_q :] = 0.0
    stiffness = np.zeros((6, 6))
    for j in range(6):
        h = rotation if j >= 3 else (translation if span is None else span)
        steps = 1 if j >= 3 else max(1, int(np.ceil(h / 0.25 - 1e-9)))  # of 0.25 m at most
        loads = []
        for sign in (1.0, -1.0):
            moved = y.copy()
            for _ in range(steps):
                if j < 3:
                    moved[q + j] += sign * h / steps
                else:
                    theta = np.zeros(3)
                    theta[j - 3] = sign * h / steps
                    moved[q + 3 : q + 7] = _rotate(moved[q + 3 : q + 7], theta)
                moved = _settle(built, moved, body)
            loads.append(line_loads(built, moved, at_rest=True)[b])
        stiffness[:, j] = -(loads[0] - loads[1]) / (2.0 * h)
    return stiffness


def _settle(built: BuiltSystem, y: np.ndarray, body: str, attempts: int = 3) -> np.ndarray:
    """``y`` with every lumped line's interior nodes in balance at rest (``settle_lines``, the
    linear axial law), their largest acceleration at most 1e-7 g: each line's end loads then
    err by at most about 1e-7 of its weight. Newton is run again from its last state when it
    stopped short (it can stall where a node sits on the seabed's kink); StaticsError naming
    the line when it does not get there."""
    p = built.params
    allowed = 1e-7 * p.gravity
    ydot = np.zeros_like(y)
    worst = np.zeros(len(p.line_n))
    for _ in range(attempts):
        y = settle_lines(p, y)
        kernel.rhs(0.0, y, p._replace(slack_allowed=0), kernel.make_work(p), ydot)
        for li in range(len(p.line_n)):
            v = int(p.line_v[li])
            worst[li] = np.abs(ydot[v : v + 3 * (int(p.line_n[li]) - 1)]).max(initial=0.0)
        if np.all(worst <= allowed):
            return y
    li = int(np.argmax(np.where(np.isfinite(worst), worst, np.inf)))
    raise StaticsError(
        f"mooring_stiffness: line '{built.layout.lines[li]}' not in balance at a moved pose of "
        f"body '{body}' (interior node acceleration {worst[li]:.3g} m/s^2 after {attempts} "
        f"solves, allowed {allowed:.3g}); use fewer segments, or another translation or span"
    )
