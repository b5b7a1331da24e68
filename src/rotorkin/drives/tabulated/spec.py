"""The tabulated drive as rotorkin's consumers see it (:class:`DriveSpec`)."""

from __future__ import annotations

from pathlib import Path

from rotorkin.drives._spec import DriveSpec
from rotorkin.drives.tabulated import schema, study
from rotorkin.vane.study import HEADLINES

SPEC = DriveSpec(
    name="tabulated",
    title="any mechanism's two member angles from a CSV table or a Fourier series -> any vane "
    "machine",
    config_model=schema.TabulatedConfig,
    study=study.evaluate,
    headline={**study.HEADLINE, **HEADLINES["twin_rotor"]},
    examples=("tabulated-engine",),
    example_dir=Path(__file__).resolve().parent / "examples",
    machine="twin_rotor",
    law=study.law,
    carries_any=True,
)
