"""Latency of the command line: ``rotorkin run`` per example, ``rotorkin --help``, the floor.

Each case is a fresh process started the way a user starts ``rotorkin`` (the console
script's two lines, ``python -c``), timed from the outside: its wall time and the CPU
time of the process and its children (the figure workers). Every case runs once per
round, the order rotated from round to round, after a warm-up round that is not kept
(files in the page cache, ``__pycache__`` written: :func:`_common.user_env`): what is
reported is the best of the warm rounds, the run least disturbed by the neighbours'
load.

Cases:

* ``run <example>`` -- the example with its default figures (drawn by the machine's
  cores, :func:`rotorkin.render.figures.draw`);
* ``run <example> --no-figures``;
* ``run <example> serial`` (``--serial``) -- the figures drawn in one process
  (``ROTORKIN_FIGURE_WORKERS=1``);
* ``--help`` -- the command list (nothing of the library imported);
* ``floor`` -- ``python -c "import numpy, matplotlib.pyplot"``: the imports no run
  with figures can avoid, the yardstick; each run's ``over_floor`` is its best wall
  time over the floor's best, measured in the same rounds.

Targets: a run with its default figures at most ``TARGET_RUN`` s wall, ``--help`` at
most ``TARGET_HELP`` s. Each case records the load average before and after it; the
file records the machine (cores, CPU) and the load at start and end.

Run from the repository root::

    python benchmarks/bench_latency.py                          # every example, 5 rounds
    python benchmarks/bench_latency.py --examples wobble-cam-engine --rounds 3 --serial
    python benchmarks/bench_latency.py --markdown benchmarks/results/latency.json
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from _common import git_commit, load, machine, user_env, write_json  # noqa: E402

DEFAULT_OUT = HERE / "results" / "latency.json"
COMMAND = "python benchmarks/bench_latency.py"
#: Wall time a run of an example with its default figures should stay under [s].
TARGET_RUN = 1.5
#: Wall time of ``rotorkin --help`` [s].
TARGET_HELP = 0.1
#: The console script, as ``python -c`` (``rotorkin`` itself is these two lines).
SCRIPT = "import sys; from rotorkin.cli import console_main; sys.exit(console_main())"
FLOOR = "import numpy, matplotlib.pyplot"


def _examples() -> list[str]:
    from rotorkin.io.config import example_names

    return example_names()


def cases(examples, serial: bool) -> dict:
    """name -> (argv, extra environment, target [s] or None)."""
    py = sys.executable
    out = {"floor": ([py, "-c", FLOOR], {}, None),
           "--help": ([py, "-c", SCRIPT, "--help"], {}, TARGET_HELP)}  # fmt: skip
    for ex in examples:
        run = [py, "-c", SCRIPT, "run", "-e", ex, "-q"]
        out[f"run {ex}"] = (run, {}, TARGET_RUN)
        out[f"run {ex} --no-figures"] = ([*run, "--no-figures"], {}, None)
        if serial:
            out[f"run {ex} serial"] = (run, {"ROTORKIN_FIGURE_WORKERS": "1"}, None)
    return out


def _once(argv, env, folder: Path) -> tuple[float, float, int]:
    """Wall and CPU time [s] of one process (and its children), and its exit code."""
    if argv[3:4] == ["run"]:
        argv = [*argv, "-o", str(folder / "out")]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True, check=False)  # fmt: skip
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed (exit {done.returncode}): {done.stderr}")
    return wall, cpu, done.returncode


def run(examples, rounds: int, serial: bool) -> dict:
    """Time every case in ``rounds`` warm rounds (after one warm-up round)."""
    table = cases(examples, serial)
    base_env = user_env(MPLBACKEND="Agg")
    names = list(table)
    walls = {n: [] for n in names}
    cpus = {n: [] for n in names}
    loads = {n: [] for n in names}
    info = machine()
    load_start = load()
    with tempfile.TemporaryDirectory(prefix="rotorkin-latency-") as tmp:
        for r in range(rounds + 1):
            order = names[r % len(names) :] + names[: r % len(names)]
            for name in order:
                argv, env, _ = table[name]
                l0 = load()
                wall, cpu, _ = _once(argv, {**base_env, **env}, Path(tmp))
                if r > 0:  # round 0 warms the caches
                    walls[name].append(wall)
                    cpus[name].append(cpu)
                    loads[name].append((l0[0], load()[0]))
    floor = min(walls["floor"])
    rows = []
    for name in names:
        argv, env, target = table[name]
        best = min(walls[name])
        rows.append({
            "case": name,
            "command": " ".join(["rotorkin", *argv[3:]] if argv[1:3] == ["-c", SCRIPT]
                                else ["python", *argv[1:]]),
            "environment": env,
            "wall_best_s": best,
            "wall_median_s": statistics.median(walls[name]),
            "cpu_best_s": min(cpus[name]),
            "over_floor": best / floor,
            "target_s": target,
            "met": None if target is None else best <= target,
            "load_min": min(a for a, _ in loads[name]),
            "load_max": max(b for _, b in loads[name]),
        })  # fmt: skip
    return {
        "benchmark": "latency",
        "commit": git_commit(),
        "date": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "machine": info,
        "rounds": rounds,
        "figure_workers": os.environ.get("ROTORKIN_FIGURE_WORKERS", "default"),
        "floor_s": floor,
        "rows": rows,
        "load_start": load_start,
        "load_end": load(),
    }


def markdown(result: dict) -> str:
    """The result as a markdown table."""
    lines = [
        "| case | wall s (best) | wall s (median) | CPU s | / floor | target s | load |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for r in result["rows"]:
        target = "" if r["target_s"] is None else (
            f"{r['target_s']:g} {'met' if r['met'] else 'NOT met'}")  # fmt: skip
        lines.append(f"| `{r['case']}` | {r['wall_best_s']:.2f} | {r['wall_median_s']:.2f} | "
                     f"{r['cpu_best_s']:.2f} | {r['over_floor']:.2f} | {target} | "
                     f"{r['load_min']:.1f}-{r['load_max']:.1f} |")  # fmt: skip
    cores = result["machine"]["usable_cores"]
    start, end = result["load_start"][0], result["load_end"][0]
    lines += ["", f"{cores} usable cores, {result['rounds']} warm rounds, best of them; "
              f"load {start:.1f} at start, {end:.1f} at end."]  # fmt: skip
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--examples", help="comma-separated examples (default: every one)")
    ap.add_argument("--rounds", type=int, default=5, help="warm rounds (best of them)")
    ap.add_argument("--serial", action="store_true", help="also each run's figures in 1 process")
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT, help="JSON result file")
    ap.add_argument("--markdown", type=Path, help="only print this result file as markdown")
    args = ap.parse_args(argv)
    if args.markdown is not None:
        print(markdown(json.loads(args.markdown.read_text())))
        return 0
    known = _examples()
    examples = known if not args.examples else [e.strip() for e in args.examples.split(",")]
    unknown = [e for e in examples if e not in known]
    if unknown:
        ap.error(f"unknown example(s) {', '.join(unknown)}; known: {', '.join(known)}")
    result = run(examples, max(1, args.rounds), args.serial)
    result["command"] = " ".join([COMMAND, *(sys.argv[1:] if argv is None else argv)])
    print(markdown(result))
    path = write_json(args.out, result)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
