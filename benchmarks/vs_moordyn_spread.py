"""seacable against MoorDyn (PyPI ``moordyn``, MoorDyn-C v2) on a spread mooring: three chains.

Three catenary chains 120 degrees apart (vs_moordyn.py's chain: d 0.137 m, 126 kg/m, EA 5.8e8 N,
each segment critically damped, Cd 1.2 across and 0.1 along, Ca 1.0, no axial added mass), 800 m
each from fairleads on a 40 m radius 10 m under water to anchors on the seabed (200 m deep) 803 m
from the centre, 165 m of each on the seabed (pretension printed), hold an imposed 6-DOF body
that surges 5 sin(2 pi t / 100) m and heaves 2 sin(2 pi t / 12) m, both times the smoothstep
r(t / 20 s) = s^3 (10 - 15 s + 6 s^2) (seacable's ``simulation.build_up``; MoorDyn is given the
same motion), 300 s. Seabed: MoorDyn's default spring-damper (kbot 3e6 Pa/m, cbot 3e5 Pa s/m on
d l), no friction; seacable's the same per metre of chain, with its default contact band (the
stiffness brought in over the first 5 mm of depth: its converged run differs from one without by
5.1e-5 of the peak tension at 50 segments, while without it generalized-alpha's Newton rebuilt
its matrix 462 times in 3,000 steps of 33 ms and rejected 49 steps, against 60 and 1, and took
4.79 residuals a step against 2.64; ``--no-band``: MoorDyn's plain contact). Both codes run in
this process; times are its CPU time.

* MoorDyn: a deck with a coupled body (BODIES) carrying the three fairlead points. Each ``Step``
  call gets the body's exact pose [x, y, z, roll, pitch, yaw] at its start and the secant rates
  to the exact pose at its end (MoorDyn holds them through the call: the path is exact at each
  call's end). A line's fairlead tension is |F - M a| at its body point: F the point's net
  force (``GetPointForce``), M its mass matrix (the line's end node with its added mass, which
  MoorDyn leaves to the host), a the exact acceleration. Converged run: RK2 at a quarter of its
  stable step (the ladder's largest at which it runs bounded), one ``Step`` per internal step;
  an eighth of that step says how far it is from converged. Every time scheme this moordyn
  accepts (a deck per name; refused names are printed) runs at the largest step of the ladder
  (0.1 s / k, then 10 ms / k, down to the converged run's) at which it is stable and accurate:
  screened over the first PROBE seconds with 10 ms calls, then run whole one ``Step`` per
  internal step and with 10 ms calls (the same steps, fewer Python calls); the faster is timed
  (a scheme whose screen projects more than SLOW s of CPU for the whole run is not run whole);
* seacable: an imposed body ``vessel`` with the two sines (exact at every stage), three fixed
  anchors and three lumped-mass lines, started ``as_given`` (each line in its static catenary
  between its ends); the tension is the magnitude of the line's force on its fairlead
  (``lines/<name>/from_force_*``, the end node's inertia included). Converged run: dopri5 at
  rtol 1e-9. generalized-alpha (defaults; and spectral radius 0 with Newton to 1e-7 of a
  segment; and the defaults with Newton to 1e-7), newmark, theta, implicit_euler and rk4 run
  at the largest accurate step of the ladder 0.1 s / k, the implicit schemes first at LONG
  steps of several output intervals (the tensions between a step's ends interpolated,
  numerics.dense) (a step seacable refuses, rk4 past its stability limit, or that diverges is
  a failed rung), dopri5 at the largest accurate rtol; cvode (a dense Jacobian) and SciPy's bdf,
  radau and lsoda at the smallest size only, each run stopped after SLOW seconds of CPU.

Accurate: each line's fairlead tension, every 0.1 s after the build-up, within 0.5 % of the peak
of the code's own converged run; the two converged runs should agree within 1 %. Times: CPU
seconds per simulated second of stepping, the best of 3 (for the settings within TIMED of their
code's fastest; the others one run), and set-up (MoorDyn: Create and Init, its initial-condition
solve; seacable: a run of one output interval, compiled beforehand); the speed-up is seacable's
fastest accurate setting against MoorDyn's, stepping alone and the whole run with its set-up.
Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/vs_moordyn_spread.py [--quick] [--sizes N ...]``
"""

