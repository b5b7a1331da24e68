"""The C allocator's thresholds for array work, and memory handed back to the system.

numpy takes the memory of each array from the C library's ``malloc``. glibc serves a
block above its mmap threshold (128 KiB to begin with) by mapping fresh pages from the
system and unmaps them when the array is freed, so a loop of array operations on
blocks of a few megabytes -- the shape of every batch evaluation here: designs x
angles, block by block -- faults every page of every temporary in again. With the
threshold raised to :data:`THRESHOLD` those temporaries come from the heap and are
reused: batch sweeps run 2-3.5x faster on the 2-core reference machine (two drives'
batch kernels, 1000 designs; docs/performance.md), at the cost of keeping up to
:data:`THRESHOLD` of freed memory in the process.

The command line sets the thresholds when it starts (the process is its own); a
program that embeds rotorkin may call :func:`tune_allocator` itself. Nothing happens
outside glibc (macOS, Windows, musl) or with ``ROTORKIN_ALLOCATOR=default`` in the
environment.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import functools
import os

__all__ = ["THRESHOLD", "tune_allocator", "release_memory"]

#: mmap and trim thresholds set by :func:`tune_allocator` [bytes]: 32 MiB (64 and 256 MiB
#: measured no faster on the sweeps above).
THRESHOLD = 32 * 2**20

# mallopt parameters (malloc.h)
_M_TRIM_THRESHOLD = -1
_M_MMAP_THRESHOLD = -3


@functools.cache
def _libc():
    """glibc, or None elsewhere."""
    try:
        name = ctypes.util.find_library("c") or "libc.so.6"
        libc = ctypes.CDLL(name)
        libc.mallopt, libc.malloc_trim  # noqa: B018 - glibc's own functions, or AttributeError
    except (OSError, AttributeError):
        return None
    return libc


def tune_allocator(threshold: int = THRESHOLD) -> bool:
    """Raise glibc's mmap and trim thresholds to ``threshold`` bytes (once per process).

    Parameters
    ----------
    threshold : int
        New mmap and trim thresholds [bytes].

    Returns
    -------
    bool
        Whether the thresholds were set (False outside glibc, or with
        ``ROTORKIN_ALLOCATOR=default``).
    """
    if os.environ.get("ROTORKIN_ALLOCATOR", "").strip().lower() == "default":
        return False
    libc = _libc()
    if libc is None:
        return False
    ok = libc.mallopt(_M_MMAP_THRESHOLD, int(threshold)) == 1
    return bool(libc.mallopt(_M_TRIM_THRESHOLD, int(threshold)) == 1 and ok)


def release_memory() -> None:
    """Hand the heap's free memory back to the system (glibc's ``malloc_trim``; else nothing)."""
    libc = _libc()
    if libc is not None:
        libc.malloc_trim(0)
