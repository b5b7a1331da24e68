"""The grid search of :mod:`rotorkin.core.nearby` against measuring every pair.

Random clouds and curves, queries inside, at the edge of and far outside the points,
radii up to the cell: every count, pair and nearest point equals the brute-force
answer (distances point to point with numpy's norm).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rotorkin.core.nearby import PointGrid, closest_pair

SETTINGS = settings(max_examples=40, deadline=None)


def _cloud(seed, n, curve):
    rng = np.random.default_rng(seed)
    if curve:  # a knotted curve on the unit sphere: points bunched along a line
        t = np.sort(rng.uniform(0, 2 * np.pi, n))
        p = np.stack([np.cos(t) * np.cos(3 * t), np.sin(t) * np.cos(3 * t), np.sin(3 * t)], 1)
        return p
    return rng.normal(size=(n, 3)) * rng.uniform(0.01, 10.0)


def _brute(points, queries):
    return np.linalg.norm(queries[:, None, :] - points[None, :, :], axis=2)


@SETTINGS
@given(
    seed=st.integers(0, 2**31),
    n=st.integers(1, 300),
    q=st.integers(1, 200),
    curve=st.booleans(),
    frac=st.floats(0.001, 1.0),
)
def test_searches_equal_measuring_every_pair(seed, n, q, curve, frac):
    points = _cloud(seed, n, curve)
    rng = np.random.default_rng(seed + 1)
    span = float(np.ptp(points, axis=0).max()) or 1.0
    queries = np.concatenate([
        points[rng.integers(0, n, q // 2)] + rng.normal(scale=0.05 * span, size=(q // 2, 3)),
        rng.uniform(-1.5, 1.5, size=(q - q // 2, 3)) * span,  # many far from every point
    ])  # fmt: skip
    radius = frac * span
    grid = PointGrid(points, radius)
    dist = _brute(points, queries)

    assert np.array_equal(grid.count_within(queries, radius), (dist <= radius).sum(axis=1))
    odd = (np.arange(q)[:, None] + np.arange(n)[None, :]) % 2 == 1  # pairs skipped
    got = grid.count_within(queries, radius, skip=lambda r, c: (r[:, None] + c[None, :]) % 2 == 1)
    assert np.array_equal(got, ((dist <= radius) & ~odd).sum(axis=1))

    qi, pi, d = grid.pairs_within(queries, radius)
    want = set(zip(*np.nonzero(dist <= radius), strict=True))
    assert set(zip(qi.tolist(), pi.tolist(), strict=True)) == want
    assert len(qi) == len(want)
    assert np.allclose(d, dist[qi, pi], rtol=0, atol=1e-12 * span)

    near_d, near_i = grid.nearest(queries, radius)
    best = dist.min(axis=1)
    found = best <= radius
    assert np.array_equal(near_i < n, found)
    assert np.allclose(near_d[found], best[found], rtol=0, atol=1e-12 * span)
    assert np.all(np.isinf(near_d[~found])) and np.all(near_i[~found] == n)

    pairs = grid.close_pairs(radius)
    own = _brute(points, points)
    i, j = np.nonzero(np.triu(own <= radius, k=1))
    assert set(map(tuple, pairs.tolist())) == set(zip(i.tolist(), j.tolist(), strict=True))


@SETTINGS
@given(seed=st.integers(0, 2**31), n=st.integers(1, 400), m=st.integers(1, 300))
def test_closest_pair_is_the_smallest_distance(seed, n, m):
    rng = np.random.default_rng(seed)
    a, b = rng.normal(size=(n, 3)), rng.normal(size=(m, 3)) + rng.normal(size=3)
    i, j, d = closest_pair(a, b, chunk=1000)  # several blocks
    dist = _brute(b, a)
    assert d == pytest.approx(dist.min(), abs=1e-12)
    assert d == pytest.approx(np.linalg.norm(a[i] - b[j]), abs=0)


def test_a_point_exactly_one_cell_away_is_found():
    """At the radius itself the point counts (distance <= r), rounding of the cells
    notwithstanding."""
    points = np.array([[0.0, 0.0, 0.0], [0.3, 0.0, 0.0]])
    grid = PointGrid(points, 0.1)
    q = np.array([[0.1, 0.0, 0.0], [0.2, 0.0, 0.0], [0.0999999, 0.0, 0.0]])
    assert grid.count_within(q, 0.1).tolist() == [1, 1, 1]


def test_radius_above_the_cell_and_empty_input_are_refused():
    grid = PointGrid(np.zeros((3, 3)), 0.5)
    with pytest.raises(ValueError, match="radius"):
        grid.count_within(np.zeros((1, 3)), 2.0)
    with pytest.raises(ValueError, match="at least one point"):
        PointGrid(np.zeros((0, 3)), 1.0)
    # coincident points: every one counted
    assert grid.count_within(np.zeros((2, 3)), 0.5).tolist() == [3, 3]
    # far and non-finite queries have no neighbour (no warning, no wrapped cell number)
    far = np.array([[1e300, 0, 0], [np.nan, 0, 0], [-np.inf, 1, 1], [0.1, 0, 0]])
    assert grid.count_within(far, 0.5).tolist() == [0, 0, 0, 3]
    assert grid.nearest(far, 0.5)[1].tolist() == [3, 3, 3, 0]
