"""Words and numbers of the report as people read them: Greek letters, units, labels, digits.

The model's texts are written in ASCII (``delta_A``, ``cm^3``, ``N*m``, ``[deg]``);
:func:`pretty` turns them into what the page shows (``δ<sub>A</sub>``, ``cm³``,
``N·m``, ``[°]``), one unit style for the whole page. Summary keys carry their
unit as a suffix (``mean_torque_Nm``); :func:`key_label` splits a key into a label
and a unit. Numbers: :func:`number` writes a value with a given number of
significant digits and writes round-off as 0 only when it is below
:data:`ROUNDOFF` times the scale of the quantity (:func:`unit_scales`), so that a
torque of 1.4e-16 N·m beside torques of 4 N·m reads 0 and a small but real value
keeps its digits.
"""

from __future__ import annotations

import html as _html
import math
import re

import numpy as np

__all__ = [
    "ROUNDOFF",
    "esc",
    "pretty",
    "plain",
    "unit_of",
    "key_label",
    "unit_scales",
    "number",
    "is_roundoff",
    "d3_format",
]

#: A value is round-off of zero when ``|value| <= ROUNDOFF * scale`` of its quantity.
ROUNDOFF = 1e-9

_GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "eps": "ε",
    "zeta": "ζ", "eta": "η", "theta": "θ", "kappa": "κ", "lambda": "λ", "mu": "μ",
    "xi": "ξ", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ", "phi": "φ",
    "varphi": "ϕ", "chi": "χ", "psi": "ψ", "omega": "ω",
    "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ", "Sigma": "Σ", "Phi": "Φ",
    "Psi": "Ψ", "Omega": "Ω",
}  # fmt: skip
_SUB_DIGITS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
_NAME = r"(?<![\w.])({})('*)(?:_([A-Za-z0-9]{{1,3}}))?('*)(?!\w)".format(
    "|".join(sorted(_GREEK, key=len, reverse=True))
)
_GREEK_RE = re.compile(_NAME)
_SUB_RE = re.compile(r"(?<![\w.])([A-Za-z])('*)_([A-Za-z0-9]{1,3})('*)(?!\w)")
_UNITS = [  # (pattern, replacement), in order
    (re.compile(r"\bkg\s*\*\s*m\^?2\b"), "kg·m²"),
    (re.compile(r"\bN\s*\*\s*m\b"), "N·m"),
    (re.compile(r"\b(c?m|mm|rad|s)\^?([23])(?![\w^])"), None),  # cm^3, mm3, rad^2, s^2
    (re.compile(r"\^2\b"), "²"),
    (re.compile(r"\^3\b"), "³"),
    (re.compile(r"\[deg\]"), "[°]"),
    (re.compile(r"^deg$"), "°"),
    (re.compile(r"(\d)\s?deg\b"), r"\1°"),
    (re.compile(r"\bdeg\b(?=/)"), "°"),
    (re.compile(r"\+-"), "±"),
    (re.compile(r"(?:<|&lt;)="), "≤"),
    (re.compile(r"(?:>|&gt;)="), "≥"),
    (re.compile(r"->"), "→"),
]
_SUPER = {"2": "²", "3": "³"}


def esc(text) -> str:
    """Text for an HTML text node (``&``, ``<``, ``>`` escaped; quotes kept for :func:`pretty`)."""
    return _html.escape(str(text), quote=False)


def _sub(token: str) -> str:
    if token.isdigit():
        return token.translate(_SUB_DIGITS)
    return f"<sub>{token}</sub>"


def _greek(m: re.Match) -> str:
    sym = _GREEK[m.group(1)]
    sub = _sub(m.group(3)) if m.group(3) else ""
    return sym + "′" * len(m.group(2)) + sub + "′" * len(m.group(4))


_DGREEK_RE = re.compile(
    r"(?<![\w.])d({})(?!\w)".format("|".join(sorted(_GREEK, key=len, reverse=True)))
)
_DSUB_RE = re.compile(r"(?<![\w.])d([A-Za-z])_([0-9]{1,2})(?!\w)")


def pretty(text: str) -> str:
    """Greek letters, subscripts and one unit style in a label (HTML in, HTML out).

    ``delta_A`` -> ``δ<sub>A</sub>``, ``gamma_0`` -> ``γ₀``, ``alpha'`` -> ``α′``,
    ``x_1`` -> ``x₁``, ``cm^3``/``cm3`` -> ``cm³``, ``N*m`` -> ``N·m``,
    ``kg*m^2`` -> ``kg·m²``, ``rad/s^3`` -> ``rad/s³``, ``[deg]`` -> ``[°]``,
    ``45 deg`` -> ``45°``, ``+-`` -> ``±``. Dotted or snake_case identifiers (config
    keys such as ``machine.vane_angle``) are left alone.
    """
    if not text:
        return text
    out = _DGREEK_RE.sub(lambda m: "d" + _GREEK[m.group(1)], str(text))  # dtheta -> dθ
    out = _DSUB_RE.sub(lambda m: "d" + m.group(1) + _sub(m.group(2)), out)  # dq_1 -> dq₁
    out = _GREEK_RE.sub(_greek, out)
    out = _SUB_RE.sub(
        lambda m: m.group(1) + "′" * len(m.group(2)) + _sub(m.group(3)) + "′" * len(m.group(4)),
        out,
    )
    for pattern, repl in _UNITS:
        if repl is None:
            out = pattern.sub(lambda m: m.group(1) + _SUPER[m.group(2)], out)
        else:
            out = pattern.sub(repl, out)
    return out


_TAG_RE = re.compile(r"<[^>]+>")


def plain(text: str) -> str:
    """A :func:`pretty` label without its HTML (``<br>`` as a space): for CSV headers, titles."""
    return _TAG_RE.sub("", str(text).replace("<br>", " ")).replace("&amp;", "&")


