"""The guide-bar + gear drive as rotorkin's consumers see it (:class:`DriveSpec`)."""

from __future__ import annotations

from pathlib import Path

from rotorkin.drives._spec import DriveSpec
from rotorkin.drives.guide_bar import cad, published, scene, schema, study, synthesis
from rotorkin.drives.guide_bar import sweep as batch
from rotorkin.drives.guide_bar.figures_sweep import sweep_recipes

SPEC = DriveSpec(
    name="guide_bar",
    title="two rotating guide-bar mechanisms + gears -> differential vane pump",
    config_model=schema.GuideBarConfig,
    study=study.evaluate,
    headline=study.HEADLINE,
    paper="JHIT 44(9) 2012",
    published=published.PUBLISHED,
    examples=("guide-bar-pump",),
    example_dir=Path(__file__).resolve().parent / "examples",
    batch=batch,
    sweep_recipes=sweep_recipes,
    tolerance_hold=batch.tolerance_hold,
    synthesize=synthesis.synthesize,
    objectives={
        "vane_angle": 'the vane angle gamma_0 ("60 deg"; default 60 deg, or the middle of the '
        "reachable range if 60 deg is not reachable)",
    },
    scene=scene,
    cad_parts=cad.cad_parts,
    check_cam=cad.check_cam,
    machine="vane_pump",
    law=study.law,
    pairs=study.pairs_of,
)
