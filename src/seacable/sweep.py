"""Load cases from one case (``seacable sweep``): the case's keys varied over values (each a
dimension, crossed with the others, or moving along one), irregular seas of several seeds, and
the rows of a table of load cases (``case.sweep``, the case file's ``sweep:`` block, and the
command line's ``--vary``). Each load case runs as ``seacable run`` runs a case, on Dask
(``seacable.cluster``: a local cluster by default, any scheduler given its address) or in this
process, into its own results file in a folder beside the summary; the summary is one Dataset
with the varied keys as dimensions holding what an engineer reads first: per line its tension's
largest, least, mean, standard deviation, most probable largest over a storm and the
utilisation of its breaking strength; per moving body its largest offset and the range of its
six motions; every load case's status.

Nothing is lost: a load case whose values the case refuses is a row ``refused`` with the
reason, a run that diverges is a row ``diverged`` (its partial results kept), one that fails or
whose worker dies is a row ``failed`` with the reason. A run's file is named by a hash of
everything the run reads (the case resolved and its side files): run again, the sweep reuses
every run that ended (``complete`` or ``diverged``) and runs the others.
"""

import copy
import hashlib
import itertools
import math
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from seacable import ahead, cluster, files, simulation
from seacable.case import loader
from seacable.case.environment import Environment
from seacable.case.sweep import WEATHER, Sweep, Variation
from seacable.case.system import SystemCase
from seacable.errors import CaseError, OutputError, SeacableError, SimulationDiverged
from seacable.results import Results
from seacable.stability.plane import case_waves, significant_height
from seacable.sweep_summary import (  # noqa: F401 (the summary's names, as seacable.sweep's)
    COMPLETE,
    DIVERGED,
    FAILED,
    NOT_RUN,
    REFUSED,
    STATUSES,
    TITLE,
    Envelope,
    LoadCase,
    Plan,
    dataset,
    envelope,
    shown,
    status_row,
    summarise,
    write,
)

ENDED = (COMPLETE, DIVERGED)  # what a sweep run again reuses
MOST_RUNS = 100_000
LARGEST_TABLE = 10_000_000  # bytes: a CSV table of load cases
IRREGULAR = ("jonswap", "pierson_moskowitz")


def parse_vary(text: str) -> Variation:
    """A ``--vary PATH=VALUES`` of the command line: VALUES ``first:stop:step`` (stop
    excluded), a list ``2,4,6`` or ``[2, 4, 6]``, or one value."""
    path, sep, values = text.partition("=")
    if not sep or not path.strip() or not values.strip():
        raise CaseError(f"--vary {text!r}: write PATH=VALUES, e.g. --vary "
                        "environment.waves[0].significant_height=2,4,6 or "
                        "--vary environment.waves[0].direction_deg=0:360:45")  # fmt: skip
    values = values.strip()
    if ":" in values and not values.startswith("["):
        listed: Any = values
    else:
        try:
            listed = loader.parse_yaml(values if values.startswith("[") else f"[{values}]")
        except CaseError:
            raise CaseError(f"--vary {text!r}: the values are not a list; write 2,4,6, "
                            "[2, 4, 6] or first:stop:step") from None  # fmt: skip
    try:
        return Variation(path=path.strip(), values=listed)
    except ValueError as exc:  # pydantic's ValidationError is a ValueError
        detail = str(exc).splitlines()[-2 if len(str(exc).splitlines()) > 2 else -1]
        raise CaseError(f"--vary {text!r}: {detail.strip()}") from None


