"""Shared parts of the HTML report: the animated scene, plots, checks and geometry helpers.

Each drive has its own module ``html_scene_<drive_type>`` with three functions,

* ``scene(result, cfg, frames) -> Scene``: the mechanism over one period of the
  input angle, drawn from the drive's and machine's own coordinates;
* ``plots(result, cfg) -> list[Plot]``: the interactive plots;
* ``checks(result, cfg) -> list[Check]``: limits approached, in plain words;

and :func:`drive_module` finds it. A :class:`Scene` is a plotly figure whose
*animated* traces get new coordinates at every frame; the page's small renderer
(:mod:`rotorkin.report.html`) swaps them in with ``Plotly.restyle`` as the slider
moves. Coordinates are in mm, rounded to 0.01 mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = [  # fmt: skip
    "Scene",
    "SceneBuilder",
    "Plot",
    "Check",
    "trace",
    "panels",
    "frame_angles",
    "join",
    "select",
    "circle",
    "sector",
    "line_figure",
    "lines_plot",
    "svaj_figure",
    "svaj_plot",
    "torque_plot",
    "mean_trace",
    "xy_figure",
    "merge_identical",
    "log_ticks",
    "detrend",
    "flywheel_checks",
    "fmt",
    "COLOR_1",
    "COLOR_2",
    "GREY",
]

#: Colours of member 1 and member 2: blue and vermilion, told apart by colour-blind readers.
COLOR_1 = "#0072b2"
COLOR_2 = "#d55e00"
#: Neutral colour: casing, hub, edges, ghost lines.
GREY = "#7f7f7f"

#: Line colours of the plots, in turn: Okabe and Ito's palette for colour-blind readers
#: (blue, vermilion, bluish green, reddish purple, orange, sky blue, black, yellow); the
#: report also gives each curve of a panel its own dash.
_PALETTE = ("#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000",
            "#b8a500")  # fmt: skip


# --------------------------------------------------------------------------------------------
# data classes
# --------------------------------------------------------------------------------------------
@dataclass
class Scene:
    """The mechanism over one period, ready for the page.

    Attributes
    ----------
    figure : dict
        Plotly figure (``data``, ``layout``) showing frame 0.
    animated : list of int
        Indices of the traces that change from frame to frame.
    frames : list of list of dict
        ``frames[f][i]`` holds the arrays (``x``, ``y``, ``z``, ``text``) of trace
        ``animated[i]`` at frame ``f``; ``None`` separates polylines.
    angles_deg : list of float
        Input angle at each frame [deg].
    angle_label : str
        What the slider moves, e.g. ``"theta (output shaft)"``.
    readouts : list of dict
        ``{"label", "unit", "values"}``: numbers shown beside the slider, per frame.
    caption : str
        One or two sentences under the scene: what is drawn, from which model.
    """

    figure: dict
    animated: list
    frames: list
    angles_deg: list
    angle_label: str
    readouts: list = field(default_factory=list)
    caption: str = ""


@dataclass
class Plot:
    """One interactive plot of the page.

    ``cursor_period_deg``: when the plot's x axis is the input angle in degrees,
    the period of that axis; the page then draws a vertical cursor at the slider's
    angle (modulo the period). ``None`` for other plots. ``torque_sign``: +1 when
    the plot's shaft torque is positive as the study's ``shaft_torque_*`` columns
    (the machine drives the shaft), -1 when it shows the torque the motor must
    supply (a pump); the report's summary table then takes the same convention.
    """

    id: str
    title: str
    figure: object
    caption: str = ""
    cursor_period_deg: float | None = None
    torque_sign: int = 1


@dataclass
class Check:
    """A check in plain words; ``level`` is ``"ok"``, ``"note"``, ``"warning"`` or ``"error"``."""

    level: str
    title: str
    text: str


def fmt(value, digits: int = 4) -> str:
    """A number for people: ``digits`` significant digits, no exponent for ordinary sizes."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if not np.isfinite(v):
            return "n/a"
        if v == 0.0:
            return "0"
        if 1e-3 <= abs(v) < 1e7:
            return f"{v:.{digits}g}" if abs(v) < 10**digits else f"{v:.0f}"
        return f"{v:.{digits - 1}e}"
    return str(value)


