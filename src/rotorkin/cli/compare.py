"""The ``rotorkin compare`` command: one vane machine on several drives, same displacement."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import numpy as np
import typer

from rotorkin.cli.console import out_console, stages
from rotorkin.cli.formats import table_number
from rotorkin.cli.options import ConfigArg, ExampleOpt, QuietOpt, SetOpt, VerboseOpt, out_option
from rotorkin.compare import ROWS, compare, plot_comparison
from rotorkin.core.errors import ConfigError
from rotorkin.io.config import load_config
from rotorkin.io.output import check_out, staged_output


def _plain(v):
    v = v.item() if isinstance(v, np.generic) else v
    return None if isinstance(v, float) and not np.isfinite(v) else v


def register(app) -> None:
    """Add ``compare`` to the typer ``app``."""

    @app.command("compare")
    def compare_drives(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        drive: Annotated[
            list[str] | None,
            typer.Option(
                "--drive",
                "-d",
                metavar="NAME[=CONFIG]",
                help="Another drive: NAME (its example's design) or NAME=CONFIG (the [drive] of "
                "that file). Repeatable; the config's own drive comes first.",
            ),
        ] = None,
        out: out_option("./rotorkin-out/<name>-compare") = None,  # fmt: skip
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):
        """Run the config's vane machine on several drives sized to the same displacement."""
        if not drive:
            raise ConfigError("--drive is missing: name at least one drive to compare with, e.g. "
                              "--drive noncircular_gears")  # fmt: skip
        with stages("compare") as step:
            step("reading the config")
            _, raw, name = load_config(config, example, set_ or [])
            outdir = out if out is not None else Path("rotorkin-out") / f"{name}-compare"
            check_out(outdir)
            step(f"running the machine on {len(drive) + 1} drives")
            result = compare(raw, drive)
        if len(result.results) < 2:
            why = "; ".join(f"{k}: {v}" for k, v in result.refused.items())
            raise ConfigError(f"--drive is not admissible: no other drive carries the machine "
                              f"({why})")  # fmt: skip
        table = result.table()
        doc = {
            "machine": result.machine,
            "drives": list(result.results),
            "rows": {k: {n: _plain(v) for n, v in row.items()} for k, row in table.items()},
            "meaning": ROWS,
            "refused": result.refused,
        }
        with stages("compare output") as step, staged_output(outdir, "compare") as (stage, written):
            step("writing the outputs and drawing the figures")
            (stage / "compare.json").write_text(json.dumps(doc, indent=2) + "\n")
            plot_comparison(result, stage)
        if quiet:
            return
        from rich.table import Table

        console = out_console()
        t = Table(title=f"{result.machine} on {len(result.results)} drives, same displacement")
        t.add_column("metric")
        for label in result.results:
            t.add_column(label, justify="right")
        for key, row in table.items():
            t.add_row(key, *(table_number(v) for v in row.values()))
        console.print(t)
        for label, why in result.refused.items():
            console.print(f"{label}: does not carry the machine: {why}", soft_wrap=True)
        console.print(f"wrote {outdir}/: {', '.join(p.name for p in written)}", soft_wrap=True)
