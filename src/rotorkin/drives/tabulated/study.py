"""Study of a vane machine on a tabulated drive (a CSV table or a Fourier series).

Config keys (SI): ``drive.table`` (a CSV file, absolute once loaded),
``drive.columns``, ``drive.harmonics``, or the Fourier law ``drive.period``,
``drive.mean_ratio``, ``drive.offset``, ``drive.a1`` ... ``drive.b2``;
``[machine]`` and ``[loads]`` of ``machine.type``, ``run``. The table is fitted by
:mod:`rotorkin.drives.tabulated.law` (trigonometric interpolation, exact
derivatives) and any vane machine runs on it (:func:`rotorkin.vane.evaluate`).
"""

from __future__ import annotations

import functools

import numpy as np

from rotorkin.drives.tabulated import law as tl
from rotorkin.studies import StudyResult
from rotorkin.vane import RotaryLaw
from rotorkin.vane import evaluate as evaluate_machine

__all__ = ["evaluate", "fourier_law", "law", "HEADLINE"]

#: The drive's summary keys printed by the command line (the machine's follow).
HEADLINE = {
    "law_harmonics": "harmonics of the fitted (or given) law",
    "law_period_deg": "period of the law in shaft angle",
    "fit_error_q_deg": "a-posteriori bound of the fit's angle error (tables)",
}


def _table(cfg: dict):
    """The table's rows ``(theta, q1, q2)`` [rad], or None for a Fourier law."""
    d = cfg["drive"]
    return tl.read_table(d["table"], d.get("columns")) if d.get("table") is not None else None


def fourier_law(cfg: dict, table=None) -> tl.FourierLaw:
    """The drive's :class:`~rotorkin.drives.tabulated.law.FourierLaw` (table fitted, or given).

    ``table``: the rows already read (:func:`_table`), so that a study reads the file once.
    """
    d = cfg["drive"]
    if d.get("table") is not None:
        rows = _table(cfg) if table is None else table
        return tl.from_table(*rows, d.get("harmonics"))
    coefficients = []
    for a, b in (("a1", "b1"), ("a2", "b2")):  # a missing sine or cosine term is 0
        ca, cb = list(d.get(a, [])), list(d.get(b, []))
        n = max(len(ca), len(cb))
        coefficients += [ca + [0.0] * (n - len(ca)), cb + [0.0] * (n - len(cb))]
    return tl.from_fourier(d["period"], d["mean_ratio"], d.get("offset", [0.0, 0.0]), *coefficients)


def _members(cfg):
    cols = cfg["drive"].get("columns")
    return tuple(cols[1:]) if cols else ("member 1", "member 2")


def law(cfg: dict) -> RotaryLaw:
    """The members' motion for any vane machine (:mod:`rotorkin.vane`)."""
    fl = fourier_law(cfg)
    return RotaryLaw(functools.partial(tl.motion, fl, members=_members(cfg)), fl.period)


def _summary(cfg: dict, fl: tl.FourierLaw, table) -> dict:
    out = {
        "law_harmonics": int(fl.harmonics),
        "law_period_deg": float(np.degrees(fl.period)),
        "member1_mean_ratio": float(fl.mean_ratio[0]),
        "member2_mean_ratio": float(fl.mean_ratio[1]),
    }
    if table is not None:
        theta, q1, q2 = table
        err = tl.fit_error(theta, q1, q2, cfg["drive"].get("harmonics"))
        out["table_rows"] = int(np.size(theta))
        out["fit_error_q_deg"] = float(np.degrees(np.max(err.q)))
        out["fit_error_dq"] = float(np.max(err.dq))
        out["fit_error_d2q_per_rad"] = float(np.max(err.d2q))
        out["fit_error_d3q_per_rad2"] = float(np.max(err.d3q))
        out["fit_method"] = err.method
    return out


def evaluate(cfg: dict) -> StudyResult:
    """Run ``machine.type`` on the tabulated drive of ``cfg`` (validated, SI)."""
    table = _table(cfg)
    fl = fourier_law(cfg, table)
    kind = cfg["machine"]["type"]
    source = "a table" if cfg["drive"].get("table") is not None else "a Fourier law"
    return evaluate_machine(
        cfg,
        RotaryLaw(functools.partial(tl.motion, fl, members=_members(cfg)), fl.period),
        drive_type="tabulated",
        title=f"{kind.replace('_', ' ')} on a tabulated drive ({source})",
        drive_summary=_summary(cfg, fl, table),
        drive_headline=HEADLINE,
    )
