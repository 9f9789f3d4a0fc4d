"""Pictures of results of a system of bodies and lines (``viz.system``): snapshots, time series,
range graphs and animations.

matplotlib is imported lazily with the non-interactive Agg backend, so importing seacable
configures nothing.
"""

from pathlib import Path

import xarray as xr

from seacable.viz import bifurcation, compare, operability, system


def plot_results(tree: xr.DataTree, path, every: float | None = None) -> Path:
    """The picture of a run's results (``viz.system.plot_system``)."""
    return system.plot_system(tree, path, every=every)


def animate_results(tree: xr.DataTree, path, **options) -> Path:
    """An animation of a run's results (GIF; the options of ``viz.system.animate_system``)."""
    return system.animate_system(tree, path, **options)


def plot_bifurcation(ds: xr.Dataset, path) -> Path:
    """The bifurcation diagram of a continuation (``viz.bifurcation``)."""
    return bifurcation.plot_bifurcation(ds, path)


def plot_operability(ds: xr.Dataset, path) -> Path:
    """The picture of an operability map (``viz.operability``)."""
    return operability.plot_operability(ds, path)


def plot_curves(ds: xr.Dataset, path) -> Path:
    """Curves of folds and Hopf points in two parameters (``viz.bifurcation``)."""
    return bifurcation.plot_curves(ds, path)


def plot_orbit(ds: xr.Dataset, path) -> Path:
    """A limit cycle's tracks and tensions (``viz.compare``)."""
    return compare.plot_orbit(ds, path)


def plot_compare(ds: xr.Dataset, path) -> Path:
    """The ships without and with their compensator, side by side (``viz.compare``)."""
    return compare.plot_compare(ds, path)


__all__ = ["animate_results", "plot_bifurcation", "plot_compare", "plot_curves",
           "plot_operability", "plot_orbit", "plot_results"]  # fmt: skip
