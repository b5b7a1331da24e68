"""One self-contained, offline HTML report of a run: header, summary, checks, animation, plots.

The page is one file: the text and tables first, then one JSON block with every
figure and the frames of the mechanism, the page's scripts, and plotly.js as inert
text at the very end (started from a Blob URL once the text is painted: the
summary shows at once, not after 5 MB of script). Nothing comes from the network.

* Summary (:mod:`rotorkin.report.summary`): labels in words, a definition, a unit
  and one torque sign rule per row, the paper's value beside ours.
* Mechanism: drawn as SVG from the frames' coordinates (computed in Python from the
  drive's and machine's own functions, see :mod:`rotorkin.render.scenes`) by
  :mod:`rotorkin.report.scene_js`; the panels stack on narrow screens.
* Player (sticky at the top from the mechanism to the end of the plots): play /
  pause by elapsed time at a chosen speed, steps, a slider, an angle box and a small
  plot of one curve with the cursor (:mod:`rotorkin.report.page_js`).
* Plots (:mod:`rotorkin.report.plots`): hover with full names, 4 significant digits
  and units, angle axes by 90 deg, dashes as well as colours, extremes marked and
  tabulated, failed checks drawn, a CSV link each; a cursor at the player's angle.

For tests and curious users the page exposes ``window.ROTORKIN``: ``ready``
(true once the mechanism and every 2D plot are drawn), ``plots`` (``id``, ``traces``,
``kind`` per drawn plot), ``deferred`` (the WebGL plots, drawn only while near the
screen: their render loop would slow the player down), ``scene`` (the animated trace
indices, frame count, ``map(trace)`` of a 2D trace's data to SVG pixels), ``frame``,
``playing``, ``drawn`` (frames drawn), ``timing`` [ms since navigation], ``errors``
(uncaught script errors) and ``show(f)`` (draw frame ``f``, returns a promise).
"""

from __future__ import annotations

import datetime as _dt
import html as _html
import json
import os
import tempfile
from pathlib import Path

import numpy as np

from rotorkin.core.errors import ConfigError
from rotorkin.drives import spec_of
from rotorkin.io.output import out_error, to_toml
from rotorkin.render import member_scene
from rotorkin.render.scenes import Check
from rotorkin.report.page_css import PAGE_CSS
from rotorkin.report.page_js import PAGE_JS
from rotorkin.report.plots import angle_symbol, format_extremes, prepare
from rotorkin.report.scene_js import SCENE_JS
from rotorkin.report.summary import TORQUE_SIGN_TEXT, summary_tables
from rotorkin.report.text import esc, plain, pretty
from rotorkin.studies.checks import rows as check_rows
from rotorkin.studies.published import paper_rows

__all__ = ["write_report", "render_report", "FRAMES"]

#: Frames of the mechanism over one period.
FRAMES = 120
#: Playback at speed 1x: one period of the input angle in this many seconds.
SECONDS_PER_PERIOD = 4.0

_LEVEL_TEXT = {"ok": "OK", "note": "NOTE", "warning": "WARNING", "error": "ERROR"}


