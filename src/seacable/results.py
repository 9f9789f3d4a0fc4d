"""Results of a run: an xarray Dataset, written to NetCDF as the run goes.

Dimensions: ``time``, ``segment`` (one per link), ``node`` (links + 1, node 0 at the top).
Every variable carries ``units`` and ``long_name``; the attributes carry provenance and the
``status`` of the run (``complete``, ``diverged``, ``interrupted``, or ``incomplete`` while it
runs or if the process died) with its ``status_message``.
"""

import datetime as _dt
import math
import platform
import shutil
from pathlib import Path
from time import monotonic

import h5netcdf
import h5py
import numba
import numpy as np
import scipy
import xarray as xr
import yaml
from xarray.backends import BackendArray
from xarray.core import indexing

from seacable import files
from seacable.errors import InputError, OutputError

TITLE = "seacable simulation results"
STATUS_COMPLETE = "complete"
STATUS_DIVERGED = "diverged"
STATUS_INTERRUPTED = "interrupted"
STATUS_INCOMPLETE = "incomplete"


def provenance(case_text: str, solver: dict) -> dict:
    from seacable import __version__

    attrs = {
        "title": TITLE,
        "seacable_version": __version__,
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "case": case_text,
        "status": STATUS_INCOMPLETE,
        "status_message": "the run has not finished (still running, or the process was killed)",
        "conventions": "SI units; x horizontal, z up, z = 0 at the still-water surface",
    }
    attrs.update({f"solver_{k}": v for k, v in solver.items()})
    attrs.update(software=_software(), platform=platform.platform(), repeat=REPEAT)
    return attrs


REPEAT = (
    "seacable repeat THIS_FILE -o OUTPUT: runs the case again from this file's attributes "
    "(case, input_files), with the software named in 'software'"
)


def restore_case(attrs, folder, carried_only: bool = False) -> Path:
    """Write the case a results file was run from (its ``case`` attribute) and the files it
    read (``input_files``) into ``folder``; returns the case file's path. A file the case named
    outside its folder (an absolute path or '..') is put inside, and the case text pointed at
    it. ValueError when the file holds no case, such a name cannot be put back, or
    (``carried_only``: to run it again) the case names a file (a ``file:`` key) the results do
    not carry: the case written then reads only what the results file holds."""
    if "case" not in attrs:
        raise ValueError("not a seacable results file (no 'case' attribute)")
    text, carried = str(attrs["case"]), yaml.safe_load(str(attrs.get("input_files", "{}")))
    for k, (name, content) in enumerate((carried or {}).items()):
        kept = name
        if Path(name).is_absolute() or ".." in Path(name).parts:
            kept = f"outside_{k}_{Path(name).name}"
            if text.count(name) != 1:
                raise ValueError(f"input file '{name}' cannot be put back in the case's text; "
                                 "run the case itself")  # fmt: skip
            text = text.replace(name, kept)
        (Path(folder) / kept).parent.mkdir(parents=True, exist_ok=True)
        (Path(folder) / kept).write_text(content)
    (Path(folder) / "case.yaml").write_text(text)
    own = Path(folder).resolve()
    for name in _named_files(yaml.safe_load(text)) if carried_only else []:
        if not (own / name).resolve().is_relative_to(own) or not (own / name).is_file():
            raise ValueError(f"its case reads '{name}', which the file does not carry "
                             "(input_files); a results file is run again from what it holds "
                             "only: run the case file itself")  # fmt: skip
    return Path(folder) / "case.yaml"


def _named_files(data) -> list[str]:
    """The values of every ``file:`` key of a case's data (tables, meshes, databases)."""
    if isinstance(data, dict):
        found = [str(v) for k, v in data.items() if k == "file" and isinstance(v, str)]
        return found + [f for v in data.values() for f in _named_files(v)]
    if isinstance(data, list):
        return [f for v in data for f in _named_files(v)]
    return []


def _software() -> str:
    """The versions a run's numbers depend on."""
    from seacable import __version__

    return (
        f"seacable {__version__}, Python {platform.python_version()}, NumPy {np.__version__}, "
        f"SciPy {scipy.__version__}, numba {numba.__version__}, h5py {h5py.__version__}, "
        f"xarray {xr.__version__}"
    )


SLOW_WRITE = 0.05  # [s] a write of rows beyond which the next ones are held (_Sink._write_held)
EAGER_BYTES = 256_000_000  # results files up to this size are read back whole after a run


