"""Static equilibrium of a 3D rigid-segment cable, towed at constant velocity or hanging.

In steady towing every node moves with the tow point, so the shape is the equilibrium of the
segments under their steady loads (apparent weight, drag and friction on the velocity relative to
the current) and the end forces. With perfect joints it follows exactly from the lower end
upwards (``kernels.chain3d_statics.static_shoot``): each segment lies along the force it transmits,
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
from seacable.kernels import chain3d_statics as c3s
from seacable.kernels.status import Status
from seacable.system.servo import sphere_directions


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
        failures = c3s.static_shoot(params, nan, z, vel, time, directors, forces)
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


def _pinned_newton(params, top, vel, time, reaction, iterations=60):
    """Newton iterations on the anchor reaction; returns (directors, forces, reaction) or None."""
    anchor = params.pin
    n = params.n
    directors = np.zeros((n, 3))
    forces = np.zeros((n + 1, 3))
    z = np.linspace(anchor[2], top[2], n + 1)[::-1]
    scale = float(np.abs(params.wet_weight).sum()) + 1.0

    def mismatch(reaction):
        nonlocal z
        c3s.static_shoot(params, reaction, z, vel, time, directors, forces)
        start = anchor - (params.length[:, None] * directors).sum(axis=0)
        z = _nodes(start, directors, params.length)[:, 2]
        return start - top

    error = mismatch(reaction)
    for _ in range(iterations):
        if not np.all(np.isfinite(error)):
            return None
        if np.linalg.norm(error) < 1e-9 * (1.0 + params.length.sum()):
            return directors.copy(), forces.copy(), reaction
        jac = np.empty((3, 3))
        step = 1e-6 * (scale + np.linalg.norm(reaction))
        for k in range(3):
            trial = reaction.copy()
            trial[k] += step
            jac[:, k] = (mismatch(trial) - error) / step
        delta = np.linalg.lstsq(jac, -error, rcond=None)[0]
        for damping in (1.0, 0.5, 0.25, 0.125, 0.0625, 0.03125):
            candidate = reaction + damping * delta
            candidate_error = mismatch(candidate)
            if np.linalg.norm(candidate_error) < np.linalg.norm(error):
                break
        else:
            return None
        reaction, error = candidate, candidate_error
    return None


def _pinned(params, top, vel, time):
    """Pinned lower end: Newton on the anchor reaction from the catenary guess; in a strong flow,
    continuation from still water (the relative flow raised step by step)."""
    guess = _catenary_guess(params, top, params.pin)
    found = _pinned_newton(params, top, vel, time, guess)
    if found is not None:
        return found[0], found[1]
    reaction = guess
    fraction, step = 0.0, 0.1
    while fraction < 1.0:
        trial = min(1.0, fraction + step)
        scaled = params._replace(
            current_u=params.current_u * trial, current_v=params.current_v * trial
        )
        found = _pinned_newton(scaled, top, np.asarray(vel) * trial, time, reaction)
        if found is None:
            step /= 2.0
            if step < 1e-3:
                raise StaticsError(
                    "the pinned static shape did not converge, even raising the flow step by "
                    f"step (stuck at {100 * fraction:.1f} % of it); check that the anchor is "
                    "reachable, or start from 'arc'"
                )
            continue
        fraction, reaction = trial, found[2]
        step = min(0.25, 1.5 * step)
    return found[0], found[1]


def static_state(params, y0, time: float = 0.0):
    """Directors (n, 3) and the heave of a floating top, for the steady shape under the motion
    the top has at ``time`` (its velocity is taken as steady)."""
    top, vel, _ = c3.top_motion(time, y0, params)
    needs_polish = bool(
        np.any(params.joint_stiffness > 0)
        or (params.bottom_kind == c3.BOTTOM_FREE and np.any(params.tie_k > 0))
        or params.top_kind == c3.TOP_HEAVE
    )
    if params.bottom_kind in (c3.BOTTOM_TRAJECTORY, c3.BOTTOM_SERVO):
        params = held_at(params, c3.target_motion(time, y0, params)[0])
    if params.bottom_kind == c3.BOTTOM_PINNED:
        if np.any(params.constrained == 0.0):
            raise StaticsError(
                "a static start cannot hold only some axes of the lower end (hold_axes); "
                "start from an 'arc'"
            )
        directors, forces = _pinned(params, top, vel, time)
    else:
        # a tied end is first shot as if free; the polish below adds the ties
        directors, forces = _free(params._replace(tie_k=np.zeros(3)), top, vel, time)
    heave = y0[3 * params.n]
    if params.top_kind == c3.TOP_HEAVE and params.top_stiffness > 0:
        u = float(c3._tf(params, c3.CH_TOP_FORCE, time)[0])
        heave = (
            params.top_rest_z + (u - params.top_net_weight - forces[0, 2]) / params.top_stiffness
        )
    if needs_polish:
        directors, heave = _polish(params, y0, directors, heave, time)
    return directors, heave


def held_at(params, point):
    """The same cable with its lower end pinned at ``point`` (all axes)."""
    return params._replace(
        bottom_kind=c3.BOTTOM_PINNED, pin=np.asarray(point, float), constrained=np.ones(3)
    )


def end_force(params, y0, point, time: float = 0.0) -> np.ndarray:
    """Force a holder must apply to the cable's lower end to keep it at ``point`` in the
    steady state of the top's motion at ``time`` [N]."""
    top, vel, _ = c3.top_motion(time, y0, params)
    _, forces = _pinned(held_at(params, point), top, vel, time)
    return -forces[-1]


