"""State-space realizations of retardation functions: for one entry K_ij(t) of a hydrodynamic
database's retardation matrix (seacable.hydrodb), a stable, strictly proper system (A, B, C)
with C e^{A t} B ~ K_ij(t), so that the radiation memory force -int_0^inf K_ij(tau) nu_j(t -
tau) d tau is -C x with x' = A x + B nu_j (x = 0 at rest): a few first-order states instead of a
convolution over the velocity history.

The fit (Kung's Hankel-SVD realization, then least squares): the samples K(k dt) are the
Markov parameters of a discrete system; the Hankel matrix H_pq = K((p + q) dt) truncated to
its ``m`` largest singular values gives a balanced discrete matrix whose eigenvalues lambda are
the poles s = ln(lambda) / dt. Poles the samples cannot resolve (|s| dt > ``FASTEST``, or on
the negative real axis) are dropped; unstable ones reflected (Re s -> -|Re s|) and every pole
kept at Re s <= -1 / (10 T), T the sampled length, so the realization decays. The residues are
then the linear least-squares fit of the samples on the modes e^{s t} (a real pole) and
e^{sigma t} cos(w t), e^{sigma t} sin(w t) (a pair), which minimises the reported error

    error = || K_fit - K ||_2 / || K ||_2   over the samples [-].

The order grows (2, 3, ... up to ``order``) until the error is at most ``tolerance``; the best
fit is kept otherwise. The realization is real and modal (block diagonal: 1x1 blocks [s] and
2x2 blocks [[sigma, w], [-w, sigma]]), B ones on each block's last state.

Units: A [1/s], B [1], C the kernel's units (K [N/m] for a force on a velocity [m/s]: x is
then [m]); times [s].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

FASTEST = 2.0  # poles beyond |s| dt are dropped (unresolved; they would bound explicit steps)
NEGLIGIBLE = 1e-6  # entries whose peak is below this part of the largest entry's are left out


@dataclass(frozen=True)
class Realization:
    """x' = A x + B u, y = C x: C e^{A t} B approximates a retardation function."""

    a: np.ndarray  # (m, m) [1/s]
    b: np.ndarray  # (m,)
    c: np.ndarray  # (m,) the kernel's units
    error: float  # relative L2 error over the fitted samples [-]

    @property
    def order(self) -> int:
        return len(self.b)

    def response(self, times) -> np.ndarray:
        """C e^{A t} B at uniform ``times`` from 0 (the impulse response), by the exact
        transition matrix e^{A dt} (scipy.linalg.expm) applied step by step."""
        from scipy.linalg import expm

        t = np.asarray(times, dtype=float)
        step = expm(self.a * (t[1] - t[0])) if len(t) > 1 else np.eye(self.order)
        x = self.b.astype(float)
        out = np.empty(len(t))
        for k in range(len(t)):
            out[k] = self.c @ x
            x = step @ x
        return out


ROWS = 120  # the Hankel matrix's rows at most (its columns: the other samples)


def _hankel(kernel: np.ndarray) -> tuple[np.ndarray, ...]:
    """The SVD of the Hankel matrix of the samples and the shifted one."""
    rows = min(ROWS, (len(kernel) - 1) // 2)
    cols = len(kernel) - rows  # H_pq = K((p + q) dt) and the shifted K((p + q + 1) dt)
    hankel = np.array([kernel[i : i + cols] for i in range(rows)])
    shifted = np.array([kernel[i + 1 : i + 1 + cols] for i in range(rows)])
    u, s, vt = np.linalg.svd(hankel, full_matrices=False)
    return u, s, vt, shifted


def _poles(svd, dt: float, span: float, order: int) -> np.ndarray:
    """The continuous poles (upper half-plane and real axis) of Kung's realization of order
    ``order``, resolved and stable (module docstring)."""
    u, s, vt, shifted = svd
    m = min(order, int(np.sum(s > s[0] * 1e-13)))
    root = np.sqrt(s[:m])
    discrete = (u[:, :m].T @ shifted @ vt[:m].T) / np.outer(root, root)
    lam = np.linalg.eigvals(discrete).astype(complex)
    lam = lam[(np.abs(lam) > math.exp(-FASTEST)) & (np.abs(np.angle(lam)) < math.pi - 1e-9)]
    poles = np.log(lam) / dt
    poles = poles[(np.abs(poles) * dt <= FASTEST) & (poles.imag >= -1e-12)]
    slowest = -0.1 / span
    return np.minimum(-np.abs(poles.real), slowest) + 1j * np.abs(poles.imag)


def _modes(poles: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, list[tuple[float, float]]]:
    """The basis of the least squares (samples x states) and each block's (sigma, w)."""
    columns, blocks = [], []
    for p in poles:
        decay = np.exp(p.real * t)
        if p.imag <= 1e-9 * abs(p):
            columns.append(decay)
            blocks.append((p.real, 0.0))
        else:
            columns += [decay * np.sin(p.imag * t), decay * np.cos(p.imag * t)]
            blocks.append((p.real, p.imag))
    return np.stack(columns, axis=1), blocks


def _realize(blocks, residues) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The modal (A, B, C): a real pole [s], B 1, C its residue; a pair [[s, w], [-w, s]],
    B (0, 1), whose e^{A t} B = e^{s t} (sin w t, cos w t), C its two coefficients."""
    m = len(residues)
    a, b = np.zeros((m, m)), np.zeros(m)
    k = 0
    for sigma, w in blocks:
        if w == 0.0:
            a[k, k], b[k] = sigma, 1.0
            k += 1
        else:
            a[k : k + 2, k : k + 2] = [[sigma, w], [-w, sigma]]
            b[k + 1] = 1.0
            k += 2
    return a, b, np.asarray(residues, dtype=float)


def fit(times, kernel, order: int = 12, tolerance: float = 0.01) -> Realization:
    """The realization of the samples ``kernel`` at uniform ``times`` from 0 [s] of lowest
    order (2, 3, ... ``order``) whose relative L2 error is at most ``tolerance``, or the best."""
    t = np.asarray(times, dtype=float)
    k = np.asarray(kernel, dtype=float)
    dt, norm = t[1] - t[0], float(np.linalg.norm(k))
    best: Realization | None = None
    svd = _hankel(k)
    for m in range(2, max(2, order) + 1):
        poles = _poles(svd, dt, t[-1], m)
        if not len(poles):
            continue
        basis, blocks = _modes(poles, t)
        if basis.shape[1] > order:
            continue
        residues = np.linalg.lstsq(basis, k, rcond=None)[0]
        error = float(np.linalg.norm(basis @ residues - k)) / norm if norm > 0 else 0.0
        if best is None or error < best.error:
            best = Realization(*_realize(blocks, residues), error=error)
        if error <= tolerance:
            break
    if best is None:
        raise ValueError("no stable pole found in the samples: is the kernel all zeros?")
    return best


def fit_matrix(times, kernels, order: int = 12, tolerance: float = 0.01
               ) -> dict[tuple[int, int], Realization]:  # fmt: skip
    """A realization of every entry (i, j) of ``kernels`` (len(times), 6, 6) whose peak is at
    least ``NEGLIGIBLE`` times the largest entry's; the others are left out."""
    k = np.asarray(kernels, dtype=float)
    peaks = np.abs(k).max(axis=0)
    largest = peaks.max()
    return {
        (i, j): fit(times, k[:, i, j], order, tolerance)
        for i in range(k.shape[1]) for j in range(k.shape[2])
        if largest > 0.0 and peaks[i, j] >= NEGLIGIBLE * largest
    }  # fmt: skip
