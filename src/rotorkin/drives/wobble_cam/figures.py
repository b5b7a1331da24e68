"""Figures of the wobble-plate + spherical-cam drive (Chen Hu et al. 2015, Fig. 8-10)
and of the twin-rotor engine built on it (chamber volumes, p-V diagram, shaft
torque with and without inertia, four-stroke timing: ours, the paper has none).

matplotlib.pyplot through :func:`rotorkin.render.figures.pyplot` (the command line
chooses the backend).
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis import pairs as pr
from rotorkin.analysis.engine_cycle import STROKE_NAMES, IdealCycle
from rotorkin.analysis.timing import shaft_speed
from rotorkin.analysis.torque import inertia_torque
from rotorkin.drives.wobble_cam import engine as eng
from rotorkin.drives.wobble_cam import forces as fo
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.render.figures import axes3d, draw, fixed_layout, plain_log_labels, pyplot, save_in

__all__ = [
    "plot_all",
    "figure_tasks",
    "fig_roller_trajectory",
    "fig_groove_centreline",
    "fig_chamber_angle",
    "fig_rotor_kinematics",
    "fig_chamber_volumes",
    "fig_pv_diagram",
    "fig_shaft_torque",
    "fig_four_stroke",
]

_ROLLER_COLOURS = ("C0", "C9", "C3", "C1")


def _closing_turns(params) -> float:
    """Shaft angle [rad] after which a groove in the cam frame closes (pi for n = -2)."""
    n2 = int(round(2.0 * params.spin_ratio))  # 2n, an integer
    for k in (1, 2, 4):  # k pi: 2 k pi in theta - psi, and k n pi in varphi must be 2 pi multiples
        if (k * n2) % 4 == 0:
            return k * np.pi
    return 4.0 * np.pi  # pragma: no cover


def _tag(params) -> str:
    return (
        f"phi = {np.degrees(params.plate_tilt):.4g} deg, "
        f"alpha = {np.degrees(params.roller_axis_angle):.4g} deg, "
        f"varphi = {params.spin_ratio:g} theta, psi = -theta"
    )


def _sphere(ax, r):
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 37), np.linspace(0, np.pi, 19))
    ax.plot_wireframe(
        r * np.cos(v),
        r * np.sin(v) * np.cos(u),
        r * np.sin(v) * np.sin(u),
        color="0.88",
        linewidth=0.3,
    )


def _four_views(fig, curves, radius_mm, title):
    """3D view + xy, xz, yz projections (paper Fig. 8/9 layout).

    curves : list of (xyz array (3, N) in mm, style dict).
    """
    ax3 = axes3d(fig, 2, 2, 1, title="(a) 3D view")
    _sphere(ax3, radius_mm)
    for p, style in curves:
        ax3.plot(p[0], p[1], p[2], **style)
    ax3.set_xlabel("x [mm]")
    ax3.set_ylabel("y [mm]")
    ax3.set_zlabel("z [mm]")
    ax3.set_box_aspect((1, 1, 1))
    lim = 1.05 * radius_mm
    for setter in (ax3.set_xlim, ax3.set_ylim, ax3.set_zlim):
        setter(-lim, lim)
    views = (
        (0, 1, "(b) z-axis view (xy plane)"),
        (0, 2, "(c) y-axis view (xz plane)"),
        (1, 2, "(d) x-axis view (yz plane)"),
    )
    for i, (a, b, sub) in enumerate(views):
        ax = fig.add_subplot(2, 2, i + 2)
        for p, style in curves:
            ax.plot(p[a], p[b], **style)
        ax.add_patch(pyplot().Circle((0, 0), radius_mm, fill=False, color="0.7", lw=0.6, ls=":"))
        ax.set_xlabel(f"{'xyz'[a]} [mm]")
        ax.set_ylabel(f"{'xyz'[b]} [mm]")
        ax.set_aspect("equal")
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.grid(True, alpha=0.4)
        ax.set_title(sub)
    fig.suptitle(title)
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=min(len(handles), 2))


def fig_roller_trajectory(params, outdir: Path, points: int = 1441) -> Path:
    """Fig. 8: trajectory of roller 1's centre in the fixed frame over one shaft turn."""
    plt = pyplot()
    turns = 1.0 if float(params.spin_ratio).is_integer() else 2.0
    theta = np.linspace(0.0, 2.0 * np.pi * turns, points)
    p = wc.roller_positions(params, theta)[0] * 1e3
    fig = plt.figure(figsize=(10, 9))
    _four_views(
        fig,
        [(p, {"color": "C0", "lw": 1.6, "label": "roller 1 centre (group 1)"})],
        params.sphere_radius * 1e3,
        f"Fig. 8  Roller trajectory in the fixed frame xyz\n{_tag(params)}",
    )
    fixed_layout(fig, 0.65, 0.95, 0.15, 0.91, 0.55, 0.8)  # the legend below
    return save_in(fig, outdir, "fig08_roller_trajectory.png")


