"""Figures of the guide-bar + gear drive of a differential vane pump (JHIT 2012, Fig. 3, 5, 9-11)
and of the pump itself (chambers, cross-sections, flow, torques; derived here).

pyplot comes from :func:`rotorkin.render.figures.pyplot` (the command line chooses the backend).
"""

from __future__ import annotations

import functools
from dataclasses import replace
from pathlib import Path

import numpy as np

from rotorkin.analysis import pairs as pr
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.machines import vane_pump as vp
from rotorkin.render.figures import draw, fixed_layout, save_in
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save as _save

__all__ = [
    "TORQUE_LAMBDAS",
    "plot_all",
    "fig_speed_ratios",
    "fig_vane_angle",
    "fig9_axes",
    "fig_input_torque",
    "fig_relative_angle",
    "fig_pump_sections",
    "fig_pump_chambers",
    "fig_pump_flow",
    "fig_pump_torque",
    "fig_forces",
]

#: The lambdas of Fig. 10 and 11 (besides the config's).
TORQUE_LAMBDAS = (0.3, 0.5, 0.7)
_LABEL = {"crank": "crank-driven", "guide": "guide-driven"}
_EQ = {"crank": 5, "guide": 6}


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
    r = gb.driven_angle(lam, driver, x)[1] / u
    fig, ax = plt.subplots(figsize=(8, 5.8))
    ax.plot(np.degrees(t), r[0], "C0", label="impeller 1 (gear 7): omega_7 / omega_driving")
    ax.plot(np.degrees(t), r[1], "C3", label="impeller 2 (gear 8): omega_8 / omega_driving")
    ax.axhline(1.0 / u, color="0.5", ls=":", label=f"mean 1/u = {1.0 / u:.3g}")
    for k, ta in enumerate(gb.equal_speed_angles(p.phase)):
        ta = float(np.mod(ta, 2.0 * np.pi))
        ra = float(gb.driven_angle(lam, driver, ta)[1]) / u
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
    return _save(fig, path, layout=(0.8, 1.17, 0.3, 0.58))


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
    fig9_axes(ax, "Fig. 9  lambda vs vane angle gamma_0, Sigma = 180 deg")
    return _save(fig, path, layout=(0.8, 0.6, 0.2, 0.37))


