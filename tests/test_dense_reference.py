"""The O(n) kernel against the thesis's dense-mass-matrix formulation, for many links."""

import sys
from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable.kernels import planar_chain as pc
from seacable.models import planar_rigid_links

sys.path.insert(0, str(Path(__file__).parent.parent / "benchmarks"))
from dense_reference import DenseThesisModel  # noqa: E402

EXAMPLE = Path(__file__).parent / "legacy_cases" / "thesis_6_1_sim6_submerged_60_links_forced.yaml"


@pytest.mark.parametrize("n", [5, 60, 200])
def test_kernel_matches_dense_mass_matrix(n):
    base = seacable.load_case(EXAMPLE)
    case = base.model_copy(update={"cables": [base.cables[0].model_copy(update={"links": n})]})
    system = planar_rigid_links.build(case)
    dense = DenseThesisModel(system.params)
    rng = np.random.default_rng(n)
    w = pc.make_workspace(n)
    ydot = np.zeros(pc.state_size(n))
    for _ in range(3):
        y = system.y0.copy()
        y[:n] = rng.uniform(-1.5, 1.5, n)
        # the structure at or below the surface, the links pointing down from it: the dense
        # formulation has no free surface
        y[n] = rng.uniform(-4, 0)
        y[n + 1 : 2 * n + 1] = rng.uniform(-1, 1, n)
        y[2 * n + 1] = rng.uniform(-1, 1)
        t = rng.uniform(0, 10)
        assert pc.rhs(t, y, system.params, w, ydot) == pc.OK
        expected = dense.rhs(t, y)
        scale = np.max(np.abs(expected))
        np.testing.assert_allclose(ydot, expected, rtol=0, atol=1e-8 * scale)
