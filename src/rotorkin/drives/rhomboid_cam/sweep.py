"""Sweep kernel of the rotary-blade engine on the rhomboid lever-cam converter, by broadcasting.

The summary keys of :mod:`rotorkin.drives.rhomboid_cam.study` for arrays of designs
with the first-harmonic law (eq. 16, ``drive.a = drive.b = []``; higher
harmonics move the stationary points of ``psi`` per design, and such configs
fall back to the scalar study): ``psi`` extremes (0 and 90 deg), the cam
profile radii, the indicator work (eq. 26-28, Gauss-Legendre on the two
monotone halves, as the study), the blade-pair and engine-volume quantities in
closed form, and, sampled on ``samples`` shaft angles per design, the peaks of
the blade speed, acceleration and jerk coefficients and the pitch-curve
curvature (:func:`~rotorkin.drives.rhomboid_cam.kinematics.law_peaks` over a
design x angle array).

Every formula is the drive's (:mod:`rotorkin.drives.rhomboid_cam.kinematics`) or the
machine's (:mod:`rotorkin.machines.rotary_blade`), called with arrays of parameters:
the kernel only gathers the designs' values and names the summary keys.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.batch import flag, full, run_blocks, sample_grid
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.machines import rotary_blade as rb

__all__ = ["DRIVE", "KEYS", "CURVES", "ANGLE", "unsupported", "metric_names", "reasons",
           "metrics", "curves", "period"]  # fmt: skip

DRIVE = "rhomboid_cam"

KEYS = frozenset(
    {
        "drive.link_length",
        "drive.psi_min",
        "loads.torque_high",
        "loads.torque_low",
        "machine.blade_thickness",
        "machine.blades_per_pair",
        "machine.inner_radius",
        "machine.outer_radius",
        "machine.axial_width",
    }
)

_METRICS = (
    "psi_min_deg",
    "psi_max_deg",
    "psi_lowest_deg",
    "psi_highest_deg",
    "psi_lowest_at_alpha_deg",
    "psi_highest_at_alpha_deg",
    "psi_monotone",
    "psi_travel_per_period_deg",
    "a1_rad",
    "b1_rad",
    "highest_harmonic",
    "link_length_mm",
    "profile_radius_min_mm",
    "profile_radius_max_mm",
    "profile_convex_radius_min_mm",
    "profile_concave_radius_min_mm",
    "profile_convex",
    "indicator_work_J",
    "indicator_work_closed_form_J",
    "mean_shaft_torque_Nm",
    "blade_speed_coeff_max",
    "blade_speed_coeff_min",
    "blade_accel_coeff_max",
    "blade_jerk_coeff_max",
    "torque_high_Nm",
    "torque_low_Nm",
    "blades_per_pair",
    "chambers",
    "blade_thickness_deg",
    "blade_thickness_max_deg",
    "sector_volume_cm3_per_rad",
    "chamber_volume_max_cm3",
    "chamber_volume_min_cm3",
    "chamber_swept_volume_cm3",
    "compression_ratio_geometric",
    "displacement_cm3_per_rev",
)

CURVES = (
    "psi_deg",
    "dpsi",
    "d2psi_per_rad",
    "d3psi_per_rad2",
    "phi1_deg",
    "phi2_deg",
    "rho_mm",
    "curvature_per_m",
)
ANGLE = ("alpha_deg", "Output-shaft angle alpha: polar angle of diagonal OA, from +x.")

_MACHINE = ("blade_thickness", "inner_radius", "outer_radius", "axial_width", "blades_per_pair")


def unsupported(cfg: dict) -> str | None:
    """Why the kernel cannot evaluate designs on this base config (None: it can)."""
    d = cfg["drive"]
    if d.get("a") or d.get("b"):
        return "drive.a / drive.b hold higher harmonics (their stationary points vary per design)"
    return None


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes."""
    return _METRICS


def period(p) -> float:
    """Period of psi in the output-shaft angle: pi [rad]."""
    return float(np.pi)


def reasons(p, code: dict) -> np.ndarray:
    """Reason code per design (0: admissible), in the order of the study's checks.

    The drive's :func:`~rotorkin.drives.rhomboid_cam.kinematics.violation`, the
    machine's :func:`~rotorkin.machines.rotary_blade.violation` and, for the drive's
    swing of ``psi``, :func:`~rotorkin.machines.rotary_blade.swing_violation`.
    """
    r = np.zeros(p.n, dtype=np.int16)
    with np.errstate(all="ignore"):
        pm = p.float("drive.psi_min")
        _report(r, rc.violation(p.float("drive.link_length"), pm), rc.CHECKS, "drive", code)
        m = {k: p[f"machine.{k}"] for k in _MACHINE}
        _report(r, rb.violation(**m), rb.CHECKS, "machine", code)
        lo, _, hi, _ = rc.psi_extremes(pm)
        swing = rb.swing_violation(m["blades_per_pair"], m["blade_thickness"], lo, hi)
        _report(r, swing, rb.SWING_CHECKS, "machine", code)
    return r


def _report(r, violation, names, section, code) -> None:
    """Flag the designs whose ``violation`` code points at ``names[i - 1]``."""
    for i, name in enumerate(names, start=1):
        key = f"{section}.{name}"
        if key in code:
            flag(r, violation == i, code[key])


