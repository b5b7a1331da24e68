"""Config schema of the twin-rotor engine on the wobble plate + spherical cam."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field

from rotorkin.core.bounds import INERTIA_MAX, gear_pressure_angle
from rotorkin.core.schema import (
    Angle,
    ContactSection,
    ExportSection,
    Inertia,
    Length,
    LimitsSection,
    RunSection,
    Section,
)
from rotorkin.machines.schema import EngineLoads, TwinRotorMachine

#: Largest |spin_ratio| [-]: the plate turns at most 20 times per shaft turn.
SPIN_RATIO_MAX = 20.0

#: Smallest plate tilt phi [rad] (0.5 deg, where the paper's Fig. 13 starts): towards 0 the
#: chamber angles stop changing and the pistons' layout needs an unbounded compression ratio.
PLATE_TILT_MIN = 0.5 * math.pi / 180.0

#: Most harmonics of the spin-law correction (spin_a, spin_b): a work cap (each harmonic is
#: evaluated on every sampled angle); synthesised laws use a few dozen.
MAX_SPIN_HARMONICS = 256
HALF_PI = 1.5707963267948966
#: Smallest angle between the roller groups (and 180 deg less the largest) [rad], 1 deg: with
#: 2-piston rotors eq. 20 admits alpha down to 0, where the plate tilt limit degenerates.
ROLLER_AXIS_ANGLE_MIN = 0.017453292519943295
#: One coefficient of the spin-law correction [rad].
Coefficient = Annotated[float, Field(ge=-10.0, le=10.0)]


class WobbleCamSection(Section):
    roller_radius: Length = Field(
        "4 mm",
        ge=1e-4,
        le=0.1,
        description="radius of the rollers in the grooves (0.1 mm <= roller_radius <= 100 mm; "
        "below the groove curvature radius, checked as by `rotorkin export`)",
    )
    shell_thickness: Length = Field(
        "12 mm",
        gt=0.0,
        le=1.0,
        description="radial thickness of the spherical cam shell, centred on r "
        "(0 < shell_thickness <= 1 m, below sphere_radius)",
    )
    groove_depth: Length = Field(
        "8 mm",
        gt=0.0,
        le=1.0,
        description="radial depth of the grooves, from the shell's inner surface "
        "(0 < groove_depth <= 1 m, below shell_thickness)",
    )
    running_clearance: Length | None = Field(
        None,
        ge=0.0,
        le=0.05,
        description="diametral running clearance between roller and groove: the groove is "
        "2 roller_radius + running_clearance wide; default the mean clearance of the ISO 286 "
        "close running fit H8/f7 at the roller diameter, 0.0315 mm at 8 mm "
        "(0 mm <= running_clearance <= roller_radius/2, and <= 50 mm)",
    )
    roller_length: Length | None = Field(
        None,
        gt=0.0,
        le=1.0,
        description="length of the inner rollers along their radial shafts; default the "
        "largest that fits, from the shell's inner radius to roller_end_gap inside the groove "
        "bottom (0 mm < roller_length <= that largest, 7.37 mm in the example; <= 1 m)",
    )
    roller_end_gap: Length = Field(
        "0.5 mm",
        ge=0.0,
        le=0.1,
        description="gap between a roller's outer rim and the groove bottom "
        "(0 mm <= roller_end_gap <= 100 mm, below the groove depth)",
    )
    bore_diameter: Length | None = Field(
        None,
        gt=0.0,
        le=1.0,
        description="diameter of the cam's bores on its axis, around the Z-shaft; default the "
        "Z-shaft's diameter plus twice cad.gap (cad.shaft_diameter < bore_diameter <= the "
        "largest clear of the grooves, 68.4 mm in the example; <= 1 m)",
    )
    slot_clearance: Length = Field(
        "1 mm",
        ge=0.0,
        le=0.1,
        description="diametral clearance of the roller shafts in the slots through the shell: "
        "each slot is the shaft's swept region widened by half of it on both sides "
        "(0 mm <= slot_clearance < 2 roller_radius + running_clearance - "
        "cad.roller_shaft_diameter, and <= 100 mm)",
    )


class WobbleCadSection(Section):
    """Sizes of the parts of the STEP assembly (``rotorkin export --format step``)."""

    shaft_diameter: Length | None = Field(
        None,
        gt=0.0,
        le=1.0,
        description="diameter of the Z-shaft's journals and crank; default sphere_radius/4, "
        "15 mm in the example (0 mm < shaft_diameter <= 1 m, and the crank's webs inside the "
        "shell)",
    )
    roller_shaft_diameter: Length | None = Field(
        None,
        gt=0.0,
        le=0.2,
        description="diameter of the roller shafts; default the roller radius "
        "(0 mm < roller_shaft_diameter <= 2 cam.roller_radius - 0.5 mm, and <= 200 mm)",
    )
    plate_thickness: Length | None = Field(
        None,
        gt=0.0,
        le=1.0,
        description="thickness of the wobble plate's disc; default 2.5 roller shaft "
        "diameters (roller_shaft_diameter + 1 mm <= plate_thickness <= "
        "drive.plate_bearing_span + wall_thickness, and <= 1 m)",
    )
    plate_radius: Length | None = Field(
        None,
        gt=0.0,
        le=10.0,
        description="radius of the wobble plate's disc; default 0.8 times the shell's inner "
        "radius (the hub plus 2 roller shaft diameters <= plate_radius <= the largest turning "
        "inside the shell, and <= 10 m)",
    )
    rail_roller_length: Length | None = Field(
        None,
        gt=0.0,
        le=1.0,
        description="length of the rail rollers along their shafts; default twice "
        "drive.rail_roller_radius (0 mm < rail_roller_length <= 1 m, the rail outside the "
        "shell)",
    )
    wall_thickness: Length | None = Field(
        None,
        gt=0.0,
        le=1.0,
        description="wall thickness of the rails, rotor discs, spokes and casing; default "
        "sphere_radius/10, 6 mm in the example (0 mm < wall_thickness <= 1 m)",
    )
    gap: Length = Field(
        "1 mm",
        ge=1e-5,
        le=0.01,
        description="clearance between parts that do not touch (0.01 mm <= gap <= 10 mm)",
    )


# --- wobble plate + spherical cam -----------------------------------------------------------
class WobbleDrive(Section):
    type: Literal["wobble_cam"]
    plate_tilt: Angle = Field(
        ge=PLATE_TILT_MIN,
        lt=HALF_PI,
        description="wobble plate tilt phi on the Z-shaft (paper Table 1) (0.5 deg <= plate_tilt "
        "< the eq. 20 limit of roller_axis_angle, 65.53 deg at 90 deg)",
    )
    roller_axis_angle: Angle = Field(
        "90 deg",
        ge=ROLLER_AXIS_ANGLE_MIN,
        le=2.0 * HALF_PI - ROLLER_AXIS_ANGLE_MIN,
        description="angle alpha between the two roller groups in the plate plane "
        "(90 deg - 180 deg / pistons_per_rotor < alpha < 90 deg + 180 deg / pistons_per_rotor, "
        "and 1 deg <= alpha <= 179 deg)",
    )
    spin_ratio: float = Field(
        -2.0,
        ge=-SPIN_RATIO_MAX,
        le=SPIN_RATIO_MAX,
        description="plate spin law varphi = spin_ratio * theta (a nonzero multiple of 0.5, "
        "-20 <= spin_ratio <= 20)",
    )
    sphere_radius: Length = Field(
        "60 mm",
        ge=0.001,
        le=10.0,
        description="radius r of the roller centres on the spherical cam (1 mm <= r <= 10 m)",
    )
    spin_a: list[Coefficient] = Field(
        default_factory=list,
        max_length=MAX_SPIN_HARMONICS,
        description="cosine coefficients of harmonics 1, 2, ... of a periodic correction "
        "added to the spin law [rad] (at most 256, each -10 <= c <= 10 rad, spin kept monotone)",
    )
    spin_b: list[Coefficient] = Field(
        default_factory=list,
        max_length=MAX_SPIN_HARMONICS,
        description="sine coefficients of harmonics 1, 2, ... of the spin-law correction [rad] "
        "(at most 256, each -10 <= c <= 10 rad, spin kept monotone)",
    )
    # --- kinetostatics: outputs, bevel gearbox, rails, bearings, plate inertia -------------
    output: Literal["shaft", "cam", "both"] = Field(
        "shaft",
        description="which output the load is taken from: 'shaft' (the Z-shaft; the cam shell "
        "only turns, driven through the bevel gearbox), 'cam' (the cam shell; the Z-shaft "
        "only turns) or 'both' (counter-rotating outputs sharing the torque, "
        "cam_torque_share at the cam shell)",
    )
    cam_torque_share: float = Field(
        0.5,
        ge=0.0,
        le=1.0,
        description="with output = 'both': fraction of the output torque taken at the cam "
        "shell, the rest at the Z-shaft (0.5: equal and opposite torques, no reaction on the "
        "housing; 0 <= share <= 1)",
    )
    bevel_ratio: float = Field(
        2.0,
        ge=1.0,
        le=10.0,
        description="tooth ratio of the gearbox's large bevel gears (on the Z-shaft and the cam "
        "shaft) to its two small idler bevels; the outputs always turn equal and opposite "
        "(1 <= ratio <= 10)",
    )
    bevel_pitch_radius: Length = Field(
        "40 mm",
        ge=0.001,
        le=10.0,
        description="mean pitch radius of the large bevel gears (1 mm <= r <= 10 m)",
    )
    bevel_pressure_angle: Angle = gear_pressure_angle("pressure angle of the bevel gear teeth")
    rail_radius: Length = Field(
        "80 mm",
        ge=0.001,
        le=10.0,
        description="distance from the plate centre to the centres of the rail rollers, along "
        "the roller shafts, outside the cam shell (sphere_radius + shell_thickness/2 + "
        "rail_roller_radius < rail_radius <= 10 m)",
    )
    rail_roller_radius: Length = Field(
        "6 mm",
        ge=1e-4,
        le=0.1,
        description="radius of the rollers in the rotors' slider rails (0.1 mm <= r <= 100 mm)",
    )
    plate_bearing_span: Length = Field(
        "40 mm",
        ge=0.001,
        le=10.0,
        description="axial distance between the two bearings of the wobble plate on the "
        "inclined section of the Z-shaft (1 mm <= span <= 10 m)",
    )
    cam_bearing_span: Length = Field(
        "100 mm",
        ge=0.001,
        le=10.0,
        description="axial distance between the two bearings of the cam shell, centred on "
        "the plate centre (1 mm <= span <= 10 m)",
    )
    plate_inertia_axial: Inertia = Field(
        "0.002 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="moment of inertia of the wobble plate with its rollers about its own axis "
        "(for the plate's gyroscopic couple; 0 <= J <= 1e5 kg*m^2)",
    )
    plate_inertia_transverse: Inertia = Field(
        "0.001 kg*m^2",
        ge=0.0,
        le=INERTIA_MAX,
        description="moment of inertia of the wobble plate with its rollers about a diameter "
        "(0 <= J <= 1e5 kg*m^2)",
    )


class WobbleMachine(TwinRotorMachine):
    """The twin-rotor engine of the paper (Table 1: compression ratio 10, 4 pistons)."""


class WobbleConfig(Section):
    title: str = ""
    drive: WobbleDrive
    machine: WobbleMachine = Field(default_factory=WobbleMachine)
    loads: EngineLoads = Field(default_factory=EngineLoads)
    cam: WobbleCamSection = Field(default_factory=WobbleCamSection)
    cad: WobbleCadSection = Field(default_factory=WobbleCadSection)
    contact: ContactSection = Field(default_factory=ContactSection)
    limits: LimitsSection = Field(default_factory=LimitsSection)
    export: ExportSection = Field(default_factory=ExportSection)
    run: RunSection = Field(default_factory=RunSection)  # 3000 rpm
