"""MoorDyn decks read as seacable cases (case.moordyn): the statics of a v2 deck against MoorPy
reading the same deck, of a v1 deck against MoorPy built from the deck's values (MoorPy's reader
takes v2's column order for v1's line properties), the conversions of the deck's conventions,
the commented case ``seacable import moordyn`` writes, a deck run as it is, and the refusals
that name the section, the row and the column."""

import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import seacable
from seacable.case import moordyn
from seacable.case.environment import Seabed
from seacable.cli import main
from seacable.system import model

mp = pytest.importorskip("moorpy")

DATA = Path(__file__).parent / "data"
V2 = DATA / "moordyn_v2_spread.txt"
V1 = DATA / "moordyn_v1_clump.txt"


def _end_tensions(results, lines: int) -> np.ndarray:
    """(from, to) end-force magnitudes of line1..lineN at the statics' state."""
    ds = results.dataset
    out = []
    for k in range(1, lines + 1):
        group = ds[f"lines/line{k}"].to_dataset().isel(time=0)
        out.append([np.linalg.norm([float(group[f"{end}_force_{c}"]) for c in "xyz"])
                    for end in ("from", "to")])  # fmt: skip
    return np.array(out)


def test_a_v2_deck_statics_match_moorpy_reading_the_same_deck():
    """Three catenary chains 650 m long in 200 m of water: fairlead tensions within 0.1 % of
    MoorPy's elastic catenaries, anchor tensions within 0.3 % (40 segments a line, a seabed
    of finite stiffness against MoorPy's rigid one)."""
    ms = mp.System(file=str(V2))
    ms.initialize()
    ms.solveEquilibrium(tol=1e-6, maxIter=2000)
    ours = _end_tensions(seacable.statics(seacable.load_case(V2)), 3)  # read by its content
    theirs = np.array([[line.TA, line.TB] for line in ms.lineList])
    assert np.abs(ours[:, 1] / theirs[:, 1] - 1).max() < 1e-3, (ours, theirs)
    assert np.abs(ours[:, 0] / theirs[:, 0] - 1).max() < 3e-3, (ours, theirs)


def test_a_v1_deck_statics_match_moorpy():
    """A chain and a wire joined at a free point (a 400 kg clump of 0.25 m^3), and a plain
    chain, to two vessel points: end tensions within 0.1 %, the clump within 1 cm."""
    ms = mp.System(depth=120.0, rho=1025.0, g=9.80665)
    ms.setLineType(name="chain", lineType={"d_vol": 0.1, "m": 60.0, "EA": 3.0e8})
    ms.setLineType(name="wire", lineType={"d_vol": 0.05, "m": 12.0, "EA": 2.0e8})
    for kind, r, m, v in ((1, [-350, 0, -120], 0, 0), (0, [-140, 0, -90], 400.0, 0.25),
                          (1, [-20, 0, -10], 0, 0), (1, [350, 0, -120], 0, 0),
                          (1, [20, 0, -10], 0, 0)):  # fmt: skip
        ms.addPoint(kind, r, m=m, v=v)
    for length, kind, a, b in ((200.0, "chain", 1, 2), (150.0, "wire", 2, 3),
                               (360.0, "chain", 4, 5)):  # fmt: skip
        ms.addLine(length, kind, pointA=a, pointB=b)
    ms.initialize()
    ms.solveEquilibrium(tol=1e-6, maxIter=2000)
    results = seacable.statics(seacable.load_case(V1))
    ours = _end_tensions(results, 3)
    theirs = np.array([[line.TA, line.TB] for line in ms.lineList])
    assert np.abs(ours / theirs - 1).max() < 1e-3, (ours, theirs)
    clump = results.dataset["bodies/point2"].to_dataset().isel(time=0)
    position = np.array([float(clump[f"position_{c}"]) for c in "xyz"])
    assert np.abs(position - ms.pointList[1].r).max() < 0.01, position


