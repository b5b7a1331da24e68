"""rotorkin solve: one key for one metric's target, on every built-in example.

The solved value is checked by running the scalar study on the solved config
(independent of the root finder), and against the metric's closed form in the
key where it has one (docs/machines/vane_pump.md, twin_rotor.md,
docs/drives/wobble_cam.md eq. 17/23, guide_bar.md eq. 5); several roots against
a dense scan; the command line writes a config that ``rotorkin run`` brings to the
target, and refuses a target out of reach and unknown names in one line (exit 2).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from rotorkin.cli import main
from rotorkin.design import OutOfReach, solve
from rotorkin.drives import evaluate
from rotorkin.io.config import example_names, load_config, validate_config
from rotorkin.sweep import Designs, evaluate_designs

TOL = 1e-9


def _pump_flow(cfg, base):
    """Mean flow [l/min]: D_period = 2 Z k s, k = w (R_c^2 - R_h^2) / 2, s = 2 atan(lambda)
    (eq. 5 at Sigma = 180 deg, u = 2, crank-driven), over T_period = 2 pi i12 / omega."""
    m, d = cfg["machine"], cfg["drive"]
    k = 0.5 * m["axial_width"] * (m["casing_radius"] ** 2 - m["hub_radius"] ** 2)
    d_period = 2 * m["vanes_per_impeller"] * k * 2.0 * math.atan(d["lambda"])
    return d_period * cfg["run"]["speed"] / (2.0 * math.pi * d["input_gear_ratio"]) * 6e4


def _stroke(cfg, base):
    """Knife-edge pistons on discs of eccentricity e: stroke 2 e [mm]."""
    return 2.0 * cfg["drive"]["eccentricity"] * 1e3


def _compression_ratio(cfg, base):
    """Chamber angles psi - t ... 180 deg - psi - t: ratio (pi - psi_min - t) / (psi_min - t)."""
    psi, t = cfg["drive"]["psi_min"], cfg["machine"]["blade_thickness"]
    return (math.pi - psi - t) / (psi - t)


def _wobble_displacement(cfg, base):
    """V_s x 2N|n| with V_s = K (alpha'_max - alpha'_min), K = w (R_o^2 - R_i^2) / 2 and
    alpha'_max/min = 2 atan(tan(alpha/2) / cos phi), 2 atan(cos(phi) tan(alpha/2)) (eq. 17)."""
    m, d = cfg["machine"], cfg["drive"]
    half, phi = 0.5 * d["roller_axis_angle"], d["plate_tilt"]
    high = 2 * math.atan(math.tan(half) / math.cos(phi))
    low = 2 * math.atan(math.cos(phi) * math.tan(half))
    swing = high - low
    k = 0.5 * m["axial_width"] * (m["outer_radius"] ** 2 - m["inner_radius"] ** 2)
    return k * swing * 2 * m["pistons_per_rotor"] * abs(d["spin_ratio"]) * 1e6


def _any_drive_displacement(cfg, base):
    """V_s x 2N x (volume cycles per turn)/2, V_s = K s with K = w (R_o^2 - R_i^2)/2 and the
    drive's relative swing s (a property of the drive alone, read at the base design)."""
    m = cfg["machine"]
    k = 0.5 * m["axial_width"] * (m["outer_radius"] ** 2 - m["inner_radius"] ** 2)
    swing = math.radians(base["relative_swing_deg"])
    return k * swing * 2 * m["pistons_per_rotor"] * base["volume_cycles_per_rev"] / 2 * 1e6


#: example, --set, key, metric, target, closed form of the metric on a validated config
CASES = [
    ("guide-bar-pump", [], "machine.casing_radius", "flow_mean_l_per_min", 20.0, _pump_flow),
    ("guide-bar-pump", [], "run.speed", "flow_mean_l_per_min", 20.0, _pump_flow),
    ("eccentric-reactor", [], "drive.eccentricity", "piston_stroke_mm", 50.0, _stroke),
    ("rhomboid-engine", [], "drive.psi_min", "compression_ratio_geometric", 6.0,
     _compression_ratio),
    ("wobble-cam-engine", [], "drive.plate_tilt", "displacement_cm3_per_rev", 800.0,
     _wobble_displacement),
    ("elliptic-gear-engine", ['loads.model="ideal"'], "machine.outer_radius",
     "displacement_cm3_per_rev", 500.0, _any_drive_displacement),
    ("tabulated-engine", ['loads.model="ideal"'], "machine.outer_radius",
     "displacement_cm3_per_rev", 1500.0, _any_drive_displacement),
]  # fmt: skip


def test_every_example_has_a_case():
    assert {c[0] for c in CASES} == set(example_names())


@pytest.mark.parametrize(("example", "sets", "key", "metric", "target", "closed"), CASES,
                         ids=[f"{c[0]}:{c[2]}" for c in CASES])  # fmt: skip
def test_solve_hits_the_target(example, sets, key, metric, target, closed):
    _, raw, _ = load_config(None, example, sets)
    res = solve(raw, key, metric, target)
    section, _, name = key.partition(".")
    cfg = validate_config(res.raw)  # the config as written, read back
    assert cfg[section][name] == res.value
    assert res.value != raw.get(section, {}).get(name)  # it moved
    # the scalar study at the solved value, independent of the root finder
    reached = evaluate(cfg).summary[metric]
    assert abs(reached - target) <= TOL * abs(target)
    assert abs(res.residual) <= TOL * abs(target) and res.reached == reached
    # the closed form of the metric in the key, at the solved value
    base = evaluate(validate_config(raw)).summary
    assert abs(closed(cfg, base) - target) <= TOL * abs(target)
    assert res.roots_seen == 1
    assert res.lower.value <= res.value <= res.upper.value


