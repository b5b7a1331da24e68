"""The ``rotorkin`` command: thin; parses, calls the library, prints, sets the exit code.

Exit codes: 0 success, 2 bad input (one line on stderr, no traceback, no
output files), 3 the machine failed us (disk full, no permission: one line saying
what to do, no output files), 1 an internal error (one line; ``ROTORKIN_DEBUG=1``
shows the traceback).
"""

from __future__ import annotations

import contextlib
import errno
import math
import os
import signal
import sys
import threading
import warnings
from pathlib import Path
from typing import Annotated

import numpy as np
import typer

from rotorkin import __version__
from rotorkin.cli import compare as cli_compare
from rotorkin.cli import export as cli_export
from rotorkin.cli import limits as cli_limits
from rotorkin.cli import optimize as cli_optimize
from rotorkin.cli import report as cli_report
from rotorkin.cli import solve as cli_solve
from rotorkin.cli import sweep as cli_sweep
from rotorkin.cli import synthesize as cli_synthesize
from rotorkin.cli.options import ConfigArg, ExampleOpt, QuietOpt, SetOpt, out_folder
from rotorkin.cli.tables import print_checks
from rotorkin.core.errors import RotorkinError
from rotorkin.drives import REGISTRY, evaluate
from rotorkin.io.config import example_names, example_path, glossary, load_config, read_toml
from rotorkin.io.output import check_out, write_outputs
from rotorkin.report.html import write_report
from rotorkin.studies.limits import refuse

app = typer.Typer(
    name="rotorkin",
    help="Design the drives of rotary variable-volume machines: kinematics, volumes, torques.",
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)


def _version(value: bool):
    if value:
        typer.echo(f"rotorkin {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Print the version.")
    ] = False,
):
    """rotorkin: exact kinematics, volumes and torques of the drives of rotary machines."""


@app.command()
def run(
    config: ConfigArg = None,
    example: ExampleOpt = None,
    set_: SetOpt = None,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", "-o", parser=out_folder, help="Output folder; default ./rotorkin-out/<name>."
        ),
    ] = None,
    quiet: QuietOpt = False,
    report: Annotated[
        bool, typer.Option("--report", help="Also write report.html (interactive, offline).")
    ] = False,
    strict: Annotated[
        bool,
        typer.Option(
            "--strict", help="Refuse a design past a plausibility limit ([limits]), exit 2."
        ),
    ] = False,
):
    """Evaluate a drive over one period; write summary.json, motion.csv and figures."""

    cfg, raw, name = load_config(config, example, set_ or [])
    outdir = out if out is not None else Path("rotorkin-out") / name
    check_out(outdir)  # before any work
    result = evaluate(cfg)
    if strict:
        refuse(result)  # before anything is written
    meta = {"name": name, "drive_type": cfg["drive"]["type"], "rotorkin_version": __version__}
    written = write_outputs(result, outdir, raw, meta)
    if report:
        written = [*written, write_report(result, cfg, raw, meta, outdir / "report.html")]
    for line in result.warnings:  # once the outputs stand: a failure stays one line
        print(f"rotorkin: warning: {_one_line(line)}", file=sys.stderr)
    if not quiet:
        _print_summary(result, name, outdir, written)


@app.command()
def examples():
    """List the built-in examples (run one with: rotorkin run --example NAME)."""

    for name in example_names():
        title = read_toml(example_path(name)).get("title", "")
        typer.echo(f"{name:20s} {title}")


@app.command()
def keys(
    drive_type: Annotated[
        str | None, typer.Argument(help=f"Only this drive type ({', '.join(REGISTRY)}).")
    ] = None,
):
    """List every config key with its default and meaning (the glossary)."""

    if drive_type is not None and drive_type not in REGISTRY:
        choices = ", ".join(REGISTRY)
        raise RotorkinError(
            f"DRIVE_TYPE = {drive_type!r} is not admissible: choose one of {choices}"
        )
    for kind, key, default, doc in glossary():
        if drive_type in (None, kind):
            typer.echo(f"{kind:14s} {key:28s} {default:14s} {doc}")


def _print_summary(result, name, outdir, written):
    from rich.console import Console
    from rich.table import Table

    console = Console(markup=False, highlight=False)
    console.print(f"{name}: {result.title}", highlight=False, soft_wrap=True)
    table = Table()
    table.add_column("metric", no_wrap=True)
    table.add_column("value", justify="right")
    meanings = result.headline if isinstance(result.headline, dict) else {}
    if meanings:
        table.add_column("meaning")
    for key in result.headline:
        value = result.summary[key]
        if isinstance(value, float):
            shown = f"{value:.6g}" if math.isfinite(value) else "n/a"
        else:
            shown = str(value)
        table.add_row(key, shown, *([meanings[key]] if meanings else []))
    console.print(table)
    print_checks(console, result.checks)
    figures = [p.name for p in written if p.suffix == ".png"]
    checks = "checks.csv, " if result.checks else ""
    console.print(
        f"wrote {outdir}/: summary.json, motion.csv, config.toml, {checks}README.txt, "
        f"{len(figures)} figures ({', '.join(figures)})",
        highlight=False,
        soft_wrap=True,
    )


