"""The natural periods of a system with vessels (``seacable modes``, ``analysis.system_modes``):
the linearisation about the static equilibrium, told apart into how each period is found.

- ``linearised``: an eigenvalue of the linearised rates (positions, velocities and the force
  models' states other than radiation memory), the added mass as the case gives it (A_inf for a
  body whose added mass comes from its hydrodynamic database).
- ``A(w) iterated``: a mode that a body with a hydrodynamic database moves most, whose added
  mass A(w) and radiation damping B(w) depend on the frequency: w is iterated until it is the
  natural frequency of (M + A(w)) x'' + C x = 0 (the undamped eigenproblem at A(w), the mode
  followed by its shape), w_{k+1} = w(A(w_k)); its damping ratio is the eigenvalue's at A(w),
  B(w) with the rest of the linearised damping. A(w) and B(w) are interpolated linearly in w
  and held at the database's ends beyond them (reported).
- ``memory pole``: a pole of the radiation memory's state space (``method: state_space``), the
  eigenvalues of the fitted retardation functions' own matrices: not a motion of the vessel.
  (A convolution adds no state: its memory is empty at rest and adds nothing to the
  linearisation.)
- ``free (no restoring)``: a degree of freedom of a floating body that nothing holds (no line,
  tie or spring to a held body): surge, sway and yaw have no restoring, zero frequency. Its
  equilibrium is found in heave, roll and pitch only, then every degree of freedom is
  linearised about it (a pitch mode then has surge free, as at sea).
"""

import logging
import math
from dataclasses import dataclass

import numpy as np

from seacable.case import loader
from seacable.case import system as sch
from seacable.forces import radiation
from seacable.forces.kinds import RADIATION_DAMPING
from seacable.system import hulls, kernel, topology
from seacable.system import model as system_model
from seacable.system.assemble import BuiltSystem
from seacable.system.coordinates import Coordinates

log = logging.getLogger(__name__)

LINEARISED, ITERATED, MEMORY_POLE, FREE = (
    "linearised", "A(w) iterated", "memory pole", "free (no restoring)"
)  # fmt: skip
SETTLED = 1e-10  # relative change of w at which its iteration stops
ITERATIONS = 200
OSCILLATES = 1e-9  # |Im lambda| above this part of |lambda| (at least 1e-9 rad/s): a mode
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


@dataclass(frozen=True)
class Equilibrium:
    """The system to linearise, its state at rest in balance, and the degrees of freedom
    (body name, dof) that have no restoring."""

    built: BuiltSystem
    y: np.ndarray
    free: list[tuple[str, str]]


def equilibrium(case: sch.SystemCase) -> Equilibrium:
    """The static equilibrium of ``case``; a floating body in a group that nothing holds
    (``system.topology.unheld``) balanced in heave, roll and pitch only (its other degrees of
    freedom held where the case puts it), then built with all its degrees of freedom."""
    derived = loader.derive_case(case, {"start": "static"})
    assert isinstance(derived, sch.SystemCase)  # derive_case keeps the form
    base = loader.case_base_dir(derived)
    settings, free = _waterplane_only(derived)
    if not settings:
        built = system_model.build(derived, base)
        y = built.y0.copy()
    else:
        held = system_model.build(loader.with_settings(derived, settings), base)
        whole = loader.derive_case(case, {"start": "as_given"})
        assert isinstance(whole, sch.SystemCase)
        built = system_model.build(whole, base)
        y = held.y0.copy()  # the same layout: a body's pose has its 7 (3) places whatever moves
    y[built.params.n_q :] = 0.0
    return Equilibrium(built, y, free)


def _waterplane_only(case: sch.SystemCase) -> tuple[list[str], list[tuple[str, str]]]:
    """The settings that keep each floating body of a group nothing holds to heave, roll and
    pitch, and the degrees of freedom they take away."""
    by_name = {body.name: body for body in case.bodies}
    settings: list[str] = []
    free: list[tuple[str, str]] = []
    for group in topology.unheld(case):
        for name in group:
            body = by_name[name]
            if not isinstance(body, sch.RigidBody | sch.PointBody) or not topology.floats(body):
                continue
            kept = [d for d in body.dofs if d in topology.WATERPLANE_DOFS]
            dropped = [d for d in body.dofs if d not in topology.WATERPLANE_DOFS]
            if dropped:
                settings.append(f"bodies.{name}.dofs=[{', '.join(kept)}]")
                free += [(name, str(d)) for d in dropped]
    return settings, free


