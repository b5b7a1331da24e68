"""Units at the boundary: strings such as ``"45 deg"`` or ``"80 mm"`` -> SI floats.

This is the one place where degrees, millimetres and rpm become radians,
metres and rad/s. Everything inside rotorkin is SI.
"""

from __future__ import annotations

import functools
import math
import re

from rotorkin.core.errors import ConfigError

__all__ = [
    "KINDS",
    "DISPLAY_UNITS",
    "to_si",
    "parse_quantity",
    "describe_kind",
    "metric_units",
    "display_value",
]

#: quantity kind -> (SI unit name for pint, example for messages, pint dimensionality)
KINDS = {
    "angle": ("rad", '"45 deg" or "0.8 rad"'),
    "length": ("m", '"80 mm" or "0.08 m"'),
    "torque": ("N*m", '"12 N*m"'),
    "speed": ("rad/s", '"3000 rpm" or "314 rad/s"'),
    "pressure": ("Pa", '"1 bar" or "101325 Pa"'),
    "inertia": ("kg*m**2", '"0.02 kg*m^2"'),
    "mass": ("kg", '"0.5 kg"'),
    "volume": ("m**3", '"2 cm^3"'),
    "energy": ("J", '"150 J"'),
    "temperature": ("K", '"600 K" or "25 degC"'),
    "modulus": ("Pa", '"2.2 GPa"'),
    "specific_energy": ("J/kg", '"44 MJ/kg"'),
}


@functools.lru_cache(maxsize=1)
def _registry():
    """pint's registry, its parsed definitions cached on disk by pint (``:auto:``, the
    user's cache folder: 0.1 s instead of 0.35 s to build); without a writable cache
    folder, built from the definitions each time. Only units outside :data:`_BASE` and
    :data:`_NAMES` need it."""
    import pint

    try:
        return pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=":auto:")
    except Exception:  # an unwritable or broken cache: build the registry afresh
        return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


#: The units written most, read without pint (whose import and registry cost ~0.3 s at
#: every start): pint's canonical name -> (factor to SI, offset to SI, dimension as the
#: powers of (m, kg, s, K)). Angles are dimensionless, as in pint. Every entry is tested
#: equal to pint's conversion.
_BASE = {
    "radian": (1.0, 0.0, (0, 0, 0, 0)),
    "degree": (math.pi / 180.0, 0.0, (0, 0, 0, 0)),
    "turn": (2.0 * math.pi, 0.0, (0, 0, 0, 0)),
    "arcminute": (math.pi / 10800.0, 0.0, (0, 0, 0, 0)),
    "revolutions_per_minute": (2.0 * math.pi / 60.0, 0.0, (0, 0, -1, 0)),
    "revolutions_per_second": (2.0 * math.pi, 0.0, (0, 0, -1, 0)),
    "hertz": (1.0, 0.0, (0, 0, -1, 0)),
    "meter": (1.0, 0.0, (1, 0, 0, 0)),
    "inch": (0.0254, 0.0, (1, 0, 0, 0)),
    "foot": (0.3048, 0.0, (1, 0, 0, 0)),
    "second": (1.0, 0.0, (0, 0, 1, 0)),
    "minute": (60.0, 0.0, (0, 0, 1, 0)),
    "hour": (3600.0, 0.0, (0, 0, 1, 0)),
    "gram": (1e-3, 0.0, (0, 1, 0, 0)),
    "metric_ton": (1e3, 0.0, (0, 1, 0, 0)),
    "pound": (0.45359237, 0.0, (0, 1, 0, 0)),
    "newton": (1.0, 0.0, (1, 1, -2, 0)),
    "pascal": (1.0, 0.0, (-1, 1, -2, 0)),
    "bar": (1e5, 0.0, (-1, 1, -2, 0)),
    "standard_atmosphere": (101325.0, 0.0, (-1, 1, -2, 0)),
    "liter": (1e-3, 0.0, (3, 0, 0, 0)),
    "cubic_centimeter": (1e-6, 0.0, (3, 0, 0, 0)),
    "joule": (1.0, 0.0, (2, 1, -2, 0)),
    "watt": (1.0, 0.0, (2, 1, -3, 0)),
    "kelvin": (1.0, 0.0, (0, 0, 0, 1)),
    "degree_Celsius": (1.0, 273.15, (0, 0, 0, 1)),
    "degree_Fahrenheit": (5.0 / 9.0, 459.67 * 5.0 / 9.0, (0, 0, 0, 1)),
}
_PREFIX = {"": 1.0, "nano": 1e-9, "micro": 1e-6, "milli": 1e-3, "centi": 1e-2, "deci": 1e-1,
           "hecto": 1e2, "kilo": 1e3, "mega": 1e6, "giga": 1e9}  # fmt: skip
