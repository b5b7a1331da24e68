"""The rotorkin report (HTML) command(s): registered on the main app by :func:`register`."""

from __future__ import annotations


def register(app) -> None:
    """Add this module's commands to the typer ``app`` (none yet)."""
