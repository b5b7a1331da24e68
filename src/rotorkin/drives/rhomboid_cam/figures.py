"""Figures of the rhomboid lever-cam converter (Zhuravlev et al. 2012: Fig. 1, eq. 13-34)
and of the rotary-blade engine built on it (chambers, p-V diagram, torques, blade layout).

matplotlib is imported when a figure is drawn (:func:`rotorkin.render.figures.pyplot`);
the backend is the caller's.
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.render.figures import draw, fixed_layout, pyplot, save, save_in

__all__ = [
    "plot_all",
    "sample_law",
    "fig_cam_profile",
    "fig_psi_law",
    "fig_blade_motion",
    "fig_work_loop",
    "plot_machine",
    "fig_chamber_volumes",
    "fig_pv_diagram",
    "fig_shaft_torque",
    "fig_blade_layout",
    "fig_forces",
]

_COLOURS = ("C0", "C1", "C2", "C3")


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
    plt = pyplot()
    law = (params.link_length, params.psi_min, params.a, params.b)
    t = np.linspace(0.0, 2.0 * np.pi, 1441)
    xy = rc.profile_point(*law, t)[0] * 1e3
    rot = np.array([[0.0, 1.0], [-1.0, 0.0]]) @ xy  # eq. 19 form: turned by -90 deg
    fig, ax = plt.subplots(figsize=(11.5, 7.5))
    ax.plot(xy[0], xy[1], "k-", lw=2.0, label="pitch curve rho = 2l cos(psi/2) (eq. 3)")
    ax.plot(rot[0], rot[1], color="0.6", ls=":", lw=1.2,
            label="eq. 19 form 2l sin(psi/2): the same cam turned 90 deg")  # fmt: skip
    al = np.radians(np.asarray(alphas_deg, dtype=float))
    v = rc.rhombus_vertices(*law, al) * 1e3  # (4, 2, n)
    mid = rc.blade_arm_points(*law, al) * 1e3
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
    return save(fig, Path(outdir) / "fig01_cam_profile.png", layout=(0.15, 0.6, 2.05, 0.53))


def fig_psi_law(params, outdir: Path, points: int = 1441) -> Path:
    """``psi``, ``psi'``, ``psi''``: the config's law and a 1st+3rd-harmonic law (eq. 13-18)."""
    plt = pyplot()
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
        p = rc.psi_law(params.psi_min, a, b, al)
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
    return save(fig, Path(outdir) / "fig02_psi_law.png", layout=(0.9, 0.6, 0.15, 0.64, 0.0, 0.21))


def fig_blade_motion(params, outdir: Path, points: int = 1441) -> Path:
    """Blade angles, speed coefficients ``1 +- psi'/2``, accelerations ``+-psi''/2`` (eq. 22)."""
    plt = pyplot()
    al = np.linspace(0.0, np.pi, points)
    q, d1, d2, _ = rc.blade_angles(params.psi_min, params.a, params.b, al)
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
    return save(
        fig, Path(outdir) / "fig03_blade_motion.png", layout=(0.85, 0.6, 0.15, 0.64, 0.0, 0.21)
    )


def fig_work_loop(params, torque_high, torque_low, outdir: Path, points: int = 1441) -> Path:
    """Blade torque against ``psi`` (compression and expansion) and ``dA/dalpha`` (eq. 24-34)."""
    plt = pyplot()
    law = (params.psi_min, params.a, params.b)
    al = np.linspace(0.0, np.pi, points)
    psi, d1 = rc.psi_law(*law, al)[:2]
    s = rc.stroke_direction(*law, al)
    m = rc.blade_torque(torque_high, torque_low, params.psi_min, psi, s)
    work = float(rc.indicator_work(*law, torque_high, torque_low))
    lo, _, hi, _ = rc.psi_extremes(*law)
    g = np.linspace(lo, hi, 201)
    mp = rc.blade_torque(torque_high, torque_low, params.psi_min, g, 1.0)
    mc = rc.blade_torque(torque_high, torque_low, params.psi_min, g, -1.0)
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
    return save(fig, Path(outdir) / "fig04_work_loop.png", layout=(0.95, 0.6, 0.15, 0.64, 0.85))


