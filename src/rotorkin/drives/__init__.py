"""Drives: the registry, the only list of drives rotorkin knows.

Each drive is a package ``rotorkin/drives/<name>/`` (kinematics, cam, config
schema, study, batch evaluation, synthesis, figures, report scene, CAD, published
numbers) whose ``spec.py`` builds a :class:`~rotorkin.drives._spec.DriveSpec`.
Everything else (config validation, ``run``, ``sweep``, ``tolerance``,
``synthesize``, ``export``, ``report``, the command-line help) iterates
:data:`REGISTRY`. Adding a drive is one package and one line in :data:`BUILTIN`; a
drive defined elsewhere (a test, a plug-in) joins with :func:`register`.

The registry knows the built-in drives by name and imports a drive's package (its
study, figures, CAD, ...) the first time its spec is asked for: ``rotorkin run`` of
one drive imports that drive only. Listing the names (:func:`names`, ``in``,
iterating the keys) and the built-in examples (:func:`example_files`) imports none.
"""

from __future__ import annotations

import dataclasses
import functools
import gc
import importlib
from collections.abc import Iterator, MutableMapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.drives._spec import DriveSpec

if TYPE_CHECKING:
    from rotorkin.synthesis import SynthesisResult

# The vane machines, the studies' checks and limits (pint, scipy) are imported by the
# functions that use them: listing the drives and examples imports none of them.

__all__ = [
    "REGISTRY",
    "DEFAULT_EXAMPLE",
    "DriveSpec",
    "get",
    "names",
    "machine_type",
    "config_model",
    "spec_of",
    "register",
    "unregister",
    "loaded",
    "example_files",
    "evaluate",
    "design_checks",
    "synthesize",
]

#: The built-in drives, in the order of the command-line help: drive.type -> the package
#: (under ``rotorkin/drives/``) whose ``SPEC`` is the drive's spec; its examples are the
#: ``examples/*.toml`` files of that package.
BUILTIN = (
    "wobble_cam",
    "eccentric_cam",
    "guide_bar",
    "rhomboid_cam",
    "noncircular_gears",
    "tabulated",
)


class Registry(MutableMapping):
    """drive.type -> :class:`DriveSpec`, importing a built-in drive on first access.

    A mapping like a dict (in the order of the command-line help): its keys, ``len``
    and ``in`` import nothing; ``registry[name]``, ``values()`` and ``items()`` import
    the drives they return (once). A spec set with ``registry[name] = spec`` (see
    :func:`register`) is held as given.
    """

    def __init__(self, builtin=()):
        # name -> its spec, or the module that holds it (not imported yet)
        self._entries: dict[str, DriveSpec | str] = {name: f"{__name__}.{name}" for name in builtin}

    def __getitem__(self, name: str) -> DriveSpec:
        entry = self._entries[name]
        if isinstance(entry, str):
            enabled = gc.isenabled()
            gc.disable()  # an import creates few cycles: no collection meanwhile
            try:
                spec = importlib.import_module(entry).SPEC
            finally:
                if enabled:
                    gc.enable()
            if spec.name != name:  # pragma: no cover - a package's SPEC under another name
                raise ValueError(f"the package {entry} holds the drive {spec.name!r}, not {name!r}")
            self._entries[name] = entry = spec
        return entry

    def __setitem__(self, name: str, spec: DriveSpec) -> None:
        self._entries[name] = spec

    def __delitem__(self, name: str) -> None:
        del self._entries[name]

    def __iter__(self) -> Iterator[str]:
        return iter(list(self._entries))

    def __len__(self) -> int:
        return len(self._entries)

    def __contains__(self, name) -> bool:
        return name in self._entries

    def loaded(self, name: str) -> bool:
        """Whether ``name``'s spec is at hand (its package imported)."""
        return isinstance(self._entries.get(name), DriveSpec)

    def package(self, name: str) -> Path | None:
        """The folder of a built-in drive not imported yet (None otherwise)."""
        entry = self._entries.get(name)
        if not isinstance(entry, str):
            return None
        return Path(__file__).resolve().parent / entry.rsplit(".", 1)[-1]

    def __repr__(self) -> str:
        shown = ", ".join(
            f"{k!r}: {'<not imported>' if isinstance(v, str) else v.title!r}"
            for k, v in self._entries.items()
        )
        return f"Registry({{{shown}}})"


