"""The report's numbers and words without a browser: extremes, hover, ticks, CSV, labels.

Every expected value is computed here from the study's own columns (``result.columns``,
the curves the drive's plots draw) with numpy, or from a closed form, not copied from
the page: the extremes against ``argmax``/``argmin``, the CSV columns against the study's
columns, the hover formats against the digits they must show, the summary's torque ripple
against ``(max - min) / |mean|`` of the shaft torque.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
from html.parser import HTMLParser

import numpy as np
import pytest

from rotorkin import __version__
from rotorkin.drives import evaluate, spec_of
from rotorkin.io.config import load_config
from rotorkin.report.html import render_report
from rotorkin.report.plots import angle_dtick, extremes, plot_csv, prepare, short_name
from rotorkin.report.text import d3_format, key_label, number, pretty, unit_of

EXAMPLES = ["wobble-cam-engine", "eccentric-reactor", "guide-bar-pump", "rhomboid-engine"]


class _Page(HTMLParser):
    """Rows of the summary table (key -> cell texts), extremes tables, visible text."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.rows, self.defs, self.text, self.extremes = {}, {}, [], []
        self._row = self._cell = self._def = None
        self._skip = 0
        self._ext = None
        self.data = None
        self._json = False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag in ("script", "style", "pre", "code"):
            self._skip += 1
            self._json = a.get("id") == "rotorkin-data"
        if tag == "tr" and "data-key" in a and a["data-key"] not in self.rows:
            self._row = [a["data-key"], []]
        elif tag == "table" and "extremes" in a.get("class", ""):
            self._ext = []
        elif tag == "tr" and self._ext is not None:
            self._ext.append([])
        elif tag == "td" and (self._row is not None or self._ext is not None):
            self._cell = []
        elif tag == "span" and a.get("class") == "def" and self._row is not None:
            self._def = []

    def handle_endtag(self, tag):
        if tag in ("script", "style", "pre", "code"):
            self._skip -= 1
        if tag == "span" and self._def is not None:
            self.defs[self._row[0]] = "".join(self._def).strip()
            self._def = None
        if tag == "td" and self._cell is not None:
            text = "".join(self._cell).strip()
            if self._row is not None:
                self._row[1].append(text)
            elif self._ext:
                self._ext[-1].append(text)
            self._cell = None
        elif tag == "tr" and self._row is not None:
            self.rows[self._row[0]] = self._row[1]
            self._row = None
        elif tag == "table" and self._ext is not None:
            self.extremes.append([r for r in self._ext if r])
            self._ext = None

    def handle_data(self, data):
        if self._json:
            self.data = json.loads(data)
            self._json = False
        for buf in (self._cell, self._def):
            if buf is not None:
                buf.append(data)
        if not self._skip:
            self.text.append(data)


@pytest.fixture(scope="module")
def runs():
    out = {}
    for name in EXAMPLES:
        cfg, raw, cname = load_config(None, name, [])
        result = evaluate(cfg)
        meta = {"name": cname, "drive_type": cfg["drive"]["type"], "rotorkin_version": __version__}
        page = _Page()
        page.feed(render_report(result, cfg, raw, meta))
        plots = spec_of(cfg).scene.plots(result, cfg)
        out[name] = {"cfg": cfg, "result": result, "page": page, "plots": plots}
    return out


