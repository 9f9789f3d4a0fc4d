"""The ship-simulator document's case form read as written (case.document.DocumentDynamics):
its ``dynamics`` block (mass, centre of inertia, rigid-body inertia at the centre of gravity,
added mass "at the center of buoyancy projected in the body frame", each matrix with ``frame``
and ``row 1`` ... ``row 6``, all in its z-down body frame) gives the same body, forces and
motions as the same vessel written in seacable's frames; the added mass is at the hull's
still-water centre of buoyancy whatever pose it starts in (a box's, in closed form); and the
block's mistakes are refused in one line naming its keys."""

import math

import numpy as np
import pytest
import yaml
from scipy.optimize import brentq

import seacable
from seacable import meshes
from seacable.errors import CaseError
from seacable.system import hulls, model

RHO, G = 1025.0, 9.81
L, B, H, DRAFT = 10.0, 4.0, 3.0, 1.0
MASS = RHO * L * B * DRAFT
# a coupled added mass in the document's body frame (x forward, y to starboard, z down) [kg,
# kg m, kg m^2]: symmetric, positive definite, with every kind of coupling
DOCUMENT = np.array([
    [2.0e3, 0.0, 150.0, 0.0, 400.0, 0.0],
    [0.0, 9.0e3, 0.0, -700.0, 0.0, 900.0],
    [150.0, 0.0, 3.0e4, 0.0, 1200.0, 0.0],
    [0.0, -700.0, 0.0, 6.0e3, 0.0, 300.0],
    [400.0, 0.0, 1200.0, 0.0, 2.0e5, 0.0],
    [0.0, 900.0, 0.0, 300.0, 0.0, 1.5e5],
])  # fmt: skip
COB_UP = (0.3, 0.0, -0.5)  # the centre of buoyancy, body frame z up [m] (the box's own)


def _yaml(path, dynamics: str, extra: str = "") -> str:
    rows = "\n".join(f"            row {i + 1}: {DOCUMENT[i].tolist()}" for i in range(6))
    block = f"""    dynamics:
        added mass matrix at the center of buoyancy projected in the body frame:
            frame: ship
{rows}
""" if dynamics == "document" else ""  # fmt: skip
    return f"""
environment: {{water_density: {RHO}, gravity: {G}}}
bodies:
  - name: ship
    type: rigid
    position: [0.0, 0.0, {H / 2 - DRAFT}]
    orientation_deg: [3.0, -1.0, 10.0]
    velocity: [0.4, 0.1, 0.0]
    angular_velocity: [0.01, 0.02, 0.03]
    mass: {MASS}
    centre_of_gravity: [0.0, 0.0, {DRAFT - H / 2}]
    inertia: [{MASS * 2.0}, {MASS * 9.0}, {MASS * 9.5}]
    mesh: {{file: {path}}}
{extra}{block}    external forces:
      - {{model: gravity}}
      - {{model: non-linear hydrostatic}}
start: as_given
simulation: {{duration: 6.0, output_interval: 0.1, integrator: dopri5, rtol: 1.0e-10}}
"""


def _ours() -> np.ndarray:
    """The same matrix in seacable's body frame (z up, y to port): a half turn about x
    changes the sign of y, z, their rotations' rates... by hand, entry by entry: an entry
    changes sign when exactly one of its two motions is sway, heave, pitch or yaw."""
    flips = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
    return DOCUMENT * np.outer(flips, flips)


def _explicit(point) -> str:
    """seacable's own form of the same added mass, at ``point``."""
    return f"    added_mass: {_ours().tolist()}\n    added_mass_point: {list(point)}\n"


def _still_water_point(hull, raw) -> tuple:
    """The still-water centre of buoyancy of the body of ``raw`` (as system.hulls finds it)."""
    case = seacable.load_case(raw)
    body = case.bodies[0]
    mesh = hulls.body_mesh(body, None, "ship")
    point = hulls.still_water(mesh, body.mass, RHO, body.centre_of_gravity, "ship")
    return tuple(float(c) for c in point.centre_of_buoyancy)


@pytest.fixture
def hull(tmp_path):
    path = tmp_path / "box.stl"
    meshes.write_stl(meshes.box(L, B, H, n=2).moved((0.3, 0.0, 0.0)), path)
    return path


def test_the_documents_block_is_the_same_vessel(tmp_path, hull):
    """Read as written, the document's block gives the added mass that seacable's own form
    gives for the matrix turned into its frame at the centre of buoyancy: the same body at
    the reference point, and the same motions of a vessel tumbling in still water."""
    document = seacable.load_case(yaml.safe_load(_yaml(hull, "document", extra=(
        f"    centre_of_buoyancy: {list(COB_UP)}\n"))))  # fmt: skip
    ours = seacable.load_case(yaml.safe_load(_yaml(hull, "ours", extra=_explicit(COB_UP))))
    a = model.build(document).params.body_added[0]
    b = model.build(ours).params.body_added[0]
    assert np.abs(b).max() > 1e4 and not np.allclose(a, DOCUMENT)
    assert a == pytest.approx(b, rel=1e-14, abs=1e-9)
    runs = [seacable.simulate(case)["bodies/ship"] for case in (document, ours)]
    for name in ("position_x", "position_y", "position_z", "roll", "pitch", "yaw"):
        assert np.ptp(runs[0][name].values) > 1e-3
        assert runs[0][name].values == pytest.approx(runs[1][name].values, abs=1e-9)


