"""The initial state of a system's lines: each lumped-mass line on its elastic catenary
(a uniform line), laid slack on the seabed (longer than its span and rise), at the angles the
case gives, or straight between its end points at t = 0, then every line's interior nodes at
their discrete static equilibrium with the bodies held where they start
(``line_balance.static_lines``). Interior velocities go linearly, along the line, from one
end's velocity to the other's. The closed-form shapes (``uniform_shapes``) also start the
statics' lines at each trial pose (system.nested)."""

import logging
import math

import numpy as np

from seacable.bodies import kinematics
from seacable.case import system as sch
from seacable.errors import CaseError
from seacable.kernels import lumped as lk
from seacable.lines import catenary
from seacable.system import kernel
from seacable.system.assemble import BuiltSystem
from seacable.system.geometry import MOST_STRAIN
from seacable.system.line_balance import static_lines

log = logging.getLogger(__name__)


def end_points(built: BuiltSystem, y: np.ndarray):
    """Positions and velocities of every point at t = 0."""
    return _points(built.params, y, 0.0)


def _points(p, y: np.ndarray, time: float):
    """Positions and velocities of every point at ``time``."""
    w = kernel.make_work(p)
    kernel.rhs(time, y, p, w, np.zeros_like(y))
    return w.ppos.copy(), w.pvel.copy()


def uniform_line(p, li: int, low_z: float) -> tuple[float, float, float, bool] | None:
    """Lumped-mass line ``li`` as the elastic catenary takes it: (L [m], w [N/m], EA [N],
    whether its lower end, at height ``low_z``, lies on the seabed); None when its segments
    differ in stiffness or weight per length (no closed form)."""
    n, s0 = p.line_n[li], p.line_seg[li]
    lengths = p.seg_length[s0 : s0 + n]
    stiffness = p.seg_stiffness[s0 : s0 + n]
    weight = p.seg_wet_weight[s0 : s0 + n]
    if np.ptp(stiffness) > 0 or np.ptp(weight / lengths) > 1e-9 * abs(weight[0] / lengths[0]):
        return None
    total = float(lengths.sum())
    on_seabed = bool(p.seabed_z > -1e29 and abs(low_z - p.seabed_z) < 1e-6)
    return total, float(weight.sum()) / total, float(stiffness[0]), on_seabed


def _catenary(p, li, start, end, env, where):
    try:
        return _uniform_nodes(p, li, start, end)
    except catenary.CatenaryError as exc:
        raise CaseError(f"{where}.initial: {exc}") from None