def plan(case: SystemCase, vary: list[Variation] | tuple = (), seeds: int | None = None,
         load_cases: str | None = None, storm: float | None = None) -> Plan:  # fmt: skip
    """The load cases of ``case``'s ``sweep:`` block with the command line's variations
    (``vary``, after the block's), ``seeds``, table of ``load_cases`` and ``storm`` (each
    replacing the block's), every one validated as a case file is.

    Raises
    ------
    CaseError
        A key that leads nowhere, a table that cannot be read, a sweep of more than MOST_RUNS
        load cases, or one whose every load case the case refuses (the first reason).
    """
    out = Plan(case, _block(case, vary, seeds, load_cases, storm))
    base = loader.case_data(case)
    base.pop("sweep", None)
    dimensions = _dimensions(out, base)
    if not dimensions:
        raise CaseError(
            "sweep: nothing varies; give --vary PATH=VALUES, --seeds N, "
            "--load-cases TABLE or a sweep: block (seacable run runs one case)"
        )
    out.dims = {name: values for name, values, _, _ in dimensions}
    count = math.prod(out.shape)
    if count > MOST_RUNS:
        raise CaseError(f"sweep: {count:,} load cases ({' x '.join(map(str, out.shape))}); a "
                        f"sweep takes at most {MOST_RUNS:,}; vary fewer values")  # fmt: skip
    shares = [share for _, _, share, _ in dimensions if share is not None]
    if len(shares) == len(dimensions):
        joint = np.ones(())
        for share in shares:
            joint = np.multiply.outer(joint, share)
        out.probability = joint
    setters = [put for _, _, _, put in dimensions]
    for index in itertools.product(*(range(n) for n in out.shape)):
        out.cases.append(_load_case(case, base, out, index, setters))
    if all(c.refused for c in out.cases):
        raise CaseError(f"sweep: the case refuses every load case; the first: "
                        f"{out.cases[0].refused}")  # fmt: skip
    return out


def _block(case: SystemCase, vary, seeds, load_cases, storm) -> Sweep:
    """The case's ``sweep:`` block with the command line's options."""
    block = case.sweep.model_dump(exclude_none=True) if case.sweep else {}
    block["vary"] = [*block.get("vary", []), *(v.model_dump(exclude_none=True) for v in vary)]
    for key, value in (("seeds", seeds), ("load_cases", load_cases), ("storm", storm)):
        if value is not None:
            block[key] = value
    try:
        return Sweep.model_validate(block)
    except ValueError as exc:
        raise CaseError(f"sweep: {loader.format_errors(exc, Sweep)}") from None  # type: ignore[arg-type]


_Dimension = tuple[str, list, np.ndarray | None, Callable[[dict, int], None]]


def _dimensions(out: Plan, base: dict) -> list[_Dimension]:
    """The sweep's dimensions in order: (name, values, their shares or None, what sets the
    k-th value in a case's mapping); ``out.along`` filled."""
    sweep, found = out.sweep, []
    for variation in sweep.vary:
        values = variation.listed()
        label = f"sweep.vary '{variation.path}'"
        _put(copy.deepcopy(base), variation.path, values[0], label)  # leads somewhere?
        if variation.along is not None:
            out.along[variation.label] = (variation.along, values)
            continue
        share = variation.probabilities
        moving = [variation] + [v for v in sweep.vary if v.along == variation.label]
        found.append((variation.label, values, None if share is None else np.asarray(share),
                      _setter(moving)))  # fmt: skip
    if sweep.load_cases is not None:
        names, rows, probability = _table(sweep.load_cases, loader.case_base_dir(out.case))
        found.append(("load_case", names, probability,
                      lambda data, k: _apply_row(data, rows[k])))  # fmt: skip
    if sweep.seeds > 1:
        spectra = [w for w in base.get("environment", {}).get("waves", [])
                   if w.get("kind") in IRREGULAR]  # fmt: skip
        if not spectra:
            raise CaseError(f"sweep.seeds {sweep.seeds}: the seeds vary the irregular seas "
                            "(environment.waves of kind jonswap or pierson_moskowitz), and "
                            "the case has none; remove seeds or add a spectrum")  # fmt: skip
        first = int(spectra[0].get("seed", 0))
        found.append(("seed", [first + k for k in range(sweep.seeds)],
                      np.full(sweep.seeds, 1.0 / sweep.seeds), _reseed))  # fmt: skip
    return found


def _setter(moving: list[Variation]) -> Callable[[dict, int], None]:
    def put(data: dict, k: int) -> None:
        for v in moving:
            _put(data, v.path, v.listed()[k], f"sweep.vary '{v.path}'")

    return put