# --------------------------------------------------------------------------------------------
# scene building
# --------------------------------------------------------------------------------------------
def frame_angles(period: float, frames: int) -> np.ndarray:
    """``frames`` input angles over one period, end excluded (the loop closes) [rad]."""
    return np.linspace(0.0, period, int(frames), endpoint=False)


def _frame_array(a, n_frames, decimals):
    """(F, n) float array, or a list of F 1-d arrays (ragged) -> F lists, rounded, NaN -> None."""
    if isinstance(a, list):
        rows = [np.round(np.asarray(r, dtype=float), decimals) for r in a]
    else:
        a = np.asarray(a, dtype=float)
        if a.ndim == 1:
            a = np.broadcast_to(a, (n_frames, a.shape[0]))
        rows = np.round(a, decimals)
    return [[None if v != v else v for v in row.tolist()] for row in rows]


class SceneBuilder:
    """Collects static and animated traces of a scene.

    Parameters
    ----------
    angles : ndarray, shape (F,)
        Input angles of the frames [rad].
    decimals : int, optional
        Rounding of the animated coordinates (2: 0.01 mm).
    """

    def __init__(self, angles, decimals: int = 2):
        self.angles = np.asarray(angles, dtype=float)
        self.decimals = decimals
        self.traces: list[dict] = []
        self.animated: list[int] = []
        self._per_frame: list[dict] = []

    @property
    def n_frames(self) -> int:
        return len(self.angles)

    def static(self, trace: dict) -> int:
        """Add a trace that does not move; array values are rounded like the animated ones."""
        trace = dict(trace)
        for key in ("x", "y", "z"):
            if key in trace and not isinstance(trace[key], list):
                trace[key] = _frame_array(np.ravel(trace[key])[None, :], 1, self.decimals)[0]
        self.traces.append(trace)
        return len(self.traces) - 1

    def animated_trace(self, trace: dict, **arrays) -> int:
        """Add a trace whose ``x``, ``y`` (``z``, ``text``) change per frame.

        Each keyword is an array of shape (F, n) or a list of F 1-d arrays (NaN
        separates polylines); ``text`` is a list of F lists of strings. A coordinate
        that does not change may be given once in ``trace`` instead.
        """
        per = {}
        for key, value in arrays.items():
            if key == "text":
                per[key] = [list(map(str, row)) for row in value]
            else:
                per[key] = _frame_array(value, self.n_frames, self.decimals)
            if len(per[key]) != self.n_frames:
                raise ValueError(f"{key}: {len(per[key])} frames, expected {self.n_frames}")
        trace = dict(trace)
        for key in ("x", "y", "z"):  # coordinates that do not change: given once, in the trace
            if key in trace and not isinstance(trace[key], list):
                trace[key] = _frame_array(np.ravel(trace[key])[None, :], 1, self.decimals)[0]
        for key, frames in per.items():
            trace[key] = frames[0]
        self.traces.append(trace)
        self.animated.append(len(self.traces) - 1)
        self._per_frame.append(per)
        return len(self.traces) - 1

    def build(self, layout: dict, angle_label: str, readouts=(), caption="") -> Scene:
        frames = [
            [{k: v[f] for k, v in per.items()} for per in self._per_frame]
            for f in range(self.n_frames)
        ]
        return Scene(
            figure={"data": self.traces, "layout": layout},
            animated=list(self.animated),
            frames=frames,
            angles_deg=np.round(np.degrees(self.angles), 4).tolist(),
            angle_label=angle_label,
            readouts=[
                {"label": lab, "unit": unit, "values": np.round(np.asarray(v, float), 4).tolist()}
                for lab, unit, v in readouts
            ],
            caption=caption,
        )


