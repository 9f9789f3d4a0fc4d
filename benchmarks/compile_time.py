"""Compile time of a first run, per example family, from an empty numba cache and from the cache.

A family is one compiled path: a system's set of line models, set of body kinds and integrator
(derived from the case files in ``examples/``; the first example of each family, in name order,
stands for it). Every system has the same compiled types (flat arrays with offsets), so the
families share most of their compiled code: the right-hand side, the outputs, the statics. Each
example is shortened to a few output intervals (``--intervals``; the point is compilation, not
simulation): its YAML is read, ``simulation.duration`` set, relative table files made absolute,
and the result written to a temporary case file that ``seacable.load_case`` validates like any
other.

For each example, two fresh Python processes run ``import seacable``, load the case, simulate it
(the first run) and simulate it again in the same process (the warm run: the same compiled code,
already in memory); both see ``NUMBA_CACHE_DIR`` set to a new temporary directory, empty for the
first process (cold) and filled by it for the second (cached), so the repository's own cache is
neither read nor written. Printed, in seconds: the import (of what a run uses: the package imports
its public names on first use), the first run counted from before
``import seacable`` to the results (import + load + simulate, as a user waits for it, less the
interpreter's start-up), cold and cached, the warm run, and the compile time estimated as cold
first run - cached first run. Budgets (issue 38): a cold first run within 15 s for the demo case
and 30 s for every family, a cached first run within 1 s. Each process uses an empty seacable
cache folder too (``SEACABLE_CACHE_DIR``: the evaluation's copies, system.variants). The
machine's load average is printed with each row (the figures are wall times).

With ``--shared``, a second table: the families run one after the other in fresh processes that
share one cache, as a user's runs do: the first family compiles the shared code, each later one
only what it adds (its integrator's chunk, mostly).

Run: python benchmarks/compile_time.py [EXAMPLE ...] [--intervals N] [--list] [--check]
[--shared]
(EXAMPLE: a file name in examples/, with or without .yaml, or a path; default: one per family).
Exit status 0 whatever the figures; with --check, 1 when a budget is exceeded or a run fails.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

HERE = Path(__file__).resolve().parent
EXAMPLES = HERE.parent / "examples"
COLD_BUDGET = 30.0  # [s] first run from an empty compile cache (issue 38: any example family)
DEMO = "thesis_6_1_sim6_submerged_60_links_forced"  # the demo case (make demo)
DEMO_BUDGET = 15.0  # [s] its first run from an empty compile cache (issue 38)
CACHED_BUDGET = 1.0  # [s] first run from the compile cache
CHILD_TIMEOUT = 1800.0  # [s] a run taking longer is reported as failed


def family(data: dict) -> str:
    """The compiled path of a case mapping: its line models, its body kinds, its force models,
    its integrator."""
    integrator = data.get("simulation", {}).get("integrator", "rk4")
    models = sorted({line.get("model", "?") for line in data.get("lines") or []})
    kinds = sorted({body.get("type", "?") for body in data.get("bodies") or []})
    forces = sorted({force.get("model", "?") for body in data.get("bodies") or []
                     for force in body.get("external forces") or []})  # fmt: skip
    return (f"{'+'.join(models)} lines, bodies {'/'.join(kinds)}, forces "
            f"{'/'.join(forces) or 'none'}, {integrator}")  # fmt: skip


def families() -> dict[str, list[Path]]:
    """Family -> its examples (name order)."""
    found: dict[str, list[Path]] = {}
    for path in sorted(EXAMPLES.glob("*.yaml")):
        found.setdefault(family(yaml.safe_load(path.read_text())), []).append(path)
    return found


def example_path(name: str) -> Path:
    path = Path(name)
    if path.exists():
        return path.resolve()
    path = EXAMPLES / (name if name.endswith((".yaml", ".yml")) else f"{name}.yaml")
    if not path.exists():
        raise SystemExit(f"example '{name}' not found (neither a path nor a file in {EXAMPLES})")
    return path


def _absolute_files(node, base: Path):
    """The mapping with every relative table ``file`` made absolute against ``base``."""
    if isinstance(node, dict):
        out = {key: _absolute_files(value, base) for key, value in node.items()}
        if isinstance(out.get("file"), str) and not Path(out["file"]).is_absolute():
            out["file"] = str((base / out["file"]).resolve())
        return out
    if isinstance(node, list):
        return [_absolute_files(value, base) for value in node]
    return node


def short_case(example: Path, intervals: int, folder: Path) -> Path:
    """A case file in ``folder``: ``example`` run for ``intervals`` output intervals."""
    data = _absolute_files(yaml.safe_load(example.read_text()), example.parent)
    simulation = data.setdefault("simulation", {})
    simulation["duration"] = intervals * float(simulation.get("output_interval", 0.1))
    path = folder / example.name
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def child(case_path: str | None) -> None:
    """In a fresh process: the times of import, first run and warm run, as one JSON line."""
    start = time.perf_counter()
    import seacable

    seacable.simulate, seacable.load_case  # noqa: B018 - what a run imports (on first use)
    times = {"import": time.perf_counter() - start}
    if case_path is not None:
        seacable.simulate(seacable.load_case(case_path))
        times["first"] = time.perf_counter() - start
        warm_start = time.perf_counter()
        seacable.simulate(seacable.load_case(case_path))
        times["warm"] = time.perf_counter() - warm_start
    print(json.dumps(times))


def run_child(case_path: Path | None, cache: Path) -> dict:
    """Times of a fresh process with NUMBA_CACHE_DIR=cache; {'error': ...} when it fails."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), OPENBLAS_NUM_THREADS="1",
               SEACABLE_CACHE_DIR=str(cache / "seacable"))  # fmt: skip
    command = [sys.executable, str(Path(__file__).resolve()), "--child"]
    command += [] if case_path is None else [str(case_path)]
    try:
        out = subprocess.run(
            command, env=env, capture_output=True, text=True, timeout=CHILD_TIMEOUT
        )
    except subprocess.TimeoutExpired:
        return {"error": f"timed out after {CHILD_TIMEOUT:.0f} s"}
    if out.returncode != 0:
        lines = out.stderr.strip().splitlines() or ["(no message)"]
        return {"error": lines[-1]}
    return json.loads(out.stdout.strip().splitlines()[-1])


