"""Guide-bar drive: lambda for a target vane angle, at any installation phase.

The inverse of the paper's section 3 (JHIT 2012, ``papers/guide_bar_pump.md``).
The theoretical vane angle ``gamma_0`` - what the slower impeller turns between
the two equal-speed points - follows from the mechanism coefficient
``lambda = d/a``, the gear ratio ``u``, the phase ``Sigma`` and the driver
(:func:`rotorkin.drives.guide_bar.kinematics.vane_angle`). The paper inverts it at
``Sigma = 180 deg`` only (eq. 5, 6;
:func:`~rotorkin.drives.guide_bar.kinematics.lambda_for_vane_angle`);
here any phase, by vectorized bracketed root finding on ``0 < lambda < 1``.

``gamma_0 u`` depends on lambda, Sigma and the driver only (``gamma_0 = f(lambda, Sigma) / u``),
so the gear ratio that gives a target vane angle at a fixed lambda is explicit:
``u = f(lambda, Sigma) / gamma_0`` (:func:`gear_ratio_for_vane_angle`).
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.angles import fmt_deg
from rotorkin.core.errors import ParameterError
from rotorkin.core.schema import validate_model
from rotorkin.drives.guide_bar import figures_synthesis
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar.schema import GuideBarConfig
from rotorkin.drives.guide_bar.study import evaluate
from rotorkin.synthesis import SynthesisResult, parse_quantity_arg, synthesized_raw_config

__all__ = [
    "vane_angle_range",
    "lambda_for_vane_angle",
    "gear_ratio_for_vane_angle",
    "DEFAULT_VANE_ANGLE",
    "default_vane_angle",
    "synthesize",
]

#: Grid of lambda on which the root is bracketed (ends 0 and 1 included).
_GRID = np.linspace(0.0, 1.0, 257)


def _vane(lam, u, phase, driver):
    with np.errstate(divide="ignore", invalid="ignore"):
        return gb.vane_angle(lam, u, phase, driver)


def vane_angle_range(u, phase, driver: str):
    """Vane angles reachable with ``0 < lambda < 1`` (an open interval) [rad].

    ``gamma_0`` is monotone in lambda (checked on a grid of 257 values; for every
    phase it falls from ``pi/u`` at ``lambda -> 0``), so the bounds are its limits
    at ``lambda = 0`` and ``lambda = 1``; where the grid showed otherwise, its
    extremes are used.

    Parameters
    ----------
    u, phase : array_like
        Gear ratio [-] and installation phase Sigma [rad], broadcast.
    driver : {"crank", "guide"}

    Returns
    -------
    (lo, hi) : tuple of ndarray
        ``lo < gamma_0 < hi`` [rad].
    """
    u = np.asarray(u, dtype=float)[..., None]
    phase = np.asarray(phase, dtype=float)[..., None]
    g = _vane(_GRID, u, phase, driver)
    return np.nanmin(g, axis=-1), np.nanmax(g, axis=-1)


def lambda_for_vane_angle(gamma0, u, phase, driver: str):
    """Mechanism coefficient lambda giving the vane angle ``gamma0`` (section 3 inverted).

    Solves ``vane_angle(lambda, u, Sigma, driver) = gamma0`` for ``0 < lambda < 1``
    by bracketing on a grid of lambda and bisecting every element at once to
    the resolution of doubles; the smallest root where there were several.
    At ``Sigma = 180 deg`` it agrees with eq. 5 (crank, ``lambda = cot(u gamma_0/2)``)
    and eq. 6 (guide, ``lambda = cos(u gamma_0/2)``).

    Parameters
    ----------
    gamma0 : array_like
        Target vane angle [rad].
    u, phase : array_like
        Gear ratio [-] and installation phase Sigma [rad], broadcast with gamma0.
    driver : {"crank", "guide"}

    Returns
    -------
    ndarray
        lambda [-], NaN where the target is not reachable (see :func:`vane_angle_range`).
    """
    gamma0, u, phase = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (gamma0, u, phase))
    )
    f = _vane(_GRID, u[..., None], phase[..., None], driver) - gamma0[..., None]
    sign = np.sign(f)
    change = (sign[..., :-1] * sign[..., 1:] <= 0.0) & np.isfinite(f[..., :-1] * f[..., 1:])
    found = change.any(axis=-1)
    i = np.argmax(change, axis=-1)
    lo, hi = _GRID[i], _GRID[i + 1]
    flo = np.take_along_axis(f, i[..., None], axis=-1)[..., 0]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        fm = _vane(mid, u, phase, driver) - gamma0
        same = np.sign(fm) == np.sign(flo)
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
        flo = np.where(same, fm, flo)
    lam = 0.5 * (lo + hi)
    ok = found & (lam > 0.0) & (lam < 1.0)
    return np.where(ok, lam, np.nan)


def gear_ratio_for_vane_angle(gamma0, lam, phase, driver: str):
    """Gear ratio u giving the vane angle ``gamma0`` at a fixed lambda [-].

    ``u = f(lambda, Sigma)/gamma0``: ``f = u gamma_0`` of
    :func:`rotorkin.drives.guide_bar.kinematics.vane_angle` does not depend on u.
    """
    return gb.vane_angle(lam, 1.0, phase, driver) / np.asarray(gamma0, dtype=float)


# --------------------------------------------------------------------------------------------
# the command's entry point
# --------------------------------------------------------------------------------------------
#: Vane angle aimed at when ``--target`` is not given [rad]: 60 deg, the guide-driven
#: example's vane angle (lambda = 0.5, u = 2), reached crank-driven with lambda = cot 60 deg.
DEFAULT_VANE_ANGLE = np.pi / 3.0


def default_vane_angle(lam, u, phase, driver: str) -> float:
    """The target vane angle when none is given [rad].

    :data:`DEFAULT_VANE_ANGLE` (60 deg) where it is reachable (:func:`vane_angle_range`)
    and differs from the design's own vane angle by more than 0.5 deg; otherwise the
    middle of the reachable range, or (where that is the design's own) the middle of the
    part of the range beyond the design's vane angle that is the larger.
    """
    lo, hi = (float(v) for v in vane_angle_range(u, phase, driver))
    own = float(gb.vane_angle(lam, u, phase, driver))
    tol = np.radians(0.5)
    for gamma in (DEFAULT_VANE_ANGLE, 0.5 * (lo + hi)):
        if lo < gamma < hi and abs(gamma - own) > tol:
            return float(gamma)
    return float(0.5 * (lo + own) if own - lo > hi - own else 0.5 * (own + hi))


def synthesize(cfg, raw, objective, target, harmonics, options=None):
    """lambda for the ``target`` vane angle (objective ``vane_angle``), keeping u, Sigma, driver.

    See :func:`rotorkin.synthesis.synthesize`. ``target`` is an angle with its
    unit (``"60 deg"``); None: :func:`default_vane_angle` (60 deg where reachable).
    The round trip evaluates the synthesized config.
    """
    if harmonics is not None:
        raise ParameterError("harmonics", str(harmonics), "not used by the guide_bar drive")
    d = cfg["drive"]
    lam0, u, phase, driver = (
        float(d["lambda"]),
        float(d["gear_ratio"]),
        float(d["phase"]),
        d["driver"],
    )
    lo, hi = (float(v) for v in vane_angle_range(u, phase, driver))
    gamma = default_vane_angle(lam0, u, phase, driver) if target is None else None
    if gamma is None:
        gamma = parse_quantity_arg(target, "angle", name="target")
    u_alt = float(gear_ratio_for_vane_angle(gamma, lam0, phase, driver)) if gamma > 0 else np.nan
    if not lo < gamma < hi:
        alt = (
            f"; or keep lambda = {lam0:g} and set drive.gear_ratio = {u_alt:.6g}"
            if np.isfinite(u_alt) and u_alt > 0
            else ""
        )
        raise ParameterError(
            "target",
            fmt_deg(gamma),
            f"{fmt_deg(lo)} < gamma_0 < {fmt_deg(hi)} (reachable with 0 < lambda < 1 at "
            f"phase = {fmt_deg(phase)}, gear_ratio = {u:g}, driver = {driver}){alt}",
        )
    lam = float(lambda_for_vane_angle(gamma, u, phase, driver))
    updates = {"drive": {"lambda": lam}}
    new_raw = synthesized_raw_config(raw, updates, objective)
    res0 = evaluate(cfg)
    res1 = evaluate(validate_model(GuideBarConfig, new_raw))
    g0 = float(gb.vane_angle(lam0, u, phase, driver))
    g1 = float(gb.vane_angle(lam, u, phase, driver))
    g1_run = float(np.radians(res1.summary["vane_angle_deg"]))
    keys = (
        ("relative_angle_swing_deg", "relative angle swing [deg]"),
        ("impeller_speed_ratio_min", "impeller speed ratio min"),
        ("impeller_speed_ratio_max", "impeller speed ratio max"),
        ("impeller_accel_peak_per_rad", "impeller accel peak [1/rad]"),
        ("input_torque_fluctuation_ratio", "input torque fluctuation"),
        ("displacement_cm3_per_rev", "displacement [cm3/rev]"),
        ("flow_ripple", "flow ripple"),
    )
    rows = [
        ("lambda", lam0, lam),
        ("vane angle gamma_0 [deg]", np.degrees(g0), np.degrees(g1)),
        ("target gamma_0 [deg]", "", np.degrees(gamma)),
        ("round trip |error| [rad]", "", abs(g1_run - gamma)),
    ]
    rows += [(label, res0.summary[k], res1.summary[k]) for k, label in keys]
    metrics = {
        "target_vane_angle_deg": float(np.degrees(gamma)),
        "target_given": target is not None,
        "reachable_vane_angle_min_deg": float(np.degrees(lo)),
        "reachable_vane_angle_max_deg": float(np.degrees(hi)),
        "baseline_lambda": lam0,
        "baseline_vane_angle_deg": float(np.degrees(g0)),
        "synthesized_vane_angle_deg": float(np.degrees(g1)),
        "round_trip_error_rad": abs(g1_run - gamma),
        "alternative_gear_ratio_at_baseline_lambda": u_alt,
    }
    for k, _ in keys:
        metrics[f"baseline_{k}"] = res0.summary[k]
        metrics[f"synthesized_{k}"] = res1.summary[k]
    notes = (
        f"alternative: keep lambda = {lam0:g} and set drive.gear_ratio = {u_alt:.6g} "
        "(gamma_0 is inversely proportional to u)",
    )
    if target is None:
        notes = (
            f"target not given: gamma_0 = {fmt_deg(gamma)} (60 deg where reachable and not "
            "the design's own; else the middle of the reachable range)",
        ) + notes

    def plot(outdir):
        return figures_synthesis.plot_guide_bar(
            outdir, (lam0, lam), u, phase, driver, gamma, float(d["input_gear_ratio"])
        )

    return SynthesisResult(
        drive_type="guide_bar",
        objective=objective,
        title=f"guide bar, {driver}-driven, phase {fmt_deg(phase)}: lambda for "
        f"gamma_0 = {fmt_deg(gamma)}",
        rows=tuple(rows),
        parameters={"lambda": lam, "gear_ratio": u, "phase_deg": float(np.degrees(phase))},
        metrics=metrics,
        updates=updates,
        notes=notes,
        plot=plot,
    )
