"""What the run loop (``simulation``) reaches of a system of bodies and lines: its build, its
output variables per group (``bodies/<name>``, ``lines/<name>``), its output rows, the scales and
frequencies the integrators' defaults and warnings use."""

import math

import numpy as np
from scipy import sparse

from seacable.case import system as sch
from seacable.system import coordinates, kernel, outputs, statics, topology
from seacable.system import rigid as rigid_kind
from seacable.system.assemble import BuiltSystem
from seacable.system.assemble import build as _assemble
from seacable.system.initial import initial_state

RATE_WHAT = ("component", "speed", "m/s", 1)  # what ``rates`` measures (divergence messages)
NEWTON = False  # the implicit schemes do not serve systems yet
DAMPING_ADVICE = "add axial damping (line_types[k].axial_damping_ratio, e.g. 0.8)"
AXES = "xyz"


def build(case: sch.SystemCase, base_dir=None) -> BuiltSystem:
    """Parameters and initial state: lines at their static shape, and with ``start: static``
    every free body at its static equilibrium too (the velocities the case gives are kept)."""
    built = _assemble(case, base_dir)
    if case.start == "static":
        topology.check_held(case)
    y0, params = initial_state(built)
    built = BuiltSystem(params=params, y0=built.y0, layout=built.layout, case=case)
    if case.start == "static":
        velocities = y0[built.params.n_q :].copy()
        y0 = statics.equilibrium(built, y0)
        y0[built.params.n_q :] = velocities
    return BuiltSystem(params=built.params, y0=y0, layout=built.layout, case=case)


def workspace(system: BuiltSystem) -> kernel.SystemWork:
    return kernel.make_work(system.params)


def _body_variables(body) -> dict:
    out = {}
    for c in AXES:
        out[f"position_{c}"] = (("time",), "m", f"position of the reference point, {c}")
    if not isinstance(body, sch.PointBody):
        for angle in ("roll", "pitch", "yaw"):
            out[angle] = (("time",), "degree", f"{angle} (R = Rz(yaw) Ry(pitch) Rx(roll))")
    if not isinstance(body, sch.FixedBody):
        for c in AXES:
            out[f"velocity_{c}"] = (("time",), "m/s", f"velocity of the reference point, {c}")
    if isinstance(body, sch.RigidBody | sch.ImposedBody):
        for c in AXES:
            out[f"angular_velocity_{c}"] = (("time",), "rad/s", f"angular velocity, {c}")
    for c in AXES:
        out[f"line_force_{c}"] = (("time",), "N", f"force of the lines and ties on the body, {c}")
    if not isinstance(body, sch.PointBody):
        for c in AXES:
            out[f"line_moment_{c}"] = (
                ("time",), "N m",
                f"moment of the lines and ties about the reference point, {c}",
            )  # fmt: skip
    return out


def _line_variables(tension: str) -> dict:
    out: dict[str, tuple[tuple[str, ...], str, str]] = {
        f"node_{c}": (("time", "node"), "m", f"node position, {c}") for c in AXES
    }
    out["tension"] = (("time", "segment"), "N", tension)
    for end in ("from", "to"):
        for c in AXES:
            out[f"{end}_force_{c}"] = (
                ("time",), "N", f"force of the line on its '{end}' point, {c}",
            )  # fmt: skip
    return out


def _rigid_variables(system: BuiltSystem, li: int) -> dict:
    p = system.params
    out = _line_variables(RIGID_TENSION)
    if p.rs_kind[li] == rigid_kind.PLANAR:
        out["angle"] = (("time", "segment"), "rad",
                        "link angle from the downward vertical, positive towards +x")  # fmt: skip
        out["angular_velocity"] = (("time", "segment"), "rad/s", "link angular velocity")
    else:
        for c in AXES:
            out[f"direction_{c}"] = (
                ("time", "segment"),
                "1",
                f"unit vector along the segment, {c}",
            )
        out["angular_rate"] = (("time", "segment"), "rad/s", "rate of turn of the segment")
    if p.rs_held[li].any():
        out["constraint_error"] = (("time",), "m", "distance of the held end from where it is held")
    return out


