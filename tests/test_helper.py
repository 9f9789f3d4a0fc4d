"""Compiling on two cores (kernels.helper): a helper process compiles the end of a list of
jobs into numba's disk cache while this process compiles its front, then loads the helper's;
a helper that fails leaves everything to this process; none is started when it is switched
off. Each test compiles functions of a module written for it (so nothing is cached yet)."""

import importlib
import secrets
import sys
import time

import pytest

from seacable.kernels import helper

COUNT = 6
MODULE = """
import numpy as np
from numba import njit, types

{functions}

def jobs():
    vector = types.Array(types.float64, 1, "C")
    return [(f, (vector, types.float64)) for f in FUNCTIONS]

def broken():
    raise RuntimeError("a recipe that fails")

FUNCTIONS = [{names}]
"""
FUNCTION = """
@njit(cache=True)
def f{k}(x, a):
    s = 0.0
    for i in range(x.shape[0]):
        s += np.sin(a * x[i] + {k}.0) / (1.0 + x[i] * x[i])
    return s
"""


@pytest.fixture
def jobs_module(tmp_path, monkeypatch):
    """A module of COUNT compiled functions never compiled before, importable here and in the
    helper (its folder on both paths; numba's cache where this process has it)."""
    name = f"helper_jobs_{secrets.token_hex(6)}"
    functions = "".join(FUNCTION.format(k=k) for k in range(COUNT))
    names = ", ".join(f"f{k}" for k in range(COUNT))
    (tmp_path / f"{name}.py").write_text(MODULE.format(functions=functions, names=names))
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setenv("PYTHONPATH", str(tmp_path))
    monkeypatch.setenv(helper.SWITCH, "1")
    monkeypatch.setattr(helper, "cores", lambda: 2)
    module = importlib.import_module(name)
    yield module
    sys.modules.pop(name, None)


def _compiled_here(module) -> list[bool]:
    """For each job, whether this process compiled it (False: loaded from the cache)."""
    return [sum(f.stats.cache_misses.values()) > 0 for f in module.FUNCTIONS]


def test_the_helper_compiles_the_end_of_the_list(jobs_module, monkeypatch):
    claim = helper._claim

    def after_the_helper(folder, index):
        """This process's first claim waits for the helper's first (the last job)."""
        if index == 0:
            end = time.monotonic() + 120
            while not (folder / f"{COUNT - 1}.claim").exists() and time.monotonic() < end:
                time.sleep(0.05)
        return claim(folder, index)

    monkeypatch.setattr(helper, "_claim", after_the_helper)
    jobs = jobs_module.jobs()
    assert not any(helper.cached(job) for job in jobs)
    helper.compile_all(jobs, (jobs_module.__name__, "jobs", ()), wanted=True)
    assert all(helper.cached(job) for job in jobs)
    here = _compiled_here(jobs_module)
    assert not here[-1], "the helper did not compile the last job"
    assert here[0], "this process did not compile the first job"
    first_loaded = here.index(False)
    assert not any(here[first_loaded:]), "the helper's jobs are the end of the list"
    x = jobs_module.np.linspace(0.0, 1.0, 5)
    for k, f in enumerate(jobs_module.FUNCTIONS):  # every job callable, whoever compiled it
        assert f(x, 0.5) == pytest.approx(sum(jobs_module.np.sin(0.5 * x + k) / (1 + x * x)))


def test_a_failing_helper_leaves_every_job_to_this_process(jobs_module):
    jobs = jobs_module.jobs()
    helper.compile_all(jobs, (jobs_module.__name__, "broken", ()), wanted=True)
    assert all(_compiled_here(jobs_module))


def test_no_helper_when_switched_off_or_not_wanted(jobs_module, monkeypatch):
    def refuse(recipe):
        raise AssertionError("a helper was started")

    monkeypatch.setattr(helper, "_start", refuse)
    jobs = jobs_module.jobs()
    helper.compile_all(jobs[:2], (jobs_module.__name__, "jobs", ()), wanted=False)
    monkeypatch.setenv(helper.SWITCH, "0")
    helper.compile_all(jobs[2:], (jobs_module.__name__, "jobs", ()), wanted=True)
    assert all(_compiled_here(jobs_module))
