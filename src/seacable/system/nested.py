"""Statics of a system of bodies and lumped-mass lines by Newton over the bodies' degrees of
freedom, every line at its static shape between them (system.statics calls it when Newton
over every coordinate at once fails; not with rigid-segment lines or natural strings).

The residual (``BodyForces``): a body's free degree of freedom its generalized force at rest
[N, N m] (earth frame, about its reference point), a line node its acceleration [m/s^2]. Along
the settled lines the bodies' forces have the Jacobian J_bb - J_bn J_nn^-1 J_nb (the lines'
stiffness condensed on the bodies, b the bodies' and n the nodes' coordinates): one sparse
solve of the whole Jacobian gives that Newton step for the bodies and, for the nodes, how they
follow it to first order, from where ``line_balance.settle_lines`` starts (a few iterations; carried
rigidly, a stiff chain's nodes would start metres out of length).

The Jacobian (``jacobian``) by central differences (forward ones give a stiff line's transverse
stiffness tens of per cent wrong: ``coordinates.fd_jacobian``), in a number of residual
evaluations that does not grow with the number of lines on a body. A body's force is its own
force models' plus, per line end on it, the end node's load (``w.end_load``) with its moment,
plus its ties'. So the nodes are perturbed in 3 (2 reach + 1) colours of every line at once
(reach: the nodes one segment, or with bending two, apart that a node's position moves), and
the change of each line end's load is read apart and carried to its body through its arm;
then the bodies, in groups that share no line end, tie or short line (each axis in turn).
"""

import numpy as np
from scipy import sparse

from seacable.system import kernel
from seacable.system.coordinates import Coordinates, accelerations, apply
from seacable.system.initial import uniform_shapes
from seacable.system.line_balance import pushed, settle_each, settle_lines
from seacable.system.pseudo_time import sparse_solve

# how hard a segment may be pushed in the nested Newton's balances, as a share of the largest
# tension: the linear axial law's push of chain lying slack in many short segments, which a
# step can leave at tens of newtons where the lines pull tens of kilonewtons
PUSH = 1e-3


class BodyForces:
    """The nested Newton's residual at a state (module docstring); after a call, ``ydot`` holds
    the rates and ``w`` the workspace (the lines' end loads, the points' arms)."""

    def __init__(self, p: kernel.SystemParams, coords: Coordinates, time: float = 0.0):
        self.p, self.coords, self.time = p, coords, time
        self.w = kernel.make_work(p)
        self.ydot = np.zeros(p.n_q + p.n_v + p.n_s)
        self.bodies = np.flatnonzero(coords.kind <= 1)
        self.body = coords.body[self.bodies]
        self.component = 3 * coords.kind[self.bodies] + coords.axis[self.bodies]

    def __call__(self, y: np.ndarray) -> np.ndarray:
        kernel.rhs(self.time, y, self.p, self.w, self.ydot)
        r = accelerations(y, self.coords, self.ydot)
        r[self.bodies] = (self.w.load - self.w.bias)[self.body, self.component]
        return r

    def body_accelerations(self) -> np.ndarray:
        """The bodies' accelerations [m/s^2, rad/s^2] at the last call."""
        return self.ydot[self.coords.v[self.bodies]]


def reach(p: kernel.SystemParams) -> int:
    """How many nodes along a line a node's position moves the loads of: 1, 2 with bending."""
    return 2 if np.any(np.asarray(p.node_bend) != 0.0) else 1


def _body_rows(coords: Coordinates) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """Per body: its coordinates' indices and their load components (0..5)."""
    out = {}
    for b in np.unique(coords.body[coords.kind <= 1]):
        mine = np.flatnonzero((coords.body == b) & (coords.kind <= 1))
        out[int(b)] = (mine, 3 * coords.kind[mine] + coords.axis[mine])
    return out


def _ends(p: kernel.SystemParams, span: int):
    """Per body: its line ends (line, end, point), the bodies its position moves the loads of
    directly (joined by a tie, or by a line of fewer than 2 ``span`` + 2 segments: their far end
    depends on its near end), and the keys of the rows it moves (for grouping)."""
    ends: dict[int, list[tuple[int, int, int]]] = {}
    near: dict[int, set[int]] = {}
    keys: dict[int, set] = {}
    for li in range(len(p.line_n)):
        points = (int(p.line_from[li]), int(p.line_to[li]))
        bodies = [int(p.point_body[a]) for a in points]
        short = int(p.line_n[li]) < 2 * span + 2
        for e in range(2):
            ends.setdefault(bodies[e], []).append((li, e, points[e]))
            keys.setdefault(bodies[e], set()).add(("line", li) if short else ("line", li, e))
            if short:
                near.setdefault(bodies[e], set()).add(bodies[1 - e])
    for k in range(len(p.tie_from)):
        a, b = int(p.point_body[p.tie_from[k]]), int(p.point_body[p.tie_to[k]])
        near.setdefault(a, set()).add(b)
        near.setdefault(b, set()).add(a)
    return ends, near, keys


