"""Statics of the two system examples against MoorPy's System (an independent quasi-static code:
elastic catenaries on a rigid frictionless seabed, free points and a free 6-DOF body):
- the buoy on three legs (one chain-rope-chain with a clump weight), without the current:
  buoy and clump positions and every line's end tensions;
- the platform on three catenary chains: its offset under a steady horizontal force and the
  6x6 stiffness of its lines at its reference point.

MoorPy's lines are uniform, so leg_c_upper (polyester then chain) is two MoorPy lines joined at a
massless free point. MoorPy puts buoyancy at a metacentre rM and the waterplane's heave
stiffness as rho g AWP z; seacable puts buoyancy at the centre of buoyancy and adds a linear
stiffness K: rM_z = z_B + K44 / (rho g V) and AWP = K33 / (rho g) give the same restoring
(to K44 (phi - sin phi), 4e-5 relative at the angles met here)."""

import numpy as np
import pytest

import seacable
from seacable.case.loader import derive_case
from seacable.system import model, statics

mp = pytest.importorskip("moorpy")

BUOY = "examples/buoy_three_lines_clump_weight.yaml"
PLATFORM = "examples/platform_three_catenary_lines.yaml"
FORCE, ARM = 1.0e5, 30.0  # N along x, m above the reference point (a wind load)


def _dump(items) -> list[dict]:
    return [item.model_dump(by_alias=True, exclude_defaults=True, mode="json") for item in items]


def _buoy_case(segments_factor: int = 1, start=None):
    """The buoy example without its current; ``start`` {body: position} a first guess."""
    base = seacable.load_case(BUOY)
    bodies = _dump(base.bodies)
    for body in bodies:
        body["position"] = list((start or {}).get(body["name"], body["position"]))
    lines = _dump(base.lines)
    for line in lines:
        for section in line["sections"]:
            section["segments"] *= segments_factor
    return derive_case(base, {"environment": {"current": None}, "bodies": bodies, "lines": lines})


def _moorpy_system(case):
    env = case.environment
    ms = mp.System(depth=env.water_depth, rho=env.water_density, g=env.gravity)
    for t in case.line_types:
        ms.setLineType(name=t.name, lineType={"d_vol": t.diameter, "m": t.mass_per_length,
                                              "EA": t.axial_stiffness})  # fmt: skip
    return ms


def _moorpy_buoy(case):
    """The buoy system in MoorPy, solved; {body: point} and {line: (first, last) MoorPy line}."""
    ms = _moorpy_system(case)
    points = {}
    for body in case.bodies:
        if body.type == "fixed":
            ms.addPoint(1, body.position)
        else:
            ms.addPoint(0, body.position, m=body.mass, v=body.displaced_volume())
        points[body.name] = ms.pointList[-1]
    ends = {}
    for line in case.lines:
        a = points[line.from_]
        first = len(ms.lineList)
        for k, section in enumerate(line.sections):
            if k < len(line.sections) - 1:  # a massless free point between two sections
                guess = a.r + 0.9 * (points[line.to].r - a.r)
                b = ms.addPoint(0, guess)
            else:
                b = points[line.to]
            ms.addLine(section.length, section.type, pointA=a.number, pointB=b.number)
            a = b
        ends[line.name] = (ms.lineList[first], ms.lineList[-1])
    ms.initialize()
    ms.solveEquilibrium(tol=1e-6, maxIter=2000)
    return points, ends


def _ours(results, group, names):
    ds = results.dataset[group].to_dataset().isel(time=0)
    return np.array([float(ds[name]) for name in names])


def _buoy_errors(case):
    """Largest position error [m] and largest relative end-tension error of the buoy case."""
    points, ends = _moorpy_buoy(case)
    results = seacable.statics(case)
    position_error = max(
        np.abs(_ours(results, f"bodies/{name}", [f"position_{c}" for c in "xyz"])
               - points[name].r).max()
        for name in ("buoy", "clump")
    )  # fmt: skip
    tension_error = 0.0
    for name, (first, last) in ends.items():
        for end, expected in (("from", first.TA), ("to", last.TB)):
            ours = np.linalg.norm(
                _ours(results, f"lines/{name}", [f"{end}_force_{c}" for c in "xyz"])
            )
            tension_error = max(tension_error, abs(ours / expected - 1))
    return position_error, tension_error


