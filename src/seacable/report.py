"""A run's results, or a sweep's summary, as one HTML page that works offline (``seacable
report``): interactive plots (plotly.js, from the ``report`` extra, written into the page),
tables and the case with its provenance. Nothing is fetched when the page opens.

A run's page: its status and provenance; the statistics of each line end's tension and each
moving body's motions (``seacable.stats``); time series of the tensions and motions; the
tensions' spectra; each line's range graph (least, mean and largest tension along it, and
curvature along the lines that bend); the system in 3D at snapshots, with a slider and an
animation; the case file. A sweep's page:
the load cases' statuses, the envelope of each line (its largest tension and utilisation,
and where), the utilisation over the sweep's first dimensions, and a row per load case.

The page records what its script did on ``<body>``: ``data-plots`` (the plots drawn with data)
and ``data-errors`` (any error the page met), which the tests read in a real browser.
"""

import html
import json
import math
from pathlib import Path

import numpy as np
import xarray as xr

from seacable import files, sweep_summary
from seacable import stats as st
from seacable.errors import SeacableError
from seacable.results import TITLE as RESULTS_TITLE
from seacable.results import Results
from seacable.viz import system as vs

MOST_POINTS = 20_000  # samples of a time series drawn (a longer run is thinned evenly)
FRAMES = 60  # snapshots of the system in its animation
KN = 1e3
COLOURS = (
    "#1f77b4",
    "#ff7f0e",
    "#2ca02c",
    "#d62728",
    "#9467bd",
    "#8c564b",
    "#e377c2",
    "#7f7f7f",
    "#bcbd22",
    "#17becf",
)  # a line's three curves of its range graph in one
GENERATOR = files.GENERATOR  # a page it may replace

STYLE = """body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1200px;color:#222}
table{border-collapse:collapse;font-size:13px;margin:1em 0}td,th{border:1px solid #ccc;
padding:3px 8px;text-align:right}th{background:#f3f3f3}td:first-child,th:first-child{
text-align:left}pre{background:#f7f7f7;padding:1em;overflow:auto;font-size:12px}
.plot{width:100%;height:420px}.tall{height:640px}.bad{color:#a00}h2{margin-top:2em}"""

WATCH = """window.seacableErrors = [];
window.addEventListener('error', function (e) { window.seacableErrors.push(e.message); });
(function () {
  var said = console.error;
  console.error = function () {
    window.seacableErrors.push(Array.prototype.join.call(arguments, ' '));
    said.apply(console, arguments);
  };
})();"""

SCRIPT = """(function () {
  var figures = JSON.parse(document.getElementById('figures').textContent);
  var drawn = 0;
  figures.forEach(function (fig) {
    var el = document.getElementById(fig.id);
    Plotly.newPlot(el, fig.data, fig.layout, {responsive: true}).then(function () {
      if (fig.frames) { return Plotly.addFrames(el, fig.frames); }
    }).then(function () {
      var points = 0;
      el.data.forEach(function (t) { points += (t.x || t.z || []).length; });
      if (points > 0) { drawn += 1; }
      document.body.dataset.plots = drawn;
    }).catch(function (e) { window.seacableErrors.push(String(e)); }).then(function () {
      if (window.seacableErrors.length) {
        document.body.dataset.errors = window.seacableErrors.join('; ');
      }
    });
  });
})();"""


def _plotly_js() -> str:
    try:
        from plotly.offline import get_plotlyjs  # type: ignore[import-untyped]
    except ImportError:
        raise SeacableError("a report needs plotly (its plots' script, written into the "
                            "page): pip install 'seacable[report]'") from None  # fmt: skip
    return get_plotlyjs()


def _numbers(values) -> list:
    """Numbers for JSON: 7 significant digits, NaN as null (a gap in a plot)."""
    return [None if not math.isfinite(v) else float(f"{v:.7g}") for v in np.asarray(
        values, dtype=float).ravel().tolist()]  # fmt: skip


def _thinned(count: int) -> np.ndarray:
    return np.unique(np.linspace(0, count - 1, min(count, MOST_POINTS)).astype(int))


def _figure(key: str, title: str, traces: list, xlabel: str, ylabel: str, **layout) -> dict:
    return {"id": key, "data": traces, "layout": {
        "title": {"text": title}, "xaxis": {"title": {"text": xlabel}},
        "yaxis": {"title": {"text": ylabel}}, "margin": {"t": 50}, **layout}}  # fmt: skip


def _table(header: list[str], rows: list[list]) -> str:
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(_cell(c))}</td>" for c in row) + "</tr>"
                   for row in rows)  # fmt: skip
    return f"<table><tr>{head}</tr>{body}</table>"


