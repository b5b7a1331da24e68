"""Benchmark: the million-design wobble-cam sweep on a 2-worker dask LocalCluster vs locally.

    python benchmarks/bench_dask.py                      # 1e6 designs, 2 workers (about 10 minutes)
    python benchmarks/bench_dask.py --designs 1e5        # the target's size (about 1.5 minutes)
    python benchmarks/bench_dask.py --help

The sweep of ``bench_sweep.py`` (plate tilt x roller axis angle x compression
ratio, ``--angles`` shaft angles per design) runs

* locally: :func:`rotorkin.sweep.execute`, the kernels on ``--workers`` threads;
* on dask: a LocalCluster of ``--workers`` single-thread worker processes,
  one task per chunk (:func:`rotorkin.sweep.engine.compute_chunk`), the
  results gathered by the client as they finish.

Both are timed interleaved (best of ``--repeat`` rounds, after a warm-up run
on the cluster); the cluster's start-up is timed apart. The two Datasets must
be identical (every variable, bit for bit); the overhead is the dask time
minus the local time, absolute and per chunk.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import interleaved, load, machine, peak_rss, wobble_vary, write_json  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--designs", default="1e6", help="designs (1e4, 1e5, 1e6 or any cube)")
    ap.add_argument("--angles", type=int, default=360, help="shaft angles per design")
    ap.add_argument("--workers", type=int, default=2, help="dask workers (and local threads)")
    ap.add_argument("--repeat", type=int, default=2, help="interleaved rounds (best kept)")
    ap.add_argument("--out", default=str(Path(__file__).parent / "results" / "dask.json"))
    args = ap.parse_args()

    from rotorkin.io.config import load_config
    from rotorkin.sweep import build_spec, execute
    from rotorkin.sweep.dask import local_client

    designs = int(float(args.designs))
    _, raw, _ = load_config(None, "wobble-cam-engine")
    spec = build_spec(raw, wobble_vary(designs), samples=args.angles)
    warm = build_spec(raw, wobble_vary(8), samples=args.angles)
    execute(warm, progress=False, threads=args.workers)
    load_before = load()
    t0 = time.perf_counter()
    with local_client(args.workers) as client:
        startup = time.perf_counter() - t0
        execute(warm, client=client, progress=False)  # workers import rotorkin
        results = {}

        def local():
            results["local"] = execute(spec, progress=False, threads=args.workers)

        def dask():
            results["dask"] = execute(spec, client=client, progress=False)

        best = interleaved({"local": local, "dask": dask}, repeat=args.repeat)
    a, b = results["local"], results["dask"]
    identical = all(np.array_equal(a[v].values, b[v].values, equal_nan=True) for v in a.variables)
    overhead = best["dask"] - best["local"]
    row = {
        "designs": spec.size,
        "angles": args.angles,
        "workers": args.workers,
        "chunks": spec.n_chunks,
        "chunk_size": spec.chunk_size,
        "local_s": best["local"],
        "dask_s": best["dask"],
        "dask_over_local": best["dask"] / best["local"],
        "overhead_s": overhead,
        "overhead_ms_per_chunk": overhead / spec.n_chunks * 1e3,
        "cluster_startup_s": startup,
        "identical": bool(identical),
        "peak_rss_client_MiB": peak_rss() / 2**20,
        "load_before": load_before,
        "load_after": load(),
    }
    print(
        f"{row['designs']} designs x {row['angles']} angles, {row['chunks']} chunks: local "
        f"{row['local_s']:.2f} s, dask ({args.workers} workers) {row['dask_s']:.2f} s, "
        f"ratio {row['dask_over_local']:.3f}, overhead {overhead:+.2f} s "
        f"({row['overhead_ms_per_chunk']:+.1f} ms/chunk); cluster start-up "
        f"{startup:.2f} s; identical: {identical}; load {load_before} -> {row['load_after']}"
    )
    cmdline = "python benchmarks/bench_dask.py " + " ".join(sys.argv[1:])
    write_json(args.out, {"benchmark": "dask", "command": cmdline.strip(), "machine": machine(),
                          "row": row})  # fmt: skip
    print(f"wrote {args.out}")
    if not identical:
        sys.exit("the dask result differs from the local one")


if __name__ == "__main__":
    main()
