"""numba's cache keyed by the package's compiled sources (kernels.stamp): a kernel's change
makes its callers' cached builds in other files stale."""

import os
import subprocess
import sys
import textwrap

import numba
from numba import njit

from seacable.kernels import hull, stamp

RUN = textwrap.dedent("""
    import sys
    from pathlib import Path
    from seacable.kernels import stamp
    stamp.PACKAGE = Path(sys.argv[1]).resolve()  # the package under test: a caller, a kernel
    sys.path.insert(0, sys.argv[1])
    import caller
    print(caller.twice(1.0))
""")


def _write(folder, kernel_value: float) -> None:
    (folder / "kernel.py").write_text(textwrap.dedent(f"""
        from numba import njit
        @njit(cache=True)
        def value():
            return {kernel_value!r}
    """))  # fmt: skip
    (folder / "caller.py").write_text(textwrap.dedent("""
        from numba import njit
        from kernel import value
        @njit(cache=True)
        def twice(x):
            return 2.0 * value() * x
    """))  # fmt: skip


def _run(folder, cache) -> float:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run([sys.executable, "-c", RUN, str(folder)], capture_output=True,
                         text=True, env=env, check=True)  # fmt: skip
    return float(out.stdout.split()[-1])


def test_a_changed_kernel_makes_its_callers_cached_builds_stale(tmp_path):
    """A caller's file unchanged, its kernel's changed (same length): numba alone would load
    the caller's cached build with the old kernel in it; stamped, the caller compiles again."""
    package, cache = tmp_path / "pkg", tmp_path / "cache"
    package.mkdir()
    _write(package, 1.0)
    assert _run(package, cache) == 2.0
    assert any(cache.rglob("*.nbi"))  # cached
    _write(package, 3.0)
    assert _run(package, cache) == 6.0


def test_the_digest_follows_compiled_sources_only(tmp_path):
    (tmp_path / "kernels").mkdir()
    (tmp_path / "kernels" / "k.py").write_text("@njit\ndef f(): pass\n")
    (tmp_path / "cli.py").write_text("print('usage')\n")
    (tmp_path / "forces").mkdir()
    (tmp_path / "forces" / "kinds.py").write_text("GRAVITY = 0\n")  # constants compiled code reads
    first = stamp.digest_of(tmp_path, "0.1")
    assert stamp.digest_of(tmp_path, "0.2") != first  # numba's version
    (tmp_path / "cli.py").write_text("print('usage: seacable')\n")  # Python-only: no change
    assert stamp.digest_of(tmp_path, "0.1") == first
    (tmp_path / "forces" / "kinds.py").write_text("GRAVITY = 1\n")
    second = stamp.digest_of(tmp_path, "0.1")
    assert second != first
    (tmp_path / "cli.py").write_text("@njit\ndef g(): pass\n")  # compiled after all
    assert stamp.digest_of(tmp_path, "0.1") != second


def test_the_package_functions_use_the_stamped_locator():
    locator = hull.place._cache._impl.locator
    assert type(locator).__name__.startswith("Seacable")
    assert locator.get_source_stamp() == ("seacable", stamp.sources_digest())
    assert stamp.sources_digest() == stamp.digest_of(stamp.PACKAGE, numba.__version__)

    @njit(cache=True)
    def outside():  # a function outside the package: numba's own locator
        return 1

    assert not type(outside._cache._impl.locator).__name__.startswith("Seacable")