class Results:
    """The outcome of :func:`seacable.simulate`: the dataset, its status and message. A system
    of bodies and lines gives a DataTree (``xarray.open_datatree``) with a group per body
    (``bodies/<name>``) and per line (``lines/<name>``); ``results["lines/chain/tension"]``.
    A run's file larger than EAGER_BYTES is read lazily (the file stays open; ``close``)."""

    def __init__(self, dataset: xr.Dataset | xr.DataTree, path: Path | None = None):
        self.dataset = dataset
        self.path = path

    @property
    def status(self) -> str:
        return self.dataset.attrs.get("status", STATUS_INCOMPLETE)

    @property
    def message(self) -> str:
        return self.dataset.attrs.get("status_message", "")

    @property
    def complete(self) -> bool:
        return self.status == STATUS_COMPLETE

    def __getitem__(self, name):
        return self.dataset[name]

    def __repr__(self) -> str:
        where = f", path={str(self.path)!r}" if self.path else ""
        return f"Results(status={self.status!r}, times={self.dataset.sizes.get('time', 0)}{where})"

    def close(self) -> None:
        """Close the file a lazily read dataset keeps open (nothing for one read whole)."""
        self.dataset.close()

    def to_netcdf(self, path) -> None:
        self.dataset.to_netcdf(path, engine="h5netcdf")

    @classmethod
    def open(cls, path, lazy: bool = False) -> "Results":
        """Read results written by seacable (complete or not: the rows a run never wrote, NaN
        in the file, are left out). ``lazy`` keeps the file open and reads a variable, or the
        part of it asked for, only when it is used (long runs). A file that keeps data in
        other files is refused (``files.self_contained``)."""
        files.self_contained(path)
        try:
            with h5netcdf.File(path, "r") as f:
                grouped = bool(f.groups)
                own = f.attrs.get("title") == TITLE
                time = np.asarray(f["time"][...], dtype=float) if "time" in f else np.zeros(0)
        except OSError as exc:
            raise InputError(f"results file '{path}' is not a readable NetCDF/HDF5 file "
                             f"({exc}); give a file that seacable wrote") from None  # fmt: skip
        written = int(np.count_nonzero(np.isfinite(time)))
        kept = time[:written]
        wrong = np.nonzero(~np.isfinite(kept[1:]) | ~(np.diff(kept) > 0.0))[0]
        if len(wrong):
            raise InputError(
                f"results file '{path}': its time at row {wrong[0] + 1} is {kept[wrong[0] + 1]} "
                f"after {kept[wrong[0]]}, not later; the file is damaged (written by another "
                "program, or changed): run its case again"
            )
        if grouped and own:
            return cls(_tree(path, lazy, written), Path(path))
        opener = xr.open_datatree if grouped else xr.open_dataset
        if lazy:
            return cls(_rows(opener(path, engine="h5netcdf"), written), Path(path))
        with opener(path, engine="h5netcdf") as ds:
            return cls(_rows(ds, written).load(), Path(path))


# h5netcdf's bookkeeping attributes, which xarray does not show (h5netcdf.attrs)
_HIDDEN = frozenset(("REFERENCE_LIST", "CLASS", "DIMENSION_LIST", "NAME", "_Netcdf4Dimid",
                     "_Netcdf4Coordinates", "_nc3_strict", "_NCProperties"))  # fmt: skip
_DIMENSION_ONLY = b"This is a netCDF dimension but not a netCDF variable"