# --------------------------------------------------------------------------------------------
# compact trace and layout dicts for the scenes
# --------------------------------------------------------------------------------------------
def trace(
    kind: str,
    name: str,
    color: str = "#404040",
    width: float = 2.0,
    on: str = "",
    legend: bool = True,
    **extra,
) -> dict:
    """A plotly trace dict of the scenes.

    ``kind``: ``"line"``, ``"fill"`` (closed polygons filled with ``color``, edge
    ``edge``/``edge_width``), ``"text"`` (``width`` = font size), ``"markers"``
    (``width`` = marker size), ``"line3d"``, ``"markers3d"``. ``on``: the 2D axes
    suffix (``""``, ``"2"``, ``"3"``). Extra keywords go into the trace.
    """
    t = {"name": name}
    if not legend:
        t["showlegend"] = False
    if kind in ("line", "fill", "text", "markers"):
        t.update(type="scatter", xaxis=f"x{on}", yaxis=f"y{on}")
    if kind in ("line", "line3d"):
        t.update(mode="lines", line={"color": color, "width": width})
        t["type"] = t.get("type", "scatter3d")
    elif kind == "fill":
        edge = {"color": extra.pop("edge", GREY), "width": extra.pop("edge_width", 1.0)}
        t.update(mode="lines", fill="toself", fillcolor=color, line=edge, hoverinfo="skip")
    elif kind == "text":
        t.update(mode="text", textfont={"size": width, "color": color}, hoverinfo="skip")
        t.setdefault("showlegend", False)
    elif kind in ("markers", "markers3d"):
        t.update(mode="markers", marker={"color": color, "size": width, **extra.pop("marker", {})})
        t["type"] = t.get("type", "scatter3d")
    else:
        raise ValueError(f"unknown trace kind {kind!r}")
    t.update(extra)
    return t


def panels(height: int, axes: list, titles: list, legend_y: float = -0.16, **extra) -> dict:
    """Layout of a scene with side-by-side 2D panels of equal scale.

    ``axes``: per panel ``(suffix, domain, x_range, y_range, x_title, y_title)``;
    ``titles``: ``(x, html)`` above the panels (paper coordinates).
    """
    grid = {"zeroline": False, "showgrid": True, "gridcolor": "#eeeeee"}
    layout = {
        "height": height,
        "margin": {"l": 55, "r": 10, "t": 40, "b": 10},
        "plot_bgcolor": "white",
        "legend": {
            "orientation": "h",
            "x": 0.0,
            "y": legend_y,
            "yanchor": "top",
            "font": {"size": 11},
        },
        "annotations": [
            {
                "text": text,
                "x": x,
                "y": 1.05,
                "xref": "paper",
                "yref": "paper",
                "showarrow": False,
                "xanchor": "left",
                "font": {"size": 13},
            }
            for x, text in titles
        ],
    }
    for suffix, domain, xr, yr, xt, yt in axes:
        layout[f"xaxis{suffix}"] = {"range": xr, "title": {"text": xt}, **grid}
        if domain is not None:
            layout[f"xaxis{suffix}"]["domain"] = domain
        layout[f"yaxis{suffix}"] = {
            "range": yr,
            "scaleanchor": f"x{suffix}",
            "anchor": f"x{suffix}",
            "title": {"text": yt},
            **grid,
        }
    layout.update(extra)
    return layout


# --------------------------------------------------------------------------------------------
# geometry helpers (vectorized over frames: inputs of shape (F,) give (F, n))
# --------------------------------------------------------------------------------------------
def join(*parts):
    """Join polylines of shape (F, n_i) into one (F, sum n_i + gaps) with NaN gaps."""
    parts = [np.atleast_2d(np.asarray(p, dtype=float)) for p in parts]
    f = max(p.shape[0] for p in parts)
    gap = np.full((f, 1), np.nan)
    out = []
    for k, p in enumerate(parts):
        if k:
            out.append(gap)
        out.append(np.broadcast_to(p, (f, p.shape[1])))
    return np.concatenate(out, axis=1)