def _cell(value) -> str:
    if isinstance(value, float):
        return "" if math.isnan(value) else f"{value:.5g}"
    return str(value)


def _page(title: str, sections: list[str], figures: list[dict]) -> str:
    data = json.dumps(figures, separators=(",", ":")).replace("</", "<\\/")
    return (
        f'<!DOCTYPE html><html lang="en"><head>{GENERATOR}<meta charset="utf-8">'
        f"<title>{html.escape(title)}</title><style>{STYLE}</style>"
        f"<script>{WATCH}</script><script>{_plotly_js()}</script></head><body>"
        f"<h1>{html.escape(title)}</h1>{''.join(sections)}"
        f'<script type="application/json" id="figures">{data}</script>'
        f"<script>{SCRIPT}</script></body></html>"
    )


def _div(key: str, tall: bool = False) -> str:
    return f'<div id="{key}" class="plot{" tall" if tall else ""}"></div>'


# ---- a run --------------------------------------------------------------------------------------
def run_page(tree: xr.DataTree, storm: float = 10800.0) -> str:
    """The page of a run's results (a system's DataTree)."""
    attrs = tree.attrs
    name = next((line.split(":", 1)[1].strip() for line in str(attrs.get("case", ""))
                 .splitlines() if line.startswith("name:")), "seacable results")  # fmt: skip
    last = vs.finite_rows(tree)
    t = np.asarray(tree["time"].values, dtype=float)[:last]
    status = str(attrs.get("status", "?"))
    sections = [
        f'<p class="{"" if status == "complete" else "bad"}"><b>{html.escape(status)}</b>: '
        f"{html.escape(str(attrs.get('status_message', '')))}; {len(t)} output times from "
        f"{t[0] if len(t) else 0:g} s to {t[-1] if len(t) else 0:g} s</p>"
    ]
    figures: list[dict] = []
    series = [(n, u, v[:last]) for n, u, v in st.series(tree)] if len(t) > 1 else []
    start = st.build_up(attrs)
    sections.append("<h2>Statistics</h2>" + _statistics(t, series, storm, start))
    keep = _thinned(len(t))
    tensions = [s for s in series if s[1] == "N"]
    traces: list[dict]
    if tensions:
        traces = [{"type": "scatter", "mode": "lines", "name": n.replace("lines/", ""),
                   "x": _numbers(t[keep]), "y": _numbers(v[keep] / KN)}
                  for n, _, v in tensions]  # fmt: skip
        figures.append(_figure("tensions", "tension at each line's ends", traces, "time [s]",
                               "tension [kN]"))  # fmt: skip
        steady = st.steady(t, start)
        if steady.sum() >= 16:  # the spectra of the run past its build-up
            spectra = []
            for n, _, v in tensions:
                f, density = st.spectrum(t[steady], v[steady] / KN)
                spectra.append(
                    {
                        "type": "scatter",
                        "mode": "lines",
                        "x": _numbers(f),
                        "name": n.replace("lines/", ""),
                        "y": _numbers(density),
                    }
                )
            figures.append(
                _figure(
                    "spectra",
                    "spectra of the tensions (Welch's)",
                    spectra,
                    "frequency [Hz]",
                    "density [kN^2/Hz]",
                    yaxis={"type": "log", "title": {"text": "density [kN^2/Hz]"}},
                )
            )
    for unit, what in (("m", "positions"), ("degree", "rotations")):
        moving = [s for s in series if s[0].startswith("bodies/") and s[1] == unit]
        if moving:
            traces = [
                {
                    "type": "scatter",
                    "mode": "lines",
                    "name": n.replace("bodies/", ""),
                    "x": _numbers(t[keep]),
                    "y": _numbers(v[keep]),
                }
                for n, _, v in moving
            ]
            figures.append(_figure(f"bodies_{unit}", f"{what} of the bodies that move",
                                   traces, "time [s]", f"[{unit}]"))  # fmt: skip
    ranges = vs.tension_ranges(tree, last)
    if ranges:
        traces = []
        for k, (line, (s, least, mean, largest)) in enumerate(ranges.items()):
            colour = COLOURS[k % len(COLOURS)]
            traces += [
                {"type": "scatter", "mode": "lines", "name": f"{line} {what}", "x": _numbers(s),
                 "y": _numbers(values / KN), "legendgroup": line,
                 "line": {"dash": dash, "color": colour}}
                for what, values, dash in (("largest", largest, "solid"), ("mean", mean, "dot"),
                                           ("least", least, "dash"))
            ]  # fmt: skip
        figures.append(
            _figure(
                "ranges",
                "range graph: tension along each line",
                traces,
                "arc length from the 'from' end [m]",
                "tension [kN]",
            )
        )
    bent = vs.curvature_ranges(tree, last, vs.bending_lines(attrs))
    if bent:
        traces = []
        for k, (line, (arc, least, mean, largest)) in enumerate(bent.items()):
            traces += [
                {"type": "scatter", "mode": "lines", "name": f"{line} {what}",
                 "x": _numbers(arc), "y": _numbers(values), "legendgroup": line,
                 "line": {"dash": dash, "color": COLOURS[k % len(COLOURS)]}}
                for what, values, dash in (("largest", largest, "solid"), ("mean", mean, "dot"),
                                           ("least", least, "dash"))
            ]  # fmt: skip
        figures.append(_figure("curvature", "range graph: curvature along the lines that bend",
                               traces, "arc length from the 'from' end [m]",
                               "curvature [1/m]"))  # fmt: skip
    scene = _scene(tree, t, last)
    if scene is not None:
        figures.append(scene)
    sections.append("<h2>Time series</h2>" + "".join(_div(f["id"], f["id"] == "system")
                                                     for f in figures))  # fmt: skip
    sections.append("<h2>The case</h2><pre>" + html.escape(str(attrs.get("case", ""))) + "</pre>")
    sections.append("<h2>Provenance</h2>" + _table(["attribute", "value"], [
        [k, str(v)[:300]] for k, v in attrs.items() if k not in ("case", "case_resolved",
                                                                 "input_files")]))  # fmt: skip
    return _page(name, sections, figures)


