"""Figure of the wobble drive's spherical cam: grooves, walls, pressure angle, curvature.

One figure, ``fig_spherical_cam.png`` (ours; the paper shows only the centre-line,
Fig. 9): (a) the sphere with the grooves' centre-lines, their wall edges on the
shell's inner surface and the crossings; (b) the same unrolled around the cam axis;
(c) the pressure angle of each roller over a shaft turn; (d) the undercut limit of the
roller radius along each groove against the roller radius.

matplotlib.pyplot through :func:`rotorkin.render.figures.pyplot`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.drives.wobble_cam import cam as sph
from rotorkin.render.figures import axes3d, fixed_layout, plain_log_labels, pyplot, save_in

__all__ = ["plot_spherical_cam"]

_COLOURS = ("C0", "C9", "C3", "C1")
#: Rollers 1', 2' dashed on top of 1, 2 (a group's two rollers often coincide).
_STYLE = ({"lw": 2.2}, {"lw": 1.1, "ls": "--"}, {"lw": 2.2}, {"lw": 1.1, "ls": "--"})


def _unrolled(p):
    """Angle about the cam axis x [deg] (from +z towards +y) and axial position x (p's unit)."""
    return np.degrees(np.arctan2(p[1], p[2])), p[0]


def _break_wraps(a, x):
    """Insert NaN where the angle jumps by more than 180 deg (plot without wrap lines)."""
    jump = np.flatnonzero(np.abs(np.diff(a)) > 180.0)
    return np.insert(a, jump + 1, np.nan), np.insert(x, jump + 1, np.nan)


def plot_spherical_cam(source, outdir, cam=None, points: int = 1441) -> list[Path]:
    """Draw the spherical cam of a wobble-cam drive.

    Parameters
    ----------
    source : dict or WobbleCam
        A validated wobble-cam config (SI; the cam comes from its ``[cam]`` section)
        or the drive's parameters.
    outdir : path-like
        Existing folder.
    cam : SphericalCam, optional
        Needed when ``source`` is a WobbleCam.
    points : int, optional
        Shaft angles per groove period.

    Returns
    -------
    list of Path
        ``[outdir / "fig_spherical_cam.png"]``.
    """
    if isinstance(source, dict):
        drive, cam = sph.from_config(source)
    else:
        drive = source
        if cam is None:
            raise TypeError("plot_spherical_cam(drive, outdir, cam=...) needs the SphericalCam")
    plt = pyplot()
    period = sph.groove_period(drive)
    theta = np.linspace(0.0, period, points)
    g = sph.groove_derivatives(drive, theta)[0] * 1e3
    walls = sph.groove_walls(drive, cam, theta, cam.inner_radius) * 1e3
    crossings = sph.groove_crossings(drive)
    distinct = sph.distinct_grooves(drive)
    info = sph.shape_summary(drive, cam)
    names = sph.ROLLER_NAMES

    fig = plt.figure(figsize=(13, 10.5))
    # (a) sphere
    ax = axes3d(
        fig,
        2,
        2,
        1,
        title="(a) grooves in the cam frame: centre-lines (r) and walls (R_i); x: crossing",
    )
    r = drive.sphere_radius * 1e3
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 37), np.linspace(0, np.pi, 19))
    ax.plot_wireframe(
        r * np.cos(v), r * np.sin(v) * np.cos(u), r * np.sin(v) * np.sin(u), color="0.88", lw=0.3
    )
    for i in distinct:
        ax.plot(*g[i], color=_COLOURS[i], lw=1.4, label=f"groove of roller {names[i]}")
        for side in (0, 1):
            ax.plot(*walls[i, side], color=_COLOURS[i], lw=0.5, alpha=0.6)
    for c in crossings:
        ax.scatter(*(c.point * 1e3), color="k", marker="x", s=40, depthshade=False)
    lim = 1.05 * r
    for setter in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        setter(-lim, lim)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x4 [mm]")
    ax.set_ylabel("y4 [mm]")
    ax.set_zlabel("z4 [mm]")

    # (b) unrolled
    ax = fig.add_subplot(2, 2, 2)
    for i in distinct:
        ax.plot(*_break_wraps(*_unrolled(g[i])), color=_COLOURS[i], lw=1.4)
        for side in (0, 1):
            ax.plot(*_break_wraps(*_unrolled(walls[i, side])), color=_COLOURS[i], lw=0.6)
    for k, c in enumerate(crossings):
        a, x = _unrolled(c.point * 1e3)
        ax.plot(a, x, "kx", ms=8, mew=1.5, label="crossing (cut through)" if k == 0 else None)
        ax.annotate(
            f"{np.degrees(c.angle):.1f} deg",
            (a, x),
            textcoords="offset points",
            xytext=(6, 6),
            fontsize=8,
        )
    ax.set_xlim(-180, 180)
    ax.set_xticks(np.arange(-180, 181, 45))
    ax.set_xlabel("angle about the cam axis x4, from z4 towards y4 [deg]")
    ax.set_ylabel("axial position x4 [mm]")
    ax.set_title("(b) unrolled: centre-lines and wall edges on the inner surface")
    ax.grid(True, alpha=0.4)
    if crossings:
        ax.legend(loc="upper right", fontsize=8)

    # (c) pressure angle over a shaft turn
    ax = fig.add_subplot(2, 2, 3)
    turn = np.linspace(0.0, 2.0 * np.pi, 1441)
    mu = np.degrees(sph.pressure_angle(drive, turn))
    t = np.degrees(turn)
    for i in range(4):
        ax.plot(t, mu[i], color=_COLOURS[i], **_STYLE[i], label=f"roller {names[i]}")
    ax.plot(t, mu.min(axis=0), color="k", lw=1.6, ls="--", label="best roller (min of 4)")
    for c in crossings:
        for k, i in enumerate(c.rollers):
            at = c.shaft_angles(k)
            ax.plot(np.degrees(at), np.degrees(sph.pressure_angle(drive, at)[i]), "kx", ms=7)
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.set_ylim(0, 95)
    ax.set_xlabel("shaft angle theta [deg]")
    ax.set_ylabel("pressure angle [deg]")
    ax.set_title(
        "(c) pressure angle: wall normal vs roller velocity relative to the shaft\n"
        f"max {info['cam_pressure_angle_max_deg']:.1f} deg; best roller at most "
        f"{info['cam_pressure_angle_best_roller_max_deg']:.1f} deg; x: roller at a crossing"
    )
    ax.grid(True, alpha=0.4)
    ax.legend(loc="upper right", fontsize=8, ncol=3)

    # (d) undercut limit vs roller radius
    ax = fig.add_subplot(2, 2, 4)
    lim_r = sph.roller_radius_limit(drive, turn, cam.inner_radius) * 1e3
    rad_c = sph.curvature_radius(drive, turn)[0] * 1e3
    for i in range(4):
        ax.plot(t, lim_r[i], color=_COLOURS[i], **_STYLE[i], label=f"limit, roller {names[i]}")
    ax.plot(t, rad_c, color="0.4", lw=0.9, ls=":", label="1/|kappa_g| on r, roller 1")
    ax.axhline(cam.roller_radius * 1e3, color="k", lw=1.8, label="roller radius")
    ax.set_yscale("log")
    plain_log_labels(ax, "y")
    low = 0.5 * min(float(lim_r.min()), cam.roller_radius * 1e3)
    ax.set_ylim(low, 3.0 * float(lim_r.max()))
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.set_xlabel("shaft angle theta [deg]")
    ax.set_ylabel("radius [mm]")
    ax.set_title(
        "(d) undercut limit of the roller radius, R_i / sqrt(1 + (r kappa_g)^2)\n"
        f"min {info['cam_roller_radius_limit_mm']:.2f} mm at theta = "
        f"{info['cam_curvature_min_theta_deg']:.1f} deg, where 1/|kappa_g| = "
        f"{info['cam_curvature_radius_min_mm']:.2f} mm"
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper right", fontsize=8, ncol=3)

    corr = " + correction" if drive.spin_a or drive.spin_b else ""
    fig.suptitle(
        "Spherical cam of the wobble drive: "
        f"phi = {np.degrees(drive.plate_tilt):.4g} deg, "
        f"alpha = {np.degrees(drive.roller_axis_angle):.4g} deg, "
        f"varphi = {drive.spin_ratio:g} theta{corr}"
        f", r = {r:.4g} mm, shell {cam.inner_radius * 1e3:.4g}..{cam.outer_radius * 1e3:.4g} mm, "
        f"groove to {cam.bottom_radius * 1e3:.4g} mm"
    )
    fixed_layout(fig, 0.7, 0.6, 0.3, 1.0, 0.85, 1.02)
    return [save_in(fig, outdir, "fig_spherical_cam.png")]
