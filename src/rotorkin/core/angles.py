"""The one branch-safe angle helper used everywhere in rotorkin.

``atan2`` jumps by 2 pi when its argument crosses the negative x axis. Every
angle rotorkin returns is a continuous function of the input angle, obtained by
measuring the angle of a vector *relative to a reference angle that is already
continuous* (usually a linear function of the input), so the correction stays
inside (-pi, pi) and no unwrapping over an array axis is ever needed.
"""

from __future__ import annotations

import numpy as np

__all__ = ["angle_near", "deg", "rad", "fmt_deg", "fmt_mm"]


def angle_near(y, x, ref):
    """Angle of the vector (x, y) on the branch closest to ``ref``.

    Returns ``ref + atan2(.)`` of the vector rotated by ``-ref``, so the
    result lies in ``(ref - pi, ref + pi]`` and is continuous wherever ``ref`` is
    continuous and the vector does not pass through the point opposite ``ref``.

    Parameters
    ----------
    y, x : array_like
        Components of the vector; broadcast together with ``ref``.
    ref : array_like
        Reference angle [rad].

    Returns
    -------
    ndarray
        Angle [rad].
    """
    ref = np.asarray(ref, dtype=float)
    c, s = np.cos(ref), np.sin(ref)
    return ref + np.arctan2(y * c - x * s, x * c + y * s)


def deg(x):
    """Radians to degrees (for edges only: reports, CLI, CAD)."""
    return np.degrees(x)


def rad(x):
    """Degrees to radians (for edges only: config, CLI)."""
    return np.radians(x)


def fmt_deg(x) -> str:
    """An angle [rad] as people read it in a message: ``'65.53 deg'``."""
    return f"{float(np.degrees(x)):.4g} deg"


def fmt_mm(x) -> str:
    """A length [m] as people read it in a message: ``'80 mm'``."""
    return f"{float(x) * 1e3:.4g} mm"
