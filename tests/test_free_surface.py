"""The free surface z = 0 for bodies: the submerged-fraction kernel against closed forms, and a
buoy floating at its waterline in the lumped-mass, 3D rigid-segment and planar models (its
equilibrium draft and heave period against closed forms, energy, implicit against rk4).

Cases are written in the single-cable form and run as the systems ``seacable upgrade`` writes
(``helpers.system_data``); a lumped-mass line is the rigid-segment system with its lines'
model changed (upgrade writes a lumped-mass cable only when it ends on an anchor)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

import seacable
from golden.record import system_rows
from helpers import rows, system_data
from seacable.case import schema
from seacable.case.loader import derive_case
from seacable.case.schema import VolumeTable
from seacable.errors import CaseError
from seacable.kernels import chain3d as c3
from seacable.kernels import lumped as lk
from seacable.kernels import planar_chain as pc
from seacable.kernels import surface
from seacable.packing import shape_row
from seacable.system import kernel, model, rigid
from seacable.system.assemble import BuiltSystem

RHO, G = 1025.0, 9.81
SPHERE_R, SPHERE_MASS, SPHERE_ADDED = 1.0, 800.0, 400.0  # m, kg, kg (wholly submerged)
CYL_R, CYL_H, CYL_MASS = 0.6, 2.0, 600.0  # m, m, kg


def _cap_volume(d, r):
    """Submerged volume of a sphere of radius r at draft d [m^3]."""
    return math.pi * d * d * (3 * r - d) / 3


def _sphere_draft():
    return brentq(lambda d: RHO * _cap_volume(d, SPHERE_R) - SPHERE_MASS, 0.0, 2 * SPHERE_R)


def _line_mass():
    """Mass the slack line puts on the body's node (lumped: half its last segment) [kg]."""
    return RHO * math.pi * 0.002**2 / 4 * 15.0 / 2


def _line(model, z0, azimuth=0.0):
    """A slack, neutrally buoyant, drag-free line of two 15 m links from an anchor 20 m down to
    a body at z0, folded towards ``azimuth`` [deg]: it exerts (almost) nothing on the body.
    (A single cable: a lumped-mass one is written as rigid segments and changed by _system.)"""
    top_z, half = -20.0, 15.0
    h = (z0 - top_z) / 2
    x1 = math.sqrt(half**2 - h**2)
    angles = [math.degrees(math.atan2(x1, -h)), math.degrees(math.atan2(-x1, -h))]
    cable = {
        "name": f"line {azimuth:g}",
        "model": "rigid_segments_3d" if model == "lumped_mass" else model,
        "links": 2,
        "length": 2 * half,
        "diameter": 0.002,
        "density": RHO,  # neutrally buoyant
        "drag_coefficient_normal": 0.0,
        "top": {
            "type": "fixed",
            "position": [0.0, top_z] if model == "rigid_links" else [0.0, 0.0, top_z],
        },  # fmt: skip
        "initial": {"shape": "angles", "angles_deg": angles},
    }
    if model != "rigid_links":
        cable["added_mass_coefficient"] = 0.0
        cable["initial"]["azimuth_deg"] = azimuth
    return cable


def _system(cables, duration, integrator, dt, bodies=(), model="rigid_segments_3d"):
    """The system of the single cables (``seacable upgrade``), its lines' model ``model`` (a
    lumped-mass line: EA 1e5 N)."""
    simulation = {"duration": duration, "output_interval": 0.005, "integrator": integrator,
                  "time_step": dt}  # fmt: skip
    data = system_data(
        {"name": "buoy", "cables": cables, "bodies": list(bodies), "simulation": simulation}
    )
    if model == "lumped_mass":
        for line in data["lines"]:
            line.update(model="lumped_mass")
            line.pop("base_reference", None)
        for line_type in data["line_types"]:
            line_type["axial_stiffness"] = 1e5
    return seacable.load_case(data)


def _simulate(cables, duration, integrator, dt, bodies=(), model="rigid_segments_3d"):
    """The run's variables under the single-cable names (golden.record.system_rows); with
    ``bodies`` (a star) the results."""
    case = _system(cables, duration, integrator, dt, bodies, model)
    results = seacable.simulate(case)
    assert results.status == "complete"
    return results.dataset if bodies else system_rows(results.dataset, case)


