"""The picture of an operability map (``seacable.stability.operability``'s Dataset). On its grid:
one panel per wind-to-current speed ratio (a row of them per control setting, when the map has
both), titled with the speeds [m/s], the status of every pair of current direction and wind
direction relative to the current (what the ships answer to most) in colour, the states whose
stable equilibrium breaks a limit but is not reached from the nominal places marked (their
motion decides them); the limits in the title and each panel's least clearance and highest
tension under it (the margins). Of a table of states: each state a dot, coloured by its status,
at the wind's direction relative to the current's against the wind speed, and in a second panel
the waves' (when the table has waves) against their height; a dot's area grows with the state's
probability."""

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
    current = ds["current_towards_deg"].values
    wind = ds["wind_towards_deg"].values
    rows = _edges(current)
    for row, control in enumerate(controls):
        part = ds if control is None else ds.sel(control=control)
        for k, ratio in enumerate(ratios):
            ax = axes[row, k]
            panel = part.isel(wind_current_ratio=k)
            codes = np.vectorize(names.index)(panel["status"].values)
            unreached = panel["reached"].values == 0 if "reached" in panel else None
            for i, towards in enumerate(current):  # each current direction's row of cells
                relative = (wind - towards + 180.0) % 360.0 - 180.0
                order = np.argsort(relative)
                cells, edges = codes[i, order][None, :], _edges(relative[order])
                for turn in (-360.0, 0.0, 360.0):  # the cells across +-180 deg on both sides
                    ax.pcolormesh(edges + turn, rows[i : i + 2], cells, cmap=cmap, vmin=-0.5,
                                  vmax=len(names) - 0.5, shading="flat")  # fmt: skip
                if unreached is not None and unreached[i].any():
                    ax.plot(relative[unreached[i]], np.full(unreached[i].sum(), towards), "x",
                            color="k", ms=4, ls="none")  # fmt: skip
            ax.set_xlim(-180.0, 180.0)
            ax.set_xlabel("wind towards, from the current's direction [deg]")
            ax.set_ylabel("current towards [deg]")
            ax.set_title(("" if control is None else f"{control}: ") + _speeds(panel, ratio)
                         + _margins(panel), fontsize=10)  # fmt: skip
    handles: list = [Patch(color=COLOURS[n], label=n) for n in names]
    if "reached" in ds and np.any(ds["reached"].values == 0):
        from matplotlib.lines import Line2D

        handles.append(Line2D([], [], marker="x", color="k", ls="none",
                              label="equilibrium not reached: the motion decides"))  # fmt: skip
    fig.legend(handles=handles, loc="lower center", ncol=min(len(handles), 7),
               bbox_to_anchor=(0.5, -0.08))  # fmt: skip
    fig.suptitle(_limits(ds))
    return save(fig, path, tight=True)


def _limits(ds: xr.Dataset) -> str:
    """The map's limits, for its title."""
    parts = [f"clearance {float(ds.attrs.get('clearance_limit', 0.0)):g} m"]
    if ds.attrs.get("tension_limits"):
        parts.append(str(ds.attrs["tension_limits"]))
    simulated = float(ds.attrs.get("simulated", 0.0) or 0.0)
    told = f"; each state simulated {simulated:g} s" if simulated else ""
    return "limits: " + "; ".join(parts) + told


def _speeds(panel: xr.Dataset, ratio: float) -> str:
    """A panel's current and wind speeds [m/s] (the ratio alone for a map without them)."""
    if "current_speed" not in panel:
        return f"wind speed = {ratio:g} x current speed"
    speed = float(np.nanmax(panel["current_speed"].values))
    return f"current {speed:g} m/s, wind {ratio * speed:g} m/s ({ratio:g} x)"


def _margins(panel: xr.Dataset) -> str:
    """A panel's least clearance and highest tension over its states (a second line)."""
    if "clearance" not in panel or "tension" not in panel:
        return ""
    clearance = panel["clearance"].values.astype(float)
    tension = panel["tension"].values.astype(float)
    least = np.nanmin(clearance) if np.isfinite(clearance).any() else np.nan
    top = np.nanmax(tension) if np.isfinite(tension).any() else np.nan
    return f"\nleast clearance {least:.3g} m, tension up to {top / 1e3:.4g} kN"


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
    fig.suptitle(_limits(ds))
    return save(fig, path, tight=True)
