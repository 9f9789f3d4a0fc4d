"""The fixed-step implicit schemes (implicit Euler, the theta-method, Newmark (gamma, beta) and
the generalized-alpha method of Chung and Hulbert (1993), as in WHOI Cable) on a system of bodies
and lines.

Every scheme is written for ``a = f(t, x, v)`` with the acceleration of the step's end, ``a1``,
as the unknown:

    x1 = x0 + h v0 + h^2 (pa a0 + b a1),     v1 = v0 + h ((1 - g) a0 + g a1),
    (1 - am) a1 + am a0 = (1 - af) f(t0 + h, x1, v1) + af f(t0, x0, v0)

    scheme              pa               b               g                am, af
    implicit Euler      0                1               1                0, 0
    theta-method        theta(1-theta)   theta^2         theta            0, 0
    Newmark             1/2 - beta       beta            gamma            0, 0
    generalized-alpha   1/2 - beta       beta            1/2 - am + af    (2r-1)/(r+1), r/(r+1)

(generalized-alpha: beta = (1 - am + af)^2 / 4, r the spectral radius at infinite frequency;
its forces blended at the alpha point, as Chung and Hulbert write it: an imposed body's motion
enters at the step's two ends exactly, as the free states do. Blending the states instead,
with the imposed motion exact at t0 + (1 - af) h, made the 20-segment mooring race's fairlead
tension 2.4 times less accurate at 25 ms: 3.7e-3 of its peak against 1.6e-3.)
The theta-method with theta = 1/2 (the trapezoidal rule) and Newmark's average acceleration
(beta = 1/4, gamma = 1/2) are the same scheme here. The integrator follows the contract of
``numerics.integrators``; its work counters add Jacobian evaluations (matrices built and
factorised), linear solves (Newton iterations) and matrix updates (a kept matrix's seabed
terms brought to the iterate and refactorised).

The unknowns of a step are the accelerations a1 of every velocity variable of the system
(``y = [Q, V, S]``: bodies, lumped nodes, rigid segments' director rates, links' angle rates,
natural strings' rates), then the rates of the force models' first-order states S (a servo's
force), advanced by the same g: s1 = s0 + h ((1 - g) ds0 + g ds1), (1 - am) ds1 + am ds0 =
(1 - af) F(t0 + h, x1, v1, s1) + af F(t0, x0, v0, s0), the conditions for second order the
same (g = 1/2 - am + af). In the line search and the convergence test a state's residual
and correction count through the change they make, g h ds, against its scale (metres per
state scale, ``Increments.weight``). The step's increment of the positions,
d = h v0 + h^2 (pa a0 + b a1),
moves each position variable additively, except a rigid body's orientation, which turns by the
rotation vector d (earth frame): q1 = exp(d / 2) q0 (``Increments``). After the step the
state is projected (unit quaternions and directors), as after every explicit step.

Newton's matrix, d(residual)/d(a1), is built by finite differences of the residual over groups
of accelerations that share no equation (``system.coordinates.colour`` of the Jacobian pattern
of ``system.model.jacobian_sparsity``): a lumped line would cost about nine residuals whatever
its length. Its interior nodes' columns are written from the laws instead
(``numerics.lumped_newton``) wherever they reach only their line's equations (every node of a
line without bending but those next to an end on a body with degrees of freedom), so that the
differences are left with the bodies' columns and their neighbours'. It is laid out and
factorised by ``numerics.bordered``: each line (or tree of rigid
lines) a banded block, the bodies' degrees of freedom the border, so a factorisation costs
O(total unknowns) for lumped lines and natural strings plus the bodies' dense Schur complement.
A rigid line's accelerations depend on all its angles (or directors): in them its block is
dense. A planar or 3D one based on a fixed or imposed body, or on a dynamic body whose rotations
are held, with a free, held or body-carrying tip, is written instead in maximal coordinates
(``numerics.rigid_newton`` and ``numerics.rigid_newton_3d``, docs/rigid_newton.md: banded,
exact, O(n) to build and factorise), with auxiliary unknowns after the velocity variables; the
others (trees of lines, lines held on a free body, turning bases) keep the dense block. The
factors are kept from step to step while they serve (modified Newton: rebuilt when, at the
contraction the last two corrections show, more than ``PATIENCE`` iterations would still be
needed, and whenever the step length changes), so most steps cost two or three residuals. A
matrix with no difference quotient left (``lumped_newton.written``: lumped lines between
fixed and imposed bodies) is built at every step's first iterate instead, and the iteration
stops on the error its contraction estimates (``lumped_newton``'s docstring, WHOLE).
Every residual of a step is evaluated at the step's end time as the next step's start time
computes it (``chunk``: t0 + h may differ from it in the last bit), so that the next step's
f(t0) finds the water kinematics its last residual recorded at that very time (kernels.lumped
LAGGED).
A Jacobian counts its residuals in the rhs evaluations.
The forces f(t0, x0, v0) that generalized-alpha blends in at a step's start are those of the
step before's last residual (its iterate before the last correction, which moved no
position by more than the tolerance), not evaluated again: one residual a step less (the
moored barge example over 100 s: 10,841 residuals against 12,700, 110 times real time against
98; its bow fairlead's largest tension 728.390 kN against 728.353). After a failed step, a
line's failure or new parameters they are evaluated.
REUSE: within a step's Newton iteration a hull mesh's loads (clipped hydrostatics,
Froude-Krylov) are computed again only when its pose moves a vertex by more than NEAR times
the tolerance from where they were last computed (kernels.hull.place; the difference
quotients compute them exactly). A massive hull's corrections fall under it after a step's
first iteration or two while its lines' nodes still converge. The loads' error is at most
K NEAR tol (K the hull's stiffness); held step after step it acts on the hull as a force and
moves it by about NEAR tol, a thousandth of what the tolerance admits. The moored FPSO of
benchmarks/vessel_cost.py (1,296 triangles, 180 wave components; ``--fpso-only --duration
1200``, the old code in turn): 17.2 times real time against 11.9, the same residuals; over
300 s its fairlead tensions 29 N (4e-5 of the peak) and its heave 5e-10 m from the old run's,
where a tolerance of 1e-8 instead of 1e-7 moves them by 170 N and 5e-6 m. At NEAR = 1 the
heave moved by 4e-6 m, as much as the tolerance's own effect: not taken. The Froude-Krylov
force alone is held further, while the pose moves no vertex by more than FAR times the
tolerance from where it was computed (kernels.hull.add_froude_krylov; the clipped
hydrostatics are computed again): it changes over a move by the waves' pressure gradient, a
wave slope's share of the hydrostatics' rho g, so that most steps compute it once, at the
predictor, where they computed it twice (the first correction's pose moves the hull beyond
NEAR tol). The same FPSO, the old code in turn: 27.5 times real time against 18.1 (medians of
3 pairs: 26.9 to 28.4 against 17.8 to 18.1; a /tmp script timing part 5 alone as the
benchmark times it); over 300 s its heave moved by 2e-8 m, its pitch by 1.6e-8 rad and its
fairlead segments' tensions by 0.05 N (7e-8 of the peak) from the old run's, 250 times less
than the tolerance's own effect above. Held for the whole step (any FAR) it moved the heave by
3e-8 m for about 10 % more speed, at FAR = 10 by 3e-8 m for 5 % (single runs of 300 s): the
tolerance kept.
ESTIMATE: each accepted step estimates its local error as Zienkiewicz and Xie (1991) do for
the Newmark family, (b - 1/6) h^2 (a1 - a0) in each position, and turns it into the lumped
lines' tensions: EA / l times the difference of a segment's two nodes' estimates (its ends'
points not estimated). A step too long for what it integrates (a line ringing after a
seabed impact, a snap) shows as an acceleration that swings from step to step; the run's
largest estimate against its largest tension is in the results, and beyond ESTIMATE_SHARE of
it the run warns (``seacable.run_report``).
"""

