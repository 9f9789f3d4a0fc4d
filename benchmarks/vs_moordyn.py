"""seacable against MoorDyn (PyPI ``moordyn``, MoorDyn-C v2) on one catenary mooring line.

200 m water depth; a 250 m studless chain (126 kg/m, EA 5.8e8 N, d 0.137 m) from an anchor on
the seabed 100 m from the fairlead, about 40 m of it lying on the seabed; the fairlead, 10 m
below the surface, surges 5 - 5 cos(2 pi t / 12) m. Both codes run in this process, with the same
line properties, drag and added-mass coefficients and seabed spring-damper (MoorDyn's defaults),
and no seabed friction (MoorDyn's default). seacable runs the line as a system of bodies and
lines: a fixed body ``anchor``, an imposed body ``fairlead`` moving with the sine, and one
lumped-mass line ``chain`` between them; its fairlead tension is the magnitude of the line's
force on the fairlead body (``bodies/fairlead/line_force_x, _y, _z``, the end node's inertia
included). Axial damping (``--damping``):

* ``critical`` (the default): each segment critically damped, as MoorDyn users set it
  (BA = -1 in its line-type table; seacable ``axial_damping_ratio: 1``): alpha = l sqrt(mu / EA),
  0.73 ms at 160 segments;
* ``overdamped`` (the race's first version, kept as a labelled variant): alpha = 2 ms
  (BA = EA x 0.002 s), 0.34, 0.69, 1.37 and 2.75 times critical at 20, 40, 80 and 160 segments,
  which forces MoorDyn's explicit step down as 1 / N^2.

For 20, 40, 80 and 160 segments:

* MoorDyn (its default RK2 scheme) runs at the largest step of a ladder at which it stays
  stable over 12 s (no error, finite and bounded tension) and agrees with its converged run
  (an eighth of its stable step) within 1 % of the peak tension (near its limit it can stay
  bounded and be 25 % off). It is driven one internal step per ``Step`` call: MoorDyn holds the
  coupled point's velocity through a ``Step`` and moves it linearly, so each call gets the exact
  fairlead position at its start and the secant velocity to the exact position at its end (the
  path is exact at every step's end; within a step it is the chord, off by a dt^2 / 8, 2e-9 m
  at a 0.1 ms step; MoorDyn has no acceleration input). Its time is also measured with 10 ms
  ``Step`` calls (the same internal steps, fewer Python calls; the velocity held through
  10 ms changes the tension, reported too): the speed-up is taken against the faster;
* seacable runs generalized-alpha (implicit, an O(n) Newton iteration per step: its matrix
  from finite differences over colour groups, banded; converged to 1e-7 of a segment; spectral
  radius 0.5, its default, and 0.8) at the largest step of a ladder whose fairlead-tension
  error against its own converged solution (dopri5, rtol 1e-9) stays within the larger of
  MoorDyn's own error (its chosen step against its converged run) and 1e-3 of the peak tension
  (equal accuracy, or 0.1 % where MoorDyn's error is smaller: the table gives both errors), and
  rk4 at the largest stable step within the same bound (a step seacable refuses, rk4 beyond its
  stability limit about the start, or one that diverges is a failed rung: the ladder goes on);
  the fastest is reported, the others too. Its fairlead moves exactly (the sine is evaluated at
  every stage).

It prints both fairlead tensions at a few times, each code's error against its own converged
run, their largest relative difference after the start-up (t >= 6 s), and the CPU time per
simulated second of each code (seacable: the whole ``simulate`` call with its start-up
equilibrium and NetCDF-free output, kernels compiled before timing; MoorDyn: its Step calls
after Init), the best of five runs of each code's chosen setting. Times are the process's CPU
time (both codes are single-threaded): on a shared machine wall time measures the load.
Run: ``python benchmarks/vs_moordyn.py [--quick] [--damping critical|overdamped]``.
"""

import argparse
import contextlib
import logging
import math
import os
import sys
import tempfile
import time

import numpy as np

import seacable

