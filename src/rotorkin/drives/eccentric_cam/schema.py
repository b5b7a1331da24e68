"""Config schema of the opposed-piston reactor on the double eccentric cams."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from rotorkin.core.bounds import (
    INERTIA_MAX,
    LENGTH_MAX,
    PRESSURE_MAX,
    PRESSURE_MIN,
)
from rotorkin.core.schema import (
    Angle,
    ContactSection,
    EmptySection,
    ExportSection,
    Inertia,
    InertialSection,
    Length,
    LimitsSection,
    Mass,
    Modulus,
    Pressure,
    RunSection,
    Section,
    Speed,
)
from rotorkin.machines.schema import machine_type


class DiscCamSection(Section):
    thickness: Length = Field(
        "20 mm",
        description="axial thickness of each eccentric disc (0 < thickness <= 2 disc_radius, "
        "the disc's diameter)",
    )


# --- double eccentric cams ------------------------------------------------------------------
class EccentricDrive(Section):
    type: Literal["eccentric_cam"]
    disc_radius: Length = Field(
        ge=0.001, le=LENGTH_MAX, description="radius R of each eccentric disc (1 mm <= R <= 10 m)"
    )
    eccentricity: Length | None = Field(
        None,
        gt=0.0,
        le=LENGTH_MAX,
        description="eccentricity e of the disc centre from the shaft (0 < e < disc_radius); "
        "required, unless inclination and slide set it (e = slide tan(inclination))",
    )
    follower: Literal["knife_edge", "flat", "roller"] = Field(
        "knife_edge", description="piston follower: knife_edge, flat or roller"
    )
    roller_radius: Length = Field(
        "0 mm",
        ge=0.0,
        le=LENGTH_MAX,
        description="roller radius r (follower = roller) (0 <= r <= 10 m; > 0 for a roller)",
    )
    tip_radius: Length = Field(
        "2 mm",
        ge=0.0,
        le=LENGTH_MAX,
        description="tip radius of a knife-edge follower, for its contact stress only "
        "(0 <= tip_radius <= 10 m; 0 or below 1 nm: a sharp edge, no contact stress; the "
        "travel takes the tip as a point, eq. 1)",
    )
    inclination: Angle = Field(
        "0 deg",
        ge=0.0,
        lt=1.5707963267948966,
        description="adjuster (paper's Fig. 2): angle alpha of each disc's own axis to the shaft "
        "(0 deg: off, the paper's circular section; 0 <= alpha < 90 deg); the section in a "
        "piston plane is then an ellipse of semi-axes R/cos(alpha) and R",
    )
    slide: Length | None = Field(
        None,
        gt=0.0,
        le=LENGTH_MAX,
        description="adjuster: axial distance s of the piston plane from the point where the "
        "disc's axis crosses the shaft axis; sets e = s tan(inclination) (0 < slide <= 10 m; "
        "needs inclination > 0; "
        "leave eccentricity out or give the same value)",
    )


class EccentricMachine(InertialSection):
    type: Literal["opposed_piston"] = machine_type("opposed_piston")
    inertia_shaft: Inertia = Field(
        "0.032 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of the input shaft (0 <= J <= 1e5 kg*m^2)",
    )
    device_length: Length = Field(
        "1000 mm",
        ge=0.001,
        le=100.0,
        description="length L of the reactor between the pistons (1 mm <= L <= 100 m; the "
        "pistons keep a gap: L > the gap change of the drive)",
    )
    bore: Length = Field(
        "50 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="piston and tube bore diameter (1 mm <= bore <= 10 m)",
    )
    fluid: Literal["gas", "liquid"] = Field("gas", description="working fluid: gas or liquid")
    initial_pressure: Pressure = Field(
        "1 bar",
        ge=PRESSURE_MIN,
        le=PRESSURE_MAX,
        description="pressure at the starting gap (0.01 bar <= p <= 1000 bar, absolute)",
    )
    polytropic_exponent: float = Field(
        1.0,
        ge=1.0,
        le=5.0 / 3.0,
        description="exponent n of the gas, p V^n = const (1 <= n <= 5/3)",
    )
    bulk_modulus: Modulus = Field(
        "1.5 GPa",
        ge=1e6,
        le=1e12,
        description="bulk modulus K of the liquid (1 MPa <= K <= 1000 GPa)",
    )
    back_pressure: Pressure = Field(
        "0 bar",
        ge=0.0,
        le=PRESSURE_MAX,
        description="absolute pressure on the outer faces of the pistons; the net force on a "
        "piston is (p - back_pressure) A. 0: vacuum, the model of the published numbers; "
        "1 bar: pistons open to the air (0 bar <= back_pressure <= 1000 bar)",
    )
    piston_mass: Mass = Field(
        "0.5 kg",
        ge=0.0,
        le=1e4,
        description="mass of each piston with its rod (0 <= m <= 10 t)",
    )


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
    contact: ContactSection = Field(default_factory=ContactSection)
    limits: LimitsSection = Field(default_factory=LimitsSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: Run = Field(default_factory=Run)
