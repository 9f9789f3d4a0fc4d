"""Pictures of a system of bodies and lines (a DataTree: ``bodies/<name>``, ``lines/<name>``):
elevation and plan views of every line and body at a few times, with the water surface and the
seabed; a range graph of each line's tension along its length (least, mean and largest over the
run, as OrcaFlex draws them); end tensions, body positions and rotations over time. Only finite
rows set the axes, so a diverged run still draws what it computed.

Animations draw each body with a hull mesh as its outline (the convex hull of its vertices
projected on the view, turned and moved with the body) and, in elevation, the incident waves'
surface along y = 0, both rebuilt from the case the results keep (``results.restore_case``);
the other bodies are drawn as their reference point."""

import logging
import math
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from seacable import files, packing
from seacable.case.loader import load_case
from seacable.kernels import waves
from seacable.meshes import Mesh
from seacable.results import restore_case
from seacable.system.hulls import body_mesh
from seacable.viz.common import (
    _finish,
    _frame_indices,
    _gif_stream,
    _progress,
    _pyplot,
    _snapshot_indices,
    check_frames,
    save,
)


def _times(tree: xr.DataTree) -> np.ndarray:
    return tree.to_dataset()["time"].values


def result_groups(tree: xr.DataTree, kind: str) -> dict[str, xr.Dataset]:
    """Each group of ``kind`` ("lines" or "bodies") of a run's results, by name (for the
    pictures, the report and the VTK export alike)."""
    if kind not in tree.children:
        return {}
    return {name: node.to_dataset() for name, node in tree[kind].children.items()}


def projected(ds: xr.Dataset, i: int, a: str, b: str):
    """Two coordinates of a line's points at output i: its nodes, or a tie's two ends."""
    if f"node_{a}" in ds:
        return ds[f"node_{a}"].values[i], ds[f"node_{b}"].values[i]
    return (
        np.array([ds[f"from_{a}"].values[i], ds[f"to_{a}"].values[i]]),
        np.array([ds[f"from_{b}"].values[i], ds[f"to_{b}"].values[i]]),
    )


def _environment(tree: xr.DataTree) -> dict:
    try:
        case = yaml.safe_load(tree.attrs.get("case", "")) or {}
    except yaml.YAMLError:
        return {}
    env = case.get("environment", {}) if isinstance(case, dict) else {}
    return env if isinstance(env, dict) else {}


def finite_rows(tree: xr.DataTree) -> int:
    """Rows up to the last one whose every line node is finite (a diverged run's last rows may
    hold NaN)."""
    times = _times(tree)
    last = len(times)
    for ds in result_groups(tree, "lines").values():
        for name in ("node_x", "node_z", "from_x"):
            if name in ds:
                finite = np.isfinite(ds[name].values.reshape(len(times), -1)).all(axis=1)
                bad = np.flatnonzero(~finite)
                if bad.size:
                    last = min(last, int(bad[0]))
    return last


def _draw_view(ax, tree, rows, a: str, b: str, plt, env: dict) -> None:
    lines, bodies = result_groups(tree, "lines"), result_groups(tree, "bodies")
    times = _times(tree)
    cmap = plt.get_cmap("viridis")
    for k, i in enumerate(rows):
        color = cmap(k / max(len(rows) - 1, 1))
        for ds in lines.values():
            h, v = projected(ds, i, a, b)
            ax.plot(h, v, "-", color=color, lw=1.0)
    for name, ds in bodies.items():
        h, v = ds[f"position_{a}"].values[rows], ds[f"position_{b}"].values[rows]
        ax.plot(h, v, "s", ms=4, mfc="none", color="k")
        ax.annotate(name, (h[-1], v[-1]), fontsize=7, xytext=(3, 3),
                    textcoords="offset points")  # fmt: skip
    if b == "z":
        ax.axhline(0.0, color="tab:blue", lw=0.8, ls="--", label="water surface")
        depth = env.get("water_depth")
        if isinstance(depth, int | float):
            ax.axhline(-float(depth), color="saddlebrown", lw=1.2, label="seabed")
        ax.legend(fontsize=7, loc="best")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"{a} [m]")
    ax.set_ylabel(f"{b} [m]")
    view = "elevation" if b == "z" else "plan"
    span = f"{times[rows[0]]:.3g} to {times[rows[-1]]:.3g} s" if len(rows) else "no rows"
    ax.set_title(f"{view}, {len(rows)} snapshots from {span}")
    if len(rows):
        sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(times[rows[0]], times[rows[-1]]))
        plt.colorbar(sm, ax=ax, label="time [s]")


