"""Benchmark: wobble-cam sweeps with the single-zone fuel-air cycle of every design.

    python benchmarks/bench_cycle.py                     # 1e4 and 1e5 designs (about 2 minutes)
    python benchmarks/bench_cycle.py --sizes 1e4         # quick look
    python benchmarks/bench_cycle.py --kernel numpy      # the numpy fallback
    python benchmarks/bench_cycle.py --help

The sweep: plate tilt (30 ... 50 deg) x roller axis angle (80 ... 100 deg) x compression
ratio (8 ... 16) of the ``wobble-cam-engine`` example, whose loads are the fuel-air cycle
(:mod:`rotorkin.machines.fuel_air`: NASA gas tables, a Wiebe burn, Woschni walls). Every
design gets the kernel's default metrics, among them the cycle's: two closed parts (chamber
kinds A and B) of 720 Runge-Kutta steps each (360 per stroke,
:func:`rotorkin.machines.fuel_air.steps_per_stroke`), on volumes from the drive's
kinematics on 2 x 1441 angles; the rotors' acceleration and jerk peaks on ``--samples``
shaft angles per design (default 360, as ``bench_sweep.py``; the sweep's own default,
20 001, adds about 0.2 ms of CPU per design). ``build_spec`` and ``execute`` of
:mod:`rotorkin.sweep`, timed together and apart.

Each size runs once in a fresh process (after a warm-up sweep of 8 designs, which loads
the compiled loops): wall and CPU time (``time.process_time``, all threads), peak RSS
(``resource.getrusage``, the results included) and the time per design.

Yardstick, like for like: ``--one-by-one`` designs of the same ranges (default 200), each
through the one-design cycle path of the study
(:func:`rotorkin.drives.wobble_cam.study.models`: the drive, its turning points, the
chambers' volumes and :func:`rotorkin.machines.fuel_air.charge_cycle`), with the compiled
integrator and with numpy; and some (``--studies``, default 20) through the whole study
(:func:`rotorkin.drives.evaluate`). The first of these designs are also swept and their
cycle metrics compared with the study's (``max_rel_diff_vs_study``; the target is 1e-9).

Target: 1e5 designs in at most 60 s on a 2-core machine, every cycle metric equal to the
study's to 1e-9. The result file records the machine and the load average: on a shared
machine the absolute times are upper bounds.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import git_commit, load, machine, peak_rss, wobble_vary, write_json  # noqa: E402

EXAMPLE = "wobble-cam-engine"
#: designs -> points per axis (tilt, roller axis angle, compression ratio)
#: The cycle's metrics compared with the study.
CYCLE = ("trapped_mass_mg", "compression_end_pressure_bar", "peak_pressure_bar",
         "peak_pressure_angle_deg", "peak_temperature_K", "indicated_work_J",
         "fuel_energy_J_per_rev", "heat_added_J_per_rev", "heat_to_walls_J_per_rev",
         "indicated_efficiency", "imep_bar", "indicated_work_per_cycle_a_J",
         "indicated_work_per_cycle_b_J", "indicated_power_kW")  # fmt: skip


def child(designs: int, threads, samples: int) -> dict:
    """One sweep of ``designs``, alone in this (fresh) process: wall, CPU, peak RSS."""
    from rotorkin.io.config import load_config
    from rotorkin.sweep import build_spec, execute

    _, raw, _ = load_config(None, EXAMPLE)
    execute(build_spec(raw, wobble_vary(8), samples=samples), progress=False, threads=threads)
    rss_start = peak_rss()
    t0, c0 = time.perf_counter(), time.process_time()
    spec = build_spec(raw, wobble_vary(designs), samples=samples)
    t1 = time.perf_counter()
    ds = execute(spec, progress=False, threads=threads)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    n = int(ds["reason"].size)
    return {
        "designs": n,
        "samples": samples,
        "grid": [len(v) for v in spec.varies],
        "metrics": len(spec.metrics),
        "inadmissible": int(np.count_nonzero(ds["reason"].values)),
        "wall_s": wall,
        "spec_s": t1 - t0,
        "execute_s": wall - (t1 - t0),
        "cpu_s": cpu,
        "us_per_design": wall / n * 1e6,
        "cpu_us_per_design": cpu / n * 1e6,
        "peak_rss_MiB": peak_rss() / 2**20,
        "rss_after_warmup_MiB": rss_start / 2**20,
        "checksum_indicated_work": float(np.nansum(ds["indicated_work_J"].values)),
    }


def _configs(count: int, seed: int = 7) -> list:
    """``count`` random designs of the swept ranges, validated configs."""
    from rotorkin.io.config import load_config

    rng = np.random.default_rng(seed)
    return [load_config(example=EXAMPLE, sets=[f"drive.plate_tilt={t} deg",
                                               f"drive.roller_axis_angle={a} deg",
                                               f"machine.compression_ratio={e}"])[0]
            for t, a, e in zip(rng.uniform(30, 50, count), rng.uniform(80, 100, count),
                               rng.uniform(8, 16, count), strict=True)]  # fmt: skip


def one_by_one(count: int, studies: int, threads) -> dict:
    """The yardstick: the same kind of designs one by one, and the sweep against the study."""
    from rotorkin import drives
    from rotorkin.core import fused
    from rotorkin.core.batch import Designs
    from rotorkin.drives.wobble_cam import study
    from rotorkin.sweep import evaluate_designs

    cfgs = _configs(count)
    out = {"designs": count}
    saved = os.environ.get(fused.KERNEL_ENV)
    for kernel in ("numba", "numpy"):
        os.environ[fused.KERNEL_ENV] = kernel
        study.models(cfgs[0])  # warm-up (loads the compiled loop)
        t0, c0 = time.perf_counter(), time.process_time()
        for cfg in cfgs:
            study.models(cfg)
        out[f"cycle_path_{kernel}_us_per_design"] = (time.perf_counter() - t0) / count * 1e6
        out[f"cycle_path_{kernel}_cpu_us_per_design"] = (time.process_time() - c0) / count * 1e6
    if saved is None:
        os.environ.pop(fused.KERNEL_ENV)
    else:
        os.environ[fused.KERNEL_ENV] = saved
    t0 = time.perf_counter()
    summaries = [drives.evaluate(cfg).summary for cfg in cfgs[:studies]]
    out["study_designs"] = studies
    out["study_us_per_design"] = (time.perf_counter() - t0) / studies * 1e6
    keys = ("drive.plate_tilt", "drive.roller_axis_angle", "machine.compression_ratio")
    table = {k: np.array([c[k.split(".")[0]][k.split(".")[1]] for c in cfgs[:studies]])
             for k in keys}  # fmt: skip
    res = evaluate_designs(Designs(cfgs[0], table, studies), CYCLE, samples=361, threads=threads)
    worst = max(abs(res["metrics"][k][i] / s[k] - 1.0) for i, s in enumerate(summaries)
                for k in CYCLE if s[k] != 0)  # fmt: skip
    out["max_rel_diff_vs_study"] = float(worst)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default="1e4,1e5", help="designs, comma-separated")
    ap.add_argument("--threads", type=int, default=None, help="kernel threads (default: cores)")
    ap.add_argument("--kernel", default=None, choices=("auto", "numpy", "numba"),
                    help="ROTORKIN_KERNEL of the sweeps (default: as set, else auto)")  # fmt: skip
    ap.add_argument("--samples", type=int, default=360,
                    help="shaft angles per design of the rotors' sampled peaks")  # fmt: skip
    ap.add_argument("--one-by-one", type=int, default=200, help="designs of the yardstick")
    ap.add_argument("--studies", type=int, default=20, help="designs through the whole study")
    ap.add_argument("--out", default=str(Path(__file__).parent / "results" / "cycle.json"))
    ap.add_argument("--child", type=int, default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.kernel:
        os.environ["ROTORKIN_KERNEL"] = args.kernel
    if args.child is not None:
        print(json.dumps(child(args.child, args.threads, args.samples)))
        return
    sizes = [int(float(s)) for s in args.sizes.split(",")]
    load_before = load()
    rows = []
    for size in sizes:  # each size alone in a fresh process
        cmd = [sys.executable, __file__, "--child", str(size), "--samples", str(args.samples)]
        if args.threads:
            cmd += ["--threads", str(args.threads)]
        before = load()
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        row = {**json.loads(out.strip().splitlines()[-1]), "load_before": before,
               "load_after": load()}  # fmt: skip
        rows.append(row)
        print(f"{row['designs']:>7} designs: {row['wall_s']:.2f} s wall (spec {row['spec_s']:.2f}"
              f" s, execute {row['execute_s']:.2f} s), {row['cpu_s']:.2f} s "
              f"CPU ({row['us_per_design']:.0f} us/design, CPU {row['cpu_us_per_design']:.0f}),"
              f" peak RSS {row['peak_rss_MiB']:.0f} MiB, load {row['load_before']} -> "
              f"{row['load_after']}", flush=True)  # fmt: skip
    yard = one_by_one(args.one_by_one, args.studies, args.threads)
    sweep_us = rows[-1]["us_per_design"]
    yard["speedup_vs_cycle_path_numba"] = yard["cycle_path_numba_us_per_design"] / sweep_us
    yard["speedup_vs_cycle_path_numpy"] = yard["cycle_path_numpy_us_per_design"] / sweep_us
    print(f"one by one ({yard['designs']} designs, the study's cycle path): "
          f"{yard['cycle_path_numba_us_per_design']:.0f} us/design compiled, "
          f"{yard['cycle_path_numpy_us_per_design']:.0f} us/design numpy; the whole study "
          f"{yard['study_us_per_design']:.0f} us/design; the largest sweep "
          f"{yard['speedup_vs_cycle_path_numba']:.0f}x / "
          f"{yard['speedup_vs_cycle_path_numpy']:.0f}x faster per design; sweep vs study: "
          f"max relative difference {yard['max_rel_diff_vs_study']:.1e}")  # fmt: skip
    big = next((r for r in rows if r["designs"] == 100_000), None)
    verdict = {"equal_to_study_1e-9": yard["max_rel_diff_vs_study"] <= 1e-9}
    if big:
        verdict.update(wall_s_1e5=big["wall_s"], under_60_s=big["wall_s"] <= 60.0,
                       peak_rss_MiB_1e5=big["peak_rss_MiB"])  # fmt: skip
    print("verdict:", json.dumps(verdict), "load before/after:", load_before, load())
    cmdline = "python benchmarks/bench_cycle.py " + " ".join(sys.argv[1:])
    write_json(args.out, {"benchmark": "cycle", "command": cmdline.strip(), "commit": git_commit(),
                          "kernel": os.environ.get("ROTORKIN_KERNEL", "auto"),
                          "machine": machine(), "load_before": load_before,
                          "load_after": load(), "rows": rows, "one_by_one": yard,
                          "verdict": verdict})  # fmt: skip
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