# a first guess near the balance (1 m): from the case's own guess statics does not converge
BUOY_START = {"buoy": [4.0, -8.0, -20.0], "clump": [80.0, -139.0, -97.0]}


def test_buoy_statics_match_moorpy():
    """Positions within 0.5 % of the buoy's depth below the surface (0.1 m), end tensions
    (magnitudes of each line's end forces) within 0.5 %."""
    position_error, tension_error = _buoy_errors(_buoy_case(start=BUOY_START))
    assert position_error < 0.005 * 20.0, position_error
    assert tension_error < 0.005, tension_error


def test_buoy_statics_from_the_case_guess():
    """From the example's own first guesses the statics finds the same balance as from a
    start near it (the bodies' Newton with the lines settled at each trial pose)."""
    far = seacable.statics(_buoy_case()).dataset
    near = seacable.statics(_buoy_case(start=BUOY_START)).dataset
    for body in ("buoy", "clump"):
        for c in "xyz":
            a = far[f"bodies/{body}/position_{c}"].values[0]
            b = near[f"bodies/{body}/position_{c}"].values[0]
            assert abs(a - b) < 1e-6, (body, c, a, b)


def _platform_case(force: float = 0.0, segments: int | None = None, guess=None):
    """The platform example with a constant force along x at ARM above its reference point
    (given as that force and its moment at the reference point), no ramp; ``guess`` (x, y, z
    [m], roll, pitch, yaw [deg]) a first guess of its pose, the stiffness still about 0."""
    base = seacable.load_case(PLATFORM)
    bodies = _dump(base.bodies)
    platform = next(b for b in bodies if b["name"] == "platform")
    forces = []
    for f in platform["external forces"]:
        if f["model"] == "linear_stiffness":
            f = {**f, "equilibrium_position": [0.0, 0.0, 0.0],
                 "equilibrium_orientation_deg": [0.0, 0.0, 0.0]}  # fmt: skip
        if f["model"] != "applied":
            forces.append(f)
    if force:
        forces.append({"model": "applied", "force_x": force, "moment_y": force * ARM})
    platform["external forces"] = forces
    if guess is not None:
        platform["position"], platform["orientation_deg"] = list(guess[:3]), list(guess[3:])
    lines = _dump(base.lines)
    for line in lines:
        line["sections"][0]["segments"] = segments or line["sections"][0]["segments"]
    return derive_case(base, {"bodies": bodies, "lines": lines})


def _moorpy_platform(case, force: float = 0.0):
    """The platform in MoorPy, in balance under ``force`` (free body)."""
    env = case.environment
    rho_g = env.water_density * env.gravity
    platform = next(b for b in case.bodies if b.name == "platform")
    k = next(f for f in platform.external_forces if f.model == "linear_stiffness").diagonal
    assert k is not None and k[3] == k[4] and not any(k[:2]) and not k[5]
    ms = _moorpy_system(case)
    metacentre = platform.centre_of_buoyancy[2] + k[3] / (rho_g * platform.volume)
    body = ms.addBody(0, np.zeros(6), m=platform.mass, v=platform.volume,
                      rCG=platform.centre_of_gravity, AWP=k[2] / rho_g, rM=[0.0, 0.0, metacentre],
                      f6Ext=np.array([force, 0.0, 0.0, 0.0, force * ARM, 0.0]))  # fmt: skip
    points = {}
    for b in case.bodies:
        if b.type == "fixed":
            points[b.name] = ms.addPoint(1, b.position).number
    for name, r in platform.points.items():
        points[f"platform.{name}"] = ms.addPoint(1, r, body=body.number).number
    for line in case.lines:
        ms.addLine(line.sections[0].length, line.sections[0].type, pointA=points[line.from_],
                   pointB=points[line.to])  # fmt: skip
    ms.initialize()
    ms.solveEquilibrium(tol=1e-7, maxIter=2000)
    return ms, body


