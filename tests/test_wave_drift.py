"""The mean wave drift force from coefficient tables (forces.wave_drift, ``model: wave
drift``): against its closed forms (D(beta) Hs^2 / 8 in a JONSWAP sea, a^2 D(w, beta)
bilinear in a regular wave), turning with the ship, its moment's lever arm, a free ship's
steady drift speed in a time simulation, and a turret-moored tanker that weathervanes to head
the waves in the horizontal-plane analyses (Weather's wave_towards_deg turning it)."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

import seacable
from seacable import seastate
from seacable.errors import CaseError
from seacable.kernels import waves
from seacable.stability import equilibria
from seacable.stability.parameters import parameter
from seacable.stability.plane import Plane, Weather
from test_stability import FPSO, _ship
from test_vessel_control import _case, _loads

EXAMPLES = Path(__file__).parent.parent / "examples"
HS, TP = 2.5, 10.0
HEADINGS = np.arange(0.0, 360.0, 30.0)
# an asymmetric table (D_X, D_Y [N/m^2], D_N [N m/m^2] per row): every column differs
TABLE = np.column_stack([HEADINGS, -1e5 * np.cos(np.radians(HEADINGS)) + 2e4,
                         -8e5 * np.sin(np.radians(HEADINGS)) + 1e4 * np.cos(np.radians(HEADINGS)),
                         3e7 * np.sin(np.radians(2 * HEADINGS)) - 5e6])  # fmt: skip


def _drift(table=TABLE, **more):
    return {"model": "wave drift", "coefficients": np.asarray(table).tolist()} | more


def _jonswap(towards=180.0, **more):
    return {"kind": "jonswap", "significant_height": HS, "peak_period": TP,
            "direction_deg": towards} | more  # fmt: skip


def _body_frame(load, yaw):
    """The load (earth frame) in the body frame of a level ship at ``yaw`` [rad]."""
    c, s = math.cos(yaw), math.sin(yaw)
    return np.array([c * load[0] + s * load[1], -s * load[0] + c * load[1], load[5]])


def test_a_frequency_independent_table_in_a_jonswap_sea_gives_d_times_hs_squared_over_8():
    """F = D(beta) sum a_i^2 to round-off, beta the direction the sea comes from relative to
    the bow (waves towards 180 deg, ship at yaw 30 deg: from 330 deg, a row of the table), and
    sum a_i^2 = Hs^2 / 8 to the discretisation's 1 %: the 200 bands between 0.5 and 3 w_p,
    each its S at a random frequency inside, are a Riemann sum of 2 int S over the bands (they
    hold 99.0 % of m0; the sum is 99.25 % of Hs^2 / 8 with seed 0)."""
    env = {"waves": [_jonswap()]}
    yaw = math.radians(30.0)
    case = _case([_drift()], env=env)
    load = _body_frame(_loads(case, angles=(0, 0, yaw)), yaw)
    spec = case.environment.waves[0]
    total = float(np.sum(seastate.components(spec, waves.DEEP, 9.81)[:, 0] ** 2))
    expected = TABLE[HEADINGS == 330.0][0, 1:] * total
    np.testing.assert_allclose(load, expected, rtol=1e-12)
    wp = 2.0 * math.pi / TP
    bands = 2.0 * quad(lambda w: float(seastate.spectrum(spec, w)), 0.5 * wp, 3.0 * wp)[0]
    assert bands / (HS**2 / 8.0) == pytest.approx(0.990, abs=5e-4)  # the tails: 1.0 %
    assert total == pytest.approx(bands, rel=0.005)
    assert total == pytest.approx(HS**2 / 8.0, rel=0.01)


def test_a_regular_wave_with_a_frequency_table_gives_a_squared_d_bilinear():
    """a^2 D(w, beta) with D bilinear between the table's frequencies and headings: at
    w = 0.5 rad/s (between 0.4 and 0.6) and beta = 20 deg (between 0 and 30)."""
    omegas = (0.4, 0.6, 0.8)
    scale = {0.4: 0.3, 0.6: 1.0, 0.8: 0.7}
    rows = [[w, *(r[0:1]), *(scale[w] * r[1:] + w * 1e3)] for w in omegas for r in TABLE]
    height, omega = 3.0, 0.5
    env = {"waves": [{"kind": "airy", "height": height, "period": 2 * math.pi / omega,
                      "direction_deg": 200.0}]}  # fmt: skip
    yaw = math.radians(0.0)  # from 20 deg: the waves go towards 200
    load = _body_frame(_loads(_case([_drift(rows)], env=env)), yaw)

    def at(w, row):
        return scale[w] * TABLE[row, 1:] + w * 1e3

    beta_mix = 20.0 / 30.0
    low = (1 - beta_mix) * at(0.4, 0) + beta_mix * at(0.4, 1)
    high = (1 - beta_mix) * at(0.6, 0) + beta_mix * at(0.6, 1)
    np.testing.assert_allclose(load, (height / 2) ** 2 * (0.5 * low + 0.5 * high), rtol=1e-12)


def test_the_force_turns_with_the_ship_and_head_seas_on_a_symmetric_hull_push_straight():
    """Ship and waves turned together: the same body-frame load. Head seas on a symmetric
    table (0 to 180 deg, mirrored): no sway force, no yaw moment, the surge force D_X(0)."""
    rng = np.random.default_rng(7)
    for _ in range(3):
        yaw, towards = rng.uniform(-math.pi, math.pi, 2)
        turn = rng.uniform(-math.pi, math.pi)
        loads = []
        for extra in (0.0, turn):
            env = {"waves": [_jonswap(math.degrees(towards + extra), frequencies=40)]}
            load = _loads(_case([_drift()], env=env), angles=(0, 0, yaw + extra))
            loads.append(_body_frame(load, yaw + extra))
        np.testing.assert_allclose(loads[1], loads[0], rtol=1e-10, atol=1e-6)
    half = TABLE[HEADINGS <= 180.0]
    half[:, 2:] = [[-8e5 * math.sin(math.radians(b)), 3e7 * math.sin(math.radians(2 * b))]
                   for b in half[:, 0]]  # fmt: skip
    env = {"waves": [{"kind": "airy", "height": 2.0, "period": 9.0, "direction_deg": 235.0}]}
    yaw = math.radians(55.0)  # heading into the waves
    load = _loads(_case([_drift(half, symmetric=True)], env=env), angles=(0, 0, yaw))
    body = _body_frame(load, yaw)
    assert body[0] == pytest.approx(half[0, 1], rel=1e-12)  # a = 1 m
    assert abs(body[1]) < 1e-9 and abs(body[2]) < 1e-6


def test_the_moment_about_the_reference_point_includes_the_points_lever_arm():
    """A table at P = (60, -8, 0) gives the load of the same table at the reference point with
    D_N + x_P D_Y - y_P D_X."""
    env = {"waves": [_jonswap(130.0, frequencies=40)]}
    xp, yp = 60.0, -8.0
    moved = TABLE.copy()
    moved[:, 3] += xp * TABLE[:, 2] - yp * TABLE[:, 1]
    at_p = _loads(_case([_drift(point=[xp, yp, 0.0])], env=env), angles=(0, 0, 0.4))
    at_o = _loads(_case([_drift(moved)], env=env), angles=(0, 0, 0.4))
    np.testing.assert_allclose(at_p, at_o, rtol=1e-12, atol=1e-6)


def test_a_free_ship_drifts_at_the_speed_where_its_damping_meets_the_force():
    """A ship free in surge and sway on linear damping only, in a regular wave from 45 deg off
    the bow: its velocity settles at B^-1 F (earth frame), F = a^2 D(45 deg) turned."""
    damping = (4e5, 2e6)
    env = {"waves": [{"kind": "airy", "height": 2.0, "period": 8.0, "direction_deg": 225.0}]}
    forces = [_drift(), {"model": "linear_damping",
                         "diagonal": [damping[0], damping[1], 0, 0, 0, 0]}]  # fmt: skip
    case = _case(forces, env=env, duration=150.0, dofs=["surge", "sway"],
                 added_mass=[1e5, 1e6, 0, 0, 0, 0])  # fmt: skip
    ship = seacable.simulate(case)["bodies/ship"]
    d = np.interp(45.0, HEADINGS, TABLE[:, 1]), np.interp(45.0, HEADINGS, TABLE[:, 2])
    expected = np.array(d) / np.array(damping)  # the ship at yaw 0: body frame = earth frame
    got = ship["velocity_x"].values[-1], ship["velocity_y"].values[-1]
    np.testing.assert_allclose(got, expected, rtol=1e-5)


def test_bad_tables_and_a_model_without_waves_are_refused_with_the_field_named():
    env = {"waves": [_jonswap()]}
    with pytest.raises(CaseError, match=r"external forces.*wave drift.*needs environment.waves"):
        seacable.simulate(_case([_drift()]))
    with pytest.raises(CaseError, match="angles .* must increase strictly"):
        seacable.simulate(_case([_drift(TABLE[::-1])], env=env))
    rows = [[0.5, *r] for r in TABLE] + [[0.4, *r] for r in TABLE]
    with pytest.raises(CaseError, match="frequencies .* ascending"):
        seacable.simulate(_case([_drift(rows)], env=env))
    rows = [[0.5, *r] for r in TABLE] + [[0.6, *r] for r in TABLE[:-1]]
    with pytest.raises(CaseError, match="the headings at 0.6 rad/s"):
        seacable.simulate(_case([_drift(rows)], env=env))


def test_a_csv_table_gives_the_inline_tables_load(tmp_path):
    """A CSV file of five columns (a header, a comment) gives the inline table's load; a second
    header line and a row of six columns are refused with the file named."""
    rows = [[w, r[0], *(r[1:] * w)] for w in (0.4, 0.9) for r in TABLE]
    env = {"waves": [_jonswap(100.0, frequencies=40)]}
    text = "# a drift table\nomega,beta_deg,D_X,D_Y,D_N\n" + "".join(
        ",".join(repr(float(v)) for v in row) + "\n" for row in rows
    )
    (tmp_path / "drift.csv").write_text(text)
    inline = _loads(_case([_drift(rows)], env=env), angles=(0, 0, 0.3))
    from_file = _loads(_case([_drift(str(tmp_path / "drift.csv"))], env=env), angles=(0, 0, 0.3))
    np.testing.assert_array_equal(from_file, inline)
    (tmp_path / "two.csv").write_text("a second header\n" + text)
    with pytest.raises(CaseError, match=r"two\.csv': bad row \['omega'"):
        seacable.simulate(_case([_drift(str(tmp_path / "two.csv"))], env=env))
    (tmp_path / "six.csv").write_text(text + "0.9,10,1,2,3,4\n")
    with pytest.raises(CaseError, match=r"six\.csv': row .* needs 4 or 5 columns"):
        seacable.simulate(_case([_drift(str(tmp_path / "six.csv"))], env=env))


# ---- the horizontal-plane analyses ---------------------------------------------------------
RHO, G = 1025.0, 9.81


def tanker_drift_table() -> list[list[float]]:
    """A symmetric drift table for the FPSO of tests/test_stability (L 310 m, B 58 m), at
    midship, of the short-wave asymptote's size: a fully reflecting wall takes 1/2 rho g a^2
    per metre of its length normal to the waves: beam seas 1/2 rho g L, head seas
    1/2 rho g B 2/3 (a round bow); D = D_X0 cos beta, D_Y0 sin beta between (an
    approximation, not a computed table)."""
    length, beam = FPSO[0], FPSO[1]
    dx0, dy0 = 0.5 * RHO * G * beam * 2.0 / 3.0, 0.5 * RHO * G * length
    return [[b, -dx0 * math.cos(math.radians(b)), -dy0 * math.sin(math.radians(b)), 0.0]
            for b in range(0, 181, 15)]  # fmt: skip


def turret_in_waves(towards=180.0, turret=120.0):
    """The FPSO on its turret (a tie of no length, 1 MN/m) in a JONSWAP sea of Hs 2.5 m and
    no current, linear damping giving its rest some decay."""
    extra = [{"model": "wave drift", "symmetric": True, "coefficients": tanker_drift_table()},
             {"model": "linear_damping", "diagonal": [1e6, 1e7, 0, 0, 0, 1e11]}]  # fmt: skip
    ship = _ship("fpso", FPSO, "short-wing", {"turret": [turret, 0, 0]}, [-turret, 0, 0],
                 extra)  # fmt: skip
    return seacable.load_case({
        "environment": {"waves": [_jonswap(towards, frequencies=50)]},
        "bodies": [{"name": "anchor", "type": "fixed", "position": [0, 0, 0]}, ship],
        "lines": [{"name": "mooring", "model": "tie", "from": "anchor", "to": "fpso.turret",
                   "unstretched_length": 0.0, "stiffness": 1e6}],
        "start": "as_given",
        "simulation": {"duration": 100.0, "output_interval": 1.0, "build_up": 50.0},
    })  # fmt: skip


def _stable_headings(plane):
    found = equilibria.find(plane, None, 8)
    # in [0, 360), a heading of -1e-15 deg read as 0
    return [(math.degrees(e.x[2]) + 1e-9) % 360.0 - 1e-9 for e in found if e.stable], found


def test_a_turret_moored_tanker_weathervanes_to_head_the_waves():
    """Waves only: the one stable equilibrium heads the waves (heading = their direction +
    180 deg), pushed back from the turret by the head seas' D_X0 Hs^2/8 over the mooring's
    stiffness; the opposite heading is an equilibrium too, unstable. Weather's
    wave_towards_deg turns the stable one with the waves; wave_height scales the offset as
    Hs^2; the continuation parameter waves.towards_deg sets the same weather. The
    simulation's build-up does not reach the plane (the sea taken risen)."""
    plane = Plane.of(turret_in_waves(180.0))
    stable, found = _stable_headings(plane)
    assert stable == pytest.approx([0.0], abs=1e-6)
    assert len(found) == 2 and not found[1].stable
    assert abs(math.degrees(found[1].x[2])) == pytest.approx(180.0, abs=1e-6)
    sea = plane.built.params.wave
    push = -tanker_drift_table()[0][1] * float(np.sum(sea[waves.A] ** 2))
    x_turret = found[0].x[0] + 120.0
    assert x_turret == pytest.approx(-push / 1e6, rel=1e-6)
    Weather(wave_towards_deg=120.0).apply(plane.built)
    stable, _ = _stable_headings(plane)
    assert stable == pytest.approx([300.0], abs=1e-6)
    Weather(wave_height=2.0 * HS, wave_towards_deg=180.0).apply(plane.built)
    found = [e for e in equilibria.find(plane, None, 8) if e.stable]
    assert found[0].x[0] + 120.0 == pytest.approx(-4.0 * push / 1e6, rel=1e-6)
    parameter(plane, "waves.towards_deg").set(plane, 90.0)
    stable, _ = _stable_headings(plane)
    assert stable == pytest.approx([270.0], abs=1e-6)
    Weather().apply(plane.built)  # the case's own sea back
    np.testing.assert_array_equal(plane.built.params.wave[waves.A], sea[waves.A])