def tension_ranges(tree: xr.DataTree, last: int) -> dict[str, tuple]:
    """Each line's range graph over the first ``last`` rows: the arc length [m] from its
    'from' end of the segments' centres (or of the nodes, for a line that gives its tension
    there), and the least, mean and largest tension [N] there."""
    out = {}
    for name, ds in result_groups(tree, "lines").items():
        if "tension" not in ds or ds["tension"].ndim != 2:
            continue
        tension = ds["tension"].values[:last]
        arc = ds["arc_length"].values
        centres = 0.5 * (arc[1:] + arc[:-1]) if tension.shape[1] == arc.size - 1 else arc
        out[name] = (centres, tension.min(axis=0), tension.mean(axis=0), tension.max(axis=0))
    return out


def bending_lines(attrs) -> list[str]:
    """The lines of the results' case (``attrs``: its ``case_resolved``) with a section whose
    line type has a bending stiffness."""
    try:
        case = yaml.safe_load(str(attrs.get("case_resolved", ""))) or {}
    except yaml.YAMLError:
        return []
    if not isinstance(case, dict):
        return []
    stiff = {t.get("name") for t in case.get("line_types", []) or []
             if isinstance(t, dict) and _positive(t.get("bending_stiffness"))}  # fmt: skip
    return [str(line.get("name")) for line in case.get("lines", []) or []
            if isinstance(line, dict)
            and any(isinstance(p, dict) and p.get("type") in stiff
                    for p in line.get("sections", []) or [])]  # fmt: skip


def _positive(value) -> bool:
    try:
        return float(value) > 0.0
    except (TypeError, ValueError):
        return False


def curvature_ranges(tree: xr.DataTree, last: int, names) -> dict[str, tuple]:
    """The range graph of the curvature of the lines ``names`` over the first ``last`` rows:
    the arc length [m] of their inner nodes and the least, mean and largest curvature [1/m]
    there, the angle between the segments each side over their mean length."""
    out = {}
    groups = result_groups(tree, "lines")
    for name in names:
        ds = groups.get(name)
        if ds is None or "node_x" not in ds or ds["node_x"].shape[1] < 3:
            continue
        nodes = np.stack([ds[f"node_{c}"].values[:last] for c in "xyz"], axis=-1)
        step = np.diff(nodes, axis=1)
        length = np.linalg.norm(step, axis=-1)
        unit = step / np.where(length > 0.0, length, 1.0)[..., None]
        cosine = np.clip((unit[:, 1:] * unit[:, :-1]).sum(axis=-1), -1.0, 1.0)
        kappa = np.arccos(cosine) / (0.5 * (length[:, 1:] + length[:, :-1]))
        arc = ds["arc_length"].values[1:-1] if "arc_length" in ds else np.arange(kappa.shape[1])
        out[name] = (arc, kappa.min(axis=0), kappa.mean(axis=0), kappa.max(axis=0))
    return out


def _draw_range(ax, tree, last: int) -> None:
    """Least, mean and largest tension [kN] along each line over the finite rows (at the
    segments' centres, or at the nodes for a line that gives it there)."""
    drawn = False
    colours = {}
    for name, (centres, least, mean, largest) in tension_ranges(tree, last).items():
        (line,) = ax.plot(centres, mean / 1e3, label=f"{name} mean")
        ax.fill_between(centres, least / 1e3, largest / 1e3, alpha=0.25,
                        color=line.get_color(), label=f"{name} least to largest")  # fmt: skip
        colours[name] = line.get_color()
        drawn = True
    ax.set_xlabel("arc length from the 'from' end [m]")
    ax.set_ylabel("tension [kN]")
    ax.set_title("tension range along each line")
    bent = curvature_ranges(tree, last, bending_lines(tree.attrs))
    if bent:  # the curvature of the lines that bend, on the right
        right = ax.twinx()
        for name, (arc, _, mean, largest) in bent.items():
            right.plot(
                arc, largest, ":", color=colours.get(name), label=f"{name} largest curvature"
            )
            right.plot(arc, mean, "-.", color=colours.get(name), label=f"{name} mean curvature")
        right.set_ylabel("curvature [1/m]")
        right.legend(fontsize=7, loc="upper right")
        ax.set_title("tension and curvature range along each line")
    if drawn:
        ax.legend(fontsize=7, loc="upper left" if bent else "best")
    else:
        _empty(ax, "no lines in this system")


def _draw_end_tensions(ax, tree, last: int) -> None:
    t = _times(tree)[:last]
    for name, ds in result_groups(tree, "lines").items():
        for end in ("from", "to"):
            parts = [f"{end}_force_{c}" for c in "xyz"]
            if all(p in ds for p in parts):
                force = np.linalg.norm(np.stack([ds[p].values[:last] for p in parts]), axis=0)
                ax.plot(t, force / 1e3, label=f"{name}, '{end}' end")
        if "tension" in ds and ds["tension"].ndim == 1:
            ax.plot(t, ds["tension"].values[:last] / 1e3, label=f"{name} (tie)")
    _finish(ax, "force of each line on its end points", "[kN]")
    if not ax.lines:
        _empty(ax, "no lines in this system")


