"""Rhomboid drive and rotary-blade machine over arrays of designs, against one design at a time.

The one-design references are the dataclasses (their ``__post_init__`` errors) and the
scalar calls; the independent models: chamber volumes sampled over a swing of psi and
reduced by brute force, the first-harmonic law's extremes and travel in closed form
(eq. 16), the indicator work of eq. 31/34, and the curvature of the pitch curve from
the circle through three nearby points.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core.errors import ParameterError
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.machines import rotary_blade as rb

RNG_SEEDS = (0, 1, 2)


# --- admissibility: one function for one design and for many --------------------------------
def _drive_name(L, p):
    try:
        rc.RhomboidCam(L, p)
    except ParameterError as exc:
        return exc.name
    return ""


def test_drive_violation_matches_the_dataclass_per_design():
    L = np.array([0.1, -0.1, np.nan, 0.1, 0.1, 0.1, 0.0, 0.2])
    p = np.radians([40.0, 40.0, 40.0, 0.0, 90.0, 95.0, -5.0, 89.9])
    code = rc.violation(L, p)
    names = ["" if c == 0 else rc.CHECKS[c - 1] for c in code]
    assert names == [_drive_name(x, y) for x, y in zip(L, p, strict=True)]
    assert names == ["", "link_length", "link_length", "psi_min", "psi_min", "psi_min",
                     "link_length", ""]  # fmt: skip


def test_drive_error_names_parameter_value_and_range():
    with pytest.raises(ParameterError, match=r"^psi_min = 95 deg .*0 deg < psi_min < 90 deg"):
        rc.RhomboidCam(0.1, np.radians(95.0))
    with pytest.raises(ParameterError, match=r"^link_length = -100 mm .*link_length > 0 mm"):
        rc.RhomboidCam(-0.1, np.radians(40.0))
    # many designs: the first inadmissible one is named
    with pytest.raises(ParameterError, match=r"^psi_min = 91 deg"):
        rc.RhomboidCam(np.array([0.1, 0.1]), np.radians([40.0, 91.0]))


def _machine_name(**kw):
    try:
        rb.RotaryBlade(**kw)
    except ParameterError as exc:
        return exc.name
    return ""


@pytest.mark.parametrize("seed", RNG_SEEDS)
def test_machine_violation_matches_the_dataclass_per_design(seed):
    rng = np.random.default_rng(seed)
    n = 200
    kw = {
        "blade_thickness": rng.uniform(-0.2, 2.0, n),
        "inner_radius": rng.uniform(-0.01, 0.1, n),
        "outer_radius": rng.uniform(-0.02, 0.12, n),
        "axial_width": rng.uniform(-0.01, 0.05, n),
        "blades_per_pair": rng.integers(0, 5, n),
        "inertia_shaft": rng.uniform(-0.01, 0.1, n),
        "inertia_blade_pair_1": rng.uniform(-0.01, 0.1, n),
        "inertia_blade_pair_2": rng.uniform(-0.01, 0.1, n),
    }
    code = rb.violation(**kw)
    one = [_machine_name(**{k: v[i].item() for k, v in kw.items()}) for i in range(n)]
    assert ["" if c == 0 else rb.CHECKS[c - 1] for c in code] == one
    assert {"", "blades_per_pair", "blade_thickness", "inner_radius"} <= set(one)


def test_swing_violation_matches_check_swing():
    B = np.array([2, 2, 3, 3, 3, 1])
    t = np.radians([10.0, 45.0, 10.0, 16.0, 14.9, 170.0])
    lo = np.radians([40.0, 40.0, 40.0, 75.0, 75.0, 40.0])
    hi = np.pi - lo
    code = rb.swing_violation(B, t, lo, hi)
    for i in range(B.size):
        m = rb.RotaryBlade(t[i] if t[i] < np.pi / B[i] else 0.0, 0.03, 0.09, 0.05, int(B[i]))
        if t[i] >= np.pi / B[i]:
            continue  # refused by the dataclass already
        try:
            rb.check_swing(m, lo[i], hi[i])
            name = ""
        except ParameterError as exc:
            name = exc.name
        assert name == ("" if code[i] == 0 else rb.SWING_CHECKS[code[i] - 1])
    assert list(code[:5]) == [0, 1, 2, 1, 0]


def test_blade_thickness_max_against_sampled_chamber_angles():
    # independent: the smallest chamber angle over a sampled swing, with t = 0
    for B in (1, 2, 3):
        for lo_deg, hi_deg in ((40.0, 140.0), (75.0, 105.0), (10.0, 100.0)):
            psi = np.radians(np.linspace(lo_deg, hi_deg, 10_001))
            expect = min(np.min(psi), np.min(2 * np.pi / B - psi))
            got = rb.blade_thickness_max(B, np.radians(lo_deg), np.radians(hi_deg))
            assert got == pytest.approx(expect, abs=1e-12)


# --- physics over arrays of designs ---------------------------------------------------------
@pytest.mark.parametrize("seed", RNG_SEEDS)
def test_class_volume_range_against_sampled_chambers(seed):
    rng = np.random.default_rng(seed)
    n = 12
    B = rng.integers(1, 4, n)
    lo = rng.uniform(0.2, 1.0, n)
    hi = np.minimum(np.pi - lo, 2 * np.pi / B - 0.3)
    t = rng.uniform(0.0, 0.9, n) * rb.blade_thickness_max(B, lo, hi)
    ri, ro, w = rng.uniform(0.0, 0.03, n), rng.uniform(0.05, 0.1, n), rng.uniform(0.01, 0.05, n)
    m = rb.RotaryBlade(t, ri, ro, w, B)
    figures = rb.chamber_figures(m, lo, hi)
    v_min, v_max = rb.class_volume_range(m, lo, hi)
    for i in range(n):
        one = rb.RotaryBlade(t[i], ri[i], ro[i], w[i], int(B[i]))
        psi = np.linspace(lo[i], hi[i], 2001)
        q = np.stack([psi, np.zeros_like(psi)])  # phi_1 = psi, phi_2 = 0
        v = rb.chamber_volumes(one, q)  # (2B, 2001)
        np.testing.assert_allclose(v_min[:, i], [v[0].min(), v[1].min()], rtol=1e-12)
        np.testing.assert_allclose(v_max[:, i], [v[0].max(), v[1].max()], rtol=1e-12)
        assert figures["volume_max"][i] == pytest.approx(v.max(), rel=1e-12)
        assert figures["volume_min"][i] == pytest.approx(v.min(), rel=1e-12)
        swept = np.max(v.max(axis=1) - v.min(axis=1))
        assert figures["swept_volume"][i] == pytest.approx(swept, rel=1e-12)
        ratio = np.min(v.max(axis=1) / v.min(axis=1))
        assert figures["compression_ratio"][i] == pytest.approx(ratio, rel=1e-12)


def test_first_harmonic_extremes_and_travel_for_arrays():
    pm = np.radians(np.linspace(5.0, 85.0, 17))
    lo, alo, hi, ahi = rc.psi_extremes(pm)
    np.testing.assert_allclose(lo, pm, rtol=0, atol=1e-14)  # eq. 16 at alpha = 90 deg
    np.testing.assert_allclose(hi, np.pi - pm, rtol=0, atol=1e-14)
    assert (alo, ahi) == (np.pi / 2, 0.0)
    np.testing.assert_allclose(rc.psi_total_variation(pm), 2 * (np.pi - 2 * pm), atol=1e-14)
    # the scalar call gives the same numbers
    for i in (0, 8, 16):
        assert rc.psi_extremes(float(pm[i]))[0] == lo[i]
        assert rc.psi_total_variation(float(pm[i])) == rc.psi_total_variation(pm)[i]


def test_indicator_work_for_arrays_equals_eq31_and_scalar_calls():
    pm = np.radians(np.array([20.0, 40.0, 60.0, 80.0]))
    m1, m2 = np.array([100.0, 50.0, -20.0, 7.0]), np.array([40.0, 60.0, -80.0, 0.0])
    work = rc.indicator_work(pm, (), (), m1, m2)
    np.testing.assert_allclose(work, (m1 - m2) * (np.pi - 2 * pm), rtol=1e-13)
    for i in range(pm.size):
        assert float(rc.indicator_work(pm[i], (), (), m1[i], m2[i])) == pytest.approx(
            work[i], rel=1e-14
        )


def test_law_peaks_for_arrays_equal_scalar_calls_and_three_point_curvature():
    alpha = np.linspace(0.0, np.pi, 4001)
    L = np.array([[0.1], [0.12], [0.2]])
    pm = np.radians([[20.0], [40.0], [70.0]])
    peaks = rc.law_peaks(L, pm, (), (), alpha)
    for i in range(3):
        one = rc.law_peaks(float(L[i, 0]), float(pm[i, 0]), (), (), alpha)
        for k, v in one.items():
            assert peaks[k][i] == v, k
        # curvature of the pitch curve from the circle through three points
        p = rc.profile_point(float(L[i, 0]), float(pm[i, 0]), (), (), alpha)[0]
        a, b, c = p[:, :-2], p[:, 1:-1], p[:, 2:]
        ab, bc, ca = (np.hypot(*(b - a)), np.hypot(*(c - b)), np.hypot(*(a - c)))
        cross = (b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0]
        kappa = 2 * cross / (ab * bc * ca)  # > 0 turning left (counter-clockwise)
        assert peaks["convex_radius_min"][i] == pytest.approx(1 / kappa.max(), rel=1e-3)
        if kappa.min() < 0:
            assert peaks["concave_radius_min"][i] == pytest.approx(-1 / kappa.min(), rel=1e-3)
        assert bool(peaks["convex"][i]) == bool(kappa.min() >= 0)
    # first harmonic: |psi'| <= 2 a_1, |psi''| <= 4 a_1, |psi'''| <= 8 a_1, all reached
    a1 = np.pi / 2 - pm[:, 0]
    np.testing.assert_allclose(peaks["speed_coeff_max"], 1 + a1, rtol=1e-6)
    np.testing.assert_allclose(peaks["accel_coeff_max"], 2 * a1, rtol=1e-12)
    np.testing.assert_allclose(peaks["jerk_coeff_max"], 4 * a1, rtol=1e-6)


def test_dataclasses_hold_arrays_of_designs():
    m = rb.RotaryBlade(np.radians([5.0, 10.0]), 0.03, np.array([0.08, 0.09]), 0.05, 2)
    assert m.outer_radius.shape == (2,) and isinstance(m.inner_radius, float)
    np.testing.assert_allclose(rb.sector_constant(m), 0.5 * (m.outer_radius**2 - 0.03**2) * 0.05)
    d = rc.RhomboidCam(np.array([0.1, 0.2]), np.radians([30.0, 60.0]))
    assert d.link_length.shape == (2,)
    with pytest.raises(ParameterError, match="^psi_min = 2 values"):
        rc.RhomboidCam(0.1, np.radians([30.0, 60.0]), (0.01,))


def test_gas_violation_matches_the_dataclass_per_design():
    p = np.array([2e5, -1.0, np.nan, 2e5, 2e5, 2e5])
    th = np.array([900.0, 900.0, 900.0, 0.0, 900.0, np.inf])
    tc = np.array([330.0, 330.0, 330.0, 330.0, -5.0, 330.0])
    code = rb.gas_violation(p, th, tc)
    for i in range(p.size):
        try:
            rb.IsothermalGas(p[i], th[i], tc[i])
            name = ""
        except ParameterError as exc:
            name = exc.name
        assert name == ("" if code[i] == 0 else rb.GAS_CHECKS[code[i] - 1])
    assert list(code) == [0, 1, 1, 2, 3, 2]
    with pytest.raises(ParameterError, match=r"^cold_temperature = -5 K .*cold_temperature > 0 K"):
        rb.IsothermalGas(2e5, 900.0, -5.0)
