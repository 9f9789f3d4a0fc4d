"""Pictures of results: cable snapshots in one frame (as in the thesis), time series, animation.

matplotlib is imported lazily with the non-interactive Agg backend, so importing seacable
configures nothing.
"""

import logging
import shutil
from io import BytesIO
from pathlib import Path

import numpy as np
import xarray as xr

log = logging.getLogger(__name__)


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _snapshot_indices(times: np.ndarray, every: float | None) -> np.ndarray:
    if len(times) == 0:
        return np.array([], dtype=int)
    if every is None:
        every = max((times[-1] - times[0]) / 30.0, 1e-12)
    targets = np.arange(times[0], times[-1] + 1e-9, every)
    return np.unique(np.searchsorted(times, targets - 1e-9).clip(0, len(times) - 1))


def _draw_snapshots(ax, ds: xr.Dataset, every: float | None, plt) -> None:
    times = ds["time"].values
    idx = _snapshot_indices(times, every)
    cmap = plt.get_cmap("viridis")
    for k, i in enumerate(idx):
        color = cmap(k / max(len(idx) - 1, 1))
        ax.plot(ds["node_x"].values[i], ds["node_z"].values[i], "-", color=color, lw=1.0)
    if len(idx):
        first, last = idx[0], idx[-1]
        ax.plot(ds["node_x"].values[first, -1], ds["node_z"].values[first, -1], "ko", ms=5)
        ax.plot(ds["node_x"].values[last, -1], ds["node_z"].values[last, -1], "kx", ms=7)
    ax.axhline(0.0, color="tab:blue", lw=0.8, ls="--")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    status = ds.attrs.get("status", "?")
    ax.set_title(f"cable every {every or (times[-1] - times[0]) / 30:.3g} s (o start, x end)"
                 + ("" if status == "complete" else f" [{status}]"))  # fmt: skip
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(times[0], times[-1]))
    plt.colorbar(sm, ax=ax, label="time [s]")


def plot_results(ds: xr.Dataset, path, every: float | None = None) -> Path:
    """Cable snapshots and time series of the variables the results hold: link angles, end
    positions, tensions, attachment forces, energies (3D results: plan and side views instead
    of snapshots and angles; a trajectory case its tracking error). A panel whose variables a
    result lacks says so instead of failing."""
    if "cable" in ds.dims:
        return _plot_star(ds, path, every)
    if "node_y" in ds:
        return _plot_3d(ds, path, every)
    if "strain" in ds:
        return _plot_string(ds, path, every)
    plt = _pyplot()
    fig, axes = plt.subplots(2, 3, figsize=(18, 9), constrained_layout=True)
    _draw_snapshots(axes[0, 0], ds, every, plt)
    _draw_angles(axes[0, 1], ds)
    t = ds["time"].values
    ends = {"bottom end x": _node(ds, "x", -1), "bottom end z": _node(ds, "z", -1)}
    ends["top z"] = ds["top_heave"].values if "top_heave" in ds else None
    _draw_series(axes[0, 2], t, ends, "end positions", "[m]")
    _draw_tension(axes[1, 0], ds, ("top link", "middle link", "bottom link"))
    forces = {name: _values(ds, name) for name in
              ("top_force_x", "top_force_z", "bottom_force_x", "bottom_force_z")}  # fmt: skip
    _draw_series(axes[1, 1], t, forces, "force of the cable on its attachments", "[N]")
    _draw_energy(axes[1, 2], ds)
    return _save(fig, ds, path, plt)


def _values(ds: xr.Dataset, name: str):
    """The values of variable ``name``, or None when the results do not hold it."""
    return ds[name].values if name in ds else None


def _node(ds: xr.Dataset, axis: str, node: int):
    """Coordinate ``axis`` [m] of node ``node`` over time, or None."""
    name = f"node_{axis}"
    return ds[name].values[:, node] if name in ds else None