def fig_groove_centreline(params, outdir: Path, points: int = 1441) -> Path:
    """Fig. 9: figure-eight groove centre-lines in the cam frame (roller 1 bold)."""
    plt = pyplot()
    theta = np.linspace(0.0, _closing_turns(params), points)
    g = wc.groove_points(params, theta) * 1e3
    names = (
        "roller 1 (group 1)",
        "roller 1' (group 1)",
        "roller 2 (group 2)",
        "roller 2' (group 2)",
    )
    curves = [(g[0], {"color": "C0", "lw": 2.0, "label": f"groove of {names[0]}"})]
    for k in (1, 2, 3):
        curves.append(
            (
                g[k],
                {
                    "color": _ROLLER_COLOURS[k],
                    "lw": 0.8,
                    "alpha": 0.45,
                    "label": f"groove of {names[k]}",
                },
            )
        )
    fig = plt.figure(figsize=(10, 9))
    _four_views(
        fig,
        curves,
        params.sphere_radius * 1e3,
        "Fig. 9  Figure-eight groove centre-lines in the cam frame x4y4z4\n" + _tag(params),
    )
    fixed_layout(fig, 0.65, 1.22, 0.15, 0.91, 0.55, 0.8)  # the legend below
    return save_in(fig, outdir, "fig09_groove_centreline.png")


def fig_chamber_angle(params, layout, outdir: Path, points: int = 1441) -> Path:
    """Fig. 10: chamber angles delta_A and delta_B over one shaft turn [deg]."""
    plt = pyplot()
    theta = np.linspace(0.0, 2.0 * np.pi, points)
    q = wc.rotor_angles(params, theta)[0]
    da, db = wc.chamber_angles(layout.piston_width, q[1] - q[0], pistons=params.pistons_per_rotor)
    fig, ax = plt.subplots(figsize=(9, 5))
    t = np.degrees(theta)
    ax.plot(t, np.degrees(da), color="C0", lw=1.8, label="chamber kind A, delta_A (eq. 19)")
    ax.plot(t, np.degrees(db), color="C1", lw=1.4, ls="--", label="chamber kind B, delta_B")
    lo, hi = (
        min(layout.chamber_a_min, layout.chamber_b_min),
        max(layout.chamber_a_max, layout.chamber_b_max),
    )
    for v in (lo, hi):
        ax.axhline(np.degrees(v), color="0.5", lw=0.7, ls=":")
    ax.text(
        2,
        np.degrees(hi) + 1.0,
        f"swing {np.degrees(layout.swing):.2f} deg, beta = {np.degrees(layout.piston_width):.2f}"
        f" deg, eps_A = {layout.compression_ratio_a:.3g}, eps_B = {layout.compression_ratio_b:.3g}",
        fontsize=9,
    )
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.set_ylim(0, np.degrees(hi) + 14.0)
    ax.set_xlabel("shaft angle theta [deg]")
    ax.set_ylabel("chamber angle delta [deg]")
    ax.set_title("Fig. 10  Angle between neighbouring pistons vs shaft angle\n" + _tag(params))
    ax.grid(True, alpha=0.4)
    ax.legend(loc="upper right", ncol=2, fontsize=9)
    fixed_layout(fig, 0.7, 0.6, 0.3, 0.58)
    return save_in(fig, outdir, "fig10_chamber_angle.png")


