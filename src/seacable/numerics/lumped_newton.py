"""Newton's matrix of the lumped-mass lines written from their laws instead of by differences.

An interior node j of a lumped line (kernels.lumped) has the residual
res_j = (1 - am) a1_j + am a0_j - (1 - af) M_j^-1 F_j(x1, v1) - af f0_j, and its forces F_j
depend on its own and its two neighbours' positions and velocities only. The column of node m's
acceleration is, at each node j next to it (``system_implicit`` gives x1 and v1 the reaches
b h^2 and g h),

    d res_j / d a1_m = (1 - am) delta_jm I - (1 - af) M_j^-1 (dF_j/dx_m b h^2 + dF_j/dv_m g h)

with, for each segment s from node a to node b (tension T, tangent t, stretched length L,
unstretched l, EA, Kelvin-Voigt alpha; the pull P = T t acts on a, -P on b):

    dP/d(x_b - x_a) = EA / l t t^T + EA alpha / (l L) t (dv - (dv . t) t)^T + T / L (I - t t^T)
    dP/d(v_b - v_a) = EA alpha / l t t^T             (both zero where the segment is slack)

the drag on the velocity of its centre relative to the water, r = (v_a + v_b) / 2 - u, half on
each node: d(-Dn |r_n| r_n - Dt |r_t| r_t t) / dr = -Dn (|r_n| (I - t t^T) + r_n r_n^T / |r_n|)
- 2 Dt |r_t| t t^T (times the segment's wet share), and the seabed's (kernels.lumped
seabed_gradient) on the node's own block. Left out, as the difference quotients of the frozen
laws leave out the waves' gradient: the drag's and the added mass's change with the segment's
direction, the buoyancy's with a segment's share under the surface. They only slow Newton's
contraction (the matrix is not the residual's derivative); the residual itself is exact.

A node's columns are written so when every equation they reach is one of its line's interior
nodes (``eligible``): its line has no bending stiffness, and neither of its neighbours is an
end on a body with degrees of freedom (whose rows the differences keep). A line with no
other columns costs no residual for its matrix: on the spread mooring of
benchmarks/vs_moordyn_spread.py (three lines on an imposed body) the matrix is built from the
laws alone.

WHOLE: a matrix written whole from the laws (``written``: no difference quotient left, no
rigid line) costs less than two residuals (a compiled fill of 14 us and a factorisation of 5
us against 9 us a residual, three lines of 50 segments), so ``system_implicit`` builds it at
every step's first iterate (kept from step to step as a differenced one is, each iteration
contracted by 0.1 to 0.3: the touchdown nodes' contact and the lines' turning change it), and,
the iteration then contracting fast (a correction 3e-4 times the one before), stops as soon as
the error the last correction leaves, ratio / (1 - ratio) times it, is within the tolerance
(``converged``; Hairer and Wanner's test for simplified Newton iterations), not only when the
correction itself is; the forces the next step starts from are the last residual's moved by
that correction to first order (``ends``, with the matrix: the correction solved J da = r, and
J = (1 - am) I - (1 - af) df/da1). A differenced matrix kept from earlier steps keeps the old
test and forces: on a natural string (tests/test_natural_string.py) generalized-alpha's order
fell from 2 to 1.5 with them. On the spread mooring (50 segments, 0.1 s, Newton to 1e-9 of a
segment) a step took 10.1 residuals (3.2 of them for 0.35 matrices by differences) and 6.3
corrections, with 0.8 updates of the seabed terms; now 2.6 residuals and 2.5 corrections on
1.16 matrices: 254 against 81 us (compiled loops of 300 steps, 30 s into the run; the fairlead
tensions' error against a converged run the same to three digits)."""

import math

import numpy as np
from numba import njit

from seacable.kernels import chain3d, lumped
from seacable.kernels.jit import JIT, inner
from seacable.kernels.surface import segment_submersion