def jacobian(forces: BodyForces, y: np.ndarray) -> sparse.csc_matrix:
    """d(residual)/d(increments) of ``forces`` about ``y`` (module docstring)."""
    p, coords = forces.p, forces.coords
    n = len(coords.kind)
    span = reach(p)
    rows_of = _body_rows(coords)
    ends, near, keys = _ends(p, span)
    nodes = np.flatnonzero(coords.kind == 2)  # line by line, node by node, x y z
    line = coords.line[nodes]
    local = (coords.q[nodes] - np.asarray(p.line_q)[line]) // 3  # the node's place, 0 first
    inside = np.asarray(p.line_n)[line] - 1  # interior nodes of its line
    period = 2 * span + 1
    node_colour = ((np.arange(len(nodes)) // 3) % period) * 3 + coords.axis[nodes]
    parts: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    forces(y)
    arm = forces.w.parm.copy()

    def difference(columns, step):
        dx = np.zeros(n)
        dx[columns] = step
        plus = forces(apply(y, coords, dx))
        loads = forces.w.end_load.copy()
        minus = forces(apply(y, coords, -dx))
        return 0.5 * (plus - minus), 0.5 * (loads - forces.w.end_load)

    for c in range(3 * period if len(nodes) else 0):
        which = np.flatnonzero(node_colour == c)
        columns = nodes[which]
        step = 1e-6 * np.maximum(1.0, np.abs(y[coords.q[columns]]))
        dr, dload = difference(columns, step)
        # the node rows within reach along the same line
        offset = np.repeat(np.arange(-span, span + 1), 3)  # a node's three rows per neighbour
        rows = 3 * (which // 3)[:, None] + (3 * offset + np.tile(np.arange(3), period))[None, :]
        place = local[which][:, None] + offset[None, :]
        ok = (place >= 0) & (place < inside[which][:, None])
        cols = np.broadcast_to(columns[:, None], rows.shape)[ok]
        hits = nodes[rows[ok]]
        parts.append((hits, cols, dr[hits] / np.broadcast_to(step[:, None], rows.shape)[ok]))
        # each line end it moves: that end's load, with its moment, on the end's body
        for k, column, h in zip(which, columns, step, strict=True):
            li = int(line[k])
            for e, distance in ((0, int(local[k])), (1, int(inside[k] - 1 - local[k]))):
                point = int(p.line_from[li] if e == 0 else p.line_to[li])
                b = int(p.point_body[point])
                if distance >= span or b not in rows_of:
                    continue
                df = dload[li, e] / h
                generalized = np.concatenate([df, np.cross(arm[point], df)])
                index, component = rows_of[b]
                parts.append((index, np.full(len(index), column), generalized[component]))
    for group in _groups(rows_of, near, keys):
        for slot in range(6):
            columns = np.array([rows_of[b][0][slot] for b in group if len(rows_of[b][0]) > slot])
            if not len(columns):
                continue
            step = np.where(coords.kind[columns] == 1, 1e-6,
                            1e-6 * np.maximum(1.0, np.abs(y[coords.q[columns]])))  # fmt: skip
            dr, _ = difference(columns, step)
            for column, h in zip(columns, step, strict=True):
                b = int(coords.body[column])
                hits = [rows_of[o][0] for o in {b, *near.get(b, ())} if o in rows_of]
                for li, e, _ in ends.get(b, []):
                    mine = (line == li) & ((local < span) if e == 0 else (local >= inside - span))
                    hits.append(nodes[mine])
                rows = np.unique(np.concatenate(hits))  # a short line on b at both ends
                parts.append((rows, np.full(len(rows), column), dr[rows] / h))
    rows, cols, values = (np.concatenate([part[i] for part in parts]) for i in range(3))
    return sparse.csc_matrix((values, (rows, cols)), shape=(n, n))


def _groups(rows_of, near, keys) -> list[list[int]]:
    """The free bodies in groups whose members move no row in common (greedy): a body moves
    its own forces and its lines' end rows (``keys``), and the forces of the bodies ``near``
    it."""
    moved = {b: {("body", o) for o in {b, *near.get(b, ())}} | keys.get(b, set())
             for b in rows_of}  # fmt: skip
    groups: list[tuple[list[int], set]] = []
    for b in rows_of:
        for members, taken in groups:
            if not moved[b] & taken:
                members.append(b)
                taken |= moved[b]
                break
        else:
            groups.append(([b], set(moved[b])))
    return [members for members, _ in groups]


def bodies_newton(
    p: kernel.SystemParams, coords: Coordinates, y: np.ndarray, limit: np.ndarray,
    iterations: int, tolerance: float, time: float = 0.0, law: int = 0,
) -> np.ndarray | None:  # fmt: skip
    """Newton over the bodies' degrees of freedom, the lines settled at each trial pose
    (``settle_lines``, the axial ``law``: by default the linear one; module docstring; with
    the physical one, kernels.lumped LAW, chain laid slack bends at its touchdown where the
    linear law pushes a segment), until the bodies' accelerations
    are below ``tolerance`` [m/s^2, rad/s^2]. Each step is cut to ``limit`` (per body
    coordinate [m, rad]) and halved until the lines settle (from a step of metres their Newton
    can fail) and the bodies' forces drop. Returns the last state, or None when a segment is
    pushed there (beyond a strain of 1e-8 and PUSH of the largest tension): a balance of the
    linear law that the physical one does not have."""
    p = p._replace(slack_allowed=law)
    forces = BodyForces(p, coords, time)
    bodies = forces.bodies
    nodes = coords.kind == 2

    def settled(state):
        """The lines settled at ``state``'s pose: from its nodes (carried along by the step
        to first order), else line by line from there and from the closed forms'
        shapes (a line lifted from the seabed, or laid on it, in this step); the first
        that settles (1e-5 g) unpushed, else the least pushed."""
        tried: list = []
        for attempt in range(3):
            if attempt == 0:
                out = settle_lines(p, uniform_shapes(p, state, time, slack_only=True),
                                   slack=0, time=time)  # fmt: skip
            else:
                start = tried[0][0] if attempt == 1 else uniform_shapes(p, state, time)
                out = settle_each(p, start, slack=law, time=time)
            r = forces(out)
            result = out, r, forces.body_accelerations(), pushed(p, forces.w, PUSH)
            if np.abs(r[nodes]).max(initial=0.0) < 1e-5 * p.gravity and not result[3]:
                return result
            tried.append(result)
        return min(tried, key=lambda t: (not np.abs(t[1][nodes]).max(initial=0.0)
                                         < 1e-5 * p.gravity, t[3]))  # fmt: skip

    def better(trial, now, plateau):
        """Its lines settled (1e-5 g), not pushed harder than now (``line_balance.pushed``: a step
        that lowers a buoy lays chain on the seabed, straight and pushed, and a pushed chain
        can hold the buoy off), the bodies' forces lower, or no higher on a ``plateau`` (a
        body on lines lying slack, which do not pull harder until they lift)."""
        r_trial, r_now = trial[1], now[1]
        lower = np.linalg.norm(r_trial[bodies]) < np.linalg.norm(r_now[bodies]) * (
            1.0 + 1e-9 if plateau else 1.0)  # fmt: skip
        return (np.all(np.isfinite(r_trial)) and np.abs(r_trial[nodes]).max(initial=0.0)
                < 1e-5 * p.gravity and trial[3] <= now[3] and lower)  # fmt: skip

    y, r, a, compression = settled(y)
    for _ in range(iterations):
        if not np.all(np.isfinite(r)) or np.abs(a).max(initial=0.0) < tolerance:
            break
        step, plateau = _step(jacobian(forces, y), r, bodies, limit)
        if step is None:
            break
        largest = float(np.max(np.abs(step[bodies]) / limit))
        if largest > 1.0:
            step /= largest
        for fraction in (1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125):
            attempt = settled(apply(y, coords, fraction * step))
            if better(attempt, (y, r, a, compression), plateau):
                break
        else:
            break
        y, r, a, compression = attempt
    return None if compression else y


def _step(jac: sparse.csc_matrix, r: np.ndarray, bodies: np.ndarray, limit: np.ndarray):
    """Newton's step; where its matrix is singular or nearly (a step beyond a hundred step
    limits; a body on lines that all lie slack has no
    stiffness until they lift: chain lying slack none across itself), the step of the matrix
    shifted on its diagonal as a step of pseudo-transient continuation is (system.pseudo_time):
    each body coordinate by its force over its step limit, which moves a free body that
    far along its force, each node by 1e-9 of the largest node stiffness. With whether it was
    shifted; None when even that fails."""
    step = sparse_solve(jac, -r)
    if step is not None and np.all(np.abs(step[bodies]) < 100.0 * limit):
        return step, False
    diagonal = np.abs(jac.diagonal())
    shift = np.full(len(r), 1e-9 * max(float(diagonal.max(initial=0.0)), 1e-300))
    shift[bodies] = np.maximum(np.abs(r[bodies]) / limit, 1e-9 * diagonal[bodies])
    return sparse_solve(jac - sparse.diags(shift), -r), True
