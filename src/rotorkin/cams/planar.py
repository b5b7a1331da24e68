"""Generic planar cam geometry on arrays: offsets, curvature, pressure angle, undercut, resampling.

Not in any of the papers; textbook cam geometry (e.g. Norton, *Cam Design and
Manufacturing Handbook*, ch. 7) written for closed pitch curves sampled on any
array shape. Conventions used throughout:

* A curve is an array of points of shape ``(2, ...)`` (x, y) [m] with its first
  and second derivatives with respect to its parameter ``t`` (``dp``, ``d2p``,
  same shape). Closed curves run **counter-clockwise**, so the left normal
  points inwards and the **outward normal** is ``n = (y', -x') / |p'|``.
* Signed curvature ``kappa = (x' y'' - y' x'') / |p'|^3`` [1/m]: positive where
  a counter-clockwise curve is convex (its centre of curvature inside), negative
  where concave. The signed radius of curvature is ``1 / kappa``.
* Offset by a signed distance ``d`` [m]: ``q = p + d n`` (``d > 0`` outwards).
  A roller of radius ``r`` whose centre runs on the pitch curve touches the
  cam on the offset ``d = -r`` when it rolls on the *outside* of a disc cam
  (cam plates, discs) and on ``d = +r`` when it runs inside a ring.
  The offset's signed radius is ``1/kappa + d``: where it changes sign the
  actual profile has a cusp (the roller undercuts the cam), i.e. where
  ``1 + d kappa <= 0``.
* Pressure angle: the angle between the line of the contact force (the common
  normal, through the roller centre) and the velocity of the roller centre
  relative to the member that guides it, in ``(-pi/2, pi/2]``.

The frozen dataclasses :class:`Curve`, :class:`Part` (with its :class:`Slab` s and
:class:`Placement`) and :class:`ProfileCheck` carry finished geometry to the CAD
writers (:mod:`rotorkin.render.cad`) and the checks to the command line.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

__all__ = [
    "Curve",
    "Part",
    "Placement",
    "Slab",
    "ProfileCheck",
    "arc_points",
    "chordal_deviation",
    "circle_curve",
    "facing_clearance",
    "offset_curve",
    "offset_radius",
    "outward_normal",
    "polygon_area",
    "pressure_angle",
    "radius_of_curvature",
    "resample_closed",
    "signed_curvature",
    "undercut_intervals",
]


# --- result objects -----------------------------------------------------------------------
@dataclass(frozen=True)
class Curve:
    """A drawn curve: points in mm-free SI, the layer it goes on, exact circle if it is one.

    Attributes
    ----------
    name : str
        File-name stem, e.g. ``"profile"``, ``"pitch"``, ``"roller_A"``.
    layer : str
        DXF layer: ``"PROFILE"`` (the cut outline), ``"PITCH"`` (roller-centre
        curve), ``"ROLLER"``, ``"LINKAGE"``, ``"AXIS"``.
    points : ndarray, shape (n, 2)
        Vertices [m]; for a closed curve the last vertex joins the first (it is
        not repeated).
    closed : bool
        Whether the polyline closes.
    circle : tuple of float or None
        ``(cx, cy, r)`` [m] when the curve is an exact circle (written to DXF as
        a CIRCLE entity; ``points`` then holds its polygon within the tolerance).
    edges : tuple
        The exact edges of a closed contour that is cut (:mod:`rotorkin.cams.edges`:
        lines, arcs, B-splines within the export tolerance), counter-clockwise; the
        STEP and DXF writers use them, ``points`` is then their polygon (STL, CSV).
        Empty: the curve is drawn from ``points`` (or ``circle``).
    """

    name: str
    layer: str
    points: np.ndarray
    closed: bool = True
    circle: tuple[float, float, float] | None = None
    edges: tuple = ()


@dataclass(frozen=True)
class Slab:
    """An axial slab of a part: closed regions of its section extruded over ``z0 <= z <= z1``.

    Attributes
    ----------
    z0, z1 : float
        Axial extent in the part's frame [m], ``z0 < z1``.
    outlines : tuple of Curve
        Outer contours of the regions (disjoint), counter-clockwise.
    holes : tuple of Curve
        Contours cut out of them (a bore), counter-clockwise too.
    name : str
        What the slab is (``"relief"``), for people.
    """

    z0: float
    z1: float
    outlines: tuple[Curve, ...]
    holes: tuple[Curve, ...] = ()
    name: str = ""


@dataclass(frozen=True)
class Placement:
    """Where a part sits in its machine at ``theta = 0``: turned by ``angle`` [rad] about z,
    then shifted by ``(x, y, z)`` [m]."""

    x: float = 0.0
    y: float = 0.0
    angle: float = 0.0
    z: float = 0.0

    def as_tuple(self) -> tuple[float, float, float, float]:
        """``(x, y, angle, z)``."""
        return (self.x, self.y, self.angle, self.z)


@dataclass(frozen=True)
class Part:
    """A planar part: its outline to cut and extrude, and every curve of its drawing.

    Attributes
    ----------
    name : str
        File-name stem and STEP product name (``"disc_left"``, ``"impeller_1"``).
    outline : Curve
        The closed profile of the part (layer ``"PROFILE"``), counter-clockwise.
    thickness : float
        Axial thickness of the extruded solid [m] (from z = 0).
    curves : tuple of Curve
        Every curve of the drawing, the outline first.
    title : str
        One line saying what the part is.
    holes : tuple of Curve
        Contours cut through the whole thickness (the shaft bore with its keyway).
    slabs : tuple of Slab
        The solid as axial slabs joined, when its section changes along the axis; empty:
        one slab, ``outline`` less ``holes`` over the thickness.
    cuts : tuple of Slab
        Regions cut out of the slabs afterwards (a relief turned into the impellers'
        vane roots); a cut that reaches an end face of the part runs through it.
    placement : Placement
        The part's place in the machine at ``theta = 0`` (the STEP assembly).
    hub : object or None
        The bore's :class:`rotorkin.render.workshop.Hub` (None: no bore).
    notes : tuple of str
        Lines for the drawing (fits, clearances), below the title.
    gaps : tuple of (str, float)
        The running gaps cut into the part, by pair (``("vane tip to casing", 4.7e-5)``) [m].
    """

    name: str
    outline: Curve
    thickness: float
    curves: tuple[Curve, ...]
    title: str = ""
    holes: tuple[Curve, ...] = ()
    slabs: tuple[Slab, ...] = ()
    cuts: tuple[Slab, ...] = ()
    placement: Placement = Placement()
    hub: object = None
    notes: tuple[str, ...] = ()
    gaps: tuple[tuple[str, float], ...] = ()

    def solid_slabs(self) -> tuple[Slab, ...]:
        """The slabs of the solid (:attr:`slabs`, or the one slab of the plain plate)."""
        if self.slabs:
            return self.slabs
        return (Slab(0.0, float(self.thickness), (self.outline,), tuple(self.holes)),)


@dataclass(frozen=True)
class ProfileCheck:
    """Checks of a planar cam profile for a roller (all SI; never raises to build).

    Attributes
    ----------
    roller_radius : float
        Roller radius the checks are for [m].
    min_convex_radius : float
        Smallest radius of curvature of the convex stretches of the pitch curve [m]
        (``inf`` if the curve has none).
    min_convex_radius_alpha : float
        Cam angle where it occurs [rad].
    min_concave_radius : float
        Smallest radius of curvature of the concave stretches [m] (``inf``: convex cam).
    max_pressure_angle : float
        Largest magnitude of the pressure angle over all rollers and the turn [rad].
    max_pressure_angle_alpha : float
        Cam angle of the roller where it occurs [rad].
    undercut : bool
        ``roller_radius >= min_convex_radius``: the actual profile has a cusp.
    min_clearance : float
        Smallest gap between a roller and the cam away from its own contact [m]
        (:func:`facing_clearance`); ``inf`` when no other flank faces any roller,
        negative when a roller cuts into the cam elsewhere.
    min_clearance_alpha : float
        Cam angle of the roller where it occurs [rad] (nan when ``inf``).
    profile_min_radius : float
        Smallest distance of the actual profile from the cam centre [m].
    extra : dict
        Drive-specific values (e.g. the gap between neighbouring rollers).
    """

    roller_radius: float
    min_convex_radius: float
    min_convex_radius_alpha: float
    min_concave_radius: float
    max_pressure_angle: float
    max_pressure_angle_alpha: float
    undercut: bool
    min_clearance: float
    min_clearance_alpha: float
    profile_min_radius: float
    extra: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        """No undercut, no interference, actual profile clear of the centre."""
        return bool(
            not self.undercut and not self.min_clearance < 0.0 and self.profile_min_radius > 0.0
        )


# --- differential geometry ----------------------------------------------------------------
def outward_normal(dp):
    """Unit outward normal ``(y', -x') / |p'|`` of a counter-clockwise curve, shape (2, ...)."""
    dp = np.asarray(dp, dtype=float)
    return np.stack([dp[1], -dp[0]]) / np.hypot(dp[0], dp[1])


