"""The corpus of bad inputs (tests/corpus/bad_inputs.toml), one test per case.

Each case runs ``rotorkin.cli.main`` in an empty working folder and must give its
exit code, exactly one line on stderr containing its fragment, no traceback, no
"internal error", and leave nothing behind beyond the files the case created. A
case that runs longer than :data:`CASE_SECONDS` fails instead of hanging the
suite; one that asks for absurd memory meets an address-space limit instead of
the machine's.
"""

from __future__ import annotations

import contextlib
import os
import resource
import signal
import tomllib
from pathlib import Path

import pytest

from rotorkin.cli import main

pytestmark = pytest.mark.slow

CORPUS = Path(__file__).parent / "corpus" / "bad_inputs.toml"
#: Longest run of one case [s].
CASE_SECONDS = 20
#: Address space a case may add to the test process [bytes].
CASE_MEMORY = 4 << 30


class CaseTimeout(BaseException):
    """Raised by the alarm; a BaseException so that the command cannot swallow it."""


@contextlib.contextmanager
def guarded(seconds: int = CASE_SECONDS, memory: int = CASE_MEMORY):
    """Run the body under an alarm of ``seconds`` and an address-space limit."""

    def ring(signum, frame):
        raise CaseTimeout(f"still running after {seconds} s")

    previous = signal.signal(signal.SIGALRM, ring)
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    with open("/proc/self/statm") as fh:
        used = int(fh.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    limit = used + memory
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def load_cases(path: Path = CORPUS) -> list[dict]:
    with path.open("rb") as fh:
        return tomllib.load(fh)["case"]


def expanded(text: str, expand: dict) -> str:
    for mark, (piece, times) in expand.items():
        text = text.replace(f"@{mark}@", piece * times)
    return text


def make_files(folder: Path, files: list[dict], expand: dict) -> None:
    for spec in files:
        path = folder / spec["path"]
        kind = spec["kind"]
        if kind == "text":
            path.write_text(expanded(spec["text"], expand), encoding="utf-8")
        elif kind == "bytes":
            if "hex" in spec:
                path.write_bytes(bytes.fromhex(spec["hex"]))
            else:
                fill = spec["fill"].encode()
                path.write_bytes((fill * (spec["size"] // len(fill) + 1))[: spec["size"]])
        elif kind == "dir":
            path.mkdir()
        elif kind == "fifo":
            os.mkfifo(path)
        elif kind == "symlink":
            os.symlink(spec["target"], path)
        else:
            raise ValueError(f"unknown kind of file {kind!r} in the corpus")


def snapshot(folder: Path) -> dict[str, tuple]:
    """Every entry under ``folder`` (hidden ones too) with its kind, size and mtime."""
    seen = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = Path(root, name)
            st = path.lstat()
            seen[str(path.relative_to(folder))] = (st.st_mode, st.st_size, st.st_mtime_ns)
    return seen


def run_case(case: dict, folder: Path, capsys) -> tuple[int, str, dict, dict]:
    """Run one case in ``folder``; return (exit code, stderr, entries before, after)."""
    expand = case.get("expand", {})
    make_files(folder, case.get("files", []), expand)
    args = [expanded(a, expand) for a in case["args"]]
    before = snapshot(folder)
    capsys.readouterr()
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        with guarded():
            code = main(args)
    finally:
        os.chdir(cwd)
    err = capsys.readouterr().err
    return code, err, before, snapshot(folder)


def check(case: dict, code: int, err: str, before: dict, after: dict) -> None:
    lines = err.strip().splitlines()
    assert "Traceback" not in err, err
    assert "internal error" not in err, err
    assert code == case["exit"], f"exit {code}, stderr: {err!r}"
    assert len(lines) == 1, f"{len(lines)} lines on stderr: {err!r}"
    assert case["fragment"] in lines[0], f"{case['fragment']!r} not in {lines[0]!r}"
    left = sorted(set(after) - set(before))
    assert not left, f"left behind: {left[:10]}"
    changed = sorted(k for k in before if after.get(k) != before[k])
    assert not changed, f"changed or removed: {changed[:10]}"


CASES = load_cases()


def test_the_corpus_is_well_formed():
    ids = [c["id"] for c in CASES]
    assert len(ids) == len(set(ids))
    assert len(CASES) >= 320
    commands = {c["args"][0] for c in CASES}
    assert {"run", "examples", "keys", "export", "synthesize", "report", "sweep",
            "tolerance"} <= commands  # fmt: skip
    for c in CASES:
        assert c["exit"] in (2, 3) and c["fragment"], c["id"]


@pytest.mark.parametrize("case", CASES, ids=[c["id"] for c in CASES])
def test_bad_input(case, tmp_path, capsys):
    folder = tmp_path / "work"
    folder.mkdir()
    code, err, before, after = run_case(case, folder, capsys)
    check(case, code, err, before, after)