def test_the_added_mass_is_at_the_still_water_centre_of_buoyancy(hull):
    """Without ``centre_of_buoyancy``, the point is the hull's centre of buoyancy floating
    free at rest: a start heeled, pitched, raised or turned gives the same added mass, bit for
    bit (at the start pose's centre of buoyancy a 3 degree heel moved it by 1 %), and the
    results say which point was used."""
    raw = yaml.safe_load(_yaml(hull, "document"))
    upright = model.build(seacable.load_case(raw))
    for pose in ([3.0, -1.0, 10.0], [-8.0, 2.5, 0.0]):
        raw["bodies"][0]["orientation_deg"] = pose
        raw["bodies"][0]["position"] = [1.0, -2.0, H / 2 - DRAFT + 0.2]
        tilted = model.build(seacable.load_case(raw))
        assert np.array_equal(tilted.params.body_added, upright.params.body_added)
    facts = upright.layout.facts["added_mass_point"]
    assert facts.startswith("ship: [") and "still-water centre of buoyancy" in facts


@pytest.mark.parametrize("cog_x", [0.3, 0.0])
def test_a_box_floats_where_its_closed_form_says(cog_x):
    """The still-water centre of buoyancy of a box (10 x 4 x 3 m, centred 0.3 m forward of the
    reference point, its weight that of 1 m of draft): with the centre of gravity above the
    box's centre it floats upright, the centre of buoyancy half the draft below the waterline
    (0.3, 0, -1.0); 0.3 m aft it trims by the head until the centre of buoyancy of the
    trapezoidal underwater prism is on the centre of gravity's vertical (the prism's moments in
    closed form, the trim by brentq)."""
    mesh = meshes.box(L, B, H, n=2).moved((0.3, 0.0, 0.0))
    cog = np.array([cog_x, 0.0, DRAFT - H / 2])
    floating = hulls.still_water(mesh, MASS, RHO, cog, "ship")
    x0, x1 = 0.3 - L / 2, 0.3 + L / 2

    def centre(slope):  # the waterline z = c - H/2 + slope x in the body frame, its volume L B T
        c = (L * DRAFT - slope * (x1**2 - x0**2) / 2) / (x1 - x0)
        first = c * (x1**2 - x0**2) / 2 + slope * (x1**3 - x0**3) / 3
        square = c * c * (x1 - x0) + c * slope * (x1**2 - x0**2) + slope**2 * (x1**3 - x0**3) / 3
        return np.array([first / (L * DRAFT), 0.0, -H / 2 + square / (2 * L * DRAFT)])

    # B - G along the earth's vertical, the waterline's normal (-slope, 0, 1) in the body frame
    slope = brentq(lambda a: (centre(a) - cog)[0] + a * (centre(a) - cog)[2], -0.5, 0.5,
                   xtol=1e-16)  # fmt: skip
    assert floating.centre_of_buoyancy == pytest.approx(centre(slope), abs=1e-12)
    assert abs(math.tan(math.radians(floating.pitch_deg))) == pytest.approx(abs(slope), 1e-9)
    if cog_x == 0.3:
        assert floating.centre_of_buoyancy == pytest.approx([0.3, 0.0, -1.0], abs=1e-12)
        assert floating.height == pytest.approx(H / 2 - DRAFT, abs=1e-12)
    else:
        assert floating.pitch_deg < -2.0  # bow down, by 2.19 degrees


# the whole block: mass, centre of inertia (a little to starboard and below the reference
# point), rigid-body inertia at the centre of gravity with its products, added mass
INERTIA_DOCUMENT = MASS * np.array([[2.0, 0.05, -0.1], [0.05, 9.0, 0.02], [-0.1, 0.02, 9.5]])
COG_DOCUMENT = (0.1, 0.02, H / 2 - DRAFT)  # x forward, y to starboard, z down [m]


def _whole_block(path) -> dict:
    raw = yaml.safe_load(_yaml(path, "document"))
    body = raw["bodies"][0]
    for key in ("mass", "centre_of_gravity", "inertia"):
        body.pop(key)
    rigid = np.zeros((6, 6))
    rigid[:3, :3] = MASS * np.eye(3)
    rigid[3:, 3:] = INERTIA_DOCUMENT
    body["dynamics"] |= {
        "centre of inertia": {"frame": "ship", **{
            c: {"value": v, "unit": "m"} for c, v in zip("xyz", COG_DOCUMENT, strict=True)}},
        "mass": {"value": MASS / 1000.0, "unit": "tonne"},
        "rigid body inertia matrix at the center of gravity and projected in the body frame": {
            "frame": "ship", **{f"row {i + 1}": rigid[i].tolist() for i in range(6)}},
    }  # fmt: skip
    return raw


