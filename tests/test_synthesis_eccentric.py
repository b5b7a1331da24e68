"""Eccentric-cam synthesis: lambda or the follower for a tolerated gap change."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate, synthesize
from rotorkin.drives.eccentric_cam import synthesis as se
from rotorkin.io.config import load_config, validate_config
from rotorkin.synthesis import synthesized_raw_config


def _gap(beta, R, e):
    """Gap change from explicit geometry: each knife edge on the follower axis touches its disc.

    Left disc centre at e (cos b, sin b), right at -e (cos b, sin b); a follower tip on
    the x axis touches its disc where (x - c_x)^2 + c_y^2 = R^2, on the side facing
    the reactor (travel towards the centre positive; zero at the balanced position).
    """
    cx, cy = e * np.cos(beta), e * np.sin(beta)
    left = cx + np.sqrt(R * R - cy * cy) - R  # inward travel of the left piston
    right = -cx + np.sqrt(R * R - cy * cy) - R  # mirror: the right disc is half a turn on
    return left + right


def _peak(R, e):
    """Largest |gap change| by bounded minimisation of the geometry (value error 2nd order)."""
    res = minimize_scalar(
        lambda b: _gap(b, R, e), bounds=(0.3, 2.8), method="bounded", options={"xatol": 1e-10}
    )
    return -float(res.fun)


@pytest.mark.parametrize("gap_mm", [0.5, 5.0, 10.0, 21.0, 60.0])
def test_contact_radius_keeps_stroke(gap_mm):
    e, gap = 0.04, gap_mm * 1e-3
    Rc = float(se.contact_radius_for_gap_change(gap, e))
    assert Rc > e
    assert abs(_peak(Rc, e) - gap) <= 1e-9 * gap


@pytest.mark.parametrize("gap_mm", [0.5, 5.0, 10.0, 21.0, 100.0])
def test_eccentricity_keeps_disc(gap_mm):
    R, gap = 0.08, gap_mm * 1e-3
    e = float(se.eccentricity_for_gap_change(gap, R))
    assert 0.0 < e < R
    assert abs(_peak(R, e) - gap) <= 1e-9 * gap


def test_out_of_range_is_nan_and_vectorized():
    out = se.contact_radius_for_gap_change(np.array([[0.01, 0.09], [0.0, 0.05]]), 0.04)
    assert out.shape == (2, 2)
    assert np.isnan(out[0, 1]) and np.isnan(out[1, 0]) and np.isfinite(out[0, 0])
    assert np.isnan(se.eccentricity_for_gap_change(0.2, 0.08))


@pytest.mark.parametrize("target", ["1 %", "0.01", "10 mm", "0.35%"])
def test_synthesize_round_trip(target):
    cfg, raw, _ = load_config(None, "eccentric-reactor", [])
    res = synthesize(cfg, raw, "gap_change", target)
    want = res.metrics["target_gap_change_mm"] * 1e-3
    expected = {"1 %": 0.01, "0.01": 0.01, "10 mm": 0.01, "0.35%": 0.0035}[target]
    assert abs(want - expected) < 1e-15
    assert res.metrics["round_trip_relative_error"] <= 1e-9
    new = validate_config(synthesized_raw_config(raw, res.updates, "gap_change"))
    d = new["drive"]
    assert d["eccentricity"] == pytest.approx(0.04, rel=1e-14)  # the stroke is kept
    assert abs(_peak(d["disc_radius"], d["eccentricity"]) - want) <= 1e-9 * want
    summary = evaluate(new).summary
    assert abs(abs(summary["gap_change_min_mm"]) * 1e-3 - want) <= 1e-9 * want
    options = {k: v for k, v in res.metrics.items() if k.startswith("option_")}
    # the roller option: disc and eccentricity kept, the roller grows the contact radius
    r = options["option_roller_roller_radius_mm"] * 1e-3
    assert abs(_peak(0.08 + r, 0.04) - want) <= 1e-9 * want
    e2 = options["option_disc_eccentricity_mm"] * 1e-3
    assert abs(_peak(0.08, e2) - want) <= 1e-9 * want


def test_zero_target_gives_flat_follower():
    cfg, raw, _ = load_config(None, "eccentric-reactor", [])
    res = synthesize(cfg, raw, "gap_change", "0")
    assert res.updates["drive"]["follower"] == "flat"
    new = validate_config(synthesized_raw_config(raw, res.updates, "gap_change"))
    assert evaluate(new).summary["gap_change_min_mm"] == 0.0


def test_roller_baseline_keeps_roller():
    cfg, raw, _ = load_config(
        None, "eccentric-reactor", ["drive.follower=roller", "drive.roller_radius=10 mm"]
    )
    res = synthesize(cfg, raw, "gap_change", "1 %")
    new = validate_config(synthesized_raw_config(raw, res.updates, "gap_change"))
    d = new["drive"]
    assert d["follower"] == "roller" and d["roller_radius"] == pytest.approx(0.01)
    assert abs(_peak(d["disc_radius"] + d["roller_radius"], d["eccentricity"]) - 0.01) <= 1e-11


@pytest.mark.parametrize(
    "target, words",
    [
        ("9 %", ["target = ", "|Delta| < 80 mm"]),
        ("-1 %", ["target = ", ">= 0"]),
        ("lots", ["target = ", "'lots'"]),
    ],
)
def test_errors(target, words):
    cfg, raw, _ = load_config(None, "eccentric-reactor", [])
    with pytest.raises(ParameterError) as err:
        synthesize(cfg, raw, "gap_change", target)
    msg = str(err.value)
    assert "\n" not in msg and "--" not in msg and err.value.name == "target"
    for w in words:
        assert w in msg


def test_default_target_half_the_design_gap():
    """No --target: half the example's own peak gap change, met by the forward analysis."""
    cfg, raw, _ = load_config(None, "eccentric-reactor", [])
    res = synthesize(cfg, raw, "gap_change")
    own = _peak(0.08, 0.04)  # 21.44 mm, knife edge R = 80 mm, e = 40 mm
    want = 0.5 * own
    assert res.metrics["target_gap_change_mm"] * 1e-3 == pytest.approx(want, rel=1e-12)
    assert res.metrics["target_given"] is False
    new = validate_config(synthesized_raw_config(raw, res.updates, "gap_change"))
    summary = evaluate(new).summary
    assert abs(abs(summary["gap_change_min_mm"]) * 1e-3 - want) <= 1e-9 * want
    assert abs(summary["gap_change_min_mm"]) < abs(evaluate(cfg).summary["gap_change_min_mm"])
    assert new["drive"]["eccentricity"] == pytest.approx(0.04, rel=1e-14)


def test_default_target_of_a_flat_follower_is_zero():
    cfg, raw, _ = load_config(None, "eccentric-reactor", ["drive.follower=flat"])
    res = synthesize(cfg, raw, "gap_change")
    assert res.metrics["target_gap_change_mm"] == 0.0
    assert res.updates["drive"]["follower"] == "flat"
