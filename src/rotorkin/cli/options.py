"""Arguments and options that every ``rotorkin`` command shares (typer annotations)."""

from __future__ import annotations

import functools
import re
from pathlib import Path
from typing import Annotated

import typer

from rotorkin.cli.console import quiet_callback, verbose_callback
from rotorkin.core.errors import ParameterError
from rotorkin.drives import DEFAULT_EXAMPLE

__all__ = ["ConfigArg", "ExampleOpt", "SetOpt", "QuietOpt", "VerboseOpt", "FormatOpt", "FORMATS",
           "check_format", "out_folder", "out_option", "flag_names"]  # fmt: skip

#: The config file (positional).
ConfigArg = Annotated[
    Path | None,
    typer.Argument(metavar="CONFIG", help=f"TOML config; default: the {DEFAULT_EXAMPLE} example."),
]
#: ``--example NAME``: start from a built-in example instead of a file.
ExampleOpt = Annotated[
    str | None,
    typer.Option("--example", "-e", metavar="NAME", help="Start from a built-in example by name."),
]
#: ``--set section.key=VALUE``, repeatable.
SetOpt = Annotated[
    list[str] | None,
    typer.Option(
        "--set", "-s", metavar="KEY=VALUE",
        help='Override a config key, e.g. drive.plate_tilt="30 deg" (repeatable).',
    ),
]  # fmt: skip

#: The formats of a command's printed summary.
FORMATS = ("table", "json", "csv")

#: ``--format table|json|csv``: how the summary is printed on stdout.
FormatOpt = Annotated[
    str,
    typer.Option(
        "--format", metavar="table|json|csv",
        help="How the summary is printed: a table for people, or json / csv (every value "
        "at full precision) for programs.",
    ),
]  # fmt: skip


def check_format(fmt: str) -> str:
    """``--format``: one of :data:`FORMATS` (case and spaces ignored), else one line, exit 2."""
    chosen = str(fmt).strip().lower()
    if chosen not in FORMATS:
        raise ParameterError("--format", repr(fmt), f"one of {', '.join(FORMATS)}")
    return chosen


def out_folder(text: str) -> Path:
    """``--out``: a folder name; an empty one (which would mean the current folder) is refused."""
    if not str(text).strip():
        raise typer.BadParameter("an empty folder name is not admissible", param_hint="--out")
    if "\0" in str(text):
        raise typer.BadParameter("a folder name cannot hold a NUL character", param_hint="--out")
    return Path(text)


def out_option(default: str):
    """``--out``/``-o`` with ``default`` (where the outputs go without it) in its help."""
    return Annotated[
        Path | None,
        typer.Option(
            "--out", "-o", metavar="DIR", parser=out_folder,
            help=f"Output folder; default {default}.",
        ),
    ]  # fmt: skip


#: ``--quiet``.
QuietOpt = Annotated[
    bool,
    typer.Option(
        "--quiet", "-q", callback=quiet_callback,
        help="Print nothing on success (errors and warnings still go to stderr).",
    ),
]  # fmt: skip
#: ``--verbose``.
VerboseOpt = Annotated[
    bool,
    typer.Option(
        "--verbose", "-v", callback=verbose_callback,
        help="Also say on stderr what is done and how long each step takes; a traceback on "
        "an internal error.",
    ),
]  # fmt: skip


def flag_names(**flags):
    """Decorate a command: a library error naming a parameter names the flag the user typed.

    The library speaks of its parameters (``samples = 2 is not admissible: samples
    >= 3``); ``flag_names(samples="--angles")`` makes the command say ``--angles = 2 is
    not admissible: --angles >= 3``.
    """

    def decorate(command):
        @functools.wraps(command)
        def wrapped(*args, **kwargs):
            try:
                return command(*args, **kwargs)
            except ParameterError as exc:
                flag = flags.get(exc.name)
                if flag is None:
                    raise
                word = rf"(?<![\w.-]){re.escape(exc.name)}(?!\w)"
                raise ParameterError(flag, exc.value, re.sub(word, flag, exc.admissible)) from None

        return wrapped

    return decorate
