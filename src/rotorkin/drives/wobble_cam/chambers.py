"""Slider-angle limits and chamber angles of the wobble-cam engine (Chen Hu et al. 2015).

The bookkeeping between the slider (rail) angle ``alpha' = Phi_2 - Phi_1`` of
:mod:`rotorkin.drives.wobble_cam.kinematics` and the chambers between the pistons of the
two rotors: the interference limits of eq. 20 and the plate-tilt limit they
set, the extremes of the slider angle (eq. 17) and the chamber angles of both
kinds (eq. 18-19). The functions take plain numbers (floats or arrays); the
piston width for a design compression ratio (eq. 21-22) and the cycle counts, which take a
:class:`rotorkin.drives.wobble_cam.kinematics.WobbleCam`, are in
:mod:`rotorkin.drives.wobble_cam.kinematics`. The piston offset gamma and the
chamber count are the machine's (:mod:`rotorkin.machines.twin_rotor`). Every
public name is also importable from :mod:`rotorkin.drives.wobble_cam.kinematics`
(where the conventions are stated).
"""

from __future__ import annotations

import numpy as np

from rotorkin.machines.twin_rotor import chamber_count, piston_offset

__all__ = [
    "PISTON_OFFSET",
    "CHAMBERS",
    "piston_offset",
    "chamber_count",
    "slider_angle_limits",
    "max_plate_tilt",
    "slider_angle_extremes",
    "chamber_angles",
    "chamber_gaps",
    "design_kind_a",
    "zero_width_ratio",
    "piston_width",
    "compression_ratio_violation",
]

#: Angle gamma between a piston's centre line and the nearest rail [rad] (eq. 18-19, N = 4).
PISTON_OFFSET = np.pi / 8.0
#: Number of chambers between the two 4-piston rotors.
CHAMBERS = 8


def slider_angle_limits(pistons=4):
    """Interference limits of the slider angle, eq. 20 generalised [rad].

    The centre lines of neighbouring pistons must not cross:
    ``alpha'_min >= 2 gamma = pi/2 - pi/N`` (kind A) and
    ``alpha'_max <= 2 pi/N + 2 gamma = pi/2 + pi/N`` (kind B); pi/4 and 3 pi/4 at N = 4.

    Returns
    -------
    (lower, upper) : tuple of ndarray
        Of ``pistons``' shape (it may be an array).
    """
    g2 = 2.0 * piston_offset(pistons)
    return g2, 2.0 * np.pi / np.asarray(pistons, dtype=float) + g2


def max_plate_tilt(roller_axis_angle, pistons=4):
    """Largest plate tilt at which the pistons do not interfere (eq. 20) [rad].

    Eq. 20 asks ``alpha'_max <= 3 pi/4`` and ``alpha'_min >= pi/4`` (N = 4; in
    general :func:`slider_angle_limits`); with eq. 17 in closed form (see
    :func:`slider_angle_extremes`) this gives, with ``t_N = tan(pi/4 - pi/(2N))``,
    ``cos(phi_lim) = max(t_N tan(alpha/2), t_N / tan(alpha/2))``.
    The paper reads "about 65 deg" off Fig. 13 for ``alpha = 90 deg``, N = 4; the
    exact value is 65.53 deg (``cos(phi_lim) = tan(pi/8) = sqrt(2) - 1``). At
    N = 2 the limit is 90 deg for every alpha.

    Parameters
    ----------
    roller_axis_angle : array_like
        Angle alpha between the roller groups [rad],
        ``pi/2 - pi/N < alpha < pi/2 + pi/N`` (outside, no tilt is admissible and
        NaN is returned).
    pistons : int or array_like, optional
        Pistons per rotor N (even, default 4); broadcasts with ``roller_axis_angle``.

    Returns
    -------
    ndarray
        Limit plate tilt [rad].
    """
    t = np.tan(np.asarray(roller_axis_angle, dtype=float) / 2.0)
    tn = np.tan(np.pi / 4.0 - np.pi / (2.0 * np.asarray(pistons, dtype=float)))
    cos_lim = np.maximum(t * tn, tn / t)
    with np.errstate(invalid="ignore"):
        return np.where(cos_lim < 1.0, np.arccos(np.minimum(cos_lim, 1.0)), np.nan)


