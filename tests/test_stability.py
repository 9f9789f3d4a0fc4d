"""The horizontal-plane stability analyses (seacable.stability) against closed forms derived
by hand (docs/tandem.md): a turret-moored tanker in current loses its weathervaning balance
at a pitchfork where the turret passes the neutral point L N'_v / Y'_v; a shuttle tanker on a
hawser from a fixed point fishtails below an astern thrust where the Routh-Hurwitz condition
of its linearised sway-yaw equations fails (a Hopf point). Both hull models; both located by
continuation (seacable.stability.continuation). Every equilibrium found balances its forces
to round-off, and the eigenvalues match the growth a time simulation shows."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import seacable
from seacable.errors import CaseError
from seacable.forces import hull_current as hc
from seacable.stability import equilibria
from seacable.stability.continuation import Continuation
from seacable.stability.parameters import parameter
from seacable.stability.plane import Plane, Weather

RHO, U = 1025.0, 1.0
FORMS = ("short-wing", "cross-flow")
FPSO = (310.0, 58.0, 20.5, 0.85)  # L, B, T, C_B: a VLCC-sized FPSO
OSAKA = (325.0, 53.0, 21.73, 0.831)  # the Esso Osaka (Crane 1973)
XB, KH = 160.0, 2.0e5  # the shuttle's bow fairlead [m from midship], the hawser's k [N/m]


def _ship(name, hull, form, point, position, extra=()):
    length, beam, draught, block = hull
    mass = RHO * length * beam * draught * block
    m22, m26, m62, m66 = hc.added_mass(length, beam, draught, block)
    added = np.zeros((6, 6))
    added[0, 0], added[1, 1], added[1, 5], added[5, 1], added[5, 5] = (
        0.05 * mass, m22, m26, m62, m66)  # fmt: skip
    return {"name": name, "type": "rigid", "position": position, "mass": mass,
            "inertia": [1e12, 1e12, mass * (0.25 * length) ** 2],
            "dofs": ["surge", "sway", "yaw"], "added_mass": added.tolist(), "points": point,
            "external forces": [{"model": form, "length": length, "beam": beam,
                                 "draught": draught, "block_coefficient": block,
                                 "cross_flow_drag": 0.9}, *extra]}  # fmt: skip


def _case(bodies, lines):
    return seacable.load_case({
        "environment": {"current": {"velocity": U, "direction_deg": 180.0}},
        "bodies": [{"name": "anchor", "type": "fixed", "position": [0, 0, 0]}, *bodies],
        "lines": lines, "start": "as_given",
        "simulation": {"duration": 100.0, "output_interval": 1.0},
    })  # fmt: skip


def turret_case(form, turret=150.0, stiffness=1e6):
    ship = _ship("fpso", FPSO, form, {"turret": [turret, 0, 0]}, [-turret, 0, 0])
    return _case([ship], [{"name": "mooring", "model": "tie", "from": "anchor",
                           "to": "fpso.turret", "unstretched_length": 0.0,
                           "stiffness": stiffness}])  # fmt: skip


def shuttle_case(form, hawser=80.0, thrust=0.0):
    astern = {"model": "applied", "frame": "body",
              "force_x": {"kind": "constant", "value": -thrust}}  # fmt: skip
    ship = _ship("shuttle", OSAKA, form, {"bow": [XB, 0, 0]}, [-(hawser + XB), 0, 0], [astern])
    return _case([ship], [{"name": "hawser", "model": "tie", "from": "anchor",
                           "to": "shuttle.bow", "unstretched_length": hawser,
                           "stiffness": KH}])  # fmt: skip


@pytest.mark.parametrize("form", FORMS)
def test_the_weathervaning_balance_is_lost_where_the_turret_passes_the_neutral_point(form):
    """Pinned at a turret x_t forward of midship, a tanker heading into the current has the
    yaw stiffness -1/2 rho L^2 U^2 (L N'_v - x_t Y'_v) about the turret, whatever the
    mooring's stiffness (docs/tandem.md): it turns unstable, by a pitchfork, at
    x_t = L N'_v / Y'_v."""
    length, beam, draught, block = FPSO
    d = hc.clarke(length, beam, draught, block)
    neutral = length * d["N_v"] / d["Y_v"]
    for stiffness in (1e5, 1e7):
        plane = Plane.of(turret_case(form, stiffness=stiffness))
        Weather(U, 180.0).apply(plane.built)
        turret = parameter(plane, "bodies.fpso.points.turret.x")
        branch = Continuation(plane, turret).run(np.array([-150.0, 0.0, 0.0]), 150.0, 60.0)
        points = [s for s in branch.special if s.kind != "hopf"]
        assert [s.kind for s in points] == ["branch point"]
        assert points[0].parameter == pytest.approx(neutral, abs=1e-5)  # 1e-7 relative
        assert branch.unstable[0] == 0 and branch.unstable[-1] == 1


def _routh_hurwitz(thrust, hawser=80.0):
    """a3 a2 a1 - a3^2 a0 - a4 a1^2 of det(M s^2 + C s + K), the shuttle's sway-yaw
    equations linearised by hand (docs/tandem.md), with Clarke's derivatives and added masses:
    the shuttle is stable where it and every coefficient are positive."""
    length, beam, draught, block = OSAKA
    d = hc.clarke(length, beam, draught, block)
    mass = RHO * length * beam * draught * block
    izz = mass * (0.25 * length) ** 2
    m22, m26, m62, m66 = hc.added_mass(length, beam, draught, block)
    row = np.array(hc.pack("cross-flow", (0, 0, 0), length, beam, draught, block, None, 0.9,
                           0.0, 1.19e-6, 0.25, None))  # fmt: skip
    drag = -hc.coefficients(row, U, 0.0, 0.0)[0] * 0.5 * RHO * length * draught
    t0 = drag + thrust  # the hawser's tension
    le = hawser + t0 / KH  # its stretched length
    q, el = 0.5 * RHO, length
    m = np.array([[mass + m22, m26], [m62, izz + m66]])
    c = np.array([[-q * el**2 * U * d["Y_v"], -m22 * U - q * el**3 * U * d["Y_r"]],
                  [-q * el**3 * U * d["N_v"], -m62 * U - q * el**4 * U * d["N_r"]]])  # fmt: skip
    k = np.array([
        [t0 / le, q * el**2 * U**2 * d["Y_v"] + t0 + t0 * XB / le],
        [XB * t0 / le, q * el**3 * U**2 * d["N_v"] + XB * t0 * XB / le + XB * t0],
    ])  # fmt: skip
    poly = [[np.poly1d([m[i, j], c[i, j], k[i, j]]) for j in range(2)] for i in range(2)]
    a4, a3, a2, a1, a0 = (poly[0][0] * poly[1][1] - poly[0][1] * poly[1][0]).coeffs
    return a3 * a2 * a1 - a3**2 * a0 - a4 * a1**2


@pytest.mark.parametrize("form", FORMS)
def test_the_shuttles_hopf_point_in_astern_thrust_agrees_with_routh_hurwitz(form):
    hopf = brentq(_routh_hurwitz, 1e5, 2e5, xtol=1e-9)
    plane = Plane.of(shuttle_case(form))
    Weather(U, 180.0).apply(plane.built)
    thrust = parameter(plane, "bodies.shuttle.external forces.1.force_x")
    branch = Continuation(plane, thrust).run(np.array([-(80.0 + XB), 0.0, 0.0]), -4e5, 0.0)
    found = [s for s in branch.special if s.kind == "hopf"]
    assert len(found) == 1
    assert -found[0].parameter == pytest.approx(hopf, rel=1e-6)
    assert branch.unstable[0] == 0 and branch.unstable[-1] == 2  # fishtailing without thrust


@pytest.mark.parametrize("form", FORMS)
def test_every_equilibrium_balances_and_the_reversed_one_is_unstable(form):
    """The turret-moored tanker has two equilibria: head into the current (stable) and stern
    into it (divergent); each balances its loads to round-off, and the ship does not move
    over the ground while the current flows past it."""
    plane = Plane.of(turret_case(form, turret=120.0))
    found = equilibria.find(plane, Weather(U, 180.0))
    assert len(found) == 2
    kinds = {round(math.degrees(abs(e.x[2]))): e.kind for e in found}
    assert kinds == {0: "stable", 180: "unstable: divergent"}
    for eq in found:
        assert eq.residual < 1e-12
        rates = plane.rates(np.concatenate([eq.x, np.zeros(3)]))
        tension = plane.work.tie_tension[0]  # the current's drag, held by the mooring
        assert tension > 1e4
        assert np.abs(rates[3:5] * plane.weight[:2]).max() < 1e-11 * tension  # round-off
        assert abs(rates[5] * plane.weight[2]) < 1e-11 * tension
        assert rates[0] == rates[1] == rates[2] == 0.0  # at rest over the ground


def test_the_analyses_refuse_what_they_cannot_take():
    case = turret_case("cross-flow")
    data = case.model_dump(by_alias=True)
    data["bodies"][1]["dofs"] = ["surge", "sway", "heave", "yaw"]
    with pytest.raises(CaseError, match="dofs: \\[surge, sway, yaw\\]"):
        Plane.of(seacable.load_case(data))
    data = case.model_dump(by_alias=True)
    data["bodies"][0] = {"name": "anchor", "type": "imposed"}  # at the origin, at rest
    with pytest.raises(CaseError, match="an imposed body moves in time"):
        Plane.of(seacable.load_case(data))
    plane = Plane.of(case)
    with pytest.raises(CaseError, match="no tie 'hawser'"):
        parameter(plane, "lines.hawser.unstretched_length")
    with pytest.raises(CaseError, match="the parameters are"):
        parameter(plane, "current.angle")


EXAMPLE = "examples/tandem_offloading_fpso_shuttle.yaml"


def test_the_tandem_example_from_the_command_line(tmp_path):
    """`seacable equilibria` and `seacable continuation` on the example: the stable tandem
    (both ships heading nearly into the weather, the shuttle behind the FPSO), its unstable
    companions, the branches in the astern thrust with their Hopf points, the files and the
    diagram."""
    import xarray as xr
    from click.testing import CliRunner

    from seacable.cli import main

    root = __import__("pathlib").Path(__file__).parent.parent
    out = tmp_path / "eq.nc"
    run = CliRunner().invoke(main, ["equilibria", str(root / EXAMPLE), "-o", str(out)])
    assert run.exit_code == 0, run.output
    assert "4 equilibria" in run.output and "1. stable" in run.output
    found = xr.open_dataset(out)
    stable = found.isel(equilibrium=0)
    assert bool(stable["stable"]) and found["stable"].values.sum() == 1
    fpso, shuttle = (list(found["body"].values).index(b) for b in ("fpso", "shuttle"))
    assert (
        abs(float(stable["heading"][fpso])) < 10.0 and abs(float(stable["heading"][shuttle])) < 20.0
    )
    assert float(stable["x"][shuttle]) < float(stable["x"][fpso]) - 300.0  # behind it
    assert float(found["residual"].max()) < 1e-12
    picture = tmp_path / "d.png"
    run = CliRunner().invoke(main, [
        "continuation", str(root / EXAMPLE), "--parameter",
        "bodies.shuttle.external forces.2.force_x", "--from", "-6e5", "--to", "0",
        "--plot", str(picture), "-o", str(tmp_path / "c.nc"), "--current", "0.8", "180",
    ])  # fmt: skip
    assert run.exit_code == 0, run.output
    assert "hopf at" in run.output and picture.stat().st_size > 20_000
    branches = xr.open_dataset(tmp_path / "c.nc")
    assert branches.sizes["point"] > 100 and (branches["special_kind"] == "hopf").sum() >= 1
    run = CliRunner().invoke(main, [
        "continuation", str(root / EXAMPLE), "--parameter", "lines.nothing.stiffness",
        "--from", "0", "--to", "1",
    ])  # fmt: skip
    assert run.exit_code != 0 and "no tie 'nothing'" in run.output


def _simulate_from(case, plane, x, duration, output_interval):
    """The system's own time simulation (seacable.simulate, dopri5 at rtol 1e-10) from the
    plane state ``x`` of the case's one free body."""
    data = case.model_dump(by_alias=True)
    body = data["bodies"][1]
    body["position"] = [float(x[0]), float(x[1]), 0.0]
    body["orientation_deg"] = [0.0, 0.0, math.degrees(x[2])]
    body["velocity"] = [float(x[3]), float(x[4]), 0.0]
    body["angular_velocity"] = [0.0, 0.0, float(x[5])]
    data["simulation"] = {"duration": duration, "output_interval": output_interval,
                          "integrator": "dopri5", "rtol": 1e-10, "atol": 1e-12}  # fmt: skip
    return seacable.simulate(seacable.load_case(data)).dataset["bodies/shuttle"]