def _uniform_nodes(p, li, start, end, slack_only: bool = False):
    """The nodes of lumped line ``li`` from ``start`` to ``end`` on its elastic catenary, or,
    when it has an end on the seabed and is longer than its span and rise (or shorter by less
    than a segment, where its segments can lie so), laid slack on the seabed (``_laid``); None
    when it is not uniform (``uniform_line``), has no weight in water, or (``slack_only``) is
    not laid. Raises catenary.CatenaryError."""
    n, s0 = p.line_n[li], p.line_seg[li]
    lengths = p.seg_length[s0 : s0 + n]
    low, high, flip = (start, end, False) if start[2] <= end[2] else (end, start, True)
    uniform = uniform_line(p, li, float(low[2]))
    if uniform is None:
        return None  # not uniform: straight, then the static solve
    total, w, ea, on_seabed = uniform
    if not w > 0.0:
        return None  # neutral or buoyant: no hanging catenary; straight, then the static solve
    span_vector = high[:2] - low[:2]
    span = float(np.hypot(*span_vector))
    rise = float(high[2] - low[2])
    # slack: longer than span plus rise, its hanging part stretched by its own weight (w h^2 /
    # 2 EA: 6 cm for 235 m of 80 mm chain, beyond which no catenary with tension joins them)
    # nearly so, by less than a segment: its segments may still lie slack, the one that cuts
    # the catenary's touchdown shorter than its arc (``_laid``'s heap where it fits)
    gap = span + rise - total - w * rise**2 / (2.0 * ea)
    ordered = lengths[::-1] if flip else lengths
    laid = _laid(ordered, low, high, w, ea) if on_seabed and gap < lengths.max() else None
    if laid is not None:
        nodes = laid
    elif slack_only:
        return None
    elif not on_seabed and dips(p, total, w, low, high, span):
        nodes = _touching_down(lengths[::-1] if flip else lengths, low, high, w, p.seabed_z)
    else:
        # ends one above the other, the line longer than the rise and nothing under it: it
        # hangs folded, a U without span; started as the U of a span of a thousandth of it
        folded = not on_seabed and span < 1e-3 * total and rise < total
        h, v_f = catenary.solve(max(span, 1e-3 * total) if folded else span, rise, total, w,
                                ea, on_seabed)  # fmt: skip
        # arc length of each node from the low end (lengths run from the line's start)
        s_low = np.concatenate([[0.0], np.cumsum(lengths[::-1] if flip else lengths)])
        x, z = catenary.profile(s_low, h, v_f, total, w, ea, on_seabed)
        direction = span_vector / span if span > 0 else np.array([1.0, 0.0])
        if folded:  # sheared to the ends' true span
            x = x - (x[-1] - span) * s_low / s_low[-1]
        nodes = np.column_stack([low[0] + x * direction[0], low[1] + x * direction[1],
                                 low[2] + z])  # fmt: skip
    if p.seabed_z > -1e29:
        # nodes lying on the seabed start at the penetration that carries their weight
        stiffness_per_length = p.node_seabed_stiffness[p.line_node[li]] / (0.5 * lengths[0])
        lying = np.abs(nodes[:, 2] - (low[2] if on_seabed else p.seabed_z)) < 1e-9
        lying[0] = lying[-1] = False
        nodes[lying, 2] -= lk.seabed_resting_depth(w, stiffness_per_length, p.seabed_band)
    return nodes[::-1] if flip else nodes


def towed_hanging(p, y: np.ndarray, time: float = 0.0) -> np.ndarray | None:
    """``y`` with every free point body at the end of a lumped line from a fixed or imposed
    body hung straight below that end by the line's length (above the seabed), the line's
    nodes evenly between them: a tow's start from which its balance is reached whatever its
    towed bodies' first guess. None when there is no such body."""
    ppos, _ = _points(p, y, time)
    out = y.copy()
    moved = False
    for li in range(len(p.line_n)):
        ends = (int(p.line_from[li]), int(p.line_to[li]))
        bodies = [int(p.point_body[e]) for e in ends]
        free = [k for k in (0, 1) if p.body_kind[bodies[k]] == kinematics.DYNAMIC
                and not p.body_rigid[bodies[k]] and p.body_q[bodies[k]] >= 0]  # fmt: skip
        held = [k for k in (0, 1) if p.body_kind[bodies[k]] <= kinematics.IMPOSED]
        if len(free) != 1 or len(held) != 1:
            continue
        n, s0 = int(p.line_n[li]), int(p.line_seg[li])
        lengths = p.seg_length[s0 : s0 + n]
        top = ppos[ends[held[0]]]
        bottom = top - [0.0, 0.0, float(lengths.sum())]
        bottom[2] = max(bottom[2], p.seabed_z + 1e-3 * float(lengths.sum()))
        q = int(p.body_q[bodies[free[0]]])
        out[q : q + 3] = bottom
        s = np.concatenate([[0.0], np.cumsum(lengths if held[0] == 0 else lengths[::-1])])
        nodes = top + (s / s[-1])[:, None] * (bottom - top)[None, :]
        nodes = nodes if held[0] == 0 else nodes[::-1]
        out[p.line_q[li] : p.line_q[li] + 3 * (n - 1)] = nodes[1:-1].ravel()
        moved = True
    return out if moved else None


