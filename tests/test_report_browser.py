"""The HTML report in a real headless browser (Debian chromium + chromedriver, selenium).

One browser session for the four examples' reports. Each report is opened from
file:// with the network off (host resolver mapped to nothing, and CDP's
offline network emulation); then: no JavaScript errors, no resource from the
network, every plot drawn with the expected number of traces, the slider moves
the mechanism (coordinates read back from the page, both plotly's data and the
drawn SVG paths), play/pause works, and a screenshot is saved.

Screenshots: ``$ROTORKIN_ARTIFACTS`` if set (e.g. ``tests/artifacts``), else a
pytest temporary folder; the path is printed (``pytest -s``) and attached to the
test report as the ``artifacts`` property.
"""

from __future__ import annotations

import json
import os
import shutil
import time
from pathlib import Path

import pytest

from rotorkin import __version__
from rotorkin.drives import REGISTRY, evaluate
from rotorkin.io.config import example_names, load_config
from rotorkin.report.html import write_report

pytestmark = [pytest.mark.browser, pytest.mark.slow]

CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
EXAMPLES = example_names()  # every built-in example
LOAD_TIMEOUT = 90.0


def _need_browser():
    webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed")
    for path in (CHROMIUM, CHROMEDRIVER):
        if not (os.path.exists(path) or shutil.which(os.path.basename(path))):
            pytest.skip(f"{path} is missing (apt install chromium chromium-driver)")
    return webdriver


@pytest.fixture(scope="module")
def artifacts(tmp_path_factory):
    folder = os.environ.get("ROTORKIN_ARTIFACTS")
    path = Path(folder) if folder else tmp_path_factory.mktemp("report-artifacts")
    path.mkdir(parents=True, exist_ok=True)
    print(f"\nreport screenshots in {path}")
    return path


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    out = {}
    for name in EXAMPLES:
        cfg, raw, cname = load_config(None, name, [])
        meta = {"name": cname, "drive_type": cfg["drive"]["type"], "rotorkin_version": __version__}
        out[name] = write_report(
            evaluate(cfg), cfg, raw, meta, tmp_path_factory.mktemp(name) / "report.html"
        )
    return out


@pytest.fixture(scope="module")
def browser():
    webdriver = _need_browser()
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM if os.path.exists(CHROMIUM) else shutil.which("chromium")
    for arg in (
        "--headless=new",
        "--no-sandbox",
        "--disable-dev-shm-usage",
        "--window-size=1400,1000",
        "--force-device-scale-factor=1",
        # software WebGL for the 3D plots (no GPU here)
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        # no network: every host name resolves to nothing
        "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE localhost",
    ):
        opts.add_argument(arg)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = Service(
        CHROMEDRIVER if os.path.exists(CHROMEDRIVER) else shutil.which("chromedriver")
    )
    driver = webdriver.Chrome(service=service, options=opts)
    driver.set_page_load_timeout(LOAD_TIMEOUT)
    driver.set_script_timeout(30)
    driver.execute_cdp_cmd("Network.enable", {})
    driver.execute_cdp_cmd(
        "Network.emulateNetworkConditions",
        {"offline": True, "latency": 0, "downloadThroughput": 0, "uploadThroughput": 0},
    )
    yield driver
    driver.quit()


def _wait(driver, script, timeout, what):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        value = driver.execute_script(script)
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError(f"timed out after {timeout:.0f} s waiting for {what}")


def _severe(driver):
    return [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]


_DRAWN = """
const out = [];
for (const p of window.ROTORKIN.plots) {
  const gd = document.getElementById(p.id);
  const full = gd._fullData || [];
  const twoD = full.filter(t => t.type === 'scatter' && t.visible === true).length;
  const groups = gd.querySelectorAll('.scatterlayer .trace').length;
  const svg = gd.querySelector('svg.main-svg');
  const scenes = Object.keys(gd._fullLayout || {}).filter(k => /^scene\\d*$/.test(k));
  const gl = scenes.map(k => {
    const s = gd._fullLayout[k]._scene;
    const c = s && s.glplot && s.glplot.canvas;
    return c ? [c.width, c.height] : null;
  });
  out.push({id: p.id, kind: p.kind, expected: p.traces, data: gd.data.length,
            full: full.length, twoD: twoD, groups: groups,
            svg: svg ? [svg.clientWidth, svg.clientHeight] : null, gl: gl});
}
return JSON.stringify(out);
"""

