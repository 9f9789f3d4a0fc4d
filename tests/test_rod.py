"""Rods fixed to a body (forces.rod): the hydrostatics of a column crossing the surface at any
tilt against a quadrature of its submerged volume written here, Morison's loads on a submerged
pontoon in a wave against a quadrature of Morison's integral with textbook Airy kinematics
(tests/test_line_waves.airy), the heave period of a free column from its stiffness and its
rod's end added mass, the energy of a free decay, and the case checks that go with them."""

import math

import numpy as np
import pytest

import seacable
from seacable.case.system import ignored_inputs
from seacable.errors import CaseError
from seacable.system import kernel, model
from test_body_morison import _loads
from test_line_waves import airy

RHO, G = 1025.0, 9.81


def _rod(a, b, d, segments, **coefficients):
    return {"model": "rod", "end_a": list(a), "end_b": list(b), "diameter": d,
            "segments": segments, **coefficients}  # fmt: skip


def _case(forces, position=(0.0, 0.0, 0.0), angles=(0.0, 0.0, 0.0), mass=0.0, waves=(),
          current=0.0, dofs=(), inertia=(0.0, 0.0, 0.0), simulation=None):  # fmt: skip
    environment = {"water_density": RHO, "gravity": G, "waves": list(waves),
                   "wave_stretching": "vertical"}  # fmt: skip
    if current:
        environment["current"] = {"velocity": current}
    body = {"name": "spar", "type": "rigid", "position": list(position),
            "orientation_deg": list(angles), "mass": mass, "inertia": list(inertia),
            "dofs": list(dofs), "external forces": forces}  # fmt: skip
    return seacable.load_case({
        "environment": environment, "bodies": [body], "lines": [], "start": "as_given",
        "simulation": simulation or {"duration": 1.0, "output_interval": 0.1},
    })  # fmt: skip


def _submerged(a, t, length, radius, n=200):
    """Volume [m^3] and centroid [m] of the part under z = 0 of the cylinder from ``a`` along
    the unit axis ``t`` (pointing up), by Gauss quadrature over its section: along each
    generator, exactly the part below the surface."""
    e1 = np.cross(t, [0.0, 1.0, 0.0])
    e1 = e1 / np.linalg.norm(e1) if np.linalg.norm(e1) > 1e-9 else np.array([1.0, 0.0, 0.0])
    e2 = np.cross(t, e1)
    x, wr = np.polynomial.legendre.leggauss(n)
    r, wr = (x + 1) / 2 * radius, wr * radius / 2
    phi = np.linspace(0.0, 2 * np.pi, 2 * n, endpoint=False)
    rr, pp = np.meshgrid(r, phi, indexing="ij")
    weight = np.outer(wr, np.full(phi.size, 2 * np.pi / phi.size)) * rr
    off = rr[..., None] * (np.cos(pp)[..., None] * e1 + np.sin(pp)[..., None] * e2)
    top = np.clip(-(a[2] + off[..., 2]) / t[2], 0.0, length)  # wet length of each generator
    volume = np.sum(weight * top)
    moment = np.sum(weight * top**2 / 2) * t + np.sum(weight[..., None] * top[..., None] * off,
                                                      axis=(0, 1))  # fmt: skip
    return volume, a + moment / volume


@pytest.mark.parametrize("tilt", [0.0, 3.0, 10.0, 30.0])
def test_a_tilted_column_has_the_exact_hydrostatics_of_its_wetted_part(tilt):
    """A column 8 m across, 50 m long, 40 m of it below its reference point, which floats
    0.6 m above the water, pitched 0-30 deg: the rod's force and moment are those of rho g
    times the submerged volume at its centroid (quadrature above), the waterplane's tilt
    included, to 1e-9."""
    case = _case([_rod((0, 0, -40), (0, 0, 10), 8.0, 10)], position=(0, 0, 0.6),
                 angles=(0, tilt, 0))  # fmt: skip
    (load,) = _loads(case, (0.0,))
    th = math.radians(tilt)
    t = np.array([math.sin(th), 0.0, math.cos(th)])
    a = np.array([0.0, 0.0, 0.6]) - 40 * t
    volume, centre = _submerged(a, t, 50.0, 4.0)
    buoyancy = RHO * G * volume
    arm = centre - [0.0, 0.0, 0.6]
    expected = np.array([0.0, 0.0, buoyancy, arm[1] * buoyancy, -arm[0] * buoyancy, 0.0])
    np.testing.assert_allclose(load, expected, rtol=1e-9, atol=1e-9 * buoyancy)


