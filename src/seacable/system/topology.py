"""The graph of a system: bodies joined by lines and ties. A group of bodies joined to no fixed
or imposed body, with no restoring force of its own (a ``linear_stiffness``, or buoyancy of a
shape the free surface cuts, which holds heave alone), has no static equilibrium: the statics
refuses it, naming the bodies. Rigid lines form trees: a line carries the point body at its end,
which may start further lines (``rigid_tips``, their sweep order by ``depth``); a line held at
its end on another free body couples the two (``ports``); a planar line's bodies must stay in
its plane (``planar_ends``)."""

import numpy as np

from seacable.case import system as sch
from seacable.case.base import Constant
from seacable.case.forces import LinearStiffness
from seacable.errors import CaseError


def groups(case: sch.SystemCase) -> list[list[str]]:
    """The names of the bodies of each connected group (lines and ties are the edges)."""
    parent = {body.name: body.name for body in case.bodies}

    def root(name: str) -> str:
        while parent[name] != name:
            parent[name] = parent[parent[name]]
            name = parent[name]
        return name

    edges = [(line.from_, line.to) for line in case.lines]
    edges += [(body.name, body.pinned_to) for body in case.bodies
              if isinstance(body, sch.RigidBody) and body.pinned_to is not None]  # fmt: skip
    for ref_a, ref_b in edges:
        a, b = ref_a.partition(".")[0], ref_b.partition(".")[0]
        if a in parent and b in parent:
            parent[root(a)] = root(b)
    out: dict[str, list[str]] = {}
    for body in case.bodies:
        out.setdefault(root(body.name), []).append(body.name)
    return list(out.values())


# a floating body free in these only may be held by its waterplane alone
WATERPLANE_DOFS = {"heave", "roll", "pitch"}
WATERPLANE_MODELS = ("rod", "non-linear hydrostatic")  # the buoyancy of what the surface cuts


def floats(body) -> bool:
    """Whether ``body`` has the buoyancy of what the free surface cuts (a waterplane that may
    hold it in heave, roll and pitch)."""
    models = {f.model for f in getattr(body, "external_forces", ())}
    return bool(models & set(WATERPLANE_MODELS)) or (
        getattr(body, "shape", None) is not None and "buoyancy" in models
    )


def _holds(body) -> bool:
    if isinstance(body, sch.FixedBody | sch.ImposedBody) or not getattr(body, "dofs", True):
        return True  # held in space (a body without a free degree of freedom too)
    if floats(body) and set(body.dofs) <= WATERPLANE_DOFS:
        return True  # held by its waterplane
    return any(isinstance(f, LinearStiffness) for f in body.external_forces)


def unheld(case: sch.SystemCase) -> list[list[str]]:
    """The groups of bodies (``groups``) that nothing holds: no static equilibrium."""
    by_name = {body.name: body for body in case.bodies}
    return [group for group in groups(case) if not any(_holds(by_name[n]) for n in group)]


def check_held(case: sch.SystemCase) -> None:
    """Refuse a group of free bodies that nothing holds (for a static start)."""
    for group in unheld(case):
        raise CaseError(
            f"bodies {group}: a group that nothing holds (no fixed or imposed body among "
            "them, no linear_stiffness, no floating body free in heave, roll and pitch "
            "only), so it has no static equilibrium; join it to a "
            "fixed body with a line or a tie, give one of them a linear_stiffness, or use "
            "start: as_given to let it drift"
        )


# ---- trees of rigid lines and the bodies they carry ----------------------------------------------
def rigid_lines(case) -> list[tuple[int, "sch.RigidLine"]]:
    return [(k, line) for k, line in enumerate(case.lines)
            if isinstance(line, sch.RigidLine)]  # fmt: skip


