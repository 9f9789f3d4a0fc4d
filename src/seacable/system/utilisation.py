"""Each line section's largest tension against its line type's breaking strength (the
utilisation a mooring designer checks against a safety factor), from a run's or a statics'
tensions, and the warning at the start of a run when a section's static tension already
exceeds the case's ``utilisation_limit`` of it."""

from typing import NamedTuple

import numpy as np

from seacable.case import system as sch
from seacable.lines.lumped_mass import T_ROW
from seacable.system import kernel


class SectionLoad(NamedTuple):
    line: str
    section: int  # 0 first, from the line's ``from`` end
    line_type: str
    largest_tension: float  # [N], over the section's segments (and the run's times)
    breaking_strength: float | None  # [N]
    utilisation: float | None  # largest_tension / breaking_strength


def sections(case: sch.SystemCase, line) -> list[tuple[int, str, int, int, float | None]]:
    """A line's sections: (index, type, first segment, segments, breaking strength [N] or
    None)."""
    types = {t.name: t for t in case.line_types}
    out, first = [], 0
    for k, section in enumerate(line.sections):
        out.append((k, section.type, first, section.segments,
                    types[section.type].breaking_strength))  # fmt: skip
        first += section.segments
    return out


def section_loads(case: sch.SystemCase, tensions: dict[str, np.ndarray]) -> list[SectionLoad]:
    """Every section of the lines named in ``tensions`` (each line's tension [N], time by
    segment, or time alone for a natural string): its largest tension and utilisation."""
    out = []
    for line in case.lines:
        if line.name not in tensions:
            continue
        tension = np.asarray(tensions[line.name], dtype=float)
        tension = tension.reshape(tension.shape[0], -1) if tension.ndim else tension.reshape(1, 1)
        for k, kind, first, count, strength in sections(case, line):
            part = tension[:, first : first + count] if tension.shape[1] > 1 else tension
            finite = part[np.isfinite(part)]
            largest = float(finite.max()) if finite.size else float("nan")
            share = largest / strength if strength else None
            out.append(SectionLoad(line.name, k, kind, largest, strength, share))
    return out


def start_warnings(case: sch.SystemCase, p: kernel.SystemParams, y: np.ndarray) -> list[str]:
    """One line per lumped line section whose tension at the state ``y`` (a run's start)
    exceeds ``utilisation_limit`` of its breaking strength."""
    lumped = [line for line in case.lines if isinstance(line, sch.LumpedMassLine)]
    if not any(s[4] for line in lumped for s in sections(case, line)):
        return []
    w = kernel.make_work(p)
    kernel.rhs(0.0, y, p, w, np.zeros_like(y))
    tensions = {}
    for li, line in enumerate(lumped):
        first = p.line_node[li]
        tensions[line.name] = w.nodes[T_ROW, first : first + p.line_n[li]][None, :].copy()
    out = []
    for load in section_loads(case, tensions):
        if load.utilisation is not None and load.utilisation > case.utilisation_limit:
            out.append(
                f"lines ({load.line}) section {load.section + 1} ({load.line_type}): its "
                f"tension at the start, {load.largest_tension / 1e3:.4g} kN, is "
                f"{100 * load.utilisation:.3g} % of its breaking strength, above "
                f"utilisation_limit {case.utilisation_limit:g}; lengthen or strengthen the "
                "line, or raise the limit"
            )
    return out


def report(loads: list[SectionLoad]) -> list[str]:
    """The lines the command line prints: each section with a breaking strength."""
    return [
        f"line {load.line} section {load.section + 1} ({load.line_type}): largest tension "
        f"{load.largest_tension / 1e3:.4g} kN, {100 * load.utilisation:.3g} % of its breaking "
        f"strength {load.breaking_strength / 1e3:.4g} kN"
        for load in loads
        if load.utilisation is not None and load.breaking_strength is not None
    ]
