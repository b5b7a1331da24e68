"""Where the groove centre-lines of the spherical cam cross, and how close two grooves come.

The figure-eight of each groove crosses itself; where two branches cross, the groove
must be cut through and each branch loses its walls over ``2 rho / sin`` of the angle
between them. Split from :mod:`rotorkin.drives.wobble_cam.cam` (which re-exports every name).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.nearby import PointGrid, closest_pair
from rotorkin.drives.wobble_cam import grooves as gr
from rotorkin.drives.wobble_cam import kinematics as wc

__all__ = ["GrooveCrossing", "groove_crossings", "groove_separation"]


@dataclass(frozen=True)
class GrooveCrossing:
    """A point where two groove centre-lines cross (or one crosses itself).

    Attributes
    ----------
    rollers : tuple of int
        Roller indices (order of :func:`rotorkin.drives.wobble_cam.kinematics.roller_offsets`);
        equal for a self-crossing.
    theta : tuple of float
        Shaft angles at which each roller passes the point, in ``[0, period)`` [rad].
    point : ndarray, shape (3,)
        The crossing point in the cam frame [m].
    angle : float
        Angle between the two branches, in ``(0, pi/2]`` [rad].
    period : float
        Groove period [rad]: each roller passes again every ``period``.
    """

    rollers: tuple
    theta: tuple
    point: np.ndarray
    angle: float
    period: float

    def shaft_angles(self, k: int = 0, turn: float = 2.0 * np.pi) -> np.ndarray:
        """Shaft angles in ``[0, turn)`` at which branch k's roller passes the point [rad]."""
        return np.arange(self.theta[k], turn - 1e-12, self.period)

    def gap_length(self, roller_radius: float) -> float:
        """Length of either branch left without walls by the other groove: ``2 rho / sin`` [m]."""
        return 2.0 * roller_radius / np.sin(self.angle)


def _newton_crossing(drive, ri, rj, t1, t2, iterations=30):
    """Gauss-Newton on ``g_i(t1) = g_j(t2)``, vectorized over candidates (pinv: no singular)."""
    k = np.arange(len(ri))
    for _ in range(iterations + 1):
        g1, d1, _ = gr.groove_derivatives(drive, t1)
        g2, d2, _ = gr.groove_derivatives(drive, t2)
        a, da, b, db = g1[ri, :, k], d1[ri, :, k], g2[rj, :, k], d2[rj, :, k]
        jac = np.stack([da, -db], axis=2)  # (K, 3, 2)
        rhs = -np.einsum("kia,ki->ka", jac, a - b)
        step = np.einsum("kab,kb->ka", np.linalg.pinv(np.einsum("kia,kib->kab", jac, jac)), rhs)
        if np.all(np.abs(step) < 1e-15):
            break
        t1, t2 = t1 + step[:, 0], t2 + step[:, 1]
    return t1, t2, np.linalg.norm(a - b, axis=1), a, da, db


