"""Sparse Newton matrices of systems of bodies and lines: banded blocks bordered by a few dense
rows and columns, factorised in O(total unknowns) (numba).

The unknowns are ordered so that each *block* (the unknowns of one line, or of lines that
couple directly, such as a tree of rigid lines) is contiguous and banded, and the *border*
(the bodies' degrees of freedom) comes last::

    [ A_1            B_1 ] [x_1]   [r_1]
    [      ...       ... ] [...] = [...]
    [           A_m  B_m ] [x_m]   [r_m]
    [ C_1  ...  C_m  D   ] [x_b]   [r_b]

Blocks couple to each other only through the border. Each A_l is factorised by banded
Gaussian elimination with partial pivoting (LINPACK's scheme: the upper band grows by the lower
bandwidth), then the border's Schur complement S = D - sum_l C_l A_l^-1 B_l is formed and
factorised densely (it is stored as a band as wide as itself). B_l and C_l keep only the border
columns and rows that block l touches. A factorisation costs O(sum_l n_l kl_l (kl_l + ku_l) +
n_l t_l (kl_l + ku_l) + border^3) for blocks of n_l unknowns, bandwidths kl_l, ku_l and t_l
touched border unknowns; a solve, the same without the cubes.

A block whose unknowns come in threes that couple only to the threes before and after
(``tri``: a lumped line's interior nodes, each with its two neighbours) is factorised instead
as 3 x 3 blocks without pivoting (block LU, each diagonal block's Schur complement inverted by
cofactors in its place in the band): a lumped line's matrix is (1 - am) I plus M^-1 times a
symmetric positive semi-definite one, up to the friction's and the axial damping's small
unsymmetric parts, which block LU factorises stably; a zero or non-finite determinant fails
the factorisation as a zero pivot does. On three 50-segment lines (147 unknowns each,
bandwidths 5) a factorisation takes 5 us and a solve 3 us so, 20 and 11 us by the banded
elimination (compiled loops of each).

Every matrix entry lives in one flat array ``mat`` (bands first, the border's band, then every
B_l and every C_l); ``structure`` maps each non-zero (row, column) of a pattern to its place
(``dest``) so that a finite-difference Jacobian is written straight into it.
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit
from scipy import sparse

from seacable.kernels.chain3d import adjugate3
from seacable.kernels.jit import JIT, inner


class Bordered(NamedTuple):
    """Where each unknown and each matrix entry goes (all flat, with offsets; see the module
    docstring). Blocks 0..m-1 are the banded blocks, block m the border."""

    order: np.ndarray  # (N,) int: the unknown at each position
    start: np.ndarray  # (m + 2,) int: first position of each block (the border last), then N
    kl: np.ndarray  # (m + 1,) int: lower bandwidth
    ku: np.ndarray  # (m + 1,) int: upper bandwidth
    band: np.ndarray  # (m + 1,) int: first entry of the block's band in ``mat``
    touch_at: np.ndarray  # (m + 1,) int: first entry of the block's touched border in touch
    touch: np.ndarray  # border positions (relative to the border's start) each block touches
    b_at: np.ndarray  # (m,) int: first entry of B_l in ``mat`` (n_l x t_l, row-major)
    c_at: np.ndarray  # (m,) int: first entry of C_l in ``mat`` (t_l x n_l, row-major)
    size: int  # entries of ``mat``
    nz_ptr: np.ndarray  # (N + 1,) int: the pattern's non-zeros of each column (unknown)
    nz_row: np.ndarray  # row (unknown) of each non-zero
    nz_dest: np.ndarray  # its entry in ``mat``
    colour_ptr: np.ndarray  # (colours + 1,) int: columns of each colour in colour_cols
    colour_cols: np.ndarray  # columns (unknowns) that share no row, colour by colour
    tri: np.ndarray  # (m + 1,) int: 1 where a block is factorised as 3 x 3 blocks (module
    # docstring; the border never)


def _width(kl: int, ku: int) -> int:
    return 2 * kl + ku + 1


def structure(
    pattern: sparse.spmatrix,
    border: np.ndarray,
    colours: np.ndarray,
    key: np.ndarray | None = None,
    triple: np.ndarray | None = None,
) -> Bordered:
    """The layout for a square ``pattern`` (the non-zeros of the matrix; the diagonal is added)
    whose unknowns ``border`` (a boolean mask) form the border; ``colours`` groups columns that
    share no row (``system.coordinates.colour``; a negative colour: a column the differences
    leave out, its entries written otherwise). Unknowns outside the border that couple
    directly are put in one block, ordered by ``key`` (default: by index; a block whose
    unknowns are numbered apart, such as a rigid line's accelerations and its auxiliary
    unknowns, is kept banded by a key that interleaves them). ``triple`` (a boolean mask, None:
    none) marks the unknowns whose blocks may be factorised as 3 x 3 blocks without pivoting
    (``tri``): a block of them only, in threes each coupled to its neighbours, bandwidths 5."""
    n = pattern.shape[0]
    coo = (sparse.csr_matrix(pattern) + sparse.identity(n, format="csr")).tocoo()
    rows, cols = coo.row.astype(np.int64), coo.col.astype(np.int64)
    border = np.asarray(border, dtype=bool)
    inner = ~border[rows] & ~border[cols]
    link = sparse.coo_matrix((np.ones(int(inner.sum())), (rows[inner], cols[inner])), (n, n))
    _, label = sparse.csgraph.connected_components(link, directed=False)
    label = np.where(border, -1, label)
    rank = np.arange(n) if key is None else np.asarray(key)
    blocks = [np.flatnonzero(label == g) for g in np.unique(label[~border])]
    blocks = [b[np.argsort(rank[b], kind="stable")] for b in blocks]
    blocks.sort(key=lambda b: int(b[0]))
    order = np.concatenate([*blocks, np.flatnonzero(border)]).astype(np.int64)
    position = np.empty(n, dtype=np.int64)
    position[order] = np.arange(n)
    m = len(blocks)
    start = np.zeros(m + 2, dtype=np.int64)
    start[1 : m + 1] = np.cumsum([len(b) for b in blocks])
    start[m + 1] = n
    block_of = np.full(n, m, dtype=np.int64)  # by position
    for g in range(m):
        block_of[start[g] : start[g + 1]] = g
    pr, pc = position[rows], position[cols]
    kl = np.zeros(m + 1, dtype=np.int64)
    ku = np.zeros(m + 1, dtype=np.int64)
    nb = int(n - start[m])
    kl[m] = ku[m] = max(nb - 1, 0)
    same = block_of[pr] == block_of[pc]
    np.maximum.at(kl, block_of[pr][same], np.maximum(pr - pc, 0)[same])
    np.maximum.at(ku, block_of[pr][same], np.maximum(pc - pr, 0)[same])
    kl[m] = ku[m] = max(nb - 1, 0)
    band = np.zeros(m + 1, dtype=np.int64)
    at = 0
    for g in range(m + 1):
        band[g] = at
        at += int(start[g + 1] - start[g]) * _width(int(kl[g]), int(ku[g]))
    # the border each block touches: keys g * nb + (border position), sorted
    cross = ~same
    r_in = block_of[pr[cross]] < m
    g_of = np.where(r_in, block_of[pr[cross]], block_of[pc[cross]])
    b_of = np.where(r_in, pc[cross], pr[cross]) - start[m]
    keys = np.unique(g_of * max(nb, 1) + b_of)
    touch = (keys % max(nb, 1)).astype(np.int64)
    touch_at = np.searchsorted(keys // max(nb, 1), np.arange(m + 1)).astype(np.int64)
    count = np.diff(touch_at)
    sizes = np.diff(start[: m + 1])
    b_at = (at + np.cumsum(sizes * count) - sizes * count).astype(np.int64)
    at += int(np.sum(sizes * count))
    c_at = (at + np.cumsum(sizes * count) - sizes * count).astype(np.int64)
    at += int(np.sum(sizes * count))
    # where each non-zero goes
    dest = np.empty(len(rows), dtype=np.int64)
    g = block_of[pr[same]]
    i, j = pr[same] - start[g], pc[same] - start[g]
    dest[same] = band[g] + i * (2 * kl[g] + ku[g] + 1) + (j - i + kl[g])
    t = np.searchsorted(keys, g_of * max(nb, 1) + b_of)
    t = t - touch_at[g_of]
    local = np.where(r_in, pr[cross], pc[cross]) - start[g_of]
    dest[cross] = np.where(
        r_in,
        b_at[np.minimum(g_of, m - 1)] + local * count[np.minimum(g_of, m - 1)] + t,
        c_at[np.minimum(g_of, m - 1)] + t * sizes[np.minimum(g_of, m - 1)] + local,
    )
    by_col = np.argsort(cols, kind="stable")
    nz_ptr = np.zeros(n + 1, dtype=np.int64)
    nz_ptr[1:] = np.cumsum(np.bincount(cols, minlength=n))
    colours = np.asarray(colours, dtype=np.int64)
    counted = np.flatnonzero(colours >= 0)
    colour_cols = counted[np.argsort(colours[counted], kind="stable")].astype(np.int64)
    colour_ptr = np.zeros(int(colours.max(initial=-1)) + 2, dtype=np.int64)
    colour_ptr[1:] = np.cumsum(np.bincount(colours[counted], minlength=len(colour_ptr) - 1))
    tri = np.zeros(m + 1, dtype=np.int64)
    if triple is not None:
        apart = np.zeros(m + 1, dtype=bool)  # an entry beyond the neighbouring threes
        np.logical_or.at(
            apart, g, np.abs((pr[same] - start[g]) // 3 - (pc[same] - start[g]) // 3) > 1
        )
        mask = np.asarray(triple, dtype=bool)
        for b in range(m):
            mine = order[start[b] : start[b + 1]]
            tri[b] = int(len(mine) % 3 == 0 and not apart[b] and bool(mask[mine].all())
                         and kl[b] == 5 and ku[b] == 5)  # fmt: skip
    return Bordered(
        order=order, start=start, kl=kl, ku=ku, band=band, touch_at=touch_at, touch=touch,
        b_at=b_at, c_at=c_at, size=at, nz_ptr=nz_ptr, nz_row=rows[by_col],
        nz_dest=dest[by_col], colour_ptr=colour_ptr, colour_cols=colour_cols, tri=tri,
    )  # fmt: skip


@inner
def _band_factor(mat, at, n, kl, ku, piv, p0):
    """Banded LU with partial pivoting, in place (rows of width 2 kl + ku + 1 from column
    i - kl); row swaps in piv[p0 + k]. False on a zero or non-finite pivot."""
    w = 2 * kl + ku + 1
    for k in range(n):
        last = min(n - 1, k + kl)
        best = k
        big = abs(mat[at + k * w + kl])
        for r in range(k + 1, last + 1):
            v = abs(mat[at + r * w + (k - r + kl)])
            if v > big:
                best, big = r, v
        if big == 0.0 or not np.isfinite(big):
            return False
        piv[p0 + k] = best
        right = min(n - 1, k + kl + ku)
        if best != k:
            for c in range(k, right + 1):
                a = at + k * w + (c - k + kl)
                b = at + best * w + (c - best + kl)
                mat[a], mat[b] = mat[b], mat[a]
        pivot = mat[at + k * w + kl]
        for r in range(k + 1, last + 1):
            rk = at + r * w + (k - r + kl)
            f = mat[rk] / pivot
            mat[rk] = f
            if f != 0.0:
                for c in range(k + 1, right + 1):
                    mat[at + r * w + (c - r + kl)] -= f * mat[at + k * w + (c - k + kl)]
    return True


@inner
def _band_solve(mat, at, n, kl, ku, piv, p0, x, x0, stride):
    """Solve in place with ``_band_factor``'s factors for the vector x[x0 + i * stride]."""
    w = 2 * kl + ku + 1
    for k in range(n):
        p = piv[p0 + k]
        if p != k:
            a, b = x0 + k * stride, x0 + p * stride
            x[a], x[b] = x[b], x[a]
        xk = x[x0 + k * stride]
        if xk != 0.0:
            for r in range(k + 1, min(n - 1, k + kl) + 1):
                x[x0 + r * stride] -= mat[at + r * w + (k - r + kl)] * xk
    for k in range(n - 1, -1, -1):
        acc = x[x0 + k * stride]
        for c in range(k + 1, min(n - 1, k + kl + ku) + 1):
            acc -= mat[at + k * w + (c - k + kl)] * x[x0 + c * stride]
        x[x0 + k * stride] = acc / mat[at + k * w + kl]


