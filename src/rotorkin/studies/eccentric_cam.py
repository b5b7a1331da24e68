"""Study of the opposed-piston reactor driven by double eccentric discs (Zhu & Zhu 2012).

Config keys (SI, defaults filled by :mod:`rotorkin.io.config`):
``drive.disc_radius``, ``drive.eccentricity``, ``drive.follower``,
``drive.roller_radius``, ``machine.device_length``, ``run.points``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin._angles import fmt_mm
from rotorkin.drives import eccentric_cam as ec
from rotorkin.errors import ParameterError
from rotorkin.studies import StudyResult
from rotorkin.studies._common import angle_grid, build_params

__all__ = ["evaluate", "HEADLINE"]

#: Summary keys printed by the command line, in order.
HEADLINE = (
    "follower",
    "lambda",
    "gap_change_min_mm",
    "gap_change_min_ratio",
    "gap_change_to_length_percent",
    "piston_stroke_mm",
    "pressure_angle_max_deg",
)

#: Samples per shaft turn used for the peaks of the piston derivatives (independent of run.points).
_PEAK_SAMPLES = 20_001


def _summary(params: ec.EccentricCam, device_length: float) -> dict:
    e = float(params.eccentricity)
    dmin, bmin = ec.gap_change_extreme(params)
    knife = ec.EccentricCam(params.disc_radius, e, "knife_edge")
    fine = np.linspace(0.0, ec.period(params), _PEAK_SAMPLES)
    _, d1, d2, d3 = ec.piston_travels(params, fine)
    rc = params.contact_radius
    return {
        "follower": params.follower,
        "lambda": params.lam,
        "lambda_contact": e / rc,
        "gap_change_min_mm": dmin * 1e3,
        "gap_change_min_ratio": dmin / e,
        "gap_change_min_angle_deg": float(np.degrees(bmin)),
        "gap_change_to_length": abs(dmin) / device_length,
        "gap_change_to_length_percent": 100.0 * abs(dmin) / device_length,
        "gap_change_min_knife_edge_mm": ec.gap_change_extreme(knife)[0] * 1e3,
        "piston_stroke_mm": ec.piston_stroke(params) * 1e3,
        "piston_velocity_peak_mm_per_rad": float(np.max(np.abs(d1))) * 1e3,
        "piston_accel_peak_mm_per_rad2": float(np.max(np.abs(d2))) * 1e3,
        "piston_jerk_peak_mm_per_rad3": float(np.max(np.abs(d3))) * 1e3,
        "pressure_angle_max_deg": float(np.degrees(ec.pressure_angle_max(params))),
        "device_length_mm": device_length * 1e3,
    }


_DOCS = {
    "beta_deg": "Shaft angle beta; 0 puts the left piston at its top (+e), the right at its "
    "bottom.",
    "z_left_mm": "Left piston travel z from mid position, positive towards the reactor centre "
    "(eq. 1).",
    "z_right_mm": "Right piston travel z' from mid position, positive towards the reactor centre "
    "(eq. 3).",
    "gap_change_mm": "Gap change Delta = z + z' (eq. 5); negative: the inner faces stand apart.",
    "x_left": "Dimensionless left travel x = z/e = xi + mu (eq. 2).",
    "x_right": "Dimensionless right travel x' = z'/e = mu - xi (eq. 4).",
    "xi": "Harmonic part xi = cos beta of x (Fig. 6).",
    "mu": "Additional part mu of x, the same for both pistons (Fig. 6).",
    "delta": "Dimensionless gap change delta = Delta/e = x + x' (eq. 6).",
    "z_left_velocity_mm_per_rad": "dz/dbeta, left piston velocity over shaft speed.",
    "z_right_velocity_mm_per_rad": "dz'/dbeta, right piston velocity over shaft speed.",
    "z_left_accel_mm_per_rad2": "d2z/dbeta2, left piston acceleration over shaft speed squared.",
    "z_right_accel_mm_per_rad2": "d2z'/dbeta2, right piston acceleration over shaft speed squared.",
    "z_left_jerk_mm_per_rad3": "d3z/dbeta3, left piston jerk over shaft speed cubed.",
    "z_right_jerk_mm_per_rad3": "d3z'/dbeta3, right piston jerk over shaft speed cubed.",
    "pressure_angle_left_deg": "Angle between the left contact normal and the piston axis "
    "(0 for a flat face).",
}


def _columns(params: ec.EccentricCam, points: int) -> dict:
    beta = angle_grid(ec.period(params), points)
    q, d1, d2, d3 = ec.piston_travels(params, beta)
    dec = ec.decomposition(params, beta)
    cols = {
        "beta_deg": np.degrees(beta),
        "z_left_mm": q[0] * 1e3,
        "z_right_mm": q[1] * 1e3,
        "gap_change_mm": (q[0] + q[1]) * 1e3,
        "x_left": dec["x"],
        "x_right": dec["x_right"],
        "xi": dec["xi"],
        "mu": dec["mu"],
        "delta": dec["delta"],
    }
    for name, arr in (("velocity", d1), ("accel", d2), ("jerk", d3)):
        suffix = {"velocity": "mm_per_rad", "accel": "mm_per_rad2", "jerk": "mm_per_rad3"}[name]
        cols[f"z_left_{name}_{suffix}"] = arr[0] * 1e3
        cols[f"z_right_{name}_{suffix}"] = arr[1] * 1e3
    cols["pressure_angle_left_deg"] = np.degrees(ec.pressure_angle(params, beta))
    return cols


def evaluate(cfg: dict) -> StudyResult:
    """Run the eccentric-cam study on a validated config (SI values).

    Parameters
    ----------
    cfg : dict
        ``cfg["drive"]``: ``disc_radius`` [m], ``eccentricity`` [m], ``follower``,
        ``roller_radius`` [m]; ``cfg["machine"]["device_length"]`` [m];
        ``cfg["run"]["points"]``.

    Returns
    -------
    StudyResult
        Summary keys: see :data:`HEADLINE` and ``docs/drives/eccentric_cam.md``.
    """
    d = cfg["drive"]
    params = build_params(
        ec.EccentricCam,
        "drive",
        {
            "disc_radius": d["disc_radius"],
            "eccentricity": d["eccentricity"],
            "follower": d.get("follower", "knife_edge"),
            "roller_radius": d.get("roller_radius", 0.0),
        },
    )
    length = float(cfg["machine"]["device_length"])
    if not (np.isfinite(length) and length > 0.0):
        raise ParameterError("machine.device_length", fmt_mm(length), "device_length > 0 mm")
    summary = _summary(params, length)
    columns = _columns(params, cfg["run"]["points"])

    def plot(outdir: Path) -> list[Path]:
        from rotorkin.report import figures_eccentric_cam

        return figures_eccentric_cam.plot_all(params, Path(outdir))

    return StudyResult(
        drive_type="eccentric_cam",
        title="Opposed-piston reactor, double eccentric cams",
        summary=summary,
        columns=columns,
        column_docs=dict(_DOCS),
        headline=HEADLINE,
        plot=plot,
    )
