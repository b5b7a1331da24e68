"""HTML report of the twin-rotor engine on the wobble-plate + spherical-cam drive.

The scene has two views of the same instant, both from the model's coordinates:

* the drive in 3D (fixed frame xyz, x along the Z-shaft): the shaft and its
  inclined middle section (the plate axis, the cross product of two plate radii of
  :func:`rotorkin.drives.wobble_cam.kinematics.plate_point`), the wobble plate, the four roller
  shafts with their inner rollers (on the sphere,
  :func:`~rotorkin.drives.wobble_cam.kinematics.roller_positions`) and outer rollers, the
  slider rails of both rotors (planes through the x axis at the rotor angles
  ``Phi_k`` of :func:`~rotorkin.drives.wobble_cam.kinematics.rotor_angles`) and the four
  groove centre-lines of the cam (:func:`~rotorkin.drives.wobble_cam.kinematics.groove_points`,
  cam frame) turned with the cam to ``psi = -theta`` (``r|0 = A_psi r|4``, eq. 9-11);
* the annular cylinder seen from the shaft end (+x; y to the right, z up, angles
  from +z towards +y): the pistons of rotor 1 at ``Phi_1 + gamma + 2 pi k/N`` and of
  rotor 2 at ``Phi_2 - gamma + 2 pi k/N``, ``piston_width`` wide, and the chambers
  between them coloured by their stroke, labelled with their pressure
  (:func:`rotorkin.drives.wobble_cam.engine.engine_state`).

The outer rollers sit at 1.3 sphere radii on the roller shafts and the plate is
drawn with 0.7 sphere radii: the paper gives neither, they are for the picture.
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import engine_cycle as ec
from rotorkin.drives.wobble_cam import engine as eng
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam.study import models
from rotorkin.render.scenes import (
    COLOR_1,
    COLOR_2,
    GREY,
    Check,
    Plot,
    SceneBuilder,
    contact_checks,
    flywheel_checks,
    fmt,
    force_plot,
    frame_angles,
    join,
    lines_plot,
    mean_trace,
    merge_identical,
    panels,
    sector,
    select,
    svaj_plot,
    torque_plot,
    trace,
    xy_figure,
)

__all__ = ["scene", "plots", "checks"]

_OUTER = 1.3  # outer rollers, in sphere radii (drawing only)
_PLATE = 0.7  # plate radius, in sphere radii (drawing only)
_STROKE_COLORS = ("#9ecae1", "#fdd0a2", "#fc9272", "#c7c7c7")  # intake, compr., power, exhaust


def _groove_period(params) -> float:
    """Shaft angle after which a groove centre-line closes (pi for the paper's law)."""
    n = float(params.spin_ratio)
    plain = not (params.spin_a or params.spin_b)
    return np.pi if plain and n.is_integer() and int(n) % 2 == 0 else 2.0 * np.pi


def _annulus(machine):
    if machine.section == "circular":
        h = 0.5 * machine.section_diameter
        return (machine.mean_radius - h) * 1e3, (machine.mean_radius + h) * 1e3
    return machine.inner_radius * 1e3, machine.outer_radius * 1e3


def _end_view(rho, ang):
    """Seen from +x: y to the right, z up; angles from +z towards +y."""
    return rho * np.sin(ang), rho * np.cos(ang)


def scene(result, cfg, frames: int = 120):
    """The drive (3D) and the rotors (end view) over one shaft turn."""
    params, machine, cycle = models(cfg)
    theta = frame_angles(wc.period(params), frames)
    nf = len(theta)
    b = SceneBuilder(theta)
    r = params.sphere_radius * 1e3
    tilt = params.plate_tilt
    spin = wc.spin_law(params, theta)[0]
    offsets = wc.roller_offsets(params.roller_axis_angle)

    def plate(c, radius):  # plate points at angles c, (3, F, len(c)) [mm]
        return wc.plate_point(tilt, radius, theta[:, None], spin[:, None], np.atleast_1d(c))

    # the sphere of the groove centre-lines: circles about x (unchanged by the cam's turn)
    t = np.linspace(0.0, 2.0 * np.pi, 73)
    lat = np.radians([-60, -30, 0, 30, 60])[:, None]
    rings = np.stack(
        np.broadcast_arrays(
            r * np.sin(lat), r * np.cos(lat) * np.sin(t), r * np.cos(lat) * np.cos(t)
        )
    )  # (3, 5, 73)
    xyz = join(*rings.transpose(1, 0, 2))
    b.static(
        trace(
            "line3d",
            "sphere r (groove centres)",
            "#c8c8c8",
            2,
            x=xyz[0],
            y=xyz[1],
            z=xyz[2],
            hoverinfo="skip",
        )
    )
    b.static(
        trace(
            "line3d", "Z-shaft (x axis)", "#404040", 9, x=[-1.45 * r, 1.45 * r], y=[0, 0], z=[0, 0]
        )
    )
    # the cam's grooves (cam frame) turned with the cam, psi = -theta: r|0 = A_psi r|4
    g4 = wc.groove_points(params, np.linspace(0.0, _groove_period(params), 73)) * 1e3
    psi = wc.cam_angle(theta)[:, None, None]
    gy = np.cos(psi) * g4[None, :, 1] + np.sin(psi) * g4[None, :, 2]  # (F, 4, n)
    gz = -np.sin(psi) * g4[None, :, 1] + np.cos(psi) * g4[None, :, 2]
    gx = join(*[g4[k, 0][None, :] for k in range(4)])[0]  # x does not change in a turn about x
    b.animated_trace(
        trace("line3d", "cam grooves (turn with psi = -theta)", "#2ca02c", 4, x=gx),
        y=join(*gy.transpose(1, 0, 2)),
        z=join(*gz.transpose(1, 0, 2)),
    )
    # inclined middle section of the shaft: the plate axis, normal to two plate radii
    normal = np.cross(plate(0.0, 1.0)[..., 0], plate(0.5 * np.pi, 1.0)[..., 0], axis=0)  # (3, F)
    ends = 0.45 * r * normal[:, :, None] * np.array([-1.0, 1.0])
    b.animated_trace(
        trace("line3d", "inclined section (plate axis)", "#404040", 12),
        x=ends[0],
        y=ends[1],
        z=ends[2],
    )
    # the plate: a disc (mesh fan about its centre) and its rim
    rim = plate(np.linspace(0.0, 2.0 * np.pi, 37)[:-1], _PLATE * r)  # (3, F, 36)
    disc = np.concatenate([np.zeros((3, nf, 1)), rim], axis=2)
    fan = np.arange(1, 37)
    b.animated_trace(
        {
            "type": "mesh3d",
            "name": "wobble plate",
            "color": "#90a4ae",
            "opacity": 0.9,
            "flatshading": True,
            "hoverinfo": "skip",
            "i": [0] * 36,
            "j": fan.tolist(),
            "k": (fan % 36 + 1).tolist(),
        },
        x=disc[0],
        y=disc[1],
        z=disc[2],
    )
    rim = np.concatenate([rim, rim[..., :1]], axis=2)
    b.animated_trace(
        trace("line3d", "plate rim", "#546e7a", 4, legend=False), x=rim[0], y=rim[1], z=rim[2]
    )
    # roller shafts, inner rollers (on the sphere, in the grooves), outer rollers (in the rails)
    inner = wc.roller_positions(params, theta) * 1e3  # (4, 3, F)
    q = wc.rotor_angles(params, theta)[0]  # (2, F)
    # a rail: a rectangle in the plane of the x axis and the direction Phi_g, around the path
    # of the outer roller (|x| <= R sin(phi), R cos(phi) <= distance from x <= R)
    xr, lo, hi = _OUTER * r * np.array([np.sin(tilt), np.cos(tilt), 1.0]) + 0.1 * r * np.array(
        [1.0, -1.0, 1.0]
    )
    rail_x, rail_r = np.array([-xr, xr, xr, -xr, -xr]), np.array([lo, lo, hi, hi, lo])
    for g, color in ((0, COLOR_1), (1, COLOR_2)):
        c = offsets[[2 * g, 2 * g + 1]]
        a, o = plate(c, _PLATE * r), plate(c, _OUTER * r)  # (3, F, 2)
        shafts = [join(*[np.stack([a[i][:, k], o[i][:, k]], 1) for k in (0, 1)]) for i in range(3)]
        b.animated_trace(
            trace("line3d", f"roller shafts, group {g + 1}", color, 7, legend=False),
            x=shafts[0],
            y=shafts[1],
            z=shafts[2],
        )
        rin = inner[[2 * g, 2 * g + 1]]
        b.animated_trace(
            trace(
                "markers3d",
                f"rollers of group {g + 1} (in the grooves)",
                color,
                7,
                marker={"line": {"color": "black", "width": 1}},
            ),
            x=rin[:, 0].T,
            y=rin[:, 1].T,
            z=rin[:, 2].T,
        )
        b.animated_trace(
            trace(
                "markers3d",
                f"outer rollers of group {g + 1} (in rotor {g + 1}'s rails)",
                color,
                5,
                legend=False,
                marker={"symbol": "square"},
            ),
            x=o[0],
            y=o[1],
            z=o[2],
        )
        ang = q[g][:, None, None] + np.array([0.0, np.pi])[None, :, None]  # (F, 2 rails, 1)
        ry, rz = rail_r * np.sin(ang), rail_r * np.cos(ang)
        rx = np.broadcast_to(rail_x, ry.shape)
        b.animated_trace(
            trace("line3d", f"rails of rotor {g + 1}", color, 3),
            x=join(rx[:, 0], rx[:, 1]),
            y=join(ry[:, 0], ry[:, 1]),
            z=join(rz[:, 0], rz[:, 1]),
        )
    # the rotors seen from the shaft end
    state = eng.engine_state(params, machine, cycle, theta)
    ri, ro = _annulus(machine)
    n = machine.pistons_per_rotor
    gam = float(wc.piston_offset(n))
    beta = eng.piston_layout(params, machine).piston_width
    t = np.linspace(0.0, 2.0 * np.pi, 121)
    cx, cy = _end_view(np.r_[np.full(121, ro), np.nan, np.full(121, ri)], np.r_[t, np.nan, t])
    b.static(trace("line", "cylinder wall and hub", GREY, 2, x=cx, y=cy, hoverinfo="skip"))
    k = np.arange(n)[None, :] * 2.0 * np.pi / n
    c1 = q[0][:, None] + gam + k  # (F, N) piston centre lines
    c2 = q[1][:, None] - gam + k
    nxt = np.roll(c1, -1, axis=1) + 2.0 * np.pi * (np.arange(n) == n - 1)
    # chamber 2m (kind A): rotor-1 piston m -> rotor-2 piston m; 2m+1 (B): -> rotor-1 piston m+1
    a0 = np.stack([c1, c2], axis=2).reshape(nf, 2 * n) + 0.5 * beta
    a1 = np.stack([c2, nxt], axis=2).reshape(nf, 2 * n) - 0.5 * beta
    polys = [sector(ri, ro, a0[:, j], a1[:, j], 10, _end_view) for j in range(2 * n)]
    for s_id, name in enumerate(ec.STROKE_NAMES):
        mask = state.stroke == s_id
        b.animated_trace(
            trace("fill", f"{name} stroke", _STROKE_COLORS[s_id], edge_width=0.5),
            x=select([p[0] for p in polys], mask),
            y=select([p[1] for p in polys], mask),
        )
    for g, (cen, color) in enumerate(((c1, COLOR_1), (c2, COLOR_2))):
        pist = [
            sector(ri, ro, cen[:, m] - 0.5 * beta, cen[:, m] + 0.5 * beta, 6, _end_view)
            for m in range(n)
        ]
        b.animated_trace(
            trace("fill", f"pistons of rotor {g + 1}", color, edge="black"),
            x=join(*[p[0] for p in pist]),
            y=join(*[p[1] for p in pist]),
        )
    # every chamber's number and pressure: inside a wide chamber, outside the cylinder wall
    # beside a narrow one (the firing pressure is reached in the narrowest chamber)
    p_bar, wide = state.pressure.T / 1e5, (a1 - a0) > np.radians(14)
    radius = np.where(wide, 0.5 * (ri + ro), ro + 0.2 * (ro - ri) + 8.0)
    lx, ly = _end_view(radius, 0.5 * (a0 + a1))
    labels = [[f"{j + 1}<br>{p_bar[f, j]:.3g} bar" for j in range(2 * n)] for f in range(nf)]
    b.animated_trace(
        trace("text", "chamber: number, pressure", "#202020", 11), x=lx, y=ly, text=labels
    )
    lim = [-(1.12 * ro + 0.2 * (ro - ri) + 14.0), 1.12 * ro + 0.2 * (ro - ri) + 14.0]
    layout = panels(
        620,
        [("", [0.6, 1.0], lim, lim, "y [mm]", "z [mm]")],
        [
            (0.0, "<b>Drive</b> (3D, drag to turn): plate, rollers, rails, cam grooves"),
            (0.6, "<b>Rotors</b> seen from the shaft end (+x)"),
        ],
        legend_y=-0.1,
    )
    axis = {"range": [-1.5 * r, 1.5 * r]}
    layout["scene"] = {
        "domain": {"x": [0.0, 0.56], "y": [0.0, 1.0]},
        "aspectmode": "data",
        "xaxis": {"title": {"text": "x [mm]"}, **axis},
        "yaxis": {"title": {"text": "y [mm]"}, **axis},
        "zaxis": {"title": {"text": "z [mm]"}, **axis},
        "camera": {"eye": {"x": 1.8, "y": -0.95, "z": 0.35}},
    }
    readouts = [
        ("Phi_1 (rotor 1)", "deg", np.degrees(q[0])),
        ("Phi_2 (rotor 2)", "deg", np.degrees(q[1])),
        ("alpha' = Phi_2 - Phi_1", "deg", np.degrees(q[1] - q[0])),
        ("chamber 1 volume", "cm3", state.chambers.volume[0] * 1e6),
        ("chamber 1 pressure", "bar", state.pressure[0] / 1e5),
    ]
    caption = (
        "Drawn from the model: wobble_cam.plate_point, roller_positions, rotor_angles and "
        "groove_points (the grooves turned with the cam, psi = -theta), engine.engine_state "
        "(chambers coloured by stroke, labelled with their pressure). The outer rollers and the "
        "plate's size are drawn for the picture (the paper gives neither)."
    )
    return b.build(layout, "theta, Z-shaft angle", readouts, caption)


def _distinct(cols) -> dict:
    """Force and stress columns with equal values merged into one (named for all of them).

    Opposite rollers carry equal loads, and so do the two bevel meshes: drawn apart, one
    curve would hide the other. Equal: within 1e-7 of the curve's largest value (the
    contact stresses of opposite rollers differ by round-off where the load is small).
    """
    out = {}
    for suffix in ("_force_N", "_contact_stress_MPa"):
        kept = []  # [stems, values]
        for k, v in cols.items():
            if not k.endswith(suffix):
                continue
            stem = k[: -len(suffix)]
            tol = 1e-7 * float(np.nanmax(np.abs(v))) if np.any(np.isfinite(v)) else 0.0
            same = next((e for e in kept if np.allclose(e[1], v, atol=tol, equal_nan=True)), None)
            if same is None:
                kept.append([[stem], v])
            else:
                same[0].append(stem)
        out.update({"_and_".join(stems) + suffix: v for stems, v in kept})
    out.update({k: v for k, v in cols.items() if k not in out and "_force_N" not in k
                and "_contact_stress_MPa" not in k})  # fmt: skip
    return out


def plots(result, cfg) -> list[Plot]:
    """SVAJ of the rotors, chambers, pressures, torque, p-V, rollers and grooves (3D)."""
    cols, s = result.columns, result.summary
    params = models(cfg)[0]
    th, x_lab = cols["theta_deg"], "shaft angle theta [deg]"
    rpm = fmt(s.get("shaft_speed_mean_rpm", float("nan")))
    members = [
        (f"rotor {k}", c, f"rotor{k}_angle_deg", f"rotor{k}")
        for k, c in ((1, COLOR_1), (2, COLOR_2))
    ]
    angles = [
        ("slider angle alpha'", cols["slider_angle_deg"]),
        ("chamber A delta_A", cols["chamber_a_angle_deg"]),
        ("chamber B delta_B", cols["chamber_b_angle_deg"]),
    ]
    volumes = [(f"chamber {k.upper()} volume", cols[f"chamber_{k}_volume_cm3"]) for k in "ab"]
    out = [
        svaj_plot(
            cols,
            th,
            x_lab,
            members,
            "rad",
            "Rotor angle (minus the uniform mean rotation), "
            f"speed, acceleration, jerk at {rpm} rpm",
            360.0,
        ),
        lines_plot(
            "plot-chambers",
            "Chambers",
            th,
            x_lab,
            [("angle [deg]", angles), ("volume [cm^3]", volumes)],
            "Slider angle (eq. 15), chamber angles (eq. 19) and volumes",
            360.0,
        ),
    ]
    pcols = [c for c in cols if c.startswith("chamber") and c.endswith("_pressure_bar")]
    if pcols:
        named = [(f"chamber {c.split('_')[0][7:]}", cols[c]) for c in pcols]
        shown = merge_identical(named)
        rows = [("pressure [bar]", shown)]
        out.append(
            lines_plot(
                "plot-pressure",
                "Chamber pressures",
                th,
                x_lab,
                rows,
                "Chamber pressures, ideal four-stroke cycle"
                + (
                    f" ({len(shown)} distinct of {len(named)} chambers)"
                    if len(shown) < len(named)
                    else ""
                ),
                360.0,
                height=440,
                caption="Chambers whose pressure is the same at every shaft angle share one "
                "curve, named for all of them in the legend (drawn separately, one would hide "
                "the other).",
            )
        )
    out.append(
        torque_plot(
            cols,
            th,
            x_lab,
            [
                (
                    "gas [N*m]",
                    [
                        ("gas torque", cols["shaft_torque_Nm"]),
                        mean_trace(th, s.get("mean_torque_Nm", np.nan)),
                    ],
                )
            ],
            f"Torque on the Z-shaft by virtual work at {rpm} rpm (positive: the gas drives "
            "the shaft)",
            360.0,
        )
    )
    if "chamber1_pressure_bar" in cols:
        pv = [
            (
                "chamber 1 (kind A)",
                cols["chamber_a_volume_cm3"],
                cols["chamber1_pressure_bar"],
                None,
            )
        ]
        out.append(
            Plot(
                "plot-pv",
                "p-V diagram",
                xy_figure(
                    pv,
                    "volume [cm^3]",
                    "pressure [bar]",
                    "p-V diagram of chamber 1 over one shaft turn (2 cycles), log-log",
                    height=480,
                    log=True,
                ),
            )
        )
    out.append(
        Plot(
            "plot-sphere",
            "Rollers and grooves (3D)",
            _sphere_figure(params),
            "Paths of the inner rollers in the fixed frame (paper Fig. 8; rollers 2-4 "
            "from the legend), or, with the button, the groove centre-lines they cut in "
            "the turning cam, in the cam frame (Fig. 9). Drag to rotate, scroll to zoom.",
        )
    )
    forces = force_plot(
        _distinct(cols),
        th,
        x_lab,
        f"Forces in the pairs at {rpm} rpm (rotor and plate inertia; pairs that carry the "
        "same load share a curve)",
        360.0,
    )
    if forces is not None:
        out.append(forces)
    return out


def _sphere_figure(params):
    """One rotatable scene: the rollers' paths (fixed frame) or the grooves (cam frame)."""
    import plotly.graph_objects as go

    r = params.sphere_radius * 1e3
    th = np.linspace(0.0, 2.0 * np.pi, 361)
    rollers = wc.roller_positions(params, th) * 1e3
    tg = np.linspace(0.0, _groove_period(params), 181)
    grooves = wc.groove_points(params, tg) * 1e3
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 37), np.linspace(-np.pi / 2, np.pi / 2, 19))
    fig = go.Figure(
        go.Surface(
            x=r * np.sin(v),
            y=r * np.cos(v) * np.sin(u),
            z=r * np.cos(v) * np.cos(u),
            showscale=False,
            opacity=0.15,
            colorscale=[[0, "#bbbbbb"], [1, "#bbbbbb"]],
            hoverinfo="skip",
            name="sphere",
            showlegend=False,
        )
    )
    colors = (COLOR_1, "#6baed6", COLOR_2, "#fb6a4a")
    for k in range(4):
        fig.add_trace(
            go.Scatter3d(
                x=rollers[k, 0],
                y=rollers[k, 1],
                z=rollers[k, 2],
                mode="lines",
                name=f"roller {k + 1} path (group {k // 2 + 1})",
                visible=True if k == 0 else "legendonly",
                line={"color": colors[k], "width": 5},
            )
        )
    for k in range(4):
        fig.add_trace(
            go.Scatter3d(
                x=grooves[k, 0],
                y=grooves[k, 1],
                z=grooves[k, 2],
                mode="lines",
                name=f"groove of roller {k + 1}",
                visible=False,
                line={"color": colors[k], "width": 5},
            )
        )
    show_rollers = [True, True] + ["legendonly"] * 3 + [False] * 4
    show_grooves = [True] + [False] * 4 + [True] * 4

    def axes(t):
        return {f"scene.{a}axis.title.text": f"{a}{t} [mm]" for a in "xyz"}

    buttons = [
        {
            "label": "Roller paths, fixed frame xyz (Fig. 8)",
            "method": "update",
            "args": [{"visible": show_rollers}, axes("")],
        },
        {
            "label": "Groove centre-lines, cam frame x4y4z4 (Fig. 9)",
            "method": "update",
            "args": [{"visible": show_grooves}, axes("4")],
        },
    ]
    fig.update_layout(
        scene={
            "aspectmode": "cube",
            "xaxis_title": "x [mm]",
            "yaxis_title": "y [mm]",
            "zaxis_title": "z [mm]",
            "camera": {"eye": {"x": 1.7, "y": -1.6, "z": 0.9}},
        },
        updatemenus=[
            {
                "type": "buttons",
                "direction": "right",
                "buttons": buttons,
                "x": 0.0,
                "xanchor": "left",
                "y": 1.08,
                "yanchor": "bottom",
                "showactive": True,
                "font": {"size": 12},
            }
        ],
        height=600,
        template="plotly_white",
        margin={"l": 0, "r": 0, "t": 90, "b": 0},
        title={
            "text": f"Rollers and grooves on the sphere r = {fmt(r)} mm",
            "x": 0.01,
            "font": {"size": 15},
        },
        legend={"x": 0.82, "y": 0.95},
    )
    return fig


