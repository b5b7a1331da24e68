"""The double eccentric-cam drive as rotorkin's consumers see it (:class:`DriveSpec`)."""

from __future__ import annotations

from pathlib import Path

from rotorkin.drives._spec import DriveSpec
from rotorkin.drives.eccentric_cam import cad, published, scene, schema, study, synthesis
from rotorkin.drives.eccentric_cam import sweep as batch
from rotorkin.drives.eccentric_cam.figures_sweep import sweep_recipes

SPEC = DriveSpec(
    name="eccentric_cam",
    title="two eccentric discs on one shaft -> opposed-piston reactor",
    config_model=schema.EccentricConfig,
    study=study.evaluate,
    headline=study.HEADLINE,
    paper="Zhu & Zhu 2012",
    published=published.PUBLISHED,
    examples=("eccentric-reactor",),
    example_dir=Path(__file__).resolve().parent / "examples",
    batch=batch,
    sweep_recipes=sweep_recipes,
    synthesize=synthesis.synthesize,
    objectives={
        "gap_change": 'the tolerated peak gap change ("1 %" or "0.01" of L, or "5 mm"; '
        "default: half the config's own)",
    },
    scene=scene,
    cad_parts=cad.cad_parts,
    check_cam=cad.check_cam,
    machine="opposed_piston",
)
