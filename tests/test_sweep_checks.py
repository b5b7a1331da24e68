"""The checks of ``rotorkin run`` across a sweep: margins per design, refusals, the cap.

Each check's margin in the sweep equals the one ``run`` prints for that design (also
checked design by design in ``test_sweep.py``); here: what a check refuses becomes the
design's ``reason``, the drive's checks run once per geometry, the cap is said, and the
limits' margins are the limit less the worst swept metric.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.cli import main
from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate
from rotorkin.io.config import load_config
from rotorkin.studies.limits import worst_result
from rotorkin.sweep import build_spec, execute, reason_text
from rotorkin.sweep import checks as sc


def _sweep(example, vary, sets=(), **kw):
    _, raw, _ = load_config(None, example, list(sets))
    spec = build_spec(raw, vary, **kw)
    return spec, execute(spec, progress=False)


def test_a_geometry_a_check_refuses_is_inadmissible_with_the_checks_key():
    """A roller too large for the rhomboid cam: run refuses it naming cam.roller_radius; the
    sweep marks exactly those designs with that key and NaN, the others get the margins."""
    radii = ["10mm", "30mm", "45mm", "60mm"]
    spec, ds = _sweep("rhomboid-engine", [f"cam.roller_radius={','.join(radii)}"], check=False)
    names = [m for m in spec.metrics if sc.is_check(m)]
    assert any("undercut" in m for m in names)
    refused = 0
    for i, r in enumerate(radii):
        cfg = load_config(None, "rhomboid-engine", [f"cam.roller_radius={r}"])[0]
        d = ds.isel({"cam.roller_radius": i})
        try:
            res = evaluate(cfg)
        except ParameterError as exc:
            refused += 1
            assert reason_text(ds, int(d["reason"])) == exc.name == "cam.roller_radius"
            assert all(np.isnan(float(d[m])) for m in spec.metrics)
            continue
        assert int(d["reason"]) == 0
        margins = {sc.metric_name(c.name, c.unit): c.margin for c in res.checks}
        for m in names:
            assert float(d[m]) == pytest.approx(margins[m], rel=1e-12, abs=1e-12)
    assert refused == 2  # 45 mm and 60 mm reach across the cam's waist


def test_the_drive_checks_run_once_per_geometry(monkeypatch):
    """The loads do not move the geometry: 3 tilts x 4 intake pressures = 3 evaluations."""
    _, raw, _ = load_config(None, "wobble-cam-engine", [])
    vary = [
        "drive.plate_tilt=30deg,35deg,40deg",
        "loads.ambient_pressure=0.8bar,0.9bar,1bar,1.1bar",
    ]
    spec = build_spec(raw, vary)
    calls = []
    real = drives.design_checks

    def counting(cfg):
        calls.append(cfg["drive"]["plate_tilt"])
        return real(cfg)

    monkeypatch.setattr(drives, "design_checks", counting)
    ds = execute(spec, progress=False)
    assert np.allclose(sorted(calls), np.radians([30.0, 35.0, 40.0]), rtol=1e-12)
    name = next(m for m in spec.metrics if "undercut" in m)
    values = ds[name].values
    assert np.all(values == values[:, :1])  # the same margin at every pressure
    assert np.all(np.diff(values[:, 0]) != 0)  # and another at every tilt


def test_beyond_the_cap_the_drive_checks_are_not_recorded_and_it_is_said(
    monkeypatch, tmp_path, capsys
):
    monkeypatch.setattr(sc, "MAX_GEOMETRIES", 2)
    _, raw, _ = load_config(None, "wobble-cam-engine", [])
    spec = build_spec(raw, ["drive.plate_tilt=30deg,35deg,40deg"])
    assert not any("undercut" in m for m in spec.metrics)
    ds = execute(spec, progress=False)
    assert "not recorded: 3 distinct geometries" in ds.attrs["design_checks"]
    assert "check_peak_gas_pressure_margin_bar" in ds  # the limits' margins stay
    code = main(["sweep", "-e", "wobble-cam-engine", "--vary", "drive.plate_tilt=30deg:40deg:3",
                 "-o", str(tmp_path / "out")])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 0 and "rotorkin: note: the drive's design checks are not recorded" in err


def test_the_limit_margins_are_the_limit_less_the_worst_swept_metric():
    """Independent arithmetic on the swept metrics, with the limit itself swept."""
    vary = ["limits.peak_pressure=40bar,60bar,250bar", "drive.plate_tilt=30deg,40deg"]
    spec, ds = _sweep("wobble-cam-engine", vary)
    margin = ds["check_peak_gas_pressure_margin_bar"].values
    limit = np.array([40.0, 60.0, 250.0])[:, None]
    assert np.allclose(margin, limit - ds["peak_pressure_bar"].values, rtol=0, atol=1e-9)
    # the violations bit says the same as a negative margin
    bit = (ds["violations"].values & 1) != 0
    assert np.array_equal(bit, margin < 0) and bit.any() and not bit.all()


def test_a_drive_without_checks_says_so():
    # the guide bar has no design checks of its own; its contact stress measures a limit
    spec, ds = _sweep("guide-bar-pump", ["machine.casing_radius=40mm,50mm"])
    assert [m for m in spec.metrics if sc.is_check(m)] == ["check_peak_contact_stress_margin_MPa"]
    spec, ds = _sweep("guide-bar-pump", ["machine.casing_radius=40mm,50mm"],
                      metrics=["displacement_cm3_per_rev", "flywheel_inertia_kgm2"])  # fmt: skip
    assert not any(sc.is_check(m) for m in spec.metrics)
    assert ds.attrs["design_checks"].startswith("none")


def test_a_liquids_negative_pressure_is_no_peak_pressure():
    """The largest magnitude counts for a signed angle, the largest value for a pressure."""
    cols = {"pressure_bar": np.array([1.0, -317.0, 0.5])}
    assert worst_result("limits.peak_pressure", {}, cols) == ("max of pressure_bar", 1.0)
    cols = {"pressure_angle_deg": np.array([10.0, -40.0])}
    assert worst_result("limits.pressure_angle", {}, cols)[1] == 40.0
