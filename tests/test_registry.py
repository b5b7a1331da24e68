"""A drive defined here, registered at run time, goes through run, sweep, report and keys.

The drive: two rotors on sine laws about a uniform rotation,
``q1 = theta + a sin(theta)``, ``q2 = theta + pi/2 - a sin(theta)``: the relative
angle ``pi/2 - 2 a sin(theta)`` swings by ``4 a``. Nothing outside this file knows it.
"""

from __future__ import annotations

import json
from typing import Literal

import numpy as np
import pytest
import xarray as xr
from pydantic import Field

from rotorkin import drives
from rotorkin.cli import main
from rotorkin.core.motion import Motion
from rotorkin.core.schema import Angle, EmptySection, ExportSection, RunSection, Section
from rotorkin.drives import DriveSpec
from rotorkin.studies import StudyResult
from rotorkin.studies.helpers import angle_grid


class SineDrive(Section):
    type: Literal["sine_rotors"]
    amplitude: Angle = Field("20 deg", ge=0.0, le=0.7, description="amplitude a of the sine laws")


class SineConfig(Section):
    title: str = ""
    drive: SineDrive
    machine: EmptySection = Field(default_factory=EmptySection)
    loads: EmptySection = Field(default_factory=EmptySection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)


def sine_motion(amplitude, theta) -> Motion:
    a, t = np.asarray(amplitude, dtype=float), np.asarray(theta, dtype=float)
    s, c = np.sin(t), np.cos(t)
    return Motion(
        theta=t,
        q=np.stack([t + a * s, t + np.pi / 2 - a * s]),
        dq=np.stack([1 + a * c, 1 - a * c]),
        d2q=np.stack([-a * s, a * s]),
        d3q=np.stack([-a * c, a * c]),
        members=("rotor 1", "rotor 2"),
    )


HEADLINE = {
    "relative_angle_swing_deg": "swing of the angle between the rotors",
    "speed_ratio_max": "largest rotor speed over shaft speed",
}


def sine_study(cfg: dict) -> StudyResult:
    a = cfg["drive"]["amplitude"]
    theta = angle_grid(2 * np.pi, cfg["run"]["points"])
    m = sine_motion(a, theta)
    rel = m.q[1] - m.q[0]
    return StudyResult(
        drive_type="sine_rotors",
        title="two rotors on sine laws",
        summary={
            "relative_angle_swing_deg": float(np.degrees(np.ptp(rel))),
            "speed_ratio_max": float(np.max(m.dq)),
        },
        columns={
            "theta_deg": np.degrees(theta),
            "rotor1_angle_deg": np.degrees(m.q[0]),
            "rotor2_angle_deg": np.degrees(m.q[1]),
        },
        column_docs={
            "theta_deg": "shaft angle",
            "rotor1_angle_deg": "rotor 1 angle",
            "rotor2_angle_deg": "rotor 2 angle",
        },
        headline=HEADLINE,
        motion=m,
        warnings=("drive.amplitude = 0: the rotors turn uniformly, nothing breathes",)
        if a == 0
        else (),
    )


SPEC = DriveSpec(
    name="sine_rotors", title="two rotors on sine laws", config_model=SineConfig, study=sine_study,
    headline=HEADLINE,
)  # fmt: skip


@pytest.fixture
def sine_drive(tmp_path):
    drives.register(SPEC)
    cfg = tmp_path / "sine.toml"
    cfg.write_text('title = "sine rotors"\n[drive]\ntype = "sine_rotors"\namplitude = "15 deg"\n')
    try:
        yield cfg
    finally:
        drives.unregister("sine_rotors")


def test_a_name_registers_once():
    drives.register(SPEC)
    try:
        with pytest.raises(ValueError, match="registered already"):
            drives.register(SPEC)
    finally:
        drives.unregister("sine_rotors")
    assert "sine_rotors" not in drives.names()


def test_run(sine_drive, tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", str(sine_drive), "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["relative_angle_swing_deg"] == pytest.approx(4 * 15.0, rel=1e-4)
    assert summary["speed_ratio_max"] == pytest.approx(1 + np.radians(15), rel=1e-6)
    assert (out / "motion.csv").read_text().startswith("theta_deg,rotor1_angle_deg")
    printed = capsys.readouterr().out
    assert "relative_angle_swing_deg" in printed and "two rotors on sine laws" in printed


def test_keys_and_bad_value(sine_drive, capsys):
    assert main(["keys", "sine_rotors"]) == 0
    assert "drive.amplitude" in capsys.readouterr().out
    assert main(["run", str(sine_drive), "--set", "drive.amplitude=50 deg", "-q"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "drive.amplitude" in err[0]


def test_sweep(sine_drive, tmp_path, capsys):
    out = tmp_path / "sweep"
    code = main(
        ["sweep", str(sine_drive), "--vary", "drive.amplitude=10deg:30deg:3", "--out", str(out)]
    )
    assert code == 0, capsys.readouterr().err
    with xr.open_dataset(out / "sweep.nc") as ds:
        swing = ds["relative_angle_swing_deg"].values
        amp = ds["drive.amplitude"].values
    np.testing.assert_allclose(amp, [10.0, 20.0, 30.0])
    np.testing.assert_allclose(swing, 4 * amp, rtol=1e-4)


def test_report(sine_drive, tmp_path):
    assert main(["report", str(sine_drive), "--out", str(tmp_path)]) == 0
    html = (tmp_path / "report.html").read_text()
    assert "two rotors on sine laws" in html and "No drive-specific checks" in html
    assert "relative_angle_swing_deg" in html


def test_export_says_there_is_nothing_to_export(sine_drive, tmp_path, capsys):
    assert main(["export", str(sine_drive), "--out", str(tmp_path / "cad")]) == 2
    assert "has no parts to export" in capsys.readouterr().err
    assert not (tmp_path / "cad").exists()


def test_tolerance(sine_drive, tmp_path, capsys):
    out = tmp_path / "tol"
    code = main(
        ["tolerance", str(sine_drive), "--tol", "drive.amplitude=1deg", "--samples", "50",
         "--out", str(out)]
    )  # fmt: skip
    assert code == 0, capsys.readouterr().err
    swing = json.loads((out / "tolerance.json").read_text())["metrics"]["relative_angle_swing_deg"]
    # a = 15 deg +- 1 deg uniformly: the swing 4 a lies in [56, 64] deg, nominal 60 deg
    assert swing["nominal"] == pytest.approx(60.0, rel=1e-4)
    assert 56.0 - 1e-6 <= swing["min"] < swing["max"] <= 64.0 + 1e-6
    assert swing["admissible"] == 50


def test_a_meaningless_input_is_warned_about_in_one_line(sine_drive, tmp_path, capsys):
    out = tmp_path / "run"
    assert (
        main(["run", str(sine_drive), "--set", "drive.amplitude=0 deg", "-q", "--out", str(out)])
        == 0
    )
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [
        "rotorkin: warning: drive.amplitude = 0: the rotors turn uniformly, nothing breathes"
    ]
    assert (
        main(["report", str(sine_drive), "--set", "drive.amplitude=0 deg", "--out", str(out)]) == 0
    )
    assert "nothing breathes" in (out / "report.html").read_text()


def test_every_drive_ships_its_examples_in_its_package():
    from rotorkin.io.config import read_toml

    for name, spec in drives.REGISTRY.items():
        assert spec.examples, name
        for example in spec.examples:
            path = spec.example_dir / f"{example}.toml"
            assert path.is_file() and path.parent.parent.name == name
            assert read_toml(path)["drive"]["type"] == name