POSE = ("position_x", "position_y", "position_z", "roll", "pitch", "yaw")


def test_platform_offset_under_a_steady_force_matches_moorpy():
    """100 kN at 30 m above the waterline: surge, heave and pitch within 1 % (sway, roll and
    yaw stay zero). 1 MN would put the platform 136 m off in MoorPy, where the lee line is
    longer than its span plus its rise and lies slack on the seabed (no unique lumped shape)."""
    case = _platform_case(FORCE)  # from the upright pose: 40 m off (statics' homotopy)
    _, body = _moorpy_platform(case, FORCE)
    expected = np.concatenate([body.r6[:3], np.degrees(body.r6[3:])])
    ours = _ours(seacable.statics(case), "bodies/platform", POSE)
    for i in (0, 2, 4):
        assert abs(ours[i] / expected[i] - 1) < 0.01, (POSE[i], ours[i], expected[i])
    for i in (1, 3, 5):
        assert abs(ours[i]) < 1e-6 * abs(expected[0]), (POSE[i], ours[i])


def _stiffnesses(segments: int, span: float | None = None):
    """Ours and MoorPy's lines-only 6x6 at the platform's balance: tangent (MoorPy's analytic),
    or with the translation columns secants over +-``span`` [m] (MoorPy's lines re-solved at
    the same poses)."""
    case = _platform_case(segments=segments)
    ms, body = _moorpy_platform(case)
    body.type = -1  # coupled: its lines' stiffness at its reference point
    ms.initialize()
    expected = ms.getCoupledStiffnessA(lines_only=True)
    if span is not None:
        at = body.r6.copy()
        for j in range(3):
            loads = []
            for sign in (1.0, -1.0):
                body.setPosition(at + sign * span * np.eye(6)[j])
                for line in ms.lineList:
                    line.staticSolve()
                loads.append(body.getForces(lines_only=True))
            expected[:, j] = -(loads[0] - loads[1]) / (2.0 * span)
        body.setPosition(at)
    built = model.build(case)
    ours = statics.mooring_stiffness(built, built.y0, "platform", span=span)
    return ours, expected


def test_platform_mooring_stiffness_rotations_match_moorpy():
    """Roll, pitch and yaw stiffness of the lines within 1 % (70 segments of 10 m)."""
    ours, expected = _stiffnesses(70)
    for i in (3, 4, 5):
        assert abs(ours[i, i] / expected[i, i] - 1) < 0.01, (i, ours[i, i], expected[i, i])
    assert np.allclose(ours, ours.T, rtol=0, atol=1e-3 * np.abs(ours).max())


def test_platform_mooring_secant_stiffness_matches_moorpy():
    """Surge and heave stiffness of the lines as secants over +-5 m, against MoorPy's over the
    same poses: within 0.5 % (70 segments of 10 m). A lumped line's tangent stiffness is a
    sawtooth along the pose (the slope drops each time a node lifts off the seabed: one 10 m
    segment of touchdown travel per ~5 m of heave), -3 % and -7 % from the continuous
    catenary's at this pose and up to +-20 % elsewhere; a secant over one period of it
    averages it out (benchmarks/mooring_stiffness_study.py on branch ``stiffness``: within
    0.2 % of a closed-form catenary's at 70 and 140 segments)."""
    ours, expected = _stiffnesses(70, span=5.0)
    for i in (0, 2):
        assert abs(ours[i, i] / expected[i, i] - 1) < 0.005, (i, ours[i, i], expected[i, i])


