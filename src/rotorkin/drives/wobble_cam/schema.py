"""Config schema of the twin-rotor engine on the wobble plate + spherical cam."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from rotorkin.core.schema import (
    Angle,
    Energy,
    ExportSection,
    Inertia,
    InertialSection,
    Length,
    Pressure,
    RunSection,
    Section,
    Volume,
)


class WobbleCamSection(Section):
    roller_radius: Length = Field("4 mm", description="radius of the rollers in the grooves")
    shell_thickness: Length = Field(
        "12 mm", description="radial thickness of the spherical cam shell, centred on r"
    )
    groove_depth: Length = Field(
        "8 mm", description="radial depth of the grooves, from the shell's inner surface"
    )


# --- wobble plate + spherical cam -----------------------------------------------------------
class WobbleDrive(Section):
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


class WobbleMachine(InertialSection):
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
    inertia_shaft: Inertia = Field(
        "0.004 kg*m^2", description="inertia of the input shaft with the plate and rollers"
    )
    inertia_rotor_1: Inertia = Field("0.008 kg*m^2", description="inertia of rotor 1")
    inertia_rotor_2: Inertia = Field("0.008 kg*m^2", description="inertia of rotor 2")


class EngineLoads(Section):
    ambient_pressure: Pressure = Field("1 bar", description="intake and exhaust pressure")
    polytropic_exponent: float = Field(
        1.35, description="exponent n of compression and expansion, p V^n = const"
    )
    heat_per_cycle: Energy = Field(
        "90 J", description="heat added at minimum volume, per chamber and four-stroke cycle"
    )


class WobbleConfig(Section):
    title: str = ""
    drive: WobbleDrive
    machine: WobbleMachine = Field(default_factory=WobbleMachine)
    loads: EngineLoads = Field(default_factory=EngineLoads)
    cam: WobbleCamSection = Field(default_factory=WobbleCamSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)  # 3000 rpm
