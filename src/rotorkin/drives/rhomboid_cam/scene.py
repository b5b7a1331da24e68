"""HTML report of the rotary-blade engine on the rhomboid lever-cam converter.

The scene shows one output-shaft turn in two views, both from the model's coordinates:

* the converter: the fixed cam (pitch curve of eq. 3 from
  :func:`rotorkin.drives.rhomboid_cam.kinematics.profile_point`, and the two walls of its
  track, the pitch curve offset by the roller radius ``cam.roller_radius`` along
  its normal), the rhombus ABCD of :func:`~rotorkin.drives.rhomboid_cam.kinematics.rhombus_vertices`
  with its rollers, the output-shaft arm along the diagonal CA (at ``alpha``) and the
  two blade arms through the midpoints of the sides
  (:func:`~rotorkin.drives.rhomboid_cam.kinematics.blade_arm_points`);
* the working space: blade pairs 1 and 2 at ``phi_1 + 2 pi m/B`` and
  ``phi_2 + 2 pi m/B`` (:func:`~rotorkin.drives.rhomboid_cam.kinematics.blade_angles`), the
  chambers between them (:func:`rotorkin.machines.rotary_blade.chamber_angles`,
  ``chamber_volumes``), coloured by whether they grow or shrink.
"""

from __future__ import annotations

import numpy as np

from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam.study import drive_params
from rotorkin.machines import rotary_blade as rb
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
    merge_identical,
    panels,
    sector,
    select,
    svaj_plot,
    torque_plot,
    trace,
    xy_figure,
)
from rotorkin.studies.helpers import build_params

__all__ = ["scene", "plots", "checks"]

_GROW, _SHRINK, _RHOMBUS = "#fdae6b", "#9ecae1", "#6a3d9a"


def _models(cfg):
    m = cfg["machine"]
    params = drive_params(cfg)
    keys = ("blade_thickness", "inner_radius", "outer_radius", "axial_width", "blades_per_pair")
    machine = build_params(rb.RotaryBlade, "machine", {k: m[k] for k in keys if k in m})
    roller = float((cfg.get("cam") or {}).get("roller_radius", 0.0) or 0.0)
    return params, machine, roller


def _law(params):
    return (params.psi_min, params.a, params.b)


def track_walls(params, roller, alpha):
    """The cam's pitch curve and the two walls of the roller track [mm], each (x, y).

    The walls are the pitch curve offset by the roller radius along its unit
    normal ``(y', -x')/|p'|`` (outwards for the counter-clockwise curve).
    """
    p, dp, _ = rc.profile_point(params.link_length, *_law(params), alpha)
    n = np.stack([dp[1], -dp[0]]) / np.hypot(dp[0], dp[1])
    return p * 1e3, (p - roller * n) * 1e3, (p + roller * n) * 1e3


