"""HTML report of the opposed-piston reactor on the double eccentric cams.

The scene is a section through the reactor axis, with the shaft axis normal to
the page: on the left and on the right a disc of radius R turns about the shaft
with eccentricity e (both disc centres at ``e (cos beta, sin beta)`` from the
shaft, the same shaft seen from the same side), and pushes its piston along the
reactor axis. The follower point is at ``contact_radius + z`` from the shaft
(knife edge ``R``, roller ``R + r``, flat face ``R``), with the travels ``z``, ``z'``
of :func:`rotorkin.drives.eccentric_cam.kinematics.piston_travels` (positive towards the
reactor centre). The dashed lines mark where a flat-faced (harmonic) piston
would stand, ``+-e cos beta`` (eq. 7, 8): the gap between them and the faces
is the paper's lag ``Delta/2``. The tube between the pistons is drawn broken: its
length L is not to scale. Volume and pressure: :mod:`rotorkin.machines.opposed_piston`.
"""

from __future__ import annotations

import numpy as np

from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam.study import drive_params, machine_params, sections
from rotorkin.machines import opposed_piston as op
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
    svaj_plot,
    torque_plot,
    trace,
    xy_figure,
)

__all__ = ["scene", "plots", "checks"]

_FLUID = "#c6dbef"


def _models(cfg):
    params = drive_params(cfg)
    machine, _ = sections(cfg)
    return params, machine_params(params, machine)


def _rect(x0, x1, h):
    """Closed rectangles from x0 to x1 (arrays (F,)), height 2h about the axis -> (F, 5)."""
    x0, x1 = np.atleast_1d(x0)[:, None], np.atleast_1d(x1)[:, None]
    xs = np.concatenate([x0, x1, x1, x0, x0], axis=1)
    ys = np.broadcast_to(np.array([-h, -h, h, h, -h]), xs.shape)
    return xs, ys