def select(parts, mask):
    """Per frame, join only the polylines whose ``mask[k, f]`` is true (ragged result).

    ``parts``: list of P arrays of shape (F, n_k); ``mask``: bool array (P, F).
    Returns a list of F 1-d arrays (NaN between polylines; one NaN when none is selected,
    so that the trace keeps its legend entry).
    """
    parts = [np.atleast_2d(np.asarray(p, dtype=float)) for p in parts]
    mask = np.asarray(mask, dtype=bool)
    out = []
    for f in range(mask.shape[1]):
        chosen = [p[f] for p, m in zip(parts, mask[:, f], strict=True) if m]
        pieces = []
        for k, c in enumerate(chosen):
            if k:
                pieces.append([np.nan])
            pieces.append(c)
        out.append(np.concatenate(pieces) if pieces else np.full(1, np.nan))  # keeps the legend
    return out


def circle(cx, cy, r, n: int = 48):
    """Closed circle polylines of centres ``(cx, cy)`` (shape (F,)) -> x, y of shape (F, n + 1)."""
    t = np.linspace(0.0, 2.0 * np.pi, n + 1)
    cx, cy = np.atleast_1d(cx)[:, None], np.atleast_1d(cy)[:, None]
    return cx + r * np.cos(t), cy + r * np.sin(t)


def sector(r_in, r_out, a0, a1, n: int = 12, polar=None):
    """Closed annulus-sector polygons from angle ``a0`` to ``a1`` (arrays, shape (F,)) [rad].

    ``polar(rho, angle) -> (x, y)`` maps polar coordinates to the drawing plane
    (default ``x = rho cos a``, ``y = rho sin a``). Returns x, y of shape (F, 2n + 1).
    """
    polar = polar or (lambda rho, ang: (rho * np.cos(ang), rho * np.sin(ang)))
    a0, a1 = np.atleast_1d(a0)[:, None], np.atleast_1d(a1)[:, None]
    s = np.linspace(0.0, 1.0, n)[None, :]
    outer = a0 + (a1 - a0) * s
    inner = outer[:, ::-1]
    ang = np.concatenate([outer, inner, outer[:, :1]], axis=1)
    rho = np.concatenate(
        [
            np.full(outer.shape, r_out),
            np.full(inner.shape, r_in),
            np.full((ang.shape[0], 1), r_out),
        ],
        axis=1,
    )
    return polar(rho, ang)


# --------------------------------------------------------------------------------------------
# plots
# --------------------------------------------------------------------------------------------
def _go():
    import plotly.graph_objects as go

    return go


def _base_layout(title: str, height: int) -> dict:
    return {
        "title": {"text": title, "x": 0.01, "xanchor": "left", "font": {"size": 15}},
        "height": height,
        "template": "plotly_white",
        "margin": {"l": 70, "r": 20, "t": 50, "b": 50},
        "legend": {"orientation": "h", "y": -0.12, "x": 0.0, "font": {"size": 11}},
        "hovermode": "x unified",
    }


def line_figure(x, x_label, rows, title, height=None):
    """Stacked line plots sharing the x axis.

    ``rows``: ``[(y_label, [(name, y), ...]), ...]``, one subplot per row, one trace per
    ``(name, y)``, coloured in turn from the palette; a ``(name, y, style)`` triple adds
    line options (``dash``, ``color``, ``width``; ``like_previous``: the previous trace's
    colour). Each y range is padded (:func:`_pad`),
    so that a curve at the extreme of its row is not drawn on the plot's edge.
    """
    from plotly.subplots import make_subplots

    n = len(rows)
    fig = make_subplots(rows=n, cols=1, shared_xaxes=True, vertical_spacing=0.05 if n > 1 else 0)
    k = 0
    for r, (y_label, traces) in enumerate(rows, start=1):
        for name, y, *style in traces:
            style = dict(style[0]) if style else {}
            if style.pop("like_previous", False) and k:  # e.g. a mean: the colour of its curve
                k -= 1
            line = {"color": _PALETTE[k % len(_PALETTE)], "width": 2, **style}
            fig.add_trace(_go().Scatter(x=x, y=y, name=name, mode="lines", line=line), r, 1)
            k += 1
        fig.update_yaxes(title_text=y_label, row=r, col=1)
        fig.update_yaxes(range=_pad([y for _, y, *_ in traces]), row=r, col=1)
    fig.update_xaxes(title_text=x_label, row=n, col=1)
    fig.update_layout(**_base_layout(title, height or (260 + 190 * n)))
    return fig


