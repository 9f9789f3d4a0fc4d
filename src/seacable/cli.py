"""The ``seacable`` command line: parse, call the public API, write. Nothing else."""

import logging
import math
import sys
import tempfile
from dataclasses import replace
from pathlib import Path
from typing import NoReturn

import click
import h5netcdf
import numpy as np
import xarray as xr

import seacable
from seacable import analysis, bem, meshes, simulation, viz
from seacable.case import legacy, loader
from seacable.case.system import SystemCase
from seacable.results import restore_case
from seacable.stability import operability as stability_map
from seacable.stability.api import weather_of

# exit codes (README, "Command line"): 0 done; 1 a bug in seacable; 2 the input (case file,
# output path, no equilibrium, a file that cannot be read or written); 3 the run diverged;
# 128 + the signal when interrupted (130 Ctrl-C, 143 SIGTERM)
EXIT_BUG, EXIT_INPUT, EXIT_DIVERGED = 1, 2, 3
REPORT = "https://github.com/seacable/seacable/issues"


def _fail(message: str, code: int = 1) -> NoReturn:
    click.echo(f"error: {message}", err=True)
    sys.exit(code)


class _Boundary(click.Group):
    """The command line's one error boundary: every failure a user can meet is one line on
    stderr and an exit code; anything else is a bug, said so in one line (``--debug``: the
    traceback)."""

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except (click.exceptions.Exit, click.ClickException, SystemExit):
            raise
        except seacable.SimulationInterrupted as exc:
            _fail(str(exc), 128 + exc.signal)
        except KeyboardInterrupt:
            _fail("interrupted", 130)
        except seacable.SimulationDiverged as exc:
            _fail(str(exc), EXIT_DIVERGED)
        except seacable.SeacableError as exc:
            _fail(str(exc), EXIT_INPUT)
        except OSError as exc:  # a file that cannot be read or written
            where = f" '{exc.filename}'" if exc.filename else ""
            _fail(f"cannot use the file{where}: {exc.strerror or exc}", EXIT_INPUT)
        except Exception as exc:
            if ctx.params.get("debug"):
                raise
            _fail(
                f"internal error, a bug in seacable ({type(exc).__name__}: "
                f"{str(exc)[:200]}); please report it at {REPORT} with the case file, and "
                "run again with --debug for the traceback",
                EXIT_BUG,
            )


@click.group(cls=_Boundary)
@click.version_option(seacable.__version__, prog_name="seacable")
@click.option("-v", "--verbose", is_flag=True, help="Show seacable's debug messages.")
@click.option("--debug", is_flag=True, help="Show the traceback of an internal error.")
def main(verbose: bool, debug: bool) -> None:
    """Simulate marine cables and the bodies they connect."""
    _configure_logging(verbose)


class _StderrHandler(logging.StreamHandler):
    """A stream handler writing to whatever ``sys.stderr`` is when a record comes (a program
    or a test may swap it after the command line has configured logging)."""

    seacable_cli = True  # marks the handlers the command line installs (replaced on each call)

    @property
    def stream(self):
        return sys.stderr

    @stream.setter
    def stream(self, value):
        pass


def _configure_logging(verbose: bool) -> None:
    """seacable's own log on stderr, at INFO (DEBUG with -v); other packages' loggers (numba's
    compiler logs hundreds of thousands of DEBUG lines) are left to Python's default, which
    shows their warnings and errors only. seacable's records still propagate (to the handlers
    a host program or pytest installs on the root logger), but the root has no handler here."""
    package = logging.getLogger("seacable")
    for handler in [h for h in package.handlers if getattr(h, "seacable_cli", False)]:
        package.removeHandler(handler)
    handler = _StderrHandler()
    handler.setFormatter(logging.Formatter("%(levelname)s: %(message)s"))
    package.addHandler(handler)
    package.setLevel(logging.DEBUG if verbose else logging.INFO)


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--progress/--no-progress", default=True, help="Progress bar on long runs.")
def run(case_file: str, output: str | None, progress: bool) -> None:
    """Run CASE_FILE and write its results (default: CASE_FILE with .nc)."""
    output = output or str(Path(case_file).with_suffix(".nc"))
    try:
        case = seacable.load_case(case_file)
        results = seacable.simulate(case, output=output, progress=progress)
    except seacable.SimulationDiverged as exc:
        _fail(f"{exc}\npartial results (status 'diverged'): {output}", EXIT_DIVERGED)
    except seacable.SimulationInterrupted as exc:  # exit 130 (Ctrl-C) or 143 (SIGTERM)
        _fail(f"{exc}\npartial results (status 'interrupted'): {output}", 128 + exc.signal)
    click.echo(f"{results.status}: {results.message}; results in {output}")


