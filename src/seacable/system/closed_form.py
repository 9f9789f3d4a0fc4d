"""The free bodies' balance on their lines' closed forms: the statics' first guess when Newton
from the case's start fails (MoorPy's model of a mooring). Each uniform lumped-mass line is an
elastic catenary between its ends with the part on the seabed through its lower end
(lines.catenary), or, longer than its span and rise, laid slack with only its hanging part's
weight on its upper end, or, its ends above the seabed and its middle on it, two arms tangent to
the seabed (``initial.touchdown``: H, and each arm's weight on its end; no H when it lies
slack); its end forces are those of the continuous line. The bodies' own force
models and ties act as the system evaluates them (their loads at rest, ``kernel.rhs``), the
lumped lines' end loads there replaced by the closed forms'.

Newton over the free bodies' degrees of freedom (central differences of the closed forms:
smooth but where a line lifts off or lays down), each step cut to the statics' step limits and
halved until the forces drop, or at least stay as they were; where its matrix is singular, or
nearly (a body on lines that all lie slack: no stiffness across until they lift), the step of
the matrix shifted on its diagonal by the largest force over its limit, which moves the bodies
along their forces, none beyond its limit (pseudo-transient continuation, as
``system.nested``'s), the forces unchanged until a line lifts: 1.2 km for 10 kN on three lines
2.3 to 5 km long in 876 m of water (``tests/test_statics_family.py``). The lumped lines then
start on their closed-form shapes between the poses found, where the statics' Newton has a
short way to go: a platform whose lines lie slack no longer has to be followed by the lumped
lines' Newton over the hundred metres it travels before they hold it.
"""

import numpy as np

from seacable.lines import catenary
from seacable.system import kernel
from seacable.system.coordinates import Coordinates, apply
from seacable.system.initial import dips, touchdown, uniform_line
from seacable.system.pseudo_time import shifted_step


def applies(p: kernel.SystemParams, coords: Coordinates) -> bool:
    """Every lumped line uniform and heavier than water (``initial.uniform_line``), and no
    rigid line or natural string: the closed forms describe every line."""
    if len(p.rs_n) or len(p.nat_n) or not np.any(coords.kind <= 1):
        return False
    for li in range(len(p.line_n)):
        uniform = uniform_line(p, li, 0.0)
        if uniform is None or not uniform[1] > 0.0:
            return False
    return True


class _Forces:
    """The free bodies' forces at rest with the lines' closed forms (module docstring) at a
    state; None where a line has no catenary between its ends."""

    def __init__(self, p: kernel.SystemParams, coords: Coordinates, time: float):
        self.p, self.coords, self.time = p._replace(slack_allowed=0), coords, time
        self.w = kernel.make_work(self.p)
        self.ydot = np.zeros(p.n_q + p.n_v + p.n_s)
        self.rows = np.flatnonzero(coords.kind <= 1)
        self.component = 3 * coords.kind[self.rows] + coords.axis[self.rows]
        self.guess: dict[int, tuple[float, float]] = {}  # each line's last (H, V_F)

    def __call__(self, y: np.ndarray) -> np.ndarray | None:
        p, w = self.p, self.w
        kernel.rhs(self.time, y, p, w, self.ydot)
        load = w.load - w.bias
        for li in range(len(p.line_n)):
            ends = self._ends(li)
            if ends is None:
                return None
            for e, point in enumerate((p.line_from[li], p.line_to[li])):
                b = p.point_body[point]
                arm = w.parm[point]
                change = ends[e] - w.end_load[li, e]
                load[b, :3] += change
                load[b, 3:] += np.cross(arm, change)
        return load[self.coords.body[self.rows], self.component]

    def _ends(self, li: int):
        """The closed form's forces [N] on the line's ``from`` and ``to`` ends."""
        p, w = self.p, self.w
        start, end = w.ppos[p.line_from[li]], w.ppos[p.line_to[li]]
        flip = start[2] > end[2]
        low, high = (end, start) if flip else (start, end)
        uniform = uniform_line(p, li, float(low[2]))
        assert uniform is not None  # applies()
        length, weight, ea, on_seabed = uniform
        across = high[:2] - low[:2]
        span = float(np.hypot(*across))
        rise = float(high[2] - low[2])
        direction = across / span if span > 0.0 else np.zeros(2)
        if on_seabed and length + weight * rise**2 / (2.0 * ea) >= span + rise:
            on_low, on_high = np.zeros(3), np.array([0.0, 0.0, -weight * rise])  # laid slack
        elif not on_seabed and dips(p, length, weight, low, high, span):
            # its middle on the seabed: two arms tangent to it, as the line starts
            heights = (float(low[2] - p.seabed_z), float(high[2] - p.seabed_z))
            h, _, arc = touchdown(length, heights, span, weight)
            on_low = np.array([h * direction[0], h * direction[1], -weight * arc[0]])
            on_high = np.array([-h * direction[0], -h * direction[1], -weight * arc[1]])
        else:
            try:
                h, v_f = catenary.solve(span, rise, length, weight, ea, on_seabed,
                                        guess=self.guess.get(li))  # fmt: skip
            except catenary.CatenaryError:
                return None
            self.guess[li] = (h, v_f)
            v_low = v_f - weight * length
            if on_seabed and v_low < 0.0:
                v_low = 0.0  # its lower part lies on the seabed
            on_low = np.array([h * direction[0], h * direction[1], v_low])
            on_high = np.array([-h * direction[0], -h * direction[1], -v_f])
        return (on_high, on_low) if flip else (on_low, on_high)


def pose(p: kernel.SystemParams, coords: Coordinates, y: np.ndarray, limit: np.ndarray,
         time: float = 0.0, iterations: int = 100) -> np.ndarray | None:  # fmt: skip
    """The state with the free bodies at their balance on the lines' closed forms (module
    docstring), their forces below 1e-9 of the largest force met; None when it is not found
    (or ``applies`` is False). ``limit``: each body coordinate's largest step [m, rad]."""
    if not applies(p, coords):
        return None
    forces = _Forces(p, coords, time)
    rows = forces.rows
    r = forces(y)
    if r is None:
        return None
    scale = float(np.abs(r).max()) + 1.0
    steps = np.where(coords.kind[rows] == 1, 1e-5, 1e-3)  # [rad, m]: closed forms are smooth
    for _ in range(iterations):
        scale = max(scale, float(np.abs(r).max()))
        if np.abs(r).max() <= 1e-9 * scale:
            return y
        jac = np.empty((len(rows), len(rows)))
        for j, h in enumerate(steps):
            moved = []
            for sign in (1.0, -1.0):
                dx = np.zeros(len(coords.kind))
                dx[rows[j]] = sign * h
                moved.append(forces(apply(y, coords, dx)))
            if moved[0] is None or moved[1] is None:
                return None
            jac[:, j] = (moved[0] - moved[1]) / (2.0 * h)
        step = shifted_step(jac, r, limit, along=True)
        if step is None:
            return None
        largest = float(np.max(np.abs(step) / limit))
        if largest > 1.0:
            step /= largest
        for fraction in 0.5 ** np.arange(12):
            dx = np.zeros(len(coords.kind))
            dx[rows] = fraction * step
            trial = apply(y, coords, dx)
            r_trial = forces(trial)
            # not worse (to the rounding of the lumped lines' loads it replaces): on lines that
            # all lie slack the force stays as it is until one lifts
            if r_trial is not None and np.linalg.norm(r_trial) <= np.linalg.norm(r) * (1 + 1e-9):
                y, r = trial, r_trial
                break
        else:
            return None
    return None