def fig_rotor_kinematics(params, outdir: Path, points: int = 2881) -> Path:
    """Rotor angles relative to their mean motion and the 3 kinematic coefficients."""
    plt = pyplot()
    theta = np.linspace(0.0, 2.0 * np.pi, points)
    q, d1, d2, d3 = wc.rotor_angles(params, theta)
    mean = 1.0 + params.spin_ratio
    coef = "" if abs(mean) == 1.0 else f"{abs(mean):g} "
    rel = f"Phi {'-' if mean >= 0 else '+'} {coef}theta [deg]"
    t = np.degrees(theta)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    panels = (
        (np.degrees(q - mean * theta), rel, "(a) relative angle"),
        (d1, "dPhi/dtheta [-]", "(b) speed ratio"),
        (d2, "d2Phi/dtheta2 [1/rad]", "(c) acceleration coefficient"),
        (d3, "d3Phi/dtheta3 [1/rad^2]", "(d) jerk coefficient"),
    )
    for ax, (y, label, sub) in zip(axes.flat, panels, strict=True):
        ax.plot(t, y[0], color="C0", lw=1.5, label="rotor 1")
        ax.plot(t, y[1], color="C3", lw=1.2, ls="--", label="rotor 2")
        ax.set_ylabel(label)
        ax.set_title(sub)
        ax.grid(True, alpha=0.4)
        ax.set_xlim(0, 360)
        ax.set_xticks(np.arange(0, 361, 45))
    for ax in axes[1]:
        ax.set_xlabel("shaft angle theta [deg]")
    axes[0, 0].legend(loc="center right")
    fig.suptitle("Rotor kinematics (exact closed forms)\n" + _tag(params))
    fixed_layout(fig, 0.85, 0.6, 0.3, 0.91, 0.85, 0.45)
    return save_in(fig, outdir, "fig_rotor_kinematics.png")


# --------------------------------------------------------------------------------------------
# the engine
# --------------------------------------------------------------------------------------------
_STROKE_COLOURS = (
    "#9ecae1",
    "#fdd0a2",
    "#fc9272",
    "#d9d9d9",
)  # intake, compression, power, exhaust


def _xaxis(ax, end_deg, label=True):
    ax.set_xlim(0, end_deg)
    step = 45 if end_deg <= 360 else 90
    ax.set_xticks(np.arange(0, end_deg + 1, step))
    ax.grid(True, alpha=0.4)
    if label:
        ax.set_xlabel("shaft angle theta [deg]")


def _engine_tag(params, machine, cycle) -> str:
    if machine.section == "rectangular":
        sec = (
            f"annulus {machine.inner_radius * 1e3:.4g}/{machine.outer_radius * 1e3:.4g} mm x "
            f"{machine.axial_width * 1e3:.4g} mm"
        )
    else:
        sec = (
            f"torus R_m {machine.mean_radius * 1e3:.4g} mm, d {machine.section_diameter * 1e3:.4g}"
            " mm"
        )
    return (
        f"N = {machine.pistons_per_rotor} pistons/rotor, {sec}, "
        f"V_c = {machine.clearance_volume * 1e6:.3g} cm^3, eps = {machine.compression_ratio:g}, "
        + _cycle_tag(cycle)
    )


def _cycle_tag(cycle) -> str:
    if isinstance(cycle, IdealCycle):
        return f"n = {cycle.polytropic_exponent:g}, Q = {cycle.heat_per_cycle:.4g} J"
    lo = cycle.loads
    return (
        f"fuel-air, phi = {lo.equivalence_ratio:g}, p_i = {lo.intake_pressure / 1e5:.3g} bar, "
        f"burn {np.degrees(lo.burn_start):.3g}+{np.degrees(lo.burn_duration):.3g} deg"
    )


