"""A rigid line's Newton rows in maximal coordinates (numerics.rigid_newton): the correction
they give equals the dense one (J^-1 r with J by central differences over every acceleration;
a line from an imposed body to a free or held tip, and the thesis's line from its heaving
structure), their band does not grow with the number of links, and an implicit run with them
follows the run with the dense block and a tight dopri5 run."""

import numpy as np
import pytest
from numba import njit

import seacable
from seacable.bodies import kinematics
from seacable.numerics import bordered, implicit_setup, rigid_newton, system_implicit
from seacable.system import kernel, rigid
from seacable.system import model as system_model


@njit
def _jacobian(t1, y0, acc, a1, h, coef, pj, w, inc, lay, rows, mat, r0, vec, work):
    """system_implicit._jacobian (compiled for compiled callers only), its rigid rows on."""
    return system_implicit._jacobian(t1, y0, acc, a1, h, coef, pj, w, inc, lay, rows, mat, r0,
                                     vec, work, True)  # fmt: skip


def _line_case(n, integrator="generalized_alpha", duration=1.0, held=False, **simulation):
    """A planar line of n links (20 m, with joint springs and dampers, drag, a current) from a
    crane tip that surges, to a 30 kg clump with drag (``held``: to a fixed point instead;
    "joint": with a spring and damper there), starting on an arc."""
    angles = np.radians(np.linspace(20.0, 50.0, n))  # the arc's links
    end = [20.0 / n * float(np.sin(angles).sum()), 0.0, -20.0 / n * float(np.cos(angles).sum())]
    bodies = [
        {"name": "top", "type": "imposed", "x": {"kind": "sine", "amplitude": 1.0, "period": 3.0}},
        {
            "name": "end",
            "type": "point",
            "position": end,
            "mass": 30.0,
            "volume": 0.004,
            "external forces": [
                {"model": "gravity"},
                {"model": "buoyancy"},
                {"model": "drag", "drag_coefficient": 1.0, "area": [0.1, 0.1, 0.1]},
            ],
        },
    ]
    if held:
        bodies[1] = {"name": "end", "type": "fixed", "position": end}
    line_type = {
        "name": "rope",
        "diameter": 0.03,
        "mass_per_length": 2.0,
        "bending_stiffness": 5.0,
        "drag_coefficient_normal": 1.2,
        "drag_coefficient_tangential": 0.05,
        "added_mass_coefficient": 0.0,
    }
    line = {
        "name": "rope",
        "model": "rigid_links",
        "from": "top",
        "to": "end",
        "sections": [{"type": "rope", "segments": n, "length": 20.0}],
        "initial": {"arc_deg": [20.0, 50.0]},
        "base_reference": [0.0, 0.0, -1.0],
        "joint_damping": 0.5,
    }
    if held == "joint":
        line.update({"tip_joint_stiffness": 40.0, "tip_joint_damping": 0.3,
                     "tip_reference": [0.6, 0.0, -0.8]})  # fmt: skip
    data = {
        "environment": {"water_depth": 100.0, "current": {"velocity": 0.4}},
        "bodies": bodies,
        "line_types": [line_type],
        "lines": [line],
        "start": "as_given",
        "simulation": {
            "duration": duration,
            "output_interval": 0.1,
            "integrator": integrator,
            **simulation,
        },
    }
    return seacable.load_case(data)


SCHEMES = [
    (implicit_setup.scheme("generalized_alpha", spectral_radius=0.5), 0.05),
    (implicit_setup.scheme("implicit_euler"), 0.01),
]  # the schemes and steps [s] the corrections are compared at