_SNAPSHOT = """
const gd = document.getElementById('mechanism');
const S = window.ROTORKIN.scene;
const data = S.animated.map(t => {
  const d = gd.data[t], o = {};
  for (const k of ['x', 'y', 'z', 'text']) { if (d[k] !== undefined) o[k] = Array.from(d[k]); }
  return o;
});
const paths = Array.from(gd.querySelectorAll('.scatterlayer .trace path.js-line, '
                                              + '.scatterlayer .trace path.js-fill'))
                   .map(p => p.getAttribute('d'));
return JSON.stringify({frame: window.ROTORKIN.frame, data: data, paths: paths});
"""


_PLAY_PAUSE = """
const done = arguments[arguments.length - 1];
const button = document.getElementById('play-button'), f0 = ROTORKIN.frame, t0 = performance.now();
button.click();
(function poll() {
  const advanced = ROTORKIN.frame !== f0;
  if (advanced || performance.now() - t0 > 20000) {
    const playing = ROTORKIN.playing;
    button.click();
    done({advanced: advanced, was_playing: playing, playing: ROTORKIN.playing,
          label: button.textContent.replace(/[^A-Za-z]/g, '')});
  } else { setTimeout(poll, 20); }
})();
"""


@pytest.mark.parametrize("name", EXAMPLES)
def test_report_in_browser(name, browser, reports, artifacts, record_property):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    record_property("artifacts", str(artifacts))
    browser.get_log("browser")  # drop what an earlier page left
    browser.get(reports[name].as_uri())
    _wait(
        browser,
        "return window.ROTORKIN && (window.ROTORKIN.ready || window.ROTORKIN.errors.length > 0)",
        LOAD_TIMEOUT,
        "the report to draw",
    )
    rk = browser.execute_script("return {ready: ROTORKIN.ready, errors: ROTORKIN.errors}")
    assert rk["ready"] and rk["errors"] == [], rk["errors"]
    assert _severe(browser) == []
    urls = browser.execute_script(
        "return performance.getEntriesByType('resource').map(r => r.name)"
    )
    assert all(u.startswith(("file:", "data:", "blob:")) for u in urls), urls

    # every plot drawn, with the expected number of traces
    plots = json.loads(browser.execute_script(_DRAWN))
    # a drive's own scene: at least 6; the generic one of a vane machine: members, chambers,
    # p-V, torque and the mechanism
    assert len(plots) >= (6 if REGISTRY[load_config(example=name)[0]["drive"]["type"]].scene
                          else 5)  # fmt: skip
    for p in plots:
        assert p["data"] == p["full"] == p["expected"] > 0, p
        if p["twoD"]:
            assert p["svg"] and min(p["svg"]) > 100, p
            assert p["groups"] == p["twoD"], p
        if p["kind"] == "3d":
            assert p["gl"] and all(g and min(g) > 100 for g in p["gl"]), p

    # the slider moves the mechanism: drag it with the mouse, read the coordinates back
    section = browser.find_element(By.ID, "animation")
    browser.execute_script("arguments[0].scrollIntoView()", section)
    before = json.loads(browser.execute_script(_SNAPSHOT))
    assert before["frame"] == 0
    slider = browser.find_element(By.ID, "angle-slider")
    ActionChains(browser).click_and_hold(slider).move_by_offset(
        slider.size["width"] // 5, 0
    ).release().perform()
    frame = _wait(browser, "return ROTORKIN.frame", 10, "the slider to move the frame")
    _wait(
        browser,
        f"return document.getElementById('angle-slider').value == '{frame}'",
        5,
        "the slider and the frame to agree",
    )
    data = json.loads(
        browser.execute_script("return document.getElementById('rotorkin-data').textContent")
    )["scene"]

    def drawn_is_frame():
        now = json.loads(browser.execute_script(_SNAPSHOT))
        if now["frame"] != frame:
            return None
        for got, want in zip(now["data"], data["frames"][frame], strict=True):
            if any(got.get(k) != v for k, v in want.items()):
                return None
        return now

    end = time.monotonic() + 10
    after = None
    while after is None and time.monotonic() < end:
        after = drawn_is_frame()
        time.sleep(0.05)
    assert after is not None, "the mechanism's traces did not take the slider's frame"
    changed = [a != b for a, b in zip(after["data"], before["data"], strict=True)]
    assert sum(changed) >= len(changed) // 2, f"only {sum(changed)} of {len(changed)} moved"
    assert after["paths"] != before["paths"], "the drawn SVG did not change"
    angle = float(browser.find_element(By.ID, "angle-value").text)
    assert angle == pytest.approx(data["angles_deg"][frame], abs=0.06)

    # play, then pause (one round trip: a page busy animating 3D answers webdriver slowly)
    played = browser.execute_async_script(_PLAY_PAUSE)
    assert played["advanced"] and played["was_playing"] is True, played
    assert played["playing"] is False and played["label"] == "Play", played
    assert _severe(browser) == []
    assert browser.execute_script("return ROTORKIN.errors") == []

    # screenshots: the mechanism, and the whole page
    browser.execute_script("arguments[0].scrollIntoView()", section)
    shot = artifacts / f"{name}-mechanism.png"
    assert browser.save_screenshot(str(shot))
    full = artifacts / f"{name}-page.png"
    size = browser.execute_script("return [document.body.scrollWidth, document.body.scrollHeight]")
    png = browser.execute_cdp_cmd(
        "Page.captureScreenshot",
        {
            "format": "png",
            "captureBeyondViewport": True,
            "clip": {"x": 0, "y": 0, "width": size[0], "height": size[1], "scale": 1},
        },
    )
    import base64

    full.write_bytes(base64.b64decode(png["data"]))
    for path in (shot, full):
        blob = path.read_bytes()
        assert blob[:8] == b"\x89PNG\r\n\x1a\n" and len(blob) > 50_000, path