def test_a_submerged_rod_and_a_rod_in_air_have_plain_buoyancy():
    """A brace wholly under water, turned in every axis: rho g V at its middle; the same rod
    wholly above the water: nothing."""
    rod = _rod((-3, 1, -2), (4, -2, 3), 1.5, 6)
    volume = math.pi * 1.5**2 / 4 * math.dist((-3, 1, -2), (4, -2, 3))
    case = _case([rod], position=(2, 1, -20), angles=(20, -35, 70))
    (load,) = _loads(case, (0.0,))
    built = model.build(case)
    w = kernel.make_work(built.params)
    kernel.rhs(0.0, built.y0.copy(), built.params, w, np.zeros_like(built.y0))
    rot = np.asarray(w.rot[0])
    middle = rot @ np.array([0.5, -0.5, 0.5])
    f = np.array([0.0, 0.0, RHO * G * volume])
    np.testing.assert_allclose(load, [*f, *np.cross(middle, f)], rtol=1e-10, atol=1e-6)
    (dry,) = _loads(_case([rod], position=(2, 1, 20), angles=(20, -35, 70)), (0.0,))
    assert not np.any(dry)


def _morison(a, b, d, ca, cd, cd_end, ca_end, t, current, wave):
    """Morison's integral along a submerged rod at rest from a to b (points in the x-z plane,
    the wave towards +x), by Gauss quadrature, with the end terms: force and moment about the
    origin."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    length = np.linalg.norm(b - a)
    tan = (b - a) / length
    area = math.pi * d * d / 4
    xs, ws = np.polynomial.legendre.leggauss(64)
    force, moment = np.zeros(3), np.zeros(3)
    for x, w in zip(xs, ws, strict=True):
        p = a + (x + 1) / 2 * (b - a)
        u, v, du, dv = airy(*wave, None, p[0], p[2], t)
        vel, acc = np.array([u + current, 0.0, v]), np.array([du, 0.0, dv])
        vn = vel - (vel @ tan) * tan
        f = RHO * area * (acc + ca * (acc - (acc @ tan) * tan))
        f += 0.5 * RHO * cd * d * np.linalg.norm(vn) * vn
        f += [0.0, 0.0, RHO * G * area]
        force += f * w / 2 * length
        moment += np.cross(p, f) * w / 2 * length
    for end in (a, b):
        u, v, du, dv = airy(*wave, None, end[0], end[2], t)
        vel, acc = np.array([u + current, 0.0, v]), np.array([du, 0.0, dv])
        f = (0.5 * RHO * cd_end * area * abs(vel @ tan) * (vel @ tan)
             + ca_end * RHO * math.pi * d**3 / 12 * (acc @ tan)) * tan  # fmt: skip
        force += f
        moment += np.cross(end, f)
    return np.concatenate([force, moment])


def test_a_submerged_pontoon_in_a_wave_feels_morisons_integral():
    """A pontoon 30 m long, 3 m across, sloping 10 deg, 8 to 13 m down, in a 2 m, 8 s wave and
    a 0.4 m/s current, at rest: its loads at six times against Morison's integral (quadrature,
    textbook Airy) with its end terms, within 2e-4 of their largest at 100 segments (the
    segments' midpoint rule)."""
    slope = math.radians(10)
    a = (-15 * math.cos(slope), 0.0, -13.0)
    b = (15 * math.cos(slope), 0.0, -13.0 + 30 * math.sin(slope))
    coefficients = {"drag_coefficient": 1.1, "added_mass_coefficient": 0.9,
                    "end_drag_coefficient": 0.7, "end_added_mass_coefficient": 0.6}  # fmt: skip
    wave = {"kind": "airy", "height": 2.0, "period": 8.0}
    times = np.linspace(0.0, 8.0, 7)[:-1]
    loads = _loads(_case([_rod(a, b, 3.0, 100, **coefficients)], waves=[wave], current=0.4),
                      times)  # fmt: skip
    for t, load in zip(times, loads, strict=True):
        expected = _morison(a, b, 3.0, 0.9, 1.1, 0.7, 0.6, t, 0.4, (1.0, 8.0))
        scale = np.abs(expected[:3]).max()
        np.testing.assert_allclose(load[:3], expected[:3], atol=2e-4 * scale)
        np.testing.assert_allclose(load[3:], expected[3:], atol=2e-4 * scale * 15)


def test_a_free_column_heaves_at_its_natural_period_and_keeps_its_energy():
    """A free column 6 m across, 30 m draft, on heave alone, 0.5 m above its balance and let
    go: its heave period is 2 pi sqrt((m + CaEnd rho pi d^3 / 12) / (rho g A)) within 1e-5
    (measured 2e-9: the rod's end added mass is in the body's mass), and without drag its
    energy stays within 1e-9 of the stored potential (4e-12: the rod's potential is its
    force's)."""
    d, draft, ca_end = 6.0, 30.0, 0.8
    area = math.pi * d * d / 4
    mass = RHO * area * draft
    added = ca_end * RHO * math.pi * d**3 / 12
    period = 2 * math.pi * math.sqrt((mass + added) / (RHO * G * area))
    forces = [
        {"model": "gravity"},
        _rod((0, 0, -draft), (0, 0, 10), d, 8, end_added_mass_coefficient=ca_end),
    ]
    case = _case(forces, position=(0, 0, 0.5), mass=mass, inertia=(1e8, 1e8, 1e7),
                 dofs=("heave",), simulation={"duration": 35.0, "output_interval": 0.05,
                                              "integrator": "rk4", "time_step": 0.01})  # fmt: skip
    data = seacable.simulate(case).dataset
    body = data["bodies/spar"].to_dataset()
    z, time = body["position_z"].values, body["time"].values
    up = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))
    crossings = time[up] - z[up] * (time[up + 1] - time[up]) / (z[up + 1] - z[up])
    measured = np.diff(crossings).mean()
    assert abs(measured / period - 1) < 1e-5, (measured, period)
    total = data["total_energy"].values
    stored = 0.5 * RHO * G * area * 0.5**2
    assert np.ptp(total) < 1e-9 * stored, (np.ptp(total), stored)


