"""The command line's analyses of ships in the horizontal plane (seacable.stability,
docs/tandem.md): ``equilibria``, ``continuation``, ``curves``, ``orbit``, ``operability`` and
``compare``, registered on ``seacable.cli.main`` (``COMMANDS``); their failures reach its one
error boundary as seacable's exceptions."""

import math
from dataclasses import replace
from pathlib import Path

import click
import numpy as np
import xarray as xr

import seacable
from seacable import cli_types as types
from seacable import cluster, files, viz
from seacable.case import loader
from seacable.case.sweep import range_values
from seacable.case.system import SystemCase
from seacable.errors import CaseError
from seacable.stability import operability as stability_map
from seacable.stability.api import weather_of
from seacable.stability.plane import significant_height

LOADED: dict[str, SystemCase] = {}  # the case a command works on: its errors link to its keys


def load(case_file: str | Path, settings: tuple[str, ...] = ()) -> SystemCase:
    """The case of CASE_FILE with the command line's ``--set`` changes, kept in ``LOADED``
    for the command line's error boundary (``cli``: an error naming a key links to it)."""
    case = loader.with_settings(seacable.load_case(case_file), settings)
    LOADED["case"] = case
    return case


def _weather(case, current, wind, waves) -> seacable.Weather:
    """The case's weather with the options' current and wind (speed, towards_deg) and waves
    (significant height, towards_deg) replacing its own."""
    weather = weather_of(case)
    if current is not None:
        weather = replace(weather, current_speed=current[0], current_towards_deg=current[1])
    if wind is not None:
        weather = replace(weather, wind_speed=wind[0], wind_towards_deg=wind[1])
    if waves is not None:
        weather = replace(weather, wave_height=waves[0], wave_towards_deg=waves[1])
    return weather


WEATHER_OPTIONS = [
    click.option("--current", nargs=2, type=(types.SPEED, types.ANGLE), default=None,
                 help="Uniform current: speed [m/s] and the direction it goes towards [deg] "
                      "(default: the case's)."),
    click.option("--wind", nargs=2, type=(types.SPEED, types.ANGLE), default=None,
                 help="Constant wind: speed [m/s] and the direction it blows towards [deg] "
                      "(default: the case's)."),
    click.option("--waves", nargs=2, type=(types.NONNEGATIVE, types.ANGLE), default=None,
                 help="The case's waves scaled to a significant height [m] and turned to a mean "
                      "direction they go towards [deg] (default: the case's; they act through "
                      "the ships' wave drift)."),
    click.option("--headings", type=types.count(1, 360), default=12, show_default=True,
                 help="Starting headings per body in the search for equilibria."),
]  # fmt: skip


def _weather_options(command):
    for option in reversed(WEATHER_OPTIONS):
        command = option(command)
    return command


@click.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@_weather_options
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
def equilibria(case_file: str, current, wind, waves, headings: int, output: str | None) -> None:
    """Every equilibrium of the ships of CASE_FILE in the horizontal plane (surge, sway, yaw)
    for a current and a wind, and its stability from the linearised system's eigenvalues."""
    case = load(case_file)
    _check(case, output)
    weather = _weather(case, current, wind, waves)
    found = seacable.equilibria(case, weather, headings=headings)
    sea = ""
    if isinstance(case, SystemCase) and case.environment.waves:
        height = weather.wave_height or significant_height(case.environment)
        towards = ("" if weather.wave_towards_deg is None
                   else f" towards {weather.wave_towards_deg:g} deg")  # fmt: skip
        sea = f", waves Hs {height:g} m{towards}"
    click.echo(f"current {weather.current_speed:g} m/s towards {weather.current_towards_deg:g} "
               f"deg, wind {weather.wind_speed:g} m/s towards {weather.wind_towards_deg:g} deg"
               f"{sea}: {found.sizes['equilibrium']} equilibria")  # fmt: skip
    for i in range(found.sizes["equilibrium"]):
        e = found.isel(equilibrium=i)
        poses = "; ".join(
            f"{b} at ({e['x'].values[j]:.2f}, {e['y'].values[j]:.2f}) m heading "
            f"{e['heading'].values[j]:.2f} deg" for j, b in enumerate(found["body"].values)
        )  # fmt: skip
        growth = float(e["eigenvalue_real"].values.max())
        tensions = ", ".join(f"{t} {e['tension'].values[k] / 1e3:.4g} kN"
                             for k, t in enumerate(found["tie"].values))  # fmt: skip
        click.echo(f"{i + 1}. {e['kind'].item()} (largest Re lambda {growth:.3g} 1/s): {poses}"
                   + (f"; {tensions}" if tensions else ""))  # fmt: skip
    _write(found, output, "equilibria")