def _put(data: dict, path: str, value: Any, label: str) -> None:
    """Set the key at ``path`` of a case's mapping, or the weather by its short path
    (case.sweep.WEATHER)."""
    if path not in WEATHER:
        if path.partition(".")[0] in ("waves", "current", "wind"):
            raise CaseError(
                f"{label}: not a weather path; the weather's are "
                f"{', '.join(WEATHER)} (or a case key: environment.waves[0]...)"
            )
        loader.set_key(data, path, value, label)
        return
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise CaseError(f"{label}: {value!r} is not a number; the weather takes numbers")
    environment = data.setdefault("environment", {})
    kind, what = path.split(".")
    if kind == "waves":
        _waves(environment, what, float(value), label)
    elif kind == "current":
        current = environment.setdefault("current", {"velocity": 0.0})
        if what == "speed" and "profile" in current:
            raise CaseError(
                f"{label}: the case's current is a profile; vary "
                "environment.current.profile, or give it a uniform velocity"
            )
        current["velocity" if what == "speed" else "direction_deg"] = float(value)
    else:
        if environment.get("wind") is None:
            raise CaseError(f"{label}: the case has no wind; add environment.wind (speed, "
                            "direction_deg) and a body's wind force model")  # fmt: skip
        environment["wind"]["speed" if what == "speed" else "direction_deg"] = float(value)


def _waves(environment: dict, what: str, value: float, label: str) -> None:
    """Every wave scaled to the significant height ``value`` [m] (``what`` 'height'), or
    turned to the mean direction ``value`` [deg] (the direction seacable continuation takes:
    stability.plane.case_waves)."""
    waves = environment.get("waves") or []
    if not waves:
        doing = "scale" if what == "height" else "turn"
        raise CaseError(f"{label}: the case has no waves to {doing}; add environment.waves")
    try:
        sea = Environment.model_validate(environment)
    except ValueError:
        return  # the case refuses its environment: said when the load case is validated
    if what == "height":
        factor = value / significant_height(sea)
        for wave in waves:
            key = "height" if wave.get("kind") == "airy" else "significant_height"
            wave[key] = float(wave[key]) * factor
    else:
        turn = value - case_waves(sea)[1]
        for wave in waves:
            wave["direction_deg"] = float(wave.get("direction_deg", 0.0)) + turn


def _apply_row(data: dict, row: dict) -> None:
    for path, value in row.items():
        _put(data, path, value, f"sweep.load_cases column '{path}'")


def _reseed(data: dict, k: int) -> None:
    for wave in data["environment"]["waves"]:
        if wave.get("kind") in IRREGULAR:
            wave["seed"] = int(wave.get("seed", 0)) + k


def _cell(text: str, name: str, number: int, key: str) -> Any:
    """A load case's value (YAML), or a CaseError naming the table, its line and column."""
    try:
        return loader.parse_yaml(text) if text else None
    except CaseError as exc:
        detail = " ".join(str(exc).partition(": ")[2].split())
        raise CaseError(f"sweep.load_cases '{name}' line {number}, {key} {files.quoted(text)}: "
                        f"not a YAML value ({detail})") from None  # fmt: skip


def _table(name: str, base_dir) -> tuple[list[str], list[dict], np.ndarray | None]:
    """A CSV table of load cases: the row labels, each row's keys and values (read as YAML:
    numbers, words, lists in brackets), and the probability column (None without it)."""
    path = Path(base_dir or ".") / name
    if path.suffix.lower() != ".csv":
        raise CaseError(f"sweep.load_cases '{name}': give a CSV table (.csv)")
    text = files.read_text(path, "sweep.load_cases: table", LARGEST_TABLE, CaseError,
                           fix="save it as UTF-8 CSV",
                           give="give the table's path relative to the case file")  # fmt: skip
    reader = files.csv_rows(text, f"sweep.load_cases '{name}'", CaseError)
    header = [h.strip() for h in next(reader, (0, []))[1]]
    keys = [h for h in header if h not in ("name", "probability")]
    if not keys or len(set(header)) != len(header) or "" in header:
        raise CaseError(f"sweep.load_cases '{name}': its header must name each key once (as "
                        "--set writes them), with optional columns name and probability; it "
                        f"has {header}")  # fmt: skip
    labels: list[str] = []
    rows: list[dict] = []
    shares: list[float] = []
    for number, cells in reader:
        if len(cells) != len(header):
            raise CaseError(f"sweep.load_cases '{name}' line {number}: {len(cells)} cells "
                            f"for {len(header)} columns")  # fmt: skip
        row = {h: c.strip() for h, c in zip(header, cells, strict=True)}
        labels.append(row.pop("name", "") or str(len(labels) + 1))
        if "probability" in row:
            shares.append(_share(row.pop("probability"), name, number))
        rows.append({k: _cell(v, name, number, k) for k, v in row.items()})
    if not rows:
        raise CaseError(f"sweep.load_cases '{name}': no rows; give one row per load case")
    if len(set(labels)) != len(labels):
        raise CaseError(f"sweep.load_cases '{name}': the names must differ")
    return labels, rows, (np.array(shares) if "probability" in header else None)