def uniform_shapes(p, y: np.ndarray, time: float = 0.0, slack_only: bool = False):
    """``y`` with every uniform lumped line's nodes on its closed-form shape between its ends
    as they are at ``y`` (``_uniform_nodes``: the elastic catenary, or laid slack on the
    seabed); with ``slack_only``, only the lines laid slack: chain lying slack, whose shape the
    statics do not determine (any shape that pushes no segment is in balance on a frictionless
    seabed), and whose nodes, carried along with a moved end, would be pushed (the linear axial
    law of the static solves would hold a body off with it). The other lines' nodes, and
    those with no closed form, as they are."""
    ppos, _ = _points(p, y, time)
    out = y.copy()
    for li in range(len(p.line_n)):
        start, end = ppos[p.line_from[li]], ppos[p.line_to[li]]
        try:
            nodes = _uniform_nodes(p, li, start, end, slack_only)
        except catenary.CatenaryError:
            continue
        if nodes is not None:
            out[p.line_q[li] : p.line_q[li] + 3 * (p.line_n[li] - 1)] = nodes[1:-1].ravel()
    return out


def dips(p, total, w, low, high, span) -> bool:
    """A line hanging between ends above the seabed whose inextensible catenary would reach
    below it: its middle lies on the seabed (``_touching_down``, ``touchdown``)."""
    if p.seabed_z < -1e29 or min(low[2], high[2]) <= p.seabed_z:
        return False
    rise = float(high[2] - low[2])
    if total <= math.hypot(span, rise) * (1.0 + 1e-9):
        return False
    try:
        h, v_f = catenary.solve(max(span, 1e-3 * total), rise, total, w, math.inf, False)
    except catenary.CatenaryError:
        return True
    v_a = v_f - w * total
    if v_a >= 0.0 or v_f <= 0.0:
        return False  # the lowest point is an end
    sag = h / w * (math.sqrt(1.0 + (v_a / h) ** 2) - 1.0)  # below the lower end
    return float(low[2]) - sag < p.seabed_z


def _laid(lengths, low, high, w: float = 0.0, ea: float = math.inf):
    """The nodes (from the lower end ``low``, on the seabed) of a line too long to reach
    ``high`` as a catenary (longer than its span and rise): it hangs straight down from the
    upper end, its last hanging segment reaches the seabed towards the lower end, and the rest
    lies on the seabed as a polygon inscribed in a circular arc from the lower end, bulging to
    its left: the lying segments at their unstretched length, slack and at rest (the linear
    axial law of the static solves pushes back on a segment shorter than that), the hanging
    ones stretched by the weight in water ``w`` [N/m] of the line below them (EA ``ea``): the
    foot's segment, which takes up what the drop leaves, is then never pushed either. None
    when the lying part cannot reach the foot without being stretched (a line shorter than
    its span and rise by more than its segments cut off its touchdown)."""
    n = len(lengths)
    horizontal = low[:2] - high[:2]
    span = float(np.hypot(*horizontal))
    toward = horizontal / span if span > 0.0 else np.array([-1.0, 0.0])
    unstretched = lengths[::-1].astype(float)
    hanging = _drop(unstretched, high, float(low[2]), toward, span)
    if w > 0.0 and math.isfinite(ea):
        # as many hanging as the stretch of that many lets hang (stretched, fewer hang): from
        # the unstretched count down, the first count that holds, else that count's drop
        tried = []
        for m in range(len(hanging) - 1, 0, -1):
            below = np.cumsum(unstretched[:m][::-1])[::-1] - 0.5 * unstretched[:m]
            from_top = unstretched.copy()
            from_top[:m] *= 1.0 + w * below / ea
            tried.append(_drop(from_top, high, float(low[2]), toward, span))
            if len(tried[-1]) - 1 == m:
                break
        hanging = tried[-1] if len(tried[-1]) - 1 == m else tried[0]
    k = n + 1 - len(hanging)  # the foot's node
    if lengths[:k].sum() < float(np.hypot(*(hanging[-1, :2] - low[:2]))) * (1.0 - 1e-12):
        return None  # the lying part cannot reach the foot slack
    nodes = np.empty((n + 1, 3))
    nodes[k:] = hanging[::-1]
    nodes[: k + 1, :2] = _lying(lengths[:k], low[:2], hanging[-1, :2], toward)
    nodes[: k + 1, 2] = low[2]
    return nodes


