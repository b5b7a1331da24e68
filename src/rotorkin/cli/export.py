"""The ``rotorkin export`` command (CAD files of a config's cams or impellers).

Registered on the main app by :func:`register`. Writes DXF, STL, STEP or CSV
through :func:`rotorkin.io.export.export` (a progress bar per part on a terminal's
stderr, none with ``--quiet``), then prints the files written, the parts' bores,
keyways and running gaps, and the profile checks in short tables.
"""

from __future__ import annotations

import contextlib
import time
from pathlib import Path
from typing import Annotated

import typer

from rotorkin.cli.console import err_console, note, out_console, require, stages
from rotorkin.cli.options import (
    ConfigArg,
    ExampleOpt,
    QuietOpt,
    SetOpt,
    VerboseOpt,
    flag_names,
    out_option,
)
from rotorkin.cli.tables import print_checks
from rotorkin.core.errors import RotorkinError
from rotorkin.drives import design_checks, get
from rotorkin.io.config import load_config
from rotorkin.io.export import FORMATS, export, profile_checks, workshop_rows

#: The modules (of the optional ``cad`` extra) each format is written with.
NEEDS = {"dxf": ("ezdxf",), "stl": ("trimesh", "manifold3d"), "step": ("build123d",),
         "csv": ()}  # fmt: skip


def _size(n: int) -> str:
    return f"{n / 1024:.1f} KiB" if n < 1024 * 1024 else f"{n / 1024 / 1024:.2f} MiB"


def _fmt(value, digits=4) -> str:
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def _check_rows(cfg: dict) -> list[tuple[str, str]]:
    """(metric, value) rows of the profile checks, units in the metric names."""
    import numpy as np

    spec = get(cfg["drive"]["type"])
    if spec.check_rows is not None:
        return spec.check_rows(cfg)
    rows = []
    for label, c in profile_checks(cfg):
        deg = np.degrees
        rows += [
            (f"{label}: roller radius mm", _fmt(c.roller_radius * 1e3)),
            (
                f"{label}: min convex radius of curvature (pitch) mm",
                f"{_fmt(c.min_convex_radius * 1e3)} at {_fmt(deg(c.min_convex_radius_alpha))} deg",
            ),
            (f"{label}: min concave radius of curvature (pitch) mm",
             _fmt(c.min_concave_radius * 1e3)),
            (
                f"{label}: max pressure angle deg",
                f"{_fmt(deg(c.max_pressure_angle))} at {_fmt(deg(c.max_pressure_angle_alpha))} deg",
            ),
            (f"{label}: min roller-to-cam clearance mm", _fmt(c.min_clearance * 1e3)),
            (f"{label}: actual profile nearest the axis mm", _fmt(c.profile_min_radius * 1e3)),
            (f"{label}: undercut", "yes" if c.undercut else "no"),
        ]  # fmt: skip
    return rows


def register(app) -> None:
    """Add ``export`` to the typer ``app``."""

    @app.command("export")
    @flag_names(fmt="--format")
    def export_cmd(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        fmt: Annotated[
            str,
            typer.Option(
                "--format", "-f", metavar="dxf|stl|step|csv|all",
                help='The file format; dxf, stl and step need the "cad" extra.',
            ),
        ] = "dxf",
        out: out_option("./rotorkin-out/<name>/cad") = None,
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):  # fmt: skip
        """Write CAD files of the cam(s): DXF profiles, STL/STEP solids, CSV point lists (mm)."""

        fmt_ = fmt.strip().lower()
        if fmt_ not in (*FORMATS, "all"):
            raise RotorkinError(
                f"--format = {fmt!r} is not admissible: choose one of {', '.join(FORMATS)}, all"
            )
        for f in FORMATS if fmt_ == "all" else (fmt_,):
            require(*NEEDS[f])  # before any work
        with stages("export checks") as step:
            step("reading the config")
            cfg, _, name = load_config(config, example, set_ or [])
            outdir = out if out is not None else Path("rotorkin-out") / name / "cad"
            step("checking the profiles")
            rows = _check_rows(cfg)
            checks = design_checks(cfg)  # the same checks as run (with their margins)
        t0 = time.perf_counter()
        with _progress_bar(quiet) as progress:
            written = export(cfg, fmt_, outdir, name, progress=progress)
        note(f"writing {len(written)} {fmt_} file(s): {time.perf_counter() - t0:.2f} s")
        if not quiet:
            _print(name, cfg["drive"]["type"], fmt_, outdir, written, rows, workshop_rows(cfg))
            print_checks(out_console(), checks)


@contextlib.contextmanager
def _progress_bar(quiet: bool):
    """A rich progress bar on stderr, one step per part and format; None (no bar) when
    quiet or when stderr is no terminal (a pipe, a test)."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    console = err_console()
    if quiet or not console.is_terminal:
        yield None
        return
    columns = (TextColumn("{task.description:<28}"), BarColumn(), MofNCompleteColumn(),
               TimeElapsedColumn())  # fmt: skip
    with Progress(*columns, console=console, transient=True) as bar:
        task = bar.add_task("export", total=None)

        def progress(label: str, done: int, total: int) -> None:
            bar.update(task, description=label, completed=done, total=total, refresh=True)

        yield progress


def _print(name, kind, fmt, outdir, written, rows, parts=()) -> None:
    from rich.table import Table

    console = out_console()
    what = "file(s) in every format" if fmt == "all" else f"{fmt} file(s)"
    console.print(f"{name} ({kind}): wrote {len(written)} {what} to {outdir}/",
                  highlight=False, soft_wrap=True)  # fmt: skip
    files = Table()
    files.add_column("file")
    files.add_column("size", justify="right")
    for p in written:
        files.add_row(p.name, _size(p.stat().st_size))
    console.print(files)
    for title, first, pairs in (("workshop", "part", parts), ("profile checks", "check", rows)):
        if not pairs:
            continue
        table = Table(title=title)
        table.add_column(first)
        table.add_column("value", justify="right")
        for k, v in pairs:
            table.add_row(k, v)
        console.print(table)
