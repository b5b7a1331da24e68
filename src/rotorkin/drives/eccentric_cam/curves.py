"""The drive's per-angle output columns, for one design (study) or many (batch module).

Names and units of ``motion.csv`` (``_mm``: millimetres, ``_deg``: degrees, no suffix:
dimensionless); each column from :mod:`rotorkin.drives.eccentric_cam.kinematics`.
"""

from __future__ import annotations

import numpy as np

from rotorkin.drives.eccentric_cam import kinematics as ec

__all__ = ["drive_curves"]

_ORDERS = (("velocity", "mm_per_rad"), ("accel", "mm_per_rad2"), ("jerk", "mm_per_rad3"))


def drive_curves(params: ec.EccentricCam, beta) -> dict:
    """Travels (eq. 1, 3), gap change (eq. 5), Fig. 6 decomposition (eq. 2, 4, 6), the
    travels' derivatives and the left pressure angle at the shaft angles ``beta`` [rad].

    Parameters
    ----------
    params : EccentricCam
        Floats, or arrays broadcasting against ``beta`` (``(n, 1)`` against ``(m,)``).
    beta : array_like
        Shaft angles [rad].

    Returns
    -------
    dict of str -> ndarray
        ``z_left_mm``, ``z_right_mm``, ``gap_change_mm``, ``x_left``, ``x_right``,
        ``xi``, ``mu``, ``delta``, ``z_{left,right}_{velocity,accel,jerk}_...``
        [mm/rad^n], ``pressure_angle_left_deg``; the broadcast shape of parameters
        and angles.
    """
    q = ec.piston_travels(params, beta)
    dec = ec.decomposition(params, beta)
    cols = {
        "z_left_mm": q[0][0] * 1e3,
        "z_right_mm": q[0][1] * 1e3,
        "gap_change_mm": (q[0][0] + q[0][1]) * 1e3,
        "x_left": dec["x"],
        "x_right": dec["x_right"],
        "xi": dec["xi"],
        "mu": dec["mu"],
        "delta": dec["delta"],
    }
    for k, (name, suffix) in enumerate(_ORDERS, start=1):
        cols[f"z_left_{name}_{suffix}"] = q[k][0] * 1e3
        cols[f"z_right_{name}_{suffix}"] = q[k][1] * 1e3
    cols["pressure_angle_left_deg"] = np.degrees(ec.pressure_angle(params, beta))
    return cols