def _drop(lengths, top, floor, toward, farthest):
    """The points (from ``top`` down) of segments ``lengths`` (from the top) hanging straight
    down from ``top`` while they stay above the seabed at ``floor`` [m], then the next one
    reaching it aslant towards ``toward`` (at most ``farthest`` [m] off): its foot last."""
    points, depth, k = [np.asarray(top, float)], 0.0, 0
    rise = float(top[2] - floor)
    while k < len(lengths) - 1 and depth + lengths[k] < rise:
        depth += lengths[k]
        k += 1
        points.append(top - [0.0, 0.0, depth])
    reach = math.sqrt(max(lengths[k] ** 2 - (rise - depth) ** 2, 0.0))
    foot = top[:2] + min(reach, farthest) * toward
    points.append(np.array([foot[0], foot[1], floor]))
    return np.array(points)


def _lying(lying, start, end, toward):
    """The horizontal positions (len(lying) + 1, 2) of a chain of segments ``lying`` [m] on
    the seabed from ``start`` to ``end``: straight when they reach no farther, else a polygon
    inscribed in a circular arc bulging to its left, each segment at its length (``toward``:
    the heading where the two points coincide)."""
    chord = end - start
    distance = float(np.hypot(*chord))
    s = np.concatenate([[0.0], np.cumsum(lying)])
    if len(lying) < 2 or lying.sum() <= distance * (1.0 + 1e-12):
        return start + (s / max(lying.sum(), 1e-300))[:, None] * chord[None, :]
    from scipy.optimize import brentq  # here: its import is slow (docs/architecture.md)

    def angle(radius):  # the arc's angle when each segment is a chord of a circle this wide
        return 2.0 * np.arcsin(np.minimum(lying / (2.0 * radius), 1.0)).sum()

    smallest = 0.5 * float(lying.max())
    closed = brentq(lambda r: angle(r) - 2 * math.pi, smallest, 1e3 * lying.sum())
    radius = brentq(lambda r: 2 * r * math.sin(angle(r) / 2) - distance, closed,
                    1e9 * lying.sum(), xtol=1e-12 * lying.sum())  # fmt: skip
    half = np.arcsin(lying / (2.0 * radius))
    turn = angle(radius) / 2 - (2.0 * np.cumsum(half) - half)  # each chord's heading
    along = chord / distance if distance > 0.0 else toward
    left = np.array([-along[1], along[0]])
    steps = lying[:, None] * (np.cos(turn)[:, None] * along + np.sin(turn)[:, None] * left)
    return start + np.concatenate([[[0.0, 0.0]], np.cumsum(steps, axis=0)])


def touchdown(total: float, heights, span: float, w: float):
    """(H [N], each arm's horizontal reach [m], each arm's length [m]) of an inextensible line
    of length ``total`` and weight ``w`` [N/m] whose middle lies on the seabed between ends
    ``heights`` above it, ``span`` apart (``_touching_down``): arm i of height h_i rises over
    (H/w) acosh(1 + w h_i / H) along sqrt(h_i^2 + 2 h_i H / w) of line; H = 0, the arms
    hanging straight down, when the line is longer than its span and both heights."""
    from scipy.optimize import brentq  # here: its import is slow (docs/architecture.md)

    def arms(h):
        return (
            [h / w * math.acosh(1.0 + w * z / h) for z in heights],
            [math.sqrt(z * z + 2.0 * z * h / w) for z in heights],
        )

    def gap(h):
        reach, arc = arms(h)
        return sum(reach) + total - sum(arc) - span

    if total - sum(heights) >= span:
        return 0.0, [0.0, 0.0], [float(z) for z in heights]
    high = w * total
    while gap(high) < 0.0:
        high *= 2.0
    tension = brentq(gap, 1e-12 * high, high, xtol=1e-12 * high)
    reach, arc = arms(tension)
    return tension, reach, arc