def write_report(result, cfg, raw, meta, path) -> Path:
    """Write the interactive HTML report of a run, atomically.

    Parameters
    ----------
    result : rotorkin.studies.StudyResult
        From :func:`rotorkin.drives.evaluate` on ``cfg``.
    cfg : dict
        The validated config (SI values) the result was computed from.
    raw : dict
        The config as written (after ``--set``), shown as TOML.
    meta : dict
        ``name``, ``drive_type``, ``rotorkin_version``.
    path : path-like
        The HTML file to write; its folder is created if missing. The page is
        written to a temporary file next to it and moved into place at the end.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    if path.exists() and path.is_dir():
        raise ConfigError(f"report path = {str(path)!r} is not admissible: it is a folder")
    text = render_report(result, cfg, raw, meta)
    parent = path.parent if str(path.parent) else Path(".")
    try:
        parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=parent)
    except OSError as exc:
        out_error(parent, exc)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes it private; a report is for reading
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


def render_report(result, cfg, raw, meta, frames: int = FRAMES) -> str:
    """The report as one HTML string (see :func:`write_report`)."""
    import plotly.offline

    spec = spec_of(cfg)
    mod = spec.scene or member_scene
    scene = mod.scene(result, cfg, frames)
    plots = mod.plots(result, cfg)
    failed = [c for c in result.checks if not c.passed]
    entries = [prepare(p, failed) for p in plots]
    sign = next((p.torque_sign for p in plots if p.id == "plot-torque"), 1)
    checks = [Check("warning", "Input", line) for line in result.warnings]
    for c, (name, value, limit, margin, _) in zip(result.checks, check_rows(result.checks),
                                                  strict=True):  # fmt: skip
        where = [x for x in entries if c.name in x["checks"]]
        shown = ""
        if where:
            links = ", ".join(f"<a href='#box-{x['id']}'>{_html.escape(x['title'])}</a>"
                              for x in where)  # fmt: skip
            shown = f" Marked on the plot{'s' if len(where) > 1 else ''}: {links}."
        text = f"{value}, limit {limit}, margin {margin} ({c.key}).{shown}"
        checks.append(Check("ok" if c.passed else "error", name, text))
    checks += mod.checks(result, cfg)
    papers = paper_rows(spec.published, spec.paper, cfg, result.summary)
    angles = np.asarray(scene.angles_deg, dtype=float)
    period = float((angles[1] - angles[0]) * len(angles)) if len(angles) > 1 else 360.0
    angle_label = pretty(esc(scene.angle_label))
    symbol = angle_symbol(angle_label)
    mini = next((x["id"] for x in entries if x["id"] == "plot-torque" and x["curves"]), None)
    mini = mini or next((x["id"] for x in entries if x["curves"]), "")
    data = {
        "plots": [_plot_json(x) for x in entries],
        "scene": {
            "id": "mechanism",
            "figure": _plain(_pretty_scene(scene.figure)),
            "kind": _kind(scene.figure["data"]),
            "animated": scene.animated,
            "frames": _pretty_frames(scene),
            "angles_deg": scene.angles_deg,
            "angle_label": angle_label,
            "angle_symbol": symbol,
            "period_deg": period,
            "seconds_per_period": SECONDS_PER_PERIOD,
            "readouts": scene.readouts,
        },
        "mini_default": mini,
    }
    blob = json.dumps(data, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
    title = str(raw.get("title") or cfg.get("title") or result.title)
    when = _dt.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    e = _html.escape
    body = [
        "<header>",
        f"<h1>{e(title)}</h1>",
        f"<p class='sub'>{e(result.title)}</p>",
        "<p class='meta'>",
        f"example/config <b>{e(str(meta.get('name', '')))}</b> &middot; drive "
        f"<code>{e(str(meta.get('drive_type', result.drive_type)))}</code> &middot; rotorkin "
        f"{e(str(meta.get('rotorkin_version', '')))} &middot; written {e(when)}",
        "</p>",
        "<details class='config'><summary>Configuration (TOML, as run)</summary>",
        f"<pre id='config-toml'>{e(to_toml(raw))}</pre></details>",
        _nav(entries),
        "</header>",
        "<section id='summary'><h2>Summary</h2>",
        "<p class='hint'>Our values at this config; beside them the paper's value where the "
        "paper gives one for this config: <i>printed</i> = a number the paper prints for its own "
        "case, <i>formula</i> = the paper's closed-form equation evaluated at this config. "
        f"Shaft torque, {TORQUE_SIGN_TEXT[sign].removeprefix('sign: ')}. Values within "
        "10<sup>−9</sup> of the "
        "largest value of the same unit are round-off and shown as 0.</p>",
        summary_tables(result, papers, sign),
        "</section>",
        "<section id='checks'><h2>Checks and warnings</h2>",
        _checks_html(checks),
        "</section>",
        "<div class='stage'>",
        "<h2 id='animation'>Mechanism</h2>",
        _player(scene, angle_label, symbol, period),
        "<div id='mechanism' class='mech'></div>",
        _readouts(scene),
        f"<p class='caption'>{pretty(esc(scene.caption))}</p>",
        "<section id='plots'><h2>Plots</h2>",
        "<p class='hint'>Hover for values (4 significant digits, with units), drag to zoom, "
        "double-click to reset; ▲ / ▼ mark each curve's largest and smallest value, ✖ a "
        "failed design check. The dashed cursor follows the player's angle.</p>",
    ]
    for x in entries:
        body.append(_plot_box(x))
    body += [
        "</section>",
        "</div>",
        "<footer>rotorkin report: one file, works offline. Plots by plotly.js (embedded; it "
        "starts after the text is shown), mechanism drawn as SVG from the model's "
        "coordinates.</footer>",
    ]
    plotly_js = plotly.offline.get_plotlyjs().replace("</script", "<\\/script")
    return "\n".join(
        [
            "<!DOCTYPE html>",
            "<html lang='en'><head><meta charset='utf-8'>",
            "<meta name='viewport' content='width=device-width, initial-scale=1'>",
            f"<title>rotorkin report: {e(title)}</title>",
            f"<style>{PAGE_CSS}</style>",
            "</head><body><main>",
            *body,
            "</main>",
            f"<script type='application/json' id='rotorkin-data'>{blob}</script>",
            f"<script>{SCENE_JS}</script>",
            f"<script>{PAGE_JS}</script>",
            f"<script type='text/plain' id='plotly-src'>{plotly_js}</script>",
            "</body></html>",
            "",
        ]
    )


# --------------------------------------------------------------------------------------------
# pieces of the page
# --------------------------------------------------------------------------------------------
def _nav(entries) -> str:
    links = [("summary", "Summary"), ("checks", "Checks"), ("animation", "Mechanism")]
    links += [(f"box-{x['id']}", x["title"]) for x in entries]
    items = " &middot; ".join(f"<a href='#{i}'>{_html.escape(t)}</a>" for i, t in links)
    return f"<nav>{items}</nav>"


def _checks_html(checks) -> str:
    e = _html.escape
    items = []
    for c in checks:
        text = c.text if "<a href=" in c.text else esc(c.text)
        items.append(
            f"<li class='check {e(c.level)}'><span class='badge'>"
            f"{_LEVEL_TEXT.get(c.level, c.level.upper())}</span> <b>{pretty(esc(c.title))}.</b> "
            f"{pretty(text)}</li>"
        )
    return f"<ul id='checks-list'>{''.join(items)}</ul>"


def _player(scene, angle_label: str, symbol: str, period: float) -> str:
    n = len(scene.angles_deg)
    step = period / max(n, 1)
    speeds = "".join(
        f"<option value='{v}'{' selected' if v == 1 else ''}>{t}</option>"
        for v, t in ((0.25, "¼×"), (0.5, "½×"), (1, "1×"), (2, "2×"))
    )
    return (
        "<div id='player' class='player' role='group' aria-label='mechanism player'>"
        "<div class='controls'>"
        "<button id='play-button' type='button' aria-pressed='false' title='play / pause'>"
        "&#9654; Play</button>"
        "<button id='step-back' type='button' title='previous frame' aria-label='previous frame'>"
        "&#9664;</button>"
        "<button id='step-fwd' type='button' title='next frame' aria-label='next frame'>"
        "&#9654;</button>"
        f"<input id='angle-slider' type='range' min='0' max='{n - 1}' step='1' value='0' "
        f"aria-label='{_html.escape(plain(angle_label))}'>"
        f"<label class='angle' title='{_html.escape(plain(angle_label))}: type an angle, Enter "
        f"(nearest of {n} frames)'>{symbol} = <input id='angle-input' type='number' "
        f"inputmode='decimal' min='0' max='{period:g}' step='{step:g}' value='0'>°</label>"
        f"<label class='speed' title='1× = one period in {SECONDS_PER_PERIOD:g} s'>"
        f"<span class='speed-word'>speed </span><select id='speed' aria-label='speed'>{speeds}"
        "</select></label>"
        "</div>"
        "<div class='mini'><select id='mini-select' aria-label='curve in the small plot'>"
        "</select><span id='mini-value'></span><div class='mini-plot'><svg id='mini-svg' "
        "role='img' aria-label='the chosen curve over one period, with the player\u2019s "
        "angle'></svg><div id='mini-cursor'></div><div id='mini-dot'></div></div>"
        "</div></div>"
    )


def _readouts(scene) -> str:
    reads = "".join(
        f"<span class='ro'><span class='ro-label'>{pretty(esc(r['label']))}</span> "
        f"<span class='ro-value' data-i='{k}'></span>{_unit(r['unit'])}</span>"
        for k, r in enumerate(scene.readouts)
    )
    return f"<div class='readouts'>{reads}</div>"


def _unit(unit: str) -> str:
    u = pretty(esc(unit))
    return "" if not u else u if u == "°" else f"\u2009{u}"


def _plot_box(x: dict) -> str:
    e = _html.escape
    height = int((x["figure"]["layout"] or {}).get("height") or 450)
    tools = [f"<a id='csv-{x['id']}' href='#' download='{x['id'][5:]}.csv'>CSV of the data</a>"]
    if x["checks"]:
        tools.append(f"<span class='failed'>✖ failed: {e('; '.join(x['checks']))}</span>")
    parts = [
        f"<div class='plot-box' id='box-{x['id']}'>",
        f"<h3>{e(x['title'])}</h3>",
        f"<p class='heading'>{x['heading']}</p>",
        f"<div class='plot-tools'>{''.join(tools)}</div>",
        f"<div id='{x['id']}' class='plot' style='min-height:{height}px'></div>",
    ]
    if x["caption"]:
        parts.append(f"<p class='caption'>{x['caption']}</p>")
    if x["extremes"]:
        parts.append(
            "<details class='ext'><summary>Extremes: each curve's largest and smallest value "
            "and where</summary>" + format_extremes(x["extremes"], x["x_symbol"]) + "</details>"
        )
    parts.append("</div>")
    return "".join(parts)


def _pretty_scene(fig: dict) -> dict:
    """The scene's names, titles and axis labels in the page's style (Greek letters, units)."""
    fig = {"data": [dict(t) for t in fig["data"]], "layout": dict(fig["layout"])}
    for t in fig["data"]:
        if t.get("name"):
            t["name"] = pretty(esc(t["name"]))
        if isinstance(t.get("text"), list):
            t["text"] = [pretty(str(v)) for v in t["text"]]
    layout = fig["layout"]
    for k, v in list(layout.items()):
        if (k.startswith(("xaxis", "yaxis")) or k == "scene") and isinstance(v, dict):
            v = layout[k] = dict(v)
            t = v.get("title")
            if isinstance(t, dict) and t.get("text"):
                v["title"] = {**t, "text": pretty(t["text"])}
    layout["annotations"] = [{**a, "text": pretty(a.get("text", ""))}
                             for a in layout.get("annotations") or []]  # fmt: skip
    return fig


def _pretty_frames(scene) -> list:
    """The frames with their text labels in the page's style (``cm3`` -> ``cm³``, Greek)."""
    cache: dict[str, str] = {}

    def one(text):
        if text not in cache:
            cache[text] = pretty(text)
        return cache[text]

    out = []
    for frame in scene.frames:
        out.append([{**d, "text": [one(t) for t in d["text"]]} if "text" in d else d
                    for d in frame])  # fmt: skip
    return out


