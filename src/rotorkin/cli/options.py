"""Arguments and options that every ``rotorkin`` command shares (typer annotations)."""

from __future__ import annotations

import functools
import re
from pathlib import Path
from typing import Annotated

import typer

from rotorkin.core.errors import ParameterError
from rotorkin.drives import DEFAULT_EXAMPLE

__all__ = ["ConfigArg", "ExampleOpt", "SetOpt", "QuietOpt", "out_folder", "out_option",
           "flag_names"]  # fmt: skip

#: The config file (positional).
ConfigArg = Annotated[
    Path | None, typer.Argument(help=f"TOML config; default: the {DEFAULT_EXAMPLE} example.")
]
#: ``--example NAME``: start from a built-in example instead of a file.
ExampleOpt = Annotated[
    str | None, typer.Option("--example", "-e", help="Start from a built-in example by name.")
]
#: ``--set section.key=VALUE``, repeatable.
SetOpt = Annotated[
    list[str] | None,
    typer.Option("--set", "-s", help="Override a key: section.key=VALUE (repeatable)."),
]


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
        typer.Option("--out", "-o", parser=out_folder, help=f"Output folder; default {default}."),
    ]


#: ``--quiet``.
QuietOpt = Annotated[bool, typer.Option("--quiet", "-q", help="Print nothing on success.")]


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