def _buoy(model, shape, mass, z0, added=0.0, duration=5.0, integrator="rk4", dt=1e-3):
    """A body released at rest at z0 on a slack line (_line)."""
    cable = _line(model, z0)
    cable["bottom"] = {"type": "free", "body": {"mass": mass, "shape": shape, "added_mass": added}}
    return _simulate([cable], duration, integrator, dt, model=model)


def _heave(ds):
    return ds["time"], ds["node_z"][:, -1]


def _period_and_mean(t, z):
    """Mean of the extremes and the mean period between upward crossings of it."""
    mean = 0.5 * (z.min() + z.max())
    s = z - mean
    up = np.nonzero((s[:-1] < 0) & (s[1:] >= 0))[0]
    crossings = t[up] - s[up] * (t[up + 1] - t[up]) / (s[up + 1] - s[up])
    assert len(crossings) >= 3
    return float(np.mean(np.diff(crossings))), mean


# ---- the kernel -------------------------------------------------------------------------------
def test_sphere_fraction_slope_and_potential_match_closed_forms():
    row = shape_row(schema.Sphere(kind="sphere", radius=2.0), 4)
    volume = 4 / 3 * math.pi * 8
    for z in np.linspace(-2.5, 2.5, 23):
        f, slope, integral = surface.submersion(z, row)
        d = min(max(2.0 - z, 0.0), 4.0)
        assert f == pytest.approx(_cap_volume(d, 2.0) / volume, abs=1e-14)
        waterplane = math.pi * (4.0 * d - d * d)
        assert -volume * slope == pytest.approx(waterplane, abs=1e-12)
        # I(z) = z while wholly submerged, then z_full + the integral of f
        expected = z if z <= -2.0 else -2.0 + quad(lambda s: surface.submersion(s, row)[0],
                                                    -2.0, z)[0]  # fmt: skip
        assert integral == pytest.approx(expected, abs=1e-10)
    eps = 1e-7  # C1 at both poles: the slope vanishes there
    for pole in (-2.0, 2.0):
        assert abs(surface.submersion(pole - eps, row)[1]) < 1e-6
        assert abs(surface.submersion(pole + eps, row)[1]) < 1e-6


def test_cylinder_and_table_fractions():
    cylinder = shape_row(
        schema.VerticalCylinder(kind="vertical_cylinder", radius=1.0, height=3.0), 4
    )
    assert surface.submersion(0.0, cylinder)[:2] == pytest.approx((0.5, -1 / 3))
    assert surface.submersion(-1.5, cylinder) == (1.0, 0.0, -1.5)
    assert surface.submersion(1.6, cylinder)[:2] == (0.0, 0.0)
    # once clear of the water, I is the height of the volume's centroid above the reference
    # point: 0 for a centred cylinder (-H/2 + the integral of f = -H/2 + H/2)
    assert surface.submersion(1.6, cylinder)[2] == pytest.approx(0.0, abs=1e-15)
    # the same cylinder as a table: identical fraction, slope and potential
    table = VolumeTable(kind="table", submerged_volume=[[-1.5, 3 * math.pi], [1.5, 0.0]])
    row = shape_row(table, 8)
    for z in (-2.0, -1.0, 0.3, 1.4, 2.0):
        np.testing.assert_allclose(surface.submersion(z, row), surface.submersion(z, cylinder))


def _body_case(**buoy):
    """A point body ``buoy`` on a lumped-mass line from a fixed point 10 m above it."""
    return {
        "bodies": [{"name": "top", "type": "fixed", "position": [0.0, 0.0, 0.0]},
                   {"name": "buoy", "type": "point", "position": [0.0, 0.0, -10.0], **buoy}],
        "line_types": [{"name": "rope", "diameter": 0.01, "mass_per_length": 1.0,
                        "axial_stiffness": 1e6}],
        "lines": [{"name": "rope", "model": "lumped_mass", "from": "top", "to": "buoy",
                   "sections": [{"type": "rope", "length": 10.0, "segments": 2}]}],
        "simulation": {"duration": 1.0, "output_interval": 0.1},
    }  # fmt: skip


@pytest.mark.parametrize(
    "table, match",
    [
        ([[0.0, 1.0], [-1.0, 0.0]], "strictly ascending"),
        ([[-1.0, 1.0], [0.0, 2.0], [1.0, 0.0]], "must not increase"),
        ([[-1.0, 1.0], [1.0, 0.5]], "must not increase"),
    ],
)
def test_bad_table_is_refused(table, match):
    shape = {"kind": "table", "submerged_volume": table}
    with pytest.raises(CaseError, match=r"bodies\[1\]\.shape.*" + match):
        seacable.load_case(_body_case(mass=1.0, shape=shape))