import argparse
import contextlib
import logging
import math
import os
import signal
import sys
import tempfile
from functools import partial
from pathlib import Path

import numpy as np

import seacable

sys.path.insert(0, str(Path(__file__).resolve().parent))

from vs_moordyn import (  # noqa: E402  (the single-line race's chain, seabed and tools)
    CA,
    CD_N,
    CD_T,
    CLOCK,
    DEPTH,
    DIAMETER,
    EA,
    MASS,
    SEABED_C,
    SEABED_K,
    _quiet,
    ladder,
    options,
    timed,
)

LENGTH, RADIUS, FAIRLEAD_RADIUS, FAIRLEAD_Z = 800.0, 803.0, 40.0, -10.0
AZIMUTHS = (0.0, 120.0, 240.0)  # [deg] the lines' directions from the body's centre
MOTIONS = ((5.0, 100.0), (2.0, 12.0))  # surge and heave: amplitude [m], period [s]
BUILD_UP = 20.0  # [s] the motions' ramp; the comparison starts after it
BAND = None  # seacable's seabed contact band [m]: None, its default; --no-band: 0
OUTPUT = 0.1  # [s] both codes' tension samples
COUPLING = 0.01  # [s] MoorDyn's coarse Step calls
PROBE = 40.0  # [s] MoorDyn's ladder screens each step over this much of the run
TOLERANCE = 0.005  # accurate: within this share of the converged run's peak tension
AGREE = 0.01  # the two converged runs should agree this well
REPEAT = 3  # the chosen settings' times are the best of this many
TIMED = 2.0  # ... those within this factor of their code's fastest (the others: one run)
SLOW = 60.0  # [s] CPU after which a cvode or SciPy run is stopped
# MoorDyn's scheme names (its documentation's, and older ones); the implicit families take
# their iteration count in the name: 5 and 10 (at 20 segments, with 1 none ran at 5 ms or more,
# with 3 they ran at explicit steps, 5 to 10 ms; with 5 and 10 at 25 to 50 ms, with 20 no longer)
MD_CANDIDATES = (
    "RK2", "Euler", "LEuler", "Heun", "RK4", "AB2", "AB3", "AB4", "LAB2", "LAB3", "LAB4",
    "LEuler2", "LEuler3", "LEuler4", "LTrap2", "LTrap3", "LTrap4", "Midpoint",
    "Midpoint5", "Midpoint10", "BEuler5", "BEuler10", "ACA5", "ACA10", "Wilson5", "Wilson10",
)  # fmt: skip
NEWTON = {"newton_tolerance": 1e-7}
SC_FIXED = (("generalized_alpha", {}), ("generalized_alpha r0", {"spectral_radius": 0.0, **NEWTON}),
            ("generalized_alpha 1e-7", NEWTON), ("newmark", {}), ("theta", {}),
            ("implicit_euler", {}), ("rk4", {}))  # fmt: skip
LONG = (0.5, 0.4, 0.3, 0.2)  # [s] the implicit schemes' steps tried first: several OUTPUTs
SC_ADAPTIVE = ("dopri5", "cvode", "bdf", "radau", "lsoda")
SC_SMALL_ONLY = ("cvode", "bdf", "radau", "lsoda")  # dense Jacobians or steps in Python
RTOLS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 1e-6)


