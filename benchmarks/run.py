"""Benchmarks over commits: a short regression gate on ratios, and the full refresh.

::

    python benchmarks/run.py --short                     # < 60 s; exit 1 on a regression
    python benchmarks/run.py --short --update-baseline   # accept the current ratios
    python benchmarks/run.py --full                      # every figure of docs/performance.md

**Short mode** times every drive's kinematics at ``SHORT_POINTS`` points against its
own floor (b') in the same rounds (``bench_kinematics.measure``) and compares three
*ratios* per drive with ``benchmarks/baseline.json``: library / floor (b'), the numpy
fallback / floor (b') and the allocating public call / the allocating floor. A ratio
more than ``--tolerance`` (25 %) above its baseline fails the run (exit 1). Ratios,
not times: both sides of a ratio are measured in the same rounds, so a shared,
loaded machine moves them far less than the times. A different CPU does move them (an
Intel Xeon's transcendental functions cost other multiples of each other than an AMD
EPYC's: the guide bar's ratio is 1.67 on one, 2.43 on the other, for the same code),
so the baseline holds ratios per CPU model and per kernel (``numba`` when the ``fast``
extra is installed, else ``numpy``); a CPU or kernel without a baseline is reported, not
gated. One more row, ``wobble_cam_peaks``, gates the design-space sweep's kernel: the
wobble cam's rotor peaks of :data:`PEAKS_DESIGNS` designs at :data:`PEAKS_ANGLES` angles
(``rotorkin.drives.wobble_cam.fast.rotor_extremes``, each design its own rotor motion)
against its floor (b'): numpy's ``arctan`` of the two arguments a point, in place (the
only transcendental calls a point makes; the angles' ``tan`` is taken once per call).
Each run can be
appended to ``benchmarks/results/history.jsonl`` (``--record``: commit, date, machine,
load, ratios), the record of the figures over commits.

**Full mode** refreshes the absolute figures: ``bench_kinematics.py`` (every drive, 1e4
and 1e6 points), ``bench_sweep.py`` (1e3 and 1e4 designs, like-for-like baseline) and
``bench_latency.py`` (``rotorkin run`` of every example, ``--help``, the import floor),
their result files in ``benchmarks/results/``, and the tables of ``docs/performance.md``
between their ``<!-- bench:... -->`` markers. Best run in a quiet spell: the load
average is recorded with every figure.

Why a small JSON tracker rather than asv or pytest-benchmark: asv builds an
environment per commit and stores absolute times, pytest-benchmark compares absolute
times between runs; on a shared 2-core machine absolute times move by 2x with the
neighbours' load, while the ratio of the library to its floor measured in the same
rounds moves by a few percent. Neither tool gates on such in-run ratios without a
plugin of our own, and both are one more dependency for CI.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import bench_kinematics  # noqa: E402
from _common import git_commit, interleaved, load, machine, write_json  # noqa: E402
from cases import CASES  # noqa: E402

from rotorkin.core.fused import use_compiled  # noqa: E402

BASELINE = HERE / "baseline.json"
HISTORY = HERE / "results" / "history.jsonl"
DOCS = HERE.parent / "docs" / "performance.md"
#: Points of the short mode (above AUTO_MIN_POINTS: the kernel a large evaluation uses).
SHORT_POINTS = 200_000
#: Ratios gated in short mode (all "lower is better").
GATED = ("lib_over_floor", "numpy_over_floor", "alloc_over_floor_alloc")
TOLERANCE = 0.25
#: The row of the sweep's rotor peaks, and its designs x angles (a sweep's own tile).
PEAKS = "wobble_cam_peaks"
PEAKS_DESIGNS, PEAKS_ANGLES = 600, 360


def short(drives=None, rounds: int = 80, budget: float = 6.0, cap: int = 1000,
          echo=print) -> dict:  # fmt: skip
    """``drives`` (default all) at :data:`SHORT_POINTS` points: ratios, load, kernel."""
    t0 = time.perf_counter()
    info = machine()
    start = load()
    rows = {}
    for name in drives or (*CASES, PEAKS):
        if name == PEAKS:
            row = peaks(rounds, budget)
        else:
            row = bench_kinematics.measure(CASES[name], SHORT_POINTS, cap, rounds, budget)
        rows[name] = row
        echo(f"  {name:<18} " + "  ".join(f"{k} {row['ratios'][k]:.2f}" for k in GATED
                                           if k in row["ratios"])
             + f"  (load {row['load_before'][0]:.1f})")  # fmt: skip
    return {
        "points": SHORT_POINTS,
        "kernel": "numba" if use_compiled(SHORT_POINTS) else "numpy",
        "commit": git_commit(),
        "date": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "machine": info,
        "load_start": start,
        "load_end": load(),
        "seconds": time.perf_counter() - t0,
        "ratios": {
            name: {k: row["ratios"][k] for k in GATED if k in row["ratios"]}
            for name, row in rows.items()
        },
        "rows": rows,
    }


def peaks(rounds: int = 80, budget: float = 6.0) -> dict:
    """The sweep's rotor peaks against their floor (b'), timed in the same rounds."""
    import numpy as np

    from rotorkin.drives.wobble_cam import fast

    theta = np.linspace(0.0, 2.0 * np.pi, PEAKS_ANGLES)
    tilt = np.linspace(np.radians(30.0), np.radians(50.0), PEAKS_DESIGNS)
    alpha = np.linspace(np.radians(80.0), np.radians(100.0), PEAKS_DESIGNS)
    points = PEAKS_DESIGNS * PEAKS_ANGLES
    kernel = "numba" if use_compiled(points) else "numpy"
    args = np.random.default_rng(0).uniform(-3.0, 3.0, 2 * points)  # S/(g - C) of both rotors
    work = np.empty_like(args)
    fns = {
        "lib": lambda: fast.rotor_extremes(tilt, alpha, 1.0, theta, kernel=kernel),
        "floor": lambda: np.arctan(args, out=work),
    }
    for fn in fns.values():  # warm-up: compiled loops loaded, pages touched
        fn()
    load0 = load()
    stats = {}
    best = interleaved(fns, rounds, budget, stats)
    ns = {name: t / points * 1e9 for name, t in best.items()}
    return {
        "points": points,
        "designs": PEAKS_DESIGNS,
        "angles": PEAKS_ANGLES,
        "kernel": kernel,
        "rounds": stats["rounds"],
        "ns_per_point": ns,
        "ratios": {"lib_over_floor": ns["lib"] / ns["floor"]},
        "load_before": load0,
        "load_after": load(),
    }


def reference(result: dict, baseline: dict):
    """The baseline ratios of ``result``'s kernel on its CPU model (None: none recorded)."""
    cpu = baseline.get("cpus", {}).get(result["machine"]["cpu"], {})
    return cpu.get("kernels", {}).get(result["kernel"])


