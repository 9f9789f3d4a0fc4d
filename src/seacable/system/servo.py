"""The trajectory servo of a system (``model: servo``, ``forces.servo``): its stiffness K from
static equilibria, its start, and the stability of its closed loop.

K (Jacquot & Marichal 1993, section 4): the body is held, in turn, at the target and at 14
points on a sphere of ``sphere_radius`` around it (the axes and the diagonals), every other
servo's body at its own target, every other body as the case has it and every kinematic body
in its steady motion (``statics.equilibrium``); the holding forces against the displacements
give K by least squares. In those equilibria the body is an imposed body at the held point,
moving with the target's reference body (the target's ``relative_to``) so that the steady
motion exists. The servo acts on a bare line end (``check_body``: no mass, no other force
model), so the holding force is minus the force of its lines; the start is the equilibrium with
every servo's body at its target and its force F0 that holding force.

The closed loop, linearised about the start, is dy/dt = (J0 + (a/dt) G + b H) y (the law is
linear in a/dt and b): ``ServoLoop`` gives its growth rate; a gain and step whose error would
grow by more than e over the run are refused (``check``)."""

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.sparse.linalg import splu

from seacable.case import system as sch
from seacable.case.forces import ServoForce
from seacable.errors import CaseError
from seacable.forces import servo
from seacable.forces.kinds import SERVO
from seacable.system import assemble, coordinates, kernel, statics
from seacable.system.assemble import BuiltSystem
from seacable.system.initial import initial_state
from seacable.system.line_balance import static_lines

GAIN_LIMIT = 2.0  # the schema's largest gain a
TOLERANCE = 1e-13  # of the equilibria: K is a difference of holding forces 1e4 times larger


def sphere_directions() -> np.ndarray:
    """The 14 unit directions the end is moved along to measure its stiffness: the six axis
    directions and the eight diagonals."""
    directions = [np.eye(3)[k] * sign for k in range(3) for sign in (1.0, -1.0)]
    directions += [np.array([a, b, c]) / math.sqrt(3.0)
                   for a in (1, -1) for b in (1, -1) for c in (1, -1)]  # fmt: skip
    return np.array(directions)


@dataclass(frozen=True)
class ServoLoop:
    """The linearised closed loop of a servo: ``J0``, ``G`` (per unit a/dt [1/s]) and ``H``
    (per unit b), all (ny, ny)."""

    J0: np.ndarray
    G: np.ndarray
    H: np.ndarray

    def growth_rate(self, gain: float, rate_gain: float, step: float) -> float:
        """Largest real part [1/s] of the loop's eigenvalues with gain a, rate gain b and servo
        step dt [s]."""
        jacobian = self.J0 + (gain / step) * self.G + rate_gain * self.H
        return float(np.max(np.linalg.eigvals(jacobian).real))

    def sampled_growth_rate(self, gain: float, rate_gain: float, step: float) -> float:
        """The same [1/s] for the law as the paper writes it, a correction once per servo step
        (the force held in between): y -> (I + a G + b dt H) expm(J0 dt) y per step, the growth
        rate ln(largest |eigenvalue|) / dt."""
        from scipy.linalg import expm  # here: its import is slow (docs/architecture.md)

        size = self.J0.shape[0]
        jump = np.eye(size) + gain * self.G + rate_gain * step * self.H
        largest = np.max(np.abs(np.linalg.eigvals(jump @ expm(self.J0 * step))))
        return float(np.log(largest) / step)

    def largest_stable_gain(self, rate_gain: float, step: float, growth: float) -> float:
        """The largest gain a <= 2 whose growth rate stays at or below ``growth`` [1/s]
        (bisection; 0 if none)."""
        if self.growth_rate(GAIN_LIMIT, rate_gain, step) <= growth:
            return GAIN_LIMIT
        low, high = 0.0, GAIN_LIMIT
        for _ in range(20):
            middle = 0.5 * (low + high)
            if self.growth_rate(middle, rate_gain, step) <= growth:
                low = middle
            else:
                high = middle
        return low


def servos(built: BuiltSystem) -> list[tuple[int, int, ServoForce]]:
    """Every servo: (its force row f, its body b, its spec)."""
    p = built.params
    rows = [f for f in range(len(p.force_kind)) if p.force_kind[f] == SERVO]
    specs = [(b, spec) for b, body in enumerate(built.case.bodies)
             for spec in getattr(body, "external_forces", []) if spec.model == "servo"]  # fmt: skip
    return [(f, b, spec) for f, (b, spec) in zip(rows, specs, strict=True)]


