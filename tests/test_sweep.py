"""Sweeps: every design equals the scalar study run on its own; reasons; CLI; paper figures."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from rotorkin.cli import main
from rotorkin.core.errors import ConfigError, ParameterError, RotorkinError
from rotorkin.drives import evaluate
from rotorkin.io.config import load_config
from rotorkin.sweep import SweepFallbackWarning, reason_text, run_sweep
from rotorkin.sweep.checks import is_check, metric_name

# Each case: example, base --set items, --vary items (lists, so that the test can rebuild every
# design from the same strings), some combinations inadmissible on purpose.
CASES = {
    "wobble-cam-engine": (
        [],
        ["drive.plate_tilt=25deg,40deg,55deg", "drive.roller_axis_angle=70deg,90deg,110deg",
         "machine.compression_ratio=4,12", "machine.section=rectangular,circular"],
    ),
    "eccentric-reactor": (
        ["drive.roller_radius=3 mm"],
        ["drive.eccentricity=10mm,40mm,70mm", "drive.follower=knife_edge,flat,roller",
         "machine.fluid=gas,liquid"],
    ),
    "guide-bar-pump": (
        [],
        ["drive.lambda=0.2,0.5,0.8", "drive.driver=crank,guide", "drive.input_gear_ratio=1,2",
         "machine.vane_angle=40deg,50deg"],
    ),
    "rhomboid-engine": (
        [],
        ["drive.psi_min=20deg,45deg,80deg", "machine.blade_thickness=5deg,30deg",
         "machine.blades_per_pair=1,2"],
    ),
}  # fmt: skip


def _designs(varies):
    """Every combination of the --vary lists, as (index tuple, --set items), C order."""
    keys = [v.split("=")[0] for v in varies]
    values = [v.split("=")[1].split(",") for v in varies]
    for idx in np.ndindex(*(len(v) for v in values)):
        yield idx, [f"{k}={vals[i]}" for k, vals, i in zip(keys, values, idx, strict=True)]


def _visible(folder):
    """Names of the files people read (not the hidden manifest of the staged output)."""
    return sorted(p.name for p in folder.iterdir() if not p.name.startswith("."))


def _close(a, b, scale):
    return a == b or (np.isnan(a) and np.isnan(b)) or abs(a - b) <= 1e-12 * max(abs(b), scale)


@pytest.mark.slow
@pytest.mark.parametrize("example", sorted(CASES))
def test_sweep_equals_the_designs_run_one_by_one(example):
    sets, varies = CASES[example]
    _, raw, _ = load_config(None, example, sets)
    ds = run_sweep(raw, varies, keep_curves=True, progress=False)
    flags = ("reason", "violations")  # per-design codes, not metrics
    metrics = [k for k, v in ds.data_vars.items() if "point" not in v.dims and k not in flags]
    curves = [k for k, v in ds.data_vars.items() if "point" in v.dims]
    assert len(metrics) >= 25 and len(curves) >= 8
    seen_bad = seen_ok = 0
    for idx, items in _designs(varies):
        d = ds.isel(dict(zip([v.split("=")[0] for v in varies], idx, strict=True)))
        cfg = load_config(None, example, sets + items)[0]
        try:
            res = evaluate(cfg)
        except ParameterError as exc:  # inadmissible: NaN and the key the study names
            seen_bad += 1
            assert reason_text(ds, int(d["reason"])) == exc.name
            assert all(np.isnan(float(d[m])) for m in metrics)
            continue
        seen_ok += 1
        assert int(d["reason"]) == 0
        # the checks run prints, by the name the sweep gives their margins
        margins = {metric_name(c.name, c.unit): c.margin for c in res.checks}
        for m in metrics:
            scale = max(np.nanmax(np.abs(ds[m].values)), 1e-300)
            expect = margins[m] if is_check(m) else float(res.summary[m])
            assert _close(float(d[m]), expect, scale), (m, items)
        for c in curves:
            expect = res.columns[c]
            assert np.allclose(d[c].values, expect, rtol=1e-12, atol=1e-12 * np.abs(expect).max())
    assert seen_ok >= 10
    if example != "eccentric-reactor":
        assert seen_bad >= 1  # combinations that the study refuses are marked, not fatal


def test_slider_angle_extremes_against_eq15_by_brute_force():
    # independent: the paper's eq. 15 (arccos form) maximised over the spin angle numerically
    _, raw, _ = load_config(None, "wobble-cam-engine",
                            ["machine.compression_ratio=1e6", "loads.model=ideal"])  # fmt: skip
    ds = run_sweep(
        raw,
        {
            "drive.plate_tilt": "10deg,30deg,50deg,57deg",
            "drive.roller_axis_angle": "75deg,90deg,105deg",
        },
        progress=False,
    )
    v = np.linspace(0.0, np.pi, 200_001)
    for tilt in (10.0, 30.0, 50.0, 57.0):
        for alpha in (75.0, 90.0, 105.0):
            p, a = np.radians(tilt), np.radians(alpha)
            c2 = np.cos(p) ** 2
            s1, s2 = np.sin(v - a / 2), np.sin(v + a / 2)
            k1, k2 = np.cos(v - a / 2), np.cos(v + a / 2)
            num = s1 * s2 + c2 * k1 * k2
            den = np.sqrt((s1**2 + c2 * k1**2) * (s2**2 + c2 * k2**2))
            ang = np.degrees(np.arccos(np.clip(num / den, -1, 1)))
            d = ds.sel({"drive.plate_tilt": tilt, "drive.roller_axis_angle": alpha})
            assert float(d["slider_angle_max_deg"]) == pytest.approx(ang.max(), abs=1e-6)
            assert float(d["slider_angle_min_deg"]) == pytest.approx(ang.min(), abs=1e-6)


def test_results_do_not_depend_on_chunks_or_threads():
    _, raw, _ = load_config(None, "wobble-cam-engine")
    vary = {"drive.plate_tilt": "30deg:50deg:7", "drive.roller_axis_angle": "80deg:100deg:5"}
    a = run_sweep(raw, vary, progress=False, samples=2001)
    b = run_sweep(raw, vary, progress=False, samples=2001, chunk_size=3, threads=1)
    xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())


def test_samples_set_the_sampled_peaks_only():
    _, raw, _ = load_config(None, "wobble-cam-engine")
    vary = {"drive.plate_tilt": "30deg,45deg"}
    fine = run_sweep(raw, vary, progress=False)
    coarse = run_sweep(raw, vary, progress=False, samples=360)
    assert np.array_equal(fine["chamber_swing_deg"], coarse["chamber_swing_deg"])
    # a coarse grid misses the peak by O(h^2): close, not equal
    np.testing.assert_allclose(coarse["rotor_accel_peak_per_rad"],
                               fine["rotor_accel_peak_per_rad"], rtol=2e-3)  # fmt: skip


def test_a_key_outside_the_kernels_falls_back_to_the_scalar_study_with_one_warning():
    _, raw, _ = load_config(None, "wobble-cam-engine")
    with pytest.warns(SweepFallbackWarning, match="design by design"):
        ds = run_sweep(
            raw,
            {"machine.inertia_rotor_1": "0.004 kg*m^2,0.02 kg*m^2"},
            metrics=["chamber_swing_deg", "flywheel_inertia_kgm2"],
            progress=False,
        )
    for i, j in enumerate(("0.004 kg*m^2", "0.02 kg*m^2")):
        s = evaluate(load_config(None, "wobble-cam-engine", [f"machine.inertia_rotor_1={j}"])[0])
        assert float(ds["flywheel_inertia_kgm2"][i]) == s.summary["flywheel_inertia_kgm2"]
        assert float(ds["chamber_swing_deg"][i]) == s.summary["chamber_swing_deg"]


@pytest.mark.parametrize(
    ("vary", "words"),
    [
        (["drive.bogus=1,2"], "unknown key drive.bogus"),
        (["drive.plate_tilt=20deg:60deg:0"], "empty range"),
        (["drive.plate_tilt="], "empty list"),
        (["drive.plate_tilt=20:60:5"], "has no unit"),
        (["drive.plate_tilt=20deg:70deg:6"], "crosses an admissible limit"),
        (["machine.compression_ratio=2,10"], "crosses an admissible limit"),
        (["drive.spin_a=1,2"], "only single numbers"),
        (["drive.plate_tilt=30deg", "drive.plate_tilt=40deg"], "given twice"),
        (["machine.section=round"], "machine.section"),
    ],
)
def test_bad_specs_raise_one_line(vary, words):
    _, raw, _ = load_config(None, "wobble-cam-engine")
    with pytest.raises((ConfigError, RotorkinError), match=words) as info:
        run_sweep(raw, vary, progress=False)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("bad", ["95 deg", "-5 deg", "0.1 deg"])
@pytest.mark.parametrize("where", [0, 3, 7])
def test_a_list_names_its_value_outside_the_schema_wherever_it_stands(bad, where):
    # outside the schema's bounds, first, inside or last: refused in the schema's words
    from rotorkin.sweep.spec import parse_vary

    _, raw, _ = load_config(None, "wobble-cam-engine")
    items = [f"{20 + 3 * i} deg" for i in range(8)]
    items[where] = bad
    with pytest.raises(ConfigError, match=f"plate_tilt = {bad} is not admissible") as info:
        parse_vary("drive.plate_tilt=" + ",".join(items), raw)
    assert "\n" not in str(info.value)


def test_a_long_list_is_parsed_as_its_values_one_by_one():
    from rotorkin.sweep.spec import parse_vary

    _, raw, _ = load_config(None, "wobble-cam-engine")
    items = [f"{10 + 0.5 * i:.1f} deg" for i in range(100)] + ["0.9 rad", "0.5 deg"]
    got = parse_vary("drive.plate_tilt=" + ",".join(items), raw).values
    each = [load_config(None, "wobble-cam-engine", [f"drive.plate_tilt={t}"])[0]["drive"]
            ["plate_tilt"] for t in items]  # fmt: skip
    assert got == tuple(each)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--vary", "drive.bogus=1,2"], "unknown key drive.bogus"),
        (["--vary", "drive.plate_tilt=20deg:60deg:0"], "empty range"),
        (["--vary", "drive.plate_tilt=20:60:5"], "has no unit"),
        (["--vary", "drive.plate_tilt=20deg:70deg:6"], "crosses an admissible limit"),
        (["--vary", "drive.plate_tilt"], "KEY=START:STOP:N"),
        ([], "give at least one --vary"),
        (
            ["--vary", "drive.plate_tilt=30deg", "--workers", "2", "--scheduler", "tcp://x:1"],
            "not both",
        ),
        (["-e", "rhomboid-engine", "--paper-figures"], "no sweep figures"),
    ],
)
def test_cli_bad_specs_exit_2_with_one_line_and_write_nothing(args, words, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["sweep", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1 and "Traceback" not in err
    assert not out.exists() and not list(tmp_path.iterdir())


def _cli_sweep(tmp_path, name, *varies):
    out = tmp_path / name
    args = ["sweep", "-e", "wobble-cam-engine", "--angles", "2001", "--out", str(out), "-q"]
    for item in varies:
        args += ["--vary", item]
    assert main(args) == 0
    return xr.open_dataset(out / "sweep.nc", engine="scipy").load()


@pytest.mark.slow
@pytest.mark.parametrize(
    "varies",
    [
        ["drive.plate_tilt=20deg:65deg:46"],  # the issue's example
        ["drive.plate_tilt=20deg:65deg:46", "machine.compression_ratio=14,20"],
    ],
)
def test_cli_issue_example_marks_combinations_nan_with_a_reason(varies, tmp_path):
    """Tilts at which the compression ratio needs a negative piston width are NaN, not fatal."""
    ds = _cli_sweep(tmp_path, "sw", *varies)
    tilt = ds["drive.plate_tilt"].values
    assert np.allclose(tilt, np.arange(20.0, 66.0))
    metrics = [k for k, v in ds.data_vars.items() if k not in ("reason", "violations")]
    eps_values = ds["machine.compression_ratio"].values if len(varies) > 1 else [None]
    n_bad = n_ok = 0
    for i, t in enumerate(tilt):
        for j, eps in enumerate(eps_values):
            d = ds.isel(
                {"drive.plate_tilt": i, **({} if eps is None else {"machine.compression_ratio": j})}
            )
            items = [f"drive.plate_tilt={t:g}deg"]
            if eps is not None:
                items.append(f"machine.compression_ratio={eps:g}")
            cfg = load_config(None, "wobble-cam-engine", items)[0]
            try:
                res = evaluate(cfg)
            except ParameterError as exc:
                n_bad += 1
                assert reason_text(ds, int(d["reason"])) == exc.name == "machine.compression_ratio"
                assert all(np.isnan(float(d[m])) for m in metrics)
                continue
            n_ok += 1
            assert int(d["reason"]) == 0
            for m in ("chamber_swing_deg", "piston_width_deg", "slider_angle_max_deg",
                      "compression_ratio_geometric", "peak_pressure_bar", "indicated_work_J",
                      "max_plate_tilt_deg"):  # fmt: skip
                assert float(d[m]) == pytest.approx(res.summary[m], rel=1e-12, abs=1e-12), m
            # the sampled peaks on the sweep's 2001 angles vs the study's 20001: O(h^2)
            assert float(d["rotor_accel_peak_per_rad"]) == pytest.approx(
                res.summary["rotor_accel_peak_per_rad"], rel=2e-4
            )
    # eps = 10 is admissible up to 59 deg (eq. 21: 10.07 at 60 deg); eps = 14 and 20 further
    if len(varies) == 1:
        assert (n_ok, n_bad) == (40, 6)
        assert np.all(ds["reason"].values[:40] == 0) and np.all(ds["reason"].values[40:] > 0)
    else:
        assert n_ok >= 80 and n_bad >= 1 and n_ok + n_bad == 92


def test_a_value_past_its_own_limit_at_every_swept_partner_is_refused(tmp_path, capsys):
    # 70 deg is past eq. 20 (65.53 deg at most, at 90 deg) for every roller axis angle swept
    out = tmp_path / "no"
    args = ["sweep", "-e", "wobble-cam-engine", "--vary", "drive.plate_tilt=50deg,62deg,70deg",
            "--vary", "drive.roller_axis_angle=80deg,90deg", "--vary",
            "machine.compression_ratio=30", "--out", str(out)]  # fmt: skip
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "at 70 deg crosses an admissible limit" in err
    assert "drive.plate_tilt = 70 deg" in err and not out.exists()
    # without 70 deg: 62 deg is past eq. 20 at 80 deg only (60.42 deg) -> NaN there, not fatal
    ds = _cli_sweep(
        tmp_path,
        "ok",
        "drive.plate_tilt=50deg,62deg",
        "drive.roller_axis_angle=80deg,90deg",
        "machine.compression_ratio=30",
    )
    reason = ds["reason"].values[:, :, 0]
    assert reason_text(ds, reason[1, 0]) == "drive.plate_tilt"
    assert reason[0, 0] == reason[0, 1] == reason[1, 1] == 0
    assert np.isnan(float(ds["chamber_swing_deg"][1, 0, 0]))


def test_cli_writes_sweep_nc_readable_by_another_netcdf_reader(tmp_path, capsys):
    from scipy.io import netcdf_file

    out = tmp_path / "sw"
    args = [
        "sweep",
        "-e",
        "wobble-cam-engine",
        "--vary",
        "drive.plate_tilt=30deg:57deg:7",
        "--vary",
        "drive.roller_axis_angle=80deg,100deg",
        "--angles",
        "721",
        "--out",
        str(out),
    ]
    assert main(args) == 0
    printed = capsys.readouterr().out
    assert "sweep.nc" in printed and "14 designs" in printed
    assert _visible(out) == ["README.txt", "sweep.nc", "sweep_overview.png"]
    with netcdf_file(out / "sweep.nc", "r", mmap=False) as f:
        swing = np.array(f.variables["chamber_swing_deg"][:])
        tilt = np.array(f.variables["drive.plate_tilt"][:])
        alpha = np.array(f.variables["drive.roller_axis_angle"][:])
        reason = np.array(f.variables["reason"][:])
    assert swing.shape == (7, 2) and np.allclose(tilt, np.linspace(30, 57, 7))
    c = np.cos(np.radians(tilt))[:, None]
    t = np.tan(np.radians(alpha) / 2)[None, :]
    expect = np.degrees(2 * np.arctan(t / c) - 2 * np.arctan(c * t))  # eq. 17
    ok = reason == 0
    assert np.allclose(swing[ok], expect[ok], rtol=1e-12) and np.all(np.isnan(swing[~ok]))
    assert ok.sum() >= 10 and (~ok).sum() >= 1  # 57 deg at 100 deg: eq. 21 needs eps > 16.9


def test_paper_figures_of_the_guide_bar_match_eq5_eq6(tmp_path, capsys):
    out = tmp_path / "pf"
    assert main(["sweep", "-e", "guide-bar-pump", "--paper-figures", "--out", str(out), "-q"]) == 0
    names = _visible(out)
    assert names == ["paper_fig10.png", "paper_fig10_11.nc", "paper_fig11.png", "paper_fig9.nc",
                     "paper_fig9.png"]  # fmt: skip
    for png in out.glob("*.png"):
        assert png.stat().st_size > 20_000 and png.read_bytes()[:4] == b"\x89PNG"
    ds = xr.open_dataset(out / "paper_fig9.nc", engine="scipy").load()
    lam = ds["drive.lambda"].values
    for u in (2.0, 3.0):
        crank = ds["vane_angle_deg"].sel({"drive.gear_ratio": u, "drive.driver": "crank"})
        guide = ds["vane_angle_deg"].sel({"drive.gear_ratio": u, "drive.driver": "guide"})
        # eq. 5: arccos(lambda / sqrt(1 + lambda^2)) = u gamma_0 / 2; eq. 6: arccos(lambda) = ...
        assert np.allclose(crank, np.degrees(2 * np.arccos(lam / np.sqrt(1 + lam**2)) / u))
        assert np.allclose(guide, np.degrees(2 * np.arccos(lam) / u))
    # Fig. 10/11 (docs/sweeps.md): M7 = M8 = 10 N*m, Sigma = 180 deg, u = i12 = 2: guide-driven
    # M1 = 2 M/(u i12) = 5 N*m exactly at every lambda (flat, unlike the paper's plot);
    # crank-driven it fluctuates
    ds = xr.open_dataset(out / "paper_fig10_11.nc", engine="scipy").load()
    torque = ds["input_torque_Nm"]
    guide = torque.sel({"drive.driver": "guide"}).values
    crank = torque.sel({"drive.driver": "crank"}).values
    assert guide.shape[0] >= 3 and np.all(np.isfinite(guide))
    assert np.allclose(guide, 5.0, rtol=0, atol=1e-12)
    assert np.all(np.ptp(crank, axis=-1) > 0.1)


def test_paper_figures_of_the_eccentric_cams_hold_the_published_delta(tmp_path):
    out = tmp_path / "pf"
    assert main(["sweep", "-e", "eccentric-reactor", "--paper-figures", "--out", str(out),
                 "-q"]) == 0  # fmt: skip
    ds = xr.open_dataset(out / "paper_fig6_7.nc", engine="scipy").load()
    d = ds.sel({"drive.eccentricity": 40.0})  # lambda = 0.5 on R = 80 mm
    i = int(np.argmin(np.abs(ds["beta_deg"].values - 90.0)))
    assert float(d["delta"][i]) == pytest.approx(-0.5359, abs=1e-4)  # the paper's number
    assert (out / "paper_fig6.png").stat().st_size > 20_000
    assert (out / "paper_fig7.png").stat().st_size > 20_000


def test_paper_figures_of_the_wobble_cam_hold_the_published_numbers(tmp_path):
    out = tmp_path / "pf"
    assert main(["sweep", "-e", "wobble-cam-engine", "--paper-figures", "--out", str(out),
                 "-q"]) == 0  # fmt: skip
    assert _visible(out) == ["paper_fig11.nc", "paper_fig11.png", "paper_fig12.nc",
                             "paper_fig12.png", "paper_fig13.nc", "paper_fig13.png"]  # fmt: skip
    for png in out.glob("*.png"):
        assert png.stat().st_size > 20_000 and png.read_bytes()[:4] == b"\x89PNG"

    # Fig. 13 (alpha = 90 deg): alpha'_max reaches 135 deg and alpha'_min 45 deg at the eq. 20
    # limit, 65.53 deg; the sweep stops 0.05 deg short of it, so extrapolate its last points
    ds = xr.open_dataset(out / "paper_fig13.nc", engine="scipy").load()
    tilt = ds["drive.plate_tilt"].values
    amax, amin = ds["slider_angle_max_deg"].values, ds["slider_angle_min_deg"].values
    assert np.all(ds["reason"].values == 0) and tilt[0] == 0.5
    assert tilt[-1] == pytest.approx(65.53 - 0.05, abs=5e-3)
    fit_max = np.polynomial.Polynomial.fit(tilt[-4:], amax[-4:], 2)
    fit_min = np.polynomial.Polynomial.fit(tilt[-4:], amin[-4:], 2)
    assert fit_max(65.53) == pytest.approx(135.0, abs=0.02)
    assert fit_min(65.53) == pytest.approx(45.0, abs=0.02)
    assert 134.5 < amax[-1] < 135.0 and 45.0 < amin[-1] < 45.5
    # with growing phi, alpha'_max rises and alpha'_min falls, faster and faster
    assert np.all(np.diff(amax) > 0) and np.all(np.diff(amin) < 0)
    assert np.all(np.diff(amax, 2) > 0) and np.all(np.diff(amin, 2) < 0)

    # Fig. 12 (phi = 45 deg): Table 1's 109.47 / 70.53 deg at alpha = 90 deg, where the swing
    # (38.94 deg) is largest; alpha'_max and alpha'_min both rise with alpha
    ds = xr.open_dataset(out / "paper_fig12.nc", engine="scipy").load()
    alpha = ds["drive.roller_axis_angle"].values
    mid = int(np.argmax(ds["chamber_swing_deg"].values))
    assert alpha[mid] == pytest.approx(90.0, abs=1e-9)
    d = ds.isel({"drive.roller_axis_angle": mid})
    assert float(d["slider_angle_max_deg"]) == pytest.approx(109.47, abs=5e-3)
    assert float(d["slider_angle_min_deg"]) == pytest.approx(70.53, abs=5e-3)
    assert float(d["chamber_swing_deg"]) == pytest.approx(38.94, abs=5e-3)
    assert np.all(np.diff(ds["slider_angle_max_deg"].values) > 0)
    assert np.all(np.diff(ds["slider_angle_min_deg"].values) > 0)

    # Fig. 11: at alpha = 90 deg the neighbouring chambers A and B follow the same law (same
    # extremes); at alpha != 90 deg they differ
    ds = xr.open_dataset(out / "paper_fig11.nc", engine="scipy").load()
    assert ds.sizes["point"] == 721 and np.allclose(ds["theta_deg"].values[[0, -1]], [0, 360])
    for i, a in enumerate(ds["drive.roller_axis_angle"].values):
        d = ds.isel({"drive.roller_axis_angle": i})
        ca, cb = d["chamber_a_angle_deg"].values, d["chamber_b_angle_deg"].values
        gap = abs(ca.min() - cb.min())
        assert gap < 1e-9 if a == 90.0 else gap > 1.0, (a, gap)
        # the curve's extremes on 721 angles are the closed form's to the sampling error
        s = d["slider_angle_deg"].values
        assert s.max() == pytest.approx(float(d["slider_angle_max_deg"]), abs=1e-3)
        assert s.min() == pytest.approx(float(d["slider_angle_min_deg"]), abs=1e-3)


# the kernel's opt-in metrics: every curve evaluated per design and angle, reduced
_SAMPLED_OF = {
    "sampled_slider_angle_min_deg": ("slider_angle_min_deg", "slider_angle_deg", min),
    "sampled_slider_angle_max_deg": ("slider_angle_max_deg", "slider_angle_deg", max),
    "sampled_chamber_a_angle_min_deg": ("chamber_a_angle_min_deg", "chamber_a_angle_deg", min),
    "sampled_chamber_a_angle_max_deg": ("chamber_a_angle_max_deg", "chamber_a_angle_deg", max),
    "sampled_chamber_b_angle_min_deg": ("chamber_b_angle_min_deg", "chamber_b_angle_deg", min),
    "sampled_chamber_b_angle_max_deg": ("chamber_b_angle_max_deg", "chamber_b_angle_deg", max),
    "sampled_chamber_a_volume_min_cm3": ("chamber_a_volume_min_cm3", "chamber_a_volume_cm3", min),
    "sampled_chamber_a_volume_max_cm3": ("chamber_a_volume_max_cm3", "chamber_a_volume_cm3", max),
    "sampled_chamber_b_volume_min_cm3": ("chamber_b_volume_min_cm3", "chamber_b_volume_cm3", min),
    "sampled_chamber_b_volume_max_cm3": ("chamber_b_volume_max_cm3", "chamber_b_volume_cm3", max),
    "sampled_rotor_speed_ratio_min": ("rotor_speed_ratio_min", "rotor{}_speed_ratio", min),
    "sampled_rotor_speed_ratio_max": ("rotor_speed_ratio_max", "rotor{}_speed_ratio", max),
}  # fmt: skip
_SAMPLED_VARY = {
    "drive.plate_tilt": "25deg:57deg:5",
    "drive.roller_axis_angle": "80deg,90deg,104deg",
    "machine.compression_ratio": "12,30",
    "machine.clearance_volume": "0cm^3,2cm^3",
}


def test_sampled_extremes_of_every_curve_agree_with_the_closed_forms_to_the_sampling_error():
    from rotorkin.drives.wobble_cam.sweep import SAMPLED_METRICS

    assert set(SAMPLED_METRICS) == set(_SAMPLED_OF)
    _, raw, _ = load_config(None, "wobble-cam-engine")
    closed = [v[0] for v in _SAMPLED_OF.values()]
    peaks = ["rotor_accel_peak_per_rad", "rotor_jerk_peak_per_rad2"]
    ds = run_sweep(raw, _SAMPLED_VARY, metrics=[*SAMPLED_METRICS, *closed, *peaks], samples=360,
                   progress=False)  # fmt: skip
    default = run_sweep(raw, _SAMPLED_VARY, samples=360, progress=False)
    ok = ds["reason"].values == 0
    assert 20 <= ok.sum() < ok.size
    h = 2 * np.pi / 359  # grid step [rad]
    missed = {}
    for name, (ref, _, pick) in _SAMPLED_OF.items():
        s, c = ds[name].values, ds[ref].values
        assert np.all(np.isnan(s[~ok])) and np.all(np.isfinite(s[ok]))
        # sampled extremes never pass the true ones, and miss them by O(f'' h^2 / 8)
        inner = (s - c) if pick is min else (c - s)
        scale = np.abs(c[ok]).max()
        assert np.all(inner[ok] >= -1e-12 * scale), name
        assert np.all(inner[ok] <= h * h * scale), name
        missed[name] = inner[ok].max() / scale
    # the slider's largest angle is at theta = 0, a grid point (exact); its smallest is not:
    # really sampled, not the closed form copied
    assert missed["sampled_slider_angle_max_deg"] < 1e-14
    assert 1e-7 < missed["sampled_slider_angle_min_deg"] < 1e-4
    assert 1e-7 < missed["sampled_rotor_speed_ratio_max"] < 1e-4
    # the peaks come out of the same pass bit for bit as without the curves
    for m in peaks:
        np.testing.assert_array_equal(ds[m].values, default[m].values)


def test_sampled_extremes_equal_the_study_columns_on_the_same_grid():
    from rotorkin.drives.wobble_cam.sweep import SAMPLED_METRICS

    _, raw, _ = load_config(None, "wobble-cam-engine")
    points = int(load_config(None, "wobble-cam-engine")[0]["run"]["points"])
    ds = run_sweep(raw, _SAMPLED_VARY, metrics=list(SAMPLED_METRICS), samples=points,
                   progress=False)  # fmt: skip
    checked = 0
    for idx, items in _designs([f"{k}={v}" for k, v in {
            "drive.plate_tilt": "25deg,33deg,41deg,49deg,57deg",
            "drive.roller_axis_angle": "80deg,90deg,104deg",
            "machine.compression_ratio": "12,30",
            "machine.clearance_volume": "0cm^3,2cm^3"}.items()]):  # fmt: skip
        d = ds.isel(dict(zip(_SAMPLED_VARY, idx, strict=True)))
        try:
            res = evaluate(load_config(None, "wobble-cam-engine", items)[0])
        except ParameterError:
            assert int(d["reason"]) != 0
            continue
        checked += 1
        for name, (_, column, pick) in _SAMPLED_OF.items():
            cols = [res.columns[column.format(k)] for k in (1, 2)] if "{}" in column else \
                [res.columns[column]]  # fmt: skip
            expect = pick(float(pick(c)) for c in cols)
            assert float(d[name]) == pytest.approx(expect, rel=1e-12, abs=1e-12), (name, items)
    assert checked >= 30


def test_sampled_extremes_of_a_corrected_spin_law_take_the_library_path():
    from rotorkin.drives.wobble_cam import kinematics as wc
    from rotorkin.drives.wobble_cam.sweep import SAMPLED_METRICS

    sets = [
        "drive.spin_a=[0.05]",
        "drive.spin_b=[0.02]",
        "machine.compression_ratio=30",
        "loads.model=ideal",
    ]  # the kinematics alone, in the batch kernel
    try:
        _, raw, _ = load_config(None, "wobble-cam-engine", sets)
    except ConfigError:
        pytest.skip("spin_a/spin_b not settable with --set")
    ds = run_sweep(raw, {"drive.plate_tilt": "30deg,45deg"}, samples=361,
                   metrics=[*SAMPLED_METRICS, "rotor_speed_ratio_min"], progress=False)  # fmt: skip
    for i, tilt in enumerate((30.0, 45.0)):
        cfg = load_config(None, "wobble-cam-engine", [*sets, f"drive.plate_tilt={tilt}deg"])[0]
        d = cfg["drive"]
        params = wc.WobbleCam(d["plate_tilt"], d["roller_axis_angle"], d["spin_ratio"],
                              d["sphere_radius"], 4, tuple(d["spin_a"]),
                              tuple(d["spin_b"]))  # fmt: skip
        theta = np.linspace(0, 2 * np.pi, 361)
        q, d1, _, _ = wc.rotor_angles(params, theta)
        s = np.degrees(q[1] - q[0])
        assert float(ds["sampled_slider_angle_max_deg"][i]) == pytest.approx(s.max(), rel=1e-12)
        assert float(ds["sampled_slider_angle_min_deg"][i]) == pytest.approx(s.min(), rel=1e-12)
        assert float(ds["sampled_rotor_speed_ratio_min"][i]) == d1.min()
        assert float(ds["rotor_speed_ratio_min"][i]) == d1.min()


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--vary", "drive.plate_tilt=20deg:65deg:10000000000000"],
         "N = 10000000000000; N <= 1e+06"),
        (["--vary", "drive.plate_tilt=20deg:65deg:20000", "--vary",
          "drive.roller_axis_angle=80deg:100deg:10000"], "2e+08 designs is not admissible"),
        (["--vary", "drive.plate_tilt=20deg:65deg:1000", "--vary",
          "drive.roller_axis_angle=80deg:100deg:200", "--curves"], "would take 11.9 GiB"),
        (["--vary", "drive.type=a,b"], "drive.type = 'a' is not admissible"),
        (["--vary", "drive.type=eccentric_cam"], "one sweep per drive type"),
    ],
)  # fmt: skip
def test_cli_huge_sweeps_and_drive_type_exit_2_with_one_line(args, words, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["sweep", "-e", "wobble-cam-engine", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1 and "Traceback" not in err, err
    assert not out.exists()


def test_result_memory_estimate_matches_the_dataset():
    from rotorkin.sweep import build_spec, execute, result_bytes

    _, raw, _ = load_config(None, "wobble-cam-engine")
    vary = ["drive.plate_tilt=30deg:50deg:6", "drive.roller_axis_angle=85deg,95deg"]
    spec = build_spec(raw, vary, keep_curves=True, samples=101)
    ds = execute(spec, progress=False)
    data = sum(v.nbytes for v in ds.data_vars.values()) + ds["theta_deg"].nbytes
    assert result_bytes(spec.size, len(spec.metrics), 11, spec.points) == data


def test_progress_moves_block_by_block_within_a_chunk(monkeypatch):
    import rotorkin.sweep as sweep
    from rotorkin.sweep import build_spec
    from rotorkin.sweep.engine import compute_chunk

    class Bar:
        def __init__(self):
            self.moves = []

        def advance(self, task, n):
            self.moves.append(n)

    monkeypatch.setattr(sweep, "_PROGRESS_EVERY", 0.0)
    _, raw, _ = load_config(None, "wobble-cam-engine")
    vary = ["drive.plate_tilt=30deg:50deg:40", "drive.roller_axis_angle=85deg:95deg:50"]
    spec = build_spec(raw, vary, samples=360, chunk_size=2000)
    progress = sweep._Progress(False, spec.size)
    progress.bar, progress.task = Bar(), 0
    with progress.within(2000):
        res = compute_chunk(spec, 0, 2000)
    during = list(progress.bar.moves)
    progress.finish_chunk(res["stop"] - res["start"])
    assert len(during) >= 5 and max(during) <= 2000 // 5  # moved many times inside the chunk
    assert sum(progress.bar.moves) == 2000  # and exactly the chunk's designs in all
    # without a bar nothing is reported and the chunk is counted whole
    quiet = sweep._Progress(False, spec.size)
    with quiet.within(2000):
        compute_chunk(spec, 0, 2000)
    quiet.finish_chunk(2000)
