"""Benchmark: rotary-blade engines swept with their dynamics, forces and gas cycle per design.

    python benchmarks/bench_stirling.py             # 512 adiabatic, 1000 Schmidt, 1000 linear
    python benchmarks/bench_stirling.py --adiabatic 128 --schmidt 200 --linear 200   # quick
    python benchmarks/bench_stirling.py --help

The designs: the ``rhomboid-engine`` example with ``loads.pressure_model`` adiabatic or
schmidt, its charge pressure (2 ... 40 bar) and the cold set's phase angle (60 ... 120
deg) drawn at random; and under the paper's linear torque model, psi_min (30 ... 50
deg) and the high torque (100 ... 300 N m). Each design gets every metric the kernel
computes for the model (:func:`rotorkin.drives.rhomboid_cam.sweep.metric_names`: the
law, the machine, the dynamics, the converter's forces and its pairs' contact stresses
and friction on 20 001 shaft angles, and a Stirling model's cycle), through
:func:`rotorkin.sweep.engine.evaluate_designs` on ``--threads`` threads.

Yardstick, like for like: the first ``--studies`` designs (default 3) each through the
study (:func:`rotorkin.drives.evaluate`: the same cycle, its 720 Runge-Kutta steps per
period, the same 20 001 angles, and the rest of the study's summary, which is a small
part of its time); their metrics are compared with the kernel's (``max_rel_diff``).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import against_study, machine, report_against_study  # noqa: E402


def _case(model: str, n: int, studies: int, threads: int) -> dict:
    from rotorkin.core.batch import Designs
    from rotorkin.drives.rhomboid_cam import sweep as kernel
    from rotorkin.io.config import load_config
    from rotorkin.sweep.engine import evaluate_designs

    cfg, _, _ = load_config(example="rhomboid-engine", sets=[f"loads.pressure_model={model}"])
    rng = np.random.default_rng(1)
    if model == "linear":
        table = {"drive.psi_min": np.radians(rng.uniform(30.0, 50.0, n)),
                 "loads.torque_high": rng.uniform(100.0, 300.0, n)}  # fmt: skip
    else:
        table = {"loads.charge_pressure": rng.uniform(2e5, 40e5, n),
                 "loads.phase_angle": np.radians(rng.uniform(60.0, 120.0, n))}  # fmt: skip
    p = Designs(cfg, table, n)
    names = list(kernel.metric_names(cfg))
    start, cpu = time.perf_counter(), time.process_time()
    res = evaluate_designs(p, names, threads=threads)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    study, worst = against_study(p, res["metrics"], names, studies)
    return {"model": model, "designs": n, "metrics": len(names), "wall_s": wall, "cpu_s": cpu,
            "ms_per_design": wall / n * 1e3, "study_ms_per_design": study * 1e3,
            "ratio_vs_study": study / (wall / n), "max_rel_diff": worst,
            "admissible": int((res["reason"] == 0).sum())}  # fmt: skip


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--adiabatic", type=int, default=512, help="designs of the adiabatic model")
    ap.add_argument("--schmidt", type=int, default=1000, help="designs of the Schmidt model")
    ap.add_argument("--linear", type=int, default=1000,
                    help="designs of the linear torque model")  # fmt: skip
    ap.add_argument("--studies", type=int, default=3, help="designs through the study")
    ap.add_argument("--threads", type=int, default=2, help="kernel threads")
    ap.add_argument("--out", default=str(Path(__file__).parent / "results" / "stirling.json"))
    args = ap.parse_args()
    info = machine()
    cases = [
        _case(m, n, args.studies, args.threads)
        for m, n in (
            ("adiabatic", args.adiabatic),
            ("schmidt", args.schmidt),
            ("linear", args.linear),
        )  # fmt: skip
        if n > 0
    ]
    report_against_study(args.out, info, cases, "model", 9)


if __name__ == "__main__":
    main()
