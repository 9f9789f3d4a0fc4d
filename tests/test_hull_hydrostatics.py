"""Hull meshes and non-linear hydrostatics (seacable.meshes, kernels.hull, forces.hydrostatic)
against closed forms: a box (exact on its planar faces: to round-off) and a sphere (converging
with the mesh); the mesh readers, the winding repair and the refusals; the force model's
stiffness, righting arms, potential and free-decay periods."""

import math

import numpy as np
import pytest

import seacable
from seacable import meshes
from seacable.bodies import kinematics
from seacable.errors import CaseError
from seacable.system import kernel, model

RHO, G = 1025.0, 9.81
L, B, H = 10.0, 4.0, 3.0


def _turn(roll=0.0, pitch=0.0, yaw=0.0):
    out = np.zeros((3, 3))
    kinematics.rotation(*kinematics.euler_quaternion(roll, pitch, yaw), out)
    return out


def test_box_upright_against_closed_forms():
    """Volume (three ways), centre of buoyancy, waterplane area, its centre and moments of a
    box at draft T, whatever its yaw and its position in the plane: to round-off."""
    mesh = meshes.checked(meshes.box(L, B, H, n=3))
    for draft, yaw, x, y in ((1.0, 0.0, 0.0, 0.0), (2.2, 0.7, 3.0, -5.0), (0.3, -2.0, 1.0, 1.0)):
        z = H / 2 - draft  # the centre's elevation
        stat = meshes.hydrostatics(mesh, (x, y, z), _turn(yaw=yaw))
        volume = L * B * draft
        assert stat.volumes_xyz == pytest.approx((volume,) * 3, rel=1e-13)
        assert stat.closed()
        assert stat.centre_of_buoyancy == pytest.approx((0, 0, -H / 2 + draft / 2), abs=1e-12)
        assert stat.waterplane_area == pytest.approx(L * B, rel=1e-13)
        assert stat.flotation_centre == pytest.approx((0, 0), abs=1e-12)
        c, s = math.cos(yaw), math.sin(yaw)
        ix, iy = B * L**3 / 12, L * B**3 / 12  # int x^2, int y^2 in the box's own axes
        expected = (c * c * ix + s * s * iy, s * s * ix + c * c * iy, c * s * (ix - iy))
        assert stat.waterplane_moments == pytest.approx(expected, rel=1e-12, abs=1e-9)


def _cap(radius, depth):
    """Volume, centre height (from the sphere's centre) and waterplane area of a spherical
    cap of depth d."""
    volume = math.pi * depth**2 * (3 * radius - depth) / 3
    centre = -3 * (2 * radius - depth) ** 2 / (4 * (3 * radius - depth))
    return volume, centre, math.pi * (2 * radius * depth - depth**2)


@pytest.mark.parametrize("elevation", [0.0, 0.35, -0.6])
def test_sphere_converges_at_second_order(elevation):
    """A sphere's submerged cap: the mesh's volume, centre of buoyancy and waterplane area
    approach the closed forms, the error divided by about four each time the mesh is halved."""
    radius = 1.0
    volume, centre, area = _cap(radius, radius - elevation)
    errors = []
    for n in (8, 16, 32, 64):
        stat = meshes.hydrostatics(meshes.checked(meshes.sphere(radius, n)), (0, 0, elevation))
        assert stat.closed()
        errors.append(
            (abs(stat.volume / volume - 1), abs(stat.centre_of_buoyancy[2] - centre),
             abs(stat.waterplane_area / area - 1))
        )  # fmt: skip
    errors = np.array(errors)
    ratios = errors[:-1] / errors[1:]
    assert np.all(ratios > 3.0), ratios
    assert np.all(errors[-1] < [2e-3, 2e-3, 2e-3]), errors[-1]


def _row_hydro(mesh, pos, rot):
    return meshes.hydrostatics(mesh, pos, rot)


