"""Sweep kernel of the opposed-piston reactor on double eccentric discs, by broadcasting.

The summary keys of :mod:`rotorkin.drives.eccentric_cam.study` for arrays of designs:
the gap change at 90 deg (eq. 5, 6; the contact radius ``Rc = R``, ``R + r`` or
infinite for a flat face), the stroke, the pressure angle, the reactor's volume
extremes and pressures (closed forms), and the peaks of the piston velocity,
acceleration and jerk coefficients sampled on ``samples`` shaft angles (the
drive's :func:`~rotorkin.drives.eccentric_cam.kinematics.harmonic_travel` and
:func:`~rotorkin.drives.eccentric_cam.kinematics.additional_travel`, broadcast over a
design x angle array).
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.batch import flag, full, run_blocks, sample_grid
from rotorkin.drives.eccentric_cam import kinematics as ec

__all__ = ["DRIVE", "KEYS", "CURVES", "ANGLE", "unsupported", "metric_names", "reasons",
           "metrics", "curves", "period"]  # fmt: skip

DRIVE = "eccentric_cam"

KEYS = frozenset(
    {
        "drive.disc_radius",
        "drive.eccentricity",
        "drive.follower",
        "drive.roller_radius",
        "machine.device_length",
        "machine.bore",
        "machine.fluid",
        "machine.initial_pressure",
        "machine.polytropic_exponent",
        "machine.bulk_modulus",
    }
)

_METRICS = (
    "lambda",
    "lambda_contact",
    "gap_change_min_mm",
    "gap_change_min_ratio",
    "gap_change_min_angle_deg",
    "gap_change_to_length",
    "gap_change_to_length_percent",
    "gap_change_min_knife_edge_mm",
    "piston_stroke_mm",
    "piston_velocity_peak_mm_per_rad",
    "piston_accel_peak_mm_per_rad2",
    "piston_jerk_peak_mm_per_rad3",
    "pressure_angle_max_deg",
    "device_length_mm",
    "bore_mm",
    "piston_area_cm2",
    "enclosed_volume_min_cm3",
    "enclosed_volume_max_cm3",
    "chamber_volume_min_cm3",
    "chamber_volume_max_cm3",
    "volume_change_cm3",
    "volume_change_relative",
    "compression_ratio_geometric",
    "initial_pressure_bar",
    "pressure_max_bar",
    "pressure_min_bar",
    "pressure_ripple_bar",
    "pressure_ripple_relative",
    "cavitation",
)

CURVES = (
    "z_left_mm",
    "z_right_mm",
    "gap_change_mm",
    "x_left",
    "x_right",
    "xi",
    "mu",
    "delta",
    "z_left_velocity_mm_per_rad",
    "z_right_velocity_mm_per_rad",
    "z_left_accel_mm_per_rad2",
    "z_right_accel_mm_per_rad2",
    "z_left_jerk_mm_per_rad3",
    "z_right_jerk_mm_per_rad3",
    "pressure_angle_left_deg",
)
ANGLE = ("beta_deg", "Shaft angle beta; 0 puts the left piston at its top (+e).")


def unsupported(cfg: dict) -> str | None:
    """Why the kernel cannot evaluate designs on this base config (None: it can)."""
    return None


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes."""
    return _METRICS


def period(p) -> float:
    """Period of the pistons' motion: one shaft turn [rad]."""
    return 2.0 * np.pi


def _contact_radius(p):
    """``Rc``: R (knife edge), R + r (roller), inf (flat) [m], per design."""
    follower = np.asarray(p["drive.follower"])
    R, r = p.float("drive.disc_radius"), p.float("drive.roller_radius")
    return np.where(follower == "knife_edge", R, np.where(follower == "roller", R + r, np.inf))


def reasons(p, code: dict) -> np.ndarray:
    """Reason code per design (0: admissible), in the order of the study's checks."""
    r = np.zeros(p.n, dtype=np.int16)
    with np.errstate(all="ignore"):
        R, e = p.float("drive.disc_radius"), p.float("drive.eccentricity")
        flag(r, ~(np.isfinite(R) & (R > 0.0)), code["drive.disc_radius"])
        flag(r, ~(np.isfinite(e) & (e > 0.0) & (e < R)), code["drive.eccentricity"])
        rr = p.float("drive.roller_radius")
        flag(r, ~(np.isfinite(rr) & (rr >= 0.0)), code["drive.roller_radius"])
        roller = np.asarray(p["drive.follower"]) == "roller"
        flag(r, roller & ~(rr > 0.0), code["drive.roller_radius"])
        for key in ("device_length", "bore", "initial_pressure", "polytropic_exponent",
                    "bulk_modulus"):  # fmt: skip
            v = p.float(f"machine.{key}")
            flag(r, ~(np.isfinite(v) & (v > 0.0)), code[f"machine.{key}"])
    return r