def scene(result, cfg, frames: int = 120):
    """The converter and the working space over one output-shaft turn."""
    params, machine, roller = _models(cfg)
    alpha = frame_angles(2.0 * np.pi, frames)
    nf = len(alpha)
    b = SceneBuilder(alpha)
    law = _law(params)
    L, r = params.link_length * 1e3, roller * 1e3
    # --- the converter (axes x, y)
    pitch, inner, outer = track_walls(params, roller, np.linspace(0.0, 2.0 * np.pi, 361))
    if r > 0:
        b.static(
            trace(
                "line",
                "cam track (pitch +- roller radius)",
                "#404040",
                2,
                x=np.r_[inner[0], np.nan, outer[0]],
                y=np.r_[inner[1], np.nan, outer[1]],
                hoverinfo="skip",
            )
        )
    b.static(
        trace(
            "line",
            "cam pitch curve rho(alpha) (eq. 3)",
            GREY,
            1.5,
            x=pitch[0],
            y=pitch[1],
            hoverinfo="skip",
            line={"color": GREY, "width": 1.5, "dash": "dash"},
        )
    )
    v = rc.rhombus_vertices(params.link_length, *law, alpha) * 1e3  # (4, 2, F): A, B, C, D
    arm = np.stack([v[2], v[0]], axis=-1)  # C -> A, through O
    b.animated_trace(
        trace("line", "output-shaft arm (diagonal CA)", "#303030", 7), x=arm[0], y=arm[1]
    )
    mids = rc.blade_arm_points(params.link_length, *law, alpha) * 1e3  # AB, BC, CD, DA
    for name, (i, j), color in (
        ("blade arm, pair 1 (midpoints of AB, CD)", (0, 2), COLOR_1),
        ("blade arm, pair 2 (midpoints of DA, BC)", (3, 1), COLOR_2),
    ):
        seg = np.stack([mids[i], mids[j]], axis=-1)
        b.animated_trace(
            trace("line", name, color, 5, mode="lines+markers", marker={"size": 8}),
            x=seg[0],
            y=seg[1],
        )
    ring = np.concatenate([v, v[:1]], axis=0)  # A B C D A
    b.animated_trace(
        trace("line", f"rhombus ABCD, side 2l = {fmt(L)} mm", _RHOMBUS, 3),
        x=ring[:, 0].T,
        y=ring[:, 1].T,
    )
    rr = r if r > 0 else 0.04 * L
    rollers = [circle(v[k, 0], v[k, 1], rr, 24) for k in range(4)]
    b.animated_trace(
        trace("fill", "rollers at A, B, C, D", "#ffffff", edge=_RHOMBUS, edge_width=2),
        x=join(*[c[0] for c in rollers]),
        y=join(*[c[1] for c in rollers]),
    )
    out = 1.0 + (rr + 7.0) / np.maximum(np.hypot(v[:, 0], v[:, 1]), 1e-9)  # labels beyond
    b.animated_trace(
        trace("text", "vertex names", _RHOMBUS, 13),
        x=(v[:, 0] * out).T,
        y=(v[:, 1] * out).T,
        text=[["A", "B", "C", "D"]] * nf,
    )
    b.static(trace("markers", "O: shaft axis", "black", 9, legend=False, x=[0], y=[0]))
    # --- the working space (axes x2, y2)
    ri, ro = machine.inner_radius * 1e3, machine.outer_radius * 1e3
    bp, t = machine.blades_per_pair, machine.blade_thickness
    cas = circle(np.zeros(1), np.zeros(1), ro, 96)
    b.static(
        trace(
            "line",
            "casing",
            "#404040",
            2,
            on="2",
            legend=False,
            x=cas[0][0],
            y=cas[1][0],
            hoverinfo="skip",
        )
    )
    q, dq = rc.blade_angles(*law, alpha)[:2]  # (2, F)
    step = 2.0 * np.pi / bp * np.arange(bp)[None, :]
    # chamber 2m: pair 2 -> pair 1 (blade m); chamber 2m+1: pair 1 (m) -> pair 2 (m + 1)
    a0 = np.stack([q[1][:, None] + step, q[0][:, None] + step], 2).reshape(nf, 2 * bp)
    a1 = np.stack([q[0][:, None] + step, q[1][:, None] + step + 2.0 * np.pi / bp], 2)
    a1 = a1.reshape(nf, 2 * bp)
    polys = [sector(ri, ro, a0[:, j] + t / 2, a1[:, j] - t / 2, 16) for j in range(2 * bp)]
    dvol = rb.chamber_volume_derivative(machine, dq)  # (2B, F)
    for name, mask, color in (
        ("chamber growing", dvol > 0, _GROW),
        ("chamber shrinking", dvol <= 0, _SHRINK),
    ):
        b.animated_trace(
            trace("fill", name, color, on="2", edge_width=0.5),
            x=select([p[0] for p in polys], mask),
            y=select([p[1] for p in polys], mask),
        )
    for g, color in ((0, COLOR_1), (1, COLOR_2)):
        blades = [sector(ri, ro, q[g] + s - t / 2, q[g] + s + t / 2, 4) for s in step[0]]
        b.animated_trace(
            trace("fill", f"blades of pair {g + 1}", color, on="2", edge="black"),
            x=join(*[p[0] for p in blades]),
            y=join(*[p[1] for p in blades]),
        )
    hub = circle(np.zeros(1), np.zeros(1), ri, 96)
    b.static(
        trace(
            "fill",
            "hub",
            "#e0e0e0",
            on="2",
            legend=False,
            edge="#404040",
            edge_width=1.5,
            x=hub[0][0],
            y=hub[1][0],
        )
    )
    tip = 0.85 * ri * np.stack([np.cos(alpha), np.sin(alpha)])
    b.animated_trace(
        trace(
            "line",
            "output shaft (alpha)",
            "black",
            4,
            on="2",
            legend=False,
            mode="lines+markers",
            marker={"size": [0, 8]},
        ),
        x=np.stack([0 * alpha, tip[0]], 1),
        y=np.stack([0 * alpha, tip[1]], 1),
    )
    vol = rb.chamber_volumes(machine, q) * 1e6
    mid = 0.5 * (a0 + a1)
    rm = 0.5 * (ri + ro)
    b.animated_trace(
        trace("text", "chamber: number, volume", "#202020", 11, on="2"),
        x=rm * np.cos(mid),
        y=rm * np.sin(mid),
        text=[[f"{j + 1}<br>{vol[j, f]:.0f} cm3" for j in range(2 * bp)] for f in range(nf)],
    )
    lim1 = 1.15 * max(float(np.max(np.abs(outer))), L)
    lim2 = 1.1 * ro
    layout = panels(
        620,
        [
            ("", [0.0, 0.5], [-lim1, lim1], [-lim1, lim1], "x [mm]", "y [mm]"),
            ("2", [0.56, 1.0], [-lim2, lim2], [-lim2, lim2], "x [mm]", ""),
        ],
        [
            (0.0, "<b>Converter</b>: rhombus rolling on the fixed cam"),
            (0.56, "<b>Working space</b>: blades and chambers"),
        ],
    )
    psi = q[0] - q[1]
    readouts = [
        ("psi = phi_1 - phi_2", "deg", np.degrees(psi)),
        ("phi_1", "deg", np.degrees(q[0])),
        ("phi_2", "deg", np.degrees(q[1])),
        ("rho = OA", "mm", np.hypot(v[0, 0], v[0, 1])),
        ("chamber 1 volume", "cm3", vol[0]),
    ]
    caption = (
        "Drawn from the model: rhomboid_cam.profile_point (cam), rhombus_vertices, "
        "blade_arm_points, blade_angles, and rotary_blade.chamber_volumes. The output shaft "
        "turns uniformly with the diagonal OA; the blade pairs follow phi = alpha +- psi/2 "
        "(eq. 21). The cam track walls are the pitch curve offset by cam.roller_radius "
        f"= {fmt(r)} mm."
    )
    return b.build(layout, "alpha, output-shaft angle", readouts, caption)


