"""Config schema of the rotary-blade engine on the rhomboid linkage + cam."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from rotorkin.core.schema import (
    Angle,
    ExportSection,
    Inertia,
    InertialSection,
    Length,
    Pressure,
    RunSection,
    Section,
    Speed,
    Temperature,
    Torque,
)


class PlanarCamSection(Section):
    roller_radius: Length = Field("10 mm", description="radius of the rollers on the cam")
    thickness: Length = Field("20 mm", description="axial thickness of the cam plate")


# --- rhomboid linkage on a cam --------------------------------------------------------------
class RhomboidDrive(Section):
    type: Literal["rhomboid_cam"]
    link_length: Length = Field(description="side 2l of the rhomboid")
    psi_min: Angle = Field(description="smallest angle psi_min between the blade axes")
    a: list[float] = Field(
        default_factory=list, description="cosine coefficients a3, a5, ... of psi(alpha) [rad]"
    )
    b: list[float] = Field(
        default_factory=list, description="sine coefficients b3, b5, ... of psi(alpha) [rad]"
    )


class RhomboidLoads(Section):
    torque_high: Torque = Field("100 N*m", description="torque level M1 of the linear blade model")
    torque_low: Torque = Field("40 N*m", description="torque level M2 of the linear blade model")
    pressure_model: Literal["linear", "isothermal"] = Field(
        "linear", description="blade loads: the paper's linear torque model or isothermal gas"
    )
    charge_pressure: Pressure = Field(
        "2 bar", description="isothermal model: pressure at the largest volume, cold"
    )
    hot_temperature: Temperature = Field("900 K", description="isothermal model: expansion")
    cold_temperature: Temperature = Field("330 K", description="isothermal model: compression")


class RotaryBladeMachine(InertialSection):
    inertia_shaft: Inertia = Field("0.01 kg*m^2", description="inertia of the input shaft")
    blades_per_pair: int = Field(2, description="blades on each of the two blade pairs")
    blade_thickness: Angle = Field("10 deg", description="angular thickness of one blade")
    inner_radius: Length = Field("30 mm", description="hub radius of the working space")
    outer_radius: Length = Field("90 mm", description="casing radius of the working space")
    axial_width: Length = Field("50 mm", description="axial width of the working space")
    inertia_blade_pair_1: Inertia = Field("0.005 kg*m^2", description="inertia of blade pair 1")
    inertia_blade_pair_2: Inertia = Field("0.005 kg*m^2", description="inertia of blade pair 2")


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
    export: ExportSection = Field(default_factory=ExportSection)
    run: Run = Field(default_factory=Run)
