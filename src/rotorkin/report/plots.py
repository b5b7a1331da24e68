"""The report's interactive plots made readable: labels, hover, ticks, styles, extremes, checks.

A drive's plots (:class:`rotorkin.render.scenes.Plot`) arrive as plotly figures
written for any screen. :func:`prepare` turns one into what the page embeds:

* the title leaves the figure (it becomes an HTML heading that wraps on a phone,
  instead of a plotly title cut at the edge and covered by the toolbar);
* Greek letters and one unit style in every label (:func:`rotorkin.report.text.pretty`);
* hover: full trace names, the value with 4 significant digits at the scale of the
  curve and its unit (read from the axis label), never SI suffixes;
* angle axes ticked every 90 deg (45 deg for spans under 270 deg, 15 deg under 90);
* colour-blind safe: the curves of one panel differ by dash as well as by colour;
* markers at the largest and smallest value of every curve over the input angle, the
  table of them (:func:`extremes`), and for every failed design check whose unit a
  panel shows, its limit as a line and the worst point marked;
* the plot's data as CSV (:func:`plot_csv`), for the page's download link.
"""

from __future__ import annotations

import base64
import re

import numpy as np

from rotorkin.report.text import d3_format, esc, number, plain, pretty, unit_of

__all__ = [
    "prepare",
    "extremes",
    "format_extremes",
    "plot_csv",
    "angle_dtick",
    "hover_template",
    "short_name",
    "angle_symbol",
]

_DASHES = ("solid", "dash", "dot", "dashdot", "longdash", "longdashdot")
_AXIS_RE = re.compile(r"^([xy])axis(\d*)$")
_LIMIT_COLOR = "#000000"
# units a failed check may be drawn on without a shared word (they name one quantity)
_PLAIN_UNITS = {"MPa", "bar", "K"}


def angle_dtick(span: float) -> float:
    """Tick spacing of an angle axis spanning ``span`` [deg]: 90, or 45 / 15 for short spans."""
    span = abs(float(span))
    if span >= 270.0:
        return 180.0 if span > 900.0 else 90.0
    return 45.0 if span > 90.0 else 15.0


def short_name(name: str, limit: int = 28) -> str:
    """A legend name for a narrow screen: up to the first ``:``/``(`` or ``limit`` characters.

    The full name stays in the hover box.
    """
    text = plain(name)
    if len(text) <= limit:
        return name
    for sep in (": ", " (", ", "):
        head = text.split(sep, 1)[0]
        if 3 <= len(head) <= limit:
            return head
    cut = text[:limit].rsplit(" ", 1)[0]
    return cut + "…"


def hover_template(name: str, values, unit: str, x_label: str = "", x_values=None,
                   x_unit: str = "") -> str:  # fmt: skip
    """Hover text of a trace: full name, value at 4 significant digits, unit.

    With ``x_values`` (an x-y plot, closest-point hover) the x value is written too.
    """
    fy = d3_format(values)
    u = ("" if unit == "°" else " ") + unit if unit else ""
    if x_values is None:
        return f"{name}: %{{y:{fy}}}{u}<extra></extra>"
    fx = d3_format(x_values)
    xu = ("" if x_unit == "°" else " ") + x_unit if x_unit else ""
    return f"{name}<br>{x_label}: %{{x:{fx}}}{xu}<br>%{{y:{fy}}}{u}<extra></extra>"


def _axes(layout: dict) -> dict:
    return {k: v for k, v in layout.items() if _AXIS_RE.match(k) and isinstance(v, dict)}


def _axis_key(ref: str) -> str:  # "x2" -> "xaxis2"
    return f"{ref[0]}axis{ref[1:]}"


def _title(axis: dict) -> str:
    t = axis.get("title")
    return (t.get("text") if isinstance(t, dict) else t) or ""


def _color(t: dict, k: int) -> str:
    line, marker = t.get("line") or {}, t.get("marker") or {}
    c = line.get("color") or marker.get("color")
    return c if isinstance(c, str) else "#444444"


def _is_curve(t: dict) -> bool:
    return (t.get("type") in (None, "scatter", "scattergl") and t.get("y") is not None
            and "lines" in (t.get("mode") or "lines"))  # fmt: skip


