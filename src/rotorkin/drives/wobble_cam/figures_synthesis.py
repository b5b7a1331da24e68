"""Figure of ``rotorkin synthesize``: the baseline (paper's) design beside the synthesized one."""

from __future__ import annotations

import numpy as np

from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.render.figures import BASELINE as _BASE
from rotorkin.render.figures import SYNTHESIZED as _SYN
from rotorkin.render.figures import degree_axis as _deg_axis
from rotorkin.render.figures import plain_log_labels
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save_in as _save
from rotorkin.synthesis import DWELL_TOLERANCE

__all__ = ["plot_wobble"]


#: Shaft angles [rad] at which :func:`plot_wobble` draws the laws (its ``target`` too).
LAW_THETA = np.linspace(0.0, np.pi, 1441)


def plot_wobble(outdir, base, synth, target, groove_closing, offset, objective):
    """Chamber-angle laws (baseline, target, synthesized), spin laws and grooves.

    Parameters
    ----------
    outdir : path
    base, synth : WobbleCam
        Baseline and synthesized drives.
    target : ndarray
        Target slider angle at :data:`LAW_THETA` [rad].
    groove_closing : float
        Shaft angle after which the baseline's grooves close [rad].
    offset : float
        ``2 gamma + beta``: slider angle minus chamber angle of kind A [rad].
    objective : str
    """
    plt = _plt()
    theta = LAW_THETA
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
    for p, st in ((base, _BASE), (synth, _SYN)):
        sp = wc.spin_law(p, theta)
        delta = wc.slider_angle(p.plate_tilt, p.roller_axis_angle, sp[0]) - offset
        axes[0].plot(x, np.degrees(delta), **st)
        axes[1].plot(x, sp[1], **st)
    axes[0].plot(x, np.degrees(target - offset), color="k", ls=(0, (4, 3)), lw=1.0, label="target")
    axes[0].plot([], [], color="C2", alpha=0.3, lw=6, label="dwell bands")
    for p, st in ((base, _BASE), (synth, _SYN)):
        sp = wc.spin_law(p, theta)[0]
        err = np.degrees(wc.slider_angle(p.plate_tilt, p.roller_axis_angle, sp) - target)
        axes[2].semilogy(
            x,
            np.maximum(np.abs(err), 1e-17),
            color=st["color"],
            lw=1.0,
            label=f"|{st['label']} - target|",
        )
        plain_log_labels(axes[2], "y")
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
    tg = np.linspace(0.0, groove_closing, 1441)
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