def compare(result: dict, baseline: dict, tolerance: float = TOLERANCE) -> list[str]:
    """Regressions: lines ``drive ratio: now vs baseline (+x %)`` past ``tolerance``."""
    ref = reference(result, baseline)
    if ref is None:
        return []
    bad = []
    for name, ratios in result["ratios"].items():
        for key, value in ratios.items():
            base = ref.get(name, {}).get(key)
            if base is not None and value > base * (1.0 + tolerance):
                more, limit = (value / base - 1) * 100, tolerance * 100
                bad.append(f"{name} {key}: {value:.2f} vs baseline {base:.2f} "
                           f"(+{more:.0f} %, limit +{limit:.0f} %)")  # fmt: skip
    return bad


def update_baseline(result: dict, path: Path = BASELINE) -> Path:
    """Store ``result``'s ratios as the baseline of its kernel on its CPU model (others kept)."""
    data = json.loads(path.read_text()) if path.exists() else {}
    data.setdefault("about", "ratios of benchmarks/run.py --short (lower is better), per CPU "
                    "model and kernel")  # fmt: skip
    cpu = data.setdefault("cpus", {}).setdefault(result["machine"]["cpu"], {})
    cpu.setdefault("kernels", {})[result["kernel"]] = result["ratios"]
    cpu.setdefault("recorded", {})[result["kernel"]] = {
        "commit": result["commit"],
        "date": result["date"],
        "points": result["points"],
        "cpu": result["machine"]["cpu"],
        "vector_isa": result["machine"]["vector_isa"],
        "numpy": result["machine"]["numpy"],
        "numba": result["machine"]["numba"],
        "load_start": result["load_start"],
        "load_end": result["load_end"],
    }
    return write_json(path, data)


