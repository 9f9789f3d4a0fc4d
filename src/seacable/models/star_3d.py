"""Several 3D cables holding one shared body (a "star"): parameters, state and outputs.

Each cable is built as a ``rigid_segments_3d`` cable whose lower end is closed (held), then the
closing force comes from the shared body's dynamics (``kernels.star3d``). The body is a point:
mass, buoyancy, added mass and drag per axis.
"""

from dataclasses import dataclass
from typing import Generic, TypeVar

import numpy as np

from seacable.case import schema
from seacable.errors import CaseError
from seacable.kernels import chain3d as c3
from seacable.kernels import lumped_star, star3d
from seacable.models import common
from seacable.models import rigid_segments_3d as seg
from seacable.models.common import body_loads, current_arrays, shape_width

# the kernel's parameter tuple: star3d.StarParams here, kernels.lumped_star's for lumped cables
ParamsT = TypeVar("ParamsT", covariant=True)


@dataclass(frozen=True)
class StarSystem(Generic[ParamsT]):
    params: ParamsT
    y0: np.ndarray
    n_links: int  # segments per cable (all equal)
    cables: int
    names: tuple[str, ...]


AnyStar = StarSystem[star3d.StarParams | lumped_star.LumpedStarParams]  # sizes, coords: both


def _body(case: schema.Case) -> schema.SharedBody:
    return case.bodies[0]


def build(case: schema.Case, base_dir=None) -> StarSystem[star3d.StarParams]:
    """Assemble the star of ``case``: every cable attached to its one shared body."""
    body = _body(case)
    position = np.array(schema.xyz(body.position), dtype=float)
    chains, states = [], []
    for k, cable in enumerate(case.cables):
        if cable.model != "rigid_segments_3d":
            raise CaseError(
                f"cables[{k}].model: value '{cable.model}'; the cables on one shared body share "
                f"one model: make it '{case.cables[0].model}' like cables[0] (rigid_segments_3d "
                "or lumped_mass)"
            )
        held = cable.model_copy(update={"bottom": schema.PinnedBottom(type="pinned")})
        single = case.model_copy(update={"cables": [held], "bodies": []})
        single._base_dir = base_dir
        system = seg.build(single, base_dir)
        end = seg.end_position(system.params, system.y0)
        gap = float(np.linalg.norm(end - position))
        if gap > 1e-3:
            raise CaseError(
                f"cables[{k}]: its initial shape ends {gap:.3f} m from body '{body.name}' at "
                f"{position.tolist()} (it ends at {np.round(end, 3).tolist()}); change the "
                "cable's initial shape or top position, or the body's position"
            )
        chains.append(system.params._replace(pin=position.copy()))
        states.append(system.y0)
    env = case.environment
    loads = body_loads(body, env, shape_width(case))
    offsets = np.concatenate([[0], np.cumsum([len(s) for s in states])]).astype(np.int64)
    current_z, current_u, current_v = current_arrays(env)
    params = star3d.StarParams(
        chains=tuple(chains),
        offsets=offsets,
        body_mass=np.ascontiguousarray(loads.mass, dtype=float),
        body_wet_weight=float(loads.wet_weight),
        body_drag=np.ascontiguousarray(loads.drag, dtype=float),
        body_shape=np.ascontiguousarray(loads.shape, dtype=float),
        body_added=np.ascontiguousarray(loads.added, dtype=float),
        body_buoyancy=float(loads.buoyancy),
        current_z=current_z,
        current_u=current_u,
        current_v=current_v,
        stabilization_frequency=float(case.simulation.constraint_stabilization_frequency),
    )
    y0 = np.concatenate([*states, position, np.zeros(3)])
    names = tuple(c.name for c in case.cables)
    return StarSystem(params, y0, case.cables[0].links, len(chains), names)


VARIABLES = {
    **{f"node_{a}": (("time", "cable", "node"), "m", f"node position, {a}") for a in "xyz"},
    "tension": (("time", "cable", "segment"), "N", "axial tension at the segment centre"),
    **{
        f"top_force_{a}": (
            ("time", "cable"),
            "N",
            f"force of each cable on its top attachment (an anchor), {a}",
        )
        for a in "xyz"
    },  # fmt: skip
    **{f"body_{a}": (("time",), "m", f"position of the shared body, {a}") for a in "xyz"},
    **{
        f"body_velocity_{a}": (("time",), "m/s", f"velocity of the shared body, {a}") for a in "xyz"
    },
    "angular_rate": (("time", "cable", "segment"), "rad/s", "rate of turn of the segment"),
}