def test_the_whole_block_is_the_same_vessel(hull):
    """The document's whole block and seacable's own keys (the centre of gravity and the
    inertia turned by hand: y and z change sign, so do the products I_xy and I_xz) give the
    same body and, from a heeled start, the same motions bit for bit; the results record the
    still-water point."""
    document = _whole_block(hull)
    ours = yaml.safe_load(_yaml(hull, "ours"))
    x, y, z = COG_DOCUMENT
    flip = np.diag([1.0, -1.0, -1.0])
    ours["bodies"][0] |= {"centre_of_gravity": [x, -y, -z],
                          "inertia": (flip @ INERTIA_DOCUMENT @ flip).tolist()}  # fmt: skip
    point = _still_water_point(hull, ours)
    assert point[1] < -1e-3  # weight to starboard (y < 0 here): buoyancy follows it there
    ours["bodies"][0] |= {"added_mass": _ours().tolist(), "added_mass_point": list(point)}
    cases = [seacable.load_case(raw) for raw in (document, ours)]
    a, b = (model.build(case).params for case in cases)
    for name in ("body_mass", "body_cog", "body_inertia", "body_added"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    runs = [seacable.simulate(case) for case in cases]
    assert "still-water centre of buoyancy" in runs[0].dataset.attrs["added_mass_point"]
    for name in ("position_z", "roll", "pitch", "yaw"):
        motion = [run["bodies/ship"][name].values for run in runs]
        assert np.ptp(motion[0]) > 1e-3 and np.array_equal(motion[0], motion[1])


ADDED = "added mass matrix at the center of buoyancy projected in the body frame"
RIGID = "rigid body inertia matrix at the center of gravity and projected in the body frame"


def _set(key, **update):
    return lambda body: body["dynamics"][key].update(update)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (_set(ADDED, frame="other"), f"dynamics.{ADDED}.frame: 'other' is not this body"),
        (_set("centre of inertia", frame="NED"),
         "dynamics.centre of inertia.frame: 'NED' is not this body; it is given in the body's "
         "own frame: write frame: ship"),
        (lambda body: body.update(added_mass=[1.0] * 6),
         f"'added_mass' and the document's 'dynamics.{ADDED}' both give"),
        (lambda body: body.update(mass=1.0), "'mass' and the document's 'dynamics.mass' both"),
        (lambda body: body.update(inertia=[1.0] * 3),
         f"'inertia' and the document's 'dynamics.{RIGID}' both give the body's inertia"),
        (lambda body: body.update(centre_of_gravity=[0.0] * 3),
         "'centre_of_gravity' and the document's 'dynamics.centre of inertia' both"),
        (lambda body: body.pop("mesh") and body["external forces"].pop(),
         f"dynamics.{ADDED}: the matrix is at the still-water centre of buoyancy, found from "
         "the hull: give the hull's 'mesh', or the point as 'centre_of_buoyancy'"),
        (lambda body: body["dynamics"][ADDED].pop("row 4"), f"dynamics.{ADDED}.row 4: required"),
        (_set(RIGID, **{"row 2": [0.0, MASS, 0.0, 0.0, 0.0]}),
         f"dynamics.{RIGID}.row 2: 5 numbers; a row of the 6x6 matrix has 6"),
        (_set("mass", unit="ton"), "dynamics.mass: unit 'ton' is not a unit of mass"),
        (_set("mass", value=1.0), f"mass 1 tonne and {RIGID} .row 1: {MASS:g} kg. give two"),
        (_set(RIGID, **{"row 1": [MASS, 0.0, 0.0, 0.0, 0.0, 5e3]}),
         f"{RIGID}: coupling terms .rows 1-3 columns 4-6, rows 4-6 columns 1-3. up to 5000"),
        (lambda body: body["dynamics"].update(
            {RIGID.replace("gravity and", "buoyancy"): body["dynamics"].pop(RIGID)}),
         "seacable reads the rigid-body inertia at the centre of gravity"),
        (lambda body: body["dynamics"].update({
            "hydrodynamic forces calculation point in body frame": {
                c: {"value": 0.0, "unit": "m"} for c in "xyz"}}),
         "is where the hydrodynamic database's forces are given, and the body has no"),
    ],
)  # fmt: skip
def test_the_documents_mistakes_are_refused(hull, change, message):
    """Each mistake in one line, naming the document's keys as written."""
    raw = _whole_block(hull)
    change(raw["bodies"][0])
    with pytest.raises(CaseError, match=message.replace("(", ".").replace(")", ".")):
        seacable.load_case(raw)
