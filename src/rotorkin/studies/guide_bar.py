"""Study of the differential vane pump driven by two rotating guide bars + gears (JHIT 2012).

Config keys (SI, defaults filled by :mod:`rotorkin.io.config`):
``drive.lambda``, ``drive.gear_ratio``, ``drive.input_gear_ratio``,
``drive.phase``, ``drive.driver``, ``loads.impeller_torque_1``,
``loads.impeller_torque_2``, ``run.points``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.drives import guide_bar as gb
from rotorkin.studies import StudyResult
from rotorkin.studies._common import angle_grid, build_params

__all__ = ["evaluate", "HEADLINE"]

#: Summary keys printed by the command line, in order.
HEADLINE = (
    "driver",
    "vane_angle_deg",
    "relative_angle_swing_deg",
    "impeller_speed_ratio_min",
    "impeller_speed_ratio_max",
    "input_torque_min_Nm",
    "input_torque_max_Nm",
    "input_torque_mean_Nm",
)

#: Samples per period used for extremes and peaks (independent of run.points).
_PEAK_SAMPLES = 20_001


def _deg(x) -> float:
    return float(np.degrees(x))


def _summary(params: gb.GuideBar, m7: float, m8: float) -> dict:
    lam, u, i12, phase = (
        float(params.lam),
        float(params.gear_ratio),
        float(params.input_gear_ratio),
        float(params.phase),
    )
    other = "guide" if params.driver == "crank" else "crank"
    rmin, rmax = (float(v) for v in gb.speed_ratio_range(lam, u, params.driver))
    # the two equal-speed points, as driving angles of mechanism 1 in [0, 2 pi), ascending
    t_a, t_b = sorted(float(np.mod(t, 2.0 * np.pi)) for t in gb.equal_speed_angles(phase))
    ratio_a = float(gb.driven_angle(lam, t_a, params.driver)[1]) / u
    ratio_b = float(gb.driven_angle(lam, t_b, params.driver)[1]) / u
    fine = np.linspace(0.0, gb.period(params), _PEAK_SAMPLES)
    _, d1, d2, d3 = gb.impeller_angles(params, fine)
    torque = m7 * d1[0] + m8 * d1[1]
    mean = (m7 + m8) / (u * i12)  # each impeller's speed ratio averages 1/(u i12)
    tmin, tmax = float(np.min(torque)), float(np.max(torque))
    return {
        "driver": params.driver,
        "lambda": lam,
        "gear_ratio": u,
        "input_gear_ratio": i12,
        "phase_deg": _deg(phase),
        "vane_angle_deg": _deg(gb.vane_angle(lam, u, phase, params.driver)),
        "vane_angle_crank_driven_deg": _deg(gb.vane_angle(lam, u, phase, "crank")),
        "vane_angle_guide_driven_deg": _deg(gb.vane_angle(lam, u, phase, "guide")),
        "vane_angle_other_driver_deg": _deg(gb.vane_angle(lam, u, phase, other)),
        "relative_angle_swing_deg": _deg(gb.relative_angle_swing(params)),
        "impeller_speed_ratio_min": rmin,
        "impeller_speed_ratio_max": rmax,
        "impeller_speed_ratio_mean": 1.0 / u,
        "equal_speed_driving_angle_1_deg": _deg(t_a),
        "equal_speed_driving_angle_2_deg": _deg(t_b),
        "equal_speed_input_angle_1_deg": _deg(t_a * i12),
        "equal_speed_input_angle_2_deg": _deg(t_b * i12),
        "equal_speed_ratio_1": ratio_a,
        "equal_speed_ratio_2": ratio_b,
        "input_torque_min_Nm": tmin,
        "input_torque_max_Nm": tmax,
        "input_torque_mean_Nm": mean,
        "input_torque_fluctuation_Nm": tmax - tmin,
        "input_torque_fluctuation_ratio": (tmax - tmin) / abs(mean) if mean != 0.0 else np.nan,
        "impeller_speed_ratio_input_min": rmin / i12,
        "impeller_speed_ratio_input_max": rmax / i12,
        "impeller_accel_peak_per_rad": float(np.max(np.abs(d2))),
        "impeller_jerk_peak_per_rad2": float(np.max(np.abs(d3))),
    }


_DOCS = {
    "theta_deg": "Input gear 1 angle theta; the driving members turn at theta / i12.",
    "driving_angle_1_deg": "Driving angle x_1 = theta / i12 of mechanism 1 (crank or guide bar), "
    "from the line guide pivot -> crank pivot.",
    "driving_angle_2_deg": "Driving angle x_2 = Sigma + theta / i12 of mechanism 2.",
    "impeller1_angle_deg": "Impeller 1 angle q_1 = f(x_1)/u, positive in its mean sense of "
    "turning.",
    "impeller2_angle_deg": "Impeller 2 angle q_2 = f(x_2)/u, positive in its mean sense of "
    "turning.",
    "relative_angle_deg": "Angle between the impellers q_2 - q_1; a chamber angle is this plus a "
    "constant of the vane layout.",
    "impeller1_speed_ratio": "dq_1/dtheta, impeller 1 speed over input gear speed (eq. 1 or 3 "
    "over i12).",
    "impeller2_speed_ratio": "dq_2/dtheta, impeller 2 speed over input gear speed.",
    "impeller1_accel_per_rad": "d2q_1/dtheta2, impeller 1 acceleration over input speed squared.",
    "impeller2_accel_per_rad": "d2q_2/dtheta2, impeller 2 acceleration over input speed squared.",
    "impeller1_jerk_per_rad2": "d3q_1/dtheta3, impeller 1 jerk over input speed cubed.",
    "impeller2_jerk_per_rad2": "d3q_2/dtheta3, impeller 2 jerk over input speed cubed.",
    "input_torque_Nm": "Torque M1 on input gear 1 by virtual work, M7 dq_1/dtheta + "
    "M8 dq_2/dtheta (eq. 7, 8).",
}


def _columns(params: gb.GuideBar, m7: float, m8: float, points: int) -> dict:
    theta = angle_grid(gb.period(params), points)
    x = gb.driving_angles(params, theta)
    q, d1, d2, d3 = gb.impeller_angles(params, theta)
    cols = {"theta_deg": np.degrees(theta)}
    for k in (0, 1):
        cols[f"driving_angle_{k + 1}_deg"] = np.degrees(x[k])
    for k in (0, 1):
        cols[f"impeller{k + 1}_angle_deg"] = np.degrees(q[k])
    cols["relative_angle_deg"] = np.degrees(q[1] - q[0])
    for name, arr in (("speed_ratio", d1), ("accel_per_rad", d2), ("jerk_per_rad2", d3)):
        for k in (0, 1):
            cols[f"impeller{k + 1}_{name}"] = arr[k]
    cols["input_torque_Nm"] = m7 * d1[0] + m8 * d1[1]
    return cols


def evaluate(cfg: dict) -> StudyResult:
    """Run the guide-bar pump study on a validated config (SI values).

    Parameters
    ----------
    cfg : dict
        ``cfg["drive"]``: ``lambda``, ``gear_ratio``, ``input_gear_ratio``,
        ``phase`` [rad], ``driver``; ``cfg["loads"]``: ``impeller_torque_1``,
        ``impeller_torque_2`` [N*m]; ``cfg["run"]["points"]``.

    Returns
    -------
    StudyResult
        Summary keys: see :data:`HEADLINE` and ``docs/drives/guide_bar.md``.
    """
    d = cfg["drive"]
    params = build_params(
        gb.GuideBar,
        "drive",
        {
            "lam": d["lambda"],
            "gear_ratio": d["gear_ratio"],
            "input_gear_ratio": d.get("input_gear_ratio", 1.0),
            "phase": d.get("phase", np.pi),
            "driver": d.get("driver", "crank"),
        },
        aliases={"lam": "lambda"},
    )
    loads = cfg.get("loads", {})
    m7 = float(loads.get("impeller_torque_1", 0.0))
    m8 = float(loads.get("impeller_torque_2", 0.0))
    summary = _summary(params, m7, m8)
    columns = _columns(params, m7, m8, cfg["run"]["points"])

    def plot(outdir: Path) -> list[Path]:
        from rotorkin.report import figures_guide_bar

        return figures_guide_bar.plot_all(params, m7, m8, Path(outdir))

    return StudyResult(
        drive_type="guide_bar",
        title="Differential vane pump, rotating guide-bar + gear drive",
        summary=summary,
        columns=columns,
        column_docs=dict(_DOCS),
        headline=HEADLINE,
        plot=plot,
    )