def fig9_axes(ax, title: str) -> None:
    """Axes, grid, legend and title of Fig. 9 (lambda over the vane angle gamma_0 [deg])."""
    ax.set_xlabel("theoretical vane angle gamma_0 [deg]")
    ax.set_ylabel("mechanism coefficient lambda = d/a [-]")
    ax.set_ylim(0.0, 1.0)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title(title)


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
            vals.append(gb.input_torque(p, m7, m8, np.linspace(0.0, gb.period(p), 721)))
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
        ax.plot(np.degrees(theta), gb.input_torque(p, m7, m8, theta), style,
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
    return _save(fig, path, layout=(0.8, 0.6, 0.2, 0.58))


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
    return _save(fig, path, layout=(0.85, 0.6, 0.2, 0.58))


# --------------------------------------------------------------------------------------------
# the pump (derived here)
# --------------------------------------------------------------------------------------------
_DISCHARGE, _SUCTION = "#d62728", "#1f77b4"


def _pump_tag(pump, ports) -> str:
    return (
        f"Z = {pump.vanes_per_impeller} vanes/impeller, vane angle "
        f"{np.degrees(pump.vane_angle):.2f} deg, R_h = {pump.hub_radius * 1e3:.4g} mm, "
        f"R_c = {pump.casing_radius * 1e3:.4g} mm, w = {pump.axial_width * 1e3:.4g} mm, "
        f"p_s = {ports.suction_pressure / 1e5:.3g} bar, "
        f"p_d = {ports.discharge_pressure / 1e5:.3g} bar"
    )


def _theta_axis(ax, theta, ylabel):
    ax.set_xlabel("input gear angle theta [deg]")
    ax.set_ylabel(ylabel)
    ax.set_xlim(0.0, np.degrees(theta[-1]))
    ax.set_xticks(np.arange(0.0, np.degrees(theta[-1]) + 1.0, 90.0))
    ax.grid(True, alpha=0.4)


def _shade_strokes(ax, theta, dv_a):
    """Background: red where the A chambers discharge, blue where they suck."""
    deg = np.degrees(theta)
    ax.fill_between(deg, 0, 1, where=dv_a < 0, color=_DISCHARGE, alpha=0.07,
                    transform=ax.get_xaxis_transform(), lw=0)  # fmt: skip
    ax.fill_between(deg, 0, 1, where=dv_a >= 0, color=_SUCTION, alpha=0.07,
                    transform=ax.get_xaxis_transform(), lw=0)  # fmt: skip


def fig_pump_sections(drive: gb.GuideBar, pump, ports, path: Path) -> Path:
    """Cross-sections of the pump at four input angles: vanes and chambers by port."""
    plt = _plt()
    i12 = float(drive.input_gear_ratio)
    t_a, t_b = sorted(float(np.mod(t, 2.0 * np.pi)) for t in gb.equal_speed_angles(drive.phase))
    period = gb.period(drive)
    thetas = np.mod(
        np.array([t_a, 0.5 * (t_a + t_b), t_b, 0.5 * (t_a + t_b) + np.pi]) * i12, period
    )
    names = np.array(["equal speed", "between", "equal speed", "between"])[np.argsort(thetas)]
    thetas = np.sort(thetas)
    motion = gb.motion(drive, thetas)
    vanes = vp.vane_angles(pump, motion)  # (2, Z, 4)
    phi, dphi, _, _ = vp.chamber_angles(pump, motion)
    k = pump.volume_per_angle * 1e6
    z = int(pump.vanes_per_impeller)
    rh, rc, g = pump.hub_radius * 1e3, pump.casing_radius * 1e3, float(pump.vane_angle)
    from matplotlib.patches import Patch, Wedge  # with pyplot, not when the drive is imported

    fig, axes = plt.subplots(1, 4, figsize=(16, 5.2))
    for n, ax in enumerate(axes):
        ax.add_patch(Wedge((0, 0), rc * 1.04, 0, 360, width=rc * 0.04, color="0.3"))
        ax.add_patch(Wedge((0, 0), rh, 0, 360, color="0.85"))
        for j in range(2 * z):
            m, kind = divmod(j, 2)
            start = vanes[kind, m, n] + 0.5 * g  # trailing vane's leading face
            rate = dphi[j, n]
            colour = "0.75" if abs(rate) < 1e-9 else (_DISCHARGE if rate < 0 else _SUCTION)
            ax.add_patch(Wedge((0, 0), rc, np.degrees(start), np.degrees(start + phi[j, n]),
                               width=rc - rh, color=colour, alpha=0.35, lw=0))  # fmt: skip
            if phi[j, n] > np.radians(8.0):
                mid = start + 0.5 * phi[j, n]
                ax.text(0.5 * (rc + rh) * np.cos(mid), 0.5 * (rc + rh) * np.sin(mid),
                        f"{'AB'[kind]}{m + 1}", ha="center", va="center", fontsize=8)  # fmt: skip
        for kind, colour in ((0, "k"), (1, "C2")):
            for m in range(z):
                c = vanes[kind, m, n]
                ax.add_patch(Wedge((0, 0), rc, np.degrees(c - 0.5 * g), np.degrees(c + 0.5 * g),
                                   width=rc - rh, color=colour, alpha=0.85, lw=0))  # fmt: skip
                ax.plot([rh * np.cos(c), rc * np.cos(c)], [rh * np.sin(c), rc * np.sin(c)],
                        color="w", lw=0.6, ls=":")  # fmt: skip
        ax.set_xlim(-1.1 * rc, 1.1 * rc)
        ax.set_ylim(-1.1 * rc, 1.1 * rc)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_title(f"theta = {np.degrees(thetas[n]):.1f} deg ({names[n]})\n"
                     f"V_A = {phi[0, n] * k:.4g} cm^3, V_B = {phi[1, n] * k:.4g} cm^3",
                     fontsize=9)  # fmt: skip
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("y [mm]")
    handles = [Patch(color="k", label="impeller 1 vanes"),
               Patch(color="C2", label="impeller 2 vanes"),
               Patch(color=_DISCHARGE, alpha=0.35, label="chamber shrinking: discharge port"),
               Patch(color=_SUCTION, alpha=0.35, label="chamber growing: suction port"),
               Patch(color="0.75", alpha=0.35, label="at rest: port switch-over")]  # fmt: skip
    fig.legend(handles=handles, loc="lower center", ncol=5, fontsize=9)
    fig.suptitle("Pump cross-sections (sense of rotation counter-clockwise)\n"
                 + _pump_tag(pump, ports), fontsize=10)  # fmt: skip
    fixed_layout(fig, 0.85, 0.52, 0.15, 0.64, 0.6)
    return save_in(fig, path.parent, path.name)


def fig_pump_chambers(pump, ports, theta, state, path: Path) -> Path:
    """Chamber volumes and pressures over a period (A and B chambers), ports shaded."""
    plt = _plt()
    deg = np.degrees(theta)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 7), sharex=True,
                                   gridspec_kw={"height_ratios": [2, 1]})  # fmt: skip
    z = int(pump.vanes_per_impeller)
    for ax in (ax1, ax2):
        _shade_strokes(ax, theta, state["dV"][0])
    ax1.plot(deg, state["V"][0] * 1e6, "C0", lw=2, label=f"chambers A (x{z}): impeller 1 -> 2")
    ax1.plot(deg, state["V"][1] * 1e6, "C1", lw=2, label=f"chambers B (x{z}): impeller 2 -> 1")
    total = (state["V"][0] + state["V"][1]) * 1e6
    same = np.allclose(total, pump.chamber_angle_range[1] * pump.volume_per_angle * 1e6)
    ax1.plot(deg, total, color="C2", lw=4, alpha=0.35,
             label="A + B (constant" + (", = V_max)" if same else ")"))  # fmt: skip
    lo, hi = pump.chamber_angle_range
    k = pump.volume_per_angle * 1e6
    ax1.axhline(lo * k, color="k", lw=0.8, ls="--")
    ax1.axhline(hi * k, color="k", lw=0.8, ls="--")
    ax1.annotate(f"V_max = {hi * k:.4g} cm^3", (deg[-1], hi * k), xytext=(-6, 4),
                 textcoords="offset points", ha="right", fontsize=8)  # fmt: skip
    ax1.annotate(f"V_min = {lo * k:.4g} cm^3", (deg[-1], lo * k), xytext=(-6, 4),
                 textcoords="offset points", ha="right", fontsize=8)  # fmt: skip
    _theta_axis(ax1, theta, "chamber volume [cm^3]")
    ax1.set_xlabel("")
    ax1.legend(fontsize=8, loc="center right")
    ax1.set_title("Chamber volumes over one period (background: chambers A discharging red, "
                  "sucking blue)\n" + _pump_tag(pump, ports), fontsize=9)  # fmt: skip
    ax2.plot(deg, state["p"][0] / 1e5, "C0", lw=2, label="chambers A")
    ax2.plot(deg, state["p"][1] / 1e5, "C1", lw=1.5, ls="--", label="chambers B")
    _theta_axis(ax2, theta, "pressure [bar]")
    span = abs(ports.discharge_pressure - ports.suction_pressure) / 1e5
    ax2.set_ylim(
        min(ports.suction_pressure, ports.discharge_pressure) / 1e5 - 0.15 * span - 0.1,
        max(ports.suction_pressure, ports.discharge_pressure) / 1e5 + 0.15 * span + 0.1,
    )
    ax2.legend(fontsize=8, loc="center right")
    return _save(fig, path, layout=(0.85, 0.6, 0.3, 0.5, 0.0, 0.21))