def rigid_tips(case: sch.SystemCase) -> dict[int, int]:
    """{body index: rigid-line number} of the point bodies carried at a rigid-segment line's
    tip: a point body that ends one rigid line only, unless carrying it would close a ring of
    lines each carried by the next, or would start a line held on a free body (``ports``) from
    a carried body. Such a body is left free instead, and the line that ends on it held there
    (the same motion: its holding force then an unknown of its group's solve). Refuses a
    massless body that would have to be left free (its group's solve needs a mass)."""
    names = [b.name for b in case.bodies]
    lines = rigid_lines(case)
    ends = [line.to.partition(".")[0] for _, line in lines]
    tips: dict[int, int] = {}
    base: dict[int, int] = {}  # rigid-line number -> base body
    for r, (_, line) in enumerate(lines):
        start = line.from_.partition(".")[0]
        if ends[r] not in names or start not in names:
            continue  # named in the error of the point's resolution
        b = names.index(ends[r])
        base[r] = names.index(start)
        if isinstance(case.bodies[b], sch.PointBody) and ends.count(ends[r]) == 1:
            tips[b] = r

    def free(b: int, why: str) -> None:
        body = case.bodies[b]
        assert isinstance(body, sch.PointBody)  # tips are point bodies
        if body.mass <= 0.0 and not np.any(np.asarray(body.added_mass) > 0.0):
            k, line = lines[tips[b]]
            raise CaseError(
                f"lines[{k}] ({line.name}).to: body '{body.name}' is massless, and {why}, so "
                "it must be solved as a free body, which needs a mass; give it a mass, or "
                "make one of these lines a lumped_mass line"
            )
        del tips[b]

    for b in sorted(tips):  # walk down from each tip to its root: a ring never ends
        if b not in tips:
            continue
        seen, at = [b], base[tips[b]]
        while at in tips and at not in seen:
            seen.append(at)
            at = base[tips[at]]
        if at in seen:  # a ring: leave its last body free
            ring = sorted(lines[tips[x]][1].name for x in seen[seen.index(at) :])
            free(max(seen[seen.index(at) :]), f"lines {ring} would close a ring")
    while True:  # a line held on a free body from a carried one: leave that one free
        carried = [(r, a) for r, a, _ in ports(case, tips) if a in tips]
        if not carried:
            return tips
        r, a = carried[0]
        free(a, f"line '{lines[r][1].name}' starts on it and ends on another free body")


def ports(case: sch.SystemCase, tips: dict[int, int]) -> list[tuple[int, int, int]]:
    """(rigid-line number, base body, end body) of every rigid line held at its end on a free
    (point or rigid) body that it does not carry: a two-port between the two bodies, whose
    accelerations are then solved together (docs/rigid_segment_lines.md, "Lines between two
    moving bodies")."""
    names = [b.name for b in case.bodies]
    out = []
    for r, (_, line) in enumerate(rigid_lines(case)):
        a, b = line.from_.partition(".")[0], line.to.partition(".")[0]
        if a not in names or b not in names or tips.get(names.index(b)) == r:
            continue
        body = case.bodies[names.index(b)]
        if isinstance(body, sch.PointBody | sch.RigidBody):
            out.append((r, names.index(a), names.index(b)))
    return out


def joints(case: sch.SystemCase, tips: dict[int, int]) -> list[tuple[int, int, str]]:
    """(pinned body, the body it is pinned to, that body's point) of every rigid body pinned
    to another's point (``pinned_to``: a spherical joint whose force is an unknown of its
    group's solve)."""
    names = [b.name for b in case.bodies]
    out = []
    for c, body in enumerate(case.bodies):
        ref = getattr(body, "pinned_to", None)
        if ref is None:
            continue
        where = f"bodies[{c}] ({body.name}).pinned_to"
        name = ref.partition(".")[0]
        if name not in names or name == body.name:
            raise CaseError(f"{where}: '{ref}' names no other body; bodies are {names} (write "
                            "'body' or 'body.point')")  # fmt: skip
        if names.index(name) in tips:
            raise CaseError(
                f"{where}: body '{name}' is carried at a rigid line's tip; pin to a rigid body, "
                "a fixed or an imposed one"
            )
        out.append((c, names.index(name), ref))
    return out


def joint_points(case: sch.SystemCase, tips: dict[int, int], point) -> np.ndarray:
    """(nj, 2) the points of each joint (``joints``): the pinned body's reference point, the
    other body's point; ``point(ref, where)`` is the index of the point ``body`` or
    ``body.point`` (system.assemble's, created on first use)."""
    rows = []
    for c, _, ref in joints(case, tips):
        where = f"bodies[{c}] ({case.bodies[c].name}).pinned_to"
        rows.append([point(case.bodies[c].name, where), point(ref, where)])
    return np.array(rows, dtype=np.int64).reshape(-1, 2)


def port_groups(case: sch.SystemCase, tips: dict[int, int]) -> list[tuple[list[int], list[int]]]:
    """The groups of free bodies whose accelerations rigid lines held at their ends (``ports``)
    or joints (``joints``) couple, with those lines and joints: (bodies in ascending order,
    rigid-line numbers r and joints j as -1 - j). A line joins its end body to a free base, a
    joint its pinned body to the body it is pinned to (when free); the holding forces are
    unknowns of the group's solve."""
    free = [isinstance(b, sch.PointBody | sch.RigidBody) for b in case.bodies]
    parent: dict[int, int] = {}

    def root(b: int) -> int:
        while parent.setdefault(b, b) != b:
            b = parent[b]
        return b

    found = [(r, a, b) for r, a, b in ports(case, tips)]
    found += [(-1 - j, a, c) for j, (c, a, _) in enumerate(joints(case, tips))]
    for _, a, b in found:
        root(b)
        if free[a] and a not in tips:
            parent[root(a)] = root(b)
    out: dict[int, tuple[list[int], list[int]]] = {}
    for b in sorted(parent):
        out.setdefault(root(b), ([], []))[0].append(b)
    for r, _, b in found:
        out[root(b)][1].append(r)
    return list(out.values())


