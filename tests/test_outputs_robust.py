"""Outputs: one writer per folder, nothing left by a failure, a kill or SIGTERM."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from rotorkin.cli import main
from rotorkin.core.errors import ConfigError
from rotorkin.io.output import output_lock, staged_output


def test_a_second_writer_of_the_same_folder_is_refused(tmp_path):
    out = tmp_path / "out"
    with output_lock(out):
        with pytest.raises(
            ConfigError, match=rf"is being written by another rotorkin .*{os.getpid()}"
        ):
            with staged_output(out):
                pass
    with staged_output(out) as (stage, _):  # free again
        (stage / "a.txt").write_text("a")
    assert (out / "a.txt").read_text() == "a" and not (tmp_path / ".out.lock").exists()


def test_the_cli_refuses_a_folder_being_written(tmp_path, capsys):
    out = tmp_path / "run"
    with output_lock(out):
        assert main(["run", "-e", "eccentric-reactor", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "being written by another rotorkin" in err[0]
    assert not out.exists()


def test_a_killed_runs_staging_folder_goes_with_the_next_output(tmp_path):
    stale = tmp_path / ".out.tmp-abc123"
    stale.mkdir()
    (stale / "half.csv").write_text("1,2")
    with staged_output(tmp_path / "out") as (stage, _):
        (stage / "b.txt").write_text("b")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_a_failure_removes_the_folders_it_created(tmp_path):
    out = tmp_path / "a" / "b" / "out"
    with pytest.raises(RuntimeError):
        with staged_output(out) as (stage, _):
            (stage / "x.txt").write_text("x")
            raise RuntimeError("boom")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_sigterm_leaves_nothing_half_written(tmp_path):
    out = tmp_path / "sweep"
    args = ["sweep", "-e", "wobble-cam-engine", "--out", str(out), "-q",
            "--vary", "drive.plate_tilt=20deg:60deg:300",
            "--vary", "drive.roller_axis_angle=80deg:100deg:300"]  # fmt: skip
    proc = subprocess.Popen([sys.executable, "-m", "rotorkin.cli", *args],
                            stderr=subprocess.PIPE, text=True)  # fmt: skip
    deadline = time.monotonic() + 60
    while not list(tmp_path.glob(".sweep.tmp-*")):  # the run is writing
        assert proc.poll() is None and time.monotonic() < deadline
        time.sleep(0.01)
    proc.send_signal(signal.SIGTERM)
    err = proc.communicate(timeout=60)[1].strip().splitlines()
    assert proc.returncode == 143 and err[-1].startswith("rotorkin: terminated")
    left = sorted(p.name for p in tmp_path.iterdir())
    assert left in ([], ["sweep"])  # no staging folder, no lock
    if left:  # only the committed chunks of the sweep, kept to resume
        assert {p.name for p in out.iterdir()} <= {".chunks"}


def test_a_sweep_without_one_admissible_design_is_refused(tmp_path, capsys):
    out = tmp_path / "sweep"
    args = ["sweep", "--set", "drive.plate_tilt=70 deg", "--vary",
            "machine.compression_ratio=8:12:3", "--out", str(out)]  # fmt: skip
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no design of the sweep is admissible" in err[0]
    assert "drive.plate_tilt" in err[0] and not out.exists()


def test_a_tolerance_analysis_without_one_admissible_sample_is_refused(
    tmp_path, capsys, monkeypatch
):
    import numpy as np

    import rotorkin.tolerance as tol

    real = tol.evaluate_designs

    def none_admissible(p, *args, **kwargs):
        res = real(p, *args, **kwargs)
        if p.n > 1:
            res["reason"] = np.full(p.n, 3, dtype=np.int16)
        return res

    monkeypatch.setattr(tol, "evaluate_designs", none_admissible)
    out = tmp_path / "tol"
    args = ["tolerance", "--tol", "drive.plate_tilt=0.1deg", "--samples", "50", "--out", str(out)]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "every one of the 50 samples is inadmissible" in err[0]
    assert not out.exists()