def test_the_plane_refuses_first_order_wave_loads_and_waves_it_cannot_vary():
    case = turret_in_waves()
    data = case.model_dump(by_alias=True, exclude_none=True)
    data["bodies"][1]["external forces"].append({"model": "non-linear Froude-Krylov"})
    data["bodies"][1]["mesh"] = {"file": str(EXAMPLES / "data" / "barge.stl")}
    with pytest.raises(CaseError, match="external forces.3: 'non-linear Froude-Krylov' in "
                                        "waves"):  # fmt: skip
        Plane.of(seacable.load_case(data))
    from test_stability import turret_case

    plane = Plane.of(turret_case("short-wing"))
    with pytest.raises(CaseError, match="environment.waves: none"):
        Weather(1.0, 180.0, wave_height=2.0).apply(plane.built)


def test_the_examples_fpso_settles_between_current_wind_and_waves():
    """examples/turret_fpso_wave_drift.yaml: a stable equilibrium with the case's weather; its
    waves scaled to nothing give the heading of the same FPSO without its wave drift model
    (to 1e-6 deg), and the waves, from 30 deg off the bow, turn it by more than a degree
    towards them (headings grow towards port: waves towards 150 deg come from -30 deg)."""
    from seacable.case import loader
    from seacable.stability.datasets import weather_of

    case = loader.load_case(EXAMPLES / "turret_fpso_wave_drift.yaml")
    weather = weather_of(case)
    plane = Plane.of(case, loader.case_base_dir(case))
    stable, _ = _stable_headings_in(plane, weather)
    calm = replace(weather, wave_height=1e-9)
    still, _ = _stable_headings_in(plane, calm)
    data = case.model_dump(by_alias=True, exclude_none=True)
    data["bodies"][1]["external forces"].pop()
    without = Plane.of(seacable.load_case(data), loader.case_base_dir(case))
    bare, _ = _stable_headings_in(without, weather)
    assert len(stable) == len(still) == len(bare) == 1
    assert _wrapped(still[0]) == pytest.approx(_wrapped(bare[0]), abs=1e-6)
    assert _wrapped(stable[0]) < _wrapped(bare[0]) - 1.0


