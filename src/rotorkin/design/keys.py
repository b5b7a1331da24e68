"""The config keys a design command varies: which are admissible, their bounds, their values.

A design command (``solve``, ``optimize``) varies *continuous* keys: single
numbers and quantities of the drive's config schema (``machine.casing_radius``,
``drive.plate_tilt``, ``drive.lambda``), not integers, choices or lists. Their
admissible range is the schema field's ``ge``/``gt``/``le``/``lt`` bounds (SI);
what the drive itself refuses (a cross-key rule such as ``hub_radius <
casing_radius``) is found by evaluating designs (reason codes of
:func:`rotorkin.sweep.evaluate_designs`). Values are SI inside and written in the
unit people read (``mm``, ``deg``, ``rpm``: :data:`rotorkin.sweep.spec.DISPLAY_UNITS`)
at the edges.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

from rotorkin import drives
from rotorkin.core.errors import ConfigError, ParameterError, shown
from rotorkin.core.units import parse_quantity
from rotorkin.io.config import validate_config
from rotorkin.sweep.engine import kernel_of, optional_metrics
from rotorkin.sweep.spec import Field, bounds_of, field_of

__all__ = [
    "KeyInfo",
    "continuous_keys",
    "key_info",
    "numeric_metrics",
    "check_metric",
    "parse_key_value",
    "value_text",
    "with_values",
]


@dataclass(frozen=True)
class KeyInfo:
    """A continuous config key with its schema bounds.

    Attributes
    ----------
    key : str
        ``section.name``.
    field : rotorkin.sweep.spec.Field
        Its kind, display unit and factor from SI.
    low, high : float or None
        The schema's bounds [SI]; None where the schema has none.
    low_open, high_open : bool
        The bound itself is excluded (``gt``/``lt``).
    current : float or None
        The value of the base config [SI] (None when the key is unset, e.g. a
        vane angle that defaults to the drive's own).
    """

    key: str
    field: Field
    low: float | None
    high: float | None
    low_open: bool = False
    high_open: bool = False
    current: float | None = None

    @property
    def unit(self) -> str:
        """Unit people read (``"mm"``, ``"deg"``; ``""`` when dimensionless)."""
        return self.field.unit

    @property
    def factor(self) -> float:
        """SI value x factor = value in :attr:`unit`."""
        return self.field.factor

    def show(self, value: float) -> str:
        """``value`` [SI] as people read it: ``"35.51 mm"``, ``"0.5"`` (6 significant digits)."""
        text = f"{value * self.factor:.6g}"
        return f"{text} {self.unit}" if self.unit else text

    def admissible(self) -> str:
        """The schema's range as a sentence: ``"1 mm <= casing_radius <= 10000 mm"``."""
        name = self.key.partition(".")[2]
        low = "" if self.low is None else f"{self.show(self.low)} {'<' if self.low_open else '<='} "
        high = "" if self.high is None else (f" {'<' if self.high_open else '<='} "
                                             f"{self.show(self.high)}")  # fmt: skip
        return f"{low}{name}{high}" if (low or high) else f"{name} (no bounds in the schema)"

    def inside(self, value: float) -> bool:
        """Whether ``value`` [SI] lies within the schema's bounds."""
        if not math.isfinite(value):
            return False
        if self.low is not None and (value < self.low or (self.low_open and value == self.low)):
            return False
        return not (self.high is not None
                    and (value > self.high or (self.high_open and value == self.high)))  # fmt: skip


def _machine(raw: dict) -> str | None:
    section = raw.get("machine")
    return section.get("type") if isinstance(section, dict) else None


def _continuous(field: Field | None) -> bool:
    return field is not None and (field.dimensional or field.kind == "float")


def continuous_keys(cfg: dict) -> list[str]:
    """Every continuous key of ``cfg``'s drive (and machine), in schema order.

    Parameters
    ----------
    cfg : dict
        A validated (or raw) config: its ``drive.type`` and ``machine.type`` fix the keys.
    """
    drive_type = cfg["drive"]["type"]
    machine = _machine(cfg)
    model = drives.config_model(drive_type, machine)
    out = []
    for section, sfield in model.model_fields.items():
        for name, f in getattr(sfield.annotation, "model_fields", {}).items():
            if name == "type":
                continue
            key = f"{section}.{f.alias or name}"
            if _continuous(field_of(drive_type, key, machine)):
                out.append(key)
    return out


def key_info(raw: dict, cfg: dict, key: str, option: str) -> KeyInfo:
    """Check that ``key`` is a continuous key of the config; its :class:`KeyInfo`.

    Parameters
    ----------
    raw, cfg : dict
        The base config as written and validated (SI).
    key : str
        ``section.name``.
    option : str
        The option that named it (``--for``, ``--vary``), for messages.

    Raises
    ------
    ConfigError
        One line naming the key and the admissible keys.
    """
    drive_type = cfg["drive"]["type"]
    machine = _machine(raw)
    field = field_of(drive_type, key, machine) if isinstance(key, str) else None
    if not _continuous(field):
        keys = continuous_keys(cfg)
        kind = {"int": "an integer", "choice": "a choice"}.get(getattr(field, "kind", ""), "a list")
        why = "unknown key" if field is None else f"{kind} key cannot be varied continuously"
        raise ConfigError(f"{option} {shown(key)} is not admissible ({why}): one of the number "
                          f"keys of drive.type = {drive_type}: {', '.join(keys)}")  # fmt: skip
    low, high, low_open, high_open = bounds_of(drive_type, key, machine)
    low = low if np.isfinite(low) else None
    high = high if np.isfinite(high) else None
    section, _, name = key.partition(".")
    current = (cfg.get(section) or {}).get(name)
    if isinstance(current, list):
        raise ConfigError(f"{option} {key} is not admissible here: the config gives a list "
                          f"({len(current)} values); set one value first: --set "
                          f"{key}=VALUE")  # fmt: skip
    current = None if current is None else float(current)
    return KeyInfo(key, field, low, high, low_open, high_open, current)


def parse_key_value(info: KeyInfo, text: str, option: str) -> float:
    """A value of ``info``'s key as written (``"80 mm"``, ``"0.5"``) -> SI, within the schema.

    Raises
    ------
    ConfigError
        One line: missing or wrong unit, not a number, outside the schema's range.
    """
    text = str(text).strip()
    if info.field.dimensional:
        value, reason = parse_quantity(text, info.field.kind)
        if reason:
            raise ConfigError(f"{option}: {info.key} = {shown(text)} {reason}")
    else:
        try:
            value = float(text)
        except ValueError:
            raise ConfigError(f"{option}: {info.key} = {shown(text)} is not admissible: needs a "
                              "number") from None  # fmt: skip
    if not info.inside(value):
        raise ConfigError(f"{option}: {info.key} = {shown(text)} is not admissible: "
                          f"{info.admissible()}")  # fmt: skip
    return float(value)


def value_text(info: KeyInfo, value: float):
    """``value`` [SI] as a config holds it: ``"35.512345678901 mm"`` or a bare float.

    The number is written with 17 significant digits in the display unit, so that
    reading it back gives ``value`` to a rounding of the unit conversion.
    """
    if not info.field.dimensional:
        return float(value)
    return f"{float(value) * info.factor:.17g} {info.unit}"


def with_values(raw: dict, infos, values) -> tuple[dict, dict]:
    """A copy of ``raw`` with each key set to its value [SI]; the copy and its validated config.

    Raises
    ------
    ConfigError
        The config's own message when the schema refuses the values.
    """
    out = copy.deepcopy(raw)
    for info, value in zip(infos, values, strict=True):
        section, _, name = info.key.partition(".")
        out.setdefault(section, {})[name] = value_text(info, value)
    return out, validate_config(out)


def numeric_metrics(cfg: dict) -> tuple[str, ...]:
    """Summary keys with a number (not a flag): the kernel's metrics and the study's summary."""
    kern = kernel_of(cfg["drive"]["type"], cfg)
    names = [*kern.metric_names(cfg), *optional_metrics(kern, cfg)]
    try:
        summary = drives.evaluate(cfg).summary
    except ParameterError:  # the base design is refused: the kernel's names are all there is
        summary = {}
    names += [k for k, v in summary.items() if isinstance(v, (int, float, np.number))]
    return tuple(n for n in dict.fromkeys(names) if not isinstance(summary.get(n), bool))


def check_metric(name: str, known: tuple[str, ...], what: str) -> str:
    """``name`` if it is a numeric metric; else one line (``what`` is not admissible ...)."""
    if name not in known:
        raise ConfigError(f"{what} is not admissible: the metric {shown(name)} is none of "
                          "the numeric summary keys and sweep metrics: "
                          + ", ".join(known))  # fmt: skip
    return name
