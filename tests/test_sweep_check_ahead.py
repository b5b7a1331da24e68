"""A sweep's last check (one design through the study) runs beside the sweep, and refuses
before anything is written."""

from __future__ import annotations

import os
import pickle

import numpy as np
import pytest

from rotorkin.cli import main
from rotorkin.core import forked
from rotorkin.core.errors import RotorkinError
from rotorkin.io.config import load_config
from rotorkin.report import figures_sweep as fs
from rotorkin.sweep import CheckAhead, build_spec, check_spec_values, compute

VARY = ["drive.plate_tilt=30deg:50deg:4", "machine.compression_ratio=8:16:3"]
# read by the study's pair forces only, no kernel: the grid's checks pass it
BAD = "drive.rail_radius=70mm"
REFUSED = "the base config is not admissible: drive.rail_radius = 70 mm is not admissible"


@pytest.fixture
def forking(monkeypatch):
    """Fork even if an earlier test left threads running (the study takes no lock)."""
    monkeypatch.setattr(forked, "fork_safe", lambda: True)


def _spec(sets=(), **kw):
    _, raw, _ = load_config(None, None, list(sets))
    return build_spec(raw, VARY, check=False, **kw)


def test_the_study_check_runs_in_another_process_and_refuses_there(forking):
    with CheckAhead(_spec([BAD])) as check:
        job = check._job
        assert job is not None and job.pid != os.getpid()
        with pytest.raises(RotorkinError, match=REFUSED):
            check.confirm()
    # the same line as the check made in this process
    with pytest.raises(RotorkinError) as here:
        check_spec_values(_spec([BAD]))
    assert str(here.value).startswith(REFUSED)


def test_without_fork_the_check_is_made_at_once(monkeypatch):
    monkeypatch.setattr(forked, "ahead", lambda *a: None)
    with pytest.raises(RotorkinError, match=REFUSED):
        CheckAhead(_spec([BAD]))
    with CheckAhead(_spec()) as check:
        assert check._job is None
        check.confirm()


def test_an_admissible_base_passes_and_cancel_ends_the_child(forking):
    check = CheckAhead(_spec())
    check.confirm()
    check = CheckAhead(_spec())
    pid = check._job.pid
    check.cancel()
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, os.WNOHANG)  # already waited for


def test_a_refused_confirm_writes_nothing_into_the_store(tmp_path):
    spec = _spec(chunk_size=3)  # 4 chunks
    calls = []

    def refuse():
        calls.append(1)
        raise RotorkinError("refused")

    store = tmp_path / "out"
    with pytest.raises(RotorkinError, match="refused"):
        compute(spec, store=store, progress=False, confirm=refuse)
    assert calls == [1]
    assert not store.exists()
    # confirmed: the store is made and the result written, confirm called once
    compute(spec, store=store, progress=False, confirm=lambda: calls.append(2))
    assert calls == [1, 2]
    assert (store / "sweep.nc").is_file()


def test_the_command_refuses_the_base_in_one_line_and_leaves_the_folder_alone(
    tmp_path, capsys, forking
):
    out = tmp_path / "sweep"
    args = ["sweep", *(a for v in VARY for a in ("--vary", v)), "-q", "--out", str(out)]
    assert main([*args, "--set", BAD]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"rotorkin: error: {REFUSED}")
    assert not out.exists()
    assert main(args) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert main([*args, "--set", BAD]) == 2
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


def test_the_overview_task_carries_the_drawn_lines_only(tmp_path):
    spec = _spec()
    res = compute(spec, progress=False)
    metrics = list(spec.metrics)
    task = fs.overview_task(res, metrics, tmp_path / "a.png")
    data = pickle.dumps(task)
    assert len(data) < 20_000
    plan = task.args[0]
    assert len(plan["curves"]) == 6  # the first six metrics the sweep moves
    for label, y in plan["curves"]:
        name = label.split(" [")[0]
        np.testing.assert_array_equal(y, np.asarray(res[name].values)[:, :])
    path = pickle.loads(data)()
    again = fs.fig_overview(res, metrics, tmp_path / "b.png")
    assert path.read_bytes() == again.read_bytes()
