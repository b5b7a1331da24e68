"""ISO 286 limits and fits: tolerance grades, shaft deviations, clearances of hole-basis fits.

ISO 286-1:2010 (Table 1, standard tolerance grades IT6..IT9) and ISO 286-2:2010 (Table 2,
fundamental deviations of the shafts ``d e f g h js k``), nominal sizes up to 500 mm, each
range "over the previous end, up to and including this one". Holes of position H
(``EI = 0``, ``ES = IT``). For a shaft of position ``d..h`` the table value is the upper
deviation ``es`` and ``ei = es - IT``; for ``k`` it is ``ei`` and ``es = ei + IT``; ``js``
is ``+-IT/2``. The diametral clearance of a fit is

    clearance_min  = EI - es
    clearance_max  = ES - ei
    clearance_mean = (ES + EI)/2 - (es + ei)/2

(what parts machined to the middle of both zones have: the usual basis of a CAM program).
Example, the close running fit H8/f7 at 8 mm (range over 6 up to 10 mm): IT8 = 22 um,
IT7 = 15 um, es = -13 um, so 13 to 50 um, 31.5 um on average.

Used by every part that runs on or in another (:mod:`rotorkin.render.workshop` for hubs and
running gaps, a drive's own grooves and rollers).
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError

__all__ = ["SIZES_MM", "IT", "SHAFT_DEVIATIONS", "fit_limits", "fit_clearance", "running_gap"]

#: Upper ends of the ISO 286 nominal size ranges [mm].
SIZES_MM = np.array([3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500], dtype=float)
#: ISO 286-1 standard tolerance grades [um] per size range of :data:`SIZES_MM`.
IT = {
    6: (6, 8, 9, 11, 13, 16, 19, 22, 25, 29, 32, 36, 40),
    7: (10, 12, 15, 18, 21, 25, 30, 35, 40, 46, 52, 57, 63),
    8: (14, 18, 22, 27, 33, 39, 46, 54, 63, 72, 81, 89, 97),
    9: (25, 30, 36, 43, 52, 62, 74, 87, 100, 115, 130, 140, 155),
}
#: ISO 286-2 fundamental deviations of shafts [um]: upper deviation es of d..h, lower
#: deviation ei of k (grades 4 to 7); js is +-IT/2.
SHAFT_DEVIATIONS = {
    "d": (-20, -30, -40, -50, -65, -80, -100, -120, -145, -170, -190, -210, -230),
    "e": (-14, -20, -25, -32, -40, -50, -60, -72, -85, -100, -110, -125, -135),
    "f": (-6, -10, -13, -16, -20, -25, -30, -36, -43, -50, -56, -62, -68),
    "g": (-2, -4, -5, -6, -7, -9, -10, -12, -14, -15, -17, -18, -20),
    "h": (0,) * 13,
    "k": (0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 4, 4, 5),
}


def _ranges(size) -> np.ndarray:
    """Index of each size's ISO 286 range (``size`` [m], any shape)."""
    s = np.asarray(size, dtype=float) / 1e-3
    bad = ~np.isfinite(s) | (s <= 0.0) | (s > SIZES_MM[-1])
    if np.any(bad):
        raise ParameterError(
            "size", fmt_mm(float(np.ravel(s)[np.argmax(np.ravel(bad))]) * 1e-3),
            "0 mm < size <= 500 mm (ISO 286 tables)",
        )  # fmt: skip
    return np.searchsorted(SIZES_MM, s - 1e-9)


def fit_limits(fit: str, size):
    """Limit deviations of a hole-basis fit such as ``"H7/g6"`` at ``size`` [m].

    Parameters
    ----------
    fit : str
        Hole ``H<grade>`` and shaft ``<d|e|f|g|h|js|k><grade>``, grades 6 to 9.
    size : float or array_like
        Nominal size [m], ``0 < size <= 500 mm``.

    Returns
    -------
    ((EI, ES), (ei, es))
        Lower and upper deviations of the hole and the shaft [m], each the shape of ``size``.
    """
    try:
        hole, shaft = str(fit).split("/")
        grade_h, grade_s = int(hole[1:]), int(shaft.lstrip("jsdefghk"))
        ok = hole[0] == "H" and shaft.rstrip("0123456789") in (*SHAFT_DEVIATIONS, "js")
        ok = ok and grade_h in IT and grade_s in IT
    except (ValueError, IndexError):
        ok = False
    if not ok:
        raise ParameterError("fit", repr(fit), "a hole-basis fit such as 'H7/g6' (grades 6..9)")
    i = _ranges(size)
    um = 1e-6
    it_h = np.asarray(IT[grade_h], dtype=float)[i] * um
    it_s = np.asarray(IT[grade_s], dtype=float)[i] * um
    zero = np.zeros_like(it_h)
    if shaft.startswith("js"):
        return (zero, it_h), (-0.5 * it_s, 0.5 * it_s)
    dev = np.asarray(SHAFT_DEVIATIONS[shaft[0]], dtype=float)[i] * um
    if shaft[0] == "k":
        return (zero, it_h), (dev, dev + it_s)
    return (zero, it_h), (dev - it_s, dev)


def fit_clearance(fit: str, size, which: str = "mean"):
    """Diametral clearance of a hole-basis fit at ``size`` [m] (negative: interference).

    Parameters
    ----------
    fit : str
        As in :func:`fit_limits`, e.g. ``"H8/f7"`` (close running).
    size : float or array_like
        Nominal diameter [m], ``0 < size <= 500 mm``.
    which : {"mean", "min", "max"}
        The mean of the clearances (parts machined to the middle of both zones; default),
        the smallest or the largest.

    Returns
    -------
    ndarray
        [m], the shape of ``size``.
    """
    (ei_h, es_h), (ei_s, es_s) = fit_limits(fit, size)
    if which == "mean":
        return 0.5 * (ei_h + es_h) - 0.5 * (ei_s + es_s)
    if which == "min":
        return ei_h - es_s
    if which == "max":
        return es_h - ei_s
    raise ParameterError("which", repr(which), "'mean', 'min' or 'max'")


def running_gap(fit: str, size) -> float:
    """Radial running gap [m]: half the mean diametral clearance of ``fit`` at ``size`` [m]."""
    return float(0.5 * fit_clearance(fit, size))
