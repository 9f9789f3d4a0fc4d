"""Poth's string pendulum in natural variables (strain and tangent direction): parameters,
initial state, outputs. See ``kernels.natural`` for the equations.

A planar extensible string without bending stiffness hangs from a fixed pivot, carries a point
mass at its end and moves in air under gravity (the paper's problem): ``model: natural_string``
with ``tangent: angle`` (eps, phi) or ``tangent: cartesian`` (eps, t_x, t_z). Its displacement
form is the lumped-mass model with the same top, body and ``environment.in_air``.
"""

import math
from dataclasses import dataclass

import numpy as np

from seacable.case import schema
from seacable.errors import CaseError
from seacable.kernels import natural as nk
from seacable.models import common
from seacable.models.common import add_total_energy


@dataclass(frozen=True)
class NaturalSystem:
    params: nk.NaturalParams
    y0: np.ndarray
    n_links: int
    top: tuple[float, float]


def _check(case: schema.Case) -> None:
    cable = case.cables[0]
    where = "cables[0]"
    if not case.environment.in_air:
        raise CaseError(
            f"{where}.model: natural_string is Poth's string pendulum in air (gravity only); set "
            "environment.in_air: true, or use model: lumped_mass for a cable in water"
        )
    if cable.axial_stiffness is None:
        raise CaseError(f"{where}.axial_stiffness: a natural_string needs EA [N]")
    if not isinstance(cable.top, schema.FixedTop):
        raise CaseError(f"{where}.top: a natural_string hangs from a fixed pivot (type: fixed)")
    bottom = cable.bottom
    if not isinstance(bottom, schema.FreeBottom) or bottom.body.mass <= 0.0:
        raise CaseError(
            f"{where}.bottom: a natural_string carries an end mass: type free with body.mass > 0"
        )
    if cable.link_lengths is not None or cable.link_masses is not None:
        raise CaseError(f"{where}: a natural_string is uniform: give length and mass_per_length")
    if cable.initial.shape not in ("arc", "angles"):
        raise CaseError(f"{where}.initial: a natural_string starts unstretched from arc or angles")


def build(case: schema.Case, base_dir=None) -> NaturalSystem:
    _check(case)
    cable = case.cables[0]
    top, bottom = cable.top, cable.bottom
    # narrowed as _check ensured: a fixed top, a free bottom carrying the end mass, EA given
    assert isinstance(top, schema.FixedTop) and isinstance(bottom, schema.FreeBottom)
    assert cable.axial_stiffness is not None
    n = cable.links
    length = float(cable.lengths().sum())
    mu = float(cable.masses().sum()) / length
    cartesian = cable.tangent == "cartesian"
    params = nk.NaturalParams(
        n=n,
        length=length,
        mu=mu,
        end_mass=float(bottom.body.mass),
        axial_stiffness=float(cable.axial_stiffness),
        axial_damping=float(cable.axial_damping_time or 0.0),
        slack_allowed=1,
        gravity=float(case.environment.gravity),
        cartesian=1 if cartesian else 0,
    )
    links = cable.initial.angles(n)  # one per element, from the downward vertical
    nodes = np.empty(n + 1)
    nodes[0], nodes[-1] = links[0], links[-1]
    nodes[1:-1] = 0.5 * (links[:-1] + links[1:])
    b = nk.block(params)
    y0 = np.zeros(nk.state_size(n, cartesian))
    if cartesian:
        y0[1 : 3 * (n + 1) : 3] = np.sin(nodes)
        y0[2 : 3 * (n + 1) : 3] = -np.cos(nodes)
    else:
        y0[1 : b * (n + 1) : 2] = nodes
    x, _, z = schema.xyz(top.position)
    return NaturalSystem(params=params, y0=y0, n_links=n, top=(x, z))