DEPTH, LENGTH, DIAMETER, MASS, EA = 200.0, 250.0, 0.137, 126.0, 5.8e8
# axial damping per variant: seacable's field and value, MoorDyn's BA column [N s, or -zeta]
DAMPING = {
    "critical": ("axial_damping_ratio", 1.0, -1.0),
    "overdamped": ("axial_damping_time", 0.002, EA * 0.002),
}
ANCHOR = (-100.0, 0.0, -200.0)
FAIRLEAD_Z = -10.0
# MoorDyn's default seabed, kbot = 3e6 Pa/m and cbot = 3e5 Pa s/m on the contact area d l, as
# stiffness and damping per metre of chain (a softer, lightly damped seabed makes the touchdown
# nodes ring and sends stress waves up the chain that neither code resolves at large steps)
SEABED_K, SEABED_C = 3.0e6 * DIAMETER, 3.0e5 * DIAMETER  # [N/m/m], [N s/m/m]
CD_N, CD_T, CA = 1.2, 0.1, 1.0
PERIOD, AMPLITUDE = 12.0, 5.0
OUTPUT = 0.05  # [s] both codes report the fairlead force at this interval
COUPLING = 0.01  # [s] MoorDyn's coarse coupling step (its timing without per-step Python calls)
SETTLED = 6.0  # [s] start-up excluded from the comparison
MD_SOUND = 0.01  # MoorDyn's step must agree with its converged run within 1 % of the peak tension
MD_REFERENCE = 8  # MoorDyn's converged run: its stable step over this (second order: 1/64)
# seacable's Newton iterations stop when the last position correction is below 1e-7 of a
# segment (the default, 1e-9, is tighter than any step's own error here); the accuracy check
# against the converged reference decides as for every other setting
NEWTON = {"newton_tolerance": 1e-7}
REPEAT = 5  # the chosen runs' times are the best of this many
# both codes run single-threaded in this process (set OPENBLAS_NUM_THREADS=1): its CPU time
# measures their work whatever else the machine runs, where wall time grows with the load
CLOCK = time.process_time


def fairlead_x(t):
    w = 2 * math.pi / PERIOD
    return AMPLITUDE - AMPLITUDE * math.cos(w * t), AMPLITUDE * w * math.sin(w * t)


# ---- MoorDyn -------------------------------------------------------------------------------------
def _moordyn_file(path, segments, dt, ba):
    text = f"""--------------------- MoorDyn Input File ------------------------------------
seacable benchmark: catenary chain, fairlead surge
---------------------- LINE TYPES -------------------------------------------
TypeName  Diam   Mass/m  EA    BA/-zeta  EI    Cd    Ca    CdAx  CaAx
(name)    (m)    (kg/m)  (N)   (N-s/-)   (N-m^2) (-) (-)   (-)   (-)
chain {DIAMETER} {MASS} {EA} {ba} 0.0 {CD_N} {CA} {CD_T} 0.0
---------------------- POINTS -----------------------------------------------
ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca
(#) (-)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)
1  Fixed  {ANCHOR[0]}  {ANCHOR[1]}  {ANCHOR[2]}  0  0  0  0
2  Coupled  0.0  0.0  {FAIRLEAD_Z}  0  0  0  0
---------------------- LINES ------------------------------------------------
ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#) (name) (#) (#) (m) (-) (-)
1  chain  1  2  {LENGTH}  {segments}  -
{options(dt, "RK2")}"""
    with open(path, "w") as f:
        f.write(text)


def options(dt, scheme):
    """A deck's OPTIONS (and its closing line): the step ``dt`` [s] and time ``scheme``, the
    seabed, the water and the initial-condition solve both races use."""
    return f"""---------------------- OPTIONS ----------------------------------------------
{dt!r}  dtM
{scheme}  tScheme
{SEABED_K / DIAMETER}  kbot
{SEABED_C / DIAMETER}  cbot
{DEPTH}  WtrDpth
1025.0  rho
9.81  g
1.0  dtIC
100.0  TmaxIC
4.0  CdScaleIC
0.0001  threshIC
0  writeLog
------------------------- need this line ------------------------------------
"""


