"""The operability map's cost (issue: 36 current directions x 36 wind directions x 3 speed
ratios, 3,888 weather states): equilibria and stability of each on one core (in this process,
aim under a minute), and the same map with a 10-minute motion of each state on a local Dask
cluster of 2 worker processes (aim under 10 minutes). CPU and wall times, after a small warm-up
map (numba's compilation is cached on disk and not counted).

    python benchmarks/operability_map.py [--count 36] [--workers 2] [--skip-simulated]
                                         [--control off|on|both]

``--control``: the example's compensator as the case says (off), on, or both (the map twice).
"""

import argparse
import os
import time
from pathlib import Path

import numpy as np

import seacable
from seacable.stability.operability import Limits, grid, operability, shares

EXAMPLE = Path(__file__).parent.parent / "examples" / "tandem_offloading_fpso_shuttle.yaml"


def _counts(found) -> str:
    """The statuses' counts, per control when the map has that dimension."""
    return "; ".join((f"{label}: " if label else "")
                     + ", ".join(f"{n} {c}" for n, c in counts.items())
                     for label, counts, _ in shares(found))  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--count", type=int, default=36, help="directions of each kind")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--skip-simulated", action="store_true")
    parser.add_argument("--control", choices=["off", "on", "both"], default=None)
    args = parser.parse_args()
    case = seacable.load_case(EXAMPLE)
    limits = Limits(30.0, (("hawser", 3.0e6),))
    angles = np.arange(0.0, 360.0, 360.0 / args.count)
    states, shape = grid(0.8, angles, angles, np.array([10.0, 20.0, 30.0]))
    small, small_shape = grid(0.8, angles[:2], angles[:2], np.array([10.0]))
    warm = {"simulate": 600.0, "scheduler": None, "control": args.control}
    operability(case, small, small_shape, limits, **warm)  # warm-up
    cpu, wall = time.process_time(), time.perf_counter()
    found = operability(case, states, shape, limits, scheduler=None, control=args.control)
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    count = found["status"].size
    print(f"equilibria and stability, {count} states (control {args.control or 'as the case'}"
          "), one core (this process): "
          f"CPU {cpu:.1f} s, wall {wall:.1f} s ({1e3 * cpu / count:.1f} ms a state); "
          + _counts(found))  # fmt: skip
    if args.skip_simulated:
        return
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:  # fmt: skip
        address = client.scheduler.address
        operability(case, small, small_shape, limits, simulate=600.0, scheduler=address,
                    control=args.control)  # fmt: skip
        wall = time.perf_counter()
        found = operability(
            case, states, shape, limits, simulate=600.0, scheduler=address, control=args.control
        )
        wall = time.perf_counter() - wall
    print(f"with 600 s of motion a state, {args.workers} worker processes on "
          f"{os.cpu_count()} cores: wall {wall:.1f} s; "
          + _counts(found))  # fmt: skip


if __name__ == "__main__":
    main()