#: name as written -> pint's reading of it ``(prefix, canonical name)`` (tested against pint).
_NAMES = {
    **dict.fromkeys(("rad", "radian", "radians"), ("", "radian")),
    **dict.fromkeys(("deg", "degree", "degrees"), ("", "degree")),
    **dict.fromkeys(("turn", "turns", "revolution", "revolutions"), ("", "turn")),
    **dict.fromkeys(("arcmin", "arcminute"), ("", "arcminute")),
    "rpm": ("", "revolutions_per_minute"), "rps": ("", "revolutions_per_second"),
    "Hz": ("", "hertz"), "kHz": ("kilo", "hertz"),
    **dict.fromkeys(("m", "meter", "metre", "meters", "metres"), ("", "meter")),
    "mm": ("milli", "meter"), "cm": ("centi", "meter"), "dm": ("deci", "meter"),
    "km": ("kilo", "meter"), "um": ("micro", "meter"), "\u00b5m": ("micro", "meter"),
    "nm": ("nano", "meter"), "in": ("", "inch"), "inch": ("", "inch"), "ft": ("", "foot"),
    **dict.fromkeys(("s", "sec", "second", "seconds"), ("", "second")),
    "ms": ("milli", "second"), "us": ("micro", "second"),
    **dict.fromkeys(("min", "minute", "minutes"), ("", "minute")),
    **dict.fromkeys(("h", "hr", "hour", "hours"), ("", "hour")),
    "g": ("", "gram"), "kg": ("kilo", "gram"), "mg": ("milli", "gram"),
    "t": ("", "metric_ton"), "tonne": ("", "metric_ton"), "lb": ("", "pound"),
    "N": ("", "newton"), "kN": ("kilo", "newton"), "mN": ("milli", "newton"),
    "Pa": ("", "pascal"), "hPa": ("hecto", "pascal"), "kPa": ("kilo", "pascal"),
    "MPa": ("mega", "pascal"), "GPa": ("giga", "pascal"),
    "bar": ("", "bar"), "mbar": ("milli", "bar"), "atm": ("", "standard_atmosphere"),
    **dict.fromkeys(("L", "l", "liter", "litre"), ("", "liter")),
    "mL": ("milli", "liter"), "ml": ("milli", "liter"), "cc": ("", "cubic_centimeter"),
    "J": ("", "joule"), "kJ": ("kilo", "joule"), "MJ": ("mega", "joule"),
    "GJ": ("giga", "joule"), "mJ": ("milli", "joule"),
    "W": ("", "watt"), "kW": ("kilo", "watt"), "MW": ("mega", "watt"),
    "K": ("", "kelvin"), "kelvin": ("", "kelvin"),
    **dict.fromkeys(("degC", "\u00b0C", "celsius"), ("", "degree_Celsius")),
    **dict.fromkeys(("degF", "\u00b0F", "fahrenheit"), ("", "degree_Fahrenheit")),
}  # fmt: skip
#: Dimension of each kind's SI unit, powers of (m, kg, s, K); a speed is compared as 1/s.
_KIND_DIMENSION = {
    "angle": (0, 0, 0, 0), "length": (1, 0, 0, 0), "torque": (2, 1, -2, 0),
    "speed": (0, 0, -1, 0), "pressure": (-1, 1, -2, 0), "inertia": (2, 1, 0, 0),
    "mass": (0, 1, 0, 0), "volume": (3, 0, 0, 0), "energy": (2, 1, -2, 0),
    "temperature": (0, 0, 0, 1), "modulus": (-1, 1, -2, 0), "specific_energy": (2, 0, -2, 0),
}  # fmt: skip