def plots(result, cfg) -> list[Plot]:
    """SVAJ of the blade pairs, chambers, torque, p-V or work loop, cam, curvature, forces."""
    cols, s = result.columns, result.summary
    params, _, roller = _models(cfg)
    al, x_lab = cols["alpha_deg"], "output-shaft angle alpha [deg]"
    per = float(np.degrees(rc.period(params)))
    rpm = fmt(s.get("shaft_speed_mean_rpm", float("nan")))
    members = [
        (f"blade pair {k}", c, f"phi{k}_deg", f"blade_pair_{k}")
        for k, c in ((1, COLOR_1), (2, COLOR_2))
    ]
    vcols = sorted(c for c in cols if c.startswith("chamber") and c.endswith("_volume_cm3"))
    volumes = merge_identical([(f"chamber {c.split('_')[0][7:]}", cols[c]) for c in vcols])
    out = [
        svaj_plot(
            cols,
            al,
            x_lab,
            members,
            "rad",
            "Blade pairs: angle relative to the output "
            f"shaft, speed, acceleration, jerk at {rpm} rpm",
            per,
        ),
        lines_plot(
            "plot-chambers",
            "Chambers",
            al,
            x_lab,
            [("psi [deg]", [("psi (eq. 13)", cols["psi_deg"])]), ("volume [cm^3]", volumes)],
            "Angle between the blade axes and chamber volumes",
            per,
        ),
        torque_plot(
            cols,
            al,
            x_lab,
            [
                (
                    "blades [N*m]",
                    [
                        ("blade torque (virtual work)", cols["shaft_torque_Nm"]),
                        mean_trace(al, s.get("mean_torque_Nm", np.nan)),
                    ],
                )
            ],
            f"Torque on the output shaft at {rpm} rpm ({s.get('pressure_model')} model; "
            "positive: the blades drive the shaft)",
            per,
        ),
    ]
    if "chamber1_pressure_bar" in cols:
        pv = [("chamber 1", cols["chamber1_volume_cm3"], cols["chamber1_pressure_bar"], None)]
        out.append(
            Plot(
                "plot-pv",
                "p-V diagram",
                xy_figure(
                    pv,
                    "volume [cm^3]",
                    "pressure [bar]",
                    f"p-V diagram of chamber 1 ({s.get('pressure_model')} model)",
                    height=480,
                ),
            )
        )
    else:
        loop = [("blade torque M_1 (eq. 29)", cols["psi_deg"], cols["blade_torque_Nm"], None)]
        out.append(
            Plot(
                "plot-pv",
                "Work loop",
                xy_figure(
                    loop,
                    "psi [deg]",
                    "blade torque M_1 [N*m]",
                    "Work loop of the linear torque model: enclosed area = indicator work "
                    f"A = {fmt(s['indicator_work_J'])} J per half turn",
                    height=480,
                ),
                "The paper's torque model has no pressures; its work loop plays the "
                "role of the p-V diagram (eq. 27-28).",
            )
        )
    pitch, inner, outer = track_walls(params, roller, np.linspace(0.0, 2.0 * np.pi, 721))
    curves = [
        ("pitch curve (eq. 3)", pitch[0], pitch[1], {"line": {"dash": "dash", "color": GREY}})
    ]
    if roller > 0:
        curves += [
            ("track wall, inner", inner[0], inner[1], {"line": {"color": COLOR_1}}),
            ("track wall, outer", outer[0], outer[1], {"line": {"color": COLOR_2}}),
        ]
    out.append(
        Plot(
            "plot-cam",
            "Cam profile",
            xy_figure(
                curves,
                "x [mm]",
                "y [mm]",
                f"Cam: pitch curve and roller track (roller radius {fmt(roller * 1e3)} mm)",
                equal=True,
                height=600,
                legend_right=True,
            ),
            "The track walls are offset curves of the pitch curve; where the pitch curve bends "
            "tighter than the roller radius they would cross (undercut).",
        )
    )
    inv = np.full_like(al, 1.0 / roller if roller > 0 else np.nan)
    rows = [
        ("rho [mm]", [("polar radius rho = OA", cols["rho_mm"])]),
        (
            "curvature [1/m]",
            [
                ("curvature of the pitch curve", cols["curvature_per_m"]),
                ("+1/roller radius", inv),
                ("-1/roller radius", -inv),
            ],
        ),
    ]
    out.append(
        lines_plot(
            "plot-curvature",
            "Cam curvature",
            al,
            x_lab,
            rows,
            "Pitch curve: polar radius and signed curvature (negative: concave)",
            per,
        )
    )
    forces = force_plot(_distinct_forces(cols), al, x_lab, f"Forces in the converter's pairs "
                        f"at {rpm} rpm (blade loads and inertia)", per)  # fmt: skip
    if forces is not None:
        out.append(forces)
    return out


