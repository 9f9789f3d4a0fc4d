"""An operability map: for many weather states (a grid of current and wind directions and
speeds, or a user's table of current, wind and waves: ``table``), is the tandem safe?

Each state gets one status (``STATUSES``):

- ``stable``: a stable equilibrium exists, its hulls' clearance and its ties' tensions within
  the limits (with ``simulate``: and the motion from it stays within them); in a calm (no
  current, wind or waves) a neutral one counts (``equilibria.Equilibrium.neutral``: nothing
  damps the ships or holds their heading, and nothing drives them);
- ``limit exceeded``: the stable equilibrium (one whose hulls do not overlap, the ships lying
  to each other most as at their nominal places: ``equilibria.relative``) breaks a tension
  limit or comes closer than the clearance limit;
- ``cycling``: no stable equilibrium: the ships oscillate (fishtailing); the message names
  the kind of the equilibrium kept; with ``simulate`` the motion stays within the limits;
- ``collision risk``: with ``simulate``, the motion brings the hulls closer than the clearance
  limit (or every stable equilibrium has overlapping hulls);
- ``no equilibrium``: the search found none (the ships may drift on, or the search missed
  them: it is exhaustive only where its scan's premise holds, see below);
- ``failed``: the state could not be analysed; its message says why. A failed state is a row
  with its message, never a lost map.

The equilibria of a state are found from those of the nearest state solved (the map is swept
in order, so neighbours start each other) and, when those give no stable one with the hulls
apart, by the whole search (scanned starts and ``headings`` per body:
seacable.stability.equilibria), and classified by their eigenvalues. With ``simulate`` [s] each
state is also integrated for that long (the fixed-step flow of seacable.stability.orbits) from
the equilibrium kept (above: the stable one, or without one the unstable one where the ships
lie most as at their nominal places) pushed off by 1 m and 1 deg (``start`` "equilibrium"),
or (``start`` "nominal") from the ships at rest as at their nominal places around the first
ship where that equilibrium has it (``equilibria.placed``): the shuttle just connected astern
of the FPSO as it weathervanes, and the motion that follows.

States run in chunks, in this process (``scheduler=None``) or on Dask: ``"local"`` starts a
local cluster of one single-threaded worker process per core; any other string is the address
of a running scheduler. Dask does the scheduling and the transport; a chunk lost with its
worker becomes rows of ``failed``.
"""

import math
import tempfile
from dataclasses import dataclass, replace

import numpy as np
import xarray as xr

from seacable import cluster, files
from seacable.case import loader
from seacable.case.system import SystemCase
from seacable.errors import CaseError
from seacable.stability import equilibria as eq
from seacable.stability import orbits
from seacable.stability.plane import Plane, Weather, case_waves

CONTROLS = ("uncontrolled", "controlled")
STARTS = ("equilibrium", "nominal")  # where a map's simulations start (``operability``)
# the compensators' settings a map runs (``operability``'s ``control``)
CONTROL: dict = {None: (None,), "off": (False,), "on": (True,), "both": (False, True)}
# [s] how long the motion from the nominal places may take to reach a stable equilibrium that
# breaks a limit before that equilibrium decides the state: an hour, as the example case's
# duration that ``compare`` runs by default
REACH = 3_600.0
STATUSES = ("stable", "limit exceeded", "cycling", "collision risk", "no equilibrium", "failed")


@dataclass(frozen=True)
class Limits:
    """The operator's limits: the least clearance between the hulls [m] and the largest
    tension of each tie [N] (by name; a tie not named has none)."""

    clearance: float = 0.0
    tension: tuple[tuple[str, float], ...] = ()


def grid(current_speed: float, current_towards: np.ndarray, wind_towards: np.ndarray,
         ratios: np.ndarray) -> tuple[list[Weather], dict]:  # fmt: skip
    """The weather states of a grid: every current direction (towards) [deg] with every wind
    direction [deg] and every ratio of wind speed to current speed; returns the states (current
    direction slowest, ratio fastest) and the grid's coordinates; a grid of more than
    MOST_STATES states is refused with its size."""
    size = len(current_towards) * len(wind_towards) * len(ratios)
    if size > MOST_STATES:
        raise CaseError(
            f"operability grid: {len(current_towards):,} current directions x "
            f"{len(wind_towards):,} wind directions x {len(ratios):,} ratios = "
            f"{size:,} states, more than {MOST_STATES:,}; take larger steps"
        )
    states = [Weather(current_speed, float(c), float(r) * current_speed, float(w))
              for c in current_towards for w in wind_towards for r in ratios]  # fmt: skip
    coords = {"current_towards_deg": np.asarray(current_towards, float),
              "wind_towards_deg": np.asarray(wind_towards, float),
              "wind_current_ratio": np.asarray(ratios, float)}  # fmt: skip
    return states, coords


