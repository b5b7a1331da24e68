"""Summaries printed as a table (people), JSON or CSV (programs), the choice of ``--format``.

JSON and CSV carry every number at full precision (Python's shortest repr, which
reads back to the same float); a value that is not finite is ``null`` in JSON and
an empty cell in CSV. A table shows 6 significant digits on a terminal and full
precision when stdout is a pipe or a file (:func:`table_number`).
"""

from __future__ import annotations

import csv
import json
import math
import sys

import numpy as np

from rotorkin.cli.console import out_console, stdout_is_terminal

__all__ = ["plain", "table_number", "print_json", "print_csv", "flat_rows", "print_run_summary",
           "run_document", "check_records"]  # fmt: skip


def plain(value):
    """A JSON value: numpy scalars as Python ones, non-finite floats as None, recursively."""
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def table_number(value, digits: int = 6) -> str:
    """A number for a table: ``digits`` significant on a terminal, full precision otherwise."""
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    if isinstance(value, float) and not math.isfinite(value):
        return "n/a"
    if not stdout_is_terminal():
        return repr(value)
    return f"{value:.{digits}g}"


def _cell(value) -> str:
    value = plain(value)
    if value is None:
        return ""
    return repr(value) if isinstance(value, float) else str(value)


def print_json(doc) -> None:
    """``doc`` as indented JSON on stdout (strict: no NaN, no Infinity)."""
    sys.stdout.write(json.dumps(plain(doc), indent=2, allow_nan=False) + "\n")


def print_csv(header, rows) -> None:
    """A CSV table on stdout: ``header`` then ``rows`` (floats at full precision)."""
    writer = csv.writer(sys.stdout, lineterminator="\n")
    writer.writerow(header)
    for row in rows:
        writer.writerow([_cell(v) for v in row])


def flat_rows(doc, prefix: str = "") -> list[tuple[str, object]]:
    """``(field, value)`` rows of a record: ``a.b`` for nested fields, ``a[i]`` in lists."""
    items = doc.items() if isinstance(doc, dict) else ((f"[{i}]", v) for i, v in enumerate(doc))
    rows = []
    for field, value in items:
        name = (
            f"{prefix}{field}" if str(field).startswith("[") or not prefix else f"{prefix}.{field}"
        )
        if isinstance(value, (dict, list, tuple)) and value:
            rows += flat_rows(value, name)
        else:
            rows.append((name, value))
    return rows


def check_records(checks) -> list[dict]:
    """The design's checks as JSON records (value, limit and margin in ``unit``)."""
    return [{"check": c.name, "where": c.where, "key": c.key, "value": c.value,
             "limit": c.limit, "unit": c.unit, "upper": c.upper, "margin": c.margin,
             "passed": c.passed} for c in checks]  # fmt: skip


def _meanings(result) -> dict:
    return dict(result.headline) if isinstance(result.headline, dict) else {}


def run_document(result, name: str, outdir, written) -> dict:
    """What ``rotorkin run --format json`` prints: every summary value, checks, files."""
    return {
        "name": name,
        "title": result.title,
        "drive_type": result.drive_type,
        "summary": dict(result.summary),
        "headline": list(result.headline),
        "meaning": _meanings(result),
        "checks": check_records(result.checks),
        "warnings": list(result.warnings),
        "out": str(outdir),
        "files": [p.name for p in written],
    }


def print_run_summary(result, name: str, outdir, written, fmt: str) -> None:
    """Print ``rotorkin run``'s summary in ``fmt``: ``table``, ``json`` or ``csv``.

    The table lists the headline metrics with their meaning, the checks and the
    files written; JSON and CSV list every summary value (CSV: ``metric, value,
    meaning``, one row per summary key).
    """
    if fmt == "json":
        print_json(run_document(result, name, outdir, written))
        return
    meanings = _meanings(result)
    if fmt == "csv":
        print_csv(("metric", "value", "meaning"),
                  [(k, v, meanings.get(k, "")) for k, v in result.summary.items()])  # fmt: skip
        return
    from rich.table import Table

    from rotorkin.cli.tables import print_checks

    console = out_console()
    console.print(f"{name}: {result.title}", soft_wrap=True)
    table = Table()
    table.add_column("metric", no_wrap=True)
    table.add_column("value", justify="right", no_wrap=True)
    if meanings:
        table.add_column("meaning")
    for key in result.headline:
        shown = table_number(result.summary[key])
        table.add_row(key, shown, *([meanings[key]] if meanings else []))
    console.print(table)
    print_checks(console, result.checks)
    figures = [p.name for p in written if p.suffix == ".png"]
    files = [p.name for p in written if p.suffix != ".png"]
    drawn = f", {len(figures)} figures ({', '.join(figures)})" if figures else ", no figures"
    console.print(f"wrote {outdir}/: {', '.join(files)}{drawn}", soft_wrap=True)
