"""Golden results of every example, and the comparison of a run to them.

Each example was shortened to a 1 s run and integrated with its own integrator at settings tight
enough that the results are the physics of the model, not of the step: a fixed-step scheme's
step halved, an adaptive scheme's rtol divided by 10, until one more refinement changed no
variable by more than 1e-11 of its scale. The recorded file (``tests/golden/<example>.nc.gz``)
holds every variable and coordinate of that run, the case changes that derive it from the
example (attribute ``golden_changes``, JSON) and the change measured on the last refinement
(``golden_refinement_change``: the estimated discretisation error, a fraction of each
variable's scale), and where measured how far round-off alone moves each variable
(``golden_roundoff_change``; a comparison then allows twice that where it exceeds 1e-9). A run
of the example with the same integrator at these settings must match within 1e-9 of each
variable's scale (:func:`compare_to_golden`).

The goldens were recorded by the single-cable core (``cables:`` with ``top`` and ``bottom``),
retired after commit 4911bc8: they are frozen. Each example is now a system of bodies and lines
(``seacable upgrade``); its run is compared through :func:`system_rows`, which names the
system's variables as the single-cable model named them (``lines/<line>/from_force_x`` was
``top_force_x``, the top body's height was ``top_heave``). To re-record a golden, check that
commit out (``git worktree add /tmp/old 4911bc8``) and run there, from its root::

    PYTHONPATH=src python tests/golden/record.py [example stems...]
    PYTHONPATH=src python tests/golden/record.py --roundoff [example stems...]
"""

import gzip
import io
import json
import sys
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import xarray as xr

import seacable
from seacable.case.loader import derive_case

GOLDEN = Path(__file__).resolve().parent
EXAMPLES = GOLDEN.parent.parent / "examples"
DURATION = 1.0  # [s] of every golden run
MIN_ROWS = 5  # an example's output interval is kept when it gives at least this many rows
SHORT_INTERVAL = 0.1  # [s] output interval otherwise
TOLERANCE = 1e-9  # a run matches its golden result within this fraction of each scale
# ... or within twice the change round-off alone makes (``roundoff_changes``), where that is
# larger: an ill-conditioned variable (measured, and written in the golden file)
ROUNDOFF = "golden_roundoff_change"
ROUNDOFF_MARGIN = 2.0
# a variable is measured against at least this fraction of the largest of the variables in its
# units: one that is nearly zero by the physics (the velocity of a huge end mass that stands for
# a pin) has round-off errors that are large against its own magnitude but not against the
# motion, and another formulation need not reproduce them
UNITS_FLOOR = 1e-3
# one whose largest magnitude is below this fraction of its units' largest (a force component
# zero by symmetry, a pinned end's velocity: round-off) is measured against that largest one
ROUND_OFF = 1e-9
# variables of these units are all measured against the largest of them: the energies are terms
# of one balance, and the total (nearly constant, possibly near zero) is a sum of the others
SHARED_SCALE_UNITS = ("J",)


def example_path(stem: str) -> Path:
    return EXAMPLES / f"{stem}.yaml"


def example_stems() -> list[str]:
    """The examples with a golden file: recorded from the single-cable form before the system
    of bodies and lines replaced it; the examples written as systems from the start are checked
    against MoorPy and closed forms instead (tests/test_system*.py)."""
    return sorted(p.name.removesuffix(".nc.gz") for p in GOLDEN.glob("*.nc.gz"))


def golden_path(stem: str) -> Path:
    """NetCDF-3 (classic, 64-bit offsets), gzip-compressed: a third of the size of NetCDF-4's
    HDF5 for these small files; ``gunzip -k`` gives a file any NetCDF tool reads."""
    return GOLDEN / f"{stem}.nc.gz"


def output_interval(interval: float) -> float:
    """The example's output interval [s] if it divides DURATION into MIN_ROWS or more rows,
    else SHORT_INTERVAL."""
    count = DURATION / interval
    if abs(count - round(count)) < 1e-9 * count and round(count) >= MIN_ROWS:
        return interval
    return SHORT_INTERVAL