def fig_pump_flow(pump, ports, theta, state, summary, path: Path) -> Path:
    """Delivered flow over a period, its mean and ripple."""
    plt = _plt()
    deg = np.degrees(theta)
    q = state["flow"] * 60.0e3
    fig, ax = plt.subplots(figsize=(9, 5))
    _shade_strokes(ax, theta, state["dV"][0])
    ax.plot(deg, q, "k", lw=2, label="delivered flow Q")
    mean = summary["flow_mean_l_per_min"]
    ax.axhline(mean, color="C2", ls="--", label=f"mean {mean:.4g} L/min")
    ax.set_ylim(bottom=0.0)
    _theta_axis(ax, theta, "flow [L/min]")
    ax.legend(fontsize=8, loc="upper right")
    rpm = summary["shaft_speed_mean_rpm"]
    ax.set_title(
        f"Pump flow at {rpm:.5g} rpm: displacement {summary['displacement_cm3_per_rev']:.4g} "
        f"cm^3 per input turn, ripple (max - min)/mean = {summary['flow_ripple']:.3g}\n"
        + _pump_tag(pump, ports),
        fontsize=9,
    )
    return _save(fig, path, layout=(0.85, 0.6, 0.3, 0.5))


def fig_pump_torque(pump, ports, theta, state, summary, path: Path) -> Path:
    """Input-shaft torque with and without inertia, and the torques on the impellers."""
    plt = _plt()
    deg = np.degrees(theta)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 7.5), sharex=True)
    ax1.plot(deg, state["shaft"], "C0", lw=2, label="fluid only (virtual work)")
    ax1.plot(deg, state["net"], "C3", lw=1.5, label="fluid + inertia of shaft and impellers")
    ax1.axhline(summary["mean_torque_Nm"], color="k", ls="--", lw=1,
                label=f"mean {summary['mean_torque_Nm']:.4g} N*m")  # fmt: skip
    _theta_axis(ax1, theta, "torque on input gear 1 [N*m]")
    ax1.set_xlabel("")
    ax1.legend(fontsize=8, loc="lower right")
    fly = summary["flywheel_inertia_kgm2"]
    ax1.set_title(
        "Torque of the pump on the input shaft (negative: the motor drives), at "
        f"{summary['shaft_speed_mean_rpm']:.5g} rpm; flywheel for C_s = "
        f"{summary['speed_fluctuation']:.3g}: {fly:.3g} kg*m^2\n" + _pump_tag(pump, ports),
        fontsize=9,
    )
    ax2.plot(deg, state["M"][0], "k", lw=1.5, label="impeller 1: sum p dV/dq_1")
    ax2.plot(deg, state["M"][1], "C2", lw=1.5, ls="--", label="impeller 2: sum p dV/dq_2")
    _theta_axis(ax2, theta, "pressure torque on impeller [N*m]")
    ax2.legend(fontsize=8, loc="lower right")
    return _save(fig, path, layout=(0.95, 0.6, 0.3, 0.5, 0.0, 0.21))