def _stable_headings_in(plane, weather):
    weather.apply(plane.built)
    return _stable_headings(plane)


def _wrapped(degrees):
    return (degrees + 180.0) % 360.0 - 180.0


def test_the_command_lines_waves_option_scales_and_turns_the_sea():
    """`seacable equilibria --waves 5 150` on the example: the sea of Hs 5 m (twice the case's)
    turns the FPSO to -12.28 deg (-1.89 deg in the case's own sea); `seacable continuation
    --parameter waves.towards_deg` follows its heading as the waves turn."""
    from click.testing import CliRunner

    from seacable.cli import main

    example = str(EXAMPLES / "turret_fpso_wave_drift.yaml")
    run = CliRunner().invoke(main, ["equilibria", example, "--waves", "5", "150"])
    assert run.exit_code == 0, run.output
    assert "waves Hs 5 m towards 150 deg: 2 equilibria" in run.output
    assert "1. stable" in run.output and "heading -12.28 deg" in run.output
    run = CliRunner().invoke(main, ["equilibria", example])
    assert "waves Hs 2.5 m: 2 equilibria" in run.output and "heading -1.89 deg" in run.output
    arguments = ["--parameter", "waves.towards_deg", "--from", "120", "--to", "180"]
    run = CliRunner().invoke(main, ["continuation", example, *arguments])
    assert run.exit_code == 0, run.output
    assert " branches, " in run.output
