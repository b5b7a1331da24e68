"""Figures of the rhomboid lever-cam converter (Zhuravlev et al. 2012: Fig. 1, eq. 13-34).

matplotlib is imported lazily inside the functions (Agg backend).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.drives import rhomboid_cam as rc

__all__ = [
    "plot_all",
    "sample_law",
    "fig_cam_profile",
    "fig_psi_law",
    "fig_blade_motion",
    "fig_work_loop",
]

_DPI = 120
_COLOURS = ("C0", "C1", "C2", "C3")


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def sample_law(psi_min):
    """A 1st+3rd-harmonic comparison law: ``a3 = -(pi/2 - psi_min)/8``, ``b3 = 0``.

    With eq. 15 this gives ``psi' = -3 (pi/2 - psi_min) sin^3 2 alpha``:
    monotone, with ``psi'' = 0`` at the extremes (dwell), at the price of a
    larger peak ``psi''``.

    Returns
    -------
    (a, b) : tuple of tuple
    """
    return (-(0.5 * np.pi - psi_min) / 8.0,), ()


def _tag(params) -> str:
    law = "first harmonic (eq. 16)"
    if params.a or params.b:
        a = ", ".join(f"{v:.4g}" for v in params.a)
        b = ", ".join(f"{v:.4g}" for v in params.b)
        law = f"a = [{a}], b = [{b}] rad"
    size = f"2l = {params.link_length * 1e3:.4g} mm"
    return f"{size}, psi_min = {np.degrees(params.psi_min):.4g} deg, {law}"


def fig_cam_profile(params, outdir: Path, alphas_deg=(0.0, 30.0, 60.0)) -> Path:
    """Cam pitch curve with rhombus, rollers and blade axes at a few shaft angles (cf. Fig. 1)."""
    plt = _plt()
    law = (params.link_length, params.psi_min, params.a, params.b)
    t = np.linspace(0.0, 2.0 * np.pi, 1441)
    xy = rc.profile_point(t, *law)[0] * 1e3
    rot = np.array([[0.0, 1.0], [-1.0, 0.0]]) @ xy  # eq. 19 form: turned by -90 deg
    fig, ax = plt.subplots(figsize=(11.5, 7.5))
    ax.plot(xy[0], xy[1], "k-", lw=2.0, label="pitch curve rho = 2l cos(psi/2) (eq. 3)")
    ax.plot(rot[0], rot[1], color="0.6", ls=":", lw=1.2,
            label="eq. 19 form 2l sin(psi/2): the same cam turned 90 deg")  # fmt: skip
    al = np.radians(np.asarray(alphas_deg, dtype=float))
    v = rc.rhombus_vertices(al, *law) * 1e3  # (4, 2, n)
    mid = rc.blade_arm_points(al, *law) * 1e3
    reach = 1.9 * 0.5 * params.link_length * 1e3
    for j, a_deg in enumerate(alphas_deg):
        c = _COLOURS[j % len(_COLOURS)]
        poly = np.concatenate([v[:, :, j], v[:1, :, j]])
        label = f"rhombus ABCD, alpha = {a_deg:g} deg"
        ax.plot(poly[:, 0], poly[:, 1], "-", color=c, lw=1.4, label=label)
        ax.plot(v[:, 0, j], v[:, 1, j], "o", ms=9, mfc="white", mec=c, mew=1.6)
        for k, ls in ((0, "--"), (1, "-.")):  # pair 1 through mid AB, pair 2 through mid DA
            u = mid[0 if k == 0 else 3, :, j]
            u = u / np.hypot(*u) * reach
            ax.plot([-u[0], u[0]], [-u[1], u[1]], ls, color=c, lw=0.9)
        ax.plot(mid[:, 0, j], mid[:, 1, j], "s", ms=4, color=c)
        if j == 0:
            for name, p in zip("ABCD", v[:, :, j], strict=True):
                ax.annotate(name, p, xytext=(6, 6), textcoords="offset points", color=c)
    ax.plot([], [], "k--", lw=0.9, label="blade pair 1 axis (phi_1 = alpha + psi/2)")
    ax.plot([], [], "k-.", lw=0.9, label="blade pair 2 axis (phi_2 = alpha - psi/2)")
    ax.plot(0, 0, "k+", ms=12)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(f"Cam pitch curve and rhomboid (cf. Fig. 1)\n{_tag(params)}", fontsize=10)
    ax.grid(True, alpha=0.4)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8)
    fig.tight_layout()
    path = Path(outdir) / "fig01_cam_profile.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path


def fig_psi_law(params, outdir: Path, points: int = 1441) -> Path:
    """``psi``, ``psi'``, ``psi''``: the config's law and a 1st+3rd-harmonic law (eq. 13-18)."""
    plt = _plt()
    al = np.linspace(0.0, np.pi, points)
    sa, sb = sample_law(params.psi_min)
    eq = "eq. 13" if (params.a or params.b) else "eq. 16"
    laws = [
        (f"config law ({eq})", params.a, params.b, "-"),
        (f"1st + 3rd harmonic, a3 = {sa[0]:.4f} rad (eq. 18)", sa, sb, "--"),
    ]
    fig, axes = plt.subplots(3, 1, figsize=(8, 8.5), sharex=True)
    labels = ("psi [deg]", "dpsi/dalpha [-]", "d2psi/dalpha2 [1/rad]")
    for name, a, b, ls in laws:
        p = rc.psi_law(al, params.psi_min, a, b)
        for ax, y, conv in zip(axes, p[:3], (np.degrees, None, None), strict=True):
            ax.plot(np.degrees(al), conv(y) if conv else y, ls, label=name)
    for ax, lab in zip(axes, labels, strict=True):
        ax.set_ylabel(lab)
        ax.grid(True, alpha=0.4)
    axes[0].axhline(np.degrees(params.psi_min), color="0.5", lw=0.8)
    axes[0].axhline(180.0 - np.degrees(params.psi_min), color="0.5", lw=0.8)
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("alpha [deg]")
    axes[-1].set_xticks(np.arange(0, 181, 30))
    fig.suptitle(f"Angle between the blade axes psi(alpha)\n{_tag(params)}", fontsize=10)
    fig.tight_layout()
    path = Path(outdir) / "fig02_psi_law.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path


def fig_blade_motion(params, outdir: Path, points: int = 1441) -> Path:
    """Blade angles, speed coefficients ``1 +- psi'/2``, accelerations ``+-psi''/2`` (eq. 22)."""
    plt = _plt()
    al = np.linspace(0.0, np.pi, points)
    q, d1, d2, _ = rc.blade_angles(al, params.psi_min, params.a, params.b)
    ad = np.degrees(al)
    fig, axes = plt.subplots(3, 1, figsize=(8, 8.5), sharex=True)
    axes[0].plot(ad, ad, color="0.6", lw=0.8, label="alpha (output shaft)")
    for k, c in ((0, "C0"), (1, "C3")):
        axes[0].plot(ad, np.degrees(q[k]), color=c, label=f"phi_{k + 1} (blade pair {k + 1})")
        axes[1].plot(ad, d1[k], color=c, label=f"dphi_{k + 1}/dalpha = 1 {'+-'[k]} psi'/2")
        axes[2].plot(ad, d2[k], color=c, label=f"d2phi_{k + 1}/dalpha2 = {'+-'[k]}psi''/2")
    for ax, lab in zip(axes, ("angle [deg]", "speed coefficient [-]", "accel. coeff. [1/rad]"),
                       strict=True):  # fmt: skip
        ax.set_ylabel(lab)
        ax.grid(True, alpha=0.4)
        ax.legend(fontsize=8)
    axes[-1].set_xlabel("alpha [deg]")
    axes[-1].set_xticks(np.arange(0, 181, 30))
    fig.suptitle(f"Blade motion\n{_tag(params)}", fontsize=10)
    fig.tight_layout()
    path = Path(outdir) / "fig03_blade_motion.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path


