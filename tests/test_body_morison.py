"""Bodies without a hull mesh or database in waves (forces.drag on the water's velocity,
forces.fluid_inertia): the loads at rest against Morison's equation written here from the
textbook Airy kinematics (tests/test_line_waves.airy, not kernels.waves), a turned rigid body's
moment from its centre of buoyancy and its added mass's coupling terms, a neutrally buoyant
body carried on the Airy orbit, and the case checks that go with them."""

import math

import numpy as np
import pytest

import seacable
from seacable.case.system import ignored_inputs
from seacable.errors import CaseError
from seacable.system import kernel, model
from test_line_waves import _fit, airy

RHO, G = 1025.0, 9.81
WAVE = {"kind": "airy", "height": 2.0, "period": 7.0}


def _case(body, waves=(WAVE,), depth=None, current=0.0, simulation=None):
    environment = {
        "water_density": RHO,
        "gravity": G,
        "waves": list(waves),
        "wave_stretching": "vertical",
    }  # linear theory's kinematics below z = 0
    if depth is not None:
        environment["water_depth"] = depth
    if current:
        environment["current"] = {"velocity": current}
    return seacable.load_case({
        "environment": environment, "bodies": [body], "lines": [], "start": "as_given",
        "simulation": simulation or {"duration": 1.0, "output_interval": 0.1},
    })  # fmt: skip


def _loads(case, times):
    """The body's force models' load (6) at rest at each time [N, N m]."""
    built = model.build(case)
    p = built.params
    w = kernel.make_work(p)
    out = []
    for t in times:
        kernel.rhs(t, built.y0.copy(), p, w, np.zeros_like(built.y0))
        out.append(w.models[0].copy())
    return np.array(out)


@pytest.mark.parametrize("depth", [None, 25.0])
def test_a_point_body_at_rest_feels_morisons_equation(depth):
    """A buoy held 4 m down (V 3 m^3, Ca 0.8 per axis, CdA 1.5, 2, 2.5 m^2) in a regular wave
    (H 2 m, T 7 s) and a 0.3 m/s current, at eight times: drag 0.5 rho CdA_k |u| u_k on the
    water's velocity, inertia (rho V + Ca rho V) du/dt, weight and buoyancy, to round-off."""
    v, ca, cda = 3.0, 0.8, np.array([1.5, 2.0, 2.5])
    at = (4.0, 0.0, -4.0)
    body = {"name": "buoy", "type": "point", "position": list(at), "mass": 1000.0,
            "volume": v, "added_mass": ca * RHO * v, "dofs": [],
            "external forces": [{"model": "gravity"}, {"model": "buoyancy"},
                                {"model": "drag", "drag_coefficient": 1.0, "area": cda.tolist()},
                                {"model": "fluid inertia"}]}  # fmt: skip
    times = np.linspace(0.0, 7.0, 9)[:-1]
    loads = _loads(_case(body, depth=depth, current=0.3), times)
    for t, load in zip(times, loads, strict=True):
        u, w, du, dw = airy(1.0, 7.0, depth, at[0], at[2], t)
        rel = np.array([u + 0.3, 0.0, w])
        drag = 0.5 * RHO * cda * np.linalg.norm(rel) * rel
        inertia = (1 + ca) * RHO * v * np.array([du, 0.0, dw])
        expected = drag + inertia + [0.0, 0.0, (RHO * v - 1000.0) * G]
        np.testing.assert_allclose(load[:3], expected, rtol=1e-10, atol=1e-9 * RHO * v * G)
        assert np.abs(load[3:]).max() < 1e-9


