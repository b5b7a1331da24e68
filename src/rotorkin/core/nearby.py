"""Which points lie near which: a uniform grid of cells, searched with numpy.

A point within ``cell`` of a query lies in one of the 27 cells around the query's own
(cells of side ``cell``). :class:`PointGrid` sorts the points by cell once; a search
sorts the queries by cell, and measures every query of a cell against every point of
the 27 cells around it in one matrix product: the loop runs over occupied cells, never
over points or queries, and no compiled tree is needed.

Made for points along curves (a cam's grooves sampled at a few thousand points): a
search measures each query against the points within about 1.5 cells of it, so its cost
grows with the cell against the distances asked for.
"""

from __future__ import annotations

import numpy as np

__all__ = ["PointGrid", "closest_pair"]

#: The 27 cell offsets around a cell, itself included.
_AROUND = np.stack(np.meshgrid(*[np.arange(-1, 2)] * 3, indexing="ij"), -1).reshape(-1, 3)
#: Cells across the points' widest extent, at most: fewer, fuller cells (a search's
#: loop runs over the occupied cells; each measures its queries in one product).
_CELLS_ACROSS = 32


class PointGrid:
    """Points in 3D bucketed into cubic cells, for searches within a distance of ``cell``.

    Parameters
    ----------
    points : array_like, shape (n, 3)
    cell : float
        The largest distance a search may ask for: the side of a cell, enlarged to a
        32nd of the points' widest extent where that is larger (the answers stay the
        same).
    """

    def __init__(self, points, cell: float):
        self.points = _as_points(points)
        if not len(self.points):
            raise ValueError("PointGrid needs at least one point")
        span = float(np.ptp(self.points, axis=0).max())
        # a hair larger: a point exactly ``cell`` away, rounded, still in a neighbouring cell
        self.cell = max(float(cell) * (1.0 + 1e-9), span / _CELLS_ACROSS, np.finfo(float).tiny)
        ijk = self._cells(self.points)
        self.lo = ijk.min(axis=0) - 1
        self.shape = ijk.max(axis=0) - self.lo + 2
        key = self._key(ijk)
        self.order = np.argsort(key, kind="stable")
        self.keys = key[self.order]
        self._squares = np.einsum("ij,ij->i", self.points, self.points)

    def _cells(self, xyz):
        """Integer cell coordinates (far or non-finite points clipped: no cell of the grid)."""
        with np.errstate(invalid="ignore"):
            return np.clip(np.nan_to_num(np.floor(xyz / self.cell), nan=-(2.0**60)),
                           -(2.0**60), 2.0**60).astype(np.int64)  # fmt: skip

    def _key(self, ijk):
        """Each cell's number, -1 outside the grid (no point there)."""
        rel = ijk - self.lo
        inside = np.all((rel >= 0) & (rel < self.shape), axis=-1)
        key = (rel[..., 0] * self.shape[1] + rel[..., 1]) * self.shape[2] + rel[..., 2]
        return np.where(inside, key, -1)

    def _cells_of(self, queries, radius):
        """The queries cell by cell, with the points in the 27 cells around each cell.

        Yields ``(rows, cand)``: the queries in one cell (indices) and the points around
        it (indices). A cell whose surroundings hold no point is not yielded.
        """
        if float(radius) > self.cell:
            raise ValueError(f"radius = {float(radius)} is above the grid's cell {self.cell}")
        cells = self._cells(queries)
        own = self._key(cells)
        by_cell = np.argsort(own, kind="stable")
        keys, first = np.unique(own[by_cell], return_index=True)
        bounds = np.append(first, len(own))
        around = self._key(cells[by_cell[first]][:, None, :] + _AROUND)  # (G, 27)
        start = np.searchsorted(self.keys, around, side="left")
        count = np.where(around >= 0, np.searchsorted(self.keys, around, side="right") - start, 0)
        total = count.sum(axis=1)
        c, s = count.ravel(), start.ravel()
        slot = np.repeat(s - (np.cumsum(c) - c), c) + np.arange(c.sum())
        cands = np.split(self.order[slot], np.cumsum(total)[:-1])
        for g in np.flatnonzero(total):
            yield by_cell[bounds[g] : bounds[g + 1]], cands[g]

    def _groups(self, queries, radius):
        """The queries cell by cell, each cell's queries against the points around it.

        Yields ``(rows, cand, d2)``: :meth:`_cells_of`'s rows and candidates, and their
        squared distances ``(len(rows), len(cand))``, written ``|q|^2 + |p|^2 - 2 q.p``
        (one matrix product a cell; rounding ~1e-16 of the squared norms) except within
        rounding of ``radius^2``, where ``d2 <= radius^2`` is made to say what
        ``|q - p| <= radius`` says.
        """
        radius = float(radius)
        r2 = radius * radius
        qq = np.einsum("ij,ij->i", queries, queries)
        for rows, cand in self._cells_of(queries, radius):
            scale = qq[rows, None] + self._squares[cand]
            d2 = scale - 2.0 * (queries[rows] @ self.points[cand].T)
            # within rounding of the radius: measured point to point, so that the
            # answer is ``|q - p| <= radius`` exactly
            i, j = np.nonzero(np.abs(d2 - r2) <= 1e-14 * scale + 1e-300)
            if len(i):
                s2 = np.sum((queries[rows[i]] - self.points[cand[j]]) ** 2, axis=1)
                d2[i, j] = np.where(np.sqrt(s2) <= radius, np.minimum(s2, r2),
                                    np.maximum(s2, np.nextafter(r2, np.inf)))  # fmt: skip
            yield rows, cand, d2

    def count_within(self, queries, radius, skip=None) -> np.ndarray:
        """How many points lie within ``radius`` (<= ``cell``) of each query (distance <= r).

        ``skip(rows, cand)``, if given, returns a boolean ``(len(rows), len(cand))``:
        the pairs of queries and points (indices) not to count.
        """
        queries = _as_points(queries)
        out = np.zeros(len(queries), dtype=np.intp)
        r2 = float(radius) ** 2
        for rows, cand, d2 in self._groups(queries, radius):
            hit = d2 <= r2
            if skip is not None:
                hit &= ~skip(rows, cand)
            out[rows] = np.count_nonzero(hit, axis=1)
        return out

    def pairs_within(self, queries, radius):
        """``(qi, pi, distance)`` of every point within ``radius`` of a query."""
        queries = _as_points(queries)
        r2 = float(radius) ** 2
        qi, pi = [np.zeros(0, dtype=np.intp)], [np.zeros(0, dtype=np.intp)]
        for rows, cand, d2 in self._groups(queries, radius):
            i, j = np.nonzero(d2 <= r2)
            qi.append(rows[i])
            pi.append(cand[j])
        qi, pi = np.concatenate(qi), np.concatenate(pi)
        return qi, pi, np.linalg.norm(queries[qi] - self.points[pi], axis=1)

    def nearest(self, queries, radius):
        """The nearest point within ``radius`` of each query.

        Returns
        -------
        distance, index : ndarray
            ``inf`` and ``n`` (one past the last point) where none is that close; the
            distance measured point to point (exact to rounding).
        """
        queries = _as_points(queries)
        distance = np.full(len(queries), np.inf)
        index = np.full(len(queries), len(self.points), dtype=np.intp)
        radius = float(radius)
        # the nearest of a cell's candidates maximises q.p - |p|^2 / 2 (|q|^2 is common
        # to a row): one matrix product and one pass a cell; whether it lies within the
        # radius is then measured point to point
        half = 0.5 * self._squares
        rows, best = [], []
        for cell_rows, cand in self._cells_of(queries, radius):
            score = queries[cell_rows] @ self.points[cand].T
            score -= half[cand]
            rows.append(cell_rows)
            best.append(cand[np.argmax(score, axis=1)])
        if rows:
            rows, best = np.concatenate(rows), np.concatenate(best)
            d = np.linalg.norm(queries[rows] - self.points[best], axis=1)
            hit = d <= radius
            index[rows[hit]], distance[rows[hit]] = best[hit], d[hit]
        return distance, index

    def close_pairs(self, radius):
        """Every pair ``i < j`` of the grid's own points within ``radius``: ``(k, 2)`` ints."""
        qi, pi, _ = self.pairs_within(self.points, radius)
        keep = qi < pi
        return np.stack([qi[keep], pi[keep]], axis=1)


def _as_points(xyz):
    return np.asarray(xyz, dtype=float).reshape(-1, 3)


def closest_pair(a, b, chunk: int = 1 << 20):
    """The closest pair of a point of ``a`` (n, 3) and one of ``b`` (m, 3): ``(i, j, distance)``.

    Every pair is measured (``|a|^2 + |b|^2 - 2 a.b``, a matrix product a block of
    about ``chunk`` pairs): the nearest pair of two curves, however far apart they run.
    The distance returned is measured point to point.
    """
    a, b = _as_points(a), _as_points(b)
    bb = np.einsum("ij,ij->i", b, b)
    rows = max(1, chunk // max(len(b), 1))
    best = (np.inf, 0, 0)
    for lo in range(0, len(a), rows):
        block = a[lo : lo + rows]
        d2 = (np.einsum("ij,ij->i", block, block)[:, None] + bb) - 2.0 * (block @ b.T)
        i, j = divmod(int(np.argmin(d2)), len(b))
        if d2[i, j] < best[0]:
            best = (float(d2[i, j]), lo + i, j)
    i, j = best[1], best[2]
    return i, j, float(np.linalg.norm(a[i] - b[j]))