import math

import numpy as np
from numba import njit

from seacable.kernels import chain3d, hull, lumped
from seacable.kernels.jit import JIT, inner
from seacable.kernels.status import NEWTON_FAILED, NON_FINITE, OK
from seacable.numerics import bordered, dense, lumped_newton, rigid_newton
from seacable.numerics.integrators import record, step_time
from seacable.system import kernel as system_kernel

FD_STEP = 1.5e-8  # relative change of a position for the difference quotients
MAX_SUBSTEPS = 64  # a step whose Newton iteration fails is retried in up to this many parts
PATIENCE = 4.0  # modified Newton: the matrix is rebuilt when, at the contraction the last two
# corrections show, more than PATIENCE iterations would still be needed (or more than are left).
# A matrix costs about 13 residuals of an iteration on the moored barge (24 difference
# quotients, most without the hull's models, and a factorisation). Its example run for 100 s at
# 0.05 s (a scratch run timed as benchmarks/vessel_cost.py times its runs): PATIENCE 2, 3, 4, 6
# gave 43.1, 43.8, 44.9, 40.9 times real time; the rule it replaces (rebuilt after 3
# iterations on one matrix, or when a correction shrank by less than half) 37.0. Over the
# benchmark's 200 s (python benchmarks/vessel_cost.py --realtime-only): 34.6, was 26.6.
UPDATES = 2  # a stale matrix's seabed terms are updated at most UPDATES times a step, then it
# is rebuilt (_matrix): the rest of it ages too. The moored barge over the benchmark's 200 s at
# 0.05 s (a scratch run timed as the benchmark times them): 46.8 times real time without
# updates (1,597 matrices, 19 failed steps); once a step 49.5 (723, 41); twice 52.9 (428, 47);
# without a limit 53.1 (170, 86). Updating the contact's terms without the friction's: 35.5.
SEARCH = 4  # a correction that does not lower the residual is halved up to SEARCH times
NEAR = 1e-3  # within a step's Newton iteration, a hull mesh's loads (kernels.hull.place) are
# reused while its pose moves no vertex by more than NEAR times the Newton tolerance from
# where they were computed (module docstring, REUSE)
FAR = 1.0  # ... and its Froude-Krylov force while its pose moves no vertex by more than FAR times
# the tolerance from where it was computed (module docstring, REUSE)


