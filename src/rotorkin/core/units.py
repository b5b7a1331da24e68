"""Units at the boundary: strings such as ``"45 deg"`` or ``"80 mm"`` -> SI floats.

This is the one place where degrees, millimetres and rpm become radians,
metres and rad/s. Everything inside rotorkin is SI.
"""

from __future__ import annotations

import functools
import math

from rotorkin.core.errors import ConfigError

__all__ = ["KINDS", "to_si", "parse_quantity", "describe_kind", "metric_units"]

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
}


@functools.lru_cache(maxsize=1)
def _registry():
    import pint

    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


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


def parse_quantity(value, kind: str) -> tuple[float, str]:
    """``(number_in_SI, "")`` or ``(nan, reason)`` where the reason completes
    the sentence ``"<key> = <value> <reason>"``."""
    si, _ = KINDS[kind]
    bad = float("nan")
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        return bad, f"is not admissible: needs {describe_kind(kind)}"
    if isinstance(value, (int, float)):
        return bad, (
            f'has no unit: write it as a string with a unit, e.g. "{value} {_suggest_unit(kind)}"'
        )
    import pint

    ureg = _registry()
    try:
        quantity = ureg.Quantity(value.strip())
    except (pint.errors.PintError, ValueError, TypeError, AttributeError, SyntaxError):
        return bad, f"cannot be read: needs {describe_kind(kind)}"
    if not isinstance(quantity, ureg.Quantity) or quantity.unitless:
        return bad, f"has no unit: needs {describe_kind(kind)}"
    try:
        number = float(quantity.to(si).magnitude)
    except pint.errors.DimensionalityError:
        return bad, f"has the wrong unit: needs {describe_kind(kind)}"
    if not math.isfinite(number):
        return bad, "is not admissible: needs a finite value"
    return number, ""


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
    }[kind]


#: Suffix of a summary key or column name -> its unit (longer suffixes first).
_UNITS = (
    ("_rad_per_s3", "rad/s^3"), ("_rad_per_s2", "rad/s^2"), ("_rad_per_s", "rad/s"),
    ("_m_per_s3", "m/s^3"), ("_m_per_s2", "m/s^2"), ("_m_per_s", "m/s"), ("_rpm", "rpm"),
    ("_mm_per_rad3", "mm/rad^3"), ("_mm_per_rad2", "mm/rad^2"), ("_mm_per_rad", "mm/rad"),
    ("_per_rad2", "1/rad^2"), ("_per_rad", "1/rad"), ("_per_m", "1/m"), ("_deg", "deg"),
    ("_mm", "mm"), ("_cm3_per_rev", "cm^3/rev"), ("_cm3_per_rad", "cm^3/rad"), ("_cm3", "cm^3"),
    ("_cm2", "cm^2"), ("_Nm", "N*m"), ("_J_per_rev", "J/rev"), ("_J", "J"), ("_bar", "bar"),
    ("_kW", "kW"), ("_W", "W"), ("_l_per_min", "l/min"), ("_percent", "%"), ("_rad", "rad"),
    ("_kgm2", "kg*m^2"), ("_K", "K"),
)  # fmt: skip


def metric_units(name: str) -> str:
    """Unit of a summary key from its suffix ("1" when dimensionless)."""
    return next((u for suffix, u in _UNITS if name.endswith(suffix)), "1")
