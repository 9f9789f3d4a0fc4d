"""A rod: a slender rigid cylinder fixed to a body (a spar, a semi-submersible's column or
pontoon, a brace: MoorDyn's rods on a body, OrcaFlex's cylinders of a spar buoy), with the
hydrostatic and Morison loads of its part under the instantaneous surface.

The rod runs from end A to end B (body frame [m]), diameter d, cut into n segments of length
l. On each segment's wetted part (kernels.morison.wet_part: the share of its axis under the
surface drawn straight between its ends' elevations, with its centroid), of volume
V = A l s (A = pi d^2 / 4, s the wetted share), in water of velocity u and acceleration a
(the current's and the waves' at the centroid, the environment's stretching):

- buoyancy rho g V upwards at the centroid (the pressure of the still water on the closed
  surface under the waterline: with the moment below, the exact hydrostatics of a cylinder
  cut by the surface);
- normal drag 0.5 rho Cd d l s |u_n| u_n on the normal part u_n of the water's velocity
  relative to the segment (the body's velocity there, v + omega x r);
- Froude-Krylov and added-mass inertia rho V (a + Ca a_n) (kernels.morison.inertia, Ca the
  normal added-mass coefficient): Morison's inertia term, the axial Froude-Krylov included
  (it is the pressure difference between the ends);

and at each wetted end (under the surface):

- axial drag 0.5 rho CdEnd A |u_t| u_t on the axial part of the relative velocity;
- axial added mass CaEnd rho (pi d^3 / 12) on the water's axial acceleration (half a sphere of
  the rod's diameter per end, as MoorDyn has it).

A rod crossing the surface (one end wet, the other dry) at an angle theta from the vertical
also takes the moment of the waterplane's tilt, rho g I (-tan(theta) e + tan(theta)^2 t / 2)
x z (I = pi d^4 / 64, t the axis from the wet end up, e the section's direction of steepest
rise): the submerged part's centroid lies off the axis by that much. With the segments'
buoyancy it makes the exact restoring of a tilted column, rho g (I + V z_b) theta for small
angles; its potential is rho g I sin(theta) tan(theta) / 2.

The rod's own added mass (normal and end terms on its part under the still water at the
body's start pose) joins the body's (``added_mass``), so that the body's acceleration meets
it; the rod's mass is the body's (give the body's ``mass`` and inertia with its rods).
"""

import math

import numpy as np

from seacable.bodies.dynamics import add_force
from seacable.bodies.kinematics import turn
from seacable.kernels import morison, waves
from seacable.kernels.chain3d_layout import _current
from seacable.kernels.jit import inner
from seacable.kernels.surface import segment_submersion
from seacable.packing import transported

ROW = 12  # A (3), B (3) [m] body frame; d [m]; n; Cd, Ca, CdEnd, CaEnd
END_VOLUME = math.pi / 12.0  # the end's added volume over d^3: half a sphere of diameter d


def pack(spec) -> list[float]:
    """The row of a ``rod`` (case.forces.Rod)."""
    return [*spec.end_a, *spec.end_b, spec.diameter, float(spec.segments),
            spec.drag_coefficient, spec.added_mass_coefficient, spec.end_drag_coefficient,
            spec.end_added_mass_coefficient]  # fmt: skip


def added_mass(row, rho: float, position, rot) -> np.ndarray:
    """The rod's added mass [kg, kg m, kg m^2] (6x6, body frame, at the reference point) on
    its part under the still water with the body at ``position`` [m], turned by ``rot``
    (3x3): the normal term of each segment at its wetted part's centroid, the axial term of
    each wetted end."""
    row = np.asarray(row, float)
    a_b, b_b, d, n = row[0:3], row[3:6], row[6], int(row[7])
    ca, ca_end = row[9], row[11]
    axis = b_b - a_b
    length = float(np.linalg.norm(axis))
    tb = axis / length
    normal = np.eye(3) - np.outer(tb, tb)
    area = math.pi * d * d / 4.0

    def z_of(r):  # a body-frame point's elevation [m]
        return position[2] + (rot @ r)[2]

    total = np.zeros((6, 6))
    for i in range(n):
        p0, p1 = a_b + axis * (i / n), a_b + axis * ((i + 1) / n)
        wet, share, _ = segment_submersion(z_of(p0), z_of(p1))
        if wet > 0.0:  # the wetted part's normal added mass, and its own turning's
            mass = ca * rho * area * length / n * wet
            part = _point_mass(mass * normal, share * p0 + (1.0 - share) * p1)
            part[3:, 3:] += mass * (length / n * wet) ** 2 / 12.0 * normal
            total += part
    for end in (a_b, b_b):
        if z_of(end) < 0.0:
            total += _point_mass(ca_end * rho * END_VOLUME * d**3 * np.outer(tb, tb), end)
    return total