def end_stiffness(params, y0, time: float, radius: float):
    """Stiffness K [N/m] of the cable's lower end and the force F0 holding it at its target:
    static equilibria with the end on a sphere of ``radius`` [m] around the target, linearised
    by least squares (Jacquot & Marichal, section 4)."""
    centre = np.asarray(c3.target_motion(time, y0, params)[0], float)
    f0 = end_force(params, y0, centre, time)
    displacements = radius * sphere_directions()
    forces = np.array([end_force(params, y0, centre + d, time) for d in displacements]) - f0
    k_transposed, *_ = np.linalg.lstsq(displacements, forces, rcond=None)
    return k_transposed.T, f0


def static_directors(params, y0, time: float = 0.0) -> np.ndarray:
    """Directors of the steady shape; the heave of a floating top is written into ``y0``."""
    directors, heave = static_state(params, y0, time)
    y0[3 * params.n] = heave
    return directors


def _basis(e):
    """Two unit vectors normal to each row of e (rows of the returned arrays)."""
    axis = np.zeros_like(e)
    axis[np.arange(len(e)), np.argmin(np.abs(e), axis=1)] = 1.0
    t1 = np.cross(axis, e)
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    return t1, np.cross(e, t1)


def _polish(params, y0, directors, heave, time, max_iterations=30):
    """Newton iterations on the dynamic residual: zero director and heave accelerations with
    every node moving with the top (elastic joints, ties, a heaving top)."""
    n = params.n
    heaving = params.top_kind == c3.TOP_HEAVE
    w = c3.make_workspace(n)
    ydot = np.zeros(c3.state_size(n))

    def state(d, z):
        y = np.zeros(c3.state_size(n))
        y[: 3 * n] = (d / np.linalg.norm(d, axis=1)[:, None]).ravel()
        y[3 * n] = z
        return y

    def residual(d, z, t1, t2):
        status = c3.rhs(time, state(d, z), params, w, ydot)
        if status != Status.OK:
            return None
        edd = ydot[3 * n + 1 : 6 * n + 1].reshape(n, 3) * params.length[:, None]
        r = np.concatenate([(edd * t1).sum(axis=1), (edd * t2).sum(axis=1)])
        return np.append(r, ydot[6 * n + 1]) if heaving else r

    scale = 9.81 * float(params.length.max())
    for _ in range(max_iterations):
        t1, t2 = _basis(directors)
        r = residual(directors, heave, t1, t2)
        if r is None:
            break
        if np.max(np.abs(r)) < 1e-11 * scale:
            return directors, heave
        size = 2 * n + (1 if heaving else 0)
        jac = np.empty((len(r), size))
        eps = 1e-7
        for k in range(size):
            d, z = directors.copy(), heave
            if k < 2 * n:
                d[k % n] += eps * (t1 if k < n else t2)[k % n]
            else:
                z += eps * max(1.0, abs(heave))
            step = eps if k < 2 * n else eps * max(1.0, abs(heave))
            rk = residual(d, z, t1, t2)
            if rk is None:
                raise StaticsError("the static residual could not be evaluated near the solution")
            jac[:, k] = (rk - r) / step
        delta = np.linalg.lstsq(jac, -r, rcond=None)[0]
        for damping in (1.0, 0.5, 0.25, 0.1):
            d = directors + damping * (delta[:n, None] * t1 + delta[n : 2 * n, None] * t2)
            z = heave + (damping * delta[-1] if heaving else 0.0)
            d /= np.linalg.norm(d, axis=1)[:, None]
            rn = residual(d, z, t1, t2)
            if rn is not None and np.linalg.norm(rn) < np.linalg.norm(r):
                directors, heave = d, z
                break
        else:
            break
    raise StaticsError(
        "the static shape with elastic joints, ties or a heaving top did not converge; "
        "start from an 'arc' and let the dynamics settle, or reduce the joint stiffness"
    )
