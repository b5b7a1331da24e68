"""Config schema of the opposed-piston reactor on the double eccentric cams."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from rotorkin.core.schema import (
    EmptySection,
    ExportSection,
    Inertia,
    InertialSection,
    Length,
    Mass,
    Modulus,
    Pressure,
    RunSection,
    Section,
    Speed,
)


class DiscCamSection(Section):
    thickness: Length = Field("20 mm", description="axial thickness of each eccentric disc")


# --- double eccentric cams ------------------------------------------------------------------
class EccentricDrive(Section):
    type: Literal["eccentric_cam"]
    disc_radius: Length = Field(description="radius R of each eccentric disc")
    eccentricity: Length = Field(description="eccentricity e of the disc centre from the shaft")
    follower: Literal["knife_edge", "flat", "roller"] = Field(
        "knife_edge", description="piston follower: knife_edge, flat or roller"
    )
    roller_radius: Length = Field("0 mm", description="roller radius r (follower = roller)")


class EccentricMachine(InertialSection):
    inertia_shaft: Inertia = Field("0.032 kg*m^2", description="inertia of the input shaft")
    device_length: Length = Field(
        "1000 mm", description="length L of the reactor between the pistons"
    )
    bore: Length = Field("50 mm", description="piston and tube bore diameter")
    fluid: Literal["gas", "liquid"] = Field("gas", description="working fluid: gas or liquid")
    initial_pressure: Pressure = Field("1 bar", description="pressure at the starting gap")
    polytropic_exponent: float = Field(1.0, description="exponent n of the gas, p V^n = const")
    bulk_modulus: Modulus = Field("1.5 GPa", description="bulk modulus K of the liquid")
    piston_mass: Mass = Field("0.5 kg", description="mass of each piston with its rod")


class Run(RunSection):
    speed: Speed = Field(
        "600 rpm",
        description="input shaft speed: one value, or a list sampled evenly over one period",
    )


class EccentricConfig(Section):
    title: str = ""
    drive: EccentricDrive
    machine: EccentricMachine = Field(default_factory=EccentricMachine)
    loads: EmptySection = Field(default_factory=EmptySection)
    cam: DiscCamSection = Field(default_factory=DiscCamSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: Run = Field(default_factory=Run)