def _distinct_forces(cols) -> dict:
    """The pairs' force and stress columns, identical curves merged into one named for all.

    The half-turn symmetry makes the pairs at C, D copies of those at A, B (and a roller's
    pin carries its cam force): drawn one over the other they would hide each other.
    """
    out = {}
    for suffix in ("_force_N", "_contact_stress_MPa"):
        groups: list[list] = []
        for key, y in cols.items():
            if not key.endswith(suffix):
                continue
            y = np.asarray(y, dtype=float)
            for g in groups:
                if g[1].shape == y.shape and np.allclose(g[1], y, rtol=1e-9, atol=1e-9):
                    g[0].append(key[: -len(suffix)])
                    break
            else:
                groups.append([[key[: -len(suffix)]], y])
        out.update({"_=_".join(names) + suffix: y for names, y in groups})
    if "friction_torque_Nm" in cols:
        out["friction_torque_Nm"] = cols["friction_torque_Nm"]
    return out


def checks(result, cfg) -> list[Check]:
    """Cam curvature vs roller, law monotony, blade thickness, flywheel, contact stress."""
    s = result.summary
    params, machine, roller = _models(cfg)
    out = []
    r = roller * 1e3
    conc, conv = s.get("profile_concave_radius_min_mm"), s.get("profile_convex_radius_min_mm")
    for kind, rad in (("concave", conc), ("convex", conv)):
        if rad is None or not np.isfinite(rad) or r <= 0:
            continue
        margin = rad - r
        level = "error" if margin <= 0 else ("warning" if margin < 0.2 * r else "ok")
        text = (
            f"The tightest {kind} bend of the pitch curve has a radius of {fmt(rad)} mm, "
            f"the roller {fmt(r)} mm: "
        )
        text += (
            "the roller track would undercut there (its wall loops back)."
            if margin <= 0
            else f"a margin of only {fmt(margin)} mm."
            if level == "warning"
            else f"a margin of {fmt(margin)} mm."
        )
        out.append(Check(level, f"Cam {kind} curvature vs roller radius", text))
    if s.get("psi_monotone") is False:
        out.append(
            Check(
                "warning",
                "psi is not monotone between its extremes",
                "The law has extra stationary points: the chambers pause or reverse "
                "within a stroke.",
            )
        )
    else:
        out.append(
            Check(
                "ok",
                "psi law",
                f"psi runs monotonically between {fmt(s['psi_lowest_deg'])} "
                f"and {fmt(s['psi_highest_deg'])} deg (eq. 5, 6 hold).",
            )
        )
    t, tmax = s.get("blade_thickness_deg"), s.get("blade_thickness_max_deg")
    if t is not None and tmax is not None:
        out.append(
            Check(
                "warning" if t > 0.9 * tmax else "ok",
                "Blade thickness",
                f"Blades {fmt(t)} deg thick; the chambers close at {fmt(tmax)} deg "
                f"(psi_min): smallest chamber angle {fmt(tmax - t)} deg, compression "
                f"ratio {fmt(s.get('compression_ratio_geometric'))}.",
            )
        )
    lo, hi = s.get("blade_speed_coeff_min"), s.get("blade_speed_coeff_max")
    if lo is not None:
        stops = lo <= 0.0
        out.append(
            Check(
                "warning" if stops else "ok",
                "Blade speeds",
                f"The blades turn at {fmt(lo)} to {fmt(hi)} times the shaft speed"
                + (": they stop and reverse." if stops else ", never stopping."),
            )
        )
    return out + flywheel_checks(s, "the blades") + contact_checks(s, cfg)
