"""The non-linear Froude-Krylov force on a hull mesh (forces.froude_krylov, kernels.hull)
against the closed form of a box in a regular deep-water wave, and the undisturbed pressure
(hydrostatic and Froude-Krylov together) vanishing at the wave surface."""

import math

import numpy as np
import pytest
from numba import njit
from scipy.integrate import quad
from scipy.spatial.transform import Rotation

import seacable
from seacable import meshes, seastate
from seacable.bodies import kinematics
from seacable.kernels import hull, waves
from seacable.system import kernel, model

RHO, G = 1025.0, 9.81
L, B, H, DRAFT = 20.0, 8.0, 6.0, 3.0
PERIOD = 6.0


def _case(tmp_path, n, amplitude, forces, heading=0.0, phase=0.0):
    path = tmp_path / f"box{n}.stl"
    meshes.write_stl(meshes.box(L, B, H, n=n), path, binary=False)
    return seacable.load_case({
        "environment": {"water_density": RHO, "gravity": G, "waves": [
            {"kind": "airy", "height": 2 * amplitude, "period": PERIOD,
             "direction_deg": heading, "phase_deg": phase}]},
        "bodies": [{"name": "box", "type": "rigid", "position": [0, 0, H / 2 - DRAFT],
                    "mass": RHO * L * B * DRAFT, "mesh": {"file": str(path)},
                    "external forces": [{"model": m} for m in forces]}],
        "start": "as_given", "simulation": {"duration": 1.0, "output_interval": 0.1},
    })  # fmt: skip


def _load(built, t, angles=(0.0, 0.0, 0.0)):
    p, y = built.params, built.y0.copy()
    y[3:7] = kinematics.euler_quaternion(*(float(a) for a in angles))
    w = kernel.make_work(p)
    kernel.rhs(t, y, p, w, np.zeros_like(y))
    return w.load[0].copy()


def _closed_form(amplitude, t):
    """F_x, F_z of the linear incident pressure rho g a e^{kz} cos(kx - w t) on the box's
    mean wetted surface (deep water), and M_y about the reference point (the box's centre,
    H/2 - DRAFT above the waterline) by quadrature of the same pressure."""
    omega = 2 * math.pi / PERIOD
    k = omega**2 / G
    c = RHO * G * amplitude
    fx = -2 * c * B * (1 - math.exp(-k * DRAFT)) / k * math.sin(k * L / 2) * math.sin(omega * t)
    fz = c * math.exp(-k * DRAFT) * B * 2 / k * math.sin(k * L / 2) * math.cos(omega * t)
    zc = H / 2 - DRAFT

    def p(x, z):
        return c * math.exp(k * z) * math.cos(k * x - omega * t)

    # M_y = sum over faces of (z - zc) dF_x - x dF_z, dF = -p n dA (p does not vary across)
    front = quad(lambda z: -(z - zc) * p(L / 2, z) * B, -DRAFT, 0, epsabs=0, epsrel=1e-10)[0]
    back = quad(lambda z: (z - zc) * p(-L / 2, z) * B, -DRAFT, 0, epsabs=0, epsrel=1e-10)[0]
    bottom = quad(lambda x: -x * p(x, -DRAFT) * B, -L / 2, L / 2, epsabs=0, epsrel=1e-10)[0]
    return fx, fz, front + back + bottom


def test_a_box_in_a_regular_wave_against_the_closed_form(tmp_path):
    """A small wave (its non-linear part below 1e-7), meshes of 8, 16 and 32 squares a side:
    the force and pitch moment agree with the closed form to 2e-6 of its amplitude on the
    coarsest mesh, 2e-7 on the finer ones (measured 1.7e-6, 1.3e-7, 5.9e-8: the edge-midpoint
    rule on the exponential decay, then the wave's non-linear part); the sway force, roll and
    yaw moments of a head sea vanish (to the quadrature's error)."""
    amplitude = 1e-6
    errors = []
    for n in (8, 16, 32):
        built = model.build(_case(tmp_path, n, amplitude, ["non-linear Froude-Krylov"]))
        worst = 0.0
        for t in np.linspace(0.0, PERIOD, 7)[:-1]:
            load = _load(built, t)
            fx, fz, my = _closed_form(amplitude, t)
            scale = RHO * G * amplitude * L * B
            worst = max(worst, abs(load[0] - fx) / scale, abs(load[2] - fz) / scale,
                        abs(load[4] - my) / (scale * L))  # fmt: skip
            # quadrature on triangles cut one way only: not exactly symmetric
            assert abs(load[1]) < 1e-4 * scale and np.abs(load[[3, 5]]).max() < 1e-4 * scale * L
        errors.append(worst)
    assert errors[0] < 2e-6 and max(errors[1:]) < 2e-7, errors