_TEXTS = """
const gd = document.getElementById(arguments[0]);
const texts = sel => Array.from(gd.querySelectorAll(sel)).map(t => t.textContent);
return {x: texts('.xaxislayer-above .xtick text'), y: texts('.yaxislayer-above .ytick text'),
        y2: texts('.yaxislayer-above .y2tick text'), legend: texts('.legend .legendtext'),
        lines: Array.from(gd.querySelectorAll('.scatterlayer .trace path.js-line'))
                    .filter(p => (p.getAttribute('d') || '').length > 20).length};
"""


def _drawn_texts(browser, reports, name, pid):
    browser.get(reports[name].as_uri())
    _wait(browser, "return window.ROTORKIN && window.ROTORKIN.ready", LOAD_TIMEOUT, "the report")
    return browser.execute_script(_TEXTS, pid)


def _number(label):  # plotly draws minus signs as U+2212
    return float(label.replace("\u2212", "-").replace(",", ""))


def test_drawn_labels_are_readable(browser, reports):
    """What the reader sees: full tick numbers on the log p-V, every chamber curve drawn and
    named, the pump's torque curves named by their model."""
    pv = _drawn_texts(browser, reports, "wobble-cam-engine", "plot-pv")
    assert [_number(t) for t in pv["y"]] == [1, 2, 5, 10, 20, 50], pv["y"]
    assert [_number(t) for t in pv["x"]] == [10, 20, 30, 50, 70], pv["x"]
    pressure = browser.execute_script(_TEXTS, "plot-pressure")
    assert pressure["lines"] == len(pressure["legend"]) == 4, pressure
    named = sorted(int(n) for t in pressure["legend"] for n in t.split() if n.isdigit())
    assert named == list(range(1, 9)), pressure["legend"]
    torque = _drawn_texts(browser, reports, "guide-bar-pump", "plot-torque")
    legend = " | ".join(torque["legend"])
    assert "paper eq. 7/8: constant impeller loads M7" in legend, legend
    assert "ideal ports: chamber pressures" in legend, legend
    assert "motor torque with inertia" in legend, legend
    # one sign convention: both load panels read positive (the motor supplies the torque)
    eq78, ports = ([_number(t) for t in torque[k]] for k in ("y", "y2"))
    assert min(eq78) >= 4 and max(eq78) <= 6.67, eq78  # eq. 7/8: 4 ... 6.67 N*m
    assert min(ports) >= 0 and max(ports) >= 30, ports  # ideal ports: 0 ... 36.7 N*m
