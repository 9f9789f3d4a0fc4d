"""Rigid lines held at their end on a free body (two-ports, system.rigid.ports): a rigid body
at a line's end, a line between two free bodies, a loop on one body. Checked against the tree
form of the same physics (the body carried at the line's end), against the energy without
damping, and against the reciprocity of the line's coupling."""

import math

import numpy as np
import pytest

from seacable.case.loader import load_case
from seacable.errors import CaseError
from seacable.simulation import simulate
from seacable.system import kernel, model

ROPE = {"name": "rope", "diameter": 0.02, "mass_per_length": 1.5, "drag_coefficient_normal": 0.0}
MODELS = ["rigid_segments_3d", "rigid_links"]
TIGHT = {"integrator": "dopri5", "rtol": 1e-10, "atol": 1e-10, "output_interval": 0.05}


def _dofs(planar: bool) -> list[str]:
    return ["surge", "heave"] if planar else ["surge", "sway", "heave"]


def _case(bodies, lines, duration=2.0, **simulation):
    return load_case({
        "name": "ports", "start": "as_given", "environment": {"in_air": True, "gravity": 9.81},
        "bodies": bodies, "line_types": [ROPE], "lines": lines,
        "simulation": {"duration": duration, **TIGHT, **simulation},
    })  # fmt: skip


def _line(name, a, b, length, model, segments=5):
    return {"name": name, "model": model, "from": a, "to": b,
            "sections": [{"type": "rope", "length": length, "segments": segments}]}  # fmt: skip


def _pendulum(model, ball_kind, free_base):
    """A line from a base to a 30 kg ball in air: the base fixed, or a 40 kg point body on a
    stiff tie to an anchor. As a point body the ball is carried at the line's end (the tree
    form); as a rigid body whose rotations are held, the same ball is a free body the line's
    end is held on (a two-port)."""
    planar = model == "rigid_links"
    ball = {"name": "ball", "type": ball_kind, "position": [4.0, 0.0, -6.0], "mass": 30.0,
            "dofs": _dofs(planar), "external forces": [{"model": "gravity"}]}  # fmt: skip
    if ball_kind == "rigid":
        ball["inertia"] = [1.0, 1.0, 1.0]
    bodies = [{"name": "base", "type": "fixed", "position": [-2.0, 0.0, 0.0]}, ball]
    lines = [_line("line", "base", "ball", 9.0, model)]
    if free_base:
        bodies[0] = {"name": "base", "type": "point", "position": [-2.0, 0.0, 0.0],
                     "mass": 40.0, "dofs": _dofs(planar),
                     "external forces": [{"model": "gravity"}]}  # fmt: skip
        bodies.append({"name": "anchor", "type": "fixed", "position": [-2.0, 0.0, 1.0]})
        lines.append({"name": "tie", "model": "tie", "from": "anchor", "to": "base",
                      "unstretched_length": 0.5, "stiffness": 3e4})  # fmt: skip
    return _case(bodies, lines)


def _ball(ds) -> np.ndarray:
    return np.stack([ds[f"bodies/ball/position_{c}"].values for c in "xyz"])


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("free_base", [False, True], ids=["fixed base", "free base"])
def test_a_body_held_at_the_end_moves_as_the_body_carried_there(model, free_base):
    """The ball swings alike in both forms (it falls about 3 m and swings 6 m): within 1e-9 m on
    a fixed base, 1e-6 m on a free base (the tie's 3e4 N/m and the held end's stabilisation
    leave the integrator's error at about 1e-7 m there)."""
    carried = _ball(simulate(_pendulum(model, "point", free_base)).dataset)
    held = _ball(simulate(_pendulum(model, "rigid", free_base)).dataset)
    assert np.ptp(carried[0]) > 3.0
    np.testing.assert_allclose(held, carried, rtol=0, atol=1e-6 if free_base else 1e-9)