def _canonical(name: str):
    """``(prefix, canonical name, suffix)`` of a unit name as pint reads it, or ``()``."""
    known = _NAMES.get(name)
    if known is not None:
        return (known[0], known[1], "")
    try:
        found = _registry().parse_unit_name(name)
    except Exception:  # pint raises several kinds for a name it does not know
        return ()
    return found[0] if found else ()


def describe_kind(kind: str) -> str:
    """A short phrase for messages: ``'an angle, e.g. "45 deg" or "0.8 rad"'``."""
    article = "an" if kind[0] in "aeiou" else "a"
    return f"{article} {kind} with its unit, e.g. {KINDS[kind][1]}"


def to_si(key: str, value, kind: str) -> float:
    """Parse a dimensional config value to a float in SI units.

    Parameters
    ----------
    key : str
        Config key, for messages (``"drive.plate_tilt"``).
    value : str
        The value as written, a string with a unit (``"45 deg"``).
    kind : str
        One of :data:`KINDS`.

    Returns
    -------
    float
        The value in rad, m, N*m or rad/s.

    Raises
    ------
    ConfigError
        When the value is a bare number (rotorkin never guesses a unit), is not
        a string, does not parse, or has the wrong dimension.
    """
    number, reason = parse_quantity(value, kind)
    if reason:
        raise ConfigError(f"{key} = {value!r} {reason}")
    return number


#: Longest value string read [characters]; longer ones are refused before any parsing.
MAX_TEXT = 64
#: Largest exponent of a unit factor (``m^3``).
MAX_POWER = 4
_NUMBER = re.compile(r"([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d{1,3})?)\s*(.*)", re.S)
_TOKEN = re.compile(r"\s*(?:(?P<name>[A-Za-z_\u00b5\u00b0][A-Za-z_0-9\u00b5\u00b0]*)"
                    r"|(?P<op>\*\*|[*/^\u00b7])|(?P<int>[+-]?\d+)|(?P<bad>\S))")  # fmt: skip
#: Units that say "angle" in a speed (rad/s, deg/s, rpm); a speed without one (Hz, 1/min)
#: counts revolutions.
_ANGULAR = {"radian", "degree", "turn", "arcminute", "arcsecond", "gradian",
            "revolutions_per_minute", "revolutions_per_second"}  # fmt: skip


def _unit_factors(text: str):
    """``[(name, power)]`` of a unit expression, or a reason string.

    The grammar is a product of unit names from pint's registry with small integer
    powers: ``name[^n]`` joined by ``*``, ``/``, ``·`` or a space (``N*m``,
    ``kg*m^2``, ``1/min``, ``rad/s``, ``cm^3``). Nothing is evaluated: no
    parentheses, no arithmetic, no power beyond :data:`MAX_POWER`, no name twice.
    """
    tokens = []
    for m in _TOKEN.finditer(text):
        if m.group("bad"):
            return f"has a character a unit cannot have: {m.group('bad')!r}"
        tokens.append((m.lastgroup, m.group(m.lastgroup)))
    factors, sign, i, seen = [], 1, 0, set()
    if tokens[:2] == [("int", "1"), ("op", "/")]:  # 1/min
        i, sign = 2, -1
    expect_factor = True
    while i < len(tokens):
        kind, tok = tokens[i]
        if kind == "op" and tok in ("*", "\u00b7", "/") and not expect_factor:
            sign = -1 if tok == "/" else 1
            expect_factor, i = True, i + 1
            continue
        if kind != "name":
            return "cannot be read as a number times a unit"
        canonical = _canonical(tok)
        if not canonical:
            return f"has an unknown unit {tok!r}"
        if canonical in seen:
            return f"names the unit {tok!r} twice"
        seen.add(canonical)
        power = 1
        if i + 1 < len(tokens) and tokens[i + 1][1] in ("^", "**"):
            if i + 2 >= len(tokens) or tokens[i + 2][0] != "int":
                return "cannot be read as a number times a unit"
            power = int(tokens[i + 2][1])
            if not 1 <= abs(power) <= MAX_POWER:
                return f"has a unit power {power} beyond +-{MAX_POWER}"
            i += 2
        factors.append((tok, canonical, sign * power))
        sign, expect_factor, i = 1, False, i + 1
    if expect_factor:
        return "cannot be read as a number times a unit"
    return factors


