"""The HTML report without a browser: structure, size, offline, paper-vs-ours values, geometry.

Every expected number here is computed independently in the test (explicit
rotation matrices, line-circle intersections, sampled mechanism geometry), not
copied from the code's output. The browser checks live in test_report_browser.py.
"""

from __future__ import annotations

import base64
import html
import json
import os
import re
import subprocess
import sys
import tomllib
from html.parser import HTMLParser

import numpy as np
import plotly.offline
import pytest

from rotorkin import __version__
from rotorkin.cli import main
from rotorkin.drives import evaluate
from rotorkin.io.config import example_names, load_config
from rotorkin.report.html import FRAMES, write_report

EXAMPLES = example_names()  # every built-in example
PLOTS = {  # plot ids every report of the drive must have
    "wobble_cam": {"plot-svaj", "plot-chambers", "plot-torque", "plot-pv", "plot-sphere"},
    "eccentric_cam": {"plot-svaj", "plot-gap", "plot-volume", "plot-torque", "plot-pv", "plot-cam"},
    "guide_bar": {"plot-svaj", "plot-speed", "plot-chambers", "plot-torque", "plot-pv"},
    "rhomboid_cam": {"plot-svaj", "plot-chambers", "plot-torque", "plot-pv", "plot-cam"},
    "noncircular_gears": {"plot-members", "plot-chambers", "plot-pv", "plot-torque", "plot-forces"},
    "tabulated": {"plot-members", "plot-chambers", "plot-pv", "plot-torque"},
}


