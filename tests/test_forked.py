"""rotorkin.core.forked: a call run ahead in a forked process, its outcome brought back."""

from __future__ import annotations

import os
import threading
import time

import numpy as np
import pytest

from rotorkin.core import forked
from rotorkin.core.errors import ParameterError


@pytest.fixture
def forking(monkeypatch):
    """Fork even if an earlier test left threads running (these calls take no lock)."""
    monkeypatch.setattr(forked, "fork_safe", lambda: True)


def _children() -> set[int]:
    """Pids of this process's children (from /proc)."""
    me = str(os.getpid())
    out = set()
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    if f.read().rsplit(")", 1)[1].split()[1] == me:
                        out.add(int(entry))
            except OSError:
                pass
    return out


def test_the_child_returns_what_the_call_returns(forking):
    data = np.arange(12.0).reshape(3, 4)  # inherited, not pickled on the way in
    job = forked.ahead(np.sum, data, 0)
    assert job is not None and job.pid != os.getpid()
    np.testing.assert_array_equal(job.result(), data.sum(axis=0))
    assert job.done()
    assert job.pid not in _children()  # waited for


def test_an_exception_is_raised_here_as_raised_there(forking):
    def refuse():
        raise ParameterError("drive.plate_tilt", "80 deg", "0 < plate_tilt < 60 deg")

    job = forked.ahead(refuse)
    with pytest.raises(ParameterError) as info:
        job.result()
    assert str(info.value) == str(ParameterError("drive.plate_tilt", "80 deg",
                                                 "0 < plate_tilt < 60 deg"))  # fmt: skip
    assert info.value.name == "drive.plate_tilt"


def test_a_child_that_dies_is_an_error_not_a_value(forking):
    job = forked.ahead(os._exit, 7)
    with pytest.raises(RuntimeError, match="ended with code 7"):
        job.result()


def test_done_does_not_wait_and_cancel_ends_the_child(forking):
    job = forked.ahead(time.sleep, 30.0)
    t0 = time.perf_counter()
    assert not job.done()
    job.cancel()
    assert time.perf_counter() - t0 < 5.0
    assert job.pid not in _children()
    assert job.done()


def test_no_fork_beside_a_foreign_thread():
    stop = threading.Event()
    other = threading.Thread(target=stop.wait, name="someone-else")
    other.start()
    try:
        assert not forked.fork_safe()
        assert forked.ahead(int, "1") is None
    finally:
        stop.set()
        other.join()
