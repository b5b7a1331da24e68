"""Pistons and chambers of the wobble-cam twin-rotor engine (eq. 17-23 of Chen Hu et al. 2015).

The bookkeeping between the slider (rail) angle ``alpha' = Phi_2 - Phi_1`` of
:mod:`rotorkin.drives.wobble_cam.kinematics` and the chambers between the pistons of the
two rotors: the piston offset gamma, the interference limits of eq. 20 and the
plate-tilt limit they set, the extremes of the slider angle (eq. 17), the
chamber angles of both kinds (eq. 18-19), the piston width for a design
compression ratio (eq. 21-22) and the cycle counts. Every public name is also
importable from :mod:`rotorkin.drives.wobble_cam.kinematics` (where the conventions are
stated); ``params`` is a :class:`rotorkin.drives.wobble_cam.kinematics.WobbleCam`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rotorkin.core.errors import ParameterError

if TYPE_CHECKING:
    from rotorkin.drives.wobble_cam.kinematics import WobbleCam

__all__ = [
    "PISTON_OFFSET",
    "CHAMBERS",
    "piston_offset",
    "chamber_count",
    "slider_angle_limits",
    "max_plate_tilt",
    "slider_angle_extremes",
    "chamber_angles",
    "min_compression_ratio",
    "PistonLayout",
    "piston_layout",
    "volume_cycles_per_rev",
    "power_strokes_per_rev",
]

#: Angle gamma between a piston's centre line and the nearest rail [rad] (eq. 18-19, N = 4).
PISTON_OFFSET = np.pi / 8.0
#: Number of chambers between the two 4-piston rotors.
CHAMBERS = 8


def piston_offset(pistons=4):
    """Angle gamma between a piston's centre line and the nearest rail [rad] (eq. 18-19).

    With 2 rails per rotor (pi apart) and N pistons (2 pi/N apart): eq. 18 gives
    ``alpha'_1 + alpha'_2 = pi`` and ``delta_A + delta_B + 2 beta = 2 pi/N``; eq. 19,
    ``alpha' = delta + beta + 2 gamma``, written for both chamber kinds then
    gives ``gamma = pi/4 - pi/(2N)`` (pi/8 at the paper's N = 4; 0 at N = 2).
    """
    return np.pi / 4.0 - np.pi / (2.0 * np.asarray(pistons, dtype=float))


def chamber_count(pistons=4) -> int:
    """Chambers between two rotors of N pistons each: ``2 N`` (8 in the paper)."""
    return 2 * int(pistons)


def slider_angle_limits(pistons=4):
    """Interference limits of the slider angle, eq. 20 generalised [rad].

    The centre lines of neighbouring pistons must not cross:
    ``alpha'_min >= 2 gamma = pi/2 - pi/N`` (kind A) and
    ``alpha'_max <= 2 pi/N + 2 gamma = pi/2 + pi/N`` (kind B); pi/4 and 3 pi/4 at N = 4.

    Returns
    -------
    (lower, upper) : tuple of float
    """
    g2 = 2.0 * float(piston_offset(pistons))
    return g2, 2.0 * np.pi / float(pistons) + g2


def _check_pistons(pistons):
    """ParameterError unless N is an even integer >= 2."""
    ok = isinstance(pistons, (int, np.integer)) and not isinstance(pistons, bool)
    if not (ok and pistons >= 2 and pistons % 2 == 0):
        raise ParameterError(
            "pistons_per_rotor",
            repr(pistons),
            "an even integer >= 2 (each rotor has 2 rails 180 deg apart, so its pistons must "
            "repeat every 180 deg for eq. 18-19 and the period of one shaft turn)",
        )


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
    pistons : int, optional
        Pistons per rotor N (even, default 4).

    Returns
    -------
    ndarray
        Limit plate tilt [rad].
    """
    t = np.tan(np.asarray(roller_axis_angle, dtype=float) / 2.0)
    tn = np.tan(np.pi / 4.0 - np.pi / (2.0 * float(pistons)))
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


def chamber_angles(slider, piston_width, pistons=4):
    """Angles of the two chamber kinds from the slider angle (eq. 18-19) [rad].

    ``delta_A = alpha' - 2 gamma - beta`` (rotor-1 piston to the rotor-2 piston
    ahead of it) and ``delta_B = 2 pi/N + 2 gamma - alpha' - beta`` (the next
    chamber), ``gamma = pi/4 - pi/(2N)`` (:func:`piston_offset`);
    ``delta_A + delta_B + 2 beta = 2 pi/N`` (eq. 18; pi/2 at N = 4). Kind B is
    eq. 19 written with the complementary slider angle ``alpha'_2 = pi - alpha'``
    (eq. 18). The 2N chambers alternate A, B.

    Parameters
    ----------
    slider : array_like
        alpha' [rad].
    piston_width : float
        beta [rad].
    pistons : int, optional
        N, pistons per rotor (default 4, the paper's).

    Returns
    -------
    (delta_A, delta_B) : tuple of ndarray
    """
    slider = np.asarray(slider, dtype=float)
    g2 = 2.0 * float(piston_offset(pistons))
    a = slider - g2 - piston_width
    b = 2.0 * np.pi / float(pistons) + g2 - slider - piston_width
    return a, b


def _gaps(params: WobbleCam):
    """Smallest and largest centre-line gap of chamber kinds A and B [rad]."""
    amax, amin = slider_angle_extremes(params.plate_tilt, params.roller_axis_angle)
    amax, amin = float(amax), float(amin)
    lo, hi = slider_angle_limits(params.pistons_per_rotor)
    return (amin - lo, amax - lo), (hi - amax, hi - amin)


def min_compression_ratio(params: WobbleCam) -> float:
    """Compression ratio reached with zero-width pistons; any design ratio must exceed it.

    The piston width beta of :func:`piston_layout` is positive iff
    ``eps > g_max / g_min``, the ratio of the largest to the smallest
    centre-line gap of the tighter chamber kind.
    """
    ga, gb = _gaps(params)
    lo, hi = min((ga, gb), key=lambda g: g[0])
    return hi / lo


@dataclass(frozen=True)
class PistonLayout:
    """Piston width and chamber extremes for a design compression ratio.

    Attributes
    ----------
    compression_ratio : float
        Design ratio eps, reached by the tighter chamber kind.
    piston_width : float
        beta [rad].
    chamber_a_min, chamber_a_max, chamber_b_min, chamber_b_max : float
        Extremes of delta_A and delta_B [rad].
    compression_ratio_a, compression_ratio_b : float
        ``delta_max / delta_min`` of each kind.
    design_kind : str
        ``"A"`` or ``"B"``: the kind with the smaller minimum (ratio = eps).
    """

    compression_ratio: float
    piston_width: float
    chamber_a_min: float
    chamber_a_max: float
    chamber_b_min: float
    chamber_b_max: float
    compression_ratio_a: float
    compression_ratio_b: float
    design_kind: str

    @property
    def swing(self) -> float:
        """``delta_max - delta_min = alpha'_max - alpha'_min`` (eq. 23) [rad]."""
        return self.chamber_a_max - self.chamber_a_min


def piston_layout(params: WobbleCam, compression_ratio: float) -> PistonLayout:
    """Piston width beta giving the design compression ratio (eq. 21-22, generalised).

    The chamber kind with the smaller minimum angle gets exactly
    ``eps = delta_max/delta_min`` (volume proportional to angle, no clearance
    volume): with its centre-line gaps ``g_min, g_max``,
    ``beta = (eps g_min - g_max) / (eps - 1)``. At ``alpha = 90 deg`` both kinds
    coincide (``alpha'_max + alpha'_min = pi``) and this is eq. 21 (N = 4),
    ``beta = (eps+1)/(eps-1) alpha'_min - pi (eps+3) / (4 (eps-1))``; for N pistons
    ``beta = (eps+1)/(eps-1) alpha'_min - (pi + (eps-1)(pi/2 - pi/N)) / (eps-1)``. For other
    alpha the paper's eq. 21 does not hold (it assumes
    ``alpha'_max + alpha'_min = pi``); the other kind then has a lower ratio
    (Fig. 11).

    Parameters
    ----------
    params : WobbleCam
    compression_ratio : float
        eps, ``min_compression_ratio(params) < eps < inf``.

    Raises
    ------
    ParameterError
        named ``"compression_ratio"`` when eps is not admissible.
    """
    eps = float(compression_ratio)
    lo_ratio = min_compression_ratio(params)
    if not (np.isfinite(eps) and eps > max(lo_ratio, 1.0)):
        raise ParameterError(
            "compression_ratio",
            f"{eps:g}",
            f"compression_ratio > {lo_ratio:.4g} (the ratio of zero-width pistons at this "
            "plate tilt and roller axis angle; a smaller one needs a negative piston width, "
            "eq. 21)",
        )
    ga, gb = _gaps(params)
    kind, (gmin, gmax) = min((("A", ga), ("B", gb)), key=lambda k: k[1][0])
    beta = (eps * gmin - gmax) / (eps - 1.0)
    a = (ga[0] - beta, ga[1] - beta)
    b = (gb[0] - beta, gb[1] - beta)
    return PistonLayout(
        compression_ratio=eps,
        piston_width=beta,
        chamber_a_min=a[0],
        chamber_a_max=a[1],
        chamber_b_min=b[0],
        chamber_b_max=b[1],
        compression_ratio_a=a[1] / a[0],
        compression_ratio_b=b[1] / b[0],
        design_kind=kind,
    )


# --------------------------------------------------------------------------------------------
# counts
# --------------------------------------------------------------------------------------------
def volume_cycles_per_rev(params: WobbleCam) -> int:
    """Volume cycles of each chamber per shaft turn: ``2 |n|`` (alpha' has period pi in varphi).

    Paper section 1.2 and 4.2.3: 4 at n = -2.
    """
    return int(round(2.0 * abs(params.spin_ratio)))


def power_strokes_per_rev(params: WobbleCam, strokes_per_cycle: int = 4) -> int:
    """Power strokes per shaft turn: ``2N chambers x 2 |n| / (strokes_per_cycle / 2)``.

    A four-stroke cycle takes two volume cycles: 16 at N = 4, n = -2 (paper section 1.2).
    """
    chambers = chamber_count(params.pistons_per_rotor)
    return int(round(chambers * volume_cycles_per_rev(params) * 2 / strokes_per_cycle))
