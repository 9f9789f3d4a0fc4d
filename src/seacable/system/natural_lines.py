"""The natural-variables strings of a system (``model: natural_string``, lines.natural_string):
their checks, their flat arrays (SystemParams' ``nat_`` fields) and their initial state."""

import numpy as np

from seacable.case import system as sch
from seacable.errors import CaseError


def _strings(case: sch.SystemCase) -> list[tuple[int, sch.NaturalStringLine]]:
    return [(k, line) for k, line in enumerate(case.lines)
            if isinstance(line, sch.NaturalStringLine)]  # fmt: skip


def tips(case: sch.SystemCase) -> set[int]:
    """The bodies carried at the strings' ends (no state of their own), each checked: Poth's
    pendulum, a string in air from a fixed point to an end mass under gravity alone."""
    names = [body.name for body in case.bodies]
    out = set()
    for k, line in _strings(case):
        where = f"lines[{k}] ({line.name})"
        if not case.environment.in_air:
            raise CaseError(
                f"{where}.model: natural_string is Poth's string pendulum in air (gravity "
                "only); set environment.in_air: true, or use model: lumped_mass in water"
            )
        start, end = line.from_.partition(".")[0], line.to.partition(".")[0]
        if start not in names or end not in names:
            continue  # named by the points' resolution
        if not isinstance(case.bodies[names.index(start)], sch.FixedBody):
            raise CaseError(f"{where}.from: a natural_string hangs from a point of a fixed body; "
                            f"'{start}' is not fixed")  # fmt: skip
        body = case.bodies[names.index(end)]
        models = [spec.model for spec in getattr(body, "external_forces", [])]
        if not isinstance(body, sch.PointBody) or body.mass <= 0.0 or models != ["gravity"]:
            raise CaseError(
                f"{where}.to: a natural_string carries its end mass, a point body with mass > 0 "
                f"and gravity as its only force model; '{end}' is not one"
            )
        if "." in line.to:
            raise CaseError(f"{where}.to: the end mass is the body itself: write '{end}'")
        b = names.index(end)
        if b in out:
            raise CaseError(f"{where}.to: '{end}' is already carried by another natural_string")
        others = [other.name for other in case.lines if other is not line and end in
                  (other.from_.partition(".")[0], other.to.partition(".")[0])]  # fmt: skip
        if others:
            raise CaseError(
                f"{where}.to: the end mass '{end}' also holds {others}, whose forces a "
                "natural_string's end mass does not take (gravity only); hang the other lines "
                "elsewhere, or use model: lumped_mass"
            )
        out.add(b)
    return out


def table(case: sch.SystemCase, layout, point, q_at: int, v_at: int):
    """The strings' flat arrays (``point(ref, where)`` resolves a point), their node
    variables' initial values (from ``q_at`` on) and how many variables they add to the
    positions and to the velocities."""
    types = {t.name: t for t in case.line_types}
    names = [body.name for body in case.bodies]
    keys = ("nat_n", "nat_q", "nat_v", "nat_from", "nat_tip", "nat_cartesian", "nat_length",
            "nat_mu", "nat_ea", "nat_alpha")  # fmt: skip
    out: dict[str, list] = {key: [] for key in keys}
    initial: list[float] = []
    for k, line in _strings(case):
        where = f"lines[{k}] ({line.name})"
        section = line.sections[0]
        if section.type not in types:
            raise CaseError(f"{where}.sections[0].type: no line type '{section.type}'; "
                            f"line_types are {list(types)}")  # fmt: skip
        kind = types[section.type]
        if kind.axial_stiffness is None:
            raise CaseError(f"{where}.sections[0].type: line type '{kind.name}' has no "
                            "axial_stiffness; a natural_string needs EA [N]")  # fmt: skip
        joints = [key for key in ("joint_stiffness", "joint_damping") if getattr(section, key)]
        if joints:
            raise CaseError(f"{where}.sections[0].{joints[0]}: a natural_string has no joints; "
                            "leave it out")  # fmt: skip
        n = section.segments
        links = np.radians(line.initial.angles(n))
        if len(links) != n:
            raise CaseError(f"{where}.initial.angles_deg: {len(links)} angles for {n} segments")
        nodes = np.empty(n + 1)  # each node between two segments at their mean angle
        nodes[0], nodes[-1] = links[0], links[-1]
        nodes[1:-1] = 0.5 * (links[:-1] + links[1:])
        cartesian = line.tangent == "cartesian"
        block = np.zeros((n + 1, 3 if cartesian else 2))
        if cartesian:
            block[:, 1], block[:, 2] = np.sin(nodes), -np.cos(nodes)
        else:
            block[:, 1] = nodes
        layout.natural.append(line.name)
        out["nat_n"].append(n)
        out["nat_q"].append(q_at + len(initial))
        out["nat_v"].append(v_at + len(initial))
        out["nat_from"].append(point(line.from_, f"{where}.from"))
        out["nat_tip"].append(names.index(line.to))
        out["nat_cartesian"].append(1 if cartesian else 0)
        out["nat_length"].append(float(section.length))
        out["nat_mu"].append(float(kind.mass_per_length))
        out["nat_ea"].append(float(kind.axial_stiffness))
        out["nat_alpha"].append(float(kind.axial_damping_time or 0.0))
        initial += block.ravel().tolist()
    arrays = {key: np.array(values, dtype=float) for key, values in out.items()}
    return arrays, initial


def hanging(p, y: np.ndarray) -> np.ndarray:
    """``y`` with every string hanging straight down from its pivot at rest, each node's strain
    the weight below it (the string's and its end mass's) over EA: the statics of Poth's
    pendulum (gravity alone; system.statics starts its Newton there). The discrete equations
    (kernels.natural) balance this exactly: their tension's second difference is zero between
    the ends, and the boundary rows give the slope mu g and the end value m g."""
    out = y.copy()
    for li in range(len(p.nat_n)):
        n, q, v = int(p.nat_n[li]), int(p.nat_q[li]), int(p.nat_v[li])
        width = 3 if p.nat_cartesian[li] else 2
        s = np.linspace(0.0, float(p.nat_length[li]), n + 1)
        below = p.nat_mu[li] * (p.nat_length[li] - s) + p.body_mass[int(p.nat_tip[li])]
        block = np.zeros((n + 1, width))
        block[:, 0] = p.gravity * below / p.nat_ea[li]
        if width == 3:
            block[:, 2] = -1.0  # t = (0, -1): down
        out[q : q + width * (n + 1)] = block.ravel()
        out[v : v + width * (n + 1)] = 0.0
    return out
