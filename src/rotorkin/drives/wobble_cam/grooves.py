"""Groove centre-lines of the spherical cam and their derivatives (cam frame).

The roller centres seen from the cam, eq. 10-11 of Chen Hu et al. (2015)
(:func:`rotorkin.drives.wobble_cam.kinematics.groove_points`), with two exact
derivatives; the shaft angle after which they close and which rollers share a
groove. Used by :mod:`rotorkin.drives.wobble_cam.cam_crossings` and
:mod:`rotorkin.drives.wobble_cam.cam` (which re-exports the public names).
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import kinematics as wc

__all__ = ["groove_derivatives", "groove_period", "distinct_grooves"]

#: d psi / d theta of the drive's cam law ``psi = -theta`` (linear, so this is exact).
_CAM_RATE = float(wc.cam_angle(1.0) - wc.cam_angle(0.0))
#: Samples per groove period for the searches (minimum, crossings); refined afterwards.
_SEARCH_SAMPLES = 4096
#: Fraction of a step by which search samples are shifted off round angles.
_SAMPLE_SHIFT = 0.5 * (np.sqrt(5.0) - 1.0)


# --------------------------------------------------------------------------------------------
# centre-lines and their derivatives
# --------------------------------------------------------------------------------------------
def _cross_x(v):
    """``e_x x v`` for v of shape (3, ...)."""
    return np.stack([np.zeros_like(v[0]), -v[2], v[1]])


def _partials(drive: wc.WobbleCam, theta):
    """Groove point ``p``, ``dp/d(theta - psi)``, ``dp/du`` (shape (3, 4, ...)) and the spin law.

    ``p = plate_point(theta - psi, u)``, ``u = varphi + c`` (eq. 10-11). Exact partials:
    ``dp/d(theta - psi) = -e_x x p`` (``A_t`` turns z towards +y, a turn about -x) and
    ``dp/du = plate_point(theta - psi, u + pi/2)`` (the plate radius turned by 90 deg).
    """
    theta = np.asarray(theta, dtype=float)
    c = wc.roller_offsets_against(drive, theta)
    spin = wc.spin_law(drive, theta)
    cam = wc.cam_angle(theta)
    phi, r = drive.plate_tilt, drive.sphere_radius
    p = wc.groove_point(phi, r, theta, cam, spin[0], c)
    pu = wc.groove_point(phi, r, theta, cam, spin[0], c + 0.5 * np.pi)
    return p, -_cross_x(p), pu, spin


def groove_derivatives(drive: wc.WobbleCam, theta):
    """Groove centre-lines of the 4 rollers and their first two derivatives (cam frame).

    ``g(theta) = plate_point(theta - psi, varphi + c)`` (eq. 10-11,
    :func:`rotorkin.drives.wobble_cam.kinematics.groove_points`), with ``psi = -theta`` and the
    spin law of ``drive`` (periodic correction included); derivatives by the chain
    rule from the exact partials of :func:`_partials`.

    Parameters
    ----------
    drive : WobbleCam
    theta : array_like, shape (...)
        Shaft angle [rad].

    Returns
    -------
    (g, dg, d2g) : tuple of ndarray, shape (4, 3, ...)
        [m], [m/rad], [m/rad^2]; roller index first.
    """
    p, pt, pu, spin = _partials(drive, theta)
    w = 1.0 - _CAM_RATE  # d(theta - psi)/d theta
    d1 = pt * w + pu * spin[1]
    ptu = -_cross_x(pu)
    ptt = -_cross_x(pt)
    d2 = ptt * w * w + 2.0 * ptu * w * spin[1] - p * spin[1] ** 2 + pu * spin[2]
    return tuple(np.moveaxis(x, 0, 1) for x in (p, d1, d2))


def groove_period(drive: wc.WobbleCam) -> float:
    """Shaft angle after which every groove centre-line closes: pi, 2 pi or 4 pi [rad].

    ``theta - psi = 2 theta`` closes after pi; the spin law adds ``n T`` (a multiple of
    2 pi needed) and its correction (2 pi periodic). Found by testing the candidates.
    """
    theta = np.linspace(0.0, 2.0 * np.pi, 64, endpoint=False)
    g0 = groove_derivatives(drive, theta)[0]
    for period in (np.pi, 2.0 * np.pi, 4.0 * np.pi):
        g1 = groove_derivatives(drive, theta + period)[0]
        if np.max(np.abs(g1 - g0)) < 1e-9 * drive.sphere_radius:
            return period
    raise ParameterError(  # pragma: no cover - WobbleCam admits only closing laws
        "spin_ratio", f"{drive.spin_ratio:g}", "a law whose grooves close"
    )


def distinct_grooves(drive: wc.WobbleCam) -> list[int]:
    """Rollers whose grooves are distinct curves (all 4, or 2 when rollers share grooves).

    When the plate has turned by pi relative to the cam after a shift of the shaft
    angle by a multiple of pi shorter than the groove period (spin ratio -1, -1/2,
    ...), roller ``c`` runs on in the groove of roller ``c + pi``: one groove for two
    rollers. Checked numerically for every such shift.
    """
    period = groove_period(drive)
    theta = np.linspace(0.0, period, 97)
    g = groove_derivatives(drive, theta)[0]
    shifts = np.pi * np.arange(1, int(round(period / np.pi)))
    shifted = [groove_derivatives(drive, theta + x)[0] for x in shifts]
    keep: list[int] = []
    for j in range(4):
        if not any(
            np.max(np.abs(gs[i] - g[j])) < 1e-9 * drive.sphere_radius
            for i in keep
            for gs in shifted
        ):
            keep.append(j)
    return keep
