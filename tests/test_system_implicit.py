"""The fixed-step implicit schemes on systems of bodies and lines (numerics.system_implicit):
the bordered banded solver against a dense solve, second-order convergence of Newmark and
generalized-alpha on a spinning rigid body (its orientation moved by rotation vectors) and on
the servo's force (a first-order state), and every line model against a tight dopri5 run at
steps far beyond the explicit limit."""

import functools
import math

import numpy as np
import pytest
from scipy import sparse
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation

import seacable
from helpers import turning_body_case
from seacable.kernels import lumped as lk
from seacable.kernels import waves
from seacable.numerics import bordered
from seacable.system.coordinates import colour


def _bordered_matrix(rng, sizes, n_border, bandwidth):
    """A random matrix of blocks (banded, of the given sizes) coupled through ``n_border``
    unknowns scattered among them, and the border's mask."""
    n = sum(sizes) + n_border
    border = np.zeros(n, dtype=bool)
    border[rng.choice(n, n_border, replace=False)] = True
    inner = np.flatnonzero(~border)
    where = np.flatnonzero(border)
    a = np.zeros((n, n))
    first = 0
    for size in sizes:
        block = inner[first : first + size]
        first += size
        for i in range(size):
            for j in range(max(0, i - bandwidth), min(size, i + bandwidth + 1)):
                a[block[i], block[j]] = rng.normal()
            for b in where[:2]:
                a[block[i], b] = rng.normal() * (i % 3 == 0)
                a[b, block[i]] = rng.normal() * (i % 4 == 0)
    a[np.ix_(where, where)] = rng.normal(size=(n_border, n_border))
    return a + 3.0 * np.eye(n), border


@pytest.mark.parametrize(
    ("sizes", "n_border", "bandwidth"),
    [([10, 20], 3, 2), ([50], 0, 1), ([], 4, 0), ([5, 5, 5], 6, 4), ([12], 2, 11)],
)
def test_bordered_solver_matches_a_dense_solve(sizes, n_border, bandwidth):
    rng = np.random.default_rng(len(sizes) + n_border)
    a, border = _bordered_matrix(rng, sizes, n_border, bandwidth)
    pattern = sparse.csr_matrix(a != 0.0)
    layout = bordered.structure(pattern, border, colour(pattern))
    assert len(layout.start) - 2 == len(sizes)  # blocks that do not couple stay apart
    piv = np.zeros(len(a), dtype=np.int64)
    mat = np.zeros(layout.size)
    for j in range(len(a)):  # as a finite-difference Jacobian fills it
        for k in range(layout.nz_ptr[j], layout.nz_ptr[j + 1]):
            mat[layout.nz_dest[k]] += a[layout.nz_row[k], j]
    assert bordered.factor(layout, mat, piv)
    rhs = rng.normal(size=len(a))
    x, scratch = np.empty_like(rhs), np.empty_like(rhs)
    bordered.solve(layout, mat, piv, rhs, x, scratch)
    assert np.abs(x - np.linalg.solve(a, rhs)).max() < 1e-12 * np.abs(x).max()


def test_a_singular_block_is_reported():
    a = np.eye(4)
    a[1, 1] = 0.0
    pattern = sparse.csr_matrix(np.ones((4, 4)))
    layout = bordered.structure(pattern, np.zeros(4, dtype=bool), colour(pattern))
    mat = np.zeros(layout.size)
    for j in range(4):
        for k in range(layout.nz_ptr[j], layout.nz_ptr[j + 1]):
            mat[layout.nz_dest[k]] += a[layout.nz_row[k], j]
    assert not bordered.factor(layout, mat, np.zeros(4, dtype=np.int64))


