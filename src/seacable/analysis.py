"""Analyses built on a case's dynamics: the natural modes of a system of bodies and lines about
its static equilibrium, and its statics."""

import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

from seacable import natural_periods
from seacable.case import loader
from seacable.case.system import SystemCase
from seacable.errors import CaseError, memory_check
from seacable.kernels.status import Status
from seacable.numerics import stability
from seacable.results import (
    STATUS_COMPLETE,
    STATUS_DIVERGED,
    Results,
    _Sink,
    check_output,
    provenance,
    restore_case,
)
from seacable.system import model as system_model
from seacable.system import statics as system_statics
from seacable.system import utilisation
from seacable.system.utilisation import SectionLoad


def system_modes(case: SystemCase, count: int = 12, allow_large: bool = False) -> xr.Dataset:
    """The natural modes of a system of bodies and lines about its static equilibrium.

    The rates of every free degree of freedom (a body's free translations and rotations, every
    line node) are linearised by central differences of the compiled right-hand side
    (``system.statics.jacobian``; rotations as small rotation vectors in the earth frame), and
    the eigenvalues of the first-order system give each mode's frequency and damping. The
    ``count`` slowest oscillatory modes are returned, slowest first; a mode that a body with a
    hydrodynamic database moves most has its period at its own frequency's added mass A(w)
    (iterated), the radiation memory's poles are listed apart, and a floating body that
    nothing holds has its equilibrium in heave, roll and pitch and its other degrees of freedom
    listed as free, without restoring (``seacable.natural_periods``).

    Returns
    -------
    xarray.Dataset
        ``period`` [s] = 2 pi / |Im lambda| (2 pi / w for a period at A(w), inf for a free
        degree of freedom), ``frequency`` |lambda| [rad/s] (undamped equivalent),
        ``damping_ratio`` -Re(lambda) / |lambda| (dimension ``mode``), ``method`` how each was
        found (``linearised``, ``A(w) iterated``, ``free (no restoring)``, ``memory pole``), and
        ``shape`` (``mode``, ``coordinate``): the position part of each mode, real part with the
        largest component 1 (zero for the free and memory rows); coordinate names
        ``body:surge`` ... ``body:yaw`` and ``line:node k:x``; ``dominant`` names each mode's
        largest body coordinate (or line; ``body:radiation memory`` for a memory pole).

    The eigenvalues are those of the whole dense matrix, which holds about 48 m^2 bytes for
    m rates (500 segments: 0.47 GB measured, 1,000: 1.9 GB in 87 s); beyond
    ``errors.MEMORY_BUDGET`` the case is refused unless ``allow_large``.
    """
    if not isinstance(case, SystemCase):
        raise CaseError("modes: give a case with bodies: and lines: (a system)")
    axial = stability.axial_bound(case)  # before the build and its statics: the lines' rates
    rates = (axial.states if axial is not None else 0) + 12 * len(case.bodies)
    segments = sum(s.segments for line in case.lines for s in getattr(line, "sections", []))
    memory_check(
        f"modes: the {rates:,} rates of this system ({segments:,} line segments) make a dense "
        "matrix whose eigenvalues grow in memory with the square of the segments (in time "
        "with the cube)",
        48.0 * rates**2,
        "use fewer segments for the modes (the slowest hardly depend on them: --set "
        "lines.NAME.sections[0].segments=...)",
        allow_large,
    )
    state = natural_periods.equilibrium(case)
    built = state.built
    a, coords = system_statics.jacobian(built, state.y)
    names = _coordinate_names(built, coords)
    # each coordinate's share of the mode's kinetic energy ranks it (a rotation in rad and a
    # translation in m compare through the body's inertia and mass)
    weight = np.sqrt(_inertia_diagonal(built, coords))
    found = natural_periods.find(state, a, coords, weight, count)
    shapes = found.shape
    dominant = [names[c].split(":node")[0] if c >= 0 else named
                for c, named in zip(found.coordinate, found.named, strict=True)]  # fmt: skip
    lam, natural = found.value, found.natural
    with np.errstate(divide="ignore", invalid="ignore"):
        period = np.where(natural > 0.0, 2 * np.pi / natural, np.inf)
        damping = np.where(np.abs(lam) > 0.0, -lam.real / np.abs(lam), np.nan)
    return xr.Dataset(
        {
            "period": ("mode", period, {"units": "s", "long_name":
                       "period: 2 pi / |Im lambda| (linearised, memory pole), 2 pi / w at "
                       "A(w) (A(w) iterated), inf (free)"}),
            "frequency": ("mode", np.abs(lam), {"units": "rad/s",
                          "long_name": "undamped-equivalent angular frequency |lambda|"}),
            "damping_ratio": ("mode", damping, {"units": "1",
                              "long_name": "-Re(lambda) / |lambda|"}),
            "shape": (("mode", "coordinate"), shapes.real, {"units": "1",
                      "long_name": "position part of the mode, largest component 1"}),
            "dominant": ("mode", np.array(dominant, dtype=object), {"units": "1",
                         "long_name": "the body coordinate (or line) the mode moves most"}),
            "method": ("mode", np.array(found.method, dtype=object), {"units": "1",
                       "long_name": "how the period is found: linearised, A(w) iterated, "
                       "memory pole, free (no restoring)"}),
        },
        coords={"coordinate": names},
    )  # fmt: skip