def _statistics(t, series, storm: float, start: float) -> str:
    kept, rows = st.table(t, series, storm, start)
    if not rows:
        return "<p>No line tension or body motion to summarise.</p>"
    return (f"<p>From {kept[0]:g} s (the build-up left out) to {kept[-1]:g} s. The most "
            f"probable largest of a {storm:g} s storm: Rayleigh's, mean + std sqrt(2 ln(storm "
            "/ Tz)), and a Weibull law fitted to the cycles' peaks (shape 2 is Rayleigh's).</p>"
            + _table(["series", "unit", "largest", "least", "mean", "std", "Tz [s]",
                      "MPM Rayleigh", "MPM Weibull", "shape"],
                     [[n, u, s.largest, s.least, s.mean, s.std, s.tz, s.mpm, f, k]
                      for n, u, s, f, k in rows]))  # fmt: skip


def _scene(tree: xr.DataTree, t: np.ndarray, last: int) -> dict | None:
    """The lines in 3D at FRAMES snapshots: the first drawn, the others as frames."""
    lines = {n: ds for n, ds in vs.result_groups(tree, "lines").items()}
    if not lines or last < 1:
        return None
    picks = np.unique(np.linspace(0, last - 1, min(last, FRAMES)).astype(int))

    def traces(i: int) -> list:
        out = []
        for name, ds in lines.items():
            x, y = vs.projected(ds, i, "x", "y")
            _, z = vs.projected(ds, i, "x", "z")
            out.append({"type": "scatter3d", "mode": "lines", "name": name,
                        "x": _numbers(x), "y": _numbers(y), "z": _numbers(z)})  # fmt: skip
        return out

    frames = [{"name": f"{t[i]:g}", "data": traces(i)} for i in picks]
    steps = [
        {
            "label": f["name"],
            "method": "animate",
            "args": [[f["name"]], {"mode": "immediate", "frame": {"duration": 0, "redraw": True}}],
        }
        for f in frames
    ]
    play = {"type": "buttons", "showactive": False, "x": 0.0, "y": 0.0, "buttons": [
        {"label": "play", "method": "animate", "args": [None, {
            "frame": {"duration": 150, "redraw": True}, "fromcurrent": True}]}]}  # fmt: skip
    figure = _figure("system", "the system at the output times [s]", traces(int(picks[0])), "",
                     "", scene={"aspectmode": "data", "xaxis": {"title": {"text": "x [m]"}},
                                "yaxis": {"title": {"text": "y [m]"}},
                                "zaxis": {"title": {"text": "z [m]"}}},
                     sliders=[{"steps": steps, "currentvalue": {"prefix": "t = "}}],
                     updatemenus=[play])  # fmt: skip
    figure["frames"] = frames
    return figure