def _norm(ds: xr.Dataset, prefix: str):
    """Magnitude over time of the vector variables ``prefix_x/y/z``, or None if one is absent."""
    parts = [_values(ds, f"{prefix}_{a}") for a in "xyz"]
    if any(p is None for p in parts):
        return None
    return np.linalg.norm(np.stack(parts), axis=0)


def _draw_series(ax, t, series: dict, title: str, ylabel: str) -> None:
    """Plot the series that exist (None marks an absent variable); say so if none does."""
    present = {label: v for label, v in series.items() if v is not None}
    for label, values in present.items():
        ax.plot(t, values, label=label)
    _finish(ax, title, ylabel)
    if not present:
        ax.text(0.5, 0.5, "not in these results", ha="center", va="center",
                transform=ax.transAxes)  # fmt: skip


def _draw_tension(ax, ds: xr.Dataset, labels) -> None:
    """Tension [N] of the first, middle and last link or segment."""
    series = dict.fromkeys(labels)
    if "tension" in ds:
        tension = ds["tension"].values
        for label, j in zip(labels, (0, tension.shape[1] // 2, -1), strict=True):
            series[label] = tension[:, j]
    _draw_series(ax, ds["time"].values, series, "tension", "tension [N]")


def _plot_string(ds: xr.Dataset, path, every: float | None) -> Path:
    """Natural-variables string: snapshots, the end mass's path, strain and energy."""
    plt = _pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(13, 9), constrained_layout=True)
    _draw_snapshots(axes[0, 0], ds, every, plt)
    ax = axes[0, 1]
    if "end_x" in ds and "end_z" in ds:
        ax.plot(ds["end_x"].values, ds["end_z"].values, "k-", lw=1.0)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("path of the end mass")
    t = ds["time"].values
    strain = ds["strain"].values
    series = {label: strain[:, j] for label, j in
              (("pivot", 0), ("middle", strain.shape[1] // 2), ("end mass", -1))}  # fmt: skip
    _draw_series(axes[1, 0], t, series, "axial strain", "[-]")
    _draw_energy(axes[1, 1], ds)
    return _save(fig, ds, path, plt)


def _follows_trajectory(ds: xr.Dataset) -> bool:
    """True when the results are of a case whose lower end follows a target trajectory."""
    names = ("tracking_error", "target_x", "target_y", "target_z")
    return all(n in ds for n in names) and bool(np.any(np.isfinite(ds["tracking_error"].values)))


def _end_is_fixed(ds: xr.Dataset) -> bool:
    """True when the lower end does not move (an anchor): its force is then the story."""
    ends = [ds[f"node_{a}"].values[:, -1] for a in "xyz"]
    return max(float(np.ptp(e)) for e in ends) < 1e-9 if len(ends[0]) else True


def _plot_3d(ds: xr.Dataset, path, every: float | None) -> Path:
    plt = _pyplot()
    fig, axes = plt.subplots(2, 3, figsize=(18, 10), constrained_layout=True)
    times = ds["time"].values
    idx = _snapshot_indices(times, every)
    cmap = plt.get_cmap("viridis")
    x, y, z = (ds[f"node_{a}"].values for a in "xyz")
    for ax, (h, v, hl, vl, title) in zip(
        axes[0, :2],
        ((x, y, "x [m]", "y [m]", "plan view (top end's track dashed)"),
         (x, z, "x [m]", "z [m]", "side view")),
        strict=True,
    ):  # fmt: skip
        for k, i in enumerate(idx):
            ax.plot(h[i], v[i], "-", color=cmap(k / max(len(idx) - 1, 1)), lw=1.0)
        ax.plot(h[:, 0], v[:, 0], "k--", lw=0.8)
        ax.set_xlabel(hl)
        ax.set_ylabel(vl)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(title)
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(times[0], times[-1]))
    plt.colorbar(sm, ax=axes[0, 1], label="time [s]")
    top = {f"force {a}": -v if (v := _values(ds, f"top_force_{a}")) is not None else None
           for a in "xyz"}  # fmt: skip
    top["magnitude (tension at the top)"] = _norm(ds, "top_force")
    _draw_series(axes[0, 2], times, top, "force at the top attachment on the cable", "[N]")
    _draw_tension(axes[1, 0], ds, ("top segment", "middle segment", "bottom segment"))
    bottom = {f"force {a}": _values(ds, f"bottom_force_{a}") for a in "xyz"}
    bottom["magnitude"] = _norm(ds, "bottom_force")
    if _follows_trajectory(ds):
        _draw_series(axes[1, 1], times, bottom, "force of the cable on the vehicle (lower end)",
                     "[N]")  # fmt: skip
        _draw_tracking_error(axes[1, 2], ds)
        return _save(fig, ds, path, plt)
    if _end_is_fixed(ds):
        _draw_series(axes[1, 1], times, bottom, "force of the cable on its anchor (lower end)",
                     "[N]")  # fmt: skip
    else:
        lower = {"bottom end z [m]": z[:, -1],
                 "bottom end vertical speed [m/s]": _values(ds, "bottom_velocity_z")}  # fmt: skip
        speed = _norm(ds, "top_velocity")
        if speed is not None and np.any(speed > 0):
            lower["tow speed [m/s]"] = speed
        _draw_series(axes[1, 1], times, lower, "lower end: elevation and speed", "[m], [m/s]")
    _draw_energy(axes[1, 2], ds)
    return _save(fig, ds, path, plt)


def _draw_tracking_error(ax, ds: xr.Dataset) -> None:
    """Distance of the lower end from its target over the largest displacement of the target
    relative to the top end (in metres when the target has not moved relative to it)."""
    times = ds["time"].values
    error = ds["tracking_error"].values
    relative = np.stack([ds[f"target_{a}"].values - ds[f"node_{a}"].values[:, 0] for a in "xyz"])
    largest = float(np.max(np.linalg.norm(relative - relative[:, :1], axis=0)))
    if largest < 1e-6:
        ax.semilogy(times, np.maximum(error, 1e-16), label="target fixed relative to the top")
        _finish(ax, "position error", "[m]")
        return
    ax.semilogy(times, np.maximum(error / largest, 1e-16),
                label=f"largest displacement {largest:.3g} m")  # fmt: skip
    _finish(ax, "position error / largest displacement", "[-]")


def _plot_star(ds: xr.Dataset, path, every: float | None) -> Path:
    """Several cables on a shared body: side and plan views, the body's rise, anchor tensions."""
    plt = _pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(14, 10), constrained_layout=True)
    times = ds["time"].values
    idx = _snapshot_indices(times, every)
    cmap = plt.get_cmap("viridis")
    x, y, z = (ds[f"node_{a}"].values for a in "xyz")  # (time, cable, node)
    for ax, (h, v, hl, vl, title) in zip(
        axes[0],
        ((x, z, "x [m]", "z [m]", "side view: successive shapes"),
         (x, y, "x [m]", "y [m]", "plan view")),
        strict=True,
    ):  # fmt: skip
        for k, i in enumerate(idx):
            color = cmap(k / max(len(idx) - 1, 1))
            for c in range(h.shape[1]):
                ax.plot(h[i, c], v[i, c], "-", color=color, lw=0.9)
        ax.set_xlabel(hl)
        ax.set_ylabel(vl)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(title)
    axes[0, 0].axhline(0.0, color="tab:blue", lw=0.8, ls="--")
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(times[0], times[-1]))
    plt.colorbar(sm, ax=axes[0, 1], label="time [s]")
    body = {"body elevation z [m]": _values(ds, "body_z"),
            "body vertical speed [m/s]": _values(ds, "body_velocity_z")}  # fmt: skip
    _draw_series(axes[1, 0], times, body, "time law of the body", "[m], [m/s]")
    tension = _norm(ds, "top_force")
    anchors = {} if tension is None else {f"cable {c}": tension[:, c] for c in range(x.shape[1])}
    _draw_series(axes[1, 1], times, anchors, "tension at the anchors (top ends)", "[N]")
    return _save(fig, ds, path, plt)


def _draw_angles(ax, ds: xr.Dataset) -> None:
    """Every link's angle for short cables (as the thesis's figure 6.1), else a selection."""
    if "angle" not in ds:
        _draw_series(ax, ds["time"].values, {}, "link angles from the downward vertical", "[deg]")
        return
    angles = np.degrees(ds["angle"].values)
    n = angles.shape[1]
    links = range(n) if n <= 12 else np.unique(np.linspace(0, n - 1, 7).round().astype(int))
    for i in links:
        ax.plot(ds["time"].values, angles[:, i], lw=1.0, label=f"link {i}")
    _finish(ax, "link angles from the downward vertical", "[deg]")


def _finish(ax, title: str, ylabel: str) -> None:
    ax.set_xlabel("time [s]")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)


