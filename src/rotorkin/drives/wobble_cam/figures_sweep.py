"""Sweeps behind the parameter-study figures of Chen Hu et al. 2015 (Fig. 11-13)."""

from __future__ import annotations

import numpy as np

from rotorkin.render.figures import Recipe
from rotorkin.render.figures import pyplot as _plt
from rotorkin.render.figures import save as _save

__all__ = ["sweep_recipes"]


def sweep_recipes(cfg) -> list[Recipe]:
    """Fig. 11 (slider angle over a turn for five roller axis angles), Fig. 12 and Fig. 13."""
    tilt = cfg["drive"]["plate_tilt"]
    alpha = cfg["drive"]["roller_axis_angle"]
    n = cfg["machine"]["pistons_per_rotor"]
    tn = np.tan(np.pi / 4.0 - np.pi / (2.0 * n))
    c = np.cos(tilt)
    a_lo, a_hi = np.degrees(2.0 * np.arctan(tn / c)), np.degrees(2.0 * np.arctan(c / tn))
    t = np.tan(0.5 * alpha)
    lim = np.degrees(np.arccos(max(t * tn, tn / t)))
    pad = 0.05
    d1 = max(5.0 * np.floor((90.0 - a_lo - 1.0) / 5.0), 0.5 * (90.0 - a_lo))
    d2 = 5.0 * np.floor(0.1 * d1 + 0.5) if d1 >= 10.0 else 0.5 * d1
    alphas = 90.0 + np.array([-d1, -d2, 0.0, d2, d1])  # symmetric pairs alpha, 180 - alpha
    common = ("machine.compression_ratio=1e6", "loads.model=ideal")
    note = ("compression ratio set to 1e6 so that eq. 21 admits every design up to the eq. 20 "
            "limit (the slider angle does not depend on it), with the ideal cycle")  # fmt: skip
    metrics = ("slider_angle_max_deg", "slider_angle_min_deg", "chamber_swing_deg")
    return [
        Recipe("fig11", common, ("drive.roller_axis_angle="
                                 + ",".join(f"{a:.4f}deg" for a in alphas),),
               True, ("paper_fig11.png",), note, metrics, _wobble_fig11),
        Recipe("fig12", common, (f"drive.roller_axis_angle={a_lo + pad:.4f}deg:"
                                 f"{a_hi - pad:.4f}deg:121",), False, ("paper_fig12.png",), note,
               metrics, _wobble_fig12),
        Recipe("fig13", common, (f"drive.plate_tilt=0.5deg:{lim - pad:.4f}deg:131",), False,
               ("paper_fig13.png",), note, metrics, _wobble_fig13),
    ]  # fmt: skip


def _wobble_fig11(ds, outdir, recipe, cfg):
    plt = _plt()
    key = "drive.roller_axis_angle"
    theta = ds["theta_deg"].values
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5.4))
    for i, a in enumerate(ds[key].values):
        curve = ds["slider_angle_deg"].isel({key: i}).values
        group = "A" if a < 90 - 1e-9 else ("B" if a > 90 + 1e-9 else "")
        style = dict(ls="--" if group == "B" else "-", color=f"C{i}",
                     lw=2.4 if not group else 1.5)  # fmt: skip
        label = f"alpha = {a:.4g} deg" + (f" (group {group})" if group else "")
        ax1.plot(theta, curve, label=label, **style)
        ax2.plot(theta, curve - np.min(curve), label=label, **style)
    base = _wobble_base(cfg)
    ax1.set_ylabel("slider angle alpha' [deg]")
    ax2.set_ylabel("alpha' - alpha'_min = delta - delta_min [deg]")
    ax1.set_title("(a) slider angle alpha' (eq. 15)", fontsize=10)
    ax2.set_title("(b) volume change: groups A and B differ except at the extremes", fontsize=10)
    for ax in (ax1, ax2):
        ax.set_xlabel("shaft angle theta [deg]")
        ax.set_xlim(0.0, 180.0)
        ax.set_xticks(np.arange(0.0, 181.0, 45.0))
        ax.grid(True, alpha=0.4)
    handles, labels = ax1.get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=8, loc="lower center", ncol=5)
    fig.suptitle(
        "Fig. 11  Effect of the roller axis angle alpha on the volume change "
        f"(plate tilt {base['tilt']:.4g} deg; half a shaft turn shown)",
        fontsize=11,
    )
    return [_save(fig, outdir / recipe.figures[0], rect=(0.0, 0.07, 1.0, 1.0))]


def _wobble_base(cfg) -> dict:
    """Plate tilt and roller axis angle [deg] and pistons of a wobble sweep's base config."""
    cfg = cfg
    return {"tilt": np.degrees(cfg["drive"]["plate_tilt"]),
            "alpha": np.degrees(cfg["drive"]["roller_axis_angle"]),
            "pistons": cfg["machine"]["pistons_per_rotor"]}  # fmt: skip


def _limits(n: int):
    g2 = np.degrees(np.pi / 2.0 - np.pi / n)
    return g2, np.degrees(2.0 * np.pi / n) + g2


def _extremes_plot(ds, cfg, key, xlabel, title, path, mark):
    plt = _plt()
    x = ds[key].values
    base = _wobble_base(cfg)
    lo, hi = _limits(base["pistons"])
    fig, ax = plt.subplots(figsize=(8, 5.2))
    ax.plot(x, ds["slider_angle_max_deg"].values, "C3", lw=2, label="alpha'_max (eq. 17)")
    ax.plot(x, ds["slider_angle_min_deg"].values, "C0", lw=2, label="alpha'_min (eq. 17)")
    ax.plot(x, ds["chamber_swing_deg"].values, "k:", lw=1.5,
            label="swing alpha'_max - alpha'_min (eq. 23)")  # fmt: skip
    ax.axhline(hi, color="C3", ls="--", lw=1, label=f"eq. 20: alpha'_max <= {hi:.0f} deg")
    ax.axhline(lo, color="C0", ls="--", lw=1, label=f"eq. 20: alpha'_min >= {lo:.0f} deg")
    ax.axvline(mark, color="0.4", ls="-.", lw=1, label=f"config: {mark:.4g} deg")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("slider angle extremes [deg]")
    ax.set_ylim(0.0, 180.0)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="upper left", ncol=2)
    ax.set_title(title, fontsize=10)
    return _save(fig, path)


def _wobble_fig12(ds, outdir, recipe, cfg):
    base = _wobble_base(cfg)
    return [
        _extremes_plot(
            ds,
            cfg,
            "drive.roller_axis_angle",
            "roller axis angle alpha [deg]",
            "Fig. 12  alpha'_max and alpha'_min against the roller axis angle alpha\n"
            f"plate tilt {base['tilt']:.4g} deg, over the alphas eq. 20 admits "
            f"({base['pistons']} pistons per rotor)",
            outdir / recipe.figures[0],
            base["alpha"],
        )
    ]


def _wobble_fig13(ds, outdir, recipe, cfg):
    base = _wobble_base(cfg)
    x = ds["drive.plate_tilt"].values
    path = _extremes_plot(
        ds, cfg, "drive.plate_tilt", "plate tilt phi [deg]",
        "Fig. 13  alpha'_max and alpha'_min against the plate tilt phi\n"
        f"roller axis angle {base['alpha']:.4g} deg; eq. 20 limit phi < {x[-1] + 0.05:.2f} deg",
        outdir / recipe.figures[0], base["tilt"])  # fmt: skip
    return [path]