def _num(text: str) -> float:
    """The number a cell starts with; U+2212 minus, thousands commas and x10^n allowed."""
    t = text.replace("\u2212", "-").replace(",", "")
    m = re.search(r"[-+]?\d+(?:\.\d*)?(?:e[-+]?\d+)?", t)
    value = float(m.group(0))
    sup = re.search(r"×10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)", t)
    if sup:
        value *= 10.0 ** int(sup.group(1).translate(str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")))
    return value


def _d3(fmt: str, v: float) -> str:
    """What a d3 format of the kinds the report writes (",.Nf", ".Ne", ",.Nr") makes of v."""
    m = re.fullmatch(r"(,?)\.(\d+)([fer])", fmt)
    assert m, fmt
    n = int(m.group(2))
    if m.group(3) == "r":  # n significant digits, fixed notation
        rounded = float(f"{v:.{n}g}")
        decimals = max(0, n - 1 - int(math.floor(math.log10(abs(rounded)))))
        return format(rounded, f"{m.group(1)}.{decimals}f")
    return format(v, f"{m.group(1)}.{n}{m.group(3)}")


def _significant(text: str, fmt: str = "f") -> int:
    """Significant digits written; with a "r" format (rounded to n significant digits) the
    trailing zeros of an integer are placeholders."""
    mantissa = text.replace(",", "").replace("-", "").split("e")[0]
    digits = mantissa.replace(".", "").lstrip("0")
    return len(digits.rstrip("0") or "0") if fmt.endswith("r") else len(digits)


# --------------------------------------------------------------------------------------------
# words and digits
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("raw", "shown"),
    [
        ("chamber A delta_A", "chamber A δ<sub>A</sub>"),
        ("volume [cm^3]", "volume [cm³]"),
        ("chamber 1 volume cm3", "chamber 1 volume cm³"),
        ("torque [N*m]", "torque [N·m]"),
        ("flywheel [kg*m^2]", "flywheel [kg·m²]"),
        ("jerk [rad/s^3]", "jerk [rad/s³]"),
        ("shaft angle theta [deg]", "shaft angle θ [°]"),
        ("alpha' = Phi_2 - Phi_1", "α′ = Φ₂ - Φ₁"),
        ("alpha'_max", "α′<sub>max</sub>"),
        ("vane angle gamma_0 at 45 deg", "vane angle γ₀ at 45°"),
        ("+-e cos beta", "±e cos β"),
        ("M7 dq_1/dtheta + M8 dq_2/dtheta", "M7 dq₁/dθ + M8 dq₂/dθ"),
        ("limit &lt;= 250 bar, >= 0 mm", "limit ≤ 250 bar, ≥ 0 mm"),
        ("machine.vane_angle and shaft_torque_Nm", "machine.vane_angle and shaft_torque_Nm"),
    ],
)
def test_pretty_labels(raw, shown):
    assert pretty(raw) == shown


def test_key_labels_and_units():
    assert key_label("mean_torque_Nm") == ("Mean torque", "N·m")
    assert key_label("slider_angle_max_deg") == ("Slider angle, max", "°")
    assert key_label("displacement_cm3_per_rev") == ("Displacement", "cm³/rev")
    assert key_label("flow_mean_l_per_min") == ("Flow, mean", "l/min")
    assert key_label("psi_min_deg") == ("ψ, min", "°")
    assert key_label("torque_ripple") == ("Torque ripple", "")
    assert unit_of("pressure [bar]") == "bar" and unit_of("speed ratio") == ""


def test_roundoff_is_zero_only_relative_to_the_scale():
    assert number(1.4135798584282297e-16, 4, scale=4.16) == "0"  # a zero mean torque's round-off
    assert number(1.4135798584282297e-16) == "1.414×10⁻¹⁶"  # no scale: written as it is
    assert number(2e-6, 4, scale=1000.0) == "2.000×10⁻⁶"  # above 1e-9 of the scale: kept
    assert number(-16.234197941547663) == "−16.23"
    assert number(600.0000000000001, 6) == "600"
    assert number(-217558100.0) == "−2.176×10⁸"


@pytest.mark.parametrize("big", [0.00123, 0.5, 3.7, 36.67, 657.0, 4188.4, 30646.9, 2.1e8, 7e-5])
def test_hover_format_has_four_significant_digits(big):
    values = np.array([0.0, 0.25 * big, -big])
    fmt = d3_format(values)
    text = _d3(fmt, -big)
    assert _significant(text, fmt) == 4, text
    assert not re.search(r"[kMGTmunμ]$", text)  # d3's SI suffixes never appear


def test_angle_tick_spacing():
    assert [angle_dtick(s) for s in (360, 720, 300, 180, 120, 90, 30)] == [
        90, 90, 90, 45, 45, 15, 15
    ]  # fmt: skip
    for span in (360.0, 720.0, 180.0):
        ticks = np.arange(0.0, span + 1e-9, angle_dtick(span))
        assert np.all(np.mod(ticks, 90.0 if span >= 270 else 45.0) == 0.0)


def test_short_legend_names_keep_the_start():
    name = "paper eq. 7/8: constant impeller loads M7 = 10, M8 = 10 N·m"
    assert short_name(name) == "paper eq. 7/8"
    assert short_name("rotor 1") == "rotor 1"
    long = "a flat-faced harmonic piston face position without any separator at all"
    assert len(short_name(long)) <= 29 and long.startswith(short_name(long).rstrip("…"))


# --------------------------------------------------------------------------------------------
# the plots of the four examples
# --------------------------------------------------------------------------------------------
def _decoded(fig):
    from rotorkin.report.plots import _decode

    j = fig.to_plotly_json() if hasattr(fig, "to_plotly_json") else fig
    return {"data": [_decode(dict(t)) for t in j["data"]], "layout": _decode(dict(j["layout"]))}


def _series(values):
    return np.array([np.nan if v is None else v for v in np.ravel(values)], dtype=float)


@pytest.mark.parametrize("name", EXAMPLES)
def test_extremes_against_argmax(runs, name):
    """Each curve's largest and smallest value and the angle of its first occurrence."""
    checked = 0
    for plot in runs[name]["plots"]:
        if plot.cursor_period_deg is None:
            continue
        fig = _decoded(plot.figure)
        rows = {r["trace"]: r for r in extremes(fig)}
        for i, t in enumerate(fig["data"]):
            if t.get("y") is None or "lines" not in (t.get("mode") or "lines"):
                continue
            x, y = _series(t["x"]), _series(t["y"])
            if np.nanmax(y) - np.nanmin(y) <= 1e-12 * np.nanmax(np.abs(y)):
                assert i not in rows, "a constant line has no extremes"
                continue
            r = rows[i]
            hi, lo = int(np.nanargmax(y)), int(np.nanargmin(y))
            tol = 1e-9 * (y[hi] - y[lo])  # round-off: a periodic curve meets it again
            assert r["max"] == pytest.approx(y[hi], abs=tol) and r["min"] == pytest.approx(
                y[lo], abs=tol
            )
            # the first sample at the extreme
            assert r["x_max"] == x[np.flatnonzero(y >= y[hi] - tol)[0]]
            assert r["x_min"] == x[np.flatnonzero(y <= y[lo] + tol)[0]]
            checked += 1
    assert checked >= 8


def test_extremes_table_against_the_study_columns(runs):
    """The wobble engine's gas torque and chamber pressures: the page's extremes table against
    numpy on the study's columns."""
    run = runs["wobble-cam-engine"]
    cols, page = run["result"].columns, run["page"]
    theta = np.asarray(cols["theta_deg"])
    tables = {tuple(r[0] for r in t): t for t in page.extremes}
    torque = next(t for k, t in tables.items() if "gas torque" in k)
    row = next(r for r in torque if r[0] == "gas torque")
    T = np.asarray(cols["shaft_torque_Nm"])
    tol = 1e-9 * (T.max() - T.min())  # the first angle of an extreme met again each cycle
    assert _num(row[2]) == pytest.approx(T.max(), rel=5e-4)
    assert _num(row[3]) == pytest.approx(theta[np.flatnonzero(T >= T.max() - tol)[0]], abs=0.051)
    assert _num(row[4]) == pytest.approx(T.min(), rel=5e-4)
    assert _num(row[5]) == pytest.approx(theta[np.flatnonzero(T <= T.min() + tol)[0]], abs=0.051)
    pressure = next(t for k, t in tables.items() if any("chambers 1 and 5" in n for n in k))
    row = next(r for r in pressure if r[0].startswith("chambers 1 and 5"))
    p1 = np.asarray(cols["chamber1_pressure_bar"])
    assert _num(row[2]) == pytest.approx(p1.max(), rel=5e-4)
    assert _num(row[3]) == pytest.approx(theta[np.argmax(p1)], abs=0.051)


@pytest.mark.parametrize("name", EXAMPLES)
def test_hover_names_units_digits_and_ticks(runs, name):
    data = runs[name]["page"].data
    assert data is not None
    checked = 0
    for p in data["plots"]:
        layout = p["figure"]["layout"]
        assert layout["hoverlabel"]["namelength"] == -1, "names are never cut"
        for key, axis in layout.items():
            if re.fullmatch(r"[xy]axis\d*", key):
                assert axis["exponentformat"] == "power", (p["id"], key)
            if p["cursor_period_deg"] and re.fullmatch(r"xaxis\d*", key):
                span = p["cursor_period_deg"]
                assert axis["tick0"] == 0 and axis["dtick"] == angle_dtick(span), (p["id"], key)
                assert axis["dtick"] in (45.0, 90.0) and axis["ticksuffix"] == "°"
                checked += 1
        for t in p["figure"]["data"]:
            if t.get("type") != "scatter" or t.get("meta") or t.get("hoverinfo") == "skip":
                continue
            tmpl = t["hovertemplate"]
            assert tmpl.startswith(t["name"]), (p["id"], tmpl)  # the full name, not cut
            ya = "yaxis" + t.get("yaxis", "y")[1:]
            unit = unit_of(layout[ya]["title"]["text"])
            if unit:
                assert unit in tmpl, (p["id"], tmpl)
            fmt = re.search(r"%\{y:([^}]*)\}", tmpl).group(1)
            y = _series(t["y"])
            big = float(np.nanmax(np.abs(y)))
            if big > 0:
                assert _significant(_d3(fmt, big), fmt) == 4, (p["id"], t["name"], fmt, big)
    assert checked >= 8


@pytest.mark.parametrize("name", EXAMPLES)
def test_no_snake_case_or_ascii_units_shown(runs, name):
    page = runs[name]["page"]
    text = " ".join(page.text)
    for bad in ("cm^3", "N*m", "kg*m^2", "[deg]", "delta_", "alpha'", "OCR", "^2", "^3"):
        assert bad not in text, bad
    assert not re.search(r"\d cm3\b", text)
    for key, cells in page.rows.items():
        label = cells[0].replace(page.defs.get(key, ""), "")
        assert "_" not in label, (key, label)  # labels in words
    for p in page.data["plots"]:
        fig = p["figure"]
        labels = [t.get("name") or "" for t in fig["data"]]
        axes = [a for k, a in fig["layout"].items() if re.fullmatch(r"[xy]axis\d*", k)]
        labels += [a["title"]["text"] for a in axes if isinstance(a.get("title"), dict)]
        for label in labels:
            for bad in ("cm^3", "cm3", "N*m", "[deg]", "delta_", "^2", "^3", "theta", "alpha"):
                assert bad not in label, (p["id"], label)


# --------------------------------------------------------------------------------------------
# CSV
# --------------------------------------------------------------------------------------------
def _csv(runs, name, pid):
    p = next(p for p in runs[name]["page"].data["plots"] if p["id"] == pid)
    rows = list(csv.reader(io.StringIO(p["csv"])))
    head, body = rows[0], np.array([[float(v) if v else np.nan for v in r] for r in rows[1:]])
    return head, body


def test_csv_holds_the_study_columns(runs):
    cols = runs["wobble-cam-engine"]["result"].columns
    head, body = _csv(runs, "wobble-cam-engine", "plot-pressure")
    assert head[0] == "shaft angle θ [°]"
    assert np.allclose(body[:, 0], cols["theta_deg"], rtol=1e-6, atol=1e-9)
    k = next(i for i, h in enumerate(head) if h.startswith("chambers 1 and 5"))
    assert head[k].endswith("[bar]")
    assert np.allclose(body[:, k], cols["chamber1_pressure_bar"], rtol=1e-6)
    assert np.allclose(body[:, k], cols["chamber5_pressure_bar"], rtol=1e-6)
    head, body = _csv(runs, "wobble-cam-engine", "plot-svaj")
    k = head.index("rotor 1: jerk [rad/s³]")
    assert np.allclose(body[:, k], cols["rotor1_jerk_rad_per_s3"], rtol=1e-6)
    cols = runs["guide-bar-pump"]["result"].columns
    head, body = _csv(runs, "guide-bar-pump", "plot-torque")
    k = next(i for i, h in enumerate(head) if h.startswith("paper eq. 7/8"))
    assert head[k].endswith("[N·m]")
    assert np.allclose(body[:, k], cols["input_torque_Nm"], rtol=1e-6)
    k = next(i for i, h in enumerate(head) if h.startswith("ideal ports: chamber pressures"))
    assert np.allclose(body[:, k], -np.asarray(cols["shaft_torque_Nm"]), rtol=1e-6, atol=1e-9)


def test_csv_of_an_xy_plot_keeps_both_axes():
    fig = {"data": [{"type": "scatter", "name": "loop", "x": [1.0, 2.0, 3.0], "y": [5, 6, 5]},
                    {"type": "scatter", "name": "other", "x": [0.5, 1.5], "y": [1, 2]}],
           "layout": {"xaxis": {"title": {"text": "volume [cm^3]"}},
                      "yaxis": {"title": {"text": "pressure [bar]"}}}}  # fmt: skip
    rows = list(csv.reader(io.StringIO(plot_csv(fig))))
    assert rows[0] == ["loop: volume [cm³]", "loop: pressure [bar]", "other: volume [cm³]",
                       "other: pressure [bar]"]  # fmt: skip
    assert rows[1] == ["1", "5", "0.5", "1"] and rows[3] == ["3", "5", "", ""]


# --------------------------------------------------------------------------------------------
# summary table
# --------------------------------------------------------------------------------------------
def test_summary_definitions_and_torque_ripple(runs):
    for name in EXAMPLES:
        page, result = runs[name]["page"], runs[name]["result"]
        for key in result.headline:
            if key in result.summary:
                assert page.defs.get(key), (name, key)
        if "torque_ripple" in result.summary:
            assert "|T" in page.defs["torque_ripple"]  # (T_max - T_min) / |T_mean|
            # (max - min) / |mean| over one period (the study samples finer than its columns)
            T = np.asarray(result.columns["shaft_torque_Nm"])
            ripple = (T.max() - T.min()) / abs(np.mean(T[:-1]))
            assert _num(page.rows["torque_ripple"][1]) == pytest.approx(ripple, rel=1e-3)


def test_pump_torque_on_the_plots_convention(runs):
    """The table's mean torque of the pump equals the plot's mean line (the motor's torque)."""
    run = runs["guide-bar-pump"]
    row, definition = run["page"].rows["mean_torque_Nm"], run["page"].defs["mean_torque_Nm"]
    assert "motor supplies" in row[0] and "positive when the motor drives" in definition
    plot = next(p for p in run["page"].data["plots"] if p["id"] == "plot-torque")
    mean_line = next(t for t in plot["figure"]["data"] if t["name"].startswith("ideal-ports mean"))
    assert _num(row[1]) == pytest.approx(mean_line["y"][0], rel=1e-4)
    assert _num(row[1]) > 0 and run["result"].summary["mean_torque_Nm"] < 0
    # work of the ideal ports per period over the period angle, from the study's columns
    x, T = (np.asarray(run["result"].columns[k]) for k in ("theta_deg", "shaft_torque_Nm"))
    assert _num(row[1]) == pytest.approx(-np.trapezoid(T, np.radians(x)) / np.radians(x[-1]),
                                         rel=2e-3)  # fmt: skip
    engine = runs["wobble-cam-engine"]["page"].defs["mean_torque_Nm"]
    assert "positive when the machine" in engine


def test_roundoff_shown_as_zero(runs):
    rows = runs["eccentric-reactor"]["page"].rows
    summary = runs["eccentric-reactor"]["result"].summary
    # the mean of a torque whose integral over the period vanishes: round-off or exactly 0
    assert abs(summary["mean_torque_Nm"]) < 1e-12 * summary["shaft_torque_max_Nm"]
    assert rows["mean_torque_Nm"][1].split()[0] == "0"
    for key, cells in rows.items():
        if len(cells) > 3 and cells[3]:
            diff = cells[3].split()[0]
            assert "e-1" not in diff and "×10⁻¹" not in diff, (key, cells[3])


# --------------------------------------------------------------------------------------------
# the mechanism: every chamber's pressure; failed checks drawn
# --------------------------------------------------------------------------------------------
def test_every_wobble_chamber_pressure_is_labelled(runs):
    run = runs["wobble-cam-engine"]
    scene = run["page"].data["scene"]
    k = next(i for i, t in enumerate(scene["animated"])
             if "pressure" in scene["figure"]["data"][t].get("name", ""))  # fmt: skip
    cols = run["result"].columns
    theta = np.asarray(cols["theta_deg"])
    chambers = sorted(int(c[7:].split("_")[0]) for c in cols
                      if re.fullmatch(r"chamber\d+_pressure_bar", c))  # fmt: skip
    frames_max = []
    for f, fr in enumerate(scene["frames"]):
        labels = fr[k]["text"]
        assert len(labels) == len(chambers) == 8
        got = {int(t.split("<br>")[0]): float(t.split("<br>")[1].split()[0]) for t in labels}
        assert sorted(got) == chambers
        a = scene["angles_deg"][f] % 360.0
        want = {c: np.interp(a, theta, cols[f"chamber{c}_pressure_bar"]) for c in chambers}
        for c in chambers:
            assert got[c] == pytest.approx(want[c], rel=6e-3, abs=6e-3), (f, c)
        frames_max.append(max(got.values()))
    assert max(frames_max) > 0.8 * run["result"].summary["peak_pressure_bar"]


def test_failed_checks_are_drawn(runs, tmp_path):
    run = runs["wobble-cam-engine"]
    failed = [c for c in run["result"].checks if not c.passed]
    assert [c.key for c in failed] == ["contact.allowable_stress"]
    forces = next(p for p in run["page"].data["plots"] if p["id"] == "plot-forces")
    limit = next(t for t in forces["figure"]["data"] if t.get("meta") == "limit"
                 and t.get("mode") == "lines")  # fmt: skip
    assert limit["y"] == [failed[0].limit] * 2 and "FAILS" in limit["name"]
    mark = next(t for t in forces["figure"]["data"] if t.get("name") == "failed check ✖")
    stress = max(np.nanmax(run["result"].columns[c]) for c in run["result"].columns
                 if c.endswith("_contact_stress_MPa"))  # fmt: skip
    assert mark["y"][0] == pytest.approx(stress, rel=1e-5)
    peak = run["result"].summary["peak_contact_stress_MPa"]  # on the study's finer grid
    assert mark["y"][0] == pytest.approx(peak, rel=2e-4)
    # a pressure limit below the cycle's peak: drawn on the pressure plot at its value
    cfg, raw, cname = load_config(None, "wobble-cam-engine", ["limits.peak_pressure=40 bar"])
    result = evaluate(cfg)
    plots = spec_of(cfg).scene.plots(result, cfg)
    bad = [c for c in result.checks if not c.passed]
    entry = prepare(next(p for p in plots if p.id == "plot-pressure"), bad)
    assert "peak gas pressure" in entry["checks"]
    line = next(t for t in entry["figure"]["data"] if t.get("meta") == "limit")
    assert line["y"] == [pytest.approx(40.0)] * 2
    peak = max(np.nanmax(result.columns[c]) for c in result.columns
               if re.fullmatch(r"chamber\d+_pressure_bar", c))  # fmt: skip
    mark = entry["figure"]["data"][-1]
    assert mark["y"][0] == pytest.approx(peak, rel=1e-9) and math.isfinite(mark["x"][0])
