"""Compiling on two cores: a list of compiled functions shared with a helper process.

numba compiles in one thread of one process (its compiler holds a global lock and most of its
work is Python), so a first run used one core of two. ``compile_all`` takes a list of jobs,
each a compiled function (a dispatcher) and the signature to compile it for: this process
compiles them from the front of the list, a helper process (``python -m
seacable.kernels.helper``) from the back, each claiming a job before it starts it (a file made
with ``O_EXCL`` in a folder of the two), until they meet. The helper writes what it compiles
into numba's disk cache; this process then loads it from there. The helper rebuilds the same
list from a recipe (a module, a function of it and its arguments, pickled): the signatures
must not depend on anything the arguments do not carry.

Nothing depends on the helper: if it cannot start, fails or is killed, this process compiles
what it left (its status is logged at DEBUG). It is used only where it can help: when
``wanted`` (the caller knows the functions are not cached), on a machine with two cores or
more, unless ``SEACABLE_COMPILE_HELPER=0``.
"""

import importlib
import logging
import os
import pickle
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

Job = tuple[Any, tuple]  # a dispatcher and the signature (a tuple of numba types) to compile
Recipe = tuple[str, str, tuple]  # a module, a function of it returning the jobs, its arguments
log = logging.getLogger("seacable.compiling")
SWITCH = "SEACABLE_COMPILE_HELPER"  # 0: compile in this process only


def cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def cached(job: Job) -> bool:
    """Whether numba's disk cache holds ``job`` compiled (False when that cannot be read:
    the helper is then started for nothing, never skipped wrongly)."""
    dispatcher, signature = job
    cache = getattr(dispatcher, "_cache", None)
    try:
        key = cache._index_key(signature, dispatcher.targetctx.codegen())  # type: ignore[union-attr]
        return key in cache._cache_file._load_index()  # type: ignore[union-attr]
    except Exception:  # noqa: BLE001 - numba's cache internals: any failure means "not known"
        return False


def compile_all(jobs: list[Job], recipe: Recipe, wanted: bool) -> None:
    """Compile (or load from numba's cache) every job, the end of the list in a helper process
    when ``wanted`` and the machine has two cores (the module's docstring)."""
    helper = None
    if wanted and cores() >= 2 and os.environ.get(SWITCH, "1") != "0" and len(jobs) > 1:
        helper = _start(recipe)
    try:
        for index, job in enumerate(jobs):
            if helper is not None and not _claim(helper[1], index):
                break  # the helper has this one and every one after it
            job[0].compile(job[1])
    except BaseException:
        if helper is not None:
            helper[0].kill()
        raise
    finally:
        if helper is not None:
            _finish(*helper)
    for dispatcher, signature in jobs:  # the helper's: from the cache (here if it failed)
        dispatcher.compile(signature)


def _start(recipe: Recipe) -> tuple[subprocess.Popen, Path] | None:
    folder = Path(tempfile.mkdtemp(prefix="seacable-compile-"))
    try:
        (folder / "recipe.pickle").write_bytes(pickle.dumps(recipe))
        package = str(Path(__file__).resolve().parents[2])  # the folder seacable is in
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [package, env.get("PYTHONPATH")]))
        with open(folder / "log", "wb") as output:
            process = subprocess.Popen(
                [sys.executable, "-m", "seacable.kernels.helper", str(folder)],
                stdin=subprocess.DEVNULL, stdout=output, stderr=output, env=env,
            )  # fmt: skip
    except (OSError, pickle.PicklingError) as error:
        log.debug("no helper to compile with: %s", error)
        shutil.rmtree(folder, ignore_errors=True)
        return None
    return process, folder


def _finish(process: subprocess.Popen, folder: Path) -> None:
    code = process.wait()
    if code != 0:
        tail = (folder / "log").read_text(errors="replace")[-2000:]
        log.debug("the compiling helper ended with %s:\n%s", code, tail)
    shutil.rmtree(folder, ignore_errors=True)


def _claim(folder: Path, index: int) -> bool:
    """Claim job ``index`` (False: the other process has it)."""
    try:
        os.close(os.open(folder / f"{index}.claim", os.O_CREAT | os.O_EXCL | os.O_WRONLY))
    except FileExistsError:
        return False
    return True


def _help(folder: Path) -> None:
    """The helper: the recipe's jobs compiled from the back until the other process's claims."""
    module, name, args = pickle.loads((folder / "recipe.pickle").read_bytes())
    jobs: list[Job] = getattr(importlib.import_module(module), name)(*args)
    for index in reversed(range(len(jobs))):
        if not _claim(folder, index):
            return
        dispatcher, signature = jobs[index]
        dispatcher.compile(signature)


if __name__ == "__main__":
    _help(Path(sys.argv[1]))
