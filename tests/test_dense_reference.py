"""The O(n) rigid-link line of a system against the thesis's dense-mass-matrix formulation, for
many links."""

import sys
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable.case.loader import derive_case
from seacable.kernels.status import Status
from seacable.system import kernel, model

sys.path.insert(0, str(Path(__file__).parent.parent / "benchmarks"))
from dense_reference import DenseThesisModel, dense_state, system_rates, thesis_chain  # noqa: E402

EXAMPLE = (
    Path(__file__).parent.parent / "examples" / "thesis_6_1_sim6_submerged_60_links_forced.yaml"
)


@pytest.mark.parametrize("n", [5, 60, 200])
def test_kernel_matches_dense_mass_matrix(n):
    base = seacable.load_case(EXAMPLE)
    lines = [base.lines[0].model_dump(mode="json", by_alias=True, exclude_none=True)]
    lines[0]["sections"][0]["segments"] = n
    built = model.build(derive_case(base, {"lines": lines}))
    chain = thesis_chain(built)
    assert chain.n == n and chain.force[1] == 25000.0 and chain.body_drag > 0.0
    dense = DenseThesisModel(chain)
    rng = np.random.default_rng(n)
    w = model.workspace(built)
    ydot = np.zeros_like(built.y0)
    for _ in range(3):
        y = built.y0.copy()
        y[chain.rs_q : chain.rs_q + n] = rng.uniform(-1.5, 1.5, n)
        # the structure at or below the surface, the links pointing down from it: the dense
        # formulation has no free surface
        y[chain.top_q] = rng.uniform(-4, 0)
        y[chain.rs_v : chain.rs_v + n] = rng.uniform(-1, 1, n)
        y[chain.top_v] = rng.uniform(-1, 1)
        t = rng.uniform(0, 10)
        assert kernel.rhs(t, y, built.params, w, ydot) == Status.OK
        expected = dense.rhs(t, dense_state(chain, y))
        scale = np.max(np.abs(expected))
        np.testing.assert_allclose(system_rates(chain, ydot), expected, rtol=0, atol=1e-8 * scale)
