"""Non-circular gears and the tabulated drive through the command line, and ``compare``."""

from __future__ import annotations

import json

import ezdxf
import numpy as np
import pytest

from rotorkin import drives
from rotorkin.cli import main
from rotorkin.drives.noncircular_gears import kinematics as ng
from rotorkin.drives.wobble_cam import study as wobble
from rotorkin.io.config import load_config, validate_config
from rotorkin.machines import twin_rotor as tr


def _run(args, capsys):
    code = main(args)
    out, err = capsys.readouterr()
    return code, out, err


# --- non-circular gears ------------------------------------------------------------------------
def test_elliptic_gear_engine_numbers_from_the_closed_forms(tmp_path, capsys):
    code, _, err = _run(["run", "-e", "elliptic-gear-engine", "-q", "--out", str(tmp_path)],
                        capsys)  # fmt: skip
    assert code == 0, err
    s = json.loads((tmp_path / "summary.json").read_text())
    cfg, _, _ = load_config(example="elliptic-gear-engine")
    gears = ng.NoncircularGears(lobes=2, rotor_lobes=2, eccentricity=0.2, centre_distance=0.12)
    lo, hi = ng.relative_angle_extremes(gears)
    # swept volume K s per chamber and stroke, 8 chambers, one four-stroke cycle per turn
    sizes = ("inner_radius", "outer_radius", "axial_width")
    k = tr.volume_per_radian(tr.TwinRotor(**{f: cfg["machine"][f] for f in sizes}))
    assert s["displacement_cm3_per_rev"] == pytest.approx(8 * k * (hi - lo) * 1e6, rel=1e-12)
    assert s["relative_swing_deg"] == pytest.approx(np.degrees(hi - lo), rel=1e-12)
    assert s["power_strokes_per_rev"] == 8
    assert (
        s["transmission_ratio_min"] == pytest.approx(2 / 3) and s["transmission_ratio_max"] == 1.5
    )
    assert s["compression_ratio_geometric"] == pytest.approx(10.0, rel=1e-12)
    assert s["mean_torque_Nm"] * 2 * np.pi == pytest.approx(s["indicated_work_J"], rel=1e-12)


def test_a_concave_pitch_curve_is_refused_in_one_line(tmp_path, capsys):
    code, out, err = _run(["run", "-e", "elliptic-gear-engine", "--set", "drive.eccentricity=0.4",
                           "--out", str(tmp_path / "o")], capsys)  # fmt: skip
    assert code == 2
    assert err.count("\n") == 1 and "drive.eccentricity = 0.4" in err and "convex" in err
    assert not (tmp_path / "o").exists()


def test_pitch_curves_exported_as_dxf_lie_on_the_pitch_curves(tmp_path, capsys):
    code, _, err = _run(["export", "-e", "elliptic-gear-engine", "--format", "dxf", "--out",
                         str(tmp_path)], capsys)  # fmt: skip
    assert code == 0, err
    params = ng.NoncircularGears(lobes=2, rotor_lobes=2, eccentricity=0.2, centre_distance=0.12,
                                 phase=np.pi / 2)  # fmt: skip
    for which in ng.WHICH:
        doc = ezdxf.readfile(tmp_path / f"elliptic-gear-engine_{which}_gear.dxf")
        splines = doc.modelspace().query("SPLINE[layer=='PITCH']")  # B-spline pieces
        pts = [np.array(list(e.construction_tool().approximate(400)))[:, :2] for e in splines]
        assert doc.header["$INSUNITS"] == 4  # millimetres
        xy = np.concatenate(pts) / 1e3
        angle = np.arctan2(xy[:, 1], xy[:, 0])
        r = np.hypot(xy[:, 0], xy[:, 1])
        assert len(splines) >= 8 and len(r) > 3000
        assert r == pytest.approx(ng.pitch_radius(params, which, angle), abs=1e-5)  # tolerance


# --- tabulated --------------------------------------------------------------------------------
def _wobble_table(path, points=721):
    cfg, _, _ = load_config(example="wobble-cam-engine")
    m = wobble.law(cfg).motion(np.linspace(0.0, 2 * np.pi, points))
    rows = np.column_stack([np.degrees(m.theta), np.degrees(m.q[0]), np.degrees(m.q[1])])
    np.savetxt(path, rows, delimiter=",", header="theta [deg],rotor 1 [deg],rotor 2 [deg]",
               comments="", fmt="%.17g")  # fmt: skip
    return cfg