def _point_mass(m3: np.ndarray, r) -> np.ndarray:
    """A 3x3 mass at body-frame point r as a 6x6 at the reference point (v + w x r)."""
    m6 = np.zeros((6, 6))
    m6[:3, :3] = m3
    return transported(m6, tuple(float(v) for v in r))


@inner
def _ends(row, pos, rot):
    """The ends A and B in the earth frame, the unit axis from A to B and the length [m]."""
    a = turn(rot, (row[0], row[1], row[2]))
    b = turn(rot, (row[3], row[4], row[5]))
    a = (pos[0] + a[0], pos[1] + a[1], pos[2] + a[2])
    b = (pos[0] + b[0], pos[1] + b[1], pos[2] + b[2])
    length = math.sqrt((b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2 + (b[2] - a[2]) ** 2)
    return a, b, ((b[0] - a[0]) / length, (b[1] - a[1]) / length, (b[2] - a[2]) / length), length


@inner
def _relative(c, pos, vel, omega, current_z, current_u, current_v, u):
    """The water's velocity ``u`` plus the current's at point c, less the body's there."""
    r = (c[0] - pos[0], c[1] - pos[1], c[2] - pos[2])
    cu, cv = _current(current_z, current_u, current_v, c[2])
    return (
        u[0] + cu - vel[0] - (omega[1] * r[2] - omega[2] * r[1]),
        u[1] + cv - vel[1] - (omega[2] * r[0] - omega[0] * r[2]),
        u[2] - vel[2] - (omega[0] * r[1] - omega[1] * r[0]),
    )


@inner
def _waterplane_moment(tangent, wet_a, rho_g_i):
    """The moment [N m] of the waterplane's tilt on a rod crossing the surface (module
    docstring); ``wet_a``: end A is the wet one."""
    sign = 1.0 if wet_a else -1.0
    t = (sign * tangent[0], sign * tangent[1], sign * tangent[2])  # from the wet end up
    cos = t[2]
    if cos <= 1e-9:
        return 0.0, 0.0
    # e tan(theta) = (z - cos t) / cos; the moment of (-tan e + tan^2 t / 2) x z
    tan2 = (1.0 - cos * cos) / (cos * cos)
    ox = -(0.0 - cos * t[0]) / cos + 0.5 * tan2 * t[0]
    oy = -(0.0 - cos * t[1]) / cos + 0.5 * tan2 * t[1]
    # (ox, oy, oz) x (0, 0, 1) = (oy, -ox, 0)
    return rho_g_i * oy, -rho_g_i * ox


@inner
def add(row, pos, rot, vel, omega, rho, gravity, current_z, current_u, current_v, t, wave,
        depth, stretch, trig, rhs):  # fmt: skip
    """The rod's loads (module docstring) as a force and a moment about the body's reference
    point ``pos`` into ``rhs`` (6); ``trig``: kernels.waves' scratch."""
    a, b, tangent, length = _ends(row, pos, rot)
    d, n = row[6], int(row[7])
    cd, ca, cd_end, ca_end = row[8], row[9], row[10], row[11]
    area = 0.25 * math.pi * d * d
    seg = length / n
    highest = morison.crest(wave)
    still = (0.0, 0.0, 0.0)
    for i in range(n):
        f0, f1 = i / n, (i + 1) / n
        p0 = (a[0] + f0 * (b[0] - a[0]), a[1] + f0 * (b[1] - a[1]), a[2] + f0 * (b[2] - a[2]))
        p1 = (a[0] + f1 * (b[0] - a[0]), a[1] + f1 * (b[1] - a[1]), a[2] + f1 * (b[2] - a[2]))
        wet, share = morison.wet_part(wave, t, highest, p0[0], p0[1], p0[2], p1[0], p1[1],
                                      p1[2], trig)  # fmt: skip
        if wet <= 0.0:
            continue
        c = morison.centroid(share, p0, p1)
        arm = (c[0] - pos[0], c[1] - pos[1], c[2] - pos[2])
        volume = area * seg * wet
        add_force(arm, 0.0, 0.0, rho * gravity * volume, rhs)
        u, acc = still, still
        if wave.shape[1] > 0:
            u, acc = morison.water_at(wave, t, c, depth, stretch, trig)
            fi = morison.inertia(rho * volume, ca * rho * volume, 0.0, acc[0], acc[1], acc[2],
                                 tangent[0], tangent[1], tangent[2])  # fmt: skip
            add_force(arm, fi[0], fi[1], fi[2], rhs)
        if cd > 0.0:
            rel = _relative(c, pos, vel, omega, current_z, current_u, current_v, u)
            along = rel[0] * tangent[0] + rel[1] * tangent[1] + rel[2] * tangent[2]
            rn = (rel[0] - along * tangent[0], rel[1] - along * tangent[1],
                  rel[2] - along * tangent[2])  # fmt: skip
            k = 0.5 * rho * cd * d * seg * wet * math.sqrt(rn[0] ** 2 + rn[1] ** 2 + rn[2] ** 2)
            add_force(arm, k * rn[0], k * rn[1], k * rn[2], rhs)
    wet_a = a[2] < waves.elevation(wave, t, a[0], a[1], trig)
    wet_b = b[2] < waves.elevation(wave, t, b[0], b[1], trig)
    for end in range(2):
        if not (wet_a if end == 0 else wet_b):
            continue
        c = a if end == 0 else b
        arm = (c[0] - pos[0], c[1] - pos[1], c[2] - pos[2])
        u, acc = still, still
        if wave.shape[1] > 0:
            u, acc = morison.water_at(wave, t, c, depth, stretch, trig)
        rel = _relative(c, pos, vel, omega, current_z, current_u, current_v, u)
        along = rel[0] * tangent[0] + rel[1] * tangent[1] + rel[2] * tangent[2]
        a_along = acc[0] * tangent[0] + acc[1] * tangent[1] + acc[2] * tangent[2]
        k = 0.5 * rho * cd_end * area * abs(along) * along + ca_end * rho * END_VOLUME * d**3 * (
            a_along
        )
        add_force(arm, k * tangent[0], k * tangent[1], k * tangent[2], rhs)
    if wet_a != wet_b:
        mx, my = _waterplane_moment(tangent, wet_a, rho * gravity * math.pi * d**4 / 64.0)
        rhs[3] += mx
        rhs[4] += my


@inner
def potential(row, pos, rot, rho, gravity):
    """The potential [J] of the rod's hydrostatic load in still water: -rho g A l times the
    mean of min(z, 0) along each segment, and the waterplane's rho g I sin tan / 2."""
    a, b, tangent, length = _ends(row, pos, rot)
    d, n = row[6], int(row[7])
    area = 0.25 * math.pi * d * d
    total = 0.0
    for i in range(n):
        za = a[2] + (i / n) * (b[2] - a[2])
        zb = a[2] + ((i + 1) / n) * (b[2] - a[2])
        _, _, mean_depth = segment_submersion(za, zb)
        total -= rho * gravity * area * (length / n) * mean_depth
    if (a[2] < 0.0) != (b[2] < 0.0):
        cos = abs(tangent[2])
        if cos > 1e-9:
            sin = math.sqrt(max(0.0, 1.0 - cos * cos))
            total += rho * gravity * math.pi * d**4 / 64.0 * 0.5 * sin * sin / cos
    return total