def test_readers_and_writers_agree(tmp_path):
    """A binary STL, an ASCII STL, an OBJ of quadrilaterals and a GDF with two planes of
    symmetry of the same box give the same hydrostatics."""
    mesh = meshes.checked(meshes.box(L, B, H, n=2))
    meshes.write_stl(mesh, tmp_path / "a.stl")
    meshes.write_stl(mesh, tmp_path / "b.stl", binary=False)
    half = np.array([L, B, H]) / 2
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half
    quads = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    obj = "".join(f"v {x} {y} {z}\n" for x, y, z in corners)
    obj += "".join("f " + " ".join(f"{i + 1}/1" for i in q) + "\n" for q in quads)
    (tmp_path / "c.obj").write_text(obj)
    # a quarter of the box's surface (x >= 0, y >= 0), WAMIT's symmetry flags mirror it
    quarter = [
        [(L / 2, 0, -H / 2), (L / 2, B / 2, -H / 2), (L / 2, B / 2, H / 2), (L / 2, 0, H / 2)],
        [(0, B / 2, -H / 2), (0, B / 2, H / 2), (L / 2, B / 2, H / 2), (L / 2, B / 2, -H / 2)],
        [(0, 0, -H / 2), (L / 2, 0, -H / 2), (L / 2, B / 2, -H / 2), (0, B / 2, -H / 2)],
        [(0, 0, H / 2), (0, B / 2, H / 2), (L / 2, B / 2, H / 2), (L / 2, 0, H / 2)],
    ]
    gdf = "quarter box\n1.0 9.81\n1 1\n4\n"
    gdf += "".join(" ".join(f"{c:g}" for p in panel for c in p) + "\n" for panel in quarter)
    (tmp_path / "d.gdf").write_text(gdf)
    pos, rot = (0.3, -0.2, 0.4), _turn(0.1, -0.05, 0.3)
    reference = meshes.hydrostatics(mesh, pos, rot)
    for name in ("a.stl", "b.stl", "c.obj", "d.gdf"):
        read = meshes.checked(meshes.read(tmp_path / name), pos, rot)
        stat = meshes.hydrostatics(read, pos, rot)
        assert stat.volume == pytest.approx(reference.volume, rel=1e-6), name
        assert stat.centre_of_buoyancy == pytest.approx(reference.centre_of_buoyancy, abs=1e-6)
        assert stat.waterplane_area == pytest.approx(reference.waterplane_area, rel=1e-6)
    # ASCII STL is written to 17 digits: read back exactly
    again = meshes.read(tmp_path / "b.stl")
    assert meshes.hydrostatics(again, pos, rot).volume == pytest.approx(reference.volume,
                                                                         rel=1e-14)  # fmt: skip


def test_winding_is_repaired():
    """Triangles turned over at random, or all of them, are wound outward again."""
    mesh = meshes.box(L, B, H, n=3)
    expected = meshes.hydrostatics(mesh, (0, 0, 0.5)).volume
    rng = np.random.default_rng(3)
    tri = mesh.triangles.copy()
    turned = rng.random(len(tri)) < 0.4
    tri[turned] = tri[turned][:, ::-1]
    for broken in (meshes.Mesh(mesh.vertices, tri), mesh.flipped()):
        assert meshes.hydrostatics(broken, (0, 0, 0.5)).volume != pytest.approx(expected)
        fixed = meshes.checked(broken, (0, 0, 0.5))
        assert meshes.hydrostatics(fixed, (0, 0, 0.5)).volume == pytest.approx(expected, rel=1e-13)


def test_meshes_that_are_not_hulls_are_refused():
    mesh = meshes.box(L, B, H, n=2)
    centres = mesh.vertices[mesh.triangles].mean(axis=1)
    bottom = np.nonzero(centres[:, 2] < -H / 2 + 1e-9)[0]
    top = np.nonzero(centres[:, 2] > H / 2 - 1e-9)[0]
    holed = meshes.Mesh(mesh.vertices, np.delete(mesh.triangles, bottom[0], axis=0))
    with pytest.raises(meshes.MeshError, match="not closed below the waterline"):
        meshes.checked(holed, (0, 0, 0.5))
    # open above the waterline only (no deck): a hull
    decked = meshes.Mesh(mesh.vertices, np.delete(mesh.triangles, top, axis=0))
    stat = meshes.hydrostatics(meshes.checked(decked, (0, 0, 0.5)), (0, 0, 0.5))
    assert stat.volume == pytest.approx(L * B * 1.0)
    tripled = meshes.Mesh(mesh.vertices, np.concatenate([mesh.triangles, mesh.triangles[:1]]))
    with pytest.raises(meshes.MeshError, match="more than two triangles"):
        meshes.checked(tripled)


def test_unreadable_mesh_files_are_named(tmp_path):
    (tmp_path / "junk.stl").write_text("this is not a mesh")
    (tmp_path / "empty.obj").write_text("# nothing\n")
    for name, match in (
        ("junk.stl", "not a readable STL"),
        ("empty.obj", "no triangles"),
        ("absent.stl", "does not exist"),
        ("hull.ply", "format 'ply'"),
    ):
        with pytest.raises(meshes.MeshError, match=match):
            meshes.read(tmp_path / name)


