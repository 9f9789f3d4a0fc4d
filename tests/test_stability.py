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
