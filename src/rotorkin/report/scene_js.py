"""The page's renderer of the mechanism: plain SVG, no plotly, no WebGL (JavaScript source).

The scene arrives as a plotly-style figure (:class:`rotorkin.render.scenes.Scene`:
2D panels side by side on ``xaxis``/``xaxis2`` ... with equal scales, and an
optional 3D ``scene``) with per-frame coordinates of its animated traces. This
renderer draws it as one SVG per panel, in a flex row that wraps to one panel per
line on narrow screens, with the panel titles and the legend as HTML (they wrap
instead of overlapping). A frame swaps in the coordinates of the animated traces
by rewriting their path data: a few milliseconds, so playback keeps up on a phone
or in software rendering. The 3D panel is an orthographic projection of the
model's 3D coordinates, turned by dragging (azimuth, elevation).

``window.RKScene(root, scene)`` returns ``{draw(frame), layout(), map, panels}``;
``map(trace)`` gives the data-to-pixel mapping of a 2D trace (for tests).
"""

SCENE_JS = r"""
(function () {
  "use strict";
  var NS = "http://www.w3.org/2000/svg";
  var DASH = {dash: "6 4", dot: "2 3", dashdot: "6 3 2 3", longdash: "11 5",
              longdashdot: "11 4 2 4", solid: null};
  var THREE = {scatter3d: 1, mesh3d: 1, surface: 1};
  function el(tag, attrs, parent) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs) {
      if (attrs[k] !== null && attrs[k] !== undefined) e.setAttribute(k, attrs[k]);
    }
    if (parent) parent.appendChild(e);
    return e;
  }
  function title(a) {
    var t = a && a.title;
    return (t && (t.text !== undefined ? t.text : t)) || "";
  }
  function nice(span, n) {
    var raw = span / Math.max(1, n), p = Math.pow(10, Math.floor(Math.log10(raw))), m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
  }
  function num(v) {
    var a = Math.abs(v);
    var s = a >= 100 || a === 0 ? v.toFixed(0) : a >= 10 ? v.toFixed(1).replace(/\.0$/, "")
            : v.toPrecision(2).replace(/\.?0+$/, "");
    return s.replace("-", "\u2212");
  }
  function textOf(html) {  // plotly mini-HTML -> lines of plain text
    return String(html).split(/<br\s*\/?>/i).map(function (s) {
      return s.replace(/<[^>]+>/g, "").replace(/&amp;/g, "&").replace(/&lt;/g, "<")
              .replace(/&gt;/g, ">");
    });
  }

  function RKScene(root, S) {
    var L = S.figure.layout, data = S.figure.data, A = {};
    S.animated.forEach(function (t, i) { A[t] = i; });
    // ---- panels
    var panels = [];
    Object.keys(L).forEach(function (k) {
      var m = /^xaxis(\d*)$/.exec(k);
      if (!m) return;
      var xa = L[k], ya = L["yaxis" + m[1]] || {};
      panels.push({kind: "2d", ref: "x" + m[1], domain: xa.domain || [0, 1], xa: xa, ya: ya,
                   equal: !!ya.scaleanchor, axes: xa.visible !== false, yaxes: ya.visible !== false,
                   traces: [], title: ""});
    });
    if (L.scene) {
      panels.push({kind: "3d", domain: (L.scene.domain && L.scene.domain.x) || [0, 1],
                   sc: L.scene, traces: [], title: ""});
    }
    if (!panels.length) {
      panels.push({kind: "2d", ref: "x", domain: [0, 1], xa: {}, ya: {}, equal: false,
                   axes: true, yaxes: true, traces: [], title: ""});
    }
    panels.sort(function (a, b) { return a.domain[0] - b.domain[0]; });
    data.forEach(function (t, i) {
      var p = null;
      if (THREE[t.type]) { p = panels.filter(function (q) { return q.kind === "3d"; })[0]; }
      else {
        var ref = t.xaxis || "x";
        p = panels.filter(function (q) { return q.ref === ref; })[0] || panels[0];
      }
      if (p) p.traces.push(i);
    });
    (L.annotations || []).forEach(function (a) {
      if (a.xref !== "paper") return;
      var best = null, d = 1e9;
      panels.forEach(function (p) {
        var dd = Math.abs(p.domain[0] - (a.x || 0));
        if (dd < d) { d = dd; best = p; }
      });
      if (best) best.title += (best.title ? "<br>" : "") + a.text;
    });
    // ---- DOM
    root.innerHTML = "";
    var row = document.createElement("div");
    row.className = "mech-row";
    root.appendChild(row);
    panels.forEach(function (p, k) {
      p.box = document.createElement("div");
      p.box.className = "mpanel mpanel-" + p.kind;
      p.box.setAttribute("data-panel", k);
      if (p.title) {
        var h = document.createElement("div");
        h.className = "mtitle";
        h.innerHTML = p.title;
        p.box.appendChild(h);
      }
      // two stacked SVGs: the static traces and the grid below, the moving traces above in
      // a layer of their own, so that a frame repaints only what moves
      var stack = document.createElement("div");
      stack.className = "mstack";
      p.box.appendChild(stack);
      p.svg = el("svg", {"class": "msvg", role: "img"}, stack);
      p.svg2 = el("svg", {"class": "msvg anim", "aria-hidden": "true"}, stack);
      p.grid = el("g", {"class": "grid"}, p.svg);
      p.layer = el("g", {"class": "data"}, p.svg);
      p.layer2 = el("g", {"class": "data"}, p.svg2);
      p.stack = stack;
      if (p.kind === "3d") {
        p.hint = document.createElement("div");
        p.hint.className = "mhint";
        p.hint.textContent = "drag to turn";
        p.box.appendChild(p.hint);
      }
      row.appendChild(p.box);
    });
    var hidden = {};
    var legend = document.createElement("div");
    legend.className = "mlegend";
    root.appendChild(legend);
    var seen = {};
    data.forEach(function (t, i) {
      if (t.showlegend === false || !t.name) return;
      var key = t.legendgroup || t.name;
      if (seen[key]) return;
      seen[key] = 1;
      var b = document.createElement("button");
      b.type = "button";
      b.className = "li";
      b.setAttribute("aria-pressed", "true");
      var sw = el("svg", {width: 26, height: 12, "class": "sw"});
      swatch(t, sw);
      b.appendChild(sw);
      var s = document.createElement("span");
      s.innerHTML = t.name;  // names and titles come in the page's style
      b.appendChild(s);
      b.addEventListener("click", function () {
        hidden[key] = !hidden[key];
        b.setAttribute("aria-pressed", hidden[key] ? "false" : "true");
        b.classList.toggle("off", !!hidden[key]);
        redrawAll();
      });
      legend.appendChild(b);
    });
    function isHidden(t) { return !!hidden[t.legendgroup || t.name]; }
    function swatch(t, sw) {
      var line = t.line || {}, mk = t.marker || {};
      if (t.fill === "toself") {
        el("rect", {x: 3, y: 1, width: 20, height: 10, fill: t.fillcolor || "#ccc",
                    stroke: line.color || "#777",
                    "stroke-width": Math.min(line.width || 1, 2)}, sw);
      } else if (t.type === "mesh3d") {
        el("rect", {x: 3, y: 1, width: 20, height: 10, fill: t.color || "#aaa",
                    opacity: t.opacity || 1}, sw);
      } else if ((t.mode || "lines").indexOf("lines") >= 0) {
        el("line", {x1: 1, y1: 6, x2: 25, y2: 6, stroke: line.color || "#444",
                    "stroke-width": Math.min(line.width || 2, 5),
                    "stroke-dasharray": DASH[line.dash] || null}, sw);
      } else {
        el("path", {d: symbol(mk.symbol, 13, 6, 4), fill: color(mk.color)}, sw);
      }
    }
    function color(c) { return typeof c === "string" ? c : "#444"; }
    function symbol(sym, x, y, r) {
      sym = sym || "circle";
      function P(pts) {
        return "M" + pts.map(function (q) { return q[0] + "," + q[1]; }).join("L") + "Z";
      }
      if (sym.indexOf("square") === 0) {
        return P([[x - r, y - r], [x + r, y - r], [x + r, y + r], [x - r, y + r]]);
      }
      if (sym.indexOf("diamond") === 0) return P([[x, y - r], [x + r, y], [x, y + r], [x - r, y]]);
      if (sym.indexOf("triangle-up") === 0) {
        return P([[x, y - r], [x + r, y + r * 0.8], [x - r, y + r * 0.8]]);
      }
      return "M" + (x - r) + "," + y + "a" + r + "," + r + " 0 1,0 " + 2 * r + ",0" +
             "a" + r + "," + r + " 0 1,0 " + (-2 * r) + ",0";
    }
    // ---- trace elements (created once, reused every frame)
    var nodes = data.map(function (t, i) {
      var p = panels.filter(function (q) { return q.traces.indexOf(i) >= 0; })[0];
      var g = el("g", {"class": "tr", "data-trace": i},
                 p ? (A[i] === undefined ? p.layer : p.layer2) : null);
      var n = {g: g, panel: p, path: null, marks: null, texts: []};
      var mode = t.mode || (t.type === "mesh3d" ? "" : "lines");
      var line = t.line || {};
      if (t.type === "mesh3d") {
        n.path = el("path", {fill: t.color || "#90a4ae", "fill-opacity": t.opacity || 1,
                             stroke: "none"}, g);
      } else if (mode.indexOf("lines") >= 0 || t.fill === "toself") {
        var w = line.width === undefined ? 2 : line.width;
        n.path = el("path", {fill: t.fill === "toself" ? (t.fillcolor || "#ccc") : "none",
                             stroke: w > 0 ? (line.color || "#444") : "none", "stroke-width": w,
                             "stroke-dasharray": DASH[line.dash] || null,
                             "stroke-linejoin": "round", "stroke-linecap": "round",
                             "class": t.fill === "toself" ? "js-fill" : "js-line"}, g);
      }
      if (mode.indexOf("markers") >= 0) {
        var mk = t.marker || {}, ml = mk.line || {};
        n.marks = el("path", {fill: color(mk.color), stroke: ml.color || null,
                              "stroke-width": ml.width || null, "class": "js-markers"}, g);
      }
      if (mode.indexOf("text") >= 0) {
        var count = ((A[i] === undefined ? t.text : S.frames[0][A[i]].text) || []).length;
        if (count === 1 && p) {
          // a single label (the state of the machine) is a line of HTML under the panel's
          // title: it wraps on a phone instead of lying over the drawing
          n.caption = document.createElement("div");
          n.caption.className = "mstate";
          p.box.insertBefore(n.caption, p.stack);
        } else {
          n.textLayer = g;
        }
      }
      return n;
    });
    // ---- geometry of the panels
    var view = {az: 0, el: 0};
    var P3 = panels.filter(function (p) { return p.kind === "3d"; })[0];
    if (P3) {
      var eye = (P3.sc.camera && P3.sc.camera.eye) || {x: 1.5, y: -1.5, z: 1};
      view.az = Math.atan2(eye.y, eye.x);
      view.el = Math.atan2(eye.z, Math.hypot(eye.x, eye.y));
      var R0 = 0, cx = 0, cy = 0, cz = 0;
      ["x", "y", "z"].forEach(function (a, k) {
        var r = P3.sc[a + "axis"] && P3.sc[a + "axis"].range;
        if (!r) return;
        var c = 0.5 * (r[0] + r[1]);
        if (k === 0) cx = c; else if (k === 1) cy = c; else cz = c;
      });
      P3.centre = [cx, cy, cz];
      function grow(xs, ys, zs) {
        for (var j = 0; j < xs.length; j++) {
          if (xs[j] === null || ys[j] === null || zs[j] === null) continue;
          var d = Math.hypot(xs[j] - cx, ys[j] - cy, zs[j] - cz);
          if (d > R0) R0 = d;
        }
      }
      P3.traces.forEach(function (i) {
        var t = data[i];
        if (A[i] === undefined) { grow(t.x || [], t.y || [], t.z || []); return; }
        S.frames.forEach(function (fr) {
          var d = fr[A[i]];
          grow(d.x || t.x, d.y || t.y, d.z || t.z);
        });
      });
      P3.radius = R0 || 1;
      var drag = null;
      P3.stack.addEventListener("pointerdown", function (ev) {
        drag = {x: ev.clientX, y: ev.clientY, az: view.az, el: view.el};
        P3.stack.setPointerCapture(ev.pointerId);
      });
      P3.stack.addEventListener("pointermove", function (ev) {
        if (!drag) return;
        view.az = drag.az - (ev.clientX - drag.x) * 0.01;
        view.el = Math.max(-1.5, Math.min(1.5, drag.el + (ev.clientY - drag.y) * 0.01));
        redraw3d();
      });
      ["pointerup", "pointercancel"].forEach(function (n) {
        P3.stack.addEventListener(n, function () { drag = null; });
      });
    }
    function layout() {
      var cw = row.clientWidth || 800, narrow = cw < 800, gap = 12;
      var total = panels.reduce(function (s, p) { return s + (p.domain[1] - p.domain[0]); }, 0);
      // at most 480 px high (and 60 % of the window): the drawing stays in view with the
      // player, and a frame repaints fewer pixels
      var maxH = Math.max(220, Math.min((L.height || 520) - 50, 480,
                                        0.6 * (window.innerHeight || 800)));
      panels.forEach(function (p) {
        var share = (p.domain[1] - p.domain[0]) / total;
        var w = narrow ? cw : Math.floor((cw - gap * (panels.length - 1)) * share);
        w = Math.min(w, 960);  // a wide drawing is no clearer beyond this, only slower
        p.box.style.width = w + "px";
        var h;
        if (p.kind === "3d") {
          h = Math.min(w, maxH);
          p.m = {l: 4, r: 4, t: 4, b: 4};
          p.w = w; p.h = h;
          p.s = 0.47 * Math.min(w, h) / P3.radius;
        } else {
          p.m = p.axes ? {l: p.yaxes ? 46 : 8, r: 8, t: 6, b: 38} : {l: 4, r: 4, t: 4, b: 4};
          var xr = p.xa.range || bounds(p, "x"), yr = p.ya.range || bounds(p, "y");
          var pw = w - p.m.l - p.m.r, sx = pw / (xr[1] - xr[0]), sy;
          if (p.equal) {
            var ph = (yr[1] - yr[0]) * sx;
            if (ph > maxH - p.m.t - p.m.b) { sx = (maxH - p.m.t - p.m.b) / (yr[1] - yr[0]); }
            sy = sx;
            h = Math.ceil((yr[1] - yr[0]) * sy) + p.m.t + p.m.b;
          } else {
            h = Math.max(120, (L.height || 300) - 70);
            sy = (h - p.m.t - p.m.b) / (yr[1] - yr[0]);
          }
          var ox = p.m.l + 0.5 * (pw - (xr[1] - xr[0]) * sx);
          p.map = [sx, ox - xr[0] * sx, -sy, p.m.t + yr[1] * sy];
          p.w = w; p.h = h; p.xr = xr; p.yr = yr;
        }
        [p.svg, p.svg2].forEach(function (svg) {
          svg.setAttribute("width", p.w);
          svg.setAttribute("height", p.h);
          svg.setAttribute("viewBox", "0 0 " + p.w + " " + p.h);
        });
        if (p.kind === "2d") axes2d(p);
      });
      redrawAll();
    }
    function bounds(p, a) {
      var lo = Infinity, hi = -Infinity;
      p.traces.forEach(function (i) {
        var t = data[i], arrays = [t[a] || []];
        if (A[i] !== undefined) {
          S.frames.forEach(function (fr) { if (fr[A[i]][a]) arrays.push(fr[A[i]][a]); });
        }
        arrays.forEach(function (v) {
          for (var j = 0; j < v.length; j++) {
            if (v[j] !== null) { lo = Math.min(lo, v[j]); hi = Math.max(hi, v[j]); }
          }
        });
      });
      if (!(hi > lo)) { lo = -1; hi = 1; }
      var pad = 0.06 * (hi - lo);
      return [lo - pad, hi + pad];
    }
    function axes2d(p) {
      p.grid.innerHTML = "";
      function label(a, s) { el("text", a, p.grid).textContent = s; }
      if (!p.axes) return;
      var m = p.map, x0 = (p.m.l - m[1]) / m[0], x1 = (p.w - p.m.r - m[1]) / m[0];
      var y1 = (p.m.t - m[3]) / m[2], y0 = (p.h - p.m.b - m[3]) / m[2];
      var dx = nice(x1 - x0, Math.max(2, Math.floor((p.w - p.m.l) / 70)));
      var dy = nice(y1 - y0, Math.max(2, Math.floor((p.h - p.m.b) / 45)));
      el("rect", {x: p.m.l, y: p.m.t, width: p.w - p.m.l - p.m.r, height: p.h - p.m.t - p.m.b,
                  fill: "none", stroke: "#d9dce1"}, p.grid);
      for (var v = Math.ceil(x0 / dx) * dx; v <= x1 + 1e-9; v += dx) {
        var X = m[0] * v + m[1];
        el("line", {x1: X, x2: X, y1: p.m.t, y2: p.h - p.m.b, stroke: "#eef0f3"}, p.grid);
        label({x: X, y: p.h - p.m.b + 13, "text-anchor": "middle", "class": "tick"}, num(v));
      }
      if (p.yaxes) {
        for (v = Math.ceil(y0 / dy) * dy; v <= y1 + 1e-9; v += dy) {
          var Y = m[2] * v + m[3];
          el("line", {x1: p.m.l, x2: p.w - p.m.r, y1: Y, y2: Y, stroke: "#eef0f3"}, p.grid);
          label({x: p.m.l - 4, y: Y + 3.5, "text-anchor": "end", "class": "tick"}, num(v));
        }
      }
      var xt = textOf(title(p.xa)).join(" ");
      if (xt) {
        label({x: p.m.l + 0.5 * (p.w - p.m.l - p.m.r), y: p.h - 6, "text-anchor": "middle",
               "class": "atitle"}, xt);
      }
      var yt = textOf(title(p.ya)).join(" ");
      if (yt && p.yaxes) {
        var yc = p.m.t + 0.5 * (p.h - p.m.t - p.m.b);
        label({x: 11, y: yc, "text-anchor": "middle", transform: "rotate(-90 11 " + yc + ")",
               "class": "atitle"}, yt);
      }
    }
    // ---- drawing
    var current = 0;
    function coords(i, f) {
      var t = data[i], d = A[i] === undefined ? null : S.frames[f][A[i]];
      return {x: (d && d.x) || t.x || [], y: (d && d.y) || t.y || [], z: (d && d.z) || t.z || [],
              text: (d && d.text) || t.text};
    }
    function project(p) {
      var ca = Math.cos(view.az), sa = Math.sin(view.az);
      var ce = Math.cos(view.el), se = Math.sin(view.el);
      var c = p.centre, s = p.s, X0 = p.w / 2, Y0 = p.h / 2;
      return function (x, y, z) {
        x -= c[0]; y -= c[1]; z -= c[2];
        return [X0 + s * (-sa * x + ca * y), Y0 - s * (-se * ca * x - se * sa * y + ce * z)];
      };
    }
    function xy(q) { return q[0].toFixed(1) + "," + q[1].toFixed(1); }
    function drawTrace(i, f) {
      var n = nodes[i], t = data[i], p = n.panel;
      if (!p || !p.w) return;
      n.g.style.display = isHidden(t) ? "none" : "";
      var c = coords(i, f), pts = [], j, k, q;
      var tp = p.kind === "3d" ? project(p) : null, m = p.map;
      for (j = 0; j < c.x.length; j++) {
        if (c.x[j] === null || c.y[j] === null || (tp && c.z[j] === null)) {
          pts.push(null);
          continue;
        }
        pts.push(tp ? tp(c.x[j], c.y[j], c.z[j]) : [m[0] * c.x[j] + m[1], m[2] * c.y[j] + m[3]]);
      }
      if (t.type === "mesh3d") {
        var I = t.i || [], J = t.j || [], K = t.k || [], d = "";
        for (k = 0; k < I.length; k++) {
          var a = pts[I[k]], b = pts[J[k]], cc = pts[K[k]];
          if (a && b && cc) d += "M" + [a, b, cc].map(xy).join("L") + "Z";
        }
        n.path.setAttribute("d", d);
        return;
      }
      if (n.path) {
        var parts = [], pen = false, close = t.fill === "toself";
        for (j = 0; j < pts.length; j++) {
          q = pts[j];
          if (!q) { if (pen && close) parts.push("Z"); pen = false; continue; }
          parts.push((pen ? "L" : "M") + q[0].toFixed(2) + "," + q[1].toFixed(2));
          pen = true;
        }
        if (pen && close) parts.push("Z");
        n.path.setAttribute("d", parts.join(""));
      }
      if (n.marks) {
        var mk = t.marker || {}, size = mk.size === undefined ? 6 : mk.size, dm = "";
        for (j = 0; j < pts.length; j++) {
          q = pts[j];
          var sz = Array.isArray(size) ? size[j] : size;
          if (q && sz > 0) dm += symbol(mk.symbol, +q[0].toFixed(2), +q[1].toFixed(2), sz / 2);
        }
        n.marks.setAttribute("d", dm);
      }
      if (n.caption) {
        var one = String((c.text || [""])[0]);
        if (n.caption._s !== one) { n.caption._s = one; n.caption.innerHTML = one; }
        n.caption.style.display = isHidden(t) ? "none" : "";
      }
      if (n.textLayer) {
        var tf = t.textfont || {}, texts = c.text || [];
        for (j = 0; j < pts.length; j++) {
          var node = n.texts[j];
          if (!node) {
            node = n.texts[j] = el("text", {"text-anchor": "middle", "class": "mlabel",
                                            fill: tf.color || "#202020",
                                            "font-size": tf.size || 12}, n.g);
            node._s = null;
          }
          q = pts[j];
          var str = q ? String(texts[j] === undefined ? "" : texts[j]) : "";
          if (node._s !== str) {
            node._s = str;
            node.textContent = "";
            var lines = textOf(str);
            lines.forEach(function (ln, r) {
              var ts = el("tspan", {x: 0, dy: r ? "1.15em" : 0}, node);
              ts.textContent = ln;
            });
            node._n = lines.length;
          }
          if (q) {
            var fs = tf.size || 12, y0 = q[1] - 0.5 * (node._n - 1) * 1.15 * fs + 0.35 * fs;
            node.setAttribute("transform", "translate(" + xy([q[0], y0]) + ")");
          }
        }
        for (j = pts.length; j < n.texts.length; j++) {
          n.texts[j].textContent = "";
          n.texts[j]._s = "";
        }
      }
    }
    function triad(p) {
      if (!p.axisLayer) p.axisLayer = el("g", {"class": "triad"}, p.svg);
      p.axisLayer.innerHTML = "";
      var ca = Math.cos(view.az), sa = Math.sin(view.az);
      var ce = Math.cos(view.el), se = Math.sin(view.el);
      var o = [30, p.h - 30];
      [["x", 1, 0, 0], ["y", 0, 1, 0], ["z", 0, 0, 1]].forEach(function (a) {
        var X = -sa * a[1] + ca * a[2], Y = -se * ca * a[1] - se * sa * a[2] + ce * a[3];
        var e = [o[0] + 20 * X, o[1] - 20 * Y];
        el("line", {x1: o[0], y1: o[1], x2: e[0], y2: e[1], stroke: "#555", "stroke-width": 1.2},
           p.axisLayer);
        el("text", {x: o[0] + 27 * X, y: o[1] - 27 * Y + 4, "text-anchor": "middle",
                    "class": "tick"}, p.axisLayer).textContent = a[0];
      });
    }
    function redraw3d() {
      if (!P3) return;
      P3.traces.forEach(function (i) { drawTrace(i, current); });
      triad(P3);
    }
    function redrawAll() {
      for (var i = 0; i < data.length; i++) drawTrace(i, current);
      if (P3) triad(P3);
    }
    function draw(f) {
      current = f;
      for (var k = 0; k < S.animated.length; k++) drawTrace(S.animated[k], f);
    }
    var pending = null;
    if (window.ResizeObserver) {
      new ResizeObserver(function () {
        if (pending) return;
        pending = requestAnimationFrame(function () { pending = null; layout(); });
      }).observe(row);
    }
    layout();
    return {draw: draw, layout: layout, panels: panels, nodes: nodes,
            map: function (i) {
              var n = nodes[i];
              return n && n.panel && n.panel.map ? n.panel.map.slice() : null;
            },
            view: view};
  }
  window.RKScene = RKScene;
})();
"""
