"""Steady shapes of the 3D rigid-segment chain: shooting from the lower end (numba).

See ``models.statics`` and docs/architecture.md, "Statics (3D)"."""

import math

import numpy as np
from numba import njit

from seacable.kernels.chain3d import (
    CH_BODY_FX,
    CH_BODY_FY,
    CH_BODY_FZ,
    _basis,
    _current,
    _point_loads,
    _tf,
)
from seacable.kernels.timefn import JIT


# ---- statics: shooting from the lower end ----------------------------------------------------
@njit(**JIT)
def _static_link_force(p, i, ex, ey, ez, zc, vel):
    """Steady load on segment i with director e, centre at elevation zc, moving at vel."""
    cu, cv = _current(p.current_z, p.current_u, p.current_v, zc)
    rx, ry, rz = vel[0] - cu, vel[1] - cv, vel[2]
    vt = rx * ex + ry * ey + rz * ez
    nx, ny, nz = rx - vt * ex, ry - vt * ey, rz - vt * ez
    vn = math.sqrt(nx * nx + ny * ny + nz * nz)
    cn = -p.drag_normal[i] * vn
    ct = -p.drag_tangential[i] * abs(vt) * vt
    return cn * nx + ct * ex, cn * ny + ct * ey, cn * nz + ct * ez - p.wet_weight[i]


@njit(**JIT)
def _static_point_force(p, k, z, vel, t):
    """Steady force on the point body at node k (the bottom body when k == n), no ties."""
    cu, cv = _current(p.current_z, p.current_u, p.current_v, z)
    rx, ry, rz = vel[0] - cu, vel[1] - cv, vel[2]
    speed = math.sqrt(rx * rx + ry * ry + rz * rz)
    loads = np.empty(8)
    _point_loads(p, k, z, loads)
    dx, dy, dz = loads[4] * speed, loads[5] * speed, loads[6] * speed
    if k < p.n:
        return -dx * rx, -dy * ry, -dz * rz - loads[3]
    fx, _, _ = _tf(p, CH_BODY_FX, t)
    fy, _, _ = _tf(p, CH_BODY_FY, t)
    fz, _, _ = _tf(p, CH_BODY_FZ, t)
    return fx - dx * rx, fy - dy * ry, fz - dz * rz - loads[3]


@njit(**JIT)
def _moment_residual(p, i, ex, ey, ez, t1x, t1y, t1z, t2x, t2y, t2z, lx, ly, lz, zc, vel):
    """Components along t1, t2 of h(e) = -(lam_below - F(e)/2) (zero when e is parallel to h),
    and h . e (the segment's tension, which must be positive)."""
    inv = 1.0 / math.sqrt(ex * ex + ey * ey + ez * ez)
    ex, ey, ez = ex * inv, ey * inv, ez * inv
    fx, fy, fz = _static_link_force(p, i, ex, ey, ez, zc, vel)
    hx, hy, hz = -(lx - 0.5 * fx), -(ly - 0.5 * fy), -(lz - 0.5 * fz)
    tension = hx * ex + hy * ey + hz * ez
    # the part of h normal to e, in the fixed basis
    px, py, pz = hx - tension * ex, hy - tension * ey, hz - tension * ez
    return t1x * px + t1y * py + t1z * pz, t2x * px + t2y * py + t2z * pz, tension