def parse_quantity(value, kind: str) -> tuple[float, str]:
    """``(number_in_SI, "")`` or ``(nan, reason)`` where the reason completes
    the sentence ``"<key> = <value> <reason>"``.

    A quantity is a decimal number followed by a unit expression (see
    :func:`_unit_factors`); it is read without evaluating anything, so no input
    can make it slow. A speed in a unit without an angle (``"50 Hz"``,
    ``"3000 1/min"``) counts revolutions: 50 Hz = 3000 rpm. A temperature must be
    above absolute zero.
    """
    si, _ = KINDS[kind]
    bad = float("nan")
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        return bad, f"is not admissible: needs {describe_kind(kind)}"
    if isinstance(value, (int, float)):
        return bad, (
            f'has no unit: write it as a string with a unit, e.g. "{value} {_suggest_unit(kind)}"'
        )
    text = value.strip()
    if len(text) > MAX_TEXT:
        return bad, f"is not admissible: longer than {MAX_TEXT} characters"
    m = _NUMBER.fullmatch(text)
    if m is None:
        return bad, f"has no number: needs {describe_kind(kind)}"
    number_text, unit_text = m.groups()
    if not unit_text.strip():
        return bad, f"has no unit: needs {describe_kind(kind)}"
    number = float(number_text)
    if not math.isfinite(number):
        return bad, "is not admissible: needs a finite value"
    how = _conversion(unit_text, kind)
    if isinstance(how, str):
        return bad, f"{how}: needs {describe_kind(kind)}"
    scale, offset = how
    converted = number * scale + offset
    if not math.isfinite(converted):
        return bad, "is not admissible: needs a finite value"
    if kind == "temperature" and converted <= 0.0:
        return bad, "is not admissible: a temperature above absolute zero (0 K)"
    return converted, ""


@functools.lru_cache(maxsize=512)
def _conversion(unit_text: str, kind: str):
    """``(scale, offset)`` with ``SI = number * scale + offset`` for a unit expression, or why not.

    Read once per unit text and quantity kind (a list of a million values in the same
    unit costs one pint conversion).
    """
    factors = _unit_factors(unit_text)
    if isinstance(factors, str):
        return factors
    how = _table_conversion(factors, kind)
    if how is None:
        how = _pint_conversion(factors, kind)
    if isinstance(how, str):
        return how
    scale, zero = how
    angular = any(canon[1] in _ANGULAR for _, canon, _ in factors)
    if kind == "speed" and not angular:
        scale *= 2.0 * math.pi  # cycles per time (Hz, 1/min): revolutions
    if kind == "angle" and not angular:
        return "has the wrong unit"
    return scale, zero


def _table_conversion(factors, kind: str):
    """:func:`_conversion`'s ``(scale, offset)`` to SI from :data:`_BASE`, "has the wrong
    unit", or None where a unit is not in the table (or an offset unit is not alone)."""
    scale, dims, zero = 1.0, [0, 0, 0, 0], 0.0
    for _, (prefix, name, suffix), power in factors:
        base = _BASE.get(name)
        if base is None or suffix or prefix not in _PREFIX:
            return None
        factor, offset, dim = base
        if offset and (len(factors) > 1 or power != 1 or prefix):
            return None  # degC^2, degC/s: pint's rules for offset units
        scale *= (_PREFIX[prefix] * factor) ** power
        zero = offset
        dims = [d + power * e for d, e in zip(dims, dim, strict=True)]
    if tuple(dims) != _KIND_DIMENSION[kind]:
        return "has the wrong unit"
    return scale, zero