@click.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option(
    "--parameter",
    "path",
    required=True,
    help="What varies: current.speed, current.towards_deg, wind.speed, "
    "wind.towards_deg, waves.height, waves.towards_deg, lines.<tie>.unstretched_length, "
    "lines.<tie>.stiffness, "
    "bodies.<body>.points.<point>.x, bodies.<body>.external forces.<k>.force_x",
)
@click.option("--from", "start", type=types.ANY, required=True,
              help="The parameter's first value.")  # fmt: skip
@click.option("--to", "end", type=types.ANY, required=True, help="Its last value.")
@_weather_options
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Bifurcation diagram (.png).")
@click.option("--cycles", type=types.count(0, 100), default=0, show_default=True,
              help="Periodic orbits to follow from each Hopf point, and its kind.")  # fmt: skip
def continuation(case_file: str, path: str, start: float, end: float, current, wind, waves,
                 headings: int, output: str | None, plot: str | None,
                 cycles: int) -> None:  # fmt: skip
    """Branches of equilibria of the ships of CASE_FILE as a parameter varies, with their
    folds, branch points and Hopf points (pseudo-arclength continuation); with --cycles, the
    branches of limit cycles born at the Hopf points and whether each is super- or
    subcritical, by simulation."""
    case = load(case_file)
    _check(case, output, plot)
    found = seacable.continuation(case, path, start, end, _weather(case, current, wind, waves),
                                  headings=headings, cycles=cycles)  # fmt: skip
    branches = np.unique(found["branch"].values)
    click.echo(f"{len(branches)} branches, {found.sizes['point']} points")
    for i in range(found.sizes["special"]):
        s = found.isel(special=i)
        extra = (f", period {2 * math.pi / s['special_frequency'].item():.4g} s"
                 if s["special_kind"].item() == "hopf" else "")  # fmt: skip
        headings_text = ", ".join(f"{b} {s['special_heading'].values[j]:.3f} deg"
                                  for j, b in enumerate(found["body"].values))  # fmt: skip
        if "special_criticality" in found and s["special_criticality"].item():
            by = {"branch": "the side its cycles lie on"}.get(
                s["special_criticality_by"].item(), "simulation"
            )
            extra += f", {s['special_criticality'].item()} by {by}"
        if s["special_kind"].item() == "fold of cycles":
            headings_text = "where the limit cycles turn back"
        click.echo(f"{s['special_kind'].item()} at {path} = "
                   f"{s['special_parameter'].item():.10g} (branch "
                   f"{s['special_branch'].item()}; {headings_text}{extra})")  # fmt: skip
    if "cycle" in found.dims:
        for k in np.unique(found["cycle_special"].values):
            on = found.where(found["cycle_special"] == k, drop=True)
            click.echo(f"  cycles from the Hopf point {k + 1}: {on.sizes['cycle']} orbits, "
                       f"{path} {on['cycle_parameter'].values[0]:.6g} to "
                       f"{on['cycle_parameter'].values[-1]:.6g}, period "
                       f"{on['cycle_period'].values[0]:.5g} to "
                       f"{on['cycle_period'].values[-1]:.5g} s, "
                       f"{int(on['cycle_stable'].sum())} stable")  # fmt: skip
    _write(found, output, "branches", plot, viz.plot_bifurcation, "diagram")


@click.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("--parameter", "path", required=True, help="The first parameter (a path, as "
              "for continuation).")  # fmt: skip