def _tree(path, lazy: bool, written: int) -> xr.DataTree:
    """A grouped results file that seacable wrote, as ``xarray.open_datatree`` with h5netcdf
    reads it (the same tree: tests/test_results_io.py), without h5netcdf's dimension lookup:
    it names a variable's dimension through HDF5's name of the object a reference points to,
    which HDF5 finds by searching the file, so that reading grows with the square of the
    variables (a run of 800 anchors, 9,800 variables, read back in 340 s; 7.5 s here). Here each
    dimension's dataset is known by its object (``h5py``'s ids compare by address). ``lazy``
    keeps the file open and reads a variable as it is indexed (``Results.close``); the first
    ``written`` time rows are kept (``_rows``)."""
    f = h5py.File(path, "r")
    try:
        names, groups = {}, {"/": f}

        def visit(name, obj):
            if isinstance(obj, h5py.Group):
                groups["/" + name] = obj
            elif obj.attrs.get("CLASS") == b"DIMENSION_SCALE":
                names[obj.id] = name.rpartition("/")[2]

        f.visititems(visit)
        tree = {}
        for where, group in groups.items():
            variables = {}
            for name, obj in group.items():
                if not isinstance(obj, h5py.Dataset) or bytes(
                    obj.attrs.get("NAME", b"")
                ).startswith(_DIMENSION_ONLY):
                    continue  # a dimension without values
                if "DIMENSION_LIST" in obj.attrs:
                    dims = tuple(names[f[refs[-1]].id] for refs in obj.attrs["DIMENSION_LIST"])
                else:  # a coordinate: its dimension's own dataset
                    dims = (name,)
                data = indexing.LazilyIndexedArray(_Stored(obj)) if lazy else obj[...]
                variables[name] = xr.Variable(dims, data, _attributes(obj.attrs))
            tree[where] = xr.decode_cf(xr.Dataset(variables, attrs=_attributes(group.attrs)))
        result = _rows(xr.DataTree.from_dict(tree), written)
    except (KeyError, ValueError, TypeError, OSError) as exc:  # changed or damaged
        f.close()
        raise InputError(f"results file '{path}' cannot be read as seacable's results "
                         f"({type(exc).__name__}: {files.quoted(str(exc), 80)}); the file is "
                         "damaged or was changed: run its case again") from None  # fmt: skip
    except BaseException:
        f.close()
        raise
    if lazy:
        result.set_close(f.close)
    else:
        f.close()
    return result


def _attributes(stored) -> dict:
    """An HDF5 object's attributes as h5netcdf gives them: its bookkeeping left out, text
    decoded, a one-element array as its element."""
    attrs = {}
    for key in stored:
        if key in _HIDDEN:
            continue
        value = stored[key]
        if isinstance(value, bytes):
            value = value.decode("utf-8", "surrogateescape")
        elif isinstance(value, np.ndarray):
            if value.dtype.kind in "SO":
                value = [v.decode("utf-8", "surrogateescape") if isinstance(v, bytes) else v
                         for v in value.flat]  # fmt: skip
            if len(value) == 1:
                value = value[0]
        attrs[key] = value
    return attrs


class _Stored(BackendArray):
    """A variable of an open results file, read as it is indexed (xarray's lazy indexing)."""

    def __init__(self, dataset: h5py.Dataset):
        self.dataset = dataset
        self.shape = dataset.shape
        self.dtype = dataset.dtype

    def __getitem__(self, key):
        return indexing.explicit_indexing_adapter(
            key, self.shape, indexing.IndexingSupport.OUTER_1VECTOR, self._read
        )

    def _read(self, key):
        return self.dataset[key]


def _rows(ds, count: int):
    """The first ``count`` time rows of a Dataset or DataTree (every group's time alike)."""
    return ds.isel(time=slice(0, count)) if "time" in ds.dims else ds


