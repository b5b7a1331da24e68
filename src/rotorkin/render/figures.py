"""Helpers of the matplotlib figures, and the recipe of a paper's sweep figure.

matplotlib is imported when a figure is drawn, never at import time, and its
backend is left to the caller: the command line selects Agg; a notebook keeps
its own.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

__all__ = [
    "recording",
    "DPI",
    "BASELINE",
    "SYNTHESIZED",
    "pyplot",
    "save",
    "save_in",
    "degree_axis",
    "Recipe",
]

#: Resolution of the PNG figures [dots per inch].
DPI = 120


def pyplot():
    """``matplotlib.pyplot``, imported on first use."""
    import matplotlib.pyplot as plt

    return plt


#: Figures kept open by :func:`recording` (None: figures are closed once written).
_RECORDED: list | None = None


@contextlib.contextmanager
def recording():
    """Collect every figure written inside the block as ``(path, Figure)``, still open.

    For tests and notebooks that look at what a figure plots (its lines' data)
    rather than at the PNG; the figures are closed when the block ends.
    """
    global _RECORDED
    previous, _RECORDED = _RECORDED, []
    record = _RECORDED
    try:
        yield record
    finally:
        _RECORDED = previous
        for _, fig in record:
            pyplot().close(fig)


def _done(fig, path: Path) -> None:
    """Close a written figure, or keep it for :func:`recording`."""
    if _RECORDED is None:
        pyplot().close(fig)
    else:
        _RECORDED.append((Path(path), fig))


def _laid_out(fig) -> None:
    """Forget the inert layout engine ``tight_layout`` leaves behind.

    matplotlib keeps a placeholder engine after ``fig.tight_layout()``, and
    ``savefig`` then draws the whole figure once more before drawing it for the file
    (about a third of a figure's time); the placeholder lays nothing out, so the file
    is the same without it.
    """
    import matplotlib
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    if isinstance(fig.get_layout_engine(), PlaceHolderLayoutEngine) and not (
        matplotlib.rcParams["figure.autolayout"]
        or matplotlib.rcParams["figure.constrained_layout.use"]
    ):
        fig.set_layout_engine(None)


def save(fig, path: Path, dpi: int = DPI, rect=None) -> Path:
    """Lay out (within ``rect`` of the figure, when given), write and close ``fig``."""
    if rect is None:
        fig.tight_layout()
    else:
        fig.tight_layout(rect=rect)
    _laid_out(fig)
    fig.savefig(path, dpi=dpi)
    _done(fig, path)
    return Path(path)


@dataclass(frozen=True)
class Recipe:
    """A sweep behind one or more of a paper's figures.

    ``sets`` are ``--set`` overrides of the config, ``vary`` the ``--vary`` items,
    ``figures`` the PNG names drawn from its dataset, ``note`` what the recipe
    changes in the config and why, ``metrics`` the summary keys it needs and
    ``plot(ds, outdir, recipe, cfg) -> list[Path]`` draws the figures from the
    sweep's dataset and its validated base config.
    """

    key: str
    sets: tuple
    vary: tuple
    curves: bool
    figures: tuple
    note: str = ""
    metrics: tuple = field(default=())
    plot: Callable | None = field(default=None, compare=False, repr=False)


#: Line styles of a baseline design and a synthesized one drawn side by side.
BASELINE = {"color": "0.45", "lw": 1.6, "label": "baseline (paper)"}
SYNTHESIZED = {"color": "C3", "lw": 1.8, "label": "synthesized"}


def save_in(fig, outdir, name: str, dpi: int = DPI) -> Path:
    """Write and close ``fig`` as ``outdir/name`` (its layout as it is); return the path."""
    path = Path(outdir) / name
    _laid_out(fig)
    fig.savefig(path, dpi=dpi)
    _done(fig, path)
    return path


def degree_axis(ax, end: float, step: float, label: str | None) -> None:
    """An x axis of angles from 0 to ``end`` [deg] with ticks every ``step``, and a grid."""
    import numpy as np

    ax.set_xlim(0.0, end)
    ax.set_xticks(np.arange(0.0, end + 1e-9, step))
    if label:
        ax.set_xlabel(label)
    ax.grid(True, alpha=0.4)
