"""Figures of the double eccentric-cam drive (Zhu & Zhu 2012, Fig. 6-8, and a follower comparison)
and of the opposed-piston reactor on it (volume, pressure, forces, torques; derived here).

matplotlib is imported on first use (:func:`rotorkin.render.figures.pyplot`).
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.machines import opposed_piston as op
from rotorkin.render.figures import draw, plain_log_labels
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save as _save

__all__ = [
    "LAMBDAS",
    "plot_all",
    "fig_decomposition",
    "fig_gap_change_ratio",
    "fig_pistons",
    "fig_followers",
    "fig_reactor_volume_pressure",
    "fig_reactor_torque",
    "fig_reactor_ripple_vs_lambda",
    "fig_forces",
]

#: The eccentricity ratios drawn in Fig. 6 and 7 (besides the config's).
LAMBDAS = (0.1, 0.3, 0.5, 0.7, 0.9)


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
    return _save(fig, path, layout=(1.0, 1.3, 0.3, 0.68, 1.1))


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
    return _save(fig, path, layout=(0.9, 0.6, 0.3, 0.37))


def fig_pistons(params: ec.EccentricCam, path: Path) -> Path:
    """Fig. 8: x, x' and delta vs beta at the config's drive."""
    plt = _plt()
    beta = _beta()
    b = np.degrees(beta)
    d = ec.decomposition(params, beta)
    fig, ax = plt.subplots(figsize=(8, 5.6))
    ax.plot(b, d["x"], "C0", label="x = z/e (left piston)")
    ax.plot(b, d["x_right"], "C3", label="x' = z'/e (right piston)")
    ax.plot(b, -d["x_right"], "C3:", lw=1, label="-x' (mirror: x + x' = delta)")
    ax.plot(b, d["delta"], "k", lw=2, label="delta = x + x'")
    dmin, bmin = ec.gap_change_extreme(params)
    e = float(params.eccentricity)
    ax.plot([np.degrees(bmin)], [dmin / e], "ko")
    ax.annotate(f"delta = {dmin / e:.4f}\nDelta = {dmin * 1e3:.3g} mm",
                (np.degrees(bmin), dmin / e), textcoords="offset points", xytext=(-95, -10),
                fontsize=8, va="center", bbox={"fc": "white", "ec": "0.7", "pad": 2},
                arrowprops={"arrowstyle": "-", "color": "0.4"})  # fmt: skip
    _axes_deg(ax, "x, x', delta [-]")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=4)
    ax.set_title("Fig. 8  Left and right pistons and gap change\n" + _tag(params))
    return _save(fig, path, layout=(1.0, 0.98, 0.3, 0.58))


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
    return _save(fig, path, layout=(0.87, 0.6, 0.3, 0.68, 0.95))


# --------------------------------------------------------------------------------------------
# the reactor (derived here)
# --------------------------------------------------------------------------------------------
def _reactor_tag(params, reactor) -> str:
    fluid = (
        f"gas, n = {reactor.polytropic_exponent:.3g}"
        if reactor.fluid == "gas"
        else f"liquid, K = {reactor.bulk_modulus / 1e9:.3g} GPa"
    )
    return (
        f"bore {reactor.bore * 1e3:.4g} mm, L = {reactor.device_length * 1e3:.5g} mm, {fluid}, "
        f"p0 = {reactor.initial_pressure / 1e5:.4g} bar; " + _tag(params)
    )


def fig_reactor_volume_pressure(params, reactor, beta, state, summary, path: Path) -> Path:
    """Enclosed volume and pressure over a shaft turn, against the flat-follower ideal."""
    plt = _plt()
    b = np.degrees(beta)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 7.5), sharex=True)
    v0 = reactor.volume_initial * 1e6
    ax1.plot(b, state["V"][0] * 1e6, "C0", lw=2, label=f"{params.follower} follower")
    ax1.axhline(v0, color="C3", ls="--", label=f"flat follower: constant V0 = {v0:.5g} cm^3")
    ax1.annotate(f"V_max = {summary['enclosed_volume_max_cm3']:.5g} cm^3 "
                 f"(+{100 * summary['volume_change_relative']:.3g} %)",
                 (90.0, summary["enclosed_volume_max_cm3"]), xytext=(8, -14),
                 textcoords="offset points", fontsize=8)  # fmt: skip
    _axes_deg(ax1, "enclosed volume [cm^3]")
    ax1.set_xlabel("")
    ax1.legend(fontsize=8, loc="center right")
    ax1.set_title(
        "Enclosed volume and pressure over one shaft turn\n" + _reactor_tag(params, reactor),
        fontsize=9,
    )
    p = state["p"][0] / 1e5
    ax2.plot(b, p, "k", lw=2, label="pressure (absolute)")
    ax2.axhline(reactor.initial_pressure / 1e5, color="C3", ls="--", label="flat follower: p0")
    if np.min(p) < 0.0:
        ax2.axhspan(min(np.min(p) * 1.05, -1.0), 0.0, color="C3", alpha=0.08, lw=0)
        ax2.axhline(0.0, color="C3", lw=0.8)
        ax2.text(0.5, 0.04, "below 0 bar: the liquid would be in tension, it cavitates "
                 "(model no longer valid)", transform=ax2.transAxes, ha="center", fontsize=8,
                 color="C3")  # fmt: skip
    _axes_deg(ax2, "pressure [bar]")
    ax2.legend(fontsize=8, loc="center right")
    ax2.set_title(f"pressure ripple {summary['pressure_ripple_bar']:.4g} bar "
                  f"({summary['pressure_ripple_relative']:.4g} x p0)", fontsize=9)  # fmt: skip
    return _save(fig, path, layout=(0.97, 0.6, 0.3, 0.5, 0.0, 0.38))


def fig_reactor_torque(params, reactor, beta, state, summary, path: Path) -> Path:
    """Shaft torque with and without inertia, and the piston forces, over a turn."""
    plt = _plt()
    b = np.degrees(beta)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 7.5), sharex=True)
    ax1.plot(b, state["shaft"], "C0", lw=2, label="fluid only: p dV/dbeta (virtual work)")
    ax1.plot(b, state["net"], "C3", lw=1.5, label="fluid + inertia of shaft and pistons")
    ax1.plot(b, -state["inertia"], "0.5", lw=1, ls=":", label="inertia only")
    ax1.axhline(0.0, color="k", lw=0.8)
    _axes_deg(ax1, "torque on the shaft [N*m]")
    ax1.set_xlabel("")
    ax1.legend(fontsize=8, loc="lower right")
    ax1.set_title(
        f"Torque on the shaft at {summary['shaft_speed_mean_rpm']:.5g} rpm (positive: drives the "
        f"shaft); flywheel for C_s = {summary['speed_fluctuation']:.3g}: "
        f"{summary['flywheel_inertia_kgm2']:.3g} kg*m^2\n" + _reactor_tag(params, reactor),
        fontsize=9,
    )
    ax2.plot(b, state["F"][0] / 1e3, "C0", lw=2, label="fluid on the left piston")
    ax2.plot(b, state["F"][1] / 1e3, "C1", lw=1.5, ls="--", label="fluid on the right piston")
    _axes_deg(ax2, "piston force [kN] (+ towards the centre)")
    ax2.legend(fontsize=8, loc="lower right")
    return _save(fig, path, layout=(1.08, 0.6, 0.3, 0.5, 0.0, 0.21))


def fig_reactor_ripple_vs_lambda(params, reactor, path: Path) -> Path:
    """Design chart: pressure ripple vs lambda = e/R at the config's disc radius and fluid."""
    plt = _plt()
    R = float(params.disc_radius)
    lams = np.linspace(0.02, 0.95, 187)
    fig, ax = plt.subplots(figsize=(8, 5.2))
    r_cfg = float(params.roller_radius) if params.follower == "roller" else 0.25 * R
    A, L = reactor.area, float(reactor.device_length)
    for label, rc, colour in (("knife edge", R, "C0"),
                              (f"roller, r = {r_cfg * 1e3:.3g} mm", R + r_cfg, "C2")):  # fmt: skip
        # Delta_min at 90 deg (eq. 5), for every lambda at once
        dmin = ec.gap_change_extreme(ec.EccentricCam(rc, lams * R))[0]
        ripple = reactor.initial_pressure - op.pressure_from_volume(reactor, A * (L - dmin))
        ax.semilogy(lams, ripple / 1e5, color=colour, lw=2, label=label)
        plain_log_labels(ax, "y")
    if reactor.fluid == "liquid":
        ax.axhline(reactor.initial_pressure / 1e5, color="C3", ls="--",
                   label="ripple = p0: the liquid cavitates above")  # fmt: skip
    vmax = op.volume_extremes(reactor)[1]
    own = (reactor.initial_pressure - float(op.pressure_from_volume(reactor, vmax))) / 1e5
    if own > 0.0:
        ax.plot([params.lam], [own], "k*", ms=12,
                label=f"config: {own:.4g} bar ({params.follower})")  # fmt: skip
    ax.set_xlabel("eccentricity ratio lambda = e/R [-]")
    ax.set_ylabel("pressure ripple p0 - p_min [bar]")
    ax.set_xlim(0.0, 1.0)
    ax.grid(True, which="both", alpha=0.4)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("Pressure ripple vs eccentricity ratio (the flat follower gives none)\n"
                 + _reactor_tag(params, reactor), fontsize=9)  # fmt: skip
    return _save(fig, path, layout=(0.9, 0.6, 0.3, 0.5))


