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
    SpecificEnergy,
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
    "vane_pump": "differential vane pump: Z vanes on each impeller, leakage and port losses",
    "rotary_blade": "rotary-blade Stirling engine: B blades per pair, hot and cold blade sets",
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
    model: Literal["fuel_air", "ideal"] = Field(
        "fuel_air",
        description="cycle of the chambers: 'fuel_air' (the charge trapped at intake closure "
        "burns by a Wiebe law, heat goes to the walls, properties vary with temperature) or "
        "'ideal' (the air-standard Otto cycle: a fixed heat_per_cycle at the dead centre, "
        "polytropic strokes; the papers' comparisons)",
    )
    ambient_pressure: Pressure = Field(
        "1 bar",
        ge=1e3,
        le=1e7,
        description="exhaust pressure; also the intake pressure of the ideal cycle "
        "(0.01 bar <= p <= 100 bar, absolute)",
    )
    polytropic_exponent: float = Field(
        1.35,
        gt=1.0,
        le=5.0 / 3.0,
        description="ideal cycle: exponent n of compression and expansion, p V^n = const "
        "(1 < n <= 5/3)",
    )
    heat_per_cycle: Energy = Field(
        "90 J",
        ge=0.0,
        le=1e6,
        description="ideal cycle: heat added at minimum volume, per chamber and four-stroke "
        "cycle (0 <= Q <= 1 MJ)",
    )
    intake_pressure: Pressure = Field(
        "1 bar",
        ge=1e3,
        le=1e7,
        description="fuel-air cycle: pressure of the charge at intake closure; above ambient "
        "for a supercharged engine (0.01 bar <= p <= 100 bar, absolute)",
    )
    intake_temperature: Temperature = Field(
        "320 K",
        ge=200.0,
        le=1000.0,
        description="fuel-air cycle: temperature of the charge at intake closure "
        "(200 K <= T <= 1000 K)",
    )
    residual_fraction: float = Field(
        0.05,
        ge=0.0,
        le=0.5,
        description="fuel-air cycle: mass fraction of burnt gas left in the charge "
        "(0 <= x_r <= 0.5)",
    )
    equivalence_ratio: float = Field(
        1.0,
        ge=0.2,
        le=2.0,
        description="fuel-air cycle: fuel-air ratio over the stoichiometric one; above 1 only "
        "the fuel the air can burn releases heat (0.2 <= phi <= 2)",
    )
    fuel_heating_value: SpecificEnergy = Field(
        "44 MJ/kg",
        ge=1e6,
        le=1.5e8,
        description="fuel-air cycle: lower heating value of the fuel; gasoline 44 MJ/kg, "
        "methanol 20 MJ/kg, hydrogen 120 MJ/kg (1 MJ/kg <= LHV <= 150 MJ/kg)",
    )
    stoichiometric_afr: float = Field(
        14.6,
        ge=1.0,
        le=100.0,
        description="fuel-air cycle: air-fuel mass ratio of the stoichiometric mixture; "
        "gasoline 14.6, methanol 6.5, hydrogen 34.3 (1 <= AFR_s <= 100)",
    )
    fuel_hc_ratio: float = Field(
        1.87,
        ge=0.0,
        le=4.0,
        description="fuel-air cycle: hydrogen-to-carbon atom ratio of the fuel, for the burnt "
        "gas's composition; gasoline 1.87, methane 4 (0 <= y <= 4)",
    )
    combustion_efficiency: float = Field(
        0.97,
        gt=0.0,
        le=1.0,
        description="fuel-air cycle: fraction of the fuel's energy released (0 < eta_c <= 1)",
    )
    burn_start: Angle = Field(
        "-10 deg",
        ge=-3.141592653589793,
        le=3.141592653589793,
        description="fuel-air cycle: start of the burn in the chamber's cycle angle (180 deg "
        "per stroke), from the dead centre of smallest volume, negative before it "
        "(-180 deg <= start <= 180 deg)",
    )
    burn_duration: Angle = Field(
        "50 deg",
        ge=0.0017453292519943296,
        le=3.141592653589793,
        description="fuel-air cycle: duration of the burn (Wiebe, 99.3 % burnt at a = 5) in the "
        "chamber's cycle angle (0.1 deg <= duration <= 180 deg, start + duration <= 180 deg)",
    )
    wiebe_a: float = Field(
        5.0, ge=0.1, le=20.0,
        description="fuel-air cycle: Wiebe efficiency parameter a (0.1 <= a <= 20)",
    )  # fmt: skip
    wiebe_m: float = Field(
        2.0, ge=0.0, le=10.0,
        description="fuel-air cycle: Wiebe form factor m (0 <= m <= 10)",
    )  # fmt: skip
    heat_transfer: Literal["woschni", "none"] = Field(
        "woschni",
        description="fuel-air cycle: heat transfer to the walls, 'woschni' (Woschni's "
        "correlation, wall area from the chamber) or 'none' (adiabatic)",
    )
    wall_temperature: Temperature = Field(
        "450 K",
        ge=250.0,
        le=1500.0,
        description="fuel-air cycle: temperature of the chamber walls (250 K <= T_w <= 1500 K)",
    )
    gas_properties: Literal["auto", "nasa", "constant"] = Field(
        "auto",
        description="fuel-air cycle: 'nasa' (NASA polynomials of air and the burnt gas, "
        "GRI-Mech 3.0 data), 'constant' (one ratio of specific heats, specific_heat_ratio) "
        "or 'auto' (the same as nasa)",
    )
    specific_heat_ratio: float = Field(
        1.3,
        gt=1.0,
        le=5.0 / 3.0,
        description="fuel-air cycle with gas_properties = 'constant': c_p / c_v of the gas "
        "(1 < gamma <= 5/3)",
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
    port_land: Angle = Field(
        "0 deg",
        ge=0.0,
        le=62.83185307179586,  # ten turns; the drive's shortest stroke is checked on it
        description="sealing land of the ports: the shaft angle round each turning point of the "
        "relative angle during which every chamber is closed to both ports (its fluid trapped); "
        "0: ideal ports (0 deg <= port_land < the shortest stroke, the shaft angle between two "
        "turning points; > 0 needs a dead volume, a vane_angle below the widest; "
        "port_land <= 3600 deg)",
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
        "switch to the outlet and the pressure of a trapped chamber; 1.5 GPa: mineral oil "
        "(0.01 GPa <= K <= 100 GPa)",
    )
    vapour_pressure: Pressure = Field(
        "0.1 bar",
        ge=0.0,
        le=PRESSURE_MAX,
        description="cavitation floor, absolute: a warning when the pressure of a chamber closed "
        "by machine.port_land falls below it; 0.1 bar: a cautious gas-release pressure of "
        "mineral oil (its vapour pressure proper is far lower) (0 bar <= p_v <= 1000 bar)",
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
