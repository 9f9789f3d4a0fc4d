"""Stepping a case from another program, as MoorDyn's coupling interface does: a floating-body
solver (or OpenFAST, WEC-Sim, a Python loop) gives the motion of the case's coupled bodies at
each of its steps and takes back the forces the lines put on them::

    coupling = Coupling("lines.txt")                # a case, or a MoorDyn deck
    forces = coupling.init(x0)                      # the statics, the coupled bodies at x0
    for k in range(steps):
        forces = coupling.step(x, v, k * dt, dt)    # from t = k dt to (k + 1) dt

The coupled bodies are imposed bodies (MoorDyn's coupled and vessel points and bodies come in
as such): by default every imposed body that follows no track and no other body. Each takes 3
values (x, y, z [m]) when all its points are its reference point (a coupled point), else 6
(x, y, z [m], roll, pitch, yaw [rad]: R = Rz(yaw) Ry(pitch) Rx(roll), docs/conventions.md), in
the order of the case's bodies; ``v`` their rates. Over a step the bodies move from ``x`` with
the velocity ``v`` and the acceleration a = (v - v_last) / dt (as MoorDyn's coupled kinematics
take it; the position x + v t + a t^2 / 2, exact for a steady acceleration, where MoorDyn's
stays x + v t), and the forces returned are the lines', ties' and joints' force on each body at
the step's end (and their moment about its reference point, for 6 values) [N, N m], earth
axes, as the results' ``line_force`` and ``line_moment``.

The case's own compiled fixed-step integrator (rk4, ``simulation.time_step``) runs each step
in steps of at most that size, a whole number of them per coupling step; the coupling step
``dt`` is the same at every call, and each call starts where the last one ended. Forces and
imposed motions of the case's time functions (waves, current, applied loads) keep their
absolute time.
"""

import logging
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from seacable.bodies import kinematics
from seacable.case import loader
from seacable.case.base import Constant
from seacable.case.system import ImposedBody, SystemCase
from seacable.errors import CaseError, SimulationDiverged
from seacable.kernels.status import Status
from seacable.numerics import integrators
from seacable.simulation import prepare
from seacable.system import model as system_model
from seacable.system.assemble import BuiltSystem
from seacable.timefunctions import SENTINEL

log = logging.getLogger(__name__)


