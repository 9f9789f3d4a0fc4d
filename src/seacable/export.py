"""A run's results for ParaView (``seacable export --vtk``): a VTK file a time (XML
UnstructuredGrid, ``.vtu``) and a collection that orders them (``.pvd``, which ParaView opens
as a time series). Each file holds every line as segments between its nodes, with each
segment's tension (``tension`` [N], cell data; a tie is one segment), and every body with a hull
mesh as its triangles, turned and moved to where the body is (``body``: the body's or line's
number, in ``names`` order). Written as text: readable by any VTK reader (meshio's in the
tests)."""

from pathlib import Path

import numpy as np
import xarray as xr

from seacable import files
from seacable.errors import SeacableError
from seacable.viz import system as vs
from seacable.viz.common import every_rows

LINE, TRIANGLE = 3, 5  # VTK's cell types
MOST_FILES = 10_000


def frames(tree: xr.DataTree, every: float | None) -> np.ndarray:
    """The output rows written: each one, or one every ``every`` seconds (finite rows only)."""
    t = np.asarray(tree["time"].values, dtype=float)[: vs.finite_rows(tree)]
    if every is None or len(t) < 2:
        return np.arange(len(t))
    if not every > 0.0:
        raise SeacableError(f"--every {every:g}: give a positive interval [s]")
    return every_rows(t, every)


def pieces(tree: xr.DataTree, i: int, hulls: dict) -> tuple[np.ndarray, list, list, list]:
    """Output row i as (points, cells as (type, vertex numbers), each cell's tension [N] (NaN
    on a hull), each cell's part number)."""
    points: list[np.ndarray] = []
    cells: list[tuple[int, np.ndarray]] = []
    tension: list[float] = []
    part: list[int] = []
    count = 0
    groups = vs.result_groups(tree, "lines")
    for k, (_, ds) in enumerate(groups.items()):
        x, y = vs.projected(ds, i, "x", "y")
        _, z = vs.projected(ds, i, "x", "z")
        xyz = np.column_stack([x, y, z])
        force = np.atleast_1d(ds["tension"].values[i]) if "tension" in ds else np.zeros(1)
        segments = len(xyz) - 1
        if force.size == segments + 1:  # given at the nodes: the segment's ends' mean
            force = 0.5 * (force[1:] + force[:-1])
        force = np.broadcast_to(force, segments) if force.size == 1 else force
        points.append(xyz)
        cells += [(LINE, np.array([count + j, count + j + 1])) for j in range(segments)]
        tension += [float(v) for v in force]
        part += [k] * segments
        count += len(xyz)
    bodies = vs.result_groups(tree, "bodies")
    for k, (name, mesh) in enumerate(hulls.items()):
        if name not in bodies or "roll" not in bodies[name]:
            continue
        points.append(vs.placed(mesh.vertices, bodies[name], i))
        cells += [(TRIANGLE, count + tri) for tri in mesh.triangles]
        tension += [float("nan")] * len(mesh.triangles)
        part += [len(groups) + k] * len(mesh.triangles)
        count += len(mesh.vertices)
    return (np.vstack(points) if points else np.zeros((0, 3))), cells, tension, part


def _array(name: str, values, kind: str = "Float64", components: int = 1) -> str:
    text = " ".join(f"{v:.9g}" if kind == "Float64" else str(int(v))
                    for v in np.asarray(values).ravel())  # fmt: skip
    return (f'<DataArray type="{kind}" Name="{name}" NumberOfComponents="{components}" '
            f'format="ascii">{text}</DataArray>')  # fmt: skip


def vtu(points: np.ndarray, cells: list, tension: list, part: list) -> str:
    """One UnstructuredGrid file's text."""
    connectivity = np.concatenate([c for _, c in cells]) if cells else np.zeros(0)
    offsets = np.cumsum([len(c) for _, c in cells]) if cells else np.zeros(0)
    return (
        '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
        'byte_order="LittleEndian">\n<UnstructuredGrid>\n'
        f'<Piece NumberOfPoints="{len(points)}" NumberOfCells="{len(cells)}">\n'
        f"<Points>{_array('points', points, components=3)}</Points>\n<Cells>"
        f"{_array('connectivity', connectivity, 'Int64')}{_array('offsets', offsets, 'Int64')}"
        f"{_array('types', [t for t, _ in cells], 'UInt8')}</Cells>\n"
        f'<CellData Scalars="tension">{_array("tension", tension)}'
        f"{_array('part', part, 'Int32')}</CellData>\n"
        "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n"
    )


def _head(path: Path) -> bytes:
    with path.open("rb") as f:
        return f.read(300)


def write(tree: xr.DataTree, output: Path, every: float | None = None,
          inputs=()) -> list[Path]:  # fmt: skip
    """The run's files: ``output`` (the ``.pvd`` collection) and a folder beside it (``output``
    without its suffix, ``_vtk``) of one ``.vtu`` a time written; returns the files written.
    ``inputs``: the files read (the results), which no output may be."""
    files.check_output(output, "collection", inputs)
    picks = frames(tree, every)
    if len(picks) > MOST_FILES:
        raise SeacableError(f"{len(picks):,} output times; export at most {MOST_FILES:,} files: "
                            "give --every SECONDS")  # fmt: skip
    folder = output.with_name(output.stem + "_vtk")
    if folder.is_symlink() or (folder.exists() and not folder.is_dir()):
        raise SeacableError(f"the VTK files' folder '{folder}' (beside output '{output}') is a "
                            "link or a file; remove it or choose another output name")  # fmt: skip
    folder.mkdir(exist_ok=True)
    meshes, _ = vs.scene(tree)
    t = np.asarray(tree["time"].values, dtype=float)
    names = [*vs.result_groups(tree, "lines"), *meshes]
    written, entries = [], []
    for n, i in enumerate(picks):
        path = folder / f"step_{n:05d}.vtu"
        files.replace_text(path, vtu(*pieces(tree, int(i), meshes)))
        written.append(path)
        entries.append(f'<DataSet timestep="{t[i]:.9g}" file="{folder.name}/{path.name}"/>')
    files.replace_text(
        output,
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="1.0">\n'
        f"<!-- parts: {_parts(names)} -->\n"
        "<Collection>\n" + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n",
    )
    return [output, *written]


def _parts(names: list[str]) -> str:
    """The parts' numbers and names, for an XML comment (which cannot hold "--")."""
    return ", ".join(f"{k} {name}".replace("--", "- -") for k, name in enumerate(names))