def _touching_down(lengths, start, end, w, seabed_z):
    """The nodes of a line hanging from ``start`` to ``end`` (both above the seabed at
    ``seabed_z``) whose middle lies on the seabed: two inextensible catenaries, each tangent to
    the seabed where it touches down, the part between laid straight (the horizontal tension
    H [N] that makes the span: arm i of height h_i rises over (H/w) acosh(1 + w h_i / H) along
    sqrt(h_i^2 + 2 h_i H / w) of line), or, when the line is longer than its span and both
    heights, hanging straight down from both ends (``_drop``) and lying slack in an arc
    between the two feet."""
    heights = (float(start[2] - seabed_z), float(end[2] - seabed_z))
    total = float(lengths.sum())
    horizontal = end[:2] - start[:2]
    span = float(np.hypot(*horizontal))
    toward = horizontal / span if span > 0.0 else np.array([1.0, 0.0])
    tension, reach, arc = touchdown(total, heights, span, w)
    if tension == 0.0:  # slack: both ends hang straight down, the rest lies in an arc
        first = _drop(lengths, start, seabed_z, toward, 0.5 * span)
        last = _drop(lengths[::-1], end, seabed_z, -toward, 0.5 * span)
        nodes = np.empty((len(lengths) + 1, 3))
        a, b = len(first) - 1, len(lengths) + 1 - len(last)  # the feet's nodes
        nodes[: a + 1], nodes[b:] = first, last[::-1]
        nodes[a : b + 1, :2] = _lying(lengths[a:b], first[-1, :2], last[-1, :2], toward)
        nodes[a : b + 1, 2] = seabed_z
        return nodes
    s = np.concatenate([[0.0], np.cumsum(lengths)])
    nodes = np.empty((len(s), 3))
    feet = (start[:2] + reach[0] * toward, end[:2] - reach[1] * toward)
    for from_end, near in ((s, 0), (total - s, 1)):
        on = from_end <= arc[near]
        sigma = arc[near] - from_end[on]  # arc length from the foot up the arm
        x = tension / w * np.arcsinh(w * sigma / tension)
        z = tension / w * (np.sqrt(1.0 + (w * sigma / tension) ** 2) - 1.0)
        side = -toward if near == 0 else toward
        nodes[on, :2] = feet[near] + x[:, None] * side[None, :]
        nodes[on, 2] = seabed_z + z
    lying = (s > arc[0]) & (total - s > arc[1])
    if lying.any():
        inner = s[lying]
        pieces = np.diff(np.concatenate([[arc[0]], inner, [total - arc[1]]]))
        nodes[lying, :2] = _lying(pieces, feet[0], feet[1], toward)[1:-1]
        nodes[lying, 2] = seabed_z
    return nodes


def initial_state(built: BuiltSystem) -> tuple[np.ndarray, kernel.SystemParams]:
    """The initial state, and the parameters with every rigid line's first-joint reference
    (its first segment's initial direction, unless the case gives one)."""
    p, case = built.params, built.case
    y = built.y0.copy()
    if len(p.rs_n):
        y, p = _rigid_initial(built, y)
    if len(p.joint):
        _pinned(p, y, case)
    ppos, pvel = end_points(BuiltSystem(p, y, built.layout, case), y)
    lumped = [line for line in case.lines if isinstance(line, sch.LumpedMassLine)]
    for li, line in enumerate(lumped):
        n = p.line_n[li]
        start, end = ppos[p.line_from[li]], ppos[p.line_to[li]]
        s0 = p.line_seg[li]
        arc = np.concatenate([[0.0], np.cumsum(p.seg_length[s0 : s0 + n])])
        arc /= arc[-1]
        where = f"lines ({line.name})"
        _stretch(p, li, start, end, where, case.start == "as_given")
        nodes = None
        if isinstance(line.initial, sch.LineAngles):
            nodes = _lumped_angles(line, p.seg_length[s0 : s0 + n], start, end, where)
        elif line.initial == "catenary":
            nodes = _catenary(p, li, start, end, case.environment, where)
        if nodes is None:
            nodes = start + arc[:, None] * (end - start)[None, :]
        q, v = p.line_q[li], p.line_v[li]
        y[q : q + 3 * (n - 1)] = nodes[1:-1].ravel()
        va, vb = pvel[p.line_from[li]], pvel[p.line_to[li]]
        y[v : v + 3 * (n - 1)] = (va + arc[1:-1, None] * (vb - va)[None, :]).ravel()
    if lumped and any(line.initial == "catenary" for line in lumped):
        kept = [(p.line_q[li], p.line_v[li], 3 * (p.line_n[li] - 1))
                for li, line in enumerate(lumped) if line.initial != "catenary"]  # fmt: skip
        settled = static_lines(p, y, warn=case.start != "static")
        for q, v, size in kept:  # straight lines and given angles stay as they are
            settled[q : q + size] = y[q : q + size]
            settled[v : v + size] = y[v : v + size]
        y = settled
    return y, p


