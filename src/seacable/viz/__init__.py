"""Pictures of results: snapshots, time series, range graphs and animations, for one cable
(``viz.cable``) and for a system of bodies and lines (``viz.system``).

matplotlib is imported lazily with the non-interactive Agg backend, so importing seacable
configures nothing.
"""

from pathlib import Path

import xarray as xr

from seacable.viz import cable, system


def plot_results(ds: xr.Dataset | xr.DataTree, path, every: float | None = None) -> Path:
    """The picture of a run's results (see ``viz.cable.plot_results`` and
    ``viz.system.plot_system``)."""
    if isinstance(ds, xr.DataTree):
        return system.plot_system(ds, path, every=every)
    return cable.plot_results(ds, path, every=every)


def animate_results(ds: xr.Dataset | xr.DataTree, path, **options) -> Path:
    """An animation of a run's results (GIF, or MP4 with ffmpeg); the options of
    ``viz.cable.animate_results``."""
    if isinstance(ds, xr.DataTree):
        return system.animate_system(ds, path, **options)
    return cable.animate_results(ds, path, **options)


__all__ = ["animate_results", "plot_results"]
