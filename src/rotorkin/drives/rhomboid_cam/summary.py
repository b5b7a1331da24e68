"""Summary keys of the rhomboid drive and of the engine's geometry, for one design or many.

The study (:mod:`rotorkin.drives.rhomboid_cam.study`, one design, floats) and the sweep
kernel (:mod:`rotorkin.drives.rhomboid_cam.sweep`, arrays of first-harmonic designs)
both build these keys here, from the drive's functions
(:mod:`rotorkin.drives.rhomboid_cam.kinematics`) and the machine's
(:mod:`rotorkin.machines.rotary_blade`); the keys carry their units as suffixes.
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import flywheel as fw
from rotorkin.analysis import torque as at
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.machines import rotary_blade as rb
from rotorkin.studies.helpers import time_peak_keys

__all__ = [
    "LAW_KEYS",
    "PEAK_KEYS",
    "GEOMETRY_KEYS",
    "DYNAMICS_KEYS",
    "SLUGS",
    "TIME_KEYS",
    "CURVE_KEYS",
    "law_curves",
    "law_summary",
    "peak_summary",
    "engine_geometry_summary",
    "dynamics_summary",
]

#: Keys of :func:`peak_summary` (sampled on a grid of shaft angles).
PEAK_KEYS = (
    "profile_convex_radius_min_mm",
    "profile_concave_radius_min_mm",
    "profile_convex",
    "blade_speed_coeff_max",
    "blade_speed_coeff_min",
    "blade_accel_coeff_max",
    "blade_jerk_coeff_max",
)


#: Keys of :func:`law_summary` and :func:`peak_summary`, in the order of ``summary.json``.
LAW_KEYS = (
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
    *PEAK_KEYS[:3],
    "indicator_work_J",
    "indicator_work_closed_form_J",
    "mean_shaft_torque_Nm",
    *PEAK_KEYS[3:],
    "torque_high_Nm",
    "torque_low_Nm",
)
#: Keys of :func:`engine_geometry_summary`, in order.
GEOMETRY_KEYS = (
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

#: Keys of :func:`dynamics_summary`, in order.
DYNAMICS_KEYS = (
    "indicated_work_J",
    "indicated_work_per_period_J",
    "indicated_power_kW",
    "mean_torque_Nm",
    *at.SHAFT_TORQUE_KEYS,
    "inertia_torque_peak_Nm",
    "blade_pair_torque_peak_Nm",
    "equivalent_inertia_mean_kgm2",
    "equivalent_inertia_min_kgm2",
    "equivalent_inertia_max_kgm2",
    "energy_fluctuation_J",
    "speed_fluctuation_without_flywheel",
    "speed_fluctuation",
    "flywheel_inertia_kgm2",
)

#: Key stems of the two blade pairs.
SLUGS = ("blade_pair_1", "blade_pair_2")
#: Keys of :func:`rotorkin.studies.helpers.time_peaks` for the blade pairs.
TIME_KEYS = time_peak_keys(SLUGS)


#: Keys of :func:`law_curves`, in the order of ``motion.csv``.
CURVE_KEYS = (
    "psi_deg",
    "dpsi",
    "d2psi_per_rad",
    "d3psi_per_rad2",
    "phi1_deg",
    "phi2_deg",
    "rho_mm",
    "curvature_per_m",
)


def law_curves(link_length, psi_min, a, b, alpha) -> dict:
    """The law, the blade-pair angles and the pitch curve against the shaft angle.

    Parameters broadcast against ``alpha`` [rad] (e.g. ``(n, 1)`` against ``(m,)``).

    Returns
    -------
    dict
        :data:`CURVE_KEYS` -> arrays: ``psi`` [deg] and its derivatives (eq. 13, 14),
        ``phi_1``, ``phi_2`` [deg] (eq. 21), ``rho`` [mm] (eq. 3) and its curvature [1/m].
    """
    psi, d1, d2, d3 = rc.psi_law(psi_min, a, b, alpha)
    phi = rc.blade_angles(psi_min, a, b, alpha)[0]
    return {
        "psi_deg": np.degrees(psi),
        "dpsi": d1,
        "d2psi_per_rad": d2,
        "d3psi_per_rad2": d3,
        "phi1_deg": np.degrees(phi[0]),
        "phi2_deg": np.degrees(phi[1]),
        "rho_mm": rc.profile_radius(link_length, psi_min, a, b, alpha)[0] * 1e3,
        "curvature_per_m": rc.profile_curvature(link_length, psi_min, a, b, alpha),
    }


def law_summary(link_length, psi_min, a, b, torque_high, torque_low) -> dict:
    """The law ``psi(alpha)``, the cam's radii and the paper's indicator work (eq. 13-34).

    Parameters
    ----------
    link_length : array_like
        ``2l`` [m].
    psi_min : array_like
        [rad]; an array only for the first-harmonic law (``a = b = ()``).
    a, b : sequence of float
        Higher harmonics [rad].
    torque_high, torque_low : array_like
        ``M1``, ``M2`` of the linear model (eq. 29) [N m].

    Returns
    -------
    dict
        Summary key -> value (float or array, broadcast of the inputs).
    """
    deg = np.degrees
    lo, alo, hi, ahi = rc.psi_extremes(psi_min, a, b)
    a1, b1 = rc.first_harmonic(psi_min, a, b)
    rho_min, rho_max = rc.profile_radius_range(link_length, lo, hi)
    work = rc.indicator_work(psi_min, a, b, torque_high, torque_low)
    return {
        "psi_min_deg": deg(psi_min),
        "psi_max_deg": deg(np.pi - psi_min),
        "psi_lowest_deg": deg(lo),
        "psi_highest_deg": deg(hi),
        "psi_lowest_at_alpha_deg": deg(alo),
        "psi_highest_at_alpha_deg": deg(ahi),
        "psi_monotone": rc.psi_is_monotone(psi_min, a, b),
        "psi_travel_per_period_deg": deg(rc.psi_total_variation(psi_min, a, b)),
        "a1_rad": a1,
        "b1_rad": b1 + 0.0,  # no negative zero
        "highest_harmonic": 2 * max(len(a), len(b)) + 1,
        "link_length_mm": link_length * 1e3,
        "profile_radius_min_mm": rho_min * 1e3,
        "profile_radius_max_mm": rho_max * 1e3,
        "indicator_work_J": work,
        "indicator_work_closed_form_J": rc.indicator_work_closed_form(
            psi_min, torque_high, torque_low
        ),
        "mean_shaft_torque_Nm": work / np.pi,
        "torque_high_Nm": torque_high,
        "torque_low_Nm": torque_low,
    }


def peak_summary(peaks: dict) -> dict:
    """The :data:`PEAK_KEYS` from the output of :func:`~.kinematics.law_peaks`."""
    return {
        "profile_convex_radius_min_mm": peaks["convex_radius_min"] * 1e3,
        "profile_concave_radius_min_mm": peaks["concave_radius_min"] * 1e3,
        "profile_convex": peaks["convex"],
        "blade_speed_coeff_max": peaks["speed_coeff_max"],
        "blade_speed_coeff_min": peaks["speed_coeff_min"],
        "blade_accel_coeff_max": peaks["accel_coeff_max"],
        "blade_jerk_coeff_max": peaks["jerk_coeff_max"],
    }


def engine_geometry_summary(machine, psi_lo, psi_hi, psi_travel_per_rev) -> dict:
    """Blades and chamber volumes of the rotary-blade engine over the drive's swing of psi.

    Parameters
    ----------
    machine : rotorkin.machines.rotary_blade.RotaryBlade
        One design or arrays of designs.
    psi_lo, psi_hi : array_like
        Lowest and highest ``psi`` [rad].
    psi_travel_per_rev : array_like
        Total travel of ``psi`` per output-shaft revolution [rad].
    """
    deg = np.degrees
    B = machine.blades_per_pair
    vol = rb.chamber_figures(machine, psi_lo, psi_hi)
    return {
        "blades_per_pair": B,
        "chambers": 2 * B,
        "blade_thickness_deg": deg(machine.blade_thickness),
        "blade_thickness_max_deg": deg(rb.blade_thickness_max(B, psi_lo, psi_hi)),
        "sector_volume_cm3_per_rad": rb.sector_constant(machine) * 1e6,
        "chamber_volume_max_cm3": vol["volume_max"] * 1e6,
        "chamber_volume_min_cm3": vol["volume_min"] * 1e6,
        "chamber_swept_volume_cm3": vol["swept_volume"] * 1e6,
        "compression_ratio_geometric": vol["compression_ratio"],
        "displacement_cm3_per_rev": rb.displacement_per_rev(machine, psi_travel_per_rev) * 1e6,
    }


def dynamics_summary(machine, alpha, motion, members, torque, omega, coefficient,
                     work_period) -> tuple[dict, dict]:  # fmt: skip
    """Work, torques, inertia and flywheel of the engine over one period (:data:`DYNAMICS_KEYS`).

    For one design or many: with the parameters as columns ``(d, 1)`` against the
    angles, every curve is ``(..., d, n)`` and every key an array ``(d,)``.

    Parameters
    ----------
    machine : rotorkin.machines.rotary_blade.RotaryBlade
        Its inertias (floats or columns).
    alpha : ndarray, shape (n,)
        Output-shaft angles over one period, ends included [rad].
    motion : rotorkin.core.motion.Motion
        The blade pairs at ``alpha``.
    members, torque : ndarray
        Torques of the loads on the blade pairs (2, ..., n) and on the shaft (..., n) [N m].
    omega : tuple of array_like
        ``(omega, omega_dot, ...)`` at ``alpha`` [rad/s, rad/s^2].
    coefficient : array_like
        ``machine.speed_fluctuation``, the wanted coefficient of speed fluctuation.
    work_period : array_like
        Work of the loads over one period [J].

    Returns
    -------
    (summary, curves) : dict, dict
        The keys, and the curves the figures draw: ``"inertia_torque"`` (what the shaft
        spends on the inertias at the run speed), ``"with_inertia"`` (the shaft torque
        less it), ``"steady"`` (less the inertia torque at the constant mean speed),
        ``"equivalent_inertia"``, ``"omega_mean"``.
    """
    alpha = np.asarray(alpha, dtype=float)
    period = alpha[-1] - alpha[0]
    js, jm = machine.inertia_shaft, machine.member_inertias
    dq, d2q = motion.dq, motion.d2q
    t_inertia = at.inertia_torque(js, jm, dq, d2q, omega[0], omega[1])
    w = np.broadcast_to(np.asarray(omega[0], dtype=float), np.shape(torque))
    w_mean = np.mean(w[..., :-1], axis=-1)
    steady = torque - at.inertia_torque(js, jm, dq, d2q, w_mean[..., None], 0.0)
    j_eq = at.equivalent_inertia(js, jm, dq)
    j_mean = np.mean(j_eq[..., :-1], axis=-1)
    d_e = fw.energy_fluctuation(steady, alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        free = np.where(j_mean > 0.0, fw.speed_fluctuation_coefficient(d_e, j_mean, w_mean),
                        np.inf)  # fmt: skip
    work_period = np.asarray(work_period, dtype=float)
    work_rev = (2.0 * np.pi / period) * work_period
    with_inertia = torque - t_inertia
    summary = {
        "indicated_work_J": work_rev,
        "indicated_work_per_period_J": work_period,
        "indicated_power_kW": work_period / np.trapezoid(1.0 / w, alpha, axis=-1) * 1e-3,
        "mean_torque_Nm": work_rev / (2.0 * np.pi),
        **at.shaft_torque_summary(torque, with_inertia),
        "inertia_torque_peak_Nm": np.max(np.abs(t_inertia), axis=-1),
        "blade_pair_torque_peak_Nm": np.max(np.abs(members), axis=(0, -1)),
        "equivalent_inertia_mean_kgm2": j_mean,
        "equivalent_inertia_min_kgm2": np.min(j_eq, axis=-1),
        "equivalent_inertia_max_kgm2": np.max(j_eq, axis=-1),
        "energy_fluctuation_J": d_e,
        "speed_fluctuation_without_flywheel": free,
        "speed_fluctuation": np.asarray(coefficient, dtype=float),
        "flywheel_inertia_kgm2": fw.flywheel_inertia(d_e, w_mean, coefficient, j_mean),
    }
    curves = {"inertia_torque": t_inertia, "with_inertia": with_inertia, "steady": steady,
              "equivalent_inertia": j_eq, "omega_mean": w_mean}  # fmt: skip
    return summary, curves