def _equilibrium_and_pair(plane):
    """The shuttle's equilibrium heading into the current and its fishtailing pair (the
    oscillation that turns it most for its sideways motion; the other is the surge on the
    hawser)."""
    found = [e for e in equilibria.find(plane, Weather(U, 180.0)) if abs(e.x[2]) < 1.0][0]
    x = np.concatenate([found.x, np.zeros(3)])
    lam, vectors = np.linalg.eig(plane.jacobian(x))
    pairs = np.flatnonzero(np.abs(lam.imag) > 1e-12)
    turning = np.abs(vectors[2, pairs]) * 100.0 / np.abs(vectors[:2, pairs]).sum(axis=0)
    k = pairs[np.argmax(turning)]
    return x, lam[k], vectors[:, k].real


@pytest.mark.parametrize("thrust", [0.0, 2.0e5])
def test_the_eigenvalues_give_the_growth_and_decay_a_simulation_shows(thrust):
    """Without astern thrust the shuttle's least damped pair grows (fishtailing starts); with
    200 kN it decays: the envelope of the yaw of a time simulation from a small push along the
    pair's eigenvector grows or decays at Re(lambda), its period 2 pi / Im(lambda)."""
    case = shuttle_case("short-wing", thrust=thrust)
    plane = Plane.of(case)
    x, lam, push = _equilibrium_and_pair(plane)
    start = x + 1e-4 * push / np.abs(push[:3]).max()
    period = 2 * math.pi / abs(lam.imag)
    ship = _simulate_from(case, plane, start, float(math.ceil(6 * period)), 1.0)
    t, yaw = ship["time"].values, np.radians(ship["yaw"].values) - x[2]
    peaks = np.flatnonzero((yaw[1:-1] > yaw[:-2]) & (yaw[1:-1] >= yaw[2:])) + 1
    peaks = peaks[t[peaks] > period]  # past the start's transient of the other modes
    slope = np.polyfit(t[peaks], np.log(yaw[peaks]), 1)[0]
    assert slope == pytest.approx(lam.real, rel=0.02)
    assert np.diff(t[peaks]).mean() == pytest.approx(period, rel=0.01)
    assert (lam.real > 0) == (thrust == 0.0)


