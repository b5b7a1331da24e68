"""Tolerance analysis: a seeded run reproduces a Monte-Carlo computed here from the paper."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from rotorkin.cli import main
from rotorkin.core.errors import ConfigError
from rotorkin.io.config import load_config
from rotorkin.tolerance import run_tolerance, summarize


def _independent(seed, n, w_tilt, s_alpha, eps=10.0):
    """Chen Hu et al.'s eq. 17 and eq. 21 with numpy's sampling, pistons of the nominal width."""
    rng = np.random.default_rng(seed)
    phi = np.radians(45.0) + rng.uniform(-w_tilt, w_tilt, size=n)
    alpha = np.radians(90.0) + rng.normal(0.0, s_alpha, size=n)
    amax = 2.0 * np.arctan(np.tan(alpha / 2.0) / np.cos(phi))  # eq. 17
    amin = 2.0 * np.arctan(np.cos(phi) * np.tan(alpha / 2.0))
    amin0 = 2.0 * np.arctan(np.cos(np.radians(45.0)))
    beta = (eps + 1) / (eps - 1) * amin0 - np.pi * (eps + 3) / (4 * (eps - 1))  # eq. 21, N = 4
    a = (amin - np.pi / 4 - beta, amax - np.pi / 4 - beta)  # eq. 19, gamma = 22.5 deg
    b = (3 * np.pi / 4 - amax - beta, 3 * np.pi / 4 - amin - beta)  # eq. 18
    ratio_a, ratio_b = a[1] / a[0], b[1] / b[0]
    tighter = np.where(a[0] <= b[0], ratio_a, ratio_b)
    return {"compression_ratio": tighter, "compression_ratio_a": ratio_a,
            "compression_ratio_b": ratio_b, "chamber_swing_deg": np.degrees(amax - amin),
            "piston_width_deg": np.full(n, np.degrees(beta))}  # fmt: skip


def test_seeded_run_reproduces_an_independent_monte_carlo():
    _, raw, _ = load_config(None, "wobble-cam-engine")
    ds = run_tolerance(raw, ["drive.plate_tilt=0.1deg", "drive.roller_axis_angle=0.2deg:normal"],
                       samples=3000, seed=7, angles=721)  # fmt: skip
    ref = _independent(7, 3000, np.radians(0.1), np.radians(0.2))
    stats = summarize(ds)
    assert np.all(ds["reason"].values == 0)
    for m, values in ref.items():
        np.testing.assert_allclose(ds[m].values, values, rtol=1e-11)
        s = stats[m]
        assert s["mean"] == pytest.approx(np.mean(values), rel=1e-11)
        assert s["std"] == pytest.approx(np.std(values, ddof=1), rel=1e-8, abs=1e-12)
        for q in (1, 5, 50, 95, 99):
            assert s[f"p{q}"] == pytest.approx(np.percentile(values, q), rel=1e-11)
    # the tolerances open a spread of the real compression ratio around the design's 10
    assert stats["compression_ratio"]["nominal"] == pytest.approx(10.0, rel=1e-12)
    assert stats["compression_ratio_a"]["p95"] - stats["compression_ratio_a"]["p5"] > 0.5
    assert stats["piston_width_deg"]["std"] == 0.0  # the pistons are as manufactured


def test_the_sampled_keys_follow_the_documented_draws():
    _, raw, _ = load_config(None, "eccentric-reactor")
    ds = run_tolerance(raw, ["drive.eccentricity=0.05mm:normal", "machine.device_length=1mm"],
                       samples=200, seed=11, angles=361)  # fmt: skip
    rng = np.random.default_rng(11)
    e = 40.0 + 1e3 * rng.normal(0.0, 5e-5, size=200)
    length = 1000.0 + 1e3 * rng.uniform(-1e-3, 1e-3, size=200)
    np.testing.assert_allclose(ds["drive.eccentricity"].values, e, rtol=1e-13)
    np.testing.assert_allclose(ds["machine.device_length"].values, length, rtol=1e-13)
    # eq. 5 at 90 deg with R = 80 mm: Delta = 2 (sqrt(R^2 - e^2) - R)
    np.testing.assert_allclose(ds["gap_change_min_mm"].values,
                               2 * (np.sqrt(80.0**2 - e**2) - 80.0), rtol=1e-10)  # fmt: skip


def test_inadmissible_samples_are_counted_and_left_out():
    _, raw, _ = load_config(None, "wobble-cam-engine")
    ds = run_tolerance(raw, ["drive.plate_tilt=25deg"], samples=400, seed=2, angles=361)
    bad = ds["reason"].values != 0
    assert 0 < bad.sum() < 400
    assert np.all(np.isnan(ds["chamber_swing_deg"].values[bad]))
    s = summarize(ds)["chamber_swing_deg"]
    assert s["admissible"] == 400 - bad.sum() and s["inadmissible"] == bad.sum()
    assert s["max"] == pytest.approx(np.nanmax(ds["chamber_swing_deg"].values))


def test_the_guide_bar_pump_keeps_its_vane_angle():
    # one vane per impeller leaves room: the nominal gamma_0 vane fits every sampled lambda
    _, raw, _ = load_config(None, "guide-bar-pump", ["machine.vanes_per_impeller=1"])
    ds = run_tolerance(raw, ["drive.lambda=0.002"], samples=300, seed=5, angles=361)
    assert np.all(ds["reason"].values == 0)
    assert np.ptp(ds["pump_vane_angle_deg"].values) == 0.0
    assert np.ptp(ds["vane_angle_deg"].values) > 0.01


@pytest.mark.parametrize(
    ("tol", "words"),
    [
        ("drive.plate_tilt=0.1", "has no unit"),
        ("drive.plate_tilt=0.1deg:cauchy", "uniform (default) or normal"),
        ("drive.plate_tilt=-0.1deg", "must be > 0"),
        ("drive.bogus=1", "unknown key drive.bogus"),
        ("machine.section=1", "not a continuous quantity"),
        ("drive.plate_tilt", "KEY=START:STOP:N"),
    ],
)
def test_bad_tolerances_exit_2_with_one_line(tol, words, tmp_path, capsys):
    out = tmp_path / "tol"
    assert main(["tolerance", "--tol", tol, "--samples", "10", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1
    assert not out.exists()


def test_no_tolerance_is_refused():
    _, raw, _ = load_config(None, "wobble-cam-engine")
    with pytest.raises(ConfigError, match="at least one --tol"):
        run_tolerance(raw, [])


@pytest.mark.slow
def test_cli_writes_json_netcdf_and_histograms(tmp_path, capsys):
    out = tmp_path / "tol"
    args = [
        "tolerance",
        "-e",
        "wobble-cam-engine",
        "--tol",
        "drive.plate_tilt=0.1deg",
        "--tol",
        "drive.roller_axis_angle=0.1deg:normal",
        "--samples",
        "600",
        "--seed",
        "3",
        "--angles",
        "361",
        "--out",
        str(out),
    ]
    assert main(args) == 0
    assert "compression_ratio" in capsys.readouterr().out
    assert sorted(p.name for p in out.iterdir() if not p.name.startswith(".")) == [
        "README.txt",
        "tolerance.json",
        "tolerance.nc",
        "tolerance_histograms.png",
    ]
    doc = json.loads((out / "tolerance.json").read_text())
    assert doc["seed"] == 3 and doc["samples"] == 600
    with xr.open_dataset(out / "tolerance.nc", engine="scipy") as ds:
        values = ds["compression_ratio"].values
    assert doc["metrics"]["compression_ratio"]["p99"] == pytest.approx(np.percentile(values, 99))
    png = out / "tolerance_histograms.png"
    assert png.stat().st_size > 30_000 and png.read_bytes()[:4] == b"\x89PNG"