def _stroke_bands(ax, theta_deg, stroke, alpha=0.35, labels=True):
    """Shade the strokes of one chamber along the x axis."""

    edges = np.flatnonzero(np.diff(stroke)) + 1
    starts = np.concatenate([[0], edges])
    ends = np.concatenate([edges, [len(stroke) - 1]])
    seen = set()
    for a, b in zip(starts, ends, strict=True):
        k = int(stroke[a])
        label = STROKE_NAMES[k] if labels and k not in seen else None
        seen.add(k)
        ax.axvspan(
            theta_deg[a], theta_deg[b], color=_STROKE_COLOURS[k], alpha=alpha, lw=0, label=label
        )


def fig_chamber_volumes(params, layout, machine, cycle, outdir: Path, points: int = 2881) -> Path:
    """Chamber volumes of both kinds and dV/dtheta over one turn; chamber 1 strokes shaded."""

    plt = pyplot()
    theta = np.linspace(0.0, 2.0 * np.pi, points)
    ch = eng.chambers(params, machine, theta, layout)
    stroke = eng.strokes(params, machine, theta)[0]
    t = np.degrees(theta)
    v_min, v_max = eng.volume_limits(machine, layout)
    fig, (ax, ax2) = plt.subplots(
        2, 1, figsize=(10, 7.5), sharex=True, gridspec_kw={"height_ratios": (3, 2)}
    )
    _stroke_bands(ax, t, stroke)
    ax.plot(t, ch.volume[0] * 1e6, color="C0", lw=2.0, label="kind A (chambers 1, 3, ...)")
    ax.plot(t, ch.volume[1] * 1e6, color="C3", lw=1.6, ls="--", label="kind B (chambers 2, 4, ...)")
    for v in (v_min[0], v_max[0]):
        ax.axhline(v * 1e6, color="0.4", lw=0.7, ls=":")
    eps_a, eps_b = eng.compression_ratio_geometric(machine, layout)
    ax.set_title(
        f"(a) V_max = {v_max.max() * 1e6:.2f} cm^3, V_min = {v_min.min() * 1e6:.2f} cm^3, "
        f"swept {eng.swept_volume(machine, layout) * 1e6:.2f} cm^3 per stroke,\n"
        f"eps_geo A/B = {eps_a:.3g}/{eps_b:.3g}, "
        f"displacement {eng.displacement_per_rev(params, machine, layout) * 1e6:.0f} cm^3/rev; "
        "shading: strokes of chamber 1",
        fontsize=9,
    )
    ax.set_ylim(0, v_max.max() * 1e6 * 1.32)
    ax.set_ylabel("chamber volume V [cm^3]")
    ax.legend(loc="upper center", ncol=6, fontsize=8)
    _xaxis(ax, 360, label=False)
    ax2.plot(t, ch.dvolume[0] * 1e6, color="C0", lw=1.8, label="dV_A/dtheta")
    ax2.plot(t, ch.dvolume[1] * 1e6, color="C3", lw=1.4, ls="--", label="dV_B/dtheta")
    ax2.axhline(0, color="0.3", lw=0.6)
    ax2.set_ylabel("dV/dtheta [cm^3/rad]")
    ax2.set_title("(b) exact derivatives", fontsize=9)
    ax2.legend(loc="upper right", fontsize=8)
    _xaxis(ax2, 360)
    fig.suptitle(
        "Chamber volumes over one shaft turn\n" + _engine_tag(params, machine, cycle), fontsize=10
    )
    fixed_layout(fig, 0.9, 0.6, 0.3, 0.98, 0.0, 0.42)
    return save_in(fig, outdir, "fig_chamber_volumes.png")


