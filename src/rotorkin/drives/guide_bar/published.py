"""The numbers of J. Harbin Inst. Tech. 44(9) 2012 per summary key.

Each is the paper's formula as printed (the ``*_eq*`` and ``vane_angle_half_turn``
functions of :mod:`rotorkin.drives.guide_bar.kinematics`), evaluated where the paper
evaluates it; the study derives the same keys from the geometry.
"""

from __future__ import annotations

import numpy as np

from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.studies.published import Published

_D = np.radians

# --- guide bar: JHIT 2012 ---------------------------------------------------------------------
_HALF_TURN = {"drive.phase": np.pi}


def _lu(cfg):
    return cfg["drive"]["lambda"], cfg["drive"]["gear_ratio"]


def _eq7_input_torque(cfg, n=7201):
    """M1 over one turn of the driving members by eq. 7 (crank) or eq. 3-4 + 8 (guide) [N*m]."""
    lam, u = _lu(cfg)
    i12 = cfg["drive"]["input_gear_ratio"]
    m7, m8 = cfg["loads"]["impeller_torque_1"], cfg["loads"]["impeller_torque_2"]
    x1 = np.linspace(0.0, 2.0 * np.pi, n)
    x2 = x1 + cfg["drive"]["phase"]

    if cfg["drive"]["driver"] == "crank":
        return gb.input_torque_eq7(lam, u, i12, m7, m8, x1, x2)
    # eq. 8: the virtual-work balance with the eq. 3 ratio (its own zero of x)
    return (gb.speed_ratio_eq3(lam, u, x1) * m7 + gb.speed_ratio_eq3(lam, u, x2) * m8) / i12


PUBLISHED = (
    Published(
        "vane_angle_crank_driven_deg",
        lambda c: np.degrees(gb.vane_angle_half_turn(*_lu(c), "crank")),
        1e-6,
        "eq. 5",
        "formula",
        _HALF_TURN,
    ),
    Published(
        "vane_angle_guide_driven_deg",
        lambda c: np.degrees(gb.vane_angle_half_turn(*_lu(c), "guide")),
        1e-6,
        "eq. 6",
        "formula",
        _HALF_TURN,
    ),
    Published(
        "impeller_speed_ratio_min",
        lambda c: float(gb.speed_ratio_eq1(*_lu(c), 0.0)),
        1e-9,
        "eq. 1 at x = 0",
        "formula",
        {"drive.driver": "crank"},
    ),
    Published(
        "impeller_speed_ratio_max",
        lambda c: float(gb.speed_ratio_eq1(*_lu(c), np.pi)),
        1e-9,
        "eq. 1 at x = 180 deg",
        "formula",
        {"drive.driver": "crank"},
    ),
    Published(
        "impeller_speed_ratio_min",
        lambda c: float(gb.speed_ratio_eq3(*_lu(c), 0.0)),
        1e-9,
        "eq. 3 at x = 0",
        "formula",
        {"drive.driver": "guide"},
    ),
    Published(
        "impeller_speed_ratio_max",
        lambda c: float(gb.speed_ratio_eq3(*_lu(c), np.pi)),
        1e-9,
        "eq. 3 at x = 180 deg",
        "formula",
        {"drive.driver": "guide"},
    ),
    Published(
        "impeller_speed_ratio_mean",
        lambda c: 1 / _lu(c)[1],
        1e-9,
        "sect. 2 (mean ratio 1/u)",
        "formula",
    ),
    Published(
        "input_torque_min_Nm",
        lambda c: float(np.min(_eq7_input_torque(c))),
        1e-6,
        "eq. 7 (crank) / eq. 8 (guide)",
        "formula",
    ),
    Published(
        "input_torque_max_Nm",
        lambda c: float(np.max(_eq7_input_torque(c))),
        1e-6,
        "eq. 7 (crank) / eq. 8 (guide)",
        "formula",
    ),
)