LUMPED_TENSION = "axial tension of the segment (no compression)"
RIGID_TENSION = "axial force at the segment's centre (positive pulling, negative compressed)"
TIE_VARIABLES = {
    "tension": (("time",), "N", "tension of the tie (zero when slack)"),
    "distance": (("time",), "m", "distance between the tie's points"),
    **{f"{end}_{c}": (("time",), "m", f"position of the '{end}' point, {c}")
       for end in ("from", "to") for c in AXES},
}  # fmt: skip


ENERGY_VARIABLES = {
    "kinetic_energy": (("time",), "J", "kinetic energy of bodies and line nodes (added mass in)"),
    "gravity_potential_energy": (("time",), "J", "potential of gravity and buoyancy"),
    "elastic_energy": (("time",), "J", "axial, bending, seabed, tie and linear-spring energy"),
    "total_energy": (("time",), "J", "kinetic + gravity potential + elastic energy"),
}


def variables(system: BuiltSystem) -> dict:
    """Every output variable, its name prefixed by its group (the energies at the top)."""
    out = dict(ENERGY_VARIABLES)
    for body in system.case.bodies:
        for name, spec in _body_variables(body).items():
            out[f"bodies/{body.name}/{name}"] = spec
    for line in system.layout.lines:
        for name, spec in _line_variables(LUMPED_TENSION).items():
            out[f"lines/{line}/{name}"] = spec
    for li, line in enumerate(system.layout.rigid):
        for name, spec in _rigid_variables(system, li).items():
            out[f"lines/{line}/{name}"] = spec
    for line in system.layout.ties:
        for name, spec in TIE_VARIABLES.items():
            out[f"lines/{line}/{name}"] = spec
    return out


def sizes(system: BuiltSystem) -> dict:
    p = system.params
    out = {}
    for li, line in enumerate(system.layout.lines):
        out[f"lines/{line}/segment"] = int(p.line_n[li])
        out[f"lines/{line}/node"] = int(p.line_n[li]) + 1
    for li, line in enumerate(system.layout.rigid):
        out[f"lines/{line}/segment"] = int(p.rs_n[li])
        out[f"lines/{line}/node"] = int(p.rs_n[li]) + 1
    return out


def coords(system: BuiltSystem) -> dict:
    p = system.params
    out = {}
    for li, line in enumerate(system.layout.lines):
        n, s0 = int(p.line_n[li]), int(p.line_seg[li])
        arc = np.concatenate([[0.0], np.cumsum(p.seg_length[s0 : s0 + n])])
        out[f"lines/{line}/arc_length"] = (
            "node", arc, "m", "unstretched arc length from the 'from' end",
        )  # fmt: skip
    for li, line in enumerate(system.layout.rigid):
        n, s0 = int(p.rs_n[li]), int(p.rs_seg[li])
        arc = np.concatenate([[0.0], np.cumsum(p.rs_length[s0 : s0 + n])])
        out[f"lines/{line}/arc_length"] = ("node", arc, "m", "arc length from the 'from' end")
    return out


BODY_NAMES = (
    *(f"position_{c}" for c in AXES), "roll", "pitch", "yaw",
    *(f"velocity_{c}" for c in AXES), *(f"angular_velocity_{c}" for c in AXES),
    *(f"line_force_{c}" for c in AXES), *(f"line_moment_{c}" for c in AXES),
)  # fmt: skip


