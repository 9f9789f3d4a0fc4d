"""The ``seacable`` command line: parse, call the public API, write. Nothing else."""

import logging
import math
import sys
import tempfile
from pathlib import Path
from typing import NoReturn

import click
import h5netcdf
import numpy as np
import xarray as xr

import seacable
from seacable import (
    ahead,
    analysis,
    bem,
    cli_ships,
    cli_sweep,
    export,
    files,
    meshes,
    report,
    simulation,
    viz,
)
from seacable import cli_types as types
from seacable import stats as stats_module
from seacable.case import legacy, loader, moordyn, reference
from seacable.case.system import SystemCase
from seacable.results import TITLE, restore_case
from seacable.system import utilisation

# exit codes (README, "Command line"): 0 done; 1 a bug in seacable; 2 the input (case file,
# output path, no equilibrium, a file that cannot be read or written); 3 the run diverged;
# 128 + the signal when interrupted (130 Ctrl-C, 143 SIGTERM)
EXIT_BUG, EXIT_INPUT, EXIT_DIVERGED = 1, 2, 3
REPORT = "https://github.com/seacable/seacable/issues"


def _fail(message: str, code: int = 1) -> NoReturn:
    click.echo(f"error: {message}", err=True)
    sys.exit(code)


def _linked(message: str) -> str:
    """A case's error with the address of the key it names in the reference (once)."""
    case = cli_ships.LOADED.get("case")
    link = reference.link_for(message, case) if case is not None else None
    return (
        message if link is None or "(reference: " in message else f"{message} (reference: {link})"
    )


class _Boundary(click.Group):
    """The command line's one error boundary: every failure a user can meet is one line on
    stderr and an exit code; anything else is a bug, said so in one line (``--debug``: the
    traceback)."""

    def invoke(self, ctx: click.Context):
        cli_ships.LOADED.clear()  # a case of an earlier call (in one process) is not this one's
        try:
            return super().invoke(ctx)
        except click.UsageError as exc:  # an option's or argument's value: one line
            command = " ".join(filter(None, ["seacable", ctx.invoked_subcommand]))
            _fail(f"{exc.format_message()} (see {command} --help)", EXIT_INPUT)
        except (click.exceptions.Exit, click.ClickException, SystemExit):
            raise
        except seacable.SimulationInterrupted as exc:
            _fail(str(exc), 128 + exc.signal)
        except KeyboardInterrupt:
            _fail("interrupted", 130)
        except seacable.SimulationDiverged as exc:
            _fail(str(exc), EXIT_DIVERGED)
        except seacable.CaseError as exc:
            _fail(_linked(str(exc)), EXIT_INPUT)
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


_SET = click.option(
    "--set", "settings", multiple=True, metavar="PATH=VALUE",
    help="Change one key of the case for this command, as the file nests it "
    "(simulation.duration=10, bodies.buoy.mass=2e5, environment.waves[0].significant_height=4); "
    "repeatable.",
)  # fmt: skip


_case = cli_ships.load  # the case of CASE_FILE with the command line's --set changes


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="NetCDF file to write.")
@click.option("--progress/--no-progress", default=True, help="Progress bar on long runs.")
@click.option("--yes", is_flag=True, help="Run a case estimated to take more than about an "
              "hour (simulation.allow_long_run: true).")  # fmt: skip
@_SET
def run(case_file: str, output: str | None, progress: bool, yes: bool,
        settings: tuple[str, ...]) -> None:  # fmt: skip
    """Run CASE_FILE and write its results (default: CASE_FILE with .nc)."""
    output = output or str(Path(case_file).with_suffix(".nc"))
    settings = (*settings, "simulation.allow_long_run=true") if yes else settings
    try:
        case = _case(case_file, settings)
        results = seacable.simulate(case, output=output, progress=progress)
    except seacable.SimulationDiverged as exc:
        _fail(f"{exc}\npartial results (status 'diverged'): {output}", EXIT_DIVERGED)
    except seacable.SimulationInterrupted as exc:  # exit 130 (Ctrl-C) or 143 (SIGTERM)
        _fail(f"{exc}\npartial results (status 'interrupted'): {output}", 128 + exc.signal)
    _utilisation(results, case)
    _sweep_note(case)
    click.echo(f"{results.status}: {results.message}; results in {output}")


