"""Figures of the guide-bar + gear drive of a differential vane pump (JHIT 2012, Fig. 3, 5, 9-11).

matplotlib is imported lazily inside the functions (Agg backend).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from rotorkin.drives import guide_bar as gb

__all__ = [
    "TORQUE_LAMBDAS",
    "plot_all",
    "fig_speed_ratios",
    "fig_vane_angle",
    "fig_input_torque",
    "fig_relative_angle",
]

_DPI = 120
#: The lambdas of Fig. 10 and 11 (besides the config's).
TORQUE_LAMBDAS = (0.3, 0.5, 0.7)
_LABEL = {"crank": "crank-driven", "guide": "guide-driven"}
_EQ = {"crank": 5, "guide": 6}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=_DPI)
    _plt().close(fig)
    return path


def _tag(p: gb.GuideBar) -> str:
    return (
        f"lambda = {p.lam:.3g}, u = {p.gear_ratio:.3g}, i12 = {p.input_gear_ratio:.3g}, "
        f"Sigma = {np.degrees(p.phase):.4g} deg"
    )


def fig_speed_ratios(params: gb.GuideBar, driver: str, path: Path, number: int) -> Path:
    """Fig. 3 (crank-driven) / Fig. 5 (guide-driven): impeller speed over driving-member speed."""
    plt = _plt()
    p = replace(params, driver=driver)
    lam, u = float(p.lam), float(p.gear_ratio)
    t = np.linspace(0.0, 2.0 * np.pi, 721)
    x = np.stack([t, t + float(p.phase)])
    r = gb.driven_angle(lam, x, driver)[1] / u
    fig, ax = plt.subplots(figsize=(8, 5.8))
    ax.plot(np.degrees(t), r[0], "C0", label="impeller 1 (gear 7): omega_7 / omega_driving")
    ax.plot(np.degrees(t), r[1], "C3", label="impeller 2 (gear 8): omega_8 / omega_driving")
    ax.axhline(1.0 / u, color="0.5", ls=":", label=f"mean 1/u = {1.0 / u:.3g}")
    for k, ta in enumerate(gb.equal_speed_angles(p.phase)):
        ta = float(np.mod(ta, 2.0 * np.pi))
        ra = float(gb.driven_angle(lam, ta, driver)[1]) / u
        ax.plot([np.degrees(ta)], [ra], "ko", label="equal-speed points" if k == 0 else None)
        ax.annotate(f"{np.degrees(ta):.1f} deg", (np.degrees(ta), ra),
                    textcoords="offset points", xytext=(6, 8), fontsize=8)  # fmt: skip
    g0 = float(gb.vane_angle(lam, u, p.phase, driver))
    ax.set_xlabel(f"driving angle of mechanism 1 ({driver} angle) t = theta / i12 [deg]")
    ax.set_ylabel("impeller speed / driving-member speed [-]")
    ax.set_xlim(0.0, 360.0)
    ax.set_xticks(np.arange(0.0, 361.0, 45.0))
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    ax.set_title(
        f"Fig. {number}  {_LABEL[driver]} impeller speeds ({_tag(p)})\n"
        f"vane angle gamma_0 = {np.degrees(g0):.2f} deg"
    )
    return _save(fig, path)


def fig_vane_angle(params: gb.GuideBar, path: Path) -> Path:
    """Fig. 9: lambda vs theoretical vane angle gamma_0 for u = 2 and 3, both drivers."""
    plt = _plt()
    lam = np.linspace(0.01, 0.99, 197)
    fig, ax = plt.subplots(figsize=(8, 5))
    styles = {("crank", 2.0): "C0-", ("guide", 2.0): "C3-", ("crank", 3.0): "C0--",
              ("guide", 3.0): "C3--"}  # fmt: skip
    for n, (driver, u) in enumerate((("crank", 2.0), ("guide", 2.0), ("crank", 3.0),
                                     ("guide", 3.0))):  # fmt: skip
        g0 = gb.vane_angle_half_turn(lam, u, driver)
        ax.plot(np.degrees(g0), lam, styles[driver, u],
                label=f"{n + 1}: {_LABEL[driver]}, u = {u:g} (eq. {_EQ[driver]})")  # fmt: skip
    if abs(np.cos(0.5 * params.phase)) > 1e-12 or params.gear_ratio not in (2.0, 3.0):
        for driver in gb.DRIVERS:
            g0 = gb.vane_angle(lam, params.gear_ratio, params.phase, driver)
            ax.plot(np.degrees(g0), lam, color="C0" if driver == "crank" else "C3", ls=":",
                    label=f"{_LABEL[driver]}, config u = {params.gear_ratio:.3g}, "
                    f"Sigma = {np.degrees(params.phase):.4g} deg")  # fmt: skip
    g_cfg = gb.vane_angle(params.lam, params.gear_ratio, params.phase, params.driver)
    ax.plot([np.degrees(g_cfg)], [params.lam], "k*", ms=12,
            label=f"config ({_LABEL[params.driver]}): {np.degrees(g_cfg):.2f} deg")  # fmt: skip
    ax.set_xlabel("theoretical vane angle gamma_0 [deg]")
    ax.set_ylabel("mechanism coefficient lambda = d/a [-]")
    ax.set_ylim(0.0, 1.0)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title("Fig. 9  lambda vs vane angle gamma_0, Sigma = 180 deg")
    return _save(fig, path)


def _torques(m7: float, m8: float):
    if m7 == 0.0 and m8 == 0.0:
        return 10.0, 10.0, " (config loads are zero: M7 = M8 = 10 N*m drawn)"
    return m7, m8, ""


def _torque_limits(params: gb.GuideBar, lams, m7, m8):
    """y limits covering both drivers' torque curves at every lambda drawn."""
    vals = []
    for driver in gb.DRIVERS:
        for lam in lams:
            p = replace(params, lam=lam, driver=driver)
            vals.append(gb.input_torque(p, np.linspace(0.0, gb.period(p), 721), m7, m8))
    lo, hi = float(np.min(vals)), float(np.max(vals))
    pad = 0.06 * max(hi - lo, 1e-3 * max(abs(lo), abs(hi), 1e-12))
    return lo - pad, hi + pad


