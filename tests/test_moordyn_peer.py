"""A MoorDyn deck run by MoorDyn itself (PyPI ``moordyn``) and by seacable, same deck, same
segments: the fairlead forces of the statics within 0.5 % (MoorDyn's dynamic relaxation against
seacable's Newton statics), and the fairlead tension time series under an imposed surge within
1 % of its peak (MoorDyn stepped through its coupling interface, seacable's imposed bodies
moved by the same time functions); decks with a free body, with rods on a spar and with a
free rod."""

import math
from pathlib import Path

import numpy as np
import pytest

import seacable
from helpers import quiet_stdout
from seacable.case import moordyn as deck_reader

md = pytest.importorskip("moordyn")

DECK = Path(__file__).parent / "data" / "moordyn_v2_spread.txt"
COUPLED = ("point4", "point5", "point6")  # the deck's coupled points, one line to each
SURGE, PERIOD, DURATION, COUPLING_STEP = 5.0, 20.0, 30.0, 0.02


def _start(case: dict) -> np.ndarray:
    bodies = {b["name"]: b for b in case["bodies"]}
    return np.concatenate([[bodies[n][k]["value"] for k in "xyz"] for n in COUPLED])


def _surge(x0: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
    """Every coupled point moved along x by SURGE (1 - cos w t): from rest, at rest again."""
    w = 2 * math.pi / PERIOD
    x, v = x0.copy(), np.zeros_like(x0)
    x[0::3] += SURGE * (1 - math.cos(w * t))
    v[0::3] = SURGE * w * math.sin(w * t)
    return x, v


def _fairlead_forces(dataset, time=slice(None)) -> np.ndarray:
    """(time, line) magnitude of each line's force on its coupled point."""
    out = []
    for k in (1, 2, 3):
        group = dataset[f"lines/line{k}"].to_dataset().isel(time=time)
        out.append(np.sqrt(sum(group[f"to_force_{c}"].values ** 2 for c in "xyz")))
    return np.array(out).T


def _deck(folder: Path, source: Path = DECK) -> Path:
    """The deck copied where MoorDyn may write its output files (beside the deck)."""
    copy = folder / source.name
    copy.write_text(source.read_text())
    return copy


OC3 = Path(__file__).parent / "data" / "moordyn_v2_oc3_hywind.txt"  # as MoorDyn's example


@pytest.mark.parametrize("source", [DECK, OC3], ids=["spread", "oc3"])
def test_statics_match_moordyn_on_the_same_deck(tmp_path, source):
    deck = _deck(tmp_path, source)
    case = deck_reader.read(deck)
    x0 = _start(case)
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, x0, np.zeros_like(x0))
        theirs = np.reshape(md.Step(system, x0, np.zeros_like(x0), 0.0, 0.002), (-1, 3))
        md.Close(system)
    ours = _fairlead_forces(seacable.statics(seacable.load_case(deck)).dataset, 0)
    share = ours / np.linalg.norm(theirs, axis=1) - 1
    assert np.abs(share).max() < 5e-3, share


@pytest.mark.parametrize("source", [DECK, OC3], ids=["spread", "oc3"])
def test_fairlead_tensions_under_an_imposed_surge_match_moordyn(tmp_path, source):
    deck = _deck(tmp_path, source)
    case = deck_reader.read(deck)
    x0 = _start(case)
    times, theirs = [0.0], []
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, *_surge(x0, 0.0))
        points = [md.GetPoint(system, k) for k in (4, 5, 6)]
        theirs.append([np.linalg.norm(md.GetPointForce(p)) for p in points])
        steps = round(DURATION / COUPLING_STEP)
        for k in range(steps):
            t = k * COUPLING_STEP
            forces = md.Step(system, *_surge(x0, t), t, COUPLING_STEP)
            times.append((k + 1) * COUPLING_STEP)
            theirs.append(np.linalg.norm(np.reshape(forces, (-1, 3)), axis=1))
        md.Close(system)
    for body in case["bodies"]:
        if body["name"] in COUPLED:
            offset = body["x"]["value"] + SURGE
            body["x"] = {"kind": "sine", "amplitude": SURGE, "period": PERIOD,
                         "phase": -math.pi / 2, "offset": offset}  # fmt: skip
    case["simulation"]["duration"] = DURATION
    results = seacable.simulate(seacable.load_case(case))
    time = results.dataset["lines/line1"].to_dataset()["time"].values
    ours = _fairlead_forces(results.dataset)
    theirs_at = np.array([np.interp(time, times, np.array(theirs)[:, k]) for k in range(3)]).T
    peak = theirs_at.max(axis=0)
    assert peak[0] > 1.15 * theirs_at[0, 0]  # the surge loads line 1 by more than 15 %
    error = np.abs(ours - theirs_at).max(axis=0) / peak
    assert error.max() < 1e-2, error


