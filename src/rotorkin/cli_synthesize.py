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

from rotorkin.cli_options import ConfigArg, ExampleOpt, QuietOpt, SetOpt
from rotorkin.errors import RotorkinError

__all__ = ["register", "write_synthesis"]


def _objective_help() -> str:
    from rotorkin.synthesis import OBJECTIVES

    return "; ".join(f"{kind}: {', '.join(names)}" for kind, (_, names) in OBJECTIVES.items())


def register(app) -> None:
    """Add ``synthesize`` to the typer ``app``."""

    @app.command()
    def synthesize(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        objective: Annotated[
            str | None,
            typer.Option(
                "--objective",
                help="What to synthesize, by drive type: rhomboid_cam: min_accel, dwell_min, "
                "dwell_max, min_pressure_angle; wobble_cam: sine_chamber, dwell_min_volume; "
                "guide_bar: vane_angle; eccentric_cam: gap_change.",
            ),
        ] = None,
        target: Annotated[
            str | None,
            typer.Option(
                "--target",
                help="What the objective aims at, by objective: dwell_min_volume (wobble_cam): "
                'the dwell fraction at minimum volume ("0.12" or "12 %"; default: the longest '
                "dwell whose grooves the roller can follow, the range is checked); vane_angle "
                '(guide_bar): the vane angle gamma_0 ("60 deg"; default 60 deg, or the middle of '
                "the reachable range if 60 deg is not reachable); gap_change (eccentric_cam): the "
                'tolerated peak gap change ("1 %" or "0.01" of L, or "5 mm"; default: half the '
                "config's own). No target for sine_chamber (a fixed law) nor for the "
                "rhomboid_cam objectives min_accel, dwell_min, dwell_max, min_pressure_angle "
                "(optimised).",
            ),
        ] = None,
        harmonics: Annotated[
            int | None,
            typer.Option(
                "--harmonics",
                help="Rhomboid cam: higher odd harmonics to optimise (default 2: 3rd and 5th). "
                "Wobble cam: highest harmonic of the spin correction (default: as needed).",
            ),
        ] = None,
        max_pressure_angle: Annotated[
            str | None,
            typer.Option(
                "--max-pressure-angle",
                help="Rhomboid and wobble cams: bound on the peak pressure angle, 0 < angle < "
                '90 deg (e.g. "55 deg"; default: 45 deg or the baseline law\'s peak, whichever '
                "is larger; wobble cam: that of the best-placed roller).",
            ),
        ] = None,
        out: Annotated[
            Path | None,
            typer.Option(
                "--out", "-o", help="Output folder; default ./rotorkin-out/<name>-<objective>."
            ),
        ] = None,
        quiet: QuietOpt = False,
    ):
        """Synthesize a design for an objective; compare it with the config's (the paper's)."""
        from rotorkin import __version__
        from rotorkin.io.config import load_config
        from rotorkin.synthesis import OBJECTIVES, parse_quantity_arg, synthesized_raw_config
        from rotorkin.synthesis import synthesize as run_synthesis

        cfg, raw, name = load_config(config, example, set_ or [])
        kind = cfg["drive"]["type"]
        if objective is None:
            raise RotorkinError(
                f"--objective is missing: choose one of {', '.join(OBJECTIVES[kind][1])} "
                f"for drive.type = {kind}"
            )
        limit = (
            None
            if max_pressure_angle is None
            else parse_quantity_arg(max_pressure_angle, "angle", "--max-pressure-angle")
        )
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
    from rotorkin.io.output import staged_output, to_toml

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
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    from rotorkin.synthesis import fmt

    console = Console()
    console.print(escape(result.title), highlight=False, soft_wrap=True)
    table = Table()
    table.add_column("metric")
    table.add_column("baseline", justify="right")
    table.add_column("synthesized", justify="right")
    for metric, base, synth in result.rows:
        table.add_row(escape(metric), escape(fmt(base)), escape(fmt(synth)))
    console.print(table)
    for line in result.notes:
        console.print(escape(line), highlight=False, soft_wrap=True)
    names = ", ".join(p.name for p in written)
    console.print(f"wrote {outdir}/: {names}", highlight=False, soft_wrap=True)
