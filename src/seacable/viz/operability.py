"""The picture of an operability map (``seacable.stability.operability``'s Dataset on its
grid): one panel per wind-to-current speed ratio (a row of them per control setting, when the
map has both), the status of every pair of current and wind directions in colour."""

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
            ax.pcolormesh(ds["wind_towards_deg"].values, ds["current_towards_deg"].values,
                          codes, cmap=cmap, vmin=-0.5, vmax=len(names) - 0.5,
                          shading="nearest")  # fmt: skip
            ax.set_xlabel("wind towards [deg]")
            ax.set_ylabel("current towards [deg]")
            ax.set_title(("" if control is None else f"{control}: ")
                         + f"wind speed = {ratio:g} x current speed")  # fmt: skip
    fig.legend(handles=[Patch(color=COLOURS[n], label=n) for n in names], loc="lower center",
               ncol=len(names), bbox_to_anchor=(0.5, -0.08))  # fmt: skip
    return save(fig, path, tight=True)