def _tethered(model, loop=False, duration=3.0, hang="tie", **simulation):
    """A point body on a stiff tie to an anchor and a rigid body (6 DOF in 3D; surge, heave and
    pitch in the plane) hanging from it on a rigid line held at a point off its centre
    (``loop``: and a second line from one of its points to another, a bridle). In air,
    without damping. ``hang="line"``: the point body hangs from the anchor on a straight rigid
    line (which would carry it) instead of the tie."""
    planar = model == "rigid_links"
    eye = [-0.5, 0.0 if planar else 0.2, 0.3]
    hull = {"name": "hull", "type": "rigid", "position": [6.0, 0.0, -4.0], "mass": 50.0,
            "inertia": [20.0, 30.0, 25.0],
            "points": {"eye": eye, "bow": [1.0, 0.0, 0.4], "stern": [-1.0, 0.0, 0.4]},
            "dofs": ["surge", "heave", "pitch"] if planar else
            ["surge", "sway", "heave", "roll", "pitch", "yaw"],
            "external forces": [{"model": "gravity"}]}  # fmt: skip
    bodies = [{"name": "anchor", "type": "fixed", "position": [0.0, 0.0 if planar else -0.5, 0.0]},
              {"name": "top", "type": "point", "position": [0.0, 0.0, -1.0], "mass": 80.0,
               "dofs": _dofs(planar), "external forces": [{"model": "gravity"}]},
              hull]  # fmt: skip
    reach = float(np.linalg.norm(np.add(hull["position"], eye) - [0.0, 0.0, -1.0]))
    lines = [{"name": "tie", "model": "tie", "from": "anchor", "to": "top",
              "unstretched_length": 1.0, "stiffness": 2e4},
             _line("line", "top", "hull.eye", 1.15 * reach, model, segments=6)]  # fmt: skip
    if hang == "line":  # the point body hung on a rigid line instead: a base it would carry
        length = math.dist(bodies[0]["position"], bodies[1]["position"])
        lines[0] = {**_line("tie", "anchor", "top", length, model, segments=2),
                    "initial": "straight"}  # fmt: skip
    if loop:
        lines.append(_line("bridle", "hull.bow", "hull.stern", 2.6, model, segments=4))
    return _case(bodies, lines, duration=duration, **simulation)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("loop", [False, True], ids=["line", "line and bridle"])
def test_energy_of_bodies_joined_by_rigid_lines_is_conserved(model, loop):
    """Without damping the total energy stays constant as the body swings, turns and the lines
    fold (its kinetic energy swings by about 2.5 kJ): to 1e-8 of that swing, with the error
    falling with the integrator's tolerance (the held ends' stabilisation conserves it). With
    the bridle in 3D it was 1.1e-5, 1.5e-6 and 5.7e-8 J at rtol 1e-10, 1e-11 and 1e-12: at
    1e-10 the bound held by a factor of two or less and a change of rounding could break it, so
    the run takes 1e-11 (a margin of about 17)."""
    ds = simulate(_tethered(model, loop, rtol=1e-11, atol=1e-11)).dataset
    swing = np.ptp(ds["kinetic_energy"].values)
    assert swing > 1e3
    assert np.ptp(ds["total_energy"].values) < 1e-8 * swing
    assert np.abs(ds["lines/line/constraint_error"].values).max() < 1e-8
    assert np.ptp(ds["bodies/hull/pitch"].values) > 5.0  # degrees: it turns


def _ring(model, reverse=False, duration=2.0):
    """Three 20 kg balls joined in a ring by three straight rigid lines, one of them hung from
    an anchor by a fourth, released in air without damping: the ring swings and turns.
    ``reverse``: the ring's lines written the other way round (other balls are then carried
    at their ends, others held)."""
    dofs = {"dofs": _dofs(True)} if model == "rigid_links" else {}

    def ball(name, at):
        return {"name": name, "type": "point", "position": at, "mass": 20.0,
                "external forces": [{"model": "gravity"}], **dofs}  # fmt: skip

    ring = [("a", "b"), ("b", "c"), ("c", "a")]
    if reverse:
        ring = [(b, a) for a, b in ring]
    at = {"a": [0.0, 0.0, -3.0], "b": [3.0, 0.0, -6.0], "c": [-3.0, 0.0, -5.0]}
    lines = [_line("hang", "anchor", "a", 3.0, model)]
    for a, b in ring:  # each straight between its balls: the same start however written
        lines.append({**_line(a + b, a, b, math.dist(at[a], at[b]), model),
                      "initial": "straight"})  # fmt: skip
    return _case([{"name": "anchor", "type": "fixed", "position": [0.0, 0.0, 0.0]},
                  *[ball(name, position) for name, position in at.items()]],
                 lines, duration=duration)  # fmt: skip


