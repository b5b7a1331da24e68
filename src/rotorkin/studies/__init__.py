"""Studies: what every drive's study returns, and the helpers they share.

A drive's study (``rotorkin/drives/<name>/study.py``, reached through the
registry's :func:`rotorkin.drives.evaluate`) reads the config (SI values, see
:mod:`rotorkin.io.config`), builds the drive's parameter dataclass, evaluates
the drive over one period and returns a :class:`StudyResult`: the flat
summary, the per-angle columns of ``motion.csv`` and a function that draws the
figures.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["StudyResult"]


@dataclass
class StudyResult:
    """What one run of a study produced.

    Attributes
    ----------
    drive_type : str
        ``drive.type`` of the config.
    title : str
        One line for people, e.g. ``"Twin-rotor engine, wobble plate + spherical cam"``.
    summary : dict
        Flat mapping of metric name (unit as suffix, e.g. ``chamber_swing_deg``)
        to a float, int, bool or str. Written as ``summary.json``.
    columns : dict of str -> ndarray
        1-d arrays of equal length, one row per input angle over one period;
        names carry their unit as suffix (``theta_deg``, ``z_left_mm``); a
        dimensionless column has no unit suffix. Written as ``motion.csv``.
    column_docs : dict of str -> str
        One sentence per column of ``columns`` (what it is, sign convention).
    headline : dict of str -> str
        Summary keys shown in the printed table, in order, each with a short line
        saying what it is (which model, which sign); a tuple of keys is accepted.
    plot : callable
        ``plot(outdir: Path) -> list[Path]`` writes the PNG figures.
    """

    drive_type: str
    title: str
    summary: dict
    columns: dict
    column_docs: dict
    headline: dict | tuple
    plot: Callable[[Path], list[Path]] = field(repr=False)

    def __post_init__(self):
        lengths = {np.shape(v) for v in self.columns.values()}
        if len(lengths) > 1:
            raise ValueError(f"columns of unequal shape: {lengths}")
        missing = set(self.columns) - set(self.column_docs)
        if missing:
            raise ValueError(f"undocumented columns: {sorted(missing)}")
