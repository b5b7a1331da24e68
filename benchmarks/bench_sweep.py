"""Benchmark: a million-design wobble-cam sweep, time, peak memory and time per design.

    python benchmarks/bench_sweep.py                    # 1e4, 1e5, 1e6 designs (a few minutes)
    python benchmarks/bench_sweep.py --sizes 1e4,1e5    # quick look
    python benchmarks/bench_sweep.py --help

The sweep: plate tilt (30 ... 50 deg) x roller axis angle (80 ... 100 deg) x
compression ratio (8 ... 16), ``--angles`` shaft angles per design (default
360), through :func:`rotorkin.sweep.run_sweep`'s two steps, timed apart:
``build_spec`` (validating the spec: units, the admissibility scan of the grid,
one scalar study run of an admissible design) and ``execute`` (the computation).
Every design gets every metric of the wobble kernel (67): the 53 default ones
-- closed forms of the paper (slider and chamber angle extremes eq. 17-23, the
eq. 20 tilt limit, piston width eq. 21, compression ratios, volumes,
displacement, cycle pressures and work) -- and the 12 opt-in ``sampled_*``
ones, for which *every kinematic curve is evaluated per design and shaft angle*
(the design x angle array, in cache-sized blocks on all cores): both rotor
angles (an ``arctan`` each) and their first, second and third derivatives, the
slider angle, the chamber angles of both kinds and the chamber volumes, reduced
to their extremes, the rotors' speed-ratio extremes and the peaks of
acceleration and jerk. Results stay in memory (no store).

Memory: each size runs once in a fresh process (its own peak RSS, measured with
``resource.getrusage``; the results, 8 bytes per design and metric, included).
Time: all sizes in one process, interleaved (each size once per round, the
best of ``--repeat`` rounds kept), so that a change of load hits them alike.

Baseline, in the same rounds: 20 designs of the same ranges run one by one
through the scalar study (:func:`rotorkin.drives.evaluate`, ``run.points =
--angles``), as a loop over designs would. The study samples the peaks of its
curves on ``rotorkin.core.batch.DEFAULT_SAMPLES`` = 20 001 angles per design
whatever ``run.points``, so the like-for-like comparison is a sweep at that many
samples: ``--like-designs`` designs (default 1000) at 20 001 samples, timed in the
same rounds, wall and CPU (``speedup_like_for_like``; the study still computes more:
columns, forces, pairs, so even this flatters the sweep a little). The speed-up
against the sweep at ``--angles`` samples (``speedup_unequal_samples``) compares
360 samples with 20 001 and is kept only to show the difference.

The command line (``--cli``, also part of a full run): ``rotorkin sweep`` as a user
runs it, each in a process of its own.

* Peak RSS against the result: the default example with ``loads.model = ideal``
  over compression ratio x heat per cycle x polytropic exponent (``--cli-designs``,
  default 1e6 designs, 360 angles), which writes ``sweep.nc``, the overview figure
  and README; the same command over 2 x 2 x 2 designs is the baseline (interpreter,
  imports, kernels compiled, figure). ``rss_over_result = (peak - baseline peak) /
  result bytes``, the result's bytes being those of its arrays (every variable of
  ``sweep.nc``, read from its header). Those keys leave the drive's geometry alone,
  so the rotors' curves are evaluated once for all designs. Target: at most 1.15.
* As many designs, each with its own rotor motion (plate tilt x roller axis angle,
  ``sqrt(--cli-designs)`` values each, the ideal cycle, 360 angles): every curve of
  every design evaluated; the drive's design checks are not recorded beyond 2048
  geometries. Its wall time and peak RSS.
* Fixed cost of a 1e3-design sweep (the default example, plate tilt x roller axis
  angle x compression ratio, 10 values each): the process's wall time minus the
  engine's computation (the time inside ``compute_chunk``): interpreter start,
  imports, config and units, the spec's checks with one design through the scalar
  study, the overview figure, ``sweep.nc`` and README. Its parts are timed apart.
  Target: at most 0.5 s.

Targets: at most 60 s and 1.5 GiB for 1e6 designs x 360
angles on a 2-core machine, and a compute time per design constant within
15 % from 1e4 to 1e6 designs. The result file records the load average: on a
shared machine the absolute times are upper bounds.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import load, machine, peak_rss, user_env, wobble_vary, write_json  # noqa: E402

from rotorkin.core.batch import DEFAULT_SAMPLES  # noqa: E402

#: designs -> points per axis (tilt, roller axis angle, compression ratio)


def metrics() -> list[str]:
    """Every metric of the wobble kernel: its defaults and the sampled extremes of every curve."""
    from rotorkin.drives.wobble_cam.sweep import SAMPLED_METRICS, metric_names

    return [*metric_names({}), *SAMPLED_METRICS]


def _setup(angles: int, threads):
    from rotorkin.io.config import load_config
    from rotorkin.sweep import run_sweep

    _, raw, _ = load_config(None, "wobble-cam-engine")
    run_sweep(
        raw, wobble_vary(8), samples=angles, progress=False, threads=threads, metrics=metrics()
    )  # warm-up
    return raw


def child(designs: int, angles: int, threads) -> dict:
    """Memory of one size, alone in this (fresh) process: one run, peak RSS."""
    from rotorkin.sweep import build_spec, execute

    raw = _setup(angles, threads)
    rss_start = peak_rss()
    t0 = time.perf_counter()
    spec = build_spec(raw, wobble_vary(designs), samples=angles, metrics=metrics())
    ds = execute(spec, progress=False, threads=threads)
    seconds = time.perf_counter() - t0
    return {
        "designs": int(ds["reason"].size),
        "grid": [len(v) for v in spec.varies],
        "metrics": len(spec.metrics),
        "inadmissible": int(np.count_nonzero(ds["reason"].values)),
        "single_run_s": seconds,
        "peak_rss_MiB": peak_rss() / 2**20,
        "rss_after_warmup_MiB": rss_start / 2**20,
        "checksum_accel_peaks": float(np.nansum(ds["rotor_accel_peak_per_rad"].values)),
        "checksum_sampled_slider_min": float(np.nansum(ds["sampled_slider_angle_min_deg"].values)),
    }


#: The CLI's memory grid (keys that leave the geometry alone) and its baseline.
CLI_SETS = ("loads.model=ideal",)
#: The fixed-cost sweep: 1e3 designs of the default example.
CLI_FIXED_VARY = ("drive.plate_tilt=30deg:50deg:10", "drive.roller_axis_angle=80deg:100deg:10",
                  "machine.compression_ratio=8:16:10")  # fmt: skip

#: Runs ``rotorkin sweep`` in this child, timing the parts; prints one JSON line.
_CLI_CHILD = """
import json, os, resource, sys, time
t0 = time.perf_counter()
os.environ.setdefault("MPLBACKEND", "Agg")
parts = {}

