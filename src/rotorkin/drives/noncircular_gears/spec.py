"""The non-circular gear drive as rotorkin's consumers see it (:class:`DriveSpec`)."""

from __future__ import annotations

from pathlib import Path

from rotorkin.drives._spec import DriveSpec
from rotorkin.drives.noncircular_gears import cad, schema, study
from rotorkin.vane.study import HEADLINES

SPEC = DriveSpec(
    name="noncircular_gears",
    title="two pairs of non-circular gears -> any vane machine (twin-rotor engine by default)",
    config_model=schema.NoncircularConfig,
    study=study.evaluate,
    headline={**study.HEADLINE, **HEADLINES["twin_rotor"]},
    examples=("elliptic-gear-engine",),
    example_dir=Path(__file__).resolve().parent / "examples",
    cad_parts=cad.cad_parts,
    check_cam=cad.check_cam,
    machine="twin_rotor",
    law=study.law,
    carries_any=True,
)