def _spinning(integrator, dt=None, **simulation):
    """A rigid body (asymmetric inertia, off-centre gravity) on 6x6 linear springs, spinning
    and swinging; a lumped line between two fixed points beside it (a system needs a line)."""
    sim = {"duration": 1.0, "output_interval": 0.1, "integrator": integrator, **simulation}
    if dt is not None:
        sim["time_step"] = dt
    case = turning_body_case(sim)
    case["bodies"] = [*case["bodies"][:2], {"name": "low", "type": "fixed",
                                            "position": [0.0, 0.0, -6.5]}]  # fmt: skip
    case["lines"] = [{**case["lines"][0], "to": "low"}]
    case["bodies"][1]["external forces"].append(
        {"model": "linear_stiffness", "diagonal": [2000.0, 2000.0, 2000.0, 40.0, 30.0, 20.0]}
    )
    return seacable.simulate(seacable.load_case(case)).dataset["bodies/float"]


def _errors(body, reference):
    position = max(
        float(np.abs(body[k].values - reference[k].values).max())
        for k in ("position_x", "position_y", "position_z")
    )

    def turn(rows):
        angles = np.c_[rows["roll"].values, rows["pitch"].values, rows["yaw"].values]
        return Rotation.from_euler("xyz", angles)

    return position, float((turn(body) * turn(reference).inv()).magnitude().max())


@pytest.mark.parametrize("integrator", ["newmark", "generalized_alpha"])
def test_a_spinning_rigid_body_converges_at_second_order(integrator):
    """Halving the step divides the position and the orientation errors by four: the
    orientation's increments (rotation vectors) are consistent with the scheme."""
    reference = _spinning("dopri5", rtol=1e-12)
    assert np.ptp(reference["yaw"].values) > 1.0  # it turns
    coarse = _errors(_spinning(integrator, 5e-3, newton_tolerance=1e-12), reference)
    fine = _errors(_spinning(integrator, 2.5e-3, newton_tolerance=1e-12), reference)
    for c, f in zip(coarse, fine, strict=True):
        assert 3.5 < c / f < 4.5
    assert fine[1] < 0.03


def _example(name, integrator, duration, **simulation):
    case = seacable.load_case(f"examples/{name}.yaml")
    sim = case.simulation.model_copy(
        update={"integrator": integrator, "duration": duration, **simulation}
    )
    return seacable.simulate(case.model_copy(update={"simulation": sim})).dataset


def _worst(ds, reference) -> tuple[float, str]:
    """The largest difference of any output over the largest magnitude of its kind (the three
    components of a vector together)."""
    worst = (0.0, "")
    for node in reference.subtree:
        rows = node.ds
        for name, values in rows.data_vars.items():
            if name.endswith("energy") or name == "constraint_error":
                continue
            kind = name[:-2] if name[-2:] in ("_x", "_y", "_z") else name
            family = [k for k in rows.data_vars if k == name or k[:-2] == kind]
            scale = max(float(np.nanmax(np.abs(rows[k].values))) for k in family)
            if scale < 1e-6:
                continue
            gap = float(np.nanmax(np.abs(ds[node.path][name].values - values.values))) / scale
            worst = max(worst, (gap, f"{node.path}/{name}"))
    return worst


@pytest.mark.parametrize(
    ("example", "integrator", "dt", "duration", "within"),
    [
        # 40 lumped segments, part on the seabed, fairlead surging: 0.02 s is six times the
        # rk4 stability limit (omega dt = 2.8)
        ("catenary_mooring_line_surge", "generalized_alpha", 0.02, 6.0, 2e-3),
        ("catenary_mooring_line_surge", "newmark", 0.01, 6.0, 1e-5),
        ("two_buoys_moored_with_hawser", "newmark", 0.01, 2.0, 1e-4),  # a loop, point bodies
        ("platform_three_catenary_lines", "newmark", 0.01, 2.0, 1e-3),  # a 6-DOF rigid body
        pytest.param(
            "thesis_6_1_sim2_submerged_12_links", "newmark", 0.01, 2.0, 1e-3, marks=pytest.mark.slow
        ),  # planar links (and the two structures below)
        ("thesis_6_3_sim1_two_floating_structures", "newmark", 0.005, 2.0, 5e-3),
        ("rising_body_four_cables", "newmark", 0.005, 2.0, 1e-3),  # 3D rigid segments
    ],
)
def test_implicit_runs_of_the_examples_agree_with_dopri5(example, integrator, dt, duration,
                                                         within):  # fmt: skip
    reference = _example(example, "dopri5", duration, rtol=1e-9)
    ds = _example(example, integrator, duration, time_step=dt)
    assert ds.attrs["status"] == "complete"
    gap, where = _worst(ds, reference)
    assert gap < within, where
    attrs = ds.attrs
    assert 0 < attrs["solver_jacobian_evaluations"] <= attrs["solver_linear_solves"]


