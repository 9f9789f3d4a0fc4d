"""The picture of an operability map (``seacable.stability.operability``'s Dataset). On its
grid: one panel per wind-to-current speed ratio (a row of them per control setting, when the
map has both), the status of every pair of current and wind directions in colour. Of a table of
states: each state a dot, coloured by its status, at the wind's direction relative to the
current's against the wind speed, and in a second panel the waves' (when the table has waves)
against their height; a dot's area grows with the state's probability."""

from pathlib import Path

import numpy as np
import xarray as xr

from seacable.viz.common import _pyplot, save

COLOURS = {
    "stable": "#2ca02c",
    "limit exceeded": "#ff7f0e",
    "cycling": "#1f77b4",
    "collision risk": "#d62728",
    "no equilibrium": "#7f7f7f",
    "failed": "#000000",
}


def plot_operability(ds: xr.Dataset, path) -> Path:
    """The map of ``ds`` (module docstring), written to ``path``."""
    plt = _pyplot()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    names = list(COLOURS)
    if "wind_current_ratio" not in ds.dims:
        return _plot_states(ds, path)
    ratios = ds["wind_current_ratio"].values
    controls = list(ds["control"].values) if "control" in ds.dims else [None]
    size = (5.5 * len(ratios), 5 * len(controls))
    fig, axes = plt.subplots(len(controls), len(ratios), figsize=size, squeeze=False,
                             constrained_layout=True)  # fmt: skip
    cmap = ListedColormap([COLOURS[n] for n in names])
    for row, control in enumerate(controls):
        part = ds if control is None else ds.sel(control=control)
        for k, ratio in enumerate(ratios):
            ax = axes[row, k]
            status = part["status"].isel(wind_current_ratio=k).values
            codes = np.vectorize(names.index)(status)
            ax.pcolormesh(_edges(ds["wind_towards_deg"].values),
                          _edges(ds["current_towards_deg"].values), codes, cmap=cmap,
                          vmin=-0.5, vmax=len(names) - 0.5, shading="flat")  # fmt: skip
            ax.set_xlabel("wind towards [deg]")
            ax.set_ylabel("current towards [deg]")
            ax.set_title(("" if control is None else f"{control}: ")
                         + f"wind speed = {ratio:g} x current speed")  # fmt: skip
    fig.legend(handles=[Patch(color=COLOURS[n], label=n) for n in names], loc="lower center",
               ncol=len(names), bbox_to_anchor=(0.5, -0.08))  # fmt: skip
    return save(fig, path, tight=True)


SINGLE_WIDTH = 10.0  # [deg] the cell of a grid's only direction


def _edges(directions: np.ndarray) -> np.ndarray:
    """The cells' edges [deg] around a grid's directions: halfway between neighbours, the
    outer ones as far out as the inner ones; a single direction in a cell SINGLE_WIDTH wide
    (matplotlib's own cells, "nearest", have no width then: a grid of one current direction
    drew an empty map)."""
    values = np.asarray(directions, dtype=float)
    if values.size == 1:
        return values[0] + np.array([-0.5, 0.5]) * SINGLE_WIDTH
    middle = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[2 * values[0] - middle[0]], middle, [2 * values[-1] - middle[-1]]])


def _plot_states(ds: xr.Dataset, path) -> Path:
    """A map of a table of states (module docstring)."""
    plt = _pyplot()
    from matplotlib.patches import Patch

    controls = list(ds["control"].values) if "control" in ds.dims else [None]
    waves = bool(np.isfinite(ds["wave_height"].values).any())
    panels = 2 if waves else 1
    fig, axes = plt.subplots(len(controls), panels, figsize=(6 * panels, 4.5 * len(controls)),
                             squeeze=False, constrained_layout=True)  # fmt: skip
    current = ds["current_towards"].values
    if "control" in ds.dims:
        current = current[0]
    share = ds["probability"].values if "probability" in ds else None
    if share is not None and "control" in ds.dims:
        share = share[0]
    size = 30.0 if share is None else 10.0 + 400.0 * share / max(float(share.max()), 1e-30)
    for row, control in enumerate(controls):
        part = ds if control is None else ds.sel(control=control)
        colours = [COLOURS[str(n)] for n in part["status"].values]
        pairs = [("wind_towards", "wind_speed", "wind towards - current towards [deg]",
                  "wind speed [m/s]")]  # fmt: skip
        if waves:
            pairs.append(("wave_towards", "wave_height", "waves towards - current towards [deg]",
                          "significant wave height [m]"))  # fmt: skip
        for k, (angle, speed, xlabel, ylabel) in enumerate(pairs):
            ax = axes[row, k]
            relative = (part[angle].values - current + 180.0) % 360.0 - 180.0
            ax.scatter(relative, part[speed].values, s=size, c=colours, edgecolors="none")
            ax.set_xlim(-180.0, 180.0)
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            ax.set_title(("" if control is None else f"{control}: ")
                         + f"{part['status'].size} states")  # fmt: skip
    fig.legend(handles=[Patch(color=COLOURS[n], label=n) for n in COLOURS], loc="lower center",
               ncol=len(COLOURS), bbox_to_anchor=(0.5, -0.08))  # fmt: skip
    return save(fig, path, tight=True)