def timed(owner, name, label):
    fn = getattr(owner, name)

    def wrapper(*args, **kwargs):
        t = time.perf_counter()
        try:
            return fn(*args, **kwargs)
        finally:
            parts[label] = parts.get(label, 0.0) + time.perf_counter() - t

    setattr(owner, name, wrapper)

import atexit
import rotorkin.cli as cli
import rotorkin.cli.sweep
import rotorkin.render.figures as render
import rotorkin.report.figures_sweep as figures
import rotorkin.sweep as sweep
import rotorkin.sweep.engine as engine
from rotorkin.sweep.result import SweepResult

parts["imports"] = time.perf_counter() - t0
timed(sweep, "compute_chunk", "compute")
timed(engine, "check_spec_values", "spec_checks")
timed(sweep, "check_spec_values", "spec_checks")
# the command's own: the grid's checks, then the wait for the study's check run beside it
timed(sweep.CheckAhead, "__init__", "spec_checks")
timed(sweep.CheckAhead, "confirm", "spec_checks")
timed(figures, "fig_overview", "overview_figure")
timed(figures, "overview_task", "overview_figure")
# the wait for the figure, drawn by the drawing process while sweep.nc is written
timed(render.Drawing, "paths", "overview_figure")
timed(SweepResult, "to_netcdf", "write_netcdf")
command = cli.main