def derived(stem: str, changes: Mapping):
    """The example's case with ``changes`` (a nested mapping of case keys, as
    :func:`seacable.case.loader.derive_case` takes) applied through the loader's validation.
    The single-cable keys are dropped (``cables``: the servo's step, kept at the example's
    while the time step was refined, is written in the system example). A seabed is the
    plain spring the goldens were recorded with (``contact_band`` 0)."""
    case = seacable.load_case(example_path(stem))
    changes = {key: value for key, value in changes.items() if key != "cables"}
    if case.environment.seabed is not None:
        assert "environment" not in changes
        changes["environment"] = {"seabed": {"contact_band": 0.0}}
    return derive_case(case, changes)


def run(stem: str, changes: Mapping) -> dict:
    """The example's results under the single-cable names (the mapping of :func:`system_rows`,
    or of :func:`star_rows` for lines from one body)."""
    case = derived(stem, changes)
    results = seacable.simulate(case)
    if results.status != "complete":
        raise RuntimeError(f"{stem} with {dict(changes)}: {results.status}: {results.message}")
    if sum(line.from_ == case.bodies[0].name for line in case.lines) > 1:
        return star_rows(results.dataset, case)
    return system_rows(results.dataset, case)


def star_rows(tree, case) -> dict:
    """A star (an upgraded case of cables from their tops to the body they share, the first
    body: each cable lines from that body back to its top, through the bodies along it) under
    the single-cable star's names: per cable, from its top, ``node_*``, ``tension`` and
    ``angular_rate`` (cable, node or segment), its top's load as ``top_force_*``, the shared
    body's position and velocity as ``body_*`` and ``body_velocity_*``."""
    shared = case.bodies[0].name
    out: dict = {}
    chains = []
    for first in (line for line in case.lines if line.from_ == shared):
        chain = [first]
        while True:
            following = [line for line in case.lines if line.from_ == chain[-1].to]
            if not following:
                break
            chain.append(following[0])
        chains.append([tree[f"lines/{line.name}"].to_dataset() for line in chain][::-1])
    for name in ("node_x", "node_y", "node_z", "tension", "angular_rate"):
        per_cable = []
        for chain in chains:
            parts = [line[name].values[:, ::-1] for line in chain]
            if name.startswith("node_"):
                parts = parts[:1] + [part[:, 1:] for part in parts[1:]]
            per_cable.append(np.concatenate(parts, axis=1))
        out[name] = np.stack(per_cable, axis=1)
    body = tree[f"bodies/{shared}"].to_dataset()
    for c in "xyz":
        out[f"top_force_{c}"] = np.stack([chain[0][f"to_force_{c}"].values for chain in chains],
                                         axis=1)  # fmt: skip
        out[f"body_{c}"] = body[f"position_{c}"].values
        out[f"body_velocity_{c}"] = body[f"velocity_{c}"].values
    out["time"] = tree["time"].values
    spans = np.concatenate([np.diff(line["arc_length"].values)[::-1] for line in chains[0]])
    out["arc_length"] = np.concatenate([[0.0], np.cumsum(spans)])  # from the top (all alike)
    return out


