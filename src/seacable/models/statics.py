"""Static equilibrium of a 3D rigid-segment cable, towed at constant velocity or hanging.

In steady towing every node moves with the tow point, so the shape is the equilibrium of the
segments under their steady loads (apparent weight, drag and friction on the velocity relative to
the current) and the end forces. With perfect joints it follows exactly from the lower end
upwards (``kernels.chain3d.static_shoot``): each segment lies along the force it transmits,
corrected by half its own load. For a free lower end this is one sweep (repeated while the
depths, hence the current, settle); for a pinned lower end the anchor reaction is found by Newton
iterations on the position of the top, started from the inextensible catenary between the ends.
Elastic joints are then handled by Newton iterations on the full dynamic residual.
"""

import math

import numpy as np
from scipy.optimize import brentq

from seacable.errors import SeacableError
from seacable.kernels import chain3d as c3


class StaticsError(SeacableError):
    """The static equilibrium could not be found; the message says why and what to try."""


def _nodes(top, directors, lengths):
    return np.vstack([top, top + np.cumsum(lengths[:, None] * directors, axis=0)])


def _free(params, top, vel, time):
    n = params.n
    z = top[2] - np.concatenate([[0.0], np.cumsum(params.length)])
    directors = np.zeros((n, 3))
    forces = np.zeros((n + 1, 3))
    nan = np.full(3, np.nan)
    for _ in range(100):
        failures = c3.static_shoot(params, nan, z, vel, time, directors, forces)
        nodes = _nodes(top, directors, params.length)
        change = np.max(np.abs(nodes[:, 2] - z))
        z = nodes[:, 2]
        if change < 1e-10 * (1.0 + np.abs(z).max()):
            break
    else:
        raise StaticsError("the depths of the static shape did not settle in 100 sweeps")
    if failures:
        raise StaticsError(
            f"{failures} segment directions did not converge in the static sweep (a segment "
            "with almost no tension in a strong flow); add an end body or start from 'arc'"
        )
    return directors, forces


def _catenary_guess(params, top, anchor):
    """Anchor reaction of the inextensible catenary through both ends (initial guess)."""
    length = float(params.length.sum())
    span_vec = top - anchor
    horizontal = math.hypot(span_vec[0], span_vec[1])
    rise = span_vec[2]
    chord = math.hypot(horizontal, rise)
    if length <= chord * (1 + 1e-9):
        raise StaticsError(
            f"the cable ({length:.4g} m) is not longer than the distance between its ends "
            f"({chord:.4g} m): a rigid-segment cable cannot be stretched; move the anchor"
        )
    weight = max(float(params.wet_weight.sum()) / length, 1e-9)
    direction = np.array([span_vec[0], span_vec[1], 0.0]) / max(horizontal, 1e-12)
    if horizontal < 1e-9 * length:
        return np.array([0.0, 0.0, 0.0])
    target = math.sqrt(length**2 - rise**2)
    # 2 a sinh(h / 2a) falls from +inf to h as a grows: bracket where sinh stays finite
    a = brentq(lambda a: 2 * a * math.sinh(horizontal / (2 * a)) - target,
               horizontal / 1400.0, horizontal * 1e6)  # fmt: skip
    x_low = horizontal / 2 - a * math.asinh(rise / (2 * a * math.sinh(horizontal / (2 * a))))
    h = a * weight
    slope = math.sinh(-x_low / a)
    return h * direction + np.array([0.0, 0.0, h * slope])


def _pinned(params, top, vel, time):
    anchor = params.pin
    n = params.n
    reaction = _catenary_guess(params, top, anchor)
    directors = np.zeros((n, 3))
    forces = np.zeros((n + 1, 3))
    z = np.linspace(anchor[2], top[2], n + 1)[::-1]
    scale = float(np.abs(params.wet_weight).sum()) + 1.0

    def mismatch(reaction):
        nonlocal z
        c3.static_shoot(params, reaction, z, vel, time, directors, forces)
        start = anchor - (params.length[:, None] * directors).sum(axis=0)
        z = _nodes(start, directors, params.length)[:, 2]
        return start - top

    error = mismatch(reaction)
    for _ in range(60):
        if np.linalg.norm(error) < 1e-9 * (1.0 + params.length.sum()):
            return directors.copy(), forces.copy()
        jac = np.empty((3, 3))
        step = 1e-6 * scale
        for k in range(3):
            trial = reaction.copy()
            trial[k] += step
            jac[:, k] = (mismatch(trial) - error) / step
        delta = np.linalg.lstsq(jac, -error, rcond=None)[0]
        for damping in (1.0, 0.5, 0.25, 0.125, 0.0625):
            candidate = reaction + damping * delta
            candidate_error = mismatch(candidate)
            if np.linalg.norm(candidate_error) < np.linalg.norm(error):
                break
        reaction, error = candidate, candidate_error
    raise StaticsError(
        f"the pinned static shape did not converge (top missed by {np.linalg.norm(error):.3g} m "
        "after 60 Newton steps); check that the anchor is reachable, or start from 'arc'"
    )


def static_state(params, y0, time: float = 0.0):
    """Directors (n, 3) and node forces (n+1, 3) of the steady shape for the motion of the top
    at ``time`` (its velocity is taken as steady)."""
    top, vel, _ = c3.top_motion(time, y0, params)
    if np.any(params.joint_stiffness > 0):
        raise StaticsError(
            "the static solver handles perfect joints only (joint_stiffness and "
            "bending_stiffness zero); start from an 'arc' or remove the joint stiffness"
        )
    if params.bottom_kind == c3.BOTTOM_PINNED:
        return _pinned(params, top, vel, time)
    if np.any(params.tie_k > 0):
        raise StaticsError("the static solver does not handle tied ends; start from an 'arc'")
    return _free(params, top, vel, time)


def static_directors(params, y0, time: float = 0.0) -> np.ndarray:
    return static_state(params, y0, time)[0]