#: drive.type -> its spec, in the order of the command-line help (built-in drives are
#: imported on first access, see :class:`Registry`).
REGISTRY: Registry = Registry(BUILTIN)

#: Most harmonics a synthesized law may have (``rotorkin synthesize --harmonics``).
MAX_HARMONICS = 1000

#: The example ``rotorkin run`` evaluates without a config.
DEFAULT_EXAMPLE = "wobble-cam-engine"


def register(spec: DriveSpec, *, replace: bool = False) -> DriveSpec:
    """Add a drive to :data:`REGISTRY`; refuse a second drive of the same name."""
    if not isinstance(spec, DriveSpec):
        raise TypeError(f"register() takes a DriveSpec, not {type(spec).__name__}")
    if spec.name in REGISTRY and not replace:
        raise ValueError(f"a drive named {spec.name!r} is registered already")
    REGISTRY[spec.name] = spec
    return spec


def unregister(name: str) -> None:
    """Remove a drive registered with :func:`register` (tests, plug-ins)."""
    REGISTRY.pop(name, None)


def names() -> list[str]:
    """The registered drive types (nothing imported)."""
    return list(REGISTRY)


def loaded(name: str) -> bool:
    """Whether the drive ``name`` has been imported (its spec is at hand)."""
    return REGISTRY.loaded(name)


def example_files() -> dict[str, Path]:
    """Built-in example name -> its TOML file, over every registered drive.

    A built-in drive not imported yet is read from its package's ``examples`` folder
    (nothing imported); any other from its spec's ``examples`` and ``example_dir``.
    """
    out = {}
    for kind in REGISTRY:
        folder = REGISTRY.package(kind)
        if folder is not None:
            out.update({p.stem: p for p in sorted((folder / "examples").glob("*.toml"))})
            continue
        spec = REGISTRY[kind]
        if spec.example_dir is not None:
            out.update({name: spec.example_dir / f"{name}.toml" for name in spec.examples})
    return out


def get(name) -> DriveSpec:
    """The spec of ``drive.type = name``; :class:`ConfigError` naming the choices if unknown."""
    spec = REGISTRY.get(name) if isinstance(name, str) else None
    if spec is None:
        shown = "missing" if name is None else f"= {name!r}"
        raise ConfigError(
            f"drive.type {shown} is not admissible: choose one of "
            + ", ".join(repr(k) for k in REGISTRY)
        )
    return spec


def machine_type(cfg: dict, spec: DriveSpec | None = None) -> str:
    """``machine.type`` of a config (raw or validated); the drive's own machine when unset."""
    spec = get(cfg["drive"]["type"]) if spec is None else spec
    section = cfg.get("machine")
    kind = section.get("type") if isinstance(section, dict) else None
    return spec.machine if kind is None else kind


def _check_machine(spec: DriveSpec, kind) -> None:
    from rotorkin.vane import MACHINES

    if kind == spec.machine:
        return
    if spec.law is None:
        raise ConfigError(
            f"machine.type = {kind!r} is not admissible: drive.type = {spec.name} carries "
            f"machine.type = {spec.machine!r} only"
        )
    if not isinstance(kind, str) or kind not in MACHINES:
        raise ConfigError(
            f"machine.type = {kind!r} is not admissible: on drive.type = {spec.name} choose one "
            "of " + ", ".join(repr(k) for k in MACHINES)
        )


@functools.cache
def _composed(model: type, kind: str) -> type:
    from pydantic import Field, create_model

    from rotorkin.vane import MACHINES

    machine, loads, _ = MACHINES[kind]
    return create_model(
        f"{model.__name__}_{kind}",
        __base__=model,
        machine=(machine, Field(default_factory=machine)),
        loads=(loads, Field(default_factory=loads)),
    )