def _corrections(case, scheme, h, lines=1, bodies=0):
    """The Newton correction at a perturbed state and acceleration: (maximal coordinates, the
    dense J^-1 r with J by central differences)."""
    system = system_model.build(case)
    p = system.params
    w = kernel.make_work(p)
    nq, nv = int(p.n_q), int(p.n_v)
    rng = np.random.default_rng(3)
    y = system.y0.copy()
    v, q, n = int(p.rs_v[0]), int(p.rs_q[0]), int(p.rs_n[0])
    if p.rs_kind[0] == rigid.PLANAR:
        y[v : v + n] += 0.5 * rng.normal(size=n)  # a moving line
    else:  # rates normal to the directors
        e = y[q : q + 3 * n].reshape(n, 3)
        u = 0.5 * rng.normal(size=(n, 3))
        y[v : v + 3 * n] += (u - np.sum(u * e, axis=1)[:, None] * e).ravel()
    acc = np.zeros(nv)
    assert implicit_setup.initial_acceleration(0.3, y, p, w, acc) == 0
    a1 = acc + rng.normal(size=nv)
    for body in np.flatnonzero(p.body_kind == kinematics.DYNAMIC):  # held axes keep a0's
        bv, size = int(p.body_v[body]) - nq, 6 if p.body_rigid[body] else 3
        held = np.flatnonzero(p.body_free[body, :size] == 0.0)
        a1[bv + held] = acc[bv + held]  # (their rows k_m delta = r give delta = 0 in a run)
    inc, lay, rows = implicit_setup.newton(case, system)
    assert (len(rows.line), len(rows.body)) == (lines, bodies)
    vec = np.zeros((10, len(y)))
    ydot = np.empty(len(y))
    kernel.rhs(0.3, y, p, w, ydot)
    vec[9][:nv] = ydot[nq : nq + nv]

    def residual(a):
        out = np.zeros(nv)
        system_implicit._residual(0.3 + h, y, acc, a, h, scheme, p, w, inc, vec[0], vec[1],
                                  vec[2][:nv], out, vec[9][:nv])  # fmt: skip
        return out

    jac = np.empty((nv, nv))
    for j in range(nv):
        step = np.zeros(nv)
        step[j] = 1e-5 * max(1.0, abs(a1[j]))
        jac[:, j] = (residual(a1 + step) - residual(a1 - step)) / (2.0 * step[j])
    res = residual(a1)
    dense = np.linalg.solve(jac, res)
    mat = np.zeros(lay.size)
    piv = np.zeros(lay.order.shape[0], dtype=np.int64)
    counters = np.zeros(8, dtype=np.int64)
    status = _jacobian(0.3 + h, y, acc, a1, h, scheme, p, w, inc, lay, rows, mat, res, vec,
                       counters)  # fmt: skip
    assert status == 0
    assert bordered.factor(lay, mat, piv)
    big = np.zeros((3, rows.size))
    rigid_newton.rhs(rows, p, res, big[0])
    bordered.solve(lay, mat, piv, big[0], big[1], big[2])
    return big[1][:nv], dense


@pytest.mark.parametrize("held", [False, True, "joint"])
@pytest.mark.parametrize(("scheme", "h"), SCHEMES)
def test_the_correction_in_maximal_coordinates_is_the_dense_one(scheme, h, held):
    maximal, dense = _corrections(_line_case(8, held=held), scheme, h)
    assert np.abs(maximal - dense).max() < 1e-6 * np.abs(dense).max()


@pytest.mark.parametrize(("planar", "aux", "rates"), [(True, (8, 2), 1), (False, (12, 3), 3)])
def test_the_band_does_not_grow_with_the_links(planar, aux, rates):
    """Planar links (kl = ku = 9) and 3D segments (kl = 16, ku = 17): per link ``aux``
    auxiliary unknowns, then more at the tip; ``rates`` velocity variables per link."""
    widths = []
    for n in (10, 40, 160):
        case = _line_case(n) if planar else _line_3d_case(n)
        system = system_model.build(case)
        inc, lay, rows = implicit_setup.newton(case, system)
        assert list(rows.line) == [0] and len(lay.start) == 3  # one block, no border
        assert rows.size == int(system.params.n_v) + aux[0] * n + aux[1]
        widths.append((int(lay.kl[0]), int(lay.ku[0])))
        assert lay.size <= 60 * rows.size  # entries: O(unknowns)
        dense = implicit_setup.newton(case, system, maximal=False)[1]
        assert dense.kl[0] == rates * n - 1  # the block in the rates: full
    assert widths[0] == widths[1] == widths[2]
    assert widths[0] == ((9, 9) if planar else (16, 17))