def _share(text: str, name: str, number: int) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0.0 <= value <= 1.0:
        shown = files.quoted(text)
        raise CaseError(f"sweep.load_cases '{name}' line {number}: probability {shown} must "
                        "be a share of the time, from 0 to 1")  # fmt: skip
    return value


def _load_case(case: SystemCase, base: dict, out: Plan, index: tuple[int, ...],
               setters: list) -> LoadCase:  # fmt: skip
    label = ", ".join(f"{d}={shown(v[k])}" for (d, v), k in zip(out.dims.items(), index,
                                                                 strict=True))  # fmt: skip
    data = copy.deepcopy(base)
    for put, k in zip(setters, index, strict=True):
        put(data, k)
    try:
        derived = loader.load_case(data)
    except CaseError as exc:
        return LoadCase(index, label, refused=" ".join(str(exc).split()))
    derived._base_dir, derived._source_file = case._base_dir, case._source_file
    digest = hashlib.sha256()
    for text in loader.record(derived).values():
        digest.update(text.encode())
    number = "-".join(str(k) for k in index) or "0"
    return LoadCase(index, label, data, f"run-{number}-{digest.hexdigest()[:16]}.nc")


# ---- running ----------------------------------------------------------------------------------
def run_one(data: dict, base_dir: str | None, source: str | None, path: str,
            storm: float) -> dict:  # fmt: skip
    """Run one load case (a case's mapping; relative names from ``base_dir``) into the file
    ``path`` and return its summary row (``summarise``) with its wall time: where Dask sends
    it, plain data in and out. A run that fails is a row ``failed`` with the reason."""
    started = time.perf_counter()
    try:
        case = loader.load_case(data)
        case._base_dir, case._source_file = base_dir, source
        try:
            results = simulation.simulate(case, output=path)
        except SimulationDiverged as exc:
            results = exc.results
        row = summarise(results, case, storm)
        results.close()
    except (SeacableError, OSError) as exc:
        row = status_row(FAILED, str(exc))
    except Exception as exc:  # noqa: BLE001 (a bug of one run is a row, not a lost batch)
        row = status_row(FAILED, f"internal error, a bug in seacable ({type(exc).__name__}: {exc})")
    row["seconds"] = time.perf_counter() - started
    return row


def _reused(folder: Path, load: LoadCase, case: SystemCase, storm: float) -> dict | None:
    """The row of a run a sweep already ended (its file found by the hash of what it reads,
    whatever its place in that sweep), or None when there is none or it did not end."""
    digest = load.file.rsplit("-", 1)[-1]
    for path in sorted(folder.glob(f"run-*-{digest}")):
        try:
            results = Results.open(path, lazy=True)
        except (OSError, ValueError):
            continue
        try:
            if results.status not in ENDED:
                continue
            derived = loader.load_case(load.data or {})
            derived._base_dir, derived._source_file = case._base_dir, case._source_file
            row = summarise(results, derived, storm)
        finally:
            results.close()
        row.update(seconds=math.nan, reused=True, file=path.name)
        return row
    return None


def runs_folder(output: Path) -> Path:
    """The folder of a summary's runs: ``sweep.nc`` -> ``sweep.runs``."""
    return output.with_name(output.name.rsplit(".", 1)[0] + ".runs")


