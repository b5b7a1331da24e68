"""Study of the wobble-plate + spherical-cam twin-rotor engine (Chen Hu et al. 2015).

Config keys (SI, defaults filled by :mod:`rotorkin.io.config`):
``drive.plate_tilt``, ``drive.roller_axis_angle``, ``drive.spin_ratio``,
``drive.sphere_radius``, ``machine.compression_ratio``, ``run.points``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.drives import wobble_cam as wc
from rotorkin.errors import ParameterError
from rotorkin.studies import StudyResult
from rotorkin.studies._common import angle_grid, build_params

__all__ = ["evaluate", "HEADLINE"]

#: Summary keys printed by the command line, in order.
HEADLINE = (
    "slider_angle_max_deg",
    "slider_angle_min_deg",
    "chamber_angle_max_deg",
    "chamber_angle_min_deg",
    "chamber_swing_deg",
    "piston_width_deg",
    "volume_cycles_per_rev",
    "power_strokes_per_rev",
    "max_plate_tilt_deg",
)

#: Samples per shaft turn used for the peaks of the rotor derivatives (independent of run.points).
_PEAK_SAMPLES = 20_001


def _deg(x) -> float:
    return float(np.degrees(x))


def _layout(params, eps):
    try:
        return wc.piston_layout(params, eps)
    except ParameterError as exc:
        raise ParameterError("machine.compression_ratio", exc.value, exc.admissible) from None


def _summary(params, layout) -> dict:
    amax, amin = (
        float(v) for v in wc.slider_angle_extremes(params.plate_tilt, params.roller_axis_angle)
    )
    design_min, design_max = (
        (layout.chamber_a_min, layout.chamber_a_max)
        if layout.design_kind == "A"
        else (layout.chamber_b_min, layout.chamber_b_max)
    )
    # peaks of the rotor kinematic coefficients on a fine grid (closed-form values, sampled)
    fine = np.linspace(0.0, wc.period(params), _PEAK_SAMPLES)
    _, _, d2, d3 = wc.rotor_angles(params, fine)
    c, n = np.cos(params.plate_tilt), params.spin_ratio
    # dPhi/dtheta = 1 + n c / D with c^2 <= D <= 1: extremes 1 + n c and 1 + n / c
    ratios = sorted((1.0 + n * c, 1.0 + n / c))
    return {
        "slider_angle_max_deg": _deg(amax),
        "slider_angle_min_deg": _deg(amin),
        "chamber_angle_max_deg": _deg(design_max),
        "chamber_angle_min_deg": _deg(design_min),
        "chamber_swing_deg": _deg(amax - amin),
        "piston_width_deg": _deg(layout.piston_width),
        "volume_cycles_per_rev": wc.volume_cycles_per_rev(params),
        "power_strokes_per_rev": wc.power_strokes_per_rev(params),
        "max_plate_tilt_deg": _deg(wc.max_plate_tilt(params.roller_axis_angle)),
        "piston_offset_gamma_deg": _deg(wc.PISTON_OFFSET),
        "chambers": wc.CHAMBERS,
        "compression_ratio": float(layout.compression_ratio),
        "min_compression_ratio": float(wc.min_compression_ratio(params)),
        "design_chamber_kind": layout.design_kind,
        "chamber_a_angle_min_deg": _deg(layout.chamber_a_min),
        "chamber_a_angle_max_deg": _deg(layout.chamber_a_max),
        "chamber_b_angle_min_deg": _deg(layout.chamber_b_min),
        "chamber_b_angle_max_deg": _deg(layout.chamber_b_max),
        "compression_ratio_a": float(layout.compression_ratio_a),
        "compression_ratio_b": float(layout.compression_ratio_b),
        "volume_cycles_per_rev_all_chambers": wc.CHAMBERS * wc.volume_cycles_per_rev(params),
        "rotor_mean_speed_ratio": float(1.0 + n),
        "rotor_speed_ratio_min": float(ratios[0]),
        "rotor_speed_ratio_max": float(ratios[1]),
        "rotor_accel_peak_per_rad": float(np.max(np.abs(d2))),
        "rotor_jerk_peak_per_rad2": float(np.max(np.abs(d3))),
    }


_DOCS = {
    "theta_deg": "Output-shaft angle theta, positive from +z towards +y about x.",
    "rotor1_angle_deg": "Rotor 1 angle Phi_1 in the yz plane from +z towards +y (rail of group 1).",
    "rotor2_angle_deg": "Rotor 2 angle Phi_2 in the yz plane from +z towards +y (rail of group 2).",
    "rotor1_speed_ratio": "dPhi_1/dtheta, rotor 1 speed over shaft speed.",
    "rotor2_speed_ratio": "dPhi_2/dtheta, rotor 2 speed over shaft speed.",
    "rotor1_accel_per_rad": "d2Phi_1/dtheta2, rotor 1 angular acceleration per shaft speed^2.",
    "rotor2_accel_per_rad": "d2Phi_2/dtheta2, rotor 2 angular acceleration per shaft speed^2.",
    "rotor1_jerk_per_rad2": "d3Phi_1/dtheta3, rotor 1 angular jerk over shaft speed cubed.",
    "rotor2_jerk_per_rad2": "d3Phi_2/dtheta3, rotor 2 angular jerk over shaft speed cubed.",
    "slider_angle_deg": "Slider (rail) angle alpha' = Phi_2 - Phi_1 (eq. 15).",
    "chamber_a_angle_deg": "Chamber kind A angle delta_A = alpha' - 2 gamma - beta (eq. 19).",
    "chamber_b_angle_deg": "Chamber kind B, delta_B = pi/2 + 2 gamma - alpha' - beta (eq. 18).",
    "roller1_x_mm": "Roller 1 (group 1, c = -alpha/2) centre x in the fixed frame (eq. 8).",
    "roller1_y_mm": "Roller 1 centre y in the fixed frame (eq. 8).",
    "roller1_z_mm": "Roller 1 centre z in the fixed frame (eq. 8).",
    "groove1_x_mm": "Groove centre-line point of roller 1, x4 in the cam frame (eq. 11).",
    "groove1_y_mm": "Groove centre-line point of roller 1, y4 in the cam frame (eq. 11).",
    "groove1_z_mm": "Groove centre-line point of roller 1, z4 in the cam frame (eq. 11).",
}


def _columns(params, layout, points) -> dict:
    theta = angle_grid(wc.period(params), points)
    q, d1, d2, d3 = wc.rotor_angles(params, theta)
    slider = q[1] - q[0]
    da, db = wc.chamber_angles(slider, layout.piston_width)
    roller = wc.roller_positions(params, theta)[0] * 1e3
    groove = wc.groove_points(params, theta)[0] * 1e3
    cols = {"theta_deg": np.degrees(theta)}
    for k in (0, 1):
        cols[f"rotor{k + 1}_angle_deg"] = np.degrees(q[k])
    for k in (0, 1):
        cols[f"rotor{k + 1}_speed_ratio"] = d1[k]
    for k in (0, 1):
        cols[f"rotor{k + 1}_accel_per_rad"] = d2[k]
    for k in (0, 1):
        cols[f"rotor{k + 1}_jerk_per_rad2"] = d3[k]
    cols["slider_angle_deg"] = np.degrees(slider)
    cols["chamber_a_angle_deg"] = np.degrees(da)
    cols["chamber_b_angle_deg"] = np.degrees(db)
    for i, ax in enumerate("xyz"):
        cols[f"roller1_{ax}_mm"] = roller[i]
    for i, ax in enumerate("xyz"):
        cols[f"groove1_{ax}_mm"] = groove[i]
    return cols


def evaluate(cfg: dict) -> StudyResult:
    """Run the wobble-cam study on a validated config (SI values).

    Parameters
    ----------
    cfg : dict
        ``cfg["drive"]``: ``plate_tilt`` [rad], ``roller_axis_angle`` [rad],
        ``spin_ratio`` [-], ``sphere_radius`` [m]; ``cfg["machine"]["compression_ratio"]``;
        ``cfg["run"]["points"]``.

    Returns
    -------
    StudyResult
        Summary keys: see :data:`HEADLINE` and the docs page ``docs/drives/wobble_cam.md``.
    """
    d = cfg["drive"]
    params = build_params(
        wc.WobbleCam,
        "drive",
        {
            "plate_tilt": d["plate_tilt"],
            "roller_axis_angle": d["roller_axis_angle"],
            "spin_ratio": d["spin_ratio"],
            "sphere_radius": d["sphere_radius"],
        },
    )
    layout = _layout(params, cfg["machine"]["compression_ratio"])
    summary = _summary(params, layout)
    columns = _columns(params, layout, cfg["run"]["points"])

    def plot(outdir: Path) -> list[Path]:
        from rotorkin.report import figures_wobble_cam

        return figures_wobble_cam.plot_all(params, layout, Path(outdir))

    return StudyResult(
        drive_type="wobble_cam",
        title="Twin-rotor engine, wobble plate + spherical cam",
        summary=summary,
        columns=columns,
        column_docs=dict(_DOCS),
        headline=HEADLINE,
        plot=plot,
    )
