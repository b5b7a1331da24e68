"""Figures of a vane machine on any rotary drive: the members, the chambers, the torque."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.render.figures import degree_axis, pyplot, save

__all__ = ["plot_machine"]


def _step(end: float) -> float:
    return 45.0 if end <= 360.0 + 1e-9 else 90.0


def plot_machine(setup, st, theta, outdir: Path, title: str) -> list[Path]:
    """Write ``members.png``, ``chambers.png`` and ``shaft_torque.png``.

    Over one shaft turn, or one period of the drive when that is longer.

    Parameters
    ----------
    setup : rotorkin.vane.machines.Setup
    st : rotorkin.vane.machines.State
        The machine at ``theta``.
    theta : ndarray
        ``0 .. 2 pi`` [rad].
    """
    plt = pyplot()
    deg = np.degrees(theta)
    mo = st.motion
    names = mo.members
    out = []

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.5, 6.0), sharex=True)
    for k in (0, 1):
        a1.plot(deg, mo.dq[k], label=f"{names[k]}: speed ratio")
    a1.set_ylabel("member speed / shaft speed")
    a1.legend(loc="best", fontsize=8)
    a1.grid(True, alpha=0.4)
    a2.plot(deg, np.degrees(mo.q[1] - mo.q[0]), color="C2", label="relative angle (mounted)")
    a2.axhline(np.degrees(setup.r_lo + setup.shift), color="0.5", lw=0.8, ls=":")
    a2.axhline(np.degrees(setup.r_hi + setup.shift), color="0.5", lw=0.8, ls=":")
    a2.set_ylabel("q2 - q1 [deg]")
    a2.legend(loc="best", fontsize=8)
    degree_axis(a2, deg[-1], _step(deg[-1]), "shaft angle theta [deg]")
    fig.suptitle(title, fontsize=10)
    out.append(save(fig, Path(outdir) / "members.png"))

    fig, (b1, b2) = plt.subplots(2, 1, figsize=(7.5, 6.0), sharex=True)
    for j, tag in ((0, "A"), (1, "B")):
        b1.plot(deg, st.volume[j] * 1e6, label=f"chamber {j + 1} (kind {tag})")
        b2.plot(deg, st.pressure[j] / 1e5, label=f"chamber {j + 1} (kind {tag})")
    b1.set_ylabel("volume [cm^3]")
    b1.legend(loc="best", fontsize=8)
    b1.grid(True, alpha=0.4)
    b2.set_ylabel("pressure [bar]")
    b2.legend(loc="best", fontsize=8)
    degree_axis(b2, deg[-1], _step(deg[-1]), "shaft angle theta [deg]")
    fig.suptitle(f"{setup.kind}: chambers", fontsize=10)
    out.append(save(fig, Path(outdir) / "chambers.png"))

    fig, ax = plt.subplots(figsize=(7.5, 4.0))
    ax.plot(deg, st.shaft, color="C3", label="machine on the shaft")
    ax.axhline(float(np.trapezoid(st.shaft, theta)) / (theta[-1] - theta[0]), color="0.4", ls="--",
               lw=1.0, label="mean")  # fmt: skip
    ax.set_ylabel("shaft torque [N m] (+ drives the shaft)")
    ax.legend(loc="best", fontsize=8)
    degree_axis(ax, deg[-1], _step(deg[-1]), "shaft angle theta [deg]")
    out.append(save(fig, Path(outdir) / "shaft_torque.png"))
    return out