def test_the_deck_conventions_become_the_case_fields():
    case = moordyn.read(V2)
    chain = case["line_types"][0]
    assert chain["axial_damping_ratio"] == 1.0  # BA -1: a damping ratio
    assert chain["drag_coefficient_normal"] == 2.4 and chain["drag_coefficient_tangential"] == 0.4
    assert case["environment"]["seabed"]["stiffness_per_area"] == 3.0e6
    assert case["environment"]["water_depth"] == 200.0
    kinds = {body["name"]: body["type"] for body in case["bodies"]}
    assert kinds["point1"] == "fixed" and kinds["point4"] == "imposed"
    assert case["simulation"]["time_step"] == 0.002
    along = V2.read_text().replace("0.4    0.0", "0.4    0.5")  # CaAx
    assert moordyn.read(along)["line_types"][0]["added_mass_coefficient_tangential"] == 0.5
    damped = V2.read_text().replace("5.8e8    -1.0", "5.8e8    2.9e7")  # BA [N s]
    assert moordyn.read(damped)["line_types"][0]["axial_damping_time"] == pytest.approx(0.05)
    v1 = moordyn.read(V1)
    clump = next(body for body in v1["bodies"] if body["name"] == "point2")
    assert clump["type"] == "point" and clump["mass"] == 400.0 and clump["volume"] == 0.25
    assert clump["added_mass"] == pytest.approx(1025.0 * 0.25)
    vessel = next(body for body in v1["bodies"] if body["name"] == "vessel")
    assert vessel["points"] == {"point3": [-20.0, 0.0, -10.0], "point5": [20.0, 0.0, -10.0]}
    assert v1["lines"][1]["to"] == "vessel.point3"


def test_import_writes_a_commented_case_and_a_deck_runs_as_it_is(tmp_path):
    output = tmp_path / "case.yaml"
    result = CliRunner().invoke(main, ["import", "moordyn", str(V2), "-o", str(output)])
    assert result.exit_code == 0, result.output
    text = output.read_text()
    assert text.startswith("# seacable case imported from the MoorDyn v2 deck")
    assert "dtIC 5.0: not used" in text and "OUTPUTS (FairTen1, FairTen2, FairTen3)" in text
    written, deck = seacable.load_case(output), seacable.load_case(V2)
    assert written.model_dump(mode="json") == deck.model_dump(mode="json")
    same = CliRunner().invoke(main, ["import", "moordyn", str(V2), "-o", str(V2)])
    assert same.exit_code == 2 and "is a file this command reads" in same.output
    checked = CliRunner().invoke(main, ["validate", str(V1)])
    assert checked.exit_code == 0 and "point2 (point)" in checked.output, checked.output


HANGING = """---------------------- LINE TYPES ----------------------
Name  Diam  Mass/m   EA     BA    EI  Cd   Ca   CdAx  CaAx
(-)   (m)   (kg/m)   (N)    (-)   (-) (-)  (-)  (-)   (-)
rope  0.1   8.0503   1.0e9  -0.1  0   0.0  0.0  0.0   0.0
---------------------- POINTS ----------------------
ID  Attachment  X     Y    Z       Mass    Volume  CdA  Ca
(-) (-)         (m)   (m)  (m)     (kg)    (m^3)   (-)  (-)
1   Fixed       0.0   0.0  -5.0    0       0       0    0
2   Free        6.0   0.0  -85.0   2.0e4   0       0    0
---------------------- LINES ----------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs
(-) (-)       (-)      (-)      (m)       (-)      (-)
1   rope      1        2        80.0      10       -
---------------------- OPTIONS ----------------------
0.05     cfl
1025.0   WtrDnsty
300      WtrDpth
"""  # a rope as heavy as the water it displaces (1025 pi 0.1^2 / 4 = 8.0503 kg/m)


