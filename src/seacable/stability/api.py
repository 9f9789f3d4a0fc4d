"""The analyses' public forms: every equilibrium of a case for a weather, and the branches of
equilibria in a parameter, as xarray Datasets (``seacable.equilibria``,
``seacable.continuation``), the limit cycles (``seacable.periodic_orbit``), the curves of
folds and Hopf points in two parameters (``seacable.curves``); ``compare`` and ``weather_of``
come from their own modules (``stability.compare``, ``stability.datasets``)."""

import math

import numpy as np
import xarray as xr

from seacable.case.system import SystemCase
from seacable.errors import CaseError
from seacable.stability import cycles as cycle_branches
from seacable.stability import equilibria as eq
from seacable.stability import orbits, two_parameter
from seacable.stability.compare import compare
from seacable.stability.continuation import (
    Branch,
    Continuation,
    ContinuationError,
    SpecialPoint,
)
from seacable.stability.datasets import (
    hull_variables,
    plane_of,
    pose_variables,
    weather_attrs,
    weather_of,
)
from seacable.stability.parameters import parameter as named_parameter
from seacable.stability.parameters import unit
from seacable.stability.plane import Plane, Weather

# the most fixed steps ``periodic_orbit`` lets a motion run to settle on its cycle by default
# (about a minute: 20 us a step for one ship)
SETTLE_STEPS = 3_000_000


def equilibria(case: SystemCase | str, weather: Weather | None = None,
               headings: int = 12) -> xr.Dataset:  # fmt: skip
    """Every equilibrium of ``case`` in the horizontal plane for ``weather`` (the case's own by
    default), from ``headings`` headings per body (seacable.stability.equilibria), the stable
    ones first, then the most visited.

    Returns
    -------
    xarray.Dataset
        Per ``equilibrium`` and ``body``: ``x``, ``y`` [m], ``heading`` [deg]; per
        equilibrium: ``stable``, ``kind`` (stable, unstable: divergent / oscillatory),
        ``residual`` (the force balance, relative), ``hits`` (starts that reached it),
        ``tension`` (per ``tie``) [N]; ``eigenvalue_real``, ``eigenvalue_imag`` [1/s] per
        ``mode``, largest real part first.
    """
    plane = plane_of(case)
    weather = weather or weather_of(plane.built.case)
    found = eq.find(plane, weather, headings)
    n = len(plane.bodies)
    xs = np.array([e.x for e in found]).reshape(len(found), 3 * n)
    lam = np.array([e.eigenvalues[np.argsort(-e.eigenvalues.real)] for e in found]).reshape(
        len(found), 6 * n
    )
    tension = np.zeros((len(found), len(plane.built.layout.ties)))
    for i, e in enumerate(found):
        plane.rates(np.concatenate([e.x, np.zeros(3 * n)]))
        tension[i] = plane.work.tie_tension
    return xr.Dataset(
        {
            **pose_variables(plane, xs, "equilibrium"),
            "stable": ("equilibrium", np.array([e.stable for e in found], dtype=bool)),
            "kind": ("equilibrium", np.array([e.kind for e in found], dtype=str)),
            "residual": ("equilibrium", np.array([e.residual for e in found]), {"units": "1"}),
            "hits": ("equilibrium", np.array([e.hits for e in found])),
            "tension": (("equilibrium", "tie"), tension, {"units": "N"}),
            "eigenvalue_real": (("equilibrium", "mode"), lam.real, {"units": "1/s"}),
            "eigenvalue_imag": (("equilibrium", "mode"), lam.imag, {"units": "1/s"}),
        },
        coords={"body": plane.names, "tie": list(plane.built.layout.ties)},
        attrs=weather_attrs(weather),
    )


