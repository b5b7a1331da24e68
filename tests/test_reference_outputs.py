"""Every example prints the numbers it printed before the drives moved into their packages.

``tests/data/reference_outputs.json`` holds, per example, the ``summary.json`` and the
minimum, maximum, mean and one row of every ``motion.csv`` column, written by
``rotorkin run`` at the commit before the restructuring; keys, columns and examples added
since (the pairs' forces, the new drives' examples) were added to it once each, after
checking that no earlier number moved. A change of any summary key
or column beyond round-off (1e-9 relative) fails here; a new key fails too, so that an
output change is always a decision.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from rotorkin.cli import main

REFERENCE = json.loads((Path(__file__).parent / "data" / "reference_outputs.json").read_text())


def _close(a, b) -> bool:
    if isinstance(b, float) or isinstance(a, float):
        return bool(np.isclose(float(a), float(b), rtol=1e-9, atol=1e-12))
    return a == b


@pytest.mark.slow
@pytest.mark.parametrize("example", sorted(REFERENCE))
def test_example_outputs_unchanged(example, tmp_path, monkeypatch):
    import rotorkin.drives

    real = rotorkin.drives.evaluate  # the PNGs are not compared here
    monkeypatch.setattr(rotorkin.drives, "evaluate", lambda cfg: _no_figures(real(cfg)))
    out = tmp_path / example
    assert main(["run", "-e", example, "--out", str(out), "-q"]) == 0
    ref = REFERENCE[example]
    summary = json.loads((out / "summary.json").read_text())
    assert sorted(summary) == sorted(ref["summary"])
    changed = {k: (summary[k], v) for k, v in ref["summary"].items() if not _close(summary[k], v)}
    assert not changed
    with (out / "motion.csv").open() as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
    head, data = rows[0], np.array(rows[1:], dtype=float)
    assert len(data) == ref["rows"] and sorted(head) == sorted(ref["columns"])
    for i, name in enumerate(head):
        col = data[:, i]
        stats = [col.min(), col.max(), col.mean(), col[len(col) // 7]]
        np.testing.assert_allclose(stats, ref["columns"][name], rtol=1e-9, atol=1e-9, err_msg=name)


def _no_figures(result):
    import dataclasses

    return dataclasses.replace(result, write_figures=lambda outdir: [])
