"""Resumable sweeps: SIGKILL a sweep mid-way, restart it, get the uninterrupted result."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr

from rotorkin.cli import main
from rotorkin.io.config import load_config
from rotorkin.sweep import build_spec
from rotorkin.sweep import execute as run_spec
from rotorkin.sweep.engine import chunk_bounds, compute_chunk
from rotorkin.sweep.store import ChunkStore

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="SIGKILL is POSIX")

# 30 one-design chunks, each slow enough (1e6 shaft angles per design) to be killed between
ARGS = [
    "sweep",
    "-e",
    "wobble-cam-engine",
    "--vary",
    "drive.plate_tilt=30deg:50deg:6",
    "--vary",
    "drive.roller_axis_angle=85deg:95deg:5",
    "--angles",
    "1000001",
    "--chunk",
    "1",
]


def _open(path):
    with xr.open_dataset(path, engine="scipy") as ds:
        return ds.load()


@pytest.mark.slow
def test_a_killed_sweep_restarts_where_it_stopped_and_equals_an_uninterrupted_run(tmp_path, capsys):
    out = tmp_path / "killed"
    chunks = out / ".chunks"
    proc = subprocess.Popen([sys.executable, "-m", "rotorkin.cli", *ARGS, "--out", str(out),
                             "-q"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)  # fmt: skip
    deadline = time.monotonic() + 120.0
    try:
        while not list(chunks.glob("*/chunk_*.nc")):
            assert proc.poll() is None, proc.stderr.read().decode()
            assert time.monotonic() < deadline, "no chunk committed in 120 s"
            time.sleep(0.005)
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.wait(timeout=60)
        proc.stderr.close()
    assert proc.returncode == -signal.SIGKILL
    assert not (out / "sweep.nc").exists(), "the sweep finished before it could be killed"
    done = sorted(chunks.glob("*/chunk_*.nc"))
    assert 1 <= len(done) < 30

    # restart (same command): only the missing chunks are computed
    assert main([*ARGS, "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert f"resuming: {len(done)} of 30 chunks already committed, computing {30 - len(done)}" \
        in err  # fmt: skip
    assert not chunks.exists(), "the chunk files are removed once sweep.nc is written"
    resumed = _open(out / "sweep.nc")

    fresh_dir = tmp_path / "fresh"
    assert main([*ARGS, "--out", str(fresh_dir), "-q"]) == 0
    fresh = _open(fresh_dir / "sweep.nc")
    xr.testing.assert_identical(resumed, fresh)  # no design lost, duplicated or altered
    assert resumed["reason"].size == 30 and np.all(resumed["reason"] == 0)


def _spec(chunk_size=4, **kw):
    _, raw, _ = load_config(None, "eccentric-reactor")
    return build_spec(raw, ["drive.eccentricity=10mm:70mm:7", "machine.bore=40mm,50mm"],
                      chunk_size=chunk_size, samples=301, **kw)  # fmt: skip


def test_store_keeps_committed_chunks_and_drops_temporaries_and_stale_specs(tmp_path):
    spec = _spec()
    store = ChunkStore.of_spec(tmp_path / ".chunks", spec.manifest())
    assert store.open() == set()
    for i in (0, 2):
        store.commit(i, compute_chunk(spec, *chunk_bounds(spec, i)))
    (store.folder / ".chunk_000001.nc.tmp-99999").write_bytes(b"half a file")
    assert ChunkStore.of_spec(tmp_path / ".chunks", spec.manifest()).open() == {0, 2}
    assert not list(store.folder.glob(".*tmp*"))
    back = store.read(2)
    direct = compute_chunk(spec, *chunk_bounds(spec, 2))
    assert np.array_equal(back["design"], direct["design"])
    for m, v in direct["metrics"].items():
        assert np.array_equal(back["metrics"][m], v, equal_nan=True)
    # resume through execute: equal to a run without a store
    resumed = run_spec(spec, store=tmp_path, progress=False)
    plain = run_spec(spec, progress=False)
    xr.testing.assert_identical(resumed, plain)
    xr.testing.assert_identical(_open(tmp_path / "sweep.nc"), plain)
    # another spec in the same store keeps its own chunks: neither deletes the other's
    other = _spec(chunk_size=5)
    mine = ChunkStore.of_spec(tmp_path / ".chunks", spec.manifest())
    mine.open()
    mine.commit(0, compute_chunk(spec, *chunk_bounds(spec, 0)))
    theirs = ChunkStore.of_spec(tmp_path / ".chunks", other.manifest())
    assert theirs.open() == set() and theirs.folder != mine.folder
    assert ChunkStore.of_spec(tmp_path / ".chunks", spec.manifest()).open() == {0}
    # the same folder, given explicitly, holds one spec: another one there starts afresh
    s2 = ChunkStore(tmp_path / ".chunks", spec.manifest())
    s2.open()
    s2.commit(0, compute_chunk(spec, *chunk_bounds(spec, 0)))
    assert ChunkStore(tmp_path / ".chunks", other.manifest()).open() == set()


@pytest.mark.parametrize("with_store", [False, True])
def test_a_design_computed_twice_and_one_never_is_refused(tmp_path, monkeypatch, with_store):
    """Each design must land in the result exactly once, with or without a chunk store: a
    chunk that reports its neighbour's designs (3 counted twice, 3 never: 6) fails the sweep
    instead of leaving designs unset (the result is not prefilled); nothing is written."""
    import rotorkin.sweep as sweep

    _, raw, _ = load_config(None, "wobble-cam-engine", ["loads.model=ideal"])
    spec = build_spec(raw, ["machine.compression_ratio=8:12:6"], chunk_size=3, samples=90)
    real = sweep.compute_chunk

    def shifted(spec, start, stop, threads=None):
        res = real(spec, start, stop, threads)
        if start > 0:  # the second chunk claims the first chunk's designs
            res["design"] = np.asarray(res["design"]) - start
        return res

    monkeypatch.setattr(sweep, "compute_chunk", shifted)
    store = tmp_path / "out" if with_store else None
    with pytest.raises(RuntimeError, match="6 designs lost or duplicated"):
        sweep.compute(spec, store=store, progress=False)
    assert not (tmp_path / "out" / "sweep.nc").exists()
