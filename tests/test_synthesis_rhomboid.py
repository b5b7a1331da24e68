"""Rhomboid-cam synthesis: optimal harmonics beat the first-harmonic law and meet the checks.

The checks here are independent of the optimiser: psi by the drive's psi_law, its
derivatives by finite differences, the pitch curve's curvature and pressure angle by
finite differences of its points, the dwell by counting samples.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate, synthesize
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam import synthesis as sr
from rotorkin.io.config import load_config, validate_config
from rotorkin.synthesis import dwell_fraction, synthesized_raw_config

L, PSI_MIN, ROLLER = 0.12, np.radians(40.0), 0.01
N = 40_000  # samples per period for the independent checks


def _psi(a, b, alpha):
    return rc.psi_law(PSI_MIN, a, b, alpha)[0]


def _fd(f, x, h, order):
    if order == 1:
        return (f(x + h) - f(x - h)) / (2 * h)
    return (f(x + h) - 2 * f(x) + f(x - h)) / h**2


def _independent(a, b):
    """Objectives and checks of a law from sampled geometry only."""
    alpha = np.arange(N) * np.pi / N
    h = 1e-4
    psi = _psi(a, b, alpha)
    d2 = _fd(lambda x: _psi(a, b, x), alpha, h, 2)

    def point(x):
        rho = L * np.cos(0.5 * _psi(a, b, x))
        return np.stack([rho * np.cos(x), rho * np.sin(x)])

    p1 = _fd(point, alpha, h, 1)
    p2 = _fd(point, alpha, h, 2)
    kappa = (p1[0] * p2[1] - p1[1] * p2[0]) / np.hypot(*p1) ** 3  # CCW curve: convex > 0
    # pressure angle: between the curve's normal and the radial direction (roller velocity
    # relative to the shaft), i.e. between the tangent and the circumferential direction
    radial = point(alpha) / np.hypot(*point(alpha))
    tangent = p1 / np.hypot(*p1)
    pa = np.arcsin(np.abs(np.sum(tangent * radial, axis=0)))
    tol = 0.02 * (np.pi - 2 * PSI_MIN)
    return {
        "accel": 0.5 * np.max(np.abs(d2)),
        "dwell_min": np.mean(np.abs(psi - PSI_MIN) < tol),
        "dwell_max": np.mean(np.abs(psi - (np.pi - PSI_MIN)) < tol),
        "pressure": np.max(pa),
        "convex_radius": 1.0 / np.max(kappa),
        # monotone between the extremes: psi never rises on [0, pi/2] (sampled values)
        "rising_on_first_quarter": np.max(np.diff(psi[alpha <= np.pi / 2])),
        "psi_lo": psi.min(),
        "psi_hi": psi.max(),
    }


def test_batched_law_matches_drive():
    rng = np.random.default_rng(3)
    alpha = np.linspace(-1.0, 4.0, 301)
    law = sr.Law(PSI_MIN, 3, alpha)
    x = rng.normal(scale=0.05, size=(5, 6))
    for order in range(4):
        got = law.psi(x, order)
        for i in range(5):
            a, b = law.split(x[i])
            np.testing.assert_allclose(got[i], rc.psi_law(PSI_MIN, a, b, alpha)[order], atol=1e-12)


def test_batched_pressure_angle_matches_cams_module():
    from rotorkin.drives.rhomboid_cam import cam as cam

    alpha = np.arange(720) * np.pi / 720
    law = sr.Law(PSI_MIN, 2, alpha)
    rng = np.random.default_rng(5)
    x = rng.normal(scale=0.02, size=(4, 4))
    got = sr._pressure_batch(law, L, x)
    for i in range(4):
        want = np.max(np.abs(cam.pressure_angles(L, PSI_MIN, *law.split(x[i]), alpha)))
        assert got[i] == pytest.approx(want, abs=1e-13)


def test_dwell_near_min_equals_dwell_near_max_eq10():
    rng = np.random.default_rng(11)
    alpha = np.arange(4000) * np.pi / 4000
    tol = 0.02 * (np.pi - 2 * PSI_MIN)
    for _ in range(5):
        a, b = tuple(rng.normal(scale=0.03, size=2)), tuple(rng.normal(scale=0.01, size=2))
        psi = _psi(a, b, alpha)
        lo = dwell_fraction(psi, PSI_MIN, tol)
        hi = dwell_fraction(psi, np.pi - PSI_MIN, tol)
        assert lo == pytest.approx(hi, abs=1e-12)


def test_dwell_fraction_exact_for_a_cosine():
    # |cos t| < 0.5 on a third of the period: 2 * (pi/3) of 2 pi
    t = np.arange(3000) * 2 * np.pi / 3000
    assert dwell_fraction(np.cos(t), 0.0, 0.5) == pytest.approx(1.0 / 3.0, abs=1e-6)
    assert dwell_fraction(np.cos(t)[None].repeat(3, 0), 1.0, 1e-9).shape == (3,)


@pytest.mark.parametrize(
    "objective, key, sign",
    [
        ("min_accel", "accel", 1.0),
        ("dwell_min", "dwell_min", -1.0),
        ("dwell_max", "dwell_max", -1.0),
        ("min_pressure_angle", "pressure", 1.0),
    ],
)
def test_optimum_beats_first_harmonic_and_meets_constraints(objective, key, sign):
    limit = np.radians(55.0)
    x, info = sr.optimize_law(L, PSI_MIN, ROLLER, objective, 2, pa_limit=limit, maxiter=30)
    a, b = tuple(x[:2]), tuple(x[2:])
    base, opt = _independent((), ()), _independent(a, b)
    assert sign * opt[key] < sign * base[key] - 1e-3 * abs(base[key])  # strictly better
    # constraints, by independent sampling
    assert opt["rising_on_first_quarter"] <= 1e-14
    assert opt["psi_lo"] >= PSI_MIN - 1e-9 and opt["psi_hi"] <= np.pi - PSI_MIN + 1e-9
    assert opt["convex_radius"] > ROLLER  # no undercut
    assert opt["pressure"] <= limit + 1e-6
    assert rc.psi_is_monotone(PSI_MIN, a, b)


def test_min_accel_three_harmonics_approaches_constant_acceleration():
    x, _ = sr.optimize_law(L, PSI_MIN, ROLLER, "min_accel", 3, pa_limit=np.nan, maxiter=40)
    acc = _independent(tuple(x[:3]), tuple(x[3:]))["accel"]
    swing = np.pi - 2 * PSI_MIN
    # rest-to-rest over a quarter period: no law beats constant acceleration, 8 swing/pi^2
    assert 8 * swing / np.pi**2 < acc < 0.9 * swing


def test_synthesize_on_the_example_and_run_the_result():
    cfg, raw, _ = load_config(None, "rhomboid-engine", ["run.points=181"])
    res = synthesize(cfg, raw, "min_accel")
    assert res.metrics["better"] and res.metrics["constraints_met"]
    new = validate_config(synthesized_raw_config(raw, res.updates, "min_accel"))
    a, b = tuple(new["drive"]["a"]), tuple(new["drive"]["b"])
    ind = _independent(a, b)
    assert ind["accel"] < _independent((), ())["accel"]
    assert ind["pressure"] <= np.radians(res.metrics["pressure_angle_limit_deg"]) + 1e-6
    out = evaluate(new)
    assert out.summary["blade_accel_coeff_max"] == pytest.approx(ind["accel"], rel=1e-6)
    # the indicator work of a monotone law does not depend on the profile (eq. 34)
    assert out.summary["indicator_work_J"] == pytest.approx(
        res.metrics["baseline_indicator_work_J"]
    )


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"target": "3 deg"}, "target = "),
        ({"harmonics": 21}, "harmonics = 21"),
        ({"harmonics": 0}, "harmonics = 0"),
        ({"max_pressure_angle": np.radians(30.0)}, "max_pressure_angle = "),
    ],
)
def test_errors(kwargs, name):
    cfg, raw, _ = load_config(None, "rhomboid-engine", [])
    with pytest.raises(ParameterError) as err:
        synthesize(cfg, raw, "min_accel", **kwargs)
    assert str(err.value).startswith(name)


def test_undercutting_roller_is_refused():
    cfg, raw, _ = load_config(None, "rhomboid-engine", ["cam.roller_radius=60 mm"])
    with pytest.raises(ParameterError, match="cam.roller_radius"):
        synthesize(cfg, raw, "min_accel")