def _pad(arrays, frac: float = 0.05, log: bool = False):
    """Axis range ``[lo, hi]`` over ``arrays``, widened by ``frac`` of the span on each side.

    Plotly's autorange puts the extreme of a line on the plot's edge, where it hides
    under the axis (a horizontal limit line, the straight sides of a p-V loop). With
    ``log`` the range is in decades (``log10``), as plotly wants for a log axis.
    Returns ``None`` (autorange) when there is no finite value.
    """
    vals = np.concatenate([np.ravel(np.asarray(a, dtype=float)) for a in arrays])
    vals = vals[np.isfinite(vals)]
    if log:
        vals = np.log10(vals[vals > 0.0])
    if vals.size == 0:
        return None
    lo, hi = float(vals.min()), float(vals.max())
    span = hi - lo if hi > lo else max(abs(hi), 1.0)
    return [lo - frac * span, hi + frac * span]


def log_ticks(lo: float, hi: float) -> list[float]:
    """Readable tick values of a log axis from ``lo`` to ``hi``: 1, 2, 5, 10, 20, 50 ...

    Plotly labels the minor ticks of a log axis with their leading digit only
    ("2 ... 8" for 20 ... 80); explicit ``tickvals`` give full numbers. When the range
    spans less than about a decade, 3 and 7 are added (1, 2, 3, 5, 7, 10 ...).
    """
    if not (lo > 0.0 and hi > lo):
        return []
    decades = range(int(np.floor(np.log10(lo))), int(np.ceil(np.log10(hi))) + 1)
    for mantissas in ((1, 2, 5), (1, 2, 3, 5, 7), (1, 1.5, 2, 3, 4, 5, 6, 7, 8)):
        ticks = [float(f"{m * 10.0**e:.6g}") for e in decades for m in mantissas]
        ticks = [t for t in ticks if lo * (1 - 1e-9) <= t <= hi * (1 + 1e-9)]
        if len(ticks) >= 4:
            break
    return ticks


def merge_identical(traces, what: str = "chambers"):
    """Merge the ``(name, y)`` traces whose curves are identical into one, named for all.

    Identical curves drawn one over the other hide all but the last; merged, the
    legend says which they are: ``("chamber 1", p1), ("chamber 5", p1)`` become
    ``("chambers 1 and 5 (identical)", p1)``. ``name`` ends with the member's label
    (``"chamber 1"`` -> ``"1"``); ``what`` is the plural used for a merged trace.
    """
    groups: list[list] = []
    for name, y in traces:
        y = np.asarray(y, dtype=float)
        for g in groups:
            if g[1].shape == y.shape and np.allclose(g[1], y, rtol=1e-9, atol=1e-12):
                g[0].append(name)
                break
        else:
            groups.append([[name], y])
    out = []
    for names, y in groups:
        if len(names) == 1:
            out.append((names[0], y))
            continue
        labels = [str(n).rsplit(" ", 1)[-1] for n in names]
        listed = ", ".join(labels[:-1]) + f" and {labels[-1]}"
        out.append((f"{what} {listed} (identical)", y))
    return out