@dataclass(frozen=True)
class Database:
    """A body whose added mass is its database's: A(w) - A_inf and B(w) at the database's
    frequencies [rad/s], reference point, body frame."""

    index: int
    name: str
    omega: np.ndarray
    added: np.ndarray  # (n, 6, 6) A(w) - A_inf [kg, kg m, kg m^2]
    damping: np.ndarray  # (n, 6, 6) B(w) [N s/m, N s, N m s]

    def at(self, w: float) -> tuple[np.ndarray, np.ndarray]:
        """A(w) - A_inf and B(w), linear in w, held at the database's ends."""
        k = int(np.clip(np.searchsorted(self.omega, w), 1, len(self.omega) - 1))
        share = float(np.clip((w - self.omega[k - 1]) / (self.omega[k] - self.omega[k - 1]), 0, 1))
        added, damping = ((1 - share) * v[k - 1] + share * v[k] for v in (self.added, self.damping))
        return added, damping


def databases(built: BuiltSystem) -> list[Database]:
    """The bodies whose added mass is their database's A_inf (no added_mass of their own, no
    ship-simulator dynamics block), alone in their solve (no rigid line or joint holding them
    to another free body), with at least two frequencies."""
    case, p = built.case, built.params
    base = loader.case_base_dir(case)
    out = []
    for b, body in enumerate(case.bodies):
        if not isinstance(body, sch.RigidBody) or body.hydrodynamics is None:
            continue
        if body.dynamics is not None or np.any(body.added_mass) or p.body_group[b, 0] >= 0:
            continue
        where = f"bodies[{b}] ({body.name})"
        db = hulls.body_database(body, base, where, case.environment)
        if len(db.omega) < 2:
            continue
        infinite = hulls.database_added_mass(body, base, where, case.environment)
        out.append(Database(b, body.name, db.omega, db.added_mass - infinite, db.damping))
    return out


def memory_states(p: kernel.SystemParams) -> dict[int, np.ndarray]:
    """{body: its radiation memory's state-space states (force models' states, 0 the first)}."""
    first = int(p.n_q + p.n_v)  # force_state: the place in y
    found: dict[int, np.ndarray] = {}
    for f in range(len(p.force_kind)):
        if p.force_kind[f] == RADIATION_DAMPING and p.force_state[f] >= 0:
            count = radiation.state_count(p.force_data[p.force_at[f] :])
            states = int(p.force_state[f]) - first + np.arange(count)
            body = int(p.force_body[f])
            found[body] = np.concatenate([found.get(body, np.zeros(0, np.int64)), states])
    return found


@dataclass(frozen=True)
class Modes:
    """The modes found, slowest first within each kind: ``value`` the eigenvalue lambda [1/s]
    (complex; for ``A(w) iterated`` the damped one at A(w), B(w); 0 for ``free``), ``natural``
    [rad/s] the frequency the period is of (|Im lambda|, the iterated w, or 0), ``shape`` the
    position part (coordinates), ``method`` how each was found, ``label`` what moves (a
    coordinate index, or -1 with the name in ``named``)."""

    value: np.ndarray
    natural: np.ndarray
    shape: np.ndarray
    method: list[str]
    coordinate: np.ndarray
    named: list[str]