@inner
def _advance(y0, d, y, inc):
    """The positions of y moved from y0's by the increment d (velocity-sized)."""
    for i in range(inc.q_of_v.shape[0]):
        q = inc.q_of_v[i]
        if q >= 0:
            y[q] = y0[q] + d[i]
    for k in range(inc.quat_q.shape[0]):
        q, v = inc.quat_q[k], inc.quat_v[k]
        tx, ty, tz = d[v], d[v + 1], d[v + 2]
        angle = math.sqrt(tx * tx + ty * ty + tz * tz)
        qw, qx, qy, qz = y0[q], y0[q + 1], y0[q + 2], y0[q + 3]
        if angle < 1e-300:
            y[q], y[q + 1], y[q + 2], y[q + 3] = qw, qx, qy, qz
            continue
        s = math.sin(0.5 * angle) / angle
        dw, dx, dy, dz = math.cos(0.5 * angle), s * tx, s * ty, s * tz
        y[q] = dw * qw - dx * qx - dy * qy - dz * qz
        y[q + 1] = dw * qx + dx * qw + dy * qz - dz * qy
        y[q + 2] = dw * qy - dx * qz + dy * qw + dz * qx
        y[q + 3] = dw * qz + dx * qy - dy * qx + dz * qw


@inner
def _state(y0, acc, a1, h, coef, inc, y, d, nq):
    """y: the state at the end of the step from y0 with end accelerations a1 (then the force
    models' states from their end rates, s1 = s0 + h ((1 - g) ds0 + g ds1))."""
    pa, b, g = coef[0], coef[1], coef[2]
    nv = inc.q_of_v.shape[0]
    for i in range(nv):
        d[i] = h * y0[nq + i] + h * h * (pa * acc[i] + b * a1[i])
    n = a1.shape[0]
    y[nq + n :] = y0[nq + n :]
    for i in range(n):
        y[nq + i] = y0[nq + i] + h * ((1.0 - g) * acc[i] + g * a1[i])
    _advance(y0, d, y, inc)


