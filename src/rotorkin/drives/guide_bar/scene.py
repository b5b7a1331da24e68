"""HTML report of the differential vane pump on the rotating guide-bar + gear drive.

The scene shows one period of the input gear (``2 pi i12``: each guide-bar
mechanism turns once) in three views, from the model's coordinates:

* mechanism 1 and mechanism 2, in units of the crank length ``a`` (the paper gives
  no size): guide pivot C at the origin, crank pivot A at ``(lambda, 0)``, the crank
  at the crank angle and the guide bar at the guide angle, one of them the driving
  angle ``x_k = sigma_k + theta/i12`` (:func:`rotorkin.drives.guide_bar.kinematics.driving_angles`)
  and the other from :func:`~rotorkin.drives.guide_bar.kinematics.driven_angle`; the slider
  block sits at the crank pin ``(lambda + cos x, sin x)``, which lies on the guide bar;
* the pump section: the vanes of both impellers
  (:func:`rotorkin.machines.vane_pump.vane_angles`) and the chambers between
  them (:func:`~rotorkin.machines.vane_pump.chamber_angles`), coloured by the port
  they are open to (shrinking: discharge, growing: suction).
"""

from __future__ import annotations

import numpy as np

from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar.study import drive_params, pump_params
from rotorkin.machines import vane_pump as vp
from rotorkin.render.scenes import (
    COLOR_1,
    COLOR_2,
    GREY,
    Check,
    Plot,
    SceneBuilder,
    circle,
    contact_checks,
    flywheel_checks,
    fmt,
    force_plot,
    frame_angles,
    join,
    lines_plot,
    mean_trace,
    panels,
    sector,
    select,
    svaj_plot,
    torque_plot,
    trace,
    xy_figure,
)

__all__ = ["scene", "plots", "checks", "mechanism_points"]

_DISCHARGE, _SUCTION, _REST = "#f4a6a6", "#a6c8e8", "#dddddd"


def _models(cfg):
    params = drive_params(cfg)
    return params, pump_params(cfg, params)


def mechanism_points(params, theta):
    """Crank and guide angles and the crank pin of both mechanisms (units of ``a``).

    Returns
    -------
    (crank, guide, pin) : ndarray, shapes (2, F), (2, F), (2, 2, F)
        Crank angle and guide-bar angle [rad] from the line C -> A; crank pin
        ``(lambda + cos(crank), sin(crank))`` per mechanism.
    """
    x = gb.driving_angles(params, theta)
    f = gb.driven_angle(params.lam, params.driver, x)[0]
    crank, guide = (x, f) if params.driver == "crank" else (f, x)
    pin = np.stack([params.lam + np.cos(crank), np.sin(crank)], axis=1)
    return crank, guide, pin


