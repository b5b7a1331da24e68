"""The report of a drive that brings no scene of its own: its two members, from its motion.

A drive's spec may leave ``scene`` empty; the report then shows the two working
members as arms turning about the machine axis (or, for members that slide, as
two blocks on a line), their angles and kinematic coefficients over one period,
and no drive-specific checks. It reads :attr:`StudyResult.motion` only, so any
drive registered with a study gets a working report.
"""

from __future__ import annotations

import numpy as np

from rotorkin.render.scenes import (
    COLOR_1,
    COLOR_2,
    GREY,
    Check,
    Plot,
    SceneBuilder,
    circle,
    contact_checks,
    force_plot,
    frame_angles,
    lines_plot,
    trace,
    xy_figure,
)

__all__ = ["scene", "plots", "checks"]


def _sample(motion, angles):
    """Member positions at the frame angles (periodic interpolation of the study's grid)."""
    theta = np.asarray(motion.theta, dtype=float).ravel()
    q = np.asarray(motion.q, dtype=float).reshape(2, -1)
    return np.stack([np.interp(angles, theta, q[k]) for k in (0, 1)])


def scene(result, cfg, frames: int = 120):
    """Both members over one period: arms at the member angles (or blocks at the travels)."""
    motion = result.motion
    theta = np.asarray(motion.theta, dtype=float).ravel()
    angles = frame_angles(float(theta[-1] - theta[0]), frames) + float(theta[0])
    q = _sample(motion, angles)
    b = SceneBuilder(angles)
    if motion.unit == "rad":
        ring = circle(0.0, 0.0, 1.0, 96)
        b.static(trace("line", "casing", GREY, 1.0, x=ring[0], y=ring[1], legend=False))
        for k, color in ((0, COLOR_1), (1, COLOR_2)):
            x = np.stack([np.zeros_like(q[k]), np.cos(q[k])], axis=1)
            y = np.stack([np.zeros_like(q[k]), np.sin(q[k])], axis=1)
            b.animated_trace(trace("line", motion.members[k], color, 5.0), x=x, y=y)
        lim = [-1.15, 1.15]
        layout = {
            "height": 420,
            "xaxis": {"range": lim, "scaleanchor": "y", "visible": False},
            "yaxis": {"range": lim, "visible": False},
            "margin": {"l": 10, "r": 10, "t": 10, "b": 10},
            "plot_bgcolor": "white",
        }
        what = "angle"
        readouts = [(f"{motion.members[k]} angle", "deg", np.degrees(q[k])) for k in (0, 1)]
    else:
        span = float(np.max(np.abs(q))) or 1.0
        for k, color in ((0, COLOR_1), (1, COLOR_2)):
            x = np.stack([q[k] - 0.05 * span, q[k] + 0.05 * span], axis=1) * 1e3
            b.animated_trace(trace("line", motion.members[k], color, 14.0), x=x, y=[0.0, 0.0])
        lim = [-1.2e3 * span, 1.2e3 * span]
        layout = {
            "height": 220,
            "xaxis": {"range": lim, "title": {"text": "travel [mm]"}},
            "yaxis": {"visible": False},
            "plot_bgcolor": "white",
        }
        what = "travel"
        readouts = [(f"{motion.members[k]} travel", "mm", 1e3 * q[k]) for k in (0, 1)]
    return b.build(
        layout,
        "input angle",
        readouts,
        caption=f"The two members at their {what}s over one period, from the drive's motion.",
    )


def plots(result, cfg) -> list:
    """Member positions and their first three kinematic coefficients over one period."""
    m = result.motion
    x = np.degrees(np.asarray(m.theta, dtype=float).ravel())
    scale, unit = (np.degrees, "deg") if m.unit == "rad" else ((lambda v: 1e3 * v), "mm")
    rows = [
        (f"position [{unit}]", [(m.members[k], scale(m.q[k])) for k in (0, 1)]),
        (f"d/dtheta [{unit}/rad]", [(m.members[k], scale(m.dq[k])) for k in (0, 1)]),
        (f"d2/dtheta2 [{unit}/rad^2]", [(m.members[k], scale(m.d2q[k])) for k in (0, 1)]),
        (f"d3/dtheta3 [{unit}/rad^3]", [(m.members[k], scale(m.d3q[k])) for k in (0, 1)]),
    ]
    out = [
        lines_plot(
            "plot-members",
            "Members",
            x,
            "input angle theta [deg]",
            rows,
            "Both members over one period",
            period=float(x[-1] - x[0]),
        )
    ]
    out += _machine_plots(result.columns)
    cols = result.columns
    if "theta_deg" in cols:
        x = np.asarray(cols["theta_deg"], dtype=float)
        forces = force_plot(cols, x, "shaft angle theta [deg]", "Forces of the drive's pairs",
                            float(x[-1] - x[0]))  # fmt: skip
        if forces is not None:
            out.append(forces)
    return out


def _machine_plots(cols: dict) -> list:
    """Chambers and shaft torque of a vane machine's columns (:mod:`rotorkin.vane`), if any."""
    if "theta_deg" not in cols:
        return []
    x = np.asarray(cols["theta_deg"], dtype=float)
    out = []
    kinds = [k for k in ("a", "b") if f"chamber_{k}_volume_cm3" in cols]
    if kinds:
        rows = [("volume [cm^3]", [(f"chamber kind {k.upper()}", cols[f"chamber_{k}_volume_cm3"])
                                   for k in kinds])]  # fmt: skip
        if all(f"chamber_{k}_pressure_bar" in cols for k in kinds):
            pressure = [(f"chamber kind {k.upper()}", cols[f"chamber_{k}_pressure_bar"])
                        for k in kinds]  # fmt: skip
            rows.append(("pressure [bar]", pressure))
        out.append(lines_plot("plot-chambers", "Chambers", x, "shaft angle theta [deg]", rows,
                              "Volume and pressure of the two kinds of chamber",
                              period=float(x[-1] - x[0])))  # fmt: skip
    if kinds and all(f"chamber_{k}_pressure_bar" in cols for k in kinds):
        pv = [(f"chamber kind {k.upper()}", cols[f"chamber_{k}_volume_cm3"],
               cols[f"chamber_{k}_pressure_bar"], None) for k in kinds]  # fmt: skip
        out.append(Plot("plot-pv", "p-V diagram",
                        xy_figure(pv, "volume [cm^3]", "pressure [bar]",
                                  "p-V diagram of the chambers", height=440)))  # fmt: skip
    if "shaft_torque_Nm" in cols:
        series = [("machine", cols["shaft_torque_Nm"])]
        if "shaft_torque_with_inertia_Nm" in cols:
            series.append(("with inertia", cols["shaft_torque_with_inertia_Nm"]))
        out.append(lines_plot("plot-torque", "Shaft torque", x, "shaft angle theta [deg]",
                              [("torque [N*m]", series)],
                              "Torque of the machine on the shaft, + drives it",
                              period=float(x[-1] - x[0])))  # fmt: skip
    return out


def checks(result, cfg) -> list:
    """Contact stress and efficiency where the drive has pairs; no drive-specific checks."""
    return contact_checks(result.summary, cfg) + [
        Check(
            "note",
            "No drive-specific checks",
            f"The drive {result.drive_type!r} brings no report scene of its own; shown are its "
            "members' motion and the summary.",
        )
    ]