VARIABLES = {
    "node_x": (("time", "node"), "m", "node position, x (trapezoidal integral of the tangent)"),
    "node_z": (("time", "node"), "m", "node position, z"),
    "strain": (("time", "node"), "1", "axial strain at the node"),
    "tension": (("time", "node"), "N", "axial tension at the node (no compression)"),
    "end_x": (("time",), "m", "end mass position, x"),
    "end_z": (("time",), "m", "end mass position, z"),
    "kinetic_energy": (("time",), "J", "kinetic energy (trapezoidal quadrature)"),
    "gravity_potential_energy": (("time",), "J", "potential energy of gravity"),
    "elastic_energy": (("time",), "J", "axial strain energy (trapezoidal quadrature)"),
    "total_energy": (("time",), "J", "kinetic + gravity potential + elastic energy"),
}

RATE_WHAT = ("node", "strain rate", "1/s", 0)
NEWTON = False  # the implicit schemes run systems of bodies and lines only


def shortest_segment(system: NaturalSystem) -> float:
    """Newton's tolerance is a strain here (the variables are strains and directions)."""
    return 1.0


def sizes(system: NaturalSystem) -> dict:
    return {"node": system.n_links + 1}


def coords(system: NaturalSystem) -> dict:
    arc = np.linspace(0.0, system.params.length, system.n_links + 1)
    return {
        "node": ("node", np.arange(system.n_links + 1, dtype=float), "1", "node index (0: pivot)"),
        "arc_length": ("node", arc, "m", "unstretched arc length from the pivot"),
    }


def workspace(system: NaturalSystem):
    return nk.make_workspace(system.n_links)


def rows(times, states, system: NaturalSystem, w) -> tuple[dict, int]:
    n = system.n_links
    m = len(times)
    nodes = np.empty((m, n + 1, 2))
    strain = np.empty((m, n + 1))
    tension = np.empty((m, n + 1))
    scalars = np.empty((m, nk.N_SCALARS))
    status = nk.outputs_chunk(times, states, system.params, w, nodes, strain, tension, scalars)
    x0, z0 = system.top
    out = {
        "time": times,
        "node_x": x0 + nodes[:, :, 0],
        "node_z": z0 + nodes[:, :, 1],
        "strain": strain,
        "tension": tension,
    }
    for k, name in enumerate(nk.SCALAR_NAMES):
        out[name] = scalars[:, k]
    out["end_x"] = out["end_x"] + x0
    out["end_z"] = out["end_z"] + z0
    # potential energy relative to the pivot's level
    return add_total_energy(out), status


DAMPING_ADVICE = common.AXIAL_DAMPING_ADVICE  # divergence messages


def state_scale(case: schema.Case, system: NaturalSystem) -> np.ndarray:
    """Typical magnitude of each state (``common.state_scale``): strains the static strain of
    the cable's weight, weight / EA, angles and tangent components 1."""
    cable = case.cables[0]
    b = nk.block(system.params)
    strain = (
        float(np.sum(cable.masses())) * case.environment.gravity / system.params.axial_stiffness
    )
    per_node = np.ones(b)
    per_node[0] = strain
    positions = np.tile(per_node, system.n_links + 1)
    return common.state_scale(cable, case.environment, positions)


def rates(system: NaturalSystem, y) -> np.ndarray:
    b = nk.block(system.params)
    v0 = b * (system.n_links + 1)
    return np.abs(y[v0::b])


def fastest_frequency(system: NaturalSystem) -> tuple[float, str]:
    """Axial mode of the finest grid: 2 (k / l) sqrt(EA / mu) (the Nyquist axial wave)."""
    p = system.params
    omega = 2.0 * p.n / p.length * math.sqrt(p.axial_stiffness / p.mu)
    return omega, f"axial waves on the {p.n}-element grid (EA {p.axial_stiffness:.3g} N)"


def node_block(system: NaturalSystem) -> int:
    """Variables per node: the stiff integrators' Jacobian is node-neighbour structured."""
    return nk.block(system.params)