def _pinned(p, y: np.ndarray, case) -> None:
    """Each body pinned to another's point (``p.joint``) at that point at t = 0, with its
    velocity, into ``y`` (bodies pinned to pinned bodies after them); refuses a case that puts
    it more than 1 mm away."""
    for _ in range(len(p.joint)):
        ppos, pvel = _points(p, y, 0.0)
        for pc, pp in p.joint:
            b = int(p.point_body[pc])
            gap = float(np.linalg.norm(ppos[pp] - y[p.body_q[b] : p.body_q[b] + 3]))
            if gap > 1e-3:
                body = case.bodies[b]
                raise CaseError(
                    f"bodies[{b}] ({body.name}).position {list(body.position)} is "
                    f"{gap:.6g} m from '{body.pinned_to}' at the start "
                    f"{np.round(ppos[pp], 9).tolist()}: a pinned body's reference point starts "
                    "at the point it is pinned to; give that position"
                )
            y[p.body_q[b] : p.body_q[b] + 3] = ppos[pp]
            y[p.body_v[b] : p.body_v[b] + 3] = pvel[pp]


def _directors(line, n: int, where: str) -> tuple[np.ndarray, np.ndarray]:
    """Unit directors (n, 3) of the segment angles a line's ``initial`` gives, and the angles
    [rad]; refused unless one per segment."""
    angles = line.initial.angles(n)
    if len(angles) != n:
        raise CaseError(
            f"{where}.initial.angles_deg: {len(angles)} angles for a line of {n} segments; give "
            "one per segment"
        )
    a = np.radians(np.asarray(angles, dtype=float))
    azimuth = np.radians(line.initial.azimuth_deg)
    e = np.column_stack([np.sin(a) * np.cos(azimuth), np.sin(a) * np.sin(azimuth), -np.cos(a)])
    return e, a


def _lumped_angles(line, lengths, start, end, where) -> np.ndarray:
    """A lumped line's nodes (n + 1, 3) at the angles the case gives, each segment at its
    unstretched length from ``start``; its last node is its ``to`` point, which must be within
    1 mm of the shape's end."""
    e, _ = _directors(line, len(lengths), where)
    nodes = start + np.vstack([np.zeros(3), np.cumsum(lengths[:, None] * e, axis=0)])
    miss = float(np.linalg.norm(nodes[-1] - end))
    if miss > 1e-3:
        raise CaseError(
            f"{where}.initial: the given angles end the line at "
            f"{np.round(nodes[-1], 4).tolist()} m but its 'to' point is at "
            f"{np.round(end, 4).tolist()} m ({miss:.4g} m apart; allowed 1 mm): move that point "
            "to the line's end or change the angles"
        )
    nodes[-1] = end
    return nodes


