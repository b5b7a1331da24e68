"""rotorkin optimize: NSGA-II on the sweep kernels, against fronts known in closed form.

The vane pump's mean flow and tip leakage are closed forms of its casing radius
R_c and axial width w (docs/machines/vane_pump.md, machines/pump_flow.py):
``Q = 2 Z k s n / i12`` with ``k = w (R_c^2 - R_h^2)/2``, ``s = 2 atan(lambda)``, and
``L = 2 Z w h^3 dp / (12 mu gamma R_c)``. Maximising Q and minimising L over a box
puts the whole front on ``R_c = R_c,max`` (for a leakage, more radius gives more flow
and less leakage), ``w`` over its range: a straight segment ``(a w, b w)`` in the
objectives' plane, cut at ``w >= Q_min / a`` by a flow constraint.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
import xarray as xr

from rotorkin.cli import main
from rotorkin.design.optimize import build_spec, optimize
from rotorkin.drives import evaluate
from rotorkin.io.config import load_config


def _segment_distance(q, leak, a, b, w_lo, w_hi):
    """Distance of front points from the exact segment {(a w, b w): w_lo <= w <= w_hi},
    in objectives scaled by the segment's far end (so the segment runs on the diagonal)."""
    qn, ln = q / (a * w_hi), leak / (b * w_hi)
    t = np.clip(0.5 * (qn + ln), w_lo / w_hi, 1.0)
    return np.hypot(qn - t, ln - t)


