"""Checks shared by the tests of the sweep kernels: a kernel's values and reasons are the
study's, design by design."""

from __future__ import annotations

import numpy as np

from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate
from rotorkin.sweep.engine import reason_keys


def assert_equal_to_study(p, got: dict, names, round_off: dict | None = None) -> int:
    """Every admissible design's kernel value equals the study's (1e-9 relative).

    ``round_off`` maps a key whose value is a cancellation (e.g. a conservative fluid's
    work) to the key giving its scale: there the tolerance is 1e-9 of that scale. A key
    the study leaves out is NaN. Returns the number of designs compared.
    """
    round_off = round_off or {}
    seen = 0
    for i in range(p.n):
        try:
            summary = evaluate(p.config(i)).summary
        except ParameterError:
            continue
        seen += 1
        for name in names:
            want = float(summary.get(name, np.nan))
            scale = abs(float(summary[round_off[name]])) * 1e-9 if name in round_off else 0.0
            np.testing.assert_allclose(got[name][i], want, rtol=1e-9, atol=scale,
                                       err_msg=f"{name}, design {i}")  # fmt: skip
    return seen


def assert_reasons_of_study(p, reason, drive_type: str) -> None:
    """Each design's reason code names the key the study refuses it for (``"ok"``: none)."""
    keys = reason_keys(drive_type)
    for i in range(p.n):
        try:
            evaluate(p.config(i))
            want = "ok"
        except ParameterError as exc:
            want = exc.name
        assert keys[reason[i]] == want, f"design {i}"


def assert_refused_as_study(cfg: dict, table: dict, names, drive_type: str, first: str) -> None:
    """Designs ``table`` (the first refused for the key ``first``, the second admissible)
    through the sweep engine: each design's reason is the study's, a refused design's
    values NaN, the admissible one's computed."""
    from rotorkin.core.batch import Designs
    from rotorkin.sweep.engine import evaluate_designs

    p = Designs(cfg, table, len(next(iter(table.values()))))
    res = evaluate_designs(p, names, threads=1)
    assert_reasons_of_study(p, res["reason"], drive_type)
    assert reason_keys(drive_type)[res["reason"][0]] == first
    assert all(np.isnan(res["metrics"][m][0]) for m in names)
    assert all(np.isfinite(res["metrics"][m][1]) for m in names)


def assert_kernel_is_study(cfg: dict, table: dict, names):
    """Designs ``table`` through the sweep engine with no design falling back to the study
    (a fallback warning fails), at least half of them admissible, every admissible one's
    values the study's (:func:`assert_equal_to_study`). Returns the designs and the mask of
    the admissible ones."""
    import warnings

    from rotorkin.core.batch import Designs
    from rotorkin.sweep.engine import evaluate_designs

    n = len(next(iter(table.values())))
    p = Designs(cfg, table, n)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = evaluate_designs(p, names, threads=2)
    ok = res["reason"] == 0
    assert ok.sum() >= n // 2
    assert assert_equal_to_study(p, res["metrics"], names) == ok.sum()
    return p, ok