def check_body(case: sch.SystemCase) -> None:
    """Refuse a servo whose body is not a bare cable end: a point body of no mass whose only
    force model is the servo (the vehicle's motion is its target's; the servo sets the force
    it applies to the line's end)."""
    for b, body in enumerate(case.bodies):
        models = [spec.model for spec in getattr(body, "external_forces", [])]
        if "servo" not in models:
            continue
        where = f"bodies[{b}] ({body.name})"
        if not isinstance(body, sch.PointBody) or body.mass or models != ["servo"]:
            raise CaseError(
                f"{where}: a servo acts on a line's bare end: a point body with mass 0 and the "
                f"servo as its only force model (it has type '{body.type}', mass "
                f"{getattr(body, 'mass', 0.0):g} kg and force models {models}); give the "
                "vehicle's path to an imposed body named as the servo's target"
            )


def start(built: BuiltSystem, y: np.ndarray):
    """At t = 0: the parameters with every servo's K, and the state with every servo's body
    held at its target, its force F0 the one that holds it there, everything else in balance
    (the static start of a system with servos; with ``start: as_given`` only F0 is taken)."""
    p = built.params
    held, solved, forces, targets = _equilibria(built, y, 0.0)
    for f, b, spec in servos(built):
        p = with_stiffness(p, f, _stiffness(held, solved, forces, targets, b, spec, 0.0))
    out = _restored(built, held, solved)
    for f, b, _ in servos(built):
        out[p.force_state[f] : p.force_state[f] + 3] = forces[b]
    return p, out


def refresh(built: BuiltSystem, p: kernel.SystemParams, time: float, y: np.ndarray):
    """The parameters with K recomputed about the current targets at ``time``, for the servos
    that ask (``recompute_interval``)."""
    asked = [(f, b, spec) for f, b, spec in servos(built) if spec.recompute_interval is not None]
    if asked:
        held, solved, forces, targets = _equilibria(built, y, time)
        for f, b, spec in asked:
            p = with_stiffness(p, f, _stiffness(held, solved, forces, targets, b, spec, time))
    return p


def refresh_interval(case: sch.SystemCase) -> float | None:
    """How often [s] the servos' K is recomputed (the shortest asked; None: never)."""
    asked = [spec.recompute_interval for body in case.bodies
             for spec in getattr(body, "external_forces", [])
             if spec.model == "servo" and spec.recompute_interval is not None]  # fmt: skip
    return min(asked) if asked else None


def with_stiffness(p: kernel.SystemParams, f: int, k: np.ndarray) -> kernel.SystemParams:
    data = p.force_data.copy()
    data[p.force_at[f] : p.force_at[f] + 9] = np.asarray(k, float).ravel()
    return p._replace(force_data=data)


def _targets(built: BuiltSystem, y: np.ndarray, time: float) -> dict[int, tuple]:
    """Per servo body: its target at ``time`` as (offset, reference body): from the reference
    point of the body the target moves with (its ``relative_to``, or itself when imposed), in
    earth axes; absolute (None) otherwise."""
    p = built.params
    w = kernel.make_work(p)
    kernel.rhs(time, y, p, w, np.zeros_like(y))
    case = built.case
    names = [body.name for body in case.bodies]
    out = {}
    for _, b, spec in servos(built):
        point = w.ppos[built.layout.point_index[spec.target]]
        aim = case.bodies[names.index(spec.target.partition(".")[0])]
        parent = getattr(aim, "relative_to", None) or (
            aim.name if isinstance(aim, sch.ImposedBody) else None)  # fmt: skip
        origin = w.pos[names.index(parent)] if parent is not None else np.zeros(3)
        out[b] = (point - origin, parent)
    return out


def _equilibria(built: BuiltSystem, y: np.ndarray, time: float):
    """Every servo body held at its target: the system (``_held_at``), its equilibrium at
    ``time`` (from the lines' shapes at the start, else from ``y``), the holding forces and
    the targets (``_targets``)."""
    targets = _targets(built, y, time)
    held = _held_at(built, targets)
    begin = held.y0 if time == 0.0 else _without(built, y)
    solved = statics.equilibrium(held, begin, tolerance=TOLERANCE, time=time)
    loads = statics.line_loads(held, solved, at_rest=True, time=time)
    return held, solved, {b: -loads[b, :3] for b in targets}, targets