def fig_forces(params, beta, cols: dict, path: Path) -> Path:
    """Forces over the turn: every pair's normal force, the signed follower push and side
    thrust, the contact stress (when the follower has a contact radius)."""
    plt = _plt()
    deg = np.degrees(beta)
    stresses = [k for k in cols if k.endswith("_contact_stress_MPa")]
    rows = 3 if stresses else 2
    fig, axes = plt.subplots(rows, 1, figsize=(8, 2.8 * rows + 0.8), sharex=True)
    ax = axes[0]
    for k in cols:
        if k.endswith("_force_N"):
            ax.plot(deg, cols[k], lw=1.4, label=k[: -len("_force_N")].replace("_", " "))
    ax.set_ylabel("normal force [N]")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, alpha=0.4)
    ax = axes[1]
    for side, c in (("left", "C0"), ("right", "C1")):
        ax.plot(deg, cols[f"follower_normal_{side}_N"], color=c, lw=1.6,
                label=f"{side} disc push N (< 0: lift-off)")  # fmt: skip
        ax.plot(deg, cols[f"side_thrust_{side}_N"], color=c, ls="--", lw=1.2,
                label=f"{side} side thrust N n_y (+y wall > 0)")  # fmt: skip
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_ylabel("signed force [N]")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, alpha=0.4)
    if stresses:
        ax = axes[2]
        for k in stresses:
            ax.plot(deg, cols[k], lw=1.4, label=k[: -len("_contact_stress_MPa")].replace("_", " "))
        ax.set_ylabel("Hertz pressure [MPa]")
        ax.legend(fontsize=7)
        ax.grid(True, alpha=0.4)
    axes[-1].set_xlabel("shaft angle beta [deg]")
    axes[-1].set_xlim(0.0, 360.0)
    fig.suptitle(f"Pair forces at the run speed, {params.follower} follower, "
                 f"R = {float(params.disc_radius) * 1e3:.4g} mm, "
                 f"e = {float(params.eccentricity) * 1e3:.4g} mm", fontsize=10)  # fmt: skip
    return _save(fig, path, layout=(0.95, 0.6, 0.3, 0.49, 0.0, 0.22))