def signed_curvature(dp, d2p):
    """Signed curvature ``(x' y'' - y' x'') / |p'|^3`` [1/m] (positive: convex, CCW curve)."""
    dp, d2p = np.asarray(dp, dtype=float), np.asarray(d2p, dtype=float)
    return (dp[0] * d2p[1] - dp[1] * d2p[0]) / np.hypot(dp[0], dp[1]) ** 3


def radius_of_curvature(dp, d2p):
    """Signed radius of curvature ``1 / kappa`` [m]; ``inf`` on straight stretches."""
    k = signed_curvature(dp, d2p)
    with np.errstate(divide="ignore"):
        return np.where(k == 0.0, np.inf, 1.0 / np.where(k == 0.0, 1.0, k))


def offset_curve(p, dp, distance):
    """Offset ``p + d n`` of a curve by the signed distance ``d`` [m] (``d > 0`` outwards).

    The actual profile of a cam for a roller of radius ``r`` rolling on its
    outside is ``offset_curve(pitch, dpitch, -r)``.
    """
    return np.asarray(p, dtype=float) + np.asarray(distance, dtype=float) * outward_normal(dp)


def offset_radius(dp, d2p, distance):
    """Signed radius of curvature of the offset curve, ``1/kappa + d`` [m].

    Where it has the opposite sign to ``1/kappa`` (``1 + d kappa < 0``) the
    offset runs backwards: a cusp (undercut).
    """
    return radius_of_curvature(dp, d2p) + np.asarray(distance, dtype=float)


