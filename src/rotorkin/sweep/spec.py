"""Sweep specifications: ``--vary KEY=START:STOP:N`` / ``KEY=v1,v2,...`` -> validated SI values.

Every value is validated through the config schema (units, types, choices), so a
sweep refuses exactly what ``rotorkin run --set KEY=VALUE`` refuses, with the
same one-line messages. Dimensional keys need a unit on every value
(``20deg:65deg:46``, ``30deg,45deg``); dimensionless keys take bare numbers,
choice keys (``drive.driver``, ``drive.follower``, ...) their names.
"""

from __future__ import annotations

import copy
import tomllib
import typing
from dataclasses import dataclass, replace

import numpy as np

from rotorkin import drives
from rotorkin.core.errors import ConfigError, shown
from rotorkin.core.schema import annotation_kind
from rotorkin.core.units import DISPLAY_UNITS, parse_quantity
from rotorkin.io.config import validate_config

__all__ = ["Vary", "Field", "DISPLAY_UNITS", "parse_vary", "parse_item", "field_of",
           "display", "bounds_of"]  # fmt: skip

#: Most values of one ``--vary`` range (``N``); the whole grid is capped by
#: :data:`rotorkin.sweep.MAX_DESIGNS` and the result's memory by ``MAX_RESULT_BYTES``.
MAX_VALUES = 1_000_000


@dataclass(frozen=True)
class Field:
    """What a config key holds: ``kind`` is a quantity kind (``"angle"`` ...),
    ``"float"``, ``"int"``, ``"choice"`` (with ``choices``) or ``"other"`` (not sweepable)."""

    key: str
    kind: str
    choices: tuple = ()
    constrained: bool = False

    @property
    def dimensional(self) -> bool:
        return self.kind in DISPLAY_UNITS

    @property
    def unit(self) -> str:
        """Unit of the coordinate in a sweep result ("" if dimensionless)."""
        return DISPLAY_UNITS[self.kind][0] if self.dimensional else ""

    @property
    def factor(self) -> float:
        """SI value x factor = value in :attr:`unit`."""
        return DISPLAY_UNITS[self.kind][1] if self.dimensional else 1.0


@dataclass(frozen=True)
class Vary:
    """One swept key: its values (SI floats, ints or choice names) as given on the command line."""

    key: str
    text: str
    values: tuple
    field: Field

    def __len__(self) -> int:
        return len(self.values)

    def display_values(self) -> np.ndarray:
        """Values in the unit people read (deg, mm, ...; 12 significant digits), or the names."""
        if self.field.kind == "choice":
            return np.array(self.values, dtype=object)
        if self.field.kind == "int":
            return np.asarray(self.values, dtype=np.int32)
        # rounded to 12 significant digits: "105deg" reads back as 105.0, not 104.99999999999999
        scaled = np.asarray(self.values, dtype=float) * self.field.factor
        return np.array([float(f"{v:.12g}") for v in scaled])

    def array(self) -> np.ndarray:
        """Values as an array for the kernels (SI floats, ints, or object strings)."""
        if self.field.kind == "choice":
            return np.array(self.values, dtype=object)
        if self.field.kind == "int":
            return np.asarray(self.values, dtype=np.int64)
        return np.asarray(self.values, dtype=float)


def display(field: Field, value) -> str:
    """A value of ``field`` as people read it: ``"65.53 deg"``, ``"0.5"``, ``"crank"``."""
    if field.kind == "choice":
        return str(value)
    if field.dimensional:
        return f"{float(value) * field.factor:.6g} {field.unit}"
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def _model_field(drive_type: str, key: str, machine: str | None):
    """The pydantic field of ``key`` (``section.name``) in the drive's config model, or None."""
    section, _, name = key.partition(".")
    model = drives.config_model(drive_type, machine)
    sfield = model.model_fields.get(section)
    if sfield is None or not name or "." in name:
        return None
    fields = getattr(sfield.annotation, "model_fields", {})
    return next((f for n, f in fields.items() if name in (n, f.alias) and n != "type"), None)


def bounds_of(drive_type: str, key: str, machine: str | None = None) -> tuple:
    """The schema's bounds of a numeric key: ``(lo, hi, lo_open, hi_open)``, SI.

    ``-inf`` / ``inf`` where the schema sets none; ``lo_open`` is True for a strict
    bound (``gt``), False for an inclusive one (``ge``).
    """
    field = _model_field(drive_type, key, machine)
    lo, hi, lo_open, hi_open = -np.inf, np.inf, False, False
    for m in field.metadata if field is not None else ():
        for attr, low, strict in (("ge", True, False), ("gt", True, True),
                                  ("le", False, False), ("lt", False, True)):  # fmt: skip
            v = getattr(m, attr, None)
            if v is None:
                continue
            if low:
                lo, lo_open = float(v), strict
            else:
                hi, hi_open = float(v), strict
    return lo, hi, lo_open, hi_open