def group_arrays(case: sch.SystemCase, tips: dict[int, int], nb: int) -> dict[str, np.ndarray]:
    """The groups of free bodies that rigid lines held on them or joints join, and those lines
    and joints (system kernel's ``body_group``, ``group_first``, ``group_member``)."""
    group = -np.ones((nb, 2), dtype=np.int64)
    first, bodies_in, lines_in = [[0, 0]], [], []
    for g, (bodies, held) in enumerate(port_groups(case, tips)):
        for s, b in enumerate(bodies):
            group[b] = g, s
        bodies_in += bodies
        lines_in += held
        first.append([len(bodies_in), len(lines_in)])
    return dict(body_group=group, group_first=np.array(first, dtype=np.int64),
                group_member=np.array(bodies_in + lines_in, dtype=np.int64))  # fmt: skip


def planar_ends(case, line, where: str, tip: int) -> None:
    """Refuse a body of a planar line that can move out of the x-z plane."""
    names = [b.name for b in case.bodies]
    for end, ref in (("from", line.from_), ("to", line.to)):
        name = ref.partition(".")[0]
        if name not in names or (end == "to" and tip >= 0):
            continue  # unknown: named elsewhere; carried at the tip: moves with the line
        body = case.bodies[names.index(name)]
        out_of_plane = ""
        if isinstance(body, sch.ImposedBody):
            keys = ("y", "roll_deg", "yaw_deg")
            still = {k: isinstance(getattr(body, k), Constant) for k in keys}
            moving = [k for k, constant in still.items() if not constant]
            moving += [k for k in ("roll_deg", "yaw_deg") if still[k] and getattr(body, k).value]
            if moving:
                out_of_plane = f"its {moving} move or turn it out of the plane"
        elif isinstance(body, sch.PointBody) and "sway" in body.dofs:
            out_of_plane = "its dofs include sway"
        elif isinstance(body, sch.RigidBody):
            extra = sorted(set(body.dofs) - {"surge", "heave", "pitch"})
            if extra:
                out_of_plane = f"its dofs include {extra}"
        if out_of_plane:
            raise CaseError(
                f"{where}.{end}: a planar rigid_links line stays in the x-z plane, but body "
                f"'{name}' can leave it ({out_of_plane}); keep that body in the plane (dofs "
                "surge, heave, pitch; no y, roll or yaw motion) or use model: rigid_segments_3d"
            )


def depth(case, tips: dict[int, int], r: int) -> int:
    """How many rigid lines carry line r's base (0: a base that no rigid line carries)."""
    names = [b.name for b in case.bodies]
    lines = rigid_lines(case)
    depth, at = 0, names.index(lines[r][1].from_.partition(".")[0])
    while at in tips:
        depth += 1
        at = names.index(lines[tips[at]][1].from_.partition(".")[0])
    return depth


def joined(case, layout, joined, tips, fields, rows) -> None:
    """Each line that ``continues`` another through the body between them: a row of ``rows``
    (``rs_tip_joint``: the other line, this one, its first joint's spring and damper), which
    then act there instead of against ``base_reference``."""
    names = [b.name for b in case.bodies]
    for r, line, where in joined:
        if line.continues not in layout.rigid:
            raise CaseError(f"{where}.continues: no rigid line '{line.continues}'; rigid lines "
                            f"are {layout.rigid}")  # fmt: skip
        other = layout.rigid.index(line.continues)
        body = names.index(line.from_.partition(".")[0])
        if tips.get(body) != other:
            raise CaseError(
                f"{where}.continues: line '{line.continues}' does not carry '{line.from_}' at "
                "its end; a line continues the rigid line that carries its 'from' body (a "
                "point body between them)"
            )
        if fields["rs_kind"][other] != fields["rs_kind"][r] or line.base_reference is not None:
            what = "base_reference" if line.base_reference is not None else "model"
            raise CaseError(
                f"{where}.{what}: a line that continues '{line.continues}' has its first joint "
                "on that line's last segment: give it the same model and no base_reference"
            )
        s0 = int(fields["rs_seg"][r])
        spring, damper = (float(fields[f"rs_joint_{key}"][s0]) for key in ("stiffness", "damping"))
        fields["rs_joint_stiffness"][s0] = fields["rs_joint_damping"][s0] = 0.0
        rows.append([float(other), float(r), 0.0, 0.0, 0.0, spring, damper])
