"""A foil's lift and drag on its inflow, and the gear that turns it: shared by the rudder
(``forces.rudder``) and the fin (``forces.fin``).

Geometry (body frame): the span direction a (unit, from the foil's root to its tip) and the
chord at zero angle c0 (unit, normal to a, from the trailing edge to the leading edge). The
foil's sections, its inflow, lift and drag lie in the plane normal to a. At the foil angle
delta [rad], the chord is turned about a by the right-hand rule,

    c = cos(delta) c0 + sin(delta) (a x c0)

(a rudder hangs down, a = -z, with c0 = +x: c = (cos delta, -sin delta, 0), its trailing edge
to port for delta > 0). Inflow: s, the foil's velocity through the water in the body frame;
s_p = s - (s . a) a its part in the foil's plane, V = |s_p| (the flow along the span adds no
lift). The angle of attack alpha = atan2((s_p x c) . a, c . s_p) is the angle from the inflow to
the chord about a, folded into [-90, 90] deg (the foil taken as symmetric fore and aft, for
flow from its trailing edge). With q = 1/2 rho V^2, the force on the foil is

    F = q A (C_L(alpha) (a x s_p) / V - C_D(alpha) s_p / V),

lift normal to the inflow in the foil's plane, drag along the water's flow past the foil (a
foil going ahead with the chord turned nose-up about a lifts towards a x s: a rudder going
ahead at delta > 0 is pushed to starboard). C_L = a_L alpha up to the stall angle and held at
a_L alpha_stall beyond (a_L the lift slope [1/rad]), C_D = C_D0 + C_L^2 / (pi Lambda) (Lambda
the aspect ratio; no induced drag when not given); or C_L, C_D from a table in alpha (held at
its end values).

The gear (optional; a rudder's steering gear, a fin's actuator): the foil's law gives the
command delta_c and delta is a state that follows it as a rate-limited first-order lag,
d delta/dt = clip((delta_c - delta) / T, -rate, rate).

A model's row holds the foil's block from an offset ``at``: A, a_L, alpha_stall, C_D0,
1/(pi Lambda) (0: none), the table's rows n (0: the lift slope), then n rows (alpha [rad]
ascending, C_L, C_D).
"""

import math

from numba import njit

from seacable.kernels.jit import JIT

ROWS = 5  # the block's count of table rows, from its offset
HEADER = 6  # the block's floats before its table


def pack(area, lift_slope, stall_deg, drag, aspect_ratio, table) -> list[float]:
    """The foil's block: ``area`` A [m^2], ``lift_slope`` a_L [1/rad] (None with a table), the
    stall angle [deg], C_D0, the aspect ratio (None: no induced drag), the table's rows
    (alpha [deg], C_L, C_D) or None."""
    rows = [[math.radians(r[0]), float(r[1]), float(r[2])] for r in table or []]
    return [float(area), float(lift_slope or 0.0), math.radians(stall_deg), float(drag),
            1.0 / (math.pi * aspect_ratio) if aspect_ratio else 0.0, float(len(rows)),
            *(v for r in rows for v in r)]  # fmt: skip


@njit(inline="always", **JIT)
def _table(row, at, n, column, alpha):
    """Column ``column`` of the block's (alpha, C_L, C_D) table at ``alpha``, held beyond its
    ends."""
    first = at + HEADER
    if alpha <= row[first]:
        return row[first + column]
    last = first + 3 * (n - 1)
    if alpha >= row[last]:
        return row[last + column]
    k = 0
    while row[first + 3 * (k + 1)] <= alpha:
        k += 1
    a0, a1 = row[first + 3 * k], row[first + 3 * (k + 1)]
    y0, y1 = row[first + 3 * k + column], row[first + 3 * (k + 1) + column]
    return y0 + (y1 - y0) * (alpha - a0) / (a1 - a0)


@njit(inline="always", **JIT)
def coefficients(row, at, alpha):
    """C_L and C_D at the angle of attack ``alpha`` [rad] (in [-pi/2, pi/2]) of the foil whose
    block starts at ``row[at]``."""
    n = int(row[at + ROWS])
    if n > 0:
        return _table(row, at, n, 1, alpha), _table(row, at, n, 2, alpha)
    stall = row[at + 2]
    lift = row[at + 1] * min(stall, max(-stall, alpha))
    return lift, row[at + 3] + row[at + 4] * lift * lift


@njit(inline="always", **JIT)
def force(row, at, rho, s, span, chord, delta):
    """The foil's lift and drag (fx, fy, fz) [N] in the body frame: its block at ``row[at]``,
    ``s`` its velocity through the water (body frame) [m/s], ``span`` a and ``chord`` c0 (unit,
    body frame), ``delta`` its angle [rad]. None (zeros) when the foil does not move through
    the water in its plane."""
    sx, sy, sz = s
    ax, ay, az = span
    along = sx * ax + sy * ay + sz * az
    px, py, pz = sx - along * ax, sy - along * ay, sz - along * az
    speed = math.sqrt(px * px + py * py + pz * pz)
    if speed == 0.0:
        return 0.0, 0.0, 0.0
    bx, by, bz = ay * chord[2] - az * chord[1], az * chord[0] - ax * chord[2], \
        ax * chord[1] - ay * chord[0]  # fmt: skip
    cos, sin = math.cos(delta), math.sin(delta)
    cx, cy, cz = cos * chord[0] + sin * bx, cos * chord[1] + sin * by, cos * chord[2] + sin * bz
    across = ax * (py * cz - pz * cy) + ay * (pz * cx - px * cz) + az * (px * cy - py * cx)
    alpha = math.atan2(across, cx * px + cy * py + cz * pz)
    if alpha > 0.5 * math.pi:
        alpha -= math.pi
    elif alpha < -0.5 * math.pi:
        alpha += math.pi
    lift, drag = coefficients(row, at, alpha)
    lx, ly, lz = ay * pz - az * py, az * px - ax * pz, ax * py - ay * px  # a x s_p
    scale = 0.5 * rho * speed * row[at]  # q A / V
    return (scale * (lift * lx - drag * px), scale * (lift * ly - drag * py),
            scale * (lift * lz - drag * pz))  # fmt: skip


@njit(inline="always", **JIT)
def limited(value, limit):
    """``value`` within +-``limit`` (0: no limit)."""
    if limit > 0.0:
        return min(limit, max(-limit, value))
    return value


@njit(inline="always", **JIT)
def gear_rate(command, angle, rate, lag):
    """The gear's d delta/dt [rad/s]: towards ``command`` from ``angle`` [rad] with the time
    constant ``lag`` [s], at most ``rate`` [rad/s]."""
    return min(rate, max(-rate, (command - angle) / lag))
