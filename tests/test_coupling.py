"""The stepping interface (seacable.coupling): a floating-body solver written in Python
(examples/coupled_platform_driver.py) driving the example's three-chain mooring through
``Coupling.step`` gives the platform's surge that seacable's own rigid body gives, and the
interface refuses what it cannot step. Against MoorDyn's own Step: tests/test_moordyn_peer.py."""

import sys
from pathlib import Path

import numpy as np
import pytest

from seacable.coupling import Coupling
from seacable.errors import CaseError

sys.path.insert(0, str(Path(__file__).parents[1] / "examples"))
import coupled_platform_driver as driver  # noqa: E402


def test_a_python_floating_body_solver_drives_the_mooring():
    """60 s of a 1 MN wind ramp: the coupled run (semi-implicit Euler at 0.05 s, the mooring
    stepped by rk4 inside) within 0.5 % of the peak surge of seacable's rigid body (0.07 %
    over 120 s measured)."""
    coupled = driver.coupled(duration=60.0)
    native = driver.native(duration=60.0)
    surge = np.interp(native[:, 0], coupled[:, 0], coupled[:, 1])
    peak = np.abs(native[:, 1]).max()
    assert peak > 50.0
    assert np.abs(surge - native[:, 1]).max() < 5e-3 * peak


def test_what_cannot_be_stepped_is_refused_by_name():
    case = driver.mooring()
    case["simulation"]["integrator"] = "dopri5"
    with pytest.raises(CaseError, match="integrator: rk4 and time_step"):
        Coupling(case)
    with pytest.raises(CaseError, match="coupled body 'anchor_1'"):
        Coupling(driver.mooring(), bodies=["anchor_1"])
    coupling = Coupling(driver.mooring())
    assert coupling.sizes == [6]  # a body with points off its reference: x, y, z and angles
    with pytest.raises(RuntimeError, match="init"):
        coupling.step(np.zeros(6), np.zeros(6), 0.0, 0.1)
    coupling.init(np.zeros(6))
    with pytest.raises(ValueError, match="dt: -0.1"):
        coupling.step(np.zeros(6), np.zeros(6), 0.0, -0.1)
    coupling.step(np.zeros(6), np.zeros(6), 0.0, 0.1)
    with pytest.raises(ValueError, match="steps by 0.1 s"):
        coupling.step(np.zeros(6), np.zeros(6), 0.1, 0.2)