@contextlib.contextmanager
def _quiet(log=os.devnull):
    """MoorDyn-C writes its progress and errors to the C stdout and stderr: silence them (or
    send them to the file ``log``, to read what it said)."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved, sink = (os.dup(1), os.dup(2)), os.open(log, os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
    os.dup2(sink, 1)
    os.dup2(sink, 2)
    try:
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (sink, *saved):
            os.close(fd)


def run_moordyn(segments, dt, duration, ba, coupling=None):
    """Fairlead tension every OUTPUT seconds, the CPU time of the Step calls and of Create and
    Init (its start-up: reading the file and its own initial-condition solve), or None on
    failure. MoorDyn moves a coupled point from the position it is given with the velocity it
    is given over each ``Step`` of ``coupling`` seconds (None: one internal step, ``dt``): each
    call gets the exact position at its start and the secant velocity to the exact position at
    its end, which keeps the point on the exact path at every call's end. MoorDyn's
    coupled-point force leaves out the inertia of the point's mass (the line's end node), which
    it reports separately for the host to add; that inertia is taken off here, as seacable's top
    force includes it."""
    import moordyn

    coupling = dt if coupling is None else coupling
    per_output = int(round(OUTPUT / coupling))
    w = 2 * math.pi / PERIOD
    with tempfile.TemporaryDirectory() as folder, _quiet():
        path = os.path.join(folder, "line.txt")
        _moordyn_file(path, segments, dt, ba)
        start = CLOCK()
        system = moordyn.Create(path)
        moordyn.Init(system, [0.0, 0.0, FAIRLEAD_Z], [0.0, 0.0, 0.0])
        startup = CLOCK() - start
        point = moordyn.GetPoint(system, 2)
        mass = moordyn.GetPointM(point)
        steps = int(round(duration / coupling))
        tension = np.empty(steps // per_output)
        start = CLOCK()
        try:
            x = fairlead_x(0.0)[0]
            for k in range(steps):
                x_next = fairlead_x((k + 1) * coupling)[0]
                position, velocity = [x, 0.0, FAIRLEAD_Z], [(x_next - x) / coupling, 0.0, 0.0]
                force = moordyn.Step(system, position, velocity, k * coupling, coupling)
                x = x_next
                if (k + 1) % per_output == 0:
                    ax = AMPLITUDE * w * w * math.cos(w * (k + 1) * coupling)
                    inertia = [mass[c][0] * ax for c in range(3)]
                    tension[k // per_output] = math.dist(force, inertia)
        except Exception:  # MoorDyn raises on NaN node positions
            return None, None, None
        finally:
            cpu = CLOCK() - start
            moordyn.Close(system)
    return tension, cpu, startup


def ladder(start, smallest):
    """The steps both codes try, largest first: start / k for k = 1, 2, 3, 4, 6, 8, 12, ...
    (each divides the interval it starts from; ratios 1.5 and 4/3 alternate)."""
    k = 1
    while start / k > smallest:
        yield start / k
        if k == 1:
            k = 2
        elif k & (k - 1) == 0:  # a power of two: x 1.5
            k = k * 3 // 2
        else:  # 3 x a power of two: x 4/3
            k = k * 4 // 3


def moordyn_stable_step(segments, reference_peak, ba, probe=12.0):
    """The largest step of the ladder at which MoorDyn runs ``probe`` seconds with a finite
    tension below twice the peak (probed with COUPLING-second Step calls)."""
    for dt in ladder(COUPLING, 1e-6):
        tension, _, _ = run_moordyn(segments, dt, probe, ba, coupling=COUPLING)
        if tension is not None and np.all(np.isfinite(tension)):
            if tension.max() < 2.0 * reference_peak:
                return dt
    raise RuntimeError("MoorDyn found no stable step")


def _swing(tension, times):
    late = tension[times >= SETTLED]
    return float(late.max() - late.min())


def moordyn_run(segments, duration, ba, times, peak):
    """MoorDyn's chosen run: the largest step from its stable one down to a quarter of it that
    agrees with its converged run (an MD_REFERENCE-th of the stable step) within MD_SOUND of
    the peak tension (a bounded run is not yet a sound one: near its stability limit MoorDyn can
    stay finite and wrong). Its CPU time is the best of REPEAT runs, driven as chosen and with
    COUPLING-second Step calls; the latter's change of the tension swing is reported."""
    stable = moordyn_stable_step(segments, peak, ba)
    converged, _, _ = run_moordyn(segments, stable / MD_REFERENCE, duration, ba)
    for dt in ladder(stable, stable / 4):
        tension, cpu, startup = run_moordyn(segments, dt, duration, ba)
        if tension is not None and (error := _error(tension, converged, times)) <= MD_SOUND:
            break
    else:
        raise RuntimeError(f"MoorDyn: no step within {MD_SOUND:.0%} at {segments} segments")
    coarse, coarse_cpu, _ = run_moordyn(segments, dt, duration, ba, coupling=COUPLING)
    for _ in range(REPEAT - 1):
        cpu = min(cpu, run_moordyn(segments, dt, duration, ba)[1])
        coarse_cpu = min(coarse_cpu, run_moordyn(segments, dt, duration, ba, COUPLING)[1])
    return dict(
        moordyn=tension,
        md_dt=dt,
        md_stable=stable,
        md_per_s=cpu / duration,
        md_coarse_per_s=coarse_cpu / duration,
        md_startup=startup,
        md_error=error,
        md_coarse_swing=_swing(coarse, times) / _swing(tension, times) - 1,
        md_coarse_error=_error(coarse, tension, times),
    )


