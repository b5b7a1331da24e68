"""The ``rotorkin sweep`` and ``rotorkin tolerance`` commands: registered on the app by register().

Bad specifications (unknown key, empty range, missing unit, a swept value
inadmissible on its own) stop before anything is written: one line, exit 2.
Outputs are written atomically (a staging folder next to the target, or a
temporary file renamed into place); a sweep's chunks are committed to
``OUT/.chunks`` as they finish, so a killed sweep restarted with the same
command computes only the missing ones.
"""

from __future__ import annotations

import contextlib
import json
import math
import sys
import time
from pathlib import Path
from typing import Annotated

import typer

from rotorkin.cli.console import out_console, require, stages
from rotorkin.cli.formats import table_number
from rotorkin.cli.options import (
    ConfigArg,
    ExampleOpt,
    QuietOpt,
    SetOpt,
    VerboseOpt,
    flag_names,
    out_folder,
)
from rotorkin.core.errors import ConfigError
from rotorkin.drives import REGISTRY, spec_of
from rotorkin.io.config import apply_sets, load_config
from rotorkin.io.output import check_out, staged_output
from rotorkin.render.figures import draw_soon, drawing_ahead
from rotorkin.report import figures_sweep as fs
from rotorkin.sweep import CheckAhead, build_spec, compute
from rotorkin.sweep.checks import skipped as skipped_checks
from rotorkin.sweep.engine import SweepFallbackWarning, coverage
from rotorkin.sweep.store import write_dataset
from rotorkin.tolerance import summarize, tolerance_result

__all__ = ["register"]


def _headline(cfg: dict) -> tuple:
    return tuple(spec_of(cfg).headline)


def _note(message: str, quiet: bool) -> None:
    if not quiet:
        print(f"rotorkin: note: {message}", file=sys.stderr)


def _client(workers, scheduler):
    if workers is not None and scheduler is not None:
        raise ConfigError("give either --workers N or --scheduler ADDR, not both")
    if workers is not None:
        from rotorkin.sweep.dask import local_client

        return local_client(workers)
    if scheduler is not None:
        from rotorkin.sweep.dask import connect

        return connect(scheduler)
    return contextlib.nullcontext(None)


def _jsonable(value):
    if isinstance(value, dict):
        return {k: _jsonable(v) for k, v in value.items()}
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _readme(ds, title: str, files: list[str]) -> str:
    lines = [title, "", "variables (netCDF, read with xarray.open_dataset(path)):"]
    width = max(len(str(k)) for k in ds.variables)
    for name, var in ds.variables.items():
        dims = ", ".join(var.dims)
        lines.append(f"  {str(name).ljust(width)}  [{var.attrs.get('units', '')}]  ({dims})")
    lines += ["", "reason codes: " + ds["reason"].attrs.get("flag_meanings", "")]
    lines += ["", "files:"] + [f"  {f}" for f in files]
    return "\n".join(lines) + "\n"


