"""A sweep's cost on a local Dask cluster against the same load cases one after the other in
this process (issue 41): 32 load cases of the spread mooring example (4 significant heights x
8 wave directions, each run for ``--duration`` seconds of the sea), wall time of each way and
their ratio, after a warm-up (numba's compilation is cached on disk and not counted). The
ratio is bounded by the cores: each worker process runs one load case at a time.

    python benchmarks/sweep_cluster.py [--duration 30] [--workers 2]
"""

import argparse
import os
import tempfile
import time
from pathlib import Path

import seacable
from seacable import sweep
from seacable.case import loader

EXAMPLE = Path(__file__).parent.parent / "examples" / "spread_mooring_in_waves.yaml"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--duration", type=float, default=30.0, help="[s] of each run")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    case = loader.with_settings(seacable.load_case(EXAMPLE),
                                [f"simulation.duration={args.duration}"])  # fmt: skip
    vary = [sweep.parse_vary("environment.waves[0].significant_height=2,3,4,5"),
            sweep.parse_vary("environment.waves[0].direction_deg=0:360:45")]  # fmt: skip
    todo = sweep.plan(case, vary)
    warm = sweep.plan(loader.with_settings(case, ["simulation.duration=1"]), vary[:1])
    from distributed import Client, LocalCluster

    with tempfile.TemporaryDirectory() as folder:
        sweep.execute(warm, Path(folder) / "warm.nc", None)
        wall = time.perf_counter()
        alone = sweep.execute(todo, Path(folder) / "alone.nc", None)
        alone_wall = time.perf_counter() - wall
        local = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                             dashboard_address=None)  # fmt: skip
        with local as cluster, Client(cluster) as client:
            address = client.scheduler.address
            sweep.execute(warm, Path(folder) / "warm_cluster.nc", address)
            wall = time.perf_counter()
            spread = sweep.execute(todo, Path(folder) / "cluster.nc", address)
            cluster_wall = time.perf_counter() - wall
    same = bool((alone["tension_max"] == spread["tension_max"]).all())
    print(
        f"{len(todo.cases)} load cases of {args.duration:g} s, {os.cpu_count()} cores: one "
        f"after the other in this process {alone_wall:.1f} s ({alone.attrs['counts']}); on "
        f"{args.workers} Dask workers {cluster_wall:.1f} s ({spread.attrs['counts']}); "
        f"ratio {alone_wall / cluster_wall:.2f}; the same tensions bit for bit: {same}"
    )


if __name__ == "__main__":
    main()
