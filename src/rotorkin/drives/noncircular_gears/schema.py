"""Config schema of the non-circular gear drive (any vane machine; twin-rotor engine default)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from rotorkin.core.bounds import LENGTH_MAX, gear_pressure_angle
from rotorkin.core.schema import (
    Angle,
    ContactSection,
    ExportSection,
    Length,
    LimitsSection,
    RunSection,
    Section,
)
from rotorkin.machines.schema import EngineLoads, TwinRotorMachine


class NoncircularDrive(Section):
    type: Literal["noncircular_gears"]
    lobes: int = Field(
        2, ge=1, le=12, description="lobes n of the driving gears on the shaft (1 <= n <= 12)"
    )
    rotor_lobes: int = Field(
        2,
        ge=1,
        le=12,
        description="lobes m of the driven gears on the rotors (1 <= m <= 12); the rotors turn "
        "n/m times per shaft turn",
    )
    eccentricity: float = Field(
        0.2,
        ge=0.0,
        lt=1.0,
        description="eccentricity e of the driving pitch curve r = p/(1 - e cos n phi) "
        "(0 <= e < 1, and both pitch curves convex: e <= 1/(n^2 - 1) for n >= 2)",
    )
    centre_distance: Length = Field(
        "120 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="distance between the shaft and the rotors' axis (1 mm <= a <= 10 m)",
    )
    phase: Angle | None = Field(
        None,
        ge=-6.283185307179586,
        le=6.283185307179586,
        description="angle between the two driving gears on the shaft (-360 deg <= phase <= "
        "360 deg); default 180 deg / n (the two speed ratios in antiphase: the largest swing)",
    )
    pressure_angle: Angle = gear_pressure_angle(
        "pressure angle of the gear-cutting tool; the pitch curves' inclination adds to it"
    )
    face_width: Length = Field(
        "20 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="face width of the gears, for the exported pitch-curve plates "
        "(1 mm <= face_width <= 10 m)",
    )


class NoncircularConfig(Section):
    title: str = ""
    drive: NoncircularDrive
    machine: TwinRotorMachine = Field(default_factory=TwinRotorMachine)
    loads: EngineLoads = Field(default_factory=EngineLoads)
    contact: ContactSection = Field(default_factory=ContactSection)
    limits: LimitsSection = Field(default_factory=LimitsSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)
