"""Timing helpers shared by the benchmarks (small and stable: other benchmarks import them).

* :func:`best_of` -- best wall time of a few calls;
* :func:`interleaved` -- best times of several functions measured round-robin,
  so that a change of load on a shared machine hits all of them alike and
  their *ratios* stay meaningful;
* :func:`peak_rss` -- peak resident memory of this process;
* :func:`machine` -- cores, CPU, vector instruction sets, numpy/python/numba versions and
  the load average;
* :func:`scaling_probe` -- how much 2 processes gain over 1 here (scalar and SIMD work);
* :func:`write_json` -- write a result file atomically;
* :func:`wobble_vary` -- the `--vary` ranges of the wobble-cam sweep benchmarks;
* :func:`against_study` -- the study's time per design and its largest difference from a
  kernel's values (the like-for-like yardstick of the kernel benchmarks).
"""

from __future__ import annotations

import json
import os
import platform
import resource
import sys
import time
from pathlib import Path

import numpy as np

from rotorkin.core.memory import tune_allocator

#: The allocator the command line runs with (rotorkin.core.memory), for the library and
#: its yardsticks alike: both sides of every ratio are timed in the same process.
ALLOCATOR_TUNED = tune_allocator()

__all__ = [
    "best_of",
    "interleaved",
    "peak_rss",
    "load",
    "machine",
    "vector_isa",
    "git_commit",
    "scaling_probe",
    "write_json",
    "against_study",
]


def best_of(fn, repeat: int = 5) -> float:
    """Smallest wall time of ``repeat`` calls of ``fn()`` [s] (the least disturbed one)."""
    best = float("inf")
    for _ in range(max(1, int(repeat))):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def interleaved(fns: dict, repeat: int = 5, budget: float | None = None, stats=None) -> dict:
    """Best wall time [s] of each function, measured in rounds (each function once per round).

    Parameters
    ----------
    fns : dict of str -> callable
        The functions to time (no arguments).
    repeat : int
        Rounds (at least 1).
    budget : float, optional
        Stop after the round in which the total time passes ``budget`` seconds
        (at least one round is always run).
    stats : dict, optional
        Filled with ``rounds`` (rounds run) and ``seconds`` (their total time).

    Returns
    -------
    dict of str -> float
        Best time of each function [s].
    """
    best = dict.fromkeys(fns, float("inf"))
    start = time.perf_counter()
    names = list(fns)
    for r in range(max(1, int(repeat))):
        # rotate the order so that no function always runs right after the same one
        for name in names[r % len(names) :] + names[: r % len(names)]:
            t0 = time.perf_counter()
            fns[name]()
            best[name] = min(best[name], time.perf_counter() - t0)
        if budget is not None and time.perf_counter() - start > budget:
            break
    if stats is not None:
        stats.update(rounds=r + 1, seconds=time.perf_counter() - start)
    return best


def peak_rss() -> int:
    """Peak resident set size of this process so far [bytes] (Linux: ru_maxrss in KiB)."""
    kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return int(kib) * (1 if sys.platform == "darwin" else 1024)


def user_env(**extra) -> dict:
    """The environment of a command as a user starts it: this one, bytecode cached.

    ``PYTHONDONTWRITEBYTECODE`` (set by some sandboxes and CI images) is dropped: an
    installed package has its ``.pyc`` files, and without them every start compiles
    the library's sources again (0.1-0.3 s of a run). The first, discarded round
    writes them.
    """
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    return {**env, **extra}


def load() -> list:
    """Load average over 1, 5 and 15 minutes (``os.getloadavg``), rounded."""
    return [round(x, 2) for x in os.getloadavg()]


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def vector_isa() -> list:
    """The vector instruction sets of the CPU among avx, avx2, fma, avx512f (``/proc/cpuinfo``)."""
    try:
        text = Path("/proc/cpuinfo").read_text()
    except OSError:
        return []
    for line in text.splitlines():
        if line.startswith("flags"):
            flags = set(line.split(":", 1)[1].split())
            return [f for f in ("avx", "avx2", "fma", "avx512f") if f in flags]
    return []


def _numba_version():
    try:
        import numba
    except ImportError:
        return None
    return numba.__version__


def git_commit():
    """The commit of the working tree (``git rev-parse HEAD``), or None."""
    import subprocess

    try:
        out = subprocess.run(
            ["git", "rev-parse", "HEAD"],
            cwd=Path(__file__).resolve().parent,
            capture_output=True,
            text=True,
            check=True,
        )
    except (OSError, subprocess.CalledProcessError):
        return None
    return out.stdout.strip()