def test_natural_string_converges_at_second_order():
    """Poth's string in its natural variables (strain and angle per node) with Newmark."""
    name, duration = "poth_string_pendulum_natural_variables", 1.0
    reference = _example(name, "dopri5", duration, rtol=1e-10)
    coarse = _worst(_example(name, "newmark", duration, time_step=0.01), reference)[0]
    fine = _worst(_example(name, "newmark", duration, time_step=0.005), reference)[0]
    assert 3.5 < coarse / fine < 4.5


@functools.cache
def _servo_reference():
    return _servo_end("dopri5", rtol=1e-10, atol=1e-10)


def _servo_end(integrator, duration=12.0, **simulation):
    """The servo example's line end (its massless body pulled by the servo's force, a
    first-order state) through the first 2 s of the manoeuvre."""
    case = seacable.load_case("examples/jacquot_marichal_trajectory_servo.yaml")
    sim = {"duration": duration, "output_interval": 0.1, "integrator": integrator, **simulation}
    case = case.model_copy(update={"simulation": type(case.simulation)(**sim)})
    ds = seacable.simulate(case).dataset
    assert ds.attrs["status"] == "complete"
    return np.stack([ds[f"bodies/end/position_{c}"].values for c in "xyz"])


@pytest.mark.parametrize(("integrator", "order"), [("generalized_alpha", 2), ("newmark", 2),
                                                   ("implicit_euler", 1)])  # fmt: skip
def test_the_implicit_schemes_advance_the_servos_force(integrator, order):
    """The servo's force is solved for with the accelerations (its rate an unknown of Newton's
    system, s1 = s0 + h ((1 - g) ds0 + g ds1)): against a tight dopri5 run the error falls by
    2^order when the step is halved (generalized-alpha 5.3e-6, 1.3e-6 and 3.4e-7 m at 20, 10
    and 5 ms, ratios 4.00 and 3.99; Newmark 3.99 and 3.99; implicit Euler 8.1e-4, 4.0e-4 and
    2.0e-4 m, ratios 2.01 and 2.00). Before, the implicit schemes refused the servo."""
    reference = _servo_reference()
    errors = [np.abs(_servo_end(integrator, time_step=dt) - reference).max()
              for dt in (0.01, 0.005)]  # fmt: skip
    assert errors[1] < (1e-5 if order == 2 else 2e-3)
    assert 2**order * 0.9 < errors[0] / errors[1] < 2**order * 1.1


