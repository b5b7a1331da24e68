"""Property tests of the guide-bar drive and its pump (hypothesis).

Relations the mechanism gives exactly, stated here and checked on random designs:

* broadcasting: parameters of any shape against angles of any shape give, element by
  element, what scalar calls give;
* periodicity: the impeller speeds repeat after ``2 pi i12`` of the input angle, the
  angles advance by ``2 pi/u``; ``g(x + 2 pi) = g(x) + 2 pi``;
* installation phase: impeller 2 is impeller 1 shifted by ``Sigma i12`` of input angle;
* oddness: ``g(-x) = -g(x)`` and ``h(-y) = -h(y)`` (the frame line is a mirror line),
  so the relative angle ``r = q_2 - q_1`` is even about each equal-speed point;
* inverse mechanisms: the guide-driven mechanism is the crank-driven one run backwards,
  ``h(g(x)) = x`` and ``h'(g(x)) g'(x) = 1``;
* admissibility: the vectorised check names, per design, the parameter the dataclass
  names for that design alone.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from rotorkin.core.batch import Designs
from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import pump as gb_pump
from rotorkin.drives.guide_bar import sweep as batch
from rotorkin.io.config import load_config
from rotorkin.machines import vane_pump as vp
from rotorkin.sweep.engine import reason_keys

SETTINGS = settings(max_examples=40, deadline=None)

lams = st.floats(0.05, 0.95)
ratios = st.floats(0.5, 4.0)
input_ratios = st.floats(0.3, 3.0)
phases = st.floats(0.1, 2.0 * np.pi - 0.1)
drivers = st.sampled_from(gb.DRIVERS)
angles = st.floats(-20.0, 20.0)


@st.composite
def drives(draw):
    return gb.GuideBar(draw(lams), draw(ratios), draw(input_ratios), draw(phases), draw(drivers))


def _theta_arrays(max_dims=3):
    shapes = hnp.array_shapes(min_dims=0, max_dims=max_dims, min_side=1, max_side=4)
    return hnp.arrays(np.float64, shapes, elements=angles)


# --------------------------------------------------------------------------------------------
# broadcasting
# --------------------------------------------------------------------------------------------
@SETTINGS
@given(p=drives(), theta=_theta_arrays())
def test_angles_of_any_shape_equal_scalar_calls(p, theta):
    q = gb.impeller_angles(p, theta)
    for k, arr in enumerate(q):
        assert arr.shape == (2, *theta.shape)
        for idx in np.ndindex(theta.shape):
            one = gb.impeller_angles(p, float(theta[idx]))[k]
            # equal to the last bits (vectorised and scalar sin/cos may differ by 1 ulp)
            np.testing.assert_allclose(arr[(slice(None), *idx)], one, rtol=1e-14, atol=1e-14)
    rates = gb.impeller_rates(p, theta)
    for k in range(3):
        np.testing.assert_array_equal(rates[k], q[k + 1])
    m = gb.motion(p, theta)
    assert m.theta.shape == theta.shape and m.q.shape == (2, *theta.shape)


@SETTINGS
@given(
    n=st.integers(1, 5),
    data=st.data(),
    theta=hnp.arrays(np.float64, st.integers(1, 6), elements=angles),
)
def test_parameter_arrays_against_angle_arrays_equal_scalar_calls(n, data, theta):
    """Parameters (n, 1) against angles (m,): element (i, j) is design i at angle j."""
    lam = np.array(data.draw(st.lists(lams, min_size=n, max_size=n)))[:, None]
    u = np.array(data.draw(st.lists(ratios, min_size=n, max_size=n)))[:, None]
    i12 = np.array(data.draw(st.lists(input_ratios, min_size=n, max_size=n)))[:, None]
    ph = np.array(data.draw(st.lists(phases, min_size=n, max_size=n)))[:, None]
    drv = np.array(data.draw(st.lists(drivers, min_size=n, max_size=n)))[:, None]
    many = gb.GuideBar(lam, u, i12, ph, drv)
    q = gb.impeller_angles(many, theta)
    assert q[0].shape == (2, n, theta.size)
    swing = gb.relative_angle_swing(many)
    lo, hi = gb_pump.relative_angle_extremes(many)
    for i in range(n):
        one = gb.GuideBar(lam[i, 0], u[i, 0], i12[i, 0], ph[i, 0], str(drv[i, 0]))
        want = gb.impeller_angles(one, theta)
        for k in range(4):
            np.testing.assert_allclose(q[k][:, i], want[k], rtol=1e-15, atol=1e-15)
        assert swing[i, 0] == pytest.approx(gb.relative_angle_swing(one), rel=1e-15)
        assert (lo[i, 0], hi[i, 0]) == pytest.approx(gb_pump.relative_angle_extremes(one))


@SETTINGS
@given(
    lam=hnp.arrays(np.float64, (3, 1, 2), elements=lams),
    x_shape=hnp.broadcastable_shapes((3, 1, 2), min_dims=0, max_dims=3),
    data=st.data(),
)
def test_one_mechanism_broadcasts_lambda_against_angles(lam, x_shape, data):
    x = data.draw(hnp.arrays(np.float64, x_shape, elements=angles))
    for fn in (gb.guide_angle, gb.crank_angle):
        out = fn(lam, x)
        shape = np.broadcast_shapes(lam.shape, x.shape)
        for k, arr in enumerate(out):
            assert arr.shape == shape
            idx = tuple(s - 1 for s in shape)
            one = fn(float(np.broadcast_to(lam, shape)[idx]), float(np.broadcast_to(x, shape)[idx]))
            assert arr[idx] == pytest.approx(one[k], rel=1e-14, abs=1e-14)


# --------------------------------------------------------------------------------------------
# periodicity, phase, oddness, inverse mechanisms
# --------------------------------------------------------------------------------------------
@SETTINGS
@given(p=drives(), theta=hnp.arrays(np.float64, 7, elements=angles))
def test_period_of_the_impellers(p, theta):
    per = gb.period(p)
    a, b = gb.impeller_angles(p, theta), gb.impeller_angles(p, theta + per)
    np.testing.assert_allclose(b[0] - a[0], 2.0 * np.pi / p.gear_ratio, rtol=1e-11, atol=1e-11)
    for k in (1, 2, 3):
        scale = np.max(np.abs(a[k])) + 1.0
        np.testing.assert_allclose(b[k], a[k], rtol=1e-9, atol=1e-9 * scale)


@SETTINGS
@given(p=drives(), theta=hnp.arrays(np.float64, 7, elements=angles))
def test_impeller_2_is_impeller_1_shifted_by_the_phase(p, theta):
    shift = p.phase * p.input_gear_ratio
    q = gb.impeller_angles(p, theta)
    q1 = gb.impeller_angles(p, theta + shift)
    for k in range(4):
        scale = np.max(np.abs(q[k][1])) + 1.0
        np.testing.assert_allclose(q[k][1], q1[k][0], rtol=1e-11, atol=1e-11 * scale)


@SETTINGS
@given(lam=lams, x=hnp.arrays(np.float64, 9, elements=angles))
def test_both_mechanisms_are_odd(lam, x):
    for fn in (gb.guide_angle, gb.crank_angle):
        f, fm = fn(lam, x), fn(lam, -x)
        np.testing.assert_allclose(fm[0], -f[0], atol=1e-12)
        np.testing.assert_allclose(fm[1], f[1], rtol=1e-13)  # even derivative
        np.testing.assert_allclose(fm[2], -f[2], atol=1e-12)
        np.testing.assert_allclose(fm[3], f[3], rtol=1e-12, atol=1e-12)
        f2 = fn(lam, x + 2.0 * np.pi)
        np.testing.assert_allclose(f2[0], f[0] + 2.0 * np.pi, atol=1e-12)


@SETTINGS
@given(p=drives(), s=hnp.arrays(np.float64, 7, elements=st.floats(0.0, 10.0)))
def test_relative_angle_is_even_about_an_equal_speed_point(p, s):
    theta_a = gb.equal_speed_angles(p.phase)[0] * p.input_gear_ratio
    r = gb.motion(p, np.concatenate([theta_a - s, theta_a + s])).relative
    n = s.size
    np.testing.assert_allclose(r[0][:n], r[0][n:], atol=1e-11)
    np.testing.assert_allclose(r[1][:n], -r[1][n:], atol=1e-11)  # odd speed difference
    # and stationary there: both impellers turn equally fast
    dq = gb.impeller_rates(p, theta_a)[0]
    assert dq[0] == pytest.approx(dq[1], rel=1e-12)


@SETTINGS
@given(lam=lams, x=hnp.arrays(np.float64, 9, elements=angles))
def test_guide_driven_is_crank_driven_run_backwards(lam, x):
    g = gb.guide_angle(lam, x)
    h = gb.crank_angle(lam, g[0])
    np.testing.assert_allclose(h[0], x, atol=1e-11)
    np.testing.assert_allclose(h[1] * g[1], 1.0, rtol=1e-12)
    # second order: h'' g'^2 + h' g'' = 0 (d2/dx2 of h(g(x)) = x)
    np.testing.assert_allclose(h[2] * g[1] ** 2 + h[1] * g[2], 0.0, atol=1e-10)


@SETTINGS
@given(lam=lams, x=hnp.arrays(np.float64, 5, elements=angles), driver=drivers)
def test_rates_are_the_derivatives_of_the_angle(lam, x, driver):
    """Central differences of the angle (an independent check of the closed forms)."""
    h = 1e-4
    f = [gb.driven_angle(lam, driver, x + k * h)[0] for k in (-2, -1, 0, 1, 2)]
    rates = gb.driven_rates(lam, driver, x)
    d1 = (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * h)
    d2 = (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * h * h)
    scale = 1.0 / (1.0 - lam) ** 3
    np.testing.assert_allclose(rates[0], d1, atol=1e-8 * scale)
    np.testing.assert_allclose(rates[1], d2, atol=1e-5 * scale)


# --------------------------------------------------------------------------------------------
# admissibility written once
# --------------------------------------------------------------------------------------------
bad_or_good = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.floats(-2.0, 3.0))


@SETTINGS
@given(
    lam=hnp.arrays(np.float64, 6, elements=st.one_of(lams, bad_or_good)),
    u=hnp.arrays(np.float64, 6, elements=st.one_of(ratios, bad_or_good)),
    phase=hnp.arrays(np.float64, 6, elements=st.one_of(phases, st.sampled_from([0.0, 2 * np.pi]))),
    driver=hnp.arrays("<U5", 6, elements=st.sampled_from(["crank", "guide", "slide"])),
)
def test_vectorised_check_names_what_the_dataclass_names(lam, u, phase, driver):
    codes = gb.inadmissible(lam, u, 1.0, phase, driver)
    for i in range(6):
        try:
            gb.GuideBar(float(lam[i]), float(u[i]), 1.0, float(phase[i]), str(driver[i]))
        except ParameterError as exc:
            assert codes[i] > 0 and gb.FIELDS[codes[i] - 1] == exc.name
        else:
            assert codes[i] == 0
    if codes.any():
        with pytest.raises(ParameterError) as err:
            gb.GuideBar(lam, u, 1.0, phase, driver)
        assert err.value.name == gb.FIELDS[codes[np.flatnonzero(codes)[0]] - 1]


@SETTINGS
@given(
    p=drives(),
    z=st.integers(0, 6),
    gamma=st.one_of(st.none(), st.floats(-0.2, 1.5)),
    rh=st.floats(-0.01, 0.1),
    w=st.floats(-0.01, 0.05),
)
def test_pump_check_names_what_the_pump_names(p, z, gamma, rh, w):
    code = int(gb_pump.inadmissible(p, z, gamma, rh, 0.08, w))
    try:
        gb_pump.vane_pump(p, z, gamma, rh, 0.08, w)
    except ParameterError as exc:
        assert code > 0 and gb_pump.CHECKS[code - 1] == exc.name
    else:
        assert code == 0


@SETTINGS
@given(p=drives(), z=st.integers(1, 4), theta=hnp.arrays(np.float64, 5, elements=angles))
def test_chamber_angles_share_the_space_between_the_vanes(p, z, theta):
    """phi_A + phi_B = 2 pi/Z - 2 gamma, and every chamber angle stays in its closed-form range."""
    try:
        pump = gb_pump.vane_pump(p, z, 0.02)
    except ParameterError:
        return
    phi = vp.chamber_angles(pump, gb.motion(p, theta))[0]
    np.testing.assert_allclose(phi[0::2] + phi[1::2], 2 * np.pi / z - 0.04, atol=1e-12)
    lo, hi = pump.chamber_angle_range
    assert np.all(phi >= lo - 1e-12) and np.all(phi <= hi + 1e-12)


@settings(max_examples=30, deadline=None)
@given(
    lam=hnp.arrays(np.float64, 5, elements=st.sampled_from([0.3, 0.5, 0.9, 1.0, -0.1])),
    z=hnp.arrays(np.int64, 5, elements=st.integers(0, 4)),
    rh=hnp.arrays(np.float64, 5, elements=st.sampled_from([0.0, 0.03, 0.08, 0.09])),
    ps=hnp.arrays(np.float64, 5, elements=st.sampled_from([0.0, 1.0e5])),
)
def test_sweep_reasons_name_what_the_study_names(lam, z, rh, ps):
    """The batch module's reason per design is the config key the scalar study's error names."""
    cfg = load_config(None, "guide-bar-pump", [])[0]
    table = {
        "drive.lambda": lam,
        "machine.vanes_per_impeller": z,
        "machine.hub_radius": rh,
        "loads.suction_pressure": ps,
    }
    p = Designs(cfg, table, 5)
    keys = reason_keys("guide_bar")
    reason = batch.reasons(p, {k: i for i, k in enumerate(keys)})
    for i in range(5):
        try:
            evaluate(p.config(i))
        except ParameterError as exc:
            assert keys[reason[i]] == exc.name
        else:
            assert reason[i] == 0


@SETTINGS
@given(
    designs=st.lists(
        st.tuples(drives(), st.integers(1, 3), st.floats(0.01, 0.3), st.floats(0.01, 0.07)),
        min_size=1,
        max_size=5,
    )
)
def test_pump_of_array_designs_equals_one_pump_per_design(designs):
    """The pump's closed forms over (n,) arrays of designs equal the pumps built one by one."""
    ones = []
    for p, z, gamma, rh in designs:
        try:
            ones.append((p, gb_pump.vane_pump(p, z, gamma, rh)))
        except ParameterError:
            continue
    if not ones:
        return
    fields = ("lam", "gear_ratio", "input_gear_ratio", "phase", "driver")
    params = gb.GuideBar(*(np.array([getattr(p, f) for p, _ in ones]) for f in fields))
    many = gb_pump.vane_pump(
        params,
        np.array([one.vanes_per_impeller for _, one in ones]),
        np.array([one.vane_angle for _, one in ones]),
        np.array([one.hub_radius for _, one in ones]),
    )
    disp = gb_pump.displacement(params, many)
    for i, (p, one) in enumerate(ones):
        assert many.swing[i] == pytest.approx(one.swing, rel=1e-14, abs=1e-15)
        assert many.vane_angle_max[i] == pytest.approx(one.vane_angle_max, rel=1e-14, abs=1e-15)
        for a, b in zip(many.chamber_angle_range, one.chamber_angle_range, strict=True):
            assert a[i] == pytest.approx(b, rel=1e-13, abs=1e-14)
        for key, value in gb_pump.displacement(p, one).items():
            assert disp[key][i] == pytest.approx(value, rel=1e-13)
