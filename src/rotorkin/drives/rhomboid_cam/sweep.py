"""Sweep kernel of the rotary-blade engine on the rhomboid lever-cam converter, by broadcasting.

The summary keys of :mod:`rotorkin.drives.rhomboid_cam.study` for arrays of designs
with the first-harmonic law (eq. 16, ``drive.a = drive.b = []``; higher
harmonics move the stationary points of ``psi`` per design, and such configs
fall back to the scalar study): ``psi`` extremes (0 and 90 deg), the cam
profile radii, the indicator work (eq. 26-28, Gauss-Legendre on the two
monotone halves, as the study), the blade-pair and engine-volume quantities in
closed form, and, sampled on ``samples`` shaft angles per design, the peaks of
the blade speed, acceleration and jerk coefficients and the pitch-curve
curvature (:func:`~rotorkin.drives.rhomboid_cam.kinematics.psi_law`,
:func:`~rotorkin.drives.rhomboid_cam.kinematics.profile_curvature` broadcast over a
design x angle array).
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.batch import flag, full, run_blocks, sample_grid
from rotorkin.drives.rhomboid_cam import kinematics as rc

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

_STATIONARY = np.array([0.0, 0.5 * np.pi, np.pi])  # of the first-harmonic law


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
    """Reason code per design (0: admissible), in the order of the study's checks."""
    r = np.zeros(p.n, dtype=np.int16)
    with np.errstate(all="ignore"):
        L = p.float("drive.link_length")
        flag(r, ~(np.isfinite(L) & (L > 0.0)), code["drive.link_length"])
        pm = p.float("drive.psi_min")
        flag(r, ~(np.isfinite(pm) & (pm > 0.0) & (pm < 0.5 * np.pi)), code["drive.psi_min"])
        B = np.asarray(p["machine.blades_per_pair"])
        flag(r, ~(B >= 1), code["machine.blades_per_pair"])
        Bf = np.where(B >= 1, B, 1).astype(float)
        ro, ri = p.float("machine.outer_radius"), p.float("machine.inner_radius")
        flag(r, ~(np.isfinite(ro) & (ro > 0.0)), code["machine.outer_radius"])
        flag(r, ~(np.isfinite(ri) & (ri >= 0.0) & (ri < ro)), code["machine.inner_radius"])
        w = p.float("machine.axial_width")
        flag(r, ~(np.isfinite(w) & (w > 0.0)), code["machine.axial_width"])
        t = p.float("machine.blade_thickness")
        flag(r, ~(np.isfinite(t) & (t >= 0.0) & (t < np.pi / Bf)), code["machine.blade_thickness"])
        lo, hi = _extremes(pm)
        t_max = np.minimum(lo, 2.0 * np.pi / Bf - hi)
        swing_bad = ~(t < t_max)
        flag(r, swing_bad & (t_max > 0.0), code["machine.blade_thickness"])
        flag(r, swing_bad, code["machine.blades_per_pair"])
    return r


def _extremes(psi_min):
    """Lowest and highest psi of the first-harmonic law (at 90 deg and 0 deg) [rad]."""
    psi = rc.psi_law(_STATIONARY, np.asarray(psi_min, dtype=float)[..., None])[0]
    return psi[..., 1], psi[..., 0]


