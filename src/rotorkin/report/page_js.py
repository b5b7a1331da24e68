"""The page's script: the player, the mechanism, the plots drawn after the text (JavaScript).

Order of work, so that the text and tables show at once and the page never freezes:

1. the summary, checks and captions are plain HTML, drawn before any script runs;
2. the mechanism is drawn as SVG by :data:`rotorkin.report.scene_js.SCENE_JS` and the
   player works at once (it does not need plotly);
3. plotly.js, embedded as inert text at the end of the page, is then started from a
   Blob URL, and the plots are drawn one per task, those nearest the screen first;
   WebGL plots only while they are near the screen (their render loop runs on every
   animation frame and would halve the player's frame rate in software rendering).

Playback runs by elapsed time (``requestAnimationFrame``): the frame shown is the
one the clock has reached at the chosen speed, so a slow machine skips frames
instead of slowing down. ``window.ROTORKIN`` exposes ``ready``, ``errors``,
``plots``, ``deferred``, ``scene``, ``frame``, ``playing``, ``drawn`` (frames drawn),
``timing``, ``retried`` (the messages of failed parses of plotly.js that a second parse
made good) and ``show(frame)`` (returns a promise) for scripts and tests.
"""

PAGE_JS = r"""
(function () {
  "use strict";
  var t0 = performance.now();
  var R = window.ROTORKIN = {ready: false, errors: [], plots: [], scene: null, frame: 0,
                             playing: false, drawn: 0, deferred: [], timing: {script: t0},
                             retried: []};
  window.addEventListener("error", function (ev) {
    // a failed parse of plotly.js from its Blob URL is retried (startPlotly), not an error yet
    if (R.plotlyUrl && ev.filename === R.plotlyUrl) R.retried.push(String(ev.message));
    else R.errors.push(String(ev.message));
  });
  window.addEventListener("unhandledrejection", function (ev) {
    R.errors.push("unhandled rejection: " + String(ev.reason));
  });
  var D = JSON.parse(document.getElementById("rotorkin-data").textContent);
  var S = D.scene, n = S.frames.length;
  var $ = function (id) { return document.getElementById(id); };
  // ---------------------------------------------------------------- the mechanism
  var scene = window.RKScene($("mechanism"), S);
  // the mechanism is drawn only while on screen (a frame drawn off screen is wasted work)
  var mechVisible = true, mechFrame = 0;
  if (window.IntersectionObserver) {
    new IntersectionObserver(function (es) {
      mechVisible = es[es.length - 1].isIntersecting;
      if (mechVisible && mechFrame !== R.frame) { scene.draw(R.frame); mechFrame = R.frame; }
    }).observe($("mechanism"));
  }
  R.scene = {id: "mechanism", animated: S.animated, frames: n, angles_deg: S.angles_deg,
             map: scene.map, view: scene.view};
  R.timing.mechanism = performance.now();
  var slider = $("angle-slider"), angleIn = $("angle-input"), playBtn = $("play-button");
  var speedSel = $("speed"), reads = document.querySelectorAll(".ro-value");
  var period = S.period_deg;
  function fmt(v) {
    return (Math.abs(v) >= 1000 ? v.toFixed(0) : v.toPrecision(4)).replace("-", "\u2212");
  }
  var cursors = [];
  // numbers and the slider are rewritten at most 8 times a second while playing (nobody reads
  // faster, and every rewrite repaints them): the moving parts follow every frame
  var lastText = -1e9;
  function texts(f, now) {
    lastText = now;
    slider.value = f;
    var a = S.angles_deg[f];
    if (!typing) angleIn.value = a.toFixed(1);
    S.readouts.forEach(function (r, k) {
      var text = fmt(r.values[f]);
      if (reads[k].textContent !== text) reads[k].textContent = text;
    });
    mini.text(a);
  }
  function show(f, now) {
    f = ((f % n) + n) % n;
    R.frame = f;
    if (mechVisible) { scene.draw(f); mechFrame = f; }
    R.drawn++;
    var a = S.angles_deg[f];
    cursors.forEach(function (c) { if (c.visible) c.to(a); });
    mini.to(a);
    if (now === undefined || now - lastText > 120) texts(f, now === undefined ? -1e9 : now);
    return Promise.resolve(f);
  }
  R.show = show;
  // ---------------------------------------------------------------- the player
  var playing = false, raf = null, clock = null, typing = false;
  function base() { return parseFloat(speedSel.value) || 1; }
  function loop(now) {
    if (!playing) return;
    if (clock === null) clock = {t: now, f: R.frame};
    var f = Math.floor(clock.f + (now - clock.t) / 1000 * n / S.seconds_per_period * base()) % n;
    if (f !== R.frame) show(f, now);
    raf = requestAnimationFrame(loop);
  }
  function setPlaying(on) {
    if (on === playing) return;
    playing = on;
    R.playing = on;
    clock = null;
    playBtn.innerHTML = on ? "&#10073;&#10073; Pause" : "&#9654; Play";
    playBtn.setAttribute("aria-pressed", on ? "true" : "false");
    if (on) raf = requestAnimationFrame(loop);
    else {
      if (raf) cancelAnimationFrame(raf);
      texts(R.frame, -1e9);  // the numbers of the frame it stopped at
    }
  }
  playBtn.addEventListener("click", function () { setPlaying(!playing); });
  speedSel.addEventListener("change", function () { clock = null; });
  $("step-back").addEventListener("click", function () { setPlaying(false); show(R.frame - 1); });
  $("step-fwd").addEventListener("click", function () { setPlaying(false); show(R.frame + 1); });
  slider.addEventListener("input", function () {
    setPlaying(false);
    show(parseInt(slider.value, 10));
  });
  function toAngle() {
    typing = false;
    var a = parseFloat(String(angleIn.value).replace(",", "."));
    if (!isFinite(a)) return;
    a = ((a % period) + period) % period;
    var step = period / n;
    setPlaying(false);
    show(Math.round(a / step) % n);
    angleIn.value = S.angles_deg[R.frame].toFixed(1);
  }
  angleIn.addEventListener("input", function () { typing = true; });
  angleIn.addEventListener("blur", function () { typing = false; });
  angleIn.addEventListener("change", toAngle);
  angleIn.addEventListener("keydown", function (ev) { if (ev.key === "Enter") toAngle(); });
  // the player's height, for anchors scrolled under it
  var player = $("player");
  function playerHeight() {
    document.documentElement.style.setProperty("--player-h", player.offsetHeight + "px");
  }
  // ---------------------------------------------------------------- the small plot
  var mini = (function () {
    var svg = $("mini-svg"), sel = $("mini-select"), out = $("mini-value");
    var cursorDiv = $("mini-cursor"), dotDiv = $("mini-dot");
    var curves = [];
    D.plots.forEach(function (p) {
      (p.curves || []).forEach(function (c) {
        curves.push({plot: p, trace: c[0], name: c[1], unit: c[2], panel: c[3]});
      });
    });
    curves.forEach(function (c, k) {
      var o = document.createElement("option");
      o.value = k;
      o.textContent = c.plot.title + ": " + c.name;
      sel.appendChild(o);
    });
    var pick = Math.max(0, curves.findIndex(function (c) { return c.plot.id === D.mini_default; }));
    sel.value = pick;
    var cur = null, geo = null, NS = "http://www.w3.org/2000/svg";
    function draw() {
      var c = curves[parseInt(sel.value, 10)];
      cur = c;
      svg.innerHTML = "";
      if (!c) return;
      var W = svg.clientWidth || 300, H = svg.clientHeight || 80;
      svg.setAttribute("viewBox", "0 0 " + W + " " + H);
      var t = c.plot.figure.data[c.trace], xs = t.x, ys = t.y;
      var lo = Infinity, hi = -Infinity;
      ys.forEach(function (v) { if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); } });
      if (!(hi > lo)) { hi = lo + 1; }
      var pad = 0.08 * (hi - lo), ml = 48, mr = 16, mt = 4, mb = 14;
      lo -= pad; hi += pad;
      var P = c.plot.cursor_period_deg, x0 = xs[0], x1 = xs[xs.length - 1];
      var sx = (W - ml - mr) / (x1 - x0), sy = (H - mt - mb) / (hi - lo);
      geo = {sx: sx, sy: sy, ml: ml, mt: mt, mb: mb, x0: x0, x1: x1, hi: hi, H: H, P: P};
      function mk(tag, a) {
        var e = document.createElementNS(NS, tag);
        for (var k in a) e.setAttribute(k, a[k]);
        svg.appendChild(e);
        return e;
      }
      mk("rect", {x: ml, y: mt, width: W - ml - mr, height: H - mt - mb, fill: "#fff",
                  stroke: "#d9dce1"});
      if (lo < 0 && hi > 0) {
        mk("line", {x1: ml, x2: W - mr, y1: mt + hi * sy, y2: mt + hi * sy, stroke: "#bbb"});
      }
      var dt = P >= 270 ? (P > 900 ? 180 : 90) : P > 90 ? 45 : 15;
      for (var v = Math.ceil(x0 / dt) * dt; v <= x1 + 1e-9; v += dt) {
        var X = ml + (v - x0) * sx;
        mk("line", {x1: X, x2: X, y1: mt, y2: H - mb, stroke: "#eef0f3"});
        mk("text", {x: X, y: H - 3, "text-anchor": "middle", "class": "tick"}).textContent =
          v + "\u00b0";
      }
      [hi - pad, lo + pad].forEach(function (v) {
        mk("text", {x: ml - 3, y: mt + (hi - v) * sy + 4, "text-anchor": "end",
                    "class": "tick"}).textContent = fmt(v);
      });
      var d = "", pen = false;
      for (var j = 0; j < xs.length; j++) {
        if (ys[j] === null) { pen = false; continue; }
        d += (pen ? "L" : "M") + (ml + (xs[j] - x0) * sx).toFixed(1) + "," +
             (mt + (hi - ys[j]) * sy).toFixed(1);
        pen = true;
      }
      mk("path", {d: d, fill: "none", stroke: (t.line && t.line.color) || "#1f77b4",
                  "stroke-width": 1.6});
      // the cursor and the dot are HTML boxes moved by transforms: no repaint of the curve
      cursorDiv.style.top = mt + "px";
      cursorDiv.style.height = (H - mt - mb) + "px";
      text(S.angles_deg[R.frame]);
    }
    function value(a) {
      var t = cur.plot.figure.data[cur.trace], xs = t.x, ys = t.y;
      for (var j = 1; j < xs.length; j++) {
        if (xs[j] >= a) {
          var y0 = ys[j - 1], y1 = ys[j];
          if (y0 === null || y1 === null) return null;
          return y0 + (y1 - y0) * (a - xs[j - 1]) / ((xs[j] - xs[j - 1]) || 1);
        }
      }
      return ys[ys.length - 1];
    }
    function to(a) {
      if (!cur || !geo) return;
      var x = geo.P ? ((a % geo.P) + geo.P) % geo.P : a;
      if (x < geo.x0) x += geo.P || 0;
      var X = geo.ml + (x - geo.x0) * geo.sx, y = value(x);
      cursorDiv.style.transform = "translateX(" + X.toFixed(1) + "px)";
      if (y !== null) {
        var Y = geo.mt + (geo.hi - y) * geo.sy;
        dotDiv.style.transform = "translate(" + X.toFixed(1) + "px," + Y.toFixed(1) + "px)";
      }
      geo.x = x;
      geo.y = y;
    }
    function text(a) {
      if (!cur || !geo) return;
      to(a);
      var y = geo.y;
      out.textContent = (y === null ? "n/a" : fmt(y)) + (cur.unit ? " " + cur.unit : "") +
                        " at " + S.angle_symbol + " = " + geo.x.toFixed(1) + "\u00b0";
    }
    sel.addEventListener("change", draw);
    return {draw: draw, to: to, text: text};
  })();
  // ---------------------------------------------------------------- resizing
  var resizeTimer = null;
  window.addEventListener("resize", function () {
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(function () { mini.draw(); playerHeight(); narrowNames(); }, 150);
  });
  mini.draw();
  playerHeight();
  show(0);
  // ---------------------------------------------------------------- CSV links
  D.plots.forEach(function (p) {
    var a = $("csv-" + p.id);
    if (a) a.href = URL.createObjectURL(new Blob([p.csv], {type: "text/csv"}));
  });
  // ---------------------------------------------------------------- plotly, after the text
  var config = {responsive: true, displaylogo: false, displayModeBar: "hover",
                toImageButtonOptions: {format: "png", scale: 2}};
  function narrow(el) { return (el.clientWidth || window.innerWidth) < 800; }
  function names(p, el) {
    return p.figure.data.map(function (t, i) {
      return narrow(el) && p.short ? p.short[i] : t.name;
    });
  }
  function narrowNames() {
    D.plots.forEach(function (p) {
      var el = $(p.id);
      if (!el._drawn || !p.short) return;
      var want = names(p, el), have = el.data.map(function (t) { return t.name; });
      if (want.join("\u0001") !== have.join("\u0001")) {
        Plotly.restyle(el, {name: want}).catch(function (e) { R.errors.push(String(e)); });
      }
    });
  }
  function cursorFor(p, el) {
    var c = {el: el, period: p.cursor_period_deg, x: 0, div: document.createElement("div")};
    c.div.className = "cursor";
    el.appendChild(c.div);
    c.place = function () {  // moved by a transform: the plot is not repainted
      var fl = el._fullLayout, ax = fl && fl.xaxis;
      if (!ax || !fl._size) return;
      var r = ax.range, inside = c.x >= Math.min(r[0], r[1]) && c.x <= Math.max(r[0], r[1]);
      if (c.top !== fl._size.t || c.height !== fl._size.h) {
        c.top = fl._size.t;
        c.height = fl._size.h;
        c.div.style.top = c.top + "px";
        c.div.style.height = c.height + "px";
      }
      c.div.style.transform = "translateX(" + (ax._offset + ax.l2p(c.x)).toFixed(1) + "px)";
      var shown = inside ? "block" : "none";
      if (c.div.style.display !== shown) c.div.style.display = shown;
    };
    c.to = function (a) { c.x = ((a % c.period) + c.period) % c.period; c.place(); };
    el.on("plotly_afterplot", c.place);
    c.visible = true;
    if (window.IntersectionObserver) {  // a cursor off screen waits until it is seen
      new IntersectionObserver(function (es) {
        c.visible = es[es.length - 1].isIntersecting;
        if (c.visible) c.to(S.angles_deg[R.frame]);
      }).observe(el);
    }
    c.to(S.angles_deg[R.frame]);
    cursors.push(c);
  }
  function drawPlot(p) {
    var el = $(p.id), data = p.figure.data.slice();
    var nm = names(p, el);
    data = data.map(function (t, i) {
      if (nm[i] === t.name) return t;
      var c = Object.assign({}, t);
      c.name = nm[i];
      return c;
    });
    var layout = Object.assign({}, p.figure.layout);
    if (narrow(el)) {
      var l = Math.min((layout.margin || {}).l || 60, 56);
      layout.margin = Object.assign({}, layout.margin, {l: l, r: 10});
    }
    return Plotly.newPlot(el, data, layout, config).then(function () {
      el._drawn = true;
      if (p.cursor_period_deg) cursorFor(p, el);
      R.plots.push({id: p.id, traces: p.figure.data.length, kind: p.kind});
      R.timing["drawn " + p.id] = performance.now();
    });
  }
  function distance(p) {
    var r = $(p.id).getBoundingClientRect(), h = window.innerHeight;
    return r.bottom < 0 ? -r.bottom : r.top > h ? r.top - h : 0;
  }
  // WebGL plots run a render loop of their own on every animation frame, which halves the
  // player's frame rate in software rendering: they live only while near the screen (drawn
  // when they come within half a screen, purged when they leave it; the box keeps its height)
  function liveNearScreen(p) {
    var el = $(p.id), busy = false, want = false;
    R.deferred.push(p.id);
    function settle() {
      if (busy) return;
      if (want && !el._drawn) {
        busy = true;
        drawPlot(p).then(function () { busy = false; settle(); },
                         function (e) { busy = false; R.errors.push(p.id + ": " + String(e)); });
      } else if (!want && el._drawn) {
        Plotly.purge(el);
        el._drawn = false;
        R.plots = R.plots.filter(function (q) { return q.id !== p.id; });
      }
    }
    new IntersectionObserver(function (es) {
      want = es[es.length - 1].isIntersecting;
      settle();
    }, {rootMargin: "50% 0px 50% 0px"}).observe(el);
  }
  function drawAll() {
    var left = D.plots.filter(function (p) { return p.kind !== "3d"; });
    if (window.IntersectionObserver) {
      D.plots.forEach(function (p) { if (p.kind === "3d") liveNearScreen(p); });
    } else {
      left = D.plots.slice();
    }
    function next() {
      if (!left.length) {
        R.timing.plots = performance.now();
        R.ready = true;
        return;
      }
      left.sort(function (a, b) { return distance(a) - distance(b); });
      var p = left.shift();
      drawPlot(p).then(function () { setTimeout(next, 0); },
                       function (e) {
                         R.errors.push(p.id + ": " + String(e));
                         setTimeout(next, 0);
                       });
    }
    next();
  }
  function startPlotly() {
    var src = $("plotly-src");
    function loaded() { R.timing.plotly = performance.now(); drawAll(); }
    // plotly.js evaluated again in the global scope, then as an inline script: when the
    // viewer refuses Blob URLs, or when the first parse failed (Chromium 156 was seen to
    // reject the unchanged text now and then, a SyntaxError at one fixed place in it;
    // parsed again, it loads)
    function again() {
      try { (0, eval)(src.textContent); } catch (e) { R.retried.push(String(e)); }
      if (window.Plotly) { loaded(); return; }
      var inline = document.createElement("script");
      inline.text = src.textContent;
      document.body.appendChild(inline);
      if (window.Plotly) loaded();
      else R.errors.push("plotly.js did not load: " + R.retried.join("; "));
    }
    var url = URL.createObjectURL(new Blob([src.textContent], {type: "text/javascript"}));
    var s = document.createElement("script");
    R.plotlyUrl = url;
    s.src = url;
    s.onload = function () { if (window.Plotly) loaded(); else setTimeout(again, 0); };
    s.onerror = again;
    document.body.appendChild(s);
  }
  // start plotly once the text has been painted (or after half a second at most)
  var started = false;
  function start() { if (!started) { started = true; setTimeout(startPlotly, 20); } }
  var PO = window.PerformanceObserver;
  if (PO && (PO.supportedEntryTypes || []).indexOf("paint") >= 0) {
    if (performance.getEntriesByType("paint").length) start();
    else {
      new PO(function (list, obs) { obs.disconnect(); start(); })
        .observe({type: "paint", buffered: true});
    }
  }
  requestAnimationFrame(function () {
    requestAnimationFrame(function () { setTimeout(start, 500); });
  });
})();
"""