@click.option("--from", "start", type=types.ANY, required=True, help="Its first value.")
@click.option("--to", "end", type=types.ANY, required=True, help="Its last value.")
@click.option("--second", required=True, help="The second parameter (a path).")
@click.option("--second-from", "second_start", type=types.ANY, required=True,
              help="Its value where the curves start.")  # fmt: skip
@click.option("--second-to", "second_end", type=types.ANY, required=True,
              help="Its last value.")  # fmt: skip
@_weather_options
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Picture of the curves (.png).")
def curves(case_file: str, path: str, start: float, end: float, second: str,
           second_start: float, second_end: float, current, wind, waves, headings: int,
           output: str | None, plot: str | None) -> None:  # fmt: skip
    """Curves of folds and Hopf points of the ships of CASE_FILE in two parameters: those a
    continuation in the first finds with the second at --second-from, followed as both
    change."""
    case = load(case_file)
    _check(case, output, plot)
    found = seacable.curves(case, path, start, end, second, second_start, second_end,
                            _weather(case, current, wind, waves), headings=headings)  # fmt: skip
    click.echo(f"{found.sizes['curve']} curves")
    for k, kind in enumerate(found["kind"].values):
        on = found.where(found["curve"] == k, drop=True)
        a, b = on["first"].values, on["second"].values
        click.echo(f"{k + 1}. {kind}: {on.sizes['curve_point']} points, {path} {a[0]:.8g} to "
                   f"{a[-1]:.8g} as {second} goes {b[0]:.6g} to {b[-1]:.6g}")  # fmt: skip
    _write(found, output, "curves", plot, viz.plot_curves)


@click.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option(
    "--parameter", "path", default=None, help="A parameter set first (as continuation's)."
)
@click.option("--value", type=types.ANY, default=None, help="Its value.")
@click.option("--settle", type=types.DURATION, default=None,
              help="The longest motion [s] before shooting, which ends once its amplitude "
              "settles (default: 40 e-foldings of the growing oscillation, at least 60 of "
              "its periods).")  # fmt: skip
@_weather_options
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False),
              help="Picture of the ships' tracks and tensions over a period (.png).")  # fmt: skip
def orbit(case_file: str, path: str | None, value: float | None, settle: float | None, current,
          wind, waves, headings: int, output: str | None, plot: str | None) -> None:  # fmt: skip
    """The limit cycle (fishtailing) the ships of CASE_FILE settle on from their oscillatory
    unstable equilibrium: period, amplitudes, hawser tensions, the hulls' least clearance and
    its Floquet multipliers (shooting)."""
    case = load(case_file)
    _check(case, output, plot)
    found = seacable.periodic_orbit(case, _weather(case, current, wind, waves), path, value, settle,
                                    headings=headings)  # fmt: skip
    state = "stable" if bool(found["stable"]) else "unstable"
    moduli = np.abs(found["multiplier_real"].values + 1j * found["multiplier_imag"].values)
    largest = ", ".join(f"{m:.4g}" for m in moduli[:3])
    click.echo(f"limit cycle: period {float(found['period']):.6g} s, {state} (largest "
               f"multipliers {largest}); shooting converged, residual "
               f"{float(found['residual']):.2g}")  # fmt: skip
    for j, b in enumerate(found["body"].values):
        click.echo(f"  {b}: x {found['amplitude_x'].values[j]:.4g} m, y "
                   f"{found['amplitude_y'].values[j]:.4g} m, heading "
                   f"{found['amplitude_heading'].values[j]:.4g} deg (peak to peak)")  # fmt: skip
    for k, tie in enumerate(found["tie"].values):
        click.echo(f"  {tie}: tension {found['tension_min'].values[k] / 1e3:.4g} to "
                   f"{found['tension_max'].values[k] / 1e3:.4g} kN")  # fmt: skip
    if np.isfinite(float(found["clearance"])):
        click.echo(f"  least clearance between the hulls: {float(found['clearance']):.4g} m")
    _write(found, output, "limit cycle", plot, viz.plot_orbit)


