"""The elastic catenary in closed form: a line of unstretched length L, apparent weight w per
unit length and axial stiffness EA between an anchor and a fairlead, with the part of it that
lies on a flat seabed through the anchor (no seabed friction).

Profiles (H horizontal tension, V_F vertical tension at the fairlead, s arc length from the
anchor), as in Irvine (1981) and Jonkman (2007):

- hanging clear of the seabed, V_A = V_F - w L:
  x(s) = H/w [asinh(V(s)/H) - asinh(V_A/H)] + H s / EA,
  z(s) = H/w [sqrt(1 + (V(s)/H)^2) - sqrt(1 + (V_A/H)^2)] + (V_A s + w s^2/2) / EA;
- touching down (V_F < w L, anchor on the seabed), L_B = L - V_F / w on the seabed:
  x = L_B + H/w asinh(V_F/H) + H L / EA,  z = H/w [sqrt(1 + (V_F/H)^2) - 1] + V_F^2 / (2 EA w).
"""

import math

import numpy as np

from seacable.errors import SeacableError


class CatenaryError(SeacableError):
    """No elastic catenary joins the two ends (the message says why)."""


def _ends(h, v_f, length, w, ea, seabed):
    """Horizontal span and rise of the line for tensions (h, v_f)."""
    if seabed and v_f < w * length:
        l_b = length - v_f / w
        x = l_b + h / w * math.asinh(v_f / h) + h * length / ea
        z = h / w * (math.sqrt(1 + (v_f / h) ** 2) - 1) + v_f**2 / (2 * ea * w)
        return x, z
    v_a = v_f - w * length
    x = h / w * (math.asinh(v_f / h) - math.asinh(v_a / h)) + h * length / ea
    z = h / w * (math.sqrt(1 + (v_f / h) ** 2) - math.sqrt(1 + (v_a / h) ** 2))
    z += (v_a * length + w * length**2 / 2) / ea
    return x, z


def solve(span: float, rise: float, length: float, w: float, ea: float, seabed: bool,
          guess: tuple[float, float] | None = None):  # fmt: skip
    """Tensions (H, V_F) [N] of the line reaching ``span`` horizontally and ``rise`` up [m]
    (``guess``: tried first, a nearby solution's)."""
    if w <= 0:
        raise CatenaryError(f"the line's apparent weight must be positive (got {w:.4g} N/m)")
    if math.hypot(span, rise) >= length * 2:
        raise CatenaryError("the ends are more than twice the line's length apart")
    # slack lines have small H (a few metres of line weight), taut ones large: try a wide grid
    guesses = [] if guess is None else [guess]
    guesses += [(0.5 * w * length, 0.5 * w * length + max(rise, 0) * w)]
    guesses += [
        (w * length * f, w * g)
        for f in (0.001, 0.01, 0.1, 1.0, 5.0, 1e-4, 1e-5, 1e-6)  # the last: nearly slack
        for g in (max(rise, 1.0), 0.5 * length, length, 2.0 * length)
    ]
    from scipy.optimize import fsolve  # here: its import is slow (docs/architecture.md)

    for h0, v0 in guesses:
        solution, info, ok, _ = fsolve(
            lambda q: np.subtract(
                _ends(abs(q[0]) + 1e-9, q[1], length, w, ea, seabed), (span, rise)
            ),  # fmt: skip
            (h0, v0),
            full_output=True,
            xtol=1e-13,
        )
        h, v_f = abs(solution[0]) + 1e-9, solution[1]
        if ok == 1 and np.allclose(_ends(h, v_f, length, w, ea, seabed), (span, rise), atol=1e-7):
            return h, v_f
    raise CatenaryError(
        f"no elastic catenary found for span {span:.4g} m, rise {rise:.4g} m, length {length:.4g} m"
    )


def horizontal_law(rise: float, length: float, w: float, ea: float, seabed: bool,
                   count: int = 200) -> np.ndarray:  # fmt: skip
    """The line's horizontal tension H [N] against the horizontal span [m] between its ends,
    the upper end ``rise`` [m] above the lower (``count`` rows (span, H), spans increasing):
    H over a geometric range from 1e-7 to 1e-2 of EA, for each the fairlead's vertical
    tension V_F that reaches the rise (Brent's method), and the span it gives. Below the
    first span the line hangs slack (H about 0); beyond the last it stretches as a straight
    bar would."""
    from scipy.optimize import brentq  # here: its import is slow (docs/architecture.md)

    if w <= 0:
        raise CatenaryError(f"the line's apparent weight must be positive (got {w:.4g} N/m)")
    if rise < 0.0 or rise >= length:
        raise CatenaryError(f"the rise {rise:.4g} m must lie between 0 and the line's length "
                            f"{length:.4g} m")  # fmt: skip
    rows = np.empty((count, 2))
    for k, h in enumerate(np.geomspace(1e-7 * ea, 1e-2 * ea, count)):
        high = w * length + h
        while _ends(h, high, length, w, ea, seabed)[1] < rise:
            high *= 2.0
        v_f = brentq(lambda v, h=h: _ends(h, v, length, w, ea, seabed)[1] - rise, 0.0, high,
                     xtol=1e-12 * high, rtol=1e-14)  # fmt: skip
        rows[k] = _ends(h, v_f, length, w, ea, seabed)[0], h
    return rows


def profile(s, h, v_f, length, w, ea, seabed):
    """Horizontal distance and rise from the anchor at arc lengths ``s`` (from the anchor)."""
    s = np.asarray(s, dtype=float)
    if seabed and v_f < w * length:
        l_b = length - v_f / w
        on = s <= l_b
        sp = np.maximum(s - l_b, 0.0)
        x = np.where(on, s * (1 + h / ea), l_b * (1 + h / ea) + h / w * np.arcsinh(w * sp / h)
                     + h * sp / ea)  # fmt: skip
        z = np.where(on, 0.0, h / w * (np.sqrt(1 + (w * sp / h) ** 2) - 1) + w * sp**2 / (2 * ea))
        return x, z
    v_a = v_f - w * length
    v = v_a + w * s
    x = h / w * (np.arcsinh(v / h) - math.asinh(v_a / h)) + h * s / ea
    z = h / w * (np.sqrt(1 + (v / h) ** 2) - math.sqrt(1 + (v_a / h) ** 2))
    z = z + (v_a * s + w * s**2 / 2) / ea
    return x, z