def _empty(ax, why: str) -> None:
    """A panel with nothing to draw, saying why."""
    ax.text(0.5, 0.5, why, ha="center", va="center", transform=ax.transAxes)


def _draw_bodies(ax, tree, last: int, what: str) -> None:
    t = _times(tree)[:last]
    for name, ds in result_groups(tree, "bodies").items():
        if what == "position" and "velocity_x" in ds:  # bodies that move
            for c in "xyz":
                values = ds[f"position_{c}"].values[:last]
                if np.ptp(values) > 0:
                    ax.plot(t, values, label=f"{name} {c}")
        if what == "angle" and "angular_velocity_x" in ds:
            for angle in ("roll", "pitch", "yaw"):
                values = ds[angle].values[:last]
                if np.ptp(values) > 0:
                    ax.plot(t, values, label=f"{name} {angle}")
    if what == "position":
        _finish(ax, "positions of the bodies that move", "[m]")
    else:
        _finish(ax, "rotations of the rigid bodies", "[degree]")
    if not ax.lines:
        _empty(ax, "nothing moves here")


def _title(tree: xr.DataTree) -> str:
    name = "seacable results"
    for line in str(tree.attrs.get("case", "")).splitlines():
        if line.startswith("name:"):
            name = line.split(":", 1)[1].strip()
    status = tree.attrs.get("status", "?")
    return name if status == "complete" else f"{name} [{status}]"


def plot_system(tree: xr.DataTree, path, every: float | None = None) -> Path:
    """The picture of a system's results (module docstring)."""
    plt = _pyplot()
    last = finite_rows(tree)
    times = _times(tree)[:last]
    rows = _snapshot_indices(times, every if every is not None else None)
    if len(rows) > 12:
        rows = rows[np.unique(np.linspace(0, len(rows) - 1, 12).round().astype(int))]
    env = _environment(tree)
    fig, axes = plt.subplots(2, 3, figsize=(18, 10), constrained_layout=True)
    _draw_view(axes[0, 0], tree, rows, "x", "z", plt, env)
    _draw_view(axes[0, 1], tree, rows, "x", "y", plt, env)
    _draw_range(axes[0, 2], tree, last)
    _draw_end_tensions(axes[1, 0], tree, last)
    _draw_bodies(axes[1, 1], tree, last, "position")
    _draw_bodies(axes[1, 2], tree, last, "angle")
    fig.suptitle(_title(tree))
    return save(fig, path)


log = logging.getLogger("seacable")


def scene(tree: xr.DataTree) -> tuple[dict[str, Mesh], dict]:
    """The hull (a Mesh, body frame [m]) of each body with a mesh, and the incident waves
    (``wave``, ``wave_depth``: kernels.waves) of the case the results keep; none of either,
    logged, when that case cannot be rebuilt."""
    try:
        with tempfile.TemporaryDirectory() as folder:
            case = load_case(restore_case(tree.attrs, folder))
            hulls = {body.name: body_mesh(body, folder, f"bodies[{k}]")
                     for k, body in enumerate(case.bodies)
                     if getattr(body, "mesh", None) is not None}  # fmt: skip
        return hulls, packing.wave_fields(case.environment, case.simulation.build_up)
    except Exception as exc:  # an old or hand-made file: bodies as points, a flat surface
        log.warning("animation: hulls and waves not drawn (the results' case cannot be "
                    "rebuilt: %s)", exc)  # fmt: skip
        return {}, {}


def placed(vertices: np.ndarray, ds: xr.Dataset, i: int) -> np.ndarray:
    """A body's ``vertices`` (body frame) at output i: turned by R = Rz(yaw) Ry(pitch) Rx(roll)
    and moved to the body's position (``ds``: its results)."""
    from scipy.spatial.transform import Rotation

    angles = [float(ds[name].values[i]) for name in ("roll", "pitch", "yaw")]
    turn = Rotation.from_euler("xyz", angles, degrees=True).as_matrix()
    return vertices @ turn.T + [float(ds[f"position_{c}"].values[i]) for c in "xyz"]


def _outline(vertices: np.ndarray, ds: xr.Dataset, i: int, a: str, b: str):
    """The outline of a hull (body-frame ``vertices``) in the view (a, b) at output i: the
    convex hull of its vertices turned by R = Rz(yaw) Ry(pitch) Rx(roll) and moved to the
    body's position."""
    from scipy.spatial import ConvexHull

    axes = ["xyz".index(a), "xyz".index(b)]
    points = placed(vertices, ds, i)[:, axes]
    if not np.isfinite(points).all():
        return [], []
    ring = ConvexHull(points).vertices
    ring = np.append(ring, ring[0])
    return points[ring, 0], points[ring, 1]


