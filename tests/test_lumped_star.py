"""Lumped-mass cables on one shared body (a star of extensible lines, the systems that
``seacable upgrade`` writes): the four-cable rising body against its symmetric quarter (one
cable on an exact vertical guide), energy conservation and Newton's law of an asymmetric star
in air, implicit against explicit, the sparsity pattern, refusals."""

from pathlib import Path

import numpy as np
import pytest

import seacable
from helpers import dense_jacobian, system_data, upgraded
from seacable.case import loader
from seacable.system import model

EXAMPLES = Path(__file__).parent / "legacy_cases"  # the single-cable form of the examples


def _lumped(name, duration=3.0, integrator="rk4", time_step=0.0005):
    """The example ``name`` with lumped-mass cables (EA 1e7 N), upgraded and run: the case and
    its results' tree."""
    data = loader.load_single_cable(EXAMPLES / f"{name}.yaml").model_dump(
        mode="json", exclude_unset=True
    )
    data["simulation"].update(duration=duration, integrator=integrator, time_step=time_step)
    for cable in data["cables"]:
        cable.update(model="lumped_mass", axial_stiffness=1e7)
    case = upgraded(data)
    return case, seacable.simulate(case).dataset


def _cable(case, tree, body, first):
    """Tension [N] of the lines joining ``first`` (a fixed top) to ``body``, from the top
    down (m, segments), and the force on the top [N] (m, 3)."""
    chain, tensions, point = [], [], first
    lines = list(case.lines)
    while point != body:
        line = next(ln for ln in lines if point in (ln.from_, ln.to) and ln not in chain)
        chain.append(line)
        forward = line.from_ == point
        tension = tree[f"lines/{line.name}/tension"].values
        tensions.append(tension if forward else tension[:, ::-1])
        point = line.to if forward else line.from_
    top, end = chain[0], "from" if chain[0].from_ == first else "to"
    force = np.stack([tree[f"lines/{top.name}/{end}_force_{c}"].values for c in "xyz"], axis=1)
    return np.concatenate(tensions, axis=1), force


@pytest.mark.slow  # 20 s: two runs of 6 s (systems: the golden four-cable body too)
def test_star_of_four_is_its_guided_quarter():
    """Symmetry holds the shared body on its vertical: each cable of the star then moves as
    the single cable with a quarter of the body on an exact vertical guide."""
    one_case, one = _lumped("rising_body_single_cable_guided")
    four_case, four = _lumped("rising_body_four_cables")
    end = one["bodies/end/position_z"].values
    assert end[-1] - end[0] > 5.0  # it rises
    assert np.abs(four["bodies/buoy/position_z"].values - end).max() < 1e-8
    buoy = np.hypot(four["bodies/buoy/position_x"].values, four["bodies/buoy/position_y"].values)
    assert buoy.max() < 1e-9
    tension, anchor = _cable(one_case, one, "end", "top")
    scale = np.abs(tension).max()
    for k in range(4):
        leg, force = _cable(four_case, four, "buoy", f"cable {k + 1} top")
        diff = np.abs(leg - tension).max()
        assert diff < 1e-3 * scale, (k, diff)
        np.testing.assert_allclose(np.linalg.norm(force, axis=1), np.linalg.norm(anchor, axis=1),
                                   atol=1e-3 * scale)  # fmt: skip


LEGS = ((0.0, 45.0), (100.0, 50.0), (160.0, 46.0), (230.0, 48.0))  # azimuth [deg], length [m]


def _asymmetric(integrator="rk4", time_step=0.001, duration=2.0, output_interval=0.05):
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
    return upgraded({
        "environment": {"in_air": True},
        "bodies": [{"name": "weight", "position": [3.0, -2.0, -30.0], "mass": 300.0}],
        "cables": cables,
        "simulation": {"duration": duration, "output_interval": output_interval,
                       "integrator": integrator, "time_step": time_step},
    })  # fmt: skip


def test_asymmetric_star_conserves_energy():
    ds = seacable.simulate(_asymmetric()).dataset
    energy = ds["total_energy"].values
    motion = np.abs(ds["kinetic_energy"].values).max()
    assert motion > 100.0  # it swings
    assert np.ptp(energy) < 1e-4 * motion


def test_the_star_body_follows_newtons_law():
    """The body (300 kg: the legs' half segments next to it are theirs) under the legs' pulls
    and its weight: its momentum changes by their impulse, Simpson's rule over two rk4 steps
    (output at every step)."""
    h, mass = 0.001, 300.0
    body = seacable.simulate(_asymmetric(duration=0.2, output_interval=h)).dataset["bodies/weight"]
    for a in "xyz":
        pull = body[f"line_force_{a}"].values - (mass * 9.81 if a == "z" else 0.0)
        velocity = body[f"velocity_{a}"].values
        change = mass * (velocity[2::2] - velocity[:-2:2])
        impulse = h / 3 * (pull[:-2:2] + 4 * pull[1:-1:2] + pull[2::2])
        np.testing.assert_allclose(change, impulse, atol=1e-6 * np.abs(pull).max() * 2 * h)


def test_a_star_leg_must_reach_the_shared_body():
    data = loader.load_single_cable(EXAMPLES / "rising_body_four_cables.yaml").model_dump(
        mode="json", exclude_unset=True
    )
    for cable in data["cables"]:
        cable.update(model="lumped_mass", axial_stiffness=1e7)
    data["cables"][2]["initial"]["azimuth_deg"] = 10.0
    refusal = (
        r"lines \(cable 3 2\)\.initial: the given angles end the line at .* but its 'to' point"
    )
    with pytest.raises(seacable.CaseError, match=refusal):
        model.build(seacable.load_case(system_data(data)))


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
        name = f"bodies/weight/position_{a}"
        diff = np.abs(explicit[name].values - bdf[name].values).max()
        assert diff < 1e-4, (a, diff)


def test_star_jacobian_lies_in_its_sparsity_pattern():
    """Every entry of the star's Jacobian (dense finite differences of the compiled right-hand
    side, in a moving state) falls inside the pattern SciPy's coloured differences assume."""
    system = model.build(_asymmetric(duration=0.3))
    jac = dense_jacobian(system, 0.3, 0.5, 1)
    pattern = model.jacobian_sparsity(system).toarray() != 0
    assert np.abs(jac).max() > 1.0
    outside = np.abs(jac[~pattern]).max()
    assert outside == 0.0, outside
    assert pattern.sum() < 0.2 * pattern.size  # sparse: not the dense pattern