def scene(result, cfg, frames: int = 120):
    """Both discs, followers and pistons, and the fluid between them, over one turn."""
    params, reactor = _models(cfg)
    beta = frame_angles(ec.period(params), frames)
    nf = len(beta)
    b = SceneBuilder(beta)
    R, e, bore = params.disc_radius * 1e3, params.eccentricity * 1e3, reactor.bore * 1e3
    rod, thick, seen = 0.6 * R, 0.25 * R, 1.2 * R
    contact = params.contact_radius * 1e3 if np.isfinite(params.contact_radius) else R
    D = R + e + rod + thick + seen + 0.15 * R  # the shafts at -D and +D
    z = ec.piston_travels(params, beta)[0] * 1e3  # (2, F), towards the centre
    tip = np.stack([-D + contact + z[0], D - contact - z[1]])  # follower points on the axis
    face = np.stack([tip[0] + rod + thick, tip[1] - rod - thick])  # inner faces of the pistons
    gap = 0.08 * R  # half width of the break in the tube
    # tube walls (from the pistons' rearmost position to the break), break marks, axis
    x0 = min(float(np.min(tip[0])), float(np.min(-tip[1]))) + rod - 3.0
    wall = 0.5 * bore + 4.0
    tx = [
        x0,
        -gap,
        np.nan,
        x0,
        -gap,
        np.nan,
        -x0,
        gap,
        np.nan,
        -x0,
        gap,
        np.nan,
        -gap - 6,
        -gap + 6,
        np.nan,
        gap - 6,
        gap + 6,
    ]
    ty = [
        -wall,
        -wall,
        np.nan,
        wall,
        wall,
        np.nan,
        -wall,
        -wall,
        np.nan,
        wall,
        wall,
        np.nan,
        -wall - 10,
        wall + 10,
        np.nan,
        -wall - 10,
        wall + 10,
    ]
    b.static(
        trace(
            "line",
            "reactor tube (broken: L not to scale)",
            "#404040",
            3,
            x=tx,
            y=ty,
            hoverinfo="skip",
        )
    )
    b.static(
        trace(
            "line",
            "reactor axis",
            GREY,
            1,
            legend=False,
            x=[-D - R - e, D + R + e],
            y=[0, 0],
            hoverinfo="skip",
            line={"color": GREY, "width": 1, "dash": "dashdot"},
        )
    )
    fl = [
        _rect(np.minimum(face[0], -gap), np.full(nf, -gap), 0.5 * bore),
        _rect(np.full(nf, gap), np.maximum(face[1], gap), 0.5 * bore),
    ]
    b.animated_trace(
        trace("fill", "enclosed fluid", _FLUID, edge_width=0),
        x=join(fl[0][0], fl[1][0]),
        y=join(fl[0][1], fl[1][1]),
    )
    # discs (same shaft, seen from the same side: centres at e (cos beta, sin beta)), followers
    for k, (xs, color, side) in enumerate(((-D, COLOR_1, "left"), (D, COLOR_2, "right"))):
        cx, cy = xs + e * np.cos(beta), e * np.sin(beta)
        dx, dy = circle(cx, cy, R, 72)
        b.animated_trace(
            trace(
                "fill",
                f"{side} disc (R = {fmt(R)} mm, e = {fmt(e)} mm)",
                "rgba(180,180,180,0.35)",
                edge=color,
                edge_width=2,
            ),
            x=dx,
            y=dy,
        )
        b.animated_trace(
            trace(
                "line",
                "shaft -> disc centre -> rim",
                "#303030",
                2,
                legend=False,
                mode="lines+markers",
                marker={"size": [10, 6, 5]},
            ),
            x=np.stack([np.full(nf, xs), cx, cx + R * np.cos(beta)], axis=1),
            y=np.stack([np.zeros(nf), cy, cy + R * np.sin(beta)], axis=1),
        )
        sign = 1.0 if k == 0 else -1.0
        rx, ry = _rect(tip[k], tip[k] + sign * rod, 0.08 * bore)
        px, py = _rect(tip[k] + sign * rod, face[k], 0.5 * bore - 1.0)
        b.animated_trace(
            trace("fill", f"{side} piston and rod", color, edge="black"),
            x=join(rx, px),
            y=join(ry, py),
        )
    if params.follower == "roller":
        cs = [circle(tip[k], np.zeros(nf), params.roller_radius * 1e3, 24) for k in (0, 1)]
        b.animated_trace(
            trace("fill", "rollers", "white", edge="black", edge_width=1.5),
            x=join(cs[0][0], cs[1][0]),
            y=join(cs[0][1], cs[1][1]),
        )
    elif params.follower == "flat":
        h = np.broadcast_to([-e - 12.0, e + 12.0], (nf, 2))
        b.animated_trace(
            trace("line", "flat faces", "black", 4),
            x=join(*[np.stack([tip[k], tip[k]], 1) for k in (0, 1)]),
            y=join(h, h),
        )
    else:
        b.animated_trace(
            trace("markers", "knife-edge contact points", "black", 8, marker={"symbol": "diamond"}),
            x=tip.T,
            y=np.zeros((nf, 2)),
        )
    if params.follower != "flat":  # where a flat-faced piston's face would stand: +-e cos beta
        harmonic = ec.harmonic_travel(e, beta)[0]
        hx = np.stack([-D + R + harmonic + rod + thick, D - R + harmonic - rod - thick])
        h = np.broadcast_to([-0.5 * bore - 10, 0.5 * bore + 10], (nf, 2))
        b.animated_trace(
            trace(
                "line",
                "a flat-faced (harmonic) piston's face, +-e cos beta",
                "black",
                1.5,
                line={"color": "black", "width": 1.5, "dash": "dot"},
            ),
            x=join(*[np.stack([hx[k], hx[k]], 1) for k in (0, 1)]),
            y=join(h, h),
        )
    motion = ec.motion(params, beta)
    vol = op.enclosed_volume(reactor, motion)[0][0] * 1e6
    pres = op.pressure(reactor, motion)[0][0] / 1e5
    delta = z[0] + z[1]
    length = fmt(reactor.device_length * 1e3)
    b.animated_trace(
        trace("text", "state", "#202020", 12),
        x=np.zeros((nf, 1)),
        y=np.full((nf, 1), 0.5 * bore + 34),
        text=[
            [f"L = {length} mm (not to scale)<br>Delta = {dl:.2f} mm, p = {p:.4g} bar"]
            for dl, p in zip(delta, pres, strict=True)
        ],
    )
    xr, yr = D + R + e + 10, 1.2 * (R + e)
    layout = panels(
        470,
        [("", None, [-xr, xr], [-0.96 * yr, yr], "along the reactor axis [mm]", "[mm]")],
        [
            (
                0.0,
                "<b>Section through the reactor axis</b>, shaft normal to the page "
                "(both discs on one shaft, seen from the same side)",
            )
        ],
    )
    readouts = [
        ("z (left)", "mm", z[0]),
        ("z' (right)", "mm", z[1]),
        ("Delta = z + z'", "mm", delta),
        ("volume", "cm3", vol),
        ("pressure", "bar", pres),
    ]
    caption = (
        f"Drawn from the model: eccentric_cam.piston_travels ({params.follower} follower) and "
        "opposed_piston.enclosed_volume / pressure. Dotted: where a flat-faced piston would "
        "stand; the distance to the face is the lag Delta/2 of the paper's section 3."
    )
    return b.build(layout, "beta, shaft angle", readouts, caption)


