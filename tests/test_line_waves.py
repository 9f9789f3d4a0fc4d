"""Incident waves on lumped-mass lines (kernels.morison through kernels.lumped): Morison's
loads against the textbook Airy kinematics written here (not kernels.waves), a neutrally
buoyant node carried on the Airy orbit, zero waves bitwise the still-water run, Wheeler and
vertical stretching, a mooring line's tension at the wave frequency."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

import seacable
from seacable.kernels import chain3d as c3
from seacable.kernels import lumped as lk
from seacable.kernels import waves as kw
from seacable.system import kernel, model

RHO, G = 1025.0, 9.81
D = 0.2  # line diameter [m]
AREA = math.pi * D**2 / 4


def _wave_number(omega, depth):
    """k of omega^2 = g k tanh(k h) (deep water: h None)."""
    if depth is None:
        return omega**2 / G
    return brentq(lambda k: G * k * math.tanh(k * depth) - omega**2, 1e-9, 10 * omega**2 / G)


def airy(a, period, depth, x, z, t, phase=0.0):
    """Textbook linear wave travelling towards +x, eta = a cos(kx - wt + phase): the water's
    (u, w, du/dt, dw/dt) at (x, z) [m/s, m/s^2]; finite depth: cosh k(z+h) / sinh kh and
    sinh k(z+h) / sinh kh, deep water: e^{kz}."""
    omega = 2 * math.pi / period
    k = _wave_number(omega, depth)
    theta = k * x - omega * t + phase
    if depth is None:
        horizontal = vertical = math.exp(k * z)
    else:
        horizontal = math.cosh(k * (z + depth)) / math.sinh(k * depth)
        vertical = math.sinh(k * (z + depth)) / math.sinh(k * depth)
    u = a * omega * horizontal * math.cos(theta)
    w = a * omega * vertical * math.sin(theta)
    return (
        u,
        w,
        a * omega**2 * horizontal * math.sin(theta),
        -a * omega**2 * vertical * math.cos(theta),
    )


def _case(top, bottom, segments, length, *, waves=(), depth=None, stretching="vertical",
          current=0.0, cd=1.2, cdt=0.5, ca=1.0, mass=None, ends="fixed", velocity=(0, 0, 0),
          duration=1.0, simulation=None, line_model="lumped_mass"):  # fmt: skip
    """A line (``line_model``) of a 0.2 m line type between two bodies at ``top`` and
    ``bottom`` (``ends`` fixed; ``free``: massless point bodies free to move, starting at
    ``velocity``: the whole line does; ``hang``: ``bottom`` a 50 kg point body)."""
    environment = {"water_density": RHO, "gravity": G, "waves": list(waves),
                   "wave_stretching": stretching}  # fmt: skip
    if depth is not None:
        environment["water_depth"] = depth
    if current:
        environment["current"] = {"velocity": current}
    if ends in ("fixed", "hang"):
        bodies = [{"name": "a", "type": "fixed", "position": list(top)},
                  {"name": "b", "type": "fixed", "position": list(bottom)}]  # fmt: skip
        if ends == "hang":
            bodies[1] = {"name": "b", "type": "point", "position": list(bottom), "mass": 50.0,
                         "external forces": [{"model": "gravity"}]}  # fmt: skip
    else:
        bodies = [{"name": name, "type": "point", "position": list(at), "mass": 0.0,
                   "velocity": list(velocity)}
                  for name, at in (("a", top), ("b", bottom))]  # fmt: skip
    rope = {"name": "rope", "diameter": D, "mass_per_length": mass or 3.0 * RHO * AREA,
            "axial_stiffness": 1.0e6, "drag_coefficient_normal": cd,
            "drag_coefficient_tangential": cdt, "added_mass_coefficient": ca}  # fmt: skip
    return seacable.load_case({
        "environment": environment, "bodies": bodies, "line_types": [rope],
        "lines": [{"name": "line", "model": line_model, "from": "a", "to": "b",
                   "sections": [{"type": "rope", "length": length, "segments": segments}],
                   "initial": "straight"}],
        "start": "as_given",
        "simulation": simulation or {"duration": duration, "output_interval": 0.1},
    })  # fmt: skip


def _node_loads(built, t):
    """Every node's load at rest at time t (kernels.lumped's workspace rows _F) [N]; of a 3D
    rigid-segment line, every segment's (kernels.chain3d_loads's rows _F)."""
    p = built.params
    w = kernel.make_work(p)
    kernel.rhs(t, built.y0.copy(), p, w, np.zeros_like(built.y0))
    if len(p.rs_n):
        n = p.rs_n[0]
        rows = c3.N_WORK_ROWS
        return w.rs[: rows * (n + 1)].reshape(rows, n + 1)[c3._F : c3._F + 3, :n].copy()
    return w.nodes[lk._F : lk._F + 3].copy()


def _morison_vertical(a, period, depth, x, z, t, length, current=0.0, cd=1.2, cdt=0.5, ca=1.0):
    """Morison's load [N] on a vertical segment at rest centred at (x, z): normal (horizontal)
    drag 0.5 rho Cd D l |u_n| u_n on the water's velocity relative to it (the current's and the
    wave's), tangential drag 0.5 rho (pi Cd_t) D l |u_t| u_t, inertia (1 + Ca) rho A l du/dt
    normal to it and rho A l dw/dt along it."""
    u, w, du, dw = airy(a, period, depth, x, z, t)
    u += current
    fx = 0.5 * RHO * cd * D * length * abs(u) * u + (1 + ca) * RHO * AREA * length * du
    fz = 0.5 * RHO * math.pi * cdt * D * length * abs(w) * w + RHO * AREA * length * dw
    return fx, fz


@pytest.mark.parametrize("depth", [None, 30.0])
@pytest.mark.parametrize("line_model", ["lumped_mass", "rigid_segments_3d"])
def test_a_fixed_vertical_line_feels_morisons_loads(depth, line_model):
    """Two short vertical segments held at rest in a regular wave (H 2 m, T 5 s) and a current,
    at two depths and six times: the line's load less its apparent weight is the sum of the
    textbook Morison loads at the segments' centres (the tensions cancel in the sum), on their
    unstretched lengths (a lumped line is stretched 1 %: its coefficients are per unstretched
    metre, as its mass). Lumped-mass and 3D rigid-segment lines alike."""
    a, period, length, n = 1.0, 5.0, 1.0, 2
    unstretched = 0.99 * length if line_model == "lumped_mass" else length
    wave = {"kind": "airy", "height": 2 * a, "period": period}
    worst = scale = 0.0
    for top in (-4.0, -18.0):
        built = model.build(_case((3.0, 0.0, top), (3.0, 0.0, top - length), n, unstretched,
                                  waves=[wave], depth=depth, current=0.4,
                                  line_model=line_model))  # fmt: skip
        weight = 2.0 * (RHO * AREA * unstretched * G)  # (3 - 1) rho A g per metre
        for t in np.linspace(0.0, period, 7)[:-1]:
            load = _node_loads(built, t).sum(axis=1)
            expected = np.zeros(3)
            for i in range(n):
                zc = top - (i + 0.5) * length / n
                fx, fz = _morison_vertical(a, period, depth, 3.0, zc, t, unstretched / n, 0.4)
                expected += (fx, 0.0, fz)
            expected[2] -= weight
            worst = max(worst, np.abs(load - expected).max())
            scale = max(scale, np.abs(expected).max())
    assert worst < 1e-9 * scale, (worst, scale)


@pytest.mark.parametrize("line_model", ["lumped_mass", "rigid_segments_3d"])
def test_waves_of_zero_height_are_bitwise_still_water(monkeypatch, line_model):
    """A line piercing the surface in a current, a 50 kg weight at its end, in a regular wave
    whose amplitude is then set to zero (the wave code runs: elevations, kinematics, inertia),
    gives bitwise the run without waves evaluated by the same compiled copy (the one with the
    waves' code, system.variants), and the run by the copy without it to round-off (carried by
    the adaptive steps: far below the integrator's tolerance)."""
    from seacable import packing
    from seacable.system import variants

    def run(waves):
        case = _case((0.0, 0.0, 1.0), (4.0, 0.0, -3.0), 8, 5.8, waves=waves, current=0.3,
                     ends="hang", line_model=line_model,
                     simulation={"duration": 2.0, "output_interval": 0.1, "integrator": "dopri5",
                                 "rtol": 1e-7, "atol": 1e-9})  # fmt: skip
        return seacable.simulate(case).dataset

    own_copy = run([])  # evaluated by the copy compiled without the waves' code
    features = variants.features
    with monkeypatch.context() as patch:
        patch.setattr(variants, "features", lambda p: (*features(p), "WAVES"))
        still = run([])
    original = packing.wave_fields

    rows = []

    def flat(env, build_up=0.0):
        fields = original(env, build_up)
        fields["wave"][kw.A] = 0.0
        rows.append(fields["wave"].shape[1])
        return fields

    monkeypatch.setattr(packing, "wave_fields", flat)
    flat_sea = run([{"kind": "airy", "height": 2.0, "period": 5.0}])
    assert rows and rows[-1] == 1  # the run had its (flat) wave
    for name in still.data_vars:
        np.testing.assert_array_equal(flat_sea[name].values, still[name].values, err_msg=name)
        # two compiled copies round differently (LLVM contracts and orders their operations
        # each its own way), and dopri5's step control carries a difference of one rounding
        # through 2 s: 4.5e-10 of the kinetic energy of the 3D line with numba 0.68.1 (1e-12
        # before): far below the integrator's rtol 1e-7, which is what the copies must respect
        np.testing.assert_allclose(own_copy[name].values, still[name].values, rtol=1e-8,
                                   atol=1e-10, err_msg=name)  # fmt: skip
    assert np.ptp(still["bodies/b/position_z"].values) > 0.01  # it moves


def _fit(times, values, omega, order=1):
    """Least squares of a polynomial of ``order`` in t plus A cos(w t) + B sin(w t): the
    amplitude sqrt(A^2 + B^2) and the polynomial's coefficients."""
    basis = np.column_stack([times**j for j in range(order + 1)]
                            + [np.cos(omega * times), np.sin(omega * times)])  # fmt: skip
    coef, *_ = np.linalg.lstsq(basis, values, rcond=None)
    return math.hypot(coef[-2], coef[-1]), coef[: order + 1]


def test_a_neutrally_buoyant_line_is_carried_on_the_airy_orbit():
    """A free, neutrally buoyant, drag-free line with Ca = 1 (mass rho A per metre, its ends on
    massless point bodies) lying along the crests 5 m down in deep water (a = 0.1 m, T = 6 s):
    each node's acceleration is the water's: started with the water's velocity, it moves on
    the Airy orbit of radius a e^{kz} both ways (measured 0.7 % small both ways: second order,
    ak = 0.011). Two second-order
    effects show, each against its closed form: Stokes's drift a^2 w k e^{2kz} (the velocity
    where the node is, not where it started), and a sinking at k (a w)^2 e^{2kz}: Morison's
    inertia is linear theory's local acceleration du/dt, not the particle's
    du/dt + (u . grad) u = du/dt + grad(|u|^2 / 2), which in deep water adds that much upwards."""
    a, period, z0 = 0.1, 6.0, -5.0
    omega = 2 * math.pi / period
    k = omega**2 / G
    radius = a * math.exp(k * z0)
    case = _case((0.0, -2.0, z0), (0.0, 2.0, z0), 4, 4.0, ends="free", cd=0.0, cdt=0.0,
                 velocity=(omega * radius, 0.0, 0.0),
                 mass=RHO * AREA, waves=[{"kind": "airy", "height": 2 * a, "period": period}],
                 simulation={"duration": 2 * period, "output_interval": 0.05,
                             "integrator": "dopri5", "rtol": 1e-9, "atol": 1e-11})  # fmt: skip
    ds = seacable.simulate(case).dataset
    times = ds["time"].values
    for body in ("a", "b"):
        horizontal, (_, drift) = _fit(times, ds[f"bodies/{body}/position_x"].values, omega)
        vertical, (_, rise, sink) = _fit(times, ds[f"bodies/{body}/position_z"].values, omega, 2)
        for amplitude in (horizontal, vertical):
            assert abs(amplitude / radius - 1) < 0.01, (horizontal, vertical, radius)
        stokes = omega * k * radius**2
        assert abs(drift / stokes - 1) < 0.05, (drift, stokes)  # measured 1.8 %
        convective = k * (omega * radius) ** 2
        assert abs(-2 * sink / convective - 1) < 0.05, (2 * sink, convective)  # 0.5 %
        assert abs(rise) < 0.1 * stokes, rise  # measured 0.05
        assert np.ptp(ds[f"bodies/{body}/position_y"].values) < 1e-6  # along the crests


def test_wheeler_and_vertical_stretching_on_a_line_through_the_surface():
    """A vertical line from 3 m above the mean level to 12 m below it, held in a deep-water
    wave (a = 1 m, T = 6 s), 0.25 m segments: its horizontal load is Morison's per metre
    integrated from its bottom to the instantaneous surface eta (nothing above), the kinematics
    evaluated at z (below 0) or 0 (above) for vertical stretching, at z - eta (Wheeler's
    stretching in deep water) (midpoint rule: within 1e-4). Where eta = 0 the two are the same
    load; under the crest and the trough they differ."""
    a, period, top, bottom, n = 1.0, 6.0, 3.0, -12.0, 60
    omega = 2 * math.pi / period
    loads = {}
    for stretching in ("vertical", "wheeler"):
        built = model.build(_case((0.0, 0.0, top), (0.0, 0.0, bottom), n, top - bottom,
                                  waves=[{"kind": "airy", "height": 2 * a, "period": period}],
                                  stretching=stretching))  # fmt: skip
        for quarter in range(8):  # theta = -w t from 0 (crest) by -pi/4
            t = quarter * period / 8
            eta = a * math.cos(omega * t)

            def per_metre(z, shift, t=t):
                u, _, du, _ = airy(a, period, None, 0.0, z + shift, t)
                return 0.5 * RHO * 1.2 * D * abs(u) * u + 2.0 * RHO * AREA * du

            if stretching == "vertical":
                expected = quad(per_metre, bottom, min(eta, 0.0), args=(0.0,))[0]
                expected += max(eta, 0.0) * per_metre(0.0, 0.0)
            else:
                expected = quad(per_metre, bottom, eta, args=(-eta,))[0]
            loads[stretching, quarter] = _node_loads(built, t)[0].sum()
            scale = 0.5 * RHO * 1.2 * D * (a * omega) ** 2 * (top - bottom)
            assert abs(loads[stretching, quarter] - expected) < 1e-4 * scale, (
                stretching, quarter, loads[stretching, quarter], expected)  # fmt: skip
    for quarter in (2, 6):  # eta = 0
        assert loads["vertical", quarter] == pytest.approx(loads["wheeler", quarter], rel=1e-12)
    for quarter in (0, 4):  # under the crest: Wheeler's decays from the surface; the trough
        assert abs(loads["wheeler", quarter] / loads["vertical", quarter] - 1) > 0.1


def _mooring(waves):
    """A 250 m chain (20 segments) from an anchor 200 m down to a fairlead held 8 m below the
    mean level, 100 m across, resting on the seabed: its fairlead tension [N] and times [s]."""
    chain = {"name": "chain", "diameter": 0.137, "mass_per_length": 126.0,
             "axial_stiffness": 5.0e7, "axial_damping_ratio": 0.5,
             "drag_coefficient_normal": 2.4, "drag_coefficient_tangential": 0.4}  # fmt: skip
    case = seacable.load_case({
        "environment": {"water_density": RHO, "gravity": G, "water_depth": 200.0,
                        "seabed": {"stiffness": 3.0e5, "damping": 3.0e3}, "waves": waves},
        "bodies": [{"name": "anchor", "type": "fixed", "position": [-100.0, 0.0, -200.0]},
                   {"name": "fairlead", "type": "fixed", "position": [0.0, 0.0, -8.0]}],
        "line_types": [chain],
        "lines": [{"name": "line", "model": "lumped_mass", "from": "anchor", "to": "fairlead",
                   "sections": [{"type": "chain", "length": 250.0, "segments": 20}]}],
        "simulation": {"duration": 48.0, "output_interval": 0.25, "integrator": "dopri5",
                       "rtol": 1e-6, "atol": 1e-8},
    })  # fmt: skip
    ds = seacable.simulate(case).dataset
    return ds["time"].values, ds["lines/line/tension"].values[:, -1]


def test_a_mooring_lines_tension_has_the_wave_frequency():
    """The chain in a regular wave (H 4 m, T 8 s) along it: after 16 s the fairlead tension
    oscillates at the wave's frequency (its spectrum's peak, other than the mean, at 1/T), by
    far more than in still water, where it stays where it started."""
    period = 8.0
    times, tension = _mooring([{"kind": "airy", "height": 4.0, "period": period}])
    _, still = _mooring([])
    late = (times >= 16.0) & (times < 48.0)  # four periods
    spectrum = np.abs(np.fft.rfft(tension[late] - tension[late].mean()))
    frequencies = np.fft.rfftfreq(late.sum(), times[1] - times[0])
    assert frequencies[spectrum.argmax()] == pytest.approx(1 / period, abs=1e-9)
    swing = np.ptp(tension[late])  # measured 1.0 kN of 222 kN (the fairlead is held: the
    assert swing > 0.002 * tension.mean(), swing  # waves' drag and inertia on the chain alone)
    assert np.ptp(still[late]) < 0.01 * swing, np.ptp(still[late])
