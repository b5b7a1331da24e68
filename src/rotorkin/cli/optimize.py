"""The ``rotorkin optimize`` command: the Pareto set of several metrics over several keys.

``rotorkin optimize [CONFIG] [-e NAME] [--set K=V ...] --vary KEY=LO:HI ...
--objective max:METRIC --objective min:METRIC ... [--constraint METRIC<=VALUE ...]
[--population N] [--generations G] [--seed S] --out DIR [--resume] [--report INDEX]``
runs NSGA-II (the optional ``pymoo``: ``pip install 'rotorkin[optimize]'``) and writes
into DIR (atomically: a staging folder moved in at the end) ``pareto.nc``,
``pareto.csv``, ``pareto.png`` and ``README.txt``, and prints the front. Every
generation's designs are kept in ``DIR/.optimize/``: the same command with
``--resume`` continues an interrupted search from its last finished generation.
``--report INDEX`` also writes the outputs of ``rotorkin run`` for the front's
design INDEX into ``DIR/design_INDEX/``. See ``docs/design.md``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path
from typing import Annotated

import typer

from rotorkin import __version__
from rotorkin.cli.console import out_console, require, stages
from rotorkin.cli.formats import table_number
from rotorkin.cli.options import (
    ConfigArg,
    ExampleOpt,
    QuietOpt,
    SetOpt,
    VerboseOpt,
    flag_names,
    out_folder,
)
from rotorkin.core.batch import DEFAULT_SAMPLES
from rotorkin.design.optimize import build_spec, optimize, refused_share, write_front
from rotorkin.drives import evaluate
from rotorkin.io.config import load_config
from rotorkin.io.output import check_out, staged_output, write_outputs
from rotorkin.sweep.engine import coverage

__all__ = ["register"]


def register(app) -> None:
    """Add ``optimize`` to the typer ``app``."""

    @app.command(name="optimize")
    @flag_names(population="--population", generations="--generations", seed="--seed",
                samples="--angles")  # fmt: skip
    def optimize_(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        vary: Annotated[list[str] | None, typer.Option(
            "--vary", metavar="KEY=LO:HI",
            help="KEY=LO:HI with units, e.g. machine.casing_radius=40mm:100mm "
            "(repeatable; number and quantity keys).")] = None,
        objective: Annotated[list[str] | None, typer.Option(
            "--objective", metavar="max|min:METRIC",
            help="max:METRIC or min:METRIC, a numeric summary key "
            "(repeatable).")] = None,
        constraint: Annotated[list[str] | None, typer.Option(
            "--constraint", metavar="METRIC<=VALUE",
            help="METRIC<=VALUE or METRIC>=VALUE in the metric's unit "
            "(repeatable).")] = None,
        population: Annotated[int, typer.Option(
            "--population", metavar="N", help="Designs per generation.")] = 40,
        generations: Annotated[int, typer.Option(
            "--generations", metavar="N", help="Generations of NSGA-II.")] = 30,
        seed: Annotated[int, typer.Option(
            "--seed", metavar="N", help="Seed of NSGA-II's random draws.")] = 0,
        angles: Annotated[int | None, typer.Option(
            "--angles", metavar="N",
            help="Shaft angles per period of the sampled peaks (default 20001, "
            "as rotorkin run).")] = None,
        out: Annotated[Path, typer.Option(
            "--out", "-o", metavar="DIR", parser=out_folder,
            help="Output folder (also holds the search's "
            "state in .optimize/).")] = ...,
        resume: Annotated[bool, typer.Option(
            "--resume", help="Continue the search stored in --out (same arguments; more "
            "--generations extend it).")] = False,
        report: Annotated[int | None, typer.Option(
            "--report", metavar="INDEX",
            help="Also write the outputs of rotorkin run for the front's design "
            "INDEX (column 'index' of pareto.csv) into OUT/design_INDEX.")] = None,
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):  # fmt: skip
        """Multi-objective search (NSGA-II): the Pareto set of metrics over config keys."""

        t0 = time.perf_counter()
        require("pymoo")  # before any work
        cfg, raw, name = load_config(config, example, set_ or [])
        samples = DEFAULT_SAMPLES if angles is None else angles
        spec = build_spec(raw, vary or [], objective or [], constraint or [],
                          population=population, generations=generations, seed=seed,
                          samples=samples, name=name)  # fmt: skip
        check_out(out)
        if report is not None and report < 0:
            raise typer.BadParameter("INDEX >= 0 (column 'index' of pareto.csv)",
                                     param_hint="--report")  # fmt: skip

        def status(message):
            if not quiet:
                print(f"rotorkin: note: {message}", file=sys.stderr)

        why = coverage(cfg["drive"]["type"], cfg, [v.key for v in spec.variables],
                       spec.metrics)[2]  # fmt: skip
        if why:
            status(f"{why}: evaluated design by design by the scalar study (slow)")
        with stages("optimize") as step, staged_output(out, "optimize") as (stage, written):
            step(f"NSGA-II: {spec.generations} generations x {spec.population} designs")
            res = optimize(spec, store=out / ".optimize", resume=resume, on_status=status)
            if report is not None:
                res.config(report)  # an index off the front: refused before anything is written
            write_front(res, stage)
        report_files = []
        if report is not None:
            report_raw, report_cfg = res.config(report)
            result = evaluate(report_cfg)
            meta = {"name": f"{name} design {report}", "drive_type": cfg["drive"]["type"],
                    "rotorkin_version": __version__}  # fmt: skip
            report_files = write_outputs(result, out / f"design_{report}", report_raw, meta)
        if not quiet:
            _print(res, out, written, report, report_files, time.perf_counter() - t0)


def _print(res, out, written, report, report_files, seconds) -> None:
    from rich.table import Table

    spec = res.spec
    heads = [f"{v.key} [{v.info.unit}]" for v in spec.variables] + [
        f"{m} (constraint)" for m in spec.metrics]  # fmt: skip
    console = out_console()
    if console.is_terminal:  # wide enough for the front's columns
        console.width = max(console.width, 12 + sum(max(len(h), 10) + 3 for h in heads))
    console.print(
        f"{spec.name}: NSGA-II, {len(res.history)} generations x {spec.population} designs "
        f"(seed {spec.seed}): {res.evaluations} evaluated"
        + (f", {res.replayed} generation(s) replayed from {out}/.optimize" if res.replayed else "")
        + f", {100 * refused_share(res):.3g} % refused by the drive",
        soft_wrap=True,
    )
    table = Table(title=f"Pareto set: {res.size} designs")
    table.add_column("index", justify="right")
    for v in spec.variables:
        table.add_column(f"{v.key} [{v.info.unit}]" if v.info.unit else v.key, justify="right")
    roles = {o.metric: o.sense for o in spec.objectives}
    for m in spec.metrics:
        table.add_column(f"{m} ({roles.get(m, 'constraint')})", justify="right")
    for i in range(res.size):
        row = [str(i)] + [table_number(res.display(j)[i]) for j in range(len(spec.variables))]
        table.add_row(*row, *(table_number(v) for v in res.values[i]))
    console.print(table)
    console.print(f"wrote {out}/: {', '.join(p.name for p in written)} in {seconds:.2f} s",
                  soft_wrap=True)  # fmt: skip
    if report is not None:
        console.print(f"wrote {out}/design_{report}/: {len(report_files)} files (rotorkin run's "
                      "outputs of that design)", soft_wrap=True)  # fmt: skip