def test_a_neutral_rope_and_the_cfl_number():
    """A rope of no apparent weight has no hanging catenary: it starts straight and the statics
    hang the clump below the fixed point, the rope stretched by its weight (MoorDyn's default
    g); cfl sets the step from the axial wave's transit time
    over a segment, made a whole fraction of the output interval."""
    case, written = moordyn.convert(HANGING)
    transit = 8.0 * math.sqrt(8.0503 / 1.0e9)
    step = case["simulation"]["time_step"]
    assert 0.999 * 0.05 * transit < step <= 0.05 * transit
    assert 0.1 / step == pytest.approx(round(0.1 / step), abs=1e-6)
    assert "CFL 0.05" in written
    results = seacable.statics(seacable.load_case(case))
    clump = results.dataset["bodies/point2"].to_dataset().isel(time=0)
    position = np.array([float(clump[f"position_{c}"]) for c in "xyz"])
    stretched = 80.0 * (1.0 + 2.0e4 * 9.80665 / 1.0e9)  # the clump's weight all along it
    assert np.abs(position[:2]).max() < 1e-6
    assert position[2] == pytest.approx(-5.0 - stretched, abs=1e-4)


REFUSED = [
    ("chain     0.137  126.0    5.8e8    -1.0      0    2.4   1.0   0.4    0.0",
     "chain     0.137  126.0    5.8e8    -1.0      0    2.4   1.0   0.4    0.0   0.8",
     "line 7 (LINE TYPES, column Cl): 0.8: vortex-induced vibration is not modelled"),
    ("---------------------- LINES ---",
     "---------------------- EXTERNAL LOADS ---\n---------------------- LINES ---",
     "section EXTERNAL LOADS is not read yet"),
    ("0.002    dtM", "1.0      foo       - a setting\n0.002    dtM", "option 'foo' has no"),
    ("0.002    dtM", "1        WaveKin\n0.002    dtM", "column WaveKin): '1': wave kinematics"),
    ("4    Coupled", "4    Body1  ", "column Attachment): 'Body1'"),
    ("1    chain     1        4", "1    chain     1        R1A",
     "column AttachB): 'R1A' is not a point or rod end of the deck"),
    ("650.0     40       -\n2", "6x0.0     40       -\n2", "column UnstrLen): '6x0.0' is not"),
]  # fmt: skip


def test_moordyns_other_option_names():
    """Option names MoorDyn's own decks use: WtrDnsty, FrictionCoefficient (the seabed's
    Coulomb friction), fileIC and FricDamp at its default (noted)."""
    text = (
        V2.read_text()
        .replace("1025.0   rhoW ", "1020.0   WtrDnsty ")
        .replace(
            "0.002    dtM",
            "0.5      FrictionCoefficient\n200      FricDamp\nx.ic     fileIC\n0.002    dtM",
        )
    )
    case, written = moordyn.convert(text)
    assert case["environment"]["water_density"] == 1020.0
    assert case["environment"]["seabed"]["friction_coefficient"] == 0.5
    assert "FricDamp 200: MoorDyn's default" in written and "fileIC x.ic: not used" in written
    with pytest.raises(seacable.CaseError, match="column FricDamp\\): 50: MoorDyn's friction"):
        moordyn.read(text.replace("200      FricDamp", "50       FricDamp"))


FREE_BODY = Path(__file__).parent.parent / "examples" / "moordyn" / "buoy_three_chains.txt"
BODY_ROW = (
    "1    Free       0.0   0.0   -60.0  0    0    0    4.0e4   0     2.0e5     80.0    20.0  1.0"
)
REFUSED_BODIES = [
    (BODY_ROW, BODY_ROW.replace("Free ", "Turbine"), "column Attachment): 'Turbine'"),
    (BODY_ROW, BODY_ROW.replace("  0     2.0e5", "  0|1   2.0e5"),
     "column CG): '0|1': give 1 or 3"),
    (BODY_ROW, BODY_ROW.replace(" 1.0", " 1|2"), "column Ca): '1|2': give 1 or 3"),
    ("4    Body1      -3.0      0.0       -2.0    0 ",
     "4    Body1      -3.0      0.0       -2.0    5 ", "column M): a point on body1 with a mass"),
    ("4    Body1 ", "4    Body2 ", "column Attachment): 'Body2'"),
]  # fmt: skip