def record(result: dict, path: Path = HISTORY) -> None:
    """Append the run (without its per-method rows) to the history file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    keep = {k: v for k, v in result.items() if k != "rows"}
    with path.open("a") as f:
        f.write(json.dumps(keep) + "\n")


def _replace_between(text: str, tag: str, body: str) -> str:
    start, end = f"<!-- bench:{tag} -->", f"<!-- /bench:{tag} -->"
    i, j = text.find(start), text.find(end)
    if i < 0 or j < i:
        raise SystemExit(f"{DOCS}: markers {start} ... {end} not found")
    return text[: i + len(start)] + "\n" + body.rstrip() + "\n" + text[j:]


def full(update_docs: bool = True) -> int:
    """Refresh the kinematics, sweep, cycle and latency results and the tables of the docs."""
    py = sys.executable
    kin = HERE / "results" / "kinematics.json"
    sweep = HERE / "results" / "sweep.json"
    subprocess.run([py, str(HERE / "bench_kinematics.py"), "--out", str(kin)], check=True)
    subprocess.run([py, str(HERE / "bench_sweep.py"), "--sizes", "1e3,1e4", "--repeat", "2",
                    "--like-designs", "216", "--out", str(sweep)],
                   check=True)  # fmt: skip
    subprocess.run([py, str(HERE / "bench_sweep.py"), "--cli", "--out", str(sweep)], check=True)
    cycle = HERE / "results" / "cycle.json"
    subprocess.run([py, str(HERE / "bench_cycle.py"), "--out", str(cycle)], check=True)
    latency = HERE / "results" / "latency.json"
    subprocess.run([py, str(HERE / "bench_latency.py"), "--serial", "--out", str(latency)],
                   check=True)  # fmt: skip
    if update_docs:
        write_tables()
    return 0


def write_tables() -> None:
    """Write every ``<!-- bench:TAG -->`` table of docs/performance.md from the result files."""
    text = DOCS.read_text()
    for tag, body in tables().items():
        text = _replace_between(text, tag, body)
    DOCS.write_text(text)
    print(f"updated the tables of {DOCS}")


def tables(results: Path = HERE / "results") -> dict:
    """The markdown of every ``<!-- bench:TAG -->`` table of the docs, from the result files."""
    import bench_latency

    def read(name):
        return json.loads((results / name).read_text())

    sweep = read("sweep.json")
    return {
        "kinematics": bench_kinematics.markdown(read("kinematics.json")),
        "sweep": sweep_markdown(sweep),
        "sweep-cli": sweep_cli_markdown(sweep["cli"]),
        "cycle": cycle_markdown(read("cycle.json")),
        "latency": bench_latency.markdown(read("latency.json")),
    }


def sweep_cli_markdown(cli: dict) -> str:
    """The command line's sweep: peak memory against its result, and the fixed cost."""
    mem, fixed = cli["memory"], cli["fixed_cost"]
    return "\n".join([
        "| command | designs | result MiB | peak RSS MiB | baseline MiB | (peak - baseline) "
        "/ result | wall s |",
        "|---|---:|---:|---:|---:|---:|---:|",
        f"| {mem['command']} | {mem['designs']} | {mem['result_MiB']:.0f} | "
        f"{mem['peak_rss_MiB']:.0f} | {mem['baseline_peak_rss_MiB']:.0f} | "
        f"{mem['rss_over_result']:.2f} | {mem['wall_s']:.1f} |",
        *_own_motions_row(mem),
        "",
        "| command | designs | wall s | compute alone s | fixed s | in the run: compute | "
        "interpreter | imports | spec checks | overview figure | sweep.nc |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        f"| {fixed['command']} | {fixed['designs']} | {fixed['wall_s']:.2f} | "
        f"{fixed.get('compute_alone_s', fixed['compute_s']):.2f} | {fixed['fixed_s']:.2f} | "
        f"{fixed['compute_s']:.2f} | "
        f"{fixed['interpreter_start_s']:.2f} | {fixed['imports_s']:.2f} | "
        f"{fixed['spec_checks_s']:.2f} | {fixed['overview_figure_s']:.2f} | "
        f"{fixed['write_netcdf_s']:.3f} |",
        "",
        f"Load {cli['load_before'][0]:.1f} at start, {cli['load_after'][0]:.1f} at end; "
        f"best of {fixed['rounds']} rounds.",
    ])  # fmt: skip


def _own_motions_row(mem: dict) -> list[str]:
    """The row of the sweep whose designs each have their own rotor motion (if measured)."""
    own = mem.get("own_motions")
    if not own:
        return []
    return [f"| {own['command']} | {own['designs']} | {own['result_MiB']:.0f} | "
            f"{own['peak_rss_MiB']:.0f} | {mem['baseline_peak_rss_MiB']:.0f} | "
            f"{own['rss_over_result']:.2f} | {own['wall_s']:.1f} |"]  # fmt: skip


