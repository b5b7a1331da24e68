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
from rotorkin.drives.eccentric_cam.curves import drive_curves
from rotorkin.drives.eccentric_cam.reactor import closed_forms, opposed_piston
from rotorkin.machines import opposed_piston as op

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
    if cfg["drive"].get("eccentricity") is None:
        return "the eccentricity is set by the adjuster (drive.slide), not drive.eccentricity"
    return None


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes."""
    return _METRICS


def period(p) -> float:
    """Period of the pistons' motion: one shaft turn [rad]."""
    return 2.0 * np.pi


def _drive(p, column: bool = False) -> ec.EccentricCam:
    """The drives of the designs ``p``: fields (n,), or (n, 1) with ``column``."""

    def col(v):
        v = np.asarray(v)
        return v[:, None] if column and v.ndim else v

    return ec.EccentricCam(
        col(p.float("drive.disc_radius")),
        col(p.float("drive.eccentricity")),
        col(p["drive.follower"]),
        col(p.float("drive.roller_radius")),
    )


_MACHINE = ("device_length", "bore", "fluid", "initial_pressure", "polytropic_exponent",
            "bulk_modulus")  # fmt: skip


def _machine_values(p) -> dict:
    return {k: p[f"machine.{k}"] if k == "fluid" else p.float(f"machine.{k}") for k in _MACHINE}


def reasons(p, code: dict) -> np.ndarray:
    """Reason code per design (0: admissible), in the order of the study's checks.

    The drive's :func:`~rotorkin.drives.eccentric_cam.kinematics.invalid_parameter`,
    then the reactor's :func:`~rotorkin.machines.opposed_piston.invalid_parameter`.
    """
    r = np.zeros(p.n, dtype=np.int16)
    drive = ec.invalid_parameter(
        p.float("drive.disc_radius"),
        p.float("drive.eccentricity"),
        p["drive.follower"],
        p.float("drive.roller_radius"),
    )
    machine = op.invalid_parameter(
        **_machine_values(p),
        gap_change_min=0.0,
        piston_stroke=2.0 * p.float("drive.eccentricity"),
    )
    for section, bad in (("drive", drive), ("machine", machine)):
        for name in np.unique(bad[bad != ""]):
            flag(r, bad == name, code.get(f"{section}.{name}", code["other"]))
    return r


def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,)."""
    names = set(names)
    n = p.n
    drive = _drive(p)
    rx = opposed_piston(drive, **_machine_values(p))
    val = closed_forms(drive, rx)
    val["cavitation"] = val["cavitation"].astype(float)
    peaks = {"piston_velocity_peak_mm_per_rad", "piston_accel_peak_mm_per_rad2",
             "piston_jerk_peak_mm_per_rad3"}  # fmt: skip
    if names & peaks:
        val.update(
            _peaks(full(drive.contact_radius, n), full(drive.eccentricity, n), samples, threads)
        )
    return {name: full(val[name], n) for name in names}


def _peaks(rc, e, samples, threads) -> dict:
    beta = sample_grid(2.0 * np.pi, samples)

    def fn(lo, hi):
        peaks = ec.travel_peaks(rc[lo:hi, None], e[lo:hi, None], beta)
        return dict(zip(("v", "a", "j"), peaks, strict=True))

    res = run_blocks(fn, e.size, samples, threads)
    return {
        "piston_velocity_peak_mm_per_rad": res["v"] * 1e3,
        "piston_accel_peak_mm_per_rad2": res["a"] * 1e3,
        "piston_jerk_peak_mm_per_rad3": res["j"] * 1e3,
    }


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over one turn: angle (points,), dict (n, points)."""
    beta = sample_grid(2.0 * np.pi, points)
    out = drive_curves(_drive(p, column=True), beta)
    return beta, {k: np.array(np.broadcast_to(v, (p.n, points))) for k, v in out.items()}
