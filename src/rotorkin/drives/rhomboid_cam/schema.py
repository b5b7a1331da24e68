"""Config schema of the rotary-blade engine on the rhomboid linkage + cam."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from rotorkin.core.bounds import (
    LENGTH_MAX,
    TORQUE_MAX,
)
from rotorkin.core.schema import (
    Angle,
    ContactSection,
    ExportSection,
    Length,
    LimitsSection,
    RunSection,
    Section,
    Speed,
    Torque,
)
from rotorkin.machines.schema import RotaryBladeSection, StirlingGas

#: Most harmonics a3.. (b3..) of the law psi(alpha).
MAX_HARMONICS = 20  # as rotorkin.drives.rhomboid_cam.kinematics.MAX_HARMONICS
#: One coefficient of psi(alpha) [rad].
Coefficient = Annotated[float, Field(ge=-3.141592653589793, le=3.141592653589793)]


class PlanarCamSection(Section):
    roller_radius: Length = Field(
        "10 mm",
        ge=0.0,
        le=1.0,
        description="radius of the rollers on the cam (0 <= roller_radius <= 1 m, no undercut "
        "of the cam, checked as by `rotorkin export`)",
    )
    thickness: Length = Field(
        "20 mm",
        description="axial thickness of the cam plate (0 < thickness <= the cam's outer diameter)",
    )


# --- rhomboid linkage on a cam --------------------------------------------------------------
class RhomboidDrive(Section):
    type: Literal["rhomboid_cam"]
    link_length: Length = Field(
        ge=0.001, le=LENGTH_MAX, description="side 2l of the rhomboid (1 mm <= 2l <= 10 m)"
    )
    psi_min: Angle = Field(
        gt=0.0,
        lt=1.5707963267948966,
        description="smallest angle psi_min between the blade axes (0 deg < psi_min < 90 deg)",
    )
    a: list[Coefficient] = Field(
        default_factory=list,
        max_length=MAX_HARMONICS,
        description="cosine coefficients a3, a5, ... of psi(alpha) [rad] (at most 20, each "
        "-pi <= a <= pi rad, psi kept within its range)",
    )
    b: list[Coefficient] = Field(
        default_factory=list,
        max_length=MAX_HARMONICS,
        description="sine coefficients b3, b5, ... of psi(alpha) [rad] (at most 20, each "
        "-pi <= b <= pi rad, psi kept within its range)",
    )


class RhomboidLoads(StirlingGas):
    torque_high: Torque = Field(
        "100 N*m",
        ge=-TORQUE_MAX,
        le=TORQUE_MAX,
        description="torque level M1 of the linear blade model (|M1| <= 1e6 N*m)",
    )
    torque_low: Torque = Field(
        "40 N*m",
        ge=-TORQUE_MAX,
        le=TORQUE_MAX,
        description="torque level M2 of the linear blade model (|M2| <= 1e6 N*m)",
    )
    pressure_model: Literal["linear", "adiabatic", "schmidt", "isothermal"] = Field(
        "linear",
        description="blade loads: the paper's linear torque model (eq. 29), or a gas model of "
        "the machine: adiabatic or schmidt (hot and cold blade sets joined by heater, "
        "regenerator and cooler) or isothermal (each chamber's own gas)",
    )


class RotaryBladeMachine(RotaryBladeSection):
    blade_thickness: Angle = Field(
        "10 deg",
        gt=0.0,
        lt=1.5707963267948966,
        description="angular thickness of one blade (0 deg < blade_thickness < psi_min)",
    )


class Run(RunSection):
    speed: Speed = Field(
        "1500 rpm",
        description="input shaft speed: one value, or a list sampled evenly over one period",
    )


class RhomboidConfig(Section):
    title: str = ""
    drive: RhomboidDrive
    machine: RotaryBladeMachine = Field(default_factory=RotaryBladeMachine)
    loads: RhomboidLoads = Field(default_factory=RhomboidLoads)
    cam: PlanarCamSection = Field(default_factory=PlanarCamSection)
    contact: ContactSection = Field(default_factory=ContactSection)
    limits: LimitsSection = Field(default_factory=LimitsSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: Run = Field(default_factory=Run)


def with_defaults(cfg: dict) -> dict:
    """``cfg`` with the machine, loads, run, cam and contact keys it lacks filled from the
    schema (the study's and the sweep kernel's view of a validated config)."""
    out = dict(cfg)
    for name, model in (("machine", RotaryBladeMachine), ("loads", RhomboidLoads),
                        ("run", RunSection), ("cam", PlanarCamSection),
                        ("contact", ContactSection)):  # fmt: skip
        out[name] = {**model().model_dump(), **cfg.get(name, {})}
    return out