def test_volume_and_shape_together_are_refused():
    shape = {"kind": "sphere", "radius": 0.5}
    with pytest.raises(
        CaseError, match=r"bodies\[1\]: give 'volume' \[m\^3\] or 'shape', not both"
    ):
        seacable.load_case(_body_case(mass=1.0, volume=1.0, shape=shape))


# ---- a floating buoy --------------------------------------------------------------------------
@pytest.mark.parametrize("model", ["lumped_mass", "rigid_segments_3d"])
def test_sphere_floats_at_its_draft_with_the_closed_form_heave_period(model):
    draft = _sphere_draft()
    z_eq = SPHERE_R - draft
    shape = {"kind": "sphere", "radius": SPHERE_R}
    ds = _buoy(model, shape, SPHERE_MASS, z_eq - 0.01, added=SPHERE_ADDED)
    period, mean = _period_and_mean(*_heave(ds))
    # the mean of the extremes differs from the equilibrium by O(amplitude^2)
    assert abs(mean - z_eq) < 5e-5
    fraction = _cap_volume(draft, SPHERE_R) / (4 / 3 * math.pi * SPHERE_R**3)
    waterplane = math.pi * (2 * SPHERE_R * draft - draft**2)
    mass = SPHERE_MASS + SPHERE_ADDED * fraction + (_line_mass() if model == "lumped_mass" else 0)
    expected = 2 * math.pi * math.sqrt(mass / (RHO * G * waterplane))
    assert period == pytest.approx(expected, rel=2e-3)


def test_vertical_cylinder_heave_is_linear_in_the_planar_model():
    area = math.pi * CYL_R**2
    draft = CYL_MASS / (RHO * area)
    z_eq = CYL_H / 2 - draft
    shape = {"kind": "vertical_cylinder", "radius": CYL_R, "height": CYL_H}
    ds = _buoy("rigid_links", shape, CYL_MASS, z_eq - 0.2)  # 0.2 m: linear all the way
    period, mean = _period_and_mean(*_heave(ds))
    assert mean == pytest.approx(z_eq, abs=1e-4)
    assert period == pytest.approx(2 * math.pi * math.sqrt(CYL_MASS / (RHO * G * area)), rel=2e-3)


@pytest.mark.parametrize("model", ["rigid_segments_3d", "rigid_links"])
def test_undamped_buoy_leaping_out_of_the_water_keeps_its_energy(model):
    # released wholly submerged, the sphere leaps clear of the water (to z = 6.55 m) and falls
    # back: buoyancy's work is the potential -rho g V I(z) (no drag, no added mass). The line's
    # links (inextensible here) snap taut as it flies; a lumped-mass line's stiff snap would
    # measure rk4's error on it rather than the free surface's energy
    shape = {"kind": "sphere", "radius": SPHERE_R}
    ds = _buoy(model, shape, SPHERE_MASS, -1.5, duration=6.0)
    z = ds["node_z"][:, -1]
    assert z.min() < -1.4 and z.max() > 6.0  # wholly under, then clear of the water
    energy = ds["total_energy"]
    swing = np.ptp(ds["kinetic_energy"])
    assert np.ptp(energy) < 1e-7 * swing


@pytest.mark.parametrize("model", ["lumped_mass", "rigid_segments_3d"])
def test_shared_body_of_a_star_floats_at_its_draft(model):
    draft = _sphere_draft()
    z_eq = SPHERE_R - draft
    body = {"name": "buoy", "position": [0.0, 0.0, z_eq - 0.01], "mass": SPHERE_MASS,
            "shape": {"kind": "sphere", "radius": SPHERE_R}}  # fmt: skip
    cables = [_line(model, z_eq - 0.01, azimuth) for azimuth in (0.0, 180.0)]
    for cable in cables:
        cable["bottom"] = {"type": "attached", "body": "buoy"}
    ds = _simulate(cables, 4.0, "rk4", 1e-3, bodies=[body], model=model)
    period, mean = _period_and_mean(ds["time"].values, ds["bodies/buoy/position_z"].values)
    assert abs(mean - z_eq) < 5e-5
    waterplane = math.pi * (2 * SPHERE_R * draft - draft**2)
    mass = SPHERE_MASS + (2 * _line_mass() if model == "lumped_mass" else 0.0)
    assert period == pytest.approx(2 * math.pi * math.sqrt(mass / (RHO * G * waterplane)), rel=2e-3)


