"""Figure of ``rotorkin synthesize``: the baseline (paper's) design beside the synthesized one."""

from __future__ import annotations

import numpy as np

from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.render.figures import BASELINE as _BASE
from rotorkin.render.figures import SYNTHESIZED as _SYN
from rotorkin.render.figures import degree_axis as _deg_axis
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save_in as _save

__all__ = ["plot_eccentric"]


def plot_eccentric(base, synth, options, gap, length, outdir):
    """Gap change over a turn (eq. 5): baseline, synthesized design, other options, tolerance.

    Parameters
    ----------
    base, synth : EccentricCam
        The config's design and the synthesized one.
    options : list of EccentricCam
        The other feasible designs.
    gap : float
        Tolerated peak gap change |Delta| [m].
    length : float
        Device length L [m].
    outdir : path
        Folder of ``synthesis_gap_change.png``.

    Returns
    -------
    list of Path
    """
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
