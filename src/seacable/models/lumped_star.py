"""Several lumped-mass cables holding one shared body (a star of extensible cables):
parameters, state and outputs. See ``kernels.lumped_star`` for the equations.

Each cable is built as a ``lumped_mass`` cable pinned at the body's position (so that its
initial shape, a catenary or given angles, ends there and starts at rest on that pin), then its
end is freed and becomes the shared body's node.
"""

from dataclasses import dataclass

import numpy as np

from seacable.case import schema
from seacable.errors import CaseError
from seacable.kernels import lumped as lk
from seacable.kernels import lumped_star as ls
from seacable.models import common, lumped_mass, star_3d
from seacable.models.common import add_total_energy, body_loads, shape_width, xyz_variables


@dataclass(frozen=True)
class LumpedStarSystem(star_3d.StarSystem[ls.LumpedStarParams]):
    """The star's parameters (``LumpedStarParams``), initial state, segments per cable, number
    of cables and their names."""


def _chain(case: schema.Case, k: int, body: schema.SharedBody, base_dir):
    """Cable k as a lumped-mass cable pinned at the body's starting position."""
    cable = case.cables[k]
    if cable.model != "lumped_mass":
        raise CaseError(
            f"cables[{k}].model: value '{cable.model}'; the cables on one shared body share one "
            f"model: make it '{case.cables[0].model}' like cables[0] (rigid_segments_3d or "
            "lumped_mass)"
        )
    pinned = schema.PinnedBottom(type="pinned", anchor=body.position)
    single = case.model_copy(
        update={"cables": [cable.model_copy(update={"bottom": pinned})], "bodies": []}
    )
    try:
        return lumped_mass.build(single, base_dir)
    except CaseError as exc:  # name the cable, and the body rather than an anchor
        text = (
            str(exc)
            .replace("cables[0]", f"cables[{k}]")
            .replace(
                f"cables[{k}].bottom.anchor",
                f"cables[{k}].initial (its end, on body '{body.name}')",
            )
        )
        raise CaseError(text) from None


def build(case: schema.Case, base_dir=None) -> LumpedStarSystem:
    """Assemble the star of ``case``: every lumped-mass cable ends on its one shared body."""
    body = case.bodies[0]
    position = np.array(schema.xyz(body.position), dtype=float)
    loads = body_loads(body, case.environment, shape_width(case))
    chains, positions, velocities = [], [], []
    for k in range(len(case.cables)):
        system = _chain(case, k, body, base_dir)
        p, n = system.params, system.n_links
        free = dict(bottom_kind=lk.BOTTOM_FREE, constrained=np.zeros(3))
        if k == 0:  # chain 0's end node carries the body
            point_mass = p.point_mass.copy()
            point_mass[n] += loads.mass
            wider = loads.shape.size - p.node_shape.shape[1]  # >= 0: the case's widest
            shapes = np.pad(p.node_shape, ((0, 0), (0, wider)))
            node_added, buoyancy = p.node_added.copy(), p.node_buoyancy.copy()
            shapes[n], node_added[n], buoyancy[n] = loads.shape, loads.added, loads.buoyancy
            free.update(
                body_mass=np.ascontiguousarray(loads.mass, dtype=float),
                point_mass=point_mass,
                body_wet_weight=float(loads.wet_weight),
                body_drag=np.ascontiguousarray(loads.drag, dtype=float),
                node_shape=shapes,
                node_added=node_added,
                node_buoyancy=buoyancy,
            )
        chains.append(p._replace(**free))
        nodes = system.y0[: 3 * (n + 1)]
        positions.append(nodes[: 3 * n])
        velocities.append(system.y0[3 * (n + 1) : 3 * (n + 1) + 3 * n])
    y0 = np.concatenate([*positions, position, *velocities, np.zeros(3)])
    params = ls.LumpedStarParams(chains=tuple(chains), n=case.cables[0].links)
    names = tuple(c.name for c in case.cables)
    return LumpedStarSystem(params, y0, case.cables[0].links, len(chains), names)


