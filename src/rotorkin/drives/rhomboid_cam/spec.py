"""The rhomboid linkage + cam drive as rotorkin's consumers see it (:class:`DriveSpec`)."""

from __future__ import annotations

from pathlib import Path

from rotorkin.drives._spec import DriveSpec
from rotorkin.drives.rhomboid_cam import cad, published, scene, schema, study, synthesis
from rotorkin.drives.rhomboid_cam import sweep as batch

SPEC = DriveSpec(
    name="rhomboid_cam",
    title="rhomboid linkage rolling on a cam -> rotary-blade engine",
    config_model=schema.RhomboidConfig,
    study=study.evaluate,
    headline=study.HEADLINE,
    paper="Zhuravlev et al. 2012",
    published=published.PUBLISHED,
    examples=("rhomboid-engine",),
    example_dir=Path(__file__).resolve().parent / "examples",
    batch=batch,
    synthesize=synthesis.synthesize,
    objectives={
        "min_accel": "no target: the smallest peak blade acceleration (optimised)",
        "dwell_min": "no target: the longest dwell at the smallest chamber (optimised)",
        "dwell_max": "no target: the longest dwell at the largest chamber (optimised)",
        "min_pressure_angle": "no target: the smallest peak pressure angle (optimised)",
    },
    synthesis_options=("max_pressure_angle", "harmonics"),
    scene=scene,
    cad_parts=cad.cad_parts,
    check_cam=cad.check_cam,
    machine="rotary_blade",
    law=study.law,
    pairs=study.pairs_of,
)
