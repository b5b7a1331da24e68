"""Resumable sweeps: one netCDF file per finished chunk, committed atomically, and a manifest.

Layout of a sweep folder ``DIR``::

    DIR/sweep.nc                          the assembled result (written last, atomically)
    DIR/.chunks/HASH/manifest.json        the sweep's spec and its hash (HASH: its first 16)
    DIR/.chunks/HASH/chunk_000017.nc      chunk 17: its designs' metrics, reasons, violations

A chunk file is written under a temporary name and renamed (``os.replace``)
when complete, so a chunk file that exists is complete: a sweep killed at any
moment (even by SIGKILL) and started again with the same spec finds the chunks
already committed, computes only the missing ones, and assembles the result,
checking that every design appears exactly once. A different spec in the same
folder (other keys, values, metrics, samples or chunk size) has its own chunk
folder: it neither reuses nor deletes another spec's chunks.
The chunk files go once ``sweep.nc`` is written.

Files are netCDF-3 (64-bit offsets), streamed by :mod:`rotorkin.sweep.netcdf` (no
netCDF4, zarr or xarray library is needed); the chunks are read back with
:mod:`scipy.io`, the result by :mod:`xarray` or any netCDF reader.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import shutil
from pathlib import Path

import numpy as np

from rotorkin.core.errors import ConfigError

__all__ = ["ChunkStore", "spec_hash", "write_dataset"]

_MANIFEST = "manifest.json"


def open_folder(folder: Path, shown) -> None:
    """Create a store's folder and drop the temporary files a killed writer left in it.

    ``shown`` is the ``--out`` folder named in the one-line error when it cannot be made.
    """
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        if exc.errno in (errno.ENOTDIR, errno.EEXIST, errno.ENAMETOOLONG):
            raise ConfigError(f"--out = {str(shown)!r} cannot be written: "
                              f"{exc.strerror}") from None  # fmt: skip
        raise
    for tmp in folder.glob(".*.tmp-*"):
        tmp.unlink(missing_ok=True)


def spec_hash(manifest: dict) -> str:
    """SHA-256 of the canonical JSON of a sweep's manifest."""
    text = json.dumps(manifest, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


class _Var:
    """A variable for :func:`rotorkin.sweep.netcdf.write_netcdf3`: dims, data, no attributes."""

    def __init__(self, dims, data):
        self.dims, self.data, self.attrs = dims, np.ascontiguousarray(data), {}


def _tmp(path: Path) -> Path:
    return path.with_name(f".{path.name}.tmp-{os.getpid()}")


class ChunkStore:
    """The committed chunks of one sweep in ``folder``.

    Parameters
    ----------
    folder : Path
        Working folder (created); ``DIR/.chunks`` for a sweep in ``DIR``.
    manifest : dict
        :meth:`rotorkin.sweep.engine.SweepSpec.manifest`.
    """

    def __init__(self, folder, manifest: dict):
        self.folder = Path(folder)
        self.manifest = manifest
        self.key = spec_hash(manifest)

    @classmethod
    def of_spec(cls, root, manifest: dict) -> ChunkStore:
        """The store of one spec in its own folder under ``root`` (named by the spec's hash).

        Sweeps of different specs into the same output folder keep their chunks apart,
        so one never deletes the other's; each resumes from its own.
        """
        return cls(Path(root) / spec_hash(manifest)[:16], manifest)

    def open(self) -> set[int]:
        """Prepare the folder; return the indices of the chunks already committed.

        Leftover temporary files of a killed run are removed; chunks of a
        different spec are removed too (with the old manifest).
        """
        open_folder(self.folder, self.folder.parent)
        path = self.folder / _MANIFEST
        old = None
        if path.is_file():
            try:
                old = json.loads(path.read_text()).get("hash")
            except (OSError, ValueError):
                old = None
        if old != self.key:
            for f in self.folder.glob("chunk_*.nc"):
                f.unlink()
            tmp = _tmp(path)
            tmp.write_text(json.dumps({"hash": self.key, "spec": self.manifest}, indent=1))
            os.replace(tmp, path)
        return self.committed()

    def path(self, index: int) -> Path:
        return self.folder / f"chunk_{index:06d}.nc"

    def committed(self) -> set[int]:
        """Indices of the chunk files present (each one complete, by construction)."""
        out = set()
        for f in self.folder.glob("chunk_*.nc"):
            try:
                out.add(int(f.stem.split("_")[1]))
            except (IndexError, ValueError):
                continue
        return {i for i in out if i < self.manifest["chunks"]}

    def commit(self, index: int, res: dict) -> Path:
        """Write chunk ``index`` (a :func:`~rotorkin.sweep.engine.compute_chunk` result),
        streamed and atomically (:func:`rotorkin.sweep.netcdf.write_netcdf3`: no copy of
        the chunk is held while writing)."""
        from rotorkin.sweep.netcdf import write_netcdf3

        n = int(res["stop"] - res["start"])
        violations = res.get("violations", np.zeros(n))
        var = {
            "design": _Var(("design",), np.asarray(res["design"], dtype=np.int32)),
            "reason": _Var(("design",), np.asarray(res["reason"], dtype=np.int16)),
            "violations": _Var(("design",), np.asarray(violations, dtype=np.int16)),
        }
        var.update({f"m:{k}": _Var(("design",), v) for k, v in res["metrics"].items()})
        if "curves" in res:
            angle = np.asarray(res["angle"], dtype=float)
            var["angle"] = _Var(("point",) if angle.ndim == 1 else ("design", "point"), angle)
            var.update({f"c:{k}": _Var(("design", "point"), v) for k, v in res["curves"].items()})
        attrs = {"start": int(res["start"]), "stop": int(res["stop"]), "spec_hash": self.key}
        return write_netcdf3(self.path(index), var, attrs)

    def read(self, index: int) -> dict:
        """A committed chunk back as a result dict (in memory, big-endian; the file is closed)."""
        from scipy.io import netcdf_file

        with netcdf_file(self.path(index), "r", mmap=False) as f:
            var = f.variables
            res = {
                "start": int(f.start),
                "stop": int(f.stop),
                "design": np.array(var["design"][:], dtype=np.int64),
                "reason": np.array(var["reason"][:], dtype=np.int16),
                "violations": np.array(var["violations"][:], dtype=np.int16)
                if "violations" in var
                else np.zeros(int(f.stop) - int(f.start), dtype=np.int16),
                # read into memory (mmap=False) once: views of it, no second copy
                "metrics": {k[2:]: v[:] for k, v in var.items() if k.startswith("m:")},
            }
            if "angle" in var:
                res["angle"] = np.array(var["angle"][:])
                res["curves"] = {k[2:]: v[:] for k, v in var.items() if k.startswith("c:")}
        return res

    def remove(self) -> None:
        """Delete the working folder (after the result is written), and its parent if empty."""
        shutil.rmtree(self.folder, ignore_errors=True)
        with contextlib.suppress(OSError):
            self.folder.parent.rmdir()


def write_dataset(ds, path) -> Path:
    """Write a :class:`~rotorkin.sweep.result.SweepResult` or an :class:`xarray.Dataset` as
    netCDF-3 (64-bit offsets), streamed in blocks and atomically
    (:func:`rotorkin.sweep.netcdf.write_netcdf3`)."""
    from rotorkin.sweep.netcdf import write_netcdf3

    coords = tuple(ds.coords)
    variables = {k: ds.variables[k] for k in (*ds.data_vars, *coords)}
    return write_netcdf3(path, variables, ds.attrs, coords)