def _buoy(integrator, dt):
    """A sphere (radius 1 m, 800 kg, 400 kg added mass wholly submerged) released 0.3 m below
    its draft on a slack, light line (3 g/m in water) from an anchor 20 m down: its waterplane, so
    its heave stiffness, changes by a quarter over the swing."""
    radius, mass, rho = 1.0, 800.0, 1025.0
    draft = brentq(lambda d: rho * math.pi * d * d * (3 * radius - d) / 3 - mass, 0.0, 2.0)
    rope = {"name": "rope", "diameter": 0.002, "mass_per_length": 2.0 * rho * math.pi * 1e-6,
            "axial_stiffness": 1e5, "drag_coefficient_normal": 0.0,
            "added_mass_coefficient": 0.0}  # fmt: skip
    buoy = {"name": "buoy", "type": "point", "position": [5.0, 0.0, radius - draft - 0.3],
            "mass": mass, "added_mass": 400.0, "shape": {"kind": "sphere", "radius": radius},
            "external forces": [{"model": "gravity"}, {"model": "buoyancy"}]}  # fmt: skip
    anchor = {"name": "anchor", "type": "fixed", "position": [0.0, 0.0, -20.0]}
    case = {"name": "buoy", "start": "as_given", "environment": {"water_depth": 30.0},
            "bodies": [anchor, buoy], "line_types": [rope],
            "lines": [{"name": "line", "model": "lumped_mass", "from": "anchor", "to": "buoy",
                       "sections": [{"type": "rope", "length": 30.0, "segments": 2}]}],
            "simulation": {"duration": 3.0, "output_interval": 0.005, "integrator": integrator,
                           "time_step": dt}}  # fmt: skip
    return seacable.simulate(seacable.load_case(case)).dataset["bodies/buoy/position_z"].values


def test_a_buoy_through_its_waterline_floats_as_with_rk4():
    explicit = _buoy("rk4", 1e-3)
    assert np.ptp(explicit) > 0.5  # it swings through its draft
    np.testing.assert_allclose(_buoy("newmark", 2.5e-3), explicit, atol=3e-4)  # measured 6e-5