def main(argv=None):
    parts["code"] = command(argv)
    parts["in_process_s"] = time.perf_counter() - t0
    parts["peak_rss_MiB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return parts["code"]

cli.main = main
# the console script's own ending (exit handlers, then the process ends): the report last
atexit.register(lambda: print(json.dumps(parts), flush=True))
cli.console_main()
"""


#: The same sweep's computation alone in a fresh process (no figure, no check beside it,
#: nothing written): the time ``compute`` takes when nothing else runs.
_COMPUTE_CHILD = """
import json, sys, time
import rotorkin.sweep as sweep
from rotorkin.io.config import load_config

args = sys.argv[1:]
vary = [args[i + 1] for i in range(0, len(args), 2)]
_, raw, name = load_config(None, None, [])
spec = sweep.build_spec(raw, vary, name=name, check=False)
t = time.perf_counter()
sweep.compute(spec, progress=False)
print(json.dumps({"compute_alone": time.perf_counter() - t}), flush=True)
"""


def _compute_alone(args: list[str]) -> float:
    """Seconds of ``compute`` for the sweep of ``--vary`` ARGS, alone in a fresh process."""
    proc = subprocess.run([sys.executable, "-c", _COMPUTE_CHILD, *args], capture_output=True,
                          text=True, env=user_env())  # fmt: skip
    if proc.returncode:
        raise RuntimeError(proc.stderr)
    return json.loads(proc.stdout.strip().splitlines()[-1])["compute_alone"]


def _cli(args: list[str], folder: Path, env: dict | None = None) -> dict:
    """``rotorkin sweep ARGS --out folder -q`` in a fresh process: its timed parts, wall, RSS."""
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", _CLI_CHILD, "sweep", *args, "-q", "--out",
                           str(folder)], capture_output=True, text=True,
                          env=user_env(**(env or {})))  # fmt: skip
    wall = time.perf_counter() - t0
    if proc.returncode:
        raise RuntimeError(proc.stderr)
    doc = json.loads(proc.stdout.strip().splitlines()[-1])
    if doc["code"]:
        raise RuntimeError(proc.stderr)
    doc["wall_s"] = wall
    return doc


def _result_bytes(path: Path) -> int:
    """Bytes of the arrays of a result: every variable of its netCDF file (header only)."""
    from scipy.io import netcdf_file

    size = {"d": 8, "f": 4, "i": 4, "h": 2, "b": 1, "c": 1}
    with netcdf_file(path, "r", mmap=True) as f:
        return sum(int(np.prod(v.shape, dtype=np.int64)) * size[v.typecode()]
                   for v in f.variables.values())  # fmt: skip


def cli(designs: int, repeat: int = 3) -> dict:
    """The command line: peak RSS against the result at ``designs``; fixed cost of 1e3."""
    import tempfile

    n = max(2, round(designs ** (1.0 / 3.0)))
    grid = lambda k: [*(f"--set={s}" for s in CLI_SETS), "--angles", "360",  # noqa: E731
                      "--vary", f"machine.compression_ratio=8:16:{k}",
                      "--vary", f"loads.heat_per_cycle=500J:1500J:{k}",
                      "--vary", f"loads.polytropic_exponent=1.2:1.4:{k}"]  # fmt: skip
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        # the baseline loads the code the large run loads: the compiled loops, when numba is
        # there (a large evaluation uses them; 8 designs alone would not load them)
        kernel = "numba" if importlib.util.find_spec("numba") else "numpy"
        # the smaller of two runs: one baseline run on this machine once peaked 3x higher
        small = min((_cli(grid(2), tmp / f"small{i}", {"ROTORKIN_KERNEL": kernel})
                     for i in range(2)), key=lambda r: r["peak_rss_MiB"])  # fmt: skip
        big = _cli(grid(n), tmp / "big")
        result = _result_bytes(tmp / "big" / "sweep.nc")
        # as many designs, each with its own rotor motion: no curve is shared
        m = max(2, round(designs**0.5))
        own_args = [*(f"--set={s}" for s in CLI_SETS), "--angles", "360",
                    "--vary", f"drive.plate_tilt=30deg:50deg:{m}",
                    "--vary", f"drive.roller_axis_angle=80deg:100deg:{m}"]  # fmt: skip
        own = _cli(own_args, tmp / "own")
        own_result = _result_bytes(tmp / "own" / "sweep.nc")
        fixed_args = [a for v in CLI_FIXED_VARY for a in ("--vary", v)]
        runs = [_cli(fixed_args, tmp / f"fixed{i}") for i in range(max(1, repeat))]
        alone = min(_compute_alone(fixed_args) for _ in range(max(1, repeat)))
    fixed = min(runs, key=lambda r: r["wall_s"])
    memory = {
        "designs": n**3,
        "command": "rotorkin sweep " + " ".join(grid(n)),
        "result_bytes": result,
        "result_MiB": result / 2**20,
        "peak_rss_MiB": big["peak_rss_MiB"],
        "baseline_peak_rss_MiB": small["peak_rss_MiB"],
        "baseline_kernel": kernel,
        "peak_over_result": big["peak_rss_MiB"] * 2**20 / result,
        "rss_over_result": (big["peak_rss_MiB"] - small["peak_rss_MiB"]) * 2**20 / result,
        "wall_s": big["wall_s"],
        "own_motions": {
            "designs": m**2,
            "command": "rotorkin sweep " + " ".join(own_args),
            "result_MiB": own_result / 2**20,
            "peak_rss_MiB": own["peak_rss_MiB"],
            "rss_over_result": (own["peak_rss_MiB"] - small["peak_rss_MiB"]) * 2**20 / own_result,
            "wall_s": own["wall_s"],
        },
    }
    cost = {
        "designs": 1000,
        "command": "rotorkin sweep " + " ".join(fixed_args),
        "wall_s": fixed["wall_s"],
        # the yardstick: the computation alone (best of the rounds, a fresh process each);
        # what the command's other work costs the computation beside it is fixed cost too
        "compute_alone_s": alone,
        "compute_s": fixed["compute"],
        "fixed_s": fixed["wall_s"] - alone,
        "fixed_in_run_s": fixed["wall_s"] - fixed["compute"],
        "interpreter_start_s": fixed["wall_s"] - fixed["in_process_s"],
        "imports_s": fixed["imports"],
        "spec_checks_s": fixed.get("spec_checks", 0.0),
        "overview_figure_s": fixed.get("overview_figure", 0.0),
        "write_netcdf_s": fixed.get("write_netcdf", 0.0),
        "rounds": len(runs),
    }
    cost["other_s"] = cost["fixed_in_run_s"] - sum(cost[k] for k in (
        "interpreter_start_s", "imports_s", "spec_checks_s", "overview_figure_s",
        "write_netcdf_s"))  # fmt: skip
    print(f"rotorkin sweep, {memory['designs']} designs: peak RSS {memory['peak_rss_MiB']:.0f} "
          f"MiB, baseline {memory['baseline_peak_rss_MiB']:.0f} MiB, result "
          f"{memory['result_MiB']:.0f} MiB: {memory['rss_over_result']:.3f} x the result "
          f"above the baseline")  # fmt: skip
    mo = memory["own_motions"]
    print(f"rotorkin sweep, {mo['designs']} designs, each its own rotor motion: wall "
          f"{mo['wall_s']:.1f} s, peak RSS {mo['peak_rss_MiB']:.0f} MiB")  # fmt: skip
    print(f"rotorkin sweep, 1000 designs: wall {cost['wall_s']:.2f} s, compute alone "
          f"{alone:.2f} s: fixed {cost['fixed_s']:.2f} s; in the run compute "
          f"{cost['compute_s']:.2f} s, the rest {cost['fixed_in_run_s']:.2f} s (start "
          f"{cost['interpreter_start_s']:.2f}, imports {cost['imports_s']:.2f}, spec checks "
          f"{cost['spec_checks_s']:.2f}, figure {cost['overview_figure_s']:.2f}, netCDF "
          f"{cost['write_netcdf_s']:.3f}, other {cost['other_s']:.2f})", flush=True)  # fmt: skip

    return {"memory": memory, "fixed_cost": cost,
            # False: measured on the core install (pip install ., no xarray or pandas)
            "xarray_installed": importlib.util.find_spec("xarray") is not None,
            "verdict": {"rss_within_1_15_of_result": memory["rss_over_result"] <= 1.15,
                        "fixed_cost_under_0_5_s": cost["fixed_s"] <= 0.5}}  # fmt: skip


def _one_by_one(raw: dict, angles: int, count: int):
    """The baseline: ``count`` designs of the grid, each through the scalar study.

    That is what a user without the sweep writes: a loop over designs calling
    :func:`rotorkin.drives.evaluate` on each config (``run.points = angles``), the
    same metrics a sweep gives. Returns a function that runs the loop once.
    """
    import copy

    from rotorkin.drives import evaluate
    from rotorkin.io.config import validate_config

    rng = np.random.default_rng(7)
    cfgs = []
    for tilt, alpha, eps in zip(rng.uniform(30, 50, count), rng.uniform(80, 100, count),
                                rng.uniform(8, 16, count), strict=True):  # fmt: skip
        d = copy.deepcopy(raw)
        d["drive"].update(plate_tilt=f"{tilt} deg", roller_axis_angle=f"{alpha} deg")
        d["machine"]["compression_ratio"] = float(eps)
        d.setdefault("run", {})["points"] = angles
        cfgs.append(validate_config(d))

    def loop():
        for cfg in cfgs:
            evaluate(cfg)

    return loop


def timings(sizes, angles: int, threads, repeat: int, baseline: int = 20,
            like_designs: int = 1000) -> dict:  # fmt: skip
    """Best wall and CPU times of build_spec and execute per size, sizes interleaved.

    Each round runs every size once (order rotated); the best of ``repeat`` rounds
    is kept. The CPU time (``time.process_time``, all threads) is less sensitive
    than the wall time to other processes on a shared machine.
    """
    from rotorkin.sweep import build_spec, execute

    raw = _setup(angles, threads)
    specs = {n: build_spec(raw, wobble_vary(n), samples=angles, metrics=metrics()) for n in sizes}
    best = {n: {"spec_s": np.inf, "compute_s": np.inf, "compute_cpu_s": np.inf} for n in sizes}
    loop = _one_by_one(raw, angles, baseline)
    like = build_spec(raw, wobble_vary(like_designs), samples=DEFAULT_SAMPLES, metrics=metrics())
    n_like = int(np.prod([len(v) for v in like.varies]))
    for key in ("one_by_one_s", "one_by_one_cpu_s", "like_s", "like_cpu_s"):
        best[key] = np.inf
    for r in range(max(1, repeat)):
        t0, c0 = time.perf_counter(), time.process_time()
        loop()
        t1, c1 = time.perf_counter(), time.process_time()
        best["one_by_one_s"] = min(best["one_by_one_s"], (t1 - t0) / baseline)
        best["one_by_one_cpu_s"] = min(best["one_by_one_cpu_s"], (c1 - c0) / baseline)
        execute(like, progress=False, threads=threads)
        t2, c2 = time.perf_counter(), time.process_time()
        best["like_s"] = min(best["like_s"], (t2 - t1) / n_like)
        best["like_cpu_s"] = min(best["like_cpu_s"], (c2 - c1) / n_like)
        for n in sizes[r % len(sizes) :] + sizes[: r % len(sizes)]:
            t0 = time.perf_counter()
            build_spec(raw, wobble_vary(n), samples=angles, metrics=metrics())
            t1, c1 = time.perf_counter(), time.process_time()
            execute(specs[n], progress=False, threads=threads)
            t2, c2 = time.perf_counter(), time.process_time()
            b = best[n]
            b["spec_s"] = min(b["spec_s"], t1 - t0)
            b["compute_s"] = min(b["compute_s"], t2 - t1)
            b["compute_cpu_s"] = min(b["compute_cpu_s"], c2 - c1)
    best["like_designs"] = n_like
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default="1e4,1e5,1e6", help="designs, comma-separated")
    ap.add_argument("--angles", type=int, default=360, help="shaft angles per design")
    ap.add_argument("--threads", type=int, default=None, help="kernel threads (default: cores)")
    ap.add_argument("--repeat", type=int, default=3, help="interleaved timing rounds (best kept)")
    ap.add_argument("--like-designs", type=int, default=1000,
                    help="designs of the like-for-like sweep at 20 001 samples")  # fmt: skip
    ap.add_argument("--out", default=str(Path(__file__).parent / "results" / "sweep.json"))
    ap.add_argument(
        "--cli",
        action="store_true",
        help="only the command line's memory and fixed cost, merged into --out",
    )
    ap.add_argument("--cli-designs", default="1e6",
                    help="designs of the command line's memory run")  # fmt: skip
    ap.add_argument("--child", type=int, default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child is not None:
        print(json.dumps(child(args.child, args.angles, args.threads)))
        return
    if args.cli:
        out = Path(args.out)
        doc = json.loads(out.read_text()) if out.is_file() else {"benchmark": "sweep"}
        command = "python benchmarks/bench_sweep.py " + " ".join(sys.argv[1:])
        before = load()
        found = cli(int(float(args.cli_designs)), args.repeat)
        doc["cli"] = {"command": command, "machine": machine(), "load_before": before,
                      **found, "load_after": load()}  # fmt: skip
        write_json(args.out, doc)
        print(f"wrote {args.out}")
        return
    sizes = [int(float(s)) for s in args.sizes.split(",")]
    load_before = load()
    rows = []
    for size in sizes:  # memory: each size alone in a fresh process
        cmd = [sys.executable, __file__, "--child", str(size), "--angles", str(args.angles)]
        if args.threads:
            cmd += ["--threads", str(args.threads)]
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        rows.append({**json.loads(out.strip().splitlines()[-1]), "angles": args.angles})
    times = timings([r["designs"] for r in rows], args.angles, args.threads, args.repeat,
                    like_designs=args.like_designs)  # fmt: skip
    one_us = times["one_by_one_s"] * 1e6
    like = {
        "samples": DEFAULT_SAMPLES,
        "designs": times["like_designs"],
        "sweep_us_per_design": times["like_s"] * 1e6,
        "sweep_cpu_us_per_design": times["like_cpu_s"] * 1e6,
        "one_by_one_us_per_design": one_us,
        "one_by_one_cpu_us_per_design": times["one_by_one_cpu_s"] * 1e6,
        "speedup_like_for_like": times["one_by_one_s"] / times["like_s"],
        "speedup_like_for_like_cpu": times["one_by_one_cpu_s"] / times["like_cpu_s"],
    }
    print(f"like for like ({DEFAULT_SAMPLES} samples per design, {like['designs']} designs): "
          f"sweep {like['sweep_us_per_design']:.0f} us/design (CPU "
          f"{like['sweep_cpu_us_per_design']:.0f}), one by one {one_us:.0f} us/design (CPU "
          f"{like['one_by_one_cpu_us_per_design']:.0f}): {like['speedup_like_for_like']:.0f}x "
          f"wall, {like['speedup_like_for_like_cpu']:.0f}x CPU")  # fmt: skip
    for r in rows:
        t = times[r["designs"]]
        spec_s, compute_s = t["spec_s"], t["compute_s"]
        r.update(
            t,
            total_s=spec_s + compute_s,
            compute_us_per_design=compute_s / r["designs"] * 1e6,
            cpu_us_per_design=t["compute_cpu_s"] / r["designs"] * 1e6,
            compute_ns_per_design_angle=compute_s / (r["designs"] * r["angles"]) * 1e9,
            one_by_one_us_per_design=one_us,
            speedup_unequal_samples=one_us / (compute_s / r["designs"] * 1e6),
        )
        print(f"{r['designs']:>9} designs x {r['angles']} angles: spec {spec_s:.3f} s, compute "
              f"{compute_s:.3f} s ({r['compute_us_per_design']:.2f} us/design, "
              f"{r['compute_ns_per_design_angle']:.1f} ns/design/angle; CPU "
              f"{r['cpu_us_per_design']:.2f} us/design), peak RSS "
              f"{r['peak_rss_MiB']:.0f} MiB; {r['speedup_unequal_samples']:.0f}x the designs "
              f"one by one ({one_us:.0f} us/design, {DEFAULT_SAMPLES} samples: not like for "
              f"like)", flush=True)  # fmt: skip
    ref, ref_cpu = rows[-1]["compute_us_per_design"], rows[-1]["cpu_us_per_design"]
    for r in rows:
        r["per_design_vs_largest"] = r["compute_us_per_design"] / ref
        r["cpu_per_design_vs_largest"] = r["cpu_us_per_design"] / ref_cpu
    big = next((r for r in rows if r["designs"] == 1_000_000), None)
    verdict = {
        "per_design_within_15_percent": all(
            abs(r["per_design_vs_largest"] - 1) <= 0.15 for r in rows
        ),
        "cpu_per_design_within_15_percent": all(
            abs(r["cpu_per_design_vs_largest"] - 1) <= 0.15 for r in rows
        ),
    }
    if big:
        verdict.update(total_s_1e6=big["total_s"], under_60_s=big["total_s"] <= 60.0,
                       peak_rss_MiB_1e6=big["peak_rss_MiB"],
                       under_1_5_GiB=big["peak_rss_MiB"] <= 1536.0)  # fmt: skip
    print("per design / largest size (wall, cpu):", ", ".join(f"{r['designs']}: "
          f"{r['per_design_vs_largest']:.3f}, {r['cpu_per_design_vs_largest']:.3f}"
          for r in rows))  # fmt: skip
    print("verdict:", json.dumps(verdict), "load before/after:", load_before, load())
    cmdline = "python benchmarks/bench_sweep.py " + " ".join(sys.argv[1:])
    cli_doc = {"load_before": load(), **cli(int(float(args.cli_designs)), args.repeat)}
    write_json(args.out, {"benchmark": "sweep", "command": cmdline.strip(), "machine": machine(),
                          "load_before": load_before, "load_after": load(), "rows": rows,
                          "like_for_like": like, "verdict": verdict,
                          "cli": {**cli_doc, "load_after": load()}})  # fmt: skip
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
