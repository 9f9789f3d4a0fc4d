"""What the fixed-step implicit schemes of ``numerics.system_implicit`` need besides the
system's parameters, prepared in Python once a run: a scheme's coefficients (``scheme``), the
pairing of velocities with the positions they move and the unknowns' scales (``increments``),
Newton's matrix's layout (``layout``, ``newton``), the parameters its residuals and its matrix
are evaluated with (``lagged``, ``frozen``), the arrays carried from step to step
(``carry``) and the acceleration a run starts from (``initial_acceleration``)."""

from typing import NamedTuple

import numpy as np

from seacable.bodies import kinematics
from seacable.kernels import lumped
from seacable.numerics import bordered, lumped_newton, rigid_newton
from seacable.system import coordinates, model, rigid
from seacable.system import kernel as system_kernel

# coefficient vector layout: pa, b, g, am, af
SCHEME_SIZE = 5


def scheme(name: str, theta=0.5, gamma=0.5, beta=0.25, spectral_radius=0.8) -> np.ndarray:
    """The coefficients (pa, b, g, am, af) of a named scheme (see the module docstring)."""
    if name == "implicit_euler":
        return np.array([0.0, 1.0, 1.0, 0.0, 0.0])
    if name == "theta":
        return np.array([theta * (1.0 - theta), theta * theta, theta, 0.0, 0.0])
    if name == "newmark":
        return np.array([0.5 - beta, beta, gamma, 0.0, 0.0])
    if name == "generalized_alpha":
        r = spectral_radius
        am = (2.0 * r - 1.0) / (r + 1.0)
        af = r / (r + 1.0)
        b = 0.25 * (1.0 - am + af) ** 2
        return np.array([0.5 - b, b, 0.5 - am + af, am, af])
    raise ValueError(f"unknown implicit scheme {name!r}")


class Increments(NamedTuple):
    """How the velocity variables move the positions, and the scales of every unknown (the
    accelerations of the n_v velocity variables, then the rates of the n_s force-model
    states)."""

    q_of_v: np.ndarray  # (n_v,) int: the position a velocity moves additively (-1: a rotation)
    quat_q: np.ndarray  # (k,) int: first quaternion entry of each rigid body in y
    quat_v: np.ndarray  # (k,) int: first angular-velocity entry, relative to V's start
    scale: np.ndarray  # (n_v + n_s,) typical size of each position or state (differences)
    weight: np.ndarray  # (n_v + n_s,) metres per unit of each position, or per state's scale


def increments(case, system: model.BuiltSystem) -> Increments:
    """The pairing of every velocity variable with the position it moves (the bodies' first,
    then, in order, every other variable, one for one), each rigid body's quaternion, and the
    scales of the difference quotients and of the convergence test."""
    p = system.params
    nq, nv = int(p.n_q), int(p.n_v)
    q_of_v = np.full(nv, -1, dtype=np.int64)
    used_q = np.zeros(nq, dtype=bool)
    quat_q: list[int] = []
    quat_v: list[int] = []
    weight = np.ones(nv)
    radius = np.ones(len(p.body_kind))
    for i, b in enumerate(p.point_body):
        radius[b] = max(radius[b], float(np.linalg.norm(p.point_offset[i])))
    for b in np.flatnonzero(p.body_kind == kinematics.DYNAMIC):
        q, v = int(p.body_q[b]), int(p.body_v[b]) - nq
        q_of_v[v : v + 3] = np.arange(q, q + 3)
        used_q[q : q + 3] = True
        if p.body_rigid[b]:
            quat_q.append(q + 3)
            quat_v.append(v + 3)
            used_q[q + 3 : q + 7] = True
            weight[v + 3 : v + 6] = radius[b]
    free_v = np.flatnonzero(q_of_v < 0)
    free_v = np.setdiff1d(free_v, [v + c for v in quat_v for c in range(3)])
    free_q = np.flatnonzero(~used_q)
    if len(free_v) != len(free_q):
        raise AssertionError("the system's positions and velocities do not pair")
    q_of_v[free_v] = free_q
    for li in range(len(p.rs_n)):
        per = 1 if p.rs_kind[li] == rigid.PLANAR else 3
        n, seg, v = int(p.rs_n[li]), int(p.rs_seg[li]), int(p.rs_v[li]) - nq
        weight[v : v + per * n] = np.repeat(p.rs_length[seg : seg + n], per)
    for li in range(len(p.nat_n)):
        size = (3 if p.nat_cartesian[li] else 2) * (int(p.nat_n[li]) + 1)
        v = int(p.nat_v[li]) - nq
        weight[v : v + size] = p.nat_length[li] / p.nat_n[li]
    sizes = model.state_scale(case, system)
    scale = np.where(q_of_v >= 0, sizes[:nq][np.maximum(q_of_v, 0)], 1.0)
    states = sizes[nq + nv :]  # a force model's state: its start's size, at least 1 (N)
    return Increments(
        q_of_v=q_of_v, quat_q=np.array(quat_q, dtype=np.int64),
        quat_v=np.array(quat_v, dtype=np.int64), scale=np.concatenate([scale, states]),
        weight=np.concatenate([weight, 1.0 / states]),
    )  # fmt: skip