# a user's table of weather states (``table``): its columns by name, the first four required
LARGEST_STATES = 50_000_000  # bytes of a table of weather states
MOST_STATES = 1_000_000  # weather states of a map (each an equilibrium search, or a run)
COLUMNS = ("current_speed", "current_towards_deg", "wind_speed", "wind_towards_deg",
           "wave_height", "wave_towards_deg", "probability")  # fmt: skip


def table(path) -> tuple[list[Weather], np.ndarray | None]:
    """The weather states of a CSV file (a metocean table): a header naming its columns
    (``COLUMNS``, any order: current_speed [m/s], current_towards_deg [deg],
    wind_speed [m/s], wind_towards_deg [deg]; optionally wave_height Hs [m] and
    wave_towards_deg [deg], which scale and turn the case's waves (``Weather``; empty: the
    case's own), and probability, each state's share of the time), then a state a row;
    lines starting with '#' are comments. Returns the states and the probabilities (None
    without that column)."""
    where = f"states file '{path}'"
    text = files.read_text(
        path,
        "states file",
        LARGEST_STATES,
        CaseError,
        fix="save it as UTF-8 CSV",
        give="give the path of a CSV file",
    )
    reader = files.csv_rows(text, where, CaseError)
    names = [n.strip() for n in next(reader, (0, []))[1]]
    unknown = [n for n in names if n not in COLUMNS]
    missing = [n for n in COLUMNS[:4] if n not in names]
    twice = sorted({n for n in names if names.count(n) > 1})
    if unknown or missing or twice:
        raise CaseError(f"{where}: columns {names}: " + (f"unknown {unknown}; " if unknown else "")
                        + (f"missing {missing}; " if missing else "")
                        + (f"given twice {twice}; " if twice else "")
                        + f"its header names its columns once each, of {list(COLUMNS)} (the "
                        "first four required)")  # fmt: skip
    states, shares = [], []
    for number, cells in reader:
        if len(cells) != len(names):
            raise CaseError(f"{where}, line {number}: {len(cells)} cells for {len(names)} "
                            "columns; give one cell a column (an empty one for the case's "
                            "waves)")  # fmt: skip
        values: dict[str, float | None] = {}
        for name, text in zip(names, cells, strict=True):
            text = text.strip()
            if text == "" and name in COLUMNS[4:6]:
                continue
            try:
                values[name] = float(text)
            except ValueError:
                raise CaseError(f"{where}, line {number}: {name} {files.quoted(text)} is not a "
                                "number; give a number (wave columns may be empty: the "
                                "case's waves)") from None  # fmt: skip
            if not math.isfinite(values[name] or 0.0):
                raise CaseError(f"{where}, line {number}: {name} {files.quoted(text)}: give a "
                                "finite number")  # fmt: skip
        for name in ("current_speed", "wind_speed", "wave_height", "probability"):
            if (values.get(name) or 0.0) < 0.0:
                raise CaseError(f"{where}, line {number}: {name} {values[name]:g} is negative; "
                                "give a size (the direction is the 'towards' column)")  # fmt: skip
        shares.append(values.pop("probability", math.nan))
        states.append(Weather(**values))  # type: ignore[arg-type]
    if not states:
        raise CaseError(f"{where}: no states; give a row per state under the header")
    if "probability" not in names:
        return states, None
    probability = np.array(shares)
    if not probability.sum() > 0.0:
        raise CaseError(f"{where}: the probabilities sum to {probability.sum():g}; give "
                        "each state's share of the time (they are scaled to sum to 1)")  # fmt: skip
    return states, probability / probability.sum()


