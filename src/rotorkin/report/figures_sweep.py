"""Figures drawn from sweeps: the papers' parameter studies, an overview, tolerance histograms.

``rotorkin sweep --example NAME --paper-figures`` runs, for the drive of the
config, the sweeps behind the papers' figures (:func:`paper_recipes`) and draws
them from the resulting datasets:

* wobble cam (Chen Hu et al. 2015): Fig. 11 slider angle over a shaft turn for
  several roller axis angles; Fig. 12 its extremes against the roller axis
  angle; Fig. 13 against the plate tilt (with the eq. 20 limits);
* eccentric cams (Zhu & Zhu 2012): Fig. 6 the parts xi, mu and x of the piston
  travel, Fig. 7 the gap change delta, both for lambda = 0.1 ... 0.9;
* guide bar (JHIT 2012): Fig. 9 lambda against the vane angle gamma_0 for
  u = 2, 3 and both drivers; Fig. 10 / 11 the input torque over a period for
  several lambda, crank- and guide-driven.

matplotlib is imported lazily (Agg backend).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["Recipe", "paper_recipes", "plot_recipe", "fig_overview", "fig_tolerance"]

_DPI = 120


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=_DPI)
    _plt().close(fig)
    return Path(path)


@dataclass(frozen=True)
class Recipe:
    """A sweep behind one or more of a paper's figures.

    ``sets`` are ``--set`` overrides of the config, ``vary`` the ``--vary`` items,
    ``figures`` the PNG names drawn from its dataset, ``note`` what the recipe
    changes in the config and why.
    """

    key: str
    sets: tuple
    vary: tuple
    curves: bool
    figures: tuple
    note: str = ""
    metrics: tuple = field(default=())


# --------------------------------------------------------------------------------------------
# recipes
# --------------------------------------------------------------------------------------------
def paper_recipes(cfg: dict) -> list[Recipe]:
    """The paper-figure sweeps of the config's drive (empty for the rhomboid cam)."""
    kind = cfg["drive"]["type"]
    if kind == "wobble_cam":
        return _wobble(cfg)
    if kind == "eccentric_cam":
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
            )
        ]
    if kind == "guide_bar":
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
                   "the default vane angle", ("vane_angle_deg",)),
            Recipe("fig10_11", common + torque,
                   ("drive.lambda=" + ",".join(f"{v:g}" for v in lams), "drive.driver=crank,guide"),
                   True, ("paper_fig10.png", "paper_fig11.png"),
                   "Sigma = 180 deg, the config's u, i12 and impeller torques",
                   ("input_torque_min_Nm", "input_torque_max_Nm")),
        ]  # fmt: skip
    return []


def _wobble(cfg) -> list[Recipe]:
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
    common = ("machine.compression_ratio=1e6",)
    note = ("compression ratio set to 1e6 so that eq. 21 admits every design up to the eq. 20 "
            "limit (the slider angle does not depend on it)")  # fmt: skip
    metrics = ("slider_angle_max_deg", "slider_angle_min_deg", "chamber_swing_deg")
    return [
        Recipe("fig11", common, ("drive.roller_axis_angle="
                                 + ",".join(f"{a:.4f}deg" for a in alphas),),
               True, ("paper_fig11.png",), note, metrics),
        Recipe("fig12", common, (f"drive.roller_axis_angle={a_lo + pad:.4f}deg:"
                                 f"{a_hi - pad:.4f}deg:121",), False, ("paper_fig12.png",), note,
               metrics),
        Recipe("fig13", common, (f"drive.plate_tilt=0.5deg:{lim - pad:.4f}deg:131",), False,
               ("paper_fig13.png",), note, metrics),
    ]  # fmt: skip