def rows(times, states, system: BuiltSystem, w) -> tuple[dict, int]:
    p = system.params
    m = len(times)
    nb, nl, nt = len(p.body_kind), len(p.line_n), len(p.tie_from)
    bodies = np.empty((m, nb, outputs.BODY_COLUMNS))
    nodes = np.empty((m, len(p.node_mass), 3))
    tension = np.empty((m, len(p.seg_length)))
    ends = np.empty((m, nl, 2, 3))
    ties = np.empty((m, nt, 8))
    energy = np.empty((m, 3))
    rigid = outputs.rigid_rows(p, m)
    status = outputs.outputs_chunk(
        times, states, p, w, bodies, nodes, tension, ends, ties, energy, rigid
    )
    out: dict = {"time": times}
    for k, name in enumerate(list(ENERGY_VARIABLES)[:3]):
        out[name] = energy[:, k]
    out["total_energy"] = energy.sum(axis=1)
    for b, body in enumerate(system.case.bodies):
        for k, name in enumerate(BODY_NAMES):
            out[f"bodies/{body.name}/{name}"] = bodies[:, b, k]
    for li, line in enumerate(system.layout.lines):
        n, c0, s0 = int(p.line_n[li]), int(p.line_node[li]), int(p.line_seg[li])
        for c, axis in enumerate(AXES):
            out[f"lines/{line}/node_{axis}"] = nodes[:, c0 : c0 + n + 1, c]
            out[f"lines/{line}/from_force_{axis}"] = ends[:, li, 0, c]
            out[f"lines/{line}/to_force_{axis}"] = ends[:, li, 1, c]
        out[f"lines/{line}/tension"] = tension[:, s0 : s0 + n]
    for li, line in enumerate(system.layout.rigid):
        n, c0, s0 = int(p.rs_n[li]), int(p.rs_node[li]), int(p.rs_seg[li])
        for c, axis in enumerate(AXES):
            out[f"lines/{line}/node_{axis}"] = rigid[0][:, c0 : c0 + n + 1, c]
            out[f"lines/{line}/from_force_{axis}"] = rigid[2][:, li, 0, c]
            out[f"lines/{line}/to_force_{axis}"] = rigid[2][:, li, 1, c]
        out[f"lines/{line}/tension"] = rigid[1][:, s0 : s0 + n]
        q, v = int(p.rs_q[li]), int(p.rs_v[li])
        if p.rs_kind[li] == rigid_kind.PLANAR:
            out[f"lines/{line}/angle"] = states[:, q : q + n]
            out[f"lines/{line}/angular_velocity"] = states[:, v : v + n]
        else:
            e = states[:, q : q + 3 * n].reshape(m, n, 3)
            for c, axis in enumerate(AXES):
                out[f"lines/{line}/direction_{axis}"] = e[:, :, c]
            rates = states[:, v : v + 3 * n].reshape(m, n, 3)
            out[f"lines/{line}/angular_rate"] = np.linalg.norm(rates, axis=2)
        if p.rs_held[li].any():
            out[f"lines/{line}/constraint_error"] = rigid[3][:, li]
    for k, line in enumerate(system.layout.ties):
        out[f"lines/{line}/tension"] = ties[:, k, 0]
        out[f"lines/{line}/distance"] = ties[:, k, 1]
        for c, axis in enumerate(AXES):
            out[f"lines/{line}/from_{axis}"] = ties[:, k, 2 + c]
            out[f"lines/{line}/to_{axis}"] = ties[:, k, 5 + c]
    return out, status


def _size(system: BuiltSystem) -> float:
    """A length scale of the system [m]: its lines' total length, else 1 m."""
    p = system.params
    total = (p.seg_length.sum() if len(p.line_n) else 0.0) + (
        p.rs_length.sum() if len(p.rs_n) else 0.0)  # fmt: skip
    return float(max(1.0, total))