def _stretch(p, li, start, end, where: str, as_given: bool) -> None:
    """A lumped line whose ends are farther apart than its length allows (``system.geometry``'s
    MOST_STRAIN), refused before its shape is sought. Only ends that stay where they are
    (fixed or imposed bodies, or any with ``start: as_given``): a static start moves free
    bodies from their first guess. A smaller stretch is reported by ``system.geometry`` from
    the start state."""
    ends = np.asarray(p.point_body)[[p.line_from[li], p.line_to[li]]]
    held = all(p.body_kind[b] in (kinematics.FIXED, kinematics.IMPOSED) for b in ends)
    if not (held or as_given):
        return
    s0, n = p.line_seg[li], p.line_n[li]
    length = float(p.seg_length[s0 : s0 + n].sum())
    strain = float(np.linalg.norm(end - start)) / length - 1.0
    if strain > MOST_STRAIN:
        stiffness = float(p.seg_stiffness[s0 : s0 + n].min())
        raise CaseError(
            f"{where}: its ends are {length * (1 + strain):.6g} m apart and its unstretched "
            f"length is {length:.6g} m, a strain of {100 * strain:.3g} % and a tension of about "
            f"{stiffness * strain:.4g} N (EA {stiffness:.4g} N): more stretch than a line "
            "takes; lengthen it or move its ends"
        )


def _rigid_initial(built: BuiltSystem, y: np.ndarray):
    """Directors of every rigid line from its initial shape, bases before the lines they
    carry; rates zero (node 0 moves with its point)."""
    p, case = built.params, built.case
    rigid = [line for line in case.lines if isinstance(line, sch.RigidLine)]
    ref = p.rs_ref.copy()
    tip_joints = p.rs_tip_joint.copy()
    y = y.copy()
    for li in p.rs_order[::-1]:
        line = rigid[li]
        where = f"lines ({line.name})"
        n, s0, q = int(p.rs_n[li]), int(p.rs_seg[li]), int(p.rs_q[li])
        lengths = p.rs_length[s0 : s0 + n]
        ppos, _ = end_points(BuiltSystem(p, y, built.layout, case), y)
        start = ppos[p.rs_from[li]]
        tip = int(p.rs_tip[li])
        end = p.body_pose[tip, :3] if tip >= 0 else ppos[p.rs_to[li]]
        total = float(lengths.sum())
        distance = float(np.linalg.norm(end - start))
        if tip < 0 and distance > total * (1 + 1e-9):
            raise CaseError(
                f"{where}: its ends are {distance:.6g} m apart, farther than its length "
                f"{total:.6g} m; an inextensible line cannot reach: lengthen it or move its ends"
            )
        given = None
        if isinstance(line.initial, sch.LineAngles):
            e, pose, given = _given_angles(line, p, li, start, end, where)
            if pose is not None:
                p = p._replace(body_pose=pose)
        else:
            e = _shaped(line, p, li, start, end, total, distance)
        if line.model == "rigid_links":
            if abs(end[1] - start[1]) > 1e-9 * max(1.0, total):
                raise CaseError(
                    f"{where}: a planar rigid_links line lies in an x-z plane, but its ends are "
                    f"at y = {start[1]:.6g} and {end[1]:.6g} m; put both ends at one y, or use "
                    "model: rigid_segments_3d"
                )
            y[q : q + n] = np.arctan2(e[:, 0], -e[:, 2]) if given is None else given
            y[p.rs_v[li] : p.rs_v[li] + n] = 0.0
        else:
            y[q : q + 3 * n] = e.ravel()
            y[p.rs_v[li] : p.rs_v[li] + 3 * n] = 0.0
        w = kernel.make_work(p)
        kernel.rhs(0.0, y, p, w, np.zeros_like(y))
        if np.isnan(ref[li]).any():
            ref[li] = w.rot[int(p.point_body[p.rs_from[li]])].T @ e[0]
        for joint in tip_joints:  # a held end's joint: along the last segment's start
            if int(joint[0]) == li and np.isnan(joint[2:5]).any():
                joint[2:5] = w.rot[int(p.point_body[p.rs_to[li]])].T @ e[-1]
    return y, p._replace(rs_ref=ref, rs_tip_joint=tip_joints)


