"""Figures drawn from sweeps: the papers' parameter studies, an overview, tolerance histograms.

``rotorkin sweep --example NAME --paper-figures`` runs, for the drive of the
config, the sweeps behind the papers' figures (:func:`paper_recipes`) and draws
them from the resulting datasets: each drive lists its recipes
(``DriveSpec.sweep_recipes``, in ``rotorkin/drives/<name>/figures_sweep.py``), each
recipe the sweep and the function that draws its figures. Here: the recipes'
dispatch, the overview of any sweep and the tolerance histograms.

matplotlib is imported when a figure is drawn.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from pathlib import Path

import numpy as np

from rotorkin.io.config import validate_config
from rotorkin.render.figures import Recipe, save_in
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save as _save

__all__ = [
    "Recipe",
    "paper_recipes",
    "plot_recipe",
    "fig_overview",
    "overview_task",
    "fig_tolerance",
]

_DPI = 120


def paper_recipes(cfg: dict, spec) -> list[Recipe]:
    """The paper-figure sweeps of the config's drive (empty when it has none)."""
    return list(spec.sweep_recipes(cfg)) if spec.sweep_recipes else []


# --------------------------------------------------------------------------------------------
# drawing
# --------------------------------------------------------------------------------------------
def plot_recipe(recipe: Recipe, ds, outdir: Path) -> list[Path]:
    """Draw the recipe's figures from its dataset into ``outdir``; return the paths."""
    import json

    cfg = validate_config(json.loads(ds.attrs["spec"])["base_raw"])
    return recipe.plot(ds, Path(outdir), recipe, cfg)


def fig_overview(ds, metrics, path: Path) -> Path | None:
    """Up to six metrics against the first swept key, one line per value of the second.

    The first six metrics (in ``metrics``' order) that change over the drawn designs;
    the first six unchanged ones only when none changes. Further swept keys are held
    at their first value. None when the first key is not numeric or there is nothing
    to draw. ``ds`` is a sweep's
    :class:`~rotorkin.sweep.result.SweepResult` or :class:`xarray.Dataset` (only
    ``ds[name].values``, ``.dims`` and ``.attrs`` are read).
    """
    task = overview_task(ds, metrics, path)
    return None if task is None else task()


def overview_task(ds, metrics, path: Path) -> Callable[[], Path] | None:
    """:func:`fig_overview` as a task for :func:`~rotorkin.render.figures.draw`.

    What the figure shows is taken from ``ds`` now (the drawn lines, labels and title:
    a few kB however large the sweep), so the task pickles small and draws without
    ``ds``. None when there is nothing to draw.
    """
    plan = _overview_plan(ds, metrics)
    return None if plan is None else functools.partial(_draw_overview, plan, Path(path))


def _overview_plan(ds, metrics) -> dict | None:
    """The lines, labels and title of :func:`fig_overview`, or None."""
    dims = list(ds["reason"].dims)
    if not dims or ds[dims[0]].values.dtype == object:
        return None
    held_at = (slice(None),) * min(2, len(dims)) + (0,) * (len(dims) - 2)
    moving, flat = {}, {}
    for m in metrics:
        if m not in ds or len(moving) == 6:
            continue
        y = np.asarray(ds[m].values)[held_at]  # a view: the first two dims, others held
        y = y.astype(float) if y.dtype.kind in "iub" else y
        finite = y[np.isfinite(y)] if y.dtype.kind == "f" else np.array([])
        if finite.size == 0:
            continue
        if np.ptp(finite) > 1e-9 * np.max(np.abs(finite)):
            moving[m] = y
        elif len(flat) < 6:
            flat[m] = y
    # the metrics the swept keys move; the first unchanged ones only when none moves
    curves = moving or flat
    if not curves:
        return None
    x = ds[dims[0]]
    second = dims[1] if len(dims) > 1 else None
    lines: list = [None]
    labels: list = [None]
    if second:
        values2 = ds[second].values
        lines = list(range(len(values2)))
        if len(lines) > 8:
            lines = np.unique(np.linspace(0, len(values2) - 1, 8).round().astype(int)).tolist()
        unit2 = ds[second].attrs.get("units", "1")
        labels = [f"{second.split('.')[-1]} = {_fmt(values2[j])}"
                  + ("" if unit2 == "1" else f" {unit2}") for j in lines]  # fmt: skip
    held = ", ".join(f"{d} = {_fmt(ds[d].values[0])}" for d in dims[2:])
    return {
        "x": np.array(x.values),
        "xlabel": f"{dims[0]} [{x.attrs.get('units', '')}]",
        # only the drawn lines of each metric travel (copies, not views of the sweep)
        "curves": [
            (
                f"{m} [{ds[m].attrs.get('units', '1')}]",
                np.array(y if second is None else y[:, lines]).reshape(len(x.values), -1),
            )
            for m, y in curves.items()
        ],  # fmt: skip
        "labels": labels,
        "held": held,
        "title": f"{ds.attrs.get('title', 'sweep')}: {ds.attrs['designs']} designs, "
        f"{ds.attrs['inadmissible_designs']} inadmissible (gaps)",
    }