def fig_pv_diagram(params, layout, machine, cycle, outdir: Path, points: int = 4001) -> Path:
    """p-V diagram of one four-stroke cycle of chamber 1 (kind A) and 2 (kind B), lin and log."""

    plt = pyplot()
    span = 2.0 * np.pi / abs(params.spin_ratio)  # four strokes
    theta = np.linspace(0.0, span, points)
    st = eng.engine_state(params, machine, cycle, theta)
    v_min, v_max = eng.volume_limits(machine, layout)
    eps_a, eps_b = eng.compression_ratio_geometric(machine, layout)
    ideal = isinstance(cycle, IdealCycle)
    work = (ec.indicated_work(cycle, v_max[:2], v_min[:2]) if ideal
            else [cycle.work_of_kind(0), cycle.work_of_kind(1)])  # fmt: skip
    exhaust = cycle.ambient_pressure if ideal else cycle.loads.ambient_pressure
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.2))
    for ax, log in zip(axes, (False, True), strict=True):
        for j, style in (
            (0, {"color": "C0", "lw": 2.0}),
            (1, {"color": "C3", "lw": 1.3, "ls": "--"}),
        ):
            ax.plot(
                st.chambers.volume[j] * 1e6,
                st.pressure[j] / 1e5,
                label=f"chamber {j + 1} (kind {'AB'[j]}), W = {work[j]:.2f} J",
                **style,
            )
        if log:
            ax.set_xscale("log")
            ax.set_yscale("log")
            plain_log_labels(ax)
        ax.axhline(exhaust / 1e5, color="0.5", lw=0.7, ls=":")
        ax.set_xlabel("chamber volume V [cm^3]")
        ax.set_ylabel("absolute pressure p [bar]")
        ax.grid(True, which="both" if log else "major", alpha=0.35)
    ax = axes[0]
    if ideal:
        p2 = ec.compression_end_pressure(cycle, v_max[0], v_min[0]) / 1e5
        p3 = ec.peak_pressure(cycle, v_max[0], v_min[0]) / 1e5
        p4 = ec.expansion_end_pressure(cycle, v_max[0], v_min[0]) / 1e5
        marks = (
            (v_min[0], p2, "2: end of compression"),
            (v_min[0], p3, "3: after heat Q"),
            (v_max[0], p4, "4: end of expansion"),
            (v_max[0], exhaust / 1e5, "1: BDC"),
        )
        text = (f"eps_geo A/B = {eps_a:.3g}/{eps_b:.3g}\np_peak = {p3:.1f} bar\n"
                f"efficiency = {float(ec.otto_efficiency(eps_a, cycle.polytropic_exponent)):.3f} "
                f"(Otto, n = {cycle.polytropic_exponent:g})")  # fmt: skip
    else:
        summ = cycle.summary(1.0)
        j = int(np.argmax(st.pressure[0]))
        p3 = summ["peak_pressure_bar"]
        marks = ((st.chambers.volume[0, j], st.pressure[0, j] / 1e5,
                  f"peak {summ['peak_pressure_angle_deg']:.3g} deg after TDC"),)  # fmt: skip
        text = (f"eps_geo A/B = {eps_a:.3g}/{eps_b:.3g}\np_peak = {p3:.1f} bar, "
                f"T_peak = {summ['peak_temperature_K']:.0f} K\n"
                f"indicated efficiency = {summ['indicated_efficiency']:.3f}\n"
                f"gas: {summ['gas_properties']}")  # fmt: skip
    for x, y, label in marks:
        ax.plot([x * 1e6], [y], "ko", ms=4)
        ax.annotate(label, (x * 1e6, y), textcoords="offset points", xytext=(8, 4), fontsize=8)
    ax.text(
        0.45,
        0.62,
        text,
        transform=ax.transAxes,
        fontsize=9,
        bbox={"facecolor": "white", "alpha": 0.85, "edgecolor": "0.7"},
    )
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title("(a) linear axes")
    axes[1].set_title(
        "(b) logarithmic axes: polytropes are straight lines" if ideal else "(b) logarithmic axes"
    )
    fig.suptitle(
        f"p-V diagram, {'ideal' if ideal else 'fuel-air'} four-stroke cycle\n"
        + _engine_tag(params, machine, cycle),
        fontsize=10,
    )
    fixed_layout(fig, 0.75, 0.62, 0.15, 0.85, 1.75)
    return save_in(fig, outdir, "fig_pv_diagram.png")