def test_the_undisturbed_pressure_vanishes_on_the_wave_surface(tmp_path):
    """Hydrostatic and Froude-Krylov pressure together, on a box heeled in a steep oblique
    wave: the force is the one from the pressure field integrated on the mesh clipped at the
    wave surface, which (Wheeler's stretching) is zero there: a thin slice of hull just
    above the surface changes nothing, while under it the pressure is there."""
    amplitude = 1.5
    built = model.build(_case(tmp_path, 6, amplitude, ["non-linear hydrostatic",
                                                       "non-linear Froude-Krylov"],
                              heading=30.0, phase=40.0))  # fmt: skip
    rows = waves.table(seastate.components(built.case.environment.waves[0], waves.DEEP, G),
                       waves.DEEP)  # fmt: skip
    assert np.array_equal(rows, built.params.wave)  # the wave the kernel sees
    # along a vertical line, the total pressure vanishes at eta and grows downwards at
    # rho g (1 - sum a k cos(theta)) (Wheeler: d p_dyn / dz = rho g sum a k e^{k(z - eta)} cos)
    x, y, t = 3.0, B / 2, 1.7
    eta = waves.elevation_at(rows, t, x, y)
    a, w, k, cb, sb, phase = rows[: waves.BUILD_UP]
    theta = k * (x * cb + y * sb) - w * t + phase
    slope = RHO * G * (1 - np.sum(a * k * np.cos(theta)))
    for depth in (1e-6, 1e-3):
        z = eta - depth
        total = -RHO * G * z + waves.pressure_at(rows, t, x, y, z, waves.DEEP, waves.WHEELER,
                                                 RHO * G)  # fmt: skip
        assert total == pytest.approx(slope * depth, rel=1e-3)
    # the force changes smoothly with time (no jump as panels cross the surface)
    loads = np.array([_load(built, t, (0.05, -0.02, 0.0)) for t in np.linspace(0, 1, 201)])
    jumps = np.abs(np.diff(loads[:, 2]))
    assert jumps.max() < 5 * np.median(jumps) + 1e-9 * np.abs(loads[:, 2]).max()


@njit  # not cached: a cached copy would keep the kernels it was linked with
def _kernel_load(row, pos, rot, wave, t, depth, stretch):
    """kernels.hull's Froude-Krylov load (its pressures shared by the edges' neighbours)."""
    work, load = (
        np.zeros((int(row[0]) + 1, max(hull.PHASES + 2 * wave.shape[1], hull.KEY))),
        np.zeros(6),
    )
    hull.place(row, 0, pos, rot, wave, t, work)
    hull.add_froude_krylov(row, RHO, G, wave, t, depth, stretch, work, load)
    return load


def _reference_load(mesh, pos, rot, wave, t, depth, stretch):
    """The same integral written plainly: each triangle clipped at the wave surface on its
    own (depths interpolated along the cut edges, the wet quadrilateral split from its first
    cut point), the pressure evaluated at each part's three edge midpoints."""
    arms = mesh.vertices @ rot.T
    heights = np.array([waves.elevation_at(wave, t, *(pos[:2] + r[:2])) for r in arms])
    h = heights - pos[2] - arms[:, 2]
    load = np.zeros(6)
    for tri in mesh.triangles:
        wet = [h[v] >= 0.0 for v in tri]
        if not any(wet):
            continue
        turn = 0 if sum(wet) == 3 else [w == (sum(wet) == 1) for w in wet].index(True)
        a, b, c = (arms[tri[(turn + i) % 3]] for i in range(3))
        ha, hb, hc = (h[tri[(turn + i) % 3]] for i in range(3))
        cut_ab, cut_ca = a + ha / (ha - hb) * (b - a), c + hc / (hc - ha) * (a - c)
        parts = {3: [(a, b, c)], 1: [(a, cut_ab, cut_ca)],
                 2: [(cut_ab, b, c), (cut_ab, c, cut_ca)]}[sum(wet)]  # fmt: skip
        for p, q, r in parts:
            area = np.cross(q - p, r - p) / 2.0
            for m in ((p + q) / 2.0, (q + r) / 2.0, (r + p) / 2.0):
                x, y, z = pos + m
                pressure = waves.pressure_at(wave, t, x, y, z, depth, stretch, RHO * G)
                load[:3] -= pressure / 3.0 * area
                load[3:] -= pressure / 3.0 * np.cross(m, area)
    return load


