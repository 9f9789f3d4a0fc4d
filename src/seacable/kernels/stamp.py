"""numba's on-disk cache keyed by the whole package's compiled sources, not by each file's own.

numba keys a cached function by its own source file's date and size. A compiled function
carries its callees' code from other files (a kernel inlined or linked into a force model,
an integrator's loop), so after a kernel's file changes, a caller whose file did not change
loads its old build: the old physics, silently. It happens whenever files change one by one
(a ``git pull`` or a branch switched in a checkout installed with ``pip install -e``, an
edit while developing); a wheel's install writes every file anew and hid it. Measured: after
``kernels/hull.py`` changed, ``forces/froude_krylov.py``'s cached build kept the old
``hull.place`` (the moored FPSO of benchmarks/vessel_cost.py gave the old run's heave to the
bit until the cache folder was emptied).

``install`` (called when ``seacable.kernels`` is imported, before any compiled module compiles)
puts before numba's own cache locators a variant of each that serves the package's files only
and stamps their cached builds with ``sources_digest``: every source of the package but the
top layers' Python-only modules (``PYTHON_ONLY``: no compiled function, and below them
nothing compiled imports them, tests/test_layers.py), with numba's version. A change in any
of them makes every cached build of the package stale (numba then compiles it again and
overwrites it); a file only touched, or installed again unchanged, keeps them. The copies of
the evaluation (``system.variants``) are named by the same digest.
"""

import hashlib
from pathlib import Path

import numba
from numba.core import caching

PACKAGE = Path(__file__).resolve().parents[1]

# modules of the top layers (docs/architecture.md) that compiled code cannot reach: no compiled
# function of their own, and the layer rule keeps every compiled module (and the constants it
# reads) below them; a change in them leaves the cache valid
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
COMPILED = (b"@njit", b"@inner", b"njit(", b"intrinsic")  # what marks a file as compiled code

_digest: list[str] = []  # computed once a process


def compiled_source(name: str, text: bytes) -> bool:
    """Whether the package's file ``name`` (relative, with /) can change a compiled build."""
    return not name.startswith(PYTHON_ONLY) or any(mark in text for mark in COMPILED)


def digest_of(package: Path, version: str) -> str:
    """The digest of ``package``'s sources that compiled builds depend on, with numba's
    ``version``."""
    digest = hashlib.sha256(version.encode())
    for path in sorted(package.rglob("*.py")):
        name = path.relative_to(package).as_posix()
        text = path.read_bytes()
        if compiled_source(name, text):
            digest.update(name.encode() + b"\0")
            digest.update(hashlib.sha256(text).digest())
    return digest.hexdigest()


def sources_digest() -> str:
    """``digest_of`` the installed package (once a process)."""
    if not _digest:
        _digest.append(digest_of(PACKAGE, numba.__version__))
    return _digest[0]


def _ours(py_file: str) -> bool:
    try:
        return Path(py_file).resolve().is_relative_to(PACKAGE)
    except (OSError, ValueError):
        return False


def _stamped(base: type) -> type:
    """numba's locator ``base`` for the package's files, its builds stamped by the digest."""

    class Stamped(base):
        def get_source_stamp(self):
            return ("seacable", sources_digest())

        @classmethod
        def from_function(cls, py_func, py_file):
            if not _ours(py_file):
                return None
            return super().from_function(py_func, py_file)

    Stamped.__name__ = Stamped.__qualname__ = f"Seacable{base.__name__.lstrip('_')}"
    return Stamped


def install() -> None:
    """Put the stamped locators before numba's own (once a process)."""

    def public(name):  # older numba names them with a leading underscore
        return getattr(caching, name, None) or getattr(caching, "_" + name)

    classes = public("CacheImpl")._locator_classes
    if any(getattr(c, "__name__", "").startswith("Seacable") for c in classes):
        return
    names = ("UserProvidedCacheLocator", "InTreeCacheLocator", "UserWideCacheLocator")
    bases = [public(n) for n in names]
    classes[0:0] = [_stamped(base) for base in bases]
