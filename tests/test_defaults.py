"""One source of defaults: a config that gives only the required keys is the example.

The schema's defaults are the example machines' values, so a config written by
hand with the drive's required keys gives the example's numbers, and the README's
own hand-written config gives a meaningful power (no warning, no zero).
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from rotorkin.drives import REGISTRY, evaluate
from rotorkin.io.config import load_config, validate_config

README = Path(__file__).resolve().parent.parent / "README.md"


def _required_only(spec, raw: dict) -> dict:
    """The example's [drive] keys that have no default value, and nothing else.

    A key whose default is None (a table to read, a phase computed from other keys) has no
    value of its own either: it stays.
    """
    fields = spec.config_model.model_fields["drive"].annotation.model_fields
    required = {(f.alias or n) for n, f in fields.items() if f.is_required() or f.default is None}
    return {"drive": {k: v for k, v in raw["drive"].items() if k in required}}


@pytest.mark.parametrize("example", [ex for s in REGISTRY.values() for ex in s.examples])
def test_required_keys_alone_give_the_example(example):
    cfg, raw, _ = load_config(example=example)
    spec = REGISTRY[cfg["drive"]["type"]]
    minimal = validate_config(_required_only(spec, raw))
    got, want = evaluate(minimal).summary, evaluate(cfg).summary
    assert got == want


def test_the_readme_config_gives_a_meaningful_power():
    text = README.read_text()
    block = re.search(r"```toml\n(.*?)```", text, re.S).group(1)
    result = evaluate(validate_config(tomllib.loads(block)))
    # no input leaves a number without meaning (the rollers' overload is a finding, not that)
    assert [w for w in result.warnings if "contact.allowable_stress" not in w] == []
    assert result.summary["indicated_power_kW"] > 10.0
    assert result.summary["mean_torque_Nm"] > 0.0
    assert 0.0 < result.summary["indicated_efficiency"] < 1.0