@main.command()
@click.argument("results_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="NetCDF file to write.")  # fmt: skip
@click.option("--progress/--no-progress", default=True, help="Progress bar on long runs.")
def repeat(results_file: str, output: str, progress: bool) -> None:
    """Run again the case RESULTS_FILE was written by: its case text and the files it read,
    kept in the file's attributes, written to a temporary folder and run from there (a file
    the case named outside its folder, by an absolute path or '..', is put in that folder and
    the case text pointed at it)."""
    with h5netcdf.File(results_file, "r") as f:
        attrs = dict(f.attrs)
    with tempfile.TemporaryDirectory() as folder:
        try:
            case_file = restore_case(attrs, folder)
        except ValueError as exc:
            _fail(f"{results_file}: {exc}", EXIT_INPUT)
        results = seacable.simulate(seacable.load_case(case_file), output=output,
                                    progress=progress)  # fmt: skip
    click.echo(f"{results.status}: {results.message}; results in {output}")


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Case file to write.")
def upgrade(case_file: str, output: str | None) -> None:
    """Write CASE_FILE (the single-cable form, cables: with top and bottom) in the system form
    of bodies and lines (to stdout, or OUTPUT next to it: table files keep their names)."""
    text = legacy.upgrade_text(loader.load_single_cable(case_file))
    if output is None:
        click.echo(text, nl=False)
        return
    Path(output).write_text(text)
    click.echo(f"system form in {output}")


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
def validate(case_file: str) -> None:
    """Check CASE_FILE as a run does before its first step (the system built, its tables read,
    its geometry checked, the statics it starts from solved, the step checked), without
    running it."""
    case = seacable.load_case(case_file)
    if isinstance(case, SystemCase):
        _, warning = simulation.prepare(case)  # all a run checks before its first step
        kinds = ", ".join(f"{b.name} ({b.type})" for b in case.bodies)
        models = ", ".join(f"{line.name} ({line.model})" for line in case.lines)
        if warning:
            click.echo(f"warning: {warning}", err=True)
        click.echo(
            f"ok: case '{case.name}': bodies {kinds}; lines {models}; "
            f"{case.simulation.duration:g} s with {case.simulation.integrator}"
        )
        return
    cable = case.cables[0]
    what = f"{len(case.cables)} cables on body '{case.bodies[0].name}'" if case.bodies else (
        f"cable '{cable.name}' ({cable.model}) of {cable.links} links, top {cable.top.type}, "
        f"bottom {cable.bottom.type}"
    )  # fmt: skip
    click.echo(
        f"ok: case '{case.name}': {what}, {case.simulation.duration:g} s with "
        f"{case.simulation.integrator}"
    )


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="NetCDF file to write (default: CASE_FILE with .statics.nc).")  # fmt: skip
def statics(case_file: str, output: str | None) -> None:
    """Static equilibrium of the system of CASE_FILE: every body's pose and every line's end
    tensions, printed and written."""
    output = output or str(Path(case_file).with_suffix(".statics.nc"))
    results = seacable.statics(seacable.load_case(case_file), output=output)
    tree = results.dataset
    for name, node in tree["bodies"].children.items():
        ds = node.to_dataset().isel(time=0)
        where = ", ".join(f"{ds[f'position_{c}'].item():.4g}" for c in "xyz")
        angles = ""
        if "roll" in ds:
            angles = "; roll, pitch, yaw " + ", ".join(
                f"{ds[a].item():.4g}" for a in ("roll", "pitch", "yaw")
            ) + " deg"  # fmt: skip
        click.echo(f"body {name}: at ({where}) m{angles}")
    for name, node in tree["lines"].children.items():
        ds = node.to_dataset().isel(time=0)
        if "from_force_x" in ds:
            ends = [
                math.sqrt(sum(ds[f"{end}_force_{c}"].item() ** 2 for c in "xyz"))
                for end in ("from", "to")
            ]
            click.echo(f"line {name}: end tensions {ends[0] / 1e3:.4g} kN (from), "
                       f"{ends[1] / 1e3:.4g} kN (to)")  # fmt: skip
        else:
            click.echo(f"line {name}: tension {ds['tension'].item() / 1e3:.4g} kN")
    click.echo(f"statics written: {output}")


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("--count", type=int, default=12, show_default=True, help="Slowest modes shown.")
def modes(case_file: str, count: int) -> None:
    """Natural modes of the system of CASE_FILE about its static equilibrium: period, damping
    ratio and the coordinate each mode moves most."""
    found = analysis.system_modes(seacable.load_case(case_file), count=count)
    click.echo("mode  period [s]  damping ratio  moves most")
    for k in range(found.sizes["mode"]):
        click.echo(
            f"{k + 1:4d}  {found['period'].values[k]:10.4g}  "
            f"{found['damping_ratio'].values[k]:13.3g}  {found['dominant'].values[k]}"
        )