def system_rows(tree, case) -> dict:
    """A system of lines end to end between two bodies (an upgraded single-cable example: its
    cable, cut at the bodies along it) under the single-cable model's names: the lines'
    variables joined along the cable, its end forces as ``top_force_*`` and ``bottom_force_*``,
    the first body's height and velocities as ``top_heave``, ``top_heave_velocity`` and
    ``top_velocity_*`` (zero for a fixed body), the second body's velocities as
    ``bottom_velocity_*`` and, when it is held on some axes, its start as ``target_*`` and its
    distance from it as ``tracking_error``; the energies; the coordinates ``time`` and
    ``arc_length``."""
    lines = [tree[f"lines/{line.name}"].to_dataset() for line in case.lines]
    top, end = (tree[f"bodies/{body.name}"].to_dataset() for body in case.bodies[:2])
    zeros = np.zeros(tree["time"].size)
    out = {}
    for name in dict.fromkeys(name for line in lines for name in line.data_vars):
        if name.startswith(("from_", "to_")):
            continue
        if any(name not in line for line in lines):  # a held end's: the line that ends there
            out[name] = [line for line in lines if name in line][-1][name].values
            continue
        parts = [line[name].values for line in lines]
        if lines[0][name].dims[-1] == "node":
            parts = parts[:1] + [part[:, 1:] for part in parts[1:]]  # each line's node 0: the last
        out[name] = np.concatenate(parts, axis=-1) if parts[0].ndim > 1 else parts[0]
    for c in "xyz":
        if f"from_force_{c}" in lines[0]:  # a natural string reports none
            out[f"top_force_{c}"] = lines[0][f"from_force_{c}"].values
            out[f"bottom_force_{c}"] = lines[-1][f"to_force_{c}"].values
        out[f"top_velocity_{c}"] = top[f"velocity_{c}"].values if f"velocity_{c}" in top else zeros
        out[f"bottom_velocity_{c}"] = (
            end[f"velocity_{c}"].values if f"velocity_{c}" in end else zeros
        )
    out["top_heave"] = top["position_z"].values
    out["end_x"], out["end_z"] = end["position_x"].values, end["position_z"].values
    out["top_heave_velocity"] = out["top_velocity_z"]
    held = getattr(case.bodies[1], "dofs", ["surge", "sway", "heave"]) != ["surge", "sway", "heave"]
    position = np.column_stack([end[f"position_{c}"].values for c in "xyz"])
    if case.bodies[1].type == "point" and held:
        target = np.asarray(case.bodies[1].position)[None, :] + 0.0 * position
        tracking = np.linalg.norm(position - target, axis=1)
    elif case.bodies[1].type == "imposed":  # a trajectory: the line's end is held on it
        target = position
        tip = np.column_stack([out[f"node_{c}"][:, -1] for c in "xyz"])
        tracking = np.linalg.norm(tip - target, axis=1)
    if case.bodies[1].type == "imposed" or (case.bodies[1].type == "point" and held):
        for c, axis in enumerate("xyz"):
            out[f"target_{axis}"] = target[:, c]
        out["tracking_error"] = tracking
    if "servo_force_x" in end:  # the servo's end: its force, target and error
        for name in ("servo_force_x", "servo_force_y", "servo_force_z", "target_x", "target_y",
                     "target_z", "tracking_error"):  # fmt: skip
            out[name] = end[name].values
    for name in ("kinetic_energy", "gravity_potential_energy", "elastic_energy", "total_energy"):
        out[name] = tree[name].values
    out["time"] = tree["time"].values
    out["arc_length"] = np.concatenate(
        [lines[0]["arc_length"].values]
        + [
            line["arc_length"].values[1:]
            + sum(float(x["arc_length"].values[-1]) for x in lines[: k + 1])
            for k, line in enumerate(lines[1:])
        ]
    )
    return out


def variable_scales(golden: xr.Dataset) -> dict[str, float]:
    """Scale of each variable: its largest finite magnitude over the run, at least UNITS_FLOOR
    times the largest among the variables of its units (all of that largest for
    SHARED_SCALE_UNITS and when below ROUND_OFF of it). The units scale of a rate of turn
    [rad/s] is at least the largest velocity [m/s] over the shortest link (a line in its steady
    state turns at round-off rates only)."""
    own = {}
    for name, variable in golden.data_vars.items():
        values = np.abs(variable.values[np.isfinite(variable.values)])
        own[name] = float(values.max()) if values.size else 0.0
    by_units: dict[str, float] = {}
    for name, scale in own.items():
        units = golden[name].attrs.get("units", "")
        by_units[units] = max(by_units.get(units, 0.0), scale)
    if "rad/s" in by_units and "m/s" in by_units and "link_length" in golden.coords:
        turn = by_units["m/s"] / float(golden["link_length"].min())
        by_units["rad/s"] = max(by_units["rad/s"], turn)
    scales = {}
    for name, scale in own.items():
        units = golden[name].attrs.get("units", "")
        group = by_units[units]
        shared = units in SHARED_SCALE_UNITS or scale < ROUND_OFF * group
        scales[name] = group if shared else max(scale, UNITS_FLOOR * group)
    return scales