def workspace(system: StarSystem[star3d.StarParams]):
    return tuple(c3.make_workspace(system.n_links) for _ in range(system.cables))


def sizes(system: AnyStar) -> dict:
    return {"segment": system.n_links, "node": system.n_links + 1, "cable": system.cables}


def coords(system: AnyStar) -> dict:
    lengths = system.params.chains[0].length
    return {
        "segment": ("segment", np.arange(system.n_links, dtype=float), "1", "segment index"),
        "node": ("node", np.arange(system.n_links + 1, dtype=float), "1", "node index"),
        "cable": ("cable", np.arange(system.cables, dtype=float), "1", "cable index"),
        "arc_length": (
            "node",
            np.concatenate([[0.0], np.cumsum(lengths)]),
            "m",
            "arc length of the node from the top (first cable)",
        ),  # fmt: skip
    }


def rows(times, states, system: StarSystem[star3d.StarParams], w) -> tuple[dict, int]:
    m = len(times)
    k = system.cables
    n = system.n_links
    nodes = np.empty((m, k, n + 1, 3))
    tension = np.empty((m, k, n))
    scalars = np.empty((m, k, c3.N_SCALARS))
    anchor = np.empty((m, k, 3))
    status = star3d.outputs_chunk(times, states, system.params, w, nodes, tension, scalars, anchor)
    out = {"time": times, "tension": tension}
    for c, a in enumerate("xyz"):
        out[f"node_{a}"] = nodes[:, :, :, c]
        out[f"top_force_{a}"] = anchor[:, :, c]
    b0 = system.params.offsets[-1]
    for c, a in enumerate("xyz"):
        out[f"body_{a}"] = states[:, b0 + c]
        out[f"body_velocity_{a}"] = states[:, b0 + 3 + c]
    rates_ = np.empty((m, k, n))
    for j in range(k):
        o = system.params.offsets[j]
        u = states[:, o + 3 * n + 1 : o + 6 * n + 1].reshape(m, n, 3)
        rates_[:, j] = np.linalg.norm(u, axis=2)
    out["angular_rate"] = rates_
    return out, status


DAMPING_ADVICE = common.JOINT_DAMPING_ADVICE  # divergence messages


def state_scale(case: schema.Case, system: StarSystem[star3d.StarParams]) -> np.ndarray:
    """Typical magnitude of each state (``common.state_scale``): each cable's block as the
    single cable's, then the body's coordinates at the first cable's length."""
    single = [seg.state_scale(case.model_copy(update={"cables": [c]}), system) for c in case.cables]
    body = np.full(3, common.cable_length(case.cables[0]))
    return np.concatenate([*single, common.state_scale(case.cables[0], case.environment, body)])


RATE_WHAT = ("segment (counted over the cables one after another)", "angular rate", "rad/s", 0)
NEWTON = False  # the implicit schemes run systems of bodies and lines only


def shortest_segment(system: StarSystem[star3d.StarParams]) -> float:
    """Shortest segment of any cable [m]."""
    return float(min(np.min(chain.length) for chain in system.params.chains))


def rates(system: StarSystem[star3d.StarParams], y) -> np.ndarray:
    n = system.n_links
    parts = []
    for j in range(system.cables):
        o = system.params.offsets[j]
        parts.append(np.linalg.norm(y[o + 3 * n + 1 : o + 6 * n + 1].reshape(n, 3), axis=1))
    return np.concatenate(parts)


def fastest_frequency(system: StarSystem[star3d.StarParams]) -> tuple[float, str]:
    best = (0.0, "")
    for j, chain in enumerate(system.params.chains):
        size = c3.state_size(chain.n)
        single = seg.System3D(chain, np.zeros(size), chain.n, 0.0)
        omega, what = seg.fastest_frequency(single)
        if omega > best[0]:
            best = (omega, f"cable {system.names[j]}: {what}")
    return best