def _weather(case, current, wind) -> seacable.Weather:
    """The case's weather with the options' current and wind (speed, towards_deg) replacing
    its own."""
    weather = weather_of(case)
    if current is not None:
        weather = replace(weather, current_speed=current[0], current_towards_deg=current[1])
    if wind is not None:
        weather = replace(weather, wind_speed=wind[0], wind_towards_deg=wind[1])
    return weather


WEATHER_OPTIONS = [
    click.option("--current", nargs=2, type=float, default=None,
                 help="Uniform current: speed [m/s] and the direction it goes towards [deg] "
                      "(default: the case's)."),
    click.option("--wind", nargs=2, type=float, default=None,
                 help="Constant wind: speed [m/s] and the direction it blows towards [deg] "
                      "(default: the case's)."),
    click.option("--headings", type=int, default=12, show_default=True,
                 help="Starting headings per body in the search for equilibria."),
]  # fmt: skip


def _weather_options(command):
    for option in reversed(WEATHER_OPTIONS):
        command = option(command)
    return command


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@_weather_options
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
def equilibria(case_file: str, current, wind, headings: int, output: str | None) -> None:
    """Every equilibrium of the ships of CASE_FILE in the horizontal plane (surge, sway, yaw)
    for a current and a wind, and its stability from the linearised system's eigenvalues."""
    case = seacable.load_case(case_file)
    weather = _weather(case, current, wind)
    found = seacable.equilibria(case, weather, headings=headings)
    click.echo(f"current {weather.current_speed:g} m/s towards {weather.current_towards_deg:g} "
               f"deg, wind {weather.wind_speed:g} m/s towards {weather.wind_towards_deg:g} deg: "
               f"{found.sizes['equilibrium']} equilibria")  # fmt: skip
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


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option(
    "--parameter",
    "path",
    required=True,
    help="What varies: current.speed, current.towards_deg, wind.speed, "
    "wind.towards_deg, lines.<tie>.unstretched_length, lines.<tie>.stiffness, "
    "bodies.<body>.points.<point>.x, bodies.<body>.external forces.<k>.force_x",
)
@click.option("--from", "start", type=float, required=True, help="The parameter's first value.")
@click.option("--to", "end", type=float, required=True, help="Its last value.")
@_weather_options
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Bifurcation diagram (.png).")
@click.option("--cycles", type=int, default=0, show_default=True,
              help="Periodic orbits to follow from each Hopf point, and its kind.")  # fmt: skip