def field_of(drive_type: str, key: str, machine: str | None = None) -> Field | None:
    """The :class:`Field` of ``key`` (``section.name``) for a drive type, None if unknown.

    ``machine``: the ``machine.type`` the drive carries (default: its own).
    """
    field = _model_field(drive_type, key, machine)
    if field is None:
        return None
    kind = annotation_kind(field.annotation) or next(
        (getattr(getattr(m, "func", None), "kind", None) for m in field.metadata
         if getattr(getattr(m, "func", None), "kind", None)), None)  # fmt: skip
    bounded = any(type(m).__name__ in ("Ge", "Gt", "Le", "Lt", "Interval")
                  for m in field.metadata)  # fmt: skip
    if kind:
        return Field(key, kind, (), bounded)
    ann = field.annotation
    if typing.get_origin(ann) is typing.Literal:
        return Field(key, "choice", tuple(typing.get_args(ann)))
    if ann is int:
        return Field(key, "int", (), bounded)
    if ann is float:
        return Field(key, "float", (), bounded)
    return Field(key, "other")


def _check_key(base_raw: dict, key: str, option: str, value: str | None = None
               ) -> tuple[str, Field]:  # fmt: skip
    """The drive type and :class:`Field` of a swept key; one-line errors.

    ``value`` (the first value as given, e.g. ``"a"`` of ``drive.type=a,b``) is
    what the config schema is asked about when the key is not sweepable, so
    that its message shows the value written.
    """
    drive_type = (base_raw.get("drive") or {}).get("type")
    if drive_type not in drives.REGISTRY:
        validate_config(base_raw)  # raises the config's own message
    section_raw = base_raw.get("machine")
    machine = section_raw.get("type") if isinstance(section_raw, dict) else None
    if machine is not None:
        validate_config(base_raw)  # a machine the drive cannot carry: the config's own message
    field = field_of(drive_type, key, machine)
    if field is None:
        section, _, name = key.partition(".")
        if not name:
            raise ConfigError(f"{option} {key!r} is not admissible: the key must be section.key, "
                              "e.g. drive.plate_tilt")  # fmt: skip
        if key == "drive.type" and (value in drives.REGISTRY or not value):
            raise ConfigError(f"{option} drive.type = {value or ''!r} is not admissible: a "
                              f"sweep varies the keys of one drive type (here {drive_type!r}); "
                              "run one sweep per drive type")  # fmt: skip
        probe = copy.deepcopy(base_raw)
        probe.setdefault(section, {})
        if isinstance(probe[section], dict):
            probe[section][name] = 0 if value is None else _as_written(value)
        try:
            validate_config(probe)
        except ConfigError as exc:
            raise ConfigError(f"{option}: {exc}") from None
        raise ConfigError(f"{option}: unknown key {key}")
    if field.kind == "other" or key in ("drive.type", "machine.type"):
        raise ConfigError(
            f"{option} {key} is not admissible: only single numbers, quantities and choices can "
            "be swept (not lists or names)"
        )
    return drive_type, field


def _as_written(text: str):
    """A value as TOML reads it (``2`` -> 2, ``true`` -> True), else the string itself."""
    try:
        return tomllib.loads(f"v = {text.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        return text.strip()


def _raw_value(field: Field, text: str):
    """A value as written in a TOML config: strings for quantities and choices, numbers else."""
    text = text.strip()
    if field.dimensional or field.kind == "choice":
        return text
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def _validated(base_raw: dict, field: Field, text: str, option: str):
    """The SI value of ``text`` for ``field``, with the config schema's messages.

    Quantities are parsed by :func:`rotorkin.core.units.parse_quantity` (the
    schema's own parser), choices and numbers checked as the schema does; a key
    with bounds in the schema (``run.points``) goes through the whole schema.
    """
    key = field.key
    if field.constrained:
        section, _, name = key.partition(".")
        raw = copy.deepcopy(base_raw)
        raw.setdefault(section, {})[name] = _raw_value(field, text)
        try:
            return validate_config(raw)[section][name]
        except ConfigError as exc:
            raise ConfigError(f"{option}: {exc}") from None
    text = text.strip()
    if field.dimensional:
        number, reason = parse_quantity(text, field.kind)
        if reason:
            raise ConfigError(f"{option}: {key} = {shown(text)} {reason}")
        return number
    if field.kind == "choice":
        if text not in field.choices:
            raise ConfigError(f"{option}: {key} = {shown(text)} is not admissible: choose one of "
                              + ", ".join(repr(c) for c in field.choices))  # fmt: skip
        return text
    value = _raw_value(field, text)
    if field.kind == "int":
        if isinstance(value, bool) or not isinstance(value, int):
            raise ConfigError(
                f"{option}: {key} = {shown(text)} is not admissible: needs an integer"
            )
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value):
        raise ConfigError(
            f"{option}: {key} = {shown(text)} is not admissible: needs a finite number"
        )
    return float(value)