def _title() -> str:
    """The title of the command's NetCDF output: "seacable equilibria", ..."""
    return f"seacable {click.get_current_context().info_name}"


def _check(case: SystemCase, output: str | None, plot: str | None = None,
           tension=()) -> None:  # fmt: skip
    """The command's outputs checked before it computes anything (``files.check_output``),
    and the ties its ``--tension-limit`` options name."""
    ties = [line.name for line in case.lines]
    for name, _ in tension:
        if name not in ties:
            raise CaseError(f"--tension-limit {name}: the case has no line of that name; its "
                            f"lines: {', '.join(ties)}")  # fmt: skip
    inputs = loader.files_read(case)
    if output:
        files.check_output(output, "netcdf", inputs, title=_title())
    if plot:
        files.check_output(plot, "picture", inputs, option="--plot")


def _write(found: xr.Dataset, output: str | None, what: str, plot: str | None = None,
           draw=None, picture: str = "picture") -> None:  # fmt: skip
    """An analysis's Dataset to ``output`` (NetCDF) and its picture to ``plot`` by ``draw``,
    each said in one line."""
    if output:
        found.attrs["title"] = _title()
        with files.replacing(output) as aside:
            found.to_netcdf(aside)
        click.echo(f"{what} written: {output}")
    if plot and draw is not None:
        click.echo(f"{picture} written: {draw(found, plot)}")


def _angles(text: str, option: str, low: float | None = None) -> np.ndarray:
    """Numbers (degrees, ratios) from 'first:stop:step' (stop excluded) or a comma-separated
    list, each at least ``low`` when given."""
    if ":" not in text:
        return np.array(types.numbers(text, option, low))
    try:
        values = np.array(range_values(text, option))
    except ValueError as exc:
        raise CaseError(str(exc)) from None
    if low is not None and values.min() < low:
        raise CaseError(f"{option} '{text}': every value at least {low:g}")
    return values


@click.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("--current-speed", type=types.Number(low=0.0, low_open=True, example="1.2"),
              default=None,
              help="The grid's current speed [m/s] (or --states).")  # fmt: skip
@click.option("--current-towards", default="0:360:10", show_default=True,
              help="Current directions [deg]: first:stop:step or a list.")  # fmt: skip
@click.option("--wind-towards", default="0:360:10", show_default=True,
              help="Wind directions [deg]: first:stop:step or a list.")  # fmt: skip
@click.option("--ratios", default="10,20,30", show_default=True,
              help="Wind speed over current speed, a list.")  # fmt: skip
@click.option("--states", type=click.Path(dir_okay=False), default=None,
              help="A CSV table of weather states instead of the grid: a header of "
                   "current_speed, current_towards_deg, wind_speed, wind_towards_deg and "
                   "optionally wave_height, wave_towards_deg, probability.")  # fmt: skip
@click.option("--clearance", type=types.NONNEGATIVE, default=0.0,
              help="Least clearance of the hulls [m].")  # fmt: skip
@click.option("--tension-limit", "tension", multiple=True, nargs=2, type=(str, types.POSITIVE),
              help="A tie's largest tension: NAME NEWTONS (repeatable).")  # fmt: skip
@click.option("--simulate", type=types.DURATION, default=None,
              help="Also move each state this many seconds from its equilibrium.")  # fmt: skip
@click.option("--simulate-from", "start", type=click.Choice(["equilibrium", "nominal"]),
              default="equilibrium", show_default=True,
              help="Start the motion from the equilibrium pushed by 1 m and 1 deg, or from the "
                   "ships at rest as at their nominal places around the FPSO's equilibrium "
                   "pose.")  # fmt: skip
@click.option("--control", type=click.Choice(["off", "on", "both"]), default=None,
              help="The ships' compensator off, on, or both side by side (default: as the "
                   "case says).")  # fmt: skip
