"""Checks of the state a run starts from (after its statics): what the models cannot honestly
run is refused, naming the body or line, where it is and the fix; what is possible but
unusual is reported.

- Below the seabed (z = -water_depth): bodies and the nodes of rigid lines and natural
  strings have no seabed contact, nor have lumped lines without ``environment.seabed``, so one
  that starts below the seabed (a rigid line whose hanging balance passes through it, a body
  placed under it) would move through the ground unopposed: refused. Lumped lines with the
  contact rest on it, and are not checked.
- Above the water: a body without a shape counts its volume wholly submerged wherever it is
  (``kernels.surface``: the point volume), so one whose centre of buoyancy starts clear of the
  water with a volume or an added mass would float in the air: refused, with the shapes that
  the surface cuts. (A hull whose waterplane is a linear stiffness keeps its centre of
  buoyancy below the surface: allowed.)
- Stretch: an extensible segment (lumped lines, natural strings) strained more than
  LARGE_STRAIN at the start is reported with its tension, more than MOST_STRAIN (more than
  any rope, wire or chain takes before it breaks, and far outside a linear EA) refused.
"""

import logging

import numpy as np

from seacable.bodies import kinematics
from seacable.case.system import SEABED_TOLERANCE
from seacable.errors import CaseError
from seacable.forces.kinds import DIFFRACTION, MESH, RADIATION_DAMPING
from seacable.kernels import surface
from seacable.system import kernel, outputs
from seacable.system.assemble import BuiltSystem

log = logging.getLogger("seacable")
HULL_MODELS = (*MESH, RADIATION_DAMPING, DIFFRACTION)  # a floating hull's models

MOST_STRAIN = 0.3  # a strain no rope, wire or chain takes: refused
LARGE_STRAIN = 0.05  # a strain beyond a taut line's usual pretension: reported
NO_SEABED = -1e29  # p.seabed_z below this: no seabed contact


def check_start(built: BuiltSystem, y: np.ndarray) -> None:
    """Refuse (CaseError) or report the start state ``y`` of ``built``, as the module says."""
    p = built.params
    w = kernel.make_work(p)
    row = outputs.at(p, y, 0.0, w)
    _seabed(built, row)
    _above_water(built, w)
    _stretched(built, row)


def _seabed(built: BuiltSystem, row: outputs.Rows) -> None:
    p, depth = built.params, built.case.environment.water_depth
    if depth is None:
        return
    seabed = -float(depth)
    below = f"below the seabed (z = {seabed:g} m, environment.water_depth {depth:g} m)"
    for b, body in enumerate(built.case.bodies):
        z = float(row.bodies[0, b, 2])
        if p.body_kind[b] != kinematics.FIXED and z < seabed - SEABED_TOLERANCE:
            raise CaseError(
                f"bodies[{b}] ({body.name}): starts at z = {z:.6g} m, {below}, and a body has "
                "no seabed contact; start it above the seabed or deepen the water"
            )
    advice = "shorten it, raise its ends or deepen the water"
    contact = "give environment.seabed (the contact), " + advice
    kinds = [(built.layout.rigid, p.rs_n, row.rigid[0][0], "a rigid line has")]
    kinds.append((built.layout.natural, p.nat_n, row.rigid[4][0], "a natural string has"))
    if p.seabed_z < NO_SEABED:  # lumped lines without environment.seabed: no contact either
        kinds.append((built.layout.lines, p.line_n, row.nodes[0],
                       "without environment.seabed, a lumped line has"))  # fmt: skip
    for names, counts, nodes, what in kinds:
        at = 0
        for li, line in enumerate(names):
            n = int(counts[li])
            fix = contact if what.startswith("without") else advice
            _first_below(nodes[at : at + n + 1, 2], seabed, f"lines ({line})", below,
                         f"{what} no seabed contact; {fix}")  # fmt: skip
            at += n + 1


def _first_below(z: np.ndarray, seabed: float, where: str, below: str, why: str) -> None:
    deep = np.flatnonzero(z < seabed - SEABED_TOLERANCE)
    if deep.size:
        k = int(deep[0])
        raise CaseError(
            f"{where}: node {k} starts at z = {z[k]:.6g} m, {below} ({deep.size} of its "
            f"{z.size} nodes); {why}"
        )


def _above_water(built: BuiltSystem, w: kernel.SystemWork) -> None:
    """Bodies without a shape whose centre of buoyancy starts above z = 0 (``w``: the
    workspace filled at the start state)."""
    p = built.params
    if p.rho <= 0.0:  # in air: no water to be above
        return
    for b, body in enumerate(built.case.bodies):
        if not _point_volume(p, b, body):
            continue
        z = float(w.pos[b, 2] + w.rot[b, 2] @ p.body_cob[b])  # the centre of buoyancy's
        volume = float(p.body_volume[b])
        if z > 1e-6:
            counted = f"its volume ({volume:.4g} m^3)" if volume > 0.0 else "its added mass"
            raise CaseError(
                f"bodies[{b}] ({body.name}): its centre of buoyancy starts at z = {z:.6g} m, "
                f"above the water, where a body without a shape still counts {counted} "
                "wholly submerged; give it a shape (sphere, vertical_cylinder or table) that "
                "the surface cuts, or start it below z = 0"
            )


def _point_volume(p, b: int, body) -> bool:
    """Body ``b`` (``body`` in the case) is dynamic, without a shape, a hull mesh or a
    hydrodynamic database, and has a volume or an added mass of its own (its rods' follow their
    wetted parts): both counted wholly submerged wherever it is (a hull's added mass is the
    floating vessel's)."""
    if p.rho <= 0.0 or p.body_kind[b] != kinematics.DYNAMIC:
        return False
    own = np.any(np.asarray(getattr(body, "added_mass", 0.0), float) != 0.0)
    return bool(
        p.body_shape[b, 0] == surface.POINT
        and (p.body_volume[b] > 0.0 or own)
        and not np.any((p.force_body == b) & np.isin(p.force_kind, HULL_MODELS))
    )  # fmt: skip