def eligible(p, pattern) -> tuple[np.ndarray, np.ndarray]:
    """The lumped lines (indices into the line_* arrays) with columns written from their laws,
    and a mask over ``pattern``'s columns (Newton's, over the velocity variables, COO), 1 for
    those: an interior node's of a lumped line without bending whose rows are all its line's
    interior nodes'."""
    nq = int(p.n_q)
    size = pattern.shape[0]
    column = np.zeros(size, dtype=np.int64)
    outside = np.zeros(size, dtype=bool)  # a column with a row outside its line
    owner = np.full(size, -1, dtype=np.int64)
    for li in range(len(p.line_n)):
        n, v = int(p.line_n[li]), int(p.line_v[li]) - nq
        owner[v : v + 3 * (n - 1)] = li
    row, col = np.asarray(pattern.row), np.asarray(pattern.col)
    np.logical_or.at(outside, col, owner[row] != owner[col])
    lines: list[int] = []
    for li in range(len(p.line_n)):
        n, v, c0 = int(p.line_n[li]), int(p.line_v[li]) - nq, int(p.line_node[li])
        if n < 2 or np.any(np.asarray(p.node_bend[c0 : c0 + n + 1]) != 0.0):
            continue
        for j in range(n - 1):
            cols = slice(v + 3 * j, v + 3 * j + 3)
            if not np.any(outside[cols]):
                column[cols] = 1
        if np.any(column[v : v + 3 * (n - 1)]):
            lines.append(li)
    return np.array(lines, dtype=np.int64), column


