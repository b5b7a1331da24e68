"""The numbers of Zhu & Zhu 2012 (Engineering Sciences 14(10)) per summary key."""

from __future__ import annotations

import numpy as np

from rotorkin.studies.published import Published

_D = np.radians

# --- eccentric cam: Zhu & Zhu 2012 ------------------------------------------------------------
_PAPER_DISC = {
    "drive.disc_radius": 0.08,
    "drive.eccentricity": 0.04,
    "drive.follower": "knife_edge",
}
_KNIFE = {"drive.follower": "knife_edge"}


def _eq5_90(cfg):
    """Gap change at beta = 90 deg by eq. 5: 2R (sqrt(1 - lambda^2) - 1) [m]."""
    R, e = cfg["drive"]["disc_radius"], cfg["drive"]["eccentricity"]
    return 2.0 * R * (np.sqrt(1.0 - (e / R) ** 2) - 1.0)


PUBLISHED = (
    Published(
        "gap_change_min_ratio", -0.5359, 5e-5, "sect. 2, eq. 6 at 90 deg", "printed", _PAPER_DISC
    ),
    Published(
        "gap_change_min_ratio",
        lambda c: _eq5_90(c) / c["drive"]["eccentricity"],
        1e-9,
        "eq. 6 at 90 deg",
        "formula",
        _KNIFE,
    ),
    Published("gap_change_min_mm", -21.4, 0.05, "sect. 2", "printed", _PAPER_DISC),
    Published(
        "gap_change_min_mm", lambda c: 1e3 * _eq5_90(c), 1e-9, "eq. 5 at 90 deg", "formula", _KNIFE
    ),
    Published(
        "gap_change_to_length_percent",
        2.14,
        0.005,
        "sect. 2 (OCR: 21.4/2000, read 21.4/1000)",
        "printed",
        {**_PAPER_DISC, "machine.device_length": 1.0},
    ),
    Published(
        "gap_change_min_angle_deg", 90.0, 1e-9, "sect. 2 (largest at 90 deg)", "printed", _KNIFE
    ),
    Published(
        "lambda",
        lambda c: c["drive"]["eccentricity"] / c["drive"]["disc_radius"],
        1e-12,
        "lambda = e/R",
        "formula",
    ),
    Published(
        "gap_change_min_mm",
        0.0,
        1e-9,
        "eq. 7, 8 (flat face: Delta = 0)",
        "formula",
        {"drive.follower": "flat"},
    ),
)
