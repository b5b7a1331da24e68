"""Config files: TOML in, a validated nested dict of SI values out.

A config has the sections ``[drive]`` (with ``type``), ``[machine]``,
``[loads]``, ``[cam]`` (cam geometry for checks and CAD; not for the guide
bar), ``[export]`` and ``[run]``, plus an optional top-level ``title``. Dimensional
values are strings with units (``"45 deg"``, ``"80 mm"``, ``"12 N*m"``),
converted to SI once, here; dimensionless keys take bare numbers. Unknown keys,
wrong types and missing units are refused with one line that names the key.

The schema is a set of pydantic models, one per drive type; their field
descriptions are the glossary (``rotorkin keys`` prints them).
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Annotated, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError
from pydantic_core import PydanticCustomError

from rotorkin.errors import ConfigError
from rotorkin.io.units import describe_kind, parse_quantity

__all__ = [
    "DRIVE_MODELS",
    "EXAMPLES_DIR",
    "apply_sets",
    "example_names",
    "example_path",
    "glossary",
    "load_config",
    "parse_set",
    "read_toml",
    "validate_config",
]

EXAMPLES_DIR = Path(__file__).resolve().parent.parent / "examples"


def _unit(kind: str):
    def parse(value):
        number, reason = parse_quantity(value, kind)
        if reason:
            raise PydanticCustomError("rotorkin_unit", reason)
        return number

    parse.kind = kind
    return BeforeValidator(parse)


Angle = Annotated[float, _unit("angle")]
Length = Annotated[float, _unit("length")]
Torque = Annotated[float, _unit("torque")]
Pressure = Annotated[float, _unit("pressure")]
Inertia = Annotated[float, _unit("inertia")]
Mass = Annotated[float, _unit("mass")]
Volume = Annotated[float, _unit("volume")]
Energy = Annotated[float, _unit("energy")]
Temperature = Annotated[float, _unit("temperature")]
Modulus = Annotated[float, _unit("modulus")]


def _speeds(value):
    values = value if isinstance(value, list) else [value]
    out = []
    for item in values:
        number, reason = parse_quantity(item, "speed")
        if reason:
            raise PydanticCustomError("rotorkin_unit", reason)
        out.append(number)
    return out[0] if not isinstance(value, list) else out


_speeds_validator = BeforeValidator(_speeds)
_speeds_validator.func.kind = "speed"
Speed = Annotated[float | list[float], _speeds_validator]


class _Section(BaseModel):
    model_config = ConfigDict(
        extra="forbid",
        strict=True,
        validate_default=True,
        frozen=True,
        populate_by_name=True,
        allow_inf_nan=False,
    )


class RunSection(_Section):
    points: int = Field(
        721, ge=3, le=10_000_000, description="input angles sampled over one period, ends included"
    )
    speed: Speed = Field(
        "3000 rpm",
        description="input shaft speed: one value, or a list sampled evenly over one period",
    )


class EmptySection(_Section):
    pass


class ExportSection(_Section):
    tolerance: Length = Field(
        "0.01 mm",
        description="chordal tolerance of exported curves and meshes (DXF, STL, STEP)",
    )


class WobbleCamSection(_Section):
    roller_radius: Length = Field("4 mm", description="radius of the rollers in the grooves")
    shell_thickness: Length = Field(
        "12 mm", description="radial thickness of the spherical cam shell, centred on r"
    )
    groove_depth: Length = Field(
        "8 mm", description="radial depth of the grooves, from the shell's inner surface"
    )


class PlanarCamSection(_Section):
    roller_radius: Length = Field("10 mm", description="radius of the rollers on the cam")
    thickness: Length = Field("20 mm", description="axial thickness of the cam plate")


class DiscCamSection(_Section):
    thickness: Length = Field("20 mm", description="axial thickness of each eccentric disc")


# --- wobble plate + spherical cam -----------------------------------------------------------
class WobbleDrive(_Section):
    type: Literal["wobble_cam"]
    plate_tilt: Angle = Field(description="wobble plate tilt phi on the Z-shaft (paper Table 1)")
    roller_axis_angle: Angle = Field(
        "90 deg", description="angle alpha between the two roller groups in the plate plane"
    )
    spin_ratio: float = Field(-2.0, description="plate spin law varphi = spin_ratio * theta")
    sphere_radius: Length = Field(
        "60 mm", description="radius r of the roller centres on the spherical cam"
    )
    spin_a: list[float] = Field(
        default_factory=list,
        description="cosine coefficients of harmonics 1, 2, ... of a periodic correction "
        "added to the spin law [rad]",
    )
    spin_b: list[float] = Field(
        default_factory=list,
        description="sine coefficients of harmonics 1, 2, ... of the spin-law correction [rad]",
    )


class _Inertial(_Section):
    inertia_shaft: Inertia = Field("0 kg*m^2", description="inertia of the input shaft")
    speed_fluctuation: float = Field(
        0.02, description="wanted coefficient of speed fluctuation, for the flywheel"
    )


class WobbleMachine(_Inertial):
    compression_ratio: float = Field(
        10.0,
        description="compression ratio eps = delta_max / delta_min of the chamber angles "
        "(Table 1); the geometric volume ratio when there is no clearance volume",
    )
    pistons_per_rotor: int = Field(4, description="vane pistons on each rotor")
    section: Literal["rectangular", "circular"] = Field(
        "rectangular", description="cylinder section: rectangular annulus or circular torus"
    )
    inner_radius: Length = Field("40 mm", description="inner radius of a rectangular annulus")
    outer_radius: Length = Field("80 mm", description="outer radius of a rectangular annulus")
    axial_width: Length = Field("40 mm", description="axial width of a rectangular annulus")
    mean_radius: Length = Field("60 mm", description="mean radius of a circular torus")
    section_diameter: Length = Field("40 mm", description="section diameter of a circular torus")
    clearance_volume: Volume = Field("0 cm^3", description="clearance volume of each chamber")
    inertia_rotor_1: Inertia = Field("0.01 kg*m^2", description="inertia of rotor 1")
    inertia_rotor_2: Inertia = Field("0.01 kg*m^2", description="inertia of rotor 2")


class EngineLoads(_Section):
    ambient_pressure: Pressure = Field("1 bar", description="intake and exhaust pressure")
    polytropic_exponent: float = Field(
        1.35, description="exponent n of compression and expansion, p V^n = const"
    )
    heat_per_cycle: Energy = Field(
        "0 J", description="heat added at minimum volume, per chamber and four-stroke cycle"
    )


class WobbleConfig(_Section):
    title: str = ""
    drive: WobbleDrive
    machine: WobbleMachine = Field(default_factory=WobbleMachine)
    loads: EngineLoads = Field(default_factory=EngineLoads)
    cam: WobbleCamSection = Field(default_factory=WobbleCamSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)


# --- double eccentric cams ------------------------------------------------------------------
class EccentricDrive(_Section):
    type: Literal["eccentric_cam"]
    disc_radius: Length = Field(description="radius R of each eccentric disc")
    eccentricity: Length = Field(description="eccentricity e of the disc centre from the shaft")
    follower: Literal["knife_edge", "flat", "roller"] = Field(
        "knife_edge", description="piston follower: knife_edge, flat or roller"
    )
    roller_radius: Length = Field("0 mm", description="roller radius r (follower = roller)")


class EccentricMachine(_Inertial):
    device_length: Length = Field(
        "1000 mm", description="length L of the reactor between the pistons"
    )
    bore: Length = Field("50 mm", description="piston and tube bore diameter")
    fluid: Literal["gas", "liquid"] = Field("liquid", description="working fluid: gas or liquid")
    initial_pressure: Pressure = Field("1 bar", description="pressure at the starting gap")
    polytropic_exponent: float = Field(1.0, description="exponent n of the gas, p V^n = const")
    bulk_modulus: Modulus = Field("1.5 GPa", description="bulk modulus K of the liquid")
    piston_mass: Mass = Field("0.5 kg", description="mass of each piston with its rod")


class EccentricConfig(_Section):
    title: str = ""
    drive: EccentricDrive
    machine: EccentricMachine = Field(default_factory=EccentricMachine)
    loads: EmptySection = Field(default_factory=EmptySection)
    cam: DiscCamSection = Field(default_factory=DiscCamSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)


# --- rotating guide bars + gears ------------------------------------------------------------
class GuideBarDrive(_Section):
    type: Literal["guide_bar"]
    lam: float = Field(
        alias="lambda", description="mechanism coefficient lambda = d/a (frame over crank length)"
    )
    gear_ratio: float = Field(description="ratio u from the guide-bar gear to the impeller gear")
    input_gear_ratio: float = Field(1.0, description="ratio i12 = z2/z1 from input gear 1")
    phase: Angle = Field("180 deg", description="installation phase Sigma = sigma_2 - sigma_1")
    driver: Literal["crank", "guide"] = Field(
        "crank", description="driving member: crank (paper Fig. 2) or guide (Fig. 4)"
    )


class GuideBarLoads(_Section):
    impeller_torque_1: Torque = Field("0 N*m", description="resisting torque M7 on impeller 1")
    impeller_torque_2: Torque = Field("0 N*m", description="resisting torque M8 on impeller 2")
    suction_pressure: Pressure = Field("1 bar", description="pressure at the inlet port")
    discharge_pressure: Pressure = Field("1 bar", description="pressure at the outlet port")


class VanePumpMachine(_Inertial):
    vanes_per_impeller: int = Field(2, description="vanes on each impeller")
    vane_angle: Angle | None = Field(
        None, description="angular width of a vane; default: the drive's gamma_0"
    )
    hub_radius: Length = Field("30 mm", description="impeller hub radius")
    casing_radius: Length = Field("80 mm", description="casing (vane tip) radius")
    axial_width: Length = Field("40 mm", description="axial width of the working space")
    inertia_impeller_1: Inertia = Field("0.005 kg*m^2", description="inertia of impeller 1")
    inertia_impeller_2: Inertia = Field("0.005 kg*m^2", description="inertia of impeller 2")


class GuideBarConfig(_Section):
    title: str = ""
    drive: GuideBarDrive
    machine: VanePumpMachine = Field(default_factory=VanePumpMachine)
    loads: GuideBarLoads = Field(default_factory=GuideBarLoads)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)


# --- rhomboid linkage on a cam --------------------------------------------------------------
class RhomboidDrive(_Section):
    type: Literal["rhomboid_cam"]
    link_length: Length = Field(description="side 2l of the rhomboid")
    psi_min: Angle = Field(description="smallest angle psi_min between the blade axes")
    a: list[float] = Field(
        default_factory=list, description="cosine coefficients a3, a5, ... of psi(alpha) [rad]"
    )
    b: list[float] = Field(
        default_factory=list, description="sine coefficients b3, b5, ... of psi(alpha) [rad]"
    )


class RhomboidLoads(_Section):
    torque_high: Torque = Field("0 N*m", description="torque level M1 of the linear blade model")
    torque_low: Torque = Field("0 N*m", description="torque level M2 of the linear blade model")
    pressure_model: Literal["linear", "isothermal"] = Field(
        "linear", description="blade loads: the paper's linear torque model or isothermal gas"
    )
    charge_pressure: Pressure = Field(
        "10 bar", description="isothermal model: pressure at the largest volume, cold"
    )
    hot_temperature: Temperature = Field("900 K", description="isothermal model: expansion")
    cold_temperature: Temperature = Field("330 K", description="isothermal model: compression")


class RotaryBladeMachine(_Inertial):
    blades_per_pair: int = Field(2, description="blades on each of the two blade pairs")
    blade_thickness: Angle = Field("10 deg", description="angular thickness of one blade")
    inner_radius: Length = Field("30 mm", description="hub radius of the working space")
    outer_radius: Length = Field("90 mm", description="casing radius of the working space")
    axial_width: Length = Field("50 mm", description="axial width of the working space")
    inertia_blade_pair_1: Inertia = Field("0.01 kg*m^2", description="inertia of blade pair 1")
    inertia_blade_pair_2: Inertia = Field("0.01 kg*m^2", description="inertia of blade pair 2")


class RhomboidConfig(_Section):
    title: str = ""
    drive: RhomboidDrive
    machine: RotaryBladeMachine = Field(default_factory=RotaryBladeMachine)
    loads: RhomboidLoads = Field(default_factory=RhomboidLoads)
    cam: PlanarCamSection = Field(default_factory=PlanarCamSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)


#: drive.type -> the pydantic model of a whole config of that type
DRIVE_MODELS: dict[str, type[_Section]] = {
    "wobble_cam": WobbleConfig,
    "eccentric_cam": EccentricConfig,
    "guide_bar": GuideBarConfig,
    "rhomboid_cam": RhomboidConfig,
}


# --- reading --------------------------------------------------------------------------------
def example_names() -> list[str]:
    """Names of the built-in examples (``rotorkin run --example NAME``)."""
    return sorted(p.stem for p in EXAMPLES_DIR.glob("*.toml"))


def example_path(name: str) -> Path:
    """Path of a built-in example; :class:`ConfigError` naming the choices if unknown."""
    path = EXAMPLES_DIR / f"{name}.toml"
    if not path.is_file():
        raise ConfigError(
            f"--example = {name!r} is not admissible: choose one of {', '.join(example_names())}"
        )
    return path


def read_toml(path: str | Path) -> dict:
    """Read a TOML file; any failure becomes one :class:`ConfigError` line."""
    path = Path(path)
    try:
        with path.open("rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise ConfigError(f"config file {str(path)!r} does not exist") from None
    except IsADirectoryError:
        raise ConfigError(f"config file {str(path)!r} is a directory, not a TOML file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"config file {str(path)!r} cannot be read: {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"config file {str(path)!r} is not valid TOML: {exc}") from None


def parse_set(item: str) -> tuple[list[str], object]:
    """Split ``"section.key=VALUE"``; VALUE is TOML when it parses, else a plain string."""
    if "=" not in item:
        raise ConfigError(f"--set {item!r} is not admissible: write it as section.key=VALUE")
    key, _, text = item.partition("=")
    parts = [p.strip() for p in key.strip().split(".")]
    if len(parts) < 2 or not all(parts):
        raise ConfigError(
            f"--set {item!r} is not admissible: the key must be section.key, e.g. drive.plate_tilt"
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
                raise ConfigError(f"--set {item!r} is not admissible: {part} is not a section")
            node = child
        node[parts[-1]] = value
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
            + ", ".join(repr(k) for k in DRIVE_MODELS)
        )
    kind = drive.get("type")
    if kind not in DRIVE_MODELS:
        shown = "missing" if kind is None else f"= {kind!r}"
        raise ConfigError(
            f"drive.type {shown} is not admissible: choose one of "
            + ", ".join(repr(k) for k in DRIVE_MODELS)
        )
    model = DRIVE_MODELS[kind]
    try:
        validated = model.model_validate(raw)
    except ValidationError as exc:
        raise ConfigError(_one_line(exc, model)) from None
    return validated.model_dump(by_alias=True)


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
        ``"wobble-cam-engine"``).
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
        name = example or "wobble-cam-engine"
        path = example_path(name)
    else:
        name = Path(path).stem
    raw = apply_sets(read_toml(path), sets or [])
    return validate_config(raw), raw, name


def _one_line(exc: ValidationError, model: type[BaseModel]) -> str:
    err = exc.errors(include_url=False)[0]
    loc = ".".join(str(p) for p in err["loc"])
    kind = err["type"]
    value = err.get("input")
    if kind == "missing":
        return f"missing required key {loc}: {_describe(model, err['loc'])}"
    if kind == "extra_forbidden":
        parent = _submodel(model, err["loc"][:-1])
        known = ", ".join((f.alias or n) for n, f in parent.model_fields.items() if n != "type")
        where = f"[{'.'.join(map(str, err['loc'][:-1]))}]" if len(err["loc"]) > 1 else "top level"
        return f"unknown key {loc}; known keys at {where}: {known}"
    if kind == "rotorkin_unit":
        return f"{loc} = {value!r} {err['msg']}"
    msg = err["msg"]
    if isinstance(value, dict):
        value = "{...}"
    return f"{loc} = {value!r} is not admissible: {msg[0].lower()}{msg[1:]}"


def _submodel(model, loc):
    for part in loc:
        field = model.model_fields.get(part) or next(
            (f for f in model.model_fields.values() if f.alias == part), None
        )
        if field is None or not isinstance(field.annotation, type):
            return model
        if issubclass(field.annotation, BaseModel):
            model = field.annotation
    return model


def _describe(model, loc) -> str:
    parent = _submodel(model, loc[:-1])
    for name, field in parent.model_fields.items():
        if loc[-1] in (name, field.alias):
            kinds = [getattr(m.func, "kind", None) for m in field.metadata if hasattr(m, "func")]
            unit = f" ({describe_kind(kinds[0])})" if kinds and kinds[0] else ""
            return (field.description or "required") + unit
    return "required"


def glossary() -> list[tuple[str, str, str, str]]:
    """Every config key: ``(drive type, key, default, description)``."""
    rows = []
    for kind, model in DRIVE_MODELS.items():
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