def continuation(case: SystemCase | str, parameter: str, start: float, end: float,
                 weather: Weather | None = None, headings: int = 12, step: float = 0.02,
                 switch: bool = True, points: int = 2000,
                 cycles: int = 0) -> xr.Dataset:  # fmt: skip
    """The branches of equilibria of ``case`` as ``parameter`` (a path, as
    seacable.stability.parameters names them) goes from ``start`` to ``end``: from every
    equilibrium at ``start`` (``headings`` per body), and with ``switch`` from every branch
    point found, both ways along the other branch. Folds, branch points and Hopf points are
    located (seacable.stability.continuation). With ``cycles`` > 0, from each Hopf point a
    branch of up to that many periodic orbits (multiple shooting beside an unstable
    equilibrium), and the point's criticality by simulation (seacable.stability.cycles).

    Returns
    -------
    xarray.Dataset
        Per ``point``: ``parameter``, ``branch`` (its number), ``unstable`` (eigenvalues with a
        positive real part), ``x``, ``y`` [m], ``heading`` [deg] per ``body``; per ``special``
        point: ``special_kind`` (fold, branch point, hopf), ``special_parameter``,
        ``special_branch``, ``special_frequency`` [rad/s] (Hopf), ``special_heading`` [deg],
        ``special_criticality`` (a Hopf point's, with ``cycles``: supercritical, subcritical,
        undecided, not judged; else empty), ``special_criticality_by`` ("simulation", or
        "branch": judged by the side its cycles lie on, where the equilibrium is unstable on
        both sides and no simulation settles), ``special_hysteresis`` (1: a subcritical point's
        large cycle persists where the equilibrium is stable, 0: not, -1: not judged). With
        ``cycles``, per ``cycle``: ``cycle_special`` (its Hopf point's index),
        ``cycle_parameter``, ``cycle_period`` [s], ``cycle_stable``, ``cycle_multiplier`` (the
        largest modulus but the one at 1), and per body ``cycle_heading_low``,
        ``cycle_heading_high`` [deg], ``cycle_amplitude_y`` [m] (peak to peak); the folds of
        cycles are special points of kind "fold of cycles".
    """
    plane = plane_of(case)
    weather = weather or weather_of(plane.built.case)
    weather.apply(plane.built)
    par = named_parameter(plane, parameter, weather)
    par.set(plane, start)
    work = Continuation(plane, par)
    branches: list[Branch] = []
    for e in eq.find(plane, None, headings):
        if any(_on(b, e.x, start) for b in branches):
            continue
        try:
            branches.append(work.run(e.x, start, end, step=step, points=points))
        except ContinuationError:
            continue
    if switch:
        for b in list(branches):
            for sp in [s for s in b.special if s.kind == "branch point"]:
                for sign in (1.0, -1.0):
                    direction = sign * work.null_direction(sp.x, sp.parameter)
                    try:
                        new = work.run(sp.x, sp.parameter, end if sign > 0 else start,
                                       step=step, points=points, direction=direction)  # fmt: skip
                    except ContinuationError:
                        continue
                    near = 1e-6 * par.scale
                    new.special = [s for s in new.special if abs(s.parameter - sp.parameter) > near]
                    # the branch point itself first, for the diagram
                    new.parameter.insert(0, sp.parameter)
                    new.x.insert(0, sp.x)
                    new.unstable.insert(0, new.unstable[0])
                    new.eigenvalues.insert(0, new.eigenvalues[0])
                    branches.append(new)
    found = _cycles(plane, par, branches, (min(start, end), max(start, end)), cycles)
    par.set(plane, start)
    ds = _branches_dataset(plane, parameter, branches, weather)
    return ds if found is None else _with_cycles(ds, plane, *found)


def _cycles(plane: Plane, par, branches: list[Branch], bounds: tuple[float, float],
            count: int):  # fmt: skip
    """The cycle branches and criticalities of every Hopf point (None without ``count``);
    folds of cycles are added to their Hopf point's branch as special points."""
    if count <= 0:
        return None
    out = []
    for branch in branches:
        for sp in [s for s in branch.special if s.kind == "hopf"]:
            cycle, kind = cycle_branches.from_hopf(plane, par, sp.x, sp.parameter, sp.frequency,
                                                   bounds, count, 0.2 * par.scale)  # fmt: skip
            out.append((cycle, kind))
            for mu in cycle.folds:
                branch.special.append(SpecialPoint("fold of cycles", mu,
                                                   np.full_like(sp.x, np.nan)))  # fmt: skip
    return (out,)


