"""The rotorkin sweep and tolerance commands: registered on the main app by register()."""

from __future__ import annotations


def register(app) -> None:
    """Add this module's commands to the typer ``app`` (none yet)."""
