"""Plausibility limits: which results of a study are past the config's ``[limits]``.

A design can be admissible (every key in its range, the cam checks passed) and still
give numbers no machine of this kind reaches: hundreds of bar, a pressure angle at
which the drive jams, a contact pressure the parts cannot carry. Each limit is
compared with every summary key (and motion column) that measures it:

================================  ==========================================================
limit (config key)                 summary keys / columns checked
================================  ==========================================================
``limits.peak_pressure``          ``peak_pressure_bar``, ``pressure_max_bar``,
                                  ``chamber*_pressure*_bar`` (columns: their maximum)
``limits.peak_temperature``       ``*temperature*_K`` (``hot_temperature_K`` ...)
``limits.pressure_angle``         ``*pressure_angle*max_deg`` (columns
                                  ``*pressure_angle*_deg``: their largest magnitude)
``contact.allowable_stress``      ``*contact_stress*_MPa`` (``peak_contact_stress_MPa``)
================================  ==========================================================

:func:`violations` gives one line per limit passed (the worst key names it);
:func:`violation_codes` is the same test on arrays of sweep metrics, as a bit mask.
"""

from __future__ import annotations

import math
import re

import numpy as np

from rotorkin.core.errors import ConfigError
from rotorkin.core.schema import ContactSection, LimitsSection

__all__ = [
    "LIMITS",
    "BITS",
    "limit_value",
    "violations",
    "violated",
    "violation_codes",
    "flag_doc",
    "refuse",
]

#: config key -> (summary-key pattern, column pattern or None, unit of the keys, SI -> unit)
LIMITS: dict[str, tuple[str, str | None, str, float]] = {
    "limits.peak_pressure": (
        r"^(peak_pressure|pressure_max|chamber\w*_pressure\w*)_bar$",
        r"^(chamber\w*_)?pressure_bar$",
        "bar",
        1e-5,
    ),
    "limits.peak_temperature": (r"temperature\w*_K$", r"temperature\w*_K$", "K", 1.0),
    "limits.pressure_angle": (
        r"pressure_angle\w*max_deg$",
        r"pressure_angle\w*_deg$",
        "deg",
        180.0 / math.pi,
    ),
    "contact.allowable_stress": (r"contact_stress\w*_MPa$", None, "MPa", 1e-6),
}

#: Limits whose motion columns are signed and checked by their magnitude (the others by
#: their largest value: a liquid's negative pressure is no peak pressure).
MAGNITUDES = frozenset({"limits.pressure_angle"})

#: config key -> its bit in a sweep's ``violations`` mask.
BITS: dict[str, int] = {key: 1 << i for i, key in enumerate(LIMITS)}

_DEFAULTS = {
    "limits": LimitsSection().model_dump(),
    "contact": ContactSection().model_dump(),
}


def limit_value(cfg: dict, key: str) -> float:
    """The value of a limit's config key (its default where the config has none), SI."""
    section, name = key.split(".")
    value = (cfg.get(section) or {}).get(name)
    return float(_DEFAULTS[section][name] if value is None else value)


def _number(value) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def worst_result(key: str, summary: dict, columns: dict | None = None) -> tuple | None:
    """``(name, value)`` of the largest result that limit ``key`` measures, or None.

    Summary values and the largest value of the matching motion columns (the largest
    magnitude for the limits of :data:`MAGNITUDES`), in the limit's unit
    (:data:`LIMITS`); values that are not finite are not counted.
    """
    pattern, col_pattern, _, _ = LIMITS[key]
    worst = None
    for name, value in summary.items():
        v = _number(value) if re.search(pattern, name) else None
        if v is not None and (worst is None or v > worst[1]):
            worst = (name, v)
    for name, values in (columns or {}).items() if col_pattern else ():
        if not re.search(col_pattern, name):
            continue
        arr = np.asarray(values, dtype=float)
        if key in MAGNITUDES:  # a signed angle: its size; a pressure: its highest value
            arr = np.abs(arr)
        arr = arr[np.isfinite(arr)]
        if arr.size and (worst is None or float(arr.max()) > worst[1]):
            worst = (f"max of {name}", float(arr.max()))
    return worst


def violated(summary: dict, cfg: dict, columns: dict | None = None) -> list[tuple]:
    """``[(config key, worst result name, value, limit)]`` of every limit passed (key units)."""
    out = []
    for key, (_, _, _, scale) in LIMITS.items():
        limit = limit_value(cfg, key) * scale
        worst = worst_result(key, summary, columns)
        if worst is not None and worst[1] > limit:
            out.append((key, worst[0], worst[1], limit))
    return out


def _fmt(value: float) -> str:
    return f"{value:.4g}" if abs(value) < 1e4 else f"{value:.3g}"


def violations(summary: dict, cfg: dict, columns: dict | None = None) -> list[str]:
    """One line per plausibility limit the results pass; ``[]`` when none.

    Parameters
    ----------
    summary : dict
        A study's summary (keys with their unit as suffix).
    cfg : dict
        The validated SI config: ``limits`` and ``contact.allowable_stress`` (defaults
        where missing).
    columns : dict, optional
        The study's motion columns; their extremes are checked too.

    Examples
    --------
    ``limits.peak_pressure: peak_pressure_bar = 438 bar is above 250 bar``
    """
    lines = []
    for key, name, value, limit in violated(summary, cfg, columns):
        unit = LIMITS[key][2]
        line = f"{key}: {name} = {_fmt(value)} {unit} is above {_fmt(limit)} {unit}"
        if key == "contact.allowable_stress":
            where = summary.get("peak_contact_stress_pair")
            sf = summary.get("contact_safety_factor")
            detail = [] if not isinstance(where, str) else [str(where)]
            if _number(sf) is not None:
                detail.append(f"safety factor {float(sf):.2f}")
            if detail:
                line += f" ({', '.join(detail)})"
            line += ": the parts would not hold at this speed and load"
        elif key == "limits.pressure_angle":
            line += ": the drive would jam or wear rather than drive"
        else:
            line += ": not plausible for this machine"
        lines.append(line)
    return lines


def violation_codes(metrics: dict, cfg: dict, n: int, table: dict | None = None) -> np.ndarray:
    """The ``violations`` bit mask (:data:`BITS`) of ``n`` designs from arrays of metrics.

    ``metrics`` maps summary keys to (n,) arrays (NaN: not known, not flagged); a limit
    the sweep varies is read per design from ``table`` (config key -> (n,) SI values).
    Only the limits whose keys are among ``metrics`` can be flagged.
    """
    codes = np.zeros(n, dtype=np.int16)
    table = table or {}
    for key, (pattern, _, _, scale) in LIMITS.items():
        limit = table.get(key)
        limit = (limit_value(cfg, key) if limit is None else np.asarray(limit, dtype=float)) * scale
        for name, values in metrics.items():
            if not re.search(pattern, name):
                continue
            with np.errstate(invalid="ignore"):
                past = np.asarray(values, dtype=float) > limit
            codes[past] |= BITS[key]
    return codes


def flag_doc() -> str:
    """The meaning of the ``violations`` bits, for a sweep variable's attributes."""
    return ", ".join(f"{bit} {key}" for key, bit in BITS.items())


def refuse(result) -> None:
    """``--strict``: raise :class:`ConfigError` naming the first limit ``result`` passes."""
    lines = [w for w in result.warnings if w.split(":", 1)[0] in LIMITS]
    if lines:
        more = f" (and {len(lines) - 1} more)" if len(lines) > 1 else ""
        raise ConfigError(f"--strict refuses the design: {lines[0]}{more}")
