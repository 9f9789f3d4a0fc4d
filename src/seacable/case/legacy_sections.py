"""The sections of the lines ``seacable upgrade`` writes (``case.legacy``): a single cable's
links as runs of equal segments (a section per run of links of one length, one mass per length
and the same joints), its line types (one per mass per length) and its joints' springs and
dampers.

A joint i of the single cable lies between link i - 1 (or the top) and link i; in the system
form it is the joint at the start of segment i, which a section's ``joint_stiffness`` and
``joint_damping`` give when the line type's EI (over the mean span) and the line's damping
cannot: one value per joint, or a spring on links of unequal lengths. Where the cable is cut
at a body along it (``point_bodies``), the lines meet at the body with no joint between them:
that joint must have no spring and no damper.
"""

import math
from typing import Any

import numpy as np

from seacable.case import schema


def mass_per_length(cable: schema.Cable, lengths: np.ndarray) -> np.ndarray:
    """Each link's mass per length [kg/m], with the arithmetic that gives the single cable's
    link masses back (mu l)."""
    if cable.mass_per_length is not None:
        return np.full(len(lengths), cable.mass_per_length)
    if cable.density is not None:
        return np.full(len(lengths), cable.density * math.pi * cable.diameter**2 / 4)
    return cable.masses() / lengths  # link_masses


def joints(cable: schema.Cable, lengths: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each joint's spring [N m/rad] and damper [N m s/rad] as the single-cable model has them
    (``bending_stiffness`` EI: EI over the mean length of the joint's two links, the first over
    the first link)."""
    n = len(lengths)
    given = cable.joint_stiffness
    if given is not None:
        springs = np.asarray(given, dtype=float) if isinstance(given, list) else np.full(n, given)
    elif cable.bending_stiffness is not None:
        spans = np.concatenate([[lengths[0]], 0.5 * (lengths[1:] + lengths[:-1])])
        springs = cable.bending_stiffness / spans
    else:
        springs = np.zeros(n)
    damping = cable.joint_damping
    dampers = np.asarray(damping, dtype=float) if isinstance(damping, list) else np.full(n, damping)
    return springs.astype(float), dampers.astype(float)


def _product(quotient: float, divisor: float) -> float:
    """x near quotient * divisor with x / divisor == quotient to the last bit (or that product):
    an EI whose joint stiffness EI / l is k, a section length whose segments are l."""
    x = float(quotient * divisor)
    for _ in range(8):
        if x / divisor == quotient:
            return x
        x = float(np.nextafter(x, np.inf if x / divisor < quotient else -np.inf))
    return float(quotient * divisor)


class Plan:
    """How a cable's links become the sections of its lines: its line types (``types``), each
    link's type name, and whether its joints go into the line types' EI and the lines' damping
    or into the sections (``per_joint_springs``, ``per_joint_dampers``)."""

    def __init__(self, cable: schema.Cable, base: dict[str, Any], cuts: list[int], where: str,
                 reverse: bool = False):  # fmt: skip
        """``base``: the line type's fields but its name, mass per length and EI; ``cuts``: the
        links' indices where the lines start and end (0, the bodies' nodes along the cable,
        the number of links); ``reverse``: the lines run from the cable's end to its top (a
        star's), where the line ends held on the top (its joint 0 is the line's tip joint) and
        each joint sits at the start of the segment below it."""
        self.cable, self.where, self.reverse = cable, where, reverse
        self.lengths = cable.lengths()
        self.springs, self.dampers = joints(cable, self.lengths)
        mu = mass_per_length(cable, self.lengths)
        equal = len(set(self.lengths.tolist())) == 1
        # the type's EI gives the single cable's springs exactly: EI over the mean span, or a
        # joint stiffness k on equal links as the EI k l
        from_bending = cable.bending_stiffness is not None or (
            not isinstance(cable.joint_stiffness, list) and equal
        )
        self.per_joint_springs = bool(np.any(self.springs)) and (
            len(cuts) > 2 or not from_bending or reverse
        )
        self.per_joint_dampers = len(set(self.dampers.tolist())) > 1
        bending = 0.0
        if np.any(self.springs) and not self.per_joint_springs:
            bending = (
                cable.bending_stiffness
                if cable.bending_stiffness is not None
                else _product(float(self.springs[0]), float(self.lengths[0]))  # one k, equal links
            )
        self.types: list[dict[str, Any]] = []
        names: dict[float, str] = {}
        for value in mu.tolist():
            if value not in names:
                count = len(names)
                names[value] = f"{cable.name} type" + (f" {count + 1}" if count else "")
                line_type = {"name": names[value], "diameter": base["diameter"],
                             "mass_per_length": float(value)}  # fmt: skip
                if bending:
                    line_type["bending_stiffness"] = float(bending)
                line_type.update({k: v for k, v in base.items() if k not in line_type})
                self.types.append(line_type)
        self.type_of = [names[value] for value in mu.tolist()]

    def sections(self, first: int, last: int) -> list[dict[str, Any]]:
        """The sections of the line over links ``first`` .. ``last`` - 1 (run from its end to
        its start when the plan is ``reverse``: link i's joint is then the one below it, i + 1,
        none below the last link)."""
        links = range(first, last)
        if self.reverse:
            links = links[::-1]
        n = len(self.lengths)
        runs: list[list] = []
        for i in links:
            joint = (i + 1 if i + 1 < n else None) if self.reverse else i
            spring = float(self.springs[joint]) if joint is not None else 0.0
            damper = float(self.dampers[joint]) if joint is not None else 0.0
            key = (float(self.lengths[i]), self.type_of[i],
                   spring if self.per_joint_springs else None,
                   damper if self.per_joint_dampers else None)  # fmt: skip
            if runs and runs[-1][0] == key:
                runs[-1][1] += 1
            else:
                runs.append([key, 1])
        out = []
        for (length, name, spring, damper), count in runs:
            section: dict[str, Any] = {"type": name, "segments": count,
                                       "length": _product(length, count)}  # fmt: skip
            if spring is not None:
                section["joint_stiffness"] = spring
            if damper is not None:
                section["joint_damping"] = damper
            out.append(section)
        return out

    def line_damping(self, first: int) -> float:
        """The line's joint damping [N m s/rad] (every joint's when they are alike; the sections
        give it otherwise)."""
        if self.per_joint_dampers:
            return 0.0
        return float(self.dampers[first])