def _stretched(built: BuiltSystem, row: outputs.Rows) -> None:
    p = built.params
    lines = []  # (name, strains, tensions, EA per segment)
    for li, line in enumerate(built.layout.lines):
        s0, n = int(p.line_seg[li]), int(p.line_n[li])
        stiffness = p.seg_stiffness[s0 : s0 + n]
        tension = row.tension[0, s0 : s0 + n]
        lines.append((line, tension / stiffness, tension, stiffness))
    strings, at = row.rigid[4][0], 0
    for li, line in enumerate(built.layout.natural):
        n = int(p.nat_n[li])
        strain, tension = strings[at : at + n + 1, 3], strings[at : at + n + 1, 4]
        lines.append((line, strain, tension, np.full(n + 1, float(p.nat_ea[li]))))
        at += n + 1
    for name, strain, tension, stiffness in lines:
        if not strain.size or not np.isfinite(strain).all():
            continue
        k = int(np.argmax(strain))
        if strain[k] <= LARGE_STRAIN:
            continue
        implied = (
            f"lines ({name}): its most stretched segment ({k}) starts at a strain of "
            f"{100 * strain[k]:.3g} %, a tension of {tension[k]:.4g} N (EA {stiffness[k]:.4g} N)"
        )
        if strain[k] > MOST_STRAIN:
            raise CaseError(
                f"{implied}: more stretch than a line takes; lengthen it, move its ends or "
                "lighten what it carries"
            )
        log.warning(f"{implied}; check its length, EA and what it carries")


def _resting_on_line_ends(p) -> set[int]:
    """The bodies at an end of a lumped line whose end node has seabed contact: the seabed holds
    them through it (a released line end, a clump weight on chain), at the depth that contact
    carries them, as it holds the line's nodes."""
    if p.seabed_z < NO_SEABED:
        return set()
    ends = [(int(p.line_from[li]), li, 0) for li in range(len(p.line_n))]
    ends += [(int(p.line_to[li]), li, 1) for li in range(len(p.line_n))]
    # a failure's point body takes the released ends
    ends += [(int(p.fail_point[k]), int(p.fail_line[k]), int(p.fail_end[k]))
             for k in range(len(p.fail_line))]  # fmt: skip
    return {
        int(p.point_body[point]) for point, li, end in ends
        if p.node_seabed_stiffness[int(p.line_node[li]) + end * int(p.line_n[li])] > 0.0
    }  # fmt: skip


class Watch:
    """What the start checks refuse, met during a run: a body (but one the seabed holds through
    a line's end node: ``_resting_on_line_ends``) or a contact-free node that goes below the
    seabed, a body without a shape whose centre of buoyancy rises above the
    water (its volume still counted submerged). Fed every chunk of output rows (``see``); says
    when each first happened (``warnings``). The run goes on: the rows up to then are sound."""

    def __init__(self, built: BuiltSystem):
        p, case = built.params, built.case
        depth = case.environment.water_depth
        self.seabed = None if depth is None else -float(depth) - SEABED_TOLERANCE
        self.first: dict[str, float] = {}
        self.below: list[tuple[str, str]] = []  # (variable, what)
        self.afloat: list[tuple[str, np.ndarray, str]] = []  # (group, cob, what)
        resting = _resting_on_line_ends(p)
        for b, body in enumerate(case.bodies):
            group = f"bodies/{body.name}"
            if p.body_kind[b] != kinematics.FIXED and b not in resting:
                self.below.append((f"{group}/position_z", f"body '{body.name}'"))
            if _point_volume(p, b, body):
                self.afloat.append((group, np.asarray(p.body_cob[b]), f"body '{body.name}'"))
        free = list(built.layout.rigid) + list(built.layout.natural)
        if p.seabed_z < NO_SEABED:
            free += list(built.layout.lines)
        self.below += [(f"lines/{line}/node_z", f"line '{line}'") for line in free]

    def see(self, rows: dict) -> None:
        times = rows["time"]
        if self.seabed is not None:
            for name, what in self.below:
                if name in rows and what + " below the seabed" not in self.first:
                    z = np.asarray(rows[name]).reshape(len(times), -1).min(axis=1)
                    self._first(what + " below the seabed", times, z < self.seabed)
        for group, cob, what in self.afloat:
            if what + " above the water" in self.first:
                continue
            roll, pitch = (np.radians(rows[f"{group}/{a}"]) for a in ("roll", "pitch"))
            # the third row of R = Rz(yaw) Ry(pitch) Rx(roll) (docs/conventions.md) times cob
            up = (-np.sin(pitch), np.cos(pitch) * np.sin(roll), np.cos(pitch) * np.cos(roll))
            z = rows[f"{group}/position_z"] + sum(r * c for r, c in zip(up, cob, strict=True))
            self._first(what + " above the water", times, z > SEABED_TOLERANCE)

    def _first(self, what: str, times: np.ndarray, met: np.ndarray) -> None:
        if met.any():
            self.first[what] = float(times[int(np.argmax(met))])

    def warnings(self) -> list[str]:
        """One line per thing met, with its first time."""
        out = []
        for what, t in self.first.items():
            why = (
                "no seabed contact holds it"
                if what.endswith("seabed")
                else "its volume still counts as wholly submerged: give it a shape"
            )
            out.append(f"{what} from t = {t:.6g} s, where {why}; rows after that are not sound")
        return out
