"""Lumped-mass cables on one shared body (a star of extensible cables): the four-cable rising
body against its symmetric quarter (one cable on an exact vertical guide), symmetry, energy
conservation of an asymmetric star in air, implicit against explicit, refusals."""

from pathlib import Path

import numpy as np
import pytest

import seacable
from seacable.kernels import lumped_star as ls
from seacable.models import lumped_star
from seacable.numerics import stiff
from seacable.simulation import build_system


def _load(source):
    """A case of either form: the single-cable form (``cables:``) through
    ``load_single_cable`` while the single-cable core exists, a system through ``load_case``."""
    from pathlib import Path

    from seacable.case import loader

    text = (
        Path(source).read_text()
        if isinstance(source, (str, Path)) and Path(str(source)).exists()
        else source
    )
    single = ("cables" in text) if isinstance(text, dict) else ("\ncables:" in "\n" + str(text))
    return loader.load_single_cable(source) if single else seacable.load_case(source)


EXAMPLES = Path(__file__).parent / "legacy_cases"  # the single-cable form of the examples
FORCE = ("top_force_x", "top_force_y", "top_force_z")


def _lumped(name, duration=3.0, integrator="rk4", time_step=0.0005):
    data = _load(EXAMPLES / f"{name}.yaml").model_dump(mode="json", exclude_unset=True)
    data["simulation"].update(duration=duration, integrator=integrator, time_step=time_step)
    for cable in data["cables"]:
        cable.update(model="lumped_mass", axial_stiffness=1e7)
    return seacable.simulate(_load(data)).dataset


@pytest.mark.slow  # the single-cable core's star (19 s); systems: the golden four-cable body
def test_star_of_four_is_its_guided_quarter():
    """Symmetry holds the shared body on its vertical: each cable of the star then moves as
    the single cable with a quarter of the body on an exact vertical guide."""
    one = _lumped("rising_body_single_cable_guided")
    four = _lumped("rising_body_four_cables")
    end = one["node_z"].values[:, -1]
    assert end[-1] - end[0] > 5.0  # it rises
    assert np.abs(four["body_z"].values - end).max() < 1e-8
    assert np.hypot(four["body_x"].values, four["body_y"].values).max() < 1e-9
    scale = np.abs(one["tension"].values).max()
    for k in range(4):
        diff = np.abs(four["tension"].values[:, k] - one["tension"].values).max()
        assert diff < 1e-3 * scale, (k, diff)
    force = np.linalg.norm(np.stack([four[f].values for f in FORCE]), axis=0)
    anchor = np.linalg.norm(np.stack([one[f].values for f in FORCE]), axis=0)
    np.testing.assert_allclose(force, anchor[:, None] * np.ones((1, 4)), atol=1e-3 * scale)


LEGS = ((0.0, 45.0), (100.0, 50.0), (160.0, 46.0), (230.0, 48.0))  # azimuth [deg], length [m]


def _asymmetric(integrator="rk4", time_step=0.001, duration=2.0):
    """Four cables of different lengths from four points in air to a 300 kg body below,
    started on their catenaries with the body off its balance (four, as in the rising-body
    star: a star's kernels are compiled for its number of cables)."""
    cables = []
    for k, (azimuth, length) in enumerate(LEGS):
        a = np.radians(azimuth)
        top = [float(30.0 * np.cos(a)), float(30.0 * np.sin(a)), 0.0]
        cables.append({
            "name": f"leg {k}", "model": "lumped_mass", "links": 8, "length": length,
            "diameter": 0.05, "mass_per_length": 2.0, "axial_stiffness": 1e6,
            "top": {"type": "fixed", "position": top},
            "bottom": {"type": "attached", "body": "weight"},
            "initial": {"shape": "catenary"},
        })  # fmt: skip
    return _load({
        "environment": {"in_air": True},
        "bodies": [{"name": "weight", "position": [3.0, -2.0, -30.0], "mass": 300.0}],
        "cables": cables,
        "simulation": {"duration": duration, "output_interval": 0.05, "integrator": integrator,
                       "time_step": time_step},
    })  # fmt: skip