_BRACKET_RE = re.compile(r"\[([^\[\]]*)\]\s*$")


def unit_of(label: str) -> str:
    """The unit written in square brackets at the end of an axis label (``""`` if none)."""
    m = _BRACKET_RE.search(plain(label or ""))
    return m.group(1).strip() if m else ""


# key suffix -> unit as shown; the longest suffix that matches wins
_KEY_UNITS = {
    "deg": "°", "rad": "rad", "mm": "mm", "m": "m", "cm2": "cm²", "cm3": "cm³",
    "cm3_per_rev": "cm³/rev", "cm3_per_rad": "cm³/rad", "l_per_min": "l/min", "Nm": "N·m",
    "N": "N", "MPa": "MPa", "bar": "bar", "J": "J", "J_per_rev": "J/rev", "W": "W",
    "kW": "kW", "kgm2": "kg·m²", "rpm": "rpm", "percent": "%", "K": "K", "s": "s",
    "Hz": "Hz", "m_per_s": "m/s", "m_per_s2": "m/s²", "m_per_s3": "m/s³",
    "mm_per_rad": "mm/rad", "mm_per_rad2": "mm/rad²", "mm_per_rad3": "mm/rad³",
    "rad_per_s": "rad/s", "rad_per_s2": "rad/s²", "rad_per_s3": "rad/s³",
    "per_rev": "per turn", "per_period": "per period", "per_m": "1/m", "kg": "kg",
}  # fmt: skip
_SUFFIXES = sorted(_KEY_UNITS, key=lambda s: -s.count("_"))
_QUALIFIERS = {"max", "min", "mean", "peak", "ratio"}
_WORDS = {"imep": "IMEP", "bmep": "BMEP", "rpm": "rpm"}


def key_label(key: str) -> tuple[str, str]:
    """``(label, unit)`` of a summary key: ``"mean_torque_Nm"`` -> ``("Mean torque", "N·m")``.

    The unit comes from the key's suffix (``_deg``, ``_cm3_per_rev``, ``_Nm`` ...);
    the label is the rest in words, with Greek letters (:func:`pretty`).
    """
    parts = key.split("_")
    unit = ""
    for suffix in _SUFFIXES:
        n = suffix.count("_") + 1
        if len(parts) > n and "_".join(parts[-n:]) == suffix:
            unit, parts = _KEY_UNITS[suffix], parts[:-n]
            break
    words = [_WORDS.get(w, w) for w in parts]
    if len(words) > 1 and words[-1] in _QUALIFIERS:
        words[-2] += ","
    text = pretty(" ".join(words))
    if text[:1].isascii():
        text = text[:1].upper() + text[1:]
    return text or key, unit


def unit_scales(summary: dict) -> dict:
    """The scale of each unit among the summary's numbers: the largest ``|value|`` of a key
    with that unit (dimensionless keys: 1)."""
    scales: dict[str, float] = {}
    for key, value in summary.items():
        if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
            continue
        v = float(value)
        if not math.isfinite(v):
            continue
        unit = key_label(key)[1]
        scales[unit] = max(scales.get(unit, 0.0), abs(v))
    scales[""] = 1.0
    return scales


def is_roundoff(value: float, scale: float) -> bool:
    """True when ``value`` is nonzero but within :data:`ROUNDOFF` of zero at ``scale``."""
    return value != 0.0 and abs(value) <= ROUNDOFF * abs(scale)


def number(value, digits: int = 4, scale: float | None = None) -> str:
    """A number for people: ``digits`` significant digits, round-off of zero as 0.

    ``scale``: the size of the quantity (e.g. the largest torque of the run); a value
    within :data:`ROUNDOFF` of zero at that scale is written ``0``. Without a scale a
    value is written as it is. Integers as they are, booleans as yes/no, NaN as n/a.
    Large and small values get an exponent (``2.176e+08``); a minus sign is U+2212.
    """
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value)).replace("-", "−")
    if not isinstance(value, (float, np.floating)):
        return str(value)
    v = float(value)
    if not math.isfinite(v):
        return "n/a"
    if v == 0.0 or (scale is not None and is_roundoff(v, scale)):
        return "0"
    if 1e-3 <= abs(v) < 10**digits * 10:
        text = f"{v:.{digits}g}"
        if "e" in text:  # 12345 at 4 digits: write the integer, not 1.234e+04
            text = f"{v:.0f}"
    else:
        mant, _, exp = f"{v:.{digits - 1}e}".partition("e")
        text = f"{mant}×10{_superscript(int(exp))}"
    return text.replace("-", "−")


def _superscript(n: int) -> str:
    return str(n).translate(str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹"))


def d3_format(values, digits: int = 4) -> str:
    """A d3 number format giving ``digits`` significant digits at the scale of ``values``.

    Fixed decimals for curves whose largest magnitude lies between 1e-3 and 10**digits (so
    that a value near zero on a curve reaching 36.7 reads ``0.01``, not ``0.0123456``),
    rounded integers up to 1e6 (``30,650``), exponent notation otherwise. Never plotly's SI
    suffixes (``217.6M``).
    """
    a = np.asarray(values, dtype=float)
    a = a[np.isfinite(a)]
    big = float(np.max(np.abs(a))) if a.size else 0.0
    if big == 0.0:
        return ".1f"
    if 1e-3 <= big < 10**digits:
        decimals = max(0, digits - 1 - int(math.floor(math.log10(big))))
        return f",.{decimals}f"
    if 10**digits <= big < 1e6:  # 30646.9 -> "30,650": 4 significant digits, no exponent
        return f",.{digits}r"
    return f".{digits - 1}e"