def fig_input_torque(params: gb.GuideBar, driver: str, m7, m8, path: Path, number: int) -> Path:
    """Fig. 10 (crank-driven) / 11 (guide-driven): input torque M1 over a period, several lambda."""
    plt = _plt()
    m7, m8, note = _torques(m7, m8)
    lams = sorted(set(TORQUE_LAMBDAS) | {round(float(params.lam), 12)})
    fig, ax = plt.subplots(figsize=(8, 5))
    for i, lam in enumerate(lams):
        p = replace(params, lam=lam, driver=driver)
        theta = np.linspace(0.0, gb.period(p), 721)
        style = "k--" if lam == round(float(params.lam), 12) else f"C{i}-"
        ax.plot(np.degrees(theta), gb.input_torque(p, theta, m7, m8), style,
                label=f"lambda = {lam:.3g}" + (" (config)" if style == "k--" else ""))  # fmt: skip
    lo, hi = _torque_limits(params, lams, m7, m8)
    ax.set_ylim(lo, hi)  # the same scale in Fig. 10 and 11, as the paper compares them
    ax.set_xlabel("input gear angle theta [deg]")
    ax.set_ylabel("input torque M1 [N*m]")
    ax.set_xlim(0.0, np.degrees(gb.period(params)))
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title(
        f"Fig. {number}  Input torque, {_LABEL[driver]}: u = {params.gear_ratio:.3g}, "
        f"i12 = {params.input_gear_ratio:.3g}, Sigma = {np.degrees(params.phase):.4g} deg\n"
        f"M7 = {m7:.3g} N*m, M8 = {m8:.3g} N*m{note}"
    )
    if driver == "guide" and m7 == m8 and abs(np.cos(0.5 * params.phase)) < 1e-12:
        ax.text(0.5, 0.08, "M7 = M8 and Sigma = 180 deg: M1 is constant, h'(y) + h'(y + pi) = 2",
                transform=ax.transAxes, ha="center", fontsize=9)  # fmt: skip
    return _save(fig, path)


def fig_relative_angle(params: gb.GuideBar, path: Path) -> Path:
    """Angle between the impellers q_2 - q_1 (chamber angle change) over a period, both drivers."""
    plt = _plt()
    theta = np.linspace(0.0, gb.period(params), 721)
    fig, ax = plt.subplots(figsize=(8, 5))
    for driver, colour in (("crank", "C0"), ("guide", "C3")):
        p = replace(params, driver=driver)
        q = gb.impeller_angles(p, theta)[0]
        rel = np.degrees(q[1] - q[0])
        swing = np.degrees(gb.relative_angle_swing(p))
        ax.plot(np.degrees(theta), rel, color=colour, lw=2.5 if driver == params.driver else 1.2,
                label=f"{_LABEL[driver]}: swing {swing:.2f} deg")  # fmt: skip
    ax.set_xlabel("input gear angle theta [deg]")
    ax.set_ylabel("q_2 - q_1 [deg]")
    ax.set_xlim(0.0, np.degrees(gb.period(params)))
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8)
    ax.set_title(f"Angle between the impellers (chamber angle change)\n{_tag(params)}")
    return _save(fig, path)


def plot_all(params: gb.GuideBar, m7: float, m8: float, outdir: Path) -> list[Path]:
    """Write every figure of the drive into ``outdir``; return the paths."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return [
        fig_speed_ratios(params, "crank", outdir / "fig03_speed_crank_driven.png", 3),
        fig_speed_ratios(params, "guide", outdir / "fig05_speed_guide_driven.png", 5),
        fig_vane_angle(params, outdir / "fig09_lambda_vane_angle.png"),
        fig_input_torque(params, "crank", m7, m8, outdir / "fig10_torque_crank_driven.png", 10),
        fig_input_torque(params, "guide", m7, m8, outdir / "fig11_torque_guide_driven.png", 11),
        fig_relative_angle(params, outdir / "fig_relative_angle.png"),
    ]