def _sweep_note(case) -> None:
    """A case's ``sweep:`` block is run by ``seacable sweep``, not by ``run``: said, not
    ignored silently."""
    if isinstance(case, SystemCase) and case.sweep is not None:
        click.echo(f"note: its sweep: block is for seacable sweep {case._source_file or 'CASE'}; "
                   "run and validate take the case as written", err=True)  # fmt: skip


def _utilisation(results, case) -> None:
    """Each line section with a breaking strength: its largest tension, and what share."""
    if isinstance(case, SystemCase) and any(t.breaking_strength for t in case.line_types):
        for row in utilisation.report(analysis.line_utilisation(results, case)):
            click.echo(row)


@main.command(name="compile")
@click.argument("case_files", nargs=-1, type=click.Path(dir_okay=False))
@click.option("--all", "every", is_flag=True,
              help="Also every integrator family, the statics and the modes.")  # fmt: skip
def compile_ahead(case_files: tuple[str, ...], every: bool) -> None:
    """Compile ahead of time what CASE_FILES need (none given: small systems of the common
    kinds), so that later runs start at once; cached on disk for every later process."""

    def report(done: int, total: int, label: str, seconds: float | None) -> None:
        if seconds is None:
            click.echo(f"[{done + 1}/{total}] {label} ...", err=True)
        else:
            click.echo(f"[{done}/{total}] {label}: {seconds:.1f} s", err=True)

    took = ahead.compile_ahead(list(case_files), every, report)
    click.echo(f"compiled in {took:.1f} s; later runs load it from the cache")


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
    files.check_output(output, "netcdf", [results_file], title=TITLE)
    files.self_contained(results_file)
    try:
        with h5netcdf.File(results_file, "r") as f:
            attrs = dict(f.attrs)
    except OSError as exc:
        _fail(f"{results_file}: not a readable NetCDF/HDF5 file ({exc}); give a results file "
              "that seacable wrote", EXIT_INPUT)  # fmt: skip
    with tempfile.TemporaryDirectory() as folder:
        try:
            case_file = restore_case(attrs, folder, carried_only=True)
        except ValueError as exc:
            _fail(f"{results_file}: {exc}", EXIT_INPUT)
        results = seacable.simulate(_case(case_file), output=output, progress=progress)
    click.echo(f"{results.status}: {results.message}; results in {output}")


@main.group(name="import")
def import_() -> None:
    """Read another program's input file as a seacable case."""


@import_.command(name="moordyn")
@click.argument("deck", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="Case file to write (YAML).")  # fmt: skip
def import_moordyn(deck: str, output: str) -> None:
    """Write the MoorDyn input file DECK (v1 or v2: line types, points, lines, options) as a
    commented seacable case, checked as any case is; what has no equivalent in seacable is
    refused by its section, row and column. `seacable run DECK` runs a deck as it is."""
    files.check_output(output, "case", [deck])
    case, text = moordyn.convert(deck)
    loader.load_case(case)  # refused here, before anything is written
    files.replace_text(output, text)
    click.echo(f"{len(case['lines'])} lines, {len(case['bodies'])} bodies: case in {output}")


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Case file to write.")
def upgrade(case_file: str, output: str | None) -> None:
    """Write CASE_FILE (the single-cable form, cables: with top and bottom) in the system form
    of bodies and lines (to stdout, or OUTPUT next to it: table files keep their names)."""
    case = loader.load_single_cable(case_file)
    if output is not None:
        files.check_output(output, "case", loader.files_read(case))
    text = legacy.upgrade_text(case)
    if output is None:
        click.echo(text, nl=False)
        return
    files.replace_text(output, text)
    click.echo(f"system form in {output}")


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@_SET
def validate(case_file: str, settings: tuple[str, ...]) -> None:
    """Check CASE_FILE as a run does before its first step (the system built, its tables read,
    its geometry checked, the statics it starts from solved, the step checked), without
    running it."""
    case = _case(case_file, settings)
    if isinstance(case, SystemCase):
        _, warning = simulation.prepare(case)  # all a run checks before its first step
        kinds = ", ".join(f"{b.name} ({b.type})" for b in case.bodies)
        models = ", ".join(f"{line.name} ({line.model})" for line in case.lines) or "none"
        if warning:
            click.echo(f"warning: {warning}", err=True)
        _sweep_note(case)
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
@_SET
def statics(case_file: str, output: str | None, settings: tuple[str, ...]) -> None:
    """Static equilibrium of the system of CASE_FILE: every body's pose and every line's end
    tensions, printed and written."""
    output = output or str(Path(case_file).with_suffix(".statics.nc"))
    case = _case(case_file, settings)
    results = seacable.statics(case, output=output)
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
    _utilisation(results, case)
    click.echo(f"statics written: {output}")


