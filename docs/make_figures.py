"""Draw every figure of ``docs/img`` again, from the current code.

    python docs/make_figures.py                       # all of them, into docs/img
    python docs/make_figures.py --only design_pump_pareto.png --out /tmp/img

Each figure is what a documented command or call draws, copied under the name the
documents use:

* ``wobble_chamber_angle.png`` (README): ``fig10_chamber_angle.png`` of the default
  example, as ``rotorkin run`` writes it;
* ``design_pump_pareto.png`` (``docs/design.md``): ``pareto.png`` of the pump's worked
  example, ``rotorkin optimize -e guide-bar-pump ... --seed 1`` through the library.

:data:`FIGURES` is the list: ``tests/test_docs_figures.py`` checks that it names exactly
the files of ``docs/img`` and draws one of them again.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

IMG = Path(__file__).resolve().parent / "img"


def _wobble_chamber_angle(work: Path) -> Path:
    from rotorkin.drives import evaluate
    from rotorkin.io.config import load_config

    cfg, _, _ = load_config()  # the default example, rotorkin run's
    result = evaluate(cfg)
    written = {p.name: p for p in result.write_figures(work)}
    return written["fig10_chamber_angle.png"]


def _design_pump_pareto(work: Path) -> Path:
    from rotorkin.design.optimize import build_spec, optimize, write_front
    from rotorkin.io.config import load_config

    _, raw, _ = load_config(None, "guide-bar-pump")
    spec = build_spec(
        raw,
        ["drive.lambda=0.1:0.8", "machine.casing_radius=40mm:100mm"],
        ["max:flow_mean_l_per_min", "min:input_torque_fluctuation_ratio"],
        ["input_torque_max_Nm<=7"],
        population=24,
        generations=30,
        seed=1,
        name="guide-bar-pump",
    )
    write_front(optimize(spec), work)
    return work / "pareto.png"


#: File name in ``docs/img`` -> the function that draws it into a folder and returns its path.
FIGURES: dict[str, Callable[[Path], Path]] = {
    "wobble_chamber_angle.png": _wobble_chamber_angle,
    "design_pump_pareto.png": _design_pump_pareto,
}


def make(names=None, out: Path = IMG) -> list[Path]:
    """Draw the figures ``names`` (default: all) and write them into ``out``."""
    names = list(FIGURES) if names is None else list(names)
    unknown = sorted(set(names) - set(FIGURES))
    if unknown:
        raise SystemExit(f"make_figures: unknown figure(s) {unknown}; choose from {list(FIGURES)}")
    os.environ.setdefault("MPLBACKEND", "Agg")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name in names:
        with tempfile.TemporaryDirectory() as tmp:
            drawn = FIGURES[name](Path(tmp))
            target = out / name
            shutil.copyfile(drawn, target)
        written.append(target)
    return written


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", action="append", metavar="NAME", help="one figure (repeatable)")
    ap.add_argument("--out", type=Path, default=IMG, help="folder (default: docs/img)")
    args = ap.parse_args(argv)
    for path in make(args.only, args.out):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
