"""Newton's matrix of the lumped lines written from their laws (numerics.lumped_newton): its
columns equal the difference quotients of the residual, they are written only where every
equation they reach is their line's, a matrix written so costs no residual, the steps
taken with it end where the steps with the differences end, and the lines' blocks are
factorised as 3 x 3 blocks (numerics.bordered's ``tri``)."""

import numpy as np
import pytest

import seacable
from seacable.numerics import bordered, implicit_setup, integrators, system_implicit
from seacable.system import kernel
from seacable.system import model as system_model

STEP = 0.05  # [s]
FRICTION = 0.5


def _case(bending=0.0, band=0.0, buoy=True):
    """Two chains from anchors on the seabed, one to a fairlead that surges and heaves, one
    held taut by a buoy (a point body with its own degrees of freedom), in a current (``buoy``
    False: the first alone)."""
    chain = {"name": "chain", "diameter": 0.1, "mass_per_length": 60.0, "axial_stiffness": 3e8,
             "axial_damping_ratio": 1.0, "drag_coefficient_normal": 1.2,
             "drag_coefficient_tangential": 0.1, "added_mass_coefficient": 1.0,
             "bending_stiffness": bending}  # fmt: skip
    sections = [{"type": "chain", "segments": 12, "length": length} for length in (220.0, 39.9)]
    data = {
        "name": "two chains",
        "environment": {
            "water_density": 1025.0,
            "water_depth": 100.0,
            "current": {"velocity": 0.5, "direction_deg": 30.0},
            "seabed": {
                "stiffness": 3e6,
                "damping": 3e5,
                "friction_coefficient": FRICTION,
                "contact_band": band,
            },
        },  # fmt: skip
        "bodies": [
            {
                "name": "vessel",
                "type": "imposed",
                "points": {"fairlead": [0.0, 0.0, -5.0]},
                "x": {"kind": "sine", "amplitude": 2.0, "period": 10.0},
                "z": {"kind": "sine", "amplitude": 1.0, "period": 6.0},
            },
            {
                "name": "buoy",
                "type": "point",
                "position": [-100.0, 0.0, -60.0],
                "mass": 2000.0,
                "volume": 4.0,
                "external forces": [{"model": "gravity"}, {"model": "buoyancy"}],
            },
            {"name": "a1", "type": "fixed", "position": [130.0, 0.0, -100.0]},
            {"name": "a2", "type": "fixed", "position": [-100.0, 0.0, -100.0]},
        ],  # fmt: skip
        "line_types": [chain],
        "lines": [
            {
                "name": "l1",
                "model": "lumped_mass",
                "from": "vessel.fairlead",
                "to": "a1",
                "sections": [sections[0]],
                "initial": "catenary",
            },
            {
                "name": "l2",
                "model": "lumped_mass",
                "from": "buoy",
                "to": "a2",
                "sections": [sections[1]],
                "initial": "catenary",
            },
        ],  # fmt: skip
        "simulation": {
            "duration": 1.0,
            "output_interval": STEP,
            "integrator": "generalized_alpha",
            "time_step": STEP,
            "build_up": 3.0,
        },
    }
    if not buoy:
        data["bodies"] = [b for b in data["bodies"] if b["name"] not in ("buoy", "a2")]
        data["lines"] = data["lines"][:1]
    return seacable.load_case(data)


def _moving(case, seconds=4.0):
    """The system, its work, a state ``seconds`` into the run and the scheme's acceleration
    there (reached by implicit steps with the differences)."""
    system = system_model.build(case)
    p = system.params
    y = system.y0.copy()
    w = kernel.make_work(p)
    acc = np.zeros(int(p.n_v) + int(p.n_s))
    assert implicit_setup.initial_acceleration(0.0, y, p, w, acc) == 0
    coef = implicit_setup.scheme("generalized_alpha", spectral_radius=0.5)
    inc, lay, rows = implicit_setup.newton(case, system, written=False)
    steps = round(seconds / STEP)
    work = np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
    _, status = system_implicit.chunk(
        0, y, acc, STEP, 1, 1, steps, coef, 1e-9, 10, p, implicit_setup.frozen(p), w, inc, lay,
        rows, implicit_setup.carry(system, lay), np.empty((steps, len(y))), np.empty(steps),
        work, None,
    )  # fmt: skip
    assert status == 0
    return system, w, y, acc, coef


def _matrix(case, system, w, y, acc, coef, written):
    """Newton's matrix (dense) at a1 = acc + 0.01 a step after ``y``, and the residuals it took."""
    p = system.params
    nv = int(p.n_v) + int(p.n_s)
    inc, lay, rows = implicit_setup.newton(case, system, written=written)
    vec = np.zeros((11, len(y)))
    res, mat = np.zeros(nv), np.zeros(lay.size)
    work = np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
    _residual(p, w, inc, y, acc, coef, A1 + acc, vec, res)
    status = system_implicit._jacobian(T1, y, acc, A1 + acc, STEP, coef,
                                       implicit_setup.frozen(p), w, inc, lay, rows, mat, res,
                                       vec, work, None)  # fmt: skip
    assert status == 0
    dense = np.zeros((nv, nv))
    for col in range(nv):
        for z in range(lay.nz_ptr[col], lay.nz_ptr[col + 1]):
            dense[lay.nz_row[z], col] = mat[lay.nz_dest[z]]
    return dense, rows, int(work[2])


T1, A1 = 4.0 + STEP, 0.01  # the step's end and a1 - a0 of the matrices' iterate


