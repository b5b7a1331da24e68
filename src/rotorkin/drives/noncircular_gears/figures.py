"""Figure of the non-circular gears: both pitch curves in mesh at theta = 0."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.drives.noncircular_gears import kinematics as ng
from rotorkin.render.figures import pyplot, save

__all__ = ["plot_pitch_curves"]


def plot_pitch_curves(params: ng.NoncircularGears, outdir: Path) -> list[Path]:
    """``pitch_curves.png``: driving gear at the origin, driven gear at ``(a, 0)``, in mesh."""
    plt = pyplot()
    a = float(params.centre_distance)
    angle = np.linspace(0.0, 2.0 * np.pi, 1441)
    x1, y1 = ng.pitch_curve(params, "driving", angle)
    x2, y2 = ng.pitch_curve(params, "driven", angle)
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    ax.plot(x1 * 1e3, -y1 * 1e3, color="C0", label=f"driving gear ({params.lobes} lobes)")
    ax.plot((a - x2) * 1e3, y2 * 1e3, color="C1", label=f"driven gear ({params.rotor_lobes} lobes)")
    ax.plot([0.0, a * 1e3], [0.0, 0.0], color="0.5", lw=0.8, ls=":", label="line of centres")
    ax.plot([0.0, a * 1e3], [0.0, 0.0], "k+", ms=10)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.grid(True, alpha=0.4)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=3, fontsize=8)
    ax.set_title(f"pitch curves in mesh at theta = 0, e = {params.eccentricity:g}", fontsize=10)
    return [save(fig, Path(outdir) / "pitch_curves.png", layout=(0.85, 0.95, 0.15, 0.35))]