# ---- cable segments ---------------------------------------------------------------------------
def _evaluated(case) -> tuple[BuiltSystem, kernel.SystemWork]:
    """The system at its start and its workspace after one evaluation of its rates."""
    built = model.build(case)
    w = model.workspace(built)
    kernel.rhs(0.0, built.y0, built.params, w, np.zeros_like(built.y0))
    return built, w


def _weight_above_and_below():
    """Its top's load: the weight in air of 5.5 m and the apparent weight of 14.5 m [N]."""
    return G * math.pi * 0.05**2 / 4 * (2000.0 * 20.0 - RHO * 14.5)


def test_lumped_line_hanging_from_above_the_surface_weighs_its_part_in_air_fully():
    # the loads on the unstretched line's nodes (its internal forces cancel in the sum): the
    # segment crossing the surface carries half its buoyancy, at its submerged half's centroid.
    # 20 m of line (2000 kg/m^3, 5 cm) hanging straight from 5.5 m above the water
    area = math.pi * 0.05**2 / 4
    case = seacable.load_case({
        "environment": {"water_density": RHO},
        "bodies": [{"name": "top", "type": "fixed", "position": [0.0, 0.0, 5.5]},
                   {"name": "end", "type": "point", "position": [0.0, 0.0, -14.5], "mass": 0.0}],
        "line_types": [{"name": "rope", "diameter": 0.05, "mass_per_length": 2000.0 * area,
                        "axial_stiffness": 1e8}],
        "lines": [{"name": "rope", "model": "lumped_mass", "from": "top", "to": "end",
                   "sections": [{"type": "rope", "length": 20.0, "segments": 20}],
                   "initial": "straight"}],
        "start": "as_given",
        "simulation": {"duration": 1.0, "output_interval": 0.5},
    })  # fmt: skip
    built, w = _evaluated(case)
    loads = w.nodes[lk._F + 2, :21]  # the line's 21 nodes, its ends' included
    assert loads.sum() == pytest.approx(-_weight_above_and_below(), rel=1e-12)
    first = int(built.params.line_q[0])  # interior nodes 1 ... 19 in the state
    heights = built.y0[first + 2 : first + 3 * 19 : 3]
    assert heights[4] == pytest.approx(0.5) and heights[5] == pytest.approx(-0.5)
    # nodes 5 and 6 each carry a metre of line (halves of two segments); segment 5 between
    # them is half submerged, its buoyancy B / 2 at z = -0.25 m: a quarter of it on node 5
    weight, buoyancy = 2000.0 * area * G, RHO * area * G  # of a metre of line [N]
    assert loads[5] == pytest.approx(-weight + 0.25 * 0.5 * buoyancy, rel=1e-12)
    assert loads[6] == pytest.approx(-weight + (0.75 * 0.5 + 0.5) * buoyancy, rel=1e-12)


@pytest.mark.parametrize("model", ["lumped_mass", "rigid_segments_3d"])
def test_float_at_a_joint_floats_at_its_draft(model):
    # a sphere of 0.5 m at the joint between a slack line (_line) and two more links lying
    # horizontal; heavy enough that the joint, its centre, stays under water
    radius, mass = 0.5, 400.0
    draft = brentq(lambda d: RHO * _cap_volume(d, radius) - mass, 0.0, 2 * radius)
    z_eq = radius - draft
    cable = _line(model, z_eq - 0.01)
    cable["links"], cable["length"] = 4, 60.0  # a lumped-mass line needs two segments
    cable["initial"]["angles_deg"] += [90.0, 90.0]
    cable["bottom"] = {"type": "free"}
    cable["point_bodies"] = [{"node": 2, "mass": mass, "drag_coefficient": 0.0,
                              "shape": {"kind": "sphere", "radius": radius}}]  # fmt: skip
    ds = _simulate([cable], 4.0, "rk4", 1e-3, model=model)
    period, mean = _period_and_mean(ds["time"], ds["node_z"][:, 2])
    assert abs(mean - z_eq) < 5e-5
    waterplane = math.pi * (2 * radius * draft - draft**2)
    expected = 2 * math.pi * math.sqrt(mass / (RHO * G * waterplane))
    assert period == pytest.approx(expected, rel=2e-3)


