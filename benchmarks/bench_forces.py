"""Benchmark: the wobble-cam engine swept with its dynamics and its pairs' forces per design.

    python benchmarks/bench_forces.py                 # 400 designs of one geometry, 40 of their own
    python benchmarks/bench_forces.py --shared 100 --own 10    # quick
    python benchmarks/bench_forces.py --help

The designs: the ``wobble-cam-engine`` example with the ideal cycle (``loads.model =
ideal``). "shared": the compression ratio (9 ... 16) and the heat per cycle (500 ... 1500
J) drawn at random, one drive geometry for all; "own": the plate tilt drawn at random
(38 ... 52 deg), each design its own geometry, so its own search of the grooves' walls
for the crossings' keys. Each design gets the 47 keys of the engine's dynamics and the
pairs' forces (:data:`rotorkin.drives.wobble_cam.sweep_forces.DYNAMIC` and ``FORCES``)
on 20 001 shaft angles, through :func:`rotorkin.sweep.engine.evaluate_designs` on
``--threads`` threads.

Yardstick, like for like: the first ``--studies`` designs (default 3) of each case each
through the study (:func:`rotorkin.drives.evaluate`: the same 20 001 angles, and the rest
of the study's summary and columns); their values are compared with the kernel's
(``max_rel_diff``).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import against_study, machine, report_against_study  # noqa: E402


def _case(kind: str, n: int, studies: int, threads: int) -> dict:
    from rotorkin.core.batch import Designs
    from rotorkin.drives.wobble_cam import sweep_forces as swf
    from rotorkin.io.config import load_config
    from rotorkin.sweep.engine import evaluate_designs

    cfg, _, _ = load_config(example="wobble-cam-engine", sets=["loads.model=ideal"])
    rng = np.random.default_rng(1)
    if kind == "shared":
        table = {"machine.compression_ratio": rng.uniform(9.0, 16.0, n),
                 "loads.heat_per_cycle": rng.uniform(500.0, 1500.0, n)}  # fmt: skip
    else:
        table = {"drive.plate_tilt": np.radians(rng.uniform(38.0, 52.0, n))}
    p = Designs(cfg, table, n)
    names = list(swf.DYNAMIC + swf.FORCES)
    start, cpu = time.perf_counter(), time.process_time()
    res = evaluate_designs(p, names, threads=threads)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    study, worst = against_study(p, res["metrics"], names, studies)
    return {"geometry": kind, "designs": n, "metrics": len(names), "wall_s": wall,
            "cpu_s": cpu, "ms_per_design": wall / n * 1e3, "study_ms_per_design": study * 1e3,
            "ratio_vs_study": study / (wall / n), "max_rel_diff": worst,
            "admissible": int((res["reason"] == 0).sum())}  # fmt: skip


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shared", type=int, default=400, help="designs of one geometry")
    ap.add_argument("--own", type=int, default=40, help="designs each of its own geometry")
    ap.add_argument("--studies", type=int, default=3, help="designs through the study")
    ap.add_argument("--threads", type=int, default=2, help="kernel threads")
    ap.add_argument("--out", default=str(Path(__file__).parent / "results" / "forces.json"))
    args = ap.parse_args()
    info = machine()
    _case("shared", 2, 0, args.threads)  # imports and first calls outside the timings
    cases = [_case(k, n, args.studies, args.threads)
             for k, n in (("shared", args.shared), ("own", args.own)) if n > 0]  # fmt: skip
    report_against_study(args.out, info, cases, "geometry", 6)


if __name__ == "__main__":
    main()