def _gap(ds, reference, names=("position_x", "position_z")):
    """The largest difference of the end body's position [m] and of the top's line force
    (relative to its largest)."""
    worst = 0.0
    for name in names:
        a, b = ds[f"bodies/end/{name}"].values, reference[f"bodies/end/{name}"].values
        worst = max(worst, float(np.abs(a - b).max()))
    force = [ds["bodies/top/line_force_x"].values, reference["bodies/top/line_force_x"].values]
    scale = float(np.abs(force[1]).max())
    return worst, float(np.abs(force[0] - force[1]).max()) / scale


def test_an_implicit_run_follows_the_dense_block_and_dopri5(monkeypatch):
    case = _line_case(12, time_step=0.02, duration=2.0)
    banded = seacable.simulate(case).dataset
    assert banded.attrs["status"] == "complete"
    reference = seacable.simulate(
        _line_case(12, integrator="dopri5", duration=2.0, rtol=1e-9)
    ).dataset
    position, force = _gap(banded, reference)
    assert position < 5e-3 and force < 2e-2  # the scheme's own error at 20 ms
    monkeypatch.setattr(rigid_newton, "eligible", lambda p: ([], {}))
    dense = seacable.simulate(case).dataset
    position, force = _gap(banded, dense)
    assert position < 1e-7 and force < 1e-7  # the same iteration, to Newton's tolerance


def _thesis(integrator="newmark", **simulation):
    """The thesis's 12 links from its heaving structure (a dynamic base body), in air."""
    case = seacable.load_case("examples/thesis_6_1_sim1_air_12_links.yaml")
    sim = case.simulation.model_copy(update={"integrator": integrator, **simulation})
    return case.model_copy(update={"simulation": sim})


@pytest.mark.parametrize(("scheme", "h"), SCHEMES)
def test_a_dynamic_base_body_keeps_the_dense_correction(scheme, h):
    maximal, dense = _corrections(_thesis(), scheme, h, lines=1, bodies=1)
    assert np.abs(maximal - dense).max() < 1e-5 * np.abs(dense).max()


def test_the_thesis_case_with_newmark_follows_the_dense_block_and_dopri5(monkeypatch):
    """Pouzada's 12 links in air from the heaving structure (the line's base is a dynamic body,
    its tip a 60 kg mass): 3 s at 10 ms."""
    banded = seacable.simulate(_thesis(time_step=0.01, duration=3.0)).dataset
    assert banded.attrs["status"] == "complete"
    reference = seacable.simulate(_thesis("dopri5", duration=3.0, rtol=1e-9)).dataset
    top = "bodies/top/position_z"
    heave = float(np.abs(reference[top].values).max())
    assert np.abs(banded[top].values - reference[top].values).max() < 1e-2 * heave
    assert _gap(banded, reference)[0] < 0.05  # m, the end of a 240 m line swinging
    monkeypatch.setattr(rigid_newton, "eligible", lambda p: ([], {}))
    dense = seacable.simulate(_thesis(time_step=0.01, duration=3.0)).dataset
    assert np.abs(banded[top].values - dense[top].values).max() < 1e-8 * heave
    assert _gap(banded, dense)[0] < 1e-6