def continuation(case_file: str, path: str, start: float, end: float, current, wind,
                 headings: int, output: str | None, plot: str | None,
                 cycles: int) -> None:  # fmt: skip
    """Branches of equilibria of the ships of CASE_FILE as a parameter varies, with their
    folds, branch points and Hopf points (pseudo-arclength continuation); with --cycles, the
    branches of limit cycles born at the Hopf points and whether each is super- or
    subcritical, by simulation."""
    case = seacable.load_case(case_file)
    found = seacable.continuation(case, path, start, end, _weather(case, current, wind),
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
            extra += f", {s['special_criticality'].item()} by simulation"
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


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("--parameter", "path", required=True, help="The first parameter (a path, as "
              "for continuation).")  # fmt: skip
@click.option("--from", "start", type=float, required=True, help="Its first value.")
@click.option("--to", "end", type=float, required=True, help="Its last value.")
@click.option("--second", required=True, help="The second parameter (a path).")
@click.option("--second-from", "second_start", type=float, required=True,
              help="Its value where the curves start.")  # fmt: skip
@click.option("--second-to", "second_end", type=float, required=True, help="Its last value.")
@_weather_options
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Picture of the curves (.png).")
def curves(case_file: str, path: str, start: float, end: float, second: str,
           second_start: float, second_end: float, current, wind, headings: int,
           output: str | None, plot: str | None) -> None:  # fmt: skip
    """Curves of folds and Hopf points of the ships of CASE_FILE in two parameters: those a
    continuation in the first finds with the second at --second-from, followed as both
    change."""
    case = seacable.load_case(case_file)
    found = seacable.curves(case, path, start, end, second, second_start, second_end,
                            _weather(case, current, wind), headings=headings)  # fmt: skip
    click.echo(f"{found.sizes['curve']} curves")
    for k, kind in enumerate(found["kind"].values):
        on = found.where(found["curve"] == k, drop=True)
        a, b = on["first"].values, on["second"].values
        click.echo(f"{k + 1}. {kind}: {on.sizes['curve_point']} points, {path} {a[0]:.8g} to "
                   f"{a[-1]:.8g} as {second} goes {b[0]:.6g} to {b[-1]:.6g}")  # fmt: skip
    _write(found, output, "curves", plot, viz.plot_curves)


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option(
    "--parameter", "path", default=None, help="A parameter set first (as continuation's)."
)
@click.option("--value", type=float, default=None, help="Its value.")
@click.option("--settle", type=float, default=None,
              help="Seconds of motion before shooting (default 30 periods).")  # fmt: skip
@_weather_options
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False),
              help="Picture of the ships' tracks and tensions over a period (.png).")  # fmt: skip
