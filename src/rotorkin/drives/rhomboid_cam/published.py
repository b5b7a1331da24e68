"""The numbers of Zhuravlev et al. 2012 (Izvestiya TulGU) per summary key."""

from __future__ import annotations

import numpy as np

from rotorkin.studies.published import Published

_D = np.radians

# --- rhomboid cam: Zhuravlev et al. 2012 ------------------------------------------------------
_FIRST = {"drive.a": (), "drive.b": ()}


def _swing(cfg):
    return np.pi - 2.0 * cfg["drive"]["psi_min"]


def _work(cfg):
    """A = Delta M Delta psi (eq. 31, 34) [J]."""
    return (cfg["loads"]["torque_high"] - cfg["loads"]["torque_low"]) * _swing(cfg)


PUBLISHED = (
    Published(
        "psi_max_deg",
        lambda c: 180.0 - np.degrees(c["drive"]["psi_min"]),
        1e-9,
        "eq. 5 (psi_max = pi - psi_min)",
        "formula",
    ),
    Published(
        "psi_lowest_deg",
        lambda c: np.degrees(c["drive"]["psi_min"]),
        1e-6,
        "eq. 5, 16",
        "formula",
        _FIRST,
    ),
    Published(
        "psi_highest_deg",
        lambda c: 180.0 - np.degrees(c["drive"]["psi_min"]),
        1e-6,
        "eq. 5, 16",
        "formula",
        _FIRST,
    ),
    Published(
        "profile_radius_max_mm",
        lambda c: 1e3 * c["drive"]["link_length"] * np.cos(c["drive"]["psi_min"] / 2),
        1e-6,
        "eq. 3 at psi_min",
        "formula",
        _FIRST,
    ),
    Published(
        "profile_radius_min_mm",
        lambda c: 1e3 * c["drive"]["link_length"] * np.sin(c["drive"]["psi_min"] / 2),
        1e-6,
        "eq. 3 at psi_max",
        "formula",
        _FIRST,
    ),
    Published("indicator_work_J", _work, 1e-6, "eq. 31, 34 (A = Delta M Delta psi)", "formula"),
    Published(
        "mean_shaft_torque_Nm", lambda c: _work(c) / np.pi, 1e-6, "A / pi (eq. 26)", "formula"
    ),
    Published(
        "blade_speed_coeff_max", lambda c: 1 + _swing(c) / 2, 1e-6, "eq. 16, 22", "formula", _FIRST
    ),
    Published(
        "blade_speed_coeff_min", lambda c: 1 - _swing(c) / 2, 1e-6, "eq. 16, 22", "formula", _FIRST
    ),
)