class _Page(HTMLParser):
    """Collects tags with their attributes, script texts, summary-table cells and checks."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags, self.scripts, self.rows, self.checks = [], [], {}, []
        self._script, self._row, self._cell, self._pre, self._li = None, None, None, None, None
        self.pre = {}

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.append((tag, a))
        if tag == "script":
            self._script = [a, []]
        elif tag == "tr" and "data-key" in a:
            self._row = [a["data-key"], []]
        elif tag == "td" and self._row is not None:
            self._cell = []
        elif tag == "pre":
            self._pre = [a.get("id"), []]
        elif tag == "li" and "check" in a.get("class", ""):
            self._li = [a["class"].split()[1], []]

    def handle_endtag(self, tag):
        if tag == "script" and self._script is not None:
            self.scripts.append((self._script[0], "".join(self._script[1])))
            self._script = None
        elif tag == "td" and self._cell is not None:
            self._row[1].append("".join(self._cell).strip())
            self._cell = None
        elif tag == "tr" and self._row is not None:
            self.rows.setdefault(self._row[0], self._row[1])  # the main table comes first
            self._row = None
        elif tag == "pre" and self._pre is not None:
            self.pre[self._pre[0]] = "".join(self._pre[1])
            self._pre = None
        elif tag == "li" and self._li is not None:
            self.checks.append((self._li[0], "".join(self._li[1])))
            self._li = None

    def handle_data(self, data):
        for buf in (self._script, self._pre, self._li):
            if buf is not None:
                buf[1].append(data)
        if self._cell is not None:
            self._cell.append(data)


def _report(tmp_dir, name, sets=()):
    cfg, raw, cname = load_config(None, name, list(sets))
    result = evaluate(cfg)
    meta = {"name": cname, "drive_type": cfg["drive"]["type"], "rotorkin_version": __version__}
    path = write_report(result, cfg, raw, meta, tmp_dir / "report.html")
    text = path.read_text(encoding="utf-8")
    page = _Page()
    page.feed(text)
    data = next(json.loads(t) for a, t in page.scripts if a.get("id") == "rotorkin-data")
    return {"path": path, "text": text, "page": page, "data": data, "cfg": cfg, "raw": raw}


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    return {n: _report(tmp_path_factory.mktemp(n), n) for n in EXAMPLES}


def _num(cell: str) -> float:
    """The number a table cell starts with (units, marks and U+2212 minus signs allowed)."""
    m = re.search(r"[-+]?\d+(?:\.\d*)?(?:e[-+]?\d+)?", cell.replace("\u2212", "-"))
    return float(m.group(0))


# --------------------------------------------------------------------------------------------
# structure
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", EXAMPLES)
def test_self_contained_offline_and_small(reports, name):
    r = reports[name]
    size = r["path"].stat().st_size
    assert 1_000_000 < size < 10_000_000, f"{size / 1e6:.2f} MB"
    bundle = plotly.offline.get_plotlyjs()
    assert r["text"].count(bundle) == 1, "plotly.js must be embedded exactly once"
    big = [(a, t) for a, t in r["page"].scripts if bundle in t]
    assert len(big) == 1
    # inert text at the end of the page, started by the page's script after the text shows
    assert big[0][0] == {"type": "text/plain", "id": "plotly-src"}
    assert r["text"].index("id='summary-table'") < r["text"].index(bundle[:200])
    assert r["text"].index("id='plotly-src'") > r["text"].index("id='rotorkin-data'")
    assert "createObjectURL" in r["text"]
    for tag, attrs in r["page"].tags:
        for key in ("src", "href", "data"):
            value = attrs.get(key) or ""
            assert not value.lower().startswith(("http:", "https:", "//")), (tag, attrs)
        assert not (tag == "script" and attrs.get("src")), "no external or separate scripts"
        assert tag not in ("link", "iframe", "img"), f"unexpected <{tag}>"
    css = r["text"].split("<style>", 1)[1].split("</style>", 1)[0]
    assert "url(" not in css and "@import" not in css
    assert oct(r["path"].stat().st_mode & 0o044) == oct(0o044), "report readable by others"
    assert not [p for p in r["path"].parent.iterdir() if p.name != "report.html"], "temp file left"


@pytest.mark.parametrize("name", EXAMPLES)
def test_header_plots_and_scene(reports, name):
    r = reports[name]
    cfg, data, page = r["cfg"], r["data"], r["page"]
    assert html.escape(r["raw"]["title"]) in r["text"] and f"rotorkin {__version__}" in r["text"]
    assert tomllib.loads(page.pre["config-toml"]) == r["raw"], "config shown as TOML, round-trips"
    ids = {p["id"] for p in data["plots"]}
    assert PLOTS[cfg["drive"]["type"]] <= ids
    for p in data["plots"]:
        assert p["figure"]["data"], p["id"]
        for trace in p["figure"]["data"]:
            if trace.get("meta"):  # the markers of extremes and failed checks
                continue
            n = len(trace.get("x") or trace.get("z") or [])
            assert n > 1, (p["id"], trace.get("name"))
        assert f"id='{p['id']}'" in r["text"]
    scene = data["scene"]
    assert len(scene["frames"]) == FRAMES == len(scene["angles_deg"])
    assert all(len(f) == len(scene["animated"]) for f in scene["frames"])
    assert np.all(np.diff(scene["angles_deg"]) > 0)
    kinds = {t["type"] for t in scene["figure"]["data"]}
    if cfg["drive"]["type"] == "wobble_cam":
        assert {"scatter3d", "mesh3d", "scatter"} <= kinds
    # the figure shows frame 0
    for i, t in enumerate(scene["animated"]):
        trace = scene["figure"]["data"][t]
        for key, values in scene["frames"][0][i].items():
            assert trace[key] == values
    assert page.checks and {lvl for lvl, _ in page.checks} <= {"ok", "note", "warning", "error"}


# --------------------------------------------------------------------------------------------
# paper vs ours
# --------------------------------------------------------------------------------------------
def _projected_angle(u, tilt):
    """Angle in the yz plane (from z towards y) of a plate radius at u, by explicit matrices."""
    a_phi = np.array([[np.cos(tilt), 0, np.sin(tilt)], [0, 1, 0], [-np.sin(tilt), 0, np.cos(tilt)]])
    v = a_phi @ np.array([0.0, np.sin(u), np.cos(u)])
    return np.arctan2(v[1], v[2])


def test_wobble_table_against_geometry(reports):
    rows = reports["wobble-cam-engine"]["page"].rows
    # slider angle at varphi = 0: rollers at -45 and +45 deg in the plate, plate tilted 45 deg
    amax = np.degrees(
        _projected_angle(np.pi / 4, np.pi / 4) - _projected_angle(-np.pi / 4, np.pi / 4)
    )
    amin = np.degrees(
        _projected_angle(np.pi / 2 + np.pi / 4, np.pi / 4)
        - _projected_angle(np.pi / 2 - np.pi / 4, np.pi / 4)
    )
    ours, paper, diff = (_num(c) for c in rows["slider_angle_max_deg"][1:4])
    assert ours == pytest.approx(amax, abs=1e-3) and paper == pytest.approx(amax, abs=1e-3)
    assert diff == pytest.approx(0.0, abs=1e-9)
    ours, paper, _ = (_num(c) for c in rows["chamber_swing_deg"][1:4])
    assert ours == pytest.approx(amax - amin, abs=1e-3)
    assert paper == 39.0, "printed 'about 39 deg' of Fig. 10 at the paper's Table 1"
    assert "printed" in rows["chamber_swing_deg"][5]
    assert _num(rows["max_plate_tilt_deg"][2]) == 65.0
    assert _num(rows["power_strokes_per_rev"][1]) == _num(rows["power_strokes_per_rev"][2]) == 16
    # eq. 21 at eps = 10: beta = 11/9 a'_min - pi 13/36
    beta = 11 / 9 * amin - 180 * 13 / 36
    assert _num(rows["piston_width_deg"][1]) == pytest.approx(beta, abs=1e-3)


def test_printed_value_only_for_the_papers_case(tmp_path):
    sets = ["drive.plate_tilt=30 deg", "drive.roller_axis_angle=80 deg"]
    r = _report(tmp_path, "wobble-cam-engine", sets)
    row = r["page"].rows["chamber_swing_deg"]
    c, h = np.radians(30.0), np.radians(40.0)
    swing = np.degrees(
        _projected_angle(h, c)
        - _projected_angle(-h, c)
        - _projected_angle(np.pi / 2 + h, c)
        + _projected_angle(np.pi / 2 - h, c)
    )
    assert _num(row[2]) == pytest.approx(swing, abs=1e-3), "the paper's eq. 15, not its 39 deg"
    assert "formula" in row[5]
    assert r["page"].rows["max_plate_tilt_deg"][2] == "", "Fig. 13 holds for alpha = 90 deg only"


def _knife_tip(R, e, beta, side):
    """Follower point on the axis through the shaft: the far root of |x u - c| = R."""
    c = side * e * np.array([np.cos(beta), np.sin(beta)])
    roots = np.roots([1.0, -2.0 * c[0], c @ c - R * R])
    return float(np.max(roots.real))


def test_eccentric_table_against_geometry(reports):
    rows = reports["eccentric-reactor"]["page"].rows
    beta = np.linspace(0.0, 2 * np.pi, 3601)
    z = np.array([[_knife_tip(80.0, 40.0, b, s) - 80.0 for b in beta] for s in (1, -1)])
    gap = z.sum(axis=0)
    ours, paper, diff = (_num(c) for c in rows["gap_change_min_mm"][1:4])
    assert ours == pytest.approx(gap.min(), abs=1e-3)
    assert paper == -21.4 and diff == pytest.approx(gap.min() + 21.4, abs=1e-3)
    assert _num(rows["gap_change_min_ratio"][2]) == -0.5359
    assert _num(rows["gap_change_to_length_percent"][1]) == pytest.approx(-gap.min() / 10, abs=1e-4)
    assert np.degrees(beta[np.argmin(gap)]) == pytest.approx(90.0, abs=0.2)


def test_guide_bar_table_against_geometry(reports):
    rows = reports["guide-bar-pump"]["page"].rows
    lam, u = 0.5, 2.0
    x = np.linspace(0.0, 2 * np.pi, 200_001)
    g = np.unwrap(np.arctan2(np.sin(x), lam + np.cos(x)))  # guide angle of the crank pin
    g2 = np.unwrap(np.arctan2(np.sin(x + np.pi), lam + np.cos(x + np.pi)))
    rel = (g2 - g) / u
    gamma0 = np.degrees((2 * np.pi / u - (rel.max() - rel.min())) / 2)
    ours, paper, _ = (_num(c) for c in rows["vane_angle_crank_driven_deg"][1:4])
    assert ours == pytest.approx(gamma0, abs=1e-3) and paper == pytest.approx(gamma0, abs=1e-3)
    ratio = np.gradient(g, x) / u
    assert _num(rows["impeller_speed_ratio_max"][2]) == pytest.approx(ratio.max(), abs=1e-4)
    m1 = (np.gradient(g, x) + np.gradient(g2, x)) * 10.0 / (u * 2.0)  # M7 = M8 = 10 N*m, i12 = 2
    assert _num(rows["input_torque_max_Nm"][1]) == pytest.approx(m1.max(), abs=1e-3)
    assert _num(rows["input_torque_max_Nm"][2]) == pytest.approx(m1.max(), abs=1e-3)


def test_rhomboid_table_against_quadrature(reports):
    rows = reports["rhomboid-engine"]["page"].rows
    a = np.linspace(0.0, np.pi, 200_001)
    psi = np.pi / 2 + np.radians(50.0) * np.cos(2 * a)  # eq. 16, psi_min = 40 deg
    dpsi = np.gradient(psi, a)
    x = (psi - np.pi / 2) / np.radians(50.0)
    m1 = np.where(dpsi < 0, -30.0 - 70.0 * x, 30.0 - 70.0 * x)  # eq. 29: M1 = 100, M2 = 40
    work = np.trapezoid(m1 * dpsi, a)
    ours, paper, _ = (_num(c) for c in rows["indicator_work_J"][1:4])
    assert ours == pytest.approx(work, rel=1e-4) and paper == pytest.approx(work, rel=1e-4)
    rho = 120.0 * np.cos(psi / 2)
    assert _num(rows["profile_radius_min_mm"][2]) == pytest.approx(rho.min(), abs=1e-3)


def test_checks_in_plain_words(tmp_path, reports):
    rho = reports["rhomboid-engine"]["page"].checks
    assert any(lvl == "warning" and "concave" in t and "10.81" in t for lvl, t in rho)
    liquid = _report(tmp_path, "eccentric-reactor", ["machine.fluid=liquid"])
    assert any(lvl == "error" and "cavitat" in t.lower() for lvl, t in liquid["page"].checks)
    wob = reports["wobble-cam-engine"]["page"].checks
    assert any("65.53" in t and "69 %" in t for _, t in wob), "plate tilt vs eq. 20 limit"


# --------------------------------------------------------------------------------------------
# readability of the plots
# --------------------------------------------------------------------------------------------
def _plot(r, pid):
    return next(p for p in r["data"]["plots"] if p["id"] == pid)


def _arr(values):
    """A plot array from the page's JSON: a list (None for NaN) or plotly's typed array."""
    if isinstance(values, dict):  # {"dtype": "f8", "bdata": base64, "shape": ...}
        a = np.frombuffer(base64.b64decode(values["bdata"]), dtype=values["dtype"])
        return a.astype(float).reshape(values.get("shape", a.shape))
    return np.array([np.nan if v is None else v for v in values], float)


def _twod_traces(fig):
    """(x axis, y axis, name, x, y) of the 2D line traces of a plot figure."""
    out = []
    for t in fig["data"]:
        if t.get("type", "scatter") == "scatter" and t.get("y") is not None:
            xa, ya = t.get("xaxis", "x"), t.get("yaxis", "y")
            out.append((xa, ya, t.get("name", ""), _arr(t["x"]), _arr(t["y"])))
    return out


def _axis_key(ref):  # "y2" -> "yaxis2"
    return f"{ref[0]}axis{ref[1:]}"


@pytest.mark.parametrize("name", EXAMPLES)
def test_no_curve_hides_another(reports, name):
    """Two traces drawn identically on the same axes would show as one: none may."""
    for p in reports[name]["data"]["plots"]:
        traces = _twod_traces(p["figure"])
        for i, (xa, ya, n1, x1, y1) in enumerate(traces):
            for xb, yb, n2, x2, y2 in traces[i + 1 :]:
                if (xa, ya) != (xb, yb) or x1.shape != x2.shape or y1.shape != y2.shape:
                    continue
                same = np.allclose(x1, x2, equal_nan=True) and np.allclose(y1, y2, equal_nan=True)
                assert not same, f"{p['id']}: {n2!r} hides {n1!r}"


@pytest.mark.parametrize("name", EXAMPLES)
def test_curves_stay_off_the_plot_edges(reports, name):
    """Every padded axis range holds its data with a margin: no line on the frame."""
    checked = 0
    for p in reports[name]["data"]["plots"]:
        layout = p["figure"]["layout"]
        for xa, ya, tname, x, y in _twod_traces(p["figure"]):
            for ref, v in ((ya, y), (xa, x)):
                axis = layout.get(_axis_key(ref), {})
                if "range" not in axis:
                    continue
                v = v[np.isfinite(v)]
                if axis.get("type") == "log":
                    v = np.log10(v)
                lo, hi = axis["range"]
                margin = 0.02 * (hi - lo)
                assert lo + margin < v.min() and v.max() < hi - margin, (p["id"], tname, ref)
                checked += 1
    assert checked >= 10


def test_wobble_chamber_pressures_all_visible_and_named(reports):
    fig = _plot(reports["wobble-cam-engine"], "plot-pressure")["figure"]
    names = [t["name"] for t in fig["data"]]
    curves = [t for t in fig["data"] if not t.get("meta")]  # not the max/min markers
    names = [t["name"] for t in curves]
    assert len(names) == 4, names
    named = [int(n) for name in names for n in name.replace(",", " ").split() if n.isdigit()]
    assert sorted(named) == list(range(1, 9)), "every chamber named once"
    assert all("identical" in n for n in names)
    assert (
        "4 distinct of 8 chambers"
        in _plot(reports["wobble-cam-engine"], "plot-pressure")["heading"]
    )
    # the four-stroke cycle: each curve peaks once per half turn, the peaks a quarter apart
    x = _arr(curves[0]["x"])
    peaks = sorted(x[np.argmax(_arr(t["y"]) * (x < 180))] for t in curves)
    assert np.allclose(np.diff(peaks), 45.0, atol=1.0), peaks


def test_wobble_log_pv_ticks_are_full_numbers(reports):
    layout = _plot(reports["wobble-cam-engine"], "plot-pv")["figure"]["layout"]
    for key, want in (("yaxis", [1, 2, 5, 10, 20, 50]), ("xaxis", [10, 20, 30, 50, 70])):
        axis = layout[key]
        assert axis["type"] == "log"
        assert axis["tickvals"] == want
        assert [float(t) for t in axis["ticktext"]] == want, "labels read 20, not 2"


def test_log_ticks_and_merge_identical_helpers():
    from rotorkin.render.scenes import log_ticks, merge_identical

    assert log_ticks(1.0, 65.8) == [1, 2, 5, 10, 20, 50]
    assert log_ticks(0.9, 1000.0) == [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000]
    assert log_ticks(7.2, 72.0) == [10, 20, 30, 50, 70]  # under a decade: 3 and 7 too
    assert log_ticks(0.0, 10.0) == [] and log_ticks(5.0, 5.0) == []
    a, b = np.sin(np.arange(5.0)), np.cos(np.arange(5.0))
    out = merge_identical([("chamber 1", a), ("chamber 2", b), ("chamber 3", a + 0.0),
                           ("chamber 4", b + 1e-3), ("chamber 5", a)])  # fmt: skip
    assert [n for n, _ in out] == ["chambers 1, 3 and 5 (identical)", "chamber 2", "chamber 4"]
    assert np.array_equal(out[0][1], a) and np.array_equal(out[2][1], b + 1e-3)


def test_guide_bar_torque_one_sign_convention(reports):
    """Both load models as the torque the motor must supply (positive), each named by model."""
    r = reports["guide-bar-pump"]
    p = _plot(r, "plot-torque")
    fig, cfg = p["figure"], r["cfg"]
    assert "motor must supply" in p["heading"]
    by = {t["name"]: (_arr(t["x"]), _arr(t["y"]), t.get("yaxis", "y")) for t in fig["data"]
          if not t.get("meta")}  # fmt: skip
    paper = next(n for n in by if n.startswith("paper eq. 7/8") and "M7 = 10" in n)
    ports = next(n for n in by if n.startswith("ideal ports") and "discharge 6 bar" in n)
    motor = next(n for n in by if n.startswith("motor torque with inertia"))
    inertia = by["inertia torque"][1]
    d = cfg["drive"]
    speed_ratio = 1.0 / (d["gear_ratio"] * d["input_gear_ratio"])  # mean impeller / input
    ld = cfg["loads"]
    _, m1, _ = by[paper]
    assert np.all(m1 > 0) and m1.min() == pytest.approx(4.0, abs=1e-4)  # eq. 7 at x = 0
    mean_eq7 = (ld["impeller_torque_1"] + ld["impeller_torque_2"]) * speed_ratio
    assert np.mean(m1[:-1]) == pytest.approx(mean_eq7, rel=1e-3)
    # ideal ports: the motor's work over a period = (p_d - p_s) x displaced volume
    x, mp, _ = by[ports]
    assert mp.min() > -1e-6 and mp.max() > 30.0
    dp = ld["discharge_pressure"] - ld["suction_pressure"]
    disp = _num(r["page"].rows["displacement_cm3_per_rev"][1]) * 1e-6  # per input-gear turn
    work = np.trapezoid(mp, np.radians(x))
    assert work == pytest.approx(dp * disp * x[-1] / 360.0, rel=2e-3)
    mean_line = next(v[1] for n, v in by.items() if n.startswith("ideal-ports mean"))
    assert np.allclose(mean_line, work / np.radians(x[-1]), rtol=2e-3)
    # with inertia, on the same convention: the motor supplies the load and the inertia torque
    assert np.allclose(by[motor][1], mp + inertia, atol=1e-3 * np.abs(mp).max())
    assert by[paper][2] != by[ports][2], "eq. 7/8 and ideal ports: two panels, own scales"
    # the checks say it on the same convention
    checks = " ".join(t for _, t in r["page"].checks)
    assert "motor must supply stays between 0 and 36.67 N·m" in checks, checks
    assert "-36.67" not in checks and "\u221236.67" not in checks


# --------------------------------------------------------------------------------------------
# the scenes are drawn from the model's coordinates: independent geometry on the frames
# --------------------------------------------------------------------------------------------
def _trace(scene, name_part):
    for i, t in enumerate(scene["animated"]):
        if name_part in scene["figure"]["data"][t].get("name", ""):
            return i
    raise KeyError(name_part)


def _xy(frame, i, keys=("x", "y"), scene=None):
    """Coordinates of animated trace i at a frame (a fixed one from the scene's trace)."""
    out = []
    for k in keys:
        values = frame[i][k] if k in frame[i] else scene["figure"]["data"][scene["animated"][i]][k]
        out.append(np.array([np.nan if v is None else v for v in values], float))
    return out


def test_rhombus_sides_and_blade_arms(reports):
    scene = reports["rhomboid-engine"]["data"]["scene"]
    ring, arm1 = _trace(scene, "rhombus ABCD"), _trace(scene, "blade arm, pair 1")
    for f in range(0, FRAMES, 7):
        x, y = _xy(scene["frames"][f], ring)
        assert np.allclose(np.hypot(np.diff(x), np.diff(y)), 120.0, atol=0.03)  # side 2l
        assert np.allclose([x[0] + x[2], y[0] + y[2]], 0.0, atol=0.02)  # A and C opposite
        ax, ay = _xy(scene["frames"][f], arm1)
        assert abs(ax[0] * ay[1] - ay[0] * ax[1]) < 0.05 * 120, "arm 1 passes through O"
        angle = np.degrees(np.arctan2(y[0], x[0])) % 360
        assert angle == pytest.approx(scene["angles_deg"][f] % 360, abs=0.05), "OA at alpha"


def test_wobble_rollers_on_sphere_and_grooves(reports):
    scene = reports["wobble-cam-engine"]["data"]["scene"]
    rol, gro = _trace(scene, "rollers of group 1"), _trace(scene, "cam grooves")
    for f in range(0, FRAMES, 11):
        p = np.array(_xy(scene["frames"][f], rol, ("x", "y", "z")))
        assert np.allclose(np.linalg.norm(p, axis=0), 60.0, atol=0.02)
        g = np.array(_xy(scene["frames"][f], gro, ("x", "y", "z"), scene))
        g = g[:, np.isfinite(g[0])]
        step = np.max(np.linalg.norm(np.diff(g, axis=1), axis=0))
        for k in range(p.shape[1]):
            assert np.min(np.linalg.norm(g - p[:, k : k + 1], axis=0)) < step, "roller in a groove"


def test_eccentric_followers_touch_the_discs(reports):
    scene = reports["eccentric-reactor"]["data"]["scene"]
    tips, left = _trace(scene, "knife-edge"), _trace(scene, "left disc")
    right = _trace(scene, "right disc")
    for f in range(0, FRAMES, 9):
        tx, ty = _xy(scene["frames"][f], tips)
        for k, i in enumerate((left, right)):
            dx, dy = _xy(scene["frames"][f], i)
            cx, cy = np.mean(dx[:-1]), np.mean(dy[:-1])
            assert np.hypot(tx[k] - cx, ty[k] - cy) == pytest.approx(80.0, abs=0.03)


def test_guide_bar_pin_on_the_guide(reports):
    scene = reports["guide-bar-pump"]["data"]["scene"]
    crank, guide = _trace(scene, "crank of mechanism 1"), _trace(scene, "guide bar")
    for f in range(0, FRAMES, 9):
        cx, cy = _xy(scene["frames"][f], crank)
        gx, gy = _xy(scene["frames"][f], guide)
        assert np.hypot(cx[1] - cx[0], cy[1] - cy[0]) == pytest.approx(1.0, abs=1e-3)  # crank a
        assert abs(gx[1] * cy[1] - gy[1] * cx[1]) < 2e-3 * np.hypot(gx[1], gy[1]), "pin on guide"


# --------------------------------------------------------------------------------------------
# command line
# --------------------------------------------------------------------------------------------
def test_cli_report_writes_and_prints_the_path(tmp_path, capsys):
    out = tmp_path / "r"
    assert main(["report", "-e", "eccentric-reactor", "--out", str(out)]) == 0
    printed = capsys.readouterr().out.strip()
    assert printed == str(out / "report.html") and (out / "report.html").stat().st_size > 1e6


def test_cli_report_default_folder(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    cfg = tmp_path / "mine.toml"
    cfg.write_text(_example("guide-bar-pump").read_text())
    assert main(["report", str(cfg), "--set", "drive.driver=guide"]) == 0
    path = tmp_path / "rotorkin-out" / "mine" / "report.html"
    assert capsys.readouterr().out.strip() == os.path.join("rotorkin-out", "mine", "report.html")
    page = _Page()
    page.feed(path.read_text())
    assert tomllib.loads(page.pre["config-toml"])["drive"]["driver"] == "guide"


def _example(name):
    from rotorkin.io.config import example_path

    return example_path(name)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["-e", "eccentric-reactor", "--set", "drive.eccentricity=90 mm"], "eccentricity"),
        (["-e", "nope"], "--example"),
        (["-e", "rhomboid-engine", "--set", "drive.psi_min=95 deg"], "drive.psi_min"),
    ],
)
def test_cli_report_bad_input(args, words, tmp_path, capsys):
    out = tmp_path / "o"
    assert main(["report", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err
    assert not out.exists()


def test_cli_report_out_is_a_file(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x")
    assert main(["report", "-e", "eccentric-reactor", "--out", str(f)]) == 2
    assert "--out" in capsys.readouterr().err and f.read_text() == "x"


@pytest.mark.slow
def test_run_with_report(tmp_path, monkeypatch, capsys):
    import dataclasses

    import rotorkin.drives

    real = rotorkin.drives.evaluate  # skip the PNG figures: only the --report hook is tested here
    monkeypatch.setattr(
        rotorkin.drives,
        "evaluate",
        lambda cfg: dataclasses.replace(real(cfg), write_figures=lambda outdir: []),
    )
    out = tmp_path / "run"
    assert main(["run", "-e", "guide-bar-pump", "--report", "-q", "--out", str(out)]) == 0
    assert (out / "report.html").stat().st_size > 1e6 and (out / "summary.json").exists()


@pytest.mark.slow
def test_cli_report_subprocess(tmp_path):
    out = tmp_path / "sub"
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "rotorkin.cli",
            "report",
            "-e",
            "rhomboid-engine",
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == str(out / "report.html") and proc.stderr == ""
    assert (out / "report.html").stat().st_size > 1e6