def _stiffness(held, solved, forces, targets, b: int, spec: ServoForce, time: float):
    """K [N/m] of body b's lines: its holding force with the body moved on the sphere around
    its target (the other servo bodies held at theirs), by least squares."""
    displacements = spec.sphere_radius * sphere_directions()
    coords = coordinates.coordinates(held.params)
    structure = coordinates.pattern(held.params, coords)
    centre = coordinates.Residual(held.params, coords, time)
    colours = coordinates.colour(structure)
    jacobian = coordinates.fd_jacobian(centre, solved, coords, structure, colours, centre(solved))
    factor = splu(jacobian.tocsc())
    found = []
    for d in displacements:
        system = replace(held, params=_moved(held.params, b, targets[b][0] + d))
        state = _chord(system, coords, factor, solved, time)
        if state is None:  # farther than the centre's Jacobian reaches: Newton, from the
            # lumped lines settled to the moved body (EA in stages: a stiff line's first
            # strain, all in its last segment, throws Newton off)
            begin = static_lines(system.params, solved, time=time)
            state = statics.equilibrium(system, begin, tolerance=TOLERANCE, time=time)
        found.append(-statics.line_loads(system, state, at_rest=True, time=time)[b, :3])
    k_transposed, *_ = np.linalg.lstsq(displacements, np.array(found) - forces[b], rcond=None)
    return k_transposed.T


def _chord(system: BuiltSystem, coords, factor, start: np.ndarray, time: float):
    """The equilibrium near ``start`` by chord iterations with the centre's Jacobian (its LU
    ``factor``): a point of the sphere is a small move of the held body; None when they do
    not converge (to ``TOLERANCE`` of the first residual, as ``statics.equilibrium``)."""
    residual = coordinates.Residual(system.params, coords, time)
    y, r = start, residual(start)
    tolerance = TOLERANCE * (float(np.abs(r).max()) + 1.0)
    for _ in range(40):
        if not np.all(np.isfinite(r)):
            return None
        if np.abs(r).max() < tolerance:
            return y
        y = coordinates.apply(y, coords, -factor.solve(r))
        r = residual(y)
    return None


def _moved(p: kernel.SystemParams, b: int, offset: np.ndarray) -> kernel.SystemParams:
    """``p`` (of ``_held_at``) with the held body b at ``offset``: its x, y, z channels are
    constants, their values the first coefficient of their one piece (and their value at t = 0
    for a build-up)."""
    coefs, ramps = p.tf_coefs.copy(), p.tf_build_up.copy()
    first = int(p.body_channel[b])
    for c in range(3):
        coefs[first + c, 0, 0] = offset[c]
        ramps[first + c, 1] = offset[c]
    return p._replace(tf_coefs=coefs, tf_build_up=ramps)


def _held_at(built: BuiltSystem, targets: dict[int, tuple]) -> BuiltSystem:
    """The system with each servo body b an imposed body at ``targets[b]`` (an offset from the
    reference point of a body, moving with it, or absolute), and no servo; its state the lines'
    initial shapes."""
    case = built.case
    data = case.model_dump(mode="json", by_alias=True, exclude_none=True)
    held_names = set()
    for b, (offset, parent) in targets.items():
        body: dict = {"name": case.bodies[b].name, "type": "imposed"}
        for axis, value in zip("xyz", offset, strict=True):
            body[axis] = {"kind": "constant", "value": float(value)}
        if parent is not None:
            body["relative_to"] = parent
        data["bodies"][b] = body
        held_names.add(case.bodies[b].name)
    for line in data["lines"]:
        ends = {line["from"].partition(".")[0], line["to"].partition(".")[0]}
        if ends & held_names and line["model"] != "tie":
            line["initial"] = "catenary"  # the held point is off the line's given shape
    variant = assemble.build(sch.SystemCase.model_validate(data), built.case._base_dir)
    y, params = initial_state(variant)  # the lines' shapes, the joints' unloaded directions
    return BuiltSystem(params=params, y0=y, layout=variant.layout, case=variant.case)


def _kept(built: BuiltSystem) -> np.ndarray:
    """Which entries of the state remain when the servo bodies are held (``_held_at``): all
    but their own states and their servos' (another force model's states, a radiation state
    space's, remain)."""
    p = built.params
    keep = np.ones(p.n_q + p.n_v + p.n_s, dtype=bool)
    for f, b, _ in servos(built):
        keep[p.force_state[f] : p.force_state[f] + servo.STATES] = False
        if p.body_q[b] >= 0:
            keep[p.body_q[b] : p.body_q[b] + 3] = False
            keep[p.body_v[b] : p.body_v[b] + 3] = False
    return keep


