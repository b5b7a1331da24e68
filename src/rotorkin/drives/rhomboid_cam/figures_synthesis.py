"""Figure of ``rotorkin synthesize``: the baseline (paper's) design beside the synthesized one."""

from __future__ import annotations

import numpy as np

from rotorkin.drives.rhomboid_cam import cam
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.render.figures import BASELINE as _BASE
from rotorkin.render.figures import SYNTHESIZED as _SYN
from rotorkin.render.figures import degree_axis as _deg_axis
from rotorkin.render.figures import pyplot, save_in
from rotorkin.synthesis import DWELL_TOLERANCE

__all__ = ["plot_rhomboid"]


def plot_rhomboid(outdir, link_length, psi_min, a, b, roller_radius, objective, pa_limit):
    """psi laws, blade speed and acceleration; pitch curves, profiles and pressure angles."""
    plt = pyplot()
    alpha = np.linspace(0.0, np.pi, 1441)
    x = np.degrees(alpha)
    laws = (((), ()), (tuple(a), tuple(b)))
    styles = (_BASE | {"label": "first harmonic (eq. 16, paper)"}, _SYN)
    fig, axes = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    tol = np.degrees(DWELL_TOLERANCE * (np.pi - 2.0 * psi_min))
    for ext in (np.degrees(psi_min), 180.0 - np.degrees(psi_min)):
        axes[0].axhspan(ext - tol, ext + tol, color="C2", alpha=0.15, lw=0)
    for (aa, bb), st in zip(laws, styles, strict=True):
        psi, d1, d2, _ = rc.psi_law(psi_min, aa, bb, alpha)
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
    paths = [save_in(fig, outdir, "synthesis_psi_law.png")]

    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(12, 5.6))
    full = np.linspace(0.0, 2.0 * np.pi, 1441)
    for (aa, bb), st in zip(laws, styles, strict=True):
        p = cam.pitch_curve(link_length, psi_min, aa, bb, full)[0] * 1e3
        q = cam.actual_profile(link_length, psi_min, aa, bb, roller_radius, full) * 1e3
        ax0.plot(p[0], p[1], ls="--", lw=1.0, color=st["color"])
        ax0.plot(q[0], q[1], **(st | {"label": f"{st['label']}: profile"}))
        mu = np.degrees(cam.pressure_angles(link_length, psi_min, aa, bb, alpha)[0])
        ax1.plot(x, mu, **st)
    ax0.plot([], [], ls="--", color="k", lw=1.0, label="pitch curves (roller centres)")
    r = roller_radius * 1e3
    c = cam.pitch_curve(link_length, psi_min, a, b, np.array(0.0))[0] * 1e3
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
    paths.append(save_in(fig, outdir, "synthesis_cam.png"))
    return paths