def _pint_conversion(factors, kind: str):
    """:func:`_conversion`'s ``(scale, offset)`` to SI by pint, or "has the wrong unit"."""
    import pint

    si, _ = KINDS[kind]
    ureg = _registry()
    target = "1/s" if kind == "speed" else si
    try:
        unit = ureg.dimensionless
        for name, _, power in factors:
            unit = unit * ureg.Unit(name) ** power
        zero = float(ureg.Quantity(0.0, unit).to(target).magnitude)
        scale = float(ureg.Quantity(1.0, unit).to(target).magnitude) - zero
    except (pint.errors.DimensionalityError, pint.errors.OffsetUnitCalculusError):
        return "has the wrong unit"
    return scale, zero


def _suggest_unit(kind: str) -> str:
    return {
        "angle": "deg",
        "length": "mm",
        "torque": "N*m",
        "speed": "rpm",
        "pressure": "bar",
        "inertia": "kg*m^2",
        "mass": "kg",
        "volume": "cm^3",
        "energy": "J",
        "temperature": "K",
        "modulus": "GPa",
        "specific_energy": "MJ/kg",
    }[kind]


#: Suffix of a summary key or column name -> its unit (longer suffixes first).
_UNITS = (
    ("_rad_per_s3", "rad/s^3"), ("_rad_per_s2", "rad/s^2"), ("_rad_per_s", "rad/s"),
    ("_m_per_s3", "m/s^3"), ("_m_per_s2", "m/s^2"), ("_m_per_s", "m/s"), ("_rpm", "rpm"),
    ("_mm_per_rad3", "mm/rad^3"), ("_mm_per_rad2", "mm/rad^2"), ("_mm_per_rad", "mm/rad"),
    ("_per_rad2", "1/rad^2"), ("_per_rad", "1/rad"), ("_per_m", "1/m"), ("_deg", "deg"),
    ("_mm", "mm"), ("_cm3_per_rev", "cm^3/rev"), ("_cm3_per_rad", "cm^3/rad"), ("_cm3", "cm^3"),
    ("_cm2", "cm^2"), ("_mg", "mg"), ("_Nm", "N*m"), ("_J_per_rev", "J/rev"), ("_J", "J"),
    ("_bar", "bar"),
    ("_kW", "kW"), ("_W", "W"), ("_l_per_min", "l/min"), ("_percent", "%"), ("_rad", "rad"),
    ("_kgm2", "kg*m^2"), ("_K", "K"),
)  # fmt: skip


def metric_units(name: str) -> str:
    """Unit of a summary key from its suffix ("1" when dimensionless)."""
    return next((u for suffix, u in _UNITS if name.endswith(suffix)), "1")


#: quantity kind -> (unit shown in coordinates and messages, factor from SI)
DISPLAY_UNITS = {
    "angle": ("deg", 180.0 / math.pi),
    "length": ("mm", 1e3),
    "torque": ("N*m", 1.0),
    "speed": ("rpm", 30.0 / math.pi),
    "pressure": ("bar", 1e-5),
    "inertia": ("kg*m^2", 1.0),
    "mass": ("kg", 1.0),
    "volume": ("cm^3", 1e6),
    "energy": ("J", 1.0),
    "temperature": ("K", 1.0),
    "modulus": ("GPa", 1e-9),
}


def display_value(value: float, kind: str | None) -> str:
    """An SI value in the unit people read (``"99 deg"``, ``"80 mm"``); a plain number else.

    A value that is not a number (a text as written in the config) is shown as it is.
    """
    if isinstance(value, str) or not isinstance(value, (int, float)):
        return str(value)
    if kind in DISPLAY_UNITS:
        unit, factor = DISPLAY_UNITS[kind]
        return f"{float(value) * factor:.6g} {unit}"
    return f"{float(value):.6g}"