def _without(built: BuiltSystem, y: np.ndarray) -> np.ndarray:
    """``y`` in the layout of ``_held_at``."""
    return y[_kept(built)]


def _restored(built: BuiltSystem, held: BuiltSystem, state: np.ndarray) -> np.ndarray:
    """A state of ``held`` in the layout of ``built``: each servo body where it is held,
    moving as its target's reference body; the servos' forces zero (``start`` sets them)."""
    p = built.params
    out = np.zeros(p.n_q + p.n_v + p.n_s)
    out[_kept(built)] = state
    w = kernel.make_work(held.params)
    kernel.rhs(0.0, state, held.params, w, np.zeros_like(state))
    for _, b, _ in servos(built):
        if p.body_q[b] >= 0:
            out[p.body_q[b] : p.body_q[b] + 3] = w.pos[b]
            out[p.body_v[b] : p.body_v[b] + 3] = w.vel[b]
    return out


def loop(built: BuiltSystem, y: np.ndarray) -> ServoLoop:
    """The servos' closed loop linearised about ``y`` at t = 0 (``loop_of`` the system's
    right-hand side)."""
    p0 = built.params
    w = kernel.make_work(p0)
    rows = [f for f, _, _ in servos(built)]

    def rates(gain, rate_gain, state, out):
        data = p0.force_data.copy()
        for f in rows:
            at = p0.force_at[f]
            data[at + servo.GAIN], data[at + servo.RATE_GAIN] = gain, rate_gain
            data[at + servo.STEP] = 1.0
        kernel.rhs(0.0, state, p0._replace(force_data=data), w, out)

    return loop_of(rates, y)


def loop_of(rates, y: np.ndarray) -> ServoLoop:
    """J0, G and H about ``y`` from central differences of ``rates(a / dt, b, y, out)`` (a
    model's right-hand side with its servos' a / dt and b set), one Jacobian per term."""

    def jacobian(gain, rate_gain):
        size = y.shape[0]
        result = np.empty((size, size))
        plus, minus = np.empty(size), np.empty(size)
        for i in range(size):
            h = 1e-6 * max(1.0, abs(y[i]))
            moved = y.copy()
            moved[i] += h
            rates(gain, rate_gain, moved, plus)
            moved[i] -= 2.0 * h
            rates(gain, rate_gain, moved, minus)
            result[:, i] = (plus - minus) / (2.0 * h)
        return result

    frozen = jacobian(0.0, 0.0)
    return ServoLoop(frozen, jacobian(1.0, 0.0) - frozen, jacobian(0.0, 1.0) - frozen)


def check(built: BuiltSystem, y: np.ndarray) -> float | None:
    """Refuse a servo gain and step that make the loop unstable: an error growing by more than
    a factor e over the run (growth rate above 1 / duration). Returns the growth rate [1/s]
    (None without a servo)."""
    found = servos(built)
    if not found:
        return None
    closed = loop(built, y)
    duration = built.case.simulation.duration
    allowed = 1.0 / duration
    f, b, spec = found[0]
    p = built.params
    row = p.force_data[p.force_at[f] :]
    gain, rate_gain, step = spec.gain, spec.rate_gain, float(row[servo.STEP])
    growth = closed.growth_rate(gain, rate_gain, step)
    if growth <= allowed:
        return growth
    where = f"bodies[{b}] ({built.case.bodies[b].name}).external forces[0]"  # check_body
    largest = closed.largest_stable_gain(rate_gain, step, allowed)
    if largest == 0.0:
        raise CaseError(
            f"{where}: no gain is stable with rate_gain {rate_gain:g} and servo step {step:g} s "
            f"(growth {growth:.3g} /s at gain {gain:g}); hold the line's end on the vehicle "
            "instead (the exact end force)"
        )
    given = "" if spec.step is not None else " (the integration step)"
    raise CaseError(
        f"{where}.gain: value {gain:g} with servo step {step:g} s{given} makes the servo loop "
        f"unstable: an error grows as exp({growth:.3g} t), by a factor "
        f"exp({growth * duration:.3g}) over the {duration:g} s run. The stable gains with this "
        f"step are 0 < gain <= {largest:.3g} (gain / step <= {largest / step:.3g} /s, growth "
        f"below 1 / duration). Lower the gain to at most {largest:.3g}, or lengthen the servo's "
        "step in proportion; or hold the line's end on the vehicle (the exact end force)"
    )