def test_a_turned_rigid_body_feels_its_added_mass_and_centre_of_buoyancy():
    """A rigid body yawed 30 deg and pitched 10 deg, held 6 m down in the wave, its centre of
    buoyancy 1 m above its reference point, a full (symmetric) 6x6 added mass in its frame:
    fluid inertia alone is rho V a at the centre of buoyancy plus R (A [R^T a; 0]) as force and
    moment, written here with numpy."""
    v = 5.0
    rng = np.random.default_rng(7)
    half = rng.normal(size=(6, 6)) * 300.0
    added = half @ half.T + np.diag([4e3, 5e3, 6e3, 2e3, 2e3, 3e3])
    at, cob = np.array([2.0, 1.0, -6.0]), np.array([0.0, 0.0, 1.0])
    body = {"name": "box", "type": "rigid", "position": at.tolist(), "mass": 1000.0,
            "volume": v, "centre_of_buoyancy": cob.tolist(), "added_mass": added.tolist(),
            "orientation_deg": [0.0, 10.0, 30.0], "inertia": [1e3, 1e3, 1e3], "dofs": [],
            "external forces": [{"model": "fluid inertia"}]}  # fmt: skip
    times = np.linspace(0.0, 7.0, 5)[:-1]
    loads = _loads(_case(body, waves=[{**WAVE, "direction_deg": 40.0}]), times)
    from scipy.spatial.transform import Rotation

    rot = Rotation.from_euler("ZYX", [30.0, 10.0, 0.0], degrees=True).as_matrix()
    k = (2 * math.pi / 7.0) ** 2 / G
    for t, load in zip(times, loads, strict=True):
        along = at[0] * math.cos(math.radians(40.0)) + at[1] * math.sin(math.radians(40.0))
        _, _, dh, dw = airy(1.0, 7.0, None, along, at[2], t)
        acc = np.array([dh * math.cos(math.radians(40.0)), dh * math.sin(math.radians(40.0)), dw])
        froude_krylov = RHO * v * acc
        arm = rot @ cob
        body_frame = added[:, :3] @ (rot.T @ acc)
        force = froude_krylov + rot @ body_frame[:3]
        moment = np.cross(arm, froude_krylov) + rot @ body_frame[3:]
        scale = RHO * v * (1.0 * (2 * math.pi / 7.0) ** 2) * math.exp(k * at[2])
        np.testing.assert_allclose(load, np.concatenate([force, moment]), rtol=0,
                                   atol=1e-10 * scale * 10)  # fmt: skip


def test_a_neutrally_buoyant_body_is_carried_on_the_airy_orbit():
    """A drag-free point body whose mass is its displaced mass (V 2 m^3, Ca 0.6), 6 m down in
    deep water (a = 0.2 m, T = 8 s), started with the water's velocity: its acceleration is the
    water's, so it moves on the orbit of radius a e^{kz} both ways (within 1 %), with Stokes's
    drift w k r^2 and the sinking k (w r)^2 of linear theory's local acceleration (each
    within 5 %: tests/test_line_waves, the same for a line's nodes)."""
    a, period, z0, v = 0.2, 8.0, -6.0, 2.0
    omega = 2 * math.pi / period
    k = omega**2 / G
    radius = a * math.exp(k * z0)
    body = {"name": "buoy", "type": "point", "position": [0.0, 0.0, z0],
            "velocity": [omega * radius, 0.0, 0.0], "mass": RHO * v, "volume": v,
            "added_mass": 0.6 * RHO * v,
            "external forces": [{"model": "gravity"}, {"model": "buoyancy"},
                                {"model": "fluid inertia"}]}  # fmt: skip
    ds = seacable.simulate(_case(body, waves=[{"kind": "airy", "height": 2 * a,
                                               "period": period}],
                                 simulation={"duration": 2 * period, "output_interval": 0.05,
                                             "integrator": "dopri5", "rtol": 1e-9,
                                             "atol": 1e-11})).dataset  # fmt: skip
    times = ds["time"].values
    horizontal, (_, drift) = _fit(times, ds["bodies/buoy/position_x"].values, omega)
    vertical, (_, _, sink) = _fit(times, ds["bodies/buoy/position_z"].values, omega, 2)
    for amplitude in (horizontal, vertical):
        assert abs(amplitude / radius - 1) < 0.01, (horizontal, vertical, radius)
    assert abs(drift / (omega * k * radius**2) - 1) < 0.05, drift
    assert abs(-2 * sink / (k * (omega * radius) ** 2) - 1) < 0.05, sink


def test_fluid_inertia_needs_a_volume_or_added_mass_and_no_second_froude_krylov():
    body = {"name": "buoy", "type": "point", "position": [0.0, 0.0, -5.0], "mass": 10.0,
            "external forces": [{"model": "fluid inertia"}]}  # fmt: skip
    with pytest.raises(CaseError, match="'fluid inertia' acts on the body's 'volume'"):
        _case(body)
    assert _case({**body, "volume": 1.0}) is not None
    assert _case({**body, "added_mass": 100.0}) is not None


def test_waves_on_a_body_with_drag_or_fluid_inertia_are_not_said_to_act_on_nothing():
    base = {"name": "buoy", "type": "point", "position": [0.0, 0.0, -5.0], "mass": 10.0,
            "volume": 1.0}  # fmt: skip
    bare = _case({**base, "external forces": [{"model": "buoyancy"}]})
    assert any("act on none of its force models" in line for line in ignored_inputs(bare))
    for model_ in ({"model": "fluid inertia"},
                   {"model": "drag", "drag_coefficient": 1.0, "area": 1.0}):  # fmt: skip
        held = _case({**base, "external forces": [{"model": "buoyancy"}, model_]})
        assert ignored_inputs(held) == []