def test_the_coupling_interface_steps_as_moordyn_does(tmp_path):
    """The same driver loop calls MoorDyn's Step and seacable's ``Coupling.step`` with the
    fairleads' motion at each coupling step's start: the forces they return agree within 1 %
    of the peak, and match seacable's own run of the same motion as time functions."""
    from seacable.coupling import Coupling

    deck = _deck(tmp_path)
    x0 = _start(deck_reader.read(deck))
    ours = Coupling(deck)
    assert ours.bodies == list(COUPLED) and ours.size == 9
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, *_surge(x0, 0.0))
        first = ours.init(*_surge(x0, 0.0))
        theirs, mine = [], []
        for k in range(round(DURATION / COUPLING_STEP)):
            t = k * COUPLING_STEP
            theirs.append(md.Step(system, *_surge(x0, t), t, COUPLING_STEP))
            mine.append(ours.step(*_surge(x0, t), t, COUPLING_STEP))
        md.Close(system)
    theirs, mine = np.array(theirs), np.array(mine)
    assert first.shape == (9,) and np.abs(first[0::3]).max() > 1e5
    magnitude = [np.linalg.norm(a.reshape(-1, 3, 3), axis=2) for a in (theirs, mine)]
    error = np.abs(magnitude[1] - magnitude[0]).max(axis=0) / magnitude[0].max(axis=0)
    assert error.max() < 1e-2, error
    with pytest.raises(ValueError, match="the last step ended at"):
        ours.step(*_surge(x0, 0.0), 0.0, COUPLING_STEP)
    with pytest.raises(ValueError, match="9 finite values expected"):
        ours.step(np.zeros(6), np.zeros(6), ours.t, COUPLING_STEP)


FREE_BODY = Path(__file__).parent.parent / "examples" / "moordyn" / "buoy_three_chains.txt"


def _free_body_statics():
    """seacable's statics of the free-body deck: the body's heave [m] and the fairlead
    tensions [N]."""
    dataset = seacable.statics(seacable.load_case(FREE_BODY)).dataset
    body = dataset["bodies/body1"].to_dataset().isel(time=0)
    return float(body["position_z"]), _fairlead_forces(dataset, 0)


def test_a_free_body_deck_has_moorpys_statics():
    """The deck of a submerged buoyant body (a free 6-DOF body, 412 kN net buoyancy) on three
    chains read by MoorPy (its own reader of MoorDyn decks, continuous catenaries) and by
    seacable (30 lumped segments a line): the body's heave within 0.05 m (measured 0.03 m) and
    the fairlead tensions within 0.5 % (0.003 %)."""
    mp = pytest.importorskip("moorpy")
    system = mp.System(file=str(FREE_BODY), depth=200.0)
    system.initialize()
    system.solveEquilibrium(tol=1e-6)
    theirs = np.array([line.TB for line in system.lineList])
    heave, ours = _free_body_statics()
    assert abs(heave - system.bodyList[0].r6[2]) < 0.05, (heave, system.bodyList[0].r6)
    assert np.abs(ours / theirs - 1).max() < 5e-3, (ours, theirs)


@pytest.mark.slow
def test_a_free_body_settles_in_moordyn_where_seacable_statics_puts_it(tmp_path):
    """MoorDyn's own initial-condition solver leaves the free body 3 m off its balance on this
    deck ('Remaining error after 200 s'; it keeps its best state, the body at -59.99 m); run
    on by MoorDyn for 150 s, the body heaves about seacable's static position (mean of the
    last 30 s within 0.1 m) and the fairlead tension ends within 0.5 % of seacable's
    statics."""
    deck = tmp_path / FREE_BODY.name
    deck.write_text(FREE_BODY.read_text())
    heights, tension = [], 0.0
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, np.zeros(0), np.zeros(0))
        body, point = md.GetBody(system, 1), md.GetPoint(system, 4)
        start = md.GetBodyState(body)[0][2]
        for k in range(150):
            md.Step(system, np.zeros(0), np.zeros(0), float(k), 1.0)
            heights.append(md.GetBodyState(body)[0][2])
        tension = np.linalg.norm(md.GetPointForce(point))
        md.Close(system)
    heave, ours = _free_body_statics()
    assert abs(start - heave) > 2.0  # MoorDyn's start is off
    assert abs(np.mean(heights[-30:]) - heave) < 0.1, (np.mean(heights[-30:]), heave)
    assert abs(tension / ours[0] - 1) < 5e-3, (tension, ours)


