"""Tables the commands print (rich)."""

from __future__ import annotations

from rotorkin.studies.checks import rows as check_rows

__all__ = ["print_checks"]


def print_checks(console, checks, title: str = "checks") -> None:
    """Print a design's checks as a table: value, limit, margin, ok / FAILS."""
    from rich.table import Table

    if not checks:
        return
    table = Table(title=title)
    table.add_column("check")
    for head in ("value", "limit", "margin"):
        table.add_column(head, justify="right", no_wrap=True)
    table.add_column("status")
    for row in check_rows(checks):
        table.add_row(*row)
    console.print(table)