def state_scale(case, system: BuiltSystem) -> np.ndarray:
    """Typical magnitude of each state: positions the system's length scale L, quaternions,
    rigid segments' directors and links' angles 1, velocities sqrt(g L) (angular, and the
    directors' and angles' rates: sqrt(g / L))."""
    p = system.params
    size = _size(system)
    q = np.full(p.n_q, size)
    v = np.full(p.n_v, math.sqrt(p.gravity * size))
    turning = math.sqrt(p.gravity / size)
    for b in range(len(p.body_kind)):
        if p.body_q[b] >= 0 and p.body_rigid[b]:
            q[p.body_q[b] + 3 : p.body_q[b] + 7] = 1.0
            v[p.body_v[b] + 3 : p.body_v[b] + 6] = turning
    for li in range(len(p.rs_n)):
        width = (3 if p.rs_kind[li] == rigid_kind.SEGMENTS_3D else 1) * int(p.rs_n[li])
        q[p.rs_q[li] : p.rs_q[li] + width] = 1.0
        v[p.rs_v[li] - p.n_q : p.rs_v[li] - p.n_q + width] = turning
    return np.concatenate([q, v])


def positions(system: BuiltSystem) -> int:
    return int(system.params.n_q)


def rates(system: BuiltSystem, y) -> np.ndarray:
    """Speed of every dynamic body and interior node [m/s] (divergence messages)."""
    p = system.params
    v = y[p.n_q :]
    return np.abs(v) if len(v) else np.zeros(1)


def fastest_frequency(system: BuiltSystem) -> tuple[float, str]:
    """Fastest axial mode of any segment between two nodes: 2 sqrt(EA / (m l))."""
    p = system.params
    if not len(p.line_n):
        return 1.0, "no line"
    best, what = 0.0, ""
    for li, line in enumerate(system.layout.lines):
        n, s0, c0 = int(p.line_n[li]), int(p.line_seg[li]), int(p.line_node[li])
        mass = np.minimum(p.node_mass[c0 : c0 + n], p.node_mass[c0 + 1 : c0 + n + 1])
        mass = mass + 0.5 * p.seg_added_mass[s0 : s0 + n]
        omega = 2.0 * np.sqrt(p.seg_stiffness[s0 : s0 + n] / (mass * p.seg_length[s0 : s0 + n]))
        i = int(np.argmax(omega))
        if omega[i] > best:
            best = float(omega[i])
            what = f"axial waves on segment {i} of line '{line}' ({p.seg_length[s0 + i]:.3g} m)"
    return best, what


def jacobian_sparsity(system: BuiltSystem) -> sparse.csc_matrix:
    """The pattern of d(ydot)/dy (SciPy's stiff integrators colour its columns): positions
    move with their velocities (a quaternion with its angular velocity and itself), every
    acceleration depends on the positions and velocities of the coordinates
    ``coordinates.pattern`` couples it to."""
    p = system.params
    coords = coordinates.coordinates(p)
    coupled = coordinates.pattern(p, coords).tocoo()
    n = p.n_q + p.n_v
    rows: list[int] = []
    cols: list[int] = []

    size = {1: 4, 3: 3}  # a quaternion, a director (and its rate)

    def positions(i: int) -> range:
        return range(coords.q[i], coords.q[i] + size.get(int(coords.kind[i]), 1))

    def velocities(i: int) -> range:
        return range(coords.v[i], coords.v[i] + (3 if coords.kind[i] == 3 else 1))

    for i in range(len(coords.kind)):
        for k in positions(i):  # dq/dt from v (a quaternion: from omega and itself)
            rows.extend([k] * len(velocities(i)))
            cols.extend(velocities(i))
            if coords.kind[i] in size:
                rows.extend([k] * len(positions(i)))
                cols.extend(positions(i))
    for i, j in zip(coupled.row, coupled.col, strict=True):
        for v in velocities(i):
            for k in (*positions(j), *velocities(j)):
                rows.append(v)
                cols.append(k)
    return sparse.csc_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))


def shortest_segment(system: BuiltSystem) -> float:
    p = system.params
    lengths = [p.seg_length[: int(p.line_n.sum())], p.rs_length[: int(p.rs_n.sum())]]
    every = np.concatenate(lengths)
    return float(every.min()) if every.size else 1.0