def svaj_figure(x, x_label, members, title):
    """Position, velocity, acceleration and jerk of both members, one row each.

    ``members``: ``[(name, colour, [(y_label, y) for s, v, a, j]), ...]``; the y labels
    are the first member's.
    """
    from plotly.subplots import make_subplots

    fig = make_subplots(rows=4, cols=1, shared_xaxes=True, vertical_spacing=0.035)
    for name, color, quantities in members:
        style = {"name": name, "mode": "lines", "legendgroup": name, "line": {"color": color}}
        for r, (_, y) in enumerate(quantities, start=1):
            fig.add_trace(_go().Scatter(x=x, y=y, showlegend=r == 1, **style), r, 1)
    for r, (lab, _) in enumerate(members[0][2], start=1):
        fig.update_yaxes(title_text=lab, row=r, col=1, title_font={"size": 11})
        fig.update_yaxes(range=_pad([m[2][r - 1][1] for m in members]), row=r, col=1)
    fig.update_xaxes(title_text=x_label, row=4, col=1)
    fig.update_layout(**_base_layout(title, 860))
    return fig


def xy_figure(
    traces, x_label, y_label, title, equal=False, height=520, legend_right=False, log=False
):
    """One plot of parametric curves ``[(name, x, y, style), ...]`` (style: dict of line opts).

    Both ranges are padded (:func:`_pad`) so that a loop's straight sides stay off the
    plot's edges, unless ``equal`` (equal scales: plotly sets the ranges). ``log``: both
    axes logarithmic, ticked with full numbers (:func:`log_ticks`).
    """
    go = _go()
    fig = go.Figure()
    for k, (name, x, y, style) in enumerate(traces):
        style = dict(style or {})
        mode = style.pop("mode", "lines")
        line = {"color": _PALETTE[k % len(_PALETTE)], "width": 2, **style.pop("line", {})}
        fig.add_trace(go.Scatter(x=x, y=y, name=name, mode=mode, line=line, **style))
    layout = _base_layout(title, height)
    layout["hovermode"] = "closest"
    if legend_right:
        layout["legend"] = {"x": 1.02, "y": 1.0, "font": {"size": 11}}
        layout["margin"] = {"l": 70, "r": 20, "t": 50, "b": 50}
    fig.update_layout(**layout)
    fig.update_xaxes(title_text=x_label)
    fig.update_yaxes(title_text=y_label)
    if equal:
        fig.update_yaxes(scaleanchor="x", scaleratio=1)
        return fig
    for axis, k in ((fig.update_xaxes, 1), (fig.update_yaxes, 2)):
        data = [t[k] for t in traces]
        axis(range=_pad(data, log=log))
        if log:
            vals = np.concatenate([np.ravel(np.asarray(a, dtype=float)) for a in data])
            vals = vals[np.isfinite(vals) & (vals > 0.0)]
            ticks = log_ticks(float(vals.min()), float(vals.max())) if vals.size else []
            axis(type="log", tickvals=ticks, ticktext=[fmt(t) for t in ticks])
    return fig


def lines_plot(pid, title, x, x_label, rows, heading, period=None, height=None, caption=""):
    """A :class:`Plot` of stacked line plots (:func:`line_figure`); ``period``: cursor period."""
    fig = line_figure(x, x_label, rows, heading, height=height)
    return Plot(pid, title, fig, caption, cursor_period_deg=period)


def svaj_plot(cols, x, x_label, members, unit, heading, period) -> Plot:
    """SVAJ of the two members from the study's time columns (``<slug>_speed_<unit>_per_s`` ...).

    ``members``: ``[(name, colour, position column, slug)]``. An angle (``unit = "rad"``)
    is shown minus its uniform mean rotation, a travel (``"m"``) as it is.
    """
    out = []
    for name, color, pos, slug in members:
        if unit == "rad":
            first = ("angle - uniform [deg]", detrend(cols[pos], x)[0])
        else:
            first = ("travel [mm]", cols[pos])
        out.append(
            (
                name,
                color,
                [first]
                + [
                    (
                        f"{label} [{unit}/s{'^' * bool(power)}{power}]",
                        cols[f"{slug}_{what}_{unit}_per_s{power}"],
                    )
                    for label, what, power in (
                        ("speed", "speed", ""),
                        ("accel.", "accel", "2"),
                        ("jerk", "jerk", "3"),
                    )
                ],
            )
        )
    return Plot(
        "plot-svaj", "SVAJ", svaj_figure(x, x_label, out, heading), cursor_period_deg=period
    )