def _machine(p) -> rb.RotaryBlade:
    """The designs' machines, one holder of arrays (admissible designs only)."""
    m = {k: p.float(f"machine.{k}") for k in _MACHINE}
    m["blades_per_pair"] = np.asarray(m["blades_per_pair"]).astype(np.int64)
    return rb.RotaryBlade(**m)


def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,)."""
    names = set(names)
    n = p.n
    deg = np.degrees
    L, pm = p.float("drive.link_length"), p.float("drive.psi_min")
    m1, m2 = p.float("loads.torque_high"), p.float("loads.torque_low")
    lo, alo, hi, ahi = rc.psi_extremes(pm)
    travel = rc.psi_total_variation(pm)
    work = rc.indicator_work(full(pm, n), (), (), full(m1, n), full(m2, n))
    machine = _machine(p)
    vol = rb.chamber_figures(machine, lo, hi)
    rho_min, rho_max = rc.profile_radius_range(L, lo, hi)
    revs = 2.0 * np.pi / period(p)  # periods per output-shaft revolution
    val = {
        "psi_min_deg": deg(pm),
        "psi_max_deg": deg(np.pi - pm),
        "psi_lowest_deg": deg(lo),
        "psi_highest_deg": deg(hi),
        "psi_lowest_at_alpha_deg": deg(alo),
        "psi_highest_at_alpha_deg": deg(ahi),
        "psi_monotone": 1.0,
        "psi_travel_per_period_deg": deg(travel),
        "a1_rad": rc.first_harmonic(pm)[0],
        "b1_rad": rc.first_harmonic(pm)[1] + 0.0,
        "highest_harmonic": 1.0,
        "link_length_mm": L * 1e3,
        "profile_radius_min_mm": rho_min * 1e3,
        "profile_radius_max_mm": rho_max * 1e3,
        "indicator_work_J": work,
        "indicator_work_closed_form_J": rc.indicator_work_closed_form(pm, m1, m2),
        "mean_shaft_torque_Nm": work / np.pi,
        "torque_high_Nm": m1,
        "torque_low_Nm": m2,
        "blades_per_pair": np.asarray(machine.blades_per_pair, dtype=float),
        "chambers": 2.0 * np.asarray(machine.blades_per_pair, dtype=float),
        "blade_thickness_deg": deg(machine.blade_thickness),
        "blade_thickness_max_deg": deg(rb.blade_thickness_max(machine.blades_per_pair, lo, hi)),
        "sector_volume_cm3_per_rad": rb.sector_constant(machine) * 1e6,
        "chamber_volume_max_cm3": vol["volume_max"] * 1e6,
        "chamber_volume_min_cm3": vol["volume_min"] * 1e6,
        "chamber_swept_volume_cm3": vol["swept_volume"] * 1e6,
        "compression_ratio_geometric": vol["compression_ratio"],
        "displacement_cm3_per_rev": rb.displacement_per_rev(machine, revs * travel) * 1e6,
    }
    sampled = {"profile_convex_radius_min_mm", "profile_concave_radius_min_mm", "profile_convex",
               "blade_speed_coeff_max", "blade_speed_coeff_min", "blade_accel_coeff_max",
               "blade_jerk_coeff_max"}  # fmt: skip
    if names & sampled:
        val.update(_sampled(full(L, n), full(pm, n), samples, threads))
    return {name: full(val[name], n) for name in names}


def _sampled(L, psi_min, samples, threads) -> dict:
    alpha = sample_grid(np.pi, samples)

    def fn(lo, hi):
        return rc.law_peaks(L[lo:hi, None], psi_min[lo:hi, None], (), (), alpha)

    res = run_blocks(fn, L.size, samples, threads)
    return {
        "profile_convex_radius_min_mm": res["convex_radius_min"] * 1e3,
        "profile_concave_radius_min_mm": res["concave_radius_min"] * 1e3,
        "profile_convex": res["convex"].astype(float),
        "blade_speed_coeff_max": res["speed_coeff_max"],
        "blade_speed_coeff_min": res["speed_coeff_min"],
        "blade_accel_coeff_max": res["accel_coeff_max"],
        "blade_jerk_coeff_max": res["jerk_coeff_max"],
    }


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over a period: angle (points,), dict (n, points)."""
    alpha = sample_grid(np.pi, points)
    L = full(p.float("drive.link_length"), p.n)[:, None]
    pm = full(p.float("drive.psi_min"), p.n)[:, None]
    psi, d1, d2, d3 = rc.psi_law(pm, (), (), alpha)
    phi = rc.blade_angles(pm, (), (), alpha)[0]
    out = {
        "psi_deg": np.degrees(psi),
        "dpsi": d1,
        "d2psi_per_rad": d2,
        "d3psi_per_rad2": d3,
        "phi1_deg": np.degrees(phi[0]),
        "phi2_deg": np.degrees(phi[1]),
        "rho_mm": rc.profile_radius(L, pm, (), (), alpha)[0] * 1e3,
        "curvature_per_m": rc.profile_curvature(L, pm, (), (), alpha),
    }
    return alpha, out