# ---- seacable ------------------------------------------------------------------------------------
def case(segments, duration, integrator, damping, time_step=None, **simulation):
    """The race's line as a system: a fixed body ``anchor``, an imposed body ``fairlead`` that
    surges with the sine, and the lumped-mass line ``chain`` from the fairlead to the anchor,
    started on its discrete catenary between them."""
    field, value, _ = DAMPING[damping]
    surge = {
        "kind": "sine",
        "amplitude": AMPLITUDE,
        "period": PERIOD,
        "phase": -math.pi / 2,
        "offset": AMPLITUDE,
    }
    return seacable.load_case(
        {
            "name": f"benchmark chain, {segments} segments",
            "environment": {
                "water_density": 1025.0,
                "water_depth": DEPTH,
                # MoorDyn's plain spring-damper: no smoothing band (environment.Seabed)
                "seabed": {
                    "stiffness": SEABED_K,
                    "damping": SEABED_C,
                    "friction_coefficient": 0,
                    "contact_band": 0.0,
                },
            },
            "bodies": [
                {"name": "fairlead", "type": "imposed", "x": surge, "z": FAIRLEAD_Z},
                {"name": "anchor", "type": "fixed", "position": list(ANCHOR)},
            ],
            "line_types": [
                {
                    "name": "chain",
                    "diameter": DIAMETER,
                    "mass_per_length": MASS,
                    "axial_stiffness": EA,
                    field: value,
                    "drag_coefficient_normal": CD_N,
                    "drag_coefficient_tangential": CD_T,
                    "added_mass_coefficient": CA,
                }
            ],
            "lines": [
                {
                    "name": "chain",
                    "model": "lumped_mass",
                    "from": "fairlead",
                    "to": "anchor",
                    "sections": [{"type": "chain", "segments": segments, "length": LENGTH}],
                    "initial": "catenary",
                }
            ],
            "start": "as_given",
            "simulation": {
                "duration": duration,
                "output_interval": OUTPUT,
                "integrator": integrator,
                **({"time_step": time_step} if time_step else {}),
                **simulation,
            },
        }
    )


def timed(c, limit=contextlib.nullcontext):
    """A case's results, the CPU time of its stepping and of its start-up (a run of one output
    interval, compiled beforehand: the stepping's time is the whole run's less that), the run
    inside the context ``limit()``."""
    once = {"duration": c.simulation.output_interval}
    warm = c.model_copy(update={"simulation": c.simulation.model_copy(update=once)})
    seacable.simulate(warm)  # compile (or load from the cache) first
    start = CLOCK()
    seacable.simulate(warm)
    startup = CLOCK() - start
    start = CLOCK()
    with limit():
        ds = seacable.simulate(c).dataset
    return ds, max(CLOCK() - start - startup, 1e-9), startup


def run_seacable(segments, duration, integrator, damping, time_step=None, **simulation):
    """Fairlead tension every OUTPUT seconds, the CPU time of the stepping and of the start-up
    (building the line and its equilibrium, a run of one output interval, kernels compiled
    beforehand), and the work attributes."""
    ds, cpu, startup = timed(case(segments, duration, integrator, damping, time_step, **simulation))
    # the force of the line on the fairlead body (the end node's inertia included)
    force = np.sqrt(sum(ds[f"bodies/fairlead/line_force_{c}"] ** 2 for c in "xyz"))
    # drop t = 0: MoorDyn reports from the first step
    return force.values[1:], cpu, startup, ds.attrs


