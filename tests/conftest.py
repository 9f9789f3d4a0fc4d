"""Test-session set-up: never run on a stale numba cache.

numba keys an on-disk cached function by its own source file only, so a cached integrator keeps
an old copy of a kernel it inlined after the kernel's file is edited (a stale, possibly wrong
build). Before the tests import seacable, the package's sources are hashed (but the top layers'
Python-only modules, ``PYTHON_ONLY``); when the hash differs from the one recorded with the
cache, the cached builds are deleted and compiled afresh.

On several xdist workers, the shared code is then compiled once, in two processes, before the
workers start (``pytest_sessionstart``, ``tests/warm_cache.py``).
"""

import hashlib
import os
import subprocess
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "seacable"
STAMP = PACKAGE / "__pycache__" / "numba-sources.sha256"


# modules of the top layers (docs/architecture.md) that compiled code cannot reach: no
# compiled function of their own, and the layer rule keeps every compiled module (and the
# constants it reads) below them; a change in them leaves the cache valid
PYTHON_ONLY = (
    "cli.py", "cli_ships.py", "cli_sweep.py", "cli_types.py", "sweep.py", "cluster.py",
    "case/sweep.py",
    "report.py", "export.py", "fatigue.py", "case/fatigue.py", "sweep_summary.py",
    "viz/", "results.py", "files.py", "simulation.py", "run_report.py", "analysis.py", "stats.py",
    "natural_periods.py",
    "case/loader.py", "case/reference.py",
    "case/document.py", "case/moordyn.py", "case/moordyn_tables.py",
    "coupling.py",
    "system/utilisation.py", "system/variables.py",
    "system/pseudo_time.py", "system/failures.py", "system/closed_form.py",
    "forces/bseries.py",  # the B-series' coefficients: read when a row is packed, not compiled
    "stability/api.py", "stability/operability.py", "stability/equilibria.py",
    "stability/continuation.py", "stability/parameters.py", "stability/cycles.py",
    "stability/two_parameter.py", "stability/compare.py", "stability/datasets.py",
)  # fmt: skip


def _sources_hash() -> str:
    digest = hashlib.sha256()
    for path in sorted(PACKAGE.rglob("*.py")):
        name = path.relative_to(PACKAGE).as_posix()
        text = path.read_bytes()
        compiled = b"@njit" in text or b"@inner" in text or b"njit(" in text
        if name.startswith(PYTHON_ONLY) and not compiled:
            continue
        digest.update(name.encode())
        digest.update(text)
    return digest.hexdigest()


def _drop_stale_numba_cache() -> None:
    current = _sources_hash()
    if STAMP.exists() and STAMP.read_text() == current:
        return
    for pattern in ("*.nbi", "*.nbc"):
        for cached in PACKAGE.rglob(pattern):
            cached.unlink(missing_ok=True)
    STAMP.parent.mkdir(exist_ok=True)
    STAMP.write_text(current)


_drop_stale_numba_cache()
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
