"""Compile the package's shared code once, in two processes, before pytest-xdist's workers start
(``tests/conftest.py``, only when the tests run on several workers).

Every compiled function of seacable has the same types whatever the case, and numba caches it on
disk; but each xdist worker that needs a function before another has written it compiles it
itself. Cold, each of the two workers spent about 300 s compiling the same right-hand side,
outputs and integrators' chunks. Here ``first`` runs generalized-alpha (the right-hand side, the
statics, the outputs and the implicit schemes' chunk) and ``second`` rk4 and dopri5: both compile
the shared code side by side (a second core has nothing else to do meanwhile), then each its
integrators. A warm cache makes both take a few seconds.

Run: python tests/warm_cache.py first|second
"""

import sys
from pathlib import Path

import yaml

CASE = Path(__file__).resolve().parents[1] / "examples" / "two_buoys_moored_with_hawser.yaml"


def _run(**settings) -> None:
    import seacable

    raw = yaml.safe_load(CASE.read_text())
    raw["simulation"] = {"duration": 0.02, "output_interval": 0.01, **settings}
    seacable.simulate(seacable.load_case(raw))


def main(part: str) -> None:
    if part == "first":
        _run(integrator="generalized_alpha", time_step=0.01)
    else:
        _run(integrator="rk4", time_step=0.001)
        _run(integrator="dopri5", rtol=1e-6)


if __name__ == "__main__":
    main(sys.argv[1])