def layout(
    system: model.BuiltSystem, inc: Increments, maximal: bool = True, written: bool = True
) -> tuple[bordered.Bordered, rigid_newton.RigidRows]:
    """Newton's matrix over the accelerations: the pattern of d(accelerations)/d(positions,
    velocities) folded onto the velocity variables (a position's column onto the velocity that
    moves it, ``inc``; a quaternion's onto its body's three angular velocities), the bodies'
    as the border; the rigid lines ``rigid_newton.eligible`` picks (and that couple to
    nothing else) written in maximal coordinates instead, with their auxiliary unknowns after
    the velocity variables (``rigid_newton.layout``; ``maximal=False``: none, every rigid
    line's block dense, as before; benchmarks/implicit_cost.py compares the two); the lumped
    lines' columns ``lumped_newton.eligible`` picks written from their laws (``written=False``:
    none, every column by differences). The force models' states follow the velocity
    variables, each solved for its rate."""
    p = system.params
    nq, nv = int(p.n_q), int(p.n_v) + int(p.n_s)
    full = model.jacobian_sparsity(system).tocsr()[nq : nq + nv].tocoo()
    rows, cols = [full.row[full.col >= nq]], [full.col[full.col >= nq] - nq]
    moved_by = np.full(nq, -1, dtype=np.int64)  # the velocity that moves each position
    paired = np.flatnonzero(inc.q_of_v >= 0)
    moved_by[inc.q_of_v[paired]] = paired
    turned_by = np.full(nq, -1, dtype=np.int64)  # a quaternion entry's first angular velocity
    for q, v in zip(inc.quat_q, inc.quat_v, strict=True):
        turned_by[q : q + 4] = v
    row, col = full.row[full.col < nq], full.col[full.col < nq]
    direct = moved_by[col] >= 0
    rows.append(row[direct])
    cols.append(moved_by[col[direct]])
    turn = turned_by[col] >= 0
    rows.append(np.repeat(row[turn], 3))
    cols.append((turned_by[col[turn]][:, None] + np.arange(3)[None, :]).ravel())
    row, col = np.concatenate(rows), np.concatenate(cols)
    pattern = coordinates.sparse.csr_matrix((np.ones(len(row)), (row, col)), shape=(nv, nv))
    pattern = pattern + coordinates.sparse.identity(nv, format="csr")  # coloured with it
    body_v = np.zeros(nv, dtype=bool)
    for b in np.flatnonzero(p.body_kind == kinematics.DYNAMIC):
        v = int(p.body_v[b]) - nq
        body_v[v : v + (6 if p.body_rigid[b] else 3)] = True
    pattern = pattern.tocoo()
    if written:
        lumped = lumped_newton.eligible(p, pattern)
    else:
        lumped = (np.zeros(0, dtype=np.int64), np.zeros(nv, dtype=np.int64))
    return rigid_newton.layout(p, pattern, body_v, maximal, lumped, lumped_newton.unknowns(p, nv))


def newton(
    case, system: model.BuiltSystem, maximal: bool = True, written: bool = True
) -> tuple[Increments, bordered.Bordered, rigid_newton.RigidRows]:
    """What a system's implicit steps need besides its parameters (``rows.geo`` is carried
    from step to step with the kept factors: the geometry their right-hand side needs;
    ``maximal``, ``written``: see ``layout``)."""
    inc = increments(case, system)
    return (inc, *layout(system, inc, maximal, written))


def frozen(p):
    """The parameters Newton's matrix is built with: a lumped line's laws on the branches
    (slack or taut segment, seabed contact or not) of the residual they are taken at
    (kernels.lumped FROZEN), so that no difference quotient straddles a kink. Forward
    differences across a kink gave a slack segment its taut stiffness: on a slack string of EA
    1e7 N released at rest (benchmarks/string_pendulum.py) the iteration then crept (each
    correction 0.9998 times the one before) and every step failed."""
    return p._replace(slack_allowed=lumped.FROZEN) if p.slack_allowed == lumped.LAW else p


def lagged(p):
    """The parameters a step's residuals are evaluated with: the physical laws, a lumped
    segment's water kinematics reused within the step while its wetted centroid moves less
    than kernels.lumped.REUSE / k_max from where they were evaluated at that time
    (kernels.lumped LAGGED): Newton's iterates move the nodes by fractions of a millimetre,
    and a fresh sum over every wave component at every segment was most of a residual's cost
    (benchmarks/vessel_cost.py)."""
    return p._replace(slack_allowed=lumped.LAGGED) if p.slack_allowed == lumped.LAW else p


def carry(system: model.BuiltSystem, lay: bordered.Bordered):
    """The arrays a run carries from step to step (``numerics.contract.ChunkIntegrator``, point
    5): [a1, the last step's change of acceleration, the forces at its end], [factors valid,
    their step length, the step length of that change, whether those forces are the current
    state's, the largest local tension error estimated so far and the largest tension
    (``system_implicit._estimate``)], the factors and their row swaps, the matrix before its
    factorisation and the seabed terms it holds for each lumped node
    (``system_implicit._seabed_terms``)."""
    nv = int(system.params.n_v) + int(system.params.n_s)
    return (
        np.zeros((3, nv)), np.zeros(6), np.zeros(lay.size),
        np.zeros(lay.order.shape[0], dtype=np.int64), np.zeros(lay.size),
        np.zeros((9, system.params.node_mass.shape[0])),
    )  # fmt: skip


def initial_acceleration(t, y, p, w, acc):
    """The system's accelerations at (t, y): the a0 a run starts from. Returns the status. From
    Python: a compiled wrapper would hold a second copy of the right-hand side's code
    (docs/architecture.md, "Compile time")."""
    ydot = np.empty_like(y)
    status = system_kernel.rhs(t, y, p, w, ydot)
    acc[:] = ydot[p.n_q : p.n_q + acc.shape[0]]
    return status