# --------------------------------------------------------------------------------------------
# slider angle extremes and chambers
# --------------------------------------------------------------------------------------------
def slider_angle_extremes(plate_tilt, roller_axis_angle):
    """Largest and smallest slider angle (eq. 17) [rad].

    ``alpha'_max = alpha'(varphi = 0) = 2 atan(tan(alpha/2) / cos phi)``,
    ``alpha'_min = alpha'(varphi = pi/2) = 2 atan(cos(phi) tan(alpha/2))``
    (closed forms derived here; ``d alpha'/d varphi = 0`` iff
    ``sin(2 varphi) sin(alpha) = 0``). Valid for ``0 < alpha < pi``.

    Returns
    -------
    (alpha_max, alpha_min) : tuple of ndarray
    """
    c = np.cos(np.asarray(plate_tilt, dtype=float))
    t = np.tan(0.5 * np.asarray(roller_axis_angle, dtype=float))
    return 2.0 * np.arctan(t / c), 2.0 * np.arctan(c * t)


def chamber_angles(piston_width, slider, *, pistons=4):
    """Angles of the two chamber kinds from the slider angle (eq. 18-19) [rad].

    ``delta_A = alpha' - 2 gamma - beta`` (rotor-1 piston to the rotor-2 piston
    ahead of it) and ``delta_B = 2 pi/N + 2 gamma - alpha' - beta`` (the next
    chamber), ``gamma = pi/4 - pi/(2N)`` (:func:`piston_offset`);
    ``delta_A + delta_B + 2 beta = 2 pi/N`` (eq. 18; pi/2 at N = 4). Kind B is
    eq. 19 written with the complementary slider angle ``alpha'_2 = pi - alpha'``
    (eq. 18). The 2N chambers alternate A, B.

    Parameters
    ----------
    piston_width : float or array_like
        beta [rad].
    slider : array_like
        alpha' [rad].
    pistons : int or array_like, optional
        N, pistons per rotor (default 4, the paper's).

    All three broadcast together.

    Returns
    -------
    (delta_A, delta_B) : tuple of ndarray
    """
    slider = np.asarray(slider, dtype=float)
    lo, hi = slider_angle_limits(pistons)
    a = slider - lo - piston_width
    b = hi - slider - piston_width
    return a, b


# --------------------------------------------------------------------------------------------
# piston width for a design compression ratio (eq. 21-22)
# --------------------------------------------------------------------------------------------
def chamber_gaps(plate_tilt, roller_axis_angle, pistons=4):
    """Smallest and largest centre-line gap of chamber kinds A and B [rad].

    The chamber angle of zero-width pistons: kind A ``alpha' - 2 gamma``,
    kind B ``2 pi/N + 2 gamma - alpha'`` at the slider-angle extremes (eq. 17-19).
    All arguments broadcast together.

    Returns
    -------
    ((a_min, a_max), (b_min, b_max)) : tuple of tuples of ndarray
    """
    amax, amin = slider_angle_extremes(plate_tilt, roller_axis_angle)
    lo, hi = slider_angle_limits(pistons)
    return (amin - lo, amax - lo), (hi - amax, hi - amin)


def design_kind_a(gaps):
    """Whether kind A is the tighter chamber kind (smaller minimum gap; A on a tie)."""
    (a0, _), (b0, _) = gaps
    return a0 <= b0


def zero_width_ratio(gaps):
    """Compression ratio of zero-width pistons, ``g_max / g_min`` of the tighter kind [-].

    Any design compression ratio must exceed it (the piston width of
    :func:`piston_width` is positive iff ``eps > g_max / g_min``).
    """
    (a0, a1), (b0, b1) = gaps
    return np.where(design_kind_a(gaps), a1 / a0, b1 / b0)


def piston_width(gaps, compression_ratio):
    """Piston width beta giving the design compression ratio eps (eq. 21-22, generalised) [rad].

    The tighter chamber kind, with centre-line gaps ``g_min, g_max``
    (:func:`chamber_gaps`), gets exactly ``eps = delta_max/delta_min``:
    ``beta = (eps g_min - g_max) / (eps - 1)``. Broadcasts over designs.
    """
    (a0, a1), (b0, b1) = gaps
    kind_a = design_kind_a(gaps)
    gmin, gmax = np.where(kind_a, a0, b0), np.where(kind_a, a1, b1)
    eps = np.asarray(compression_ratio, dtype=float)
    return (eps * gmin - gmax) / (eps - 1.0)


def compression_ratio_violation(gaps, compression_ratio, piston_width=None):
    """Where a design compression ratio (or a given piston width) is not admissible.

    ``eps`` must be finite and above ``max(1, zero_width_ratio(gaps))``; a given
    piston width (pistons as manufactured) must be below the smallest gap.

    Returns
    -------
    ndarray of bool
        True where inadmissible.
    """
    eps = np.asarray(compression_ratio, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        bad = ~(np.isfinite(eps) & (eps > np.maximum(zero_width_ratio(gaps), 1.0)))
        if piston_width is not None:
            (a0, _), (b0, _) = gaps
            bad = bad | ~(np.minimum(a0, b0) > piston_width)
    return bad