# Commands that live in their own modules (cad export, synthesis, html report, sweeps):
# each module has register(app), which adds its commands.
for _module in (cli_export, cli_synthesize, cli_report, cli_sweep, cli_compare, cli_limits,
                cli_solve, cli_optimize):  # fmt: skip
    _module.register(app)


class Terminated(BaseException):
    """SIGTERM, raised where the program stands so that every ``finally`` cleans up."""


def _raise_terminated(signum, frame):
    raise Terminated


def _on_sigterm():
    """Turn SIGTERM into :class:`Terminated` (main thread only); the previous handler."""
    if threading.current_thread() is not threading.main_thread():
        return None
    return signal.signal(signal.SIGTERM, _raise_terminated)


#: Exit code of a failure of the machine rather than the input (disk full, no permission).
ENVIRONMENT_ERROR = 3

_WHAT_TO_DO = {
    errno.ENOSPC: "the disk is full: free some space or write elsewhere with --out",
    errno.EDQUOT: "the disk quota is used up: free some space or write elsewhere with --out",
    errno.EACCES: "permission denied: write elsewhere with --out, or fix the folder's permissions",
    errno.EPERM: "operation not permitted: write elsewhere with --out",
    errno.EROFS: "the file system is read-only: write elsewhere with --out",
    errno.ENOMEM: "out of memory: ask for fewer points, designs or samples",
}


#: Characters that end a line for Python's ``str.splitlines`` (and for terminals).
_LINE_BREAKS = "\n\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029"


def _one_line(text: str) -> str:
    """A message on one line: line breaks a user typed are shown escaped (``\\n``)."""
    return "".join(c.encode("unicode_escape").decode() if c in _LINE_BREAKS else c for c in text)


def _environment_message(exc: OSError) -> str:
    """One line: what failed and what to do; nothing was left behind."""
    what = _WHAT_TO_DO.get(exc.errno, "the system refused; check the output folder and retry")
    where = f" ({exc.filename})" if getattr(exc, "filename", None) else ""
    return _one_line(f"cannot finish: {exc.strerror or exc}{where}; {what}; no output was written")


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the exit code."""
    # figures are files here: matplotlib draws off screen unless the user chose a backend
    os.environ.setdefault("MPLBACKEND", "Agg")
    previous = _on_sigterm()
    args = sys.argv[1:] if argv is None else list(argv)
    if not args:
        args = ["--help"]
    try:
        # numpy's floating-point warnings are not for the user: every number that could be
        # non-finite is checked before it is written or printed
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore", RuntimeWarning)
            app(args=args, prog_name="rotorkin", standalone_mode=False)
    except RotorkinError as exc:
        print(f"rotorkin: error: {_one_line(str(exc))}", file=sys.stderr)
        return 2
    except typer.Exit as exc:
        return exc.exit_code
    except typer.Abort:
        print("rotorkin: aborted", file=sys.stderr)
        return 130
    except Terminated:
        print(
            "rotorkin: terminated; no output was finished (a sweep keeps its committed "
            "chunks and resumes from them)",
            file=sys.stderr,
        )
        return 143
    except KeyboardInterrupt:
        print("rotorkin: interrupted; no output was finished", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader of our output went away (e.g. "| head"): say nothing
        with contextlib.suppress(OSError):
            sys.stderr.close()
        return ENVIRONMENT_ERROR
    except OSError as exc:  # the machine, not the input: disk full, permission, ...
        print(f"rotorkin: {_environment_message(exc)}", file=sys.stderr)
        return ENVIRONMENT_ERROR
    except Exception as exc:
        if hasattr(exc, "format_message") and hasattr(exc, "exit_code"):  # a usage error
            print(f"rotorkin: error: {_one_line(exc.format_message())}", file=sys.stderr)
            return 2
        # an internal error: one line, the traceback on request
        if os.environ.get("ROTORKIN_DEBUG"):
            raise
        print(
            f"rotorkin: internal error: {type(exc).__name__}: {exc} "
            "(set ROTORKIN_DEBUG=1 for the traceback, and please report it)",
            file=sys.stderr,
        )
        return 1
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
    return 0