def plot_all(params: ec.EccentricCam, outdir: Path, reactor=None, beta=None, state=None,
             summary=None, forces=None) -> list[Path]:  # fmt: skip
    """Write every figure of the drive (and of the reactor, when given) into ``outdir``.

    Parameters
    ----------
    params : EccentricCam
    outdir : Path
    reactor : OpposedPiston, optional
    beta, state, summary : optional
        Shaft angles, :func:`rotorkin.drives.eccentric_cam.study.reactor_state` on them
        and the study's summary; needed with ``reactor``.
    forces : dict, optional
        The study's force columns on ``beta`` (``forces.png``).

    Returns
    -------
    list of Path
    """
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    p = functools.partial
    tasks = [
        p(fig_decomposition, params, outdir / "fig06_travel_decomposition.png"),
        p(fig_gap_change_ratio, params, outdir / "fig07_gap_change_ratio.png"),
        p(fig_pistons, params, outdir / "fig08_pistons_and_gap.png"),
        p(fig_followers, params, outdir / "fig_followers_comparison.png"),
    ]
    if reactor is not None:
        tasks += [
            p(fig_reactor_volume_pressure, params, reactor, beta, state, summary,
              outdir / "reactor_volume_pressure.png"),
            p(fig_reactor_torque, params, reactor, beta, state, summary,
              outdir / "reactor_torque.png"),
            p(fig_reactor_ripple_vs_lambda, params, reactor,
              outdir / "reactor_ripple_vs_lambda.png"),
        ]  # fmt: skip
    if forces is not None:
        tasks.append(p(fig_forces, params, beta, forces, outdir / "forces.png"))
    return draw(tasks)
