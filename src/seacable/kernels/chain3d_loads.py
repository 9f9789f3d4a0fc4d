"""Loads on the 3D chain's segments: joint bending and damping moments (``joint_torques``),
kinematics of the nodes, drag, added mass and apparent weight on the relative velocity, and
in waves the water's inertia (``segment_loads``), the free surface's share of each
(``segment_surface``; numba; rows of ``chain3d_layout``)."""

import math

import numpy as np
from numba import njit

from seacable.kernels import morison, waves
from seacable.kernels.chain3d_layout import (
    _E,
    _F,
    _P,
    _SA,
    _SF,
    _SJ,
    _SQ,
    _TQ,
    _U,
    _V,
    _current,
)
from seacable.kernels.jit import JIT, inner
from seacable.kernels.surface import segment_submersion


@inner
def joint_torques(n, y, e0, u0, ref, ref_omega, stiffness, damping, w):
    """Bending moments V = k phi^2 / 2 and dampers on the relative angular velocity; joint i
    joins segment i - 1 (for i = 0: the direction ``ref`` turning at ``ref_omega``, the body the
    line hangs from) to segment i. Directors at ``y[e0 + 3 i]``, rates at ``y[u0 + 3 i]``."""
    for i in range(n):
        w[_TQ, i] = 0.0
        w[_TQ + 1, i] = 0.0
        w[_TQ + 2, i] = 0.0
    for i in range(n):
        bx, by, bz = y[e0 + 3 * i], y[e0 + 3 * i + 1], y[e0 + 3 * i + 2]
        if i == 0:
            ax, ay, az = ref[0], ref[1], ref[2]
            wax, way, waz = ref_omega[0], ref_omega[1], ref_omega[2]
        else:
            ax, ay, az = y[e0 + 3 * i - 3], y[e0 + 3 * i - 2], y[e0 + 3 * i - 1]
            uax, uay, uaz = y[u0 + 3 * i - 3], y[u0 + 3 * i - 2], y[u0 + 3 * i - 1]
            wax, way, waz = ay * uaz - az * uay, az * uax - ax * uaz, ax * uay - ay * uax
        ubx, uby, ubz = y[u0 + 3 * i], y[u0 + 3 * i + 1], y[u0 + 3 * i + 2]
        wbx, wby, wbz = by * ubz - bz * uby, bz * ubx - bx * ubz, bx * uby - by * ubx
        cx, cy, cz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx  # e_a x e_b
        sin_phi = math.sqrt(cx * cx + cy * cy + cz * cz)
        cos_phi = ax * bx + ay * by + az * bz
        phi = math.atan2(sin_phi, cos_phi)
        factor = phi / sin_phi if sin_phi > 1e-12 else 1.0
        k = stiffness[i] * factor
        c = damping[i]
        tx = k * cx + c * (wbx - wax)  # moment the joint exerts on segment a; -t on segment b
        ty = k * cy + c * (wby - way)
        tz = k * cz + c * (wbz - waz)
        w[_TQ, i] -= tx
        w[_TQ + 1, i] -= ty
        w[_TQ + 2, i] -= tz
        if i > 0:
            w[_TQ, i - 1] += tx
            w[_TQ + 1, i - 1] += ty
            w[_TQ + 2, i - 1] += tz


