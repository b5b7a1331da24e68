"""The config schema's building blocks: sections, quantities with units, the shared sections.

A drive's schema (``rotorkin/drives/<name>/schema.py``) is a pydantic model made
of these: every dimensional key is a quantity type (:data:`Angle`, :data:`Length`,
...) that reads a string with a unit (``"45 deg"``, ``"80 mm"``) and stores the SI
value; every section forbids unknown keys. The field descriptions are the glossary
(``rotorkin keys``), and the field defaults are the one source of defaults: a
drive's parameter classes take theirs from here (a test compares them).
"""

from __future__ import annotations

import re
import typing
from typing import Annotated, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError, field_validator
from pydantic_core import PydanticCustomError

from rotorkin.core.bounds import INERTIA_MAX, speed_fluctuation
from rotorkin.core.errors import ConfigError
from rotorkin.core.units import describe_kind, display_value, parse_quantity

__all__ = [
    "Angle",
    "annotation_kind",
    "Length",
    "Torque",
    "Pressure",
    "Inertia",
    "Mass",
    "Volume",
    "Energy",
    "Temperature",
    "Modulus",
    "SpecificEnergy",
    "Speed",
    "Section",
    "RunSection",
    "EmptySection",
    "ExportSection",
    "InertialSection",
    "ContactSection",
    "LimitsSection",
    "validate_model",
]


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
SpecificEnergy = Annotated[float, _unit("specific_energy")]


#: Most input angles of a run (run.points) and entries of a speed profile: 0.0036 deg apart.
MAX_POINTS = 100_001


def _speeds(value):
    values = value if isinstance(value, list) else [value]
    if len(values) > MAX_POINTS:
        raise PydanticCustomError(
            "rotorkin_unit", f"is not admissible: a speed profile of at most {MAX_POINTS} values"
        )
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


class Section(BaseModel):
    """A config section: strict types, unknown keys refused, frozen, SI after validation."""

    model_config = ConfigDict(
        extra="forbid",
        strict=True,
        validate_default=True,
        frozen=True,
        populate_by_name=True,
        allow_inf_nan=False,
    )


class RunSection(Section):
    points: int = Field(
        721, ge=3, le=MAX_POINTS, description="input angles sampled over one period, ends included"
    )
    speed: Speed = Field(
        "3000 rpm",
        description="input shaft speed: one value, or a list sampled evenly over one period",
    )


class EmptySection(Section):
    pass


class ExportSection(Section):
    tolerance: Length = Field(
        "0.01 mm",
        description="chordal tolerance of exported curves and meshes (DXF, STL, STEP), "
        "0.00001 mm ... 1 mm (and at most 1 % of the part's size, checked by export)",
    )

    bore: Length | None = Field(
        None,
        ge=0.0,
        le=0.5,
        description="nominal diameter of the shaft bore of every cam, disc, impeller and gear "
        "(vane pump: of impeller 1, on the inner shaft); default: the largest that leaves a hub "
        "wall of max(1 mm, bore/4) beyond the keyway, rounded down (whole mm to 20 mm, even mm "
        "to 50 mm, 5 mm to 150 mm, 10 mm above); 0: no bore (0 mm <= bore <= 500 mm; "
        "6 mm <= bore <= 230 mm with a keyway)",
    )
    sleeve_bore: Length | None = Field(
        None,
        ge=1e-3,
        le=0.5,
        description="vane pump: bore of impeller 2, which sits on a hollow shaft around the "
        "shaft of impeller 1 (the hollow shaft's outer diameter); default: the largest that "
        "fits its hub, rounded down like bore; the hollow shaft keeps a wall of max(1 mm, "
        "sleeve_bore/10) under its keyseat around the shaft of bore "
        "(1 mm <= sleeve_bore <= 500 mm)",
    )
    keyway: bool = Field(
        True,
        description="cut a DIN 6885-1 (ISO/R 773) parallel-key keyway into every bore, sized by "
        "the bore (true or false)",
    )
    bore_fit: Literal["H7/g6", "H7/h6", "H7/k6"] = Field(
        "H7/g6",
        description="ISO 286 fit of each hub on its shaft, hole basis: H7/g6 sliding, H7/h6 "
        "locational clearance, H7/k6 locational transition; the bore is modelled at the middle "
        "of its hole zone",
    )
    running_fit: Literal["H8/f7", "H9/d9", "H7/g6"] = Field(
        "H8/f7",
        description="ISO 286 fit that sets the running gaps: half its mean diametral clearance "
        "at the size of each pair (a cam's outer diameter, a pump's casing diameter); H8/f7 "
        "close running, H9/d9 free running, H7/g6 sliding",
    )
    running_clearance: Length | None = Field(
        None,
        ge=0.0,
        le=1e-3,
        description="radial gap of every pair that runs on another in the CAD (roller on a "
        "form-closed cam, vane tip on the casing, vane root on the other impeller's hub, vane on "
        "vane, hub on hub), overriding running_fit; a pump's machine.tip_clearance, "
        "hub_clearance and side_clearance take precedence where > 0 "
        "(0 mm <= running_clearance <= 1 mm)",
    )

    @field_validator("tolerance")
    @classmethod
    def _tolerance_range(cls, value: float) -> float:
        if not 1e-8 <= value <= 1e-3:
            raise PydanticCustomError(
                "rotorkin_range", "0.00001 mm <= tolerance <= 1 mm (a chordal tolerance)"
            )
        return value