def fig_forces(theta, pairs, model: pr.ContactModel, summary, path: Path) -> Path:
    """Forces in the pairs over a period: slider and pins, pivots and bearings, gear meshes,
    and the meshes' Hertz pressure against the allowable."""
    plt = _plt()
    deg = np.degrees(theta)
    fig, axes = plt.subplots(4, 1, figsize=(9, 11), sharex=True)

    # the crank pin carries the slider's force, an impeller's bearing its mesh's normal force
    also = {"sliding": " = crank pin", "mesh": ""}

    def shown(p):
        return not p.slug.startswith(("crank_pin", "impeller1_bearing", "impeller2_bearing"))

    groups = (
        ("slider on guide bar = crank pin [N]", lambda p: p.kind == "sliding"),
        ("pivots and bearings [N]", lambda p: p.kind == "bearing" and shown(p)),
        ("gear meshes, tooth normal force [N]", lambda p: p.kind == "mesh"),
    )
    for ax, (label, chosen) in zip(axes[:3], groups, strict=False):
        for p in filter(chosen, pairs):
            ls = "--" if "2" in p.slug or p.slug == "input_bearing" else "-"
            extra = also.get(p.kind, "")
            if p.slug.startswith("impeller_mesh"):
                extra = f" = impeller {p.slug[-1]} bearing"
            ax.plot(deg, np.abs(p.force), lw=1.4, ls=ls, label=p.name + extra)
        _theta_axis(ax, theta, label)
        ax.set_xlabel("")
        ax.set_ylim(bottom=0.0)
        ax.legend(fontsize=7, loc="upper right", ncol=2)
    ax = axes[3]
    for p in pairs:
        st = pr.stress(p, model)
        if st is not None:
            ls = "--" if "2" in p.slug else "-"
            ax.plot(deg, st / 1e6, lw=1.4, ls=ls, label=p.name)
    ax.axhline(model.allowable_stress / 1e6, color="C3", lw=1, ls=":",
               label=f"allowable {model.allowable_stress / 1e6:.4g} MPa")  # fmt: skip
    _theta_axis(ax, theta, "Hertz pressure [MPa]")
    ax.set_ylim(bottom=0.0)
    ax.legend(fontsize=7, loc="upper right", ncol=2)
    eta = summary.get("mechanical_efficiency", float("nan"))
    axes[0].set_title(
        f"Forces in the pairs at {summary.get('shaft_speed_mean_rpm', float('nan')):.5g} rpm "
        f"(pump torques, ideal ports, and impeller inertia); friction loss "
        f"{summary.get('friction_loss_W', float('nan')):.4g} W, efficiency {100 * eta:.4g} %",
        fontsize=9,
    )
    return _save(fig, path, layout=(0.95, 0.6, 0.3, 0.33, 0.0, 0.24))