def test_asymmetric_star_conserves_energy():
    ds = seacable.simulate(_asymmetric()).dataset
    energy = ds["total_energy"].values
    motion = np.abs(ds["kinetic_energy"].values).max()
    assert motion > 100.0  # it swings
    assert np.ptp(energy) < 1e-4 * motion
    # Newton's law on the body's node (the body and the half segments next to it): the legs'
    # pulls and its weight
    mass = 300.0 + sum(0.5 * 2.0 * length / 8 for _, length in LEGS)
    for a in "xyz":
        pull = ds[f"bottom_force_{a}"].values.sum(axis=1) - (mass * 9.81 if a == "z" else 0.0)
        acc = ds[f"body_acceleration_{a}"].values
        np.testing.assert_allclose(mass * acc, pull, atol=1e-6 * np.abs(pull).max())


def test_a_star_shares_one_model():
    data = _load(EXAMPLES / "rising_body_four_cables.yaml").model_dump(
        mode="json", exclude_unset=True
    )
    data["cables"][1].update(model="lumped_mass", axial_stiffness=1e7)
    with pytest.raises(seacable.CaseError, match=r"cables\[1\]\.model: value 'lumped_mass'"):
        seacable.simulate(_load(data))
    for cable in data["cables"]:
        cable.update(model="lumped_mass", axial_stiffness=1e7)
    data["cables"][2]["initial"]["azimuth_deg"] = 10.0
    with pytest.raises(seacable.CaseError, match=r"cables\[2\]\.initial .*body 'buoy'"):
        seacable.simulate(_load(data))


def test_sparse_bdf_star_agrees_with_rk4():
    """SciPy's BDF with the star's sparse Jacobian pattern (each chain's last node and the body
    coupled): the same motion as rk4."""
    explicit = seacable.simulate(_asymmetric(duration=1.0)).dataset
    case = _asymmetric(duration=1.0)
    sim = case.simulation.model_copy(
        update={"integrator": "bdf", "rtol": 1e-8, "atol": 1e-8, "time_step": None}
    )
    bdf = seacable.simulate(case.model_copy(update={"simulation": sim})).dataset
    for a in "xyz":
        diff = np.abs(explicit[f"body_{a}"].values - bdf[f"body_{a}"].values).max()
        assert diff < 1e-4, (a, diff)


def test_star_jacobian_lies_in_its_sparsity_pattern():
    """Every entry of the star's Jacobian (dense finite differences of the compiled right-hand
    side, mid-motion) falls inside the pattern SciPy's coloured differences assume."""
    case = _asymmetric(duration=0.3)
    system = build_system(case)
    model = lumped_star
    ds = seacable.simulate(case).dataset
    y = system.y0.copy()
    w = model.workspace(system)
    ydot = np.empty_like(y)
    # a moving state: the run's last positions and velocities (velocities from the nodes)
    hub = 3 * system.cables * system.n_links
    for c, a in enumerate("xyz"):
        y[hub + c] = ds[f"body_{a}"].values[-1]
        y[len(y) // 2 + hub + c] = ds[f"body_velocity_{a}"].values[-1]
    base = np.empty_like(y)
    ls.rhs(0.3, y, system.params, w, base)
    jac = np.zeros((len(y), len(y)))
    for j in range(len(y)):
        step = 1e-6 * max(1.0, abs(y[j]))
        bumped = y.copy()
        bumped[j] += step
        ls.rhs(0.3, bumped, system.params, w, ydot)
        jac[:, j] = (ydot - base) / step
    pattern = stiff.graph_sparsity(model.node_graph(system), 3).toarray() != 0
    assert np.abs(jac).max() > 1.0
    outside = np.abs(jac[~pattern]).max()
    assert outside == 0.0, outside
    assert pattern.sum() < 0.2 * pattern.size  # sparse: not the dense pattern