# --------------------------------------------------------------------------------------------
# drawing
# --------------------------------------------------------------------------------------------
def plot_recipe(recipe: Recipe, ds, outdir: Path) -> list[Path]:
    """Draw the recipe's figures from its dataset into ``outdir``; return the paths."""
    outdir = Path(outdir)
    fn = {
        "fig11": _wobble_fig11,
        "fig12": _wobble_fig12,
        "fig13": _wobble_fig13,
        "fig6_7": _eccentric_fig6_7,
        "fig9": _guide_fig9,
        "fig10_11": _guide_fig10_11,
    }
    return fn[recipe.key](ds, outdir, recipe)


def _wobble_fig11(ds, outdir, recipe):
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
    base = _wobble_base(ds)
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
    fig.tight_layout(rect=(0.0, 0.07, 1.0, 1.0))
    fig.savefig(outdir / recipe.figures[0], dpi=_DPI)
    plt.close(fig)
    return [outdir / recipe.figures[0]]


def _base_cfg(ds) -> dict:
    """The validated base config of a sweep dataset (from its ``spec`` attribute)."""
    import json

    from rotorkin.io.config import validate_config

    return validate_config(json.loads(ds.attrs["spec"])["base_raw"])


def _wobble_base(ds) -> dict:
    """Plate tilt and roller axis angle [deg] and pistons of a wobble sweep's base config."""
    cfg = _base_cfg(ds)
    return {"tilt": np.degrees(cfg["drive"]["plate_tilt"]),
            "alpha": np.degrees(cfg["drive"]["roller_axis_angle"]),
            "pistons": cfg["machine"]["pistons_per_rotor"]}  # fmt: skip


def _limits(n: int):
    g2 = np.degrees(np.pi / 2.0 - np.pi / n)
    return g2, np.degrees(2.0 * np.pi / n) + g2


def _extremes_plot(ds, key, xlabel, title, path, mark):
    plt = _plt()
    x = ds[key].values
    base = _wobble_base(ds)
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


def _wobble_fig12(ds, outdir, recipe):
    base = _wobble_base(ds)
    return [
        _extremes_plot(
            ds,
            "drive.roller_axis_angle",
            "roller axis angle alpha [deg]",
            "Fig. 12  alpha'_max and alpha'_min against the roller axis angle alpha\n"
            f"plate tilt {base['tilt']:.4g} deg, over the alphas eq. 20 admits "
            f"({base['pistons']} pistons per rotor)",
            outdir / recipe.figures[0],
            base["alpha"],
        )
    ]


def _wobble_fig13(ds, outdir, recipe):
    base = _wobble_base(ds)
    x = ds["drive.plate_tilt"].values
    path = _extremes_plot(
        ds, "drive.plate_tilt", "plate tilt phi [deg]",
        "Fig. 13  alpha'_max and alpha'_min against the plate tilt phi\n"
        f"roller axis angle {base['alpha']:.4g} deg; eq. 20 limit phi < {x[-1] + 0.05:.2f} deg",
        outdir / recipe.figures[0], base["tilt"])  # fmt: skip
    return [path]


def _eccentric_fig6_7(ds, outdir, recipe):
    plt = _plt()
    key = "drive.eccentricity"
    beta = ds["beta_deg"].values
    cfg = _base_cfg(ds)
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


_DRIVER = {"crank": "crank-driven", "guide": "guide-driven"}


def _guide_fig9(ds, outdir, recipe):
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
    ax.set_xlabel("theoretical vane angle gamma_0 [deg]")
    ax.set_ylabel("mechanism coefficient lambda = d/a [-]")
    ax.set_ylim(0.0, 1.0)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title("Fig. 9  lambda against the vane angle gamma_0, Sigma = 180 deg (from a sweep)")
    return [_save(fig, outdir / recipe.figures[0])]