def check_summary_output(output: Path, case: SystemCase) -> None:
    """Refuse a summary path that is not NetCDF or Zarr (.zarr), is a link or a file the case
    reads, or exists and is not a sweep summary (which the summary would replace), or whose
    runs' folder is a link (``files.check_output``)."""
    zarr = output.suffix.lower() == ".zarr"
    files.check_output(output, "zarr" if zarr else "netcdf", loader.files_read(case), TITLE)
    if zarr and output.exists() and not _title(lambda: xr.open_zarr(output)):
        raise OutputError(f"output '{output}' exists and is not a sweep's summary, which the "
                          "summary would replace; remove it or choose another name")  # fmt: skip
    folder = runs_folder(output)
    if folder.is_symlink() or (folder.exists() and not folder.is_dir()):
        raise OutputError(f"the runs' folder '{folder}' (beside output '{output}') is a link or "
                          "a file; remove it or choose another output name")  # fmt: skip


def _title(opener) -> bool:
    try:
        with opener() as ds:
            return ds.attrs.get("title") == TITLE
    except Exception:  # noqa: BLE001 (not a dataset at all)
        return False


def execute(
    todo: Plan,
    output: Path,
    scheduler: str | None = cluster.LOCAL,
    report: Callable[[int, int, LoadCase, dict], None] | None = None,
    rerun: bool = False,
) -> xr.Dataset:
    """Run the load cases of ``todo`` (on Dask at ``scheduler``, or in this process for None)
    into ``runs_folder(output)``, reusing the runs a sweep already ended there (``rerun``: none,
    each run again into its file: their names hash what the runs read, not the software that
    ran them), and write the summary (``dataset``) to ``output``; ``report(done, total, load
    case, row)`` as each run ends. Ctrl-C: the summary of the runs ended so far, the others
    ``not run``, then KeyboardInterrupt."""
    check_summary_output(output, todo.case)
    folder = runs_folder(output)
    folder.mkdir(exist_ok=True)
    storm = todo.sweep.storm
    rows: dict[tuple, dict] = {}
    total = len(todo.cases)

    def done(load: LoadCase, row: dict) -> None:
        row.setdefault("file", load.file if not load.refused else "")
        rows[load.index] = row
        if report is not None:
            report(len(rows), total, load, row)

    pending: list[LoadCase] = []
    for load in todo.cases:  # the rows known before any run: refused, or ended before
        known = (
            status_row(REFUSED, load.refused)
            if load.refused
            else None
            if rerun
            else _reused(folder, load, todo.case, storm)
        )
        if known is None:
            pending.append(load)
        else:
            done(load, known)
    try:
        for load, row in _runs(pending, folder, todo.case, storm, scheduler):
            done(load, row)
    finally:
        found = dataset(todo, rows, folder.name)
        write(found, output)
    return found


def _runs(pending: list[LoadCase], folder: Path, case: SystemCase, storm: float,
          scheduler: str | None) -> Iterator[tuple[LoadCase, dict]]:  # fmt: skip
    base, source = case._base_dir, case._source_file
    if not pending:
        return
    if scheduler is None:
        for load in pending:
            yield load, run_one(load.data or {}, base, source, str(folder / load.file), storm)
        return
    if scheduler == cluster.LOCAL:  # compiled once here, not in every worker at once
        first = loader.load_case(pending[0].data or {})
        first._base_dir, first._source_file = base, source
        for item in ahead.items([("sweep", first)], every=False):
            item.run()
    from distributed import as_completed

    with cluster.client(scheduler, "a sweep") as client:
        futures = {client.submit(run_one, load.data, base, source, str(folder / load.file),
                                 storm, pure=False): load
                   for load in pending}  # fmt: skip
        try:
            for future in as_completed(futures):
                load = futures[future]
                try:
                    row = future.result()
                except Exception as exc:  # noqa: BLE001 (the worker died, or the task could not run)
                    row = status_row(FAILED, f"on Dask: {type(exc).__name__}: {exc}")
                yield load, row
        finally:
            client.cancel(list(futures))
