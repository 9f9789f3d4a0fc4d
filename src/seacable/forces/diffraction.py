"""Wave excitation from a hydrodynamic database (the ship-simulator document's
``diffraction``): for each incident wave component i (kernels.waves), the database's force
transfer function X (seacable.hydrodb: per metre of amplitude, body frame, e^{-i w t}),
interpolated linearly in frequency when the case is built and in the wave's direction relative
to the body's heading at each evaluation, gives Re(X a_i e^{i theta_i}) with theta_i the wave's
phase at the body's reference point; the sum is turned into the earth frame. ``froude_krylov``
adds the database's linear Froude-Krylov part (without ``non-linear Froude-Krylov``).

A component outside the database's frequencies gets no excitation (none is known there); when
those components carry more than ``OUTSIDE`` of the waves' energy, the build says so, naming
the database, its range and the share, instead of dropping them silently.

The row: [m directions (increasing, rad), n components, the directions, then per component
and direction the six complex forces as (re, im) pairs].
"""

import logging
import math

import numpy as np

from seacable.kernels import waves
from seacable.kernels.jit import inner

OUTSIDE = 0.01  # the share of the waves' energy outside a database's frequencies said at build
log = logging.getLogger("seacable")


def pack(db, wave: np.ndarray, froude_krylov: bool) -> list[float]:
    """The row for the components ``wave`` (kernels.waves rows) from a HydroDB at the body's
    reference point (a warning when more than ``OUTSIDE`` of the waves' energy lies outside its
    frequencies)."""
    _say_outside(db, wave)
    x = db.excitation(froude_krylov)  # (n, m, 6)
    m = len(db.directions)
    out = [float(m), float(wave.shape[1]), *db.directions.tolist()]
    for omega in wave[waves.W]:
        inside = db.omega[0] <= omega <= db.omega[-1]
        per = np.zeros((m, 6), complex)
        if inside:
            for j in range(m):
                for c in range(6):
                    per[j, c] = (np.interp(omega, db.omega, x[:, j, c].real)
                                 + 1j * np.interp(omega, db.omega, x[:, j, c].imag))  # fmt: skip
        out += np.stack([per.real, per.imag], axis=-1).ravel().tolist()
    return out


def _say_outside(db, wave: np.ndarray) -> None:
    """Warn when the components outside ``db``'s frequencies carry more than ``OUTSIDE`` of
    the energy (a^2) of ``wave``."""
    energy = wave[waves.A] ** 2
    omega = wave[waves.W]
    outside = (omega < db.omega[0]) | (omega > db.omega[-1])
    total = float(energy.sum())
    share = float(energy[outside].sum()) / total if total > 0.0 else 0.0
    if share > OUTSIDE:
        name = str(db.source).split(":", 1)[-1].strip()
        log.warning(
            "hydrodynamic database '%s' covers %.4g to %.4g rad/s: %d of the %d wave components "
            "(%.1f %% of the waves' energy, %.4g to %.4g rad/s) lie outside it and get no "
            "excitation; compute the database over the waves' frequencies (seacable hydrodb "
            "--omega FIRST LAST COUNT) or cut the spectrum to its range",
            name, db.omega[0], db.omega[-1], int(outside.sum()), omega.size, 100.0 * share,
            float(omega[outside].min()), float(omega[outside].max()),
        )  # fmt: skip


@inner
def add(row, t, wave, pos, rot, scratch, rhs):
    """``scratch`` (6): the body-frame force."""
    m = int(row[0])
    n = min(int(row[1]), wave.shape[1])  # none in still water (statics)
    base = 2 + m
    # the body's heading: its x axis in the horizontal plane
    heading = math.atan2(rot[1, 0], rot[0, 0])
    fb = scratch[0:6]
    fb[:] = 0.0
    for i in range(n):
        a, w, k = wave[waves.A, i], wave[waves.W, i], wave[waves.K, i]
        cb, sb = wave[waves.COS, i], wave[waves.SIN, i]
        theta = k * (pos[0] * cb + pos[1] * sb) - w * t + wave[waves.PHASE, i]
        c, s = a * math.cos(theta), a * math.sin(theta)
        relative = math.atan2(sb, cb) - heading
        j, f = _bracket(row, m, relative)
        at0 = base + 12 * (m * i + j)
        at1 = base + 12 * (m * i + (j + 1 if m > 1 else j))
        for q in range(6):
            re = (1.0 - f) * row[at0 + 2 * q] + f * row[at1 + 2 * q]
            im = (1.0 - f) * row[at0 + 2 * q + 1] + f * row[at1 + 2 * q + 1]
            fb[q] += re * c - im * s  # Re((re + i im) a e^{i theta})
    r = waves.ramp(wave, t)[0]
    for q in range(6):
        fb[q] *= r
    for q in range(3):
        rhs[q] += rot[q, 0] * fb[0] + rot[q, 1] * fb[1] + rot[q, 2] * fb[2]
        rhs[3 + q] += rot[q, 0] * fb[3] + rot[q, 1] * fb[4] + rot[q, 2] * fb[5]


@inner
def _bracket(row, m, angle):
    """(j, f): the direction interval holding ``angle`` (wrapped into the table's range when
    it spans a full turn, else held at its ends) and the fraction across it."""
    if m == 1:
        return 0, 0.0
    first, last = row[2], row[2 + m - 1]
    while angle < first:
        angle += 2.0 * math.pi
    while angle > first + 2.0 * math.pi:
        angle -= 2.0 * math.pi
    if angle >= last:
        return m - 2, 1.0
    for j in range(m - 1):
        lo, hi = row[2 + j], row[2 + j + 1]
        if angle <= hi:
            return j, (angle - lo) / (hi - lo)
    return m - 2, 1.0