def register(app) -> None:
    """Add ``sweep`` and ``tolerance`` to the typer ``app``."""

    @app.command()
    @flag_names(samples="--angles", chunk_size="--chunk", metrics="--metrics", workers="--workers")
    def sweep(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt = None,
        vary: Annotated[list[str] | None, typer.Option(
            "--vary", metavar="KEY=START:STOP:N",
            help="KEY=START:STOP:N or KEY=v1,v2,... with units (repeatable; one "
            "dimension each, the last varies fastest).")] = None,
        curves: Annotated[bool, typer.Option(
            "--curves", help="Also keep the curves over run.points angles per design.")] = False,
        metrics: Annotated[str | None, typer.Option(
            "--metrics", metavar="all|KEY,...",
            help="'all' or a comma-separated list of summary keys; default: the "
            "vectorized ones.")] = None,
        angles: Annotated[int | None, typer.Option(
            "--angles", metavar="N",
            help="Shaft angles per period of the sampled peaks (default 20001, as "
            "rotorkin run).")] = None,
        workers: Annotated[int | None, typer.Option(
            "--workers", metavar="N",
            help='Run on a dask LocalCluster of N workers (the "dask" extra).')] = None,
        scheduler: Annotated[str | None, typer.Option(
            "--scheduler", metavar="ADDR",
            help='Run on the dask cluster at tcp://HOST:PORT (the "dask" extra).')] = None,
        chunk: Annotated[int | None, typer.Option(
            "--chunk", metavar="N",
            help="Designs per chunk (default: from a 32 MiB budget).")] = None,
        out: Annotated[Path | None, typer.Option(
            "--out", "-o", metavar="DIR", parser=out_folder,
            help="Output folder; default ./rotorkin-out/<name>-sweep.")] = None,
        paper_figures: Annotated[bool, typer.Option(
            "--paper-figures", help="Also run the sweeps of the paper's figures and draw them."
        )] = False,
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):  # fmt: skip
        """Sweep config keys over ranges or lists; write sweep.nc (netCDF) and figures."""

        t0 = time.perf_counter()
        if workers is not None or scheduler is not None:
            require("dask", "distributed")  # before any work
        cfg, raw, name = load_config(config, example, set_ or [])
        if not vary and not paper_figures:
            raise ConfigError("give at least one --vary KEY=START:STOP:N (or --paper-figures)")
        outdir = out if out is not None else Path("rotorkin-out") / f"{name}-sweep"
        check_out(outdir)
        # the drawing process, forked now, imports pyplot while the sweep is checked and
        # computed; the sweep's one design through the study runs beside it too
        with drawing_ahead(), contextlib.ExitStack() as ahead:
            specs = []  # (recipe or None, spec), all validated before anything runs
            if vary:
                specs.append(
                    (
                        None,
                        build_spec(
                            raw,
                            vary,
                            keep_curves=curves,
                            chunk_size=chunk,
                            metrics=metrics,
                            samples=angles,
                            name=name,
                            check=False,
                        ),
                    )
                )
                checked = ahead.enter_context(CheckAhead(specs[0][1]))
            if paper_figures:
                recipes = fs.paper_recipes(cfg, spec_of(cfg))
                if not recipes:
                    raise ConfigError(
                        f"--paper-figures: the {cfg['drive']['type']} paper has no "
                        "sweep figures (those of "
                        + ", ".join(k for k, s in REGISTRY.items() if s.sweep_recipes)
                        + " do)"
                    )
                for r in recipes:
                    base = apply_sets(raw, list(r.sets))
                    specs.append(
                        (
                            r,
                            build_spec(
                                base,
                                list(r.vary),
                                keep_curves=r.curves,
                                metrics=list(r.metrics) or None,
                                samples=angles,
                                name=f"{name} {r.key}",
                            ),
                        )
                    )
            for _, spec in specs:
                why = coverage(
                    spec.drive_type, spec.base_cfg, [v.key for v in spec.varies], spec.metrics
                )[2]
                if why:
                    _note(f"{why}: evaluated design by design by the scalar study (slow)", quiet)
                unchecked = skipped_checks(spec.base_cfg, spec.varies)
                if unchecked:
                    _note(unchecked, quiet)
            written, main_ds = [], None
            with (
                _client(workers, scheduler) as client,
                staged_output(outdir, "sweep") as (stage, _),
            ):
                for recipe, spec in specs:
                    if recipe is None:
                        overview = []  # drawn by the drawing process while sweep.nc is written

                        def draw_overview(result, spec=spec, overview=overview):
                            task = fs.overview_task(
                                result, _headline(spec.base_cfg), stage / "sweep_overview.png"
                            )
                            overview.append(draw_soon([task] if task else []))

                        main_ds = compute(
                            spec,
                            store=outdir,
                            client=client,
                            progress=not quiet,
                            on_status=lambda m: _note(m, quiet),
                            confirm=checked.confirm,
                            on_result=draw_overview,
                        )
                        written.append("sweep.nc")
                        written += [path.name for path in overview[0].paths()]
                        (stage / "README.txt").write_text(
                            _readme(
                                main_ds, f"rotorkin sweep of {name}: {spec.size} designs", written
                            )
                        )
                        written.append("README.txt")
                    else:
                        ds = compute(spec, client=client, progress=not quiet)
                        write_dataset(ds, stage / f"paper_{recipe.key}.nc")
                        written.append(f"paper_{recipe.key}.nc")
                        written += [p.name for p in fs.plot_recipe(recipe, ds, stage)]
            if not quiet:
                _print_sweep(name, specs, main_ds, outdir, written, time.perf_counter() - t0)

    @app.command()
    @flag_names(samples="--samples", angles="--angles", metrics="--metrics", seed="--seed")
    def tolerance(
        config: ConfigArg = None,
        example: ExampleOpt = None,
        set_: SetOpt
        = None,
        tol: Annotated[list[str] | None, typer.Option(
            "--tol", metavar="KEY=WIDTH",
            help="KEY=WIDTH (uniform, +- WIDTH) or KEY=WIDTH:normal (sigma), with "
            "units, e.g. drive.plate_tilt=0.1deg (repeatable).")] = None,
        samples: Annotated[int, typer.Option(
            "--samples", metavar="N", help="Monte-Carlo samples.")] = 10_000,
        seed: Annotated[int, typer.Option(
            "--seed", metavar="N", help="Seed of numpy's default_rng.")] = 0,
        metrics: Annotated[str | None, typer.Option(
            "--metrics", metavar="all|KEY,...",
            help="'all' or a comma-separated list; the first 9 are drawn.")] = None,
        angles: Annotated[int | None, typer.Option(
            "--angles", metavar="N",
            help="Shaft angles per period of the sampled peaks (default 20001).")]
        = None,
        out: Annotated[Path | None, typer.Option(
            "--out", "-o", metavar="DIR", parser=out_folder,
            help="Output folder; default ./rotorkin-out/<name>-tolerance.")]
        = None,
        quiet: QuietOpt = False,
        verbose: VerboseOpt = False,
    ):  # fmt: skip
        """Monte-Carlo tolerance analysis; write tolerance.json, tolerance.nc, histograms."""
        import warnings

        import numpy as np

        cfg, raw, name = load_config(config, example, set_ or [])
        outdir = out if out is not None else Path("rotorkin-out") / f"{name}-tolerance"
        check_out(outdir)
        with stages("tolerance") as step, warnings.catch_warnings(record=True) as caught:
            step(f"evaluating {samples} samples")
            warnings.simplefilter("always", SweepFallbackWarning)
            ds = tolerance_result(raw, tol or [], samples=samples, seed=seed, metrics=metrics,
                                  angles=angles)  # fmt: skip
        for w in caught:
            _note(str(w.message), quiet)
        stats = summarize(ds)
        kind = cfg["drive"]["type"]
        if metrics:
            drawn = [m for m in stats][:9]
        else:
            order = [*spec_of(cfg).tolerance_first, *_headline(cfg), *stats]
            drawn = [
                m
                for m in dict.fromkeys(order)
                if m in stats
                and stats[m]["std"]
                and stats[m]["std"] > 1e-12 * max(abs(stats[m]["mean"]), 1e-300)
            ][:9]
            drawn = drawn or list(stats)[:1]
        doc = {
            "name": name,
            "drive_type": kind,
            "samples": int(samples),
            "seed": int(seed),
            "angles_per_period": int(ds.attrs["angles_per_period"]),
            "tolerances": ds.attrs["tolerances"],
            "held_at_nominal": ds.attrs["held_at_nominal"],
            "sampling": ds.attrs["sampling"],
            "inadmissible_samples": int(np.count_nonzero(ds["reason"].values)),
            "metrics": stats,
        }
        with stages("tolerance output") as step, staged_output(outdir, "tolerance") as (stage, _):
            step("writing the outputs and drawing the histograms")
            (stage / "tolerance.json").write_text(json.dumps(_jsonable(doc), indent=2) + "\n")
            write_dataset(ds, stage / "tolerance.nc")
            fs.fig_tolerance(ds, stats, drawn, stage / "tolerance_histograms.png")
            (stage / "README.txt").write_text(
                _readme(
                    ds,
                    f"rotorkin tolerance analysis of {name}: {samples} samples, seed {seed}",
                    ["tolerance.json", "tolerance.nc", "tolerance_histograms.png"],
                )
            )
        if not quiet:
            _print_tolerance(name, ds, stats, drawn, outdir)