@pytest.mark.slow  # a 100,000 s simulation: 100 s; make test-all runs it
def test_the_shuttles_limit_cycle_and_its_floquet_multipliers_against_simulation():
    """Without astern thrust the shuttle settles on a fishtailing cycle: shooting finds it
    (the residual to round-off, a multiplier of 1 along it, the others inside the unit
    circle); a long time simulation of the system settles on the same period and amplitude;
    a push along the leading multiplier's eigenvector shrinks by |multiplier| each period."""
    from seacable.stability import orbits

    case = shuttle_case("short-wing")
    cycle = seacable.periodic_orbit(case)
    assert bool(cycle["converged"]) and float(cycle["residual"]) < 1e-9
    mult = cycle["multiplier_real"].values + 1j * cycle["multiplier_imag"].values
    assert abs(mult[0] - 1.0) < 1e-4 and bool(cycle["stable"])
    period = float(cycle["period"])
    # the system's own simulation, from near the equilibrium, settles on the cycle
    plane = Plane.of(case)
    x, _, push = _equilibrium_and_pair(plane)
    ship = _simulate_from(case, plane, x + 1e-2 * push / np.abs(push[:3]).max(), 100_000.0, 1.0)
    t, yaw = ship["time"].values, ship["yaw"].values
    tail = t > 75_000.0  # settled (the crossings' intervals still drift by 0.06 s at 50,000 s)
    s = yaw[tail] - yaw[tail].mean()
    up = np.flatnonzero((s[:-1] < 0) & (s[1:] >= 0))
    crossings = t[tail][up] - s[up] / (s[up + 1] - s[up])
    assert np.diff(crossings).mean() == pytest.approx(period, rel=2e-6)
    assert np.ptp(yaw[tail]) == pytest.approx(float(cycle["amplitude_heading"][0]), rel=2e-3)
    # Floquet: a push off the cycle along the leading nontrivial multiplier's eigenvector
    Weather(U, 180.0).apply(plane.built)
    x0 = np.array([cycle["x"].values[0, 0], cycle["y"].values[0, 0],
                   math.radians(cycle["heading"].values[0, 0])])  # fmt: skip
    orbit = orbits.shoot(plane, np.concatenate([x0, _cycle_velocity(plane, cycle)]), period)
    scale = orbits._scales(plane)
    steps = orbits._steps(plane, orbit.x0, orbit.period)
    monodromy = orbits._monodromy(plane, orbit.x0, orbit.period, steps, scale)
    values, vectors = np.linalg.eig(monodromy)
    lead = np.argsort(-np.abs(values))[1]  # the largest after the 1 along the orbit
    push = (vectors[:, lead].real + vectors[:, lead].imag) * scale
    start = orbit.x0 + 1e-3 * push / np.abs(push[:3]).max()
    every = orbit.period / 1000
    ship = _simulate_from(case, plane, start, 3000 * every, every)
    states = np.column_stack([ship["position_x"], ship["position_y"], np.radians(ship["yaw"]),
                              ship["velocity_x"], ship["velocity_y"],
                              ship["angular_velocity_z"]])  # fmt: skip
    coefficients = np.linalg.solve(vectors, ((states[::1000] - orbit.x0) / scale).T)
    growth = np.abs(coefficients[lead, 1:] / coefficients[lead, :-1])
    assert growth == pytest.approx(np.abs(values[lead]), rel=0.02)