class ContactSection(Section):
    youngs_modulus: Modulus = Field(
        "210 GPa",
        gt=1e8,
        le=1e12,
        description="Young's modulus of the contacting parts (steel: 210 GPa; 0.1 GPa < E <= "
        "1000 GPa)",
    )
    poisson_ratio: float = Field(
        0.3, ge=0.0, lt=0.5, description="Poisson's ratio of the contacting parts (0 <= nu < 0.5)"
    )
    allowable_stress: Pressure = Field(
        "1500 MPa",
        gt=0.0,
        le=1e10,
        description="allowable Hertz contact pressure (hardened steel: about 1500 MPa; "
        "0 < p <= 10000 MPa)",
    )
    roller_width: Length = Field(
        "10 mm",
        ge=1e-4,
        le=1.0,
        description="width of the rollers and followers in line contact (0.1 mm <= w <= 1 m)",
    )
    friction_rolling: float = Field(
        0.002,
        ge=0.0,
        le=0.1,
        description="rolling-resistance coefficient of rollers on cams and grooves (0 <= c <= 0.1)",
    )
    friction_sliding: float = Field(
        0.08,
        ge=0.0,
        le=1.0,
        description="Coulomb coefficient of sliding pairs, lubricated steel (0 <= mu <= 1)",
    )
    friction_mesh: float = Field(
        0.01,
        ge=0.0,
        le=0.2,
        description="fraction of the transmitted power a gear mesh loses (spur gears about "
        "0.01; 0 <= c <= 0.2)",
    )
    friction_bearing: float = Field(
        0.0015,
        ge=0.0,
        le=0.2,
        description="friction coefficient of the bearings, referred to bearing_radius (rolling "
        "bearings about 0.0015; 0 <= mu <= 0.2)",
    )
    bearing_radius: Length = Field(
        "10 mm",
        ge=1e-4,
        le=1.0,
        description="journal radius of the bearings and pins (0.1 mm <= r <= 1 m)",
    )
    efficiency_min: float = Field(
        0.9, ge=0.0, le=1.0,
        description="mechanical efficiency below which the report flags the drive (0 <= eta <= 1)",
    )  # fmt: skip


class LimitsSection(Section):
    """Plausibility limits: a design past one is admissible but its numbers are not believable.

    ``rotorkin run`` warns in one line per limit passed (``--strict`` refuses the design);
    a sweep marks such designs in its ``violations`` variable. The contact pressure's
    limit is ``contact.allowable_stress``.
    """

    peak_pressure: Pressure = Field(
        "250 bar",
        gt=0.0,
        le=1e9,
        description="highest plausible chamber (gas or fluid) pressure; above it the cycle's "
        "numbers are not believable for these machines (0 < p <= 10000 bar)",
    )
    peak_temperature: Temperature = Field(
        "3000 K",
        gt=0.0,
        le=1e5,
        description="highest plausible gas temperature, about the adiabatic flame temperature "
        "of fuels in air (0 K < T <= 100000 K)",
    )
    pressure_angle: Angle = Field(
        "60 deg",
        gt=0.0,
        lt=1.5707963267948966,
        description="largest plausible cam, groove or mesh pressure angle; past it the drive "
        "jams or wears rather than drives (0 deg < angle < 90 deg)",
    )


class InertialSection(Section):
    inertia_shaft: Inertia = Field(
        "0 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of the input shaft (0 <= J <= 1e5 kg*m^2)",
    )
    speed_fluctuation: float = speed_fluctuation()


def validate_model(model: type[BaseModel], raw: dict) -> dict:
    """Validate a raw config mapping against a whole-config model; a nested dict of SI values.

    Raises
    ------
    ConfigError
        One line naming the key, the value and what is admissible.
    """
    try:
        validated = model.model_validate(raw)
    except ValidationError as exc:
        raise ConfigError(_one_line(exc, model)) from None
    return validated.model_dump(by_alias=True)


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
    if kind == "rotorkin_range":
        return f"{loc} = {value!r} is not admissible: {err['msg']}"
    msg = err["msg"]
    if isinstance(value, dict):
        value = "{...}"
    if kind in _BOUND_ERRORS:
        # the value is SI here: shown in the unit people read, with the field's own range
        field = _field(model, err["loc"])
        unit_kind = _kind(field)
        described = (field.description or "") if field is not None else ""
        ranges = re.findall(r"\(([^()]*<[^()]*)\)", described)
        rng = ranges[-1] if ranges else ""
        bound = err.get("ctx", {})
        limit = ", ".join(f"{_BOUND_ERRORS[kind]} {display_value(v, unit_kind)}"
                          for v in bound.values())  # fmt: skip
        return f"{loc} = {display_value(value, unit_kind)} is not admissible: {rng or limit}"
    return f"{loc} = {value!r} is not admissible: {msg[0].lower()}{msg[1:]}"


#: pydantic's bound errors -> the relation the value must satisfy.
_BOUND_ERRORS = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<",
                 "less_than_equal": "<="}  # fmt: skip


def _field(model, loc):
    parent = _submodel(model, loc[:-1])
    return next((f for n, f in parent.model_fields.items() if loc[-1] in (n, f.alias)), None)


def _kind(field) -> str | None:
    """The quantity kind of a field (its unit validator's), in its metadata or annotation."""
    if field is None:
        return None
    kinds = [getattr(m.func, "kind", None) for m in field.metadata if hasattr(m, "func")]
    return kinds[0] if kinds and kinds[0] else annotation_kind(field.annotation)


def annotation_kind(annotation) -> str | None:
    """Quantity kind carried by a unit validator anywhere in an annotation, or None."""
    for meta in getattr(annotation, "__metadata__", ()):
        kind = getattr(getattr(meta, "func", None), "kind", None)
        if kind:
            return kind
    for arg in typing.get_args(annotation):
        kind = annotation_kind(arg)
        if kind:
            return kind
    return None


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
