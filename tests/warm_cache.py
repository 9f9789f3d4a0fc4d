"""Compile the package's shared code once, in two processes, before pytest-xdist's workers start
(``tests/conftest.py``, only when the tests run on several workers).

Every compiled function of seacable has the same types whatever the case, and numba caches it on
disk; but each xdist worker that needs a function before another has written it compiles it
itself. Cold, each of the two workers spent about 300 s compiling the same right-hand side,
outputs and integrators' chunks. Here ``first`` builds a system (the right-hand side and the
statics) and runs rk4 (the outputs), says so by creating the file it is given, then runs
generalized-alpha (the implicit schemes' chunk); ``second`` waits for that file, then runs dopri5,
while the first compiles the implicit chunk. A warm cache makes both take a few seconds.

Run: python tests/warm_cache.py first|second <marker file>
"""

import sys
import time
from pathlib import Path

import yaml

CASE = Path(__file__).resolve().parents[1] / "examples" / "two_buoys_moored_with_hawser.yaml"
WAIT = 900.0  # s: the longest the second waits for the first (then compiles what it needs)


def _run(**settings) -> None:
    import seacable

    raw = yaml.safe_load(CASE.read_text())
    raw["simulation"] = {"duration": 1.0, "output_interval": 0.5, **settings}
    seacable.simulate(seacable.load_case(raw))


def main(part: str, marker: Path) -> None:
    if part == "first":
        try:
            _run(integrator="rk4", time_step=0.01)
        finally:
            marker.touch()
        _run(integrator="generalized_alpha", time_step=0.05)
    else:
        start = time.monotonic()
        while not marker.exists() and time.monotonic() - start < WAIT:
            time.sleep(0.5)
        _run(integrator="dopri5", rtol=1e-6)


if __name__ == "__main__":
    main(sys.argv[1], Path(sys.argv[2]))