def _fields(weather: Weather) -> tuple[float, ...]:
    """A state as six floats, plain data for Dask (NaN: the case's waves)."""
    return (weather.current_speed, weather.current_towards_deg, weather.wind_speed,
            weather.wind_towards_deg,
            math.nan if weather.wave_height is None else weather.wave_height,
            math.nan if weather.wave_towards_deg is None else weather.wave_towards_deg)  # fmt: skip


def _weather(state: tuple[float, ...]) -> Weather:
    """``_fields``'s inverse."""
    height, towards = state[4], state[5]
    return Weather(state[0], state[1], state[2], state[3],
                   None if math.isnan(height) else height,
                   None if math.isnan(towards) else towards)  # fmt: skip


def evaluate(packed: dict, states: list[tuple[float, ...]], limits: Limits,
             simulate: float | None, headings: int, controlled: bool | None = None,
             start: str = "equilibrium") -> list[dict]:  # fmt: skip
    """The rows of a chunk of weather states (each ``_fields``), in order, the equilibria of
    one seeding the next, with the compensators on or off (``controlled``; None: as the case
    says), for the case ``packed`` (``cluster.pack``: its settings and the bytes of the files
    it reads, built in a private temporary folder). Runs where Dask sends it: plain data in
    and out."""
    with tempfile.TemporaryDirectory(prefix="seacable-") as folder:
        try:
            case = cluster.unpack(packed, folder)
            plane = Plane.of(case, folder)
            if controlled is not None:
                plane.control(controlled)
        except Exception as exc:  # the whole chunk fails the same way
            return [_failed(f"the case: {exc}") for _ in states]
        return _rows_of(plane, states, limits, simulate, headings, start)


def _rows_of(plane: Plane, states, limits, simulate, headings, start) -> list[dict]:
    """``evaluate``'s rows for the built ``plane``."""
    nominal = eq.relative(plane, plane.start()[: 3 * len(plane.bodies)])
    solved: list[tuple[np.ndarray, list[np.ndarray]]] = []  # (weather's place, equilibria)
    rows = []
    for state in states:
        try:
            _weather(state).apply(plane.built)
            # the equilibria of the nearest state solved, continued; the whole search (scanned
            # and placed starts: seacable.stability.equilibria) when they give no stable one
            # with the hulls apart, first without the compensator's saturated equilibria
            here = _place_of(state)
            near = min(solved, key=lambda s: float(np.abs(s[0] - here).sum()), default=None)
            found = search(plane, headings, near[1] if near else [])
            solved.append((here, [e.x for e in found]))
            row = _classify(plane, found, nominal, limits, simulate, start,
                            _weather(state).calm(plane.built))  # fmt: skip
            rows.append(row)
        except Exception as exc:  # one state's failure is its row
            rows.append(_failed(f"{type(exc).__name__}: {exc}"))
    return rows


def search(plane: Plane, headings: int, extra=()) -> list[eq.Equilibrium]:
    """The equilibria of ``plane`` in the weather applied to it, as the map finds them: from
    ``extra`` (a neighbour's) and the scan, then, when those give no stable one with the hulls
    apart, the whole search (scanned and placed starts, ``headings`` per body:
    seacable.stability.equilibria), first without the compensator's saturated equilibria."""
    found = eq.find(plane, None, 0, extra=list(extra), iterations=30)
    for every in (False, True) if plane.controlled else (True,):
        if any(e.stable and clearance_at(plane, e.x) > 0.0 for e in found):
            break
        found = eq.find(plane, None, headings, extra=[e.x for e in found], iterations=30,
                        every=every)  # fmt: skip
    return found


def kept(plane: Plane, found: list, nominal: np.ndarray,
         calm: bool = False) -> tuple[eq.Equilibrium | None, list[eq.Equilibrium]]:  # fmt: skip
    """The equilibrium that stands for a state (None: none found) and the stable ones: a
    stable one (in a ``calm``, a neutral one too: no energy comes in to move the ships) or,
    without one, any; of those, one whose hulls do not overlap (without a contact model,
    overlapping equilibria exist, the compensator's among them, that no ship reaches), then
    the one where the ships lie to each other most as at their ``nominal`` places
    (``equilibria.relative``'s: the weather turns the whole of them)."""
    stable = [e for e in found if e.stable or (calm and e.neutral)]
    pool = stable or found
    if not pool:
        return None, stable
    apart = [e for e in pool if clearance_at(plane, e.x) > 0.0]
    best = min(apart or pool, key=lambda e: _distance(eq.relative(plane, e.x), nominal))
    return best, stable


