"""A model input that leaves a headline number without meaning is said in one line, never 0/nan.

The command exits 0 (the rest of the analysis stands), prints one warning line per
number that lost its meaning naming the input to change, shows such a number as
``n/a`` and leaves it out of ``summary.json`` (listed under ``undefined``).
"""

from __future__ import annotations

import json

import pytest

from rotorkin.cli import main


@pytest.mark.slow
@pytest.mark.parametrize(
    ("example", "sets", "words", "undefined"),
    [
        ("guide-bar-pump", ["loads.discharge_pressure=1 bar"], "the pump lifts nothing",
         {"torque_ripple", "torque_ripple_with_inertia", "mechanical_efficiency"}),
        ("guide-bar-pump", ["loads.impeller_torque_1=0 N*m", "loads.impeller_torque_2=0 N*m"],
         "input_torque_fluctuation_ratio is not defined", {"input_torque_fluctuation_ratio"}),
        ("rhomboid-engine", ["loads.torque_high=50 N*m", "loads.torque_low=50 N*m"],
         "does no work", {"torque_ripple", "torque_ripple_with_inertia"}),
        ("eccentric-reactor", ["machine.inertia_shaft=0 kg*m^2", "machine.piston_mass=0 kg"],
         "nothing bounds the speed", {"speed_fluctuation_without_flywheel"}),
    ],
)  # fmt: skip
def test_warned_and_left_out(example, sets, words, undefined, tmp_path, capsys):
    out = tmp_path / "run"
    args = ["run", "-e", example, "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    assert main(args) == 0
    captured = capsys.readouterr()
    warnings = [line for line in captured.err.splitlines() if line.startswith("rotorkin: warning")]
    assert any(words in line for line in warnings), captured.err
    assert len(warnings) == len(captured.err.strip().splitlines())  # nothing else on stderr
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["undefined"]) == undefined
    assert not undefined & set(summary)
    assert " nan " not in captured.out.lower()


@pytest.mark.slow
def test_the_examples_have_no_warnings(tmp_path, capsys):
    for example in ("guide-bar-pump", "rhomboid-engine", "eccentric-reactor"):
        assert main(["run", "-e", example, "-q", "--out", str(tmp_path / example)]) == 0
    assert capsys.readouterr().err == ""


@pytest.mark.slow
def test_a_roller_that_export_would_refuse_is_warned_about_by_run(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", "--set", "drive.plate_tilt=40 deg", "-q", "--out", str(out)]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    # the undercut, then (a finding, not this check's) the rollers' contact pressure
    assert all(line.startswith("rotorkin: warning: ") for line in err)
    assert err[0].startswith("rotorkin: warning: cam.roller_radius = 4 mm")
    assert "rotorkin export will refuse this cam" in err[0]
    assert main(["export", "--set", "drive.plate_tilt=40 deg", "--out", str(tmp_path / "cad")]) == 2
