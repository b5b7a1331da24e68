"""Sweeps behind Fig. 9-11 of the guide-bar paper (J. Harbin Inst. Tech. 44(9), 2012)."""

from __future__ import annotations

import numpy as np

from rotorkin.drives.guide_bar.figures import fig9_axes
from rotorkin.render.figures import Recipe
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save as _save

__all__ = ["sweep_recipes"]


def sweep_recipes(cfg) -> list[Recipe]:
    """Fig. 9 (vane angle over lambda) and Fig. 10-11 (input torque over a turn)."""
    lams = sorted({0.3, 0.5, 0.7, round(float(cfg["drive"]["lambda"]), 6)})
    common = ("drive.phase=180deg", "machine.vanes_per_impeller=1")
    loads = cfg["loads"]
    torque = ()
    if loads["impeller_torque_1"] == 0.0 and loads["impeller_torque_2"] == 0.0:
        torque = ("loads.impeller_torque_1=10N*m", "loads.impeller_torque_2=10N*m")
    return [
        Recipe("fig9", common, ("drive.lambda=0.02:0.98:49", "drive.gear_ratio=2,3",
                                "drive.driver=crank,guide"), False, ("paper_fig9.png",),
               "Sigma = 180 deg; one vane per impeller so that every lambda and u admit "
               "the default vane angle", ("vane_angle_deg",), _guide_fig9),
        Recipe("fig10_11", common + torque,
               ("drive.lambda=" + ",".join(f"{v:g}" for v in lams), "drive.driver=crank,guide"),
               True, ("paper_fig10.png", "paper_fig11.png"),
               "Sigma = 180 deg, the config's u, i12 and impeller torques",
               ("input_torque_min_Nm", "input_torque_max_Nm"), _guide_fig10_11),
    ]  # fmt: skip


_DRIVER = {"crank": "crank-driven", "guide": "guide-driven"}


def _guide_fig9(ds, outdir, recipe, cfg):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(8, 5))
    lam = ds["drive.lambda"].values
    styles = {"crank": "C0", "guide": "C3"}
    for u in ds["drive.gear_ratio"].values:
        for drv in ds["drive.driver"].values:
            g = ds["vane_angle_deg"].sel({"drive.gear_ratio": u, "drive.driver": drv}).values
            ax.plot(
                g,
                lam,
                color=styles[str(drv)],
                ls="-" if u == 2 else "--",
                label=f"{_DRIVER[str(drv)]}, u = {u:g} (eq. {5 if drv == 'crank' else 6})",
            )
    fig9_axes(ax, "Fig. 9  lambda against the vane angle gamma_0, Sigma = 180 deg (from a sweep)")
    return [_save(fig, outdir / recipe.figures[0])]


def _guide_fig10_11(ds, outdir, recipe, cfg):
    plt = _plt()
    cfg = cfg
    theta = ds["theta_deg"].values
    torque = ds["input_torque_Nm"]
    lo, hi = float(np.nanmin(torque.values)), float(np.nanmax(torque.values))
    pad = 0.06 * max(hi - lo, 1e-3 * max(abs(lo), abs(hi), 1e-12))
    m7, m8 = cfg["loads"]["impeller_torque_1"], cfg["loads"]["impeller_torque_2"]
    paths = []
    for number, drv in ((10, "crank"), (11, "guide")):
        fig, ax = plt.subplots(figsize=(8, 5))
        for i, lam in enumerate(ds["drive.lambda"].values):
            cfg_lam = abs(lam - cfg["drive"]["lambda"]) < 1e-9
            ax.plot(
                theta,
                torque.sel({"drive.driver": drv}).isel({"drive.lambda": i}).values,
                "k--" if cfg_lam else f"C{i}-",
                label=f"lambda = {lam:.3g}" + (" (config)" if cfg_lam else ""),
            )
        ax.set_ylim(lo - pad, hi + pad)  # the same scale in Fig. 10 and 11, as the paper
        ax.set_xlim(0.0, float(theta[-1]))
        ax.set_xticks(np.arange(0.0, float(theta[-1]) + 1e-9, 90.0))
        ax.set_xlabel("input gear angle theta [deg]")
        ax.set_ylabel("input torque M1 [N*m]")
        ax.grid(True, alpha=0.4)
        ax.legend(fontsize=8, loc="upper right")
        ax.set_title(
            f"Fig. {number}  Input torque, {_DRIVER[drv]}: u = "
            f"{cfg['drive']['gear_ratio']:.3g}, i12 = "
            f"{cfg['drive']['input_gear_ratio']:.3g}, Sigma = 180 deg\n"
            f"M7 = {m7:.3g} N*m, M8 = {m8:.3g} N*m (eq. 7, 8)",
            fontsize=10,
        )
        if drv == "guide" and abs(m7 - m8) < 1e-12:
            ax.text(
                0.5,
                0.08,
                "M7 = M8, Sigma = 180 deg: guide-driven M1 is constant",
                transform=ax.transAxes,
                ha="center",
                fontsize=9,
            )
        paths.append(_save(fig, outdir / recipe.figures[0 if drv == "crank" else 1]))
    return paths


# --------------------------------------------------------------------------------------------
# overview of any sweep, tolerance histograms
# --------------------------------------------------------------------------------------------