def _guide_fig10_11(ds, outdir, recipe):
    plt = _plt()
    cfg = _base_cfg(ds)
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
def fig_overview(ds, metrics, path: Path) -> Path | None:
    """Up to six metrics against the first swept key, one line per value of the second.

    Further swept keys are held at their first value. None when the first key is
    not numeric or there is nothing to draw.
    """
    dims = [d for d in ds["reason"].dims]
    if not dims or ds[dims[0]].dtype == object:
        return None
    names = [m for m in metrics if m in ds and np.any(np.isfinite(ds[m].values))][:6]
    if not names:
        return None
    plt = _plt()
    sub = ds.isel({d: 0 for d in dims[2:]})
    x = sub[dims[0]]
    ncol = min(3, len(names))
    nrow = -(-len(names) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.6 * nrow + 0.8), squeeze=False)
    second = dims[1] if len(dims) > 1 else None
    lines = range(sub.sizes[second]) if second else [None]
    if second and len(lines) > 8:
        lines = np.unique(np.linspace(0, sub.sizes[second] - 1, 8).round().astype(int))
    for ax, m in zip(axes.ravel(), names, strict=False):
        for k, j in enumerate(lines):
            y = sub[m] if j is None else sub[m].isel({second: int(j)})
            lab = None
            if j is not None:
                unit = sub[second].attrs.get("units", "1")
                lab = (f"{second.split('.')[-1]} = {_fmt(sub[second][int(j)])}"
                       + ("" if unit == "1" else f" {unit}"))  # fmt: skip
            ax.plot(x.values, y.values, color=f"C{k}", label=lab)
        ax.set_xlabel(f"{dims[0]} [{x.attrs.get('units', '')}]")
        ax.set_ylabel(f"{m} [{ds[m].attrs.get('units', '1')}]", fontsize=8)
        ax.grid(True, alpha=0.4)
    for ax in axes.ravel()[len(names) :]:
        ax.set_visible(False)
    if second:
        axes.ravel()[0].legend(fontsize=7)
    held = ", ".join(f"{d} = {_fmt(ds[d][0])}" for d in dims[2:])
    fig.suptitle(f"{ds.attrs.get('title', 'sweep')}: {ds.attrs['designs']} designs, "
                 f"{ds.attrs['inadmissible_designs']} inadmissible (gaps)"
                 + (f"\nheld: {held}" if held else ""), fontsize=10)  # fmt: skip
    return _save(fig, path)


def _fmt(v) -> str:
    v = v.item() if hasattr(v, "item") else v
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def fig_tolerance(ds, stats: dict, metrics, path: Path) -> Path:
    """Histograms of the metrics of a tolerance run, nominal and percentiles marked."""
    plt = _plt()
    ok = ds["reason"].values == 0
    names = list(metrics)[:9]
    ncol = min(3, len(names))
    nrow = -(-len(names) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.4 * nrow + 1.0), squeeze=False)
    for ax, m in zip(axes.ravel(), names, strict=False):
        v = ds[m].values[ok]
        v = v[np.isfinite(v)]
        s = stats[m]
        ax.hist(v, bins=50, color="C0", alpha=0.75, label="samples")
        ax.axvline(s["nominal"], color="k", ls="--", lw=1.5, label="nominal")
        if s["p5"] is not None:
            ax.axvline(s["p5"], color="C1", ls=":", lw=1.5, label="p5, p95")
            ax.axvline(s["p95"], color="C1", ls=":", lw=1.5)
            ax.axvline(s["p50"], color="C3", ls="-", lw=1, label="p50")
        ax.set_xlabel(f"{m} [{ds[m].attrs.get('units', '1')}]", fontsize=8)
        ax.set_ylabel("samples")
        ax.ticklabel_format(axis="x", useOffset=False)
        ax.tick_params(axis="x", labelsize=7)
        ax.grid(True, alpha=0.4)
        std = s["std"]
        ax.set_title(f"std {std:.3g}" if std is not None else "no admissible sample", fontsize=9)
    for ax in axes.ravel()[len(names) :]:
        ax.set_visible(False)
    axes.ravel()[0].legend(fontsize=7)
    bad = int(np.count_nonzero(~ok))
    fig.suptitle(f"Tolerance analysis: {ds.attrs['samples']} samples, seed {ds.attrs['seed']}, "
                 f"{bad} inadmissible\n{ds.attrs['tolerances']}", fontsize=10)  # fmt: skip
    return _save(fig, path)
