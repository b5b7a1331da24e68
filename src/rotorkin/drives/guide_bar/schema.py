"""Config schema of the differential vane pump on the rotating guide bars + gears."""

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
    Torque,
)


# --- rotating guide bars + gears ------------------------------------------------------------
class GuideBarDrive(Section):
    type: Literal["guide_bar"]
    lam: float = Field(
        alias="lambda", description="mechanism coefficient lambda = d/a (frame over crank length)"
    )
    gear_ratio: float = Field(description="ratio u from the guide-bar gear to the impeller gear")
    input_gear_ratio: float = Field(2.0, description="ratio i12 = z2/z1 from input gear 1")
    phase: Angle = Field("180 deg", description="installation phase Sigma = sigma_2 - sigma_1")
    driver: Literal["crank", "guide"] = Field(
        "crank", description="driving member: crank (paper Fig. 2) or guide (Fig. 4)"
    )


class GuideBarLoads(Section):
    impeller_torque_1: Torque = Field("10 N*m", description="resisting torque M7 on impeller 1")
    impeller_torque_2: Torque = Field("10 N*m", description="resisting torque M8 on impeller 2")
    suction_pressure: Pressure = Field("1 bar", description="pressure at the inlet port")
    discharge_pressure: Pressure = Field("6 bar", description="pressure at the outlet port")


class VanePumpMachine(InertialSection):
    inertia_shaft: Inertia = Field("0.001 kg*m^2", description="inertia of the input shaft")
    vanes_per_impeller: int = Field(2, description="vanes on each impeller")
    vane_angle: Angle | None = Field(
        None, description="angular width of a vane; default: the drive's gamma_0"
    )
    hub_radius: Length = Field("30 mm", description="impeller hub radius")
    casing_radius: Length = Field("80 mm", description="casing (vane tip) radius")
    axial_width: Length = Field("40 mm", description="axial width of the working space")
    inertia_impeller_1: Inertia = Field("0.005 kg*m^2", description="inertia of impeller 1")
    inertia_impeller_2: Inertia = Field("0.005 kg*m^2", description="inertia of impeller 2")


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
    export: ExportSection = Field(default_factory=ExportSection)
    run: Run = Field(default_factory=Run)
