"""The fastest motions of a system: the eigenvalues of largest magnitude of its linearised
rates, which limit an explicit step (the rk4 step check, ``numerics.stability``; the statics'
dynamic relaxation, ``system.relax``).

The rates dy/dt = f(t, y) are linearised about a state by central differences along a
direction, J v = (f(y + d v) - f(y - d v)) / (2 d), with d a millionth of the shortest
segment (a perturbation that stays in the linear range of the stiffest segment). The
eigenvalues of J of largest magnitude are those of the dense J for a small system (two
evaluations per state) and ARPACK's (implicitly restarted Arnoldi, from a fixed start: the
same answer on every run) for a large one, from products with J alone. Lumped segments are
linearised with their axial law as if taut (``kernels.lumped.LINEAR``): a slack segment, whose
physical law gives no stiffness, has its axial waves as soon as it tightens (a line started
slack and straight would otherwise show no fast motion at all). They are the whole
system's own, whatever sets them: a lumped segment's axial waves, a rigid segment's zigzag
against its joints and the tension, a stiff tie on a light body, a seabed contact, a drag
that damps a fast motion; at the state given, so that a run's start (a tow at speed, a body
hung on its lines) is measured as it is, not bounded from its parameters.
"""

from typing import NamedTuple

import numpy as np
from scipy.sparse.linalg import ArpackError, ArpackNoConvergence, LinearOperator, eigs

from seacable.kernels import lumped
from seacable.system import kernel
from seacable.system.assemble import BuiltSystem
from seacable.system.coordinates import coordinates

DENSE_UP_TO = 100  # states: up to this, the dense Jacobian (two evaluations per state) is cheaper
COUNT = 8  # eigenvalues kept: every one within a few percent of the largest magnitude
TOLERANCE = 1e-4  # ARPACK's relative accuracy of the eigenvalues (the limit to 1e-4)


class Modes(NamedTuple):
    """The eigenvalues [1/s] of largest magnitude of the linearised rates (complex, largest
    first; empty when the system has no state that moves), and where the fastest one moves
    most (a node, a segment, a body)."""

    values: np.ndarray
    what: str


def fastest_modes(system: BuiltSystem, y: np.ndarray | None = None, time: float = 0.0) -> Modes:
    """The fastest motions of ``system`` about ``y`` (default: its initial state) at ``time``."""
    p = system.params._replace(slack_allowed=lumped.LINEAR)  # slack segments as if taut
    y = system.y0 if y is None else y
    n = len(y)
    if n == 0:
        return Modes(np.zeros(0, dtype=complex), "no state")
    w = kernel.make_work(p)
    up, down = np.empty(n), np.empty(n)
    lengths = np.concatenate(
        [p.seg_length[: int(p.line_n.sum())], p.rs_length[: int(p.rs_n.sum())]]
    )
    delta = 1e-6 * (float(lengths.min()) if lengths.size else 1.0)

    def product(v: np.ndarray) -> np.ndarray:
        v = np.asarray(v).real.ravel()
        size = float(np.abs(v).max())
        if size == 0.0:
            return np.zeros(n)
        d = delta / size
        kernel.rhs(time, y + d * v, p, w, up)
        kernel.rhs(time, y - d * v, p, w, down)
        return (up - down) / (2.0 * d)

    if n <= DENSE_UP_TO:
        jacobian = np.column_stack([product(e) for e in np.eye(n)])
        if not np.all(np.isfinite(jacobian)):
            return Modes(np.zeros(0, dtype=complex), "no finite linearisation")
        values, vectors = np.linalg.eig(jacobian)
    else:
        values, vectors = _arnoldi(LinearOperator((n, n), matvec=product, dtype=float), n)
    order = np.argsort(-np.abs(values))[:COUNT]
    values, vectors = values[order], vectors[:, order]
    if not values.size or np.abs(values[0]) == 0.0:
        return Modes(values, "no motion")
    return Modes(values, _where(system, np.abs(vectors[:, 0])))


def _arnoldi(operator: LinearOperator, n: int) -> tuple[np.ndarray, np.ndarray]:
    """ARPACK's eigenvalues of largest magnitude (to TOLERANCE), from a fixed start; those it
    settled when it stops short."""
    start = 1.0 + 0.5 * np.sin(np.arange(n))  # every component, no symmetry: reproducible
    try:
        return eigs(operator, k=COUNT, which="LM", v0=start, tol=TOLERANCE, maxiter=50 * n // COUNT)
    except ArpackNoConvergence as e:
        return e.eigenvalues, e.eigenvectors
    except ArpackError:
        return np.zeros(0, dtype=complex), np.zeros((n, 0), dtype=complex)


def _where(system: BuiltSystem, amplitude: np.ndarray) -> str:
    """The part of the system whose velocity moves most in a mode of state amplitudes
    ``amplitude``: a node or a segment of a line, a body, or a force model's state."""
    p = system.params
    coords = coordinates(p)
    forces = amplitude[p.n_q + p.n_v :]
    if not len(coords.kind) or (forces.size and forces.max() >= amplitude[: p.n_q + p.n_v].max()):
        return "a force model's state (a servo's force, a radiation state space's)"
    width = np.where(coords.kind == 3, 3, np.where(coords.kind == 7, 2, 1))
    size = amplitude[coords.v].copy()
    for k in (1, 2):  # a director's three rates, a string tangent's two
        wide = width > k
        size[wide] = np.maximum(size[wide], amplitude[coords.v[wide] + k])
    j = int(np.argmax(size))
    line, kind = int(coords.line[j]), int(coords.kind[j])
    if coords.body[j] >= 0:
        return f"body '{system.case.bodies[int(coords.body[j])].name}'"
    if kind == 2:
        node = (int(coords.q[j]) - int(p.line_q[line])) // 3 + 1
        return f"node {node} of line '{system.layout.lines[line]}'"
    if kind in (3, 4):
        segment = (int(coords.q[j]) - int(p.rs_q[line])) // (3 if kind == 3 else 1)
        return f"segment {segment} of line '{system.layout.rigid[line]}'"
    return f"line '{system.layout.natural[line]}'"


def fastest_frequency(
    system: BuiltSystem, y: np.ndarray | None = None, time: float = 0.0
) -> tuple[float, str]:
    """The magnitude [rad/s] of the fastest motion about ``y`` (default: the initial state),
    and where it moves most (1 rad/s when nothing moves)."""
    modes = fastest_modes(system, y, time)
    if not modes.values.size or np.abs(modes.values[0]) == 0.0:
        return 1.0, modes.what
    return float(np.abs(modes.values[0])), modes.what