SPAR = Path(__file__).parent / "data" / "moordyn_v2_spar_rods.txt"
SPAR_ROW = "1    Free       0.0   0.0   0.0    0    0    0 "


def _spar_statics():
    """seacable's statics of the spar deck: the body's pose (x, y, z [m], roll, pitch, yaw
    [rad]) and the fairlead tensions [N]."""
    dataset = seacable.statics(seacable.load_case(SPAR)).dataset
    body = dataset["bodies/body1"].to_dataset().isel(time=0)
    pose = [float(body[f"position_{c}"]) for c in "xyz"]
    pose += [math.radians(float(body[k])) for k in ("roll", "pitch", "yaw")]
    return np.array(pose), _fairlead_forces(dataset, 0)


def test_moordyn_holds_the_spar_with_rods_where_seacable_statics_puts_it(tmp_path):
    """A spar (a free body with a surface-piercing column and a heave plate as rods, three
    chains): MoorDyn's initial-condition solver stops 106 kN off balance (0.21 m low), so
    the check is MoorDyn's own loads with the body held (Coupled) at seacable's static pose:
    its rods and lines carry the body's weight to 1e-5 of the buoyancy, and its fairlead
    tensions are seacable's within 0.5 % (measured 0.006 %)."""
    pose, ours = _spar_statics()
    deck = tmp_path / SPAR.name
    deck.write_text(SPAR.read_text().replace(SPAR_ROW, SPAR_ROW.replace("Free   ", "Coupled")))
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, pose, np.zeros(6))
        load = np.array(md.Step(system, pose, np.zeros(6), 0.0, 0.001))
        theirs = [np.linalg.norm(md.GetPointForce(md.GetPoint(system, k))) for k in (4, 5, 6)]
        md.Close(system)
    weight = 1.78e6 * 9.81  # the body's own mass (the rods' weight is in their load)
    buoyancy = 1025.0 * 9.81 * (math.pi * 16 * (40 - pose[2]) + math.pi * 49 * 2)
    assert abs(load[2] - weight) < 1e-5 * buoyancy, (load, weight)
    assert np.abs(load[[0, 1]]).max() < 1e-5 * buoyancy
    assert np.abs(ours / np.array(theirs) - 1).max() < 5e-3, (ours, theirs)


def test_a_spar_with_rods_decays_as_in_moordyn(tmp_path):
    """The spar let go 10 m off in surge and 3 deg in pitch, with no initial-condition solve
    in MoorDyn (TmaxIC 0; seacable: start as_given), 30 s. Over the first 15 s (a pitch
    period) surge within 0.05 m (measured 0.036), heave within 0.03 m (0.022) and pitch within
    0.12 deg (0.089) of MoorDyn's; over 30 s surge within 0.1 m (0.086) and pitch 0.25 deg
    (0.20): the pitch drifts apart, MoorDyn's restoring moment of the column being 1.4 %
    stiffer than the exact one at 3 deg (-14.42 against -14.22 MN m about its foot;
    tests/test_rod.py checks seacable's against a quadrature to 1e-9), so its pitch period is
    0.7 % shorter. The fairlead tension from 5 s on (after the two codes' different starting
    line shapes have rung out) within 1.5 % of its peak (1.2 %)."""
    deck = tmp_path / SPAR.name
    decay = SPAR_ROW.replace("0.0   0.0   0.0    0    0 ", "10.0  0.0   0.6    0    3 ")
    deck.write_text(SPAR.read_text().replace(SPAR_ROW, decay).replace(
        "600.0    TmaxIC", "0.0      TmaxIC"))  # fmt: skip
    duration, step = 30.0, 0.1
    rows = []
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, np.zeros(0), np.zeros(0))
        body, point = md.GetBody(system, 1), md.GetPoint(system, 4)
        for k in range(round(duration / step)):
            md.Step(system, np.zeros(0), np.zeros(0), k * step, step)
            state = md.GetBodyState(body)[0]
            rows.append([(k + 1) * step, state[0], state[2], math.degrees(state[4]),
                         np.linalg.norm(md.GetPointForce(point))])  # fmt: skip
        md.Close(system)
    theirs = np.array(rows)
    case = deck_reader.read(deck)
    case["start"] = "as_given"
    case["simulation"].update(duration=duration, output_interval=step)
    dataset = seacable.simulate(seacable.load_case(case)).dataset
    motion = dataset["bodies/body1"].to_dataset()
    time = motion["time"].values
    ours = np.column_stack([motion["position_x"].values, motion["position_z"].values,
                            motion["pitch"].values, _fairlead_forces(dataset)[:, 0]])  # fmt: skip
    later = time >= 1.0
    for k, tolerance in enumerate(((0.05, 0.1), (0.03, 0.03), (0.12, 0.25))):
        theirs_at = np.interp(time, theirs[:, 0], theirs[:, k + 1])
        first = later & (time <= 15.0)
        assert np.abs(ours[first, k] - theirs_at[first]).max() < tolerance[0], k
        assert np.abs(ours[later, k] - theirs_at[later]).max() < tolerance[1], k
    tension = np.interp(time, theirs[:, 0], theirs[:, 4])
    settled = time >= 5.0
    assert np.abs(ours[settled, 3] - tension[settled]).max() < 0.015 * tension.max()