def _barge_case(path, draft=1.0, kg=None, added=(0.0,) * 6, **body):
    """A box barge L x B x H floating at ``draft`` (reference point at the box's centre),
    its centre of gravity ``kg`` above the keel (default: the waterline)."""
    meshes.write_stl(meshes.box(L, B, H, n=2), path)
    mass = RHO * L * B * draft
    kg = draft if kg is None else kg
    inertia = (mass * (B**2 + H**2) / 12, mass * (L**2 + H**2) / 12, mass * (L**2 + B**2) / 12)
    spec = {
        "name": "barge",
        "type": "rigid",
        "position": [0, 0, H / 2 - draft],
        "mass": mass,
        "centre_of_gravity": [0, 0, kg - H / 2],
        "inertia": inertia,
        "added_mass": list(added),
        "mesh": {"file": str(path)},
        "external forces": [{"model": "gravity"}, {"model": "non-linear hydrostatic"}],
    }
    spec |= body
    return seacable.load_case({
        "environment": {"water_density": RHO, "gravity": G},
        "bodies": [spec], "start": "as_given",
        "simulation": {"duration": 1.0, "output_interval": 0.1, "integrator": "dopri5"},
    })  # fmt: skip


def _loads(built, position, angles):
    p = built.params
    y = built.y0.copy()
    q = int(p.body_q[0])
    y[q : q + 3] = position
    y[q + 3 : q + 7] = kinematics.euler_quaternion(*(float(a) for a in angles))
    w = kernel.make_work(p)
    kernel.rhs(0.0, y, p, w, np.zeros_like(y))
    return w.load[0].copy()


def test_box_stiffness_and_righting_arms(tmp_path):
    """The force model on a box barge: in balance at its draft; heave, roll and pitch
    stiffness rho g A_wp, rho g V GM_T, rho g V GM_L; and the righting arm of a wall-sided hull,
    GZ = sin(phi) (GM + BM tan^2(phi) / 2), up to the heel that immerses the deck."""
    draft, kg = 1.5, 1.8
    built = model.build(_barge_case(tmp_path / "box.stl", draft, kg))
    z0 = H / 2 - draft
    volume = L * B * draft
    assert np.abs(_loads(built, (0, 0, z0), (0, 0, 0))).max() < 1e-9 * RHO * G * volume
    bm_t, bm_l = B**2 / (12 * draft), L**2 / (12 * draft)
    gm_t, gm_l = draft / 2 + bm_t - kg, draft / 2 + bm_l - kg
    h = 1e-5
    stiffness = np.zeros((3, 3))
    for j, (dz, droll, dpitch) in enumerate(np.eye(3) * h):
        up = _loads(built, (0, 0, z0 + dz), (droll, dpitch, 0))
        down = _loads(built, (0, 0, z0 - dz), (-droll, -dpitch, 0))
        stiffness[:, j] = -(up - down)[[2, 3, 4]] / (2 * h)
    weight = RHO * G * volume
    expected = np.diag([RHO * G * L * B, weight * gm_t, weight * gm_l])
    assert stiffness == pytest.approx(expected, rel=1e-7, abs=1e-6 * weight)
    deck = math.atan((H - draft) / (B / 2))
    for phi in np.linspace(0.05, deck, 7):
        load = _loads(built, (0, 0, z0), (phi, 0, 0))
        assert load[2] == pytest.approx(0.0, abs=1e-8 * weight)  # wall-sided: V unchanged
        gz = -load[3] / weight
        assert gz == pytest.approx(math.sin(phi) * (gm_t + bm_t * math.tan(phi) ** 2 / 2),
                                   rel=1e-10)  # fmt: skip


def test_a_mesh_given_z_down_gives_the_same_forces(tmp_path):
    """The document's body frame has z down and y to starboard: a hull written in it and read
    with ``axes: z_down`` gives the same forces and moments as the same hull written z up."""
    mesh = meshes.box(L, B, H, n=2).moved((1.0, 0.4, -0.3))  # off-centre: every moment shows
    meshes.write_stl(mesh, tmp_path / "up.stl")
    meshes.write_stl(mesh.moved(rotation=np.diag([1.0, -1.0, -1.0])), tmp_path / "down.stl")
    case = _barge_case(tmp_path / "box.stl")
    loads = []
    for name, axes in (("up.stl", "z_up"), ("down.stl", "z_down")):
        body = case.bodies[0].model_copy(update={"mesh": case.bodies[0].mesh.model_copy(
            update={"file": str(tmp_path / name), "axes": axes})})  # fmt: skip
        built = model.build(case.model_copy(update={"bodies": [body]}))
        loads.append(_loads(built, (0.2, 0.1, 0.4), (0.1, -0.05, 0.3)))
    assert loads[1] == pytest.approx(loads[0], rel=1e-6, abs=1e-3)