def _kind(traces) -> str:
    three = {"scatter3d", "mesh3d", "surface", "cone", "streamtube", "isosurface", "volume"}
    return "3d" if any(t.get("type") in three for t in traces) else "2d"


def _plot_json(x: dict) -> dict:
    fig = _plain(x["figure"])
    return {
        "id": x["id"],
        "title": x["title"],
        "heading": x["heading"],
        "figure": fig,
        "kind": _kind(fig["data"]),
        "cursor_period_deg": x["cursor_period_deg"],
        "csv": x["csv"],
        "short": x["short"],
        "curves": x["curves"],
    }


def _round_sig(a: np.ndarray, sig: int = 6) -> list:
    a = np.asarray(a, dtype=float)
    finite = np.isfinite(a)
    big = float(np.max(np.abs(a[finite]))) if finite.any() else 0.0
    if big > 0.0:
        a = np.round(a, max(0, sig - 1 - int(np.floor(np.log10(big)))))
    return [v if f else None for v, f in zip(a.tolist(), finite.ravel().tolist(), strict=True)]


def _plain(obj):
    """Figures to JSON-able Python: arrays rounded to 6 significant digits, NaN -> null."""
    if isinstance(obj, dict):
        return {k: _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fiu" and obj.ndim == 1:
            return _round_sig(obj)
        if obj.dtype.kind in "fiu":
            return [_plain(row) for row in obj]
        return [_plain(v) for v in obj.tolist()]
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not np.isfinite(obj):
        return None
    return obj