HANGING = Path(__file__).parent / "data" / "moordyn_v2_hanging_rod.txt"


def test_a_free_rod_hung_from_two_ropes_settles_in_moordyn_where_seacable_statics_puts_it(
    tmp_path,
):
    """The set-up of MoorDyn's own RodHanging test (a free 20 m rod on two 450 m ropes,
    TmaxIC 0: MoorDyn starts from catenaries and its dynamics settle the rod): after 200 s
    MoorDyn's rod is where seacable's statics puts it within 0.01 m (measured 0.002 m, the
    ropes' sag 86.19 m) and its fairlead tensions are within 0.05 % (0.003 %)."""
    deck = tmp_path / HANGING.name
    deck.write_text(HANGING.read_text())
    heights, tensions = [], []
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, np.zeros(0), np.zeros(0))
        rod = md.GetRod(system, 1)
        for k in range(200):
            md.Step(system, np.zeros(0), np.zeros(0), float(k), 1.0)
            if k >= 150:
                heights.append(md.GetRodNodePos(rod, 0)[2])
                tensions.append([md.GetLineFairTen(md.GetLine(system, j)) for j in (1, 2)])
        md.Close(system)
    dataset = seacable.statics(seacable.load_case(HANGING)).dataset
    end_a = dataset["bodies/rod1"].to_dataset().isel(time=0)  # its reference point is end A
    ours = np.array([np.linalg.norm([float(dataset[f"lines/line{k}"].to_dataset().isel(
        time=0)[f"to_force_{c}"]) for c in "xyz"]) for k in (1, 2)])  # fmt: skip
    assert abs(float(end_a["position_z"]) - np.mean(heights)) < 0.01
    assert np.abs(ours / np.mean(tensions, axis=0) - 1).max() < 5e-4, (ours, tensions[-1])


WAVES = Path(__file__).parent / "data" / "moordyn_v2_waves"


def test_a_line_in_moordyns_wave_components_pulls_as_in_moordyn(tmp_path):
    """WaveKin 7 (three components in wave_frequencies.txt beside the deck): the surface
    MoorDyn computes is seacable's to 1e-6 m at five points (3e-8 m measured: the two codes'
    wave numbers), and the tension at the fairlead of a chain hanging clear of the seabed, held
    5 m under the surface, follows MoorDyn's over 60 s within 1 % of its peak (measured
    0.48 %; it swings between 114 and 126 kN)."""
    import shutil

    from seacable.kernels import waves
    from seacable.system import model

    folder = tmp_path / "deck"
    shutil.copytree(WAVES, folder)
    deck = folder / "lines.txt"
    fairlead, duration, step = np.array([0.0, 0.0, -5.0]), 60.0, 0.05
    built = model.build(seacable.load_case(deck))
    times, theirs = [], []
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, fairlead, np.zeros(3))
        kinematics = md.GetWaves(system)
        for x in (-250.0, -120.0, -40.0, 0.0, 35.0):
            zeta = md.GetWavesKin(kinematics, x, 0.0, -10.0)[2]
            assert abs(zeta - waves.elevation_at(built.params.wave, 0.0, x, 0.0)) < 1e-6
        for k in range(round(duration / step)):
            force = md.Step(system, fairlead, np.zeros(3), k * step, step)
            times.append((k + 1) * step)
            theirs.append(np.linalg.norm(force))
        md.Close(system)
    case = deck_reader.read(deck)
    case["simulation"].update(duration=duration, output_interval=step)
    dataset = seacable.simulate(seacable.load_case(case)).dataset
    line = dataset["lines/line1"].to_dataset()
    assert float(line["node_z"].min()) > -50.0  # clear of the seabed: no contact events
    time = line["time"].values
    ours = np.sqrt(sum(line[f"to_force_{c}"].values ** 2 for c in "xyz"))
    theirs_at = np.interp(time, times, theirs)
    assert np.ptp(theirs_at) > 0.08 * theirs_at.max()  # the waves load it
    later = time >= step
    assert np.abs(ours[later] - theirs_at[later]).max() < 1e-2 * theirs_at.max()


