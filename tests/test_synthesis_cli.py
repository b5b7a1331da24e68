"""The ``rotorkin synthesize`` command: outputs, synthesized.toml runs, one-line errors."""

from __future__ import annotations

import csv
import json
import subprocess
import sys
import tomllib

import numpy as np
import pytest

from rotorkin.cli import main
from rotorkin.drives import evaluate
from rotorkin.io.config import load_config


def _files(path):
    """The output files (not the hidden manifest of what the last run wrote)."""
    return sorted(p.name for p in path.iterdir() if not p.name.startswith("."))


@pytest.mark.slow
def test_guide_bar_outputs_and_run_round_trip(tmp_path, capsys):
    out = tmp_path / "syn"
    code = main(
        [
            "synthesize",
            "-e",
            "guide-bar-pump",
            "--objective",
            "vane_angle",
            "--target",
            "58 deg",
            "--set",
            "drive.phase=150 deg",
            "--out",
            str(out),
        ]
    )
    assert code == 0
    printed = capsys.readouterr().out
    assert "vane angle gamma_0 [deg]" in printed and "baseline" in printed
    assert _files(out) == ["synthesis.json", "synthesis_vane_angle.png", "synthesized.toml"]
    assert not list(tmp_path.glob(".*tmp*"))  # the staging folder is gone
    doc = json.loads((out / "synthesis.json").read_text())
    lam = doc["parameters"]["lambda"]
    assert doc["objective"] == "vane_angle" and 0 < lam < 1
    assert any(row["metric"].startswith("lambda") for row in doc["table"])
    toml = tomllib.loads((out / "synthesized.toml").read_text())
    assert toml["drive"]["lambda"] == lam and toml["drive"]["phase"] == "150 deg"
    # the synthesized config runs, and reproduces the target
    run = tmp_path / "run"
    assert main(["run", str(out / "synthesized.toml"), "--out", str(run), "-q"]) == 0
    summary = json.loads((run / "summary.json").read_text())
    assert abs(np.radians(summary["vane_angle_deg"]) - np.radians(58.0)) < 1e-9
    png = (out / "synthesis_vane_angle.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20_000


@pytest.mark.slow
def test_rhomboid_synthesized_toml_runs_and_is_better(tmp_path, capsys):
    out = tmp_path / "rh"
    code = main(
        [
            "synthesize",
            "-e",
            "rhomboid-engine",
            "--objective",
            "min_accel",
            "--out",
            str(out),
            "--set",
            "run.points=181",
        ]
    )
    assert code == 0
    assert "strictly better, constraints met" in capsys.readouterr().out
    assert {"law.csv", "synthesis_psi_law.png", "synthesis_cam.png"} <= set(_files(out))
    # the file `rotorkin run` reads (its study, without the figures: the guide-bar test runs it)
    cfg, _, _ = load_config(out / "synthesized.toml")
    s1 = evaluate(cfg).summary
    doc = json.loads((out / "synthesis.json").read_text())
    assert s1["blade_accel_coeff_max"] == pytest.approx(doc["metrics"]["synthesized_accel_peak"])
    assert s1["blade_accel_coeff_max"] < doc["metrics"]["baseline_accel_peak"]
    with (out / "law.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    psi = np.array([float(r["psi_synthesized_deg"]) for r in rows])
    assert psi.min() == pytest.approx(40.0, abs=1e-9) and psi.max() == pytest.approx(140.0)


def test_wobble_files(tmp_path):
    out = tmp_path / "w"
    assert (
        main(
            [
                "synthesize",
                "--objective",
                "sine_chamber",
                "--out",
                str(out),
                "-q",
                "--set",
                "run.points=181",
            ]
        )
        == 0
    )
    names = _files(out)
    for name in (
        "chamber_law.csv",
        "grooves.csv",
        "synthesis_chamber_law.png",
        "synthesis_grooves.png",
        "synthesized.toml",
        "synthesis.json",
    ):
        assert name in names
    doc = json.loads((out / "synthesis.json").read_text())
    assert doc["metrics"]["round_trip_error_run_deg"] <= 1e-6
    data = np.genfromtxt(out / "chamber_law.csv", delimiter=",", names=True)
    assert np.max(np.abs(data["chamber_a_synthesized_deg"] - data["chamber_a_target_deg"])) < 1e-6


@pytest.mark.parametrize(
    "args, words",
    [
        (["-e", "rhomboid-engine", "--objective", "fastest"], ["--objective", "min_accel"]),
        (["-e", "rhomboid-engine"], ["--objective is missing", "dwell_min"]),
        (
            ["-e", "guide-bar-pump", "--objective", "vane_angle", "--target", "10 deg"],
            ["--target = 10 deg", "45 deg < gamma_0 < 90 deg"],
        ),
        (["-e", "guide-bar-pump", "--objective", "vane_angle", "--target", "ten"], ["'ten'"]),
        (
            ["-e", "rhomboid-engine", "--objective", "min_accel", "--target", "1"],
            ["--target = '1'"],
        ),
        (
            ["-e", "rhomboid-engine", "--objective", "min_accel", "--harmonics", "0"],
            ["--harmonics"],
        ),
        (
            [
                "-e",
                "eccentric-reactor",
                "--objective",
                "gap_change",
                "--target",
                "1 %",
                "--max-pressure-angle",
                "40 deg",
            ],
            ["--max-pressure-angle", "rhomboid_cam"],
        ),
        (
            ["-e", "wobble-cam-engine", "--objective", "sine_chamber"]
            + ["--max-pressure-angle", "95 deg"],
            ["--max-pressure-angle = 95 deg", "0 deg < angle < 90 deg"],
        ),
        (
            ["-e", "rhomboid-engine", "--objective", "min_accel", "--max-pressure-angle", "0 deg"],
            ["--max-pressure-angle = 0 deg", "0 deg < angle < 90 deg"],
        ),
        (
            ["-e", "wobble-cam-engine", "--objective", "dwell_min_volume", "--target", "15 %"],
            ["--target = 0.15", "< --target <= 0.12", "pressure angle exceeds 45 deg"],
        ),
        (
            ["-e", "rhomboid-engine", "--objective", "min_accel", "--max-pressure-angle", "40"],
            ["--max-pressure-angle", "unit"],
        ),
        (["-e", "nope", "--objective", "min_accel"], ["--example"]),
    ],
)
def test_errors_one_line_exit_2_no_output(tmp_path, capsys, args, words):
    out = tmp_path / "never"
    assert main(["synthesize", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("rotorkin: error:") and "\n" not in err
    for w in words:
        assert w in err
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_subprocess_eccentric(tmp_path):
    out = tmp_path / "ecc"
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "rotorkin.cli",
            "synthesize",
            "-e",
            "eccentric-reactor",
            "--objective",
            "gap_change",
            "--target",
            "0.5 %",
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    assert "options for |Delta| = 5 mm" in proc.stdout
    doc = json.loads((out / "synthesis.json").read_text())
    assert doc["metrics"]["round_trip_relative_error"] <= 1e-9


@pytest.mark.parametrize(
    "example, objective, key",
    [("guide-bar-pump", "vane_angle", "vane_angle_deg"), ("eccentric-reactor", "gap_change", "")],
)
def test_bare_examples_have_a_default_target(tmp_path, example, objective, key):
    out = tmp_path / "o"
    assert main(["synthesize", "-e", example, "--objective", objective, "-o", str(out), "-q"]) == 0
    doc = json.loads((out / "synthesis.json").read_text())
    assert doc["target"] is None
    new = load_config(out / "synthesized.toml", None, [])[0]
    summary = evaluate(new).summary
    if key:
        assert abs(summary[key] - doc["metrics"]["target_vane_angle_deg"]) < 1e-7
        assert abs(summary[key] - doc["metrics"]["baseline_vane_angle_deg"]) > 1.0
    else:
        want = doc["metrics"]["target_gap_change_mm"]
        assert abs(abs(summary["gap_change_min_mm"]) - want) <= 1e-9 * want
        assert want < abs(doc["metrics"]["baseline_gap_change_min_mm"])


def test_target_help_names_each_objective():
    from typer.testing import CliRunner

    from rotorkin.cli import app

    res = CliRunner().invoke(app, ["synthesize", "--help"], env={"COLUMNS": "400"})
    assert res.exit_code == 0
    text = " ".join(res.output.split())
    for words in (
        "dwell_min_volume (wobble_cam): the dwell fraction",
        "vane_angle (guide_bar): the vane angle",
        "gap_change (eccentric_cam): the tolerated peak gap change",
        "sine_chamber (wobble_cam): no target",
        "min_accel (rhomboid_cam): no target",
    ):
        assert words in text