def test_wobble_rotor_table_reproduces_the_wobble_run(tmp_path):
    cfg = _wobble_table(tmp_path / "rotors.csv")
    example = load_config(example="wobble-cam-engine")[1]
    raw = {"drive": {"type": "tabulated", "table": str(tmp_path / "rotors.csv")},
           "machine": example["machine"], "loads": example["loads"]}  # fmt: skip
    got = drives.evaluate(validate_config(raw)).summary
    want = drives.evaluate(cfg).summary
    for key in ("displacement_cm3_per_rev", "compression_ratio_geometric", "indicated_work_J",
                "mean_torque_Nm", "flywheel_inertia_kgm2"):  # fmt: skip
        assert got[key] == pytest.approx(want[key], rel=1e-6), key


def test_a_runs_motion_csv_is_read_back_by_its_columns(tmp_path, capsys):
    code, _, err = _run(["run", "-e", "wobble-cam-engine", "-q", "--out", str(tmp_path / "w")],
                        capsys)  # fmt: skip
    assert code == 0, err
    cfg = tmp_path / "tab.toml"
    cfg.write_text(
        '[drive]\ntype = "tabulated"\ntable = "w/motion.csv"\n'
        'columns = ["theta_deg", "rotor1_angle_deg", "rotor2_angle_deg"]\n'
    )
    code, _, err = _run(["run", str(cfg), "-q", "--out", str(tmp_path / "t")], capsys)
    assert code == 0, err
    a = json.loads((tmp_path / "t" / "summary.json").read_text())
    b = json.loads((tmp_path / "w" / "summary.json").read_text())
    # motion.csv holds the angles to 12 significant digits (not the exact closed forms)
    for key in ("displacement_cm3_per_rev", "indicated_work_J", "flywheel_inertia_kgm2"):
        assert a[key] == pytest.approx(b[key], rel=1e-6), key


def test_the_readme_table_config_runs_on_a_runs_motion_csv(tmp_path, capsys):
    import re
    from pathlib import Path

    readme = (Path(__file__).resolve().parent.parent / "README.md").read_text()
    block = [b for b in re.findall(r"```toml\n(.*?)```", readme, re.S) if "tabulated" in b][0]
    code, _, err = _run(["run", "-e", "wobble-cam-engine", "-q", "--out", str(tmp_path)], capsys)
    assert code == 0, err
    (tmp_path / "pump.toml").write_text(block)
    code, _, err = _run(["run", str(tmp_path / "pump.toml"), "-q", "--out", str(tmp_path / "p")],
                        capsys)  # fmt: skip
    assert code == 0, err
    s = json.loads((tmp_path / "p" / "summary.json").read_text())
    assert s["machine"] == "vane_pump" and s["indicated_work_J"] < 0


@pytest.mark.parametrize(
    ("body", "fragment"),
    [
        ("theta [deg],a [deg],b [deg]\n0,0,0\n1,1,1\n", "rows"),
        ("theta [deg],a [deg],b [deg]\n" + "".join(f"{t},{t},{'nan' if t == 90 else t}\n"
                                                      for t in range(0, 361, 10)), "NaN"),
        ("theta [deg],a [deg],b [deg]\n" + "".join(f"{t},{t},{t}\n" for t in range(0, 101, 5)),
         "360 deg"),
        ("theta,a [deg],b [deg]\n" + "".join(f"{t},{t},{t}\n" for t in range(0, 361, 10)),
         "unit"),
    ],
)  # fmt: skip
def test_bad_tables_are_refused_in_one_line_with_exit_2(tmp_path, capsys, body, fragment):
    (tmp_path / "t.csv").write_text(body)
    (tmp_path / "c.toml").write_text('[drive]\ntype = "tabulated"\ntable = "t.csv"\n')
    code, _, err = _run(["run", str(tmp_path / "c.toml"), "--out", str(tmp_path / "o")], capsys)
    assert code == 2
    assert err.count("\n") == 1 and "drive.table" in err
    assert fragment.lower() in err.lower()
    assert not (tmp_path / "o").exists()


def test_a_missing_table_is_refused_in_one_line(tmp_path, capsys):
    (tmp_path / "c.toml").write_text('[drive]\ntype = "tabulated"\ntable = "nope.csv"\n')
    code, _, err = _run(["run", str(tmp_path / "c.toml"), "--out", str(tmp_path / "o")], capsys)
    assert code == 2 and err.count("\n") == 1 and "drive.table" in err


