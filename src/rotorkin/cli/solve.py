"""The ``rotorkin solve`` command: one config key for one metric's target value.

``rotorkin solve [CONFIG] [-e NAME] [--set K=V ...] --for KEY --target METRIC=VALUE
[--within LO:HI] [--out DIR]`` prints the key's value (in the unit people read),
the metric reached, the residual and what bounds the search on either side; with
``--out`` it writes ``config.toml`` (the config with the key set, ready for
``rotorkin run``) and ``solve.json`` (atomically). A target out of reach is one
line naming the range the metric covers, exit 2. ``--format json`` prints the
record of ``solve.json``, ``--format csv`` the same as ``field,value`` rows (numbers
at full precision). See ``docs/design.md``.
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path
from typing import Annotated

import typer

from rotorkin import __version__
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
    flag_names,
    out_folder,
)
from rotorkin.core.errors import ConfigError, shown
from rotorkin.design import solve as solve_for
from rotorkin.io.config import load_config
from rotorkin.io.output import check_out, staged_output, to_toml

__all__ = ["register", "parse_target"]


def parse_target(text: str) -> tuple[str, float]:
    """``"METRIC=VALUE"`` -> ``(metric, value)``; one line when it is not that."""
    metric, eq, value = str(text).partition("=")
    metric, value = metric.strip(), value.strip()
    if not eq or not metric or not value:
        raise ConfigError(f"--target {shown(text)} is not admissible: write it as METRIC=VALUE, "
                          "e.g. flow_mean_l_per_min=20")  # fmt: skip
    try:
        number = float(value)
    except ValueError:
        number = math.nan
    if not math.isfinite(number):
        raise ConfigError(f"--target {metric} = {shown(value)} is not admissible: a finite number "
                          "in the metric's unit (its name's suffix: _mm, _deg, _l_per_min, "
                          "...)")  # fmt: skip
    return metric, number


def _within(text: str | None):
    if text is None:
        return None
    parts = str(text).split(":")
    if len(parts) != 2 or not all(p.strip() for p in parts):
        raise ConfigError(f"--within {shown(text)} is not admissible: write it as LO:HI with "
                          "units, e.g. 30mm:60mm")  # fmt: skip
    return parts[0].strip(), parts[1].strip()


def register(app) -> None:
    """Add ``solve`` to the typer ``app``."""

    @app.command()
    @flag_names(scan="--scan")
    def solve(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        for_: Annotated[str, typer.Option(
            "--for", metavar="KEY", help="The config key to solve for: a number or quantity key "
            "(rotorkin keys), e.g. machine.casing_radius.")] = ...,
        target: Annotated[str, typer.Option(
            "--target", metavar="METRIC=VALUE", help="A numeric summary key (summary.json of "
            "rotorkin run, or a sweep metric) and its target in the unit of the name's "
            "suffix.")] = ...,
        within: Annotated[str | None, typer.Option(
            "--within", metavar="LO:HI", help="Search only LO:HI of the key, with units (e.g. "
            "30mm:60mm); default: its whole admissible range.")] = None,
        scan: Annotated[int | None, typer.Option(
            "--scan", metavar="N", help="Values per spacing of the coarse scan (default 129 "
            "with a sweep kernel, 12 through the study).")] = None,
        out: Annotated[Path | None, typer.Option(
            "--out", "-o", metavar="DIR", parser=out_folder,
            help="Write config.toml (the solved config) and solve.json here.")] = None,
        fmt: FormatOpt = "table",
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):  # fmt: skip
        """Find the value of one config key at which one metric hits a target."""

        t0 = time.perf_counter()
        fmt = check_format(fmt)
        with stages("solve") as step:
            step("reading the config")
            cfg, raw, name = load_config(config, example, set_ or [])
            metric, value = parse_target(target)
            if out is not None:
                check_out(out)  # before any work
            step(f"solving for {for_}")
            res = solve_for(raw, for_, metric, value, within=_within(within), scan=scan)
        seconds = time.perf_counter() - t0
        written = []
        doc = {"name": name, "drive_type": cfg["drive"]["type"],
               "rotorkin_version": __version__, **res.to_dict()}  # fmt: skip
        if out is not None:
            with staged_output(out, "solve") as (stage, written):
                (stage / "config.toml").write_text(to_toml(res.raw))
                (stage / "solve.json").write_text(json.dumps(doc, indent=2) + "\n")
        for line in res.warnings:  # once the outputs stand, as rotorkin run
            print(f"rotorkin: warning: {' '.join(str(line).split())}", file=sys.stderr)
        if quiet:
            return
        if fmt == "table":
            _print(name, res, out, written, seconds)
            return
        doc["files"] = [p.name for p in written]
        if fmt == "json":
            print_json(doc)
        else:
            print_csv(("field", "value"), flat_rows(doc))


def _end(info, end) -> str:
    what = {"schema": "", "drive": "the drive refuses beyond: ", "range": "", "search": "",
            "metric": ""}[end.source]  # fmt: skip
    return f"{info.show(end.value)} ({what}{end.detail})"


def _print(name, res, out, written, seconds) -> None:
    info = res.info
    unit = "" if res.metric_unit == "1" else f" {res.metric_unit}"
    lines = [
        f"{name}: {res.key} = {res.value * info.factor:.12g}{' ' + info.unit if info.unit else ''}"
        f" gives {res.metric} = {res.reached:.12g}{unit}",
        f"  target {res.target:.12g}{unit}, residual {res.residual:.3g} (relative "
        f"{res.relative_residual:.2g})",
        "  started from "
        + ("the drive's default" if res.start is None else info.show(res.start))
        + f"; {res.evaluations} designs evaluated by the "
        + ("sweep kernel" if res.kernel else "scalar study")
        + f" in {seconds:.2f} s",
        f"  the scan saw {res.roots_seen} root{'s' if res.roots_seen != 1 else ''}"
        + ("; the one nearest the start is reported" if res.roots_seen > 1 else ""),
        f"  admissible stretch searched: from {_end(info, res.lower)}",
        f"                               to {_end(info, res.upper)}",
    ]
    if written:
        lines.append(f"wrote {out}/: {', '.join(p.name for p in written)}")
    for line in lines:
        typer.echo(line)
