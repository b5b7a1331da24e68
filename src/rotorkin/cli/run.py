"""The ``rotorkin run``, ``examples`` and ``keys`` commands: registered by :func:`register`.

``rotorkin run`` evaluates a config (or the default example), writes its outputs
(``summary.json``, ``motion.csv``, ``config.toml``, ``checks.csv``, ``README.txt``
and the figures; ``--no-figures`` leaves the figures out, ``--report`` adds the
HTML report) and prints the summary as a table, JSON or CSV (``--format``). The
figures are drawn by forked processes, one per core
(:func:`rotorkin.render.figures.draw`; ``$ROTORKIN_FIGURE_WORKERS`` sets their number),
the first forked before the study, importing matplotlib while the study computes
(:func:`rotorkin.render.figures.drawing_ahead`).
"""

from __future__ import annotations

import contextlib
import dataclasses
import gc
import sys
from pathlib import Path
from typing import Annotated

import typer

from rotorkin import __version__
from rotorkin.cli.console import one_line, require, stages
from rotorkin.cli.formats import print_run_summary
from rotorkin.cli.options import (
    ConfigArg,
    ExampleOpt,
    FormatOpt,
    QuietOpt,
    SetOpt,
    VerboseOpt,
    check_format,
    out_option,
)
from rotorkin.core.errors import RotorkinError
from rotorkin.drives import REGISTRY, evaluate
from rotorkin.io.config import example_names, example_path, glossary, load_config, read_toml
from rotorkin.io.output import check_out, write_outputs
from rotorkin.render.figures import RUN_STYLE, drawing_ahead

__all__ = ["register"]


@contextlib.contextmanager
def _frozen():
    """The objects that exist now (the libraries, the drive) out of the garbage collector's
    passes for the block (``gc.freeze``): the study's passes scan its own objects only."""
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()


def register(app) -> None:
    """Add ``run``, ``examples`` and ``keys`` to the typer ``app``."""

    @app.command()
    def run(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        out: out_option("./rotorkin-out/<name>") = None,
        report: Annotated[bool, typer.Option(
            "--report", help='Also write report.html (interactive, offline; the "report" '
            "extra).")] = False,
        strict: Annotated[bool, typer.Option(
            "--strict", help="Refuse a design past a plausibility limit ([limits]), "
            "exit 2.")] = False,
        figures: Annotated[bool, typer.Option(
            "--figures/--no-figures", help="Draw the PNG figures (the slowest part of a "
            "run; drawn by the machine's cores, ROTORKIN_FIGURE_WORKERS=1 for one "
            "process).")] = True,
        fmt: FormatOpt = "table",
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):  # fmt: skip
        """Evaluate a drive over one period; write summary.json, motion.csv and figures."""
        fmt = check_format(fmt)
        if report:
            require("plotly")  # before any work
        with stages("run") as step:
            step("reading the config")
            cfg, raw, name = load_config(config, example, set_ or [])
            outdir = out if out is not None else Path("rotorkin-out") / name
            check_out(outdir)  # before any work
            step("evaluating the design")
            with drawing_ahead(RUN_STYLE) if figures else contextlib.nullcontext():
                with _frozen():
                    result = evaluate(cfg)
                if strict:
                    from rotorkin.studies.limits import refuse

                    refuse(result)  # before anything is written
                if not figures:
                    result = dataclasses.replace(result, write_figures=lambda outdir: [])
                meta = {"name": name, "drive_type": cfg["drive"]["type"],
                        "rotorkin_version": __version__}  # fmt: skip
                step("writing the outputs and drawing the figures" if figures else
                     "writing the outputs")  # fmt: skip
                written = write_outputs(result, outdir, raw, meta)
            if report:
                step("writing the report")
                from rotorkin.report.html import write_report

                written = [*written, write_report(result, cfg, raw, meta, outdir / "report.html")]
        for line in result.warnings:  # once the outputs stand: a failure stays one line
            print(f"rotorkin: warning: {one_line(line)}", file=sys.stderr)
        if not quiet:
            print_run_summary(result, name, outdir, written, fmt)

    @app.command()
    def examples(quiet: QuietOpt = False, verbose: VerboseOpt = False):
        """List the built-in examples (run one with: rotorkin run --example NAME)."""
        if quiet:
            return
        for name in example_names():
            title = read_toml(example_path(name)).get("title", "")
            typer.echo(f"{name:20s} {title}")

    @app.command()
    def keys(
        drive_type: Annotated[str | None, typer.Argument(
            metavar="DRIVE_TYPE", help=f"Only this drive type ({', '.join(REGISTRY)}).")]
        = None,
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):  # fmt: skip
        """List every config key with its default and meaning (the glossary)."""
        if drive_type is not None and drive_type not in REGISTRY:
            choices = ", ".join(REGISTRY)
            raise RotorkinError(
                f"DRIVE_TYPE = {drive_type!r} is not admissible: choose one of {choices}"
            )
        if quiet:
            return
        for kind, key, default, doc in glossary():
            if drive_type in (None, kind):
                typer.echo(f"{kind:14s} {key:28s} {default:14s} {doc}")