def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,)."""
    names = set(names)
    n = p.n
    R, e = p.float("drive.disc_radius"), p.float("drive.eccentricity")
    rc = _contact_radius(p)
    L = p.float("machine.device_length")
    dmin = 2.0 * ec.additional_travel(rc, e, np.pi / 2.0)[0]
    knife = 2.0 * ec.additional_travel(R, e, np.pi / 2.0)[0]
    bore = p.float("machine.bore")
    area = 0.25 * np.pi * bore**2
    vmin, vmax = area * L, area * (L - dmin)
    p0 = p.float("machine.initial_pressure")
    gas = np.asarray(p["machine.fluid"]) == "gas"
    with np.errstate(divide="ignore", invalid="ignore"):
        p_gas = p0 * (vmin / vmax) ** p.float("machine.polytropic_exponent")
        p_liq = p0 - p.float("machine.bulk_modulus") * np.log(vmax / vmin)
    p_end = np.where(gas, p_gas, p_liq)
    val = {
        "lambda": e / R,
        "lambda_contact": e / rc,
        "gap_change_min_mm": dmin * 1e3,
        "gap_change_min_ratio": dmin / e,
        "gap_change_min_angle_deg": np.degrees(np.pi / 2.0),
        "gap_change_to_length": np.abs(dmin) / L,
        "gap_change_to_length_percent": 100.0 * np.abs(dmin) / L,
        "gap_change_min_knife_edge_mm": knife * 1e3,
        "piston_stroke_mm": 2.0 * e * 1e3,
        "pressure_angle_max_deg": np.degrees(np.arcsin(e / rc)),
        "device_length_mm": L * 1e3,
        "bore_mm": bore * 1e3,
        "piston_area_cm2": area * 1e4,
        "enclosed_volume_min_cm3": vmin * 1e6,
        "enclosed_volume_max_cm3": vmax * 1e6,
        "chamber_volume_min_cm3": vmin * 1e6,
        "chamber_volume_max_cm3": vmax * 1e6,
        "volume_change_cm3": (vmax - vmin) * 1e6,
        "volume_change_relative": (vmax - vmin) / vmin,
        "compression_ratio_geometric": vmax / vmin,
        "initial_pressure_bar": p0 / 1e5,
        "pressure_max_bar": p0 / 1e5,
        "pressure_min_bar": p_end / 1e5,
        "pressure_ripple_bar": (p0 - p_end) / 1e5,
        "pressure_ripple_relative": (p0 - p_end) / p0,
        "cavitation": (p_end <= 0.0).astype(float),
    }
    peaks = {"piston_velocity_peak_mm_per_rad", "piston_accel_peak_mm_per_rad2",
             "piston_jerk_peak_mm_per_rad3"}  # fmt: skip
    if names & peaks:
        val.update(_peaks(full(rc, n), full(e, n), samples, threads))
    return {name: full(val[name], n) for name in names}


def _peaks(rc, e, samples, threads) -> dict:
    beta = sample_grid(2.0 * np.pi, samples)

    def fn(lo, hi):
        h = ec.harmonic_travel(e[lo:hi, None], beta)
        a = ec.additional_travel(rc[lo:hi, None], e[lo:hi, None], beta)
        out = {}
        for k, name in ((1, "v"), (2, "a"), (3, "j")):
            left, right = np.abs(a[k] + h[k]), np.abs(a[k] - h[k])
            out[name] = np.maximum(left.max(axis=1), right.max(axis=1))
        return out

    res = run_blocks(fn, e.size, samples, threads)
    return {
        "piston_velocity_peak_mm_per_rad": res["v"] * 1e3,
        "piston_accel_peak_mm_per_rad2": res["a"] * 1e3,
        "piston_jerk_peak_mm_per_rad3": res["j"] * 1e3,
    }


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over one turn: angle (points,), dict (n, points)."""
    beta = sample_grid(2.0 * np.pi, points)
    e = full(p.float("drive.eccentricity"), p.n)[:, None]
    rc = full(_contact_radius(p), p.n)[:, None]
    h = ec.harmonic_travel(e, beta)
    a = ec.additional_travel(rc, e, beta)
    q = [np.stack([ai + hi, ai - hi]) for ai, hi in zip(a, h, strict=True)]
    xi = np.broadcast_to(np.cos(beta), (p.n, points))
    mu = a[0] / e
    out = {
        "z_left_mm": q[0][0] * 1e3,
        "z_right_mm": q[0][1] * 1e3,
        "gap_change_mm": (q[0][0] + q[0][1]) * 1e3,
        "x_left": xi + mu,
        "x_right": mu - xi,
        "xi": np.array(xi),
        "mu": mu,
        "delta": 2.0 * mu,
        "pressure_angle_left_deg": np.degrees(np.arcsin(e * np.sin(beta) / rc)),
    }
    for k, (name, suffix) in enumerate((("velocity", "mm_per_rad"), ("accel", "mm_per_rad2"),
                                        ("jerk", "mm_per_rad3")), start=1):  # fmt: skip
        out[f"z_left_{name}_{suffix}"] = q[k][0] * 1e3
        out[f"z_right_{name}_{suffix}"] = q[k][1] * 1e3
    return beta, out