def figure_tasks(params, torque_high, torque_low, outdir: Path) -> list:
    """The figures of :func:`plot_all` as tasks (:func:`rotorkin.render.figures.draw`)."""
    outdir = Path(outdir)
    p = functools.partial
    return [
        p(fig_cam_profile, params, outdir),
        p(fig_psi_law, params, outdir),
        p(fig_blade_motion, params, outdir),
        p(fig_work_loop, params, float(torque_high), float(torque_low), outdir),
    ]


def plot_all(params, torque_high, torque_low, outdir: Path) -> list[Path]:
    """Write every figure of the drive into ``outdir``; return the paths."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return draw(figure_tasks(params, torque_high, torque_low, outdir))


# --- the rotary-blade engine ---------------------------------------------------------------
def _machine_tag(machine, loads) -> str:
    m = machine
    geo = (
        f"B = {m.blades_per_pair} blades/pair, t = {np.degrees(m.blade_thickness):.4g} deg, "
        f"R_i = {m.inner_radius * 1e3:.4g} mm, R_o = {m.outer_radius * 1e3:.4g} mm, "
        f"w = {m.axial_width * 1e3:.4g} mm"
    )
    if loads.stirling is not None:
        g = loads.gas
        return (
            f"{geo}; {loads.model} Stirling circuits ({g.gas}): p_charge = "
            f"{g.charge_pressure * 1e-5:.4g} bar, T_h = {g.hot_temperature:.4g} K, "
            f"T_k = {g.cold_temperature:.4g} K, cold set {np.degrees(g.phase_angle):.4g} deg behind"
        )
    if loads.model == "isothermal":
        g = loads.gas
        return (
            f"{geo}; isothermal gas: p_charge = {g.charge_pressure * 1e-5:.4g} bar, "
            f"T_h = {g.hot_temperature:.4g} K, T_c = {g.cold_temperature:.4g} K"
        )
    return (
        f"{geo}; linear blade torque (eq. 29): M1 = {loads.torque_high:.4g} N m, "
        f"M2 = {loads.torque_low:.4g} N m"
    )


def _families(machine):
    """(index, label, colour) of the even and odd chambers (identical within a family)."""
    B = machine.blades_per_pair
    s = "s" if B > 1 else ""
    even = ", ".join(str(j + 1) for j in range(0, 2 * B, 2))
    odd = ", ".join(str(j + 1) for j in range(1, 2 * B, 2))
    return (
        (0, f"chamber{s} {even} (angle psi - t)", "C0"),
        (1, f"chamber{s} {odd} (angle {360 / B:.4g} deg - psi - t)", "C3"),
    )


def fig_chamber_volumes(machine, loads, state, summary, outdir: Path) -> Path:
    """Chamber volumes and ``dV/dalpha`` over one output-shaft revolution."""
    plt = pyplot()
    al = np.linspace(0.0, 2.0 * np.pi, 1441)
    st = state(al)
    ad = np.degrees(al)
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(9.5, 8), sharex=True)
    for j, label, c in _families(machine):
        ax.plot(ad, st.volume[j] * 1e6, color=c, lw=2.0, label=label)
        bx.plot(ad, st.dvolume[j] * 1e6, color=c, lw=2.0, label=label)
    vmax, vmin = summary["chamber_volume_max_cm3"], summary["chamber_volume_min_cm3"]
    for v, name in ((vmax, "V_max"), (vmin, "V_min")):
        ax.axhline(v, color="0.4", lw=0.8, ls="--")
        ax.annotate(f"{name} = {v:.4g} cm^3", (358, v), xytext=(0, 3),
                    textcoords="offset points", ha="right", fontsize=8)  # fmt: skip
    ax.set_ylabel("chamber volume [cm^3]")
    ax.set_ylim(0.0, 1.3 * vmax)
    ax.set_title(
        f"compression ratio {summary['compression_ratio_geometric']:.4g}, displacement "
        f"{summary['displacement_cm3_per_rev']:.5g} cm^3 per output-shaft revolution",
        fontsize=10,
    )
    k = summary["sector_volume_cm3_per_rad"]
    right = ax.secondary_yaxis(
        "right", functions=(lambda v: np.degrees(v / k), lambda g: np.radians(g) * k)
    )
    right.set_ylabel("chamber angle [deg]")
    bx.axhline(0.0, color="k", lw=0.6)
    bx.set_ylabel("dV/dalpha [cm^3/rad]")
    bx.set_xlabel("output-shaft angle alpha [deg]")
    bx.set_xticks(np.arange(0, 361, 45))
    for a in (ax, bx):
        a.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="upper center", ncol=2)
    fig.suptitle(f"Rotary-blade engine: chambers\n{_machine_tag(machine, loads)}", fontsize=9)
    return save(
        fig, Path(outdir) / "fig05_chamber_volumes.png", layout=(0.95, 0.6, 0.75, 0.8, 0.0, 0.24)
    )


def fig_pv_diagram(machine, loads, state, summary, outdir: Path) -> Path:
    """p-V diagram of the chambers, isothermal model (the ideal Stirling loop)."""
    plt = pyplot()
    al = np.linspace(0.0, np.pi, 4001)
    st = state(al)
    g = loads.gas
    fig, ax = plt.subplots(figsize=(9.5, 6.5))
    dT = g.hot_temperature - g.cold_temperature
    for j, label, c in _families(machine):
        v, p = st.volume[j] * 1e6, st.pressure[j] * 1e-5
        lo, hi = float(np.min(st.volume[j])), float(np.max(st.volume[j]))
        w = float(loads.charge[j] * dT * np.log(hi / lo))
        vv, pp = np.append(v, v[0]), np.append(p, p[0])  # close the loop
        ax.fill(vv, pp, color=c, alpha=0.12 if j == 0 else 0.05)
        ax.plot(vv, pp, "-" if j == 0 else "--", color=c, lw=2.0,
                label=f"{label}: {w:.4g} J per cycle")  # fmt: skip
    v, p = st.volume[0] * 1e6, st.pressure[0] * 1e-5
    for sign, text in ((1, f"expansion at T_h = {g.hot_temperature:.4g} K"),
                       (-1, f"compression at T_c = {g.cold_temperature:.4g} K")):  # fmt: skip
        idx = np.flatnonzero(st.stroke == sign)
        m, n = idx[len(idx) // 3], idx[len(idx) // 3 + 60]
        ax.annotate("", (v[n], p[n]), (v[m], p[m]),
                    arrowprops={"arrowstyle": "-|>", "color": "k", "lw": 1.5,
                                "mutation_scale": 18})  # fmt: skip
        ax.annotate(text, (v[m], p[m]), xytext=(12 * sign, 12 * sign), fontsize=9,
                    textcoords="offset points", va="bottom" if sign > 0 else "top",
                    ha="left" if sign > 0 else "right")  # fmt: skip
    vmin, vmax = summary["chamber_volume_min_cm3"], summary["chamber_volume_max_cm3"]
    ax.annotate("isochoric heating\n(regenerator)", (vmin, 0.55 * p.max()),
                xytext=(8, 0), textcoords="offset points", fontsize=8, color="0.3")  # fmt: skip
    ax.annotate("isochoric cooling", (vmax, 1.6 * p.min()), xytext=(-8, 0),
                textcoords="offset points", fontsize=8, color="0.3", ha="right")  # fmt: skip
    ax.set_xlabel("chamber volume V [cm^3]")
    ax.set_ylabel("absolute pressure p [bar]")
    ax.set_xlim(0.0, 1.08 * vmax)
    ax.set_ylim(0.0, 1.08 * summary["pressure_max_bar"])
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title(
        f"p-V diagram, isothermal gas: W = m R (T_h - T_c) ln(V_max/V_min) per cycle; "
        f"{summary['indicated_work_J']:.5g} J/rev, {summary['indicated_power_kW']:.4g} kW "
        f"at {summary['shaft_speed_mean_rpm']:.5g} rpm",
        fontsize=9,
    )
    fig.suptitle(_machine_tag(machine, loads), fontsize=8)
    return save(fig, Path(outdir) / "fig06_pv_diagram.png", layout=(0.75, 0.6, 0.15, 0.6))


def fig_shaft_torque(machine, loads, curves, summary, outdir: Path) -> Path:
    """Output-shaft torque with and without inertia, ``J_eq`` and the energy swing."""
    plt = pyplot()
    al = curves["alpha"]
    ad = np.degrees(al)
    gas, inert = curves["state"].torque, curves["inertia_torque"]
    mean = summary["mean_torque_Nm"]
    fig, (ax, bx, cx) = plt.subplots(3, 1, figsize=(9.5, 10), sharex=True,
                                     gridspec_kw={"height_ratios": [2.2, 1, 1.2]})  # fmt: skip
    ax.plot(ad, gas, "C2", lw=2.0, label=f"loads ({loads.model} model), without inertia")
    ax.plot(ad, gas - inert, "k", lw=1.4, label="with inertia (loads - inertia torque)")
    ax.plot(ad, inert, "C1", lw=1.0, ls="--", label="inertia torque of shaft and blade pairs")
    ax.axhline(mean, color="C2", ls=":", lw=1.2, label=f"mean {mean:.4g} N m")
    ax.axhline(0.0, color="0.3", lw=0.6)
    ax.set_ylabel("output-shaft torque [N m]")
    ax.set_title(
        f"torque ripple (max - min)/mean {summary['torque_ripple']:.3g}; with inertia "
        f"{summary['torque_ripple_with_inertia']:.3g} at {summary['shaft_speed_mean_rpm']:.5g} rpm",
        fontsize=10,
    )
    lo, hi = min(np.min(gas), np.min(inert)), max(np.max(gas), np.max(inert), np.max(gas - inert))
    ax.set_ylim(lo - 0.05 * (hi - lo), hi + 0.4 * (hi - lo))
    ax.legend(fontsize=8, loc="upper center", ncol=2)
    bx.plot(ad, curves["equivalent_inertia"], "C4", lw=1.8)
    bx.set_ylabel("J_eq [kg m^2]")
    energy = np.concatenate(([0.0], np.cumsum(0.5 * (curves["steady"][1:] + curves["steady"][:-1])
                                              * np.diff(al))))  # fmt: skip
    energy -= energy[-1] / (al[-1] - al[0]) * (al - al[0])  # remove the mean torque's share
    label = "E = integral (T_loads - T_inertia - T_mean) d alpha, inertia at the mean speed"
    cx.plot(ad, energy, "C0", lw=1.8, label=label)
    cx.axhspan(energy.min(), energy.max(), color="C0", alpha=0.08)
    cx.set_ylabel("energy [J]")
    cx.set_title(
        f"Delta E = {summary['energy_fluctuation_J']:.4g} J: speed fluctuation "
        f"{summary['speed_fluctuation_without_flywheel']:.3g} without flywheel; flywheel "
        f"{summary['flywheel_inertia_kgm2']:.3g} kg m^2 for {summary['speed_fluctuation']:.3g}",
        fontsize=10,
    )
    span = energy.max() - energy.min()
    cx.set_ylim(energy.min() - 0.05 * span, energy.max() + 0.45 * span)
    cx.legend(fontsize=8, loc="upper center")
    cx.set_xlabel("output-shaft angle alpha [deg] (one period of the machine)")
    cx.set_xticks(np.arange(0, 181, 30))
    for a in (ax, bx, cx):
        a.grid(True, alpha=0.4)
    fig.suptitle(f"Output-shaft torque and flywheel\n{_machine_tag(machine, loads)}", fontsize=9)
    return save(
        fig, Path(outdir) / "fig07_shaft_torque.png", layout=(0.97, 0.6, 0.15, 0.8, 0.0, 0.4)
    )


def fig_blade_layout(params, machine, loads, state, outdir: Path,
                     alphas_deg=(0.0, 30.0, 60.0, 90.0)) -> Path:  # fmt: skip
    """Cross-sections of the working space at a few shaft angles: blades and chambers."""
    plt = pyplot()
    Circle, Wedge = plt.Circle, plt.matplotlib.patches.Wedge

    al = np.radians(np.asarray(alphas_deg, dtype=float))
    st = state(al)
    q = st.motion.q
    B, t = machine.blades_per_pair, np.degrees(machine.blade_thickness)
    ri, ro = machine.inner_radius * 1e3, machine.outer_radius * 1e3
    fig, axes = plt.subplots(2, 2, figsize=(10, 10.5))
    for n, ax in enumerate(axes.flat[: len(alphas_deg)]):
        ax.add_patch(Circle((0, 0), ro, fill=False, lw=1.5, color="k"))
        ax.add_patch(Circle((0, 0), ri, color="0.85", ec="k", lw=1.0))
        p1, p2 = np.degrees(q[0, n]), np.degrees(q[1, n])
        for m in range(B):
            step = 360.0 * m / B
            for j, (a0, a1) in enumerate(
                ((p2 + step, p1 + step), (p1 + step, p2 + step + 360 / B))
            ):
                c = "C0" if j == 0 else "C3"
                ax.add_patch(Wedge((0, 0), ro, a0 + t / 2, a1 - t / 2, width=ro - ri,
                                   color=c, alpha=0.15))  # fmt: skip
                mid = np.radians(0.5 * (a0 + a1))
                k = 2 * m + j
                text = f"{k + 1}\n{st.volume[k, n] * 1e6:.0f} cm3"
                if st.pressure is not None:
                    text += f"\n{st.pressure[k, n] * 1e-5:.3g} bar"
                rr = 0.5 * (ri + ro)
                ax.text(rr * np.cos(mid), rr * np.sin(mid), text, ha="center", va="center",
                        fontsize=7)  # fmt: skip
            for ang, c in ((p1 + step, "C0"), (p2 + step, "C3")):
                ax.add_patch(Wedge((0, 0), ro, ang - t / 2, ang + t / 2, width=ro - ri,
                                   color=c, ec="k", lw=0.6))  # fmt: skip
        a = al[n]
        ax.annotate("", (0.9 * ri * np.cos(a), 0.9 * ri * np.sin(a)), (0, 0),
                    arrowprops={"arrowstyle": "-|>", "color": "k", "lw": 1.5})  # fmt: skip
        psi = np.degrees(q[0, n] - q[1, n])
        ax.set_title(f"alpha = {alphas_deg[n]:g} deg, psi = {psi:.4g} deg", fontsize=10)
        ax.set_xlim(-1.1 * ro, 1.1 * ro)
        ax.set_ylim(-1.1 * ro, 1.1 * ro)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.grid(True, alpha=0.3)
    axes.flat[0].plot([], [], "s", color="C0", label="blade pair 1 (phi_1 = alpha + psi/2)")
    axes.flat[0].plot([], [], "s", color="C3", label="blade pair 2 (phi_2 = alpha - psi/2)")
    axes.flat[0].plot([], [], "k-", label="arrow: output-shaft angle alpha")
    fig.legend(*axes.flat[0].get_legend_handles_labels(), loc="lower center", ncol=3, fontsize=8)
    fig.suptitle(
        f"Working space: chambers numbered counter-clockwise from blade pair 2\n"
        f"{_machine_tag(machine, loads)}",
        fontsize=9,
    )
    fixed_layout(fig, 0.85, 0.83, 0.15, 0.72, 0.85, 0.63)
    return save_in(fig, outdir, "fig08_blade_layout.png")


def fig_forces(machine, loads, curves, summary, outdir: Path) -> Path:
    """Forces in the converter over a period: rollers, guides, links; the rollers' Hertz pressure.

    ``curves["forces"]`` is :class:`rotorkin.drives.rhomboid_cam.forces.Forces` and
    ``curves["pairs"]`` its pairs on ``curves["alpha"]``; ``curves["contact"]`` the
    :class:`rotorkin.analysis.pairs.ContactModel`.
    """
    from rotorkin.analysis.pairs import stress

    plt = pyplot()
    ad = np.degrees(curves["alpha"])
    fo = curves["forces"]
    fig, axes = plt.subplots(4, 1, figsize=(9.5, 12), sharex=True)
    ax, bx, cx, dx = axes
    for k, v in enumerate("AB"):
        ax.plot(ad, fo.roller[k], _COLOURS[k], lw=1.8, label=f"roller {v} (and {'CD'[k]})")
    ax.set_ylabel("cam on roller [N]")
    ax.set_title(f"peak roller force {summary['peak_roller_force_N']:.4g} N at "
                 f"{summary['shaft_speed_mean_rpm']:.5g} rpm; A, C carry while the blades' "
                 "loads open psi, B, D while they close it", fontsize=9)  # fmt: skip
    for k, v in enumerate("AB"):
        bx.plot(ad, fo.guide[k], _COLOURS[k], lw=1.6, label=f"guide {v} (and {'CD'[k]})")
    bx.axhline(0.0, color="0.3", lw=0.6)
    bx.set_ylabel("guide on block [N]\n(+ shaft drives)")
    for j, name in enumerate(("AB", "BC")):
        for half in (0, 1):
            cx.plot(ad, fo.tension[j, half], _COLOURS[2 + j], lw=1.4, ls=("-", "--")[half],
                    label=f"link {name}, half at {name[half]}")  # fmt: skip
    cx.axhline(0.0, color="0.3", lw=0.6)
    cx.set_ylabel("link axial force [N]\n(+ tension)")
    model = curves["contact"]
    for k, pair in enumerate(curves["pairs"][:2]):
        p = stress(pair, model)
        if p is not None:
            dx.plot(ad, p / 1e6, _COLOURS[k], lw=1.6, label=f"{pair.name} (and {'CD'[k]})")
    dx.axhline(model.allowable_stress / 1e6, color="C3", ls=":", lw=1.2,
               label=f"allowable {model.allowable_stress / 1e6:.4g} MPa")  # fmt: skip
    dx.set_ylabel("Hertz pressure [MPa]")
    dx.set_xlabel("output-shaft angle alpha [deg] (one period of the machine)")
    dx.set_xticks(np.arange(0, 181, 30))
    for a in axes:
        a.grid(True, alpha=0.4)
        a.legend(fontsize=8, loc="upper right")
    fig.suptitle(f"Forces in the converter (blade loads and inertia at the run speed)\n"
                 f"{_machine_tag(machine, loads)}", fontsize=9)  # fmt: skip
    return save(fig, Path(outdir) / "fig09_forces.png", layout=(1.2, 0.6, 0.15, 0.79, 0.0, 0.22))


def plot_machine(params, machine, loads, state, curves, summary, outdir: Path) -> list[Path]:
    """Write the engine's figures (fig05-fig08; fig06, the p-V diagram, needs pressures).

    Parameters
    ----------
    state : callable
        ``state(alpha) -> rotorkin.drives.rhomboid_cam.engine.State``.
    curves : dict
        The study's fine samples over one period (``alpha``, ``state``,
        ``inertia_torque``, ``steady``, ``equivalent_inertia``; ``forces``, ``pairs``,
        ``contact`` for :func:`fig_forces`).
    summary : dict
        The study's summary.
    """
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return draw(machine_tasks(params, machine, loads, state, curves, summary, outdir))


def machine_tasks(params, machine, loads, state, curves, summary, outdir: Path) -> list:
    """The figures of :func:`plot_machine` as tasks (:func:`rotorkin.render.figures.draw`)."""
    outdir = Path(outdir)
    p = functools.partial
    tasks = [p(fig_chamber_volumes, machine, loads, state, summary, outdir)]
    if loads.model == "isothermal":
        tasks.append(p(fig_pv_diagram, machine, loads, state, summary, outdir))
    tasks.append(p(fig_shaft_torque, machine, loads, curves, summary, outdir))
    tasks.append(p(fig_blade_layout, params, machine, loads, state, outdir))
    if "forces" in curves:
        tasks.append(p(fig_forces, machine, loads, curves, summary, outdir))
    return tasks
