"""The ``rotorkin synthesize`` command: registered on the main app by :func:`register`.

``rotorkin synthesize [CONFIG] [--example NAME] [--set K=V ...] --objective NAME
[--target VALUE] [--harmonics N] [--max-pressure-angle ANGLE] [--out DIR]``
prints the baseline design beside the synthesized one and writes, into DIR
(atomically: a staging folder next to it, moved in at the end):
``synthesis.json`` (parameters, metrics, the table), ``synthesized.toml`` (a
complete config ``rotorkin run`` accepts), CSV tables and PNG figures.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated

import numpy as np
import typer

from rotorkin import __version__
from rotorkin.cli.console import out_console, stages
from rotorkin.cli.options import (
    ConfigArg,
    ExampleOpt,
    QuietOpt,
    SetOpt,
    VerboseOpt,
    flag_names,
    out_option,
)
from rotorkin.core.errors import RotorkinError
from rotorkin.drives import REGISTRY
from rotorkin.drives import synthesize as run_synthesis
from rotorkin.io.config import load_config
from rotorkin.io.output import staged_output, to_toml
from rotorkin.synthesis import fmt, parse_quantity_arg, synthesized_raw_config

__all__ = ["register", "write_synthesis"]


def _objective_help() -> str:
    """``--objective`` help: the objectives of every registered drive."""
    rows = [f"{k}: {', '.join(s.objectives)}" for k, s in REGISTRY.items() if s.objectives]
    return "What to synthesize, by drive type: " + "; ".join(rows) + "."


def _target_help() -> str:
    """``--target`` help: what each objective's target is."""
    rows = [
        f"{objective} ({kind}): {what}"
        for kind, spec in REGISTRY.items()
        for objective, what in spec.objectives.items()
    ]
    return "What the objective aims at, by objective: " + "; ".join(rows) + "."


def _option_help(option: str, what: str) -> str:
    """Help of an option that only some drives take."""
    takers = [k for k, s in REGISTRY.items() if option in s.synthesis_options]
    return f"{what} (drive.type {', '.join(takers)})."


def register(app) -> None:
    """Add ``synthesize`` to the typer ``app``."""

    @app.command()
    @flag_names(
        objective="--objective",
        target="--target",
        harmonics="--harmonics",
        max_pressure_angle="--max-pressure-angle",
    )
    def synthesize(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        objective: Annotated[
            str | None,
            typer.Option(
                "--objective",
                metavar="NAME",
                help=_objective_help(),
            ),
        ] = None,
        target: Annotated[
            str | None,
            typer.Option(
                "--target",
                metavar="VALUE",
                help=_target_help(),
            ),
        ] = None,
        harmonics: Annotated[
            int | None,
            typer.Option(
                "--harmonics",
                metavar="N",
                help=_option_help(
                    "harmonics",
                    "Harmonics of the synthesized law: higher odd harmonics to optimise, or the "
                    "highest harmonic of a correction (default: as the drive's synthesis needs)",
                ),
            ),
        ] = None,
        max_pressure_angle: Annotated[
            str | None,
            typer.Option(
                "--max-pressure-angle",
                metavar="ANGLE",
                help=_option_help(
                    "max_pressure_angle",
                    'Bound on the peak pressure angle, 0 < angle < 90 deg (e.g. "55 deg"; '
                    "default: 45 deg or the baseline law's peak, whichever is larger)",
                ),
            ),
        ] = None,
        out: out_option("./rotorkin-out/<name>-<objective>") = None,
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):
        """Synthesize a design for an objective; compare it with the config's (the paper's)."""

        cfg, raw, name = load_config(config, example, set_ or [])
        kind = cfg["drive"]["type"]
        if objective is None:
            raise RotorkinError(
                f"--objective is missing: choose one of {', '.join(REGISTRY[kind].objectives)} "
                f"for drive.type = {kind}"
            )
        limit = (
            None
            if max_pressure_angle is None
            else parse_quantity_arg(max_pressure_angle, "angle", "--max-pressure-angle")
        )
        with stages("synthesize") as step:
            step(f"synthesizing for {objective}")
            result = run_synthesis(cfg, raw, objective, target, harmonics, limit)
        new_raw = synthesized_raw_config(raw, result.updates, objective)
        outdir = out if out is not None else Path("rotorkin-out") / f"{name}-{objective}"
        meta = {
            "name": name,
            "drive_type": kind,
            "objective": objective,
            "target": target,
            "rotorkin_version": __version__,
        }
        with stages("synthesize output") as step:
            step("writing the outputs and drawing the figures")
            written = write_synthesis(result, new_raw, outdir, meta)
        if not quiet:
            _print(result, outdir, written)


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _write_csv(path: Path, columns: dict) -> None:
    names = list(columns)
    data = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    np.savetxt(path, data, delimiter=",", header=",".join(names), comments="", fmt="%.12g")


def write_synthesis(result, new_raw: dict, outdir: Path, meta: dict) -> list[Path]:
    """Write synthesis.json, synthesized.toml, the CSV tables and the figures into ``outdir``.

    Everything goes into a staging folder next to ``outdir`` first and is moved
    in (``os.replace``) only when all of it has been written.

    Returns
    -------
    list of Path
        The files written.
    """

    with staged_output(outdir, "synthesize") as (stage, written):
        doc = {
            **meta,
            "title": result.title,
            "parameters": result.parameters,
            "metrics": result.metrics,
            "table": [{"metric": m, "baseline": b, "synthesized": s} for m, b, s in result.rows],
            "notes": list(result.notes),
            "updates": result.updates,
        }
        (stage / "synthesis.json").write_text(json.dumps(_jsonable(doc), indent=2) + "\n")
        (stage / "synthesized.toml").write_text(to_toml(new_raw))
        for fname, columns in result.tables.items():
            _write_csv(stage / fname, columns)
        result.plot(stage)
    return written


def _print(result, outdir, written):
    from rich.table import Table

    console = out_console()
    console.print(result.title, highlight=False, soft_wrap=True)
    table = Table()
    table.add_column("metric")
    table.add_column("baseline", justify="right")
    table.add_column("synthesized", justify="right")
    for metric, base, synth in result.rows:
        table.add_row(metric, fmt(base), fmt(synth))
    console.print(table)
    for line in result.notes:
        console.print(line, highlight=False, soft_wrap=True)
    names = ", ".join(p.name for p in written)
    console.print(f"wrote {outdir}/: {names}", highlight=False, soft_wrap=True)