@njit(inline="always", **JIT)
def _at(at, w, kl, i, j):
    """The place of entry (i, j) of a block's band (rows of width w from column i - kl)."""
    return at + i * w + j - i + kl


@inner
def _tri_factor(mat, at, n, kl, ku):
    """Block LU without pivoting of a ``tri`` block of n unknowns, in its band: each
    sub-diagonal 3 x 3 block A_{I,I-1} becomes L_I = A_{I,I-1} D_{I-1}^-1 and each diagonal
    block the inverse of its Schur complement D_I = A_II - L_I A_{I-1,I}; the super-diagonal
    blocks stay. False on a zero or non-finite determinant."""
    w = 2 * kl + ku + 1
    low = np.empty(9)
    d = np.empty(9)
    for big in range(n // 3):
        i0 = 3 * big
        if big > 0:
            j0 = i0 - 3
            for r in range(3):
                for c in range(3):
                    total = 0.0
                    for e in range(3):
                        total += (
                            mat[_at(at, w, kl, i0 + r, j0 + e)]
                            * mat[_at(at, w, kl, j0 + e, j0 + c)]
                        )
                    low[3 * r + c] = total
            for r in range(3):
                for c in range(3):
                    mat[_at(at, w, kl, i0 + r, j0 + c)] = low[3 * r + c]
                    total = 0.0
                    for e in range(3):
                        total += low[3 * r + e] * mat[_at(at, w, kl, j0 + e, i0 + c)]
                    mat[_at(at, w, kl, i0 + r, i0 + c)] -= total
        for r in range(3):
            for c in range(3):
                d[3 * r + c] = mat[_at(at, w, kl, i0 + r, i0 + c)]
        det, adjugate = adjugate3(d)
        if det == 0.0 or not math.isfinite(det):
            return False
        for r in range(3):
            for c in range(3):
                mat[_at(at, w, kl, i0 + r, i0 + c)] = adjugate[3 * r + c] / det
    return True


@inner
def _tri_solve(mat, at, n, kl, ku, x, x0, stride):
    """Solve in place with ``_tri_factor``'s factors for the vector x[x0 + i * stride]."""
    w = 2 * kl + ku + 1
    for big in range(1, n // 3):  # z_I = r_I - L_I z_{I-1}
        i0, j0 = 3 * big, 3 * big - 3
        a, b, c = x[x0 + j0 * stride], x[x0 + (j0 + 1) * stride], x[x0 + (j0 + 2) * stride]
        for r in range(3):
            x[x0 + (i0 + r) * stride] -= (
                mat[_at(at, w, kl, i0 + r, j0)] * a
                + mat[_at(at, w, kl, i0 + r, j0 + 1)] * b
                + mat[_at(at, w, kl, i0 + r, j0 + 2)] * c
            )
    t = np.empty(3)
    for big in range(n // 3 - 1, -1, -1):  # x_I = D_I^-1 (z_I - U_I x_{I+1})
        i0 = 3 * big
        for r in range(3):
            t[r] = x[x0 + (i0 + r) * stride]
            if big + 1 < n // 3:
                for e in range(3):
                    t[r] -= mat[_at(at, w, kl, i0 + r, i0 + 3 + e)] * x[x0 + (i0 + 3 + e) * stride]
        for r in range(3):
            x[x0 + (i0 + r) * stride] = (
                mat[_at(at, w, kl, i0 + r, i0)] * t[0]
                + mat[_at(at, w, kl, i0 + r, i0 + 1)] * t[1]
                + mat[_at(at, w, kl, i0 + r, i0 + 2)] * t[2]
            )


@inner
def _block_factor(s, g, mat, piv):
    """Factorise block g (``tri`` or banded)."""
    n = s.start[g + 1] - s.start[g]
    if s.tri[g] != 0:
        return _tri_factor(mat, s.band[g], n, s.kl[g], s.ku[g])
    return _band_factor(mat, s.band[g], n, s.kl[g], s.ku[g], piv, s.start[g])


@inner
def _block_solve(s, g, mat, piv, x, x0, stride):
    """Solve in place with block g's factors for the vector x[x0 + i * stride]."""
    n = s.start[g + 1] - s.start[g]
    if s.tri[g] != 0:
        _tri_solve(mat, s.band[g], n, s.kl[g], s.ku[g], x, x0, stride)
    else:
        _band_solve(mat, s.band[g], n, s.kl[g], s.ku[g], piv, s.start[g], x, x0, stride)


@njit(**JIT)
def factor(s, mat, piv):
    """Factorise the matrix in ``mat`` (laid out by ``s``) in place: every block, B_l replaced
    by A_l^-1 B_l, the border's Schur complement. False when a pivot is zero or not finite."""
    m = s.start.shape[0] - 2
    nb = s.start[m + 1] - s.start[m]
    wb = 2 * s.kl[m] + s.ku[m] + 1
    for g in range(m):
        n = s.start[g + 1] - s.start[g]
        if not _block_factor(s, g, mat, piv):
            return False
        t0, t1 = s.touch_at[g], s.touch_at[g + 1]
        nt = t1 - t0
        for j in range(nt):  # X = A^-1 B, column by column
            _block_solve(s, g, mat, piv, mat, s.b_at[g] + j, nt)
        for a in range(nt):  # S[ta, tb] -= C[a, :] X[:, b]
            ra = s.touch[t0 + a]
            for b in range(nt):
                acc = 0.0
                for k in range(n):
                    acc += mat[s.c_at[g] + a * n + k] * mat[s.b_at[g] + k * nt + b]
                cb = s.touch[t0 + b]
                mat[s.band[m] + ra * wb + (cb - ra + s.kl[m])] -= acc
    if nb > 0:
        return _band_factor(mat, s.band[m], nb, s.kl[m], s.ku[m], piv, s.start[m])
    return True


@njit(**JIT)
def solve(s, mat, piv, rhs, x, z):
    """x = matrix^-1 rhs with ``factor``'s factors (vectors indexed by unknown; ``z`` scratch
    of the same length)."""
    m = s.start.shape[0] - 2
    n_all = s.start[m + 1]
    b0 = s.start[m]
    nb = n_all - b0
    for i in range(n_all):
        z[i] = rhs[s.order[i]]
    for g in range(m):
        n = s.start[g + 1] - s.start[g]
        _block_solve(s, g, mat, piv, z, s.start[g], np.int64(1))
        t0, nt = s.touch_at[g], s.touch_at[g + 1] - s.touch_at[g]
        for a in range(nt):  # r_b -= C A^-1 r_l
            acc = 0.0
            for k in range(n):
                acc += mat[s.c_at[g] + a * n + k] * z[s.start[g] + k]
            z[b0 + s.touch[t0 + a]] -= acc
    if nb > 0:
        _band_solve(mat, s.band[m], nb, s.kl[m], s.ku[m], piv, b0, z, b0, np.int64(1))
        for g in range(m):  # x_l = A^-1 r_l - X x_b
            n = s.start[g + 1] - s.start[g]
            t0, nt = s.touch_at[g], s.touch_at[g + 1] - s.touch_at[g]
            for k in range(n):
                acc = 0.0
                for b in range(nt):
                    acc += mat[s.b_at[g] + k * nt + b] * z[b0 + s.touch[t0 + b]]
                z[s.start[g] + k] -= acc
    for i in range(n_all):
        x[s.order[i]] = z[i]