# --- compare ----------------------------------------------------------------------------------
def test_compare_one_engine_on_three_drives_at_the_same_displacement(tmp_path, capsys):
    code, out, err = _run(["compare", "-e", "wobble-cam-engine", "--drive", "noncircular_gears",
                           "--drive", "tabulated", "--drive", "rhomboid_cam", "--out",
                           str(tmp_path)], capsys)  # fmt: skip
    assert code == 0, err
    doc = json.loads((tmp_path / "compare.json").read_text())
    assert doc["drives"] == ["wobble_cam", "noncircular_gears", "tabulated"]
    disp = doc["rows"]["displacement_cm3_per_rev"]
    assert disp["noncircular_gears"] == pytest.approx(disp["wobble_cam"], rel=1e-12)
    # the tabulated example is the wobble cam's rotor table: the same machine, number for number
    for key, row in doc["rows"].items():
        assert row["tabulated"] == pytest.approx(row["wobble_cam"], rel=1e-6, abs=1e-9), key
    assert (
        "rhomboid_cam" in doc["refused"] and "pistons_per_rotor" in doc["refused"]["rhomboid_cam"]
    )
    assert (tmp_path / "compare.png").stat().st_size > 10_000
    assert "does not carry the machine" in out


def test_compare_needs_a_drive_and_a_vane_machine(tmp_path, capsys):
    code, _, err = _run(["compare", "-e", "wobble-cam-engine", "--out", str(tmp_path)], capsys)
    assert code == 2 and "--drive" in err
    code, _, err = _run(["compare", "-e", "eccentric-reactor", "--drive", "wobble_cam", "--out",
                         str(tmp_path)], capsys)  # fmt: skip
    assert code == 2 and err.count("\n") == 1


# --- sweeps, tolerance and report through the registry ---------------------------------------
def test_sweep_of_the_gears_eccentricity_widens_the_swing(tmp_path, capsys):
    import xarray as xr

    code, _, err = _run(["sweep", "-e", "elliptic-gear-engine", "--vary",
                         "drive.eccentricity=0.05,0.15,0.25", "-q", "--out", str(tmp_path)],
                        capsys)  # fmt: skip
    assert code == 0, err
    ds = xr.open_dataset(tmp_path / "sweep.nc")
    swing = ds["relative_swing_deg"].values
    assert np.all(ds["reason"].values == 0) and np.all(np.diff(swing) > 0)
    for e, s in zip((0.05, 0.15, 0.25), swing, strict=True):
        lo, hi = ng.relative_angle_extremes(ng.NoncircularGears(eccentricity=e))
        assert s == pytest.approx(np.degrees(hi - lo), rel=1e-9)


def test_sweep_and_tolerance_of_a_pump_on_the_wobble_cam(tmp_path, capsys):
    import xarray as xr

    (tmp_path / "c.toml").write_text(
        '[drive]\ntype = "wobble_cam"\nplate_tilt = "45 deg"\nroller_axis_angle = "90 deg"\n'
        '[machine]\ntype = "vane_pump"\n'
    )
    code, _, err = _run(["sweep", str(tmp_path / "c.toml"), "--vary",
                         "machine.vanes_per_impeller=1,2,3", "-q", "--out",
                         str(tmp_path / "s")], capsys)  # fmt: skip
    assert code == 0, err
    ds = xr.open_dataset(tmp_path / "s" / "sweep.nc")
    assert np.all(ds["reason"].values == 0)
    disp = ds["displacement_cm3_per_rev"].values
    # 2 Z chambers, each sweeping k s per volume cycle: proportional to the vane count
    assert disp / np.array([1, 2, 3]) == pytest.approx(np.full(3, disp[0]), rel=1e-12)
    code, _, err = _run(["tolerance", str(tmp_path / "c.toml"), "--tol",
                         "drive.plate_tilt=0.2deg", "--samples", "16", "-q", "--out",
                         str(tmp_path / "t")], capsys)  # fmt: skip
    assert code == 0, err
    assert (tmp_path / "t" / "tolerance.nc").exists()
    # ten vanes do not fit the 38.9 deg swing (360 / 38.9 = 9.2): one line naming the key
    code, _, err = _run(["sweep", str(tmp_path / "c.toml"), "--vary",
                         "machine.vanes_per_impeller=2,10", "-q", "--out", str(tmp_path / "x")],
                        capsys)  # fmt: skip
    assert code == 2 and err.count("\n") == 1 and "machine.vanes_per_impeller" in err


def test_report_of_a_machine_on_another_drive_draws_its_chambers(tmp_path, capsys):
    (tmp_path / "c.toml").write_text(
        '[drive]\ntype = "rhomboid_cam"\nlink_length = "120 mm"\npsi_min = "40 deg"\n'
        '[machine]\ntype = "twin_rotor"\npistons_per_rotor = 2\ncompression_ratio = 8\n'
    )
    code, _, err = _run(["report", str(tmp_path / "c.toml"), "--out", str(tmp_path / "r")],
                        capsys)  # fmt: skip
    assert code == 0, err
    page = (tmp_path / "r" / "report.html").read_text()
    assert "plot-chambers" in page and "plot-torque" in page and "plot-members" in page