def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,)."""
    names = set(names)
    n = p.n
    deg = np.degrees
    L, pm = p.float("drive.link_length"), p.float("drive.psi_min")
    m1, m2 = p.float("loads.torque_high"), p.float("loads.torque_low")
    z_psi = rc.psi_law(_STATIONARY, np.asarray(pm)[..., None])[0]
    lo, hi = z_psi[..., 1], z_psi[..., 0]
    travel = np.abs(z_psi[..., 1] - z_psi[..., 0]) + np.abs(z_psi[..., 2] - z_psi[..., 1])
    work = _indicator_work(full(pm, n), full(m1, n), full(m2, n))
    B = np.asarray(p["machine.blades_per_pair"]).astype(float)
    t = p.float("machine.blade_thickness")
    ro, ri = p.float("machine.outer_radius"), p.float("machine.inner_radius")
    k = 0.5 * (ro**2 - ri**2) * p.float("machine.axial_width")
    v_even = (k * (lo - t), k * (hi - t))
    v_odd = (k * (-lo + 2.0 * np.pi / B - t), k * (-hi + 2.0 * np.pi / B - t))
    vmin = [np.minimum(*v) for v in (v_even, v_odd)]
    vmax = [np.maximum(*v) for v in (v_even, v_odd)]
    val = {
        "psi_min_deg": deg(pm),
        "psi_max_deg": deg(np.pi - pm),
        "psi_lowest_deg": deg(lo),
        "psi_highest_deg": deg(hi),
        "psi_lowest_at_alpha_deg": 90.0,
        "psi_highest_at_alpha_deg": 0.0,
        "psi_monotone": 1.0,
        "psi_travel_per_period_deg": deg(travel),
        "a1_rad": rc.first_harmonic(pm)[0],
        "b1_rad": 0.0,
        "highest_harmonic": 1.0,
        "link_length_mm": L * 1e3,
        "profile_radius_min_mm": L * np.cos(0.5 * hi) * 1e3,
        "profile_radius_max_mm": L * np.cos(0.5 * lo) * 1e3,
        "indicator_work_J": work,
        "indicator_work_closed_form_J": rc.indicator_work_closed_form(pm, m1, m2),
        "mean_shaft_torque_Nm": work / np.pi,
        "torque_high_Nm": m1,
        "torque_low_Nm": m2,
        "blades_per_pair": B,
        "chambers": 2.0 * B,
        "blade_thickness_deg": deg(t),
        "blade_thickness_max_deg": deg(np.minimum(lo, 2.0 * np.pi / B - hi)),
        "sector_volume_cm3_per_rad": k * 1e6,
        "chamber_volume_max_cm3": np.maximum(*vmax) * 1e6,
        "chamber_volume_min_cm3": np.minimum(*vmin) * 1e6,
        "chamber_swept_volume_cm3": np.maximum(vmax[0] - vmin[0], vmax[1] - vmin[1]) * 1e6,
        "compression_ratio_geometric": np.minimum(vmax[0] / vmin[0], vmax[1] / vmin[1]),
        "displacement_cm3_per_rev": B * k * (2.0 * travel) * 1e6,
    }
    sampled = {"profile_convex_radius_min_mm", "profile_concave_radius_min_mm", "profile_convex",
               "blade_speed_coeff_max", "blade_speed_coeff_min", "blade_accel_coeff_max",
               "blade_jerk_coeff_max"}  # fmt: skip
    if names & sampled:
        val.update(_sampled(full(L, n), full(pm, n), samples, threads))
    return {name: full(val[name], n) for name in names}


def _indicator_work(psi_min, m1, m2, nodes: int = 64):
    """:func:`~.kinematics.indicator_work` for arrays of first-harmonic laws."""
    z = _STATIONARY
    x, w = np.polynomial.legendre.leggauss(nodes)
    half = 0.5 * (z[1:] - z[:-1])[:, None]
    al = 0.5 * (z[1:] + z[:-1])[:, None] + half * x
    pm = psi_min[:, None, None]
    psi, d1 = rc.psi_law(al, pm)[:2]
    ends = rc.psi_law(z, psi_min[:, None])[0]
    s = np.sign(np.diff(ends, axis=-1))[:, :, None]
    M = rc.blade_torque(psi, s, m1[:, None, None], m2[:, None, None], pm)
    return np.sum(M * d1 * w * half, axis=(-2, -1))


def _sampled(L, psi_min, samples, threads) -> dict:
    alpha = sample_grid(np.pi, samples)

    def fn(lo, hi):
        pm = psi_min[lo:hi, None]
        _, d1, d2, d3 = rc.psi_law(alpha, pm)
        kappa = rc.profile_curvature(alpha, L[lo:hi, None], pm)
        return {
            "d1": np.abs(d1).max(axis=1),
            "d2": np.abs(d2).max(axis=1),
            "d3": np.abs(d3).max(axis=1),
            "convex": kappa.max(axis=1),
            "concave": -kappa.min(axis=1),
        }

    res = run_blocks(fn, L.size, samples, threads)
    concave = res["concave"]
    with np.errstate(divide="ignore"):
        concave_r = np.where(concave > 0.0, 1e3 / np.where(concave > 0.0, concave, 1.0), np.inf)
    return {
        "profile_convex_radius_min_mm": 1e3 / res["convex"],
        "profile_concave_radius_min_mm": concave_r,
        "profile_convex": (concave <= 0.0).astype(float),
        "blade_speed_coeff_max": 1.0 + 0.5 * res["d1"],
        "blade_speed_coeff_min": 1.0 - 0.5 * res["d1"],
        "blade_accel_coeff_max": 0.5 * res["d2"],
        "blade_jerk_coeff_max": 0.5 * res["d3"],
    }


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over a period: angle (points,), dict (n, points)."""
    alpha = sample_grid(np.pi, points)
    L = full(p.float("drive.link_length"), p.n)[:, None]
    pm = full(p.float("drive.psi_min"), p.n)[:, None]
    psi, d1, d2, d3 = rc.psi_law(alpha, pm)
    phi = rc.blade_angles(alpha, pm)[0]
    out = {
        "psi_deg": np.degrees(psi),
        "dpsi": d1,
        "d2psi_per_rad": d2,
        "d3psi_per_rad2": d3,
        "phi1_deg": np.degrees(phi[0]),
        "phi2_deg": np.degrees(phi[1]),
        "rho_mm": rc.profile_radius(alpha, L, pm)[0] * 1e3,
        "curvature_per_m": rc.profile_curvature(alpha, L, pm),
    }
    return alpha, out