def _shaped(line, p, li, start, end, total, distance) -> np.ndarray:
    """Unit directors (n, 3) of a catenary or straight initial shape, closed on ``end``."""
    n, s0 = int(p.rs_n[li]), int(p.rs_seg[li])
    lengths = p.rs_length[s0 : s0 + n]
    nodes = None
    weight = float(p.rs_wet_weight[s0 : s0 + n].sum()) / total
    if line.initial == "catenary" and distance < total * (1 - 1e-9) and weight > 0:
        nodes = _hanging(start, end, lengths, weight)
    if nodes is None:
        chord = end - start if distance > 0 else np.array([0.0, 0.0, -1.0])
        unit = chord / np.linalg.norm(chord)
        arc = np.concatenate([[0.0], np.cumsum(lengths)])
        nodes = start + arc[:, None] * unit[None, :]
    if distance <= total:
        nodes = _reach(nodes, lengths, start, end)
    e = np.diff(nodes, axis=0)
    return e / np.linalg.norm(e, axis=1)[:, None]


def _given_angles(line, p, li, start, end, where):
    """Unit directors (n, 3) of the angles the case gives, the bodies' poses with a body
    carried at the tip put exactly at the shape's end (None when there is none), and the
    angles [rad]."""
    n, s0 = int(p.rs_n[li]), int(p.rs_seg[li])
    if line.model == "rigid_links" and line.initial.azimuth_deg != 0.0:
        raise CaseError(f"{where}.initial.azimuth_deg: a planar rigid_links line lies in x-z; "
                        "leave azimuth_deg at 0")  # fmt: skip
    e, a = _directors(line, n, where)
    tip_end = start + (p.rs_length[s0 : s0 + n, None] * e).sum(axis=0)
    miss = float(np.linalg.norm(tip_end - end))
    tip = int(p.rs_tip[li])
    if miss > 1e-3:
        what = "the body it carries is" if tip >= 0 else "its 'to' point is"
        raise CaseError(
            f"{where}.initial: the given angles end the line at {np.round(tip_end, 4).tolist()} "
            f"m but {what} at {np.round(end, 4).tolist()} m ({miss:.4g} m apart; allowed "
            "1 mm): move it to the line's end or change the angles"
        )
    pose = None
    if tip >= 0:
        pose = p.body_pose.copy()
        pose[tip, :3] = tip_end
    return e, pose, a


def _hanging(start, end, lengths, weight):
    """Nodes on the inextensible catenary from ``start`` to ``end`` (None when none joins
    them)."""
    low, high, flip = (start, end, False) if start[2] <= end[2] else (end, start, True)
    total = float(lengths.sum())
    span_vector = high[:2] - low[:2]
    span = float(np.hypot(*span_vector))
    try:
        h, v_f = catenary.solve(span, float(high[2] - low[2]), total, weight, np.inf, False)
    except catenary.CatenaryError:
        return None
    s_high = np.concatenate([[0.0], np.cumsum(lengths[::-1] if flip else lengths)])
    x, z = catenary.profile(total - s_high, h, v_f, total, weight, np.inf, False)
    direction = span_vector / span if span > 0 else np.zeros(2)
    nodes = np.column_stack([low[0] + x * direction[0], low[1] + x * direction[1], low[2] + z])
    return nodes[::-1] if not flip else nodes


def _reach(nodes, lengths, start, end, sweeps: int = 2000):
    """Nodes moved so that every segment has its length and the chain joins ``start`` to
    ``end`` (forward-and-backward reaching, from a nearby shape: the chords of a catenary are
    a little shorter than its arcs)."""
    nodes = nodes.copy()
    n = len(lengths)
    for _ in range(sweeps):
        nodes[n] = end
        for i in range(n - 1, -1, -1):
            d = nodes[i] - nodes[i + 1]
            nodes[i] = nodes[i + 1] + lengths[i] * d / np.linalg.norm(d)
        nodes[0] = start
        for i in range(n):
            d = nodes[i + 1] - nodes[i]
            nodes[i + 1] = nodes[i] + lengths[i] * d / np.linalg.norm(d)
        if np.linalg.norm(nodes[n] - end) < 1e-14 * lengths.sum():
            break
    return nodes