def _error(tension, reference, times):
    late = times >= SETTLED
    return float(np.max(np.abs(tension[late] - reference[late])) / np.max(reference))


# seacable's configurations: generalized-alpha at its default spectral radius (0.5, safe when
# slack segments snap taut) and at 0.8 (less numerical damping: longer steps at equal accuracy
# on this line, which never goes slack), and rk4
CONFIGURATIONS = (
    ("generalized_alpha", {**NEWTON, "spectral_radius": 0.5}),
    ("generalized_alpha r0.8", {**NEWTON, "spectral_radius": 0.8}),
    ("rk4", {}),
)


def _seacable_candidates(segments, duration, damping, reference, times, target):
    """The fastest seacable run within the target, and every run found: each configuration at
    the largest step of the ladder at which it is stable and within the target. Rows:
    (stepping cpu, configuration, dt, tension, error, start-up cpu)."""
    found, refused = [], {}
    for name, settings in CONFIGURATIONS:
        integrator = name.split()[0]
        for dt in ladder(0.05, 2e-4):
            # a step seacable refuses (rk4 beyond its stability limit about the start: a
            # CaseError at load or simulate time) or that diverges is a failed rung: the
            # ladder goes on to the next, smaller step
            try:
                tension, cpu, startup, _ = run_seacable(
                    segments, duration, integrator, damping, dt, **settings
                )
            except (seacable.CaseError, seacable.SimulationDiverged) as refusal:
                refused[name] = f"{dt:.3g} s: {refusal}"
                continue
            if (error := _error(tension, reference, times)) <= target:
                found.append((cpu, name, dt, tension, error, startup))
                break
    if not found:
        last = "; ".join(f"{name} at {why}" for name, why in refused.items())
        raise RuntimeError(
            f"no seacable run within {target:.2e} at {segments} segments (last refused: {last})"
        )
    return min(found, key=lambda row: row[0]), found


def race(segments, duration, damping):
    times = np.arange(1, int(round(duration / OUTPUT)) + 1) * OUTPUT
    reference = run_seacable(segments, duration, "dopri5", damping, rtol=1e-9, atol=1e-9)[0]
    md = moordyn_run(segments, duration, DAMPING[damping][2], times, reference.max())
    target = max(md["md_error"], 1e-3)
    best, found = _seacable_candidates(segments, duration, damping, reference, times, target)
    cpu, integrator, dt, tension, error, startup = best
    # the chosen run timed again: the best of REPEAT (a 20-segment run lasts some 30 ms, where
    # the machine's noise is tens of per cent)
    settings = dict(CONFIGURATIONS)[integrator]
    for _ in range(REPEAT - 1):
        again = run_seacable(segments, duration, integrator.split()[0], damping, dt, **settings)
        cpu = min(cpu, again[1])
    md_cpu = min(md["md_per_s"], md["md_coarse_per_s"]) * duration
    return dict(
        md,
        segments=segments,
        times=times,
        seacable=tension,
        sc_integrator=integrator,
        sc_dt=dt,
        sc_per_s=cpu / duration,
        sc_startup=startup,
        sc_error=error,
        stepping=md_cpu / cpu,
        whole=(md["md_startup"] + md_cpu) / (startup + cpu),
        others={row[1]: (row[2], row[0] / duration) for row in found},
        difference=_error(tension, md["moordyn"], times),
    )


def _damping_line(damping, sizes):
    """What the variant's axial damping is at each size: alpha [ms] and zeta."""
    field, value, ba = DAMPING[damping]
    critical = [LENGTH / n * math.sqrt(MASS / EA) for n in sizes]  # alpha_crit [s]
    alphas = (
        [value * a for a in critical] if field == "axial_damping_ratio" else [value] * len(sizes)
    )
    at = ", ".join(
        f"{n}: alpha {a * 1e3:.3g} ms = {a / c:.3g} x critical"
        for n, a, c in zip(sizes, alphas, critical, strict=False)
    )
    return f"axial damping '{damping}' (seacable {field}: {value:g}; MoorDyn BA {ba:g}): {at}"


