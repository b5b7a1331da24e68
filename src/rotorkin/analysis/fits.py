"""ISO 286 limits and fits: the clearance of a running fit for a nominal diameter.

ISO 286-2:2010, tables of the standard tolerance grades IT7 and IT8 (Table 1 of
ISO 286-1) and of the fundamental deviation ``es`` of shafts ``f`` (Table 2 of
ISO 286-2), for nominal sizes up to 500 mm. The close running fit ``H8/f7`` (ISO 286-1,
annex; "close running" in the usual selection of preferred fits) gives the hole a
tolerance zone ``0 .. +IT8`` and the shaft ``es - IT7 .. es``:

    clearance_min  = -es
    clearance_max  = IT8 - es + IT7
    clearance_mean = IT8/2 - es + IT7/2

At 8 mm (range over 6 up to 10 mm): IT8 = 22 um, IT7 = 15 um, es = -13 um, so 13 to 50 um,
31.5 um on average.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError

__all__ = ["RANGES_MM", "running_fit_clearance"]

#: Upper ends of the nominal size ranges of ISO 286 [mm] (each range is "over the previous,
#: up to and including this").
RANGES_MM = np.array([3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500], dtype=float)
#: IT7 [um] per range (ISO 286-1, Table 1).
IT7_UM = np.array([10, 12, 15, 18, 21, 25, 30, 35, 40, 46, 52, 57, 63], dtype=float)
#: IT8 [um] per range (ISO 286-1, Table 1).
IT8_UM = np.array([14, 18, 22, 27, 33, 39, 46, 54, 63, 72, 81, 89, 97], dtype=float)
#: Upper deviation es of shafts f [um] per range (ISO 286-2, Table 2).
ES_F_UM = np.array([-6, -10, -13, -16, -20, -25, -30, -36, -43, -50, -56, -62, -68], dtype=float)


def running_fit_clearance(diameter, which: str = "mean"):
    """Diametral clearance of the ISO 286 close running fit H8/f7 at a nominal diameter [m].

    Parameters
    ----------
    diameter : array_like
        Nominal diameter [m], ``0 < d <= 500 mm``.
    which : {"mean", "min", "max"}
        The mean of the fit's clearance (the default; what a part machined to the middle of
        both tolerance zones has), or its smallest or largest.

    Returns
    -------
    ndarray
        [m], the shape of ``diameter``.
    """
    d = np.asarray(diameter, dtype=float)
    if np.any(~np.isfinite(d)) or np.any(d <= 0.0) or np.any(d > RANGES_MM[-1] * 1e-3):
        raise ParameterError(
            "diameter", fmt_mm(np.max(d)), "0 mm < diameter <= 500 mm (ISO 286 tables)"
        )
    k = np.searchsorted(RANGES_MM, d * 1e3, side="left")
    it7, it8, es = IT7_UM[k], IT8_UM[k], ES_F_UM[k]
    if which == "mean":
        um = 0.5 * it8 - es + 0.5 * it7
    elif which == "min":
        um = -es
    elif which == "max":
        um = it8 - es + it7
    else:
        raise ParameterError("which", repr(which), "'mean', 'min' or 'max'")
    return um * 1e-6