def relative_errors(
    golden: xr.Dataset, actual: Mapping, names: Mapping[str, str] | None = None
) -> dict[str, tuple[float, tuple, float, float]]:
    """For each golden variable: (largest error as a fraction of its scale, index of the worst
    element, golden value there, actual value there). ``actual`` maps names to arrays (an
    xarray Dataset does); ``names`` maps actual names to golden ones (default: the same names).
    A NaN in one and not the other counts as an infinite error; a golden variable with no
    actual counterpart as a NaN error."""
    names = dict(names) if names is not None else {name: name for name in golden.data_vars}
    old_to_new = {old: new for new, old in names.items()}
    scales = variable_scales(golden)
    errors = {}
    for name in golden.data_vars:
        reference = golden[name].values
        if name not in old_to_new or old_to_new[name] not in actual:
            errors[name] = (float("nan"), (), float("nan"), float("nan"))
            continue
        values = np.asarray(actual[old_to_new[name]], dtype=float)
        if values.shape != reference.shape:
            errors[name] = (float("inf"), values.shape, float("nan"), float("nan"))
            continue
        scale = scales[name] if scales[name] > 0.0 else 1.0
        error = np.abs(values - reference) / scale
        mismatch = np.isnan(values) != np.isnan(reference)
        error = np.where(np.isnan(reference) & np.isnan(values), 0.0, error)
        error = np.where(mismatch, np.inf, error)
        worst = np.unravel_index(int(np.argmax(error)), error.shape) if error.size else ()
        worst_error = float(error[worst]) if error.size else 0.0
        errors[name] = (worst_error, worst, float(reference[worst]), float(values[worst]))
    return errors


def compare_to_golden(
    golden: xr.Dataset,
    actual: Mapping,
    names: Mapping[str, str] | None = None,
    tolerance: float = TOLERANCE,
    label: str = "",
) -> list[str]:
    """One line per golden variable that ``actual`` does not match within ``tolerance`` of the
    variable's scale (empty: all match), naming the example, the variable, the worst index, the
    two values and the error. Arguments as :func:`relative_errors`."""
    failures = []
    for name, (error, index, expected, got) in relative_errors(golden, actual, names).items():
        allowed = max(tolerance, ROUNDOFF_MARGIN * golden[name].attrs.get(ROUNDOFF, 0.0))
        if error <= allowed:
            continue
        if np.isnan(error):
            failures.append(f"{label}: golden variable '{name}' has no counterpart in the run")
            continue
        dims = golden[name].dims
        where = ", ".join(f"{d}={i}" for d, i in zip(dims, index, strict=False))
        failures.append(
            f"{label}: '{name}' differs by {error:.3g} of its scale (allowed {allowed:g}) at "
            f"{where}: golden {expected!r}, run {got!r}"
        )
    return failures


def load_golden(stem: str) -> xr.Dataset:
    return read_gzipped(golden_path(stem))


def read_gzipped(path: Path) -> xr.Dataset:
    """A golden file (gzipped NetCDF 3) read whole into memory."""
    raw = gzip.decompress(path.read_bytes())
    with xr.open_dataset(io.BytesIO(raw), engine="scipy") as dataset:
        return dataset.load()


def golden_changes(golden: xr.Dataset) -> dict:
    """The simulation keys the golden run changed in its example."""
    return json.loads(golden.attrs["golden_changes"])


def main(stems: list[str], what: str = "goldens") -> None:
    """Recording needs the retired single-cable core: say where it is, and exit."""
    del stems
    sys.exit(
        f"the {what} were recorded by the single-cable core, retired after commit 4911bc8: "
        "check that commit out (git worktree add /tmp/old 4911bc8) and run this script there"
    )


if __name__ == "__main__":
    main(sys.argv[1:])