def test_kbot_acts_on_each_line_types_diameter():
    """MoorDyn's kBot and cBot act on each segment's d l: a deck of two line types of different
    diameters gives each line's nodes kBot d and cBot d times their half segments (the
    seabed's per-area form), and a case giving both forms of the stiffness is refused."""
    text = V2.read_text().replace("2    chain     2        5", "2    wire      2        5").replace(
        "---------------------- POINTS",
        "wire      0.09   40.0     6.0e8    -1.0      0    1.2   1.0   0.2    0.0\n"
        "---------------------- POINTS",
    )  # fmt: skip
    built = model.build(seacable.load_case(moordyn.read(text)))
    p = built.params
    for li, diameter in ((0, 0.137), (1, 0.09)):
        n, c0 = int(p.line_n[li]), int(p.line_node[li])
        half = 0.5 * 650.0 / 40
        assert p.node_seabed_stiffness[c0] == pytest.approx(3.0e6 * diameter * half)
        assert p.node_seabed_damping[c0 + 1] == pytest.approx(3.0e5 * diameter * 2 * half)
        assert n == 40
    with pytest.raises(ValueError, match="give 'stiffness'.*or 'stiffness_per_area'"):
        Seabed(stiffness=1.0e5, stiffness_per_area=3.0e6)


def test_a_failure_section_becomes_the_cases_failures():
    """FAILURE (FailureID Point Line(s) FailTime FailTen, 0: none): the lines' ends at the point
    released at the time or the tension; a rod's end, or neither trigger, refused by name."""
    table = ("---------------------- FAILURE ----------------------\n"
             "FailureID  Point    Line(s)   FailTime   FailTen\n"
             "()           ()       (,)      (s or 0)   (N or 0)\n"
             "1          4        1          5.0        0\n"
             "2          P1       1          0          1.2e6\n")  # fmt: skip
    text = V2.read_text().replace("--------------------------- OUTPUTS", table + "--- OUTPUTS")
    case = moordyn.read(text)
    assert case["failures"] == [
        {"name": "failure1", "at": "point4", "lines": ["line1"], "time": 5.0},
        {"name": "failure2", "at": "point1", "lines": ["line1"], "tension": 1.2e6},
    ]
    assert seacable.load_case(case).failures[1].tension == 1.2e6
    for row, message in (
        ("1          R1a      1          5.0        0", "'R1a': a point"),
        ("1          4        1          0          0", "neither FailTime"),
    ):
        with pytest.raises(seacable.CaseError, match=message):
            moordyn.read(text.replace("1          4        1          5.0        0", row))


