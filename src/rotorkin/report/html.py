"""One self-contained, offline HTML report of a run: header, summary, checks, animation, plots.

The page embeds plotly.js once, inline (no CDN, no network), and one JSON block
with every figure and the frames of the mechanism. A small script draws the
plots with ``Plotly.newPlot`` and animates the mechanism: a slider scrubs the
input angle, a button plays and pauses, and each frame's coordinates (computed
in Python from the drive's and machine's own functions, see
:mod:`rotorkin.render.scenes`) are swapped in with ``Plotly.restyle``. Plots
whose x axis is the input angle show a cursor at the slider's angle.

For tests and curious users the page exposes ``window.ROTORKIN``: ``ready``
(true once everything is drawn), ``plots`` (``id``, ``traces``, ``kind`` per plot),
``scene`` (the animated trace indices and frame count), ``frame``, ``playing``, ``errors``
(uncaught script errors), ``show(f)`` (draw frame ``f``, returns a promise).
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
from rotorkin.render.scenes import Check, fmt
from rotorkin.studies.checks import rows as check_rows
from rotorkin.studies.published import paper_rows

__all__ = ["write_report", "render_report", "FRAMES"]

#: Frames of the mechanism over one period.
FRAMES = 120

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
    checks = [Check("warning", "Input", line) for line in result.warnings]
    checks += [Check("ok" if c.passed else "error", name, f"{value}, limit {limit}, margin "
                     f"{margin} ({c.key})") for c, (name, value, limit, margin, _)
               in zip(result.checks, check_rows(result.checks), strict=True)]  # fmt: skip
    checks += mod.checks(result, cfg)
    papers = paper_rows(spec.published, spec.paper, cfg, result.summary)
    data = {
        "plots": [_plot_json(p) for p in plots],
        "scene": {
            "id": "mechanism",
            "figure": _plain(scene.figure),
            "kind": _kind(scene.figure["data"]),
            "animated": scene.animated,
            "frames": scene.frames,
            "angles_deg": scene.angles_deg,
            "angle_label": scene.angle_label,
            "readouts": scene.readouts,
        },
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
        _nav(plots),
        "</header>",
        "<section id='summary'><h2>Summary</h2>",
        "<p class='hint'>Our values at this config; beside them the paper's value where the "
        "paper gives one for this config: <i>printed</i> = a number the paper prints for its own "
        "case, <i>formula</i> = the paper's closed-form equation evaluated at this config. "
        "Difference = ours - paper.</p>",
        _summary_table(result, papers),
        "</section>",
        "<section id='checks'><h2>Checks and warnings</h2>",
        _checks_html(checks),
        "</section>",
        "<section id='animation'><h2>Mechanism</h2>",
        _controls(scene),
        "<div id='mechanism' class='plot'></div>",
        f"<p class='caption'>{e(scene.caption)}</p>",
        "</section>",
        "<section id='plots'><h2>Plots</h2>",
    ]
    for p in plots:
        body.append(f"<div class='plot-box'><div id='{p.id}' class='plot'></div>")
        if p.caption:
            body.append(f"<p class='caption'>{e(p.caption)}</p>")
        body.append("</div>")
    body += [
        "</section>",
        "<footer>rotorkin report; interactive plots by plotly.js (embedded, works offline). "
        "Hover for values, drag to zoom, double-click to reset.</footer>",
    ]
    return "\n".join(
        [
            "<!DOCTYPE html>",
            "<html lang='en'><head><meta charset='utf-8'>",
            "<meta name='viewport' content='width=device-width, initial-scale=1'>",
            f"<title>rotorkin report: {e(title)}</title>",
            f"<style>{_CSS}</style>",
            f"<script>{plotly.offline.get_plotlyjs()}</script>",
            "</head><body><main>",
            *body,
            "</main>",
            f"<script type='application/json' id='rotorkin-data'>{blob}</script>",
            f"<script>{_JS}</script>",
            "</body></html>",
            "",
        ]
    )


# --------------------------------------------------------------------------------------------
# pieces of the page
# --------------------------------------------------------------------------------------------
def _nav(plots) -> str:
    links = [("summary", "Summary"), ("checks", "Checks"), ("animation", "Mechanism")]
    links += [(p.id, p.title) for p in plots]
    items = " &middot; ".join(f"<a href='#{i}'>{_html.escape(t)}</a>" for i, t in links)
    return f"<nav>{items}</nav>"


def _value(v) -> str:

    return _html.escape(fmt(v, 6 if isinstance(v, float) else 4))


def _small(v) -> str:
    """A difference or tolerance: 3 significant digits, ``g`` style (``1e-06``)."""
    v = float(v)
    return "0" if v == 0.0 else _html.escape(f"{v:.3g}")


def _summary_table(result, papers) -> str:
    e = _html.escape
    keys = list(result.headline) + [k for k in papers if k not in result.headline]
    head = (
        "<tr><th>metric</th><th>ours</th><th>paper</th><th>difference</th>"
        "<th>tolerance</th><th>source</th></tr>"
    )
    rows = []
    for key in keys:
        if key not in result.summary:
            continue
        ours = result.summary[key]
        p = papers.get(key)
        if p is None:
            cells = "<td></td><td></td><td></td><td></td>"
            cls = ""
        else:
            mark = "&#10003;" if p["within"] else "&#10007;"
            cls = " class='agree'" if p["within"] else " class='disagree'"
            src = f"{p['reference']}, {p['where']} ({p['kind']})"
            if p["note"]:
                src += f": {p['note']}"
            cells = (
                f"<td class='num paper'>{_value(p['paper'])}</td>"
                f"<td class='num diff'>{_small(p['difference'])} {mark}</td>"
                f"<td class='num'>{_small(p['tolerance'])}</td><td>{e(src)}</td>"
            )
        rows.append(
            f"<tr data-key='{e(key)}'{cls}><td><code>{e(key)}</code></td>"
            f"<td class='num ours'>{_value(ours)}</td>{cells}</tr>"
        )
    main = f"<table id='summary-table'>{head}{''.join(rows)}</table>"
    every = "".join(
        f"<tr data-key='{e(k)}'><td><code>{e(k)}</code></td><td class='num'>{_value(v)}</td></tr>"
        for k, v in result.summary.items()
    )
    return (
        main + "<details><summary>All metrics (" + str(len(result.summary)) + ")</summary>"
        f"<table id='all-metrics'><tr><th>metric</th><th>value</th></tr>{every}</table>"
        "</details>"
    )


def _checks_html(checks) -> str:
    e = _html.escape
    items = []
    for c in checks:
        items.append(
            f"<li class='check {e(c.level)}'><span class='badge'>"
            f"{_LEVEL_TEXT.get(c.level, c.level.upper())}</span> <b>{e(c.title)}.</b> "
            f"{e(c.text)}</li>"
        )
    return f"<ul id='checks-list'>{''.join(items)}</ul>"


def _controls(scene) -> str:
    e = _html.escape
    n = len(scene.angles_deg)
    reads = "".join(
        f"<span class='ro'><span class='ro-label'>{e(r['label'])}</span> "
        f"<span class='ro-value' data-i='{k}'></span> {e(r['unit'])}</span>"
        for k, r in enumerate(scene.readouts)
    )
    return (
        "<div class='controls'>"
        "<button id='play-button' type='button' title='play / pause'>&#9654; Play</button>"
        "<button id='step-back' type='button' title='previous frame'>&#9664;</button>"
        "<button id='step-fwd' type='button' title='next frame'>&#9654;</button>"
        f"<input id='angle-slider' type='range' min='0' max='{n - 1}' step='1' value='0' "
        f"aria-label='{e(scene.angle_label)}'>"
        f"<span class='angle'>{e(scene.angle_label)} = <b id='angle-value'>0</b> deg</span>"
        f"</div><div class='readouts'>{reads}</div>"
    )


def _kind(traces) -> str:
    three = {"scatter3d", "mesh3d", "surface", "cone", "streamtube", "isosurface", "volume"}
    return "3d" if any(t.get("type") in three for t in traces) else "2d"


def _plot_json(p) -> dict:
    fig = p.figure.to_plotly_json() if hasattr(p.figure, "to_plotly_json") else p.figure
    fig = _plain(fig)
    return {
        "id": p.id,
        "title": p.title,
        "figure": fig,
        "kind": _kind(fig["data"]),
        "cursor_period_deg": p.cursor_period_deg,
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


_CSS = """
body{margin:0;background:#f4f5f7;color:#1d2330;font:15px/1.45 system-ui,-apple-system,
'Segoe UI',Roboto,sans-serif}
main{max-width:1320px;margin:0 auto;padding:18px 26px 40px;background:#fff;
box-shadow:0 0 12px rgba(0,0,0,.06)}
h1{font-size:24px;margin:6px 0 2px}h2{font-size:19px;border-bottom:2px solid #e3e6ea;
padding-bottom:4px;margin-top:30px}
.sub{margin:0;color:#445}.meta{color:#556;font-size:13px;margin:6px 0}
nav{font-size:13px;margin:10px 0 0;padding:8px 10px;background:#f1f3f6;border-radius:6px}
nav a{color:#1a5fb4;text-decoration:none}nav a:hover{text-decoration:underline}
details.config pre{background:#f7f7f9;border:1px solid #e3e3e8;padding:10px;font-size:12.5px;
max-height:340px;overflow:auto}
summary{cursor:pointer;color:#1a5fb4}
table{border-collapse:collapse;font-size:13.5px;margin:8px 0}
th,td{border-bottom:1px solid #e6e8eb;padding:4px 10px;text-align:left;vertical-align:top}
th{background:#f1f3f6}td.num{text-align:right;font-variant-numeric:tabular-nums;
white-space:nowrap}
tr.agree td.diff{color:#1e7b34}tr.disagree td.diff{color:#b3261e;font-weight:600}
.hint,.caption{color:#556;font-size:13px}
ul#checks-list{list-style:none;padding:0}
li.check{margin:6px 0;padding:7px 10px;border-left:5px solid #999;background:#fafafa}
li.ok{border-color:#2e9d4a}li.note{border-color:#3b78c4}li.warning{border-color:#e0a100;
background:#fffaf0}li.error{border-color:#c62828;background:#fff3f2}
.badge{display:inline-block;min-width:64px;font-size:11px;font-weight:700;letter-spacing:.04em}
li.ok .badge{color:#2e9d4a}li.note .badge{color:#3b78c4}li.warning .badge{color:#a87400}
li.error .badge{color:#c62828}
.controls{display:flex;align-items:center;gap:8px;flex-wrap:wrap;margin:6px 0}
.controls button{font-size:14px;padding:4px 10px;border:1px solid #b8bec8;border-radius:5px;
background:#f6f7f9;cursor:pointer}
#angle-slider{flex:1 1 380px;min-width:240px}.angle{font-size:14px;min-width:220px}
.readouts{display:flex;flex-wrap:wrap;gap:6px 18px;font-size:13px;color:#334;margin:4px 0 6px}
.ro-label{color:#667}.ro-value{font-weight:600;font-variant-numeric:tabular-nums}
.plot{width:100%;position:relative}.plot-box{margin:14px 0 22px}
.cursor{position:absolute;width:0;border-left:1.5px dotted rgba(20,20,20,.55);
pointer-events:none;display:none}
footer{margin-top:30px;color:#778;font-size:12px}
"""

_JS = r"""
(function () {
  "use strict";
  var R = window.ROTORKIN = {ready: false, errors: [], plots: [], scene: null, frame: 0};
  window.addEventListener("error", function (ev) { R.errors.push(String(ev.message)); });
  window.addEventListener("unhandledrejection", function (ev) {
    R.errors.push("unhandled rejection: " + String(ev.reason));
  });
  var D = JSON.parse(document.getElementById("rotorkin-data").textContent);
  var config = {responsive: true, displaylogo: false,
                toImageButtonOptions: {format: "png", scale: 2}};
  var jobs = [], cursors = [];
  D.plots.forEach(function (p) {
    var el = document.getElementById(p.id), layout = p.figure.layout;
    var job = Plotly.newPlot(el, p.figure.data, layout, config);
    if (p.cursor_period_deg) {
      // the slider's angle on this plot: a thin line over the plot area (an HTML overlay, so
      // moving it does not redraw the plot)
      var c = {el: el, period: p.cursor_period_deg, x: 0, div: document.createElement("div")};
      c.div.className = "cursor";
      cursors.push(c);
      job = job.then(function () {
        el.appendChild(c.div);
        el.on("plotly_afterplot", function () { place(c); });
        place(c);
      });
    }
    jobs.push(job);
    R.plots.push({id: p.id, traces: p.figure.data.length, kind: p.kind});
  });
  var S = D.scene, gd = document.getElementById(S.id);
  jobs.push(Plotly.newPlot(gd, S.figure.data, S.figure.layout, config));
  R.plots.push({id: S.id, traces: S.figure.data.length, kind: S.kind});
  R.scene = {id: S.id, animated: S.animated, frames: S.frames.length, angles_deg: S.angles_deg};
  var slider = document.getElementById("angle-slider");
  var angleOut = document.getElementById("angle-value");
  var reads = document.querySelectorAll(".ro-value");
  var playBtn = document.getElementById("play-button");
  var keys = {};
  S.frames[0].forEach(function (d) { Object.keys(d).forEach(function (k) { keys[k] = 1; }); });
  keys = Object.keys(keys);
  function update(f) {
    // one restyle for all animated traces; undefined leaves a trace's attribute unchanged
    var upd = {}, fr = S.frames[f];
    keys.forEach(function (k) {
      upd[k] = S.animated.map(function (t, i) { return fr[i][k]; });
    });
    return upd;
  }
  function fmt(v) { return Math.abs(v) >= 1000 ? v.toFixed(0) : v.toPrecision(4); }
  function place(c) {
    var fl = c.el._fullLayout, ax = fl && fl.xaxis;
    if (!ax || !fl._size) { return; }
    var r = ax.range, inside = c.x >= Math.min(r[0], r[1]) && c.x <= Math.max(r[0], r[1]);
    c.div.style.left = (ax._offset + ax.l2p(c.x)) + "px";
    c.div.style.top = fl._size.t + "px";
    c.div.style.height = fl._size.h + "px";
    c.div.style.display = inside ? "block" : "none";
  }
  function cursorsTo(a) {
    cursors.forEach(function (c) { c.x = ((a % c.period) + c.period) % c.period; place(c); });
  }
  function show(f) {
    f = ((f % S.frames.length) + S.frames.length) % S.frames.length;
    R.frame = f;
    slider.value = f;
    var a = S.angles_deg[f];
    angleOut.textContent = a.toFixed(1);
    S.readouts.forEach(function (r, k) { reads[k].textContent = fmt(r.values[f]); });
    cursorsTo(a);
    return Plotly.restyle(gd, update(f), S.animated);
  }
  R.show = show;
  var timer = null, busy = false, pending = null;
  function request(f) {  // draw frame f; while a frame is drawing, keep only the latest request
    if (busy) { pending = f; return; }
    busy = true;
    function done() {
      busy = false;
      if (pending !== null) { var q = pending; pending = null; request(q); }
    }
    show(f).then(done, function (err) { R.errors.push(String(err)); done(); });
  }
  function tick() { if (!busy) { request(R.frame + 1); } }
  function setPlaying(on) {
    if (on && !timer) {
      timer = setInterval(tick, 70);
      playBtn.innerHTML = "&#10073;&#10073; Pause";
    }
    if (!on && timer) { clearInterval(timer); timer = null; playBtn.innerHTML = "&#9654; Play"; }
    R.playing = !!timer;
  }
  playBtn.addEventListener("click", function () { setPlaying(!timer); });
  document.getElementById("step-back").addEventListener("click", function () {
    setPlaying(false); request(R.frame - 1);
  });
  document.getElementById("step-fwd").addEventListener("click", function () {
    setPlaying(false); request(R.frame + 1);
  });
  slider.addEventListener("input", function () {
    setPlaying(false); request(parseInt(slider.value, 10));
  });
  Promise.all(jobs).then(function () { return show(0); }).then(function () {
    R.ready = true;
  }, function (err) { R.errors.push(String(err)); });
})();
"""
