"""``core.batch.distinct``: the distinct rows of per-design values, against a set of tuples."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rotorkin.core import batch
from rotorkin.core.batch import distinct

# values that look alike but are not the same bits
_VALUES = [0.0, -0.0, 1.0, 1.0 + 2**-52, np.nan, -np.inf, 0.3, 2.5e-308]


def _bits(x) -> int:
    return int(np.float64(x).view(np.int64))


def _check(columns, n):
    rows, inverse = distinct(columns, n)
    assert inverse.shape == (n,) and inverse.dtype.kind == "i"
    m = rows[0].size
    assert all(r.shape == (m,) for r in rows)
    full = [np.broadcast_to(np.asarray(c, dtype=float), (n,)) for c in columns]
    # every design's row holds its values, bit for bit
    for c, r in zip(full, rows, strict=True):
        assert np.array_equal(r[inverse].view(np.int64), c.view(np.int64))
    # the rows are distinct and as many as the distinct tuples of bits
    tuples = {tuple(_bits(c[i]) for c in full) for i in range(n)}
    assert len({tuple(_bits(r[j]) for r in rows) for j in range(m)}) == m == len(tuples)


@settings(max_examples=60, deadline=None)
@given(
    n=st.integers(1, 40),
    kinds=st.lists(st.sampled_from(["scalar", "few", "many"]), min_size=1, max_size=4),
    seed=st.integers(0, 2**32 - 1),
)
def test_distinct_rows_against_tuples(n, kinds, seed):
    rng = np.random.default_rng(seed)
    columns = []
    for kind in kinds:
        if kind == "scalar":
            columns.append(float(rng.choice(_VALUES)))
        elif kind == "few":
            columns.append(rng.choice(_VALUES[: rng.integers(1, 4)], n))
        else:
            columns.append(rng.choice(_VALUES, n))
    _check(columns, n)


def test_distinct_by_sort_where_the_codes_are_too_many(monkeypatch):
    """Columns whose number-tuples exceed the direct count are numbered by sorting."""
    monkeypatch.setattr(batch, "_DIRECT_CODES", 4)
    rng = np.random.default_rng(3)
    n = 30
    columns = [rng.choice(_VALUES, n), rng.choice([1.0, 2.0, 3.0], n), 7.0, rng.choice(_VALUES, n)]
    _check(columns, n)


@pytest.mark.parametrize("columns", [[0.5, 2.0], [np.full(9, 0.5), 2.0]])
def test_distinct_of_one_design(columns):
    rows, inverse = distinct(columns, 9)
    assert [r.tolist() for r in rows] == [[0.5], [2.0]] and inverse.tolist() == [0] * 9


def test_distinct_when_every_row_differs():
    a = np.arange(12.0)
    rows, inverse = distinct([a, 1.0], 12)
    assert np.array_equal(rows[0][inverse], a) and np.all(rows[1] == 1.0)