def pressure_angle(normal, velocity):
    """Angle between the line of a contact force and a velocity [rad], in ``(-pi/2, pi/2]``.

    Signed: positive when the velocity must turn counter-clockwise to reach the
    force line. The sense of the normal does not matter (a line).

    Parameters
    ----------
    normal, velocity : array_like, shape (2, ...)
        Any lengths (not zero).
    """
    n, v = np.asarray(normal, dtype=float), np.asarray(velocity, dtype=float)
    ang = np.arctan2(v[0] * n[1] - v[1] * n[0], v[0] * n[0] + v[1] * n[1])
    return np.where(ang > 0.5 * np.pi, ang - np.pi, np.where(ang <= -0.5 * np.pi, ang + np.pi, ang))


def undercut_intervals(t, kappa, distance):
    """Parameter intervals where an offset by ``distance`` has a cusp: ``1 + d kappa <= 0``.

    Parameters
    ----------
    t : ndarray, shape (n,)
        Increasing parameter samples covering one closed curve (end excluded).
    kappa : ndarray, shape (n,)
        Signed curvature at ``t`` [1/m].
    distance : float
        Signed offset ``d`` [m] (``-r`` for a roller outside the cam).

    Returns
    -------
    ndarray, shape (k, 2)
        ``[start, end]`` of each interval [parameter units], the ends located by
        linear interpolation of ``1 + d kappa`` between samples; empty if none.
        An interval running through the end of ``t`` is split in two.
    """
    t = np.asarray(t, dtype=float)
    g = 1.0 + float(distance) * np.asarray(kappa, dtype=float)
    bad = g <= 0.0
    if not bad.any():
        return np.empty((0, 2))
    edges = np.diff(bad.astype(int), prepend=0, append=0)
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1

    def cross(i, j):  # zero of g between samples i (good) and j (bad)
        w = g[i] / (g[i] - g[j])
        return t[i] + w * (t[j] - t[i])

    lo = np.array([cross(i - 1, i) if i > 0 else t[0] for i in starts])
    hi = np.array([cross(j + 1, j) if j < t.size - 1 else t[-1] for j in ends])
    return np.column_stack([lo, hi])