def nominal_start(plane: Plane, best: eq.Equilibrium, nominal: np.ndarray) -> np.ndarray:
    """The state from which the ships start "from their nominal places": at rest, the first
    ship as at ``best``, each other at its ``nominal`` pose relative to the ship its tie holds
    it by (``equilibria.placed``): the shuttle just connected astern of the FPSO as it
    weathervanes."""
    state = np.zeros(plane.size)
    state[: 3 * len(plane.bodies)] = eq.placed(plane, best.x, nominal)
    return state


def _place_of(state: tuple[float, ...]) -> np.ndarray:
    """A weather state (``_fields``) as a point in which near states are near: the current's
    velocity [m/s], the wind's over 30 and the waves' height over 3 along their direction."""
    cs, ct, ws, wt, hs, ht = state
    ct, wt, ht = math.radians(ct), math.radians(wt), math.radians(0.0 if math.isnan(ht) else ht)
    hs = 0.0 if math.isnan(hs) else hs / 3.0
    return np.array([cs * math.cos(ct), cs * math.sin(ct), ws * math.cos(wt) / 30.0,
                     ws * math.sin(wt) / 30.0, hs * math.cos(ht), hs * math.sin(ht)])  # fmt: skip


def _failed(message: str) -> dict:
    return {"status": "failed", "message": message, "equilibria": 0, "stable_equilibria": 0,
            "growth": math.nan, "clearance": math.nan, "tension": math.nan,
            "period": math.nan, "surge_force": math.nan, "yaw_moment": math.nan,
            "reached": -1}  # fmt: skip


def clearance_at(plane: Plane, positions: np.ndarray) -> float:
    """The least distance [m] between the first two hulls' outlines at ``positions`` (inf:
    fewer than two hulls)."""
    hulls = [o for o in plane.outlines(positions) if o is not None]
    return orbits.clearance(hulls[:2]) if len(hulls) >= 2 else math.inf


def _tension_excess(plane: Plane, tension: np.ndarray, limits: Limits) -> tuple[float, str]:
    """The largest tension over its limit (ratio, > 1: exceeded) and the tie's name."""
    worst, name = 0.0, ""
    ties = list(plane.built.layout.ties)
    for tie, limit in limits.tension:
        ratio = float(tension[ties.index(tie)]) / limit
        if ratio > worst:
            worst, name = ratio, tie
    return worst, name