def machine() -> dict:
    """The machine a result was measured on: cores, CPU, vector ISA, memory, versions, load."""
    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:
        usable = os.cpu_count()
    try:
        mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        mem = None
    return {
        "cores": os.cpu_count(),
        "usable_cores": usable,
        "cpu": _cpu_model(),
        "vector_isa": vector_isa(),
        "memory_bytes": mem,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "numba": _numba_version(),
        "platform": platform.platform(),
        "load_average": load(),
        "allocator": "glibc thresholds 32 MiB" if ALLOCATOR_TUNED else "default",
    }


def write_json(path, data) -> Path:
    """Write ``data`` as indented JSON to ``path`` atomically (temporary file + rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(json.dumps(data, indent=2) + "\n")
    os.replace(tmp, path)
    return path


def _probe_work(kind: str, seconds: float, start, done) -> None:
    """Repeat one unit of ``kind`` work from ``start`` for ``seconds``; put the count."""
    v = np.random.default_rng(0).uniform(0.0, 6.0, 8192)
    o = np.empty_like(v)
    rows = np.zeros((8, 10**6)) if kind == "stores" else None
    start.wait()
    t_end, count = time.perf_counter() + seconds, 0
    while time.perf_counter() < t_end:
        if kind == "vector":
            np.tan(v, out=o)
        elif kind == "stores":
            for row in rows:
                row.fill(1.0)
        else:
            x = 0
            for i in range(2000):
                x += i
        count += 1
    done.put(count)


def scaling_probe(seconds: float = 1.0) -> dict:
    """Throughput of 2 processes over 1 on this machine, for three kinds of work.

    ``scalar``: a pure-Python loop; ``vector``: numpy ``tan`` on 8192 doubles (the SIMD
    units, in the cache); ``stores``: filling 8 rows of 1e6 doubles (64 MB, memory
    bandwidth). 2.0 means two cores working fully in parallel; a neighbour's load on the
    second core, or a memory bus one core already fills, give less -- the ceiling of any
    2-thread figure measured in the same spell.
    """
    import multiprocessing as mp

    ctx = mp.get_context("fork")
    out = {}
    for kind in ("scalar", "vector", "stores"):
        rates = []
        for procs in (1, 2):
            start, done = ctx.Barrier(procs), ctx.Queue()
            ps = [ctx.Process(target=_probe_work, args=(kind, seconds, start, done))
                  for _ in range(procs)]  # fmt: skip
            for p in ps:
                p.start()
            total = sum(done.get() for _ in ps)
            for p in ps:
                p.join()
            rates.append(total)
        out[kind] = rates[1] / rates[0]
    return out


#: Wobble-cam sweep grids (plate tilt x roller axis angle x compression ratio) by size.
GRIDS = {10_000: (25, 20, 20), 100_000: (50, 50, 40), 1_000_000: (100, 100, 100)}


def wobble_vary(designs: int) -> dict:
    """``--vary`` ranges of the benchmarks' wobble-cam sweep of about ``designs`` designs."""
    if designs in GRIDS:
        a, b, c = GRIDS[designs]
    else:
        a = b = c = max(1, round(designs ** (1.0 / 3.0)))
    return {
        "drive.plate_tilt": f"30deg:50deg:{a}",
        "drive.roller_axis_angle": f"80deg:100deg:{b}",
        "machine.compression_ratio": f"8:16:{c}",
    }


def against_study(designs, metrics: dict, names, studies: int) -> tuple[float, float]:
    """The first ``studies`` designs through the study: seconds per design, and the largest
    relative difference of the kernel's ``metrics`` from the study's values (over the
    finite, nonzero ones)."""
    from rotorkin.drives import evaluate

    studies = min(int(studies), designs.n)  # no more than the kernel ran
    start = time.perf_counter()
    worst = 0.0
    for i in range(studies):
        summary = evaluate(designs.config(i)).summary
        for name in names:
            want, got = float(summary[name]), float(metrics[name][i])
            if np.isfinite(want) and want != 0.0:
                worst = max(worst, abs(got - want) / abs(want))
    return (time.perf_counter() - start) / max(studies, 1), worst


def report_against_study(path, info: dict, cases: list, label: str, width: int) -> None:
    """Print the kernel-against-study cases (one line each, named by ``case[label]``) under
    the machine's line, and write them with the machine to ``path``."""
    print(f"{info['cpu']} ({', '.join(info['vector_isa']) or 'no AVX'}), numpy "
          f"{info['numpy']}, load {info['load_average']} -> {load()}")  # fmt: skip
    for c in cases:
        print(f"{c[label]:{width}s} {c['designs']:5d} designs x {c['metrics']} metrics: "
              f"{c['wall_s']:.1f} s ({c['ms_per_design']:.1f} ms/design); the study "
              f"{c['study_ms_per_design']:.0f} ms/design: {c['ratio_vs_study']:.1f}x; "
              f"max rel diff {c['max_rel_diff']:.1e}")  # fmt: skip
    write_json(path, {"machine": info, "cases": cases})