def facing_clearance(centres, profile, normals, radius, own):
    """Gap between each roller and the cam profile away from its own contact [m].

    For a roller of radius ``r`` centred at ``c_i`` the gap function
    ``g_i(j) = |c_i - q_j| - r`` along the profile samples ``q_j`` is zero at its
    own contact (sample ``own[i]``) and grows from there. Every *other* local
    minimum of ``g_i`` at a profile point whose outward normal faces the roller
    (``(c_i - q_j) . n_j > 0``) is a flank of the cam that the roller passes
    close to: the clearance is the smallest of them, negative when the roller
    cuts into the cam there, ``inf`` when there is none (a convex cam). Minima
    on the far side of the cam (normal facing away) are shadowed by the cam
    body and do not count - unless the roller reaches them (``g < 0``: a roller
    whose centre has entered the cam body, or that spans it).

    Parameters
    ----------
    centres : ndarray, shape (2, N)
        Roller centres [m].
    profile, normals : ndarray, shape (2, M)
        Closed profile samples (cyclic) and their unit outward normals.
    radius : float
        Roller radius [m].
    own : ndarray of int, shape (N,)
        Index of each roller's own contact point in ``profile``.

    Returns
    -------
    (clearance, index) : ndarray (N,), ndarray of int (N,)
        The gap [m] and the profile index where it occurs (-1 for ``inf``).
    """
    c = np.asarray(centres, dtype=float)[:, :, None]
    q = np.asarray(profile, dtype=float)[:, None, :]
    rel = c - q  # (2, N, M)
    gap = np.hypot(rel[0], rel[1]) - float(radius)
    facing = rel[0] * normals[0][None] + rel[1] * normals[1][None] > 0.0
    minimum = (gap < np.roll(gap, 1, axis=1)) & (gap <= np.roll(gap, -1, axis=1))
    rows = np.arange(gap.shape[0])
    minimum[rows, np.asarray(own)] = False
    cand = np.where(minimum & (facing | (gap < 0.0)), gap, np.inf)
    j = np.argmin(cand, axis=1)
    out = cand[rows, j]
    return out, np.where(np.isfinite(out), j, -1)


# --- sampling -----------------------------------------------------------------------------
def _segment_distance(q, a, b):
    """Distance of points ``q`` from the segments ``a b``; all shape (2, n)."""
    ab = b - a
    L2 = np.maximum(ab[0] ** 2 + ab[1] ** 2, 1e-300)
    s = np.clip(((q[0] - a[0]) * ab[0] + (q[1] - a[1]) * ab[1]) / L2, 0.0, 1.0)
    d = q - (a + s * ab)
    return np.hypot(d[0], d[1])


