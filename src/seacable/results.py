"""Results of a run: an xarray Dataset, written to NetCDF as the run goes.

Dimensions: ``time``, ``segment`` (one per link), ``node`` (links + 1, node 0 at the top).
Every variable carries ``units`` and ``long_name``; the attributes carry provenance and the
``status`` of the run (``complete``, ``diverged``, ``interrupted``, or ``incomplete`` while it
runs or if the process died) with its ``status_message``.
"""

import datetime as _dt
from pathlib import Path

import h5netcdf
import numpy as np
import xarray as xr

STATUS_COMPLETE = "complete"
STATUS_DIVERGED = "diverged"
STATUS_INTERRUPTED = "interrupted"
STATUS_INCOMPLETE = "incomplete"


def provenance(case_text: str, solver: dict) -> dict:
    from seacable import __version__

    attrs = {
        "title": "seacable simulation results",
        "seacable_version": __version__,
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "case": case_text,
        "status": STATUS_INCOMPLETE,
        "status_message": "the run has not finished (still running, or the process was killed)",
        "conventions": "SI units; x horizontal, z up, z = 0 at the still-water surface",
    }
    attrs.update({f"solver_{k}": v for k, v in solver.items()})
    return attrs


class Results:
    """The outcome of :func:`seacable.simulate`: the dataset, its status and message. A system
    of bodies and lines gives a DataTree (``xarray.open_datatree``) with a group per body
    (``bodies/<name>``) and per line (``lines/<name>``); ``results["lines/chain/tension"]``."""

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

    def to_netcdf(self, path) -> None:
        self.dataset.to_netcdf(path, engine="h5netcdf")

    @classmethod
    def open(cls, path, lazy: bool = False) -> "Results":
        """Read results written by seacable (complete or not). ``lazy`` keeps the file open and
        reads a variable, or the part of it asked for, only when it is used (long runs)."""
        with h5netcdf.File(path, "r") as f:
            grouped = bool(f.groups)
        opener = xr.open_datatree if grouped else xr.open_dataset
        if lazy:
            return cls(opener(path, engine="h5netcdf"), Path(path))
        with opener(path, engine="h5netcdf") as ds:
            return cls(ds.load(), Path(path))


class _Sink:
    """Where output rows go: in memory, or also appended to a NetCDF file as they come."""

    def __init__(self, path, sizes: dict, coords: dict, variables: dict, attrs: dict):
        """``sizes`` maps each dimension but time to its length; ``coords`` maps name ->
        (dim, values, units, long_name); ``variables`` maps name -> (dims, units, long_name)."""
        self.path = None if path is None else Path(path)
        self.sizes = sizes
        self.coords = coords
        self.variables = variables
        self.attrs = dict(attrs)
        self.chunks: dict[str, list[np.ndarray]] = {name: [] for name in ("time", *variables)}
        self.rows = 0
        self._file = None
        if self.path is not None:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._file = self._create()

    def _create(self):
        f = h5netcdf.File(self.path, "w")
        f.dimensions = {"time": None}
        # every group of time rows has its own unlimited time dimension (the root's time
        # coordinate applies to it): a reader sizes an unlimited dimension by visiting every
        # variable that uses it, once per variable it opens; one dimension shared by the
        # hundreds of variables of a system made opening a four-cable result take 15 s
        self.timed = sorted({_split(path)[0] for path, (dims, _, _) in self.variables.items()
                             if "time" in dims} - {""})  # fmt: skip
        for group in self.timed:
            _group(f, group).dimensions["time"] = None
        for path, size in self.sizes.items():  # a system's are per group: "lines/chain/node"
            group, dim = _split(path)
            _group(f, group).dimensions[dim] = size
        for path, (dim, values, units, long_name) in self.coords.items():
            group, name = _split(path)
            v = _group(f, group).create_variable(name, (dim,), float, data=values)
            v.attrs.update(units=units, long_name=long_name)
        t = f.create_variable("time", ("time",), float, chunks=(1024,))
        t.attrs.update(units="s", long_name="time", standard_name="time")
        for path, (dims, units, long_name) in self.variables.items():
            group, name = _split(path)
            shape = tuple(1024 if d == "time" else self._size(group, d) for d in dims)
            v = _group(f, group).create_variable(
                name, dims, float, chunks=tuple(min(s, 1024) for s in shape)
            )
            v.attrs.update(units=units, long_name=long_name)
        f.attrs.update(self.attrs)
        f.flush()
        return f

    def _size(self, group: str, dim: str) -> int:
        return self.sizes[f"{group}/{dim}" if group else dim]

    def write(self, rows: dict) -> None:
        """Append ``rows`` (name -> values, time first); names the case does not record (a
        model's rows hold all its variables) are left out."""
        count = len(rows["time"])
        if count == 0:
            return
        rows = {name: values for name, values in rows.items() if name in self.chunks}
        for name, values in rows.items():
            self.chunks[name].append(np.array(values, copy=True))
        if self._file is not None:
            start = self.rows
            self._file.resize_dimension("time", start + count)
            for group in self.timed:
                _group(self._file, group).resize_dimension("time", start + count)
            for name, values in rows.items():
                self._file[name][start : start + count, ...] = values
            self._file.flush()
        self.rows += count

    def finish(self, status: str, message: str, extra: dict) -> Results:
        self.attrs.update(status=status, status_message=message, **extra)
        if self._file is not None:
            self._file.attrs.update(status=status, status_message=message, **extra)
            self._file.close()
            self._file = None
        return Results(self._dataset(), self.path)

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