def fig_shaft_torque(
    params, layout, machine, cycle, speed, outdir: Path, points: int = 2881
) -> Path:
    """Shaft torque without and with inertia, the inertia torque and the rotors' gas torques."""

    plt = pyplot()
    theta = np.linspace(0.0, 2.0 * np.pi, points)
    st = eng.engine_state(params, machine, cycle, theta)
    m = st.chambers.motion
    w = shaft_speed(theta, speed, 2.0 * np.pi)
    t_in = inertia_torque(machine.inertia_shaft, machine.member_inertias, m.dq, m.d2q, w[0], w[1])
    net = st.shaft_torque - t_in
    mean = eng.indicated_work_per_rev(params, machine, cycle, layout) / (2.0 * np.pi)
    t = np.degrees(theta)
    rpm = float(np.mean(w[0])) * 30.0 / np.pi
    fig, axes = plt.subplots(3, 1, figsize=(10, 10), sharex=True)
    ax = axes[0]
    ax.plot(t, st.shaft_torque, color="C0", lw=1.8, label="gas torque on the shaft (no inertia)")
    ax.axhline(mean, color="C2", lw=1.2, ls="--", label=f"mean {mean:.1f} N m")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel("torque [N m]")
    ax.set_title("(a) shaft torque from the chamber pressures, sum M_i dPhi_i/dtheta")
    ax.legend(loc="upper right", fontsize=8)
    _xaxis(ax, 360, label=False)
    ax = axes[1]
    ax.plot(t, net, color="C3", lw=1.6, label="with inertia: gas - inertia torque")
    ax.plot(t, t_in, color="C1", lw=1.0, ls=":", label="inertia torque of shaft and rotors")
    ax.plot(t, st.shaft_torque, color="C0", lw=1.0, alpha=0.7, label="without inertia")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel("torque [N m]")
    ax.set_title(
        f"(b) at {rpm:.0f} rpm (mean), J_rotor = {machine.inertia_rotor_1:g}/"
        f"{machine.inertia_rotor_2:g} kg m^2, J_shaft = {machine.inertia_shaft:g} kg m^2"
    )
    ax.legend(loc="upper right", fontsize=8)
    _xaxis(ax, 360, label=False)
    ax = axes[2]
    ax.plot(t, st.member_torque[0], color="C0", lw=1.6, label="gas torque on rotor 1, M_1")
    ax.plot(t, st.member_torque[1], color="C3", lw=1.2, ls="--", label="gas torque on rotor 2, M_2")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel("torque [N m]")
    ax.set_title("(c) member torques M_i = sum_j p_j dV_j/dPhi_i (M_1 = -M_2)")
    ax.legend(loc="upper right", fontsize=8)
    _xaxis(ax, 360)
    fig.suptitle("Shaft torque over one turn\n" + _engine_tag(params, machine, cycle), fontsize=10)
    fixed_layout(fig, 1.0, 0.6, 0.3, 0.85, 0.0, 0.42)
    return save_in(fig, outdir, "fig_shaft_torque.png")


