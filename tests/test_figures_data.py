"""What every figure of ``rotorkin run`` plots, checked on its data rather than on its PNG.

For each example: every figure has at least one axes with data; every line's
points are finite where drawn and lie inside the axes' limits (nothing is drawn
off the plot); and the figures draw the model, not something else: at least one
line of the run's figures is a column of ``motion.csv`` up to a unit factor.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.drives import REGISTRY, evaluate
from rotorkin.io.config import load_config
from rotorkin.render.figures import recording

EXAMPLES = [ex for spec in REGISTRY.values() for ex in spec.examples]
#: Unit factors between a column and what a figure draws of it (same unit, or kilo/milli).
FACTORS = (1.0, 1e-3, 1e3)


def _lines(fig):
    for ax in fig.axes:
        for line in ax.get_lines():
            x = np.asarray(line.get_xdata(), dtype=float)
            y = np.asarray(line.get_ydata(), dtype=float)
            if x.size > 2:
                yield ax, x, y


def _is_column(x, y, columns) -> bool:
    """Whether (x, y) is a column of the run against its input angle, on any grid.

    The figure's points are compared with the column interpolated at the figure's
    angles (a figure may sample the drive more finely than ``run.points``).
    """
    angle = np.asarray(next(iter(columns.values())), dtype=float)
    ok = np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 3 or not np.all(np.diff(angle) > 0):
        return False
    x, y = x[ok], y[ok]
    if x.min() < angle[0] - 1e-9 or x.max() > angle[-1] + 1e-9:
        return False
    for col in list(columns.values())[1:]:
        col = np.asarray(col, dtype=float)
        if col.shape != angle.shape or not np.all(np.isfinite(col)):
            continue
        scale = float(np.max(np.abs(col)))
        if scale == 0.0:
            continue
        at = np.interp(x, angle, col)
        for f in FACTORS:
            if np.allclose(y, at * f, rtol=0.0, atol=2e-3 * scale * f):
                return True
    return False


@pytest.mark.slow
@pytest.mark.parametrize("example", EXAMPLES)
def test_figures_draw_the_model_inside_their_axes(example, tmp_path):
    result = evaluate(load_config(example=example)[0])
    with recording() as figures:
        paths = result.write_figures(tmp_path)
    assert len(figures) == len(paths) >= 3
    matched = 0
    for path, fig in figures:
        lines = list(_lines(fig))
        assert lines or any(ax.collections or ax.patches or ax.images for ax in fig.axes), path
        for ax, x, y in lines:
            finite = np.isfinite(x) & np.isfinite(y)
            if not finite.any():
                continue
            y0, y1 = sorted(ax.get_ylim())
            span = max(y1 - y0, 1e-300)
            inside = (y[finite] >= y0 - 1e-9 * span) & (y[finite] <= y1 + 1e-9 * span)
            assert inside.mean() > 0.5, f"{path.name}: a line is drawn mostly off its axes"
            matched += _is_column(x, y, result.columns)
    assert matched >= 1, "no figure line is a column of motion.csv"


def test_the_sweep_overview_draws_the_metrics_the_sweep_moves(tmp_path):
    # an impeller's inertia moves the flywheel and the torques with inertia, not the
    # pump's geometry, which comes first in the metrics' order
    from rotorkin.report.figures_sweep import fig_overview
    from rotorkin.sweep import run_sweep

    _, raw, _ = load_config(None, "guide-bar-pump")
    ds = run_sweep(raw, ["machine.inertia_impeller_1=0.001kg*m^2:0.01kg*m^2:4"],
                   samples=361, progress=False)  # fmt: skip
    metrics = [m for m in ds.data_vars if ds[m].dims == ds["reason"].dims and m != "reason"]
    spread = {m: float(np.ptp(ds[m].values)) for m in metrics if ds[m].dtype.kind == "f"}
    moving = [m for m in metrics if spread.get(m, 0.0) > 1e-9 * np.abs(ds[m].values).max()]
    assert 0 < len(moving) < len(metrics) and metrics[0] not in moving
    with recording() as figs:
        fig_overview(ds, metrics, tmp_path / "overview.png")
    ((_, fig),) = figs
    drawn = [ax.get_ylabel().split(" [")[0] for ax in fig.axes if ax.get_visible()]
    assert drawn == moving[:6]
    for ax in fig.axes[: len(drawn)]:
        (line,) = ax.get_lines()
        assert np.ptp(line.get_ydata()) > 0


def test_the_sweep_overview_of_a_sweep_that_moves_nothing_still_draws(tmp_path):
    from rotorkin.report.figures_sweep import fig_overview
    from rotorkin.sweep import run_sweep

    _, raw, _ = load_config(None, "guide-bar-pump")
    ds = run_sweep(raw, ["machine.inertia_impeller_1=0.001kg*m^2:0.01kg*m^2:3"],
                   metrics=["displacement_cm3_per_rev"], samples=361, progress=False)  # fmt: skip
    with recording() as figs:
        fig_overview(ds, ["displacement_cm3_per_rev"], tmp_path / "overview.png")
    ((_, fig),) = figs
    assert [ax.get_ylabel().split(" [")[0] for ax in fig.axes] == ["displacement_cm3_per_rev"]
