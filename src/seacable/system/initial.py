"""The initial state of a system's lines: each lumped-mass line on its elastic catenary
(a uniform line) or straight between its end points at t = 0, then every line's interior nodes
at their discrete static equilibrium with the bodies held where they start (Newton iterations
on the nodes' accelerations; block-banded finite-difference Jacobian, 9 evaluations per
Jacobian whatever the size). Interior velocities go linearly, along the line, from one end's
velocity to the other's."""

import logging
import math

import numpy as np
from scipy.linalg import solve_banded

from seacable.bodies import kinematics
from seacable.case import system as sch
from seacable.errors import CaseError
from seacable.kernels import lumped as lk
from seacable.lines import catenary
from seacable.lines.lumped_mass import T_ROW
from seacable.system import kernel
from seacable.system.assemble import BuiltSystem
from seacable.system.geometry import MOST_STRAIN
from seacable.system.pseudo_time import PseudoTime

log = logging.getLogger(__name__)


def end_points(built: BuiltSystem, y: np.ndarray):
    """Positions and velocities of every point at t = 0."""
    p = built.params
    w = kernel.make_work(p)
    kernel.rhs(0.0, y, p, w, np.zeros_like(y))
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
    when it has an end on the seabed and is longer than its span and rise, laid slack on the
    seabed (``_laid``); None when it is not uniform (``uniform_line``), has no weight in
    water, or (``slack_only``) is not laid. Raises catenary.CatenaryError."""
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
    if on_seabed and total + w * rise**2 / (2.0 * ea) >= span + rise:
        nodes = _laid(lengths[::-1] if flip else lengths, low, high)
    elif slack_only:
        return None
    else:
        h, v_f = catenary.solve(span, rise, total, w, ea, on_seabed)
        # arc length of each node from the low end (lengths run from the line's start)
        s_low = np.concatenate([[0.0], np.cumsum(lengths[::-1] if flip else lengths)])
        x, z = catenary.profile(s_low, h, v_f, total, w, ea, on_seabed)
        direction = span_vector / span if span > 0 else np.zeros(2)
        nodes = np.column_stack([low[0] + x * direction[0], low[1] + x * direction[1],
                                 low[2] + z])  # fmt: skip
    if on_seabed:
        # nodes lying on the seabed start at the penetration that carries their weight
        stiffness_per_length = p.node_seabed_stiffness[p.line_node[li]] / (0.5 * lengths[0])
        lying = (np.abs(nodes[:, 2] - low[2]) < 1e-9) & (np.arange(n + 1) > 0)
        nodes[lying, 2] -= lk.seabed_resting_depth(w, stiffness_per_length, p.seabed_band)
    return nodes[::-1] if flip else nodes


def uniform_shapes(p, y: np.ndarray, time: float = 0.0, slack_only: bool = False):
    """``y`` with every uniform lumped line's nodes on its closed-form shape between its ends
    as they are at ``y`` (``_uniform_nodes``: the elastic catenary, or laid slack on the
    seabed); with ``slack_only``, only the lines laid slack: chain lying slack, whose shape the
    statics do not determine (any shape that pushes no segment is in balance on a frictionless
    seabed), and whose nodes, carried along with a moved end, would be pushed (the linear axial
    law of the static solves would hold a body off with it). The other lines' nodes, and
    those with no closed form, as they are."""
    w = kernel.make_work(p)
    kernel.rhs(time, y, p, w, np.zeros_like(y))
    out = y.copy()
    for li in range(len(p.line_n)):
        start, end = w.ppos[p.line_from[li]], w.ppos[p.line_to[li]]
        try:
            nodes = _uniform_nodes(p, li, start, end, slack_only)
        except catenary.CatenaryError:
            continue
        if nodes is not None:
            out[p.line_q[li] : p.line_q[li] + 3 * (p.line_n[li] - 1)] = nodes[1:-1].ravel()
    return out


def _laid(lengths, low, high):
    """The nodes (from the lower end ``low``, on the seabed) of a line too long to reach
    ``high`` as a catenary (longer than its span and rise): it hangs straight down from the
    upper end, its last hanging segment reaches the seabed towards the lower end, and the rest
    lies on the seabed as a polygon inscribed in a circular arc from the lower end, bulging to
    its left: every segment at its unstretched length, the lying ones slack and at rest (the
    linear axial law of the static solves pushes back on a segment shorter than that)."""
    n = len(lengths)
    nodes = np.empty((n + 1, 3))
    nodes[n], k, depth = high, n, 0.0
    rise = float(high[2] - low[2])
    while k > 1 and depth + lengths[k - 1] < rise:
        depth += lengths[k - 1]
        k -= 1
        nodes[k] = high - [0.0, 0.0, depth]
    horizontal = low[:2] - high[:2]
    span = float(np.hypot(*horizontal))
    toward = horizontal / span if span > 0.0 else np.array([-1.0, 0.0])
    reach = math.sqrt(max(lengths[k - 1] ** 2 - (rise - depth) ** 2, 0.0))
    foot = high[:2] + min(reach, span) * toward  # the touch-down node
    nodes[k - 1] = [foot[0], foot[1], low[2]]
    chord = foot - low[:2]
    distance = float(np.hypot(*chord))
    lying = lengths[: k - 1]
    if k - 1 < 2 or lying.sum() <= distance * (1.0 + 1e-12):
        s = np.concatenate([[0.0], np.cumsum(lying)]) / max(lying.sum(), 1e-300)
        nodes[:k, :2] = low[:2] + s[:, None] * chord[None, :]
        nodes[:k, 2] = low[2]
        return nodes
    from scipy.optimize import brentq  # here: its import is slow (docs/architecture.md)

    def angle(radius):  # the arc's angle when each segment is a chord of a circle this wide
        return 2.0 * np.arcsin(np.minimum(lying / (2.0 * radius), 1.0)).sum()

    smallest = 0.5 * float(lying.max())
    closed = brentq(lambda r: angle(r) - 2 * math.pi, smallest, 1e3 * lying.sum())
    radius = brentq(lambda r: 2 * r * math.sin(angle(r) / 2) - distance, closed,
                    1e9 * lying.sum(), xtol=1e-12 * lying.sum())  # fmt: skip
    half = np.arcsin(lying / (2.0 * radius))
    turn = angle(radius) / 2 - (2.0 * np.cumsum(half) - half)  # each chord's heading
    along = chord / distance if distance > 0.0 else -toward
    left = np.array([-along[1], along[0]])
    steps = lying[:, None] * (np.cos(turn)[:, None] * along + np.sin(turn)[:, None] * left)
    nodes[1:k, :2] = low[:2] + np.cumsum(steps, axis=0)
    nodes[0, :2], nodes[:k, 2] = low[:2], low[2]
    return nodes


def initial_state(built: BuiltSystem) -> tuple[np.ndarray, kernel.SystemParams]:
    """The initial state, and the parameters with every rigid line's first-joint reference
    (its first segment's initial direction, unless the case gives one)."""
    p, case = built.params, built.case
    y = built.y0.copy()
    if len(p.rs_n):
        y, p = _rigid_initial(built, y)
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
        settled = static_lines(p, y)
        for q, v, size in kept:  # straight lines and given angles stay as they are
            settled[q : q + size] = y[q : q + size]
            settled[v : v + size] = y[v : v + size]
        y = settled
    return y, p


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


def _interior(p, at):
    """State indices of every interior node position (``at`` = p.line_q) or velocity
    (p.line_v), in line order."""
    parts = [np.arange(at[li], at[li] + 3 * (p.line_n[li] - 1)) for li in range(len(p.line_n))]
    return np.concatenate(parts) if parts else np.zeros(0, dtype=np.int64)


def steady_velocities(p: kernel.SystemParams, y: np.ndarray, time: float = 0.0) -> np.ndarray:
    """The velocities (``y[n_q:n_q + n_v]``) of a steady motion at ``time``: when every fixed or
    imposed body moves with one velocity V and none turns (a ship towing at constant speed, and
    nothing fixed; a body that holds no line or tie, such as a servo's target, does not count),
    every dynamic body and every lumped line's interior node moves with V, and rigid
    lines do not turn (their nodes move with their bases); otherwise everything at rest.
    The statics then balances the loads of that motion (drag on the velocity relative to the
    current): the steady tow, which stays steady while the kinematic bodies keep V."""
    w = kernel.make_work(p)
    moving = y.copy()
    moving[p.n_q : p.n_q + p.n_v] = 0.0
    kernel.rhs(time, moving, p, w, np.zeros_like(y))
    kinematic = np.intersect1d(np.flatnonzero(np.asarray(p.body_kind) <= kinematics.IMPOSED),
                               _holding(p))  # fmt: skip
    v = np.zeros(p.n_v)
    if not kinematic.size:
        return v
    velocity = w.vel[kinematic]
    common = velocity[0]
    scale = float(np.abs(velocity).max())
    if scale == 0.0 or np.abs(velocity - common).max() > 1e-12 * scale:
        return v
    if np.abs(w.omega[kinematic]).max() > 0.0:
        return v
    for b in np.flatnonzero(np.asarray(p.body_kind) == kinematics.DYNAMIC):
        v[p.body_v[b] - p.n_q : p.body_v[b] - p.n_q + 3] = common
    for li in range(len(p.line_n)):
        first = p.line_v[li] - p.n_q
        v[first : first + 3 * (p.line_n[li] - 1)] = np.tile(common, p.line_n[li] - 1)
    return v


def _holding(p: kernel.SystemParams) -> np.ndarray:
    """The bodies that hold a line or tie end (a body that holds nothing, such as a servo's
    target vehicle, moves as it likes without making a steady motion unsteady)."""
    points = np.concatenate([np.asarray(a, dtype=np.int64) for a in (
        p.line_from, p.line_to, p.tie_from, p.tie_to, p.rs_from, p.rs_to, p.nat_from)])  # fmt: skip
    bodies = np.asarray(p.point_body, dtype=np.int64)[points]
    tips = np.asarray(p.rs_tip, dtype=np.int64)
    return np.union1d(bodies, tips[tips >= 0])


def static_lines(p, y0, iterations: int = 30, time: float = 0.0) -> np.ndarray:
    """Every line's interior nodes at rest in balance (in a tow's steady motion:
    ``steady_velocities``), bodies held where they are at ``time`` [s]: Newton on the nodes'
    accelerations from ``y0`` (a catenary start is near the balance), else with EA raised in
    steps of ten from a thousandth of its value (a nearly inextensible line makes Newton's steps
    erratic from a straight start), each stage from the last one's result, else the first
    Newton continued. When none settles (every node's acceleration below 1e-6 g), the one
    nearest the balance, with a warning: a run or a statics starts from it. Forward differences
    here (``_newton``): with central ones, Newton converges from the catenary start of a lumped
    servo tow (tests/test_upgrade_gaps.py, lumped_servo_tow) to a balance of the linear law
    with segments pushed at 1.9 kN, where the forward one stays near the taut towed shape that
    the statics' Newton then finishes."""
    linear = p._replace(slack_allowed=0)
    if p.seabed_band > 0.0:
        # the whole search on the plain spring first, then continued to the band (see
        # _newton); else each Newton of the search continued so
        plain = _static_lines(linear._replace(seabed_band=0.0), y0, iterations, time)[0]
        continued = _newton_at(linear, plain, iterations, time)
        if _settled(linear, continued, time) and not _pushes(linear, continued, time):
            return continued
    best, left = _static_lines(linear, y0, iterations, time, _newton)
    if left is not None:
        log.warning(
            "the lines' initial static shapes are out of balance by %.3g m/s^2 at some node "
            "(Newton from the catenary start and from EA stages both stopped short)",
            left,
        )
    return best


def _static_lines(linear, y0, iterations, time, newton=None):
    """static_lines' search with the parameters ``linear`` (the linear axial law) by
    ``newton`` (default ``_newton_at``, on one seabed law): the balance, and None; or the
    state nearest it, and its largest node acceleration [m/s^2]."""
    newton = newton or _newton_at
    direct = newton(linear, y0, iterations, time)
    if _settled(linear, direct, time):
        return direct, None
    y = y0.copy()
    target = linear.seg_stiffness
    for factor in (1e-3, 1e-2, 1e-1, 1.0):
        stage = linear._replace(seg_stiffness=np.ascontiguousarray(target * factor))
        y = newton(stage, y, iterations, time)
    if _settled(linear, y, time):
        return y, None
    # Newton from the start again, longer (a catenary start can need some 40 iterations; tried
    # last because the stages keep the lines taut where a long Newton may not)
    longer = newton(linear, direct, 2 * iterations, time)
    if _settled(linear, longer, time):
        return longer, None
    # pseudo-transient steps: chain lying slack (a line longer than its span and rise) holds
    # nothing across it, where Newton's matrix is singular
    relaxed = _newton_at(linear, y0, 10 * iterations, time, pseudo=True)
    if _settled(linear, relaxed, time):
        return relaxed, None
    tried = [(_unbalance(linear, state, time), k, state)
             for k, state in enumerate((direct, y, longer, relaxed))]  # fmt: skip
    left, _, best = min(tried)
    return best, left


def _unbalance(p, y, time: float = 0.0) -> float:
    """The largest interior node's acceleration at rest [m/s^2]."""
    index = _interior(p, p.line_v)
    if not len(index):
        return 0.0
    ydot = np.zeros_like(y)
    kernel.rhs(time, _at_rest(p, y, time), p, kernel.make_work(p), ydot)
    return float(np.abs(ydot[index]).max())


def _pushes(p, y, time: float = 0.0) -> bool:
    """Whether a lumped segment is pushed at rest (``pushed``): a balance of the linear axial
    law that the physical law has not."""
    w = kernel.make_work(p)
    kernel.rhs(time, _at_rest(p, y, time), p, w, np.zeros_like(y))
    return pushed(p, w) > 0.0


def _at_rest(p, y, time: float = 0.0) -> np.ndarray:
    """A copy of ``y`` at rest: no velocities, or in a tow its steady motion
    (``steady_velocities``), whose drag the lines carry; force models' states zero."""
    at_rest = y.copy()
    at_rest[p.n_q :] = 0.0
    at_rest[p.n_q : p.n_q + p.n_v] = steady_velocities(p, at_rest, time)
    return at_rest


def _settled(p, y, time: float = 0.0) -> bool:
    """True when every interior node's acceleration at rest is below 1e-6 g."""
    return _unbalance(p, y, time) < 1e-6 * p.gravity


def settle_lines(p, y0, iterations: int = 30, slack: int = 0, time: float = 0.0) -> np.ndarray:
    """Every line's interior nodes at rest in balance (in a tow's steady motion) at ``time``
    [s] from a nearby state (no EA stages: the outer loop of the system's statics, whose lines
    start each time from their last balance, their nodes carried along with their moved ends),
    with the axial law ``slack`` (kernels.lumped.segment_loads: 0 linear); Newton with central
    differences."""
    stage = p._replace(slack_allowed=slack)
    return _newton(stage, y0, iterations, time, central=True)


def pushed(p, w, share: float = 1e-6) -> float:
    """How hard [N] the most compressed segment of the lumped lines is pushed at the last
    evaluation into the workspace ``w`` under the linear axial law (0 when none is, or by no
    more than a strain of 1e-8 or 1e-6 of the largest tension). That law, which the static
    solves use (smooth; chain lying on a frictionless seabed has one shape), has balances the
    physical law has not: chain laid straight and pushed, on the seabed or in a tow's bight."""
    if not len(p.line_n):
        return 0.0
    segments = np.concatenate([np.arange(p.line_node[li], p.line_node[li] + p.line_n[li])
                               for li in range(len(p.line_n))])  # fmt: skip
    tension = w.nodes[T_ROW, segments]
    allowed = max(1e-8 * float(np.max(p.seg_stiffness)), share * float(tension.max()))
    compression = -float(tension.min())
    return compression if compression > allowed else 0.0


def _newton(p, y0, iterations, time: float = 0.0, central: bool = False):
    """``_newton_at``; with a seabed contact band (kernels.lumped.seabed_spring), first with
    the plain spring and then from its balance with the band: the band's soft foot makes
    Newton's long first steps wander where the plain spring's did not (two moored buoys'
    statics found no balance with a 5 mm band); from the plain spring's balance the lying
    nodes sink by about half the band, where the law is linear, and Newton takes a step or
    two. ``static_lines`` continues its whole search so (an eight-segment chain from its
    catenary start, whose first Newton fails, folded into a zigzag of the linear law on the
    band, at 63 MN)."""
    if p.seabed_band > 0.0:
        y0 = _newton_at(p._replace(seabed_band=0.0), y0, iterations, time, central)
    return _newton_at(p, y0, iterations, time, central)


def _banded_jacobian(residual, y, index, r, central: bool, half: int) -> np.ndarray:
    """The lines' interior nodes' block-tridiagonal Jacobian in banded storage, by forward or
    ``central`` differences in 9 colours of columns (see ``_newton_at``)."""
    m = len(index)
    ab = np.zeros((2 * half + 1, m))
    for colour in range(9):
        columns = np.arange(colour, m, 9)
        if central:  # in metres (see _newton_at)
            step = np.full(len(columns), 1e-6)
        else:
            step = 1e-7 * np.maximum(1.0, np.abs(y[index[columns]]))
        trial = y.copy()
        trial[index[columns]] += step
        if central:
            dr = residual(trial)
            trial[index[columns]] -= 2.0 * step
            dr = 0.5 * (dr - residual(trial))
        else:
            dr = residual(trial) - r
        # each column's rows: its node's and its two neighbours' (9, those inside)
        rows = 3 * (columns // 3 - 1)[:, None] + np.arange(9)[None, :]
        cols = np.broadcast_to(columns[:, None], rows.shape)
        inside = (rows >= 0) & (rows < m)
        rows, cols = rows[inside], cols[inside]
        steps = np.broadcast_to(step[:, None], inside.shape)[inside]
        ab[half + rows - cols, cols] = dr[rows] / steps
    return ab


def _newton_at(p, y0, iterations, time: float = 0.0, central: bool = False,
               pseudo: bool = False):  # fmt: skip
    """The lines' interior nodes in balance by Newton, its block-tridiagonal Jacobian by forward
    differences (steps 1e-7 of each coordinate) or ``central`` ones (1e-6 m; two residuals per
    colour, and a stop once the step is at the positions' rounding: the residual's floor). The
    central steps are in metres, not shares of the coordinates: a node 400 m from the origin
    moved by 4e-4 m, a share of 1e-6, crossed the seabed's contact of light line (polyester
    lying on a 3e5 Pa seabed sinks by 0.1 mm) and Newton lost its way
    (benchmarks/statics_success.py); the forward ones stay shares (with steps of 1e-7 m,
    ``static_lines`` found the pushed balance of a lumped tow, tests/test_upgrade_gaps.py).
    Forward differences err by EA h / (2 l^2) on a taut segment's transverse stiffness T / l
    (17 % for a 2e8 N wire at 9 kN in 1.3 m segments) and Newton then creeps; ``static_lines``
    keeps them (see there), ``settle_lines`` takes central ones. ``pseudo``: the steps of
    pseudo-transient continuation (system.pseudo_time), for chain lying slack on the seabed,
    which holds nothing across it (Newton's matrix is singular there)."""
    index = _interior(p, p.line_q)
    m = len(index)
    if m == 0:
        return y0.copy()
    w = kernel.make_work(p)
    ydot = np.zeros_like(y0)
    velocity = _interior(p, p.line_v)  # the accelerations sit at the velocities' offsets

    def residual(y):
        kernel.rhs(time, y, p, w, ydot)
        return ydot[velocity].copy()

    y = _at_rest(p, y0, time)
    r = residual(y)
    best, best_norm = y, np.linalg.norm(r)
    scale = float(np.abs(r).max()) + 1e-6
    half = 5  # block-tridiagonal with 3 x 3 blocks: 5 diagonals either side
    clock: PseudoTime | None = None
    for _ in range(iterations):
        if np.abs(r).max() < max(1e-12 * scale, 1e-10 * p.gravity):
            break
        ab = _banded_jacobian(residual, y, index, r, central, half)
        if not np.isfinite(ab).all():
            break  # the lines went where their loads are not finite: keep the best state met
        if pseudo:
            if clock is None:  # a step moves a node by a metre at most, at first
                clock = PseudoTime(r, 1.0, 1e-10 * float(np.abs(ab[half]).max()))
            ab[half] -= clock.shift
        try:
            delta = solve_banded((half, half), ab, -r)
        except np.linalg.LinAlgError:
            break  # singular: chain lying slack holds nothing across it; keep the best state
        damping = 1.0
        if clock is not None:
            trial = y.copy()
            trial[index] += delta
            rt = residual(trial)
            if not np.all(np.isfinite(rt)) or np.linalg.norm(rt) > np.linalg.norm(r):
                clock.rejected()
                continue
            clock.accepted(float(np.linalg.norm(r)), float(np.linalg.norm(rt)))
        else:
            # the seabed's contact is not smooth: when no shorter step lowers the residual,
            # the full step is taken anyway, and the best state met is kept
            for damping in (1.0, 0.5, 0.25, 0.1, 1.0):
                trial = y.copy()
                trial[index] += damping * delta
                rt = residual(trial)
                if np.linalg.norm(rt) < np.linalg.norm(r):
                    break
        y, r = trial, rt
        if np.linalg.norm(r) < best_norm:
            best, best_norm = y, np.linalg.norm(r)
        if central and damping * np.abs(delta).max() <= 1e-12 * (1.0 + np.abs(y[index]).max()):
            break  # the residual is at its rounding floor: no step moves a node any more
    best = best.copy()
    best[p.n_q :] = y0[p.n_q :]
    return best
