"""The source papers' values, per summary key, for the "paper vs ours" column of the report.

Two kinds of entry:

* ``printed``: a number the paper prints (or reads off a figure) for its own
  case; it applies only when the config is that case (``conditions``: config
  key -> value, SI, compared with a relative tolerance of 1e-9; an empty tuple
  stands for an empty list such as ``drive.a = []``).
* ``formula``: the paper's own closed-form equation, evaluated here at the
  config's parameters, written independently of the model (e.g. eq. 15 in its
  printed arccos form where the model uses atan2). It applies to every config
  that meets its ``conditions``.

For each summary key the first applicable entry wins. ``tolerance`` is absolute,
in the key's unit: the paper's rounding for printed values ("about 39 deg": 0.5 deg),
a small numerical tolerance for formulas. Sources: ``/work/shared/papers/*.md``
("Published numbers").
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Published", "PAPERS", "PUBLISHED", "applies", "paper_rows"]

#: Short references of the four papers, by drive type.
PAPERS = {
    "wobble_cam": "Chen Hu et al. 2015",
    "eccentric_cam": "Zhu & Zhu 2012",
    "guide_bar": "JHIT 44(9) 2012",
    "rhomboid_cam": "Zhuravlev et al. 2012",
}


@dataclass(frozen=True)
class Published:
    """One published value of a summary key.

    Attributes
    ----------
    key : str
        Summary key (unit as suffix).
    value : float or callable
        The printed number, or ``f(cfg) -> float`` evaluating the paper's formula
        on the config (SI inside, result in the key's unit).
    tolerance : float
        Absolute tolerance, in the key's unit.
    where : str
        Equation, table or figure of the paper.
    kind : str
        ``"printed"`` or ``"formula"``.
    conditions : dict
        Config key (``"drive.plate_tilt"``) -> value (SI) under which it applies.
    note : str
        One short remark (e.g. the paper's wording).
    """

    key: str
    value: float | Callable
    tolerance: float
    where: str
    kind: str = "printed"
    conditions: dict = field(default_factory=dict)
    note: str = ""


def _get(cfg, dotted):
    section, _, key = dotted.partition(".")
    return (cfg.get(section) or {}).get(key)


def applies(entry: Published, cfg: dict) -> bool:
    """Whether the config meets every condition of ``entry``."""
    for dotted, want in entry.conditions.items():
        have = _get(cfg, dotted)
        if isinstance(want, tuple):
            if have is not None and len(have) and np.any(np.asarray(have, float) != 0.0):
                return False
        elif isinstance(want, str):
            if have != want:
                return False
        elif have is None or not np.isclose(float(have), float(want), rtol=1e-9, atol=1e-12):
            return False
    return True


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

_WOBBLE = (
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


_ECCENTRIC = (
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

    def ratio(x):  # impeller speed over driving-member speed, times u
        if cfg["drive"]["driver"] == "crank":  # eq. 1
            return (1 + lam * np.cos(x)) / (1 + 2 * lam * np.cos(x) + lam**2)
        w = np.sqrt(1 - (lam * np.sin(x)) ** 2)  # eq. 3 as printed (its own zero of x)
        c = lam * np.cos(x)
        return np.sqrt(np.maximum(1 - (lam * np.sin(x)) ** 2 + c**2 - 2 * c * w, 0.0)) / w

    return (ratio(x1) * m7 + ratio(x2) * m8) / (u * i12)


_GUIDE = (
    Published(
        "vane_angle_crank_driven_deg",
        lambda c: np.degrees(2 * np.arccos(_lu(c)[0] / np.sqrt(1 + _lu(c)[0] ** 2)) / _lu(c)[1]),
        1e-6,
        "eq. 5",
        "formula",
        _HALF_TURN,
    ),
    Published(
        "vane_angle_guide_driven_deg",
        lambda c: np.degrees(2 * np.arccos(_lu(c)[0]) / _lu(c)[1]),
        1e-6,
        "eq. 6",
        "formula",
        _HALF_TURN,
    ),
    Published(
        "impeller_speed_ratio_min",
        lambda c: 1 / ((1 + _lu(c)[0]) * _lu(c)[1]),
        1e-9,
        "eq. 1 at x = 0",
        "formula",
        {"drive.driver": "crank"},
    ),
    Published(
        "impeller_speed_ratio_max",
        lambda c: 1 / ((1 - _lu(c)[0]) * _lu(c)[1]),
        1e-9,
        "eq. 1 at x = 180 deg",
        "formula",
        {"drive.driver": "crank"},
    ),
    Published(
        "impeller_speed_ratio_min",
        lambda c: (1 - _lu(c)[0]) / _lu(c)[1],
        1e-9,
        "eq. 3 at x = 0",
        "formula",
        {"drive.driver": "guide"},
    ),
    Published(
        "impeller_speed_ratio_max",
        lambda c: (1 + _lu(c)[0]) / _lu(c)[1],
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


# --- rhomboid cam: Zhuravlev et al. 2012 ------------------------------------------------------
_FIRST = {"drive.a": (), "drive.b": ()}


def _swing(cfg):
    return np.pi - 2.0 * cfg["drive"]["psi_min"]


def _work(cfg):
    """A = Delta M Delta psi (eq. 31, 34) [J]."""
    return (cfg["loads"]["torque_high"] - cfg["loads"]["torque_low"]) * _swing(cfg)


_RHOMBOID = (
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

#: Published entries by drive type, in display order.
PUBLISHED = {
    "wobble_cam": _WOBBLE,
    "eccentric_cam": _ECCENTRIC,
    "guide_bar": _GUIDE,
    "rhomboid_cam": _RHOMBOID,
}


def paper_rows(drive_type: str, cfg: dict, summary: dict) -> dict:
    """The paper's value of each summary key that has one, for this config.

    Returns
    -------
    dict
        Summary key -> ``{"paper", "ours", "difference", "tolerance", "within",
        "where", "kind", "note", "reference"}`` (first applicable entry per key,
        in the order of :data:`PUBLISHED`; keys missing from ``summary`` are left out).
    """
    out = {}
    for entry in PUBLISHED.get(drive_type, ()):
        if entry.key in out or entry.key not in summary or not applies(entry, cfg):
            continue
        paper = float(entry.value(cfg) if callable(entry.value) else entry.value)
        ours = summary[entry.key]
        ours_f = float(ours)
        diff = ours_f - paper
        out[entry.key] = {
            "paper": paper,
            "ours": ours,
            "difference": diff,
            "tolerance": float(entry.tolerance),
            "within": bool(abs(diff) <= entry.tolerance + 1e-12 * max(1.0, abs(paper))),
            "where": entry.where,
            "kind": entry.kind,
            "note": entry.note,
            "reference": PAPERS[drive_type],
        }
    return out