VARIABLES = {
    **xyz_variables("node", ("time", "cable", "node"), "m", "node position"),
    "tension": (("time", "cable", "segment"), "N", "axial tension of the segment (no compression)"),
    **xyz_variables("top_force", ("time", "cable"), "N", "force of each cable on its top"),
    **xyz_variables("bottom_force", ("time", "cable"), "N", "force of each cable on the body"),
    **xyz_variables("body", ("time",), "m", "position of the shared body"),
    **xyz_variables("body_velocity", ("time",), "m/s", "velocity of the shared body"),
    **xyz_variables("body_acceleration", ("time",), "m/s2", "acceleration of the shared body"),
    "kinetic_energy": (("time",), "J", "kinetic energy of the cables and the body"),
    "gravity_potential_energy": (("time",), "J", "potential energy of apparent weights"),
    "elastic_energy": (("time",), "J", "axial strain energy, bending and seabed springs"),
    "total_energy": (("time",), "J", "kinetic + gravity potential + elastic energy"),
}

RATE_WHAT = ("node (counted over the cables one after another)", "speed", "m/s", 0)
NEWTON = False  # the implicit schemes run systems of bodies and lines only

sizes = star_3d.sizes
coords = star_3d.coords


def workspace(system: LumpedStarSystem) -> ls.StarWork:
    return ls.make_workspace(system.cables, system.n_links)


def shortest_segment(system: LumpedStarSystem) -> float:
    return float(min(c.length.min() for c in system.params.chains))


def rows(times, states, system: LumpedStarSystem, w) -> tuple[dict, int]:
    m, k, n = len(times), system.cables, system.n_links
    nodes = np.empty((m, k, n + 1, 3))
    tension = np.empty((m, k, n))
    scalars = np.empty((m, k, lk.N_SCALARS))
    body_acc = np.empty((m, 3))
    status = ls.outputs_chunk(times, states, system.params, w, nodes, tension, scalars, body_acc)
    out = {"time": times, "tension": tension}
    nq = states.shape[1] // 2
    hub = 3 * n * k
    for c, a in enumerate("xyz"):
        out[f"node_{a}"] = nodes[:, :, :, c]
        out[f"top_force_{a}"] = scalars[:, :, c]
        out[f"bottom_force_{a}"] = scalars[:, :, 3 + c]
        out[f"body_{a}"] = states[:, hub + c]
        out[f"body_velocity_{a}"] = states[:, nq + hub + c]
        out[f"body_acceleration_{a}"] = body_acc[:, c]
    for j, name in enumerate(("kinetic_energy", "gravity_potential_energy", "elastic_energy")):
        out[name] = scalars[:, :, 6 + j].sum(axis=1)
    return add_total_energy(out), status


DAMPING_ADVICE = common.AXIAL_DAMPING_ADVICE  # divergence messages


def state_scale(case: schema.Case, system: LumpedStarSystem) -> np.ndarray:
    """Typical magnitude of each state (``common.state_scale``): every coordinate (the body's
    too) the first cable's length."""
    cable = case.cables[0]
    positions = np.full(len(system.y0) // 2, common.cable_length(cable))
    return common.state_scale(cable, case.environment, positions)


def rates(system: LumpedStarSystem, y) -> np.ndarray:
    """Speed of every node [m/s] (the tops included), cable after cable, the body last."""
    return np.linalg.norm(y[len(y) // 2 :].reshape(-1, 3), axis=1)


def node_block(system: LumpedStarSystem) -> int:
    """Variables per node (the stiff integrators' Jacobian follows ``node_graph``)."""
    return 3


def node_graph(system: LumpedStarSystem) -> list[np.ndarray]:
    """Nodes each node's acceleration depends on: its neighbours along its cable (two with
    bending), a cable's last nodes and the body each other (SciPy's sparse Jacobian; CVODE's
    is dense)."""
    k, n = system.cables, system.n_links
    body = k * n
    reach = 2 if any(np.any(c.bend_stiffness > 0.0) for c in system.params.chains) else 1
    graph: list[list[int]] = [[] for _ in range(body + 1)]
    for c in range(k):
        # cable c's nodes in the star's order, its end being the body
        order = [*range(c * n, c * n + n), body]
        for j, i in enumerate(order):
            graph[i].extend(order[max(0, j - reach) : j + reach + 1])
    return [np.unique(near) for near in graph]


def fastest_frequency(system: LumpedStarSystem) -> tuple[float, str]:
    best = (0.0, "")
    for j, chain in enumerate(system.params.chains):
        single = lumped_mass.LumpedSystem(chain, np.zeros(lk.state_size(chain.n)), chain.n, 0.0)
        omega, what = lumped_mass.fastest_frequency(single)
        if omega > best[0]:
            best = (omega, f"cable {system.names[j]}: {what}")
    return best