def test_the_bodies_of_a_deck_become_fixed_imposed_and_rigid_bodies():
    """BODIES: a Free body becomes a rigid body with MoorDyn's body hydrodynamics (one CG value
    on z, one inertia for the three axes, its buoyancy at its CG, CdA on translations and, as a
    quadratic damping, on rotations, Ca rho V per axis, fluid inertia), its points the deck's
    Body1 points in its frame; Fixed and Coupled bodies keep their pose."""
    case, written = moordyn.convert(FREE_BODY)
    body = case["bodies"][0]
    assert body["name"] == "body1" and body["type"] == "rigid"
    assert body["centre_of_gravity"] == [0.0, 0.0, 0.0] == body["centre_of_buoyancy"]
    assert body["inertia"] == [2.0e5] * 3 and body["volume"] == 80.0
    assert body["added_mass"] == [82000.0] * 3 + [0.0] * 3
    assert body["points"]["point4"] == [-3.0, 0.0, -2.0]
    models = {force["model"]: force for force in body["external forces"]}
    assert set(models) == {"gravity", "buoyancy", "fluid inertia", "drag", "quadratic_damping"}
    assert models["drag"]["area"] == [20.0] * 3
    assert models["quadratic_damping"]["diagonal"] == [0.0] * 3 + [0.5 * 1025.0 * 20.0] * 3
    assert case["lines"][0]["to"] == "body1.point4"
    assert "its buoyancy acts at its CG" in written
    text = FREE_BODY.read_text()
    two = text.replace(BODY_ROW, BODY_ROW.replace("  0     2.0e5", "  0|0|1 1|2|3").replace(
        "20.0  1.0", "4|9   0.5|1|1"))  # fmt: skip
    body = moordyn.read(two)["bodies"][0]
    assert body["centre_of_gravity"] == [0.0, 0.0, 1.0] and body["inertia"] == [1.0, 2.0, 3.0]
    assert body["added_mass"][:3] == [41000.0, 82000.0, 82000.0]
    models = {force["model"]: force for force in body["external forces"]}
    assert models["drag"]["area"] == [4.0] * 3
    assert models["quadratic_damping"]["diagonal"][3:] == [0.5 * 1025.0 * 9.0] * 3
    for word, kind in (("Fixed", "fixed"), ("Coupled", "imposed")):
        row = BODY_ROW.replace("Free ", word).replace("0    0    0 ", "0    5    30")
        body = moordyn.read(text.replace(BODY_ROW, row))["bodies"][0]
        assert body["type"] == kind and body["points"]["point5"] == [1.5, 2.598, -2.0]
        if kind == "fixed":
            assert body["orientation_deg"] == [0.0, 5.0, 30.0]
        else:
            assert body["pitch_deg"]["value"] == 5.0 and body["yaw_deg"]["value"] == 30.0


@pytest.mark.parametrize(
    ("deck", "old", "new", "message"),
    [(V2, *row) for row in REFUSED] + [(FREE_BODY, *row) for row in REFUSED_BODIES],
)
def test_what_has_no_equivalent_is_refused_by_section_row_and_column(deck, old, new, message):
    text = deck.read_text()
    assert old in text
    with pytest.raises(seacable.CaseError) as error:
        moordyn.read(text.replace(old, new, 1))
    assert message in str(error.value)


SPAR = DATA / "moordyn_v2_spar_rods.txt"
COLUMN_ROW = "1    column    Body1      0     0    -40    0     0     10   10 "


