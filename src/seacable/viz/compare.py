"""The picture of the ships without and with their compensator in the same weather
(``seacable.compare``'s Dataset): above, each run's track (the hulls' outlines
every so often, darker as time goes on, the reference points' paths, the ties at the end);
below, both runs over time: the ties' distances and the hulls' clearance, the ties' tensions,
and the compensator's surge force and yaw moment. A limit cycle's tracks alike
(``plot_orbit``)."""

from pathlib import Path

import numpy as np
import xarray as xr

from seacable.viz.common import _pyplot, save

OUTLINES = 24  # hull outlines drawn along a track
STYLE = {"uncontrolled": dict(color="#d62728", ls="--"), "controlled": dict(color="#1f77b4")}


def plot_compare(ds: xr.Dataset, path) -> Path:
    """The picture of ``ds`` (module docstring), written to ``path``."""
    plt = _pyplot()
    fig = plt.figure(figsize=(15, 10), constrained_layout=True)
    grid = fig.add_gridspec(2, 6, height_ratios=(1.3, 1.0))
    controls = list(ds["control"].values)
    tracks = [fig.add_subplot(grid[0, 3 * k : 3 * k + 3]) for k in range(len(controls))]
    for ax, control in zip(tracks, controls, strict=True):
        _track(ax, ds.sel(control=control))
        run = ds.sel(control=control)
        why = run["message"].item()
        ax.set_title(f"{control}: {run['verdict'].item()}" + (f" ({why})" if why else ""))
    _same_box(tracks)
    series = [fig.add_subplot(grid[1, 2 * k : 2 * k + 2]) for k in range(3)]
    time = ds["time"].values
    for control in controls:
        run, style = ds.sel(control=control), STYLE.get(str(control), {})
        for tie in ds["tie"].values:
            series[0].plot(time, run["distance"].sel(tie=tie), label=f"{control}: {tie}",
                           **style)  # fmt: skip
            series[1].plot(time, run["tension"].sel(tie=tie) / 1e3, label=f"{control}: {tie}",
                           **style)  # fmt: skip
        series[2].plot(time, run["surge_force"] / 1e3, label=f"{control}: surge force",
                       **style)  # fmt: skip
    moment = series[2].twinx()
    for control in controls:
        style = STYLE.get(str(control), {})
        moment.plot(time, ds["yaw_moment"].sel(control=control) / 1e6, lw=0.8, color="grey",
                    ls=style.get("ls", "-"), label=f"{control}: yaw moment")  # fmt: skip
    moment.set_ylabel("compensator's yaw moment [MN m] (grey)")
    clearance = ds["clearance"]
    if np.isfinite(clearance.values).any():
        twin = series[0].twinx()
        for control in controls:
            twin.plot(time, clearance.sel(control=control), lw=0.8, color="grey",
                      ls=STYLE.get(str(control), {}).get("ls", "-"),
                      label=f"{control}: hull clearance")  # fmt: skip
        limit = float(ds.attrs.get("clearance_limit", 0.0))
        if limit > 0.0:
            twin.axhline(limit, color="k", lw=1.0, ls=":", label=f"clearance limit {limit:g} m")
        twin.set_ylabel("hull clearance [m] (grey)")
        twin.legend(fontsize=7, loc="lower right")
    for tie, newtons in _tension_limits(ds.attrs.get("tension_limits", "")):
        series[1].axhline(newtons / 1e3, color="k", lw=1.0, ls=":",
                          label=f"{tie} limit {newtons / 1e3:.4g} kN")  # fmt: skip
    for ax, label in zip(series, ("tie distance [m]", "tie tension [kN]",
                                  "compensator's surge force [kN]"), strict=True):  # fmt: skip
        ax.set_xlabel("time [s]")
        ax.set_ylabel(label)
        ax.legend(fontsize=7, loc="upper left")
        ax.grid(alpha=0.3)
    moment.legend(fontsize=7, loc="upper right")
    fig.suptitle(f"current {ds.attrs['current_speed']:g} m/s towards "
                 f"{ds.attrs['current_towards_deg']:g} deg, wind {ds.attrs['wind_speed']:g} m/s "
                 f"towards {ds.attrs['wind_towards_deg']:g} deg")  # fmt: skip
    return save(fig, path, tight=True)


def _tension_limits(text: str) -> list[tuple[str, float]]:
    """The ties' tension limits of a Dataset's attribute ("hawser 3e+06 N; ...")."""
    out = []
    for part in filter(None, (p.strip() for p in text.split(";"))):
        name, value, _ = part.rsplit(" ", 2)
        out.append((name, float(value)))
    return out


def plot_orbit(ds: xr.Dataset, path) -> Path:
    """A limit cycle (``seacable.periodic_orbit``'s Dataset): the ships' tracks over one period
    with their hulls, and the ties' tensions, written to ``path``."""
    plt = _pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 6), constrained_layout=True)
    _track(left, ds)
    _same_box([left])
    left.set_title(f"limit cycle: period {float(ds['period']):.5g} s, "
                   f"{'stable' if bool(ds['stable']) else 'unstable'}")  # fmt: skip
    for tie in ds["tie"].values:
        right.plot(ds["time"].values, ds["tension"].sel(tie=tie) / 1e3, label=str(tie))
    right.set_xlabel("time along the period [s]")
    right.set_ylabel("tie tension [kN]")
    right.legend(fontsize=8)
    right.grid(alpha=0.3)
    return save(fig, path, tight=True)


def _track(ax, run: xr.Dataset) -> None:
    """One run's hull outlines, reference-point paths and ties at the end."""
    m = run.sizes["time"]
    rows = np.unique(np.linspace(0, m - 1, min(OUTLINES, m)).astype(int))
    for j, body in enumerate(run["body"].values):
        x, y = run["x"].values[:, j], run["y"].values[:, j]
        psi = np.radians(run["heading"].values[:, j])
        ax.plot(x, y, lw=0.8, color=f"C{j}", label=str(body))
        hull = np.stack([run["hull_x"].values[j], run["hull_y"].values[j]], axis=1)
        if not np.isfinite(hull).all():
            continue
        closed = np.vstack([hull, hull[:1]])
        for k, i in enumerate(rows):
            c, s = np.cos(psi[i]), np.sin(psi[i])
            earth = closed @ np.array([[c, s], [-s, c]]) + (x[i], y[i])
            ax.plot(earth[:, 0], earth[:, 1], color=f"C{j}", lw=0.6,
                    alpha=0.15 + 0.85 * (k + 1) / len(rows))  # fmt: skip
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(fontsize=7, loc="best")
    ax.grid(alpha=0.3)


def _same_box(axes) -> None:
    """One square box of the same limits for every track (the same scale side by side)."""
    boxes = np.array([[*ax.get_xlim(), *ax.get_ylim()] for ax in axes])
    x0, x1, y0, y1 = boxes[:, 0].min(), boxes[:, 1].max(), boxes[:, 2].min(), boxes[:, 3].max()
    half = 0.5 * max(x1 - x0, y1 - y0)
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    for ax in axes:
        ax.set_xlim(cx - half, cx + half)
        ax.set_ylim(cy - half, cy + half)
        ax.set_aspect("equal", adjustable="box")