def groove_crossings(
    drive: wc.WobbleCam, samples: int = gr._SEARCH_SAMPLES
) -> list[GrooveCrossing]:
    """Every crossing of the groove centre-lines: self-crossings and between rollers.

    The closed centre-lines (:func:`distinct_grooves`, over :func:`groove_period`) are
    sampled as polylines; segment pairs closer than one segment are tested for a
    crossing in the gnomonic projection on the tangent plane (great circles map to
    straight lines); each hit is refined by Gauss-Newton on
    ``g_i(theta_1) = g_j(theta_2)`` (residual ~1e-16 m) and duplicates are merged.

    Parameters
    ----------
    drive : WobbleCam
    samples : int, optional
        Polyline points per groove period.

    Returns
    -------
    list of GrooveCrossing
        Sorted by rollers, then shaft angle.
    """
    period = gr.groove_period(drive)
    rollers = np.array(gr.distinct_grooves(drive))
    step = period / samples
    # offset by an irrational fraction of a step: crossings rarely fall on a sample
    theta = (np.arange(samples) + gr._SAMPLE_SHIFT) * step
    g = gr.groove_derivatives(drive, theta)[0][rollers]  # (m, 3, N)
    m, n = len(rollers), samples
    pts = np.moveaxis(g, 1, 2).reshape(-1, 3)  # (m N, 3)
    idx = np.arange(m * n)
    nxt = (idx // n) * n + (idx % n + 1) % n
    mid = 0.5 * (pts + pts[nxt])
    reach = float(np.max(np.linalg.norm(pts[nxt] - pts, axis=1)))
    pairs = PointGrid(mid, 1.01 * reach).close_pairs(1.01 * reach)
    if len(pairs) == 0:
        return []
    a, b = pairs[:, 0], pairs[:, 1]
    gap = np.abs(a % n - b % n)
    adjacent = (a // n == b // n) & (np.minimum(gap, n - gap) <= 1)
    a, b = a[~adjacent], b[~adjacent]
    # gnomonic projection on the tangent plane at the pair's mean direction
    c = mid[a] + mid[b]
    c /= np.linalg.norm(c, axis=1, keepdims=True)
    e1 = np.cross(c, np.where(np.abs(c[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]]))
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    e2 = np.cross(c, e1)

    def proj(p):
        q = p / np.sum(p * c, axis=1, keepdims=True)
        return np.stack([np.sum(q * e1, 1), np.sum(q * e2, 1)], 1)

    p0, p1, q0, q1 = proj(pts[a]), proj(pts[nxt[a]]), proj(pts[b]), proj(pts[nxt[b]])
    d_p, d_q, w = p1 - p0, q1 - q0, q0 - p0
    den = d_p[:, 0] * d_q[:, 1] - d_p[:, 1] * d_q[:, 0]
    safe = np.where(np.abs(den) > 0, den, 1.0)
    s = (w[:, 0] * d_q[:, 1] - w[:, 1] * d_q[:, 0]) / safe
    u = (w[:, 0] * d_p[:, 1] - w[:, 1] * d_p[:, 0]) / safe
    eps = 1e-9  # segments touching at a sample: both neighbours hit, duplicates merge below
    hit = (np.abs(den) > 0) & (s >= -eps) & (s <= 1 + eps) & (u >= -eps) & (u <= 1 + eps)
    if not np.any(hit):
        return []
    a, b, s, u = a[hit], b[hit], s[hit], u[hit]
    t1 = (a % n + gr._SAMPLE_SHIFT + s) * step
    t2 = (b % n + gr._SAMPLE_SHIFT + u) * step
    ri, rj = rollers[a // n], rollers[b // n]
    t1, t2, res, point, d1, d2 = _newton_crossing(drive, ri, rj, t1, t2)
    out: dict = {}
    for k in np.flatnonzero(res < 1e-10 * drive.sphere_radius):
        i, j = int(ri[k]), int(rj[k])
        x1, x2 = float(t1[k] % period), float(t2[k] % period)
        if (i, x1) > (j, x2):
            i, j, x1, x2 = j, i, x2, x1
        key = (i, j, round(x1 / step * 1e4), round(x2 / step * 1e4))
        cos = abs(float(np.dot(d1[k], d2[k]))) / (np.linalg.norm(d1[k]) * np.linalg.norm(d2[k]))
        out.setdefault(
            key,
            GrooveCrossing(
                rollers=(i, j),
                theta=(x1, x2),
                point=point[k].copy(),
                angle=float(np.arccos(min(cos, 1.0))),
                period=period,
            ),
        )
    return sorted(out.values(), key=lambda x: (x.rollers, x.theta))


def _closest_approach(drive, i, j, t1, t2, limit):
    """Newton on ``|g_i(t1) - g_j(t2)|^2 / 2`` from a nearby pair of samples.

    The full Hessian (curvature terms kept: at the closest approach of two grooves
    running side by side the tangents are parallel, and Gauss-Newton's ``J^T J`` is
    singular there), each step at most ``limit`` and halved until the distance does not
    grow. Returns ``(t1, t2, distance)``.
    """

    def at(u, v):
        gi, di, si = (x[i, :, 0] for x in gr.groove_derivatives(drive, np.array([u])))
        gj, dj, sj = (x[j, :, 0] for x in gr.groove_derivatives(drive, np.array([v])))
        return gi - gj, di, si, dj, sj

    r, di, si, dj, sj = at(t1, t2)
    dist = float(np.linalg.norm(r))
    for _ in range(60):
        grad = np.array([di @ r, -(dj @ r)])
        hess = np.array([[di @ di + si @ r, -(di @ dj)], [-(di @ dj), dj @ dj - sj @ r]])
        if hess[0, 0] > 0 and np.linalg.det(hess) > 0:
            step = -np.linalg.solve(hess, grad)
        else:  # not yet in the bowl: down the gradient
            step = -grad / (di @ di + dj @ dj)
        step = np.clip(step, -limit, limit)
        for _ in range(40):
            new = at(t1 + step[0], t2 + step[1])
            if np.linalg.norm(new[0]) <= dist:
                break
            step = 0.5 * step
        else:
            break  # no step shortens it: the closest approach, to rounding
        t1, t2 = t1 + step[0], t2 + step[1]
        r, di, si, dj, sj = new
        dist = float(np.linalg.norm(r))
        if np.max(np.abs(step)) < 1e-13:
            break
    return t1, t2, dist


def groove_separation(drive: wc.WobbleCam, samples: int = 2048):
    """Closest approach of the centre-lines of two different grooves.

    Every pair of samples of the two grooves is measured; the closest pair is refined
    by Newton on the squared distance (:func:`_closest_approach`).

    Returns
    -------
    (distance, rollers, theta) : float [m], tuple of int, tuple of float [rad]
        0 where two grooves cross; ``(inf, (), ())`` with one distinct groove.
    """
    period = gr.groove_period(drive)
    rollers = gr.distinct_grooves(drive)
    theta = np.linspace(0.0, period, samples, endpoint=False)
    g = gr.groove_derivatives(drive, theta)[0]
    best = (np.inf, (), ())
    for ii, i in enumerate(rollers):
        for j in rollers[ii + 1 :]:
            k, q, _ = closest_pair(g[i].T, g[j].T)
            t1, t2, dist = _closest_approach(drive, i, j, theta[k], theta[q], period / samples)
            if dist < best[0]:
                best = (dist, (i, j), (float(t1 % period), float(t2 % period)))
    return best
