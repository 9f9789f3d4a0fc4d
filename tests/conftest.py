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
import subprocess
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "seacable"
STAMP = PACKAGE / "__pycache__" / "numba-sources.sha256"


# modules of the top layers (docs/architecture.md) that compiled code cannot reach: no
# compiled function of their own, and the layer rule keeps every compiled module (and the
# constants it reads) below them; a change in them leaves the cache valid
PYTHON_ONLY = (
    "cli.py", "cli_ships.py", "viz/", "results.py", "simulation.py", "analysis.py",
    "case/loader.py",
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


def pytest_sessionstart(session) -> None:
    """On several xdist workers, compile the shared code once before they start
    (tests/warm_cache.py; xdist starts its workers in a later hook of the same name)."""
    config = session.config
    workers = getattr(config.option, "numprocesses", None)
    if hasattr(config, "workerinput") or workers in (None, 0, 1, "0", "1"):
        return
    script = str(Path(__file__).with_name("warm_cache.py"))
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    parts = [
        subprocess.Popen([sys.executable, script, part], **quiet) for part in ("first", "second")
    ]
    for part in parts:
        part.wait()  # a failure here only leaves the compiling to the workers