class Coupling:
    """A case stepped by another program (module docstring)."""

    def __init__(self, case: SystemCase | str | Path | dict, bodies: list[str] | None = None):
        self.case = case if isinstance(case, SystemCase) else loader.load_case(case)
        sim = self.case.simulation
        if sim.integrator != "rk4" or sim.time_step is None:
            raise CaseError(
                f"simulation.integrator: '{sim.integrator}'; a coupling steps with the fixed-"
                "step rk4: give integrator: rk4 and time_step [s]"
            )
        if system_model.refresh_interval(self.case) is not None:
            raise CaseError("a case with a trajectory servo cannot be stepped by another program")
        imposed = {b.name: b for b in self.case.bodies if isinstance(b, ImposedBody)}
        if bodies is None:
            bodies = [name for name, b in imposed.items()
                      if b.track is None and b.relative_to is None]  # fmt: skip
        for name in bodies:
            body = imposed.get(name)
            if body is None or body.track is not None or body.relative_to is not None:
                raise CaseError(
                    f"coupled body '{name}': not an imposed body of the case that follows no "
                    f"track and no other body; coupled bodies may be {sorted(imposed)}"
                )
        if not bodies:
            raise CaseError("the case has no imposed body to couple (MoorDyn's coupled points)")
        self.bodies = list(bodies)
        self.sizes = [3 if not any(any(v) for v in imposed[n].points.values()) else 6
                      for n in self.bodies]  # fmt: skip
        self.size = sum(self.sizes)
        self.t = 0.0
        self.dt: float | None = None
        self.steps = 0
        self.system: BuiltSystem | None = None

    def _values(self, x, name: str) -> np.ndarray:
        x = np.asarray(x, dtype=float).ravel()
        if x.shape != (self.size,) or not np.all(np.isfinite(x)):
            raise ValueError(
                f"{name}: {self.size} finite values expected (x, y, z per coupled point, "
                f"and roll, pitch, yaw per coupled body: {self._layout()}); got {x.shape[0]}"
                + ("" if np.all(np.isfinite(x)) else " with NaN or inf")
            )
        return x

    def _layout(self) -> dict[str, int]:
        return dict(zip(self.bodies, self.sizes, strict=True))

    def _six(self, x: np.ndarray) -> list[np.ndarray]:
        out, at = [], 0
        for size in self.sizes:
            six = np.zeros(6)
            six[:size] = x[at : at + size]
            out.append(six)
            at += size
        return out

    def init(self, x, v=None) -> np.ndarray:
        """The case built with the coupled bodies held at ``x`` (its statics solved, as the
        case's ``start`` says), the clock at 0, the lines' forces on them returned. ``v``
        (their rates) is the motion the first step starts with; default at rest."""
        x = self._values(x, "x")
        v = np.zeros(self.size) if v is None else self._values(v, "v")
        held = []
        for name, six in zip(self.bodies, self._six(x), strict=True):
            angles = {f"{a}_deg": Constant(value=math.degrees(six[3 + k]))
                      for k, a in enumerate(("roll", "pitch", "yaw"))}  # fmt: skip
            held.append((name, {"x": Constant(value=six[0]), "y": Constant(value=six[1]),
                                "z": Constant(value=six[2]), **angles}))  # fmt: skip
        case = self.case.model_copy(deep=True)
        for name, fields in held:
            k = next(i for i, b in enumerate(case.bodies) if b.name == name)
            case.bodies[k] = case.bodies[k].model_copy(update=fields)
        system, warning = prepare(case)
        if warning:
            log.warning(warning)  # as a run says it
        p = system.params
        index = {b.name: i for i, b in enumerate(case.bodies)}
        self.channels = [int(p.body_channel[index[name]]) for name in self.bodies]
        self.index = [index[name] for name in self.bodies]
        breaks, coefs = p.tf_breaks, p.tf_coefs
        if breaks.shape[1] < 2:  # room for the step's piece after the constant one
            breaks = np.concatenate([breaks, np.full((breaks.shape[0], 1), np.inf)], axis=1)
            coefs = np.concatenate([coefs, np.zeros((coefs.shape[0], 1, 4))], axis=1)
        motion = p.body_motion.copy()
        for b, size in zip(self.index, self.sizes, strict=True):
            motion[b] = kinematics.TURNS if size == 6 else kinematics.MOVES
        p = p._replace(tf_breaks=np.ascontiguousarray(breaks),
                       tf_coefs=np.ascontiguousarray(coefs), body_motion=motion)  # fmt: skip
        built = replace(system, params=p)
        self.system, self.p = built, p
        self.w = system_model.workspace(built)
        self.y = built.y0.copy()
        system_model.start_memory(built, self.w, 0.0, self.y)
        self.t, self.dt, self.steps = 0.0, None, 0
        self.work = np.zeros(len(integrators.WORK_NAMES), dtype=np.int64)
        self.v = v.copy()
        self._move(x, v, np.zeros_like(v), 0.0)
        return self._forces()

    def _move(self, x: np.ndarray, v: np.ndarray, a: np.ndarray, t: float) -> None:
        """The coupled channels: x until t, then x + v (t' - t) + a (t' - t)^2 / 2."""
        p = self.p
        for channel, x6, v6, a6 in zip(self.channels, self._six(x), self._six(v), self._six(a),
                                       strict=True):  # fmt: skip
            for c in range(6):
                k = channel + c
                p.tf_breaks[k, :] = np.inf
                p.tf_coefs[k, :, :] = 0.0
                p.tf_breaks[k, 0], p.tf_coefs[k, 0, 0] = SENTINEL, x6[c]
                p.tf_breaks[k, 1] = t
                p.tf_coefs[k, 1, 0], p.tf_coefs[k, 1, 1] = x6[c], v6[c]
                p.tf_coefs[k, 1, 2] = 0.5 * a6[c]
                p.tf_count[k] = 2
                p.tf_sine[k, :] = 0.0
                p.tf_build_up[k, :] = 0.0

    def step(self, x, v, t: float, dt: float) -> np.ndarray:
        """Advance from ``t`` (where the last step ended) to ``t + dt``, the coupled bodies
        moving from ``x`` at ``v``; returns the lines' forces on them at ``t + dt``."""
        if self.system is None:
            raise RuntimeError("call init(x) before step()")
        x, v = self._values(x, "x"), self._values(v, "v")
        if not (dt > 0.0 and math.isfinite(dt)):
            raise ValueError(f"dt: {dt}; a coupling step must be positive")
        if self.dt is None:
            self.dt = float(dt)
            step = self.case.simulation.time_step
            assert step is not None  # __init__ refuses a case without one
            self.per = max(1, math.ceil(self.dt / step - 1e-9))
        elif abs(dt - self.dt) > 1e-12 * self.dt:
            raise ValueError(f"dt: {dt}; this coupling steps by {self.dt} s at every call")
        if abs(t - self.t) > 1e-9 * max(1.0, self.dt):
            raise ValueError(f"t: {t}; the last step ended at {self.t} s: start there")
        self._move(x, v, (v - self.v) / self.dt, self.steps * self.dt)
        self.v = v.copy()
        states, times = np.empty((1, len(self.y))), np.empty(1)
        done, status = integrators.rk4_chunk(
            self.steps * self.per, self.y, self.dt, self.per, self.per, self.p, self.w,
            states, times, self.work,
        )  # fmt: skip
        if status != Status.OK or done != 1:
            raise SimulationDiverged(
                f"the coupled system diverged in the step from t = {self.t:.6g} s "
                f"(status {status}); a shorter simulation.time_step may hold it",
                None,
            )
        self.steps += 1
        self.t = self.steps * self.dt
        return self._forces()

    def _rows(self) -> dict:
        if self.system is None:
            raise RuntimeError("call init(x) first")
        rows, _ = system_model.rows(np.array([self.t]), self.y[None, :].copy(), self.system,
                                    self.w)  # fmt: skip
        return rows

    def _forces(self) -> np.ndarray:
        rows = self._rows()
        out = []
        for name, size in zip(self.bodies, self.sizes, strict=True):
            group = f"bodies/{name}"
            values = [rows[f"{group}/line_force_{c}"][0] for c in "xyz"]
            if size == 6:
                values += [rows[f"{group}/line_moment_{c}"][0] for c in "xyz"]
            out += values
        return np.array(out, dtype=float)

    def state(self) -> dict:
        """The lines' nodes and the bodies' motion at the current time, as the results name
        them (``lines/<name>/node_x``, ``bodies/<name>/position_x``, ...)."""
        return {k: np.asarray(v)[0] for k, v in self._rows().items() if k != "time"}
