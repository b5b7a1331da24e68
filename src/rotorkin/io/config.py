"""Config files: TOML in, a validated nested dict of SI values out.

A config has the sections ``[drive]`` (with ``type``), ``[machine]``,
``[loads]``, ``[cam]`` (cam geometry for checks and CAD; not for the guide
bar), ``[export]`` and ``[run]``, plus an optional top-level ``title``. Dimensional
values are strings with units (``"45 deg"``, ``"80 mm"``, ``"12 N*m"``),
converted to SI once, here; dimensionless keys take bare numbers. Unknown keys,
wrong types and missing units are refused with one line that names the key.

The schema is a pydantic model per drive (``DriveSpec.config_model``, built
from :mod:`rotorkin.core.schema`); their field descriptions are the glossary
(``rotorkin keys`` prints them).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from pydantic import BaseModel

from rotorkin import drives
from rotorkin.core.errors import ConfigError, shown
from rotorkin.core.schema import validate_model

__all__ = [
    "apply_sets",
    "example_names",
    "example_path",
    "glossary",
    "load_config",
    "parse_set",
    "read_toml",
    "validate_config",
]


# --- reading --------------------------------------------------------------------------------
def example_names() -> list[str]:
    """Names of the built-in examples (``rotorkin run --example NAME``)."""
    return sorted(_example_files())


def _example_files() -> dict[str, Path]:
    """Example name -> its TOML file, from every registered drive (nothing imported)."""
    return drives.example_files()


def example_path(name: str) -> Path:
    """Path of a built-in example; :class:`ConfigError` naming the choices if unknown.

    Only the names :func:`example_names` lists are accepted (never a path).
    """
    names = example_names()
    if name not in names:
        raise ConfigError(
            f"--example = {name!r} is not admissible: choose one of {', '.join(names)}"
        )
    return _example_files()[name]


#: Largest config file read [bytes]; a config is a few hundred bytes.
MAX_CONFIG_BYTES = 1 << 20
#: Deepest nesting of tables and arrays in a config (a config has sections and lists: 3).
MAX_CONFIG_DEPTH = 8
#: Most keys and list entries in a whole config.
MAX_CONFIG_ITEMS = 10_000


def read_toml(path: str | Path) -> dict:
    """Read a TOML file; any failure becomes one :class:`ConfigError` line.

    Only a regular file of at most :data:`MAX_CONFIG_BYTES` is read (a pipe, a
    device or ``/dev/zero`` is refused before reading), and the result may nest at
    most :data:`MAX_CONFIG_DEPTH` deep with at most :data:`MAX_CONFIG_ITEMS` entries.
    """
    path = Path(path)
    if "\0" in str(path):
        raise ConfigError("config file is not admissible: a file name cannot hold a NUL character")
    try:
        if path.exists() and not path.is_dir() and not path.is_file():
            raise ConfigError(f"config file {str(path)!r} is not a regular file")
        if path.is_file() and path.stat().st_size > MAX_CONFIG_BYTES:
            raise ConfigError(
                f"config file {str(path)!r} is not admissible: larger than "
                f"{MAX_CONFIG_BYTES // 1024} KiB"
            )
        with path.open("rb") as fh:
            data = tomllib.loads(fh.read(MAX_CONFIG_BYTES + 1).decode("utf-8"))
    except FileNotFoundError:
        raise ConfigError(f"config file {str(path)!r} does not exist") from None
    except IsADirectoryError:
        raise ConfigError(f"config file {str(path)!r} is a directory, not a TOML file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"config file {str(path)!r} cannot be read: {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"config file {str(path)!r} is not valid TOML: {exc}") from None
    except RecursionError:
        raise ConfigError(
            f"config file {str(path)!r} is not admissible: nested deeper than {MAX_CONFIG_DEPTH}"
        ) from None
    check_size(data, f"config file {str(path)!r}")
    return data


def check_size(data, what: str) -> None:
    """Refuse a config nested deeper than :data:`MAX_CONFIG_DEPTH` or with too many entries."""
    count, stack = 0, [(data, 1)]
    while stack:
        node, depth = stack.pop()
        if depth > MAX_CONFIG_DEPTH:
            raise ConfigError(f"{what} is not admissible: nested deeper than {MAX_CONFIG_DEPTH}")
        children = node.values() if isinstance(node, dict) else node
        for child in children:
            count += 1
            if count > MAX_CONFIG_ITEMS:
                raise ConfigError(
                    f"{what} is not admissible: more than {MAX_CONFIG_ITEMS} keys and entries"
                )
            if isinstance(child, (dict, list)):
                stack.append((child, depth + 1))


def parse_set(item: str) -> tuple[list[str], object]:
    """Split ``"section.key=VALUE"``; VALUE is TOML when it parses, else a plain string."""
    if "=" not in item:
        raise ConfigError(f"--set {shown(item)} is not admissible: write it as section.key=VALUE")
    key, _, text = item.partition("=")
    parts = [p.strip() for p in key.strip().split(".")]
    if len(parts) < 2 or len(parts) > 3 or not all(parts):
        raise ConfigError(
            f"--set {shown(item)} is not admissible: the key must be section.key, "
            "e.g. drive.plate_tilt"
        )
    text = text.strip()
    try:
        value = tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        value = text
    return parts, value


def apply_sets(raw: dict, sets: list[str]) -> dict:
    """A copy of ``raw`` with each ``--set section.key=VALUE`` applied."""
    import copy

    out = copy.deepcopy(raw)
    for item in sets:
        parts, value = parse_set(item)
        node = out
        for part in parts[:-1]:
            child = node.setdefault(part, {})
            if not isinstance(child, dict):
                raise ConfigError(f"--set {shown(item)} is not admissible: {part} is not a section")
            node = child
        node[parts[-1]] = value
    check_size(out, "the config with its --set overrides")
    return out


def validate_config(raw: dict) -> dict:
    """Validate a raw config mapping; return a nested dict of SI values, defaults filled.

    Raises
    ------
    ConfigError
        One line naming the key, the value and what is admissible.
    """
    drive = raw.get("drive")
    if not isinstance(drive, dict):
        raise ConfigError(
            "missing section [drive]: a config needs [drive] with type = one of "
            + ", ".join(repr(k) for k in drives.names())
        )
    spec = drives.get(drive.get("type"))
    section = raw.get("machine")
    kind = section.get("type") if isinstance(section, dict) else None
    return validate_model(drives.config_model(spec.name, kind), raw)


def load_config(
    path: str | Path | None = None, example: str | None = None, sets: list[str] | None = None
) -> tuple[dict, dict, str]:
    """Read, override and validate a config.

    Parameters
    ----------
    path : path, optional
        A TOML file.
    example : str, optional
        Name of a built-in example (used when ``path`` is None; the default is
        :data:`rotorkin.drives.DEFAULT_EXAMPLE`).
    sets : list of str, optional
        ``section.key=VALUE`` overrides.

    Returns
    -------
    (cfg, raw, name)
        The validated SI config, the raw mapping as written (after the
        overrides) and the run's name (example name or file stem).
    """
    if path is not None and example is not None:
        raise ConfigError("give either a CONFIG file or --example NAME, not both")
    if path is None:
        name = drives.DEFAULT_EXAMPLE if example is None else example
        path = example_path(name)
    else:
        name = Path(path).stem
    raw = apply_sets(read_toml(path), sets or [])
    cfg = validate_config(raw)
    folder = Path(path).resolve().parent
    for section, key in _path_keys(cfg):
        value = cfg[section][key]
        if isinstance(value, str) and not Path(value).is_absolute():
            cfg[section][key] = raw[section][key] = str(folder / value)
    return cfg, raw, name


def _path_keys(cfg: dict) -> list[tuple[str, str]]:
    """The file keys of a config (schema fields marked ``path``): ``[(section, key)]``.

    A relative path in a config names a file next to the config (an example's table
    ships in the example's folder); :func:`load_config` makes it absolute in both the
    config and the raw mapping, so a written ``config.toml`` runs from anywhere.
    """
    model = drives.config_model(cfg["drive"]["type"], cfg.get("machine", {}).get("type"))
    out = []
    for section, sfield in model.model_fields.items():
        for key, field in getattr(sfield.annotation, "model_fields", {}).items():
            extra = field.json_schema_extra if isinstance(field.json_schema_extra, dict) else {}
            if extra.get("path") and (cfg.get(section) or {}).get(key) is not None:
                out.append((section, key))
    return out


def glossary(drive_type: str | None = None) -> list[tuple[str, str, str, str]]:
    """Every config key: ``(drive type, key, default, description)``.

    With ``drive_type``, the keys of that drive only (importing no other drive).
    """
    rows = []
    kinds = drives.REGISTRY if drive_type is None else [drive_type]
    for kind in kinds:
        spec = drives.get(kind)
        model = spec.config_model
        for section, sfield in model.model_fields.items():
            sub = sfield.annotation
            if not (isinstance(sub, type) and issubclass(sub, BaseModel)):
                continue
            for name, field in sub.model_fields.items():
                if name == "type":
                    continue
                default = "required" if field.is_required() else _default_text(field)
                rows.append((kind, f"{section}.{field.alias or name}", default, field.description))
    return rows


def _default_text(field) -> str:
    if field.default_factory is not None:
        return repr(field.default_factory())
    return repr(field.default) if not isinstance(field.default, str) else f'"{field.default}"'