def config_model(drive_type: str, kind: str | None = None) -> type:
    """The config model of ``drive_type`` carrying ``machine.type = kind`` (default: its own).

    Raises
    ------
    ConfigError
        One line when the drive cannot carry that machine.
    """
    spec = get(drive_type)
    if kind is None or kind == spec.machine:
        return spec.config_model
    _check_machine(spec, kind)
    return _composed(spec.config_model, kind)


def spec_of(cfg: dict) -> DriveSpec:
    """The spec that evaluates ``cfg``: its drive's, or the drive carrying another vane machine.

    A drive carrying a machine that is not its own keeps its motion, cam checks and
    CAD of the drive's parts; its study is :func:`rotorkin.vane.evaluate` and it has
    no batch kernel, paper numbers, synthesis or report scene of its own.
    """
    spec = get(cfg["drive"]["type"])
    kind = machine_type(cfg, spec)
    if kind == spec.machine:
        return spec
    _check_machine(spec, kind)
    return _carrying(spec, kind)


def _carrying(spec: DriveSpec, kind: str) -> DriveSpec:
    from rotorkin.vane import evaluate as evaluate_vane_machine
    from rotorkin.vane.study import HEADLINES

    if spec.carries_any:  # its study runs any machine: only the headline's tail changes
        own = {k: v for k, v in spec.headline.items() if k not in HEADLINES.get(spec.machine, {})}
        return dataclasses.replace(
            spec,
            config_model=_composed(spec.config_model, kind),
            headline={**own, **HEADLINES[kind]},
            machine=kind,
        )

    def study(cfg):
        return evaluate_vane_machine(
            cfg,
            spec.law(cfg),
            drive_type=spec.name,
            title=f"{kind.replace('_', ' ')} on drive {spec.name}",
            drive_pairs=spec.pairs(cfg) if spec.pairs is not None else None,
        )

    return dataclasses.replace(
        spec,
        title=f"{kind.replace('_', ' ')} on the {spec.name} drive",
        config_model=_composed(spec.config_model, kind),
        study=study,
        headline=HEADLINES[kind],
        paper="",
        published=(),
        batch=None,
        sweep_recipes=None,
        tolerance_hold=None,
        tolerance_first=(),
        synthesize=None,
        objectives={},
        synthesis_options=(),
        scene=None,
        machine=kind,
    )


def evaluate(cfg: dict):
    """Run the study of ``cfg["drive"]["type"]`` (and ``machine.type``) on a validated config.

    Returns
    -------
    rotorkin.studies.StudyResult
    """
    from rotorkin.studies.checks import failure_line, limit_checks
    from rotorkin.studies.limits import violations
    from rotorkin.vane.study import CONTACT_HEADLINE

    spec = spec_of(cfg)
    checks = design_checks(cfg)  # what export refuses, every command refuses
    result = spec.study(cfg)
    if isinstance(result.headline, dict):  # every drive prints its pairs' peaks the same way
        extra = {k: v for k, v in CONTACT_HEADLINE.items()
                 if k in result.summary and k not in result.headline}  # fmt: skip
        result.headline = {**result.headline, **extra}
    lines = violations(result.summary, cfg, result.columns)
    # plausibility limits passed (rotorkin.studies.limits): one warning line each
    # the limits passed, comma-separated ("" when none): a summary value stays a plain string
    result.summary["limits_passed"] = ", ".join(line.split(":", 1)[0] for line in lines)
    # the drive's own checks that fail: one warning line each, unless the study's own
    # warnings already name the check's key
    said = [*result.warnings, *lines]
    lines += [failure_line(c) for c in checks if not c.passed
              and not any(w.startswith((f"{c.key} ", f"{c.key}:")) for w in said)]  # fmt: skip
    result.warnings = (*result.warnings, *lines)
    result.checks = (*checks, *limit_checks(result.summary, cfg, result.columns))
    return result


