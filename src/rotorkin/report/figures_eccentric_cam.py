"""Figures of the double eccentric-cam drive (Zhu & Zhu 2012, Fig. 6-8, and a follower comparison).

matplotlib is imported lazily inside the functions (Agg backend).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.drives import eccentric_cam as ec

__all__ = [
    "LAMBDAS",
    "plot_all",
    "fig_decomposition",
    "fig_gap_change_ratio",
    "fig_pistons",
    "fig_followers",
]

_DPI = 120
#: The eccentricity ratios drawn in Fig. 6 and 7 (besides the config's).
LAMBDAS = (0.1, 0.3, 0.5, 0.7, 0.9)


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _beta():
    return np.linspace(0.0, 2.0 * np.pi, 721)


def _axes_deg(ax, ylabel):
    ax.set_xlabel("shaft angle beta [deg]")
    ax.set_ylabel(ylabel)
    ax.set_xlim(0.0, 360.0)
    ax.set_xticks(np.arange(0.0, 361.0, 45.0))
    ax.grid(True, alpha=0.4)


def _family(params: ec.EccentricCam):
    """Knife-edge drives at LAMBDAS on the config's disc radius."""
    R = float(params.disc_radius)
    return [(lam, ec.EccentricCam(R, lam * R, "knife_edge")) for lam in LAMBDAS]


def _tag(params: ec.EccentricCam) -> str:
    extra = f", r = {params.roller_radius * 1e3:.4g} mm" if params.follower == "roller" else ""
    return (
        f"R = {params.disc_radius * 1e3:.4g} mm, e = {params.eccentricity * 1e3:.4g} mm, "
        f"lambda = {params.lam:.3g}, {params.follower}{extra}"
    )


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=_DPI)
    _plt().close(fig)
    return path


def fig_decomposition(params: ec.EccentricCam, path: Path) -> Path:
    """Fig. 6: harmonic part xi, additional part mu and x = xi + mu for several lambda."""
    plt = _plt()
    beta = _beta()
    b = np.degrees(beta)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5.6))
    for i, (lam, p) in enumerate(_family(params)):
        d = ec.decomposition(p, beta)
        ax1.plot(b, d["mu"], color=f"C{i}", label=f"mu, lambda = {lam:g}")
        ax2.plot(b, d["x"], color=f"C{i}", label=f"x, lambda = {lam:g}")
    d = ec.decomposition(params, beta)
    ax1.plot(b, d["mu"], "k--", lw=2, label=f"mu, config ({params.follower})")
    ax2.plot(b, d["x"], "k--", lw=2, label=f"x, config ({params.follower})")
    ax2.plot(b, d["xi"], color="0.5", lw=3, alpha=0.6, label="xi = cos beta (harmonic)")
    ax1.plot(b, d["xi"], color="0.5", lw=3, alpha=0.6, label="xi = cos beta (harmonic)")
    ax1.set_title("(a) additional part mu and harmonic part xi")
    ax2.set_title("(b) left piston x = z/e = xi + mu")
    _axes_deg(ax1, "xi, mu [-]")
    _axes_deg(ax2, "x [-]")
    for ax in (ax1, ax2):
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=3)
    fig.suptitle(
        "Fig. 6  Knife-edge piston travel: harmonic and additional parts (" + _tag(params) + ")"
    )
    return _save(fig, path)


def fig_gap_change_ratio(params: ec.EccentricCam, path: Path) -> Path:
    """Fig. 7: dimensionless gap change delta = Delta/e vs beta for several lambda."""
    plt = _plt()
    beta = _beta()
    b = np.degrees(beta)
    fig, ax = plt.subplots(figsize=(8, 5))
    for i, (lam, p) in enumerate(_family(params)):
        ax.plot(b, ec.decomposition(p, beta)["delta"], color=f"C{i}", label=f"lambda = {lam:g}")
    ax.plot(b, ec.decomposition(params, beta)["delta"], "k--", lw=2,
            label=f"config: lambda = {params.lam:.3g} ({params.follower})")  # fmt: skip
    _axes_deg(ax, "delta = Delta / e [-]")
    ax.legend(fontsize=8, loc="lower center")
    ax.set_title("Fig. 7  Change of the distance between the inner faces, knife-edge pistons")
    return _save(fig, path)


def fig_pistons(params: ec.EccentricCam, path: Path) -> Path:
    """Fig. 8: x, x' and delta vs beta at the config's drive."""
    plt = _plt()
    beta = _beta()
    b = np.degrees(beta)
    d = ec.decomposition(params, beta)
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.plot(b, d["x"], "C0", label="x = z/e (left piston)")
    ax.plot(b, d["x_right"], "C3", label="x' = z'/e (right piston)")
    ax.plot(b, -d["x_right"], "C3:", lw=1, label="-x' (mirror: x + x' = delta)")
    ax.plot(b, d["delta"], "k", lw=2, label="delta = x + x'")
    dmin, bmin = ec.gap_change_extreme(params)
    e = float(params.eccentricity)
    ax.plot([np.degrees(bmin)], [dmin / e], "ko")
    ax.annotate(f"delta = {dmin / e:.4f}\nDelta = {dmin * 1e3:.3g} mm",
                (np.degrees(bmin), dmin / e), textcoords="offset points", xytext=(12, 40),
                fontsize=8)  # fmt: skip
    _axes_deg(ax, "x, x', delta [-]")
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title("Fig. 8  Left and right pistons and gap change\n" + _tag(params))
    return _save(fig, path)


def fig_followers(params: ec.EccentricCam, path: Path) -> Path:
    """Knife-edge vs roller vs flat-faced follower: travel and gap change (derived here)."""
    plt = _plt()
    beta = _beta()
    b = np.degrees(beta)
    R, e = float(params.disc_radius), float(params.eccentricity)
    r = float(params.roller_radius) if params.follower == "roller" else 0.25 * R
    drives = (
        ("knife edge", ec.EccentricCam(R, e, "knife_edge"), "C0"),
        (f"roller, r = {r * 1e3:.3g} mm", ec.EccentricCam(R, e, "roller", r), "C2"),
        ("flat face", ec.EccentricCam(R, e, "flat"), "C3"),
    )
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    for label, p, colour in drives:
        z, _, _, _ = ec.piston_travels(p, beta)
        ax1.plot(b, z[0] * 1e3, color=colour, label=f"{label}: z (left)")
        ax1.plot(b, z[1] * 1e3, color=colour, ls="--", label=f"{label}: z' (right)")
        ax2.plot(b, ec.gap_change(p, beta)[0] * 1e3, color=colour, label=label)
    ax1.set_title("(a) piston travels, positive towards the reactor centre")
    ax2.set_title("(b) gap change Delta = z + z'")
    _axes_deg(ax1, "travel [mm]")
    _axes_deg(ax2, "Delta [mm]")
    ax1.legend(fontsize=7, loc="lower left")
    ax2.legend(fontsize=8, loc="lower left")
    fig.suptitle(f"Follower comparison: R = {R * 1e3:.4g} mm, e = {e * 1e3:.4g} mm")
    return _save(fig, path)


def plot_all(params: ec.EccentricCam, outdir: Path) -> list[Path]:
    """Write every figure of the drive into ``outdir``; return the paths."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return [
        fig_decomposition(params, outdir / "fig06_travel_decomposition.png"),
        fig_gap_change_ratio(params, outdir / "fig07_gap_change_ratio.png"),
        fig_pistons(params, outdir / "fig08_pistons_and_gap.png"),
        fig_followers(params, outdir / "fig_followers_comparison.png"),
    ]
