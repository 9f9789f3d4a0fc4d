"""Incident waves on a cable segment (Morison's equation; numba): the segment's wetted part
under the instantaneous surface, the water's velocity and acceleration at that part's centroid
(kernels.waves, stretched above the mean level), and the inertia force of the water's
acceleration. The lumped-mass (kernels.lumped) and 3D rigid-segment (kernels.chain3d_loads)
lines share them.

On a segment of displaced mass m_d = rho A l [kg] and normal added mass m_a = Ca m_d [kg],
both of its wetted fraction s, in water of velocity u and acceleration a (at the wetted part's
centroid):

- drag on the velocity relative to the water (the current's and the waves' velocity), normal
  and tangential, as the current's alone;
- Froude-Krylov and added-mass inertia ``s (m_d a + m_a (a - (a . t) t))`` [N]: the pressure
  gradient of the undisturbed wave on the whole displaced volume (as the buoyancy acts, a full
  vector) and the added mass on the water's normal acceleration, the same matrix
  m_a (I - t t^T) the segment's own acceleration meets. A neutrally buoyant, drag-free node
  whose mass is its displaced mass is carried: its acceleration is the water's.

Above the instantaneous surface there is no water: the wetted fraction is that of the segment
below the surface drawn straight between the elevations at its two ends.
"""

from numba import njit

from seacable.kernels import waves
from seacable.kernels.jit import JIT, inner
from seacable.kernels.surface import segment_submersion


@njit(inline="always", **JIT)
def crest(wave):
    """The highest the surface can rise, sum |a_i| [m] (0 without waves): a segment wholly
    below minus it is wholly wet, its ends' elevations not needed."""
    total = 0.0
    for a in wave[waves.A]:
        total += abs(a)
    return total


@inner
def wet_part(wave, t, highest, xa, ya, za, xb, yb, zb, trig):
    """The wetted fraction s of a segment from a to b [m] under the waves' surface at time t
    [s] (``highest``: :func:`crest`), and the share of it carried by end a (kernels.surface's
    lever rule: the wetted part's centroid is ``share r_a + (1 - share) r_b``; ``trig``:
    kernels.waves' scratch). Without waves
    (or their amplitudes zero) exactly kernels.surface.segment_submersion's."""
    if max(za, zb) <= -highest:
        return 1.0, 0.5
    wet, share, _ = segment_submersion(
        za - waves.elevation(wave, t, xa, ya, trig), zb - waves.elevation(wave, t, xb, yb, trig)
    )
    return wet, share


@njit(inline="always", **JIT)
def centroid(share, a, b):
    """The wetted part's centroid ``share a + (1 - share) b`` [m] (points, tuples)."""
    return (share * a[0] + (1.0 - share) * b[0], share * a[1] + (1.0 - share) * b[1],
            share * a[2] + (1.0 - share) * b[2])  # fmt: skip


@inner
def water_at(wave, t, c, depth, stretch, trig):
    """The water's velocity (3) [m/s] and acceleration (3) [m/s^2] at the wetted part's
    centroid ``c`` (:func:`centroid`; ``trig``: kernels.waves' scratch)."""
    return waves.kinematics(wave, t, c[0], c[1], c[2], depth, stretch, trig)


@inner
def water(wave, t, share, a, b, depth, stretch, trig):
    """The water's velocity and acceleration at the wetted part's centroid between points a
    and b (:func:`centroid`, :func:`water_at`)."""
    return water_at(wave, t, centroid(share, a, b), depth, stretch, trig)


@inner
def at_wetted(wave, t, share, a, b, depth, stretch, displaced, added, tangent, trig):
    """The water's velocity (3) [m/s] at the wetted part's centroid (:func:`water`) and the
    inertia force (3) [N] of its acceleration on the wetted part (displaced and normal added
    mass [kg], unit ``tangent``; the 3D segments have no added mass along them)."""
    u, acc = water(wave, t, share, a, b, depth, stretch, trig)
    force = inertia(displaced, added, 0.0, acc[0], acc[1], acc[2], tangent[0], tangent[1],
                    tangent[2])  # fmt: skip
    return u, force


@njit(inline="always", **JIT)
def inertia(displaced, added, added_along, ax, ay, az, tx, ty, tz):
    """Froude-Krylov and added-mass force [N] of the water's acceleration (ax, ay, az)
    [m/s^2] on a segment of displaced mass ``displaced``, normal added mass ``added`` and
    added mass along it ``added_along`` [kg] (all of its wetted part), unit tangent
    (tx, ty, tz)."""
    along = ax * tx + ay * ty + az * tz
    return (
        displaced * ax + added * (ax - along * tx) + added_along * along * tx,
        displaced * ay + added * (ay - along * ty) + added_along * along * ty,
        displaced * az + added * (az - along * tz) + added_along * along * tz,
    )