@main.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("--count", type=types.count(1, 10_000), default=12, show_default=True,
              help="Slowest modes shown.")  # fmt: skip
@click.option("--yes", is_flag=True, help="Compute the modes of a system estimated to need "
              "more than 1 GB of memory.")  # fmt: skip
@_SET
def modes(case_file: str, count: int, yes: bool, settings: tuple[str, ...]) -> None:
    """Natural modes of the system of CASE_FILE about its static equilibrium: period, damping
    ratio, the coordinate each mode moves most and how the period is found (linearised; A(w)
    iterated for a vessel with a hydrodynamic database; a radiation memory's pole; free, no
    restoring, for a floating body that nothing holds)."""
    found = analysis.system_modes(_case(case_file, settings), count=count, allow_large=yes)
    click.echo("mode  period [s]  damping ratio  moves most              found by")
    for k in range(found.sizes["mode"]):
        ratio = found["damping_ratio"].values[k]
        click.echo(
            f"{k + 1:4d}  {found['period'].values[k]:10.4g}  "
            f"{'' if np.isnan(ratio) else f'{ratio:.3g}':>13}  "
            f"{found['dominant'].values[k]:<22}  {found['method'].values[k]}"
        )


for _command in cli_ships.COMMANDS:  # the ships in the horizontal plane (seacable.cli_ships)
    main.add_command(_command)
for _command in cli_sweep.COMMANDS:  # load cases (seacable.cli_sweep)
    main.add_command(_command)


