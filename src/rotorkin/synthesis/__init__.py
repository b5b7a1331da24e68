"""Synthesis: the drive parameters or cam laws that produce a wanted motion.

Each drive that synthesizes has a module ``rotorkin/drives/<name>/synthesis.py``
of plain functions on arrays plus a ``synthesize(cfg, raw, objective, target,
harmonics, options)`` entry point returning a :class:`SynthesisResult`; its
objectives are listed by its ``DriveSpec`` and reached through
:func:`rotorkin.drives.synthesize`. This module holds what they share: the
result type, the dwell measure and the parsing of targets.

The result carries the baseline (the config as given: the paper's design in
the examples) beside the synthesized design, the raw config keys to change,
and the functions writing its figures and CSV files; ``rotorkin synthesize``
writes them (:mod:`rotorkin.cli.synthesize`).
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rotorkin.core.errors import ParameterError
from rotorkin.core.units import parse_quantity

__all__ = [
    "DWELL_TOLERANCE",
    "SynthesisResult",
    "synthesized_raw_config",
    "dwell_fraction",
    "parse_fraction",
    "parse_quantity_arg",
    "fmt",
]

#: Dwell tolerance as a fraction of the swing of the chamber angle (psi or delta):
#: a law "dwells" where it is within this fraction of the swing from its extreme
#: (2 deg of a 100 deg swing).
DWELL_TOLERANCE = 0.02


@dataclass(frozen=True)
class SynthesisResult:
    """What a synthesis produced, beside the design it started from.

    Attributes
    ----------
    drive_type : str
        ``drive.type``.
    objective : str
        Objective or target name (``"min_accel"``, ``"vane_angle"``, ...).
    title : str
        One line for people.
    rows : tuple of (str, object, object)
        The printed table: metric (unit in the name), baseline value,
        synthesized value (floats, bools or short strings).
    parameters : dict
        The synthesized parameters, flat, unit as key suffix (JSON).
    metrics : dict
        Flat metrics of both designs (``baseline_*``, ``synthesized_*``) and the
        round-trip errors (JSON).
    updates : dict
        ``{section: {key: raw value}}`` to apply to the raw config (values as a
        config file writes them: strings with units, bare numbers, lists).
    notes : tuple of str
        Lines printed under the table (alternatives, reasons).
    plot : callable
        ``plot(outdir) -> list[Path]``: the comparison figures (PNG).
    tables : dict
        File name -> ``{column: 1-d array}`` written as CSV (unit suffix in names).
    """

    drive_type: str
    objective: str
    title: str
    rows: tuple
    parameters: dict
    metrics: dict
    updates: dict
    notes: tuple = ()
    plot: Callable[[Path], list[Path]] = field(default=lambda outdir: [], repr=False)
    tables: dict = field(default_factory=dict, repr=False)


def synthesized_raw_config(raw: dict, updates: dict, objective: str = "") -> dict:
    """A deep copy of ``raw`` with ``updates`` applied (a config ``rotorkin run`` accepts).

    Parameters
    ----------
    raw : dict
        The config as written.
    updates : dict
        ``{section: {key: raw value}}`` (:attr:`SynthesisResult.updates`); a value
        None removes the key.
    objective : str, optional
        Appended to the title.
    """
    out = copy.deepcopy(raw)
    for section, values in updates.items():
        node = out.setdefault(section, {})
        for key, value in values.items():
            if value is None:
                node.pop(key, None)
            else:
                node[key] = value
    title = out.get("title")
    if isinstance(title, str) and title:
        out["title"] = f"{title} - synthesized ({objective})"
    return out


def dwell_fraction(values, extreme, tolerance, axis=-1):
    """Fraction of one period during which a sampled law stays within ``tolerance`` of ``extreme``.

    The samples are one period, evenly spaced, the end point *excluded*
    (periodic). Each interval between neighbouring samples (the last one
    wrapping around) counts with the share of it where ``|values - extreme| <
    tolerance``, the crossing found by linear interpolation, so the measure is
    continuous in the law (an optimiser can use it).

    Parameters
    ----------
    values : array_like, shape (..., n)
        The law over one period [any unit].
    extreme : array_like
        The extreme it dwells at (broadcast with ``values[..., 0]``).
    tolerance : array_like
        Half-width of the dwell band, > 0 (same unit).
    axis : int, optional
        Axis of the samples.

    Returns
    -------
    ndarray
        Fraction in [0, 1], shape of ``values`` without ``axis``.
    """
    v = np.moveaxis(np.asarray(values, dtype=float), axis, -1)
    g = np.asarray(tolerance, dtype=float)[..., None] - np.abs(
        v - np.asarray(extreme, dtype=float)[..., None]
    )
    g0, g1 = g, np.roll(g, -1, axis=-1)
    both = (g0 > 0.0) & (g1 > 0.0)
    one = (g0 > 0.0) != (g1 > 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        share = np.where(one, np.maximum(g0, g1) / np.abs(g0 - g1), 0.0)
    return np.mean(np.where(both, 1.0, share), axis=-1)


def parse_fraction(text, name: str = "target") -> float:
    """A fraction written ``"25 %"``, ``"25%"`` or ``"0.25"`` -> 0.25.

    Raises
    ------
    ParameterError
        When the text is not a finite number (with an optional ``%``).
    """
    s = str(text).strip()
    scale = 1.0
    if s.endswith("%"):
        s, scale = s[:-1].strip(), 0.01
    try:
        value = float(s) * scale
    except ValueError:
        raise ParameterError(
            name, repr(text), 'a number or a percentage, e.g. "0.25" or "25 %"'
        ) from None
    if not np.isfinite(value):
        raise ParameterError(name, repr(text), "a finite number")
    return value


def parse_quantity_arg(text, kind: str, name: str = "target") -> float:
    """A value with a unit (``"60 deg"``, ``"5 mm"``) -> SI float; ParameterError if not."""

    value, reason = parse_quantity(str(text), kind)
    if reason:
        raise ParameterError(name, repr(text), reason.split(": ", 1)[-1])
    return value


def fmt(value) -> str:
    """A table cell: floats to 6 significant digits, the rest as text."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.6g}"
    return str(value)