def fig_four_stroke(params, layout, machine, cycle, outdir: Path, points: int = 2881) -> Path:
    """Four-stroke timing of every chamber over one shaft turn and the chamber pressures."""

    plt = pyplot()
    theta = np.linspace(0.0, 2.0 * np.pi, points)
    st = eng.engine_state(params, machine, cycle, theta)
    t = np.degrees(theta)
    nch = machine.chambers
    fig, (ax, ax2) = plt.subplots(
        2,
        1,
        figsize=(11, 3.5 + 0.35 * nch + 3.0),
        sharex=True,
        gridspec_kw={"height_ratios": (3.5, 1.0 + 0.35 * nch)},
    )
    # chambers of one kind whose indices differ by 2 run in phase: one curve per group
    groups = {}
    for j in range(nch):
        groups.setdefault((j % 2, (j // 2) % 2), []).append(j)
    for i, members in enumerate(groups.values()):
        names = ", ".join(str(j + 1) for j in members)
        ax.plot(
            t,
            st.pressure[members[0]] / 1e5,
            lw=2.0 if i == 0 else 1.3,
            color=f"C{i}",
            label=f"chambers {names} ({'AB'[members[0] % 2]})",
        )
    ax.set_ylabel("absolute pressure p [bar]")
    ax.set_title("(a) chamber pressures (chambers listed together run in phase)")
    ax.set_ylim(0, ax.get_ylim()[1] * 1.15)
    ax.legend(loc="upper center", ncol=4, fontsize=8)
    _xaxis(ax, 360, label=False)
    for j in range(nch):
        s = st.stroke[j]
        edges = np.flatnonzero(np.diff(s)) + 1
        starts = np.concatenate([[0], edges])
        ends = np.concatenate([edges, [len(s) - 1]])
        for a, b in zip(starts, ends, strict=True):
            k = int(s[a])
            ax2.broken_barh(
                [(t[a], t[b] - t[a])],
                (nch - j - 0.4, 0.8),
                facecolors=_STROKE_COLOURS[k],
                edgecolors="0.3",
                linewidth=0.4,
            )
            if t[b] - t[a] > 20:
                ax2.text(
                    0.5 * (t[a] + t[b]),
                    nch - j,
                    STROKE_NAMES[k],
                    ha="center",
                    va="center",
                    fontsize=7,
                )
    ax2.set_yticks(np.arange(nch, 0, -1))
    ax2.set_yticklabels([f"{j + 1} ({'AB'[j % 2]})" for j in range(nch)])
    ax2.set_ylim(0.4, nch + 0.6)
    ax2.set_ylabel("chamber")
    ax2.set_title(
        f"(b) four-stroke timing: {machine.pistons_per_rotor // 2} chambers on the power stroke "
        f"at every instant, {wc.power_strokes_per_rev(params)} power strokes per turn"
    )
    _xaxis(ax2, 360)
    fig.suptitle("Four-stroke assignment\n" + _engine_tag(params, machine, cycle), fontsize=10)
    fixed_layout(fig, 0.85, 0.6, 0.3, 0.85, 0.0, 0.45)
    return save_in(fig, outdir, "fig_four_stroke.png")


def fig_forces(f: fo.Forces, plist, fp: fo.ForceParams, model, outdir: Path) -> Path:
    """Forces over the turn: grooves and rails, bearings, gearbox; groove contact stress."""
    plt = pyplot()
    t = np.degrees(f.theta)
    fig, axes = plt.subplots(4, 1, figsize=(10, 13), sharex=True)
    by = {p.slug: p for p in plist}
    ax = axes[0]
    for j, name in enumerate(fo._NAMES):
        ax.plot(t, f.groove_force[j], color=f"C{j}", lw=1.3, label=f"groove, roller {name} (N)")
        ax.plot(
            t, f.rail_force[j], color=f"C{j}", lw=1.0, ls="--", label=f"rail, roller {name} (F)"
        )
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel("force [N]")
    ax.set_title("(a) rollers: groove force N (+: cam pushes along +n, -n wall) and rail force F "
                 "(+: drives the rotor)", fontsize=9)  # fmt: skip
    ax.legend(loc="upper right", fontsize=7, ncol=4)
    _xaxis(ax, 360, label=False)
    ax = axes[1]
    for slug in _BEARINGS:
        ax.plot(t, by[slug].force, lw=1.2, label=by[slug].name)
    ax.set_ylabel("force [N]")
    ax.set_title("(b) bearing loads (the plate's couple includes its gyroscopic one)", fontsize=9)
    ax.legend(loc="upper right", fontsize=7)
    _xaxis(ax, 360, label=False)
    ax = axes[2]
    ax.plot(t, f.torque_shaft_plate, color="C0", lw=1.4, label="plate on Z-shaft, T_Z")
    ax.plot(t, f.torque_cam_grooves, color="C3", lw=1.4, label="grooves on cam shell, T_C")
    ax.plot(t, f.output_shaft, color="C0", lw=1.0, ls="--", label="Z-shaft output")
    ax.plot(t, f.output_cam, color="C3", lw=1.0, ls="--", label="cam shell output")
    ax.plot(t, f.gearbox_torque, color="C2", lw=1.0, ls=":", label="gearbox on cam shell, G")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_ylabel("torque [N m]")
    ax.set_title(f"(c) torque split, drive.output = {fp.output!r}; bevel mesh force peaks at "
                 f"{np.max(f.mesh_force):.0f} N", fontsize=9)  # fmt: skip
    ax.legend(loc="upper right", fontsize=7, ncol=3)
    _xaxis(ax, 360, label=False)
    ax = axes[3]
    for j, slug in enumerate(fo._SLUGS):
        for stem, ls in (("groove", "-"), ("rail", "--")):
            s = pr.stress(by[f"{stem}{slug}"], model)
            ax.plot(t, s / 1e6, color=f"C{j}", lw=1.1, ls=ls, label=f"{stem} {fo._NAMES[j]}")
    ax.axhline(model.allowable_stress / 1e6, color="k", lw=0.8, ls="-.", label="allowable")
    ax.set_ylabel("Hertz pressure [MPa]")
    ax.set_title("(d) contact stress of the rollers on the groove walls and rails", fontsize=9)
    ax.legend(loc="upper right", fontsize=7, ncol=5)
    _xaxis(ax, 360)
    fig.suptitle("Forces in the pairs of the wobble-cam drive over one turn", fontsize=10)
    fixed_layout(fig, 1.05, 0.6, 0.3, 0.62, 0.0, 0.38)
    return save_in(fig, outdir, "forces.png")


_BEARINGS = ("plate_bearing_a", "plate_bearing_b", "cam_bearing_a", "cam_bearing_b",
             "bevel_idler_bearing")  # fmt: skip


def figure_tasks(params, layout, outdir: Path, machine=None, cycle=None, speed=None) -> list:
    """The figures of :func:`plot_all` as tasks for :func:`rotorkin.render.figures.draw`.

    Each task draws one figure into ``outdir`` and returns its path; the list is in the
    order of :func:`plot_all`'s paths.
    """
    outdir = Path(outdir)
    p = functools.partial
    tasks = [
        p(fig_roller_trajectory, params, outdir),
        p(fig_groove_centreline, params, outdir),
        p(fig_chamber_angle, params, layout, outdir),
        p(fig_rotor_kinematics, params, outdir),
    ]
    if machine is not None:
        cycle = IdealCycle() if cycle is None else cycle
        speed = 100.0 * np.pi if speed is None else speed
        tasks += [
            p(fig_chamber_volumes, params, layout, machine, cycle, outdir),
            p(fig_pv_diagram, params, layout, machine, cycle, outdir),
            p(fig_shaft_torque, params, layout, machine, cycle, speed, outdir),
            p(fig_four_stroke, params, layout, machine, cycle, outdir),
        ]
    return tasks


def plot_all(params, layout, outdir: Path, machine=None, cycle=None, speed=None) -> list[Path]:
    """Write Fig. 8, 9, 10, the rotor kinematics and (with a machine) the engine figures.

    Parameters
    ----------
    params : WobbleCam
    layout : PistonLayout
    outdir : Path
    machine : TwinRotor, optional
    cycle : IdealCycle, optional
    speed : float or list of float, optional
        Shaft speed [rad/s] (default 3000 rpm).
    """
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return draw(figure_tasks(params, layout, outdir, machine, cycle, speed))
