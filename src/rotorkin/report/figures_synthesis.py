"""Figures of ``rotorkin synthesize``: the baseline (paper's) design beside the synthesized one.

One function per drive family, each ``plot_<drive>(outdir, ...) -> list[Path]``
writing PNG files (dpi 120). Degrees and millimetres here only.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["plot_rhomboid", "plot_wobble", "plot_guide_bar", "plot_eccentric"]

_DPI = 120
_BASE = {"color": "0.45", "lw": 1.6, "label": "baseline (paper)"}
_SYN = {"color": "C3", "lw": 1.8, "label": "synthesized"}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, outdir, name) -> Path:
    path = Path(outdir) / name
    fig.savefig(path, dpi=_DPI)
    _plt().close(fig)
    return path


def _deg_axis(ax, end, step, label):
    ax.set_xlim(0.0, end)
    ax.set_xticks(np.arange(0.0, end + 1e-9, step))
    if label:
        ax.set_xlabel(label)
    ax.grid(True, alpha=0.4)


# --------------------------------------------------------------------------------------------
# rhomboid cam
# --------------------------------------------------------------------------------------------
def plot_rhomboid(outdir, link_length, psi_min, a, b, roller_radius, objective, pa_limit):
    """psi laws, blade speed and acceleration; pitch curves, profiles and pressure angles."""
    from rotorkin.cams import rhomboid as cam
    from rotorkin.drives import rhomboid_cam as rc
    from rotorkin.synthesis import DWELL_TOLERANCE

    plt = _plt()
    alpha = np.linspace(0.0, np.pi, 1441)
    x = np.degrees(alpha)
    laws = (((), ()), (tuple(a), tuple(b)))
    styles = (_BASE | {"label": "first harmonic (eq. 16, paper)"}, _SYN)
    fig, axes = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    tol = np.degrees(DWELL_TOLERANCE * (np.pi - 2.0 * psi_min))
    for ext in (np.degrees(psi_min), 180.0 - np.degrees(psi_min)):
        axes[0].axhspan(ext - tol, ext + tol, color="C2", alpha=0.15, lw=0)
    for (aa, bb), st in zip(laws, styles, strict=True):
        psi, d1, d2, _ = rc.psi_law(alpha, psi_min, aa, bb)
        axes[0].plot(x, np.degrees(psi), **st)
        axes[1].plot(x, 1.0 + 0.5 * d1, **st)
        axes[2].plot(x, 0.5 * d2, **st)
        i = int(np.argmax(np.abs(d2)))
        axes[2].plot(x[i], 0.5 * d2[i], "o", color=st["color"], ms=5)
    axes[0].plot([], [], color="C2", alpha=0.3, lw=6, label=f"dwell band +-{tol:.3g} deg")
    axes[0].set_ylabel("psi [deg]")
    axes[0].set_title("(a) angle between the blade axes")
    axes[1].set_ylabel("dphi_1/dalpha [-]")
    axes[1].set_title("(b) speed of blade pair 1 over shaft speed (1 + psi'/2)")
    axes[2].set_ylabel("d2phi_1/dalpha2 [1/rad]")
    axes[2].set_title("(c) acceleration coefficient of blade pair 1 (psi''/2); dots: peaks")
    for i, ax in enumerate(axes):
        _deg_axis(ax, 180.0, 30.0, "output-shaft angle alpha [deg]" if i == 2 else None)
    axes[0].legend(loc="upper center", fontsize=8)
    fig.suptitle(
        f"Rhomboid cam law synthesized for {objective}, psi_min = {np.degrees(psi_min):.4g} deg"
    )
    fig.tight_layout()
    paths = [_save(fig, outdir, "synthesis_psi_law.png")]

    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(12, 5.6))
    full = np.linspace(0.0, 2.0 * np.pi, 1441)
    for (aa, bb), st in zip(laws, styles, strict=True):
        p = cam.pitch_curve(full, link_length, psi_min, aa, bb)[0] * 1e3
        q = cam.actual_profile(full, link_length, psi_min, aa, bb, roller_radius) * 1e3
        ax0.plot(p[0], p[1], ls="--", lw=1.0, color=st["color"])
        ax0.plot(q[0], q[1], **(st | {"label": f"{st['label']}: profile"}))
        mu = np.degrees(cam.pressure_angles(link_length, psi_min, aa, bb, alpha)[0])
        ax1.plot(x, mu, **st)
    ax0.plot([], [], ls="--", color="k", lw=1.0, label="pitch curves (roller centres)")
    r = roller_radius * 1e3
    c = cam.pitch_curve(np.array(0.0), link_length, psi_min, a, b)[0] * 1e3
    ax0.add_patch(plt.Circle((c[0], c[1]), r, fill=False, color="C0", lw=1.0))
    ax0.set_aspect("equal")
    ax0.set_xlabel("x [mm]")
    ax0.set_ylabel("y [mm]")
    ax0.grid(True, alpha=0.4)
    ax0.legend(loc="upper right", fontsize=7)
    ax0.set_title(f"(a) cam profiles for rollers of r = {r:.3g} mm (circle: roller A)")
    lim = np.degrees(pa_limit)
    ax1.axhline(lim, color="k", ls=":", lw=1.0, label=f"bound {lim:.4g} deg")
    ax1.axhline(-lim, color="k", ls=":", lw=1.0)
    _deg_axis(ax1, 180.0, 30.0, "output-shaft angle alpha [deg]")
    ax1.set_ylabel("pressure angle of roller A [deg]")
    ax1.set_title("(b) pressure angle (B and D: the same, 90 deg later; C = A)")
    ax1.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    paths.append(_save(fig, outdir, "synthesis_cam.png"))
    return paths


# --------------------------------------------------------------------------------------------
# wobble cam
# --------------------------------------------------------------------------------------------
def plot_wobble(outdir, base, synth, slow, offset, objective):
    """Chamber-angle laws (baseline, target, synthesized), spin laws and grooves."""
    from rotorkin.drives import wobble_cam as wc
    from rotorkin.synthesis import DWELL_TOLERANCE
    from rotorkin.synthesis import wobble as sw

    plt = _plt()
    theta = np.linspace(0.0, np.pi, 1441)
    x = np.degrees(theta)
    fig, axes = plt.subplots(3, 1, figsize=(9, 9.5), sharex=True)
    amax, amin = (
        float(v) for v in wc.slider_angle_extremes(base.plate_tilt, base.roller_axis_angle)
    )
    tol = DWELL_TOLERANCE * (amax - amin)
    for ext in (amin, amax):
        axes[0].axhspan(
            np.degrees(ext - offset - tol),
            np.degrees(ext - offset + tol),
            color="C2",
            alpha=0.15,
            lw=0,
        )
    target = sw.target_slider_angle(
        theta, base.spin_ratio, base.plate_tilt, base.roller_axis_angle, slow
    )[0]
    for p, st in ((base, _BASE), (synth, _SYN)):
        sp = wc.spin_law(p, theta)
        delta = wc.slider_angle(sp[0], p.plate_tilt, p.roller_axis_angle) - offset
        axes[0].plot(x, np.degrees(delta), **st)
        axes[1].plot(x, sp[1], **st)
    axes[0].plot(x, np.degrees(target - offset), color="k", ls=(0, (4, 3)), lw=1.0, label="target")
    axes[0].plot([], [], color="C2", alpha=0.3, lw=6, label="dwell bands")
    for p, st in ((base, _BASE), (synth, _SYN)):
        sp = wc.spin_law(p, theta)[0]
        err = np.degrees(wc.slider_angle(sp, p.plate_tilt, p.roller_axis_angle) - target)
        axes[2].semilogy(
            x,
            np.maximum(np.abs(err), 1e-17),
            color=st["color"],
            lw=1.0,
            label=f"|{st['label']} - target|",
        )
    axes[2].axhline(1e-6, color="k", ls=":", lw=1.0, label="1e-6 deg (required)")
    axes[0].set_ylabel("chamber angle delta_A [deg]")
    axes[0].set_title("(a) chamber angle: forward analysis of each spin law")
    axes[1].set_ylabel("dvarphi/dtheta [-]")
    axes[1].set_title("(b) plate spin rate relative to the inclined shaft section")
    axes[2].set_ylabel("|error| [deg]")
    axes[2].set_ylim(1e-17, 1e2)
    axes[2].set_title("(c) deviation from the target law (round trip of the synthesized law)")
    for i, ax in enumerate(axes):
        _deg_axis(ax, 180.0, 22.5, "shaft angle theta [deg]" if i == 2 else None)
        if i < 2:  # headroom for the legend above the curves
            lo, hi = ax.get_ylim()
            ax.set_ylim(lo, hi + 0.3 * (hi - lo))
            ax.legend(loc="upper center", ncol=4, fontsize=8)
        else:
            ax.legend(loc="upper right", fontsize=8)
    fig.suptitle(
        f"Wobble cam spin law synthesized for {objective} "
        f"(phi = {np.degrees(base.plate_tilt):.4g} deg)"
    )
    fig.tight_layout()
    paths = [_save(fig, outdir, "synthesis_chamber_law.png")]

    fig, axes = plt.subplots(1, 3, figsize=(14, 5))
    tg = np.linspace(0.0, sw.groove_closing_angle(base), 1441)
    R = base.sphere_radius * 1e3
    for p, st in ((base, _BASE), (synth, _SYN)):
        g = wc.groove_points(p, tg)[0] * 1e3
        for ax, (i, j) in zip(axes, ((0, 1), (0, 2), (1, 2)), strict=True):
            ax.plot(g[i], g[j], **(st | {"label": f"{st['label']}: groove of roller 1"}))
    for ax, (i, j) in zip(axes, ((0, 1), (0, 2), (1, 2)), strict=True):
        ax.add_patch(plt.Circle((0, 0), R, fill=False, color="0.7", lw=0.6, ls=":"))
        ax.set_aspect("equal")
        ax.set_xlim(-1.05 * R, 1.05 * R)
        ax.set_ylim(-1.05 * R, 1.05 * R)
        ax.set_xlabel(f"{'xyz'[i]}4 [mm]")
        ax.set_ylabel(f"{'xyz'[j]}4 [mm]")
        ax.grid(True, alpha=0.4)
        ax.set_title(f"{'xyz'[i]}4{'xyz'[j]}4 projection")
    axes[0].legend(loc="lower left", fontsize=8)
    fig.suptitle(
        "Groove centre-lines in the cam frame x4y4z4 (sphere r = "
        f"{R:.4g} mm): baseline and synthesized spin laws"
    )
    fig.tight_layout()
    paths.append(_save(fig, outdir, "synthesis_grooves.png"))
    return paths


# --------------------------------------------------------------------------------------------
# guide bar
# --------------------------------------------------------------------------------------------
def plot_guide_bar(outdir, lambdas, u, phase, driver, gamma, i12):
    """Vane angle against lambda (target, baseline, solution) and the impeller speed ratios."""
    from rotorkin.drives import guide_bar as gb

    plt = _plt()
    lam0, lam1 = lambdas
    grid = np.linspace(0.0, 0.999, 500)
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(13, 5))
    for drv, ls in (("crank", "-"), ("guide", "--")):
        with np.errstate(all="ignore"):
            g = np.degrees(gb.vane_angle(grid, u, phase, drv))
        ax0.plot(
            grid,
            g,
            ls=ls,
            color="C0" if drv == driver else "0.6",
            label=f"{drv}-driven" + (" (this drive)" if drv == driver else ""),
        )
    ax0.axhline(np.degrees(gamma), color="C3", ls=":", lw=1.0, label="target gamma_0")
    ax0.plot(
        [lam0],
        [np.degrees(gb.vane_angle(lam0, u, phase, driver))],
        "o",
        color="0.45",
        label=f"baseline lambda = {lam0:.4g}",
    )
    ax0.plot([lam1], [np.degrees(gamma)], "s", color="C3", label=f"synthesized lambda = {lam1:.6g}")
    ax0.set_xlabel("lambda = d/a [-]")
    ax0.set_ylabel("vane angle gamma_0 [deg]")
    ax0.set_xlim(0.0, 1.0)
    ax0.grid(True, alpha=0.4)
    ax0.legend(fontsize=8)
    ax0.set_title(f"(a) vane angle, phase {np.degrees(phase):.4g} deg, u = {u:g}")
    for lam, st in ((lam0, _BASE), (lam1, _SYN)):
        params = gb.GuideBar(lam, u, i12, phase, driver)
        th = np.linspace(0.0, gb.period(params), 1441)
        d1 = gb.impeller_angles(params, th)[1] * i12
        ax1.plot(np.degrees(th), d1[0], **(st | {"label": f"{st['label']}: impeller 1"}))
        ax1.plot(
            np.degrees(th),
            d1[1],
            ls="--",
            **{k: v for k, v in st.items() if k != "label"},
            label=f"{st['label']}: impeller 2",
        )
    end = np.degrees(2.0 * np.pi * i12)
    _deg_axis(ax1, end, end / 8.0, "input gear angle [deg]")
    ax1.set_ylabel("impeller speed / driving member speed [-]")
    ax1.legend(fontsize=8)
    ax1.set_title(f"(b) impeller speed ratios ({driver}-driven)")
    fig.tight_layout()
    return [_save(fig, outdir, "synthesis_vane_angle.png")]


# --------------------------------------------------------------------------------------------
# eccentric cams
# --------------------------------------------------------------------------------------------
def plot_eccentric(outdir, base, synth, options, gap, length):
    """Gap change over a turn: baseline, synthesized design, the other options, the tolerance."""
    from rotorkin.drives import eccentric_cam as ec

    plt = _plt()
    beta = np.linspace(0.0, 2.0 * np.pi, 1441)
    x = np.degrees(beta)
    fig, ax = plt.subplots(figsize=(9, 5))

    def describe(p):
        r = f", r = {p.roller_radius * 1e3:.4g} mm" if p.follower == "roller" else ""
        return (
            f"{p.follower}, R = {p.disc_radius * 1e3:.4g} mm, e = {p.eccentricity * 1e3:.4g} mm{r}"
        )

    ax.plot(
        x,
        100 * ec.gap_change(base, beta)[0] / length,
        **(_BASE | {"label": f"baseline: {describe(base)}"}),
    )
    ax.plot(
        x,
        100 * ec.gap_change(synth, beta)[0] / length,
        **(_SYN | {"label": f"synthesized: {describe(synth)}"}),
    )
    for i, p in enumerate(o for o in options if o != synth):
        ax.plot(
            x,
            100 * ec.gap_change(p, beta)[0] / length,
            ls="--",
            lw=1.0,
            color=f"C{i}",
            label=f"option: {describe(p)}",
        )
    ax.axhline(0.0, color="C2", lw=1.0, label="flat follower (eq. 7, 8)")
    ax.axhline(-100 * gap / length, color="k", ls=":", lw=1.0, label="tolerated |Delta|/L")
    _deg_axis(ax, 360.0, 45.0, "shaft angle beta [deg]")
    ax.set_ylabel("gap change Delta / L [%]")
    ax.set_title(f"Gap change between the pistons (eq. 5), L = {length * 1e3:.4g} mm")
    ax.legend(fontsize=7, loc="lower center")
    fig.tight_layout()
    return [_save(fig, outdir, "synthesis_gap_change.png")]