def _inertia_diagonal(built, coords) -> np.ndarray:
    """Mass (or moment of inertia about the reference point, added parts included) of each
    coordinate [kg, kg m^2]."""
    p = built.params
    out = np.empty(len(coords.kind))
    for i, (kind, body, axis) in enumerate(zip(coords.kind, coords.body, coords.axis, strict=True)):
        if kind == 2:
            line = int(coords.line[i])
            node = int(p.line_node[line]) + (int(coords.q[i]) - int(p.line_q[line])) // 3 + 1
            out[i] = p.node_mass[node]
        elif kind >= 5:  # a natural string's node: its share of the string's mass
            line = int(coords.line[i])
            out[i] = p.nat_mu[line] * p.nat_length[line] / p.nat_n[line]
        elif kind >= 3:  # a rigid line's segment: its moment of inertia about its centre
            line = int(coords.line[i])
            width = 3 if kind == 3 else 1
            segment = int(p.rs_seg[line]) + (int(coords.q[i]) - int(p.rs_q[line])) // width
            out[i] = p.rs_inertia[segment]
        elif kind == 0:
            out[i] = p.body_mass[body] + p.body_added[body, axis, axis]
        else:
            arm = p.body_cog[body].copy()
            arm[axis] = 0.0
            out[i] = (p.body_inertia[body, axis, axis] + p.body_mass[body] * arm @ arm
                      + p.body_added[body, 3 + axis, 3 + axis])  # fmt: skip
    return np.maximum(out, 1e-12)


def _coordinate_names(built, coords) -> list[str]:
    translations, rotations = ("surge", "sway", "heave"), ("roll", "pitch", "yaw")
    names = []
    for kind, body, axis, q, line in zip(
        coords.kind, coords.body, coords.axis, coords.q, coords.line, strict=True
    ):
        if kind == 2:
            name = built.layout.lines[int(line)]
            node = (int(q) - int(built.params.line_q[line])) // 3 + 1
            names.append(f"{name}:node {node}:{'xyz'[int(axis)]}")
        elif kind >= 5:
            width = 3 if kind == 7 else 2
            node = (int(q) - int(built.params.nat_q[line])) // width
            what = "strain" if kind == 5 else "angle"
            names.append(f"{built.layout.natural[int(line)]}:node {node}:{what}")
        elif kind >= 3:
            name = built.layout.rigid[int(line)]
            width = 3 if kind == 3 else 1
            segment = (int(q) - int(built.params.rs_q[line])) // width
            turn = ("t1", "t2")[int(axis)] if kind == 3 else "angle"
            names.append(f"{name}:segment {segment}:{turn}")
        else:
            dof = (rotations if kind == 1 else translations)[int(axis)]
            names.append(f"{built.case.bodies[int(body)].name}:{dof}")
    return names


def statics(case: SystemCase, output=None) -> Results:
    """The static equilibrium of a system (``start: static`` whatever the case says): every
    free body and line at rest in balance under its force models, gravity, buoyancy and the
    steady current, as one output row at t = 0 (the same groups and variables as a run).

    Raises
    ------
    CaseError
        ``case`` is not a system of bodies and lines (a case with ``lines:``).
    StaticsError
        No equilibrium found; the message names the body or line out of balance.
    """
    if not isinstance(case, SystemCase):
        raise CaseError(
            "statics: the case is a single cable (cables:); statics of the whole system need "
            "a case with bodies: and lines:"
        )
    if output is not None:  # refused before the statics, not after
        check_output(Path(output), loader.files_read(case))
    derived = loader.derive_case(case, {"start": "static"})
    assert isinstance(derived, SystemCase)  # derive_case keeps the form
    case = derived
    system = system_model.build(case, loader.case_base_dir(case))
    attrs = provenance(loader.case_text(case), {"analysis": "statics"})
    attrs.update(loader.record(case))
    sink = _Sink(
        output, system_model.sizes(system), system_model.coords(system),
        system_model.variables(system), attrs, inputs=loader.files_read(case),
    )  # fmt: skip
    y0 = system.y0.copy()
    y0[system.params.n_q :] = 0.0
    rows, status = system_model.rows(
        np.array([0.0]), y0[None, :], system, system_model.workspace(system)
    )
    sink.write(rows)
    if status != Status.OK:
        return sink.finish(STATUS_DIVERGED, "the equilibrium's forces are not finite", {})
    return sink.finish(STATUS_COMPLETE, "static equilibrium", {})


def line_utilisation(results: Results, case: SystemCase | None = None) -> list[SectionLoad]:
    """Each line section's largest tension in ``results`` (over its output times and the
    section's segments) and its share of the line type's breaking strength (None without
    one). ``case``: the case the results are of; by default the one they were run from
    (their ``case`` attribute, with the files it read)."""
    if case is None:
        with tempfile.TemporaryDirectory() as folder:
            case = loader.load_case(restore_case(results.dataset.attrs, folder))
    tensions = {}
    for name, node in results.dataset["lines"].children.items():
        ds = node.to_dataset()
        if "tension" in ds:
            tensions[name] = ds["tension"].values
    return utilisation.section_loads(case, tensions)
