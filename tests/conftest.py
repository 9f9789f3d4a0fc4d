"""Test-session set-up: the shared code compiled once before the workers start.

The package keeps its numba cache from going stale by itself (kernels.stamp: every cached build
is stamped by all its compiled sources). On several xdist workers, the shared code is compiled
once, in two processes, before the workers start (``pytest_sessionstart``,
``tests/warm_cache.py``).
"""

import os
import subprocess
import sys
from pathlib import Path

# the tests run on two busy workers (and tests/warm_cache.py in two processes): a compiling
# helper process (kernels.helper) would only add its import and what both sides compile twice
# (the suite from a fresh clone, cold: 587 s with helpers, 530 s without); tests/test_helper.py
# turns it on for itself
os.environ.setdefault("SEACABLE_COMPILE_HELPER", "0")
_WARM: dict[str, float] = {}  # how long tests/warm_cache.py took (wall)


def pytest_sessionstart(session) -> None:
    """On several xdist workers, compile the shared code once before they start
    (tests/warm_cache.py; xdist starts its workers in a later hook of the same name)."""
    config = session.config
    workers = getattr(config.option, "numprocesses", None)
    if hasattr(config, "workerinput") or workers in (None, 0, 1, "0", "1"):
        return
    import time

    script = str(Path(__file__).with_name("warm_cache.py"))
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    start = time.perf_counter()
    parts = [
        subprocess.Popen([sys.executable, script, part], **quiet) for part in ("first", "second")
    ]
    for part in parts:
        part.wait()  # a failure here only leaves the compiling to the workers
    _WARM["seconds"] = time.perf_counter() - start


# --- the compile share of the test run (issue 38: printed by make test) ---
_COMPILE = {"seconds": 0.0, "depth": 0, "start": 0.0, "session": 0.0}


def _listen_to_numba() -> None:
    """Add up the wall time numba spends compiling in this process (its outermost compile events:
    a function compiled inside another's compilation counts once)."""
    import time

    from numba.core import event

    class Compiling(event.Listener):
        def on_start(self, ev):
            if _COMPILE["depth"] == 0:
                _COMPILE["start"] = time.perf_counter()
            _COMPILE["depth"] += 1

        def on_end(self, ev):
            _COMPILE["depth"] -= 1
            if _COMPILE["depth"] == 0:
                _COMPILE["seconds"] += time.perf_counter() - _COMPILE["start"]

    event.register("numba:compile", Compiling())


def pytest_configure(config) -> None:
    import time

    _COMPILE["session"] = time.perf_counter()
    _listen_to_numba()
    config._seacable_compile = []  # (worker's compile seconds, worker's seconds) per worker


def pytest_sessionfinish(session) -> None:
    import time

    if hasattr(session.config, "workeroutput"):  # an xdist worker: report to the controller
        session.config.workeroutput["compile_seconds"] = _COMPILE["seconds"]
        session.config.workeroutput["worker_seconds"] = time.perf_counter() - _COMPILE["session"]


def pytest_testnodedown(node, error) -> None:
    out = getattr(node, "workeroutput", {})
    if "compile_seconds" in out:
        node.config._seacable_compile.append((out["compile_seconds"], out["worker_seconds"]))


def pytest_terminal_summary(terminalreporter, config) -> None:
    import time

    rows = config._seacable_compile or [
        (_COMPILE["seconds"], time.perf_counter() - _COMPILE["session"])
    ]
    compiling, total = sum(r[0] for r in rows), sum(r[1] for r in rows)
    warm = _WARM.get("seconds")
    text = (f"numba compiling: {compiling:.0f} s of {total:.0f} s of test processes' time "
            f"({100 * compiling / max(total, 1e-9):.0f} %)")  # fmt: skip
    if warm is not None:
        text += f"; before them, tests/warm_cache.py: {warm:.0f} s (wall, two processes)"
    terminalreporter.write_line(text)