def _extent(tree: xr.DataTree, frames, a: str) -> tuple[float, float]:
    low, high = math.inf, -math.inf
    for ds in result_groups(tree, "lines").values():
        for name in (f"node_{a}", f"from_{a}", f"to_{a}"):
            if name in ds:
                values = ds[name].values[frames]
                values = values[np.isfinite(values)]
                if values.size:
                    low, high = min(low, float(values.min())), max(high, float(values.max()))
    for ds in result_groups(tree, "bodies").values():
        values = ds[f"position_{a}"].values[frames]
        values = values[np.isfinite(values)]
        if values.size:
            low, high = min(low, float(values.min())), max(high, float(values.max()))
    if not math.isfinite(low):
        return -1.0, 1.0
    return low, high


def animate_system(
    tree: xr.DataTree,
    path,
    fps: int = 20,
    speed: float = 1.0,
    every: float | None = None,
    max_frames: int = 600,
    progress: bool = True,
) -> Path:
    """Animate a system in plan and elevation to a GIF, one frame at a time: ``fps`` frames per
    second showing ``speed`` s of results each second (or one frame every ``every`` s of
    results), at most ``max_frames``; ``progress``: a progress bar."""
    plt = _pyplot()
    path = Path(path)
    files.check_output(path, "animation")
    check_frames(fps, speed, every, max_frames)
    last = finite_rows(tree)
    times = _times(tree)[: max(last, 1)]
    frames = _frame_indices(times, every if every is not None else speed / fps, max_frames)
    env = _environment(tree)
    lines, bodies = result_groups(tree, "lines"), result_groups(tree, "bodies")
    meshes, sea = scene(tree)
    hulls = {name: mesh.vertices for name, mesh in meshes.items()}
    reach = max((float(np.abs(v).max()) for v in hulls.values()), default=0.0)
    fig, axes = plt.subplots(1, 2, figsize=(14, 6))
    artists: list[tuple] = []
    surface = None
    for ax, (a, b) in zip(axes, (("x", "y"), ("x", "z")), strict=True):
        (h0, h1), (v0, v1) = _extent(tree, frames, a), _extent(tree, frames, b)
        h0, h1, v0, v1 = h0 - reach, h1 + reach, v0 - reach, v1 + reach
        if b == "z":
            v1 = max(v1, 0.0)
        pad = 0.05 * max(h1 - h0, v1 - v0, 1.0)
        ax.set_xlim(h0 - pad, h1 + pad)
        ax.set_ylim(v0 - pad, v1 + pad)
        ax.set_aspect("equal")
        ax.set_xlabel(f"{a} [m]")
        ax.set_ylabel(f"{b} [m]")
        if b == "z":
            ax.axhline(0.0, color="tab:blue", lw=0.8, ls="--")
            if sea and sea["wave"].shape[1] > 0:
                along = np.linspace(h0 - pad, h1 + pad, 400)
                (surface,) = ax.plot([], [], color="tab:blue", lw=1.0)
            depth = env.get("water_depth")
            if isinstance(depth, int | float):
                ax.axhline(-float(depth), color="saddlebrown", lw=1.2)
        for ds in lines.values():
            (artist,) = ax.plot([], [], "k.-", lw=1.2, ms=2)
            artists.append((artist, ds, a, b, None))
        for name, ds in bodies.items():
            if name in hulls and "roll" in ds:
                (artist,) = ax.plot([], [], "-", lw=1.2, color="tab:red")
            else:
                (artist,) = ax.plot([], [], "s", ms=5, mfc="none", color="tab:red")
            artists.append((artist, ds, a, b, hulls.get(name) if "roll" in ds else None))
    label = fig.suptitle("")
    title = _title(tree)
    writer = _gif_stream(fps)
    with files.replacing(path) as aside, writer.saving(fig, aside, dpi=80):
        for i in _progress(frames, progress, path.name):
            for artist, ds, a, b, hull in artists:
                if hull is not None:
                    artist.set_data(*_outline(hull, ds, int(i), a, b))
                elif f"position_{a}" in ds:
                    artist.set_data([ds[f"position_{a}"].values[i]],
                                    [ds[f"position_{b}"].values[i]])  # fmt: skip
                else:
                    artist.set_data(*projected(ds, int(i), a, b))
            if surface is not None:
                eta = [waves.elevation_at(sea["wave"], float(times[i]), x, 0.0) for x in along]
                surface.set_data(along, eta)
            label.set_text(f"{title}  t = {times[i]:.2f} s")
            writer.grab_frame()
    plt.close(fig)
    return path
