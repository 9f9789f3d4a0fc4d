"""What the pictures of a system's results share: matplotlib loaded lazily (the Agg backend),
the output times of snapshots and of animation frames, the frames' checks, progress and the
GIF writer, the axes' finish (``viz.system``); a figure written and closed (``save``)."""

import logging
from io import BytesIO
from pathlib import Path

import numpy as np

from seacable import files

log = logging.getLogger(__name__)


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save(fig, path, tight: bool = False) -> Path:
    """Write ``fig`` to ``path`` (its folder made; ``tight``: cropped to what is drawn), close
    it, and return the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with files.replacing(path) as aside:
        fig.savefig(aside, dpi=100, bbox_inches="tight" if tight else None)
    _pyplot().close(fig)
    return path


def every_rows(times: np.ndarray, every: float) -> np.ndarray:
    """The output rows one every ``every`` seconds from the first (the row at or just after
    each multiple); every row when ``every`` is shorter than the rows' own spacing (however
    short: no list of the multiples is made then)."""
    if len(times) == 0:
        return np.array([], dtype=int)
    if float(times[-1] - times[0]) >= every * len(times):
        return np.arange(len(times))
    targets = np.arange(times[0], times[-1] + 1e-9, every)
    return np.unique(np.searchsorted(times, targets - 1e-9).clip(0, len(times) - 1))


def _snapshot_indices(times: np.ndarray, every: float | None) -> np.ndarray:
    if every is None and len(times):
        every = max((times[-1] - times[0]) / 30.0, 1e-12)
    return every_rows(times, every or 1.0)


def _finish(ax, title: str, ylabel: str) -> None:
    ax.set_xlabel("time [s]")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)


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
    frames = every_rows(times, every)
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
