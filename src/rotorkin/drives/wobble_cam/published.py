"""The numbers of Chen Hu et al. 2015 (J. NUDT 37(5)) per summary key."""

from __future__ import annotations

import numpy as np

from rotorkin.studies.published import Published

_D = np.radians


# --- wobble cam: Chen Hu et al. 2015 ----------------------------------------------------------
def _eq15(cfg, varphi):
    """Slider angle alpha' by eq. 15 as printed (arccos form) [rad]."""
    phi, a = cfg["drive"]["plate_tilt"], cfg["drive"]["roller_axis_angle"]
    m, p = varphi - a / 2.0, varphi + a / 2.0
    c2 = np.cos(phi) ** 2
    num = np.sin(m) * np.sin(p) + c2 * np.cos(m) * np.cos(p)
    den = np.sqrt((np.sin(m) ** 2 + c2 * np.cos(m) ** 2) * (np.sin(p) ** 2 + c2 * np.cos(p) ** 2))
    return float(np.arccos(np.clip(num / den, -1.0, 1.0)))


def _eq21_beta(cfg):
    """Piston width by eq. 21 (N = 4, alpha = 90 deg): (e+1)/(e-1) a'_min - pi (e+3)/(4(e-1))."""
    eps = cfg["machine"]["compression_ratio"]
    return (eps + 1) / (eps - 1) * _eq15(cfg, np.pi / 2) - np.pi * (eps + 3) / (4 * (eps - 1))


_TABLE1 = {
    "drive.plate_tilt": _D(45.0),
    "drive.roller_axis_angle": _D(90.0),
    "drive.spin_ratio": -2.0,
    "drive.spin_a": (),
    "drive.spin_b": (),
    "machine.pistons_per_rotor": 4,
}
_PAPER_LAW = {"drive.spin_ratio": -2.0, "drive.spin_a": (), "drive.spin_b": ()}
_N4_A90 = {"drive.roller_axis_angle": _D(90.0), "machine.pistons_per_rotor": 4}

PUBLISHED = (
    Published(
        "slider_angle_max_deg",
        lambda c: np.degrees(_eq15(c, 0.0)),
        1e-6,
        "eq. 15 at varphi = 0 (eq. 17)",
        "formula",
    ),
    Published(
        "slider_angle_min_deg",
        lambda c: np.degrees(_eq15(c, np.pi / 2)),
        1e-6,
        "eq. 15 at varphi = 90 deg (eq. 17)",
        "formula",
    ),
    Published(
        "chamber_swing_deg", 39.0, 0.5, "Fig. 10, Table 1", "printed", _TABLE1, "about 39 deg"
    ),
    Published(
        "chamber_swing_deg",
        lambda c: np.degrees(_eq15(c, 0.0) - _eq15(c, np.pi / 2)),
        1e-6,
        "eq. 15 (max - min)",
        "formula",
    ),
    Published(
        "piston_width_deg", lambda c: np.degrees(_eq21_beta(c)), 1e-6, "eq. 21", "formula", _N4_A90
    ),
    Published(
        "chamber_angle_min_deg",
        lambda c: np.degrees(_eq15(c, np.pi / 2) - np.pi / 4 - _eq21_beta(c)),
        1e-6,
        "eq. 19, 21",
        "formula",
        _N4_A90,
    ),
    Published(
        "chamber_angle_max_deg",
        lambda c: np.degrees(_eq15(c, 0.0) - np.pi / 4 - _eq21_beta(c)),
        1e-6,
        "eq. 19, 21",
        "formula",
        _N4_A90,
    ),
    Published("max_plate_tilt_deg", 65.0, 1.0, "Fig. 13", "printed", _N4_A90, "about 65 deg"),
    Published("volume_cycles_per_rev", 4, 0, "sect. 1.2, 4.2.3", "printed", _PAPER_LAW),
    Published(
        "volume_cycles_per_rev_all_chambers",
        32,
        0,
        "sect. 1.2",
        "printed",
        {**_PAPER_LAW, "machine.pistons_per_rotor": 4},
    ),
    Published(
        "power_strokes_per_rev",
        16,
        0,
        "sect. 1.2",
        "printed",
        {**_PAPER_LAW, "machine.pistons_per_rotor": 4},
    ),
    Published("chambers", 8, 0, "sect. 1", "printed", {"machine.pistons_per_rotor": 4}),
    Published(
        "rotor_mean_speed_ratio",
        -1.0,
        1e-12,
        "sect. 1 (rotors turn at the shaft speed, opposite)",
        "printed",
        _PAPER_LAW,
    ),
)
