"""Warm speed against another checkout, in the same run (issue 38: compile time is not bought
with run time): the thesis case with n = 120 links (10 s, rk4 5 ms, best of ``--repeat``) and
the moored barge's 60 s (CPU time, best of ``--repeat``; its real-time factor), each measured in a
fresh process after a warm-up run, this checkout and the other alternating ``--rounds`` times.

Run: python benchmarks/warm_speed.py --against OTHER_CHECKOUT [--rounds 3] [--repeat 10]
(OTHER_CHECKOUT: a git worktree of another commit, e.g. ``git worktree add /tmp/old 9a8052e``;
its ``src`` goes first on PYTHONPATH in its processes).
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from compile_time import _absolute_files  # noqa: E402


def child(root: Path, repeat: int) -> None:
    """In a fresh process: the two figures of ``root``'s examples, as one JSON line."""
    import yaml

    import seacable
    from seacable.case.loader import derive_case

    base = seacable.load_case(root / "examples" / "thesis_6_1_sim4_submerged_60_links.yaml")
    lines = [base.lines[0].model_dump(mode="json", by_alias=True, exclude_none=True)]
    lines[0]["sections"][0]["segments"] = 120
    sim = {"duration": 10.0, "output_interval": 0.1, "time_step": 0.005,
           "allow_unstable_step": True}  # fmt: skip
    thesis = derive_case(base, {"lines": lines, "simulation": sim})
    raw = yaml.safe_load((root / "examples" / "moored_barge_irregular_sea.yaml").read_text())
    raw = _absolute_files(raw, root / "examples")
    raw["simulation"]["duration"] = 60.0
    barge = seacable.load_case(raw)
    best = {"thesis": math.inf, "barge": math.inf}
    for name, case, clock in (("thesis", thesis, time.perf_counter),
                              ("barge", barge, time.process_time)):  # fmt: skip
        seacable.simulate(case)  # compile or load, warm up
        for _ in range(repeat):
            start = clock()
            seacable.simulate(case)
            best[name] = min(best[name], clock() - start)
    print(json.dumps(best))


def run(src: Path, root: Path, repeat: int) -> dict:
    env = dict(os.environ, PYTHONPATH=str(src), OPENBLAS_NUM_THREADS="1")
    command = [sys.executable, str(Path(__file__).resolve()), "--child", str(root)]
    out = subprocess.run(command + ["--repeat", str(repeat)], env=env, capture_output=True,
                         text=True, check=True)  # fmt: skip
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--against", type=Path, help="another checkout to time alongside")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--repeat", type=int, default=10)
    parser.add_argument("--child", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        child(args.child, args.repeat)
        return
    here = HERE.parent
    checkouts = [("this", here)] + ([("other", args.against.resolve())] if args.against else [])
    for k in range(args.rounds):
        for name, root in checkouts:
            best = run(root / "src", root, args.repeat)
            print(f"round {k + 1} {name:>5} ({root}): thesis n = 120 best of {args.repeat} "
                  f"{best['thesis']:.4f} s; barge 60 s {best['barge']:.2f} s CPU, real-time "
                  f"factor {60.0 / best['barge']:.1f}", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