def _with_cycles(ds: xr.Dataset, plane: Plane, found: list) -> xr.Dataset:
    """``ds`` with the cycles' variables (``continuation``'s Returns)."""
    hopf = np.flatnonzero(ds["special_kind"].values == "hopf")
    criticality = np.full(ds.sizes["special"], "", dtype=object)
    judged_by = np.full(ds.sizes["special"], "", dtype=object)
    hysteresis = np.full(ds.sizes["special"], -1)
    names = ("special", "parameter", "period", "stable", "multiplier", "low", "high",
             "amplitude_y")  # fmt: skip
    rows: dict[str, list] = {k: [] for k in names}
    for index, (cycle, kind) in zip(hopf, found, strict=True):
        criticality[index] = kind.kind
        judged_by[index] = kind.by
        hysteresis[index] = -1 if kind.hysteresis is None else int(kind.hysteresis)
        for i in range(len(cycle.parameter)):
            m = cycle.multipliers[i]
            rows["special"].append(index)
            rows["parameter"].append(cycle.parameter[i])
            rows["period"].append(cycle.period[i])
            rows["stable"].append(cycle.stable[i])
            rows["multiplier"].append(float(np.sort(np.abs(np.delete(
                m, np.argmin(np.abs(m - 1.0)))))[-1]))  # fmt: skip
            rows["low"].append(np.degrees(cycle.low[i][2::3]))
            rows["high"].append(np.degrees(cycle.high[i][2::3]))
            rows["amplitude_y"].append(cycle.amplitude[i][1::3])
    nb = len(plane.bodies)

    def body(name):
        return np.array(rows[name]).reshape(-1, nb)

    return ds.assign(
        special_criticality=("special", criticality.astype(str)),
        special_criticality_by=("special", judged_by.astype(str)),
        special_hysteresis=("special", hysteresis),
        cycle_special=("cycle", np.array(rows["special"], dtype=int)),
        cycle_parameter=(
            "cycle",
            np.array(rows["parameter"], dtype=float),
            {"units": unit(ds.attrs["parameter"])},
        ),  # fmt: skip
        cycle_period=("cycle", np.array(rows["period"], dtype=float), {"units": "s"}),
        cycle_stable=("cycle", np.array(rows["stable"], dtype=bool)),
        cycle_multiplier=("cycle", np.array(rows["multiplier"], dtype=float)),
        cycle_heading_low=(("cycle", "body"), body("low"), {"units": "deg"}),
        cycle_heading_high=(("cycle", "body"), body("high"), {"units": "deg"}),
        cycle_amplitude_y=(("cycle", "body"), body("amplitude_y"), {"units": "m"}),
    )


def _on(branch: Branch, x: np.ndarray, mu: float, tolerance: float = 1e-3) -> bool:
    """Whether the point (x, mu) lies on ``branch`` (within ``tolerance`` m and rad)."""
    for bx, bm in zip(branch.x, branch.parameter, strict=True):
        d = np.abs(bx - x)
        d[2::3] = np.abs((d[2::3] + math.pi) % (2 * math.pi) - math.pi)
        if abs(bm - mu) < 1e-9 * max(1.0, abs(mu)) and d.max() < tolerance:
            return True
    return False


def _branches_dataset(plane, parameter, branches, weather) -> xr.Dataset:
    n = len(plane.bodies)
    xs = np.concatenate([np.array(b.x).reshape(-1, 3 * n) for b in branches]) if branches else (
        np.zeros((0, 3 * n)))  # fmt: skip
    index = np.concatenate([np.full(len(b.parameter), k) for k, b in enumerate(branches)]) if (
        branches) else np.zeros(0, int)  # fmt: skip
    special = [(k, s) for k, b in enumerate(branches) for s in b.special]
    sx = np.array([s.x for _, s in special]).reshape(len(special), 3 * n)
    return xr.Dataset(
        {
            "parameter": (
                "point",
                np.concatenate([b.parameter for b in branches]) if branches else np.zeros(0),
                {"long_name": parameter, "units": unit(parameter)},
            ),  # fmt: skip
            "branch": ("point", index),
            "unstable": (
                "point",
                np.concatenate([b.unstable for b in branches]) if branches else np.zeros(0, int),
            ),  # fmt: skip
            **pose_variables(plane, xs, "point"),
            "special_kind": ("special", np.array([s.kind for _, s in special], dtype=str)),
            "special_parameter": ("special", np.array([s.parameter for _, s in special])),
            "special_branch": ("special", np.array([k for k, _ in special], dtype=int)),
            "special_frequency": (
                "special",
                np.array([s.frequency for _, s in special]),
                {"units": "rad/s"},
            ),  # fmt: skip
            "special_heading": (("special", "body"), np.degrees(sx[:, 2::3]), {"units": "deg"}),
        },
        coords={"body": plane.names},
        attrs={"parameter": parameter, **weather_attrs(weather)},
    )