def destinations(p, lines: np.ndarray, column: np.ndarray, lay) -> np.ndarray:
    """For each written column (an acceleration of node m's component c) the places in
    ``lay``'s flat matrix of its entries in the rows of nodes m - 1, m, m + 1 (component r of
    node m - 1 + d at [3 d + r]; -1 where there is none: the line's ends)."""
    nq = int(p.n_q)
    dest = np.full((len(column), 9), -1, dtype=np.int64)
    for li in lines:
        first = int(p.line_v[li]) - nq
        for col in range(first, first + 3 * (int(p.line_n[li]) - 1)):
            if not column[col]:
                continue
            top = first + 3 * ((col - first) // 3) - 3  # node m - 1's first row
            for z in range(int(lay.nz_ptr[col]), int(lay.nz_ptr[col + 1])):
                local = int(lay.nz_row[z]) - top
                if 0 <= local < 9:
                    dest[col, local] = lay.nz_dest[z]
    return dest


def unknowns(p, size: int) -> np.ndarray:
    """A mask over ``size`` unknowns (the velocity variables first): the lumped lines'
    interior nodes' (whose blocks of Newton's matrix are 3 x 3 block-tridiagonal:
    ``bordered``'s ``tri``)."""
    mask = np.zeros(size, dtype=bool)
    for li in range(len(p.line_n)):
        v = int(p.line_v[li]) - int(p.n_q)
        mask[v : v + 3 * (int(p.line_n[li]) - 1)] = True
    return mask


@njit(inline="always", **JIT)
def _outer(out, at, ax, ay, az, bx, by, bz, scale):
    """out[at : at + 9] += scale a b^T (row-major). This and the other per-segment and
    per-node helpers are inlined: called, each took and dropped a reference to its arrays
    (a fill of three 50-segment lines 18.0 -> 14.0 us, of 20-segment ones 7.8 -> 5.9)."""
    out[at] += scale * ax * bx
    out[at + 1] += scale * ax * by
    out[at + 2] += scale * ax * bz
    out[at + 3] += scale * ay * bx
    out[at + 4] += scale * ay * by
    out[at + 5] += scale * ay * bz
    out[at + 6] += scale * az * bx
    out[at + 7] += scale * az * by
    out[at + 8] += scale * az * bz


@njit(inline="always", **JIT)
def _pull(stiffness, damping, length, tension, tx, ty, tz, stretched, dvx, dvy, dvz, out):
    """dP/d(x_b - x_a) into out[0:9] and dP/d(v_b - v_a) into out[9:18] (row-major, out zero
    before) of a taut segment (module docstring)."""
    axial = stiffness / length
    along = dvx * tx + dvy * ty + dvz * tz
    across = tension / stretched
    _outer(out, 0, tx, ty, tz, tx, ty, tz, axial - across)
    out[0] += across
    out[4] += across
    out[8] += across
    rotate = axial * damping / stretched
    _outer(out, 0, tx, ty, tz, dvx - along * tx, dvy - along * ty, dvz - along * tz, rotate)
    _outer(out, 9, tx, ty, tz, tx, ty, tz, axial * damping)


@njit(inline="always", **JIT)
def _drag(normal, tangential, wet, rx, ry, rz, tx, ty, tz, out):
    """d(drag)/dr into out[18:27] (row-major, zero before) for the relative velocity r
    (module docstring)."""
    vt = rx * tx + ry * ty + rz * tz
    nx, ny, nz = rx - vt * tx, ry - vt * ty, rz - vt * tz
    vn = math.sqrt(nx * nx + ny * ny + nz * nz)
    across = -wet * normal * vn
    _outer(out, 18, tx, ty, tz, tx, ty, tz, -across - 2.0 * wet * tangential * abs(vt))
    out[18] += across
    out[22] += across
    out[26] += across
    if vn > 0.0:
        _outer(out, 18, nx, ny, nz, nx, ny, nz, -wet * normal / vn)


@inner
def _segments(y, li, p, w, vel, seg):
    """Line li's end and node velocities into ``vel`` and each segment's derivatives into
    ``seg`` (dP/d(x_b - x_a), dP/d(v_b - v_a), d(drag)/dr, row-major 3 x 3 each)."""
    n, s0, c0, v0, q0 = p.line_n[li], p.line_seg[li], p.line_node[li], p.line_v[li], p.line_q[li]
    nodes, ppos = w.nodes, w.ppos
    stiffness, damping, length = p.seg_stiffness, p.seg_damping, p.seg_length  # read once: a
    normal, tangential = p.seg_drag_normal, p.seg_drag_tangential  # read in a loop takes a
    current_z, current_u, current_v = p.current_z, p.current_u, p.current_v  # reference
    for c in range(3):
        vel[0, c] = w.pvel[p.line_from[li], c]
        vel[n, c] = w.pvel[p.line_to[li], c]
    for j in range(1, n):
        for c in range(3):
            vel[j, c] = y[v0 + 3 * (j - 1) + c]
    linear = p.slack_allowed == lumped.LINEAR
    seg[:n] = 0.0
    for i in range(n):
        s, k = s0 + i, c0 + i
        tx, ty, tz = nodes[lumped._TX, k], nodes[lumped._TX + 1, k], nodes[lumped._TX + 2, k]
        if linear or nodes[lumped._TAUT, k] != 0.0:
            _pull(
                stiffness[s], damping[s], length[s], nodes[lumped._T, k], tx, ty, tz,
                nodes[lumped._L, k], vel[i + 1, 0] - vel[i, 0], vel[i + 1, 1] - vel[i, 1],
                vel[i + 1, 2] - vel[i, 2], seg[i],
            )  # fmt: skip
        za = y[q0 + 3 * (i - 1) + 2] if i > 0 else ppos[p.line_from[li], 2]
        zb = y[q0 + 3 * i + 2] if i + 1 < n else ppos[p.line_to[li], 2]
        wet = segment_submersion(za, zb)[0]
        if wet > 0.0:
            if current_z.shape[0] == 1:
                cu, cv = current_u[0], current_v[0]
            else:
                cu, cv = chain3d._current(current_z, current_u, current_v, 0.5 * (za + zb))
            rx = 0.5 * (vel[i, 0] + vel[i + 1, 0]) - cu - nodes[lumped._WU, k]
            ry = 0.5 * (vel[i, 1] + vel[i + 1, 1]) - cv - nodes[lumped._WU + 1, k]
            rz = 0.5 * (vel[i, 2] + vel[i + 1, 2]) - nodes[lumped._WU + 2, k]
            _drag(normal[s], tangential[s], wet, rx, ry, rz, tx, ty, tz, seg[i])


@inner
def _nodes(y, li, p, w, vel, inv, bed):
    """Line li's interior nodes' inverse mass matrices into ``inv`` and their seabed
    gradients into ``bed`` (kernels.lumped.seabed_gradient; zero off the seabed)."""
    n, c0, q0 = p.line_n[li], p.line_node[li], p.line_q[li]
    nodes, node_mass = w.nodes, p.node_mass
    bed_k, bed_c = p.node_seabed_stiffness, p.node_seabed_damping
    m3 = np.empty(9)
    bed[: n + 1] = 0.0
    for j in range(1, n):
        k = c0 + j
        lumped._node_mass_into(node_mass[k], nodes, k, m3)
        det, adjugate = chain3d.adjugate3(m3)
        for e in range(9):
            inv[j, e] = adjugate[e] / det
        if p.seabed_z > -1e29 and nodes[lumped._CONTACT, k] != 0.0:
            lumped.seabed_gradient(
                y[q0 + 3 * (j - 1) + 2], vel[j, 0], vel[j, 1], vel[j, 2], p.seabed_z, bed_k[k],
                bed_c[k], p.seabed_friction, p.seabed_slip_speed, p.seabed_band, bed[j],
            )  # fmt: skip


@njit(inline="always", **JIT)
def _near(m, n, seg, inv, bed, reach, rate, am, af, block, near):
    """d res_j / d a1_m of the interior nodes j = m - 1, m, m + 1 next to node m into
    ``near[j - m + 1]`` (row-major 3 x 3; segment m - 1 joins nodes m - 1 and m, segment m
    nodes m and m + 1; P_i pulls node i by +P_i, node i + 1 by -P_i)."""
    for d in range(3):
        j = m - 1 + d
        if j < 1 or j > n - 1:
            continue
        for e in range(9):
            if d == 2:  # node m + 1, -P_m: its d/dx_a
                x, v = seg[m, e], seg[m, 9 + e] + 0.25 * seg[m, 18 + e]
            elif d == 0:  # node m - 1, +P_{m-1}: its d/dx_b
                x, v = seg[m - 1, e], seg[m - 1, 9 + e] + 0.25 * seg[m - 1, 18 + e]
            else:
                x = -seg[m - 1, e] - seg[m, e]
                v = (-seg[m - 1, 9 + e] - seg[m, 9 + e]
                     + 0.25 * (seg[m - 1, 18 + e] + seg[m, 18 + e]))  # fmt: skip
                if e % 3 == 2:
                    x += bed[j, e // 3]
                v += bed[j, 3 + e]
            block[e] = x * reach + v * rate  # dF_j/dx_m b h^2 + dF_j/dv_m g h
        for r in range(3):
            for c in range(3):
                total = 0.0
                for e in range(3):
                    total += inv[j, 3 * r + e] * block[3 * e + c]
                near[d, 3 * r + c] = -(1.0 - af) * total + (1.0 - am if d == 1 and r == c else 0.0)


@njit(**JIT)
def fill(y, h, coef, p, w, lines, column, dest, mat):
    """Add the written columns of Newton's matrix (``lines``, ``column``: ``eligible``'s;
    ``dest``: their entries' places, ``destinations``) into ``mat`` at the state ``y`` whose
    residual ``w`` holds (its tensions, tangents, the laws' branches, the water's velocity,
    the end points' velocities)."""
    b, g, am, af = coef[1], coef[2], coef[3], coef[4]
    most = 0
    for li in lines:
        most = max(most, p.line_n[li])
    seg = np.empty((most, 27))
    inv = np.empty((most + 1, 9))
    bed = np.empty((most + 1, 12))
    vel = np.empty((most + 1, 3))
    block = np.empty(9)
    near = np.empty((3, 9))
    for li in lines:
        n = p.line_n[li]
        _segments(y, li, p, w, vel, seg)
        _nodes(y, li, p, w, vel, inv, bed)
        first = p.line_v[li] - p.n_q
        for m in range(1, n):
            col0 = first + 3 * (m - 1)
            if column[col0] == 0:
                continue
            _near(m, n, seg, inv, bed, b * h * h, g * h, am, af, block, near)
            for c in range(3):
                for e in range(9):
                    at = dest[col0 + c, e]
                    if at >= 0:
                        mat[at] += near[e // 3, 3 * (e % 3) + c]


@njit(inline="always", **JIT)
def converged(correction, ratio, tol, written):
    """Whether Newton's iteration stops with a correction of ``correction`` [m] that was
    ``ratio`` times the one before (0 after a matrix was built): when it is within the
    tolerance, or, with a matrix written whole (``written``), when the error it leaves,
    ratio / (1 - ratio) times it, is (module docstring, WHOLE)."""
    if correction <= tol:
        return True
    return written and 0.0 < ratio < 0.5 and ratio / (1.0 - ratio) * correction <= tol


@inner
def ends(ends, f_iterate, da, res, coef, written):
    """The forces the next step starts from: those of the last residual, ``f_iterate`` (the
    iterate before the last correction ``da``), or, with a matrix written whole, those moved
    by the correction to first order, f - ((1 - am) da - res) / (1 - af) (``res`` the
    residual the correction was solved for; module docstring, WHOLE)."""
    if not written:
        ends[:] = f_iterate
        return
    am, af = coef[3], coef[4]
    for i in range(ends.shape[0]):
        ends[i] = f_iterate[i] - ((1.0 - am) * da[i] - res[i]) / (1.0 - af)


@njit(inline="always", **JIT)
def written(lay, rows):
    """Whether Newton's matrix is written whole from the lumped lines' laws
    (no difference quotient and no rigid line): it costs less than a
    residual, is built afresh at every step's first iterate, and is the residual's derivative
    there (up to the terms this module leaves out), so that the iteration may stop on
    the error its contraction estimates (module docstring, WHOLE)."""
    return (
        lay.colour_ptr.shape[0] == 1 and rows.lumped_line.shape[0] > 0 and rows.line.shape[0] == 0
    )