def torque_plot(cols, x, x_label, rows, heading, period, supplied=False, caption="") -> Plot:
    """Shaft torque: the load rows ``rows = [(label, [(name, y), ...]), ...]`` (with their
    means, :func:`mean_trace`), and the inertia torque with the net torque below them.

    The study's ``shaft_torque_*`` columns are positive when the machine drives the
    shaft. ``supplied=True`` (a pump: the rows given are the torque the motor must
    supply, positive) shows the net torque on the same convention, i.e. as the motor
    torque with inertia, ``inertia - shaft torque``.
    """
    if supplied:
        net = ("motor torque with inertia", -np.asarray(cols["shaft_torque_with_inertia_Nm"]))
    else:
        net = ("net: minus inertia", cols["shaft_torque_with_inertia_Nm"])
    rows = [
        *rows,
        ("with inertia [N*m]", [("inertia torque", cols["inertia_torque_Nm"]), net]),
    ]
    plot = lines_plot(
        "plot-torque", "Shaft torque", x, x_label, rows, heading, period, caption=caption
    )
    plot.torque_sign = -1 if supplied else 1
    return plot


def mean_trace(x, mean, what: str = "mean") -> tuple:
    """A dotted line at ``mean`` in the colour of the trace before it, named with its value.

    For :func:`line_figure` rows: ``("mean 5 N*m", y, style)``.
    """
    mean = float(mean)
    mean = 0.0 if abs(mean) < 1e-9 else mean  # round-off of a zero mean, not "1.4e-16 N*m"
    y = np.full(np.shape(x), mean)
    return (
        f"{what} {fmt(mean)} N*m",
        y,
        {"dash": "dot", "width": 1.5, "like_previous": True},
    )


def detrend(q, x):
    """``q`` minus the straight line through its first and last samples (uniform rotation)."""
    q = np.asarray(q, dtype=float)
    x = np.asarray(x, dtype=float)
    slope = (q[-1] - q[0]) / (x[-1] - x[0])
    return q - q[0] - slope * (x - x[0]), slope


# --------------------------------------------------------------------------------------------
# checks shared by the drives
# --------------------------------------------------------------------------------------------
def flywheel_checks(s: dict, member_word: str = "the members", supplied=False) -> list[Check]:
    """Torque reversal and the flywheel, from the common summary keys (when present).

    ``supplied``: state the torque range as the torque the motor must supply (a pump's
    plot convention), i.e. the negated ``shaft_torque_*`` range.
    """
    out = []
    lo, hi = s.get("shaft_torque_min_Nm"), s.get("shaft_torque_max_Nm")
    if supplied and lo is not None and hi is not None:
        lo, hi = -hi + 0.0, -lo + 0.0  # + 0.0: no "-0"
        if not lo < 0.0 < hi:
            text = (f"The torque the motor must supply stays between {fmt(lo)} and {fmt(hi)} "
                    f"N*m: {member_word} never drive the shaft back.")  # fmt: skip
            out.append(Check("ok", "Shaft torque keeps its sign", text))
            lo = hi = None
    if lo is not None and hi is not None and lo < 0.0 < hi:
        text = (f"Without inertia the torque on the input shaft swings from {fmt(lo)} to "
                f"{fmt(hi)} N*m: part of each turn the shaft drives {member_word} and part of "
                "it they drive the shaft.")  # fmt: skip
        out.append(Check("note", "Shaft torque reverses", text))
    elif lo is not None and hi is not None:
        text = f"The torque on the input shaft stays between {fmt(lo)} and {fmt(hi)} N*m."
        out.append(Check("ok", "Shaft torque keeps its sign", text))
    free, wanted = s.get("speed_fluctuation_without_flywheel"), s.get("speed_fluctuation")
    fly = s.get("flywheel_inertia_kgm2")
    if None in (free, wanted, fly) or not np.isfinite(free):
        return out
    if free > wanted:
        text = (f"With the inertias of the config alone the shaft speed would vary by "
                f"{100 * free:.3g} % per turn; to keep it within {100 * wanted:.3g} % add a "
                f"flywheel of {fmt(fly)} kg*m^2.")  # fmt: skip
        out.append(Check("warning", "A flywheel is needed", text))
    else:
        text = (f"The shaft speed varies by {100 * free:.3g} % per turn with the inertias of the "
                f"config, within the wanted {100 * wanted:.3g} %.")  # fmt: skip
        out.append(Check("ok", "No flywheel needed", text))
    return out