def orbit(case_file: str, path: str | None, value: float | None, settle: float | None, current,
          wind, headings: int, output: str | None, plot: str | None) -> None:  # fmt: skip
    """The limit cycle (fishtailing) the ships of CASE_FILE settle on from their oscillatory
    unstable equilibrium: period, amplitudes, hawser tensions, the hulls' least clearance and
    its Floquet multipliers (shooting)."""
    case = seacable.load_case(case_file)
    found = seacable.periodic_orbit(case, _weather(case, current, wind), path, value, settle,
                                    headings=headings)  # fmt: skip
    state = "stable" if bool(found["stable"]) else "unstable"
    moduli = np.abs(found["multiplier_real"].values + 1j * found["multiplier_imag"].values)
    largest = ", ".join(f"{m:.4g}" for m in moduli[:3])
    shooting = "converged" if bool(found["converged"]) else "did NOT converge"
    click.echo(f"limit cycle: period {float(found['period']):.6g} s, {state} (largest "
               f"multipliers {largest}); shooting {shooting}, residual "
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


def _write(found: xr.Dataset, output: str | None, what: str, plot: str | None = None,
           draw=None, picture: str = "picture") -> None:  # fmt: skip
    """An analysis's Dataset to ``output`` (NetCDF) and its picture to ``plot`` by ``draw``,
    each said in one line."""
    if output:
        found.to_netcdf(output)
        click.echo(f"{what} written: {output}")
    if plot and draw is not None:
        click.echo(f"{picture} written: {draw(found, plot)}")


def _angles(text: str, option: str) -> np.ndarray:
    """Degrees from 'first:stop:step' (stop excluded) or a comma-separated list."""
    try:
        if ":" in text:
            first, stop, step = (float(v) for v in text.split(":"))
            return np.arange(first, stop - 1e-9, step)
        return np.array([float(v) for v in text.split(",")])
    except ValueError:
        _fail(f"{option} '{text}': give first:stop:step (e.g. 0:360:10) or values separated "
              "by commas", EXIT_INPUT)  # fmt: skip


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("--current-speed", type=float, required=True, help="[m/s]")
@click.option("--current-towards", default="0:360:10", show_default=True,
              help="Current directions [deg]: first:stop:step or a list.")  # fmt: skip
@click.option("--wind-towards", default="0:360:10", show_default=True,
              help="Wind directions [deg]: first:stop:step or a list.")  # fmt: skip
@click.option("--ratios", default="10,20,30", show_default=True,
              help="Wind speed over current speed, a list.")  # fmt: skip
@click.option("--clearance", type=float, default=0.0, help="Least clearance of the hulls [m].")
@click.option("--tension-limit", "tension", multiple=True, nargs=2, type=(str, float),
              help="A tie's largest tension: NAME NEWTONS (repeatable).")  # fmt: skip
@click.option("--simulate", type=float, default=None,
              help="Also move each state this many seconds from its equilibrium.")  # fmt: skip
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
def operability(case_file: str, current_speed: float, current_towards: str, wind_towards: str,
                ratios: str, clearance: float, tension, simulate: float | None,
                control: str | None, scheduler: str, output: str | None,
                plot: str | None) -> None:  # fmt: skip
    """An operability map of the ships of CASE_FILE: for every current and wind direction and
    wind-to-current speed ratio, stable / limit exceeded / cycling / collision risk."""
    states, shape = stability_map.grid(current_speed, _angles(current_towards, "--current-towards"),
                         _angles(wind_towards, "--wind-towards"),
                         _angles(ratios, "--ratios"))  # fmt: skip
    limits = stability_map.Limits(clearance, tuple((name, value) for name, value in tension))
    where = None if scheduler == "none" else scheduler
    case = seacable.load_case(case_file)
    found = stability_map.operability(case, states, shape, limits, simulate, where,
                                      control=control)  # fmt: skip
    for part, label in _controls(found):
        names, counts = np.unique(part["status"].values, return_counts=True)
        click.echo(f"{label}{len(states)} weather states: "
                   + ", ".join(f"{c} {n}" for n, c in zip(names, counts, strict=True)))  # fmt: skip
    _write(found, output, "map", plot, viz.plot_operability)


def _controls(found: xr.Dataset) -> list[tuple[xr.Dataset, str]]:
    """A map's parts per control setting, each with its label ("" without the dimension)."""
    if "control" not in found.dims:
        return [(found, "")]
    return [(found.sel(control=c), f"{c}: ") for c in found["control"].values]


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@_weather_options
@click.option("--duration", type=float, default=None, help="[s] (default: the case's).")
@click.option("--clearance", type=float, default=0.0, help="Least clearance of the hulls [m].")
@click.option("--tension-limit", "tension", multiple=True, nargs=2, type=(str, float),
              help="A tie's largest tension: NAME NEWTONS (repeatable).")  # fmt: skip
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Picture of both runs (.png).")
def compare(case_file: str, current, wind, headings: int, duration: float | None,
            clearance: float, tension, output: str | None, plot: str | None) -> None:  # fmt: skip
    """The ships of CASE_FILE in one weather without and with their compensator, side by side:
    is it safe, with and without control? (distance, tension, thrust, clearance)."""
    case = seacable.load_case(case_file)
    limits = stability_map.Limits(clearance, tuple((name, value) for name, value in tension))
    found = seacable.compare(case, _weather(case, current, wind), duration, limits=limits)
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


@main.command()
@click.argument("mesh_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="NetCDF database to write (default: MESH_FILE with .nc).")  # fmt: skip
@click.option("--omega", nargs=3, type=float, default=(0.1, 3.0, 30), show_default=True,
              help="Angular frequencies [rad/s]: first, last, count.")  # fmt: skip
@click.option("--directions", type=str, default="0,45,90,135,180,225,270,315",
              show_default=True, help="Wave directions [deg], comma-separated.")  # fmt: skip
@click.option("--rotation-center", nargs=3, type=float, default=(0.0, 0.0, 0.0),
              show_default=True, help="The reference point [m] of the six motions.")  # fmt: skip
@click.option("--depth", type=float, default=math.inf, help="Water depth [m] (default deep).")
@click.option("--rho", type=float, default=1025.0, show_default=True, help="[kg/m^3]")
def hydrodb(mesh_file: str, output: str | None, omega, directions: str, rotation_center,
            depth: float, rho: float) -> None:  # fmt: skip
    """Compute the hydrodynamic database of the hull MESH_FILE (placed as floating, z up,
    the waterline at z = 0) with Capytaine: pip install 'seacable[bem]'."""
    first, last, count = omega
    if not (0.0 < first < last and count >= 2):
        _fail(f"--omega {first:g} {last:g} {count:g}: give 0 < first < last and a count of at "
              "least 2, e.g. --omega 0.1 3.0 30", EXIT_INPUT)  # fmt: skip
    try:
        angles = [float(a) for a in directions.split(",")]
    except ValueError:
        _fail(f"--directions '{directions}': give degrees separated by commas, e.g. 0,90,180",
              EXIT_INPUT)  # fmt: skip
    output = output or str(Path(mesh_file).with_suffix(".nc"))
    try:
        db = bem.compute_file(mesh_file, output, np.linspace(first, last, int(count)),
                              directions_deg=angles, rotation_center=rotation_center,
                              depth=depth, rho=rho)  # fmt: skip
    except ImportError as exc:
        _fail(str(exc), EXIT_INPUT)
    except meshes.MeshError as exc:
        _fail(str(exc), EXIT_INPUT)
    click.echo(f"database of {len(db.omega)} frequencies and {len(db.directions)} directions "
               f"written: {output}")  # fmt: skip


def _tree(results: seacable.Results, results_file: str) -> xr.DataTree:
    """The results' tree of groups (a system's), or a clear exit for a file without groups."""
    if not isinstance(results.dataset, xr.DataTree):
        _fail(
            f"{results_file}: results of the single-cable core (retired after commit 4911bc8); "
            "run the case as a system (seacable upgrade case.yaml -o system.yaml) and draw those",
            EXIT_INPUT,
        )
    return results.dataset


@main.command()
@click.argument("results_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Picture (default .png).")
@click.option("--every", type=float, default=None, help="Seconds between cable snapshots.")
def plot(results_file: str, output: str | None, every: float | None) -> None:
    """Draw cable snapshots and time series from RESULTS_FILE."""
    output = output or str(Path(results_file).with_suffix(".png"))
    results = seacable.Results.open(results_file)
    viz.plot_results(_tree(results, results_file), output, every=every)
    click.echo(f"picture written: {output}")


@main.command()
@click.argument("results_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="Animation file (.gif).")  # fmt: skip
@click.option("--fps", type=int, default=20, help="Frames per second of video.")
@click.option("--speed", type=float, default=1.0, help="Simulated seconds per second of video.")
@click.option("--every", type=float, default=None,
              help="Simulated seconds between frames (default: speed / fps).")  # fmt: skip
@click.option("--max-frames", type=int, default=600, show_default=True,
              help="At most this many frames, spread evenly over the run.")  # fmt: skip
@click.option("--progress/--no-progress", default=True, help="Progress bar on stderr.")
def animate(
    results_file: str,
    output: str,
    fps: int,
    speed: float,
    every: float | None,
    max_frames: int,
    progress: bool,
) -> None:
    """Animate the cable of RESULTS_FILE, drawing and writing one frame at a time."""
    results = seacable.Results.open(results_file, lazy=True)
    try:
        viz.animate_results(
            _tree(results, results_file),
            output,
            fps=fps,
            speed=speed,
            every=every,
            max_frames=max_frames,
            progress=progress,
        )
    except ValueError as exc:
        _fail(str(exc), EXIT_INPUT)
    finally:
        results.dataset.close()
    click.echo(f"animation written: {output}")


if __name__ == "__main__":
    main()
