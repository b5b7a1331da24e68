"""Helpers shared by the sweep kernels: a batch of designs, sample grids, blocked evaluation.

A drive's *batch* module (``rotorkin/drives/<name>/sweep.py``) computes the summary
metrics of many designs at once by broadcasting: per-design values are arrays of shape ``(n,)`` (or
``(n, 1)`` against the shaft-angle axis), values that do not vary are scalars.
"""

from __future__ import annotations

import contextlib
import copy
import dataclasses
import math
import os
from concurrent.futures import ThreadPoolExecutor
from contextvars import ContextVar

import numpy as np

__all__ = [
    "Designs",
    "full",
    "distinct",
    "DEFAULT_SAMPLES",
    "BLOCK_ELEMENTS",
    "sample_grid",
    "run_blocks",
    "flag",
    "block_progress",
    "number",
    "refuse_first",
]

#: Samples per period of the sampled peaks: the studies' ``_PEAK_SAMPLES``.
DEFAULT_SAMPLES = 20_001
#: Elements (designs x samples) per block of the sampled curves: a few MB, cache-friendly.
BLOCK_ELEMENTS = 1 << 16


class Designs:
    """``n`` designs: the swept keys as arrays, every other key from the base config.

    Parameters
    ----------
    cfg : dict
        Validated base config (SI values).
    table : dict of str -> ndarray, shape (n,)
        Config key (``"drive.plate_tilt"``) -> the designs' values (SI floats,
        ints, or strings for choice keys).
    n : int
        Number of designs.
    extra : dict, optional
        Values that are not config keys (e.g. a manufactured piston width held
        fixed by the tolerance analysis).
    """

    def __init__(self, cfg: dict, table: dict, n: int, extra: dict | None = None):
        self.cfg = cfg
        self.table = {k: np.asarray(v) for k, v in table.items()}
        self.n = int(n)
        self.extra = dict(extra or {})

    def __getitem__(self, key: str):
        """The designs' values of ``key``: an array (n,) if it varies, else the base scalar."""
        if key in self.table:
            return self.table[key]
        section, _, name = key.partition(".")
        return self.cfg.get(section, {}).get(name)

    def varies(self, key: str) -> bool:
        """Whether ``key`` differs between designs (it is in the table)."""
        return key in self.table

    def float(self, key: str):
        """``self[key]`` as float (array or scalar)."""
        value = self[key]
        return value.astype(float) if isinstance(value, np.ndarray) else float(value)

    def take(self, index) -> Designs:
        """The designs at ``index`` (integer array or boolean mask)."""
        index = np.asarray(index)
        n = int(np.count_nonzero(index)) if index.dtype == bool else index.size
        return Designs(self.cfg, {k: v[index] for k, v in self.table.items()}, n, self.extra)

    def config(self, i: int) -> dict:
        """The validated config (SI) of design ``i``."""
        cfg = _copied(self.cfg)
        for key, values in self.table.items():
            section, _, name = key.partition(".")
            value = values[i]
            cfg.setdefault(section, {})[name] = value.item() if hasattr(value, "item") else value
        return cfg


def _copied(value):
    """A deep copy of a config: its dicts, lists and arrays copied, numbers and strings
    shared (as :func:`copy.deepcopy` does, several times faster); other objects deep-copied."""
    kind = type(value)
    if kind is dict:
        return {k: _copied(v) for k, v in value.items()}
    if kind is list:
        return [_copied(v) for v in value]
    if kind is tuple:
        return tuple(_copied(v) for v in value)
    if kind in (float, int, str, bool) or value is None:
        return value
    return copy.deepcopy(value)


def full(value, n: int, dtype=float) -> np.ndarray:
    """``value`` (scalar or (n,)) broadcast to a fresh array of shape (n,)."""
    return np.array(np.broadcast_to(np.asarray(value, dtype=dtype), (n,)))


def distinct(columns, n: int) -> tuple[list[np.ndarray], np.ndarray]:
    """The distinct rows of per-design values, and which of them each design is.

    ``columns``: scalars or arrays (n,) (e.g. a drive's plate tilt and roller axis
    angle). Returns the columns of the m distinct rows, arrays (m,), and ``inverse``
    (n,) with ``column[i] == row[inverse[i]]``: work on the m rows, then index the
    results with ``inverse``. Values are compared bit for bit (``-0.0`` is not ``0.0``;
    a NaN is the same NaN only with its bits). Each column's values are numbered by one
    sort; a row is the tuple of its numbers, counted without a sort where there are at
    most ``max(4 n, _DIRECT_CODES)`` tuples (a byte and an index per tuple).
    """
    arrays = [np.asarray(c, dtype=float) for c in columns]
    numbered = {}  # column -> (its sorted distinct bit patterns, each design's number)
    for k, a in enumerate(arrays):
        if a.ndim == 0:
            continue
        bits = np.ascontiguousarray(np.broadcast_to(a, (n,))).view(np.int64)
        v = np.sort(bits)
        v = v[np.concatenate(([True], v[1:] != v[:-1]))]
        if v.size == n:  # every row differs
            return [np.array(np.broadcast_to(a, (n,))) for a in arrays], np.arange(n)
        numbered[k] = (v, np.searchsorted(v, bits) if v.size > 1 else None)
    used = [k for k, (v, d) in numbered.items() if d is not None]
    sizes = [numbered[k][0].size for k in used]
    if not used:  # one row
        return [a.reshape(-1)[:1].copy() for a in arrays], np.zeros(n, dtype=np.intp)
    if math.prod(sizes) <= max(_DIRECT_CODES, 4 * n):
        code = np.ravel_multi_index([numbered[k][1] for k in used], sizes)
        present = np.zeros(math.prod(sizes), dtype=bool)
        present[code] = True
        keys = np.flatnonzero(present)
        number = np.zeros(present.size, dtype=np.intp)
        number[keys] = np.arange(keys.size)
        row_digits = dict(zip(used, np.unravel_index(keys, sizes), strict=True))
        out = [numbered[k][0][row_digits[k]].view(float) if k in row_digits
               else np.full(keys.size, a.reshape(-1)[0]) for k, a in enumerate(arrays)]  # fmt: skip
        return out, number[code]
    code = np.zeros(n, dtype=np.int64)
    for k, size in zip(used, sizes, strict=True):  # numbered afresh after each column
        code = np.unique(code * size + numbered[k][1], return_inverse=True)[1].reshape(-1)
    _, first, inverse = np.unique(code, return_index=True, return_inverse=True)
    out = [np.broadcast_to(a, (n,))[first].copy() for a in arrays]
    return out, inverse.reshape(-1).astype(np.intp, copy=False)