def test_the_mooring_stiffness_is_symmetric_where_the_lines_exert_a_moment():
    """Under the 100 kN force the platform's lines exert a pitch moment M on it: the moment's
    own tangent under earth-frame rotations (symmetric=False) is skew by exactly [M x] in its
    rotation block (the generalized force of the rotation vector is J^T M), while its
    translation-rotation blocks agree (-dF/dtheta = -dM/dx transposed: mixed derivatives of
    one potential). The stiffness returned by default, the potential's Hessian, is symmetric
    to round-off and equals the tangent less [M x] / 2."""
    case = _platform_case(FORCE, segments=35)
    built = model.build(case)
    tangent = statics.mooring_stiffness(built, built.y0, "platform", symmetric=False)
    hessian = statics.mooring_stiffness(built, built.y0, "platform")
    b = built.layout.bodies.index("platform")
    m = statics.line_loads(built, built.y0, at_rest=True)[b][3:]
    skew = np.array([[0.0, -m[2], m[1]], [m[2], 0.0, -m[0]], [-m[1], m[0], 0.0]])
    scale = np.sqrt(np.outer(np.abs(np.diag(tangent)), np.abs(np.diag(tangent))))
    assert abs(m[1]) > 1e4  # a pitch moment of the lines: the two forms differ
    np.testing.assert_allclose((tangent - tangent.T)[3:, 3:], skew, rtol=0, atol=1e-6 * abs(m[1]))
    assert np.all(np.abs(tangent[:3, 3:] - tangent[3:, :3].T) <= 1e-6 * scale[:3, 3:])
    assert np.all(np.abs(hessian - hessian.T) <= 1e-6 * scale)
    np.testing.assert_allclose(hessian[3:, 3:], tangent[3:, 3:] - skew / 2, rtol=0,
                               atol=1e-6 * abs(m[1]))  # fmt: skip
    np.testing.assert_array_equal(hessian[:, :3], tangent[:, :3])


def _stiffness_with(heave_stiffness: float | None = None, mass: float | None = None):
    """The platform's lines-only 6x6 (35 segments) held at one pose near its balance (start:
    as_given), with its own waterplane heave stiffness [N/m] or mass [kg] changed."""
    base = _platform_case(segments=35)
    bodies = _dump(base.bodies)
    platform = next(b for b in bodies if b["name"] == "platform")
    platform["position"] = [1.2e-4, 0.0, 0.566]  # m
    for f in platform["external forces"]:
        if f["model"] == "linear_stiffness" and heave_stiffness is not None:
            f["diagonal"][2] = heave_stiffness
    if mass is not None:
        platform["mass"] = mass
    built = model.build(derive_case(base, {"bodies": bodies, "start": "as_given"}))
    return statics.mooring_stiffness(built, built.y0, "platform")


def test_mooring_stiffness_is_the_lines_alone():
    """The lines' stiffness does not see the body's own heave stiffness or mass (to 1e-6 of
    each entry's scale sqrt(K_ii K_jj)): at a moved, held pose the body accelerates under its
    own force models, and the lines' end nodes must not add their mass times that."""
    reference = _stiffness_with()
    scale = np.sqrt(np.outer(np.abs(np.diag(reference)), np.abs(np.diag(reference))))
    for changes in ({"heave_stiffness": 0.0}, {"mass": 2.0e7}):
        changed = _stiffness_with(**changes)
        assert np.all(np.abs(changed - reference) <= 1e-6 * scale), (changes, changed - reference)


def test_mooring_stiffness_refuses_lines_out_of_balance(monkeypatch):
    """Lines left out of balance at a moved pose (here: not re-solved at all) are refused,
    naming the line, instead of giving a stiffness from them."""
    built = model.build(_platform_case(segments=35))
    monkeypatch.setattr(statics, "settle_lines", lambda p, y, **kw: y.copy())
    with pytest.raises(statics.StaticsError, match="line 'line_1' not in balance .* m/s"):
        statics.mooring_stiffness(built, built.y0, "platform")


def test_mooring_stiffness_refuses_a_rigid_segment_line_on_the_body():
    base = _platform_case(segments=35)
    lines = _dump(base.lines)
    lines[0].update({"model": "rigid_segments_3d", "from": lines[0]["to"], "to": lines[0]["from"]})
    deeper = base.environment.model_copy(update={"water_depth": 300.0})  # it hangs to -208 m
    built = model.build(derive_case(base, {"lines": lines, "start": "as_given",
                                           "environment": deeper}))  # fmt: skip
    with pytest.raises(statics.StaticsError, match="rigid-segment line 'line_1'"):
        statics.mooring_stiffness(built, built.y0, "platform")
