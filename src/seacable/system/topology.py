"""The graph of a system: bodies joined by lines and ties. A group of bodies joined to no fixed
or imposed body, with no restoring force of its own (a ``linear_stiffness``, or buoyancy of a
shape the free surface cuts, which holds heave alone), has no static equilibrium: the statics
refuses it, naming the bodies."""

from seacable.case import system as sch
from seacable.errors import CaseError


def groups(case: sch.SystemCase) -> list[list[str]]:
    """The names of the bodies of each connected group (lines and ties are the edges)."""
    parent = {body.name: body.name for body in case.bodies}

    def root(name: str) -> str:
        while parent[name] != name:
            parent[name] = parent[parent[name]]
            name = parent[name]
        return name

    for line in case.lines:
        a, b = line.from_.partition(".")[0], line.to.partition(".")[0]
        if a in parent and b in parent:
            parent[root(a)] = root(b)
    out: dict[str, list[str]] = {}
    for body in case.bodies:
        out.setdefault(root(body.name), []).append(body.name)
    return list(out.values())


def _holds(body) -> bool:
    if isinstance(body, sch.FixedBody | sch.ImposedBody):
        return True
    return any(isinstance(f, sch.LinearStiffness) for f in body.external_forces)


def check_held(case: sch.SystemCase) -> None:
    """Refuse a group of free bodies that nothing holds (for a static start)."""
    by_name = {body.name: body for body in case.bodies}
    for group in groups(case):
        if not any(_holds(by_name[name]) for name in group):
            raise CaseError(
                f"bodies {group}: a group that nothing holds (no fixed or imposed body among "
                "them and no linear_stiffness), so it has no static equilibrium; join it to a "
                "fixed body with a line or a tie, give one of them a linear_stiffness, or use "
                "start: as_given to let it drift"
            )