def chordal_deviation(curve: Callable, t, period: float, probes: int = 7):
    """Largest distance of the exact curve from each chord of a closed polygon [m].

    Parameters
    ----------
    curve : callable
        ``curve(t) -> ndarray (2, *t.shape)`` [m].
    t : ndarray, shape (n,)
        Increasing vertex parameters of one turn, the end ``t[0] + period`` excluded.
    period : float
        Parameter period of the closed curve.
    probes : int
        Interior points checked per chord (equally spaced in the parameter).

    Returns
    -------
    ndarray, shape (n,)
        Deviation of the arc ``t[i] .. t[i+1]`` (cyclic) from its chord.
    """
    t = np.asarray(t, dtype=float)
    tn = np.append(t, t[0] + period)
    p = curve(tn)
    f = (np.arange(1, probes + 1) / (probes + 1.0))[:, None]
    tm = tn[:-1] + f * np.diff(tn)  # (probes, n)
    qm = curve(tm)
    a = np.broadcast_to(p[:, None, :-1], qm.shape)
    b = np.broadcast_to(p[:, None, 1:], qm.shape)
    return (
        _segment_distance(qm.reshape(2, -1), a.reshape(2, -1), b.reshape(2, -1))
        .reshape(tm.shape)
        .max(axis=0)
    )


def resample_closed(
    curve: Callable, t0: float, period: float, tolerance: float, start: int = 64,
    max_points: int = 200_000,
):  # fmt: skip
    """Parameters of a polygon that follows a closed curve within a chordal tolerance.

    Starting from ``start`` equal steps, every chord whose arc deviates by more
    than half the tolerance at 3 interior probe points (1/4, 1/2, 3/4) is
    split at its parameter midpoint, repeatedly (vectorised per pass). The
    factor 1/2 keeps the true deviation (checked densely by the tests) within
    the tolerance.

    Parameters
    ----------
    curve : callable
        ``curve(t) -> ndarray (2, *t.shape)`` [m], smooth and of period ``period``.
    t0 : float
        First vertex parameter.
    period : float
        Parameter period.
    tolerance : float
        Chordal tolerance [m], > 0.
    start : int
        Initial number of vertices.
    max_points : int
        Safety limit; a ``ValueError`` if exceeded (tolerance far too small).

    Returns
    -------
    ndarray, shape (n,)
        Increasing vertex parameters, ``t0`` first, ``t0 + period`` excluded.
    """
    t = t0 + period * np.arange(int(start)) / int(start)
    for _ in range(60):
        dev = chordal_deviation(curve, t, period, probes=3)
        bad = dev > 0.5 * float(tolerance)
        if not bad.any():
            return t
        tn = np.append(t, t0 + period)
        mids = 0.5 * (tn[:-1] + tn[1:])[bad]
        t = np.sort(np.concatenate([t, mids]))
        if t.size > max_points:
            break
    raise ValueError(f"tolerance {tolerance:g} m needs more than {max_points} points")


def arc_points(center, radius, a0, a1, tolerance, endpoint=True):
    """Points of a circular arc from angle ``a0`` to ``a1`` within a chordal tolerance.

    The step ``2 arccos(1 - tol/R)`` keeps the sagitta ``R (1 - cos(step/2))``
    at or below the tolerance.

    Returns
    -------
    ndarray, shape (n, 2)
        [m], from ``a0`` to ``a1`` (``a1`` included when ``endpoint``).
    """
    R = float(radius)
    step = 2.0 * np.arccos(max(1.0 - float(tolerance) / R, -1.0))
    n = max(int(np.ceil(abs(a1 - a0) / step)), 1)
    a = a0 + (a1 - a0) * np.arange(n + 1 if endpoint else n) / n
    return np.column_stack([center[0] + R * np.cos(a), center[1] + R * np.sin(a)])


def circle_curve(name, layer, center, radius, tolerance) -> Curve:
    """A full circle as a :class:`Curve` (exact circle plus its polygon within the tolerance)."""
    n_min = 16
    pts = arc_points(center, radius, 0.0, 2.0 * np.pi, tolerance, endpoint=False)
    if len(pts) < n_min:
        a = 2.0 * np.pi * np.arange(n_min) / n_min
        pts = np.column_stack([center[0] + radius * np.cos(a), center[1] + radius * np.sin(a)])
    return Curve(name, layer, pts, True, (float(center[0]), float(center[1]), float(radius)))


def polygon_area(points):
    """Signed area of a closed polygon (shoelace) [m^2]; positive counter-clockwise."""
    p = np.asarray(points, dtype=float)
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