def measure(case_path: Path | None) -> tuple[dict, dict]:
    """(cold, cached) times of ``case_path`` (None: the import alone) in a new cache."""
    with tempfile.TemporaryDirectory(prefix="seacable-numba-") as cache:
        cold = run_child(case_path, Path(cache))
        cached = run_child(case_path, Path(cache)) if "error" not in cold else cold
    return cold, cached


def figures(cold: dict, cached: dict, budget: float = COLD_BUDGET) -> tuple[str, bool]:
    """The table's figures for one example, and whether a budget is exceeded (or a run failed)."""
    if "error" in cold or "error" in cached:
        return f"failed: {cold.get('error') or cached.get('error')}", True
    over_cold, over_cached = cold["first"] > budget, cached["first"] > CACHED_BUDGET
    text = (
        f"{cold['import']:>6.2f} {cold['first']:>7.2f} {cached['first']:>6.2f} "
        f"{min(cold['warm'], cached['warm']):>6.3f} {cold['first'] - cached['first']:>7.2f} "
        f"{'OVER' if over_cold else 'ok':>5} {'OVER' if over_cached else 'ok':>7}"
    )
    return text, over_cold or over_cached


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("examples", nargs="*", help="examples to time (default: one per family)")
    parser.add_argument("--intervals", type=int, default=3, help="output intervals simulated")
    parser.add_argument("--list", action="store_true", help="print the families and stop")
    parser.add_argument(
        "--shared", action="store_true", help="also: the families in turn, sharing one cache"
    )
    parser.add_argument("--check", action="store_true", help="exit 1 when a budget is exceeded")
    parser.add_argument("--child", nargs="?", const="", default=None, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        child(args.child or None)
        return

    groups = families()
    if args.list:
        for name, members in groups.items():
            print(f"{name}: " + ", ".join(path.stem for path in members))
        return
    if args.examples:
        chosen = [example_path(name) for name in args.examples]
        rows = [(family(yaml.safe_load(path.read_text())), path) for path in chosen]
    else:
        rows = [(name, members[0]) for name, members in groups.items()]

    cold, cached = measure(None)
    print(
        "import seacable with simulate and load_case, fresh process: "
        f"{cold.get('import', float('nan')):.2f} s "
        f"(empty compile cache), {cached.get('import', float('nan')):.2f} s (cached)"
    )
    print(
        f"first run = import + load + simulate {args.intervals} output intervals; compile = "
        f"cold - cached; budgets: cold <= {COLD_BUDGET:g} s ({DEMO}: {DEMO_BUDGET:g} s), "
        f"cached <= {CACHED_BUDGET:g} s"
    )
    wide = max(len(name) for name, _ in rows)
    wide_example = max(len(example.stem) for _, example in rows)
    header = (
        f"{'family':<{wide}} {'example':<{wide_example}} {'import':>6} {'cold':>7} {'cached':>6} "
        f"{'warm':>6} {'compile':>7} {'cold?':>5} {'cached?':>7} {'load':>5}"
    )
    print(header)
    exceeded = False
    with tempfile.TemporaryDirectory(prefix="seacable-cases-") as folder:
        for name, example in rows:
            load = os.getloadavg()[0]
            budget = DEMO_BUDGET if example.stem == DEMO else COLD_BUDGET
            case_path = short_case(example, args.intervals, Path(folder))
            text, over = figures(*measure(case_path), budget)
            exceeded |= over
            print(f"{name:<{wide}} {example.stem:<{wide_example}} {text} {load:>5.2f}", flush=True)
        if args.shared:
            shared(rows, args.intervals, Path(folder), wide, wide_example)
    if args.check and exceeded:
        sys.exit(1)


def shared(rows, intervals: int, folder: Path, wide: int, wide_example: int) -> None:
    """The families' first runs in turn, in fresh processes sharing one new cache."""
    print("\nthe families in turn, one cache shared (a user's successive first runs):")
    print(f"{'family':<{wide}} {'example':<{wide_example}} {'first':>7} {'load':>5}")
    with tempfile.TemporaryDirectory(prefix="seacable-numba-") as cache:
        for name, example in rows:
            load = os.getloadavg()[0]
            out = run_child(short_case(example, intervals, folder), Path(cache))
            first = out["error"] if "error" in out else f"{out['first']:>7.2f}"
            print(f"{name:<{wide}} {example.stem:<{wide_example}} {first} {load:>5.2f}", flush=True)


if __name__ == "__main__":
    main()
