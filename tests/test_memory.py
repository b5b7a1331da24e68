"""The C allocator's thresholds (rotorkin.core.memory)."""

import platform
import subprocess
import sys

from rotorkin.core import memory

GLIBC = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"


def test_the_thresholds_are_set_under_glibc_and_nowhere_else():
    assert memory.tune_allocator() is GLIBC
    assert memory.tune_allocator(memory.THRESHOLD) is GLIBC  # again: harmless


def test_the_environment_keeps_the_default_allocator(monkeypatch):
    monkeypatch.setenv("ROTORKIN_ALLOCATOR", "default")
    assert memory.tune_allocator() is False


def test_memory_handed_back_without_error():
    memory.release_memory()


def test_the_command_line_sets_the_thresholds_at_start():
    code = (
        "import rotorkin.core.memory as m, rotorkin.cli as c; calls = []; "
        "c.tune_allocator = lambda: calls.append(1) or True; "
        "rc = c.main(['examples']); print(rc, len(calls))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split()[-2:] == ["0", "1"]
