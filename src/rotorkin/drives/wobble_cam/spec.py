"""The wobble-cam drive as rotorkin's consumers see it (:class:`DriveSpec`)."""

from __future__ import annotations

from pathlib import Path

from rotorkin.drives._spec import DriveSpec
from rotorkin.drives.wobble_cam import cad, published, scene, schema, study, synthesis
from rotorkin.drives.wobble_cam import sweep as batch
from rotorkin.drives.wobble_cam.figures_sweep import sweep_recipes

SPEC = DriveSpec(
    name="wobble_cam",
    title="wobble plate + counter-rotating spherical cam -> twin-rotor engine",
    config_model=schema.WobbleConfig,
    study=study.evaluate,
    headline=study.HEADLINE,
    paper="Chen Hu et al. 2015",
    published=published.PUBLISHED,
    examples=("wobble-cam-engine",),
    example_dir=Path(__file__).resolve().parent / "examples",
    batch=batch,
    sweep_recipes=sweep_recipes,
    tolerance_hold=batch.tolerance_hold,
    tolerance_first=(
        "compression_ratio",
        "compression_ratio_a",
        "compression_ratio_b",
        "chamber_swing_deg",
        "slider_angle_max_deg",
        "slider_angle_min_deg",
    ),
    synthesize=synthesis.synthesize,
    objectives={
        "sine_chamber": "no target: a fixed law (the chamber angle a sine of the shaft angle)",
        "dwell_min_volume": 'the dwell fraction at minimum volume ("0.12" or "12 %"; default: '
        "the longest dwell whose grooves the roller can follow, the range is checked)",
    },
    synthesis_options=("max_pressure_angle", "harmonics"),
    scene=scene,
    cad_write=cad.export_wobble,
    check_cam=cad.check_cam,
    check_rows=cad.check_rows,
    checks=cad.checks,
    machine="twin_rotor",
    law=study.law,
    pairs=study.pairs_of,
)
