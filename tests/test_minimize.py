"""rotorkin.core.minimize.bounded_min against scipy.optimize.minimize_scalar, bracket by bracket."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize_scalar

from rotorkin.core.minimize import bounded_min


def _scipy(fun1, lo, hi, xatol=1e-12):
    res = minimize_scalar(fun1, bounds=(lo, hi), method="bounded", options={"xatol": xatol})
    return res.x, res.fun


CASES = {
    # name: (vectorised f(x, c, s), scalar params per bracket)
    "cosh": lambda x, c, s: np.cosh(s * (x - c)),
    "quartic": lambda x, c, s: s * (x - c) ** 4 + 0.1 * (x - c) ** 2,
    "kink": lambda x, c, s: np.abs(x - c) * s,
    "shifted_cos": lambda x, c, s: -np.cos(s * (x - c)),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_equals_scipy_bracket_by_bracket(name):
    f = CASES[name]
    rng = np.random.default_rng(7)
    n = 64
    lo = rng.uniform(-3.0, 1.0, n)
    hi = lo + rng.uniform(0.01, 2.0, n)
    c = lo + rng.uniform(-0.2, 1.2, n) * (hi - lo)  # some minima outside: at an edge
    s = rng.uniform(0.5, 3.0, n)
    if name == "shifted_cos":
        hi = np.minimum(hi, lo + 2.0 / s)  # one minimum per bracket
    x, fx = bounded_min(lambda t: f(t, c, s), lo, hi)
    assert x.shape == fx.shape == (n,)
    for i in range(n):
        xs, fs = _scipy(lambda t, i=i: float(f(t, c[i], s[i])), lo[i], hi[i])
        assert lo[i] <= x[i] <= hi[i]
        assert abs(x[i] - xs) <= 1e-8 * max(1.0, abs(xs)), (i, x[i], xs)
        assert fx[i] <= fs + 1e-7  # both stop within ~1e-8 of the minimum (the kink: slope s)
        assert fx[i] == f(x[i], c[i], s[i])


def test_interior_minimum_to_its_tolerance():
    c = np.linspace(0.1, 0.9, 9)
    x, _ = bounded_min(lambda t: (t - c) ** 2, 0.0, 1.0, xatol=1e-12)
    np.testing.assert_allclose(x, c, atol=1e-8)


@settings(max_examples=40, deadline=None)
@given(
    shape=st.lists(st.integers(1, 4), min_size=0, max_size=3),
    centre=st.floats(-5.0, 5.0),
    width=st.floats(0.1, 4.0),
)
def test_any_shape_and_each_element_alone(shape, centre, width):
    """Brackets of any shape broadcast; each element is what its own call gives."""
    shape = tuple(shape)
    rng = np.random.default_rng(abs(hash((shape, centre))) % 2**32)
    lo = centre + rng.uniform(-1.0, 0.0, shape)
    hi = lo + width
    c = lo + rng.uniform(0.0, 1.0, shape) * width
    x, fx = bounded_min(lambda t: np.cosh(t - c), lo, hi)
    assert np.shape(x) == shape
    flat_x = np.reshape(x, -1)
    flat = zip(np.reshape(lo, -1), np.reshape(hi, -1), np.reshape(c, -1), strict=True)
    for i, (l0, h0, c0) in enumerate(flat):
        xi, _ = bounded_min(lambda t, c0=c0: np.cosh(t - c0), l0, h0)
        assert flat_x[i] == xi


def test_calls_fun_once_per_iteration_with_the_whole_array():
    shapes = []

    def f(t):
        shapes.append(np.shape(t))
        return np.cosh(t - 0.3)

    bounded_min(f, np.zeros((2, 3)), np.ones((2, 3)))
    assert set(shapes) == {(2, 3)}
    assert len(shapes) < 60
