"""Figures of the wobble-plate + spherical-cam drive (Chen Hu et al. 2015, Fig. 8-10).

matplotlib is imported lazily inside the functions (Agg backend).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.drives import wobble_cam as wc

__all__ = [
    "plot_all",
    "fig_roller_trajectory",
    "fig_groove_centreline",
    "fig_chamber_angle",
    "fig_rotor_kinematics",
]

_DPI = 120
_ROLLER_COLOURS = ("C0", "C9", "C3", "C1")


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


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
    ax3 = fig.add_subplot(2, 2, 1, projection="3d")
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
    ax3.set_title("(a) 3D view")
    views = (
        (0, 1, "(b) z-axis view (xy plane)"),
        (0, 2, "(c) y-axis view (xz plane)"),
        (1, 2, "(d) x-axis view (yz plane)"),
    )
    for i, (a, b, sub) in enumerate(views):
        ax = fig.add_subplot(2, 2, i + 2)
        for p, style in curves:
            ax.plot(p[a], p[b], **style)
        ax.add_patch(_plt().Circle((0, 0), radius_mm, fill=False, color="0.7", lw=0.6, ls=":"))
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
    plt = _plt()
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
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    path = Path(outdir) / "fig08_roller_trajectory.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path


def fig_groove_centreline(params, outdir: Path, points: int = 1441) -> Path:
    """Fig. 9: figure-eight groove centre-lines in the cam frame (roller 1 bold)."""
    plt = _plt()
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
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    path = Path(outdir) / "fig09_groove_centreline.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path


def fig_chamber_angle(params, layout, outdir: Path, points: int = 1441) -> Path:
    """Fig. 10: chamber angles delta_A and delta_B over one shaft turn [deg]."""
    plt = _plt()
    theta = np.linspace(0.0, 2.0 * np.pi, points)
    q = wc.rotor_angles(params, theta)[0]
    da, db = wc.chamber_angles(q[1] - q[0], layout.piston_width)
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
    fig.tight_layout()
    path = Path(outdir) / "fig10_chamber_angle.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path


def fig_rotor_kinematics(params, outdir: Path, points: int = 2881) -> Path:
    """Rotor angles relative to their mean motion and the 3 kinematic coefficients."""
    plt = _plt()
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
    fig.tight_layout()
    path = Path(outdir) / "fig_rotor_kinematics.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path


def plot_all(params, layout, outdir: Path) -> list[Path]:
    """Write Fig. 8, 9, 10 and the rotor kinematics figure into ``outdir``; return the paths."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return [
        fig_roller_trajectory(params, outdir),
        fig_groove_centreline(params, outdir),
        fig_chamber_angle(params, layout, outdir),
        fig_rotor_kinematics(params, outdir),
    ]
