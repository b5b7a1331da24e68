"""Plausibility limits ([limits], contact.allowable_stress): warned, refused with --strict, swept.

A design past a limit is admissible: ``rotorkin run`` writes its outputs and warns in
one line naming the limit (exit 0); with ``--strict`` it is refused in one line (exit
2, nothing written); a sweep marks it in its ``violations`` bit mask.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.cli import main
from rotorkin.core.schema import LimitsSection
from rotorkin.io.config import example_names, load_config
from rotorkin.studies.limits import BITS, LIMITS, violation_codes, violations

# (example, --set, the limit key named)
PAST = [
    (
        "elliptic-gear-engine",
        ["machine.compression_ratio=40", "loads.intake_pressure=3 bar"],
        "limits.peak_pressure",
    ),
    ("elliptic-gear-engine", ["limits.peak_pressure=50 bar"], "limits.peak_pressure"),
    (
        "rhomboid-engine",
        [
            "loads.pressure_model=isothermal",
            "loads.hot_temperature=4000 K",
            "contact.allowable_stress=5000 MPa",
        ],
        "limits.peak_temperature",
    ),  # fmt: skip
    ("eccentric-reactor", ["limits.pressure_angle=25 deg"], "limits.pressure_angle"),
    ("wobble-cam-engine", [], "contact.allowable_stress"),
]

#: What the defaults flag on the built-in examples (the wobble-cam engine's 4 mm rollers
#: are overloaded at 3000 rpm: 4161 MPa against 1500 MPa).
EXPECTED = {"wobble-cam-engine": ["contact.allowable_stress"]}


def _files(folder):
    return sorted(p.name for p in folder.iterdir() if not p.name.startswith("."))


@pytest.mark.parametrize(("example", "sets", "key"), PAST)
def test_past_a_limit_warns_in_one_line(capsys, tmp_path, example, sets, key):
    out = tmp_path / "out"
    args = ["run", "-e", example, "-q", "-o", str(out), "-s", "run.points=145"]
    for s in sets:
        args += ["-s", s]
    assert main(args) == 0
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.startswith(f"rotorkin: warning: {key}:")]
    assert len(lines) == 1, err
    assert " is above " in lines[0]
    summary = json.loads((out / "summary.json").read_text())
    assert key in summary["limits_passed"]


@pytest.mark.parametrize(("example", "sets", "key"), PAST)
@pytest.mark.parametrize("command", ["run", "report"])
def test_strict_refuses_and_writes_nothing(capsys, tmp_path, example, sets, key, command):
    out = tmp_path / "out"
    args = [command, "-e", example, "-o", str(out), "--strict", "-s", "run.points=145"]
    for s in sets:
        args += ["-s", s]
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and err.startswith("rotorkin: error: --strict")
    assert f"{key}:" in err
    assert not out.exists() or _files(out) == []


def test_strict_passes_a_plausible_design(capsys, tmp_path):
    out = tmp_path / "out"
    assert main(["run", "-e", "elliptic-gear-engine", "-q", "-o", str(out), "--strict"]) == 0
    assert "summary.json" in _files(out)
    assert json.loads((out / "summary.json").read_text())["limits_passed"] == ""


@pytest.mark.parametrize("example", sorted(example_names()))
def test_examples_flag_only_what_is_past_a_limit(example):
    cfg = load_config(None, example, ["run.points=145"])[0]
    result = drives.evaluate(cfg)
    assert result.summary["limits_passed"] == ", ".join(EXPECTED.get(example, []))
    # the contact stress is said once, as a limit
    said = [w for w in result.warnings if "contact pressure" in w or "allowable" in w]
    assert len(said) == len([k for k in result.summary["limits_passed"].split(", ") if k])


def test_every_drive_has_the_limits_section():
    for name in drives.names():
        model = drives.get(name).config_model
        assert model.model_fields["limits"].annotation is LimitsSection, name
    cfg = load_config(None, "wobble-cam-engine", [])[0]
    assert cfg["limits"]["peak_pressure"] == pytest.approx(250e5)
    assert cfg["limits"]["peak_temperature"] == pytest.approx(3000.0)
    assert cfg["limits"]["pressure_angle"] == pytest.approx(np.radians(60.0))


@pytest.mark.parametrize(
    "setting", ["limits.peak_pressure=0 bar", "limits.pressure_angle=90 deg",
                "limits.peak_temperature=1e6 K", "limits.peak_presure=1 bar"],
)  # fmt: skip
def test_limits_out_of_range_are_refused(capsys, tmp_path, setting):
    out = tmp_path / "out"
    assert main(["run", "-e", "wobble-cam-engine", "-o", str(out), "-s", setting]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and setting.split("=")[0] in err
    assert not out.exists()


def test_violations_line_names_key_value_and_limit():
    cfg = {"limits": {"peak_pressure": 250e5}}
    lines = violations({"peak_pressure_bar": 438.2, "pressure_max_bar": 300.0}, cfg)
    assert len(lines) == 1
    assert lines[0].startswith(
        "limits.peak_pressure: peak_pressure_bar = 438.2 bar is above 250 bar"
    )
    assert violations({"peak_pressure_bar": float("nan")}, cfg) == []
    assert violations({"hot_temperature_K": 3500.0}, {})[0].startswith(
        "limits.peak_temperature: hot_temperature_K = 3500 K is above 3000 K"
    )
    line = violations({}, {}, {"chamber_a_pressure_bar": np.array([1.0, 4e8, 2.0])})[0]
    assert line.startswith("limits.peak_pressure: max of chamber_a_pressure_bar = 4e+08 bar")
    assert violations({"cam_pressure_angle_max_deg": 61.0}, {})[0].startswith(
        "limits.pressure_angle:"
    )


def test_violation_codes_are_a_bit_mask():
    metrics = {
        "peak_pressure_bar": np.array([100.0, 300.0, np.nan, 300.0]),
        "peak_contact_stress_MPa": np.array([2000.0, 100.0, 100.0, 2000.0]),
    }
    codes = violation_codes(metrics, {}, 4)
    p, c = BITS["limits.peak_pressure"], BITS["contact.allowable_stress"]
    assert codes.tolist() == [c, p, 0, p | c]
    varied = {"limits.peak_pressure": np.array([50e5, 500e5, 1e5, 1e5])}
    assert violation_codes(metrics, {}, 4, varied).tolist() == [p | c, 0, 0, p | c]
    assert set(BITS) == set(LIMITS)


def test_sweep_marks_the_designs_past_a_limit():
    from rotorkin.sweep import run_sweep

    raw = load_config(None, "wobble-cam-engine", ["loads.intake_pressure=2 bar"])[1]
    ds = run_sweep(raw, {"machine.compression_ratio": "10,20,40,60"}, progress=False)
    assert ds["peak_pressure_bar"].values.tolist()[-1] > 250.0
    flags = ds["violations"].values
    past = ds["peak_pressure_bar"].values > 250.0
    bit = BITS["limits.peak_pressure"]
    assert past.tolist() == [False, False, True, True]
    assert ((flags & bit) != 0).tolist() == past.tolist()
    meanings = ds["violations"].attrs["flag_meanings"].split()
    assert meanings[int(np.log2(bit))] == "limits.peak_pressure"
    assert ds.attrs["implausible_designs"] == 2


def test_sweep_fallback_marks_from_the_whole_summary():
    from rotorkin.sweep import run_sweep

    sets = ["run.points=73", "loads.intake_pressure=3 bar"]
    raw = load_config(None, "wobble-cam-engine", sets)[1]
    with pytest.warns(Warning):
        ds = run_sweep(raw, {"machine.compression_ratio": "10,40"}, progress=False,
                       metrics=["peak_contact_stress_MPa"])  # fmt: skip
    contact = BITS["contact.allowable_stress"]
    assert all(int(f) & contact for f in ds["violations"].values)
    assert int(ds["violations"].values[1]) & BITS["limits.peak_pressure"]
