"""Throughput of every drive's kinematics against its own floor (b') and a scalar port.

For each drive (:mod:`cases`: wobble cam, eccentric cam, guide bar, non-circular
gears, rhomboid cam) and each size, every method is timed round-robin in the same
rounds (``_common.interleaved``, best of the rounds), so that the *ratios* are
measured side by side under the same load:

* ``lib`` -- the library's kinematics on 1 thread into preallocated arrays (kernel
  as installed: numba's compiled loops when the ``fast`` extra is, else numpy);
  ``lib_numpy`` the numpy fallback; ``lib_2t`` 2 threads (from 65536 points on, where
  the library shares the blocks between threads); ``lib_alloc`` the public call, which
  allocates its results;
* ``floor`` -- **floor (b')**: exactly the transcendental calls the drive's closed form
  makes (numpy, precomputed realistic arguments) plus writing its outputs, into
  preallocated arrays; ``floor_2t`` on 2 threads; ``floor_alloc`` allocating its
  output on each call (the yardstick of ``lib_alloc``);
* ``scalar`` -- the per-point baseline: the fastest reasonable scalar port
  (:mod:`scalar_ports`: ``math`` functions, constants hoisted), timed on at most
  ``--cap`` points and extrapolated per point (its cost per point does not depend on N).

Each row records the load average before and after its timing; the file records the
machine (CPU model, vector ISA from /proc/cpuinfo, numpy and numba versions) and the
load at start and end.

Run from the repository root::

    python benchmarks/bench_kinematics.py                       # 1e4 and 1e6 points, all drives
    python benchmarks/bench_kinematics.py --drives wobble_cam --sizes 1e5 --out /tmp/k.json
    python benchmarks/bench_kinematics.py --markdown benchmarks/results/kinematics.json
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import interleaved, load, machine, peak_rss, scaling_probe, write_json  # noqa: E402
from cases import CASES  # noqa: E402

from rotorkin.core.fused import MIN_PARALLEL, numba_available, use_compiled  # noqa: E402

DEFAULT_OUT = Path(__file__).resolve().parent / "results" / "kinematics.json"
COMMAND = "python benchmarks/bench_kinematics.py"
#: Targets at 1e6 points: library within 2x of floor (b') on one thread, 2 threads >= 1.8x.
TARGET_FLOOR, TARGET_SCALING, TARGET_SIZE = 2.0, 1.8, 10**6

YARDSTICKS = {
    "lib_over_floor": "library (1 thread, preallocated outputs) / floor (b')",
    "lib2_over_floor2": "library on 2 threads / floor (b') on 2 threads",
    "alloc_over_floor_alloc": "public call (allocates) / floor (b') allocating its outputs",
    "numpy_over_floor": "numpy fallback / floor (b')",
    "numpy_over_lib": "numpy fallback / library (the compiled loops' gain)",
    "scaling_lib": "library 1 thread / library 2 threads",
    "scaling_floor": "floor (b') 1 thread / floor (b') 2 threads (what this machine allows)",
    "scalar_over_lib": "scalar per-point port / library (1 thread)",
}


def measure(case, size: int, cap: int, rounds: int, budget: float) -> dict:
    """Best times of every method of ``case`` at ``size`` points, ratios, load."""
    fns, scalar_points = case.methods(size, cap)
    if size < MIN_PARALLEL:  # the library runs 1 thread below this: no 2-thread figures
        del fns["lib_2t"], fns["floor_2t"]
    for fn in fns.values():  # warm-up: compiled loops loaded, pages touched
        if fn is not fns["scalar"]:
            fn()
    load0 = load()
    stats = {}
    best = interleaved(fns, rounds, budget, stats)
    ns = {name: t / size * 1e9 for name, t in best.items()}
    ns["scalar"] = best["scalar"] / scalar_points * 1e9
    two = "lib_2t" in ns
    ratios = {
        "lib_over_floor": ns["lib"] / ns["floor"],
        "lib2_over_floor2": ns["lib_2t"] / ns["floor_2t"] if two else None,
        "alloc_over_floor_alloc": ns["lib_alloc"] / ns["floor_alloc"],
        "numpy_over_floor": ns["lib_numpy"] / ns["floor"],
        "numpy_over_lib": ns["lib_numpy"] / ns["lib"],
        "scaling_lib": ns["lib"] / ns["lib_2t"] if two else None,
        "scaling_floor": ns["floor"] / ns["floor_2t"] if two else None,
        "scalar_over_lib": ns["scalar"] / ns["lib"],
    }
    return {
        "points": size,
        "kernel": "numba" if use_compiled(size) else "numpy",
        "scalar_timed_on": scalar_points,
        "rounds": stats["rounds"],
        "ns_per_point": ns,
        "ratios": ratios,
        "load_before": load0,
        "load_after": load(),
    }


COLUMNS = (
    # header, format, getter
    ("points", None, lambda r: f"1e{round(math.log10(r['points']))}"),
    ("kernel", None, lambda r: r["kernel"]),
    ("floor b' ns", ".2f", lambda r: r["ns_per_point"]["floor"]),
    ("lib ns", ".2f", lambda r: r["ns_per_point"]["lib"]),
    ("lib/b'", ".2f", lambda r: r["ratios"]["lib_over_floor"]),
    ("numpy/b'", ".2f", lambda r: r["ratios"]["numpy_over_floor"]),
    ("alloc/b' alloc", ".2f", lambda r: r["ratios"]["alloc_over_floor_alloc"]),
    ("lib 2t/b' 2t", ".2f", lambda r: r["ratios"]["lib2_over_floor2"]),
    ("scaling lib", ".2f", lambda r: r["ratios"]["scaling_lib"]),
    ("scaling b'", ".2f", lambda r: r["ratios"]["scaling_floor"]),
    ("scalar ns", ".0f", lambda r: r["ns_per_point"]["scalar"]),
    ("scalar/lib", ".0f", lambda r: r["ratios"]["scalar_over_lib"]),
    ("load", None, lambda r: f"{r['load_before'][0]:.1f}-{r['load_after'][0]:.1f}"),
)


def _cells(row):
    cells = []
    for _, fmt, get in COLUMNS:
        value = get(row)
        cells.append("-" if value is None else value if fmt is None else f"{value:{fmt}}")
    return cells


def text_table(rows) -> str:
    """Rows as aligned text."""
    table = [[h for h, *_ in COLUMNS]] + [_cells(r) for r in rows]
    widths = [max(len(line[i]) for line in table) for i in range(len(COLUMNS))]
    return "\n".join("  ".join(c.rjust(w) for c, w in zip(line, widths, strict=True))
                     for line in table)  # fmt: skip


def markdown(result) -> str:
    """A result file as the markdown tables of ``docs/performance.md`` (one per drive)."""
    out = []
    for name, case in result["cases"].items():
        out.append(f"**{name}** -- {case['title']}; floor (b'): {case['transcendentals']} + "
                   f"{case['outputs']} outputs per point\n")  # fmt: skip
        out.append("| " + " | ".join(h for h, *_ in COLUMNS) + " |")
        out.append("|" + "---:|" * len(COLUMNS))
        out.extend("| " + " | ".join(_cells(r)) + " |" for r in case["rows"])
        out.append("")
    return "\n".join(out)


def targets(result) -> dict:
    """The targets at 1e6 points, per drive: lib/floor (b') <= 2, 2-thread scaling >= 1.8."""
    out = {}
    for name, case in result["cases"].items():
        row = next((r for r in case["rows"] if r["points"] == TARGET_SIZE), None)
        if row is None:
            continue
        r = row["ratios"]
        out[name] = {
            "lib_over_floor": r["lib_over_floor"],
            "within_2x_of_floor": r["lib_over_floor"] <= TARGET_FLOOR,
            "scaling_lib": r["scaling_lib"],
            "scaling_floor": r["scaling_floor"],
            "scaling_at_least_1_8": r["scaling_lib"] >= TARGET_SCALING,
        }
    return out


def run(drives, sizes, cap, rounds, budget, echo=print) -> dict:
    """Measure ``drives`` at ``sizes``; the result dict (also written by :func:`main`)."""
    t0 = time.perf_counter()
    info = machine()
    load_start = load()
    echo(f"kinematics throughput; {info['cpu']}, {info['usable_cores']} cores, ISA "
         f"{','.join(info['vector_isa']) or '-'}, numpy {info['numpy']}, numba {info['numba']}; "
         f"load {load_start}")  # fmt: skip
    probe_start = scaling_probe()
    echo("2 processes / 1 on this machine now: " + ", ".join(f"{k} {v:.2f}x" for k, v in
                                                             probe_start.items()))  # fmt: skip
    cases = {}
    for name in drives:
        case = CASES[name]
        agree = case.agreement()
        echo(f"\n{name}: {case.title}\n  floor (b'): {case.transcendentals} + "
             f"{case.outputs} outputs per point; agreement: "
             + ", ".join(f"{k} {v:.2g}" for k, v in agree.items()))  # fmt: skip
        rows = []
        for size in sizes:
            rows.append(measure(case, size, cap, rounds, budget))
            gc.collect()
        echo(text_table(rows))
        cases[name] = {
            "title": case.title,
            "design": case.design,
            "outputs": case.outputs,
            "transcendentals": case.transcendentals,
            "agreement": agree,
            "rows": rows,
        }
    result = {
        "benchmark": "kinematics of every drive against floor (b') and a scalar port",
        "machine": info,
        "numba_installed": numba_available(),
        "load_start": load_start,
        "load_end": load(),
        "scaling_probe": {"start": probe_start, "end": scaling_probe()},
        "yardsticks": YARDSTICKS,
        "cases": cases,
        "peak_rss_bytes": peak_rss(),
        "wall_seconds": time.perf_counter() - t0,
    }
    result["targets"] = targets(result)
    return result


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--drives", default=",".join(CASES), help="comma-separated drives")
    ap.add_argument("--sizes", default="1e4,1e6", help="comma-separated point counts")
    ap.add_argument("--cap", type=float, default=2e4, help="most points timed for the scalar port")
    ap.add_argument("--budget", type=float, default=20.0, help="seconds of timing per size")
    ap.add_argument("--rounds", type=int, default=40, help="most rounds per size")
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT, help="JSON result file")
    ap.add_argument("--markdown", type=Path, help="only print this result file as markdown")
    args = ap.parse_args(argv)
    if args.markdown is not None:
        print(markdown(json.loads(args.markdown.read_text())))
        return 0
    drives = [d.strip() for d in args.drives.split(",") if d.strip()]
    unknown = [d for d in drives if d not in CASES]
    if unknown:
        ap.error(f"unknown drive(s) {', '.join(unknown)}; known: {', '.join(CASES)}")
    sizes = [int(float(s)) for s in args.sizes.split(",") if s.strip()]
    result = run(drives, sizes, int(args.cap), args.rounds, args.budget)
    result["command"] = " ".join([COMMAND, *(sys.argv[1:] if argv is None else argv)])
    for name, t in result["targets"].items():
        print(f"{name} at 1e6: lib/floor(b') {t['lib_over_floor']:.2f} (<= {TARGET_FLOOR}: "
              f"{'met' if t['within_2x_of_floor'] else 'NOT met'}); 2-thread scaling "
              f"{t['scaling_lib']:.2f} (>= {TARGET_SCALING}: "
              f"{'met' if t['scaling_at_least_1_8'] else 'NOT met'}; the floor itself scales "
              f"{t['scaling_floor']:.2f})")  # fmt: skip
    path = write_json(args.out, result)
    print(f"load at start {result['load_start']}, at end {result['load_end']}; "
          f"peak RSS {peak_rss() / 2**20:.0f} MiB; wrote {path}")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