def _classify(plane: Plane, found: list, nominal: np.ndarray, limits: Limits,
              simulate: float | None, start: str = "equilibrium",
              calm: bool = False) -> dict:  # fmt: skip
    n = len(plane.bodies)
    best, stable = kept(plane, found, nominal, calm)
    if best is None:
        row = _failed("the search found no equilibrium")
        row["status"] = "no equilibrium"
        return row
    state = np.concatenate([best.x, np.zeros(3 * n)])
    plane.rates(state)
    tension = plane.work.tie_tension.copy()
    control = plane.work.control[0].copy() if plane.controlled else np.zeros(4)
    clearance = clearance_at(plane, best.x)
    growth = float(best.eigenvalues.real.max())
    row = {"equilibria": len(found), "stable_equilibria": len(stable), "growth": growth,
           "clearance": clearance, "tension": float(tension.max()) if tension.size else 0.0,
           "period": math.nan, "message": "", "surge_force": float(control[0]),
           "yaw_moment": float(control[1]), "reached": -1}  # fmt: skip
    excess, tie = _tension_excess(plane, tension, limits)
    saturated = bool(control[0] != control[2] or control[1] != control[3])
    breaks = clearance < limits.clearance or excess > 1.0 or saturated
    nominal_run = bool(simulate) and start == "nominal"
    motion = None
    if nominal_run or (best.stable and breaks):
        # the motion from the nominal places: does it reach the equilibrium that breaks a
        # limit? (not: the motion decides the state, not that equilibrium)
        duration = float(simulate or 0.0) if nominal_run else REACH
        motion = _motion(plane, nominal_start(plane, best, nominal), duration, limits)
        if best.stable and breaks:
            target = eq.relative(plane, best.x)
            near = min(_distance(eq.relative(plane, q[: 3 * n]), target) for q in motion[3][::5])
            row["reached"] = int(near < 5.0)
            if not row["reached"]:
                what = (f"hulls {clearance:.1f} m apart" if clearance < limits.clearance
                        else f"tie {tie} at {excess:.2f} times its tension limit"
                        if excess > 1.0 else "the compensator over its limits")  # fmt: skip
                return _unreached(row, motion, limits, what, n, duration)
    if simulate:
        if not nominal_run:  # from the equilibrium, pushed by 1 m and 1 deg (not the reach run)
            push = state.copy()
            push[0 : 3 * n : 3] += 1.0
            push[2 : 3 * n : 3] += math.radians(1.0)
            motion = _motion(plane, push, simulate, limits)
        assert motion is not None  # the nominal run's, or the one from the equilibrium
        least, highest, peak, _ = motion
        row["clearance"], row["tension"] = least, max(highest, row["tension"])
        excess = max(excess, peak)
    if row["clearance"] < limits.clearance:
        row["status"] = "collision risk" if (simulate or row["clearance"] == 0.0) else (
            "limit exceeded")  # fmt: skip
        row["message"] = f"hulls {row['clearance']:.1f} m apart (limit {limits.clearance:g} m)"
    elif excess > 1.0:
        row["status"] = "limit exceeded"
        row["message"] = f"tie {tie or 'a tie'} at {excess:.2f} times its tension limit"
    elif control[0] != control[2] or control[1] != control[3]:
        row["status"] = "limit exceeded"
        row["message"] = (
            f"the compensator needs {control[2] / 1e3:.4g} kN and "
            f"{control[3] / 1e6:.4g} MN m to hold its ship: over its limits"
        )
    elif stable:
        row["status"] = "stable"
        if not best.stable:
            row["message"] = ("calm: nothing damps the ships or holds their heading; they lie "
                              "still at any heading")  # fmt: skip
    else:
        row["status"] = "cycling"
        if not row["message"]:
            row["message"] = f"no stable equilibrium; the one kept: {best.kind}"
    return row


def _motion(plane: Plane, push: np.ndarray, duration: float,
            limits: Limits) -> tuple[float, float, float, np.ndarray]:  # fmt: skip
    """The motion from ``push`` for ``duration`` [s] (1 s steps): the hulls' least clearance
    [m], the highest tension [N], the largest ratio of a tie's tension to its limit (each
    every 5 s), and the path."""
    n = len(plane.bodies)
    _, path = orbits.integrate(plane, push, duration, int(math.ceil(duration)), record=True)
    least, peak, highest = math.inf, 0.0, 0.0
    ties = list(plane.built.layout.ties)
    for k in range(0, path.shape[0], 5):
        least = min(least, clearance_at(plane, path[k, : 3 * n]))
        plane.rates(path[k])
        tension = plane.work.tie_tension
        highest = max(highest, float(tension.max()) if tension.size else 0.0)
        for name, limit in limits.tension:
            peak = max(peak, float(tension[ties.index(name)]) / limit)
    return least, highest, peak, path


def _unreached(row: dict, motion: tuple, limits: Limits, what: str, n: int,
               duration: float) -> dict:  # fmt: skip
    """The row of a state whose stable equilibrium breaks a limit (``what``) but is not
    reached from the nominal places in ``duration`` [s]: the ``motion`` from there
    (``_motion``'s, ``n`` bodies) decides it."""
    least, highest, peak, path = motion
    tail = path[-1000:, : 3 * n]  # the last 1,000 s: at rest within 5 cm, or moving
    spread = float(np.hypot(tail[:, 0::3] - tail[:, 0::3].mean(axis=0),
                            tail[:, 1::3] - tail[:, 1::3].mean(axis=0)).max())  # fmt: skip
    still = spread < 0.05
    row["clearance"], row["tension"] = least, highest
    if least < limits.clearance:
        row["status"] = "collision risk"
    elif peak > 1.0:
        row["status"] = "limit exceeded"
    else:
        row["status"] = "stable" if still else "cycling"
    how = "comes to rest" if still else f"keeps moving ({spread:.2g} m about its mean at the end)"
    row["message"] = (
        f"the stable equilibrium ({what}) is not reached from the nominal places in "
        f"{duration:.0f} s: the motion from there {how}, the hulls at least {least:.1f} m "
        f"apart, the ties' tension up to {highest / 1e3:.4g} kN"
    )
    return row