def parse_item(item: str, option: str = "--vary") -> tuple[str, str]:
    """Split ``"KEY=SPEC"``; one-line :class:`ConfigError` when there is no ``=``."""
    if "=" not in item:
        raise ConfigError(
            f"{option} {shown(item)} is not admissible: write it as KEY=START:STOP:N or "
            "KEY=v1,v2,..."
        )
    key, _, spec = item.partition("=")
    return key.strip(), spec.strip()


def _validated_list(base_raw: dict, drive_type: str, field: Field, items: list, option: str
                    ) -> tuple:  # fmt: skip
    """The SI values of a list of texts for ``field``, as :func:`_validated` of each.

    A key with bounds is checked against them for every value at once; the whole
    schema then sees the first value out of bounds (its message), else the smallest
    and the largest (what a range ``START:STOP:N`` checks), so a list of a million
    values costs a million number parses, not a million config validations.
    """
    if not field.constrained:
        return tuple(_validated(base_raw, field, s, option) for s in items)
    free = replace(field, constrained=False)
    values = []
    for text in items:
        try:
            values.append(_validated(base_raw, free, text, option))
        except ConfigError:
            _validated(base_raw, field, text, option)  # the schema's own message
            raise
    number = np.asarray(values, dtype=float)
    section_raw = base_raw.get("machine")
    machine = section_raw.get("type") if isinstance(section_raw, dict) else None
    lo, hi, lo_open, hi_open = bounds_of(drive_type, field.key, machine)
    outside = ((number <= lo) if lo_open else (number < lo)) | (
        (number >= hi) if hi_open else (number > hi))  # fmt: skip
    picks = [int(np.argmax(outside))] if outside.any() else []
    picks += [int(np.argmin(number)), int(np.argmax(number))]
    for i in dict.fromkeys(picks):
        _validated(base_raw, field, items[i], option)
    return tuple(values)


def parse_vary(item: str, base_raw: dict) -> Vary:
    """Parse one ``--vary`` item against a base config.

    Parameters
    ----------
    item : str
        ``KEY=START:STOP:N`` (N evenly spaced values, both ends included) or
        ``KEY=v1,v2,...``; e.g. ``"drive.plate_tilt=20deg:65deg:46"``,
        ``"drive.driver=crank,guide"``, ``"drive.lambda=0.3,0.5,0.7"``.
    base_raw : dict
        The base config as written (it fixes the drive type and so the keys).

    Returns
    -------
    Vary

    Raises
    ------
    ConfigError
        One line naming the option, the key and what is admissible: unknown key,
        empty range or list, missing unit, bad number or choice.
    """
    key, spec = parse_item(item)
    option = f"--vary {key}={shown(spec)[1:-1]}"
    first = spec.split(",")[0].split(":")[0].strip()
    drive_type, field = _check_key(base_raw, key, "--vary", first or None)
    if not spec:
        raise ConfigError(f"{option} is not admissible: empty list of values")
    if ":" in spec:
        parts = spec.split(":")
        if len(parts) != 3 or not all(p.strip() for p in parts):
            raise ConfigError(f"{option} is not admissible: a range is START:STOP:N")
        try:
            count = int(parts[2])
        except ValueError:
            raise ConfigError(f"{option} is not admissible: N = {parts[2]!r} must be an integer "
                              "count of values") from None  # fmt: skip
        if count < 1:
            raise ConfigError(f"{option} is not admissible: empty range (N = {count}; N >= 1)")
        if count > MAX_VALUES:
            raise ConfigError(f"{option} is not admissible: N = {count}; N <= {MAX_VALUES:.0e} "
                              "(and at most 2e+07 designs per sweep)")  # fmt: skip
        if field.kind == "choice":
            raise ConfigError(f"{option} is not admissible: {key} takes one of "
                              f"{', '.join(field.choices)}; list them: {key}=a,b")  # fmt: skip
        start = _validated(base_raw, field, parts[0], option)
        stop = _validated(base_raw, field, parts[1], option)
        if count == 1 and start != stop:
            raise ConfigError(f"{option} is not admissible: N = 1 needs START = STOP")
        values = np.linspace(float(start), float(stop), count)
        if field.kind == "int":
            if not np.allclose(values, np.round(values), rtol=0.0, atol=1e-9):
                raise ConfigError(f"{option} is not admissible: {key} is an integer and the "
                                  f"range gives {values.tolist()}")  # fmt: skip
            values = tuple(int(v) for v in np.round(values))
        else:
            values = tuple(float(v) for v in values)
    else:
        items = [s.strip() for s in spec.split(",")]
        if not all(items):
            raise ConfigError(f"{option} is not admissible: an empty value in the list")
        values = _validated_list(base_raw, drive_type, field, items, option)
        if field.kind not in ("choice", "int"):
            values = tuple(float(v) for v in values)
    if len(set(values)) != len(values):
        raise ConfigError(f"{option} is not admissible: a value is repeated")
    return Vary(key, spec, values, field)