def _residual(p, w, inc, y, acc, coef, a1, vec, out):
    nv = len(a1)
    system_implicit._residual(T1, y, acc, a1, STEP, coef, p, w, inc, vec[0], vec[1],
                              vec[2][:nv], out, vec[9][:nv])  # fmt: skip


def test_written_columns_equal_the_residuals_derivative():
    """Tension, its damping, drag in a current, friction and contact with the seabed (a plain
    contact: the band's quadratic spring puts a share eps / 2 d of a node d deep in it into
    any difference quotient): every written column equals the residual's derivative (central
    differences on the laws' branches of the iterate) to 1e-4 of its largest entry (what the
    matrix leaves out, the drag's and the added mass's turn with a segment, is 3e-5 here; the
    differences' forward quotients are 2e-4 off on the nodes that lie still on the seabed,
    where the regularised friction bends); the columns next to the
    buoy are differenced, as are every column of a matrix without written ones."""
    case = _case()
    system, w, y, acc, coef = _moving(case)
    p = system.params
    differenced, _, cost_d = _matrix(case, system, w, y, acc, coef, written=False)
    written, rows, cost_w = _matrix(case, system, w, y, acc, coef, written=True)
    column = rows.lumped_column[: differenced.shape[0]]
    assert list(rows.lumped_line) == [0, 1]
    v2 = int(p.line_v[1]) - int(p.n_q)  # the buoy's line: its first interior node is next to it
    assert not column[v2 : v2 + 3].any() and column[v2 + 3 :].any()
    assert column[int(p.line_v[0]) - int(p.n_q) :][: 3 * 11].all()  # the fairlead's line: all
    others = np.flatnonzero(column == 0)
    assert np.array_equal(written[:, others], differenced[:, others])
    assert cost_w < cost_d  # fewer colours: the buoy's and its neighbours' only
    inc = implicit_setup.increments(case, system)
    nv = len(acc)
    vec, out = np.zeros((11, len(y))), np.zeros((2, nv))
    _residual(p, w, inc, y, acc, coef, acc + A1, vec, out[0])  # the laws' branches there
    assert np.sum(w.nodes[20, : int(p.line_node[1])] != 0.0) >= 4  # kernels.lumped._CONTACT
    frozen = implicit_setup.frozen(p)
    for j in np.flatnonzero(column):
        step = np.zeros(nv)
        step[j] = 1e-4
        for k, sign in enumerate((1.0, -1.0)):
            _residual(frozen, w, inc, y, acc, coef, acc + A1 + sign * step, vec, out[k])
        derivative = (out[0] - out[1]) / 2e-4
        scale = np.max(np.abs(derivative))
        assert np.max(np.abs(written[:, j] - derivative)) <= 1e-4 * scale, j


def test_bending_lines_keep_their_differences():
    """A line with bending stiffness couples each node to the nodes two away: not written."""
    case = _case(bending=1e4)
    system = system_model.build(case)
    _, _, rows = implicit_setup.newton(case, system)
    assert len(rows.lumped_line) == 0 and not rows.lumped_column.any()


@pytest.mark.parametrize(("band", "buoy"), [(0.0, True), (0.005, False)])
def test_steps_with_written_columns_end_where_the_differences_end(band, buoy):
    """Steps of generalized-alpha over 4 s from the moving state, the matrix written or
    differenced: the same states to well within the Newton tolerance's effect, with fewer
    residuals (without the buoy: a matrix written whole, built at every step's first
    iterate)."""
    case = _case(band=band, buoy=buoy)
    system, w, y0, acc0, coef = _moving(case)
    p = system.params
    finals, residuals = [], []
    for written in (False, True):
        inc, lay, rows = implicit_setup.newton(case, system, written=written)
        y, acc = y0.copy(), acc0.copy()
        work = np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
        steps = 80
        _, status = system_implicit.chunk(
            80, y, acc, STEP, 1, 1, steps, coef, 1e-9, 10, p, implicit_setup.frozen(p), w, inc,
            lay, rows, implicit_setup.carry(system, lay), np.empty((steps, len(y))),
            np.empty(steps), work, None,
        )  # fmt: skip
        assert status == 0 and work[1] == 0
        finals.append(y)
        residuals.append(int(work[2]))
    nq = int(p.n_q)
    assert np.max(np.abs(finals[1][:nq] - finals[0][:nq])) < 1e-6  # [m]
    assert residuals[1] < residuals[0]


def test_lumped_blocks_factorised_as_three_by_three_blocks():
    """Both lines' blocks are factorised as 3 x 3 blocks without pivoting (bordered's
    ``tri``), the buoy in the border: a solve with the factors equals a dense solve of the
    same matrix to 1e-12."""
    case = _case()
    system, w, y, acc, coef = _moving(case)
    dense, rows, _ = _matrix(case, system, w, y, acc, coef, written=True)
    inc, lay, rows = implicit_setup.newton(case, system)
    assert list(lay.tri) == [1, 1, 0]  # the two lines, then the border (the buoy)
    mat = np.zeros(lay.size)
    for col in range(dense.shape[0]):
        for z in range(lay.nz_ptr[col], lay.nz_ptr[col + 1]):
            mat[lay.nz_dest[z]] = dense[lay.nz_row[z], col]
    piv = np.zeros(lay.order.shape[0], dtype=np.int64)
    assert bordered.factor(lay, mat, piv)
    rhs = np.random.default_rng(3).normal(size=dense.shape[0])
    x, scratch = np.zeros_like(rhs), np.zeros_like(rhs)
    bordered.solve(lay, mat, piv, rhs, x, scratch)
    exact = np.linalg.solve(dense, rhs)
    assert np.max(np.abs(x - exact)) <= 1e-12 * np.max(np.abs(exact))