def _save(fig, ds: xr.Dataset, path, plt) -> Path:
    fig.suptitle(_title(ds))
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def _draw_energy(ax, ds: xr.Dataset) -> None:
    names = ("kinetic_energy", "gravity_potential_energy", "elastic_energy", "total_energy")
    series = {name.replace("_", " "): _values(ds, name) for name in names}
    _draw_series(ax, ds["time"].values, series, "energy", "[J]")


def _title(ds: xr.Dataset) -> str:
    case = ds.attrs.get("case", "")
    for line in case.splitlines():
        if line.startswith("name:"):
            return line.split(":", 1)[1].strip()
    return "seacable results"


def animate_results(
    ds: xr.Dataset,
    path,
    fps: int = 20,
    speed: float = 1.0,
    every: float | None = None,
    max_frames: int = 600,
    progress: bool = True,
) -> Path:
    """Animate the cable to a GIF (Pillow) or MP4 (needs ffmpeg on the PATH).

    One frame every ``every`` simulated seconds (default ``speed / fps``: ``speed`` simulated
    seconds per second of video), at most ``max_frames`` frames, taken evenly over the run when
    more are asked (a log line says so). Frames are drawn and written one at a time, each reading
    its own time from ``ds``, so memory does not grow with the number of frames and a dataset
    opened lazily is never read whole. A progress bar on stderr when ``progress``.
    """
    plt = _pyplot()
    from matplotlib import animation

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ValueError(f"animation file '{path}': use a .gif or .mp4 name")
    if suffix == ".mp4" and shutil.which("ffmpeg") is None:
        raise ValueError("writing .mp4 needs ffmpeg on the PATH; write a .gif instead")
    if "cable" in ds.dims:
        raise ValueError("animations of several cables are not available yet; use 'plot'")
    check_frames(fps, speed, every, max_frames)
    times = ds["time"].values
    frames = _frame_indices(times, every if every is not None else speed / fps, max_frames)
    views = [("node_x", "node_z", "x [m]", "z [m]")]
    if "node_y" in ds:
        views = [("node_x", "node_y", "x [m]", "y [m]"), *views]
    fig, axes = plt.subplots(1, len(views), figsize=(7 * len(views), 6), squeeze=False)
    lines = []
    for ax, (hn, vn, hl, vl) in zip(axes[0], views, strict=True):
        (h_min, h_max), (v_min, v_max) = _extent(ds, hn, frames), _extent(ds, vn, frames)
        pad = 0.05 * max(h_max - h_min, v_max - v_min, 1.0)
        ax.set_xlim(h_min - pad, h_max + pad)
        ax.set_ylim(v_min - pad, max(v_max, 0.0 if vn == "node_z" else v_max) + pad)
        ax.set_aspect("equal")
        if vn == "node_z":
            ax.axhline(0.0, color="tab:blue", lw=0.8, ls="--")
        ax.set_xlabel(hl)
        ax.set_ylabel(vl)
        (line,) = ax.plot([], [], "k.-", lw=1.2, ms=2)
        lines.append((line, hn, vn))
    label = fig.suptitle("")
    title = _title(ds)
    path.parent.mkdir(parents=True, exist_ok=True)
    writer = _gif_stream(fps) if suffix == ".gif" else animation.FFMpegWriter(fps=fps)
    with writer.saving(fig, path, dpi=100):
        for i in _progress(frames, progress, path.name):
            frame = ds.isel(time=int(i))
            for line, hn, vn in lines:
                line.set_data(frame[hn].values, frame[vn].values)
            label.set_text(f"{title}  t = {times[i]:.2f} s")
            writer.grab_frame()
    plt.close(fig)
    return path


