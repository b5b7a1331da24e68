"""Rhomboid lever-cam converter of a rotary-blade engine.

Zhuravlev, Donchenko, Sherstyukov, "Synthesis of the cam profile of the
lever-cam motion converter of a rotary-blade engine with external heat supply",
Izvestiya TulGU, 2012 (``papers/rhomboid_cam.md``).

Two blade pairs turn about the shaft axis O at angles ``phi_1`` and ``phi_2``;
the chambers follow the angle between them, ``psi = phi_1 - phi_2``. A rhombus
ABCD of side ``2l`` (``link_length``), centred on O, joins the blade arms
(the blade axes pass through the midpoints of opposite sides); rollers at its
vertices roll on a fixed cam whose pitch curve, in polar coordinates about O,
is ``rho(alpha)``. The diagonal OA turns uniformly with the output shaft at
the angle ``alpha`` (the input angle of every function here).

Conventions (the paper is silent or garbled):

* Plane x, y; angles positive counter-clockwise from +x.
* OA lies at ``alpha``, OB at ``alpha + pi/2``, OC at ``alpha + pi``,
  OD at ``alpha + 3 pi/2``; ``rho = OA = 2l cos(psi/2)`` (eq. 3) and
  ``OB = 2l sin(psi/2)`` (eq. 4; the OCR prints cos again, eq. 7 needs sin).
* Blade pair 1 lies through the midpoints of AB and CD, at
  ``phi_1 = alpha + psi/2``; pair 2 through the midpoints of DA and BC, at
  ``phi_2 = alpha - psi/2`` (eq. 21 with its constants taken as zero).
* The law ``psi(alpha)`` is the odd-harmonic series of eq. 13 whose first
  harmonic is fixed by eq. 15, so ``psi(0) = psi_max = pi - psi_min`` and
  ``psi(+-pi/2) = psi_min``. Eq. 19 writes the profile as ``2l sin(psi/2)``:
  by eq. 10 that is the same cam turned by a quarter turn (see
  :func:`profile_radius_eq19`).
* Torques: ``M_1`` acts on blade pair 1 and ``M_2 = -M_1`` on pair 2 (eq. 24);
  positive work is done *by* the blades on the output shaft.

All functions take the parameters first and the input angle last, and broadcast
the angle against array parameters (``psi_min``, ``link_length``, torques, e.g.
shape ``(n, 1)`` against angles ``(m,)``); the harmonic coefficients
``a = (a3, a5, ...)`` and ``b = (b3, b5, ...)`` are 1-d sequences [rad], one law.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import fmt_deg, fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion, compose
from rotorkin.drives.rhomboid_cam.kinematics_fused import law_fused

__all__ = [
    "CHECKS",
    "MAX_HARMONICS",
    "RhomboidCam",
    "blade_angles",
    "blade_arm_points",
    "blade_torque",
    "check_law",
    "check_psi_range",
    "first_harmonic",
    "indicator_work",
    "indicator_work_closed_form",
    "linear_member_torques",
    "mean_shaft_torque",
    "law_peaks",
    "motion",
    "period",
    "polar_curvature",
    "profile_curvature",
    "profile_point",
    "profile_radius",
    "profile_radius_eq19",
    "profile_radius_range",
    "psi_extremes",
    "psi_is_monotone",
    "psi_law",
    "psi_range_violation",
    "psi_stationary_points",
    "psi_total_variation",
    "radius_from_psi",
    "rhombus_vertices",
    "shaft_torque",
    "stroke_direction",
    "violation",
]

#: Largest number of higher harmonics accepted in ``a`` and in ``b`` each.
MAX_HARMONICS = 20
#: Parameters of :class:`RhomboidCam` in the order :func:`violation` checks them.
CHECKS = ("link_length", "psi_min")
#: How far [rad] psi may leave ``[psi_min, psi_max]`` before the linear torque model refuses
#: the law (eq. 2; rounding of the extremes of a law monotone between them is far smaller).
PSI_RANGE_TOL = 1e-8
#: Stationary points of the first-harmonic law (eq. 16) in one period [rad].
_FIRST_HARMONIC_STATIONARY = np.array([0.0, 0.5 * np.pi, np.pi])

_HALF_PI = 0.5 * np.pi


# --- the law psi(alpha) -------------------------------------------------------------------
def _higher(a, b):
    """Orders k = 3, 5, ... and the padded coefficient vectors a_k, b_k (k >= 3)."""
    a = np.asarray(a, dtype=float).reshape(-1)
    b = np.asarray(b, dtype=float).reshape(-1)
    n = max(a.size, b.size)
    a = np.pad(a, (0, n - a.size))
    b = np.pad(b, (0, n - b.size))
    k = 2.0 * np.arange(1, n + 1) + 1.0
    return k, a, b


def first_harmonic(psi_min, a=(), b=()):
    """First-harmonic coefficients fixed by the end conditions (eq. 15).

    ``a_1 + a_3 + a_5 + ... = pi/2 - psi_min`` and ``b_1 + 3 b_3 + 5 b_5 + ... = 0``.

    Parameters
    ----------
    psi_min : array_like
        Smallest angle between the blade axes [rad] (``psi(+-pi/2)``).
    a, b : sequence of float
        Higher cosine and sine coefficients ``a3, a5, ...`` and ``b3, b5, ...`` [rad].

    Returns
    -------
    (a_1, b_1) : ndarray, float
        [rad]; ``a_1`` has the shape of ``psi_min``.
    """
    k, ak, bk = _higher(a, b)
    a1 = _HALF_PI - np.asarray(psi_min, dtype=float) - ak.sum()
    b1 = -float(np.dot(k, bk))
    return a1, b1


def psi_law(psi_min, a, b, alpha):
    """Angle between the blade axes and its derivatives (eq. 13, 14, 15).

    ``psi = pi/2 + sum_{k odd} (a_k cos 2k alpha + b_k sin 2k alpha)`` with
    ``a_1``, ``b_1`` from :func:`first_harmonic`. With ``a = b = ()`` this is
    the patented law of eq. 16, ``psi = pi/2 + (pi/2 - psi_min) cos 2 alpha``;
    ``psi_min = pi/2`` gives the constant law ``psi = pi/2``.

    Parameters
    ----------
    alpha : array_like
        Output-shaft angle (angle of OA) [rad].
    psi_min : array_like
        [rad], broadcast with ``alpha``.
    a, b : sequence of float
        Higher harmonics ``a3, a5, ...``, ``b3, b5, ...`` [rad].

    Returns
    -------
    (psi, dpsi, d2psi, d3psi) : tuple of ndarray
        ``psi`` [rad] and its derivatives with respect to ``alpha`` [rad/rad^n].

    Notes
    -----
    Evaluated block by block from one ``tan alpha`` per point, the harmonics by angle
    sums (:mod:`rotorkin.drives.rhomboid_cam.kinematics_fused`; compiled loops when
    numba is installed, ``$ROTORKIN_KERNEL`` chooses).
    """
    _, ak, bk = _higher(a, b)
    a1, b1 = first_harmonic(psi_min, a, b)
    return tuple(law_fused(a1, b1, ak, bk, alpha))


def _scale(psi_min, a, b, order):
    """Upper bound of ``|d^n psi / d alpha^n|`` (sum of |coefficients| times (2k)^n).

    Per design: the shape of ``psi_min`` (a float for a scalar).
    """
    k, ak, bk = _higher(a, b)
    a1, b1 = first_harmonic(psi_min, a, b)
    first = np.abs(np.asarray(a1, dtype=float)) + abs(b1)
    higher = np.broadcast_to(np.abs(ak) + np.abs(bk), first.shape + ak.shape)
    w = np.concatenate(([2.0], 2.0 * k))
    out = np.sum(w**order * np.concatenate([first[..., None], higher], axis=-1), axis=-1)
    return float(out) if out.ndim == 0 else out


def period(params) -> float:
    """Period of the motion in the output-shaft angle [rad]: pi.

    ``psi`` has period pi (eq. 9); the blade angles ``alpha +- psi/2`` repeat
    after pi up to the uniform advance of pi (one half turn of the shaft
    carries each blade pair half a turn and through one full chamber cycle).
    """
    return float(np.pi)


def blade_angles(psi_min, a, b, alpha):
    """Angles of the two blade pairs and their derivatives (eq. 21, 22).

    ``phi_1 = alpha + psi/2``, ``phi_2 = alpha - psi/2`` (eq. 21 with zero
    constants), so ``phi_1' = 1 + psi'/2``, ``phi_2' = 1 - psi'/2`` (eq. 22).

    Returns
    -------
    (phi, dphi, d2phi, d3phi) : tuple of ndarray, shape (2, ...)
        Pair 1 then pair 2 [rad, rad/rad^n].
    """
    _, ak, bk = _higher(a, b)
    a1, b1 = first_harmonic(psi_min, a, b)
    return tuple(law_fused(a1, b1, ak, bk, alpha, blades=True))


def motion(params, theta) -> Motion:
    """Motion of blade pairs 1 and 2 against the output-shaft angle ``theta = alpha``.

    ``Motion.relative`` is ``phi_2 - phi_1 = -psi``.
    """
    theta = np.asarray(theta, dtype=float)
    q, d1, d2, d3 = blade_angles(params.psi_min, params.a, params.b, theta)
    return Motion(theta, q, d1, d2, d3, members=("blade pair 1", "blade pair 2"), unit="rad")


# --- the cam and the rhombus --------------------------------------------------------------
def profile_radius(link_length, psi_min, a, b, alpha):
    """Polar radius of the cam pitch curve and its derivatives (eq. 3).

    ``rho(alpha) = 2l cos(psi(alpha)/2)``: the distance of roller A from O when
    OA lies at ``alpha``. Derivatives by the chain rule (exact).

    Parameters
    ----------
    alpha : array_like
        Polar angle [rad].
    link_length : array_like
        Side ``2l`` of the rhombus [m].
    psi_min, a, b
        The law, see :func:`psi_law`.

    Returns
    -------
    (rho, drho, d2rho, d3rho) : tuple of ndarray
        [m, m/rad^n].
    """
    return radius_from_psi(link_length, psi_law(psi_min, a, b, alpha))


def radius_from_psi(link_length, psi):
    """``rho = 2l cos(psi/2)`` (eq. 3) and its derivatives from those of ``psi`` (chain rule).

    Parameters
    ----------
    link_length : array_like
        Side ``2l`` of the rhombus [m].
    psi : sequence of 4 array_like
        ``psi, psi', psi'', psi'''`` [rad, rad/rad^n], broadcast with ``link_length``.

    Returns
    -------
    (rho, drho, d2rho, d3rho) : tuple of ndarray
        [m, m/rad^n].
    """
    L = np.asarray(link_length, dtype=float)
    h = 0.5 * np.asarray(psi[0])
    c, s = np.cos(h), np.sin(h)
    return compose((L * c, -0.5 * L * s, -0.25 * L * c, 0.125 * L * s), psi)


def profile_radius_eq19(link_length, psi_min, a, b, alpha):
    """Pitch-curve radius in the form printed as eq. 19: ``2l sin(psi(alpha)/2)`` [m].

    This is ``OB`` of :func:`rhombus_vertices` as a function of the angle of
    OA, and by eq. 10 it equals ``rho(alpha + pi/2)`` of :func:`profile_radius`: the
    curve of eq. 19 is the cam of eq. 3 turned by a quarter turn (clockwise; for the
    first-harmonic law, of period pi in alpha, either way). We use eq. 3.
    """
    L = np.asarray(link_length, dtype=float)
    return L * np.sin(0.5 * psi_law(psi_min, a, b, alpha)[0])


def profile_radius_range(link_length, psi_lo, psi_hi):
    """Smallest and largest radius of the pitch curve, ``2l cos(psi/2)`` at the extremes of psi.

    ``rho`` falls as ``psi`` rises (``0 < psi < pi``), so the smallest radius is at
    ``psi_hi`` and the largest at ``psi_lo`` (eq. 3) [m]. All arguments broadcast.

    Returns
    -------
    (rho_min, rho_max) : ndarray
    """
    L = np.asarray(link_length, dtype=float)
    return L * np.cos(0.5 * np.asarray(psi_hi)), L * np.cos(0.5 * np.asarray(psi_lo))


def profile_point(link_length, psi_min, a, b, alpha):
    """Cartesian point of the pitch curve and its first two derivatives.

    ``x = rho cos alpha``, ``y = rho sin alpha`` with ``rho`` of eq. 3.

    Returns
    -------
    (p, dp, d2p) : tuple of ndarray, shape (2, ...)
        ``(x, y)`` [m] and derivatives with respect to ``alpha`` [m/rad^n].
    """
    alpha = np.asarray(alpha, dtype=float)
    r0, r1, r2, _ = profile_radius(link_length, psi_min, a, b, alpha)
    c, s = np.cos(alpha), np.sin(alpha)
    p = np.stack([r0 * c, r0 * s])
    dp = np.stack([r1 * c - r0 * s, r1 * s + r0 * c])
    d2p = np.stack([(r2 - r0) * c - 2.0 * r1 * s, (r2 - r0) * s + 2.0 * r1 * c])
    return p, dp, d2p


def profile_curvature(link_length, psi_min, a, b, alpha):
    """Signed curvature of the cam pitch curve [1/m] (not in the paper).

    ``kappa = (rho^2 + 2 rho'^2 - rho rho'') / (rho^2 + rho'^2)^(3/2)``:
    positive where the curve is convex (centre of curvature on the side of O),
    negative where concave; ``1/|kappa|`` is the radius of curvature, to be
    compared with the roller radius for undercut.
    """
    return polar_curvature(*profile_radius(link_length, psi_min, a, b, alpha)[:3])


def polar_curvature(rho, drho, d2rho):
    """Signed curvature of a polar curve ``rho(alpha)`` [1/m].

    ``kappa = (rho^2 + 2 rho'^2 - rho rho'') / (rho^2 + rho'^2)^(3/2)``; positive
    where the curve turns towards the origin (convex for a closed cam).
    """
    return (rho**2 + 2.0 * drho**2 - rho * d2rho) / (rho**2 + drho**2) ** 1.5


def law_peaks(link_length, psi_min, a, b, alpha):
    """Peaks of the blade-motion coefficients and of the pitch-curve curvature.

    Over the last axis of the broadcast of ``alpha`` with the parameters, e.g.
    ``alpha`` shape ``(m,)`` against ``link_length``, ``psi_min`` shape ``(n, 1)``
    gives ``(n,)`` arrays. The blade pairs turn at ``phi_i' = 1 +- psi'/2`` (eq. 22);
    their second and third derivatives are ``+-psi''/2`` and ``+-psi'''/2``.

    Returns
    -------
    dict of ndarray
        ``speed_coeff_max`` ``1 + max|psi'|/2``, ``speed_coeff_min`` ``1 - max|psi'|/2``,
        ``accel_coeff_max`` ``max|psi''|/2`` [1/rad], ``jerk_coeff_max``
        ``max|psi'''|/2`` [1/rad^2]; from :func:`profile_curvature`:
        ``convex_radius_min`` ``1 / max kappa`` and ``concave_radius_min``
        ``1 / max(-kappa)`` (inf where the curve is nowhere concave) [m], and
        ``convex`` (bool: ``kappa >= 0`` everywhere).
    """
    _, d1, d2, d3 = psi_law(psi_min, a, b, alpha)
    kappa = profile_curvature(link_length, psi_min, a, b, alpha)
    d1 = np.max(np.abs(d1), axis=-1)
    concave = -np.min(kappa, axis=-1)
    with np.errstate(divide="ignore"):
        concave_r = np.where(concave > 0.0, 1.0 / np.where(concave > 0.0, concave, 1.0), np.inf)
    return {
        "speed_coeff_max": 1.0 + 0.5 * d1,
        "speed_coeff_min": 1.0 - 0.5 * d1,
        "accel_coeff_max": 0.5 * np.max(np.abs(d2), axis=-1),
        "jerk_coeff_max": 0.5 * np.max(np.abs(d3), axis=-1),
        "convex_radius_min": 1.0 / np.max(kappa, axis=-1),
        "concave_radius_min": concave_r,
        "convex": concave <= 0.0,
    }


def _unit(angle):
    return np.stack([np.cos(angle), np.sin(angle)])


def rhombus_vertices(link_length, psi_min, a, b, alpha):
    """Roller centres A, B, C, D of the rhombus (eq. 3, 4).

    ``A = 2l cos(psi/2) e(alpha)``, ``B = 2l sin(psi/2) e(alpha + pi/2)``,
    ``C = -A``, ``D = -B`` with ``e(t) = (cos t, sin t)``. All four lie on the
    pitch curve: ``B(alpha) = rho(alpha + pi/2) e(alpha + pi/2)`` by eq. 10.

    Returns
    -------
    ndarray, shape (4, 2, ...)
        Vertices A, B, C, D, each ``(x, y)`` [m].
    """
    alpha = np.asarray(alpha, dtype=float)
    L = np.asarray(link_length, dtype=float)
    psi = psi_law(psi_min, a, b, alpha)[0]
    va = L * np.cos(0.5 * psi) * _unit(alpha)
    vb = L * np.sin(0.5 * psi) * _unit(alpha + _HALF_PI)
    return np.stack([va, vb, -va, -vb])


def blade_arm_points(link_length, psi_min, a, b, alpha):
    """Midpoints of the sides AB, BC, CD, DA: where the blade arms hold the rhombus.

    They lie at distance ``l`` from O, at ``phi_1``, ``phi_2 + pi``,
    ``phi_1 + pi`` and ``phi_2`` (pair 1, pair 2, pair 1, pair 2).

    Returns
    -------
    ndarray, shape (4, 2, ...)
        [m].
    """
    v = rhombus_vertices(link_length, psi_min, a, b, alpha)
    return 0.5 * (v + np.roll(v, -1, axis=0))


# --- stationary points and extremes of psi ------------------------------------------------
def _grid(a, b):
    n = max(len(np.atleast_1d(a)), len(np.atleast_1d(b)))
    return np.linspace(0.0, np.pi, 4097 + 256 * n)


def psi_stationary_points(psi_min, a=(), b=()):
    """Angles in [0, pi] splitting ``psi`` into monotone pieces [rad].

    The sign changes of ``psi'`` found on a dense grid and refined by
    vectorised bisection to machine precision, together with 0, pi/2 and pi
    (where eq. 6 makes ``psi' = 0``). Two sign changes closer than the grid
    step (~ pi / (4096 + 256 K)) would be missed. ``psi_min`` must be scalar.

    Returns
    -------
    ndarray, shape (n,)
        Sorted, first 0, last pi.
    """
    psi_min = float(psi_min)
    fixed = np.array([0.0, _HALF_PI, np.pi])
    tol = 1e-13 * _scale(psi_min, a, b, 1)
    if tol == 0.0:
        return fixed
    g = _grid(a, b)
    d1 = psi_law(psi_min, a, b, g)[1]
    sg = np.where(np.abs(d1) <= tol, 0.0, np.sign(d1))
    i = np.flatnonzero(sg[:-1] * sg[1:] < 0.0)
    lo, hi, flo = g[i], g[i + 1], sg[i]
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        same = np.sign(psi_law(psi_min, a, b, mid)[1]) == flo
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    roots = np.concatenate([fixed, 0.5 * (lo + hi), g[sg == 0.0]])
    roots = np.sort(roots[(roots >= 0.0) & (roots <= np.pi)])
    keep = np.concatenate(([True], np.diff(roots) > 1e-10))
    out = roots[keep]
    out[-1] = np.pi
    return out


def psi_extremes(psi_min, a=(), b=()):
    """Lowest and highest ``psi`` over a period, with where they occur.

    From the stationary points (exact) and the dense grid.

    Returns
    -------
    (psi_lo, alpha_lo, psi_hi, alpha_hi) : float
        [rad]. For monotone laws ``psi_lo = psi_min`` at pi/2 and
        ``psi_hi = pi - psi_min`` at 0. For the first-harmonic law (``a``, ``b``
        empty) ``psi_min`` may be an array: ``psi_lo``, ``psi_hi`` have its shape.
    """
    if not _higher(a, b)[0].size:
        pm = np.asarray(psi_min, dtype=float)
        z = psi_law(pm[..., None], (), (), _FIRST_HARMONIC_STATIONARY[:2])[0]
        lo, hi = z[..., 1], z[..., 0]
        if pm.ndim == 0:
            lo, hi = float(lo), float(hi)
        return lo, _HALF_PI, hi, 0.0
    x = np.concatenate([psi_stationary_points(psi_min, a, b), _grid(a, b)])
    psi = psi_law(float(psi_min), a, b, x)[0]
    i, j = int(np.argmin(psi)), int(np.argmax(psi))
    return float(psi[i]), float(x[i]), float(psi[j]), float(x[j])


def psi_total_variation(psi_min, a=(), b=()):
    """Total travel ``integral_0^pi |psi'| d alpha`` of the chamber angle [rad].

    Sum of ``|Delta psi|`` between consecutive stationary points; equals
    ``2 (pi - 2 psi_min)`` for a law monotone between its extremes. For the
    first-harmonic law ``psi_min`` may be an array (the result has its shape).
    """
    if not _higher(a, b)[0].size:
        pm = np.asarray(psi_min, dtype=float)
        z = psi_law(pm[..., None], (), (), _FIRST_HARMONIC_STATIONARY)[0]
        travel = np.abs(z[..., 1] - z[..., 0]) + np.abs(z[..., 2] - z[..., 1])
        return float(travel) if pm.ndim == 0 else travel
    z = psi_stationary_points(psi_min, a, b)
    return float(np.sum(np.abs(np.diff(psi_law(float(psi_min), a, b, z)[0]))))


def psi_is_monotone(psi_min, a=(), b=(), rtol=1e-9):
    """Whether ``psi`` falls monotonically from ``psi(0)`` to ``psi(pi/2)`` (and rises back).

    True when the total travel over a period is ``2 (psi(0) - psi(pi/2))``.
    Only then does the paper's eq. 34 (work independent of the profile) hold.
    For the first-harmonic law ``psi_min`` may be an array (a bool array).
    """
    swing = np.pi - 2.0 * np.asarray(psi_min, dtype=float)
    out = psi_total_variation(psi_min, a, b) <= 2.0 * swing * (1.0 + rtol) + 1e-15
    return bool(out) if np.ndim(out) == 0 else out


def check_law(psi_min, a=(), b=()):
    """Raise :class:`ParameterError` unless ``0 < psi(alpha) < pi`` for all alpha (eq. 10 needs it).

    The error names ``a`` (or ``b`` when ``a`` is empty) and the extreme reached.
    """
    lo, alo, hi, ahi = psi_extremes(psi_min, a, b)
    if lo > 0.0 and hi < np.pi:
        return
    name, coeffs = ("a", a) if len(a) else ("b", b)
    value, where = (lo, alo) if lo <= 0.0 else (hi, ahi)
    raise ParameterError(
        name,
        "[" + ", ".join(f"{float(c):.6g}" for c in coeffs) + "] rad",
        f"harmonics a, b keeping 0 deg < psi(alpha) < 180 deg for every alpha (eq. 10, 13, 15); "
        f"this law reaches psi = {fmt_deg(value)} at alpha = {fmt_deg(where)}",
    )


def psi_range_violation(psi_min, a=(), b=(), tol=PSI_RANGE_TOL):
    """Where ``psi`` leaves ``psi_min <= psi <= psi_max = pi - psi_min`` (eq. 2).

    The linear torque model (eq. 29) is defined on that range only. The first-harmonic
    law never leaves it; higher harmonics may (``a = [1.0]`` with ``psi_min = 40 deg``
    swings psi over 29 .. 151 deg).

    Parameters
    ----------
    psi_min : array_like
        [rad], any shape (with harmonics, each distinct value is checked on its own).
    a, b : sequence of float
        Higher harmonics [rad].
    tol : float
        Allowed excursion [rad].

    Returns
    -------
    ndarray of bool or bool
        Shape of ``psi_min``: True where the law leaves the range.
    """
    pm = np.asarray(psi_min, dtype=float)
    if not _higher(a, b)[0].size:
        lo, _, hi, _ = psi_extremes(pm)
    else:
        values, inverse = np.unique(pm, return_inverse=True)
        ext = np.array([psi_extremes(v, a, b)[::2] if np.isfinite(v) else (np.nan, np.nan)
                        for v in values]).reshape(-1, 2)  # fmt: skip
        lo, hi = ext[inverse.reshape(pm.shape), 0], ext[inverse.reshape(pm.shape), 1]
    with np.errstate(invalid="ignore"):
        out = (np.asarray(lo) < pm - tol) | (np.asarray(hi) > np.pi - pm + tol)
    return bool(out) if out.ndim == 0 else out


def check_psi_range(psi_min, a=(), b=(), tol=PSI_RANGE_TOL):
    """Raise :class:`ParameterError` unless ``psi_min <= psi <= psi_max`` for all alpha (eq. 2).

    For the linear torque model (eq. 29), which is defined on that range only. The
    error names ``a`` (or ``b`` when ``a`` is empty), the range and what the law reaches.
    """
    psi_min = float(psi_min)
    if not psi_range_violation(psi_min, a, b, tol):
        return
    lo, _, hi, _ = psi_extremes(psi_min, a, b)
    name, coeffs = ("a", a) if len(a) else ("b", b)
    raise ParameterError(
        name,
        str([float(c) for c in coeffs]),
        f"psi must stay within psi_min = {fmt_deg(psi_min)} ... psi_max = "
        f"{fmt_deg(np.pi - psi_min)} for the linear torque model (eq. 2); this law reaches "
        f"{np.degrees(lo):.1f} deg ... {np.degrees(hi):.1f} deg",
    )


# --- torques and work ---------------------------------------------------------------------
def stroke_direction(psi_min, a, b, alpha):
    """+1 in expansion (``psi`` rising), -1 in compression (falling).

    The sign of ``psi'``; where ``psi'`` vanishes, the stroke that begins
    there: the sign of ``psi''``, and where that vanishes too (a flat
    extreme, e.g. a dwell law) the sign of ``psi'`` a little later
    (``1e-3 / (2 k_max)`` rad); 0 for the constant law.
    """
    alpha = np.asarray(alpha, dtype=float)
    d1, d2 = psi_law(psi_min, a, b, alpha)[1:3]
    k = _higher(a, b)[0]
    later = psi_law(psi_min, a, b, alpha + 1e-3 / (2.0 * (k[-1] if k.size else 1.0)))[1]
    out = np.sign(later)
    out = np.where(np.abs(d2) > 1e-10 * _scale(psi_min, a, b, 2), np.sign(d2), out)
    return np.where(np.abs(d1) > 1e-10 * _scale(psi_min, a, b, 1), np.sign(d1), out)


def blade_torque(torque_high, torque_low, psi_min, psi, stroke):
    """Torque on blade pair 1, linear in ``psi`` (eq. 29, as read from the OCR).

    ``M_p = a - b (psi - pi/2)/(pi/2 - psi_min)`` in expansion (``stroke = +1``),
    ``M_c = -a - b (psi - pi/2)/(pi/2 - psi_min)`` in compression (-1), with
    ``a = (M1 - M2)/2``, ``b = (M1 + M2)/2``; ``stroke = 0`` gives their mean.
    Thus ``M_p(psi_min) = M1``, ``M_p(psi_max) = -M2``, ``M_c(psi_max) = -M1``,
    ``M_c(psi_min) = M2``: two parallel lines ``2a = M1 - M2`` apart. Pair 2
    carries ``M_2 = -M_1`` (eq. 24). For ``psi_min = pi/2`` the ``b`` term is
    taken as zero.

    Parameters
    ----------
    psi : array_like
        [rad].
    stroke : array_like
        +1, -1 or 0, see :func:`stroke_direction`.
    torque_high, torque_low : array_like
        ``M1``, ``M2`` [N m].
    psi_min : array_like
        [rad].

    Returns
    -------
    ndarray
        ``M_1`` [N m], all inputs broadcast.
    """
    h = _HALF_PI - np.asarray(psi_min, dtype=float)
    x = np.where(h == 0.0, 0.0, (np.asarray(psi) - _HALF_PI) / np.where(h == 0.0, 1.0, h))
    m1, m2 = np.asarray(torque_high, dtype=float), np.asarray(torque_low, dtype=float)
    return np.asarray(stroke) * 0.5 * (m1 - m2) - 0.5 * (m1 + m2) * x


def linear_member_torques(blade_torque):
    """Torques on blade pairs 1 and 2 of the linear model, ``(M_1, -M_1)`` [N m] (eq. 24).

    Parameters
    ----------
    blade_torque : array_like
        ``M_1`` of eq. 29 (:func:`blade_torque`) [N m], any shape.

    Returns
    -------
    ndarray, shape (2, ...)
    """
    m = np.asarray(blade_torque, dtype=float)
    return np.stack([m, -m])


def shaft_torque(psi_min, a, b, torque_high, torque_low, alpha):
    """Torque the blades drive the output shaft with, ``dA/d alpha`` [N m] (eq. 23, 24).

    By virtual work ``M_1 phi_1' + M_2 phi_2' = M_1 psi'`` with ``M_2 = -M_1``;
    quasi-static, frictionless, rigid links.
    """
    psi, d1 = psi_law(psi_min, a, b, alpha)[:2]
    s = stroke_direction(psi_min, a, b, alpha)
    return blade_torque(torque_high, torque_low, psi_min, psi, s) * d1


def indicator_work(psi_min, a, b, torque_high, torque_low, nodes=None):
    """Indicator work of the blade torques over one period ``0 <= alpha <= pi`` [J] (eq. 26-28).

    ``A = integral_0^pi M_1(psi, sign psi') psi' d alpha``, integrated over the
    law itself: [0, pi] is split at the stationary points of ``psi`` and each
    monotone piece is integrated by Gauss-Legendre (exact to rounding for
    these trigonometric integrands). For a law monotone between its extremes
    this equals ``Delta M Delta psi`` (eq. 31, 34); every extra back-and-forth
    swing of ``psi`` adds ``(M1 - M2)`` times its travel, so in general
    ``A = (M1 - M2) * psi_total_variation / 2`` - the paper's claim that the
    work does not depend on the profile holds for monotone laws only.

    Parameters
    ----------
    psi_min : array_like
        [rad]; scalar when ``a`` or ``b`` hold harmonics (their stationary points
        depend on the law), any shape for the first-harmonic law (stationary at
        0, pi/2, pi), broadcast with the torques.
    a, b : sequence of float
        [rad].
    torque_high, torque_low : array_like
        ``M1``, ``M2`` [N m], broadcast together.
    nodes : int, optional
        Gauss-Legendre nodes per piece; default ``64 + 16 K``.

    Returns
    -------
    ndarray
        [J], shape of the broadcast of ``psi_min`` and the torques.
    """
    k = _higher(a, b)[0].size
    if k:
        psi_min = np.asarray(float(psi_min))
        z = psi_stationary_points(psi_min, a, b)
    else:
        psi_min = np.asarray(psi_min, dtype=float)
        z = _FIRST_HARMONIC_STATIONARY
    lo, hi = z[:-1], z[1:]
    n = nodes or 64 + 16 * k
    x, w = np.polynomial.legendre.leggauss(n)
    half = 0.5 * (hi - lo)[:, None]
    al = 0.5 * (hi + lo)[:, None] + half * x
    pm = psi_min[..., None, None]
    psi, d1 = psi_law(pm, a, b, al)[:2]
    ends = psi_law(psi_min[..., None], a, b, z)[0]
    s = np.sign(np.diff(ends, axis=-1))[..., None]
    m1 = np.asarray(torque_high, dtype=float)[..., None, None]
    m2 = np.asarray(torque_low, dtype=float)[..., None, None]
    M = blade_torque(m1, m2, pm, psi, s)
    return np.sum(M * d1 * w * half, axis=(-2, -1))


def indicator_work_closed_form(psi_min, torque_high, torque_low):
    """``A = Delta M Delta psi = (M1 - M2)(pi - 2 psi_min)`` [J] (eq. 31, 34).

    Holds for laws monotone between their extremes only; see :func:`indicator_work`.
    """
    return (np.asarray(torque_high) - np.asarray(torque_low)) * (
        np.pi - 2.0 * np.asarray(psi_min, dtype=float)
    )


def mean_shaft_torque(psi_min, a, b, torque_high, torque_low):
    """Mean driving torque on the output shaft ``A / pi`` [N m] (the paper's ``M_dv``)."""
    return indicator_work(psi_min, a, b, torque_high, torque_low) / np.pi


# --- parameters ---------------------------------------------------------------------------
def violation(link_length, psi_min):
    """Which parameter of each design is out of its admissible range.

    ``link_length`` (``2l``) [m] must be finite and > 0, ``psi_min`` [rad] in
    ``(0, pi/2)`` (``pi/2`` is the constant law). The harmonics ``a``, ``b`` are
    checked per law by :func:`check_law`.

    Returns
    -------
    ndarray of int16
        Broadcast shape of the inputs: 0 where admissible, else ``i + 1`` for the
        first violated parameter ``CHECKS[i]``.
    """
    with np.errstate(invalid="ignore"):
        L = np.asarray(link_length, dtype=float)
        p = np.asarray(psi_min, dtype=float)
        bad = np.broadcast_arrays(
            ~(np.isfinite(L) & (L > 0.0)), ~(np.isfinite(p) & (p > 0.0) & (p < _HALF_PI))
        )
    out = np.zeros(bad[0].shape, dtype=np.int16)
    for i, b in enumerate(bad):
        out[(out == 0) & b] = i + 1
    return out


def _number(x):
    """A parameter as float (scalar) or float array (many designs)."""
    a = np.asarray(x, dtype=float)
    return float(a) if a.ndim == 0 else a


def _coeff_tuple(name, values):
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, repr(values), "a list of numbers [rad]") from None
    if arr.size == 0:
        return ()
    if arr.ndim != 1:
        raise ParameterError(name, repr(values), "a flat list of numbers [rad]")
    if arr.size > MAX_HARMONICS:
        raise ParameterError(
            name, f"{arr.size} coefficients", f"at most {MAX_HARMONICS} higher harmonics"
        )
    if not np.all(np.isfinite(arr)):
        raise ParameterError(name, repr(list(values)), "finite numbers [rad]")
    return tuple(float(v) for v in arr)


@dataclass(frozen=True)
class RhomboidCam:
    """Parameters of the rhomboid lever-cam converter.

    A thin holder of the parameters, validated by :func:`violation` and
    :func:`check_law`; ``link_length`` and ``psi_min`` may be arrays (many
    first-harmonic laws, broadcast together) when ``a`` and ``b`` are empty.

    Attributes
    ----------
    link_length : float
        Side ``2l`` of the rhombus [m], > 0.
    psi_min : float
        Smallest angle between the blade axes [rad], ``0 < psi_min < pi/2``;
        ``psi_max = pi - psi_min``.
    a, b : tuple of float
        Higher harmonics ``a3, a5, ...`` and ``b3, b5, ...`` of eq. 13 [rad]
        (at most :data:`MAX_HARMONICS` each); empty for the first-harmonic law
        (eq. 16). They must keep ``0 < psi < pi``.
    """

    link_length: float
    psi_min: float
    a: tuple = ()
    b: tuple = ()

    def __post_init__(self):
        code = violation(self.link_length, self.psi_min)
        if np.any(code):
            k = int(np.flatnonzero(code)[0])
            name = CHECKS[code.flat[k] - 1]
            value = np.broadcast_to(np.asarray(getattr(self, name)), code.shape).flat[k]
            if name == "link_length":
                raise ParameterError(name, fmt_mm(value), "link_length > 0 mm")
            raise ParameterError(
                name,
                fmt_deg(value),
                "0 deg < psi_min < 90 deg (psi_min = 90 deg is the constant law: no motion)",
            )
        L, p = _number(self.link_length), _number(self.psi_min)
        a = _coeff_tuple("a", self.a)
        b = _coeff_tuple("b", self.b)
        object.__setattr__(self, "link_length", L)
        object.__setattr__(self, "psi_min", p)
        object.__setattr__(self, "a", a)
        object.__setattr__(self, "b", b)
        if a or b:
            if np.ndim(p) != 0:
                raise ParameterError(
                    "psi_min", f"{np.size(p)} values", "a single value when a, b hold harmonics"
                )
            check_law(p, a, b)