def test_the_pump_radius_against_its_inverse():
    """R_c = sqrt(R_h^2 + Q i12 / (Z s w n)) with s = 2 atan(lambda), n in rev/s."""
    _, raw, _ = load_config(None, "guide-bar-pump")
    res = solve(raw, "machine.casing_radius", "flow_mean_l_per_min", 20.0)
    q = 20.0 / 6e4
    n = 1500.0 / 60.0
    exact = math.sqrt(0.03**2 + q * 2.0 / (2 * 2 * math.atan(0.5) * 0.04 * n))
    assert res.value == pytest.approx(exact, rel=1e-12)
    # the drive bounds the search below (hub radius), the schema above (10 m)
    assert res.lower.source == "drive" and "hub_radius" in res.lower.detail
    assert res.lower.value == pytest.approx(0.030, rel=1e-9)
    assert res.upper.source == "schema" and res.upper.value == 10.0
    assert res.kernel


def test_several_roots_the_nearest_to_the_start():
    """The pump's flow over the installation phase rises and falls on either side of 0:
    four roots; a dense scan finds them, the solver reports the one nearest 180 deg."""
    cfg, raw, _ = load_config(None, "guide-bar-pump")
    target = 280.0
    res = solve(raw, "drive.phase", "flow_mean_l_per_min", target)
    phase = np.radians(np.linspace(-359.9, 359.9, 20001))
    out = evaluate_designs(Designs(cfg, {"drive.phase": phase}, phase.size),
                           ["flow_mean_l_per_min"])  # fmt: skip
    d = out["metrics"]["flow_mean_l_per_min"] - target
    i = np.flatnonzero((d[:-1] * d[1:] < 0) & np.isfinite(d[:-1]) & np.isfinite(d[1:]))
    roots = phase[i] - d[i] * (phase[i + 1] - phase[i]) / (d[i + 1] - d[i])
    assert roots.size == 4 and res.roots_seen == 4
    nearest = roots[np.argmin(np.abs(roots - np.pi))]
    assert abs(res.value - nearest) < np.radians(1e-3)
    assert abs(res.reached - target) <= TOL * target
    # within a range that holds another root, that one
    other = roots[np.argmax(roots)]
    lo, hi = math.degrees(other) - 20, min(math.degrees(other) + 20, 359)
    res2 = solve(raw, "drive.phase", "flow_mean_l_per_min", target,
                 within=(f"{lo} deg", f"{hi} deg"))  # fmt: skip
    assert abs(res2.value - other) < np.radians(1e-3) and res2.lower.source == "range"


def test_out_of_reach_in_the_library():
    _, raw, _ = load_config(None, "rhomboid-engine")
    with pytest.raises(OutOfReach) as err:
        solve(raw, "drive.psi_min", "compression_ratio_geometric", 0.5)
    low, high = err.value.covers
    # the ratio falls from psi = t (blade thickness 10 deg) to psi -> 90 deg: (180-90-10)/(90-10)
    assert low == pytest.approx(1.0, rel=1e-6) and high > 1e6


def test_the_command_writes_a_config_that_runs_to_the_target(tmp_path, capsys):
    out = tmp_path / "solved"
    args = ["solve", "-e", "guide-bar-pump", "--for", "machine.casing_radius",
            "--target", "flow_mean_l_per_min=20", "--set", 'run.speed="1500 rpm"',
            "--out", str(out)]  # fmt: skip
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "machine.casing_radius = 35.48898991" in text and "the scan saw 1 root" in text
    doc = json.loads((out / "solve.json").read_text())
    assert doc["unit"] == "mm" and abs(doc["value"] - 35.4889899177) < 1e-9
    assert main(["run", str(out / "config.toml"), "--out", str(tmp_path / "run"), "-q"]) == 0
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert abs(summary["flow_mean_l_per_min"] - 20.0) <= TOL * 20.0


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--for", "machine.casing_radius", "--target", "flow_mean_l_per_min=1e9"],
         ["flow_mean_l_per_min = 1e+09 l/min is out of reach", "machine.casing_radius from "
          "30 mm to 10000 mm", "covers 3.3"]),
        (["--for", "machine.nope", "--target", "flow_mean_l_per_min=20"],
         ["--for 'machine.nope' is not admissible", "machine.casing_radius", "drive.lambda"]),
        (["--for", "machine.vanes_per_impeller", "--target", "flow_mean_l_per_min=20"],
         ["an integer key", "machine.casing_radius"]),
        (["--for", "machine.casing_radius", "--target", "flow_nope=20"],
         ["the metric 'flow_nope'", "flow_mean_l_per_min", "displacement_cm3_per_rev"]),
        (["--for", "machine.casing_radius", "--target", "flow_mean_l_per_min"],
         ["write it as METRIC=VALUE"]),
        (["--for", "machine.casing_radius", "--target", "flow_mean_l_per_min=20 l/min"],
         ["a finite number in the metric's unit"]),
        (["--for", "machine.casing_radius", "--target", "flow_mean_l_per_min=20",
          "--within", "40mm:50mm"], ["out of reach", "from 40 mm to 50 mm"]),
        (["--for", "machine.casing_radius", "--target", "flow_mean_l_per_min=20",
          "--within", "40:50mm"], ["has no unit"]),
    ],
)  # fmt: skip
def test_bad_input_is_one_line(args, words, tmp_path, capsys):
    out = tmp_path / "o"
    assert main(["solve", "-e", "guide-bar-pump", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("rotorkin: error: ")
    for w in words:
        assert w in err[0]
    assert not out.exists()
