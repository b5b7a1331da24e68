"""The ``rotorkin limits`` command: the admissible interval of one key, all constraints together.

``--format json`` (or its older spelling ``--json``) prints the interval as one JSON
object, ``--format csv`` as ``field,value`` rows; numbers at full precision.
"""

from __future__ import annotations

import math
from typing import Annotated

import typer

from rotorkin.cli.console import stages
from rotorkin.cli.formats import flat_rows, print_csv, print_json
from rotorkin.cli.options import (
    ConfigArg,
    ExampleOpt,
    FormatOpt,
    QuietOpt,
    SetOpt,
    VerboseOpt,
    check_format,
)
from rotorkin.io.config import load_config
from rotorkin.sweep.interval import (
    DEFAULT_POINTS,
    DEFAULT_POINTS_WITH_LIMITS,
    admissible_interval,
)


def _num(x: float) -> str:
    return f"{x:.10g}" if math.isfinite(x) else "n/a"


def register(app) -> None:
    """Add ``limits`` to the typer ``app``."""

    @app.command("limits")
    def limits_cmd(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        key: Annotated[
            str,
            typer.Option(
                "--key", "-k", metavar="KEY", help="The config key, e.g. drive.plate_tilt."
            ),
        ] = "",
        points: Annotated[
            int | None,
            typer.Option(
                "--points",
                metavar="N",
                help=f"Samples of the scan (default {DEFAULT_POINTS}; "
                f"with --with-limits {DEFAULT_POINTS_WITH_LIMITS}).",
            ),
        ] = None,
        with_limits: Annotated[
            bool,
            typer.Option(
                "--with-limits",
                help="Also the plausibility limits ([limits], "
                "contact stress): a full study per sample.",
            ),
        ] = False,
        as_json: Annotated[bool, typer.Option("--json", help="The same as --format json.")] = False,
        fmt: FormatOpt = "table",
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):
        """Print the admissible interval of one key, every other key held, and what binds."""
        from rotorkin.core.errors import ParameterError

        fmt = "json" if as_json else check_format(fmt)
        if not key:
            raise ParameterError("--key", "''", "a numeric config key, e.g. drive.plate_tilt")
        with stages("limits") as step:
            step("reading the config")
            _, raw, name = load_config(config, example, set_ or [])
            step(f"scanning {key}")
            r = admissible_interval(raw, key, points=points, with_limits=with_limits)
        if quiet:
            return
        if fmt in ("json", "csv"):
            doc = {
                "name": name, "key": r.key, "unit": r.unit, "value": r.value,
                "admissible": r.value_admissible, "reason": r.value_reason,
                "lo": r.lo if r.value_admissible else None,
                "hi": r.hi if r.value_admissible else None,
                "lo_binds": r.lo_binds, "hi_binds": r.hi_binds,
                "intervals": [list(i) for i in r.intervals], "points": r.points,
                "values": list(r.values),
            }  # fmt: skip
            if fmt == "json":
                print_json(doc)
            else:
                print_csv(("field", "value"), flat_rows(doc))
            return
        unit = f" {r.unit}" if r.unit else ""
        typer.echo(f"{name}: {r.key} = {_num(r.value)}{unit}")
        if r.values:
            typer.echo(f"admissible values: {', '.join(str(v) for v in r.values)}")
            if not r.value_admissible:
                typer.echo(f"not admissible: {r.value_reason}")
            return
        if r.value_admissible:
            typer.echo(f"admissible from {_num(r.lo)}{unit} to {_num(r.hi)}{unit}")
            typer.echo(f"  at {_num(r.lo)}{unit}: {r.lo_binds}")
            typer.echo(f"  at {_num(r.hi)}{unit}: {r.hi_binds}")
        else:
            typer.echo(f"not admissible: {r.value_reason}")
        others = [i for i in r.intervals if not (i[0] <= r.value <= i[1])]
        if others:
            shown = ", ".join(f"{_num(a)}..{_num(b)}{unit}" for a, b in others)
            typer.echo(f"other admissible stretches: {shown}")
        if not r.intervals:
            typer.echo(f"no admissible value among the {r.points} scanned")