def design_checks(cfg: dict) -> list:
    """The drive's checks of a validated config, with their margins, before any study.

    The drive's own (``DriveSpec.checks``) or, for a drive with planar parts, the checks
    of each cam profile (:func:`rotorkin.studies.checks.profile_checks`); then
    ``DriveSpec.check_cam``. Raises :class:`ParameterError` for what ``rotorkin export``
    refuses outright (named by config key), so every command refuses it too.

    Returns
    -------
    list of rotorkin.studies.checks.Check
    """
    spec = spec_of(cfg)
    if spec.checks is not None:
        return list(spec.checks(cfg))
    if spec.cad_parts is not None:
        from rotorkin.studies.checks import profile_checks
        from rotorkin.studies.limits import limit_value

        _, profiles = spec.cad_parts(cfg, False)
        angle = limit_value(cfg, "limits.pressure_angle")
        return [c for label, p in profiles for c in profile_checks(label, p, angle)]
    if spec.check_cam is not None:
        spec.check_cam(cfg)
    return []


def synthesize(
    cfg: dict,
    raw: dict,
    objective: str,
    target: str | None = None,
    harmonics: int | None = None,
    max_pressure_angle: float | None = None,
) -> SynthesisResult:
    """Synthesize a design for ``cfg``'s drive type.

    Parameters
    ----------
    cfg : dict
        Validated SI config (:func:`rotorkin.io.config.load_config`): the baseline.
    raw : dict
        The same config as written; the synthesized config is a copy with
        :attr:`SynthesisResult.updates` applied.
    objective : str
        One of the drive's ``DriveSpec.objectives``.
    target : str, optional
        Target value as people write it (``"60 deg"``, ``"1 %"``, ``"0.3"``,
        ``"5 mm"``), where the objective takes one.
    harmonics : int, optional
        Number of harmonics of a synthesized law, for drives that synthesize
        one (see the drive's synthesis module).
    max_pressure_angle : float, optional
        Bound on the peak pressure angle [rad], ``0 < value < pi/2``, for drives
        whose ``synthesis_options`` name it.

    Raises
    ------
    ParameterError
        Named ``--objective``, ``--target``, ``--harmonics`` or ``--max-pressure-angle``
        when not admissible.
    """
    kind = cfg["drive"]["type"]
    spec = spec_of(cfg)
    if spec.check_cam is not None:
        spec.check_cam(cfg)  # the baseline must pass what export checks
    names = tuple(spec.objectives)
    if spec.synthesize is None or not names:
        raise ParameterError(
            "drive.type",
            kind,
            "a drive with synthesis objectives: "
            + ", ".join(k for k, s in REGISTRY.items() if s.objectives),
        )
    if objective not in names:
        raise ParameterError(
            "objective",
            repr(objective),
            f"one of {', '.join(names)} for drive.type = {kind}",
        )
    if harmonics is not None and (
        isinstance(harmonics, bool) or not 1 <= int(harmonics) <= MAX_HARMONICS
    ):
        raise ParameterError("harmonics", repr(harmonics), f"1 <= harmonics <= {MAX_HARMONICS}")
    if max_pressure_angle is not None:
        if "max_pressure_angle" not in spec.synthesis_options:
            takers = [k for k, s in REGISTRY.items() if "max_pressure_angle" in s.synthesis_options]
            raise ParameterError(
                "max_pressure_angle",
                "given",
                f"only for drive.type = {' or '.join(takers)}, not {kind}",
            )
        value = float(max_pressure_angle)
        if not (np.isfinite(value) and 0.0 < value < 0.5 * np.pi):
            raise ParameterError(
                "max_pressure_angle", f"{np.degrees(value):.6g} deg", "0 deg < angle < 90 deg"
            )
        return spec.synthesize(
            cfg, raw, objective, target, harmonics, {"max_pressure_angle": max_pressure_angle}
        )
    return spec.synthesize(cfg, raw, objective, target, harmonics, None)


def __getattr__(name: str):
    """A built-in drive's package as an attribute (``rotorkin.drives.wobble_cam``), imported."""
    if name in BUILTIN:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