def test_the_rods_of_a_deck_become_rod_models_and_bodies():
    """RODS: a rod on a free body is a ``rod`` force model of that body (ROD TYPES' diameter
    and coefficients, the deck's segments), its mass (Mass/m times its length) joined to the
    body's mass, centre of gravity and inertia about it (a solid cylinder's, parallel axes),
    its ends points R<ID>A and R<ID>B for the lines; a Free rod is a rigid body at its end A,
    a Fixed rod a fixed body."""
    case = moordyn.read(SPAR)
    body = case["bodies"][0]
    column, plate = [f for f in body["external forces"] if f["model"] == "rod"]
    assert column == {"model": "rod", "end_a": [0.0, 0.0, -40.0], "end_b": [0.0, 0.0, 10.0],
                      "diameter": 8.0, "segments": 10, "drag_coefficient": 0.8,
                      "added_mass_coefficient": 1.0, "end_drag_coefficient": 0.6,
                      "end_added_mass_coefficient": 0.6}  # fmt: skip
    assert plate["diameter"] == 14.0 and plate["segments"] == 1
    masses = (1.78e6, 1.0e4 * 50, 2.0e4 * 2)
    centres = (-36.0, -15.0, -41.0)
    total = sum(masses)
    cg = sum(m * z for m, z in zip(masses, centres, strict=True)) / total
    assert body["mass"] == pytest.approx(total, rel=1e-12)
    assert body["centre_of_gravity"] == pytest.approx([0.0, 0.0, cg], abs=1e-9)
    own = (5.0e8, 1.0e4 * 50 * (50**2 / 12 + 8**2 / 16), 2.0e4 * 2 * (2**2 / 12 + 14**2 / 16))
    pitch = sum(i + m * (z - cg) ** 2 for i, m, z in zip(own, masses, centres, strict=True))
    roll_axis = 5.0e8 + 1.0e4 * 50 * 8**2 / 8 + 2.0e4 * 2 * 14**2 / 8
    assert body["inertia"] == pytest.approx([pitch, pitch, roll_axis], rel=1e-10)
    text = SPAR.read_text().replace("1    chain     1        4 ", "1    chain     1        R1A")
    rows = (
        "3    column    Free       50    0    -80    50    0    -70    4          -\n"
        "4    plate     Fixed      60    0    -150   60    0    -148   1          -\n"
    )
    text = text.replace("---------------------- POINTS", rows + "---------------------- POINTS")
    text = text.replace("2    chain     2        5 ", "2    chain     R3B      5 ")
    text = text.replace("3    chain     3        6 ", "3    chain     R4b      6 ")
    case = moordyn.read(text)
    lines = {line["name"]: line for line in case["lines"]}
    assert lines["line1"]["to"] == "body1.rod1_a"
    assert lines["line2"]["from"] == "rod3.b" and lines["line3"]["from"] == "rod4.b"
    bodies = {b["name"]: b for b in case["bodies"]}
    free, fixed = bodies["rod3"], bodies["rod4"]
    assert free["type"] == "rigid" and free["position"] == [50.0, 0.0, -80.0]
    assert free["mass"] == pytest.approx(1.0e5) and free["centre_of_gravity"] == [0, 0, 5.0]
    assert free["points"]["b"] == [0.0, 0.0, 10.0]
    assert [f["model"] for f in free["external forces"]] == ["gravity", "rod"]
    assert fixed["type"] == "fixed" and fixed["points"]["b"] == [0.0, 0.0, 2.0]
    seacable.load_case(case)  # a valid case


def test_a_line_with_bending_stiffness_at_a_rods_end_is_refused():
    """MoorDyn clamps a line with EI > 0 at a rod's end along the rod's axis (a cantilever,
    its own BeamCantilevered test); seacable's line ends turn freely: refused by row and
    column, not read as a hinge."""
    text = SPAR.read_text().replace("1    chain     1        4 ", "1    chain     1        R1A")
    assert moordyn.read(text)["lines"][0]["to"] == "body1.rod1_a"  # without EI: read
    stiff = text.replace("-1.0      0    2.4", "-1.0      1e4  2.4")
    assert stiff != text
    with pytest.raises(seacable.CaseError, match=r"\(LINES, column AttachB\): 'R1A': a line "
                       "with bending stiffness"):  # fmt: skip
        moordyn.read(stiff)


REFUSED_RODS = [
    (COLUMN_ROW, COLUMN_ROW.replace("Body1 ", "Coupled"), "column Attachment): 'Coupled'"),
    (COLUMN_ROW, COLUMN_ROW.replace("Body1     ", "Body2Pinned"),
     "column Attachment): 'Body2Pinned'"),
    (COLUMN_ROW, COLUMN_ROW.replace("column", "colum "), "column RodType): 'colum' is not a"),
    (COLUMN_ROW, COLUMN_ROW.replace("  10   10 ", "  10    0 "),
     "column NumSegs): a rod of length 50 m in 0 segments"),
    (COLUMN_ROW, COLUMN_ROW.replace("0     0     10 ", "0     0    -40 "),
     "column NumSegs): a rod of length 0 m"),
    ("1    Free       0.0", "1    Coupled    0.0", "'Body1' is a coupled body: a rod's loads"),
]  # fmt: skip