def _bent(integrator, **simulation):
    """A light lumped line with bending stiffness (EI 2 N m^2, 20 segments of 0.2 m) from a
    fixed point to a 1 kg ball in air, started on its catenary (which has no bending moments):
    the bending springs set it swinging."""
    rope = {"name": "rope", "diameter": 0.02, "mass_per_length": 1.0, "axial_stiffness": 1e5,
            "bending_stiffness": 2.0}  # fmt: skip
    ball = {"name": "ball", "type": "point", "position": [2.5, 0.0, -2.5], "mass": 1.0,
            "external forces": [{"model": "gravity"}]}  # fmt: skip
    case = {"name": "bent", "start": "as_given", "environment": {"in_air": True},
            "bodies": [{"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0]}, ball],
            "line_types": [rope],
            "lines": [{"name": "line", "model": "lumped_mass", "from": "top", "to": "ball",
                       "sections": [{"type": "rope", "length": 4.0, "segments": 20}]}],
            "simulation": {"duration": 0.5, "output_interval": 0.05, "integrator": integrator,
                           **simulation}}  # fmt: skip
    return seacable.simulate(seacable.load_case(case)).dataset


def test_a_bent_lumped_line_with_newmark_agrees_with_dopri5():
    """Bending couples next-but-one nodes: the Newton matrix's pattern holds them, Newmark
    converges in a few iterations per step and follows a tight dopri5 run."""
    reference = _bent("dopri5", rtol=1e-11, atol=1e-12)["bodies/ball/position_x"].values
    assert np.ptp(reference) > 0.05  # it swings
    ds = _bent("newmark", time_step=5e-4, newton_tolerance=1e-10)
    gap = np.abs(ds["bodies/ball/position_x"].values - reference).max()
    assert gap < 1e-4, gap  # measured 1.3e-5 m of a 0.77 m swing
    steps = ds.attrs["solver_accepted_steps"]  # measured: 4,379 iterations, 29 matrices in
    assert ds.attrs["solver_linear_solves"] <= 5 * steps  # 1,000 steps (a matrix is rebuilt
    assert ds.attrs["solver_jacobian_evaluations"] <= 0.05 * steps  # when iterating costs more)


def test_frozen_laws_keep_the_branches_of_the_last_evaluation():
    """kernels.lumped FROZEN (Newton's matrix): the axial law and the seabed on the branches
    the last LAW evaluation took. At that state the loads are the same; moved across the kinks,
    a slack segment stays slack, a taut one pulls and pushes linearly, a node that touched the
    seabed is pushed even above it."""
    n = 2
    y = np.array([0.0, 0, -10.0, 0.9, 0, -10.0, 2.1, 0, -10.02, *np.zeros(9)])  # 1 slack, 1 taut
    args = (np.ones(2), np.full(2, 1e5), np.zeros(2))  # lengths [m], EA [N], alpha [s]
    loads = (np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2), np.zeros((2, 2)))
    current = (np.zeros(1), np.zeros(1), np.zeros(1))
    still = (0.0, 9.81, waves.still(), 1e30, 0)  # t, g, no waves, depth, stretching
    seabed = (-10.01, np.full(3, 1e4), np.zeros(3), 0.0, 0.01, 0.0)  # z, k, c, mu, slip, band

    def evaluate(state, mode, w):
        lk.segment_loads(state, n, 0, 0, *args, mode, *loads, *current, *still, w)
        lk.seabed_loads(state, n, 0, *seabed, mode, w)
        return w[lk._F : lk._F + 3].copy(), w[lk._T, :n].copy()

    w = np.zeros((lk.N_WORK_ROWS, n + 1))
    forces, tension = evaluate(y, lk.LAW, w)
    assert tension[0] == 0.0 and tension[1] > 0.0
    assert list(w[lk._TAUT, :n]) == [0.0, 1.0] and list(w[lk._CONTACT]) == [0.0, 0.0, 1.0]
    same, _ = evaluate(y, lk.FROZEN, w)
    np.testing.assert_array_equal(same, forces)
    moved = y.copy()
    moved[3] = 1.25  # segment 0 stretched, segment 1 compressed
    moved[8] = -10.0  # node 2 lifted off the seabed
    _, tension = evaluate(moved, lk.FROZEN, w)
    assert tension[0] == 0.0 and tension[1] < 0.0
    assert w[lk._F + 2, 2] < -1e4 * 0.009  # the seabed pulls it back down: k (z_bed - z) < 0


def test_lagged_water_kinematics_are_reused_only_near_where_and_when_they_were_taken():
    """kernels.lumped LAGGED (an implicit step's residuals): a segment's water kinematics are
    those of the last evaluation at the same time while its wetted centroid has moved less
    than REUSE / k_max; farther, or at another time, they are evaluated again, bitwise as LAW
    evaluates them. A reused value differs from the field's by less than REUSE times the
    field's size."""
    n = 2
    y = np.array([0.0, 0, -10.0, 1.0, 0, -10.5, 2.0, 0, -11.0, *np.zeros(9)])
    args = (np.ones(2), np.full(2, 1e5), np.zeros(2))  # lengths [m], EA [N], alpha [s]
    added = np.column_stack([np.ones(2), np.zeros(2)])  # normal, along [kg]
    loads = (np.full(2, 5.0), np.ones(2), np.zeros(2), np.full(2, 7.0), added)
    current = (np.zeros(1), np.zeros(1), np.zeros(1))
    k = 2.0 / 9.81  # deep water, 2 rad/s
    wave = waves.table([[1.5, 2.0, k, 1.0, 0.0, 0.3, 0.0]], waves.DEEP)  # A, W, K, COS, SIN, PHASE
    reach = lk.REUSE / k

    def evaluate(state, mode, w, t=3.0):
        lk.segment_loads(state, n, 0, 0, *args, mode, *loads, *current, t, 9.81, wave, 1e30,
                         0, w)  # fmt: skip
        return w[lk._F : lk._F + 3].copy(), w[lk._WU : lk._WU + 6, :n].copy()

    w = np.zeros((lk.N_WORK_ROWS, n + 1))
    law, water = evaluate(y, lk.LAW, w)
    assert np.abs(water).max() > 0.1  # [m/s, m/s^2]: the wave reaches the segments
    np.testing.assert_array_equal(evaluate(y, lk.LAGGED, w)[0], law)
    near = y.copy()
    near[0] += 0.4 * reach  # segment 0's centroid moves 0.2 reach, segment 1's not at all
    reused, kept = evaluate(near, lk.LAGGED, w)
    np.testing.assert_array_equal(kept, water)
    fresh, exact = evaluate(near, lk.LAW, np.zeros_like(w))
    assert 0.0 < np.abs(exact - water).max() <= lk.REUSE * np.abs(water).max()
    assert np.abs(reused - fresh).max() > 0.0
    far = y.copy()
    far[0] += 3.0 * reach  # beyond reach: evaluated again
    evaluate(y, lk.LAW, w)
    np.testing.assert_array_equal(evaluate(far, lk.LAGGED, w)[0],
                                  evaluate(far, lk.LAW, np.zeros_like(w))[0])  # fmt: skip
    evaluate(y, lk.LAW, w)
    later = evaluate(y, lk.LAGGED, w, t=3.01)[0]  # another time: evaluated again
    np.testing.assert_array_equal(later, evaluate(y, lk.LAW, np.zeros_like(w), t=3.01)[0])


@functools.cache
def _slack_reference(ea):
    """The tight dopri5 run of ``_slack_pendulum`` (1.2 s at EA 1e7 N, 6.4 s at 1e8 N), shared
    by the schemes' cases."""
    return _slack_pendulum("dopri5", ea, rtol=1e-9, atol=1e-10)


def _slack_pendulum(integrator, ea, **simulation):
    """Poth's string pendulum in displacement variables: a 10 m lumped line of 1 kg/m from a
    fixed pivot to a 10 kg end mass, released horizontal, unstretched and at rest in air
    (its segments start exactly at the slack kink)."""
    string = {
        "name": "string",
        "diameter": 0.01,
        "mass_per_length": 1.0,
        "axial_stiffness": ea,
        "axial_damping_time": 1e-3,
    }
    case = {"environment": {"in_air": True},
            "bodies": [{"name": "pivot", "type": "fixed", "position": [0.0, 0.0, 0.0]},
                       {"name": "end", "type": "point", "position": [10.0, 0.0, 0.0],
                        "mass": 10.0, "external forces": [{"model": "gravity"}]}],
            "line_types": [string],
            "lines": [{"name": "string", "model": "lumped_mass", "from": "pivot", "to": "end",
                       "sections": [{"type": "string", "segments": 20, "length": 10.0}],
                       "initial": "straight"}],
            "start": "as_given",
            "simulation": {"duration": 0.4, "output_interval": 0.1, "integrator": integrator,
                           **simulation}}  # fmt: skip
    return seacable.simulate(seacable.load_case(case)).dataset


@pytest.mark.parametrize(
    ("integrator", "stiffness", "bound"),
    [("implicit_euler", 1e7, 2e-2), ("theta", 1e7, 1e-4), ("newmark", 1e7, 1e-4),
     ("generalized_alpha", 1e7, 1e-4), ("generalized_alpha", 1e8, 1e-4)],
)  # fmt: skip
def test_a_stiff_slack_string_steps_through_its_kinks(integrator, stiffness, bound):
    """A stiff string released slack at 5 ms steps (EA 1e7 N: 2,500 times the explicit limit's
    step; 1e8 N: 7,900 times). Forward differences across the slack kink gave slack segments
    their taut stiffness and Newton crept or cycled: three of the four schemes failed at
    t = 0. Newton's matrix on the laws' branches (``implicit_setup.frozen``) and a line search
    step through; the end mass follows a tight dopri5 run (its swing 0.4 s long, 0.8 m
    down)."""
    reference = _slack_reference(stiffness)
    ds = _slack_pendulum(integrator, stiffness, time_step=5e-3, newton_tolerance=1e-7,
                         max_newton_iterations=20)  # fmt: skip
    assert ds.attrs["status"] == "complete"
    gap = max(
        np.abs(ds[f"bodies/end/position_{a}"].values - reference[f"bodies/end/position_{a}"].values)
        .max() for a in "xz"
    )  # fmt: skip
    assert gap < bound, gap  # 9.8e-3 m (first order), 1.8e-5, 1.8e-5, 2.6e-5; 1e8: 2.6e-5 m