CURRENT = Path(__file__).parent / "data" / "moordyn_v2_current"


def test_a_line_in_moordyns_current_profile_settles_where_seacable_statics_puts_it(tmp_path):
    """Currents 1 (a steady profile in current_profile.txt beside the deck: 0 at the seabed to
    1.2 m/s at the surface, towards 30 deg): the chain of the wave deck, stepped by MoorDyn for
    200 s (its initial-condition solve leaves the current out), pulls its fairlead with the
    force seacable's statics find in the same current, within 0.1 % of its magnitude (0.03 %
    measured; the current's sideways pull 2.55 kN)."""
    import shutil

    folder = tmp_path / "deck"
    shutil.copytree(CURRENT, folder)
    deck = folder / "lines.txt"
    fairlead = np.array([0.0, 0.0, -5.0])
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, fairlead, np.zeros(3))
        for k in range(200):
            theirs = np.array(md.Step(system, fairlead, np.zeros(3), float(k), 1.0))
        md.Close(system)
    line = seacable.statics(seacable.load_case(deck)).dataset["lines/line1"].to_dataset()
    ours = np.array([float(line.isel(time=0)[f"to_force_{c}"]) for c in "xyz"])
    assert theirs[1] > 2e3  # the current pulls it sideways
    assert np.linalg.norm(ours - theirs) < 1e-3 * np.linalg.norm(theirs), (ours, theirs)


PINNED = Path(__file__).parent / "data" / "moordyn_v2_pinned_rod.txt"


def test_a_pinned_rod_swings_as_its_closed_form_and_as_in_moordyn(tmp_path):
    """The set-up of MoorDyn's own RodPinnedFloating test: a buoyant rod (1 m, 0.25 m across,
    10 kg/m in fresh water, no drag or added mass) pinned at one end and let go lying level
    swings up and over as an inverted pendulum of 90 deg amplitude: its tip rises and falls
    with half the period 4 sqrt(I / (N L / 2)) K(sin^2 45 deg) (I its inertia about the pin,
    N its net buoyancy; 0.492 s) within 1e-3 (2.4e-4 measured, the output step's), and
    MoorDyn's tip follows the same path within 1e-4 m over 3 s (1.2e-6 m measured)."""
    from scipy.special import ellipk

    deck = tmp_path / PINNED.name
    deck.write_text(PINNED.read_text())
    duration, step = 3.0, 0.002
    tips = []
    with quiet_stdout():
        system = md.Create(str(deck))
        md.Init(system, np.zeros(0), np.zeros(0))
        rod = md.GetRod(system, 1)
        for k in range(round(duration / step)):
            md.Step(system, np.zeros(0), np.zeros(0), k * step, step)
            tips.append(md.GetRodNodePos(rod, 1)[2])
        md.Close(system)
    case = deck_reader.read(deck)
    assert case["bodies"][0]["dofs"] == ["roll", "pitch", "yaw"]
    case["start"] = "as_given"
    case["simulation"].update(duration=duration, output_interval=step)
    body = seacable.simulate(seacable.load_case(case)).dataset["bodies/rod1"].to_dataset()
    tip = -5.0 - np.sin(np.radians(body["pitch"].values))  # end B: R[2, 0] = -sin(pitch)
    time = body["time"].values
    assert np.abs(tip[1:] - np.array(tips)).max() < 1e-4
    length, diameter, mass = 1.0, 0.25, 10.0
    net = (1000.0 * np.pi * diameter**2 / 4 - mass) * length * 9.80665
    inertia = mass * length**2 * (1 / 3 + diameter**2 / (16 * length**2))
    period = 4 * np.sqrt(inertia / (net * length / 2)) * ellipk(0.5)
    high = np.flatnonzero((tip[1:-1] > tip[:-2]) & (tip[1:-1] >= tip[2:])) + 1
    assert np.diff(time[high]).mean() == pytest.approx(period / 2, rel=1e-3)