def check_frames(fps: int, speed: float, every: float | None, max_frames: int) -> None:
    """Refuse animation options that draw nothing (a ValueError naming them)."""
    if fps < 1 or max_frames < 1 or speed <= 0 or (every is not None and every <= 0):
        raise ValueError(
            f"fps {fps}, max_frames {max_frames}, speed {speed}, every {every}: "
            "give fps and max_frames >= 1, speed and every > 0"
        )


def _frame_indices(times: np.ndarray, every: float, max_frames: int) -> np.ndarray:
    """Output indices of the frames: one per ``every`` seconds, at most ``max_frames`` of them
    spread evenly over the run (first and last kept)."""
    if len(times) == 0:
        raise ValueError("the results hold no time step to animate")
    targets = np.arange(times[0], times[-1] + 1e-9, every)
    frames = np.unique(np.searchsorted(times, targets - 1e-9).clip(0, len(times) - 1))
    if len(frames) > max_frames:
        kept = frames[np.unique(np.linspace(0, len(frames) - 1, max_frames).round().astype(int))]
        span = times[-1] - times[0]
        log.info(
            "animating %d frames of the %d asked (one every %.3g s of %.3g s simulated); "
            "raise --max-frames or --every for more or fewer",
            len(kept), len(frames), span / max(len(kept) - 1, 1), span,
        )  # fmt: skip
        frames = kept
    return frames