@inner
def segment_loads(n, y, e0, u0, length, wet_weight, buoyancy, drag_normal, drag_tangential,
                  added_mass, inertia, joint_stiffness, joint_damping, ref, ref_omega,
                  cz_, cu_, cv_, t, gravity, wave, wave_depth, wave_stretch, w):  # fmt: skip
    """Every node's position and velocity from node 0's (rows _P, _V of column 0, set by the
    caller) and the directors; every segment's loads (rows _F), joint and buoyancy moments
    (_TQ) and its share of the free surface (_SF, _SA, _SJ, _SQ). One line's arrays; at time
    ``t`` [s] in the incident waves ``wave`` (kernels.waves' rows, none: (0, 6)): the drag on
    the velocity relative to the water and kernels.morison's inertia at the centre, the wetted
    part under the instantaneous surface (``gravity`` [m/s^2]: the displaced mass from the
    buoyancy; ``wave`` None: compiled without the waves' code)."""
    uniform = cz_.shape[0] == 1  # read once: a call per segment with the current's arrays
    u_uniform, v_uniform = cu_[0], cv_[0]  # takes and drops three references each time
    # ``wave`` None: compiled without the waves' code (a system without waves: kernels'
    # switches, system.evaluation's WAVES); rows of none: none of it runs
    waves_on = False if wave is None else wave.shape[1] > 0
    highest = morison.crest(wave) if wave is not None and waves_on else 0.0
    trig = np.empty((0, 0)) if wave is None else waves.scratch(wave)  # each phase once
    for i in range(n):
        li = length[i]
        ex, ey, ez = y[e0 + 3 * i], y[e0 + 3 * i + 1], y[e0 + 3 * i + 2]
        ux, uy, uz = y[u0 + 3 * i], y[u0 + 3 * i + 1], y[u0 + 3 * i + 2]
        w[_E, i], w[_E + 1, i], w[_E + 2, i] = ex, ey, ez
        w[_U, i], w[_U + 1, i], w[_U + 2, i] = ux, uy, uz
        w[_P, i + 1] = w[_P, i] + li * ex
        w[_P + 1, i + 1] = w[_P + 1, i] + li * ey
        w[_P + 2, i + 1] = w[_P + 2, i] + li * ez
        w[_V, i + 1] = w[_V, i] + li * ux
        w[_V + 1, i + 1] = w[_V + 1, i] + li * uy
        w[_V + 2, i + 1] = w[_V + 2, i] + li * uz
        zc = w[_P + 2, i] + 0.5 * li * ez
        if uniform:
            cu, cv = u_uniform, v_uniform
        else:
            cu, cv = _current(cz_, cu_, cv_, zc)
        rx = w[_V, i] + 0.5 * li * ux - cu
        ry = w[_V + 1, i] + 0.5 * li * uy - cv
        rz = w[_V + 2, i] + 0.5 * li * uz
        if wave is not None and waves_on:  # wet under the instantaneous surface
            wet, share = morison.wet_part(
                wave, t, highest, w[_P, i], w[_P + 1, i], w[_P + 2, i], w[_P, i + 1],
                w[_P + 1, i + 1], w[_P + 2, i + 1], trig,
            )  # fmt: skip
        else:
            wet, share, _ = segment_submersion(w[_P + 2, i], w[_P + 2, i + 1])
        fx = fy = fz = 0.0  # the water's inertia force [N]
        if wave is not None and waves_on and wet > 0.0:
            # the water's velocity and acceleration at the wetted part's centroid
            water, (fx, fy, fz) = morison.at_wetted(
                wave, t, share, (w[_P, i], w[_P + 1, i], w[_P + 2, i]),
                (w[_P, i + 1], w[_P + 1, i + 1], w[_P + 2, i + 1]), wave_depth, wave_stretch,
                wet * buoyancy[i] / gravity, wet * added_mass[i], (ex, ey, ez), trig,
            )  # fmt: skip
            rx -= water[0]
            ry -= water[1]
            rz -= water[2]
        vt = rx * ex + ry * ey + rz * ez
        nx, ny, nz = rx - vt * ex, ry - vt * ey, rz - vt * ez
        vn = math.sqrt(nx * nx + ny * ny + nz * nz)
        cn = -drag_normal[i] * vn
        ct = -drag_tangential[i] * abs(vt) * vt
        w[_F, i] = cn * nx + ct * ex
        w[_F + 1, i] = cn * ny + ct * ey
        w[_F + 2, i] = cn * nz + ct * ez - wet_weight[i]
        segment_surface(added_mass, inertia, length, buoyancy, wet, share, w, i)
        if wet < 1.0:
            # (a branch that rewrites the loads: wholly submerged segments compute bitwise as
            # they always did) the drag and the buoyancy of the submerged part
            cn *= wet
            ct *= wet
            w[_F, i] = cn * nx + ct * ex
            w[_F + 1, i] = cn * ny + ct * ey
            w[_F + 2, i] = cn * nz + ct * ez - wet_weight[i] + (wet - 1.0) * buoyancy[i]
        if wave is not None and waves_on and wet > 0.0:
            w[_F, i] += fx
            w[_F + 1, i] += fy
            w[_F + 2, i] += fz
    joint_torques(n, y, e0, u0, ref, ref_omega, joint_stiffness, joint_damping, w)
    for i in range(n):
        if w[_SF, i] < 1.0:
            # the buoyancy's moment about the centre: (arm e) x (0, 0, lift)
            w[_TQ, i] += w[_SQ, i] * w[_E + 1, i]
            w[_TQ + 1, i] -= w[_SQ, i] * w[_E, i]


@njit(inline="always", **JIT)
def segment_surface(added_mass, inertia, length, buoyancy, wet, share_top, w, i):
    """Rows _SF, _SA, _SJ, _SQ of segment i from its submerged fraction ``wet`` and the share
    of it its top node carries (kernels.surface.segment_submersion, or kernels.morison.wet_part
    in waves): the added mass of the submerged fraction, spread as the whole segment's (so the
    rotational added inertia scales alike), and the buoyancy's moment arm to the submerged
    part's centroid."""
    w[_SF, i] = wet
    if wet < 1.0:
        ma = added_mass[i]
        lost = (1.0 - wet) * ma
        w[_SA, i] = ma - lost
        w[_SJ, i] = inertia[i] - lost * length[i] * length[i] / 12.0
        w[_SQ, i] = (0.5 - share_top) * length[i] * wet * buoyancy[i]
    else:
        w[_SA, i] = added_mass[i]
        w[_SJ, i] = inertia[i]
        w[_SQ, i] = 0.0
