"""Compiled rates of the lumped-mass lines of a system (kernels.lumped's equations, through
its shared ``segment_loads``, ``seabed_loads`` and ``bending``).

A line of n segments has nodes 0..n; its end nodes 0 and n follow the points ``from`` and
``to`` of their bodies (as MoorDyn's coupled points do) and give those bodies their mass and
their loads (``end_mass_force``); its n - 1 interior nodes are states: positions at
``y[q + 3 (j - 1) + c]``, velocities at ``y[v + 3 (j - 1) + c]`` for j = 1 .. n - 1.
"""

from numba import njit

from seacable.kernels import lumped as lk
from seacable.kernels.jit import JIT

F_ROW = lk._F  # the workspace rows of the node loads (3) and of the segment tension
T_ROW = lk._T
TANGENT_ROW = lk._TX


@njit(inline="always", **JIT)  # inlined: each call would pass and count every array
def gather(y, n, q, v, ppos, pvel, a, b, yl):
    """The line's nodes as ``yl = [r_0 .. r_n, v_0 .. v_n]``: its ends from points a and b."""
    v0 = 3 * (n + 1)
    for c in range(3):
        yl[c] = ppos[a, c]
        yl[3 * n + c] = ppos[b, c]
        yl[v0 + c] = pvel[a, c]
        yl[v0 + 3 * n + c] = pvel[b, c]
    for k in range(3 * (n - 1)):
        yl[3 + k] = y[q + k]
        yl[v0 + 3 + k] = y[v + k]


@njit(inline="always", **JIT)
def loads(
    yl, n, s0, c0, length, stiffness, damping, slack, drag_normal, drag_tangential, wet_weight,
    buoyancy, added_mass, node_bend, seabed_k, seabed_c, seabed_z, friction, slip, band, current_z,
    current_u, current_v, t, gravity, wave, wave_depth, wave_stretch, w,
):  # fmt: skip
    """Every load on the line's nodes into the workspace columns c0 .. c0 + n (``slack``:
    kernels.lumped's LAW, the physical laws; LINEAR, for smooth static solves; FROZEN, the
    laws' branches of the last LAW evaluation, for Newton's matrix), at time ``t`` [s] in the
    incident waves ``wave`` (kernels.lumped.segment_loads)."""
    lk.segment_loads(
        yl, n, s0, c0, length, stiffness, damping, slack, drag_normal, drag_tangential, wet_weight,
        buoyancy, added_mass, current_z, current_u, current_v, t, gravity, wave, wave_depth,
        wave_stretch, w,
    )  # fmt: skip
    lk.bending(n, c0, node_bend, w)
    lk.seabed_loads(yl, n, c0, seabed_z, seabed_k, seabed_c, friction, slip, band, slack, w)


@njit(inline="always", **JIT)
def interior_rates(yl, n, q, v, c0, node_mass, w, ydot):
    """Rates of the interior nodes; False when a node's mass matrix is singular."""
    v0 = 3 * (n + 1)
    ok = True
    for j in range(1, n):
        k = c0 + j
        ax, ay, az, sound = lk._node_acceleration(node_mass[k], w, k)
        ok = ok and sound
        at = 3 * (j - 1)
        for c in range(3):
            ydot[q + at + c] = yl[v0 + 3 * j + c]
        ydot[v + at] = ax
        ydot[v + at + 1] = ay
        ydot[v + at + 2] = az
    return ok


@njit(inline="always", **JIT)
def end_mass_force(node_mass, w, k, m3, force):
    """The 3x3 mass (row-major ``m3``) and the loads (``force``) of end node column k."""
    lk._node_mass_into(node_mass[k], w, k, m3)
    for c in range(3):
        force[c] = w[F_ROW + c, k]