def plots(result, cfg) -> list[Plot]:
    """SVAJ of the pistons, travel decomposition and gap, volume and pressure, torque, p-V,
    pair forces, cam."""
    cols, s = result.columns, result.summary
    params = _models(cfg)[0]
    be, x_lab = cols["beta_deg"], "shaft angle beta [deg]"
    rpm = fmt(s.get("shaft_speed_mean_rpm", float("nan")))
    members = [
        (f"{side} piston", c, f"z_{side}_mm", f"piston_{side}")
        for side, c in (("left", COLOR_1), ("right", COLOR_2))
    ]
    travel = [
        ("x = z/e (left)", cols["x_left"]),
        ("x' = z'/e (right)", cols["x_right"]),
        ("xi = cos beta (harmonic)", cols["xi"]),
        ("mu (additional)", cols["mu"]),
    ]
    pv = [("enclosed fluid", cols["volume_cm3"], cols["pressure_bar"], None)]
    return [
        svaj_plot(
            cols,
            be,
            x_lab,
            members,
            "m",
            f"Piston travel (towards the centre), speed, acceleration, jerk at {rpm} rpm",
            360.0,
        ),
        lines_plot(
            "plot-gap",
            "Travel and gap",
            be,
            x_lab,
            [
                ("travel / e", travel),
                ("gap change [mm]", [("Delta = z + z' (eq. 5)", cols["gap_change_mm"])]),
            ],
            "Travels, their decomposition (Fig. 6, 8) and the gap change (Fig. 7)",
            360.0,
        ),
        lines_plot(
            "plot-volume",
            "Volume and pressure",
            be,
            x_lab,
            [
                ("volume [cm^3]", [("enclosed volume", cols["volume_cm3"])]),
                ("pressure [bar]", [("pressure", cols["pressure_bar"])]),
            ],
            f"Enclosed volume and {s.get('fluid', '')} pressure",
            360.0,
        ),
        torque_plot(
            cols,
            be,
            x_lab,
            [
                (
                    "fluid [N*m]",
                    [
                        ("fluid torque", cols["shaft_torque_Nm"]),
                        mean_trace(be, s.get("mean_torque_Nm", np.nan)),
                    ],
                )
            ],
            f"Torque on the shaft by virtual work at {rpm} rpm (positive: the fluid drives "
            "the shaft)",
            360.0,
        ),
        Plot(
            "plot-pv",
            "p-V diagram",
            xy_figure(
                pv,
                "volume [cm^3]",
                "pressure [bar]",
                "p-V of the enclosed fluid (a line: no net work over a turn)",
                height=440,
            ),
        ),
        force_plot(cols, be, x_lab, f"Pair forces at {rpm} rpm", 360.0),
        Plot(
            "plot-cam",
            "Cam and pressure angle",
            _cam_figure(params, cols),
            "Left: a disc in its own frame with the shaft axis; the follower point runs on the "
            "contact circle. Right: pressure angle of the left follower (between contact normal "
            "and piston axis).",
        ),
    ]


