"""Every number of the published table, from the table itself.

Each drive lists the papers' numbers per summary key (``DriveSpec.published``, from
``rotorkin/drives/<name>/published.py``: printed values with the paper's rounding
as tolerance, the paper's own closed forms with a numerical one). Here every
entry is checked on its drive's example with the entry's conditions applied (the
paper's case), so that the report's "paper vs ours" column and this test read one
table. The tests ``test_papers_<drive>.py`` check the same numbers through the
drive's functions, figure by figure.
"""

from __future__ import annotations

import copy
import functools

import pytest

from rotorkin.drives import REGISTRY, evaluate
from rotorkin.io.config import load_config
from rotorkin.studies.published import applies

ENTRIES = [
    pytest.param(name, i, id=f"{name}-{entry.key}-{entry.where}"[:90])
    for name, spec in REGISTRY.items()
    for i, entry in enumerate(spec.published)
]


def _case(example: str, conditions: tuple):
    """The example's validated config with the paper's conditions set (SI values)."""
    cfg = copy.deepcopy(load_config(example=example)[0])
    for dotted, value in conditions:
        section, _, key = dotted.partition(".")
        cfg[section][key] = [] if isinstance(value, tuple) else value
    return cfg


@functools.cache
def _summary(example: str, conditions: tuple) -> dict:
    return evaluate(_case(example, conditions)).summary


def test_every_drive_with_a_paper_has_numbers():
    for name, spec in REGISTRY.items():
        if spec.paper:
            assert len(spec.published) >= 5, name


@pytest.mark.parametrize(("drive", "index"), ENTRIES)
def test_published_entry(drive, index):
    spec = REGISTRY[drive]
    entry = spec.published[index]
    conditions = tuple(sorted(entry.conditions.items()))
    cfg = _case(spec.examples[0], conditions)
    assert applies(entry, cfg)
    ours = float(_summary(spec.examples[0], conditions)[entry.key])
    paper = float(entry.value(cfg) if callable(entry.value) else entry.value)
    assert abs(ours - paper) <= entry.tolerance + 1e-12 * max(1.0, abs(paper)), (
        f"{entry.key}: ours {ours}, paper {paper} ({entry.where}, {entry.kind})"
    )