@njit(inline="always", **JIT)
def _residual(t1, y0, acc, a1, h, coef, p, w, inc, ya, ydot, d, res, f0):
    """res = (1 - am) a1 + am a0 - [(1 - af) f(t1, end state) + af f0], f0 = f(t, y0), t1 the
    step's end time (t + h to the last bit):
    the forces blended at the alpha point (as Chung and Hulbert write the scheme), so that an
    imposed body's motion enters at the step's two ends exactly, as the free states do (a
    force model's state alike, its rate in place of an acceleration); returns the status."""
    am, af = coef[3], coef[4]
    _state(y0, acc, a1, h, coef, inc, ya, d, p.n_q)
    status = system_kernel.evaluate(t1, ya, p, w, ydot)
    nq = p.n_q
    for i in range(a1.shape[0]):
        res[i] = (1.0 - am) * a1[i] + am * acc[i] - (1.0 - af) * ydot[nq + i] - af * f0[i]
    return status


@njit(inline="always", **JIT)
def _jacobian(t1, y0, acc, a1, h, coef, pj, w, inc, lay, rows, mat, r0, vec, work, rigid):
    """Newton's matrix into ``mat``: the rigid lines of ``rows`` in maximal coordinates at the
    residual r0 just evaluated (``rigid_newton.fill``: ``w`` and ``vec[0]`` hold its
    evaluation), then the rest by differences of the residual, colour by colour, with the
    parameters ``pj`` (``frozen``: the laws' branches of the residual r0); ``rigid``: as
    ``chunk``'s."""
    nv = a1.shape[0]
    ya, ydot, d, ap, rp, eps = vec[0], vec[1], vec[2][:nv], vec[3][:nv], vec[4][:nv], vec[5][:nv]
    f0 = vec[9][:nv]
    mat[:] = 0.0
    if rows.lumped_line.shape[0] > 0:
        lumped_newton.fill(ya, h, coef, pj, w, rows.lumped_line, rows.lumped_column,
                           rows.lumped_dest, mat)  # fmt: skip
    if (
        rigid is not None
        and rows.line.shape[0] > 0
        and not rigid_newton.fill(t1, ya, h, coef, pj, w, rows, mat)
    ):
        return NON_FINITE
    reach = coef[1] * h * h  # d(end position) / d(a1)
    nq, n_pos = pj.n_q, inc.q_of_v.shape[0]
    for c in range(lay.colour_ptr.shape[0] - 1):
        ap[:] = a1
        for k in range(lay.colour_ptr[c], lay.colour_ptr[c + 1]):
            j = lay.colour_cols[k]
            if j >= n_pos:  # a force model's state: d(end state) / d(rate) = g h
                eps[j] = FD_STEP * max(abs(y0[nq + j]), inc.scale[j]) / (coef[2] * h)
            else:
                q = inc.q_of_v[j]
                size = max(abs(y0[q]), inc.scale[j]) if q >= 0 else inc.scale[j]
                eps[j] = FD_STEP * size / reach
            ap[j] += eps[j]
        status = _residual(t1, y0, acc, ap, h, coef, pj, w, inc, ya, ydot, d, rp, f0)
        work[2] += 1
        if status != OK:
            return status
        for k in range(lay.colour_ptr[c], lay.colour_ptr[c + 1]):
            j = lay.colour_cols[k]
            for z in range(lay.nz_ptr[j], lay.nz_ptr[j + 1]):
                r = lay.nz_row[z]
                mat[lay.nz_dest[z]] += (rp[r] - r0[r]) / eps[j]
    return OK


@njit(inline="always", **JIT)
def _merit(res, inc, rate):
    """The residual's size for the line search: sum of (residual x metres per unit)^2, a force
    model's state's residual times ``rate`` (g / (b h): its change per unit of residual
    against a position's)."""
    total = 0.0
    n_pos = inc.q_of_v.shape[0]
    for i in range(res.shape[0]):
        r = res[i] * inc.weight[i] * (rate if i >= n_pos else 1.0)
        total += r * r
    return total