class _Sink:
    """Where output rows go: in memory, or to a NetCDF file as they come (then not kept in
    memory: ``finish`` reads them back).

    The file is crash-safe: every variable is stored contiguously, its whole size for the
    ``rows`` the run will write allocated at creation and filled with NaN (``_FillValue``), and
    the file's structure flushed then. After that a run writes raw values only, never HDF5's
    structure (no dimension grows, no chunk is allocated), and flushes after each chunk of
    rows (after several where writing is slow: ``_write_held``): a process killed at any
    moment, even with SIGKILL, leaves a file that opens, with every row up to the last flush
    and NaN after. (Appending rows to unlimited dimensions, as
    before, rewrote the file's structure at each chunk: killed mid-write, the file no longer
    opened.) The file is in proportion to its rows: no chunk padding (a line of 100,000
    segments with one row was 4.1 GB of chunks of 1024 rows)."""

    def __init__(self, path, sizes: dict, coords: dict, variables: dict, attrs: dict,
                 rows: int = 1, inputs=()):  # fmt: skip
        """``sizes`` maps each dimension but time to its length; ``coords`` maps name ->
        (dim, values, units, long_name); ``variables`` maps name -> (dims, units, long_name);
        ``rows``: the time rows the run will write at most (a file's size); ``inputs``: the
        files the run reads, which it must not replace."""
        self.path = None if path is None else Path(path)
        self.sizes = sizes
        self.coords = coords
        self.variables = variables
        self.attrs = dict(attrs)
        self.chunks: dict[str, list[np.ndarray]] = {name: [] for name in ("time", *variables)}
        self.rows = 0
        self.capacity = rows
        self._file = None
        self._held: list[tuple[int, dict]] = []  # rows not yet written: (first row, rows)
        self._due = 0.0  # monotonic() from which held rows are written
        if self.path is not None:
            check_output(self.path, inputs)
            self._room()
            # made under another name (in a private folder) and moved in once its structure is
            # on disk: the file at ``path`` is never one that does not open
            with files.replacing(self.path) as creating:
                self._file = self._create(creating)

    def _create(self, target: Path):
        f = h5netcdf.File(target, "w")
        f.dimensions = {"time": self.capacity}
        # every group of time rows has its own time dimension (the root's time coordinate
        # applies to it): one dimension shared by the hundreds of variables of a system made
        # opening a four-cable result take 15 s while it was unlimited
        self.timed = sorted({_split(path)[0] for path, (dims, _, _) in self.variables.items()
                             if "time" in dims} - {""})  # fmt: skip
        for group in self.timed:
            _group(f, group).dimensions["time"] = self.capacity
        for path, size in self.sizes.items():  # a system's are per group: "lines/chain/node"
            group, dim = _split(path)
            _group(f, group).dimensions[dim] = size
        for path, (dim, values, units, long_name) in self.coords.items():
            group, name = _split(path)
            v = _group(f, group).create_variable(name, (dim,), float, data=values)
            v.attrs.update(units=units, long_name=long_name)
        t = f.create_variable("time", ("time",), float, **_ALLOCATED)
        t.attrs.update(units="s", long_name="time", standard_name="time")
        for path, (dims, units, long_name) in self.variables.items():
            group, name = _split(path)
            v = _group(f, group).create_variable(name, dims, float, **_ALLOCATED)
            v.attrs.update(units=units, long_name=long_name)
        f.attrs.update(self.attrs)
        f.flush()  # h5netcdf's: writes its _NCProperties (an attribute: not again until close)
        f._h5file.flush()  # HDF5's: the structure on disk (h5netcdf's flush does not do it)
        return f

    def bytes_needed(self) -> int:
        """The file's size once its rows are allocated [bytes]: 8 per value of every time row
        (the rest, coordinates and attributes, is small beside it)."""
        per_row = 1
        for path, (dims, _, _) in self.variables.items():
            group, _ = _split(path)
            per_row += math.prod(self._size(group, d) for d in dims if d != "time")
        return 8 * per_row * self.capacity

    def _room(self) -> None:
        """Refuse a file the disk cannot hold (it is allocated whole when it is created), with
        the estimate and the room there is."""
        needed = self.bytes_needed()
        assert self.path is not None
        free = shutil.disk_usage(self.path.parent).free
        if needed > free:
            raise OutputError(
                f"output '{self.path}' needs about {needed / 1e9:.3g} GB ({self.capacity:,} "
                f"rows), and its disk has {free / 1e9:.3g} GB free; lengthen "
                "simulation.output_interval, shorten duration, or write elsewhere"
            )

    def _size(self, group: str, dim: str) -> int:
        return self.sizes[f"{group}/{dim}" if group else dim]

    def write(self, rows: dict) -> None:
        """Append ``rows`` (name -> values, time first); names the case does not record (a
        model's rows hold all its variables) are left out."""
        count = len(rows["time"])
        if count == 0:
            return
        rows = {name: values for name, values in rows.items() if name in self.chunks}
        if self.rows + count > self.capacity:
            raise ValueError(f"{self.rows + count} rows, more than the {self.capacity} allotted")
        if self._file is None:
            for name, values in rows.items():
                self.chunks[name].append(np.array(values, copy=True))
        else:
            held = {name: np.array(values, copy=True) for name, values in rows.items()}
            self._held.append((self.rows, held))
            if monotonic() >= self._due:
                self._write_held()
        self.rows += count

    def _write_held(self) -> None:
        """Write the rows held since the last write and flush them to disk. A write slower than
        SLOW_WRITE holds the next one until nine times its duration has passed, so that writing
        takes a tenth of a run at most (a write takes milliseconds, and every chunk's rows go
        to the file at once; a system of 3,200 anchors, 38,000 variables, takes 4 s a write).
        Each variable's dataset is opened for the write: HDF5 holds 17 kB for each one open."""
        if not self._held:
            return
        began = monotonic()
        assert self._file is not None
        stored = self._file._h5file  # HDF5's datasets: h5netcdf's look their dimensions up
        names = {name for _, rows in self._held for name in rows} - {"time"}
        # time last: a row whose time is written is whole (readers count rows by it)
        for name in (*sorted(names), "time"):
            blocks = [(start, rows[name]) for start, rows in self._held if name in rows]
            if len(blocks) == len(self._held):  # contiguous: one write
                blocks = [(blocks[0][0], np.concatenate([values for _, values in blocks]))]
            dataset = stored[name]
            for start, values in blocks:
                dataset[start : start + len(values), ...] = values
        stored.flush()  # the rows on disk (raw values only)
        self._held = []
        spent = monotonic() - began
        self._due = monotonic() + 9.0 * spent if spent > SLOW_WRITE else 0.0

    def finish(self, status: str, message: str, extra: dict) -> Results:
        self.attrs.update(status=status, status_message=message, **extra)
        if self._file is None:
            return Results(self._dataset(), self.path)
        self._write_held()
        self._file.attrs.update(status=status, status_message=message, **extra)
        self._file.close()
        self._file = None
        assert self.path is not None  # a file is open only with a path
        # read back whole when small; beyond EAGER_BYTES left on disk and read as used, so
        # that a long run's memory stays bounded to its end
        return Results.open(self.path, lazy=self.path.stat().st_size > EAGER_BYTES)

    def _dataset(self) -> xr.Dataset | xr.DataTree:
        """The rows as a Dataset, or as a DataTree when the variables live in groups."""
        groups: dict[str, tuple[dict, dict]] = {"": ({}, {})}
        for path, (dims, units, long_name) in self.variables.items():
            group, name = _split(path)
            sizes = {d: self._size(group, d) for d in dims if d != "time"}
            values = _join(self.chunks[path], dims, sizes)
            data = groups.setdefault(group, ({}, {}))[0]
            data[name] = xr.Variable(dims, values, {"units": units, "long_name": long_name})
        time = xr.Variable(("time",), _join(self.chunks["time"], ("time",), {}))
        time.attrs.update(units="s", long_name="time")
        groups[""][1]["time"] = time
        for path, (dim, values, units, long_name) in self.coords.items():
            group, name = _split(path)
            coords = groups.setdefault(group, ({}, {}))[1]
            coords[name] = xr.Variable((dim,), values, {"units": units, "long_name": long_name})
        if len(groups) == 1:
            data, coords = groups[""]
            return xr.Dataset(data, coords=coords, attrs=self.attrs)
        tree = {
            f"/{group}": xr.Dataset(data, coords=coords) for group, (data, coords) in groups.items()
        }
        tree["/"] = tree["/"].assign_attrs(self.attrs)
        return xr.DataTree.from_dict(tree)