# ---- rigid links and segments crossing the surface --------------------------------------------
CHAIN_D, CHAIN_DENSITY, CHAIN_LINK = 0.1, 2000.0, 2.0  # m, kg/m^3, m


def _chain(
    model, top_z, angles, azimuth=0.0, drag=0.0, added=0.0, joints=20.0, duration=0.5, dt=1e-3
):
    """Four 2 m links of a 10 cm line (2000 kg/m^3) from a fixed top at top_z [m], at rest at
    the given angles [deg]; drag coefficient ``drag`` (normal; a tenth of it tangential), joint
    stiffness ``joints`` [N m/rad]."""
    cable = {
        "model": model, "links": 4, "length": 4 * CHAIN_LINK, "diameter": CHAIN_D,
        "density": CHAIN_DENSITY, "drag_coefficient_normal": drag,
        "drag_coefficient_tangential": 0.1 * drag, "joint_stiffness": joints,
        "top": {"type": "fixed",
                "position": [0.0, top_z] if model == "rigid_links" else [0.0, 0.0, top_z]},
        "bottom": {"type": "free"},
        "initial": {"shape": "angles", "angles_deg": list(angles)},
    }  # fmt: skip
    if model == "rigid_segments_3d":  # (the planar model has no link added mass)
        cable["added_mass_coefficient"] = added
        cable["initial"]["azimuth_deg"] = azimuth
    simulation = {"duration": duration, "output_interval": 0.01, "integrator": "rk4",
                  "time_step": dt}  # fmt: skip
    return seacable.load_case(
        system_data({"name": "chain", "cables": [cable], "simulation": simulation})
    )


def _submerged_part(za, zb):
    """Closed form for a straight link from za (top) to zb [m]: the submerged length fraction
    and the distance from the link's centre to the submerged part's centroid, towards the
    bottom node [m] (by the link's geometry, not kernels.surface)."""
    if max(za, zb) <= 0.0:
        return 1.0, 0.0
    if min(za, zb) >= 0.0:
        return 0.0, 0.0
    cross = za / (za - zb)  # where z = 0, as a fraction of the length from the top
    low, high = (cross, 1.0) if zb < za else (0.0, cross)
    return high - low, CHAIN_LINK * (0.5 * (low + high) - 0.5)


def _link_loads_at_rest():
    """Weight and buoyancy of a whole link [N]."""
    area = math.pi * CHAIN_D**2 / 4
    return CHAIN_DENSITY * area * CHAIN_LINK * G, RHO * area * CHAIN_LINK * G


# top 0.8 m above the water: link 0 crosses downwards, link 1 lies wholly under, link 2 rises
# back through the surface, link 3 is wholly in the air
CROSSING_TOP, CROSSING_ANGLES = 0.8, (40.0, 100.0, 140.0, 120.0)


def test_planar_links_partly_above_the_water_carry_the_buoyancy_of_their_submerged_part():
    built, work = _evaluated(_chain("rigid_links", CROSSING_TOP, CROSSING_ANGLES, joints=0.0))
    w = rigid.workspace(built.params, work, 0)
    n = 4
    weight, buoyancy = _link_loads_at_rest()
    heights = w[pc._PZ, : n + 1]
    assert heights[1] < 0.0 and heights[2] < 0.0 and heights[3] > 0.0 and heights[4] > 0.0
    for i, angle in enumerate(np.radians(CROSSING_ANGLES)):
        fraction, arm = _submerged_part(heights[i], heights[i + 1])
        lift = buoyancy * fraction
        assert w[pc._FX, i] == 0.0
        assert w[pc._FZ, i] == pytest.approx(lift - weight, rel=1e-12)
        # the moment about the centre of the lift at the centroid, arm along e = (sin, -cos):
        # in the plane, (x, z) x (0, lift) = x lift, here about the angle's axis
        assert w[pc._Q, i] == pytest.approx(arm * math.sin(angle) * lift, rel=1e-12, abs=1e-12)
    assert 0.0 < w[pc._Q, 0] and w[pc._Q, 2] < 0.0  # each end's buoyancy lifts its wet end