def force_plot(cols, x, x_label, heading, period=None) -> Plot | None:
    """Normal force of every pair (``*_force_N`` columns) and the contact stresses
    (``*_contact_stress_MPa``) over the input angle; None when the study has no pairs."""
    forces = []  # pairs that carry the same force share one curve, named by both
    for k in (k for k in cols if k.endswith("_force_N")):
        name, y = k[: -len("_force_N")].replace("_", " "), np.asarray(cols[k], dtype=float)
        same = next((i for i, (_, f) in enumerate(forces) if np.allclose(f, y)), None)
        if same is None:
            forces.append((name, y))
        else:
            forces[same] = (f"{forces[same][0]} = {name}", forces[same][1])
    if not forces:
        return None
    rows = [("force [N]", forces)]
    stresses = [(k[: -len("_contact_stress_MPa")].replace("_", " "), cols[k]) for k in cols
                if k.endswith("_contact_stress_MPa")]  # fmt: skip
    if stresses:
        rows.append(("Hertz pressure [MPa]", stresses))
    if "friction_torque_Nm" in cols:
        rows.append(("friction torque [N*m]", [("friction", cols["friction_torque_Nm"])]))
    return lines_plot("plot-forces", "Forces", x, x_label, rows, heading, period,
                      caption="Normal force of every load-carrying pair, the peak Hertz "
                      "pressure of the contacts and the torque friction takes from the shaft "
                      "(first order in the friction coefficients).")  # fmt: skip


def contact_checks(summary: dict, cfg: dict) -> list[Check]:
    """Contact stress against the allowable, and the mechanical efficiency, in words."""
    out = []
    contact = cfg.get("contact") or {}
    sf = summary.get("contact_safety_factor")
    if sf is not None and np.isfinite(sf):
        allowable = contact.get("allowable_stress", 1.5e9) / 1e6
        peak = summary.get("peak_contact_stress_MPa")
        where = summary.get("peak_contact_stress_pair", "a contact")
        if sf < 1.0:
            out.append(Check("error", "Contact stress above the allowable",
                             f"{where} reaches {fmt(peak)} MPa, above contact.allowable_stress = "
                             f"{fmt(allowable)} MPa (safety factor {fmt(sf)}): a wider roller, "
                             "larger radii of curvature or a harder material"))  # fmt: skip
        else:
            out.append(Check("ok", "Contact stress",
                             f"peak {fmt(peak)} MPa at {where}, safety factor {fmt(sf)} against "
                             f"{fmt(allowable)} MPa"))  # fmt: skip
    eta = summary.get("mechanical_efficiency")
    if eta is not None and np.isfinite(eta):
        least = contact.get("efficiency_min", 0.9)
        level = "warning" if eta < least else "ok"
        out.append(Check(level, "Mechanical efficiency",
                         f"{fmt(100 * eta)} % ({fmt(summary.get('friction_loss_W'))} W lost to "
                         f"friction at the run speed); the threshold is {fmt(100 * least)} % "
                         "(contact.efficiency_min)"))  # fmt: skip
    return out
