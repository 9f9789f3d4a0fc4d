"""How seacable compiles: the options of every compiled function, and compiled functions without
a Python entry.

``JIT`` is given to every ``numba.njit``: compiled once and cached on disk (stamped by the
whole package's compiled sources, kernels.stamp: a kernel's change makes its callers' builds
in other files stale too); the numpy error model drops per-division zero checks; the safe
fastmath flags allow fused multiply-adds and reciprocals but keep NaN/inf semantics (the
divergence checks rely on them).

``inner`` compiles a function that only compiled code calls. numba builds, for every compiled
function, a CPython entry that unboxes its arguments from Python objects: code for each array
argument (for 20 functions taking a 115-array tuple, 27.7 s of compiling with their entries
against 4.5 s without, numba 0.68; the system's tuples now pass by reference, kernels.records,
but a function of many array arguments still pays for its entry). An entry is only needed where
Python calls in. ``inner`` leaves it out (and the C-callable entry, which nothing here uses);
calling such a function from Python raises ``TypeError`` instead of running code that does not
exist. It is also what a large helper should be rather than ``inline="always"``: numba copies,
types and lowers an inlined body again in every caller (the waves' kernels inlined into the
lines' loads made the moored barge's first run 11 s longer).
"""

import logging
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from numba import njit
from numba.core.registry import CPUDispatcher

JIT: dict[str, Any] = dict(cache=True, error_model="numpy", fastmath={"contract", "arcp", "nsz"})


class InnerDispatcher(CPUDispatcher):
    """A compiled function without a Python entry (see the module docstring)."""

    def __call__(self, *args, **kwargs):
        name = self.py_func.__module__ + "." + self.py_func.__qualname__
        raise TypeError(
            f"{name} is compiled for compiled callers only (seacable.kernels.jit.inner); "
            "call it from a compiled function, or compile it with njit(**JIT) to call it "
            "from Python"
        )


def inner(func):
    """``njit(**JIT)`` without the Python and C entries: for functions that only compiled code
    calls."""
    dispatcher = njit(no_cpython_wrapper=True, no_cfunc_wrapper=True, **JIT)(func)
    dispatcher.__class__ = InnerDispatcher
    return dispatcher


NOTICE_SECONDS = 1.0  # a compilation that lasts longer is announced, then its duration logged
log = logging.getLogger("seacable.compiling")


@contextmanager
def announced(what: str, rough: str) -> Iterator[None]:
    """Compile (or load from numba's cache) ``what`` inside the block; when that lasts more than
    ``NOTICE_SECONDS``, say so at INFO (the command line's default output) at that moment, with
    ``rough`` (a rough duration, "about 20 s"), and log its duration when it ends: nobody waits
    in silence for a compiler."""
    done = threading.Event()

    def notice():
        if not done.wait(NOTICE_SECONDS):
            log.info("compiling %s (first run only, cached afterwards; %s) ...", what, rough)

    watcher = threading.Thread(target=notice, daemon=True)
    start = time.perf_counter()
    watcher.start()
    try:
        yield
    finally:
        done.set()
        watcher.join()
    elapsed = time.perf_counter() - start
    level = logging.INFO if elapsed > NOTICE_SECONDS else logging.DEBUG
    log.log(level, "%s ready in %.1f s", what, elapsed)
