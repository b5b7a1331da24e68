"""Where a groove of the spherical cam has both walls: the gaps that crossings cut in them.

Where two branches of the grooves cross (or run close), each is cut through by the
other's channel. A roller runs between both walls only while its contact lines on both
walls lie on material. The contact line with wall ``s`` (``s = +1`` the ``+n`` wall,
``-1`` the ``-n`` wall) at shaft angle theta is the segment

    q(lambda) = lambda e_r(theta) + s h n(theta),   lambda over the roller's length

(``h = rho + c/2`` the groove's half-width, :attr:`SphericalCam.groove_half_width`;
``lambda`` between the roller's end faces, :attr:`SphericalCam.roller_span`). A channel
is the region swept by its tool, the cylinder of radius h on the radial line through
the centre-line: a point p lies in some channel where

    min over every groove and theta' of |p x e(theta')| < h.

The contact line touches its own channel (``= h`` at ``theta' = theta``, and no closer
nearby while the roller does not undercut), so wall ``s`` is missing at theta exactly
where a point of its contact line is strictly inside a channel. Computed here on
:data:`CONTACT_POINTS` points of the line: every groove's axes sampled into a grid of
cells (:class:`rotorkin.core.nearby.PointGrid`), a point tested against its nearest
axis sample (within ``r (pad/2)^2`` of the nearest axis); the shaft angles
scanned on :data:`SCAN` samples per groove period and every end of a gap refined by
bisection. In angular terms the contact line and the channel scale alike with the
radius (both ``atan(h / lambda)`` seen from the centre), so a gap is longest at the
roller's inner end.

Departs from the straight-branch estimate ``2 rho / sin(a)`` (the centre's distance from
the crossing, :meth:`GrooveCrossing.gap_length`): the wall's own offset shifts its gap
along the branch by ``h cot(a)``, so one wall or the other is missing over about
``2 h (cot a + 1/sin a) r / lambda_in`` of the path (22.5 mm in the example, not 11.3 mm).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.nearby import PointGrid
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam.grooves import (
    distinct_grooves,
    groove_derivatives,
    groove_period,
)

__all__ = [
    "WallGap",
    "CONTACT_POINTS",
    "contact_radii",
    "wall_gaps",
    "walls_present",
    "unguided_stretches",
]

#: Points on a contact line (between the roller's end faces) that are tested.
CONTACT_POINTS = 5
#: Shaft-angle samples per groove period of the scan (and of the axes searched).
SCAN = 2048
#: Bisection steps on each end of a gap.
_BISECT = 36
#: Bisection steps taken per search (a divisor of :data:`_BISECT`).
_LEVELS = 3


@dataclass(frozen=True)
class WallGap:
    """An interval of shaft angle over which one wall of one roller's groove is missing.

    Attributes
    ----------
    roller : int
        Roller index (order of :func:`rotorkin.drives.wobble_cam.kinematics.roller_offsets`).
    wall : int
        0: the ``+n`` wall, 1: the ``-n`` wall.
    start, end : float
        The interval [rad], ``start < end``, ``start`` in ``[0, period)``; repeats every
        ``period``.
    period : float
        Groove period [rad].
    """

    roller: int
    wall: int
    start: float
    end: float
    period: float

    def contains(self, theta):
        """Whether theta [rad] (array) lies in the interval or its repeats."""
        return (np.asarray(theta, dtype=float) - self.start) % self.period <= self.end - self.start


def contact_radii(cam, count: int = CONTACT_POINTS) -> np.ndarray:
    """Distances ``lambda`` of the tested points of a contact line from the centre [m].

    ``count`` points from the roller's inner to its outer end face
    (:attr:`SphericalCam.roller_span`).
    """
    lo, hi = cam.roller_span
    return np.linspace(lo, hi, int(count))


class _Channels:
    """Every distinct groove's axes, sampled into a grid of cells, and the rollers' own curves."""

    def __init__(self, drive, cam):
        self.drive, self.h = drive, cam.groove_half_width
        self.lam_in = cam.roller_span[0]
        self.period = groove_period(drive)
        r = drive.sphere_radius
        rollers = distinct_grooves(drive)
        t = np.arange(SCAN) * (self.period / SCAN)
        g, d1, _ = groove_derivatives(drive, t)
        self.axes = np.moveaxis(g[rollers], 1, 2).reshape(-1, 3) / r
        self.owner = np.repeat(np.array(rollers), SCAN)
        # arc length along every roller's centre-line (on the sphere r) at the samples
        speed = np.linalg.norm(d1, axis=1)  # (4, N)
        self.arc = np.cumsum(speed, axis=1) * (self.period / SCAN)
        self.length = self.arc[:, -1].copy()
        # which distinct groove each roller runs in, and the samples it is shifted by
        self.curve = {}
        for k in range(4):
            for i in rollers:
                for m in range(int(round(self.period / np.pi))):
                    shift = m * SCAN * np.pi / self.period
                    if shift == int(shift) and np.allclose(
                        g[k], np.roll(g[i], -int(shift), axis=1), atol=1e-9 * r
                    ):
                        self.curve.setdefault(k, (i, int(shift)))
        # largest angle between neighbouring axis samples: every search reaches that further
        self.pad = 1.01 * float(np.max(speed)) * (self.period / SCAN) / r
        self.eps = 1e-9 * r
        # chords of the searches: near_others', and inside's (its points lie beyond lam_in)
        self.reach = 2.0 * np.sin(np.arcsin(min(1.0, 1.05 * self.h / self.lam_in))) + 2 * self.pad
        self.grid = PointGrid(self.axes, self.reach)
        self.reach_in = 2.0 * np.sin(0.5 * np.arcsin(min(1.0, self.h / self.lam_in))) + self.pad
        self.grid_in = PointGrid(self.axes, self.reach_in)

    def near_others(self, roller):
        """Samples of ``roller``'s centre-line within 2 h of another branch (bool, (SCAN,)).

        Another branch is another groove, or the roller's own groove more than 2.5 h away
        along it (where a figure-eight crosses itself): every axis sample within reach of
        a sample (on the unit sphere), less those of its own stretch of groove.
        """
        i, shift = self.curve[roller]
        own = self.axes[self.owner == i]  # the roller's own curve, shifted by ``shift``
        at = (np.arange(SCAN) + shift) % SCAN  # the sample of curve i each point sits at
        arc, length, h = self.arc[i], self.length[i], self.h

        def own_stretch(rows, cand):
            gap = np.abs(arc[cand % SCAN][None, :] - arc[at[rows]][:, None])
            return (self.owner[cand] == i)[None, :] & (np.minimum(gap, length - gap) <= 2.5 * h)

        return self.grid.count_within(own[at], self.reach, skip=own_stretch) > 0

    def inside(self, points):
        """Whether each point (n, 3) [m] lies strictly inside some channel (bool, (n,)).

        A point is inside when its distance from the nearest axis sample (the smallest
        angle: the nearest on the unit sphere) is below the half-width. The closest axis
        sample stands within ``r (pad/2)^2`` of the closest axis (0.02 um in the example):
        the test is exact to that.
        """
        rad = np.linalg.norm(points, axis=1)
        reach = 2.0 * np.sin(0.5 * np.arcsin(np.minimum(self.h / rad, 1.0))) + self.pad
        chord, near = self.grid_in.nearest(points / rad[:, None], float(np.max(reach, initial=0.0)))
        out = np.zeros(len(points), dtype=bool)
        idx = np.flatnonzero(chord <= reach)
        if not len(idx):
            return out
        p, e = points[idx], self.axes[near[idx]]
        along = np.einsum("ij,ij->i", p, e)
        dist = np.sqrt(np.maximum(np.einsum("ij,ij->i", p, p) - along * along, 0.0))
        out[idx] = (along > 0.0) & (dist < self.h - self.eps)
        return out


def _missing(channels, cam, roller, theta, wall):
    """Whether the wall is missing: rollers, shaft angles and walls (0: +n) broadcast (bool)."""
    roller, theta, wall = np.broadcast_arrays(
        np.asarray(roller, dtype=int), np.asarray(theta, dtype=float), np.asarray(wall)
    )
    flat = theta.ravel()
    g, d1, _ = groove_derivatives(channels.drive, flat)
    k = np.arange(len(flat))
    g, d1 = g[roller.ravel(), :, k], d1[roller.ravel(), :, k]  # (T, 3)
    e = g / np.linalg.norm(g, axis=1, keepdims=True)
    n = np.cross(e, d1 / np.linalg.norm(d1, axis=1, keepdims=True))
    side = np.where(wall.ravel() == 0, 1.0, -1.0)[:, None]
    lam = contact_radii(cam)
    pts = lam[:, None, None] * e[None] + (side * cam.groove_half_width) * n[None]  # (L, T, 3)
    inside = channels.inside(pts.reshape(-1, 3))
    return inside.reshape(len(lam), -1).any(axis=0).reshape(theta.shape)


def _bisected(channels, cam, roller, wall, a, b, levels):
    """``levels`` bisection steps of every bracket (a: the wall there, b: missing) at once.

    Every midpoint the steps could visit (``2^levels - 1`` a bracket, computed as the
    steps compute them, ``0.5 (a + b)``) is searched in one call; the steps then walk
    them. The brackets returned are those of the steps taken one by one.
    """
    ends = [a, b]
    for _ in range(levels):  # the midpoints between every pair of neighbours, in order
        mids = [0.5 * (lo + hi) for lo, hi in zip(ends[:-1], ends[1:], strict=True)]
        ends = [x for pair in zip(ends[:-1], mids, strict=True) for x in pair] + [ends[-1]]
    ends = np.stack(ends)  # (2^levels + 1, brackets)
    inner = ends[1:-1]
    miss = _missing(channels, cam, roller[None, :], inner, wall[None, :])
    k = np.arange(len(a))
    lo, hi = np.zeros(len(a), dtype=int), np.full(len(a), len(ends) - 1)
    for _ in range(levels):
        mid = (lo + hi) // 2
        flag = miss[mid - 1, k]
        lo, hi = np.where(flag, lo, mid), np.where(flag, mid, hi)
    return ends[lo, k], ends[hi, k]


def _runs(mask):
    """Runs of True in a periodic boolean array: list of (first, last) indices."""
    n = len(mask)
    if mask.all():
        return [(0, n - 1)]
    start = int(np.argmin(mask))  # a False sample: no run wraps past it
    rolled = np.roll(mask, -start).astype(int)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], rolled, [0]])))
    return [(int(a) + start, int(b) - 1 + start) for a, b in zip(edges[::2], edges[1::2],
                                                                    strict=True)]  # fmt: skip


def wall_gaps(drive: wc.WobbleCam, cam, crossings=None) -> list[WallGap]:
    """Every interval of shaft angle over which a wall of a roller's groove is missing.

    Parameters
    ----------
    drive : WobbleCam
    cam : SphericalCam
        Its groove half-width and roller span set the contact lines.
    crossings : object, optional
        Not needed (the channels are searched directly); accepted so that callers holding
        :func:`groove_crossings` can pass them.

    Returns
    -------
    list of WallGap
        Sorted by roller, wall and start.
    """
    channels = _Channels(drive, cam)
    period = channels.period
    step = period / SCAN
    theta = (np.arange(SCAN) + 0.5) * step
    # the scan: every roller's samples near another branch, both walls, in one search
    rows = []  # (roller, wall, sample)
    for roller in range(4):
        near = channels.near_others(roller)
        near |= np.roll(near, 1) | np.roll(near, -1)  # the scan samples sit between them
        at = np.flatnonzero(near)
        for wall in (0, 1):
            rows.append(np.stack(np.broadcast_arrays(roller, wall, at)))
    brackets = []  # (roller, wall, outside, inside): both ends of every run of the scan
    whole = []  # walls missing over the whole period
    rows = np.concatenate(rows, axis=1)
    if rows.size:
        missing = _missing(channels, cam, rows[0], theta[rows[2]], rows[1])
        miss = np.zeros((4, 2, SCAN), dtype=bool)
        miss[rows[0], rows[1], rows[2]] = missing
        for roller, wall in np.ndindex(4, 2):
            for i, j in _runs(miss[roller, wall]):
                if (i, j) == (0, SCAN - 1):  # the wall is nowhere (the grooves cut it away)
                    whole.append(WallGap(roller, wall, 0.0, period, period))
                    continue
                brackets.append((roller, wall, theta[i % SCAN] - step, theta[i % SCAN]))
                brackets.append((roller, wall, theta[j % SCAN] + step, theta[j % SCAN]))
    out = whole
    if brackets:
        roller, wall, a, b = (np.array(x) for x in zip(*brackets, strict=True))
        for _ in range(_BISECT // _LEVELS):  # a: the wall there, b: missing
            a, b = _bisected(channels, cam, roller, wall, a, b, _LEVELS)
        ends = 0.5 * (a + b)
        for k in range(0, len(ends), 2):
            lo, hi = ends[k], ends[k + 1]
            hi = hi + period if hi < lo else hi
            start = float(lo % period)
            out.append(WallGap(int(roller[k]), int(wall[k]), start, start + hi - lo, period))
    return sorted(out, key=lambda w: (w.roller, w.wall, w.start))


def walls_present(drive: wc.WobbleCam, cam, theta, gaps=None):
    """Whether each wall of each roller's groove is there along its whole contact line.

    Parameters
    ----------
    drive, cam : WobbleCam, SphericalCam
    theta : array_like, shape (...)
        Shaft angle [rad].
    gaps : list of WallGap, optional
        Default :func:`wall_gaps`.

    Returns
    -------
    ndarray of bool, shape (4, 2, ...)
        Roller, wall (``+n``, ``-n``).
    """
    theta = np.asarray(theta, dtype=float)
    gaps = wall_gaps(drive, cam) if gaps is None else gaps
    out = np.ones((4, 2) + theta.shape, dtype=bool)
    for gap in gaps:
        out[gap.roller, gap.wall] &= ~gap.contains(theta)
    return out


def unguided_stretches(drive: wc.WobbleCam, gaps) -> list[tuple[int, float, float, float]]:
    """Stretches with one wall or the other missing: ``(roller, start, end, length [m])``.

    The gaps of a roller's two walls merged where they overlap; the length is the path
    of the roller centre on the sphere r.
    """
    out = []
    for roller in range(4):
        mine = sorted((g.start, g.end) for g in gaps if g.roller == roller)
        merged: list[list[float]] = []
        for lo, hi in mine:
            if merged and lo <= merged[-1][1]:
                merged[-1][1] = max(merged[-1][1], hi)
            else:
                merged.append([lo, hi])
        for lo, hi in merged:
            t = np.linspace(lo, hi, 257)
            speed = np.linalg.norm(groove_derivatives(drive, t)[1][roller], axis=0)
            out.append((roller, lo, hi, float(np.trapezoid(speed, t))))
    return out
