"""The Illinois (modified regula falsi) method on a bracket [a, b] of a sign change, one step at
a time so that callers evaluate the function their own way (a Runge-Kutta step, a corrected
point of a branch): ``trial`` gives the next point, ``narrow`` keeps the bracket."""

from numba import njit

from seacable.kernels.jit import JIT


@njit(**JIT)
def trial(a, fa, b, fb):
    """The secant's zero between a and b (their midpoint if it falls outside)."""
    s = b - fb * (b - a) / (fb - fa) if fb != fa else 0.5 * (a + b)
    if not (min(a, b) < s < max(a, b)):
        s = 0.5 * (a + b)
    return s


@njit(**JIT)
def narrow(a, fa, b, fb, s, fs, side):
    """The bracket after the value ``fs`` at ``s``: (a, fa, b, fb, side); the end kept twice
    in a row has its value halved (Illinois), ``side`` remembering which end moved last."""
    if (fs > 0.0) == (fb > 0.0):
        b, fb = s, fs
        if side == -1:
            fa *= 0.5
        side = -1
    else:
        a, fa = s, fs
        if side == 1:
            fb *= 0.5
        side = 1
    return a, fa, b, fb, side
