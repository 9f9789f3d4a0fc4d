"""The ship-simulator document's case form read as written (case.system.DocumentDynamics):
its ``dynamics`` block's added mass, "at the center of buoyancy projected in the body frame"
with ``frame`` and ``row 1`` ... ``row 6`` in its z-down body frame, gives the same body, forces
and motions as the same vessel written in seacable's frames; and its mistakes are refused."""

import numpy as np
import pytest
import yaml

import seacable
from seacable import meshes
from seacable.errors import CaseError
from seacable.system import model

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


def test_the_centre_of_buoyancy_comes_from_the_mesh(hull):
    """Without ``centre_of_buoyancy``, the point is the mesh's centre of buoyancy at the
    start pose (here the box's: 0.3 m forward, half the 1 m draft below the waterline, which
    is 0.5 m below the reference point)."""
    raw = yaml.safe_load(_yaml(hull, "document"))
    raw["bodies"][0]["orientation_deg"] = [0.0, 0.0, 0.0]
    a = model.build(seacable.load_case(raw)).params.body_added[0]
    raw_ours = yaml.safe_load(_yaml(hull, "ours", extra=_explicit((0.3, 0.0, -1.0))))
    raw_ours["bodies"][0]["orientation_deg"] = [0.0, 0.0, 0.0]
    b = model.build(seacable.load_case(raw_ours)).params.body_added[0]
    assert a == pytest.approx(b, rel=1e-6, abs=1e-3)  # the centre from sums over the mesh


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda body: body["dynamics"][next(iter(body["dynamics"]))].update(frame="other"),
         "frame: 'other' is not this body"),
        (lambda body: body.update(added_mass=[1.0] * 6), "both give the added mass"),
        (lambda body: body.pop("mesh") and body["external forces"].pop(),
         "give 'centre_of_buoyancy'"),
        (lambda body: body["dynamics"][next(iter(body["dynamics"]))].pop("row 4"), "row 4"),
    ],
)  # fmt: skip
def test_the_documents_mistakes_are_refused(hull, change, message):
    raw = yaml.safe_load(_yaml(hull, "document"))
    change(raw["bodies"][0])
    with pytest.raises(CaseError, match=message):
        seacable.load_case(raw)