@pytest.mark.parametrize("model", MODELS)
def test_a_ring_of_rigid_lines_keeps_its_energy_however_written(model):
    """A closed ring of inextensible lines (refused before: each line carried at the end of
    the next, or a held line from a carried body; now one ball is left free and the line
    ending on it held there): its energy stays constant to 1e-8 of its kinetic energy's swing
    (1.3e-8 J of 882 J), and written the other way round (other balls carried, other lines
    held) it moves the same within 1e-9 m (4e-11 m measured, the balls moving 5.7 m)."""
    runs = [simulate(_ring(model, reverse)).dataset for reverse in (False, True)]
    for ds in runs:
        swing = np.ptp(ds["kinetic_energy"].values)
        assert swing > 100.0
        assert np.ptp(ds["total_energy"].values) < 1e-8 * swing
    for name in "abc":
        at = [np.stack([ds[f"bodies/{name}/position_{c}"].values for c in "xz"]) for ds in runs]
        assert np.ptp(at[0]) > 1.0
        np.testing.assert_allclose(at[1], at[0], rtol=0, atol=1e-9)


@pytest.mark.parametrize("model", MODELS)
def test_a_held_line_from_a_body_another_line_would_carry_keeps_its_energy(model):
    """The body's line starts on a point body that hangs on another rigid line (refused
    before: a held line from a carried body; now that point body is left free, the line to it
    held there): without damping the energy stays constant to 1e-8 of the kinetic energy's
    swing."""
    ds = simulate(_tethered(model, hang="line", rtol=1e-11, atol=1e-11)).dataset
    swing = np.ptp(ds["kinetic_energy"].values)
    assert swing > 1e3
    assert np.ptp(ds["total_energy"].values) < 1e-8 * swing
    assert np.abs(ds["lines/tie/constraint_error"].values).max() < 1e-8


def test_a_line_between_two_free_bodies_couples_them_reciprocally():
    """The line's maps are reciprocal: the tip's acceleration per base acceleration, G, is the
    transpose of the base's force per holding force, S_0, and the tip's compliance A_L is
    symmetric (Maxwell-Betti for the accelerations), so the bodies' and holding forces' system
    is symmetric."""
    system = model.build(_tethered("rigid_segments_3d"))
    p = system.params
    w = kernel.make_work(p)
    kernel.rhs(0.0, system.y0, p, w, np.zeros(len(system.y0)))
    row = w.rs_la[int(np.flatnonzero(p.rs_port)[0])]
    g, compliance, s0 = (row[k : k + 9].reshape(3, 3) for k in (3, 12, 21))
    assert np.abs(g - np.eye(3)).max() > 0.1
    np.testing.assert_allclose(g, s0.T, rtol=0, atol=1e-12)
    np.testing.assert_allclose(
        compliance, compliance.T, rtol=0, atol=1e-12 * np.abs(compliance).max()
    )
    assert list(p.group_member) == [1, 2, 0]  # the point body and the hull, then the line


def test_a_tip_joint_on_a_free_body_is_refused():
    case = _tethered("rigid_segments_3d")
    lines = [*case.lines[:1], case.lines[1].model_copy(update={"tip_joint_stiffness": 10.0})]
    with pytest.raises(CaseError, match=r"lines\[1\] \(line\)\.tip_joint_stiffness: .* free body"):
        model.build(case.model_copy(update={"lines": lines}))


def test_an_implicit_scheme_follows_bodies_joined_by_a_rigid_line():
    """Generalized-alpha (second order) on the line from a tied point body to a rigid body:
    its error against dopri5 at 1e-10 falls about fourfold when the step halves."""
    reference = simulate(_tethered("rigid_segments_3d", duration=1.0)).dataset
    errors = []
    for step in (2e-3, 1e-3):
        case = _tethered("rigid_segments_3d", duration=1.0, integrator="generalized_alpha",
                         time_step=step)  # fmt: skip
        ds = simulate(case).dataset
        errors.append(np.abs(_hull(ds) - _hull(reference)).max())
    assert errors[0] < 1e-3 and 3.0 < errors[0] / errors[1] < 6.0


def _hull(ds) -> np.ndarray:
    return np.stack([ds[f"bodies/hull/position_{c}"].values for c in "xyz"])


