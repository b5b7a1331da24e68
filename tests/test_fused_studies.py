"""Studies and sweeps through both paths: the compiled loops run, the numbers do not change.

Every drive with a closed form evaluates its kinematics through
:mod:`rotorkin.core.fused`; here each example's study and each batch sweep runs once
with ``ROTORKIN_KERNEL=numpy`` and once with the compiled loops (forced for the study,
automatic for the sweep, whose blocks are large), the compiled loops are seen to run,
and every summary number and swept metric agrees to 1e-12.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core import fused
from rotorkin.drives import evaluate
from rotorkin.io.config import load_config
from rotorkin.sweep import run_sweep

EXAMPLES = [
    "wobble-cam-engine",
    "eccentric-reactor",
    "guide-bar-pump",
    "elliptic-gear-engine",
    "rhomboid-engine",
]

# batch sweeps: (example, varied keys) with 30 designs, so that with SAMPLES samples per
# design one evaluation of the sweep kernels passes AUTO_MIN_POINTS
SAMPLES = 4501
SWEEPS = {
    "wobble-cam-engine": {"drive.plate_tilt": "30deg:50deg:6", "drive.roller_axis_angle":
                          "80deg:100deg:5"},
    "eccentric-reactor": {"drive.eccentricity": "10mm:60mm:6", "drive.disc_radius": "80mm:90mm:5"},
    "guide-bar-pump": {"drive.lambda": "0.2:0.8:6", "drive.input_gear_ratio": "1:2:5"},
    "rhomboid-engine": {"drive.psi_min": "20deg:80deg:6", "drive.link_length": "100mm:140mm:5"},
}  # fmt: skip


@pytest.fixture
def compiled_calls(monkeypatch):
    """Counts the calls of compiled loops (any drive)."""
    calls = []
    call = fused._Loop.__call__

    def counted(self, *args):
        calls.append(self.__name__)
        return call(self, *args)

    monkeypatch.setattr(fused._Loop, "__call__", counted)
    return calls


def _numbers(summary: dict) -> dict:
    return {k: float(v) for k, v in summary.items()
            if isinstance(v, (int, float, np.floating)) and not isinstance(v, bool)}  # fmt: skip


@pytest.mark.parametrize("example", EXAMPLES)
def test_study_same_numbers_on_both_paths(example, monkeypatch, compiled_calls):
    cfg = load_config(None, example)[0]
    monkeypatch.setenv(fused.KERNEL_ENV, "numpy")
    ref = evaluate(cfg)
    assert not compiled_calls
    monkeypatch.setenv(fused.KERNEL_ENV, "numba")
    got = evaluate(cfg)
    assert compiled_calls, "the study did not run the compiled loops"
    a, b = _numbers(got.summary), _numbers(ref.summary)
    assert a.keys() == b.keys() and len(a) > 10
    for key, value in b.items():
        assert a[key] == pytest.approx(value, rel=1e-12, abs=1e-12 * abs(value) + 1e-300), key
    for key, col in ref.columns.items():
        np.testing.assert_allclose(got.columns[key], col, rtol=1e-12, atol=1e-300, err_msg=key)


@pytest.mark.parametrize("example", sorted(SWEEPS))
def test_sweep_same_metrics_on_both_paths(example, monkeypatch, compiled_calls):
    _, raw, _ = load_config(None, example)
    monkeypatch.setenv(fused.KERNEL_ENV, "numpy")
    ref = run_sweep(raw, SWEEPS[example], progress=False, samples=SAMPLES, threads=1)
    assert not compiled_calls
    monkeypatch.delenv(fused.KERNEL_ENV)
    got = run_sweep(raw, SWEEPS[example], progress=False, samples=SAMPLES, threads=1)
    assert compiled_calls, "the sweep did not run the compiled loops"
    assert ref.data_vars.keys() == got.data_vars.keys()
    for name, var in ref.data_vars.items():
        if var.dtype.kind == "f":
            np.testing.assert_allclose(got[name].values, var.values, rtol=1e-12, err_msg=name)
        else:
            np.testing.assert_array_equal(got[name].values, var.values, err_msg=name)