def find(state: Equilibrium, a: np.ndarray, coords: Coordinates, weight: np.ndarray,
         count: int) -> Modes:  # fmt: skip
    """The ``count`` slowest modes of the linearisation ``a`` (``system.statics.jacobian``
    about ``state``), each by the method that fits it (module note), then the free degrees of
    freedom, then the ``count`` slowest memory poles. ``weight``: each coordinate's square
    root of mass or inertia [kg^0.5, kg^0.5 m], which ranks what a mode moves most."""
    n = len(coords.kind)
    owned = {b: 2 * n + states for b, states in memory_states(state.built.params).items()}
    memory = np.concatenate([np.zeros(0, np.int64), *owned.values()])
    mechanical = np.delete(np.delete(a, memory, axis=0), memory, axis=1)
    _no_restoring(state, mechanical, coords)
    values, vectors = np.linalg.eig(mechanical)
    keep = np.flatnonzero(_oscillates(values))
    order = keep[np.argsort(np.abs(values[keep].imag))]
    values, shapes = values[order], vectors[:n, order].T
    natural = np.abs(values.imag)
    method = [LINEARISED] * len(values)
    bodies = databases(state.built)
    if bodies:
        owner = np.array([coords.body[np.argmax(np.abs(s) * weight)] for s in shapes])
        wanted = [k for k in range(len(values)) if owner[k] in {d.index for d in bodies}]
        frequency = _Frequency(state, mechanical, coords, bodies, weight)
        for k in wanted:
            values[k], natural[k], shapes[k] = frequency.iterate(
                float(np.abs(values[k])), shapes[k]
            )
            method[k] = ITERATED
        order = np.argsort(natural)
        values, natural, shapes = values[order], natural[order], shapes[order]
        method = [method[k] for k in order]
    values, natural, shapes, method = (
        values[:count],
        natural[:count],
        shapes[:count],
        method[:count],
    )
    if len(shapes):  # the largest component 1: the real part is the mode's shape
        shapes = shapes / shapes[np.arange(len(shapes)), np.argmax(np.abs(shapes), axis=1)][:, None]
    coordinate = [int(np.argmax(np.abs(s.real) * weight)) for s in shapes]
    named = [""] * len(values)
    poles = _memory_poles(state, a, owned, count)
    for body, dof in state.free:
        values, natural = np.append(values, 0.0), np.append(natural, 0.0)
        shapes = np.vstack([shapes, np.zeros((1, n))])
        method, coordinate, named = method + [FREE], coordinate + [-1], named + [f"{body}:{dof}"]
    for value, name in poles:
        values, natural = np.append(values, value), np.append(natural, abs(value.imag))
        shapes = np.vstack([shapes, np.zeros((1, n))])
        method, coordinate, named = method + [MEMORY_POLE], coordinate + [-1], named + [name]
    return Modes(values, natural, shapes, method, np.array(coordinate, dtype=np.int64), named)


def _oscillates(values: np.ndarray) -> np.ndarray:
    return values.imag > OSCILLATES * np.maximum(1.0, np.abs(values))


