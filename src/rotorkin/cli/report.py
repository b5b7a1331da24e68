"""The ``rotorkin report`` command: one interactive, offline HTML page of a run.

Registered on the main app by :func:`register`. ``rotorkin run ... --report``
writes the same page next to the other outputs. The page needs plotly, the
optional ``report`` extra (``pip install "rotorkin[report]"``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rotorkin import __version__
from rotorkin.cli.console import require, stages
from rotorkin.cli.options import ConfigArg, ExampleOpt, QuietOpt, SetOpt, VerboseOpt, out_option
from rotorkin.core.errors import ConfigError
from rotorkin.drives import evaluate
from rotorkin.io.config import load_config
from rotorkin.studies.limits import refuse


def register(app) -> None:
    """Add ``report`` to the typer ``app``."""

    @app.command()
    def report(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        out: out_option("./rotorkin-out/<name>") = None,
        strict: Annotated[
            bool,
            typer.Option(
                "--strict", help="Refuse a design past a plausibility limit ([limits]), exit 2."
            ),
        ] = False,
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):
        """Write report.html: summary vs the paper, checks, animated mechanism, plots (offline)."""
        from rotorkin.report.html import write_report

        require("plotly")  # before any work
        with stages("report") as step:
            step("reading the config")
            cfg, raw, name = load_config(config, example, set_ or [])
            outdir = out if out is not None else Path("rotorkin-out") / name
            if outdir.exists() and not outdir.is_dir():
                raise ConfigError(
                    f"--out = {str(outdir)!r} is not admissible: it is a file, not a folder"
                )
            step("evaluating the design")
            result = evaluate(cfg)
            if strict:
                refuse(result)  # before anything is written
            meta = {"name": name, "drive_type": cfg["drive"]["type"],
                    "rotorkin_version": __version__}  # fmt: skip
            step("writing the report")
            path = write_report(result, cfg, raw, meta, outdir / "report.html")
        if not quiet:
            typer.echo(str(path))
