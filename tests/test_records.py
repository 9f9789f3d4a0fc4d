"""The system's parameter and work tuples reach compiled code by reference (kernels.records):
the same arrays on both sides, one structure per tuple, a new one for a replaced tuple, nothing
of it pickled; and the current profile's interpolation (kernels.chain3d_layout.profile) agrees
with numpy's."""

import copy
import pickle
from pathlib import Path

import numpy as np
import pytest
from numba import njit

import seacable
from seacable.kernels import records
from seacable.kernels.chain3d_layout import profile
from seacable.system import kernel, model

EXAMPLES = Path(__file__).parent.parent / "examples"


@njit(cache=True)
def _touch(p, w):
    """Write into the workspace what compiled code reads from the parameters."""
    w.tie_tension[:] = p.gravity
    w.rhs6[0] = p.n_q
    return p.tie_length.shape[0]


@pytest.fixture(scope="module")
def system():
    return model.build(seacable.load_case(EXAMPLES / "two_buoys_moored_with_hawser.yaml"))


def test_compiled_code_shares_the_tuples_arrays(system):
    p = system.params
    w = kernel.make_work(p)
    assert _touch(p, w) == len(p.tie_length)
    assert np.all(w.tie_tension == p.gravity) and w.rhs6[0] == p.n_q


def test_one_structure_per_tuple_a_new_one_when_replaced(system):
    p = system.params
    assert records.handle(p) is records.handle(p)
    q = p._replace(gravity=1.5)
    assert type(q) is kernel.SystemParams
    assert records.handle(q) is not records.handle(p)
    w = kernel.make_work(q)
    _touch(q, w)
    assert np.all(w.tie_tension == 1.5)


def test_the_structure_is_neither_pickled_nor_copied(system):
    p = system.params
    records.handle(p)
    for clone in (pickle.loads(pickle.dumps(p)), copy.copy(p), copy.deepcopy(p)):
        assert type(clone) is kernel.SystemParams and "_record" not in clone.__dict__
        assert all(np.array_equal(a, b) for a, b in zip(clone, p, strict=True))


def test_a_class_that_is_no_named_tuple_is_refused():
    class Plain:
        pass

    with pytest.raises(TypeError, match="must extend a named tuple class"):
        records.register(Plain)


@njit(cache=True)
def _profile(xs, xp, fp, out):
    for i in range(xs.shape[0]):
        out[i] = profile(xs[i], xp, fp)


def test_the_profile_is_numpys_interpolation():
    xp = np.array([-100.0, -50.0, -50.0, -10.0, 0.0])  # a repeated point: a step
    fp = np.array([0.1, 0.5, 0.7, 0.9, 1.3])
    rng = np.random.default_rng(1)
    xs = np.concatenate([rng.uniform(-150.0, 50.0, 5000), xp, [np.nan, -np.inf, np.inf]])
    got = np.empty_like(xs)
    _profile(xs, xp, fp, got)
    expected = np.interp(xs, xp, fp)
    assert np.array_equal(np.isnan(got), np.isnan(expected))
    assert np.nanmax(np.abs(got - expected)) <= 4 * np.finfo(float).eps