def _buoy_with_two_lines():
    """A buoy free in surge and heave (a point body) carrying two planar lines of 6 links to
    two clumps, in water with a current: a body row with two lines' base forces."""
    clump = {"mass": 20.0, "volume": 0.003, "external forces": [
        {"model": "gravity"}, {"model": "buoyancy"},
        {"model": "drag", "drag_coefficient": 1.0, "area": [0.05, 0.05, 0.05]}]}  # fmt: skip
    lines, bodies = [], []
    for k, side in enumerate((1.0, -1.0)):
        angles = np.radians(side * np.linspace(10.0, 40.0, 6))
        end = [float(np.sin(angles).sum()), 0.0, -2.0 - float(np.cos(angles).sum())]
        bodies.append({"name": f"clump {k}", "type": "point", "position": end, **clump})
        lines.append({
            "name": f"line {k}", "model": "rigid_links", "from": "buoy", "to": f"clump {k}",
            "sections": [{"type": "rope", "segments": 6, "length": 6.0}],
            "initial": {"arc_deg": [side * 10.0, side * 40.0]},
            "base_reference": [0.0, 0.0, -1.0], "joint_damping": 0.2,
        })  # fmt: skip
    buoy = {
        "name": "buoy", "type": "point", "position": [0.0, 0.0, -2.0], "mass": 200.0,
        "volume": 0.1, "dofs": ["surge", "heave"],
        "external forces": [{"model": "gravity"}, {"model": "buoyancy"},
                            {"model": "drag", "drag_coefficient": 0.8, "area": [0.3, 0.3, 0.3]},
                            {"model": "linear_stiffness", "diagonal": [50.0, 0, 0, 0, 0, 0],
                             "equilibrium_position": [0.0, 0.0, -2.0]}],
    }  # fmt: skip
    rope = {"name": "rope", "diameter": 0.02, "mass_per_length": 1.5, "bending_stiffness": 2.0,
            "drag_coefficient_normal": 1.2, "added_mass_coefficient": 0.0}  # fmt: skip
    return seacable.load_case({
        "environment": {"water_depth": 50.0, "current": {"velocity": 0.3}},
        "bodies": [buoy, *bodies], "line_types": [rope], "lines": lines, "start": "as_given",
        "simulation": {"duration": 1.0, "output_interval": 0.1, "integrator": "newmark",
                       "time_step": 0.01},
    })  # fmt: skip


def test_a_body_carrying_two_lines_keeps_the_dense_correction():
    scheme = implicit_setup.scheme("generalized_alpha", spectral_radius=0.5)
    maximal, dense = _corrections(_buoy_with_two_lines(), scheme, 0.05, lines=2, bodies=1)
    assert np.abs(maximal - dense).max() < 1e-5 * np.abs(dense).max()


