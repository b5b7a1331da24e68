"""The command line: every example runs and writes its files; bad input exits 2 with one line."""

import json
import re
import subprocess
import sys

import pytest

from rotorkin.cli import main
from rotorkin.io.config import example_names

EXAMPLES = example_names()  # every built-in example


@pytest.mark.slow
@pytest.mark.parametrize("name", EXAMPLES)
def test_every_example_runs_and_writes_its_files(name, tmp_path, capsys):
    out = tmp_path / name
    assert main(["run", "--example", name, "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "summary.json" in printed
    summary = json.loads((out / "summary.json").read_text())
    assert summary["name"] == name
    header = (out / "motion.csv").read_text().splitlines()[0].split(",")
    rows = (out / "motion.csv").read_text().splitlines()[1:]
    assert len(rows) == 721
    assert all(len(r.split(",")) == len(header) for r in rows)
    readme = (out / "README.txt").read_text()
    assert all(column in readme for column in header)
    pngs = sorted(out.glob("*.png"))
    assert len(pngs) >= 3
    assert all(p.stat().st_size > 10_000 and p.read_bytes()[:4] == b"\x89PNG" for p in pngs)
    assert not list(tmp_path.glob(".*tmp*")), "staging folder left behind"


def test_default_run_is_the_wobble_cam_engine(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["run"]) == 0
    summary = json.loads((tmp_path / "rotorkin-out/wobble-cam-engine/summary.json").read_text())
    assert summary["chamber_swing_deg"] == pytest.approx(38.94, abs=0.005)
    assert summary["power_strokes_per_rev"] == 16
    assert summary["max_plate_tilt_deg"] == pytest.approx(65.53, abs=0.005)
    assert "chamber_swing_deg" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["run", "--set", "drive.plate_tilt=66 deg"], "drive.plate_tilt"),
        (["run", "--set", "drive.plate_tilt=45"], "has no unit"),
        (["run", "--set", "machine.compression_ratio=1"], "machine.compression_ratio"),
        (["run", "--set", "drive.bogus=1"], "unknown key drive.bogus"),
        (["run", "-e", "eccentric-reactor", "--set", "drive.eccentricity=80 mm"], "eccentricity"),
        (["run", "-e", "guide-bar-pump", "--set", "drive.lambda=1.0"], "drive.lambda"),
        (["run", "-e", "rhomboid-engine", "--set", "drive.psi_min=95 deg"], "drive.psi_min"),
        (["run", "-e", "rhomboid-engine", "--set", "drive.a=[1.5]"], "drive.a"),
        (["run", "no-such-file.toml"], "does not exist"),
        (["run", "--example", "nope"], "--example"),
        (["run", "--frobnicate"], "No such option"),
        (["run", "--set", "run.speed=-3000 rpm"], "run.speed = -3000 rpm"),
        (["run", "-e", "guide-bar-pump", "--set", "machine.hub_radius=100 mm"], "hub_radius"),
    ],
)
def test_bad_input_exits_2_with_one_line_and_writes_nothing(args, words, tmp_path, capsys):
    out = tmp_path / "out"
    assert main([*args, "--out", str(out)]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert words in lines[0]
    assert "Traceback" not in captured.err
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []


def test_out_that_is_a_file_is_refused(tmp_path, capsys):
    target = tmp_path / "file"
    target.write_text("x")
    assert main(["run", "--out", str(target)]) == 2
    assert "--out" in capsys.readouterr().err
    assert target.read_text() == "x"


@pytest.mark.slow
def test_console_script_entry_point_in_a_subprocess(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "rotorkin.cli", "run", "--set", "drive.plate_tilt=70 deg"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        check=False,
    )
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1
    assert "65.5" in done.stderr  # the limit is said


_CONSOLE = """
import atexit, sys
atexit.register(lambda: print("exit handler ran", flush=True))
sys.argv = ["rotorkin", *sys.argv[1:]]
from rotorkin.cli import console_main
console_main()
print("not reached")
"""


@pytest.mark.parametrize(
    ("args", "code"), [(["examples"], 0), (["run", "--set", "run.points=2"], 2)]
)
def test_console_script_leaves_with_the_code_its_output_and_exit_handlers(tmp_path, args, code):
    # the console script ends the process itself once the command returned: the exit
    # code is main's, everything printed reaches a pipe, registered exit handlers run
    done = subprocess.run([sys.executable, "-c", _CONSOLE, *args], capture_output=True,
                          text=True, cwd=tmp_path, check=False)  # fmt: skip
    assert done.returncode == code
    assert done.stdout.endswith("exit handler ran\n")
    assert "not reached" not in done.stdout
    if code == 0:
        for name in example_names():
            assert name in done.stdout
    else:
        assert done.stderr.startswith("rotorkin: error: run.points = 2")
        assert done.stderr.count("\n") == 1


def test_examples_and_keys_commands(capsys):
    assert main(["examples"]) == 0
    listed = capsys.readouterr().out
    assert all(name in listed for name in EXAMPLES)
    assert main(["keys", "rhomboid_cam"]) == 0
    assert "drive.psi_min" in capsys.readouterr().out
    assert main(["keys", "nope"]) == 2


@pytest.mark.slow
def test_a_rerun_into_the_same_folder_leaves_no_stale_files(tmp_path, capsys):
    """The wobble-cam figures of a first run do not stay beside a second run's summary;
    a file the user put there stays."""
    out = tmp_path / "mix"
    assert main(["run", "--out", str(out)]) == 0
    first = {p.name for p in out.iterdir()}
    (out / "my-notes.txt").write_text("keep me")
    assert main(["run", "--example", "eccentric-reactor", "--out", str(out)]) == 0
    capsys.readouterr()
    second = {p.name for p in out.iterdir() if not p.name.startswith(".")}
    wobble_only = {n for n in first if n.startswith("fig08_roller") or n.startswith("fig09_")}
    assert wobble_only, "the first run should have written the wobble-cam figures"
    assert not wobble_only & second
    assert (out / "my-notes.txt").read_text() == "keep me"
    summary = json.loads((out / "summary.json").read_text())
    assert summary["name"] == "eccentric-reactor"
    expected = {
        "summary.json",
        "motion.csv",
        "config.toml",
        "checks.csv",
        "README.txt",
        "my-notes.txt",
    }
    figures = {n for n in second if n.endswith(".png")}
    assert second == expected | figures
    assert figures == {n for n in (out / "README.txt").read_text().split() if n.endswith(".png")}


@pytest.mark.slow
@pytest.mark.parametrize("name", EXAMPLES)
def test_printed_summary_says_what_each_metric_is(name, tmp_path, capsys):
    """Every headline metric is in summary.json and printed with a line saying what it is
    (e.g. which torque model, which sign), so two work or torque keys cannot be confused."""
    from rotorkin.drives import evaluate
    from rotorkin.io.config import load_config

    assert main(["run", "--example", name, "--out", str(tmp_path / "o")]) == 0
    printed = capsys.readouterr().out
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    result = evaluate(load_config(example=name)[0])
    assert isinstance(result.headline, dict)
    assert "meaning" in printed
    for key, meaning in result.headline.items():
        assert key in summary
        assert len(meaning) > 10
        assert key in printed


@pytest.mark.parametrize(
    ("setting", "shown"),
    [
        ('drive.plate_tilt="99 deg"', "drive.plate_tilt = 99 deg is not admissible: 0.5 deg <="),
        ('run.speed="-5 rpm"', "run.speed = -5 rpm is not admissible"),
        ('cam.roller_radius="-1 mm"', "cam.roller_radius = -1 mm is not admissible: 0.1 mm <="),
    ],
)
def test_a_value_out_of_its_range_is_shown_in_the_unit_it_was_written_in(
    setting, shown, capsys, tmp_path
):
    assert main(["run", "--set", setting, "--out", str(tmp_path / "o"), "-q"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and shown in err[0]
    assert "1.72" not in err[0] and not re.search(r"\brad\b", err[0])  # not the SI value