@click.option(
    "--dask",
    "scheduler",
    default="local",
    show_default=True,
    help="'local' (a local cluster), 'none' (this process) or a scheduler address.",
)
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Picture of the map (.png).")
def operability(case_file: str, current_speed: float | None, current_towards: str,
                wind_towards: str, ratios: str, states: str | None, clearance: float, tension,
                simulate: float | None, start: str, control: str | None, scheduler: str,
                output: str | None, plot: str | None) -> None:  # fmt: skip
    """An operability map of the ships of CASE_FILE: for every current and wind direction and
    wind-to-current speed ratio (or every state of a table, with waves), stable / limit
    exceeded / cycling / collision risk."""
    probability = None
    if states is not None:
        weathers, probability = stability_map.table(states)
        shape = None
    elif current_speed is None:
        raise CaseError("--current-speed: missing; give the grid's current speed [m/s], or a "
                        "table of states with --states FILE")  # fmt: skip
    else:
        weathers, shape = stability_map.grid(
            current_speed, _angles(current_towards, "--current-towards"),
            _angles(wind_towards, "--wind-towards"), _angles(ratios, "--ratios", 0.0))  # fmt: skip
    limits = stability_map.Limits(clearance, tuple((name, value) for name, value in tension))
    where = None if scheduler == "none" else scheduler
    cluster.check(where)
    case = load(case_file)
    _check(case, output, plot, tension)
    found = stability_map.operability(case, weathers, shape, limits, simulate, where,
                                      control=control, probability=probability,
                                      start=start)  # fmt: skip
    for label, counts, share in stability_map.shares(found):
        by = "of the time" if probability is not None else "of the states"
        click.echo(f"{label + ': ' if label else ''}{len(weathers)} weather states: "
                   + ", ".join(f"{n} {c} ({100 * share[n]:.1f} % {by})"
                               for n, c in counts.items()))  # fmt: skip
    _write(found, output, "map", plot, viz.plot_operability)


@click.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@_weather_options
@click.option("--duration", type=types.DURATION, default=None, help="[s] (default: the case's).")
@click.option("--clearance", type=types.NONNEGATIVE, default=0.0,
              help="Least clearance of the hulls [m].")  # fmt: skip
@click.option("--tension-limit", "tension", multiple=True, nargs=2, type=(str, types.POSITIVE),
              help="A tie's largest tension: NAME NEWTONS (repeatable).")  # fmt: skip
@click.option("--start", type=click.Choice(["nominal", "case"]), default="nominal",
              show_default=True,
              help="The ships at rest at their nominal places around the FPSO weathervaned "
              "in this weather (as an operability map starts them), or as the case places "
              "them.")  # fmt: skip
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Picture of both runs (.png).")
def compare(case_file: str, current, wind, waves, headings: int, duration: float | None,
            clearance: float, tension, start: str, output: str | None,
            plot: str | None) -> None:  # fmt: skip
    """The ships of CASE_FILE in one weather without and with their compensator, side by side:
    is it safe, with and without control? (distance, tension, thrust, clearance)."""
    case = load(case_file)
    _check(case, output, plot, tension)
    limits = stability_map.Limits(clearance, tuple((name, value) for name, value in tension))
    found = seacable.compare(case, _weather(case, current, wind, waves), duration, limits=limits,
                             start=start, headings=headings)  # fmt: skip
    for control in found["control"].values:
        run = found.sel(control=control)
        peaks = ", ".join(f"{t} {run['peak_tension'].sel(tie=t).item() / 1e3:.4g} kN"
                          for t in found["tie"].values)  # fmt: skip
        why = run["message"].item()
        click.echo(f"{control}: {run['verdict'].item()}" + (f" ({why})" if why else "")
                   + f"; least clearance {run['least_clearance'].item():.4g} m; peak tension "
                   f"{peaks}; compensator up to {run['peak_surge_force'].item() / 1e3:.4g} kN "
                   f"and {run['peak_yaw_moment'].item() / 1e6:.4g} MN m, cut by its limits "
                   f"{100 * run['saturated'].item():.0f} % of the time")  # fmt: skip
    _write(found, output, "comparison", plot, viz.plot_compare)


COMMANDS = (equilibria, continuation, curves, orbit, operability, compare)