def _print_rows(rows, duration):
    header = (
        f"{'segs':>4} | {'MoorDyn dt':>10} {'s/s':>8} {'s/s 10ms':>8} {'err':>8} {'start':>7} | "
        f"{'seacable':>22} {'dt':>8} {'s/s':>8} {'err':>8} {'start':>7} | {'stepping':>8} "
        f"{'whole':>7} | {'max |dT|/T':>10} | {'10ms swing':>10} | other seacable runs"
    )
    print(header)
    print("-" * len(header))
    for r in rows:
        others = ", ".join(
            f"{name} {dt:.3g} s: {per_s:.4f} s/s" for name, (dt, per_s) in r["others"].items()
        )
        print(
            f"{r['segments']:4d} | {r['md_dt']:10.3g} {r['md_per_s']:8.4f} "
            f"{r['md_coarse_per_s']:8.4f} {r['md_error']:8.1e} {r['md_startup']:7.3f} | "
            f"{r['sc_integrator']:>22} {r['sc_dt']:8.4g} {r['sc_per_s']:8.4f} "
            f"{r['sc_error']:8.1e} {r['sc_startup']:7.3f} | {r['stepping']:7.1f}x "
            f"{r['whole']:6.1f}x | {r['difference']:10.2e} | {r['md_coarse_swing']:+9.2%} | "
            f"{others}"
        )
    print(
        "\ns/s: CPU seconds per simulated second of stepping (MoorDyn: one Step call per "
        "internal step, then with 10 ms Step calls, the same internal steps); start: start-up "
        "CPU time [s] (MoorDyn: Create and Init, its initial-condition solve run to a 1e-4 "
        "threshold; seacable: building the line and its equilibrium); stepping: speed-up of the "
        "stepping (against MoorDyn's faster driving); whole: speed-up of the whole "
        f"{duration:g} s run, start-up included; err: largest fairlead-tension error after "
        f"t = {SETTLED:g} s against the code's own converged run (MoorDyn: its stable step / "
        f"{MD_REFERENCE}; seacable: dopri5, rtol 1e-9), relative to the peak tension; "
        f"max |dT|/T: largest difference between the codes after t = {SETTLED:g} s, relative "
        "to the peak tension; 10ms swing: change of MoorDyn's tension range (max - min after "
        f"t = {SETTLED:g} s) when driven by 10 ms Step calls (velocity held through each)."
    )


DRIVEN = (
    "How each code was driven: MoorDyn-C (RK2) by one Step call per internal step, given the "
    "exact fairlead position at the step's start and the secant velocity to the exact position "
    "at its end (MoorDyn holds the velocity through a Step and has no acceleration input: "
    "within a step the fairlead follows the chord, off the path by a dt^2/8, 2e-9 m at a 0.1 ms "
    "step); "
    "its Create/Init initial-condition solve; the inertia of its coupled end node added back. "
    "seacable: the imposed sine evaluated exactly at every stage, the start from its discrete "
    "catenary equilibrium."
)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="20 and 40 segments, 12 s")
    parser.add_argument(
        "--damping",
        choices=tuple(DAMPING),
        default="critical",
        help="axial damping: each segment critically damped (default, MoorDyn's BA = -1) or "
        "the over-damped line of the first race (alpha = 2 ms, 2.75 x critical at 160 segments)",
    )
    args = parser.parse_args(argv)
    logging.getLogger("seacable").setLevel(logging.ERROR)  # the ladders probe rk4 past its limit
    sizes = (20, 40) if args.quick else (20, 40, 80, 160)
    duration = 12.0 if args.quick else 30.0
    print(_damping_line(args.damping, sizes))
    print(DRIVEN)
    print()
    rows = [race(n, duration, args.damping) for n in sizes]
    print(f"fairlead tension [kN], {sizes[-1]} segments")
    last = rows[-1]
    print(f"{'t [s]':>7} {'MoorDyn':>10} {'seacable':>10}")
    for t in (3.0, 6.0, 9.0, 12.0, 18.0, 24.0, 30.0):
        k = int(round(t / OUTPUT)) - 1
        if k < len(last["times"]):
            print(f"{t:7.1f} {last['moordyn'][k] / 1e3:10.3f} {last['seacable'][k] / 1e3:10.3f}")
    print()
    _print_rows(rows, duration)


if __name__ == "__main__":
    main()