# ---- a sweep ------------------------------------------------------------------------------------
def sweep_page(found: xr.Dataset) -> str:
    """The page of a sweep's summary (seacable.sweep)."""
    dims = [str(d) for d in found["status"].dims]
    status = found["status"].values.ravel()
    sections = [f"<p>{status.size} load cases over {', '.join(dims)}: "
                f"{html.escape(str(found.attrs.get('counts', '')))}; runs in "
                f"{html.escape(str(found.attrs.get('runs', '')))}</p>"]  # fmt: skip
    figures: list[dict] = []
    rows = [[e.line, e.tension / KN, e.utilisation, e.mpm / KN, e.at]
            for e in sweep_summary.envelope(found)]  # fmt: skip
    sections.append(
        "<h2>Envelope of each line</h2>"
        + _table(["line", "largest tension [kN]", "utilisation", "largest MPM [kN]", "at"], rows)
    )
    used = found["utilisation"].max("line", skipna=True)
    if np.isfinite(used.values).any():
        figures.append(_utilisation_figure(used, dims))
        sections.append(_div("utilisation"))
    header = [*dims, "status", "largest utilisation", "largest offset [m]", "message"]
    table_rows = []
    offset = found["offset_max"].max("body", skipna=True) if found.sizes.get("body") else None
    for index in np.ndindex(*found["status"].shape):
        table_rows.append([
            *(sweep_summary.shown(found[d].values[k].item())
              for d, k in zip(dims, index, strict=True)),
            str(found["status"].values[index]), float(used.values[index]),
            float(offset.values[index]) if offset is not None else math.nan,
            str(found["message"].values[index])[:200],
        ])  # fmt: skip
    sections.append("<h2>Load cases</h2>" + _table(header, table_rows[:2000]))
    sections.append("<h2>The case</h2><pre>" + html.escape(str(found.attrs.get("case", "")))
                    + "</pre>")  # fmt: skip
    sections.append("<h2>Provenance</h2>" + _table(["attribute", "value"], [
        [k, str(v)[:300]] for k, v in found.attrs.items() if k != "case"]))  # fmt: skip
    title = f"sweep of {found.attrs.get('case_name', 'a case')}"
    return _page(title, sections, figures)


def _utilisation_figure(used: xr.DataArray, dims: list[str]) -> dict:
    """The largest utilisation of the lines over the sweep's first dimension (a curve per
    value of the second), the others at their largest."""
    first = dims[0]
    rest = [d for d in dims[2:]]
    worst = used.max(rest, skipna=True) if rest else used
    x = [sweep_summary.shown(v.item()) for v in worst[first].values]
    if len(dims) == 1:
        traces = [{"type": "scatter", "mode": "lines+markers", "name": "largest",
                   "x": x, "y": _numbers(worst.values)}]  # fmt: skip
    else:
        second = dims[1]
        traces = [{"type": "scatter", "mode": "lines+markers",
                   "name": f"{second}={sweep_summary.shown(v.item())}", "x": x,
                   "y": _numbers(worst.sel({second: v}).values)}
                  for v in worst[second].values]  # fmt: skip
    return _figure("utilisation", "largest utilisation of the lines' breaking strength",
                   traces, first, "utilisation [-]")  # fmt: skip


def write(source: Path, output: Path, storm: float = 10800.0) -> Path:
    """The page of ``source`` (a run's results or a sweep's summary) written to ``output``."""
    files.check_output(output, "page", [source])
    if source.suffix.lower() == ".zarr":
        with xr.open_zarr(source) as found:
            text = sweep_page(found.load())
    else:
        files.self_contained(source)
        try:
            with xr.open_dataset(source, engine="h5netcdf") as root:
                title = root.attrs.get("title") or None  # a file made by hand may have none
                timed = "time" in root.coords
        except (OSError, ValueError) as exc:
            raise SeacableError(f"{source}: not a readable NetCDF/HDF5 file ({exc}); give a "
                                "file seacable wrote") from None  # fmt: skip
        if title not in (None, sweep_summary.TITLE, RESULTS_TITLE) or (title is None and not timed):
            raise SeacableError(f"{source}: not seacable's results or a sweep's summary (its "
                                f"title: {title!r}); give a file seacable wrote")  # fmt: skip
        if title == sweep_summary.TITLE:
            with xr.open_dataset(source, engine="h5netcdf") as found:
                text = sweep_page(found.load())
        else:
            results = Results.open(source)
            if not isinstance(results.dataset, xr.DataTree):
                raise SeacableError(
                    f"{source}: results of the single-cable core; run the "
                    "case as a system (seacable upgrade) and report those"
                )
            text = run_page(results.dataset, storm)
    return files.replace_text(output, text)