@njit(inline="always", **JIT)
def _search(t1, y, acc, a1, da, h, coef, p, w, inc, merit, vec, work):
    """a1 -= s da with s = 1, 1/2, ... (SEARCH halvings at most) until the residual's merit
    falls (Armijo's test); the residual at the new a1 into vec[6]. Returns (status, merit,
    whether the correction was cut)."""
    nv = a1.shape[0]
    ya, ydot, d, res, f0 = vec[0], vec[1], vec[2][:nv], vec[6][:nv], vec[9][:nv]
    trial, res_trial = vec[3][:nv], vec[4][:nv]
    fraction = 1.0
    status = OK
    trial_merit = math.inf
    for cut in range(SEARCH + 1):
        for i in range(nv):
            trial[i] = a1[i] - fraction * da[i]
        status = _residual(t1, y, acc, trial, h, coef, p, w, inc, ya, ydot, d, res_trial, f0)
        work[2] += 1
        trial_merit = _merit(res_trial, inc, coef[2] / (coef[1] * h)) if status == OK else math.inf
        if trial_merit <= (1.0 - 1e-4 * fraction) * merit or cut == SEARCH:
            break
        fraction *= 0.5
    a1[:] = trial
    res[:] = res_trial
    vec[10][:nv] = ydot[p.n_q : p.n_q + nv]  # the forces at the new iterate
    return status, trial_merit, fraction < 1.0


@inner
def _estimate(change, h, coef, p, w, fresh):
    """The step's local error in the lumped lines' tensions (module docstring, ESTIMATE):
    fresh[4] its largest so far [N], fresh[5] the largest tension so far [N] (``w``: the
    last residual's evaluation). ``change``: a1 - a0 of every velocity variable."""
    c = abs(coef[1] - 1.0 / 6.0) * h * h
    for li in range(p.line_n.shape[0]):
        n, s0, c0, v0 = p.line_n[li], p.line_seg[li], p.line_node[li], p.line_v[li] - p.n_q
        ex0 = ey0 = ez0 = 0.0  # node 0, an end: its point's motion, not estimated
        for k in range(n):
            ex = ey = ez = 0.0  # node n, the other end
            if k + 1 < n:
                v = v0 + 3 * k  # interior node k + 1
                ex, ey, ez = c * change[v], c * change[v + 1], c * change[v + 2]
            stretch = math.sqrt((ex - ex0) ** 2 + (ey - ey0) ** 2 + (ez - ez0) ** 2)
            fresh[4] = max(fresh[4], p.seg_stiffness[s0 + k] / p.seg_length[s0 + k] * stretch)
            fresh[5] = max(fresh[5], abs(w.nodes[lumped._T, c0 + k]))
            ex0, ey0, ez0 = ex, ey, ez


@njit(inline="always", **JIT)
def _stale(largest, previous, limit, left):
    """Whether Newton's matrix is to be rebuilt after a correction of (scaled) size
    ``largest`` that followed one of ``previous`` on it (inf: none): when it did not shrink, or
    when at this contraction more than PATIENCE iterations, or more than ``left``, would still
    be needed to bring it under ``limit``."""
    if largest >= previous:
        return True
    if previous == math.inf:
        return False
    needed = math.log(limit / largest) / math.log(largest / previous)
    return needed > PATIENCE or needed > left