def periodic_orbit(case: SystemCase | str, weather: Weather | None = None,
                   parameter: str | None = None, value: float | None = None,
                   settle: float | None = None, headings: int = 12) -> xr.Dataset:  # fmt: skip
    """The limit cycle the system settles on from its oscillatory unstable equilibrium (the
    most visited), found by shooting (seacable.stability.orbits), for ``weather`` (the case's
    by default) and ``parameter`` at ``value`` (a path, as seacable.stability.parameters names
    them) when given. The start: that equilibrium, pushed along the real part of its growing
    oscillation's eigenvector, integrated until its amplitude settles (``orbits.settle``), at
    most ``settle`` seconds (default: 40 e-foldings of that oscillation's growth, at least 60
    of its periods, at most ``SETTLE_STEPS`` steps). A motion that comes to rest, drifts away,
    wanders or has not settled, and a shooting that does not converge, are refused
    (CaseError) with what the motion did and what to try: the orbit returned has converged.

    Returns
    -------
    xarray.Dataset
        ``period`` [s], ``converged``, ``residual``, ``stable`` (Floquet), ``multiplier_real``,
        ``multiplier_imag`` (per ``mode``); per ``body``: ``amplitude_x``, ``amplitude_y``
        [m], ``amplitude_heading`` [deg] (peak to peak); per ``tie``: ``tension_min``,
        ``tension_max`` [N]; ``clearance`` [m], the least distance between the first two hulls'
        outlines (nan: fewer than two hulls); the track over one period per ``time`` and
        ``body``: ``x``, ``y``, ``heading``, and ``tension`` per ``tie``; ``hull_x``,
        ``hull_y`` per ``body`` and ``corner``: the hull outlines in the body frame.
    """
    plane = plane_of(case)
    weather = weather or weather_of(plane.built.case)
    weather.apply(plane.built)
    if parameter is not None:
        if value is None:
            raise CaseError(f"parameter '{parameter}': give its value")
        named_parameter(plane, parameter, weather).set(plane, value)
    found = eq.find(plane, None, headings)
    n = plane.size
    growing = [e for e in found if not e.stable and "oscillatory" in e.kind]
    if not growing:
        raise CaseError("no equilibrium with a growing oscillation: nothing to settle on a "
                        "limit cycle from (the equilibria: "
                        f"{', '.join(e.kind for e in found) or 'none'})")  # fmt: skip
    start = growing[0]
    lam, vectors = np.linalg.eig(plane.jacobian(np.concatenate([start.x, np.zeros(n // 2)])))
    pairs = np.flatnonzero(np.abs(lam.imag) > 1e-12)
    k = pairs[np.argmax(lam[pairs].real)]
    guess_period = 2 * math.pi / abs(lam[k].imag)
    push = vectors[:, k].real
    push = push / np.abs(push[: n // 2]).max()  # a metre (or a radian) at most
    x0 = np.concatenate([start.x, np.zeros(n // 2)]) + 1e-2 * push
    # growing at Re(lambda) from 1 cm to a cycle of up to a few hundred metres, then settling
    # at about that rate (near a Hopf point both are slow): 40 e-foldings, 60 periods at least
    per = max(400, math.ceil(guess_period))  # steps a period: 1 s, or finer for short ones
    longest = (
        settle
        if settle is not None
        else min(max(60.0 * guess_period, 40.0 / lam[k].real), SETTLE_STEPS * guess_period / per)
    )
    center = np.concatenate([start.x, np.zeros(n // 2)])
    # shooting starts once the motion is within 20 % of its cycle; where it does not converge
    # from there, the motion settles on (without that shortcut) and shooting tries again
    went = orbits.settle(plane, x0, guess_period, per, longest, center=center, close=0.2)
    _refuse_unsettled(went, start.kind, lam[k], settle)
    orbit = _shoot(plane, went)
    if not orbit.converged and went.elapsed < longest:
        went = orbits.settle(plane, went.state, went.period, per, longest - went.elapsed)
        _refuse_unsettled(went, start.kind, lam[k], settle)
        orbit = _shoot(plane, went)
    if not orbit.converged:
        raise CaseError(
            f"shooting did not converge on the limit cycle the motion settled on (period about "
            f"{went.period:.6g} s after {went.elapsed:.6g} s of motion): {orbit.message}; the "
            "cycle may be too weakly attracting to settle on in that time (give a longer "
            "--settle) or not a periodic orbit (simulate the motion with seacable run)"
        )
    if (np.ptp(orbit.path, axis=0) / orbits._scales(plane)).max() < 1e-2:
        raise CaseError("shooting found an orbit of under 1 cm and 1e-5 rad: an equilibrium, "
                        "not a limit cycle")  # fmt: skip
    return _orbit_dataset(plane, orbit, weather, parameter, value)


def _shoot(plane: Plane, went: orbits.Settled) -> orbits.Orbit:
    """``orbits.shoot`` from where the motion settled, not converged (with its reason) where
    the flow leaves finite values from there."""
    try:
        return orbits.shoot(plane, went.state, went.period)
    except FloatingPointError:
        nan = np.full(plane.size, np.nan)
        why = "the flow left finite values from where the motion settled"
        return orbits.Orbit(nan, math.nan, nan, False, math.inf, np.empty((0, plane.size)), why)


def _refuse_unsettled(went: orbits.Settled, kind: str, lam: complex, settle) -> None:
    """A motion (``orbits.settle``'s) that gives no limit cycle to shoot from, refused with
    what it did and what to try."""
    motion = f"the motion from the unstable equilibrium ({kind})"
    if went.status == "diverged":
        raise CaseError(f"{motion} left finite values after {went.elapsed:.6g} s: the ships "
                        "drift away, no limit cycle holds them")  # fmt: skip
    if went.status == "rest" or (went.status == "cycle" and went.amplitude < 1e-2):
        raise CaseError(f"{motion} came to rest within {went.elapsed:.6g} s (on a stable "
                        "equilibrium): no limit cycle from there")  # fmt: skip
    if went.status == "irregular":
        a = np.asarray(went.amplitudes[-5:])
        shortest, _, longest = went.periods
        raise CaseError(
            f"{motion} settled into an irregular oscillation, no single periodic orbit: over "
            f"its last {went.elapsed / len(went.amplitudes):.6g} s the time between its swings "
            f"varied from {shortest:.6g} to {longest:.6g} s and its amplitude by "
            f"{100 * np.ptp(a) / a.mean():.2g} % from one such stretch to the next; simulate it "
            "with seacable run"
        )
    if went.status == "unsettled":
        given = "the --settle given" if settle is not None else "the default"
        raise CaseError(
            f"{motion} had not settled after {went.elapsed:.6g} s ({given}): its amplitude "
            f"still went from {went.amplitudes[-2]:.4g} to {went.amplitudes[-1]:.4g} (scaled) "
            f"over the last two stretches of 10 periods; it grows at {lam.real:.3g} 1/s, one "
            f"e-folding every {1.0 / max(lam.real, 1e-300):.3g} s (near a Hopf point a cycle "
            "takes long to settle): give a longer --settle"
        )


def _orbit_dataset(plane: Plane, orbit, weather: Weather, parameter, value) -> xr.Dataset:
    m = 3 * len(plane.bodies)
    path = orbit.path
    ties = list(plane.built.layout.ties)
    tension = np.empty((path.shape[0], len(ties)))
    clear = np.full(path.shape[0], math.nan)
    for i, state in enumerate(path):
        plane.rates(state)
        tension[i] = plane.work.tie_tension
        hulls = [o for o in plane.outlines(state[:m]) if o is not None]
        if len(hulls) >= 2:
            clear[i] = orbits.clearance(hulls[:2])
    heading = np.degrees(path[:, 2:m:3])
    mult = orbit.multipliers[np.argsort(-np.abs(orbit.multipliers))]
    return xr.Dataset(
        {
            "period": ((), orbit.period, {"units": "s"}),
            "converged": ((), orbit.converged),
            "residual": ((), orbit.residual, {"units": "1"}),
            "stable": ((), orbit.stable),
            "multiplier_real": ("mode", mult.real),
            "multiplier_imag": ("mode", mult.imag),
            "amplitude_x": ("body", np.ptp(path[:, 0:m:3], axis=0), {"units": "m"}),
            "amplitude_y": ("body", np.ptp(path[:, 1:m:3], axis=0), {"units": "m"}),
            "amplitude_heading": ("body", np.ptp(heading, axis=0), {"units": "deg"}),
            "tension_min": ("tie", tension.min(axis=0), {"units": "N"}),
            "tension_max": ("tie", tension.max(axis=0), {"units": "N"}),
            "clearance": (
                (),
                float(np.nanmin(clear)) if np.isfinite(clear).any() else math.nan,
                {"units": "m", "long_name": "least distance between the hulls"},
            ),  # fmt: skip
            "x": (("time", "body"), path[:, 0:m:3], {"units": "m"}),
            "y": (("time", "body"), path[:, 1:m:3], {"units": "m"}),
            "heading": (("time", "body"), heading, {"units": "deg"}),
            "tension": (("time", "tie"), tension, {"units": "N"}),
            **hull_variables(plane),
        },
        coords={
            "time": np.linspace(0.0, orbit.period, path.shape[0]),
            "body": plane.names,
            "tie": ties,
        },  # fmt: skip
        attrs={
            **weather_attrs(weather),
            "parameter": parameter or "",
            "value": math.nan if value is None else value,
        },  # fmt: skip
    )


def curves(case: SystemCase | str, first: str, start: float, end: float, second: str,
           second_start: float, second_end: float, weather: Weather | None = None,
           headings: int = 12, points: int = 400) -> xr.Dataset:  # fmt: skip
    """Curves of folds and Hopf points in two parameters (paths, as
    seacable.stability.parameters names them): the folds and Hopf points that a continuation
    in ``first`` from ``start`` to ``end`` finds with ``second`` at ``second_start``, each
    followed (seacable.stability.two_parameter) as ``second`` goes to ``second_end`` (and
    ``first`` stays between ``start`` and ``end``), up to ``points`` points a curve.

    Returns
    -------
    xarray.Dataset
        Per ``curve``: ``kind`` (fold, hopf); per ``curve_point``: ``curve`` (its number),
        ``first`` and ``second`` (the parameters' values), ``frequency`` [rad/s] (Hopf: the
        crossing pair's), ``x``, ``y`` [m] and ``heading`` [deg] per ``body``.
    """
    plane = plane_of(case)
    weather = weather or weather_of(plane.built.case)
    weather.apply(plane.built)
    shared = {"weather": weather}
    par1 = named_parameter(plane, first, weather, shared)
    par2 = named_parameter(plane, second, weather, shared)
    par2.set(plane, second_start)
    par1.set(plane, start)
    found: list = []
    for e in eq.find(plane, None, headings):
        try:
            branch = Continuation(plane, par1).run(e.x, start, end)
        except ContinuationError:
            continue
        for sp in branch.special:
            if sp.kind in two_parameter.KINDS and not any(
                k == sp.kind and abs(mu - sp.parameter) < 1e-6 * par1.scale for k, mu, _, _ in found
            ):
                found.append((sp.kind, sp.parameter, sp.x, sp.frequency))
    box = (min(start, end), max(start, end))
    traced = []
    for kind, mu, x, omega in found:
        try:
            traced.append(two_parameter.CurveContinuation(plane, par1, par2, kind).run(
                x, mu, second_start, second_end, box, 0.0 if kind == "fold" else omega,
                points=points))  # fmt: skip
        except ContinuationError:
            continue
    par1.set(plane, start)
    par2.set(plane, second_start)
    n = len(plane.bodies)
    xs = np.array([x for c in traced for x in c.x]).reshape(-1, 3 * n)
    return xr.Dataset(
        {
            "kind": ("curve", np.array([c.kind for c in traced], dtype=str)),
            "curve": (
                "curve_point",
                np.array([k for k, c in enumerate(traced) for _ in c.first], dtype=int),
            ),  # fmt: skip
            "first": (
                "curve_point",
                np.array([v for c in traced for v in c.first]),
                {"long_name": first, "units": unit(first)},
            ),  # fmt: skip
            "second": (
                "curve_point",
                np.array([v for c in traced for v in c.second]),
                {"long_name": second, "units": unit(second)},
            ),  # fmt: skip
            "frequency": (
                "curve_point",
                np.array([v for c in traced for v in c.frequency]),
                {"units": "rad/s"},
            ),  # fmt: skip
            **pose_variables(plane, xs, "curve_point"),
        },
        coords={"body": plane.names},
        attrs={"first": first, "second": second, **weather_attrs(weather)},
    )


__all__ = ["compare", "continuation", "curves", "equilibria", "periodic_orbit", "weather_of"]