def checks(result, cfg) -> list[Check]:
    """Interference (eq. 20), closest approach of the pistons, rotor speeds, flywheel."""
    s = result.summary
    params, machine, _ = models(cfg)
    out = []
    tilt, lim = np.degrees(params.plate_tilt), s["max_plate_tilt_deg"]
    frac = tilt / lim
    out.append(
        Check(
            "warning" if frac > 0.9 else "ok",
            "Plate tilt vs interference limit",
            f"The plate tilt {fmt(tilt)} deg is {100 * frac:.0f} % of the largest tilt "
            f"at which neighbouring pistons do not collide, {fmt(lim)} deg (eq. 20; the "
            "paper reads about 65 deg off Fig. 13).",
        )
    )
    gap = min(s["chamber_a_angle_min_deg"], s["chamber_b_angle_min_deg"])
    ri, ro = _annulus(machine)
    arc = np.radians(gap) * 0.5 * (ri + ro)
    out.append(
        Check(
            "warning" if gap < 2.0 else "ok",
            "Closest approach of the pistons",
            f"At the smallest chamber volume neighbouring pistons stand {fmt(gap)} deg "
            f"apart ({fmt(arc)} mm at the mean radius); piston width {fmt(s['piston_width_deg'])} "
            f"deg for a compression ratio of {fmt(s['compression_ratio'])}.",
        )
    )
    lo, hi = s["rotor_speed_ratio_min"], s["rotor_speed_ratio_max"]
    if lo * hi > 0:
        a, b = sorted((abs(lo), abs(hi)))
        out.append(
            Check(
                "ok",
                "Rotors never stop",
                f"Each rotor turns at {fmt(a)} to {fmt(b)} times the shaft speed, never "
                "stopping or reversing.",
            )
        )
    else:
        out.append(
            Check(
                "warning",
                "Rotors stop and reverse",
                f"The rotor speed ratio runs from {fmt(lo)} to {fmt(hi)}: the rotors stop "
                "and turn back during each turn.",
            )
        )
    if "peak_pressure_bar" in s:
        out.append(
            Check(
                "note",
                "Peak cylinder pressure",
                f"The ideal cycle peaks at {fmt(s['peak_pressure_bar'])} bar (compression "
                f"ends at {fmt(s['compression_end_pressure_bar'])} bar); the gas pushes "
                f"the rotors apart with up to {fmt(s['rotor_gas_torque_peak_Nm'])} N*m.",
            )
        )
    out += contact_checks(s, cfg)
    if s.get("groove_crossing_force_max_N", 0.0) > 0.0:
        out.append(
            Check(
                "warning",
                "Rollers loaded through the groove crossings",
                f"A roller carries up to {fmt(s['groove_crossing_force_max_N'])} N while it "
                "runs through a crossing of groove branches, where a plain cylindrical roller "
                "has no wall (with the paper's grooves the other pair then stands near 90 deg "
                "pressure angle and cannot hold the plate's spin). The crossings need a "
                "follower that bridges them (e.g. an elongated boat follower).",
            )
        )
    if "cam_shell_torque_share" in s:
        out.append(
            Check(
                "note",
                "Torque split between the Z-shaft and the cam shell",
                f"The cam shell delivers {fmt(100 * s['cam_shell_torque_share'])} % of the "
                f"output torque (drive.output); the grooves alone would hand it "
                f"{fmt(100 * s['cam_shell_natural_torque_share'])} %, the bevel gearbox "
                f"carries the rest (up to {fmt(s['gearbox_torque_max_Nm'])} N*m, mesh force "
                f"{fmt(s['bevel_mesh_force_max_N'])} N).",
            )
        )
    return out + flywheel_checks(s, "the rotors")