@pytest.mark.parametrize(("old", "new", "message"), REFUSED_RODS)
def test_rods_without_an_equivalent_are_refused_by_row_and_column(old, new, message):
    text = SPAR.read_text()
    assert old in text
    with pytest.raises(seacable.CaseError) as error:
        moordyn.read(text.replace(old, new, 1))
    assert message in str(error.value) and "(RODS, column" in str(error.value)


WAVE_DECK = DATA / "moordyn_v2_waves" / "lines.txt"


def test_wave_components_beside_a_deck_become_airy_waves(tmp_path):
    """WaveKin 7: each row of wave_frequencies.txt (omega, then the complex amplitude A) but the
    first (omega 0) is an Airy wave towards +x of height 2 |A|, period 2 pi / omega and phase
    90 deg - arg A (MoorDyn's |A| sin(omega t - k x + arg A)), with Wheeler's stretching; the
    file's faults are refused by its name and line, and a deck given as text cannot have it."""
    case, written = moordyn.convert(WAVE_DECK)
    environment = case["environment"]
    assert environment["wave_stretching"] == "wheeler"
    first = environment["waves"][0]
    assert first["height"] == pytest.approx(2.0) and first["period"] == pytest.approx(4 * math.pi)
    assert first["phase_deg"] == pytest.approx(90.0 - math.degrees(math.atan2(0.6, 0.8)))
    assert len(environment["waves"]) == 3 and "WaveKin 7: 3 wave components" in written
    with pytest.raises(seacable.CaseError, match="beside the deck; read the deck from its file"):
        moordyn.read(WAVE_DECK.read_text())
    deck = tmp_path / "lines.txt"
    deck.write_text(WAVE_DECK.read_text())
    with pytest.raises(seacable.CaseError, match="wave_frequencies.txt. does not exist"):
        moordyn.read(deck)
    (tmp_path / "wave_frequencies.txt").write_text("0 0 0\n0.5 0.1\n")
    with pytest.raises(seacable.CaseError, match="wave_frequencies.txt line 2: '0.5 0.1': give"):
        moordyn.read(deck)
    (tmp_path / "wave_frequencies.txt").write_text("0.3 0 0\n0.5 0.1 0\n")
    with pytest.raises(seacable.CaseError, match="line 1: omega 0.3: the frequencies start at 0"):
        moordyn.read(deck)


def test_a_steady_current_profile_beside_a_deck_becomes_the_cases_current(tmp_path):
    """Currents 1 (or 3): current_profile.txt's rows after its three heading lines (z, ux, uy,
    uz) are the case's current profile of speeds towards their one direction; a current that
    turns with depth, a vertical one, or fewer than two rows is refused by the file's line."""
    case = moordyn.read(DATA / "moordyn_v2_current" / "lines.txt")
    current = case["environment"]["current"]
    assert current["direction_deg"] == pytest.approx(30.0)
    assert current["profile"][0] == [-51.0, 0.0] and current["profile"][-1] == [0.0, 1.2]
    deck = tmp_path / "lines.txt"
    deck.write_text((DATA / "moordyn_v2_current" / "lines.txt").read_text())
    head = "title\ncomment\nz ux uy uz\n"
    for rows, message in (
        ("-50 0.5 0 0\n0 0 0.5 0\n", "line 5: the current turns with depth (90 deg here, 0 deg"),
        ("-50 0.5 0 0\n0 1 0 0.1\n", "line 5: uz 0.1 m/s: a vertical current is not modelled"),
        ("-50 0.5 0 0\n", "a current profile needs at least 2 rows"),
    ):
        (tmp_path / "current_profile.txt").write_text(head + rows)
        with pytest.raises(seacable.CaseError) as error:
            moordyn.read(deck)
        assert message in str(error.value)