def _distance(x: np.ndarray, nominal: np.ndarray) -> float:
    """How far poses ``x`` are from ``nominal`` (both ``equilibria.relative``'s): metres,
    and 100 m a radian."""
    d = np.abs(x - nominal)
    d[2::3] = np.abs((d[2::3] + math.pi) % (2 * math.pi) - math.pi) * 100.0
    return float(d.sum())


def operability(case: SystemCase | str, states: list[Weather], shape: dict | None = None,
                limits: Limits = Limits(), simulate: float | None = None,
                scheduler: str | None = "local", chunk: int = 108,
                headings: int = 6, control: str | None = None,
                probability: np.ndarray | None = None,
                start: str = "equilibrium") -> xr.Dataset:  # fmt: skip
    """The map (module docstring) of ``states``; ``shape`` (from ``grid``): their grid's
    coordinates (else a dimension ``state``); ``control``: the compensators (forces.compensator)
    as the case says (None), "off", "on", or "both" (a leading dimension ``control``:
    uncontrolled, controlled); ``probability``: each state's share of the time (``table``),
    kept with the map (``shares`` weighs the statuses by it); ``start``: where the
    simulations start (``STARTS``; module docstring).

    Returns
    -------
    xarray.Dataset
        ``status`` (a string of ``STATUSES``), ``message``, ``equilibria``,
        ``stable_equilibria``, ``growth`` [1/s] (the largest real part at the equilibrium kept),
        ``clearance`` [m] and ``tension`` [N] (the largest tie tension; with ``simulate``,
        the least clearance and the largest tension along the motion too, every 5 s),
        ``surge_force`` [N] and
        ``yaw_moment`` [N m] (the compensator's there), the weather's six fields (a state
        without waves given has the case's, NaN without any) and ``probability`` when given,
        over the grid or ``state``.
    """
    if isinstance(case, str):
        case = loader.load_case(case)
    if not isinstance(case, SystemCase):
        raise CaseError("operability: give a case with bodies: and lines:")
    plane = Plane.of(case, loader.case_base_dir(case))  # refused here, with its one line
    if control not in CONTROL:
        raise CaseError(f"control '{control}': give one of {list(CONTROL)[1:]} (or none: as "
                        "the case says)")  # fmt: skip
    if start not in STARTS:
        raise CaseError(f"start '{start}': give one of {list(STARTS)}")
    if control not in (None, "off") and plane.controlled is None:
        raise CaseError(f"control '{control}': no ship has a 'compensator' force model; add "
                        "one ({model: compensator, point, target, distance})")  # fmt: skip
    packed = cluster.pack(case)
    if case.environment.waves:  # the case's own waves, as what they are
        height, towards = case_waves(case.environment)
        states = [replace(w, wave_height=height if w.wave_height is None else w.wave_height,
                          wave_towards_deg=towards if w.wave_towards_deg is None
                          else w.wave_towards_deg) for w in states]  # fmt: skip
    plain = [_fields(w) for w in states]
    if probability is not None and len(probability) != len(plain):
        raise CaseError(f"probability: {len(probability)} values for {len(plain)} states; give "
                        "one a state")  # fmt: skip
    for weather in states:  # what no state can have (no waves to scale): one line, not a map
        if weather.wave_height is not None or weather.wave_towards_deg is not None:
            weather.apply(plane.built)
            break
    chunks = [(plain[i : i + chunk], flag) for flag in CONTROL[control]
              for i in range(0, len(plain), chunk)]  # fmt: skip
    if scheduler is None:
        rows = [r for c, flag in chunks
                for r in evaluate(packed, c, limits, simulate, headings, flag, start)]  # fmt: skip
    else:
        rows = _on_dask(scheduler, packed, chunks, limits, simulate, headings, start)
    if control is None:
        return _dataset(rows, plain, shape, limits, simulate, probability, start)
    parts = [_dataset(rows[k * len(plain) : (k + 1) * len(plain)], plain, shape, limits,
                      simulate, probability, start)
             for k in range(len(CONTROL[control]))]  # fmt: skip
    names = [CONTROLS[int(flag)] for flag in CONTROL[control]]
    return xr.concat(parts, dim="control").assign_coords(control=names)