def _no_restoring(state: Equilibrium, mechanical: np.ndarray, coords: Coordinates) -> None:
    """Zero the position columns of the free degrees of freedom of a floating body alone in
    its group (no line or tie to another): gravity and still-water buoyancy do not change
    when it moves horizontally or turns about the vertical (its finite differences would
    leave noise, a mode of hours)."""
    case = state.built.case
    n = len(coords.kind)
    names = [body.name for body in case.bodies]
    alone = {group[0] for group in topology.groups(case) if len(group) == 1}
    alone -= {ref.partition(".")[0] for line in case.lines for ref in (line.from_, line.to)}
    for body, dof in state.free:
        if body not in alone:
            continue
        c = DOFS.index(dof)
        at = np.flatnonzero((coords.body == names.index(body)) & (coords.kind == c // 3)
                            & (coords.axis == c % 3))  # fmt: skip
        mechanical[n : 2 * n, at] = 0.0


def _memory_poles(state: Equilibrium, a: np.ndarray, owned: dict[int, np.ndarray],
                  count: int) -> list[tuple[complex, str]]:  # fmt: skip
    """The ``count`` slowest oscillatory poles of the radiation memories' state spaces (each
    body's block of their own rates in the linearisation ``a``), with the body's name."""
    found = []
    for b, states in owned.items():
        values = np.linalg.eigvals(a[np.ix_(states, states)])
        name = f"{state.built.case.bodies[b].name}:radiation memory"
        found += [(complex(v), name) for v in values[_oscillates(values)]]
    return sorted(found, key=lambda pole: abs(pole[0].imag))[:count]


class _Frequency:
    """The linearisation at the added mass A(w) and the radiation damping B(w) of the
    database bodies, from the one at A_inf: their rows of the rates, M^-1 (forces), become
    (M + A(w) - A_inf)^-1 (M (rows) - B(w) v) (their free degrees of freedom's block; the
    mass matrices the compiled kernel's, lines' end nodes included)."""

    def __init__(self, state: Equilibrium, mechanical, coords, bodies, weight) -> None:
        self.state, self.mechanical, self.coords, self.bodies = state, mechanical, coords, bodies
        self.weight = weight
        self.n = len(coords.kind)
        self.mass, self.rot = self._masses(0.0)
        self.rows = {}
        for d in bodies:
            rows = np.flatnonzero((coords.body == d.index) & (coords.kind <= 1))
            self.rows[d.index] = (rows, np.where(coords.kind[rows] == 0, 0, 3) + coords.axis[rows])

    def _masses(self, w: float) -> tuple[np.ndarray, np.ndarray]:
        """Every body's 6x6 mass matrix (earth frame, reference point) with A(w), and R."""
        p = self.state.built.params
        added = p.body_added.copy()
        for d in self.bodies:
            added[d.index] += d.at(w)[0] if w > 0.0 else 0.0
        p = p._replace(body_added=added)
        work = kernel.make_work(p)
        kernel.rhs(0.0, self.state.y, p, work, np.empty(len(self.state.y)))
        return work.mass.copy(), work.rot.copy()

    def matrix(self, w: float) -> np.ndarray:
        """The linearised rates (positions, velocities, other states) at A(w), B(w)."""
        n, out = self.n, self.mechanical.copy()
        mass, _ = self._masses(w)
        for d in self.bodies:
            rows, dof = self.rows[d.index]
            turn = np.kron(np.eye(2), self.rot[d.index])
            damping = (turn @ d.at(w)[1] @ turn.T)[np.ix_(dof, dof)]
            at_w, at_inf = mass[d.index][np.ix_(dof, dof)], self.mass[d.index][np.ix_(dof, dof)]
            out[n + rows, :] = np.linalg.solve(at_w, at_inf @ self.mechanical[n + rows, :])
            out[np.ix_(n + rows, n + rows)] -= np.linalg.solve(at_w, damping)
        return out

    def iterate(self, w: float, shape: np.ndarray) -> tuple[complex, float, np.ndarray]:
        """The mode of shape near ``shape`` at A(w) with w its own undamped natural frequency
        (from ``w``): its damped eigenvalue, w, its shape."""
        n = self.n
        for _ in range(ITERATIONS):
            values, vectors = np.linalg.eig(self.matrix(w)[n : 2 * n, :n])
            k = self._closest(vectors, shape, values.real < 0.0)
            settled, w, shape = w, math.sqrt(-values[k].real), vectors[:, k]
            if abs(w - settled) <= SETTLED * w:
                break
        else:
            log.warning("a mode's frequency did not settle at A(w): %.6g then %.6g rad/s",
                        settled, w)  # fmt: skip
        for d in self.bodies:
            if not d.omega[0] <= w <= d.omega[-1]:
                log.warning(
                    "body '%s': a mode at %.4g rad/s (%.4g s), outside its database's %.4g to "
                    "%.4g rad/s; its A(w) and B(w) held at the nearest end",
                    d.name, w, 2 * math.pi / w, *d.omega[[0, -1]],
                )  # fmt: skip
        values, vectors = np.linalg.eig(self.matrix(w))
        k = self._closest(vectors[:n], shape, _oscillates(values))
        return complex(values[k]), w, shape

    def _closest(self, vectors: np.ndarray, shape: np.ndarray, allowed: np.ndarray) -> int:
        """The column of ``vectors`` most like ``shape`` (modal assurance criterion, each
        coordinate weighted by its mass or inertia) among those ``allowed``."""
        weighted = vectors * self.weight[:, None]
        target = shape * self.weight
        match = np.abs(target.conj() @ weighted) ** 2 / (
            np.sum(np.abs(weighted) ** 2, axis=0) * np.sum(np.abs(target) ** 2)
        )
        return int(np.argmax(np.where(allowed, match, -1.0)))
