"""The bifurcation diagram of a continuation (``seacable.continuation``'s Dataset): each body's
heading against the parameter (in its units), a solid line where the equilibrium is stable,
drawn over a thin dashed one where it is not, the folds, branch points and Hopf points marked;
with cycles, each limit cycle's least and largest heading (filled: stable, open: unstable).
Only converged orbits are in the Dataset: a failed one is no result."""

from pathlib import Path

import numpy as np
import xarray as xr

from seacable.viz.common import _pyplot, save

MARKS = {
    "fold": ("s", "tab:orange"),
    "branch point": ("o", "tab:green"),
    "hopf": ("*", "tab:red"),
}  # fmt: skip (a fold of cycles has no heading: not marked)


def plot_bifurcation(ds: xr.Dataset, path) -> Path:
    """The diagram of ``ds`` (module docstring), one panel per body, written to ``path``."""
    plt = _pyplot()
    bodies = list(ds["body"].values)
    fig, axes = plt.subplots(1, len(bodies), figsize=(7 * len(bodies), 5), squeeze=False,
                             constrained_layout=True)  # fmt: skip
    for j, body in enumerate(bodies):
        ax = axes[0, j]
        for k in np.unique(ds["branch"].values):
            at = np.flatnonzero(ds["branch"].values == k)
            mu = ds["parameter"].values[at]
            heading = np.degrees(np.unwrap(np.radians(ds["heading"].values[at, j])))
            stable = ds["unstable"].values[at] == 0
            for lo, hi in _runs(stable):
                end = min(hi + 1, len(at))  # joined to the next run
                look = ({"ls": "-", "lw": 2.0, "zorder": 3} if stable[lo]
                        else {"ls": "--", "lw": 1.0, "alpha": 0.7, "zorder": 2})  # fmt: skip
                ax.plot(mu[lo:end], heading[lo:end], color=f"C{k % 10}", **look)
        if "cycle" in ds.dims:  # the limit cycles' heading range: filled stable, open not
            stable = ds["cycle_stable"].values
            for edge in ("cycle_heading_low", "cycle_heading_high"):
                for flag, face in ((True, "tab:purple"), (False, "none")):
                    at = np.flatnonzero(stable == flag)
                    ax.plot(ds["cycle_parameter"].values[at], ds[edge].values[at, j], "o",
                            ms=4, mfc=face, mec="tab:purple", ls="none",
                            label=("limit cycle, " + ("stable" if flag else "unstable"))
                            if edge.endswith("low") and at.size else None)  # fmt: skip
        for kind, (marker, colour) in MARKS.items():
            at = np.flatnonzero(ds["special_kind"].values == kind)
            if at.size:
                ax.plot(ds["special_parameter"].values[at], ds["special_heading"].values[at, j],
                        marker, color=colour, ms=9, ls="none", label=kind)  # fmt: skip
        ax.set_xlabel(_label(ds["parameter"], ds.attrs.get("parameter", "parameter")))
        ax.set_ylabel(f"{body} heading [deg]")
        ax.set_title(f"{body}: stable (solid), unstable (dashed)")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    return save(fig, path)


CURVE_COLOURS = {"fold": "tab:orange", "hopf": "tab:red"}


def plot_curves(ds: xr.Dataset, path) -> Path:
    """The two-parameter curves of ``seacable.stability.api.curves`` (folds, Hopf points): the
    second parameter against the first, written to ``path``."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7, 5.5), constrained_layout=True)
    seen = set()
    for k, kind in enumerate(ds["kind"].values):
        at = np.flatnonzero(ds["curve"].values == k)
        ax.plot(ds["first"].values[at], ds["second"].values[at], "-", lw=1.8,
                color=CURVE_COLOURS.get(str(kind), "k"),
                label=None if kind in seen else f"{kind} points")  # fmt: skip
        seen.add(kind)
    ax.set_xlabel(_label(ds["first"], ds.attrs.get("first", "first parameter")))
    ax.set_ylabel(_label(ds["second"], ds.attrs.get("second", "second parameter")))
    ax.set_title("where the equilibria fold or start to oscillate")
    ax.grid(alpha=0.3)
    if seen:
        ax.legend(fontsize=8)
    return save(fig, path)


def _label(variable: xr.DataArray, name: str) -> str:
    """An axis's label: the parameter's name and its units."""
    units = variable.attrs.get("units", "")
    return f"{name} [{units}]" if units else name


def _runs(flags: np.ndarray) -> list[tuple[int, int]]:
    """The runs of equal values: (first, last) index pairs."""
    runs, start = [], 0
    for i in range(1, len(flags) + 1):
        if i == len(flags) or flags[i] != flags[start]:
            runs.append((start, i - 1))
            start = i
    return runs