def _vee(model, form):
    """A 30 kg ball on two rigid lines from two anchors (a V), written three ways: both lines
    ending on the ball (``ends``), or one line carrying it and the other leaving it for an
    anchor (``tree``, the line from the left or from the right carrying it)."""
    dofs = {"dofs": _dofs(True)} if model == "rigid_links" else {}
    ball = {"name": "ball", "type": "point", "position": [1.0, 0.0, -6.0], "mass": 30.0,
            "external forces": [{"model": "gravity"}], **dofs}  # fmt: skip
    one, two = ("left", "ball"), ("right", "ball")
    if form == "tree, left carries":
        two = ("ball", "right")
    elif form == "tree, right carries":
        one = ("ball", "left")
    case = _case(
        [{"name": "left", "type": "fixed", "position": [-5.0, 0.0, 0.0]},
         {"name": "right", "type": "fixed", "position": [5.0, 0.0, 0.0]}, ball],
        [_line("one", *one, 9.0, model, segments=8), _line("two", *two, 8.0, model, segments=8)],
        duration=1.0,
    )  # fmt: skip
    return case.model_copy(update={"start": "static"})


def test_a_body_on_two_rigid_lines_finds_one_static_balance_however_written():
    """The V's statics, in both line models and in the three ways of writing it (holding
    forces as unknowns of the bodies' system; a tree with a held tip): one balance, within
    1e-9 m, from which a run stays at rest. Newton finds none for the trees (it turns the
    lines the wrong way from the start); the dynamic relaxation (system.relax) does."""
    found = {}
    for kind in MODELS:
        for form in ("ends", "tree, left carries", "tree, right carries"):
            ds = simulate(_vee(kind, form)).dataset
            at = _ball(ds)
            assert np.abs(at - at[:, :1]).max() < 1e-6
            assert ds["kinetic_energy"].values.max() < 1e-12
            found[kind, form] = at[:, 0]
    first = found["rigid_segments_3d", "ends"]
    assert first[2] < -6.5  # it sank from where it was placed
    for at in found.values():
        np.testing.assert_allclose(at, first, rtol=0, atol=1e-9)


def test_a_body_hung_off_its_centre_turns_until_its_centre_hangs_below_the_line():
    """A 6-DOF body hung on a rigid line from a pin at an eye 0.62 m from its centre of gravity
    (placed level, the eye up and aside): at balance the line hangs straight down from the pin
    and the centre of gravity straight below the eye, so the body stands under the pin at the
    line's length plus the eye's distance (closed form, 1e-9 m); it turned about 60 degrees to
    get there, which only the dynamic relaxation finds. A run from it stays at rest."""
    data = _tethered("rigid_segments_3d", duration=1.0).model_dump(by_alias=True, exclude_none=True)
    data["bodies"][1] = {"name": "top", "type": "fixed", "position": [0.0, 0.0, -1.0]}
    case = load_case({**data, "lines": data["lines"][1:], "start": "static"})
    ds = simulate(case).dataset
    hull = _hull(ds)
    eye = np.array([-0.5, 0.2, 0.3])
    length = sum(section.length for section in case.lines[0].sections)
    np.testing.assert_allclose(hull[:, 0], [0.0, 0.0, -1.0 - length - np.linalg.norm(eye)],
                               rtol=0, atol=1e-9)  # fmt: skip
    assert np.abs(hull - hull[:, :1]).max() < 1e-9
    assert ds["kinetic_energy"].values.max() < 1e-12
    assert abs(ds["bodies/hull/pitch"].values[0]) > 30.0


@pytest.mark.parametrize("model", MODELS)
def test_a_body_hanging_on_a_rigid_line_held_on_it_finds_its_balance(model):
    """The ball held at the line's end hangs as the ball carried there: straight below the
    pin, the line pulled straight (its holding force is an unknown of the bodies' system, so
    a straight line is no singularity), within 1e-9 m; a run from there stays at rest."""
    at = {}
    for kind in ("point", "rigid"):
        case = _pendulum(model, kind, False).model_copy(update={"start": "static"})
        ds = simulate(case).dataset
        at[kind] = _ball(ds)
        assert ds["kinetic_energy"].values.max() < 1e-20
    np.testing.assert_allclose(at["rigid"][:, 0], [-2.0, 0.0, -9.0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(at["rigid"], at["point"], rtol=0, atol=1e-9)