def test_3d_segments_partly_above_the_water_carry_the_buoyancy_of_their_submerged_part():
    azimuth = 35.0
    case = _chain("rigid_segments_3d", CROSSING_TOP, CROSSING_ANGLES, azimuth=azimuth, added=1.0,
                  joints=0.0)  # fmt: skip
    built, work = _evaluated(case)
    w = rigid.workspace(built.params, work, 0)
    n = 4
    weight, buoyancy = _link_loads_at_rest()
    heights = w[c3._P + 2, : n + 1]
    added = RHO * math.pi * CHAIN_D**2 / 4 * CHAIN_LINK
    for i in range(n):
        fraction, arm = _submerged_part(heights[i], heights[i + 1])
        e = w[c3._E : c3._E + 3, i]
        lift = np.array([0.0, 0.0, buoyancy * fraction])
        np.testing.assert_allclose(w[c3._F : c3._F + 3, i], lift - [0, 0, weight], rtol=1e-12)
        # the moment about the centre: (arm e) x lift, horizontal and normal to the azimuth
        np.testing.assert_allclose(w[c3._TQ : c3._TQ + 3, i], np.cross(arm * e, lift),
                                   rtol=1e-12, atol=1e-12)  # fmt: skip
        # the added mass of the submerged fraction, spread along the segment
        assert w[c3._SA, i] == pytest.approx(fraction * added, rel=1e-12, abs=1e-12)
        inertia = CHAIN_DENSITY * math.pi * CHAIN_D**2 / 4 * CHAIN_LINK**3 / 12
        assert w[c3._SJ, i] == pytest.approx(inertia + fraction * added * CHAIN_LINK**2 / 12)
    heading = math.radians(azimuth)
    torque = w[c3._TQ : c3._TQ + 3, 0]
    assert np.dot(torque, [math.cos(heading), math.sin(heading), 0.0]) == pytest.approx(0.0)


@pytest.mark.parametrize("model", ["rigid_links", "rigid_segments_3d"])
def test_undamped_chain_swinging_through_the_surface_keeps_its_energy(model):
    # released at rest from 80 deg with its top 2 m above the water, the chain swings down
    # through the surface: buoyancy's work is the potential -rho g A l mean(min(z, 0)) of each
    # link (no drag, no added mass). The submerged fraction's slope jumps as a node crosses the
    # surface: rk4 loses orders at those steps (wholly under or above water, this swing keeps
    # its energy to 2e-11 of the kinetic energy's swing at 1 ms, 6e-14 at 0.25 ms)
    swings = []
    for dt in (1e-3, 2.5e-4):
        ds = rows(_chain(model, 2.0, [80.0] * 4, duration=3.0, dt=dt))
        z = ds["node_z"]
        assert z[0, -1] > 0.0 and z.min() < -5.0  # wholly in the air, then mostly under water
        swings.append(np.ptp(ds["total_energy"]) / np.ptp(ds["kinetic_energy"]))
    assert swings[0] < 2e-7 and swings[1] < 1e-8  # measured: 9.8e-8 and 3.7e-9
    assert swings[1] < swings[0] / 8  # converges (measured: by 27)


def test_planar_and_3d_chains_agree_through_the_surface():
    # a planar swing through the surface with drag, in both models (no added mass in 3D: the
    # planar model has none)
    planar = rows(_chain("rigid_links", 2.0, [80.0] * 4, drag=1.2, duration=2.0))
    spatial = rows(_chain("rigid_segments_3d", 2.0, [80.0] * 4, drag=1.2, duration=2.0))
    z = planar["node_z"]
    assert z[0, -1] > 0.0 and z.min() < -1.5
    for name in ("node_x", "node_z"):
        np.testing.assert_allclose(spatial[name], planar[name], rtol=0, atol=1e-9)
    assert np.max(np.abs(spatial["node_y"])) == 0.0
    np.testing.assert_allclose(spatial["tension"], planar["tension"], rtol=1e-7, atol=1e-6)


@pytest.mark.parametrize("model", ["rigid_links", "rigid_segments_3d"])
def test_implicit_scheme_swings_the_chain_through_the_surface_as_rk4(model):
    """Newmark at 2 ms against rk4 at 0.25 ms while the links cross the surface (their
    submerged length changes)."""

    def run(integrator, dt):
        case = _chain(model, 2.0, [80.0] * 4, drag=1.2, added=1.0, duration=2.0, dt=dt)
        return rows(derive_case(case, {"simulation": {"integrator": integrator}}))

    reference = run("rk4", 2.5e-4)
    implicit = run("newmark", 2e-3)
    z = reference["node_z"]
    assert z[0, -1] > 0.0 and z.min() < -1.5
    for name in ("node_x", "node_z"):
        np.testing.assert_allclose(implicit[name], reference[name], atol=1e-4)
