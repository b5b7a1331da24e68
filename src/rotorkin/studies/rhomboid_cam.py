"""Study of the rotary-blade engine with the rhomboid lever-cam converter (Zhuravlev et al. 2012).

Config keys (SI, defaults filled by :mod:`rotorkin.io.config`):
``drive.link_length`` [m], ``drive.psi_min`` [rad], ``drive.a``, ``drive.b``
(higher harmonics a3, a5, ... and b3, b5, ... [rad]), ``loads.torque_high``,
``loads.torque_low`` [N m], ``run.points``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.drives import rhomboid_cam as rc
from rotorkin.studies import StudyResult
from rotorkin.studies._common import angle_grid, build_params

__all__ = ["evaluate", "HEADLINE"]

#: Summary keys printed by the command line, in order.
HEADLINE = (
    "psi_min_deg",
    "psi_max_deg",
    "profile_radius_min_mm",
    "profile_radius_max_mm",
    "indicator_work_J",
    "mean_shaft_torque_Nm",
    "blade_accel_coeff_max",
    "psi_monotone",
)

#: Samples per period used for the peaks of the kinematic coefficients (independent of run.points).
_PEAK_SAMPLES = 20_001


def _deg(x) -> float:
    return float(np.degrees(x))


def _summary(params, m1, m2) -> dict:
    law = (params.psi_min, params.a, params.b)
    L = params.link_length
    a1, b1 = rc.first_harmonic(*law)
    lo, alo, hi, ahi = rc.psi_extremes(*law)
    fine = np.linspace(0.0, rc.period(params), _PEAK_SAMPLES)
    _, d1, d2, d3 = rc.psi_law(fine, *law)
    kappa = rc.profile_curvature(fine, L, *law)
    convex, concave = float(np.max(kappa)), float(-np.min(kappa))
    work = float(rc.indicator_work(*law, m1, m2))
    return {
        "psi_min_deg": _deg(params.psi_min),
        "psi_max_deg": _deg(np.pi - params.psi_min),
        "psi_lowest_deg": _deg(lo),
        "psi_highest_deg": _deg(hi),
        "psi_lowest_at_alpha_deg": _deg(alo),
        "psi_highest_at_alpha_deg": _deg(ahi),
        "psi_monotone": rc.psi_is_monotone(*law),
        "psi_travel_per_period_deg": _deg(rc.psi_total_variation(*law)),
        "a1_rad": float(a1),
        "b1_rad": float(b1) + 0.0,  # no negative zero
        "highest_harmonic": 2 * max(len(params.a), len(params.b)) + 1,
        "link_length_mm": L * 1e3,
        "profile_radius_min_mm": float(L * np.cos(0.5 * hi)) * 1e3,
        "profile_radius_max_mm": float(L * np.cos(0.5 * lo)) * 1e3,
        "profile_convex_radius_min_mm": 1e3 / convex,
        "profile_concave_radius_min_mm": 1e3 / concave if concave > 0.0 else float("inf"),
        "profile_convex": bool(concave <= 0.0),
        "indicator_work_J": work,
        "indicator_work_closed_form_J": float(
            rc.indicator_work_closed_form(params.psi_min, m1, m2)
        ),
        "mean_shaft_torque_Nm": work / np.pi,
        "blade_speed_coeff_max": float(1.0 + 0.5 * np.max(np.abs(d1))),
        "blade_speed_coeff_min": float(1.0 - 0.5 * np.max(np.abs(d1))),
        "blade_accel_coeff_max": float(0.5 * np.max(np.abs(d2))),
        "blade_jerk_coeff_max": float(0.5 * np.max(np.abs(d3))),
        "torque_high_Nm": float(m1),
        "torque_low_Nm": float(m2),
    }


_DOCS = {
    "alpha_deg": "Output-shaft angle alpha: polar angle of diagonal OA, from +x counter-clockwise.",
    "psi_deg": "Angle between the blade axes psi = phi_1 - phi_2 (eq. 13).",
    "dpsi": "dpsi/dalpha (eq. 14).",
    "d2psi_per_rad": "d2psi/dalpha2.",
    "d3psi_per_rad2": "d3psi/dalpha3.",
    "phi1_deg": "Blade pair 1 angle phi_1 = alpha + psi/2 from +x (eq. 21).",
    "phi2_deg": "Blade pair 2 angle phi_2 = alpha - psi/2 from +x (eq. 21).",
    "phi1_speed_coeff": "dphi_1/dalpha = 1 + psi'/2, blade pair 1 speed over shaft speed (eq. 22).",
    "phi2_speed_coeff": "dphi_2/dalpha = 1 - psi'/2, blade pair 2 speed over shaft speed (eq. 22).",
    "phi1_accel_per_rad": "d2phi_1/dalpha2 = psi''/2.",
    "phi2_accel_per_rad": "d2phi_2/dalpha2 = -psi''/2.",
    "phi1_jerk_per_rad2": "d3phi_1/dalpha3 = psi'''/2.",
    "phi2_jerk_per_rad2": "d3phi_2/dalpha3 = -psi'''/2.",
    "rho_mm": "Cam pitch-curve polar radius rho = OA = 2l cos(psi/2) at polar angle alpha (eq. 3).",
    "drho_mm_per_rad": "drho/dalpha.",
    "x_mm": "Pitch-curve point x = rho cos(alpha) (roller A centre).",
    "y_mm": "Pitch-curve point y = rho sin(alpha) (roller A centre).",
    "rho_b_mm": "Half-diagonal OB = 2l sin(psi/2) (eq. 4), = rho at alpha + 90 deg (eq. 10).",
    "curvature_per_m": "Signed curvature of the pitch curve at A (negative where concave).",
    "stroke": "+1 expansion (psi rising, M_p), -1 compression (psi falling, M_c).",
    "blade_torque_Nm": "Torque M_1 on blade pair 1 from the linear model of eq. 29 (M_2 = -M_1).",
    "dA_dalpha_J_per_rad": "Work rate M_1 psi' = torque driving the output shaft (eq. 24).",
}


def _columns(params, m1, m2, points) -> dict:
    law = (params.psi_min, params.a, params.b)
    L = params.link_length
    alpha = angle_grid(rc.period(params), points)
    psi, d1, d2, d3 = rc.psi_law(alpha, *law)
    phi, p1, p2, p3 = rc.blade_angles(alpha, *law)
    rho, drho = rc.profile_radius(alpha, L, *law)[:2]
    xy = rc.profile_point(alpha, L, *law)[0]
    stroke = rc.stroke_direction(alpha, *law)
    torque = rc.blade_torque(psi, stroke, m1, m2, params.psi_min)
    cols = {
        "alpha_deg": np.degrees(alpha),
        "psi_deg": np.degrees(psi),
        "dpsi": d1,
        "d2psi_per_rad": d2,
        "d3psi_per_rad2": d3,
    }
    for k in (0, 1):
        cols[f"phi{k + 1}_deg"] = np.degrees(phi[k])
    for name, arr in (("speed_coeff", p1), ("accel_per_rad", p2), ("jerk_per_rad2", p3)):
        for k in (0, 1):
            cols[f"phi{k + 1}_{name}"] = arr[k]
    cols["rho_mm"] = rho * 1e3
    cols["drho_mm_per_rad"] = drho * 1e3
    cols["x_mm"] = xy[0] * 1e3
    cols["y_mm"] = xy[1] * 1e3
    cols["rho_b_mm"] = L * np.sin(0.5 * psi) * 1e3
    cols["curvature_per_m"] = rc.profile_curvature(alpha, L, *law)
    cols["stroke"] = stroke
    cols["blade_torque_Nm"] = torque
    cols["dA_dalpha_J_per_rad"] = torque * d1
    return cols


def evaluate(cfg: dict) -> StudyResult:
    """Run the rhomboid-cam study on a validated config (SI values).

    Parameters
    ----------
    cfg : dict
        ``cfg["drive"]``: ``link_length`` [m], ``psi_min`` [rad], ``a``, ``b``
        (lists [rad]); ``cfg["loads"]``: ``torque_high``, ``torque_low`` [N m];
        ``cfg["run"]["points"]``.

    Returns
    -------
    StudyResult
        Summary keys: see :data:`HEADLINE` and ``docs/drives/rhomboid_cam.md``.
    """
    d = cfg["drive"]
    params = build_params(
        rc.RhomboidCam,
        "drive",
        {
            "link_length": d["link_length"],
            "psi_min": d["psi_min"],
            "a": tuple(d.get("a", ())),
            "b": tuple(d.get("b", ())),
        },
    )
    loads = cfg.get("loads", {})
    m1 = float(loads.get("torque_high", 0.0))
    m2 = float(loads.get("torque_low", 0.0))
    summary = _summary(params, m1, m2)
    columns = _columns(params, m1, m2, cfg["run"]["points"])

    def plot(outdir: Path) -> list[Path]:
        from rotorkin.report import figures_rhomboid_cam

        return figures_rhomboid_cam.plot_all(params, m1, m2, Path(outdir))

    return StudyResult(
        drive_type="rhomboid_cam",
        title="Rotary-blade engine, rhomboid lever-cam converter",
        summary=summary,
        columns=columns,
        column_docs=dict(_DOCS),
        headline=HEADLINE,
        plot=plot,
    )
