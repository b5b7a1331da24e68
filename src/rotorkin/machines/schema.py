"""Config sections of the vane machines, shared by every drive that carries them.

A rotary two-member drive (two coaxial rotors turned by one shaft) carries any of
the three vane machines; ``[machine] type`` names it. These sections are the
machines' keys and defaults wherever they run; a drive's own schema may extend
them (the paper's load models, descriptions naming the drive's parts).
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from rotorkin.core.bounds import (
    INERTIA_MAX,
    LENGTH_MAX,
    PRESSURE_MAX,
    PRESSURE_MIN,
    TEMPERATURE_MAX,
    TEMPERATURE_MIN,
)
from rotorkin.core.schema import (
    Angle,
    Energy,
    Inertia,
    InertialSection,
    Length,
    Modulus,
    Pressure,
    Section,
    Temperature,
    Volume,
)

__all__ = [
    "VANE_MACHINES",
    "machine_type",
    "TwinRotorMachine",
    "EngineLoads",
    "VanePumpSection",
    "PumpPorts",
    "RotaryBladeSection",
    "StirlingGas",
]

#: The vane machines and what each is, in the order of the help.
VANE_MACHINES = {
    "twin_rotor": "twin-rotor four-stroke engine: N vane pistons on each rotor",
    "vane_pump": "differential vane pump: Z vanes on each impeller, ideal ports",
    "rotary_blade": "rotary-blade Stirling engine: B blades per pair, isothermal gas",
}
#: Largest compression ratio [-]: 1e6 stands for pistons of zero width (the drive alone).
COMPRESSION_RATIO_MAX = 1e6


def machine_type(name: str):
    """The ``machine.type`` field of a machine section whose type is ``name``."""
    return Field(
        name,
        description="the machine the drive moves: "
        + ", ".join(VANE_MACHINES)
        + " (any drive that turns two coaxial members carries any of them); a drive of "
        "pistons carries its own machine (opposed_piston)",
    )


class TwinRotorMachine(InertialSection):
    type: Literal["twin_rotor"] = machine_type("twin_rotor")
    compression_ratio: float = Field(
        10.0,
        gt=1.0,
        le=COMPRESSION_RATIO_MAX,
        description="compression ratio eps = delta_max / delta_min of the chamber angles "
        "; the geometric volume ratio when there is no clearance volume "
        "(1 < eps <= 1e6; eps = 1e6 stands for zero-width pistons, the drive alone; above the "
        "ratio of zero-width pistons over the drive's swing)",
    )
    pistons_per_rotor: int = Field(
        4, ge=2, le=24, description="vane pistons on each rotor (even, 2 <= N <= 24)"
    )
    section: Literal["rectangular", "circular"] = Field(
        "rectangular", description="cylinder section: rectangular annulus or circular torus"
    )
    inner_radius: Length = Field(
        "40 mm",
        ge=0.001,
        le=10.0,
        description="inner radius of a rectangular annulus (1 mm <= inner_radius < outer_radius)",
    )
    outer_radius: Length = Field(
        "80 mm",
        ge=0.001,
        le=10.0,
        description="outer radius of a rectangular annulus (inner_radius < outer_radius <= 10 m)",
    )
    axial_width: Length = Field(
        "40 mm",
        ge=0.001,
        le=10.0,
        description="axial width of a rectangular annulus (1 mm <= axial_width <= 10 m)",
    )
    mean_radius: Length = Field(
        "60 mm",
        ge=0.001,
        le=10.0,
        description="mean radius of a circular torus (1 mm <= mean_radius <= 10 m)",
    )
    section_diameter: Length = Field(
        "40 mm",
        ge=0.001,
        le=10.0,
        description="section diameter of a circular torus "
        "(1 mm <= section_diameter < 2 mean_radius)",
    )
    clearance_volume: Volume = Field(
        "0 cm^3",
        ge=0.0,
        le=1.0,
        description="clearance volume of each chamber (0 <= clearance_volume <= 1 m^3)",
    )
    inertia_shaft: Inertia = Field(
        "0.004 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of the input shaft with the drive's parts on it "
        "(0 <= J <= 1e5 kg*m^2)",
    )
    inertia_rotor_1: Inertia = Field(
        "0.008 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of rotor 1 (0 <= J <= 1e5 kg*m^2)",
    )
    inertia_rotor_2: Inertia = Field(
        "0.008 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of rotor 2 (0 <= J <= 1e5 kg*m^2)",
    )


class EngineLoads(Section):
    ambient_pressure: Pressure = Field(
        "1 bar",
        ge=1e3,
        le=1e7,
        description="intake and exhaust pressure (0.01 bar <= p <= 100 bar, absolute)",
    )
    polytropic_exponent: float = Field(
        1.35,
        gt=1.0,
        le=5.0 / 3.0,
        description="exponent n of compression and expansion, p V^n = const (1 < n <= 5/3)",
    )
    heat_per_cycle: Energy = Field(
        "90 J",
        ge=0.0,
        le=1e6,
        description="heat added at minimum volume, per chamber and four-stroke cycle "
        "(0 <= Q <= 1 MJ)",
    )


class VanePumpSection(InertialSection):
    type: Literal["vane_pump"] = machine_type("vane_pump")
    inertia_shaft: Inertia = Field(
        "0.001 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of the input shaft (0 <= J <= 1e5 kg*m^2)",
    )
    vanes_per_impeller: int = Field(
        2, ge=1, le=24, description="vanes on each impeller (1 <= Z <= 24, room for the swing)"
    )
    vane_angle: Angle | None = Field(
        None,
        ge=0.0017453292519943296,
        lt=3.141592653589793,
        description="angular width of a vane; default: the widest that fits the drive's swing "
        "(0.1 deg <= vane_angle < 180 deg, and Z (2 vane_angle + swing) <= 360 deg)",
    )
    hub_radius: Length = Field(
        "30 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="impeller hub radius (1 mm <= hub_radius < casing_radius)",
    )
    casing_radius: Length = Field(
        "80 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="casing (vane tip) radius (hub_radius < casing_radius <= 10 m)",
    )
    axial_width: Length = Field(
        "40 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="axial width of the working space (1 mm <= axial_width <= 10 m)",
    )
    inertia_impeller_1: Inertia = Field(
        "0.005 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of impeller 1 (0 <= J <= 1e5 kg*m^2)",
    )
    inertia_impeller_2: Inertia = Field(
        "0.005 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of impeller 2 (0 <= J <= 1e5 kg*m^2)",
    )
    tip_clearance: Length = Field(
        "0 mm",
        ge=0.0,
        le=1.0e-3,
        description="radial gap between a vane tip and the casing, for the laminar leakage; "
        "0: no leakage (0 mm <= tip_clearance <= 1 mm)",
    )
    side_clearance: Length = Field(
        "0 mm",
        ge=0.0,
        le=1.0e-3,
        description="axial gap between each side face of a vane and its end cover, for the "
        "laminar leakage; 0: no leakage (0 mm <= side_clearance <= 1 mm)",
    )
    hub_clearance: Length = Field(
        "0 mm",
        ge=0.0,
        le=1.0e-3,
        description="radial gap between a vane root and the other impeller's hub, for the "
        "laminar leakage; 0: no leakage (0 mm <= hub_clearance <= 1 mm)",
    )


class PumpPorts(Section):
    suction_pressure: Pressure = Field(
        "1 bar",
        ge=PRESSURE_MIN,
        le=PRESSURE_MAX,
        description="pressure at the inlet port (0.01 bar <= p <= 1000 bar, absolute)",
    )
    discharge_pressure: Pressure = Field(
        "6 bar",
        ge=PRESSURE_MIN,
        le=PRESSURE_MAX,
        description="pressure at the outlet port (0.01 bar <= p <= 1000 bar, absolute)",
    )
    fluid_viscosity: float = Field(
        0.03,
        ge=1.0e-4,
        le=10.0,
        description="dynamic viscosity of the fluid in Pa*s, for the leakage through the vane "
        "clearances; 0.03: mineral oil ISO VG 32 at 40 C (0.0001 <= mu <= 10 Pa*s)",
    )
    bulk_modulus: Modulus = Field(
        "1.5 GPa",
        ge=1.0e7,
        le=1.0e11,
        description="bulk modulus of the fluid, for the flow lost compressing a chamber at the "
        "switch to the outlet; 1.5 GPa: mineral oil (0.01 GPa <= K <= 100 GPa)",
    )


class RotaryBladeSection(InertialSection):
    type: Literal["rotary_blade"] = machine_type("rotary_blade")
    inertia_shaft: Inertia = Field(
        "0.01 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of the input shaft (0 <= J <= 1e5 kg*m^2)",
    )
    blades_per_pair: int = Field(
        2, ge=1, le=12, description="blades on each of the two blade pairs (1 <= B <= 12)"
    )
    blade_thickness: Angle = Field(
        "10 deg",
        gt=0.0,
        lt=1.5707963267948966,
        description="angular thickness of one blade "
        "(0 deg < blade_thickness, with room for the drive's swing)",
    )
    inner_radius: Length = Field(
        "30 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="hub radius of the working space (1 mm <= inner_radius < outer_radius)",
    )
    outer_radius: Length = Field(
        "90 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="casing radius of the working space (inner_radius < outer_radius <= 10 m)",
    )
    axial_width: Length = Field(
        "50 mm",
        ge=0.001,
        le=LENGTH_MAX,
        description="axial width of the working space (1 mm <= axial_width <= 10 m)",
    )
    inertia_blade_pair_1: Inertia = Field(
        "0.005 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of blade pair 1 (0 <= J <= 1e5 kg*m^2)",
    )
    inertia_blade_pair_2: Inertia = Field(
        "0.005 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="inertia of blade pair 2 (0 <= J <= 1e5 kg*m^2)",
    )


class StirlingGas(Section):
    pressure_model: Literal["adiabatic", "schmidt", "isothermal"] = Field(
        "adiabatic",
        description="gas model: adiabatic (Urieli's ideal adiabatic analysis of each circuit: "
        "the engine's chambers are the hot spaces, a second blade set lagging by phase_angle "
        "the cold ones, joined by heater, regenerator and cooler), schmidt (the same "
        "circuits, isothermal spaces) or isothermal (each chamber's own gas, hot while it "
        "expands, cold while it is compressed: no heat exchangers, an upper bound)",
    )
    charge_pressure: Pressure = Field(
        "2 bar",
        ge=PRESSURE_MIN,
        le=PRESSURE_MAX,
        description="pressure of the gas at its largest volume, all at cold_temperature: of "
        "a circuit (both chambers and the heat exchangers), or of a chamber for the "
        "isothermal model (0.01 bar <= p <= 1000 bar, absolute)",
    )
    hot_temperature: Temperature = Field(
        "900 K",
        ge=TEMPERATURE_MIN,
        le=TEMPERATURE_MAX,
        description="heater gas temperature; isothermal model: gas temperature while a "
        "chamber expands (1 K <= T_hot <= 5000 K)",
    )
    cold_temperature: Temperature = Field(
        "330 K",
        ge=TEMPERATURE_MIN,
        le=TEMPERATURE_MAX,
        description="cooler gas temperature; isothermal model: gas temperature while a "
        "chamber is compressed (1 K <= T_cold <= 5000 K)",
    )
    gas: Literal["air", "helium", "hydrogen"] = Field(
        "air", description="working gas of the adiabatic and schmidt models (R and gamma)"
    )
    phase_angle: Angle = Field(
        "90 deg",
        ge=0.0,
        le=6.283185307179586,
        description="lag of the cold blade set behind the hot one, in degrees of a "
        "chamber's volume cycle (0 deg <= phase_angle <= 360 deg)",
    )
    heater_volume: Volume | None = Field(
        None,
        ge=0.0,
        le=1.0,
        description="gas volume of each circuit's heater (0 <= V <= 1 m^3); default 0.3 x "
        "a chamber's swept volume",
    )
    regenerator_volume: Volume | None = Field(
        None,
        ge=0.0,
        le=1.0,
        description="gas (void) volume of each circuit's regenerator (0 <= V <= 1 m^3); "
        "default 0.4 x a chamber's swept volume",
    )
    cooler_volume: Volume | None = Field(
        None,
        ge=0.0,
        le=1.0,
        description="gas volume of each circuit's cooler (0 <= V <= 1 m^3); default 0.2 x a "
        "chamber's swept volume",
    )
    regenerator_effectiveness: float = Field(
        1.0,
        ge=0.0,
        le=1.0,
        description="share of the regenerator's heat it passes on; the rest loads heater and "
        "cooler (0 <= eps <= 1, 1 ideal)",
    )