#: Row codes up to which :func:`distinct` counts rows directly, at least (beyond 4 n).
_DIRECT_CODES = 1 << 20


def sample_grid(period, samples: int) -> np.ndarray:
    """``samples`` angles from 0 to ``period`` inclusive, exactly as ``numpy.linspace``.

    ``period`` may be an array ``(n, 1)`` (one period per design): the result is
    then ``(n, samples)`` with every row equal to ``np.linspace(0, period_i, samples)``.
    """
    samples = int(samples)
    period = np.asarray(period, dtype=float)
    if period.ndim == 0:
        return np.linspace(0.0, float(period), samples)
    grid = np.arange(samples, dtype=float) * (period / (samples - 1))
    grid[..., -1] = period[..., 0]
    return grid


#: ``callable(designs)`` told of each finished block of :func:`run_blocks` (progress bars).
_BLOCK_DONE: ContextVar = ContextVar("rotorkin_sweep_block_done", default=None)


@contextlib.contextmanager
def block_progress(callback):
    """Within the block, :func:`run_blocks` calls ``callback(designs)`` after each block.

    Called from the thread that called :func:`run_blocks`, in design order; the
    counts of one kernel call add up to at most its designs (a drive with several
    spin ratios runs a call per ratio, on a subset each).
    """
    token = _BLOCK_DONE.set(callback)
    try:
        yield
    finally:
        _BLOCK_DONE.reset(token)


def block_size(samples: int) -> int:
    """Designs per block so that a block holds about :data:`BLOCK_ELEMENTS` samples."""
    return max(1, BLOCK_ELEMENTS // max(int(samples), 1))


def run_blocks(fn, n: int, samples: int, threads: int | None = None) -> dict:
    """Evaluate ``fn(lo, hi) -> dict of (hi - lo,) arrays`` over blocks of designs.

    The blocks run on a thread pool (numpy releases the GIL in its loops); the
    results are stitched in design order, so they do not depend on ``threads``.
    """
    size = block_size(samples)
    bounds = [(lo, min(lo + size, n)) for lo in range(0, n, size)]
    if not bounds:
        return {}
    threads = (os.cpu_count() or 1) if threads is None else max(1, int(threads))
    done = _BLOCK_DONE.get()
    parts = []
    if threads == 1 or len(bounds) == 1:
        for lo, hi in bounds:
            parts.append(fn(lo, hi))
            if done is not None:
                done(hi - lo)
    else:
        with ThreadPoolExecutor(max_workers=min(threads, len(bounds))) as pool:
            for (lo, hi), part in zip(bounds, pool.map(lambda b: fn(*b), bounds), strict=True):
                parts.append(part)
                if done is not None:
                    done(hi - lo)
    out = {}
    for name in parts[0]:
        first = np.asarray(parts[0][name])
        arr = np.empty((n, *first.shape[1:]), dtype=first.dtype)
        for (lo, hi), part in zip(bounds, parts, strict=True):
            arr[lo:hi] = part[name]
        out[name] = arr
    return out


def flag(reason: np.ndarray, bad, code: int) -> None:
    """Set ``reason`` to ``code`` where ``bad`` and no earlier check failed (in place)."""
    bad = np.broadcast_to(np.asarray(bad, dtype=bool), reason.shape)
    reason[(reason == 0) & bad] = code


def number(value):
    """A float for one design, an array of floats for a column of designs."""
    return float(value) if np.ndim(value) == 0 else np.asarray(value, dtype=float)


def refuse_first(params, codes) -> None:
    """Refuse a parameter dataclass holding arrays of designs if any design is refused.

    ``codes`` (the dataclass's vectorised ``violation``, 0 where admissible) has the
    designs' shape; the first refused design is built alone, so the error raised is the
    one the dataclass gives that design (its field, value and admissible range).
    """
    codes = np.asarray(codes)
    bad = np.flatnonzero(codes)
    if not bad.size:
        return
    at = np.unravel_index(bad[0], codes.shape)

    def one(value):
        if np.ndim(value) == 0 or isinstance(value, (tuple, list)):
            return value
        picked = np.broadcast_to(value, codes.shape)[at]
        return picked.item() if hasattr(picked, "item") else picked

    type(params)(**{f.name: one(getattr(params, f.name)) for f in dataclasses.fields(params)})
    raise AssertionError("a refused design was admitted on its own")  # pragma: no cover