def test_rods_join_the_bodys_added_mass_and_are_checked():
    """The rod's added mass is in the body's (normal Ca rho V of its wetted part, with its
    own turning term, and the end's CaEnd rho pi d^3 / 12 along the axis); a rod on a point
    body, or of zero length, is refused by name; a body with rods in waves is not said to
    be one the waves miss."""
    d, draft = 4.0, 20.0
    rod = _rod((0, 0, -draft), (0, 0, 10), d, 5, added_mass_coefficient=1.0,
               end_added_mass_coefficient=0.6)  # fmt: skip
    case = _case([rod])
    added = np.asarray(model.build(case).params.body_added[0])
    normal = RHO * math.pi * d * d / 4 * draft
    assert added[0, 0] == pytest.approx(normal, rel=1e-12)
    assert added[2, 2] == pytest.approx(0.6 * RHO * math.pi * d**3 / 12, rel=1e-12)
    assert added[0, 4] == pytest.approx(-normal * draft / 2, rel=1e-12)
    assert added[4, 4] == pytest.approx(normal * draft**2 / 3, rel=1e-12)
    waves = _case([rod], waves=[{"kind": "airy", "height": 1.0, "period": 6.0}])
    assert ignored_inputs(waves) == []
    with pytest.raises(ValueError, match="end_a and end_b are the same point"):
        _case([_rod((0, 0, -1), (0, 0, -1), 1.0, 2)])
    point = {"name": "buoy", "type": "point", "position": [0, 0, -5], "mass": 10.0,
             "external forces": [rod]}  # fmt: skip
    with pytest.raises(CaseError, match="a rod turns with its body: give it to a 'rigid'"):
        model.build(seacable.load_case({
            "bodies": [point], "lines": [], "start": "as_given",
            "simulation": {"duration": 1.0, "output_interval": 0.1}}))  # fmt: skip


def test_a_rods_added_mass_is_taken_where_the_statics_puts_its_body():
    """A free column given 3 m below its balance (a 33 m draft), free in heave only (its
    waterplane holds it): the statics raise it until its buoyancy carries its mass (a 30 m
    draft), and its rod's normal added mass is then Ca rho A times that draft (to 1e-9), not
    the 33 m under the water at its start pose."""
    d, draft = 6.0, 30.0
    area = math.pi * d * d / 4
    forces = [
        {"model": "gravity"},
        _rod((0, 0, -33.0), (0, 0, 10), d, 43, added_mass_coefficient=1.0),
    ]
    case = seacable.load_case({
        "environment": {"water_density": RHO, "gravity": G},
        "bodies": [{"name": "spar", "type": "rigid", "position": [0.0, 0.0, 0.0],
                    "mass": RHO * area * draft, "inertia": [1e9, 1e9, 1e8],
                    "dofs": ["heave"], "external forces": forces}],
        "lines": [], "simulation": {"duration": 1.0, "output_interval": 0.1},
    })  # fmt: skip
    built = model.build(case)
    q = int(built.params.body_q[0])
    assert built.y0[q + 2] == pytest.approx(3.0, abs=1e-9)
    added = np.asarray(built.params.body_added[0])
    assert added[0, 0] == pytest.approx(RHO * area * draft, rel=1e-9)