def _cam_figure(params, cols):
    import plotly.graph_objects as go
    from plotly.subplots import make_subplots

    R, e = params.disc_radius * 1e3, params.eccentricity * 1e3
    t = np.linspace(0.0, 2.0 * np.pi, 181)
    fig = make_subplots(
        rows=1,
        cols=2,
        column_widths=[0.42, 0.58],
        horizontal_spacing=0.1,
        subplot_titles=("Disc profile (disc frame)", "Pressure angle (left)"),
    )
    fig.add_trace(
        go.Scatter(
            x=R * np.cos(t),
            y=R * np.sin(t),
            mode="lines",
            name="disc profile",
            line={"color": COLOR_1, "width": 2},
        ),
        row=1,
        col=1,
    )
    if params.follower == "roller":
        rc = (params.disc_radius + params.roller_radius) * 1e3
        fig.add_trace(
            go.Scatter(
                x=rc * np.cos(t),
                y=rc * np.sin(t),
                mode="lines",
                name="roller-centre path (R + r)",
                line={"color": GREY, "dash": "dash"},
            ),
            row=1,
            col=1,
        )
    fig.add_trace(
        go.Scatter(
            x=[-e, 0.0],
            y=[0.0, 0.0],
            mode="lines+markers+text",
            name=f"shaft axis -> disc centre (e = {fmt(e)} mm)",
            text=["shaft", "centre"],
            textposition="top center",
            line={"color": "black", "width": 2},
        ),
        row=1,
        col=1,
    )
    fig.add_trace(
        go.Scatter(
            x=cols["beta_deg"],
            y=cols["pressure_angle_left_deg"],
            mode="lines",
            name="pressure angle",
            line={"color": COLOR_2, "width": 2},
        ),
        row=1,
        col=2,
    )
    fig.update_xaxes(title_text="[mm]", row=1, col=1)
    fig.update_yaxes(title_text="[mm]", scaleanchor="x", row=1, col=1)
    fig.update_xaxes(title_text="shaft angle beta [deg]", row=1, col=2)
    fig.update_yaxes(title_text="pressure angle [deg]", row=1, col=2)
    fig.update_layout(
        height=460,
        template="plotly_white",
        margin={"l": 60, "r": 20, "t": 60, "b": 50},
        title={"text": "Cam: disc and pressure angle", "x": 0.01, "font": {"size": 15}},
        legend={"orientation": "h", "y": -0.18},
    )
    return fig


def checks(result, cfg) -> list[Check]:
    """Cavitation, pressure ripple, gap change, pressure angle, flywheel."""
    s = result.summary
    out = []
    if s.get("cavitation"):
        out.append(
            Check(
                "error",
                "Cavitation",
                f"The enclosed {s['fluid']} would have to reach {fmt(s['pressure_min_bar'])} "
                "bar absolute: below zero the liquid cavitates. Use flat-faced pistons "
                "(drive.follower = flat), a smaller eccentricity, or a gas.",
            )
        )
    else:
        out.append(
            Check(
                "ok",
                "No cavitation",
                f"The pressure stays between {fmt(s['pressure_min_bar'])} and "
                f"{fmt(s['pressure_max_bar'])} bar absolute.",
            )
        )
    ripple = s.get("pressure_ripple_relative", 0.0)
    out.append(
        Check(
            "warning" if ripple > 0.05 else "note",
            "Pressure ripple",
            f"The pressure swings by {fmt(s['pressure_ripple_bar'])} bar "
            f"({100 * ripple:.3g} % of the charge) twice a turn, because the pistons' "
            f"faces move apart by up to {fmt(abs(s['gap_change_min_mm']))} mm "
            f"({fmt(s['gap_change_to_length_percent'])} % of L).",
        )
    )
    pa = s.get("pressure_angle_max_deg", 0.0)
    level = "warning" if pa > 30.0 + 1e-6 else ("note" if pa > 25.0 else "ok")
    out.append(
        Check(
            level,
            "Pressure angle",
            f"The largest pressure angle is {fmt(pa)} deg (the usual limit for a "
            "translating follower is about 30 deg): side load on the piston rods.",
        )
    )
    lift = s.get("follower_force_min_N")
    if lift is not None:
        if s.get("follower_lift_off"):
            out.append(
                Check(
                    "error",
                    "Follower lift-off",
                    f"A disc would have to pull its piston ({fmt(lift)} N at the run "
                    "speed): only the fluid's pressure holds the pistons on the discs. "
                    "A lower speed, lighter pistons or a higher charge pressure.",
                )
            )
        else:
            out.append(
                Check(
                    "ok",
                    "Followers stay on the discs",
                    f"The smallest push of a disc on its follower is {fmt(lift)} N.",
                )
            )
    if "section_travel_difference_max_mm" in s:
        out.append(
            Check(
                "note",
                "Inclined discs",
                f"At {fmt(s['inclination_deg'])} deg the disc's section in the piston "
                f"plane is an ellipse ({fmt(s['section_major_axis_mm'])} mm by "
                f"{fmt(s['section_minor_axis_mm'])} mm): its piston travel differs from "
                "the paper's circle by up to "
                f"{fmt(s['section_travel_difference_max_mm'])} mm (gap change down to "
                f"{fmt(s['section_gap_change_min_mm'])} mm); the reactor and force "
                "results use the circle.",
            )
        )
    return out + contact_checks(s, cfg) + flywheel_checks(s, "the pistons")