def test_an_open_hull_is_refused_with_the_field_named(tmp_path):
    mesh = meshes.box(L, B, H, n=2)
    meshes.write_stl(meshes.Mesh(mesh.vertices, mesh.triangles[1:]), tmp_path / "holed.stl")
    case = _barge_case(tmp_path / "box.stl")
    body = case.bodies[0].model_copy(update={"mesh": case.bodies[0].mesh.model_copy(
        update={"file": str(tmp_path / "holed.stl")})})  # fmt: skip
    with pytest.raises(CaseError, match=r"bodies\[0\] \(barge\)\.mesh .*not closed"):
        model.build(case.model_copy(update={"bodies": [body]}))
    with pytest.raises(Exception, match="needs the body's hull"):
        seacable.load_case({
            "bodies": [{"name": "b", "type": "rigid", "position": [0, 0, 0], "mass": 1.0,
                        "external forces": [{"model": "non-linear hydrostatic"}]}],
            "simulation": {"duration": 1.0, "output_interval": 0.1},
        })  # fmt: skip


def _crossings(t, x):
    up = np.nonzero((x[1:] > 0) & (x[:-1] <= 0))[0]
    # linear interpolation of each upward zero crossing
    return t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])


@pytest.mark.parametrize("dof", ["heave", "roll", "pitch"])
def test_free_decay_periods_and_energy(tmp_path, dof):
    """Free decay of the barge (small amplitude, no damping): the period of each mode against
    2 pi sqrt((M + A) / C) from the closed-form stiffness, and the energy kept."""
    draft, kg = 1.0, 0.9
    volume, mass = L * B * draft, RHO * L * B * draft
    added = (0.0, 0.0, 0.4 * mass, 0.1 * mass * B**2, 0.2 * mass * L**2, 0.0)
    z0 = H / 2 - draft
    start = {"heave": {"position": [0, 0, z0 + 0.02]},
             "roll": {"orientation_deg": [1.0, 0, 0]},
             "pitch": {"orientation_deg": [0, 0.2, 0]}}[dof]  # fmt: skip
    case = _barge_case(tmp_path / "box.stl", draft, kg, added, dofs=[dof], **start)
    case = case.model_copy(update={"simulation": case.simulation.model_copy(
        update={"duration": 40.0, "output_interval": 0.02, "rtol": 1e-10})})  # fmt: skip
    results = seacable.simulate(case)
    body = results["bodies/barge"]
    t = results["time"].values
    signal = {"heave": body["position_z"].values - z0, "roll": body["roll"].values,
              "pitch": body["pitch"].values}[dof]  # fmt: skip
    gm_t = draft / 2 + B**2 / (12 * draft) - kg
    gm_l = draft / 2 + L**2 / (12 * draft) - kg
    # the body turns about the reference point (its other freedoms held): inertia about it
    arm = H / 2 - kg  # the centre of gravity below the reference point
    inertia = {"heave": mass + added[2],
               "roll": mass * (B**2 + H**2) / 12 + mass * arm**2 + added[3],
               "pitch": mass * (L**2 + H**2) / 12 + mass * arm**2 + added[4]}[dof]  # fmt: skip
    # restoring about the reference point, 1 m above the waterline... the moment of weight and
    # buoyancy for a rotation about it: rho g V (GM) plus the couple of the sunk or lifted
    # wedge, zero for a wall-sided box; the heave is exact
    stiffness = {"heave": RHO * G * L * B, "roll": RHO * G * volume * gm_t,
                 "pitch": RHO * G * volume * gm_l}[dof]  # fmt: skip
    period = 2 * math.pi * math.sqrt(inertia / stiffness)
    measured = np.diff(_crossings(t, signal))
    assert len(measured) >= 3
    assert measured.mean() == pytest.approx(period, rel=2e-3)
    # the hydrostatic potential is the force's: the total energy stays what it was
    energy = results["total_energy"].values
    swing = np.ptp(results["kinetic_energy"].values)
    assert swing > 0.0
    assert np.ptp(energy) < 1e-6 * swing