def _extent(ds: xr.Dataset, name: str, frames: np.ndarray, block: int = 256):
    """Smallest and largest value [m] of ``name`` over the frames, read a block at a time."""
    low, high = np.inf, -np.inf
    for start in range(0, len(frames), block):
        values = ds[name].isel(time=frames[start : start + block]).values
        low, high = min(low, float(np.nanmin(values))), max(high, float(np.nanmax(values)))
    return low, high


def _progress(frames: np.ndarray, progress: bool, name: str):
    """The frames, through a tqdm progress bar on stderr when ``progress``."""
    if not progress:
        return frames
    from tqdm import tqdm

    return tqdm(frames, unit="frame", desc=f"animating {name}", delay=1.0)


def _gif_stream(fps: int):
    """A matplotlib movie writer at ``fps`` frames per second that appends each frame to the GIF
    file as it is grabbed, all frames in the palette of the first (matplotlib's PillowWriter
    keeps every frame in memory until the end: 2.5 MB a frame for a 1400 x 600 picture)."""

    from matplotlib import animation
    from PIL import GifImagePlugin, Image

    class GifStream(animation.AbstractMovieWriter):
        def setup(self, fig, outfile, dpi=None):
            super().setup(fig, outfile, dpi=dpi)
            self._file = open(outfile, "wb")  # noqa: SIM115 (closed in finish)
            self._palette = None

        def grab_frame(self, **savefig_kwargs):
            buffer = BytesIO()
            self.fig.savefig(buffer, **{**savefig_kwargs, "format": "rgba", "dpi": self.dpi})
            rgb = Image.frombuffer("RGBA", self.frame_size, buffer.getbuffer(), "raw", "RGBA", 0, 1)
            rgb = rgb.convert("RGB")
            if self._palette is None:
                self._palette = rgb.quantize(colors=256, dither=Image.Dither.NONE)
                header, _ = GifImagePlugin.getheader(self._palette, info={"loop": 0})
                self._file.write(b"".join(header))
                frame = self._palette
            else:
                frame = rgb.quantize(palette=self._palette, dither=Image.Dither.NONE)
            duration = round(1000 / self.fps)
            self._file.write(b"".join(GifImagePlugin.getdata(frame, duration=duration)))

        def finish(self):
            self._file.write(b";")  # GIF trailer
            self._file.close()

    return GifStream(fps=fps)