def fig_work_loop(params, torque_high, torque_low, outdir: Path, points: int = 1441) -> Path:
    """Blade torque against ``psi`` (compression and expansion) and ``dA/dalpha`` (eq. 24-34)."""
    plt = _plt()
    law = (params.psi_min, params.a, params.b)
    al = np.linspace(0.0, np.pi, points)
    psi, d1 = rc.psi_law(al, *law)[:2]
    s = rc.stroke_direction(al, *law)
    m = rc.blade_torque(psi, s, torque_high, torque_low, params.psi_min)
    work = float(rc.indicator_work(*law, torque_high, torque_low))
    lo, _, hi, _ = rc.psi_extremes(*law)
    g = np.linspace(lo, hi, 201)
    mp = rc.blade_torque(g, 1.0, torque_high, torque_low, params.psi_min)
    mc = rc.blade_torque(g, -1.0, torque_high, torque_low, params.psi_min)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5))
    closed = float(rc.indicator_work_closed_form(params.psi_min, torque_high, torque_low))
    label = f"area between the lines = Delta M Delta psi = {closed:.4g} J (eq. 31, 34)"
    ax.fill_between(np.degrees(g), mc, mp, color="C2", alpha=0.15, label=label)
    gd = np.degrees(g)
    ax.plot(np.degrees(psi), m, ".", color="0.3", ms=2, zorder=1,
            label="M_1 along the law, 0 <= alpha <= 180 deg")  # fmt: skip
    ax.plot(gd, mp, "C3-", lw=2.0, zorder=2, label="M_p (expansion, psi rising)")
    ax.plot(gd, mc, "C0-", lw=2.0, zorder=2, label="M_c (compression, psi falling)")
    ax.vlines([gd[0], gd[-1]], [mc[0], mc[-1]], [mp[0], mp[-1]], colors="0.4", lw=0.8, ls=":")
    for x0, x1, y0, y1, c in ((0.45, 0.55, mp, mp, "C3"), (0.55, 0.45, mc, mc, "C0")):
        i0, i1 = int(x0 * (g.size - 1)), int(x1 * (g.size - 1))
        ax.annotate("", (gd[i1], y1[i1]), (gd[i0], y0[i0]),
                    arrowprops={"arrowstyle": "-|>", "color": c, "lw": 2.0,
                                "mutation_scale": 22})  # fmt: skip
    ax.set_xlabel("psi [deg]")
    ax.set_ylabel("blade torque M_1 [N m]")
    note = "" if rc.psi_is_monotone(*law) else "\npsi not monotone: each back-and-forth swing"
    note += "" if not note else " adds (M1 - M2) x its travel"
    ax.set_title(f"Work loop (eq. 27-29): A = {work:.4g} J per half turn{note}", fontsize=10)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8)
    bx.plot(np.degrees(al), m * d1, "C2", label="dA/dalpha = M_1 psi' (eq. 24)")
    mean = f"mean A/pi = {work / np.pi:.4g} N m"
    bx.axhline(work / np.pi, color="k", ls="--", lw=1.0, label=mean)
    bx.set_xlabel("alpha [deg]")
    bx.set_ylabel("shaft torque [N m]")
    bx.set_xticks(np.arange(0, 181, 30))
    bx.set_title("Driving torque on the output shaft", fontsize=10)
    bx.grid(True, alpha=0.4)
    bx.legend(fontsize=8)
    fig.suptitle(f"{_tag(params)}; M1 = {torque_high:g} N m, M2 = {torque_low:g} N m", fontsize=10)
    fig.tight_layout()
    path = Path(outdir) / "fig04_work_loop.png"
    fig.savefig(path, dpi=_DPI)
    plt.close(fig)
    return path


def plot_all(params, torque_high, torque_low, outdir: Path) -> list[Path]:
    """Write every figure of the drive into ``outdir``; return the paths."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return [
        fig_cam_profile(params, outdir),
        fig_psi_law(params, outdir),
        fig_blade_motion(params, outdir),
        fig_work_loop(params, float(torque_high), float(torque_low), outdir),
    ]