def _print_sweep(name, specs, ds, outdir, written, seconds) -> None:
    import numpy as np
    from rich.table import Table

    console = out_console()
    for recipe, spec in specs:
        what = "sweep" if recipe is None else f"paper {recipe.key}"
        dims = " x ".join(f"{v.key}[{len(v)}]" for v in spec.varies)
        console.print(f"{name}: {what}: {spec.size} designs ({dims})", highlight=False,
                      soft_wrap=True)  # fmt: skip
    if ds is not None:
        ok = ds["reason"].values == 0
        console.print(f"inadmissible designs: {int(np.count_nonzero(~ok))} (NaN, see 'reason')",
                      highlight=False)  # fmt: skip
        table = Table()
        for col in ("metric", "min", "max"):
            table.add_column(col, justify="left" if col == "metric" else "right")
        for key in _headline(specs[0][1].base_cfg):
            if key in ds and np.any(np.isfinite(ds[key].values)):
                v = ds[key].values
                table.add_row(key, table_number(np.nanmin(v)), table_number(np.nanmax(v)))
        console.print(table)
    console.print(f"wrote {outdir}/: {', '.join(written)} in {seconds:.2f} s", highlight=False,
                  soft_wrap=True)  # fmt: skip


def _print_tolerance(name, ds, stats, drawn, outdir) -> None:
    from rich.table import Table

    console = out_console()
    console.print(f"{name}: {ds.attrs['samples']} samples, seed {ds.attrs['seed']}: "
                  f"{ds.attrs['tolerances']}", highlight=False, soft_wrap=True)  # fmt: skip
    table = Table()
    cols = ("nominal", "mean", "std", "p5", "p95")
    table.add_column("metric (all percentiles in tolerance.json)", no_wrap=True)
    for col in cols:
        table.add_column(col, justify="right", no_wrap=True)
    for m in drawn:
        s = stats[m]
        table.add_row(m, *(("-" if s[k] is None else table_number(s[k], 5)) for k in cols))
    console.print(table)
    console.print(f"wrote {outdir}/: tolerance.json, tolerance.nc, tolerance_histograms.png, "
                  "README.txt", highlight=False, soft_wrap=True)  # fmt: skip