def _draw_overview(plan: dict, path: Path) -> Path:
    """Draw and write :func:`fig_overview`'s figure from its plan."""
    plt = _plt()
    curves, held = plan["curves"], plan["held"]
    ncol = min(3, len(curves))
    nrow = -(-len(curves) // ncol)
    width, height, top = 4.6 * ncol, 3.6 * nrow + 0.8, 0.95 if held else 0.7
    # fixed margins [in] instead of tight_layout, which draws every tick once more
    fig, axes = plt.subplots(nrow, ncol, figsize=(width, height), squeeze=False,
                             gridspec_kw={"left": 0.95 / width, "right": 1 - 0.2 / width,
                                          "bottom": 0.55 / height, "top": 1 - top / height,
                                          "wspace": 1.05 / 3.45, "hspace": 0.75 / 2.6})  # fmt: skip
    for ax, (ylabel, y) in zip(axes.ravel(), curves, strict=False):
        for k, label in enumerate(plan["labels"]):
            ax.plot(plan["x"], y[:, k], color=f"C{k}", label=label)
        ax.set_xlabel(plan["xlabel"])
        ax.set_ylabel(ylabel, fontsize=8)
        ax.grid(True, alpha=0.4)
    for ax in axes.ravel()[len(curves) :]:
        ax.set_visible(False)
    if plan["labels"][0] is not None:
        axes.ravel()[0].legend(fontsize=7)
    fig.suptitle(plan["title"] + (f"\nheld: {held}" if held else ""), fontsize=10,
                 y=1 - 0.1 / height, va="top")  # fmt: skip
    return save_in(fig, Path(path).parent, Path(path).name)


def _fmt(v) -> str:
    v = v.item() if hasattr(v, "item") else v
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def fig_tolerance(ds, stats: dict, metrics, path: Path) -> Path:
    """Histograms of the metrics of a tolerance run, nominal and percentiles marked."""
    plt = _plt()
    ok = ds["reason"].values == 0
    names = list(metrics)[:9]
    ncol = min(3, len(names))
    nrow = -(-len(names) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.4 * nrow + 1.0), squeeze=False)
    for ax, m in zip(axes.ravel(), names, strict=False):
        v = ds[m].values[ok]
        v = v[np.isfinite(v)]
        s = stats[m]
        ax.hist(v, bins=50, color="C0", alpha=0.75, label="samples")
        ax.axvline(s["nominal"], color="k", ls="--", lw=1.5, label="nominal")
        if s["p5"] is not None:
            ax.axvline(s["p5"], color="C1", ls=":", lw=1.5, label="p5, p95")
            ax.axvline(s["p95"], color="C1", ls=":", lw=1.5)
            ax.axvline(s["p50"], color="C3", ls="-", lw=1, label="p50")
        ax.set_xlabel(f"{m} [{ds[m].attrs.get('units', '1')}]", fontsize=8)
        ax.set_ylabel("samples")
        ax.ticklabel_format(axis="x", useOffset=False)
        ax.tick_params(axis="x", labelsize=7)
        ax.grid(True, alpha=0.4)
        std = s["std"]
        ax.set_title(f"std {std:.3g}" if std is not None else "no admissible sample", fontsize=9)
    for ax in axes.ravel()[len(names) :]:
        ax.set_visible(False)
    axes.ravel()[0].legend(fontsize=7)
    bad = int(np.count_nonzero(~ok))
    fig.suptitle(f"Tolerance analysis: {ds.attrs['samples']} samples, seed {ds.attrs['seed']}, "
                 f"{bad} inadmissible\n{ds.attrs['tolerances']}", fontsize=10)  # fmt: skip
    return _save(fig, path)
