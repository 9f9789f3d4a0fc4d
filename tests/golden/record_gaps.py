"""Golden results of the single-cable cases that ``seacable upgrade`` once refused
(tests/legacy_cases/gaps/): the single-cable core's run of each case as written (its own
integrator and step, no refinement), the variables its upgraded system must reproduce
(tests/test_upgrade_gaps.py: :func:`golden.record.compare_to_golden`, within 1e-9 of each
variable's scale).

The files were recorded by the single-cable core, retired after commit 4911bc8; to re-record
them, check that commit out and run there, from the repository root::

    PYTHONPATH=src python tests/golden/record_gaps.py [case stems...]
"""

import sys
from pathlib import Path

import numpy as np
import xarray as xr

import seacable
from seacable.case import legacy, loader

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from golden.record import main as retired  # noqa: E402
from golden.record import read_gzipped, system_rows  # noqa: E402
from golden.record import star_rows as rigid_star_rows  # noqa: E402

CASES = Path(__file__).resolve().parent.parent / "legacy_cases" / "gaps"
GOLDEN = Path(__file__).resolve().parent / "gaps"
# the positions, tensions and end loads along the cable (what every form reports), and the
# servo's force where there is one
VARIABLES = ("node_x", "node_y", "node_z", "tension", "top_force_x", "top_force_y",
             "top_force_z", "bottom_force_x", "bottom_force_y", "bottom_force_z",
             "servo_force_x", "servo_force_y", "servo_force_z", "body_x", "body_y",
             "body_z")  # fmt: skip


def stems() -> list[str]:
    return sorted(p.stem for p in CASES.glob("*.yaml"))


def upgraded(stem: str) -> dict:
    """The upgraded system's run of the case under the single-cable names
    (:func:`golden.record.system_rows`)."""
    case = seacable.load_case(legacy.upgrade(loader.load_single_cable(CASES / f"{stem}.yaml")))
    results = seacable.simulate(case)
    if results.status != "complete":
        raise RuntimeError(f"{stem} upgraded: {results.status}: {results.message}")
    if sum(line.to == case.bodies[0].name for line in case.lines) > 1:
        return star_rows(results.dataset, case)
    if sum(line.from_ == case.bodies[0].name for line in case.lines) > 1:
        return rigid_star_rows(results.dataset, case)  # lines from the body back to the tops
    return system_rows(results.dataset, case)


def star_rows(tree, case) -> dict:
    """A star of lumped-mass cables (lines from each top to the shared body, the first body)
    under the single-cable star's names: per cable ``node_*`` and ``tension``, its end loads
    as ``top_force_*`` and ``bottom_force_*``, the shared body's position as ``body_*``."""
    lines = [tree[f"lines/{line.name}"].to_dataset() for line in case.lines]
    body = tree[f"bodies/{case.bodies[0].name}"].to_dataset()
    out = {"time": tree["time"].values}
    for name in ("node_x", "node_y", "node_z", "tension"):
        out[name] = np.stack([line[name].values for line in lines], axis=1)
    for c in "xyz":
        out[f"top_force_{c}"] = np.stack([line[f"from_force_{c}"].values for line in lines], 1)
        out[f"bottom_force_{c}"] = np.stack([line[f"to_force_{c}"].values for line in lines], 1)
        out[f"body_{c}"] = body[f"position_{c}"].values
    return out


def path(stem: str) -> Path:
    return GOLDEN / f"{stem}.nc.gz"


def load(stem: str) -> xr.Dataset:
    return read_gzipped(path(stem))


def main(names: list[str]) -> None:
    retired(names, what="gap goldens")


if __name__ == "__main__":
    main(sys.argv[1:])
