"""The source papers' values, per summary key, for the "paper vs ours" column of the report.

Two kinds of entry:

* ``printed``: a number the paper prints (or reads off a figure) for its own
  case; it applies only when the config is that case (``conditions``: config
  key -> value, SI, compared with a relative tolerance of 1e-9; an empty tuple
  stands for an empty list such as ``drive.a = []``).
* ``formula``: the paper's own closed-form equation, evaluated here at the
  config's parameters, written independently of the model (e.g. eq. 15 in its
  printed arccos form where the model uses atan2). It applies to every config
  that meets its ``conditions``.

For each summary key the first applicable entry wins. ``tolerance`` is absolute,
in the key's unit: the paper's rounding for printed values ("about 39 deg": 0.5 deg),
a small numerical tolerance for formulas. Sources: ``/work/shared/papers/*.md``
("Published numbers"). Each drive keeps its entries in
``rotorkin/drives/<name>/published.py``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Published", "applies", "paper_rows"]


@dataclass(frozen=True)
class Published:
    """One published value of a summary key.

    Attributes
    ----------
    key : str
        Summary key (unit as suffix).
    value : float or callable
        The printed number, or ``f(cfg) -> float`` evaluating the paper's formula
        on the config (SI inside, result in the key's unit).
    tolerance : float
        Absolute tolerance, in the key's unit.
    where : str
        Equation, table or figure of the paper.
    kind : str
        ``"printed"`` or ``"formula"``.
    conditions : dict
        Config key (``"drive.plate_tilt"``) -> value (SI) under which it applies.
    note : str
        One short remark (e.g. the paper's wording).
    """

    key: str
    value: float | Callable
    tolerance: float
    where: str
    kind: str = "printed"
    conditions: dict = field(default_factory=dict)
    note: str = ""


def _get(cfg, dotted):
    section, _, key = dotted.partition(".")
    return (cfg.get(section) or {}).get(key)


def applies(entry: Published, cfg: dict) -> bool:
    """Whether the config meets every condition of ``entry``."""
    for dotted, want in entry.conditions.items():
        have = _get(cfg, dotted)
        if isinstance(want, tuple):
            if have is not None and len(have) and np.any(np.asarray(have, float) != 0.0):
                return False
        elif isinstance(want, str):
            if have != want:
                return False
        elif have is None or not np.isclose(float(have), float(want), rtol=1e-9, atol=1e-12):
            return False
    return True


_D = np.radians


def paper_rows(published, reference: str, cfg: dict, summary: dict) -> dict:
    """The paper's value of each summary key that has one, for this config.

    Parameters
    ----------
    published : sequence of Published
        A drive's entries (``DriveSpec.published``), in display order.
    reference : str
        The paper's short reference (``DriveSpec.paper``).
    cfg, summary : dict
        The validated config (SI) and the study's summary.

    Returns
    -------
    dict
        Summary key -> ``{"paper", "ours", "difference", "tolerance", "within",
        "where", "kind", "note", "reference"}`` (first applicable entry per key,
        in the order of ``published``; keys missing from ``summary`` are left out).
    """
    out = {}
    for entry in published:
        if entry.key in out or entry.key not in summary or not applies(entry, cfg):
            continue
        paper = float(entry.value(cfg) if callable(entry.value) else entry.value)
        ours = summary[entry.key]
        ours_f = float(ours)
        diff = ours_f - paper
        out[entry.key] = {
            "paper": paper,
            "ours": ours,
            "difference": diff,
            "tolerance": float(entry.tolerance),
            "within": bool(abs(diff) <= entry.tolerance + 1e-12 * max(1.0, abs(paper))),
            "where": entry.where,
            "kind": entry.kind,
            "note": entry.note,
            "reference": reference,
        }
    return out