def _decode(obj):
    """Plotly's typed arrays (``{"dtype", "bdata", "shape"}``, base64) back to numpy arrays."""
    if isinstance(obj, dict):
        if "bdata" in obj and "dtype" in obj:
            a = np.frombuffer(base64.b64decode(obj["bdata"]), dtype=np.dtype(obj["dtype"]))
            shape = obj.get("shape")
            if isinstance(shape, str):
                shape = tuple(int(v) for v in shape.split(","))
            return a.reshape(shape) if shape else a.copy()
        return {k: _decode(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_decode(v) for v in obj]
    return obj


def _arr(v) -> np.ndarray:
    return np.asarray([np.nan if a is None else a for a in np.ravel(np.asarray(v, dtype=object))],
                      dtype=float)  # fmt: skip


def _first_extreme(y: np.ndarray, largest: bool) -> int:
    """Index of the first sample at the largest (smallest) value of ``y``, NaN ignored.

    Within 1e-9 of the span counts as the extreme: a periodic curve meets its peak again
    in every cycle and at the period's end, equal but for round-off.
    """
    top, bottom = np.nanmax(y), np.nanmin(y)
    tol = 1e-9 * (top - bottom)
    return int(np.argmax(y >= top - tol) if largest else np.argmax(y <= bottom + tol))


def extremes(fig: dict) -> list[dict]:
    """Largest and smallest value of every non-constant curve, and the x where it occurs.

    Returns one dict per curve: ``trace`` (index), ``name``, ``panel`` (the y label),
    ``unit``, ``max``, ``x_max``, ``min``, ``x_min`` (first occurrence, NaN ignored).
    """
    layout = fig.get("layout") or {}
    out = []
    for i, t in enumerate(fig["data"]):
        if not _is_curve(t) or t.get("x") is None:
            continue
        x, y = _arr(t["x"]), _arr(t["y"])
        ok = np.isfinite(y) & np.isfinite(x)
        if not ok.any():
            continue
        yv = np.where(ok, y, np.nan)
        top, bottom = np.nanmax(yv), np.nanmin(yv)
        span = top - bottom
        if span <= 1e-12 * max(abs(top), abs(bottom), 1e-300):
            continue  # a constant line (a mean, a limit): nothing to mark
        hi, lo = _first_extreme(yv, True), _first_extreme(yv, False)
        label = _title(layout.get(_axis_key(t.get("yaxis", "y")), {}))
        out.append({"trace": i, "name": t.get("name") or "", "panel": label,
                    "unit": unit_of(label), "max": float(y[hi]), "x_max": float(x[hi]),
                    "min": float(y[lo]), "x_min": float(x[lo])})  # fmt: skip
    return out


def plot_csv(fig: dict, x_label: str = "") -> str:
    """The curves of a plot as CSV text (one header line; values to 7 significant digits).

    Traces that share one x array (the stacked plots over the input angle) share the
    first column; otherwise each trace brings its own x (and z) column. Header cells:
    the axis label with its unit (``shaft angle θ [°]``), then ``trace name [unit]``.
    """
    layout = fig.get("layout") or {}
    traces = [t for t in fig["data"] if t.get("type") in (None, "scatter", "scatter3d")]
    traces = [t for t in traces if t.get("y") is not None and t.get("meta") is None]
    cols: list[tuple[str, np.ndarray]] = []
    xs = [_arr(t["x"]) for t in traces if t.get("x") is not None]
    shared = bool(xs) and all(a.shape == xs[0].shape and np.array_equal(a, xs[0], equal_nan=True)
                              for a in xs) and all(t.get("z") is None for t in traces)  # fmt: skip
    if shared:
        titles = [_title(a) for k, a in sorted(_axes(layout).items()) if k[0] == "x" and _title(a)]
        xl = x_label or (titles[0] if titles else "x")
        cols.append((plain(pretty(xl)), xs[0]))
    for t in traces:
        name = plain(pretty(t.get("name") or "trace"))
        keys = ("y",) if shared else tuple(k for k in "xyz" if t.get(k) is not None)
        for k in keys:
            if t.get("type") == "scatter3d":
                unit, what = "mm", k
            else:
                label = plain(pretty(_title(layout.get(_axis_key(t.get(f"{k}axis", k)), {}))))
                unit, what = unit_of(label), re.sub(r"\s*\[[^\]]*\]$", "", label) or k
            head = f"{name}: {what}"
            cols.append((f"{head} [{unit}]" if unit else head, _arr(t[k]).ravel()))
    n = max((len(c) for _, c in cols), default=0)
    lines = [",".join(_csv_cell(h) for h, _ in cols)]
    for r in range(n):
        lines.append(",".join("" if r >= len(c) or not np.isfinite(c[r]) else f"{c[r]:.7g}"
                              for _, c in cols))  # fmt: skip
    return "\n".join(lines) + "\n"


def _csv_cell(text: str) -> str:
    return '"' + text.replace('"', '""') + '"' if any(c in text for c in ',"\n') else text


def _failed_on(check, axes: dict) -> list[str]:
    """The y axes (layout keys) a failed check's limit is drawn on: same unit, and a shared
    word unless the unit names one quantity (MPa, bar, K)."""
    words = {w for w in re.findall(r"[a-z]{4,}", check.name.lower())} - {"peak", "against"}
    out = []
    for key, axis in axes.items():
        if not key.startswith("y"):
            continue
        label = plain(_title(axis))
        if unit_of(label) != check.unit or not check.unit:
            continue
        if check.unit in _PLAIN_UNITS or words & set(re.findall(r"[a-z]{4,}", label.lower())):
            out.append(key)
    return out


def _marker_trace(name, xs, ys, symbols, colors, texts, xref, yref, meta, legend):
    return {"type": "scatter", "mode": "markers", "name": name, "x": xs, "y": ys,
            "xaxis": xref, "yaxis": yref, "meta": meta, "legendgroup": meta,
            "showlegend": legend, "text": texts, "hovertemplate": "%{text}<extra></extra>",
            "marker": {"symbol": symbols, "color": colors, "size": 10,
                       "line": {"color": "#000000", "width": 1}}}  # fmt: skip


def _span(fig: dict, xkey: str) -> float:
    """Span of the x data on an x axis (layout key ``xaxis2`` ...)."""
    ref = "x" + xkey[5:]
    xs = [
        _arr(t["x"]) for t in fig["data"] if t.get("xaxis", "x") == ref and t.get("x") is not None
    ]
    xs = np.concatenate(xs) if xs else np.zeros(1)
    return float(np.nanmax(xs) - np.nanmin(xs)) if np.isfinite(xs).any() else 360.0


def angle_symbol(label: str) -> str:
    """The Greek letter naming the angle in an axis label (``"shaft angle β"`` -> ``β``)."""
    found = re.findall(r"[α-ωΑ-Ωϕ]", plain(label))
    return found[-1] if found else "θ"


def prepare(plot, failed_checks=()) -> dict:
    """The page's entry of one plot: the polished figure and its HTML parts.

    Parameters
    ----------
    plot : rotorkin.render.scenes.Plot
    failed_checks : sequence of rotorkin.studies.checks.Check
        Checks that did not pass; each is drawn on the panels showing its unit.

    Returns
    -------
    dict
        ``id``, ``title``, ``heading``, ``caption``, ``figure`` (numpy arrays still),
        ``kind``, ``cursor_period_deg``, ``csv``, ``extremes`` (rows), ``short``
        (legend names for narrow screens, or None), ``curves`` (``[trace, name,
        unit]`` of the curves over the angle) and ``checks`` (names of the failed
        checks drawn).
    """
    fig = plot.figure.to_plotly_json() if hasattr(plot.figure, "to_plotly_json") else plot.figure
    fig = {"data": [_decode(dict(t)) for t in fig["data"]],
           "layout": _decode(dict(fig.get("layout") or {}))}  # fmt: skip
    layout = fig["layout"]
    title = layout.pop("title", None)
    heading = (title.get("text") if isinstance(title, dict) else title) or plot.title
    angle = plot.cursor_period_deg is not None
    csv = plot_csv(fig)
    axes = _axes(layout)
    x_titles = [_title(a) for k, a in sorted(axes.items()) if k.startswith("x") and _title(a)]
    x_name = angle_symbol(pretty(x_titles[0] if x_titles else ""))
    # labels: Greek letters and units; angle axes (and the axes matched to one) by 90 deg
    degrees = {k for k, a in axes.items() if k[0] == "x" and unit_of(pretty(_title(a))) == "°"}
    degrees |= {k for k, a in axes.items() if _axis_key(str(a.get("matches") or "z")) in degrees}
    for key, axis in axes.items():
        axis = layout[key] = dict(axis)
        text = pretty(_title(axis))
        if key in degrees:
            axis["ticksuffix"] = "°"
            axis["hoverformat"] = ".1f"
            text = re.sub(r"\s*\[°\]\s*$", "", text)
            span = plot.cursor_period_deg or _span(fig, key)
            axis.update(tickmode="linear", tick0=0.0, dtick=angle_dtick(span))
        if text or "title" in axis:
            axis["title"] = {**(axis.get("title") or {}), "text": text} if isinstance(
                axis.get("title"), dict) else {"text": text}  # fmt: skip
        axis.setdefault("exponentformat", "power")
        axis["automargin"] = True
        if key[0] == "x":  # clear of the lowest y tick label at the corner
            axis["ticklabelstandoff"] = 6
    axes = _axes(layout)
    for ann in layout.get("annotations") or []:
        ann["text"] = pretty(ann.get("text", ""))
    for menu in layout.get("updatemenus") or []:
        for b in menu.get("buttons") or []:
            b["label"] = pretty(b.get("label", ""))
    rows = extremes(fig) if angle else []
    # traces: names, hover, dashes
    dash_k: dict[tuple, int] = {}
    curves = []
    for i, t in enumerate(fig["data"]):
        name = pretty(t.get("name") or "")
        if "name" in t:
            t["name"] = name
        kind = t.get("type") or "scatter"
        if kind == "scatter3d":
            t["hovertemplate"] = (f"{name}<br>x %{{x:.1f}} mm<br>y %{{y:.1f}} mm<br>"
                                  "z %{z:.1f} mm<extra></extra>")  # fmt: skip
            continue
        if kind != "scatter" or t.get("y") is None or t.get("hoverinfo") == "skip":
            continue
        xa, ya = t.get("xaxis", "x"), t.get("yaxis", "y")
        ylab = plain(_title(layout.get(_axis_key(ya), {})))
        yunit = unit_of(ylab)
        if layout.get("hovermode") == "closest" or not angle:
            xlab = plain(_title(layout.get(_axis_key(xa), {})))
            t["hovertemplate"] = hover_template(name, _arr(t["y"]), yunit,
                                                re.sub(r"\s*\[[^\]]*\]$", "", xlab),
                                                _arr(t["x"]), unit_of(xlab))  # fmt: skip
        else:
            t["hovertemplate"] = hover_template(name, _arr(t["y"]), yunit)
            if _is_curve(t):
                curves.append([i, plain(name), yunit, plain(ylab)])
        if _is_curve(t):
            line = t["line"] = dict(t.get("line") or {})
            k = dash_k.get((xa, ya), 0)
            if "dash" not in line:
                line["dash"] = _DASHES[k % len(_DASHES)]
                dash_k[(xa, ya)] = k + 1
    # markers at the extremes, one trace per panel
    by_panel: dict[tuple, list] = {}
    for r in rows:
        t = fig["data"][r["trace"]]
        by_panel.setdefault((t.get("xaxis", "x"), t.get("yaxis", "y")), []).append((r, t))
    first = True
    for (xa, ya), items in by_panel.items():
        xs, ys, sym, col, txt = [], [], [], [], []
        for r, t in items:
            u = f" {r['unit']}" if r["unit"] else ""
            for which, s in (("max", "triangle-up"), ("min", "triangle-down")):
                xs.append(r[f"x_{which}"])
                ys.append(r[which])
                sym.append(s)
                col.append(_color(t, r["trace"]))
                at = r[f"x_{which}"]
                txt.append(f"{which} of {plain(pretty(r['name']))}: {number(r[which])}{u} at "
                           f"{x_name} = {at:.1f}°")  # fmt: skip
        fig["data"].append(_marker_trace("max ▲ / min ▼", xs, ys, sym, col, txt, xa, ya,
                                         "extremes", first))  # fmt: skip
        first = False
    drawn = _draw_failed(fig, failed_checks, angle)
    short = [short_name(t.get("name") or "") for t in fig["data"]]
    has_short = any(s != (t.get("name") or "") for s, t in zip(short, fig["data"], strict=True))
    _layout_for_page(layout)
    return {
        "id": plot.id,
        "title": plot.title,
        "heading": pretty(esc(plain(heading))),
        "caption": pretty(esc(plot.caption)) if plot.caption else "",
        "figure": fig,
        "cursor_period_deg": plot.cursor_period_deg,
        "csv": csv,
        "extremes": rows,
        "short": short if has_short else None,
        "curves": curves,
        "checks": drawn,
        "x_symbol": x_name,
    }


def _draw_failed(fig: dict, failed_checks, angle: bool) -> list[str]:
    """A limit line and the worst point of every failed check on the panels of its unit."""
    layout = fig["layout"]
    axes = _axes(layout)
    drawn = []
    for check in failed_checks:
        targets = _failed_on(check, axes)
        for ykey in targets:
            yref = "y" + ykey[5:]
            on = [t for t in fig["data"] if t.get("yaxis", "y") == yref and _is_curve(t)
                  and t.get("x") is not None and t.get("meta") is None]  # fmt: skip
            if not on:
                continue
            xref = on[0].get("xaxis", "x")
            allx = np.concatenate([_arr(t["x"]) for t in on])
            lo, hi = float(np.nanmin(allx)), float(np.nanmax(allx))
            sense = "≤" if check.upper else "≥"
            name = f"limit: {check.name} {sense} {number(check.limit)} {check.unit} — FAILS"
            fig["data"].append({"type": "scatter", "mode": "lines", "x": [lo, hi],
                                "y": [check.limit, check.limit], "xaxis": xref, "yaxis": yref,
                                "name": name, "meta": "limit", "hovertemplate":
                                f"{name}<extra></extra>",
                                "line": {"color": _LIMIT_COLOR, "dash": "longdash",
                                         "width": 2}})  # fmt: skip
            best = None
            for t in on:
                y = _arr(t["y"])
                j = _first_extreme(y, check.upper)
                worse = best is None or (y[j] > best[1] if check.upper else y[j] < best[1])
                if worse and not (best is not None and abs(y[j] - best[1]) <= 1e-9 * abs(y[j])):
                    best = (float(_arr(t["x"])[j]), float(y[j]), t.get("name", ""))
            where = f" at {best[0]:.1f}°" if angle else ""
            text = (f"FAILS: {check.name}: {number(best[1])} {check.unit} ({plain(best[2])})"
                    f"{where}, limit {sense} {number(check.limit)} {check.unit}")  # fmt: skip
            fig["data"].append(_marker_trace("failed check ✖", [best[0]], [best[1]],
                                             ["x-thin-open"], ["#000000"], [text], xref, yref,
                                             "limit", False))  # fmt: skip
            fig["data"][-1]["marker"].update(size=16, line={"color": "#000000", "width": 3})
            axis = layout[ykey]
            if axis.get("type") != "log" and isinstance(axis.get("range"), list):
                r0, r1 = axis["range"]
                pad = 0.05 * (max(r1, check.limit) - min(r0, check.limit))
                axis["range"] = [min(r0, check.limit - pad), max(r1, check.limit + pad)]
            drawn.append(check.name)
    return drawn


def _layout_for_page(layout: dict) -> None:
    """Room for the toolbar at the top, full names in hover boxes, a plain look."""
    margin = dict(layout.get("margin") or {})
    if not layout.get("updatemenus"):
        margin["t"] = 34
    margin.setdefault("l", 70)
    margin["r"] = max(int(margin.get("r", 20)), 16)
    layout["margin"] = margin
    layout["hoverlabel"] = {"namelength": -1, "font": {"size": 12}}
    layout.setdefault("font", {"size": 12})
    # the legend at the figure's bottom edge, below the x axis title: plotly widens the
    # bottom margin to hold it (a legend placed in plot fractions lands on the title)
    layout["legend"] = {"orientation": "h", "x": 0.0, "xanchor": "left", "yref": "container",
                        "y": 0.0, "yanchor": "bottom", "font": {"size": 11},
                        "tracegroupgap": 4}  # fmt: skip


def format_extremes(rows: list[dict], x_symbol: str = "θ") -> str:
    """The extremes of a plot as an HTML table: curve, max and where, min and where."""
    if not rows:
        return ""
    body = []
    for r in rows:
        u = f"\u2009{r['unit']}" if r["unit"] and r["unit"] != "°" else r["unit"]
        panel = pretty(esc(re.sub(r"\s*\[[^\]]*\]$", "", plain(r["panel"]))))
        body.append(
            f"<tr><td>{pretty(esc(r['name']))}</td><td>{panel}</td>"
            f"<td class='num'>{number(r['max'])}{u}</td><td class='num'>{r['x_max']:.1f}°</td>"
            f"<td class='num'>{number(r['min'])}{u}</td><td class='num'>{r['x_min']:.1f}°</td>"
            "</tr>"
        )
    return (
        "<div class='table-wrap'><table class='extremes'><thead><tr><th>curve</th><th>panel</th>"
        f"<th class='num'>max</th><th class='num'>at {x_symbol}</th><th class='num'>min</th>"
        f"<th class='num'>at {x_symbol}</th></tr></thead><tbody>{''.join(body)}</tbody></table>"
        "</div>"
    )
