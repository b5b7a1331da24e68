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

from rotorkin.core.extras import xarray_module
from rotorkin.core.motion import Motion
from rotorkin.core.units import metric_units

__all__ = ["StudyResult"]


#: Headline keys shown by ``repr`` (it stays short enough for a notebook cell).
_REPR_KEYS = 8


@dataclass(repr=False)
class StudyResult:
    """What one run of a study produced.

    Attributes
    ----------
    drive_type : str
        ``drive.type`` of the config.
    title : str
        One line for people, e.g. ``"Twin-rotor engine on a cam drive"``.
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
    write_figures : callable
        ``write_figures(outdir: Path) -> list[Path]`` writes the drive's PNG figures
        (the command line's ``run``); :meth:`plot` draws into a notebook instead.
    motion : rotorkin.core.motion.Motion, optional
        Both working members over one period (angles or travels and three
        derivatives); what :meth:`plot` and the generic report draw.
    warnings : tuple of str
        One line each: a model input that leaves a summary number without meaning
        (e.g. no heat added, so no power), naming the key to set. The command line
        prints them; the report lists them among its checks.
    checks : tuple of rotorkin.studies.checks.Check
        The design's checks with their margins (the drive's cam or part checks, the
        plausibility limits); :func:`rotorkin.drives.evaluate` fills them in.
    """

    drive_type: str
    title: str
    summary: dict
    columns: dict
    column_docs: dict
    headline: dict | tuple
    write_figures: Callable[[Path], list[Path]] = field(default=lambda outdir: [])
    motion: Motion | None = None
    warnings: tuple = ()
    checks: tuple = ()

    def __post_init__(self):
        lengths = {np.shape(v) for v in self.columns.values()}
        if len(lengths) > 1:
            raise ValueError(f"columns of unequal shape: {lengths}")
        missing = set(self.columns) - set(self.column_docs)
        if missing:
            raise ValueError(f"undocumented columns: {sorted(missing)}")

    # -- for people and notebooks ----------------------------------------------------------
    def _headline_items(self):
        keys = list(self.headline)[:_REPR_KEYS]
        return [(k, self.summary[k]) for k in keys if k in self.summary]

    def __repr__(self) -> str:
        rows = len(next(iter(self.columns.values()))) if self.columns else 0
        shown = ", ".join(f"{k}={_short(v)}" for k, v in self._headline_items())
        more = len(self.summary) - min(len(self.summary), _REPR_KEYS)
        return (
            f"<StudyResult {self.drive_type}: {self.title}; {shown}"
            f"{f' (+{more} summary keys)' if more > 0 else ''}; "
            f"{len(self.columns)} columns x {rows} angles>"
        )

    def _repr_html_(self) -> str:
        import html

        e = html.escape
        rows = "".join(
            f"<tr><td><code>{e(k)}</code></td><td style='text-align:right'>{e(_short(v))}</td>"
            f"<td>{e(str(self.headline.get(k, '')) if isinstance(self.headline, dict) else '')}"
            "</td></tr>"
            for k, v in self._headline_items()
        )
        return (
            f"<div><b>{e(self.drive_type)}</b>: {e(self.title)}<table>{rows}</table>"
            f"<small>{len(self.summary)} summary keys; {len(self.columns)} columns "
            "(<code>to_dataframe()</code>, <code>to_xarray()</code>)</small></div>"
        )

    def to_dataframe(self):
        """The per-angle columns as a :class:`pandas.DataFrame` (``motion.csv``; pandas comes
        with the ``xarray`` extra)."""
        xarray_module("Study.to_dataframe")
        import pandas as pd

        return pd.DataFrame({k: np.asarray(v) for k, v in self.columns.items()})

    def to_xarray(self):
        """The per-angle columns as an :class:`xarray.Dataset` over the input angle.

        The first column (the input angle) is the coordinate ``angle``; every other
        column a variable with its unit and description as attributes; the summary's
        numbers are attributes of the dataset. Needs the ``xarray`` extra.
        """
        xr = xarray_module("Study.to_xarray")

        names = list(self.columns)
        first = names[0]
        coords = {
            "angle": (
                "angle",
                np.asarray(self.columns[first], dtype=float),
                {"units": metric_units(first), "long_name": self.column_docs[first]},
            )
        }
        data = {
            k: (
                "angle",
                np.asarray(self.columns[k]),
                {"units": metric_units(k), "long_name": self.column_docs[k]},
            )
            for k in names[1:]
        }
        attrs = {"drive_type": self.drive_type, "title": self.title}
        for k, v in self.summary.items():
            if isinstance(v, (bool, np.bool_)):
                attrs[k] = int(v)
            elif isinstance(v, (int, float, str, np.number)):
                attrs[k] = v
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def plot(self, ax=None, what: str = "position"):
        """Both members over one period, drawn into ``ax`` (new figure when None).

        Parameters
        ----------
        ax : matplotlib Axes, optional
        what : {"position", "velocity", "acceleration", "jerk"}
            The member position or its first, second or third derivative with
            respect to the input angle (kinematic coefficients).

        Returns
        -------
        matplotlib.figure.Figure
        """
        orders = {"position": 0, "velocity": 1, "acceleration": 2, "jerk": 3}
        if what not in orders:
            raise ValueError(f"what = {what!r} is not admissible: one of {', '.join(orders)}")
        if self.motion is None:
            raise ValueError(f"the {self.drive_type} study keeps no member motion to plot")
        if ax is None:
            import matplotlib.pyplot as plt

            _, ax = plt.subplots(figsize=(7.0, 3.6))
        m = self.motion
        k = orders[what]
        values = (m.q, m.dq, m.d2q, m.d3q)[k]
        scale, unit = (np.degrees, "deg") if m.unit == "rad" else ((lambda v: 1e3 * v), "mm")
        x = np.degrees(np.asarray(m.theta, dtype=float))
        for i in (0, 1):
            ax.plot(x, scale(values[i]), label=m.members[i])
        suffix = "" if k == 0 else f"/rad{'^' + str(k) if k > 1 else ''}"
        ax.set_xlabel("input angle theta [deg]")
        ax.set_ylabel(f"{what} [{unit}{suffix}]")
        ax.set_title(self.title)
        ax.grid(True, alpha=0.4)
        ax.legend()
        return ax.figure


def _short(value) -> str:
    """A summary value in a few characters."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.5g}"
    text = str(value)
    return text if len(text) <= 24 else text[:21] + "..."
