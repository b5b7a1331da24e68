"""Arguments and options that every ``rotorkin`` command shares (typer annotations)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from rotorkin.drives import DEFAULT_EXAMPLE

__all__ = ["ConfigArg", "ExampleOpt", "SetOpt", "QuietOpt"]

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
#: ``--quiet``.
QuietOpt = Annotated[bool, typer.Option("--quiet", "-q", help="Print nothing on success.")]
