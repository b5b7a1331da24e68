"""The figure of a multi-objective search: its Pareto front (matplotlib, imported when drawn).

Two objectives: the front in the plane of the two metrics, over every admissible
design the search evaluated. More: the front in each pair of objectives (a
scatter matrix). One: the objective over the generations.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.core.units import metric_units
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save as _save

__all__ = ["plot_front"]


def _label(objective) -> str:
    unit = metric_units(objective.metric)
    unit = "" if unit == "1" else f" [{unit}]"
    return f"{objective.metric}{unit} ({objective.sense})"


def _evaluated(result, metric: str, feasible: bool = True) -> np.ndarray:
    """``metric`` of the admissible designs the search evaluated that meet every constraint
    (``feasible``) or miss one (not ``feasible``); NaN elsewhere."""
    spec = result.spec
    col = {m: i for i, m in enumerate(spec.metrics)}
    values = np.concatenate([h["values"] for h in result.history])
    reason = np.concatenate([h["reason"] for h in result.history])
    meets = np.ones(reason.size, dtype=bool)
    for c in spec.constraints:
        meets &= c.g(values[:, col[c.metric]]) <= 0.0
    keep = (reason == 0) & (meets == feasible)
    return np.where(keep, values[:, col[metric]], np.nan)


def plot_front(result, path: Path) -> Path:
    """Draw the front of ``result`` (:class:`rotorkin.design.optimize.OptimizeResult`)."""
    plt = _plt()
    objs = result.spec.objectives
    title = (f"{result.spec.name}: Pareto set of {result.size} designs "
             f"({len(result.history)} generations x {result.spec.population})")  # fmt: skip
    if len(objs) == 1:
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        gens = np.concatenate([np.full(h["X"].shape[0], k) for k, h in enumerate(result.history)])
        y = _evaluated(result, objs[0].metric)
        ax.plot(gens, y, ".", color="0.7", ms=3, label="evaluated designs")
        ax.axhline(result.column(objs[0].metric)[0], color="C3", lw=1.2, label="best")
        ax.set_xlabel("generation")
        ax.set_ylabel(_label(objs[0]))
        ax.legend(fontsize=8)
        ax.grid(True, alpha=0.4)
    elif len(objs) == 2:
        fig, ax = plt.subplots(figsize=(6.4, 4.8))
        ax.plot(_evaluated(result, objs[0].metric), _evaluated(result, objs[1].metric), ".",
                color="0.7", ms=3, label="evaluated designs")  # fmt: skip
        if result.spec.constraints:
            ax.plot(_evaluated(result, objs[0].metric, False),
                    _evaluated(result, objs[1].metric, False), "x", color="0.75", ms=3,
                    label="evaluated, missing a constraint")  # fmt: skip
        x, y = result.column(objs[0].metric), result.column(objs[1].metric)
        ax.plot(x, y, "-o", color="C3", ms=4, lw=1.0, label="Pareto set")
        ax.set_xlabel(_label(objs[0]))
        ax.set_ylabel(_label(objs[1]))
        ax.legend(fontsize=8)
        ax.grid(True, alpha=0.4)
    else:
        n = len(objs)
        fig, axes = plt.subplots(n, n, figsize=(2.6 * n, 2.6 * n), squeeze=False)
        for r in range(n):
            for c in range(n):
                ax = axes[r, c]
                if r == c:
                    ax.hist(result.column(objs[r].metric), bins=12, color="C3", alpha=0.7)
                else:
                    ax.plot(result.column(objs[c].metric), result.column(objs[r].metric), "o",
                            color="C3", ms=3)  # fmt: skip
                ax.grid(True, alpha=0.3)
                ax.tick_params(labelsize=6)
                if r == n - 1:
                    ax.set_xlabel(_label(objs[c]), fontsize=7)
                if c == 0:
                    ax.set_ylabel(_label(objs[r]), fontsize=7)
    fig.suptitle(title, fontsize=9)
    return _save(fig, Path(path))
