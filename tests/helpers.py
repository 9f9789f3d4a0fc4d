"""Small builders of cases for the tests."""

import copy
import os
from contextlib import contextmanager
from pathlib import Path

import numpy as np

import seacable
from golden.record import system_rows
from seacable.case import legacy, loader
from seacable.case.system import SystemCase

LEGACY = Path(__file__).parent / "legacy_cases"  # the single-cable form of some examples


def chain_case(n=20, top=None, bottom=None, initial=None, simulation=None, environment=None,
               **cable):  # fmt: skip
    """A case dict for one planar cable of 10 m (1 kg/m) with overridable parts."""
    data = {
        "name": f"test chain {n}",
        "environment": environment or {"in_air": True},
        "cables": [
            {
                "links": n,
                "length": 10.0,
                "diameter": 0.01,
                "mass_per_length": 1.0,
                "top": top or {"type": "fixed"},
                "bottom": bottom or {"type": "free"},
                "initial": initial or {"shape": "arc", "top_angle_deg": 0.0},
                **cable,
            }
        ],
        "simulation": simulation or {"duration": 1.0, "output_interval": 0.1},
    }
    return copy.deepcopy(data)


def system_data(source) -> dict:
    """The mapping ``seacable upgrade`` writes for a single-cable case (a mapping or a file):
    a system of bodies and lines."""
    return legacy.upgrade(loader.load_single_cable(source))


def upgraded(source) -> SystemCase:
    """The system of bodies and lines that ``seacable upgrade`` writes for a single-cable case
    (a mapping, or a file whose table files it keeps reading from the file's folder)."""
    single = loader.load_single_cable(source)
    case = seacable.load_case(legacy.upgrade(single))
    assert isinstance(case, SystemCase)
    case._base_dir = single._base_dir
    return case


def rows(case: SystemCase, **kwargs) -> dict[str, np.ndarray]:
    """A run of a system of lines end to end between two bodies (an upgraded single cable)
    under the single-cable names (``golden.record.system_rows``: ``tension``, ``node_x``,
    ``top_force_z``, ...)."""
    return system_rows(seacable.simulate(case, **kwargs).dataset, case)


def run_rows(data, **kwargs) -> dict[str, np.ndarray]:
    """The upgraded single-cable case ``data`` run: :func:`rows`."""
    return rows(upgraded(data), **kwargs)


def turning_body_case(simulation):
    """A rigid body (off-centre points, turning) hung in air from a fixed point by a lumped line
    of six segments and tied by a spring to a point body, swinging in 3D without drag or
    damping: its energy is constant."""
    rope = {"name": "rope", "diameter": 0.01, "mass_per_length": 2.0, "axial_stiffness": 2.0e5,
            "drag_coefficient_normal": 0.0}  # fmt: skip
    box = {"name": "float", "type": "rigid", "position": [3.0, 1.0, -6.0], "mass": 50.0,
           "inertia": [4.0, 6.0, 8.0], "centre_of_gravity": [0.1, 0.0, -0.2],
           "velocity": [0.0, 1.0, 0.0], "angular_velocity": [0.3, -0.2, 0.5],
           "points": {"hook": [0.2, 0.1, 0.5], "eye": [-0.3, 0.0, -0.4]},
           "external forces": [{"model": "gravity"}]}  # fmt: skip
    weight = {"name": "weight", "type": "point", "position": [3.5, 1.0, -8.0], "mass": 5.0,
              "external forces": [{"model": "gravity"}]}  # fmt: skip
    top = {"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0]}
    lines = [
        {"name": "rope", "model": "lumped_mass", "from": "top", "to": "float.hook",
         "sections": [{"type": "rope", "length": 6.5, "segments": 6}], "initial": "straight"},
        {"name": "spring", "model": "tie", "from": "float.eye", "to": "weight",
         "unstretched_length": 1.0, "stiffness": 3000.0},
    ]  # fmt: skip
    return {"name": "turning body", "start": "as_given", "environment": {"in_air": True},
            "bodies": [top, box, weight], "lines": lines, "line_types": [rope],
            "simulation": simulation}  # fmt: skip


def dense_jacobian(system, t: float, spread: float, seed: int) -> np.ndarray:
    """d(ydot)/dy of a built system by forward differences of its compiled right-hand side, at
    its start state with every velocity moved by ``spread`` times a normal draw (``seed``):
    a moving state."""
    from seacable.system import kernel, model

    p = system.params
    w = model.workspace(system)
    y = system.y0.copy()
    y[p.n_q :] += spread * np.random.default_rng(seed).normal(size=len(y))[p.n_q :]
    base, ydot = np.empty_like(y), np.empty_like(y)
    kernel.rhs(t, y, p, w, base)
    jac = np.zeros((len(y), len(y)))
    for j in range(len(y)):
        step = 1e-6 * max(1.0, abs(y[j]))
        bumped = y.copy()
        bumped[j] += step
        kernel.rhs(t, bumped, p, w, ydot)
        jac[:, j] = (ydot - base) / step
    return jac


@contextmanager
def quiet_stdout():
    """MoorDyn's library prints its progress on the process's standard output: silenced."""
    saved = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    try:
        yield
    finally:
        os.dup2(saved, 1)
        os.close(devnull)
        os.close(saved)
