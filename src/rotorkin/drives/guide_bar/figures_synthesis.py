"""Figure of ``rotorkin synthesize``: the baseline (paper's) design beside the synthesized one."""

from __future__ import annotations

import numpy as np

from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.render.figures import BASELINE as _BASE
from rotorkin.render.figures import SYNTHESIZED as _SYN
from rotorkin.render.figures import degree_axis as _deg_axis
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save_in as _save

__all__ = ["plot_guide_bar"]


def plot_guide_bar(outdir, lambdas, u, phase, driver, gamma, i12):
    """Vane angle against lambda (target, baseline, solution) and the impeller speed ratios."""
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