def smoothstep(t):
    """r, r', r'' of the build-up ramp at ``t`` [s] (seacable's ``simulation.build_up``), ``t``
    a number or an array; s = t / BUILD_UP clipped to [0, 1] gives r' = r'' = 0 outside it."""
    s = np.clip(np.asarray(t, dtype=float) / BUILD_UP, 0.0, 1.0)
    return (s**3 * (10 - 15 * s + 6 * s * s), 30 * s * s * (1 - s) ** 2 / BUILD_UP,
            60 * s * (1 - s) * (1 - 2 * s) / BUILD_UP**2)  # fmt: skip


def motion(t):
    """The body's x and z [m], each with its first two derivatives, at ``t`` [s] (a number or
    an array): r(t) times each sine."""
    r, dr, ddr = smoothstep(t)
    out = []
    for amplitude, period in MOTIONS:
        w = 2 * math.pi / period
        f, df = amplitude * np.sin(w * t), amplitude * w * np.cos(w * t)
        out.append((r * f, dr * f + r * df, ddr * f + 2 * dr * df - r * w * w * f))
    return out


def _directions():
    """cos and sin of each line's azimuth."""
    return [(math.cos(math.radians(a)), math.sin(math.radians(a))) for a in AZIMUTHS]


def catenary():
    """The elastic catenary of one line at rest (frictionless seabed): its pretension [N] and
    the length lying on the seabed [m]."""
    from scipy.optimize import brentq

    w = (MASS - 1025.0 * math.pi / 4 * DIAMETER**2) * 9.81  # submerged weight [N/m]
    span, drop = RADIUS - FAIRLEAD_RADIUS, DEPTH + FAIRLEAD_Z

    def hanging(h):  # the suspended length that reaches the fairlead at horizontal tension h
        a = h / w
        return brentq(lambda s: a * (math.hypot(1, s / a) - 1) + w * s * s / (2 * EA) - drop,
                      1e-9, LENGTH)  # fmt: skip

    def miss(h):
        s = hanging(h)
        return LENGTH - s + h / w * math.asinh(w * s / h) + h * LENGTH / EA - span

    top = w * (LENGTH**2 - drop**2) / (2 * drop) * 0.999  # the line all but lifted
    h = brentq(miss, 1e3, top)
    return math.hypot(h, w * hanging(h)), LENGTH - hanging(h)


def _error(tension, reference, times):
    """The largest |T - T_ref| over the lines after the build-up, over the reference's peak."""
    late = times[: len(tension)] >= BUILD_UP
    return float(np.max(np.abs(tension[late] - reference[: len(tension)][late]))
                 / np.max(reference))  # fmt: skip


# ---- MoorDyn -------------------------------------------------------------------------------------
def _moordyn_file(path, segments, dt, scheme):
    """The deck: one coupled body, a fixed anchor and a body point per line (anchor 2k + 1,
    fairlead 2k + 2), the lines from anchor to fairlead."""
    points, lines = [], []
    for k, (c, s) in enumerate(_directions()):
        points.append(f"{2 * k + 1} Fixed {RADIUS * c:.12g} {RADIUS * s:.12g} {-DEPTH} 0 0 0 0")
        x, y = FAIRLEAD_RADIUS * c, FAIRLEAD_RADIUS * s
        points.append(f"{2 * k + 2} Body1 {x:.12g} {y:.12g} {FAIRLEAD_Z} 0 0 0 0")
        lines.append(f"{k + 1} chain {2 * k + 1} {2 * k + 2} {LENGTH} {segments} -")
    rows = "\n".join
    text = f"""--------------------- MoorDyn Input File ------------------------------------
seacable benchmark: spread mooring of three chains on an imposed body
---------------------- LINE TYPES -------------------------------------------
TypeName  Diam   Mass/m  EA    BA/-zeta  EI    Cd    Ca    CdAx  CaAx
(name)    (m)    (kg/m)  (N)   (N-s/-)   (N-m^2) (-) (-)   (-)   (-)
chain {DIAMETER} {MASS} {EA} -1.0 0.0 {CD_N} {CA} {CD_T} 0.0
---------------------- BODIES -----------------------------------------------
ID  Attachment  X0  Y0  Z0  r0  p0  y0  Mass  CG*  I*  Volume  CdA*  Ca*
(#) (-)  (m)  (m)  (m)  (deg)  (deg)  (deg)  (kg)  (m)  (kg-m^2)  (m^3)  (m^2)  (-)
1  Coupled  0  0  0  0  0  0  0  0  0  0  0  0
---------------------- POINTS -----------------------------------------------
ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca
(#) (-)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)
{rows(points)}
---------------------- LINES ------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#) (name) (#) (#) (m) (-) (-)
{rows(lines)}
{options(dt, scheme)}"""
    with open(path, "w") as f:
        f.write(text)