def _line_3d_case(n, integrator="generalized_alpha", duration=1.0, tip="clump", **simulation):
    """A 3D line of n segments (20 m, joint springs and dampers, added mass, drag, a current
    across) from a crane tip that surges and sways, to a 30 kg clump with drag (``tip``
    "held": to a fixed point instead; "base": from a 300 kg buoy free in surge, sway and heave
    instead of the crane tip; "rigid": from a point 1 m off a rigid body's reference, the body
    free in surge, sway and heave only; "surface": the crane tip 1.5 m above the water, its first
    segment through the surface; "joint": held, with a spring and damper there; "heave held":
    the clump free in surge and sway only), starting on an arc in a plane 30 degrees from x."""
    angles = np.radians(np.linspace(20.0, 50.0, n))
    reach = 20.0 / n * float(np.sin(angles).sum())
    azimuth = np.radians(30.0)
    top = [0.0, 0.0, {"base": -2.0, "rigid": -2.0, "surface": 1.5}.get(tip, 0.0)]
    end = [top[0] + reach * float(np.cos(azimuth)), top[1] + reach * float(np.sin(azimuth)),
           top[2] - 20.0 / n * float(np.cos(angles).sum())]  # fmt: skip
    crane = {"name": "top", "type": "imposed",
             "x": {"kind": "sine", "amplitude": 1.0, "period": 3.0},
             "y": {"kind": "sine", "amplitude": 0.5, "period": 4.0},
             "z": {"kind": "constant", "value": top[2]}}  # fmt: skip
    if tip in ("base", "rigid"):
        crane = {"name": "top", "type": "point", "position": top, "mass": 300.0,
                 "volume": 0.2, "dofs": ["surge", "sway", "heave"],
                 "external forces": [
                     {"model": "gravity"}, {"model": "buoyancy"},
                     {"model": "drag", "drag_coefficient": 0.8, "area": [0.3, 0.3, 0.3]},
                     {"model": "linear_stiffness", "diagonal": [80.0, 60.0, 0, 0, 0, 0],
                      "equilibrium_position": top}]}  # fmt: skip
    line_from = "top"
    if tip == "rigid":  # the same buoy, rigid, the line from a point 1 m off its reference
        crane.update({"type": "rigid", "position": [-1.0, 0.0, -2.0], "inertia": [50.0] * 3,
                      "points": {"fairlead": [1.0, 0.0, 0.0]}})  # fmt: skip
        line_from = "top.fairlead"
    clump = {"name": "end", "type": "point", "position": end, "mass": 30.0, "volume": 0.004,
             "external forces": [{"model": "gravity"}, {"model": "buoyancy"},
                                 {"model": "drag", "drag_coefficient": 1.0,
                                  "area": [0.1, 0.1, 0.1]}]}  # fmt: skip
    if tip in ("held", "joint"):
        clump = {"name": "end", "type": "fixed", "position": end}
    if tip == "heave held":
        clump["dofs"] = ["surge", "sway"]
    line_type = {"name": "rope", "diameter": 0.03, "mass_per_length": 2.0,
                 "bending_stiffness": 5.0, "drag_coefficient_normal": 1.2,
                 "drag_coefficient_tangential": 0.05, "added_mass_coefficient": 1.0}  # fmt: skip
    line = {"name": "rope", "model": "rigid_segments_3d", "from": line_from, "to": "end",
            "sections": [{"type": "rope", "segments": n, "length": 20.0}],
            "initial": {"arc_deg": [20.0, 50.0], "azimuth_deg": 30.0},
            "base_reference": [0.0, 0.0, -1.0], "joint_damping": 0.5}  # fmt: skip
    if tip == "joint":
        line.update({"tip_joint_stiffness": 40.0, "tip_joint_damping": 0.3,
                     "tip_reference": [0.6, 0.0, -0.8]})  # fmt: skip
    return seacable.load_case({
        "environment": {"water_depth": 100.0, "current": {"velocity": 0.4, "direction_deg": 100.0}},
        "bodies": [crane, clump], "line_types": [line_type], "lines": [line],
        "start": "as_given",
        "simulation": {"duration": duration, "output_interval": 0.1, "integrator": integrator,
                       **simulation},
    })  # fmt: skip


@pytest.mark.parametrize(
    "tip", ["clump", "held", "base", "rigid", "surface", "joint", "heave held"]
)
@pytest.mark.parametrize(("scheme", "h"), SCHEMES)
def test_a_3d_line_in_maximal_coordinates_keeps_the_dense_correction(scheme, h, tip):
    """The director form's rows (numerics.rigid_newton_3d), at a state where Newton's
    directors are off unit length: the correction is J^-1 r."""
    case = _line_3d_case(6, tip=tip)
    maximal, dense = _corrections(case, scheme, h, bodies=1 if tip in ("base", "rigid") else 0)
    assert np.abs(maximal - dense).max() < 1e-6 * np.abs(dense).max()


@pytest.mark.parametrize("tip", ["clump", "base"])
def test_an_implicit_3d_run_follows_the_dense_block_and_dopri5(monkeypatch, tip):
    """generalized-alpha at 20 ms, 2 s: within the scheme's error of dopri5, and the same
    iteration as with the dense block (to Newton's tolerance)."""
    case = _line_3d_case(12, time_step=0.02, duration=2.0, tip=tip)
    banded = seacable.simulate(case).dataset
    assert banded.attrs["status"] == "complete"
    reference = seacable.simulate(
        _line_3d_case(12, integrator="dopri5", duration=2.0, tip=tip, rtol=1e-9)
    ).dataset
    names = ("position_x", "position_y", "position_z")
    position, force = _gap(banded, reference, names)
    assert position < 5e-3 and force < 2e-2
    monkeypatch.setattr(rigid_newton, "eligible", lambda p: ([], {}))
    dense = seacable.simulate(case).dataset
    position, force = _gap(banded, dense, names)
    assert position < 1e-7 and force < 1e-7