def scene(result, cfg, frames: int = 120):
    """Both guide-bar mechanisms and the pump section over one period of the input gear."""
    params, pump = _models(cfg)
    theta = frame_angles(gb.period(params), frames)
    nf = len(theta)
    b = SceneBuilder(theta, decimals=4)  # the mechanisms are drawn in units of a
    lam = float(params.lam)
    crank, guide, pin = mechanism_points(params, theta)
    driven = "guide bar" if params.driver == "crank" else "crank"
    corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [-1, -1]]) * np.array([0.12, 0.07])
    for k in (0, 1):
        on, legend = ("", "2")[k], k == 0
        b.static(
            trace(
                "line",
                "frame C-A and pivots",
                GREY,
                3,
                on=on,
                legend=legend,
                legendgroup="frame",
                mode="lines+markers",
                x=[0.0, lam],
                y=[0.0, 0.0],
                marker={"symbol": "triangle-up", "size": 12, "color": GREY},
            )
        )
        ends = np.array([-0.35, 1.0 + lam + 0.25])
        b.animated_trace(
            trace(
                "line",
                "guide bar (turns about C)",
                "#404040",
                6,
                on=on,
                legend=legend,
                legendgroup="guide",
            ),
            x=np.cos(guide[k])[:, None] * ends,
            y=np.sin(guide[k])[:, None] * ends,
        )
        b.animated_trace(
            trace(
                "line",
                f"crank of mechanism {k + 1} (turns about A)",
                (COLOR_1, COLOR_2)[k],
                5,
                on=on,
                mode="lines+markers",
                marker={"size": [6, 9]},
            ),
            x=np.stack([np.full(nf, lam), pin[k, 0]], axis=1),
            y=np.stack([np.zeros(nf), pin[k, 1]], axis=1),
        )
        c, s = np.cos(guide[k])[:, None], np.sin(guide[k])[:, None]  # block along the guide
        b.animated_trace(
            trace(
                "fill",
                "slider block on the crank pin",
                "#ffd27f",
                on=on,
                legend=legend,
                legendgroup="block",
                edge="black",
            ),
            x=pin[k, 0][:, None] + c * corners[:, 0] - s * corners[:, 1],
            y=pin[k, 1][:, None] + s * corners[:, 0] + c * corners[:, 1],
        )
    # the pump section (axes x3, y3)
    rh, rc = pump.hub_radius * 1e3, pump.casing_radius * 1e3
    g, z = float(pump.vane_angle), int(pump.vanes_per_impeller)
    motion = gb.motion(params, theta)
    vanes = vp.vane_angles(pump, motion)  # (2, Z, F)
    phi, dphi = vp.chamber_angles(pump, motion)[:2]  # (2Z, F)
    start = np.stack([vanes[j % 2, j // 2] + 0.5 * g for j in range(2 * z)])  # (2Z, F)
    polys = [sector(rh, rc, start[j], start[j] + phi[j], 14) for j in range(2 * z)]
    rest = np.abs(dphi) < 1e-9
    for name, mask, color in (
        ("chamber shrinking: discharge", (dphi < 0) & ~rest, _DISCHARGE),
        ("chamber growing: suction", (dphi > 0) & ~rest, _SUCTION),
        ("chamber at rest: port switch-over", rest, _REST),
    ):
        b.animated_trace(
            trace("fill", name, color, on="3", edge_width=0.5),
            x=select([p[0] for p in polys], mask),
            y=select([p[1] for p in polys], mask),
        )
    for k, color in ((0, COLOR_1), (1, COLOR_2)):
        vs = [sector(rh, rc, vanes[k, m] - 0.5 * g, vanes[k, m] + 0.5 * g, 10) for m in range(z)]
        b.animated_trace(
            trace("fill", f"vanes of impeller {k + 1}", color, on="3", edge="black"),
            x=join(*[p[0] for p in vs]),
            y=join(*[p[1] for p in vs]),
        )
    for name, rad, fill in (("casing", rc, "rgba(0,0,0,0)"), ("hub", rh, "#e0e0e0")):
        cx, cy = circle(np.zeros(1), np.zeros(1), rad, 96)
        b.static(
            trace(
                "fill",
                name,
                fill,
                on="3",
                legend=False,
                edge="#404040",
                edge_width=2,
                x=cx[0],
                y=cy[0],
            )
        )
    vol = phi * pump.volume_per_angle * 1e6
    mid, rm = start + 0.5 * phi, 0.5 * (rh + rc)
    b.animated_trace(
        trace("text", "chamber volumes", "#202020", 11, on="3"),
        x=(rm * np.cos(mid)).T,
        y=(rm * np.sin(mid)).T,
        text=[
            [
                f"{'AB'[j % 2]}{j // 2 + 1}<br>{vol[j, f]:.0f} cm3"
                if phi[j, f] > np.radians(12)
                else ""
                for j in range(2 * z)
            ]
            for f in range(nf)
        ],
    )
    lim, lim3 = [-(1.35 + lam), 1.35 + lam], [-1.1 * rc, 1.1 * rc]
    layout = panels(
        540,
        [
            ("", [0.0, 0.3], lim, lim, "x / a", "y / a"),
            ("2", [0.34, 0.64], lim, lim, "x / a", ""),
            ("3", [0.69, 1.0], lim3, lim3, "x [mm]", ""),
        ],
        [
            (0.0, f"<b>Mechanism 1</b> (sigma_1 = 0; the {params.driver} drives the {driven})"),
            (0.34, f"<b>Mechanism 2</b> (sigma_2 = {fmt(np.degrees(params.phase))} deg)"),
            (0.69, "<b>Pump section</b> (both impellers turn counter-clockwise)"),
        ],
    )
    q = gb.impeller_angles(params, theta)[0]
    readouts = [
        ("driving angle x_1", "deg", np.degrees(gb.driving_angles(params, theta)[0])),
        ("impeller 1", "deg", np.degrees(q[0])),
        ("impeller 2", "deg", np.degrees(q[1])),
        ("relative angle", "deg", np.degrees(q[1] - q[0])),
        ("chamber A1 volume", "cm3", vol[0]),
    ]
    caption = (
        "Drawn from the model: guide_bar.driving_angles / driven_angle (the mechanisms, in units "
        "of the crank length a: the paper gives no size) and vane_pump.vane_angles / "
        f"chamber_angles (the section). Impeller k turns by the {driven} angle / u (u = "
        f"{fmt(params.gear_ratio)}); the input gear turns i12 = {fmt(params.input_gear_ratio)} "
        "times per turn of the mechanisms."
    )
    return b.build(layout, "theta, input gear angle", readouts, caption)


def plots(result, cfg) -> list[Plot]:
    """SVAJ of the impellers, speed ratios, chambers and flow, torque, p-V, forces."""
    cols, s = result.columns, result.summary
    params = _models(cfg)[0]
    th, x_lab = cols["theta_deg"], "input gear angle theta [deg]"
    per = float(np.degrees(gb.period(params)))
    rpm = fmt(s.get("shaft_speed_mean_rpm", float("nan")))
    members = [
        (f"impeller {k}", c, f"impeller{k}_angle_deg", f"impeller{k}")
        for k, c in ((1, COLOR_1), (2, COLOR_2))
    ]
    ratios = [(f"impeller {k}", cols[f"impeller{k}_speed_ratio"]) for k in (1, 2)]
    chambers = [
        ("relative angle [deg]", [("q_2 - q_1", cols["relative_angle_deg"])]),
        (
            "volume [cm^3]",
            [(f"chamber {k.upper()}", cols[f"chamber_{k}_volume_cm3"]) for k in "ab"],
        ),
        ("flow [l/min]", [("delivered flow (ideal ports)", cols["flow_l_per_min"])]),
    ]
    # one sign convention on the whole plot: the torque the motor must supply at input gear
    # 1, positive (the paper's eq. 7/8 sense; the study's shaft_torque_* columns are
    # positive when the machine drives the shaft, so a pump's are negated here)
    ld = cfg.get("loads", {})
    m7, m8 = (ld.get(f"impeller_torque_{k}", np.nan) for k in (1, 2))
    ps, pd = (ld.get(f"{k}_pressure", np.nan) / 1e5 for k in ("suction", "discharge"))
    loads = [
        (
            "paper eq. 7/8 [N*m]",
            [
                (
                    f"paper eq. 7/8: constant impeller loads M7 = {fmt(m7)}, M8 = {fmt(m8)} N*m",
                    cols["input_torque_Nm"],
                ),
                mean_trace(th, s.get("input_torque_mean_Nm", np.nan), "eq. 7/8 mean"),
            ],
        ),
        (
            "ideal ports [N*m]",
            [
                (
                    f"ideal ports: chamber pressures, suction {fmt(ps)} / discharge {fmt(pd)} bar",
                    -np.asarray(cols["shaft_torque_Nm"]),
                ),
                mean_trace(th, -s.get("mean_torque_Nm", np.nan), "ideal-ports mean"),
            ],
        ),
    ]
    pv = [("chamber A", cols["chamber_a_volume_cm3"], cols["chamber_a_pressure_bar"], None)]
    return [
        svaj_plot(
            cols,
            th,
            x_lab,
            members,
            "rad",
            f"Impeller angle (minus uniform rotation), speed, acceleration, jerk at {rpm} rpm",
            per,
        ),
        lines_plot(
            "plot-speed",
            "Speed ratios",
            th,
            x_lab,
            [("speed / input speed", ratios)],
            f"Impeller speed over input-gear speed (eq. 1-4 over i12; {params.driver}-"
            "driven, paper Fig. 3/5)",
            per,
            height=420,
        ),
        lines_plot(
            "plot-chambers",
            "Chambers and flow",
            th,
            x_lab,
            chambers,
            "Relative angle of the impellers, chamber volumes and flow",
            per,
        ),
        torque_plot(
            cols,
            th,
            x_lab,
            loads,
            f"Input torque the motor must supply at gear 1 at {rpm} rpm (positive), two load "
            "models",
            per,
            supplied=True,
            caption="Both load models on one convention: the torque the motor must supply at "
            "input gear 1, positive. Top: the paper's eq. 7/8, M1 = M7 dq_1/dtheta + M8 "
            "dq_2/dtheta with constant impeller loads. Middle: the chamber pressures of ideal "
            "ports on the vanes, by virtual work. Bottom: the torque spent on the inertia of "
            "shaft and impellers, and the motor torque with it (ideal ports).",
        ),
        Plot(
            "plot-pv",
            "p-V diagram",
            xy_figure(
                pv,
                "volume [cm^3]",
                "pressure [bar]",
                "p-V diagram of a chamber (ideal ports)",
                height=440,
            ),
        ),
        *filter(
            None,
            [
                force_plot(
                    _distinct_forces(cols),
                    th,
                    x_lab,
                    "Forces in the pairs of both guide-bar mechanisms and the "
                    f"gear meshes at {rpm} rpm (pump torques, ideal ports, and "
                    "impeller inertia); the crank pin carries the slider's force, "
                    "an impeller's bearing its mesh's",
                    per,
                )
            ],
        ),
    ]


def _distinct_forces(cols: dict) -> dict:
    """The columns without the pairs whose force repeats another's: the crank pin carries the
    slider block's force, an impeller's bearing its mesh's normal force."""
    same = ("crank_pin1_force_N", "crank_pin2_force_N", "impeller1_bearing_force_N",
            "impeller2_bearing_force_N")  # fmt: skip
    return {k: v for k, v in cols.items() if k not in same}


def checks(result, cfg) -> list[Check]:
    """Vane clearance, speed and flow ripple, torque fluctuation, flywheel, contact stress and
    efficiency."""
    s = result.summary
    out = []
    lo = s.get("chamber_angle_min_deg")
    if lo is not None:
        if lo <= 0.5:
            out.append(
                Check(
                    "warning",
                    "Vanes touch",
                    f"At the equal-speed points the vanes of the two impellers close the "
                    f"chambers completely (smallest chamber angle {fmt(lo)} deg, vane angle "
                    f"{fmt(s['pump_vane_angle_deg'])} deg = the paper's theoretical gamma_0): "
                    "no dead volume, but no clearance either. A real pump needs a slightly "
                    "smaller vane angle (machine.vane_angle).",
                )
            )
        else:
            out.append(
                Check("ok", "Vane clearance", f"The chambers never close below {fmt(lo)} deg.")
            )
    ripple = s.get("flow_ripple")
    if ripple is not None:
        out.append(
            Check(
                "warning" if ripple > 1.0 else "note",
                "Flow ripple",
                f"The delivered flow varies between {fmt(s['flow_min_l_per_min'])} and "
                f"{fmt(s['flow_max_l_per_min'])} l/min around a mean of "
                f"{fmt(s['flow_mean_l_per_min'])} l/min (ripple {fmt(ripple)}).",
            )
        )
    if "input_torque_fluctuation_ratio" in s:
        out.append(
            Check(
                "note",
                "Input torque with constant loads (eq. 7/8)",
                f"With constant impeller torques the input torque swings between "
                f"{fmt(s['input_torque_min_Nm'])} and {fmt(s['input_torque_max_Nm'])} N*m "
                f"({fmt(100 * s['input_torque_fluctuation_ratio'])} % of the mean); "
                "guide-driven would fluctuate less (paper, Fig. 10-11).",
            )
        )
    return out + flywheel_checks(s, "the impellers", supplied=True) + contact_checks(s, cfg)