@pytest.mark.slow  # its wrapper compiles every run (uncached); make test-all
def test_the_kernel_against_a_plain_reference_on_random_poses_and_waves():
    """The kernel (each wholly wet triangle's edge pressures shared with its neighbours)
    against the integral written plainly, triangle by triangle, on a box and a sphere in
    random poses across the surface, in random seas of 1 to 7 components (deep water and
    40 m, Wheeler's and vertical stretching): the force and moment agree to 1e-12 of their
    size (measured: 1.4e-14)."""
    rng = np.random.default_rng(43)
    worst = 0.0
    for trial in range(12):
        mesh = meshes.box(L, B, H, n=3) if trial % 2 else meshes.sphere(4.0, n=6)
        n, depth = 1 + trial % 7, (waves.DEEP, 40.0)[trial % 3 == 0]
        omega = rng.uniform(0.5, 2.0, n)
        number = seastate.wave_number(omega, depth, G)
        heading = rng.uniform(0.0, 2 * np.pi, n)
        wave = waves.table(np.column_stack([
            rng.uniform(0.1, 1.0, n), omega, number, np.cos(heading), np.sin(heading),
            rng.uniform(0.0, 2 * np.pi, n), np.zeros(n)]), depth)  # fmt: skip
        pos = np.array([*rng.normal(0.0, 5.0, 2), rng.uniform(-2.0, 2.0)])
        rot = Rotation.from_euler("xyz", rng.normal(0.0, 0.3, 3)).as_matrix()
        t, stretch = rng.uniform(0.0, 1000.0), (waves.WHEELER, waves.VERTICAL)[trial % 2]
        load = _kernel_load(mesh.row(), pos, rot, wave, t, depth, stretch)
        exact = _reference_load(mesh, pos, rot, wave, t, depth, stretch)
        for part in (slice(0, 3), slice(3, 6)):
            worst = max(worst, np.abs(load[part] - exact[part]).max() / np.abs(exact[part]).max())
    assert worst < 1e-12, worst


def test_each_edge_has_one_number():
    """mesh_row numbers each edge once: the two triangles sharing it give it one number, and
    a closed mesh of nt triangles has 3 nt / 2 edges."""
    mesh = meshes.box(L, B, H, n=3)
    nt = len(mesh.triangles)
    row = mesh.row()
    edges = row[hull.HEADER + 3 * len(mesh.vertices) + 3 * nt :].astype(int).reshape(nt, 3)
    tri = mesh.triangles
    by_ends: dict = {}
    for k in range(nt):
        for side in range(3):
            ends = frozenset((tri[k, side], tri[k, (side + 1) % 3]))
            assert by_ends.setdefault(ends, edges[k, side]) == edges[k, side]
    assert len(set(by_ends.values())) == len(by_ends) == 3 * nt // 2


def test_two_hulls_in_one_system_get_each_its_own_placement(tmp_path):
    """kernels.hull.place keys the hull workspace by body, time and pose (the hydrostatics and
    the Froude-Krylov force of one body share a placement): two hulls of different meshes at
    the same pose in one system, and one of them heeled, get each the loads it gets alone, to
    the bit."""
    forces = ["non-linear hydrostatic", "non-linear Froude-Krylov"]
    one = _case(tmp_path, 6, 1.0, forces, heading=30.0)
    data = one.model_dump(mode="json", by_alias=True, exclude_none=True)
    box = data["bodies"][0]
    path = tmp_path / "other.stl"
    meshes.write_stl(meshes.box(0.6 * L, 1.3 * B, H, n=5), path, binary=False)
    other = {**box, "name": "other", "mesh": {"file": str(path)}}
    both = seacable.load_case({**data, "bodies": [box, other]})
    alone = seacable.load_case({**data, "bodies": [other]})
    for heel in ((0.0, 0.0, 0.0), (0.1, -0.05, 0.3)):
        loads = []
        for case in (both, one, alone):
            built = model.build(case)
            p, y = built.params, built.y0.copy()
            for b, body in enumerate(case.bodies):
                if body.name == "other":  # a rigid body's state: position, quaternion
                    y[7 * b + 3 : 7 * b + 7] = kinematics.euler_quaternion(*heel)
            w = kernel.make_work(p)
            for t in (0.7, 0.7, 1.3):  # the same time twice: the placement kept, then another
                kernel.rhs(t, y, p, w, np.zeros_like(y))
            loads.append(w.load[: len(case.bodies)].copy())
        assert np.array_equal(loads[0][0], loads[1][0])
        assert np.array_equal(loads[0][1], loads[2][0])
        assert not np.allclose(loads[0][0], loads[0][1])