def _on_dask(scheduler: str, packed, chunks, limits, simulate, headings,
             start) -> list[dict]:  # fmt: skip
    with cluster.client(scheduler, "a map") as client:
        [case] = client.scatter([packed], broadcast=True)  # sent to each worker once
        futures = [client.submit(evaluate, case, c, limits, simulate, headings, flag, start,
                                 pure=False) for c, flag in chunks]  # fmt: skip
        rows: list[dict] = []
        for (chunk, _), future in zip(chunks, futures, strict=True):
            try:
                rows.extend(future.result())
            except Exception as exc:  # the chunk's worker died, or the task could not run
                rows.extend(_failed(f"on Dask: {type(exc).__name__}: {exc}") for _ in chunk)
        return rows


def _dataset(rows, plain, shape, limits, simulate, probability, start) -> xr.Dataset:
    dims: tuple[str, ...] = ("state",)
    coords: dict = {}
    sizes: tuple[int, ...] = (len(rows),)
    if shape is not None:
        dims = tuple(shape)
        coords = shape
        sizes = tuple(len(v) for v in shape.values())

    def field(name, dtype=float):
        return np.array([r[name] for r in rows], dtype=dtype).reshape(sizes)

    weather = np.array(plain, dtype=float).reshape(*sizes, 6)
    shares = {} if probability is None else {
        "probability": (dims, np.asarray(probability, float).reshape(sizes))}  # fmt: skip
    return xr.Dataset(
        {
            "status": (dims, field("status", str)),
            "message": (dims, field("message", str)),
            "equilibria": (dims, field("equilibria", int)),
            "stable_equilibria": (dims, field("stable_equilibria", int)),
            "growth": (dims, field("growth"), {"units": "1/s"}),
            "clearance": (dims, field("clearance"), {"units": "m"}),
            "tension": (dims, field("tension"), {"units": "N"}),
            "surge_force": (dims, field("surge_force"), {"units": "N"}),
            "yaw_moment": (dims, field("yaw_moment"), {"units": "N m"}),
            "reached": (
                dims,
                field("reached", np.int8),
                {
                    "long_name": "the stable equilibrium that breaks a limit reached from the "
                    "nominal places (1), not reached (0: the motion decides), not asked (-1)"
                },
            ),
            "current_speed": (dims, weather[..., 0], {"units": "m/s"}),
            "current_towards": (dims, weather[..., 1], {"units": "deg"}),
            "wind_speed": (dims, weather[..., 2], {"units": "m/s"}),
            "wind_towards": (dims, weather[..., 3], {"units": "deg"}),
            "wave_height": (dims, weather[..., 4], {"units": "m", "nan": "no waves"}),
            "wave_towards": (dims, weather[..., 5], {"units": "deg", "nan": "no waves"}),
            **shares,
        },
        coords=coords,
        attrs={
            "clearance_limit": limits.clearance,
            "tension_limits": "; ".join(f"{t} {v:g} N" for t, v in limits.tension),
            "simulated": simulate or 0.0,
            "simulated_from": start if simulate else "",
            "statuses": ", ".join(STATUSES),
        },  # fmt: skip
    )


def shares(found: xr.Dataset) -> list[tuple[str, dict[str, int], dict[str, float]]]:
    """Per control setting (its label, "" without that dimension): each status's count of
    states and its share of the time (by ``probability``, else of the states)."""
    parts = [(found, "")] if "control" not in found.dims else [
        (found.sel(control=c), str(c)) for c in found["control"].values]  # fmt: skip
    out = []
    for part, label in parts:
        status = part["status"].values.ravel()
        weight = (part["probability"].values.ravel() if "probability" in part
                  else np.full(status.size, 1.0 / status.size))  # fmt: skip
        names = [n for n in STATUSES if np.any(status == n)]
        out.append((label, {n: int(np.sum(status == n)) for n in names},
                    {n: float(weight[status == n].sum()) for n in names}))  # fmt: skip
    return out
