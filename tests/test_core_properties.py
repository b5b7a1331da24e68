"""Property tests of the core: chain rule to order 3, time derivatives, the angle helper.

Each property is checked against an independent computation (finite differences
of a composed function, the plain atan2 of a rotated vector), on random inputs of
any shape, so that broadcasting is tested with the formulas.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import array_shapes

from rotorkin.core.angles import angle_near
from rotorkin.core.motion import Motion, compose, time_derivatives

SETTINGS = settings(max_examples=40, deadline=None)
shapes = array_shapes(min_dims=0, max_dims=3, max_side=4)
coef = st.floats(-1.0, 1.0, allow_nan=False)


def _fd(f, x, h=1e-3):
    """First, second, third derivatives of f at x by central differences (O(h^2))."""
    f0 = f(x)
    fp, fm = f(x + h), f(x - h)
    f2p, f2m = f(x + 2 * h), f(x - 2 * h)
    d1 = (fp - fm) / (2 * h)
    d2 = (fp - 2 * f0 + fm) / h**2
    d3 = (f2p - 2 * fp + 2 * fm - f2m) / (2 * h**3)
    return d1, d2, d3


@SETTINGS
@given(shape=shapes, a=coef, b=coef, c=coef, seed=st.integers(0, 2**31))
def test_compose_matches_finite_differences_of_sin_of_a_cubic(shape, a, b, c, seed):
    theta = np.random.default_rng(seed).uniform(-1, 1, size=shape)

    def g_of(t):
        return (a * t + b * t**2 + c * t**3, a + 2 * b * t + 3 * c * t**2, 2 * b + 6 * c * t, 6 * c)

    def h(t):
        return np.sin(g_of(t)[0])

    g = g_of(theta)
    f = (np.sin(g[0]), np.cos(g[0]), -np.sin(g[0]), -np.cos(g[0]))
    h0, h1, h2, h3 = compose(f, g)
    assert np.shape(h1) == np.shape(theta)
    d1, d2, d3 = _fd(h, theta)
    # central differences err by O(h^2) times higher derivatives, which grow like g'^k
    s = float(np.max(1.0 + np.abs(g[1]) + np.abs(g[2]) + abs(6 * c)))
    np.testing.assert_allclose(h0, h(theta), atol=1e-12)
    np.testing.assert_allclose(h1, d1, atol=1e-6 * s**3)
    np.testing.assert_allclose(h2, d2, atol=1e-5 * s**4)
    np.testing.assert_allclose(h3, d3, atol=1e-5 * s**5)


@SETTINGS
@given(shape=shapes, w0=st.floats(5.0, 400.0), wd=st.floats(-50.0, 50.0), seed=st.integers(0, 9))
def test_time_derivatives_match_a_motion_in_time(shape, w0, wd, seed):
    """q = sin(theta(t)) with theta = w0 t + wd t^2 / 2: q' in time by finite differences."""
    t = np.random.default_rng(seed).uniform(0.0, 0.05, size=shape)

    def theta_of(tt):
        return w0 * tt + 0.5 * wd * tt**2

    th = theta_of(t)
    omega, omega_dot = w0 + wd * t, wd
    v, a, j = time_derivatives(np.cos(th), -np.sin(th), -np.cos(th), omega, omega_dot, 0.0)
    d1, d2, d3 = _fd(lambda tt: np.sin(theta_of(tt)), t, h=1e-3 / w0)  # 1e-3 rad a step
    np.testing.assert_allclose(v, d1, atol=1e-5 * w0)
    np.testing.assert_allclose(a, d2, atol=1e-4 * w0**2)
    np.testing.assert_allclose(j, d3, atol=1e-2 * w0**3)


@SETTINGS
@given(shape=shapes, seed=st.integers(0, 2**31))
def test_motion_in_time_broadcasts_over_members_and_angles(shape, seed):
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(4, 2, *shape))
    m = Motion(theta=rng.normal(size=shape), q=q[0], dq=q[1], d2q=q[2], d3q=q[3])
    v, a, j = m.in_time(100.0, 5.0, 1.0)
    assert v.shape == a.shape == j.shape == (2, *shape)
    np.testing.assert_allclose(v, q[1] * 100.0)
    np.testing.assert_allclose(a, q[2] * 1e4 + q[1] * 5.0)
    np.testing.assert_allclose(j, q[3] * 1e6 + 3 * q[2] * 100.0 * 5.0 + q[1])
    rel = m.relative
    np.testing.assert_allclose(rel[1], q[1][1] - q[1][0])


@SETTINGS
@given(shape=shapes, seed=st.integers(0, 2**31))
def test_angle_near_is_atan2_on_the_branch_nearest_the_reference(shape, seed):
    rng = np.random.default_rng(seed)
    ang = rng.uniform(-50, 50, size=shape)
    ref = ang + rng.uniform(-3.0, 3.0, size=shape)  # within pi of the true angle
    r = rng.uniform(0.1, 5.0, size=shape)
    got = angle_near(r * np.sin(ang), r * np.cos(ang), ref)
    np.testing.assert_allclose(got, ang, atol=1e-9)
    np.testing.assert_allclose(np.cos(got), np.cos(np.arctan2(np.sin(ang), np.cos(ang))))
