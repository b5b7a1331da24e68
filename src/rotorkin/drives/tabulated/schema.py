"""Config schema of the tabulated drive: member angles from a CSV table or a Fourier series."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator
from pydantic_core import PydanticCustomError

from rotorkin.core.schema import (
    Angle,
    ContactSection,
    ExportSection,
    LimitsSection,
    RunSection,
    Section,
)
from rotorkin.machines.schema import EngineLoads, TwinRotorMachine

#: Most harmonics of a Fourier law or of a table's fit.
MAX_HARMONICS = 1000
#: One Fourier coefficient [rad].
Coefficient = Annotated[float, Field(ge=-1000.0, le=1000.0)]


class TabulatedDrive(Section):
    type: Literal["tabulated"]
    table: str | None = Field(
        None,
        json_schema_extra={"path": True},
        description="CSV file of shaft angle, member 1 angle, member 2 angle with units in the "
        "header (e.g. theta [deg]); one period dividing the turn, both ends included, even "
        "steps; a relative path is read from the config file's folder",
    )
    columns: list[str] | None = Field(
        None,
        min_length=3,
        max_length=3,
        description="the three columns of the table to read (default: the first three), e.g. "
        "rotorkin's own motion.csv: theta_deg, rotor1_angle_deg, rotor2_angle_deg",
    )
    harmonics: int | None = Field(
        None,
        ge=1,
        le=MAX_HARMONICS,
        description="fit the table with this many harmonics by least squares (measured, noisy "
        "data); default: the exact trigonometric interpolation of the table",
    )
    period: Angle | None = Field(
        None,
        gt=0.0,
        le=6.283185307179587,
        description="Fourier law instead of a table: its period, 360 deg / k "
        "(0 deg < period <= 360 deg)",
    )
    mean_ratio: list[float] | None = Field(
        None,
        min_length=2,
        max_length=2,
        description="Fourier law: each member's mean speed over the shaft's (two numbers)",
    )
    offset: list[Angle] = Field(
        default_factory=lambda: ["0 deg", "0 deg"],
        min_length=2,
        max_length=2,
        description="Fourier law: each member's constant angle (two angles)",
    )
    a1: list[Coefficient] = Field(
        default_factory=list,
        max_length=MAX_HARMONICS,
        description="Fourier law: member 1 cosine coefficients of harmonics 1, 2, ... [rad]",
    )
    b1: list[Coefficient] = Field(
        default_factory=list,
        max_length=MAX_HARMONICS,
        description="Fourier law: member 1 sine coefficients of harmonics 1, 2, ... [rad]",
    )
    a2: list[Coefficient] = Field(
        default_factory=list,
        max_length=MAX_HARMONICS,
        description="Fourier law: member 2 cosine coefficients of harmonics 1, 2, ... [rad]",
    )
    b2: list[Coefficient] = Field(
        default_factory=list,
        max_length=MAX_HARMONICS,
        description="Fourier law: member 2 sine coefficients of harmonics 1, 2, ... [rad]",
    )

    @model_validator(mode="after")
    def _one_source(self):
        fourier = self.period is not None or self.mean_ratio is not None
        if (self.table is None) == (not fourier):
            raise PydanticCustomError(
                "rotorkin_range",
                "give either drive.table (a CSV file) or a Fourier law (drive.period, "
                "drive.mean_ratio and the coefficients), not both and not neither",
            )
        if fourier and (self.period is None or self.mean_ratio is None):
            raise PydanticCustomError(
                "rotorkin_range", "a Fourier law needs drive.period and drive.mean_ratio"
            )
        return self


class TabulatedConfig(Section):
    title: str = ""
    drive: TabulatedDrive
    machine: TwinRotorMachine = Field(default_factory=TwinRotorMachine)
    loads: EngineLoads = Field(default_factory=EngineLoads)
    contact: ContactSection = Field(default_factory=ContactSection)
    limits: LimitsSection = Field(default_factory=LimitsSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)
