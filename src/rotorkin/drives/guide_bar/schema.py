"""Config schema of the differential vane pump on the rotating guide bars + gears."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from rotorkin.core.bounds import (
    INERTIA_MAX,
    TORQUE_MAX,
    gear_pressure_angle,
)
from rotorkin.core.schema import (
    Angle,
    ContactSection,
    ExportSection,
    Inertia,
    Length,
    LimitsSection,
    RunSection,
    Section,
    Speed,
    Torque,
)
from rotorkin.machines.schema import PumpPorts, VanePumpSection

#: Admissible mechanism coefficient lambda [-]: near 1 the guide bar's speed ratio
#: (1 + lambda) / (1 - lambda) grows without bound.
LAMBDA_MIN, LAMBDA_MAX = 0.01, 0.99
#: Admissible gear ratios u and i12 [-].
GEAR_RATIO_MIN, GEAR_RATIO_MAX = 0.1, 10.0
TWO_PI = 6.283185307179586
#: Admissible crank length and gear pitch radii [m] (a watch's wheels to a press drive's).
DRIVE_LENGTH_MIN, DRIVE_LENGTH_MAX = 1e-3, 1.0
#: Admissible gear face width [m].
FACE_WIDTH_MIN, FACE_WIDTH_MAX = 1e-3, 0.5
#: Admissible pressure angle [rad]: 10 deg to 35 deg (involute spur gears; standard 20 deg).
#: The gears' pressure angle range [rad] (:func:`rotorkin.core.bounds.gear_pressure_angle`).
PRESSURE_ANGLE_MIN, PRESSURE_ANGLE_MAX = 0.17453292519943295, 0.6108652381980153


# --- rotating guide bars + gears ------------------------------------------------------------
class GuideBarDrive(Section):
    type: Literal["guide_bar"]
    lam: float = Field(
        alias="lambda",
        ge=LAMBDA_MIN,
        le=LAMBDA_MAX,
        description="mechanism coefficient lambda = d/a (frame over crank length) "
        "(0.01 <= lambda <= 0.99: at 1 the guide bar stops turning fully round)",
    )
    gear_ratio: float = Field(
        ge=GEAR_RATIO_MIN,
        le=GEAR_RATIO_MAX,
        description="ratio u from the guide-bar gear to the impeller gear (0.1 <= u <= 10)",
    )
    input_gear_ratio: float = Field(
        2.0,
        ge=GEAR_RATIO_MIN,
        le=GEAR_RATIO_MAX,
        description="ratio i12 = z2/z1 from input gear 1 (0.1 <= i12 <= 10)",
    )
    phase: Angle = Field(
        "180 deg",
        ge=-TWO_PI,
        le=TWO_PI,
        description="installation phase Sigma = sigma_2 - sigma_1 (-360 deg <= Sigma <= 360 deg, "
        "not a multiple of 360 deg)",
    )
    driver: Literal["crank", "guide"] = Field(
        "crank", description="driving member: crank (paper Fig. 2) or guide (Fig. 4)"
    )
    # sizes for the forces in the pairs (the paper's drive is dimensionless; ours)
    crank_length: Length = Field(
        "40 mm",
        ge=DRIVE_LENGTH_MIN,
        le=DRIVE_LENGTH_MAX,
        description="crank length a (guide pivot to crank pivot: lambda a); sets the slider "
        "force (1 mm <= a <= 1 m)",
    )
    input_pitch_radius: Length = Field(
        "25 mm",
        ge=DRIVE_LENGTH_MIN,
        le=DRIVE_LENGTH_MAX,
        description="pitch radius r1 of input gear 1; gears 2 and 9 on the driving members have "
        "i12 r1 (1 mm <= r1 <= 1 m)",
    )
    output_pitch_radius: Length = Field(
        "30 mm",
        ge=DRIVE_LENGTH_MIN,
        le=DRIVE_LENGTH_MAX,
        description="pitch radius r6 of gears 6 and 11 on the driven members; the impeller gears "
        "7 and 8 have u r6 (1 mm <= r6 <= 1 m)",
    )
    face_width: Length = Field(
        "20 mm",
        ge=FACE_WIDTH_MIN,
        le=FACE_WIDTH_MAX,
        description="face width of every gear, for the Hertz pressure of the meshes "
        "(1 mm <= b <= 500 mm)",
    )
    pressure_angle: Angle = gear_pressure_angle("pressure angle alpha of the involute spur gears")


class GuideBarLoads(PumpPorts):
    impeller_torque_1: Torque = Field(
        "10 N*m",
        ge=0.0,
        le=TORQUE_MAX,
        description="resisting torque M7 on impeller 1 (0 <= M7 <= 1e6 N*m)",
    )
    impeller_torque_2: Torque = Field(
        "10 N*m",
        ge=0.0,
        le=TORQUE_MAX,
        description="resisting torque M8 on impeller 2 (0 <= M8 <= 1e6 N*m)",
    )


class VanePumpMachine(VanePumpSection):
    inertia_shaft: Inertia = Field(
        "0.001 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of the input shaft (0 <= J <= 1e5 kg*m^2)",
    )
    vane_angle: Angle | None = Field(
        None,
        ge=0.0017453292519943296,
        lt=3.141592653589793,
        description="angular width of a vane; default: the drive's gamma_0 "
        "(0.1 deg <= vane_angle < 180 deg, and Z (2 vane_angle + swing) <= 360 deg)",
    )


class Run(RunSection):
    speed: Speed = Field(
        "1500 rpm",
        description="input shaft speed: one value, or a list sampled evenly over one period",
    )


class GuideBarConfig(Section):
    title: str = ""
    drive: GuideBarDrive
    machine: VanePumpMachine = Field(default_factory=VanePumpMachine)
    loads: GuideBarLoads = Field(default_factory=GuideBarLoads)
    contact: ContactSection = Field(default_factory=ContactSection)
    limits: LimitsSection = Field(default_factory=LimitsSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: Run = Field(default_factory=Run)