@inner
def _seabed_terms(y, h, coef, p, w, lay, held, raw, update):
    """The seabed law's terms in Newton's matrix at the state ``y`` (``w`` evaluated there):
    for each interior node of each lumped line, G = dF/dr b h^2 + dF/dv g h, the derivatives
    of its seabed force (kernels.lumped.seabed_gradient) with respect to the node's
    acceleration a1. ``update`` 0.0 (a float: literal bools compiled it twice): G is recorded
    in ``held`` (the matrix just built by differences holds it). 1.0: the unfactorised matrix
    ``raw`` is moved by -(1 - af) M^-1 (G - held) at each node's diagonal block (M its 3 x 3
    mass matrix) and ``held`` becomes G. Returns whether any node's terms changed."""
    if p.seabed_z < -1e29:
        return False
    b, g, af = coef[1], coef[2], coef[4]
    grad = np.empty(12)
    m3 = np.empty(9)
    change = np.empty(9)
    moved = False
    for li in range(p.line_n.shape[0]):
        c0, q0, v0 = p.line_node[li], p.line_q[li], p.line_v[li]
        for j in range(1, p.line_n[li]):
            k = c0 + j
            q, v = q0 + 3 * (j - 1), v0 + 3 * (j - 1)
            lumped.seabed_gradient(
                y[q + 2], y[v], y[v + 1], y[v + 2], p.seabed_z, p.node_seabed_stiffness[k],
                p.node_seabed_damping[k], p.seabed_friction, p.seabed_slip_speed,
                p.seabed_band, grad,
            )  # fmt: skip
            same = True
            for e in range(9):
                term = grad[3 + e] * g * h + (grad[e // 3] * b * h * h if e % 3 == 2 else 0.0)
                change[e] = term - held[e, k]
                held[e, k] = term
                same = same and change[e] == 0.0
            if update == 0.0 or same:
                continue
            moved = True
            lumped._node_mass_into(p.node_mass[k], w.nodes, k, m3)
            det, adjugate = chain3d.adjugate3(m3)  # by cofactors: np.linalg.inv called LAPACK,
            scale = 1.0 / det  # whose thread pool then spun on the other core
            first = v - p.n_q
            for c in range(3):
                col = first + c
                for z in range(lay.nz_ptr[col], lay.nz_ptr[col + 1]):
                    r = lay.nz_row[z] - first
                    if 0 <= r < 3:
                        total = 0.0
                        for e in range(3):
                            total += adjugate[3 * r + e] * scale * change[3 * e + c]
                        raw[lay.nz_dest[z]] -= (1.0 - af) * total
    return moved


@njit(inline="always", **JIT)
def _matrix(t1, y, acc, a1, h, coef, p, pj, w, inc, lay, rows, carry, res, vec, work, updates,
            rigid):  # fmt: skip
    """Newton's matrix factorised for the iterate a1 (its state in ``vec[0]``, its residual
    ``res`` evaluated into ``w``): a kept matrix of this step length, updated fewer than
    UPDATES times in this step (``updates``), has its seabed terms brought to the iterate
    (``_seabed_terms``); when none changed, or otherwise, it is built afresh (``_jacobian``).
    Returns the status and the step's updates so far."""
    _, fresh, mat, piv, raw, held = carry
    written = lumped_newton.written(lay, rows)  # rebuilt rather than updated
    if fresh[0] != 0.0 and fresh[1] == h and updates < UPDATES and not written:
        if _seabed_terms(vec[0], h, coef, p, w, lay, held, raw, 1.0):
            mat[:] = raw
            work[6] += 1
            return (OK if bordered.factor(lay, mat, piv) else NON_FINITE), updates + 1
    if not written:
        _seabed_terms(vec[0], h, coef, p, w, lay, held, raw, 0.0)
    near, far = hull.reuse(w.hull, 0.0, 0.0)  # the difference quotients: exact loads
    status = _jacobian(t1, y, acc, a1, h, coef, pj, w, inc, lay, rows, mat, res, vec, work,
                       rigid)  # fmt: skip
    hull.reuse(w.hull, near, far)
    work[4] += 1
    if not written:
        raw[:] = mat  # kept for the seabed terms' updates
    if status == OK and not bordered.factor(lay, mat, piv):
        status = NON_FINITE
    fresh[0], fresh[1] = 1.0, h
    return status, updates


@inner
def _step(t, t1, y, acc, h, coef, tol, max_iter, p, pj, w, inc, lay, rows, carry, vec, big,
          work, rigid):  # fmt: skip
    """One implicit step of length h from (t, y, acc) to t1 (t + h as the next step's start
    computes it); updates y and acc only when it succeeds. A modified Newton iteration on the
    matrix of ``_jacobian``, kept from step to step while it serves: stale when a correction
    is no smaller than the one before, when at the contraction of the last two more than
    PATIENCE iterations (or more than are left) would still be needed, or when a line search
    cut the step; rebuilt then, when the step length changes, and at the first iterate when it
    is written whole from the laws (``lumped_newton.written``). A stale matrix has its lumped
    nodes' seabed terms brought to the current iterate instead (``_matrix``: analytic, node by
    node, then a factorisation; at most UPDATES times a step) when any changed: the contact's
    stiffness and the friction's dependence on the sliding speed change within millimetres and
    centimetres per second, and they made most of the rebuilds on the moored barge. Each
    correction that does not meet the tolerance is damped by halving (at most SEARCH times)
    until the residual's ``_merit`` falls: the laws' kinks (a segment going slack, a node
    touching the seabed) otherwise make Newton cycle between their branches. ``big`` (3,
    ``rows.size``): Newton's right-hand side, correction and scratch over every unknown, the
    rigid lines' auxiliary ones included (``rigid_newton.rhs``)."""
    q, fresh, mat, piv, raw, held = carry
    a1, trend, ends = q[0], q[1], q[2]
    nv = a1.shape[0]
    ya, ydot, d, res, da, z = vec[0], vec[1], vec[2][:nv], vec[6][:nv], vec[7][:nv], vec[8][:nv]
    f0, f_iterate = vec[9][:nv], vec[10][:nv]
    nq = p.n_q
    b = coef[1]
    f0[:] = 0.0
    if coef[4] != 0.0:  # generalized-alpha: the forces at the step's start, blended in
        if fresh[3] == 1.0:  # the last step's, from its last residual
            f0[:] = ends
        else:
            status = system_kernel.evaluate(t, y, p, w, ydot)
            work[2] += 1
            if status != OK:
                work[3] += 1
                return status
            f0[:] = ydot[nq : nq + nv]
    fresh[3] = 0.0  # until this step is accepted
    a1[:] = acc
    if fresh[2] == h:
        a1 += trend
    written = lumped_newton.written(lay, rows)
    rebuild = written
    previous = math.inf
    status = _residual(t1, y, acc, a1, h, coef, p, w, inc, ya, ydot, d, res, f0)
    work[2] += 1
    f_iterate[:] = ydot[nq : nq + nv]
    rate = coef[2] / (b * h)  # a state's change per unit of rate against a position's
    merit = _merit(res, inc, rate)
    updates = 0
    for it in range(max_iter):
        if status == OK and (rebuild or fresh[0] == 0.0 or fresh[1] != h):
            status, updates = _matrix(t1, y, acc, a1, h, coef, p, pj, w, inc, lay, rows, carry,
                                      res, vec, work, updates, rigid)  # fmt: skip
            rebuild = False
            previous = math.inf
        if status != OK:
            work[3] += 1
            fresh[0] = 0.0
            return status
        work[5] += 1
        if rigid is not None and rows.line.shape[0] > 0:
            rigid_newton.rhs(rows, p, res, big[0])
            bordered.solve(lay, mat, piv, big[0], big[1], big[2])
            da[:] = big[1][:nv]
        else:
            bordered.solve(lay, mat, piv, res, da, z)
        largest = 0.0
        for i in range(nv):
            scaled = abs(da[i]) * inc.weight[i]
            largest = max(largest, scaled * rate if i >= inc.q_of_v.shape[0] else scaled)
        if not math.isfinite(largest):
            work[3] += 1
            fresh[0] = 0.0
            return NON_FINITE
        if lumped_newton.converged(b * h * h * largest, largest / previous, tol, written):
            a1 -= da
            _state(y, acc, a1, h, coef, inc, ya, d, p.n_q)
            if system_kernel.accept(t1, ya, p, w) != 0:  # a line's failure
                fresh[0] = 0.0  # Newton's matrix is not the new system's
            else:  # the last residual's forces start the next step (module docstring)
                lumped_newton.ends(ends, f_iterate, da, res, coef, written)
                fresh[3] = 1.0
            y[:] = ya
            for i in range(nv):
                trend[i] = a1[i] - acc[i]
            _estimate(trend, h, coef, p, w, fresh)
            fresh[2] = h
            acc[:] = a1
            work[0] += 1
            return OK
        rebuild = _stale(largest, previous, tol / (b * h * h), max_iter - it - 2)
        previous = largest
        status, merit, cut = _search(t1, y, acc, a1, da, h, coef, p, w, inc, merit, vec, work)
        if cut:
            rebuild = True
    fresh[0] = 0.0
    fresh[2] = 0.0
    return NEWTON_FAILED


@njit(**JIT)
def chunk(
    first_step, y, acc, output_interval, steps_per_output, outputs_per_step, n_steps, coef, tol,
    max_iter, p, pj, w, inc, lay, rows, carried, states, times, work, rigid,
):  # fmt: skip
    """Advance ``n_steps`` implicit steps ``output_interval / steps_per_output`` [s] from global
    step ``first_step`` (which may lie inside an output interval), a row in ``states`` at each
    output reached; or, ``outputs_per_step`` m > 1 (``steps_per_output`` 1), steps of m
    output intervals, each giving m rows, those inside it interpolated (``numerics.dense``).

    ``acc`` holds the scheme's acceleration a0 at the start (the system's acceleration at the
    first call; the algorithmic one after), and is updated; ``pj`` is ``frozen(p)``, the
    parameters of Newton's matrix; ``rows`` the rigid lines written in maximal coordinates
    (``newton``); ``carried`` is ``carry``'s tuple,
    updated. ``tol`` [m] bounds the last Newton correction of the positions (b h^2 |da|, each
    unknown in metres through ``Increments.weight``). A step whose iteration fails (regularised
    seabed friction can make Newton cycle at long steps) is retried in 2, 4, ... MAX_SUBSTEPS
    equal parts, each retry counted as a rejected step. Returns (outputs reached, status);
    ``work`` gets [accepted, rejected, rhs evaluations, failed evaluations, Jacobian
    evaluations, linear solves, matrix updates] (a Jacobian's residuals count as rhs
    evaluations; accepted counts substeps; an update: the seabed's terms alone, see _step).
    ``rigid``: True, or None when ``rows`` holds no rigid line: numba compiles the chunk apart
    for None and leaves the rigid lines' Newton rows out (a branch on ``rigid is None`` is
    pruned before typing)."""
    ny = y.shape[0]
    nv = acc.shape[0]
    m = outputs_per_step
    dt = output_interval / steps_per_output if m == 1 else m * output_interval
    vec = np.empty((11, ny))
    big = np.empty((3, rows.size))
    y_saved = np.empty(ny)
    acc_saved = np.empty(nv)
    first_output = first_step // steps_per_output
    step = first_step - first_output * steps_per_output  # into its output interval
    j = np.int64(0)  # not a literal: record compiles once
    hull.reuse(w.hull, NEAR * tol, FAR * tol)  # module docstring, REUSE; 0 again on return
    for _ in range(n_steps):
        if m == 1:
            t = step_time(first_output, output_interval, steps_per_output, step, dt)
            t_next = step_time(first_output, output_interval, steps_per_output, step + 1, dt)
        else:  # as dense.record's output times
            t = (first_output + step) * m * output_interval
            t_next = (first_output + step + 1) * m * output_interval
        y_saved[:] = y
        acc_saved[:] = acc
        parts = 1
        while True:
            status = OK
            h = dt / parts
            for k in range(parts):
                t1 = t_next if k + 1 == parts else t + (k + 1) * h
                status = _step(t + k * h, t1, y, acc, h, coef, tol, max_iter, p, pj, w, inc,
                               lay, rows, carried, vec, big, work, rigid)  # fmt: skip
                if status != OK:
                    break
            if status == OK:
                break
            work[1] += 1
            y[:] = y_saved
            acc[:] = acc_saved
            if parts >= MAX_SUBSTEPS:
                hull.reuse(w.hull, 0.0, 0.0)
                return j, status
            parts *= 2
        step += 1
        if m == 1:
            j = record(step, steps_per_output, first_output, output_interval, y, states, times, j)
        else:
            j = dense.record(y_saved, y, dt, first_output + step - 1, m, output_interval,
                             inc.q_of_v, inc.quat_q, inc.quat_v, p, states, times, j)  # fmt: skip
    hull.reuse(w.hull, 0.0, 0.0)
    return j, OK