def cycle_markdown(result: dict) -> str:
    """The fuel-air cycle sweep and its one-by-one yardstick."""
    lines = [
        "| designs | samples | wall s | CPU s | us / design | CPU us / design | peak RSS MiB | "
        "load |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in result["rows"]:
        lines.append(f"| {r['designs']} | {r['samples']} | {r['wall_s']:.1f} | {r['cpu_s']:.1f} | "
                     f"{r['us_per_design']:.0f} | {r['cpu_us_per_design']:.0f} | "
                     f"{r['peak_rss_MiB']:.0f} | {r['load_before'][0]:.1f}-"
                     f"{r['load_after'][0]:.1f} |")  # fmt: skip
    one = result["one_by_one"]
    lines += [
        "",
        f"Like for like, {one['designs']} designs one by one through the study's cycle path: "
        f"{one['cycle_path_numba_us_per_design']:.0f} us per design with the compiled cycle "
        f"({one['speedup_vs_cycle_path_numba']:.0f}x the sweep's time per design), "
        f"{one['cycle_path_numpy_us_per_design']:.0f} us with the numpy one "
        f"({one['speedup_vs_cycle_path_numpy']:.0f}x); the whole study "
        f"{one['study_us_per_design'] / 1e3:.0f} ms per design ({one['study_designs']} designs). "
        f"The sweep's cycle metrics against the study's: largest relative difference "
        f"{one['max_rel_diff_vs_study']:.1e}.",
    ]
    return "\n".join(lines)


def sweep_markdown(result: dict) -> str:
    """The sweep result as the markdown table of docs/performance.md."""
    like = result["like_for_like"]
    lines = [
        "| designs | samples | compute s | us / design | CPU us / design | peak RSS MiB | load |",
        "|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in result["rows"]:
        lines.append(f"| {r['designs']} | {r['angles']} | {r['compute_s']:.2f} | "
                     f"{r['compute_us_per_design']:.0f} | {r['cpu_us_per_design']:.0f} | "
                     f"{r['peak_rss_MiB']:.0f} | {result['load_before'][0]:.1f}-"
                     f"{result['load_after'][0]:.1f} |")  # fmt: skip
    lines += [
        "",
        f"Like for like ({like['samples']} samples per design on both sides): the sweep "
        f"{like['sweep_us_per_design']:.0f} us per design ({like['designs']} designs; CPU "
        f"{like['sweep_cpu_us_per_design']:.0f} us), the study one design at a time "
        f"{like['one_by_one_us_per_design']:.0f} us (CPU {like['one_by_one_cpu_us_per_design']:.0f}"
        f" us): **{like['speedup_like_for_like']:.0f}x wall, "
        f"{like['speedup_like_for_like_cpu']:.0f}x CPU**.",
    ]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--short", action="store_true", help="regression gate on ratios (< 60 s)")
    mode.add_argument("--full", action="store_true", help="refresh every figure (minutes)")
    mode.add_argument("--tables", action="store_true",
                      help="only write the docs' tables from the result files")  # fmt: skip
    ap.add_argument("--update-baseline", action="store_true", help="store the ratios as baseline")
    ap.add_argument("--record", action="store_true", help=f"append the run to {HISTORY.name}")
    ap.add_argument("--tolerance", type=float, default=TOLERANCE, help="allowed ratio increase")
    ap.add_argument("--baseline", type=Path, default=BASELINE, help="baseline file")
    ap.add_argument("--out", type=Path, default=HERE / "results" / "short.json")
    ap.add_argument("--no-docs", action="store_true", help="--full: leave the docs as they are")
    args = ap.parse_args(argv)
    if args.full:
        return full(update_docs=not args.no_docs)
    if args.tables:
        write_tables()
        return 0
    print(f"short benchmark: every drive at {SHORT_POINTS} points, the sweep's rotor peaks at "
          f"{PEAKS_DESIGNS} x {PEAKS_ANGLES}, ratios to floor (b')")  # fmt: skip
    result = short()
    write_json(args.out, result)
    if args.record:
        record(result)
    print(f"kernel {result['kernel']}, {result['seconds']:.0f} s, load {result['load_start']} "
          f"-> {result['load_end']}")  # fmt: skip
    if args.update_baseline:
        path = update_baseline(result, args.baseline)
        print(f"baseline of kernel {result['kernel']} written to {path}")
        return 0
    baseline = json.loads(args.baseline.read_text()) if args.baseline.exists() else {}
    if reference(result, baseline) is None:
        print(f"no baseline for kernel {result['kernel']} on {result['machine']['cpu']} in "
              f"{args.baseline}: not gated")  # fmt: skip
        return 0
    bad = compare(result, baseline, args.tolerance)
    if bad:  # measured once more, the better of the two kept (noise only ever adds time)
        again = sorted({line.split()[0] for line in bad})
        print("measuring again:", ", ".join(again))
        second = short(again)
        for name in again:
            for key, value in second["ratios"][name].items():
                result["ratios"][name][key] = min(result["ratios"][name][key], value)
        bad = compare(result, baseline, args.tolerance)
    for line in bad:
        print("REGRESSION", line)
    print("ratios within tolerance of the baseline" if not bad else f"{len(bad)} regression(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
