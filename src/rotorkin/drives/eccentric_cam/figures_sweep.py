"""Sweep behind Fig. 6-7 of Zhu & Zhu 2012 (knife-edge followers, lambda = 0.1 ... 0.9)."""

from __future__ import annotations

import numpy as np

from rotorkin.render.figures import Recipe
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save as _save

__all__ = ["sweep_recipes"]


def sweep_recipes(cfg) -> list[Recipe]:
    """Fig. 6 (parts of the piston travel) and Fig. 7 (gap change ratio) over lambda = e/R."""
    R = cfg["drive"]["disc_radius"] * 1e3
    ecc = ",".join(f"{lam * R:.10g}mm" for lam in (0.1, 0.3, 0.5, 0.7, 0.9))
    return [
        Recipe(
            "fig6_7",
            ("drive.follower=knife_edge",),
            (f"drive.eccentricity={ecc}",),
            True,
            ("paper_fig6.png", "paper_fig7.png"),
            "knife-edge followers, lambda = e/R = 0.1 ... 0.9 on the config's R",
            plot=_eccentric_fig6_7,
        )
    ]


def _eccentric_fig6_7(ds, outdir, recipe, cfg):
    plt = _plt()
    key = "drive.eccentricity"
    beta = ds["beta_deg"].values
    cfg = cfg
    R = cfg["drive"]["disc_radius"] * 1e3
    lams = ds[key].values / R
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5.6))
    for i, lam in enumerate(lams):
        d = ds.isel({key: i})
        ax1.plot(beta, d["mu"].values, color=f"C{i}", label=f"mu, lambda = {lam:.2g}")
        ax2.plot(beta, d["x_left"].values, color=f"C{i}", label=f"x, lambda = {lam:.2g}")
    xi = ds["xi"].isel({key: 0}).values
    for ax in (ax1, ax2):
        ax.plot(beta, xi, color="0.5", lw=3, alpha=0.6, label="xi = cos beta (harmonic)")
        _beta_axes(ax)
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=3)
    ax1.set_ylabel("xi, mu [-]")
    ax2.set_ylabel("x = z/e [-]")
    ax1.set_title("(a) additional part mu and harmonic part xi")
    ax2.set_title("(b) left piston x = xi + mu")
    fig.suptitle(f"Fig. 6  Knife-edge piston travel for several lambda (R = {R:.4g} mm)")
    paths = [_save(fig, outdir / recipe.figures[0])]
    fig, ax = plt.subplots(figsize=(8, 5))
    for i, lam in enumerate(lams):
        ax.plot(beta, ds["delta"].isel({key: i}).values, color=f"C{i}",
                label=f"lambda = {lam:.2g}")  # fmt: skip
    _beta_axes(ax)
    ax.set_ylabel("delta = Delta / e [-]")
    ax.legend(fontsize=8, loc="lower center", ncol=2)
    ax.set_title("Fig. 7  Change of the distance between the inner faces, knife-edge pistons\n"
                 f"R = {R:.4g} mm (eq. 6)", fontsize=10)  # fmt: skip
    paths.append(_save(fig, outdir / recipe.figures[1]))
    return paths


def _beta_axes(ax):
    ax.set_xlabel("shaft angle beta [deg]")
    ax.set_xlim(0.0, 360.0)
    ax.set_xticks(np.arange(0.0, 361.0, 45.0))
    ax.grid(True, alpha=0.4)
