"""The command line's batch of load cases, ``seacable sweep`` (seacable.sweep), registered on
``seacable.cli.main`` (``COMMANDS``); its failures reach that one error boundary."""

import math
import sys
from pathlib import Path

import click

from seacable import cli_types as types
from seacable import cluster
from seacable import sweep as batch
from seacable.cli_ships import load


def _said(row: dict) -> str:
    """A run's row in a few words: its status, wall time and most used line."""
    if row["status"] != batch.COMPLETE:
        return f"{row['status']}: {row['message']}"
    took = "" if math.isnan(row.get("seconds", math.nan)) else f" in {row['seconds']:.1f} s"
    took = " (ended before, reused)" if row.get("reused") else took
    lines = row["lines"]
    if not lines:
        return f"complete{took}"
    name = max(lines, key=lambda n: lines[n]["tension_max"])
    share = lines[name]["utilisation"]
    used = "" if math.isnan(share) else f", {100 * share:.3g} % of its breaking strength"
    return f"complete{took}; largest tension {name} {lines[name]['tension_max'] / 1e3:.5g} kN{used}"


def _envelope(found) -> list[str]:
    """Per line: its largest tension over the sweep's complete runs, and where."""
    out = []
    for row in batch.envelope(found):
        used = "" if math.isnan(row.utilisation) else (
            f" ({100 * row.utilisation:.3g} % of its breaking strength)")  # fmt: skip
        out.append(f"  {row.line}: {row.tension / 1e3:.5g} kN{used} at {row.at}")
    return out


@click.command()
@click.argument("case_file", type=click.Path(dir_okay=False))
@click.option("--vary", multiple=True, metavar="PATH=VALUES",
              help="A key varied over values, a dimension of the sweep (crossed with the "
                   "others): PATH as --set writes it, VALUES first:stop:step (stop excluded), "
                   "2,4,6 or [2, 4, 6]; repeatable, after the case's sweep: block.")  # fmt: skip
@click.option("--seeds", type=click.IntRange(min=1, max=10_000), default=None,
              help="Irregular seas of each load case: every spectrum's seed plus 0 to N - 1 "
                   "(default: the sweep: block's, else 1).")  # fmt: skip
@click.option("--load-cases", type=click.Path(dir_okay=False), default=None,
              help="A CSV table of load cases: a header of keys as --set writes them, "
                   "optionally name and probability; one row a load case.")  # fmt: skip
@click.option("--storm", type=types.DURATION, default=None,
              help="Duration [s] of the storm whose most probable largest tension the summary "
                   "gives (default: the sweep: block's, else 10800).")  # fmt: skip
@click.option("--set", "settings", multiple=True, metavar="PATH=VALUE",
              help="Change one key of the case for every run, as the file nests it; "
                   "repeatable.")  # fmt: skip
@click.option("--dask", "scheduler", default=cluster.LOCAL, show_default=True,
              help="'local' (a cluster of this machine's cores), 'none' (one run after the "
                   "other in this process) or a scheduler's address (tcp://host:8786; its "
                   "workers must see the case's and the output's folders).")  # fmt: skip
@click.option("--rerun", is_flag=True,
              help="Run every load case again, replacing its results, instead of reusing the "
                   "runs that ended (after a change of seacable, say).")  # fmt: skip
@click.option("-o", "--output", type=click.Path(), default=None,
              help="The summary (.nc or .zarr; default CASE_FILE with .sweep.nc); the runs "
                   "go in a folder beside it (.runs).")  # fmt: skip
def sweep(case_file: str, vary: tuple[str, ...], seeds: int | None, load_cases: str | None,
          storm: float | None, settings: tuple[str, ...], scheduler: str, rerun: bool,
          output: str | None) -> None:  # fmt: skip
    """Run the load cases of CASE_FILE (its sweep: block and --vary, --seeds, --load-cases)
    and write their summary: per line its tensions and utilisation, per body its offset and
    motions, each run's status. Run again, it reuses the runs that ended."""
    where = None if scheduler == "none" else scheduler
    cluster.check(where)
    case = load(case_file, settings)
    table = None if load_cases is None else str(Path(load_cases).absolute())
    todo = batch.plan(case, [batch.parse_vary(v) for v in vary], seeds, table, storm)
    target = Path(output) if output else Path(case_file).with_suffix(".sweep.nc")
    sizes = " x ".join(f"{len(v)} {d}" for d, v in todo.dims.items())
    click.echo(f"{len(todo.cases)} load cases ({sizes}); runs in "
               f"{batch.runs_folder(target)}")  # fmt: skip

    def report(done: int, total: int, load_case, row: dict) -> None:
        click.echo(f"[{done}/{total}] {load_case.label}: {_said(row)}")
        sys.stdout.flush()

    try:
        found = batch.execute(todo, target, where, report,
                              rerun)  # fmt: skip
    except KeyboardInterrupt:
        click.echo(f"error: interrupted; the summary of the runs ended so far: {target}; the "
                   "same command again runs the rest", err=True)  # fmt: skip
        sys.exit(130)
    click.echo(f"{len(todo.cases)} load cases: {found.attrs['counts']}")
    envelope = _envelope(found)
    if envelope:
        click.echo("largest tension of each line over the sweep:")
        for row in envelope:
            click.echo(row)
    click.echo(f"summary written: {target}")


COMMANDS = (sweep,)