def check_output(path: Path, inputs=()) -> None:
    """Refuse an output path that cannot take results (``files.check_output``): a link, a
    directory, a file the run reads (``inputs``: its case, tables, meshes and databases), a
    name that is not a NetCDF file's, an existing file that is not seacable results, a folder
    that does not exist or cannot be written, a file another run is writing."""
    files.check_output(path, "netcdf", inputs, title=TITLE)


def _allocated() -> dict:
    """h5py's settings of a crash-safe variable (``_Sink``): contiguous, its storage allocated
    and filled with NaN when it is created."""
    plist = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
    plist.set_alloc_time(h5py.h5d.ALLOC_TIME_EARLY)
    return {"fillvalue": np.nan, "fill_time": "alloc", "dcpl": plist}


_ALLOCATED = _allocated()


def _split(path: str) -> tuple[str, str]:
    """("lines/chain", "tension") of "lines/chain/tension"; ("", name) at the top level."""
    group, _, name = path.rpartition("/")
    return group, name


def _group(f, path: str):
    """The group at ``path`` of an open h5netcdf file, created as needed."""
    group = f
    for part in filter(None, path.split("/")):
        group = group.groups[part] if part in group.groups else group.create_group(part)
    return group


def _join(chunks, dims, sizes):
    if chunks:
        return np.concatenate(chunks)
    shape = tuple(0 if d == "time" else sizes[d] for d in dims)
    return np.zeros(shape)