def _cycle_velocity(plane, cycle):
    """The cycle's start velocities, from its track (central differences of one step)."""
    dt = float(cycle["time"][1] - cycle["time"][0])
    x = cycle["x"].values[:, 0]
    y = cycle["y"].values[:, 0]
    psi = np.unwrap(np.radians(cycle["heading"].values[:, 0]))
    return np.array([(x[1] - x[-2]) / (2 * dt), (y[1] - y[-2]) / (2 * dt),
                     (psi[1] - psi[-2]) / (2 * dt)])  # fmt: skip


def test_clearance_between_outlines():
    from seacable.stability.orbits import clearance

    box = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])
    assert clearance([box, box + (5.0, 0.0)]) == pytest.approx(3.0)
    assert clearance([box, box + (4.0, 4.0)]) == pytest.approx(math.sqrt(8.0))
    assert clearance([box, box + (1.0, 0.5)]) == 0.0
    turned = np.array([[2.0, 0.0], [0.0, 2.0], [-2.0, 0.0], [0.0, -2.0]]) + (5.0, 0.0)
    assert clearance([box, turned]) == pytest.approx(2.0)


def test_the_orbit_command(tmp_path):
    import yaml
    from click.testing import CliRunner

    from seacable.cli import main

    case = tmp_path / "shuttle.yaml"
    data = shuttle_case("cross-flow").model_dump(by_alias=True, exclude_none=True)
    case.write_text(yaml.safe_dump(data))
    run = CliRunner().invoke(main, ["orbit", str(case), "-o", str(tmp_path / "o.nc"),
                                    "--plot", str(tmp_path / "o.png")])  # fmt: skip
    assert run.exit_code == 0, run.output
    assert (tmp_path / "o.png").stat().st_size > 10_000
    assert "limit cycle: period" in run.output and "shooting converged" in run.output
    assert "hawser: tension 0 to" in run.output  # it goes slack in every cycle
    root = __import__("pathlib").Path(__file__).parent.parent
    run = CliRunner().invoke(main, ["orbit", str(root / EXAMPLE)])  # it comes to rest
    assert run.exit_code != 0 and "no limit cycle from there" in run.output
