"""A failure of the machine (disk full, no permission) is one line, exit 3, and leaves nothing."""

from __future__ import annotations

import errno
import os

import pytest

import rotorkin.io.output
from rotorkin.cli import ENVIRONMENT_ERROR, main


@pytest.mark.parametrize(
    ("code", "words"),
    [(errno.ENOSPC, "disk is full"), (errno.EACCES, "permission denied"),
     (errno.EROFS, "read-only")],
)  # fmt: skip
def test_a_failing_write_leaves_nothing_behind(code, words, tmp_path, monkeypatch, capsys):
    def fail(*args, **kwargs):
        raise OSError(code, os.strerror(code), "motion.csv")

    monkeypatch.setattr(rotorkin.io.output, "_write_csv", fail)
    out = tmp_path / "run"
    assert main(["run", "-e", "eccentric-reactor", "--out", str(out)]) == ENVIRONMENT_ERROR
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0] and "--out" in err[0]
    assert list(tmp_path.iterdir()) == []  # no output folder, no staging folder