def test_hull_loads_reused_within_the_reuse_distance_only(tmp_path):
    """kernels.hull.place reuses the mesh loads computed on its last placement while a pose
    moves no vertex by more than the key row's reuse distance (numerics.system_implicit sets
    it within a Newton iteration): the loads are then those of the last placement to the bit;
    a pose moved further, another time, or a reuse distance of 0 computes them afresh, the
    same to the bit as a fresh workspace computes them."""
    built = model.build(_case(tmp_path, 6, 1.0, ["non-linear hydrostatic",
                                                 "non-linear Froude-Krylov"]))  # fmt: skip
    p, y0 = built.params, built.y0.copy()
    y0[3:7] = kinematics.euler_quaternion(0.05, -0.02, 0.1)

    def loads(w, t, dx, turn=0.0):
        y = y0.copy()
        y[0] += dx
        y[3:7] = kinematics.euler_quaternion(0.05 + turn, -0.02, 0.1)
        kernel.rhs(t, y, p, w, np.zeros_like(y))
        return w.load[0].copy()

    def fresh(t, dx, turn=0.0):
        return loads(kernel.make_work(p), t, dx, turn)

    near = 1e-6
    w = kernel.make_work(p)
    w.hull[-1, hull.NEAR] = near
    first = loads(w, 0.7, 0.0)
    assert np.array_equal(first, fresh(0.7, 0.0))
    # |dx| <= near: the last placement's loads
    assert np.array_equal(loads(w, 0.7, 0.9 * near), first)
    assert not np.array_equal(fresh(0.7, 0.9 * near), first)
    # a turn of 1e-9 rad moves the box's corners (11 m out) by 1.1e-8 m: reused; 2e-7 rad,
    # 2.3e-6 m: placed again
    assert np.array_equal(loads(w, 0.7, 0.0, 1e-9), first)
    assert np.array_equal(loads(w, 0.7, 0.0, 2e-7), fresh(0.7, 0.0, 2e-7))
    assert np.array_equal(loads(w, 0.7, 1.2 * near), fresh(0.7, 1.2 * near))
    assert np.array_equal(loads(w, 0.8, 1.2 * near), fresh(0.8, 1.2 * near))
    w.hull[-1, hull.NEAR] = 0.0
    last = loads(w, 0.8, 1.21 * near)
    assert np.array_equal(last, fresh(0.8, 1.21 * near))
    # a pose that is not a number is placed again (all its triangles dry), never reused
    w.hull[-1, hull.NEAR] = near
    assert np.array_equal(loads(w, 0.8, math.nan), fresh(0.8, math.nan))
    assert not np.array_equal(fresh(0.8, math.nan), last)


def test_froude_krylov_held_within_its_own_distance(tmp_path):
    """The Froude-Krylov force keeps its own pose and reuse distance (``hull.FAR``, set by
    numerics.system_implicit to the Newton tolerance): a pose that moves a vertex beyond the
    placement's distance (``hull.NEAR``) is placed again and its clipped hydrostatics computed
    afresh, while the Froude-Krylov force is the one computed on the pose it was held at, to
    the bit, until the pose moves beyond its distance or the time changes."""
    forces = ["non-linear hydrostatic", "non-linear Froude-Krylov"]
    both = model.build(_case(tmp_path, 6, 1.0, forces))
    alone = model.build(_case(tmp_path, 6, 1.0, forces[:1]))
    far = 1e-6

    def loads(built, w, t, dx):
        y = built.y0.copy()
        y[0] += dx
        y[3:7] = kinematics.euler_quaternion(0.05, -0.02, 0.1)
        kernel.rhs(t, y, built.params, w, np.zeros_like(y))
        return w.load[0].copy()

    def fresh(built, t, dx):
        return loads(built, kernel.make_work(built.params), t, dx)

    def froude_krylov(t, dx):  # the force on its own, by difference
        return fresh(both, t, dx) - fresh(alone, t, dx)

    w = kernel.make_work(both.params)
    w.hull[-1, hull.FAR] = far  # NEAR stays 0: every other pose is placed again
    assert np.array_equal(loads(both, w, 0.7, 0.0), fresh(both, 0.7, 0.0))
    held = loads(both, w, 0.7, 0.9 * far)
    assert not np.array_equal(held, fresh(both, 0.7, 0.9 * far))
    expected = fresh(alone, 0.7, 0.9 * far) + froude_krylov(0.7, 0.0)
    assert np.allclose(held, expected, rtol=0.0, atol=1e-9 * np.abs(expected).max())
    # beyond the distance from where it was held, another time, or a distance of 0: afresh
    assert np.array_equal(loads(both, w, 0.7, 2.1 * far), fresh(both, 0.7, 2.1 * far))
    assert np.array_equal(loads(both, w, 0.8, 2.2 * far), fresh(both, 0.8, 2.2 * far))
    w.hull[-1, hull.FAR] = 0.0
    assert np.array_equal(loads(both, w, 0.8, 2.3 * far), fresh(both, 0.8, 2.3 * far))
    # a pose that is not a number computes it afresh (nothing wet), never holds it
    w.hull[-1, hull.FAR] = far
    assert np.array_equal(loads(both, w, 0.8, math.nan), fresh(both, 0.8, math.nan))