def moordyn_schemes():
    """The candidate scheme names this moordyn accepts, and those it refuses (it falls back to
    RK2 with an error in its log, which is read here)."""
    import moordyn

    accepted, refused = [], []
    with tempfile.TemporaryDirectory() as folder:
        path, log = os.path.join(folder, "deck.txt"), os.path.join(folder, "log.txt")
        for name in MD_CANDIDATES:
            _moordyn_file(path, 2, 0.001, name)
            with _quiet(log):
                moordyn.Close(moordyn.Create(path))
            with open(log, errors="replace") as f:
                (refused if "Defaulting to RK2" in f.read() else accepted).append(name)
    return accepted, refused


def _path(duration, coupling):
    """The body's exact x, z at each call's start and the secant rates over it, as lists."""
    t = np.arange(int(round(duration / coupling)) + 1) * coupling
    (x, _, _), (z, _, _) = motion(t)
    return (x[:-1].tolist(), z[:-1].tolist(), (np.diff(x) / coupling).tolist(),
            (np.diff(z) / coupling).tolist(), t[:-1].tolist())  # fmt: skip


def run_moordyn(segments, dt, duration, scheme="RK2", coupling=None, bound=np.inf):
    """The three fairlead tensions every OUTPUT seconds, the CPU time of the Step calls and of
    Create and Init; (None, cpu, None) on failure: an error from MoorDyn (non-finite states) or
    a tension over ``bound``. ``coupling`` is the Step calls' interval (None: the step)."""
    import moordyn

    coupling = dt if coupling is None else coupling
    per_output = int(round(OUTPUT / coupling))
    xs, zs, vxs, vzs, ts = _path(duration, coupling)
    tension = np.empty((len(ts) // per_output, 3))
    with tempfile.TemporaryDirectory() as folder, _quiet():
        path = os.path.join(folder, "spread.txt")
        _moordyn_file(path, segments, dt, scheme)
        start = CLOCK()
        system = moordyn.Create(path)
        moordyn.Init(system, [0.0] * 6, [0.0] * 6)
        startup = CLOCK() - start
        points = [moordyn.GetPoint(system, 2 * k + 2) for k in range(len(AZIMUTHS))]
        step = moordyn.Step
        start = CLOCK()
        try:
            for k, (x, z, vx, vz, t) in enumerate(zip(xs, zs, vxs, vzs, ts, strict=True)):
                step(system, [x, 0.0, z, 0.0, 0.0, 0.0], [vx, 0.0, vz, 0.0, 0.0, 0.0], t, coupling)
                if (k + 1) % per_output == 0:
                    (_, _, ax), (_, _, az) = motion(t + coupling)
                    for j, point in enumerate(points):
                        force = np.array(moordyn.GetPointForce(point))
                        mass = np.array(moordyn.GetPointM(point))
                        tension[k // per_output, j] = np.linalg.norm(force - mass @ (ax, 0, az))
                    if not np.all(tension[k // per_output] < bound):  # NaN too
                        return None, CLOCK() - start, None
        except Exception:  # MoorDyn raises on non-finite states
            return None, CLOCK() - start, None
        finally:
            cpu = CLOCK() - start
            moordyn.Close(system)
    return tension, cpu, startup


def moordyn_reference(segments, duration, times, peak):
    """RK2's stable step (screened over PROBE s), its converged run (a quarter of it, one Step
    per internal step) and that run's distance from one at half its step."""
    for stable in ladder(COUPLING, 1e-5):
        if run_moordyn(segments, stable, PROBE, coupling=COUPLING, bound=2 * peak)[0] is not None:
            break
    else:
        raise RuntimeError("MoorDyn: RK2 found no stable step")
    reference = run_moordyn(segments, stable / 4, duration)[0]
    halved = run_moordyn(segments, stable / 8, duration)[0]
    return stable, reference, _error(halved, reference, times)


def _moordyn_steps(bottom):
    """MoorDyn's ladder: 0.1 s / k down to 10 ms (one Step per internal step), then
    10 ms / k (10 ms Step calls possible), down to ``bottom``."""
    return [*ladder(0.1, COUPLING), *ladder(COUPLING, bottom * 0.999)]


def _failed(tension, reference, times):
    """Why a ladder's run fails (unstable, or its error), or None if it is accurate."""
    if tension is None:
        return "unstable"
    error = _error(tension, reference, times)
    return f"error {error:.1e}" if error > TOLERANCE else None


def moordyn_scheme(segments, scheme, duration, reference, times, bottom):
    """The scheme at the largest step of the ladder that is stable and accurate, driven one
    Step per internal step and with 10 ms calls (when its step divides 10 ms); or why none
    down to ``bottom`` is (or, over SLOW s a run, is not run whole)."""
    bound, why = 3 * float(np.max(reference)), None
    for dt in _moordyn_steps(bottom):
        screen, cpu, _ = run_moordyn(segments, dt, PROBE, scheme, max(dt, COUPLING), bound)
        if (fails := _failed(screen, reference, times)) is None and cpu * duration > SLOW * PROBE:
            return f"accurate at {dt:.3g} s over {PROBE:g} s but {cpu / PROBE:.3f} s/s: not run"
        fine, cpu, startup = (None, 0, 0) if fails else run_moordyn(segments, dt, duration, scheme)
        if fails or (fails := _failed(fine, reference, times)):
            why = f"{dt:.3g} s {fails}"
            continue
        drives = {"step": (cpu, _error(fine, reference, times))}
        if dt < COUPLING:
            tension, cpu, _ = run_moordyn(segments, dt, duration, scheme, COUPLING, bound)
            if tension is not None:
                drives["10 ms"] = (cpu, _error(tension, reference, times))
        accurate = {k: v for k, v in drives.items() if v[1] <= TOLERANCE}
        best = min(accurate, key=lambda k: accurate[k][0])
        coupling = None if best == "step" else COUPLING
        return dict(code="MoorDyn", setting=scheme, step=dt, cpu=accurate[best][0], drive=best,
                    startup=startup, error=drives["step"][1],
                    error_10ms=drives.get("10 ms", (None, None))[1],
                    drives={k: v[0] / duration for k, v in drives.items()},
                    again=partial(run_moordyn, segments, dt, duration, scheme, coupling),
                    above=why)  # fmt: skip
    return f"none stable and accurate down to {bottom:.3g} s (the last rung: {why})"


# ---- seacable ------------------------------------------------------------------------------------
def case(segments, duration, integrator, time_step=None, **simulation):
    """The spread mooring as a system: the imposed body ``vessel`` with its fairleads, three
    fixed anchors and three lumped-mass lines, each started on its catenary."""
    sines = {
        c: {"kind": "sine", "amplitude": a, "period": p}
        for c, (a, p) in zip("xz", MOTIONS, strict=True)
    }
    vessel = {"name": "vessel", "type": "imposed", **sines, "points": {}}
    bodies, lines = [vessel], []
    for k, (c, s) in enumerate(_directions(), start=1):
        vessel["points"][f"fairlead_{k}"] = [FAIRLEAD_RADIUS * c, FAIRLEAD_RADIUS * s, FAIRLEAD_Z]
        anchor = [RADIUS * c, RADIUS * s, -DEPTH]
        bodies.append({"name": f"anchor_{k}", "type": "fixed", "position": anchor})
        section = {"type": "chain", "segments": segments, "length": LENGTH}
        lines.append({"name": f"line_{k}", "model": "lumped_mass", "to": f"anchor_{k}",
                      "from": f"vessel.fairlead_{k}", "sections": [section],
                      "initial": "catenary"})  # fmt: skip
    chain = {"name": "chain", "diameter": DIAMETER, "mass_per_length": MASS,
             "axial_stiffness": EA, "axial_damping_ratio": 1.0, "drag_coefficient_normal": CD_N,
             "drag_coefficient_tangential": CD_T, "added_mass_coefficient": CA}  # fmt: skip
    # MoorDyn's spring-damper and no friction, with seacable's default contact band (BAND)
    seabed = {"stiffness": SEABED_K, "damping": SEABED_C, "friction_coefficient": 0,
              **({} if BAND is None else {"contact_band": BAND})}  # fmt: skip
    return seacable.load_case(
        {
            "name": f"benchmark spread mooring, {segments} segments a line",
            "environment": {"water_density": 1025.0, "water_depth": DEPTH, "seabed": seabed},
            "bodies": bodies,
            "line_types": [chain],
            "lines": lines,
            "start": "as_given",
            "simulation": {
                "duration": duration,
                "output_interval": OUTPUT,
                "integrator": integrator,
                "build_up": BUILD_UP,
                **({"time_step": time_step} if time_step else {}),
                **simulation,
            },
        }
    )


class _TooSlow(Exception):  # a run stopped by _cpu_limit
    pass


@contextlib.contextmanager
def _cpu_limit(seconds):
    """Stop what runs inside after ``seconds`` of the process's CPU time (None: no limit)."""
    if seconds is None:
        yield
        return

    def stop(signum, frame):
        raise _TooSlow(f"stopped after {seconds:g} s of CPU")

    previous = signal.signal(signal.SIGPROF, stop)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)


def run_seacable(segments, duration, integrator, time_step=None, limit=None, **simulation):
    """The three fairlead tensions every OUTPUT seconds (t = 0 dropped), the CPU time of the
    stepping and of the start-up (a run of one output interval, compiled beforehand)."""
    c = case(segments, duration, integrator, time_step, **simulation)
    ds, cpu, startup = timed(c, partial(_cpu_limit, limit))
    tension = np.column_stack([
        np.sqrt(sum(ds[f"lines/line_{k + 1}/from_force_{a}"] ** 2 for a in "xyz")).values[1:]
        for k in range(len(AZIMUTHS))
    ])  # fmt: skip
    return tension, cpu, startup


def seacable_setting(segments, name, duration, reference, times):
    """One integrator at the largest step (or rtol) of its ladder that is accurate; or the
    reason it has none."""
    integrator, settings = name.split()[0], dict(SC_FIXED).get(name, {})
    adaptive = integrator in SC_ADAPTIVE
    limit = SLOW if integrator in SC_SMALL_ONLY else None
    why = "no accurate step"
    steps = (*(LONG if integrator != "rk4" else ()), *ladder(OUTPUT, 2e-4))
    for value in RTOLS if adaptive else steps:
        knob = {"rtol": value} if adaptive else {"time_step": value}
        try:
            tension, cpu, startup = run_seacable(
                segments, duration, integrator, limit=limit, **knob, **settings
            )
        except (seacable.CaseError, seacable.SimulationDiverged) as refusal:
            why = f"{value:.3g}: {str(refusal).splitlines()[0][:90]}"
            continue
        except _TooSlow as refusal:
            return f"{value:.3g}: {refusal}"
        if (error := _error(tension, reference, times)) > TOLERANCE:
            why = f"{value:.3g}: error {error:.1e}"
        else:
            again = partial(run_seacable, segments, duration, integrator, **knob, **settings)
            return dict(code="seacable", setting=name, step=value, cpu=cpu, startup=startup,
                        error=error, again=again,
                        above=None if why == "no accurate step" else why)  # fmt: skip
    return why


def _best_of(rows, duration):
    """Each row's CPU time per simulated second, the best of REPEAT runs for the settings
    within TIMED of their code's fastest (the others: one run, flagged)."""
    for code in {r["code"] for r in rows}:
        mine = [r for r in rows if r["code"] == code]
        fastest = min(r["cpu"] for r in mine)
        for r in mine:
            r["runs"] = 1
            if r["cpu"] <= TIMED * fastest:
                for _ in range(REPEAT - 1):
                    r["cpu"] = min(r["cpu"], r["again"]()[1])
                r["runs"] = REPEAT
            r["per_s"] = r["cpu"] / duration


# ---- the race ------------------------------------------------------------------------------------
def race(segments, duration, schemes, small):
    times = np.arange(1, int(round(duration / OUTPUT)) + 1) * OUTPUT
    sc_reference = run_seacable(segments, duration, "dopri5", rtol=1e-9, atol=1e-9)[0]
    stable, md_reference, halving = moordyn_reference(
        segments, duration, times, float(sc_reference.max())
    )
    agreement = _error(md_reference, sc_reference, times)
    print(f"\n{segments} segments a line: MoorDyn RK2 stable at {stable:.4g} s, converged run at "
          f"{stable / 4:.4g} s (at {stable / 8:.4g} s it moves {halving:.1e} of the peak); "
          f"the converged runs differ by {agreement:.2e} of the peak (limit {AGREE:.0%}); peak "
          f"tension {sc_reference.max() / 1e3:.1f} kN; at the start "
          f"{sc_reference[0].mean() / 1e3:.1f} kN", flush=True)  # fmt: skip
    found = [(f"MoorDyn {scheme}",
              moordyn_scheme(segments, scheme, duration, md_reference, times, stable / 4))
             for scheme in schemes]  # fmt: skip
    for name in [name for name, _ in SC_FIXED] + list(SC_ADAPTIVE):
        if name in SC_SMALL_ONLY and not small:
            found.append((f"seacable {name}", "run at the smallest size only (a dense Jacobian "
                          "or steps in Python: minutes a run here)"))  # fmt: skip
        else:
            found.append((f"seacable {name}", seacable_setting(segments, name, duration,
                                                               sc_reference, times)))  # fmt: skip
    rows = [row for _, row in found if isinstance(row, dict)]
    failed = [f"{what}: {row}" for what, row in found if isinstance(row, str)]
    failed += [f"{what}: the next larger rung, {row['above']}" for what, row in found
               if isinstance(row, dict) and row["above"]]  # fmt: skip
    _best_of(rows, duration)
    return dict(segments=segments, rows=rows, failed=failed, agreement=agreement)


def _knob(r):
    return f"rtol {r['step']:g}" if r["setting"] in SC_ADAPTIVE else f"{r['step']:.4g} s"


def _print_table(result, duration):
    rows = result["rows"]
    header = (
        f"{'code':>8} {'setting':>20} {'step':>11} {'s/s':>8} {'of':>2} {'drive':>5} | "
        f"{'s/s step':>8} {'s/s 10ms':>8} | {'set-up':>6} {'err':>7} {'err 10ms':>8}"
    )
    print(header)
    print("-" * len(header))
    for r in sorted(rows, key=lambda r: (r["code"], r["per_s"])):
        drives, e10 = r.get("drives", {}), r.get("error_10ms")
        step, coarse = (
            f"{drives[k]:8.4f}" if k in drives else f"{'-':>8}" for k in ("step", "10 ms")
        )
        print(
            f"{r['code']:>8} {r['setting']:>20} {_knob(r):>11} {r['per_s']:8.4f} {r['runs']:2d} "
            f"{r.get('drive', '-'):>5} | {step} {coarse} | {r['startup']:6.3f} "
            f"{r['error']:7.1e} {'-' if e10 is None else f'{e10:.1e}':>8}"
        )
    for line in result["failed"]:
        print(f"  {line}")
    md = [r for r in rows if r["code"] == "MoorDyn"]
    sc = [r for r in rows if r["code"] == "seacable"]
    if md and sc:
        m, s = min(md, key=lambda r: r["per_s"]), min(sc, key=lambda r: r["per_s"])
        whole = (m["startup"] + m["per_s"] * duration) / (s["startup"] + s["per_s"] * duration)
        print(
            f"speed-up of seacable {s['setting']} ({_knob(s)}) against MoorDyn {m['setting']} "
            f"({_knob(m)}): stepping {m['per_s'] / s['per_s']:.2f}x, the whole {duration:g} s "
            f"run with its set-up {whole:.2f}x"
        )


def _cpu_model():
    with contextlib.suppress(OSError), open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return "unknown"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="20 segments a line, 60 s")
    parser.add_argument("--sizes", type=int, nargs="+", help="segments a line (20 50 100)")
    parser.add_argument("--no-band", action="store_true", help="seacable's seabed as MoorDyn's: "
                        "no contact band (the race's first run)")  # fmt: skip
    args = parser.parse_args(argv)
    global BAND
    BAND = 0.0 if args.no_band else None
    logging.getLogger("seacable").setLevel(logging.ERROR)  # the ladders probe past the limits
    sizes = args.sizes or ((20,) if args.quick else (20, 50, 100))
    duration = 60.0 if args.quick else 300.0
    print(f"CPU: {_cpu_model()}; load average {', '.join(f'{v:.2f}' for v in os.getloadavg())}")
    pretension, grounded = catenary()
    print(f"each line at rest: pretension {pretension / 1e3:.1f} kN, {grounded:.0f} m of its "
          f"{LENGTH:g} m on the seabed (elastic catenary)")  # fmt: skip
    schemes, refused = moordyn_schemes()
    print(f"MoorDyn time schemes accepted: {', '.join(schemes)}; refused: {', '.join(refused)}")
    agreement = {}
    for segments in sizes:
        start = CLOCK()
        result = race(segments, duration, schemes, segments == min(sizes))
        _print_table(result, duration)
        agreement[segments] = result["agreement"]
        print(f"({segments} segments: {(CLOCK() - start) / 60:.1f} min of CPU)")
    print("converged runs' difference: " + ", ".join(
        f"{n} segments {a:.2e}" + (" (over 1 %)" if a > AGREE else "") for n, a in agreement.items()
    ))  # fmt: skip
    print(
        f"\ns/s: CPU seconds per simulated second of stepping, the best of 'of' runs ({REPEAT} "
        f"for the settings within {TIMED:g}x of their code's fastest, else 1; MoorDyn: the "
        "faster accurate driving, 'step' one Step call per internal step or '10 ms' calls; "
        "both columns give one run each); set-up: CPU seconds (MoorDyn: Create and Init; "
        "seacable: a run of one output interval); err: largest fairlead-tension error of the "
        f"three lines after t = {BUILD_UP:g} s against the code's own converged run (MoorDyn: "
        "RK2 at a quarter of its stable step; seacable: dopri5 at rtol 1e-9), relative to its "
        f"peak; accurate within {TOLERANCE:.1%}. load average at the end: "
        f"{os.getloadavg()[0]:.2f}"
    )


if __name__ == "__main__":
    main()