@njit(**JIT)
def static_shoot(p, bottom_force, node_z, vel, t, directors, forces):
    """Steady shape of a cable with perfect joints, built from its lower end upwards.

    ``bottom_force`` is the force of the cable on whatever holds its lower end (the anchor
    reaction for a pinned end; for a free end pass NaN and the bottom body's own steady load is
    used). ``node_z`` are elevations of the nodes used for the current profile (from the last
    iterate). Fills ``directors`` (n, 3) and ``forces`` (n+1, 3): the force that the part above
    each node exerts on the part below it. Returns the number of segments whose direction did
    not converge (0 when all did).
    """
    n = p.n
    if math.isnan(bottom_force[0]):
        fx, fy, fz = _static_point_force(p, n, node_z[n], vel, t)
        lx, ly, lz = -fx, -fy, -fz
    else:
        lx, ly, lz = bottom_force[0], bottom_force[1], bottom_force[2]
    forces[n, 0], forces[n, 1], forces[n, 2] = lx, ly, lz
    failures = 0
    ex, ey, ez = 0.0, 0.0, -1.0
    for i in range(n - 1, -1, -1):
        zc = 0.5 * (node_z[i] + node_z[i + 1])
        # moment balance about the top node: e parallel to h(e) = -(lam_below - F(e) / 2);
        # Newton on the two components of h normal to e (in a fixed basis), damped
        converged = False
        for _ in range(60):
            t1x, t1y, t1z, t2x, t2y, t2z = _basis(ex, ey, ez)
            r1, r2, tens = _moment_residual(p, i, ex, ey, ez, t1x, t1y, t1z, t2x, t2y, t2z,
                                            lx, ly, lz, zc, vel)  # fmt: skip
            scale = abs(tens) + 1e-300
            if abs(r1) + abs(r2) < 1e-14 * scale and tens > 0.0:
                converged = True
                break
            eps = 1e-7
            j11, j21, _ = _moment_residual(
                p,
                i,
                ex + eps * t1x,
                ey + eps * t1y,
                ez + eps * t1z,
                t1x,
                t1y,
                t1z,
                t2x,
                t2y,
                t2z,
                lx,
                ly,
                lz,
                zc,
                vel,
            )
            j12, j22, _ = _moment_residual(
                p,
                i,
                ex + eps * t2x,
                ey + eps * t2y,
                ez + eps * t2z,
                t1x,
                t1y,
                t1z,
                t2x,
                t2y,
                t2z,
                lx,
                ly,
                lz,
                zc,
                vel,
            )
            j11, j21, j12, j22 = (
                (j11 - r1) / eps,
                (j21 - r2) / eps,
                (j12 - r1) / eps,
                (j22 - r2) / eps,
            )
            det = j11 * j22 - j12 * j21
            if det == 0.0 or tens <= 0.0:
                # no useful Newton step: follow the transmitted force instead
                fx, fy, fz = _static_link_force(p, i, ex, ey, ez, zc, vel)
                gx, gy, gz = -(lx - 0.5 * fx), -(ly - 0.5 * fy), -(lz - 0.5 * fz)
                norm = math.sqrt(gx * gx + gy * gy + gz * gz)
                if norm == 0.0:
                    break
                ex, ey, ez = gx / norm, gy / norm, gz / norm
                continue
            da = -(j22 * r1 - j12 * r2) / det
            db = -(-j21 * r1 + j11 * r2) / det
            step = math.sqrt(da * da + db * db)
            if step > 0.3:
                da, db = 0.3 * da / step, 0.3 * db / step
            ex, ey, ez = (
                ex + da * t1x + db * t2x,
                ey + da * t1y + db * t2y,
                ez + da * t1z + db * t2z,
            )
            inv = 1.0 / math.sqrt(ex * ex + ey * ey + ez * ez)
            ex, ey, ez = ex * inv, ey * inv, ez * inv
        if not converged:
            failures += 1
        directors[i, 0], directors[i, 1], directors[i, 2] = ex, ey, ez
        fx, fy, fz = _static_link_force(p, i, ex, ey, ez, zc, vel)
        lx, ly, lz = lx - fx, ly - fy, lz - fz
        if i > 0:
            bx, by, bz = _static_point_force(p, i, node_z[i], vel, t)
            lx, ly, lz = lx - bx, ly - by, lz - bz
        forces[i, 0], forces[i, 1], forces[i, 2] = lx, ly, lz
    return failures