@main.command()
@click.argument("mesh_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="NetCDF database to write (default: MESH_FILE with .nc).")  # fmt: skip
@click.option("--omega", nargs=3, type=(types.POSITIVE, types.POSITIVE, types.count(1, 2000)),
              default=(0.1, 3.0, 30), show_default=True,
              help="Angular frequencies [rad/s]: first, last, count.")  # fmt: skip
@click.option("--directions", type=str, default="0,45,90,135,180,225,270,315",
              show_default=True, help="Wave directions [deg], comma-separated.")  # fmt: skip
@click.option("--rotation-center", nargs=3, type=types.ANY, default=(0.0, 0.0, 0.0),
              show_default=True, help="The reference point [m] of the six motions.")  # fmt: skip
@click.option("--depth", type=types.Number(low=0.0, low_open=True, infinite="deep water"),
              default=math.inf, help="Water depth [m] (default deep).")  # fmt: skip
@click.option("--rho", type=types.Number(low=1.0, high=1e5, example="1025"), default=1025.0,
              show_default=True, help="[kg/m^3]")  # fmt: skip
@click.option("--yes", is_flag=True, help="Solve a mesh estimated to need more than 1 GB of "
              "memory.")  # fmt: skip
def hydrodb(mesh_file: str, output: str | None, omega, directions: str, rotation_center,
            depth: float, rho: float, yes: bool) -> None:  # fmt: skip
    """Compute the hydrodynamic database of the hull MESH_FILE (placed as floating, z up,
    the waterline at z = 0) with Capytaine: pip install 'seacable[bem]'. Its added mass at
    infinite frequency is solved and written too. One frequency (--omega W W 1) gives a
    database for wave excitation at W; radiation memory needs many."""
    first, last, count = omega
    if count == 1 and first != last:
        _fail(f"--omega {first:g} {last:g} 1: one frequency is first = last (--omega {first:g} "
              f"{first:g} 1); several need a count above 1, e.g. --omega {first:g} {last:g} 30",
              EXIT_INPUT)  # fmt: skip
    if count > 1 and not first < last:
        _fail(f"--omega {first:g} {last:g} {count:g}: give first < last for {count:g} "
              "frequencies, e.g. --omega 0.1 3.0 30 (one frequency: --omega W W 1)",
              EXIT_INPUT)  # fmt: skip
    angles = types.numbers(directions, "--directions")
    output = output or str(Path(mesh_file).with_suffix(".nc"))
    files.check_output(output, "netcdf", [mesh_file], title=files.HYDRODB)
    try:
        db = bem.compute_file(mesh_file, output, np.linspace(first, last, int(count)),
                              directions_deg=angles, rotation_center=rotation_center,
                              depth=depth, rho=rho, allow_large=yes)  # fmt: skip
    except ImportError as exc:
        _fail(str(exc), EXIT_INPUT)
    except meshes.MeshError as exc:
        _fail(str(exc), EXIT_INPUT)
    if len(db.omega) == 1:
        click.echo(f"note: one frequency, {db.omega[0]:.6g} rad/s (period "
                   f"{2 * math.pi / db.omega[0]:.10g} s): wave excitation at it only; radiation "
                   "memory needs the damping over many frequencies", err=True)  # fmt: skip
    click.echo(f"database of {_counted(len(db.omega), 'frequency', 'frequencies')} and "
               f"{_counted(len(db.directions), 'direction', 'directions')} (and the added mass "
               f"at infinite frequency) written: {output}")  # fmt: skip


def _counted(n: int, one: str, many: str) -> str:
    return f"{n} {one if n == 1 else many}"


def _tree(results: seacable.Results, results_file: str) -> xr.DataTree:
    """The results' tree of groups (a system's), or a clear exit for a file without groups."""
    title = results.dataset.attrs.get("title") or None  # a file made by hand may have none
    if title not in (None, TITLE) or "time" not in results.dataset.coords:
        _fail(f"{results_file}: not seacable's results (its title: {title!r}, a time "
              f"coordinate: {'time' in results.dataset.coords}); give a file that seacable "
              "run wrote", EXIT_INPUT)  # fmt: skip
    if not isinstance(results.dataset, xr.DataTree):
        _fail(
            f"{results_file}: results of the single-cable core (retired after commit 4911bc8); "
            "run the case as a system (seacable upgrade case.yaml -o system.yaml) and draw those",
            EXIT_INPUT,
        )
    return results.dataset


@main.command(name="stats")
@click.argument("results_file", type=click.Path(exists=True, dir_okay=False))
@click.option(
    "--storm",
    type=types.DURATION,
    default=10800.0,
    show_default=True,
    help="Duration [s] of the storm whose most probable largest value is given.",
)
@click.option("--from", "start", type=types.NONNEGATIVE, default=None,
              help="Time [s] the statistics start from (default: the run's build-up, the ramp "
                   "that starts its waves).")  # fmt: skip
def statistics(results_file: str, storm: float, start: float | None) -> None:
    """Statistics of RESULTS_FILE: each line's tension at its ends and each moving body's
    motions, their largest, least, mean and standard deviation, zero-up-crossing period Tz
    and most probable largest value over a storm, from a Rayleigh law of the peaks and from a
    Weibull law fitted to them (seacable.stats), from the end of the run's build-up on."""
    tree = _tree(seacable.Results.open(results_file), results_file)
    start = stats_module.build_up(tree.attrs) if start is None else start
    time, rows = stats_module.table(tree["time"].values, stats_module.series(tree), storm, start)
    click.echo(f"{'':44s} {'unit':>6s} {'largest':>10s} {'least':>10s} {'mean':>10s} "
               f"{'std':>10s} {'Tz [s]':>8s} {'MPM Rayl.':>10s} {'MPM Weib.':>10s} "
               f"{'shape':>6s}")  # fmt: skip
    for name, shown, s, fitted, shape in rows:
        click.echo(f"{name:44s} {shown:>6s} {s.largest:10.4g} {s.least:10.4g} {s.mean:10.4g} "
                   f"{s.std:10.4g} {s.tz:8.3g} {s.mpm:10.4g} {fitted:10.4g} "
                   f"{shape:6.3g}")  # fmt: skip
    click.echo(f"{len(time)} rows from {time[0]:g} s to {time[-1]:g} s (--from: the build-up "
               f"left out); the most probable largest of a {storm:g} s storm: Rayleigh's mean "
               "+ std sqrt(2 ln(storm / Tz)), and a Weibull law fitted to the cycles' peaks "
               "(shape 2: Rayleigh's); NaN where the run holds too few up-crossings or "
               "peaks")  # fmt: skip


@main.command(name="export")
@click.argument("results_file", type=click.Path(exists=True, dir_okay=False))
@click.option("--vtk", is_flag=True, help="VTK files for ParaView (the only format yet).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None,
              help="The collection (.pvd; default RESULTS_FILE with .pvd); its files go in a "
                   "folder beside it (_vtk).")  # fmt: skip
@click.option(
    "--every",
    type=types.DURATION,
    default=None,
    help="Seconds between the files written (default: every output time).",
)
def export_files(results_file: str, vtk: bool, output: str | None, every: float | None) -> None:
    """RESULTS_FILE for ParaView: a VTK file a time, lines as segments with their tension and
    hulls as their meshes, and a .pvd collection that ParaView opens as a time series."""
    if not vtk:
        _fail("export: give the format, --vtk (VTK files for ParaView)", EXIT_INPUT)
    target = Path(output) if output else Path(results_file).with_suffix(".pvd")
    results = seacable.Results.open(results_file, lazy=True)
    try:
        written = export.write(_tree(results, results_file), target, every, [results_file])
    finally:
        results.close()
    click.echo(f"{len(written) - 1} VTK files and their collection written: {target}")


@main.command(name="report")
@click.argument("results_file", type=click.Path(exists=True))
@click.option("-o", "--output", type=click.Path(dir_okay=False), default=None,
              help="The page (.html; default RESULTS_FILE with .html).")  # fmt: skip
@click.option("--storm", type=types.DURATION, default=10800.0,
              show_default=True, help="Duration [s] of the storm of the statistics' most "
              "probable largest values.")  # fmt: skip
def report_page(results_file: str, output: str | None, storm: float) -> None:
    """One HTML page of RESULTS_FILE (a run's results or a sweep's summary) that works
    offline: interactive time series, range graphs, the system in 3D with an animation,
    statistics tables, the case and its provenance."""
    target = Path(output) if output else Path(results_file).with_suffix(".html")
    click.echo(f"report written: {report.write(Path(results_file), target, storm)}")


@main.command()
@click.argument("results_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), help="Picture (default .png).")
@click.option("--every", type=types.DURATION, default=None,
              help="Seconds between cable snapshots.")  # fmt: skip
def plot(results_file: str, output: str | None, every: float | None) -> None:
    """Draw cable snapshots and time series from RESULTS_FILE."""
    output = output or str(Path(results_file).with_suffix(".png"))
    files.check_output(output, "picture", [results_file])
    results = seacable.Results.open(results_file)
    viz.plot_results(_tree(results, results_file), output, every=every)
    click.echo(f"picture written: {output}")


@main.command()
@click.argument("results_file", type=click.Path(exists=True, dir_okay=False))
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True,
              help="Animation file (.gif).")  # fmt: skip
@click.option("--fps", type=types.count(1, 100), default=20, help="Frames per second of video.")
@click.option("--speed", type=types.POSITIVE, default=1.0,
              help="Simulated seconds per second of video.")  # fmt: skip
@click.option("--every", type=types.DURATION, default=None,
              help="Simulated seconds between frames (default: speed / fps).")  # fmt: skip
@click.option("--max-frames", type=types.count(1, 100_000), default=600, show_default=True,
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
    files.check_output(output, "animation", [results_file])
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