def test_front_of_flow_and_leakage_against_the_closed_form():
    _, raw, _ = load_config(None, "guide-bar-pump", ['machine.tip_clearance="0.02 mm"'])
    vary = ["machine.casing_radius=40mm:100mm", "machine.axial_width=10mm:60mm"]
    objectives = ["max:flow_mean_l_per_min", "min:leakage_tip_l_per_min"]
    spec = build_spec(raw, vary, objectives, ["flow_mean_l_per_min>=300"], population=16,
                      generations=16, seed=1)  # fmt: skip
    res = optimize(spec)
    lam, z, rh, rc, n, i12 = 0.5, 2, 0.030, 0.100, 1500 / 60, 2.0
    h, dp, mu = 2e-5, 5e5, 0.03
    gamma = 0.5 * math.pi - math.atan(lam)  # the theoretical vane angle (eq. 5, u = 2)
    a = 2 * z * 0.5 * (rc**2 - rh**2) * 2 * math.atan(lam) * n / i12 * 6e4  # l/min per m of w
    b = 2 * z * h**3 * dp / (12 * mu * gamma * rc) * 6e4
    w_lo, w_hi = 300.0 / a, 0.060
    q, leak = res.column("flow_mean_l_per_min"), res.column("leakage_tip_l_per_min")
    # the constraint holds on every design of the front
    assert np.all(q >= 300.0)
    # on the exact front: the casing radius at its bound, the objectives on the segment
    assert res.size >= 10
    assert np.all(res.X[:, 0] >= 0.97 * rc)
    assert _segment_distance(q, leak, a, b, w_lo, w_hi).max() < 0.03
    # and spread over it: both ends reached within 5 %
    assert q.min() <= 1.05 * a * w_lo and q.max() >= 0.95 * a * w_hi
    # each design's metrics are those of the scalar study at it
    _, cfg = res.config(res.size // 2)
    summary = evaluate(cfg).summary
    assert summary["flow_mean_l_per_min"] == pytest.approx(q[res.size // 2], rel=1e-12)
    assert summary["leakage_tip_l_per_min"] == pytest.approx(leak[res.size // 2], rel=1e-12)


def _kernel_spec(generations=12, seed=5):
    """Three keys through the pump's kernel, a third of the box refused (R_h >= R_c)."""
    _, raw, _ = load_config(None, "guide-bar-pump")
    return build_spec(raw, ["drive.lambda=0.1:0.8", "machine.hub_radius=20mm:90mm",
                            "machine.casing_radius=40mm:100mm"],
                      ["max:flow_mean_l_per_min", "min:input_torque_fluctuation_ratio"],
                      population=16, generations=generations, seed=seed)  # fmt: skip


def test_refused_designs_are_violations_not_objectives():
    res = optimize(_kernel_spec(generations=30))
    reasons = np.concatenate([h["reason"] for h in res.history])
    x = np.concatenate([h["X"] for h in res.history])
    refused = reasons != 0
    assert np.any(refused) and np.all(x[refused, 1] >= x[refused, 2])  # R_h >= R_c
    assert np.all(res.X[:, 1] < res.X[:, 2])
    # the torque fluctuation depends on lambda only, the flow grows with R_c^2 - R_h^2: the
    # exact front is R_h = 20 mm, R_c = 100 mm, lambda over its range. At the same torque
    # fluctuation (the same lambda) a design of the front found falls short of the exact
    # front's flow by 1 - (R_c^2 - R_h^2) / (0.1^2 - 0.02^2)
    lam, rh, rc, w = res.X[:, 0], res.X[:, 1], res.X[:, 2], 0.04
    shortfall = 1.0 - (rc**2 - rh**2) / (0.1**2 - 0.02**2)
    assert np.all(shortfall >= 0.0) and shortfall.max() < 0.03
    assert lam.min() < 0.12 and lam.max() > 0.78
    q = res.column("flow_mean_l_per_min")
    exact = 2 * 2 * 0.5 * w * (rc**2 - rh**2) * 2 * np.arctan(lam) * 25 / 2 * 6e4
    assert np.allclose(q, exact, rtol=1e-12)


class _Stop(Exception):
    pass


def test_an_interrupted_search_resumes_to_the_same_front(tmp_path):
    spec = _kernel_spec()
    whole = optimize(spec, store=tmp_path / "a")

    def stop_after(index, evaluated):
        if index == 4:
            raise _Stop

    with pytest.raises(_Stop):
        optimize(spec, store=tmp_path / "b", on_generation=stop_after)
    seen = []
    resumed = optimize(spec, store=tmp_path / "b", resume=True,
                       on_generation=lambda i, fresh: seen.append(fresh))  # fmt: skip
    assert seen == [False] * 5 + [True] * 7 and resumed.replayed == 5
    assert np.array_equal(resumed.X, whole.X) and np.array_equal(resumed.values, whole.values)
    # without resume: a fresh search, the same numbers again (one seed, one front)
    again = optimize(spec, store=tmp_path / "b")
    assert again.replayed == 0 and np.array_equal(again.X, whole.X)


def _cli(out, *extra):
    return ["optimize", "-e", "guide-bar-pump", "--vary", "drive.lambda=0.1:0.8",
            "--vary", "machine.casing_radius=40mm:100mm", "--objective",
            "max:flow_mean_l_per_min", "--objective", "min:input_torque_fluctuation_ratio",
            "--constraint", "input_torque_max_Nm<=7", "--population", "12", "--seed", "2",
            "--out", str(out), *extra]  # fmt: skip


def test_the_command_resumes_extends_and_reports(tmp_path, capsys):
    assert main(_cli(tmp_path / "whole", "--generations", "8", "-q")) == 0
    assert main(_cli(tmp_path / "part", "--generations", "3", "-q")) == 0
    assert main(_cli(tmp_path / "part", "--generations", "8", "--resume", "--report", "1")) == 0
    text = capsys.readouterr().out
    assert "3 generation(s) replayed" in text and "Pareto set" in text
    whole = (tmp_path / "whole" / "pareto.csv").read_text()
    assert (tmp_path / "part" / "pareto.csv").read_text() == whole
    ds = xr.open_dataset(tmp_path / "part" / "pareto.nc")
    rows = whole.strip().splitlines()
    assert ds.sizes["design"] == len(rows) - 1
    assert ds["machine.casing_radius"].attrs["units"] == "mm"
    assert np.all(ds["input_torque_max_Nm"].values <= 7.0)
    assert (tmp_path / "part" / "pareto.png").stat().st_size > 1000
    # the report of design 1: rotorkin run's outputs, its metric that of the front
    import json

    summary = json.loads((tmp_path / "part" / "design_1" / "summary.json").read_text())
    assert summary["flow_mean_l_per_min"] == pytest.approx(float(ds["flow_mean_l_per_min"][1]),
                                                           rel=1e-12)  # fmt: skip
    ds.close()


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (["--objective", "flow_mean_l_per_min"], ["--objective 'flow_mean_l_per_min'",
                                                  "max:METRIC or min:METRIC"]),
        (["--objective", "top:flow_mean_l_per_min"], ["max:METRIC or min:METRIC"]),
        (["--objective", "max:flow_nope"], ["--objective max:flow_nope", "the metric 'flow_nope'",
                                            "flow_mean_l_per_min"]),
        (["--objective", "max:flow_mean_l_per_min", "--constraint", "flow_mean_l_per_min<5"],
         ["--constraint 'flow_mean_l_per_min<5'", "METRIC<=VALUE or METRIC>=VALUE"]),
        (["--objective", "max:flow_mean_l_per_min", "--constraint", "flow_mean_l_per_min<=x"],
         ["METRIC<=VALUE"]),
        (["--objective", "max:flow_mean_l_per_min", "--constraint", "nope>=1"],
         ["the metric 'nope'"]),
        (["--objective", "max:flow_mean_l_per_min", "--vary", "drive.lambda=0.1:1.5"],
         ["drive.lambda = '1.5' is not admissible: 0.01 <= lambda <= 0.99"]),
        (["--objective", "max:flow_mean_l_per_min", "--vary", "drive.driver=0:1"],
         ["a choice key cannot be varied continuously"]),
        (["--objective", "max:flow_mean_l_per_min", "--population", "1"],
         ["--population = 1 is not admissible"]),
    ],
)  # fmt: skip
def test_bad_input_is_one_line(extra, words, tmp_path, capsys):
    out = tmp_path / "o"
    vary = [] if any(e.startswith("drive.lambda") or e.startswith("drive.driver") for e in extra) \
        else ["--vary", "drive.lambda=0.1:0.8"]  # fmt: skip
    args = ["optimize", "-e", "guide-bar-pump", *vary, *extra, "--out", str(out)]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("rotorkin: error: ")
    for w in words:
        assert w in err[0]
    assert not out.exists()


def test_a_report_index_off_the_front_writes_nothing(tmp_path, capsys):
    out = tmp_path / "o"
    assert main(_cli(out, "--generations", "2", "--report", "999")) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--report = 999 is not admissible" in err[0]
    assert not (out / "pareto.csv").exists()


def test_without_pymoo_one_line(monkeypatch, tmp_path, capsys):
    monkeypatch.setitem(sys.modules, "pymoo.algorithms.moo.nsga2", None)
    assert main(_cli(tmp_path / "o", "--generations", "2")) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "pip install 'rotorkin[optimize]'" in err[0]