def plot_all(params: gb.GuideBar, m7: float, m8: float, outdir: Path, pump=None, ports=None,
             theta=None, state=None, summary=None, pairs=None,
             contact=None) -> list[Path]:  # fmt: skip
    """Write every figure of the drive (and of the pump, when given) into ``outdir``.

    Parameters
    ----------
    params : GuideBar
    m7, m8 : float
        The paper's constant impeller torques [N*m] (Fig. 10, 11).
    outdir : Path
    pump, ports : VanePump, PortPressures, optional
    theta, state, summary : optional
        Input angles, :func:`rotorkin.drives.guide_bar.pump.pump_state` on them and
        the study's summary; needed with ``pump``.
    pairs, contact : list of Pair, ContactModel, optional
        The pairs at ``theta`` and the contact model: ``forces.png``.

    Returns
    -------
    list of Path
    """
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    p = functools.partial
    tasks = [
        p(fig_speed_ratios, params, "crank", outdir / "fig03_speed_crank_driven.png", 3),
        p(fig_speed_ratios, params, "guide", outdir / "fig05_speed_guide_driven.png", 5),
        p(fig_vane_angle, params, outdir / "fig09_lambda_vane_angle.png"),
        p(fig_input_torque, params, "crank", m7, m8, outdir / "fig10_torque_crank_driven.png", 10),
        p(fig_input_torque, params, "guide", m7, m8, outdir / "fig11_torque_guide_driven.png", 11),
        p(fig_relative_angle, params, outdir / "fig_relative_angle.png"),
    ]
    if pump is not None:
        tasks += [
            p(fig_pump_sections, params, pump, ports, outdir / "pump_sections.png"),
            p(fig_pump_chambers, pump, ports, theta, state, outdir / "pump_chambers.png"),
            p(fig_pump_flow, pump, ports, theta, state, summary, outdir / "pump_flow.png"),
            p(fig_pump_torque, pump, ports, theta, state, summary, outdir / "pump_torque.png"),
        ]
    if pairs:
        tasks.append(p(fig_forces, theta, pairs, contact or pr.ContactModel(), summary or {},
                       outdir / "forces.png"))  # fmt: skip
    return draw(tasks)
