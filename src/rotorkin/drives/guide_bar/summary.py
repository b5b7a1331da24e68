"""Closed-form summary keys of the drive and the pump, for one design or arrays of designs.

The study (:mod:`rotorkin.drives.guide_bar.study`, one design) and the sweep kernel
(:mod:`rotorkin.drives.guide_bar.sweep`, many) both report these keys; each samples
the input torque and the impeller peaks on its own grid and passes the extremes in.
Every value broadcasts over the parameters (floats or arrays); a 0-d result is a
Python float.
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import flywheel as fw
from rotorkin.analysis import torque as tq
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import pump as gb_pump
from rotorkin.machines import vane_pump as vp
from rotorkin.studies.helpers import time_peak_keys

__all__ = ["drive_summary", "pump_summary", "work_summary", "dynamics_summary", "FLOW_KEYS",
           "TORQUE_KEYS", "SLUGS", "TIME_KEYS"]  # fmt: skip

#: Keys of :func:`dynamics_summary` from the geometric flow, in order.
FLOW_KEYS = ("flow_max_l_per_min", "flow_min_l_per_min", "flow_ripple")
#: Keys of :func:`dynamics_summary` from the torques and inertias, in order.
TORQUE_KEYS = (
    "shaft_torque_min_Nm",
    "shaft_torque_max_Nm",
    "torque_ripple",
    "shaft_torque_with_inertia_min_Nm",
    "shaft_torque_with_inertia_max_Nm",
    "torque_ripple_with_inertia",
    "equivalent_inertia_mean_kgm2",
    "energy_fluctuation_J",
    "speed_fluctuation_without_flywheel",
    "speed_fluctuation",
    "flywheel_inertia_kgm2",
)
#: Key stems of the two impellers.
SLUGS = ("impeller1", "impeller2")
#: Keys of :func:`rotorkin.studies.helpers.time_peaks` for the impellers.
TIME_KEYS = time_peak_keys(SLUGS)
_M3_TO_L_PER_MIN = 60.0e3


def _out(x):
    """A 0-d value as a Python float (arrays unchanged)."""
    return float(x) if np.ndim(x) == 0 else np.asarray(x)


def drive_summary(params: gb.GuideBar, m7, m8, sampled: dict | None = None) -> dict:
    """The drive's keys: vane angles, swing, speed ratios, equal-speed points, input torque.

    Parameters
    ----------
    params : GuideBar
    m7, m8 : array_like
        The paper's constant resisting torques on impeller 1 and 2 [N*m] (eq. 7, 8).
    sampled : dict, optional
        Extremes over a period on the caller's grid: ``"input_torque_min_Nm"``,
        ``"input_torque_max_Nm"`` [N*m], ``"impeller_accel_peak_per_rad"`` [1/rad],
        ``"impeller_jerk_peak_per_rad2"`` [1/rad^2]; without it those keys and the
        torque fluctuation are left out.

    Returns
    -------
    dict
        Summary key -> value (degrees where the key says so).
    """
    lam, u, phase, driver = params.lam, params.gear_ratio, params.phase, params.driver
    u, i12 = (np.asarray(v, dtype=float) for v in (u, params.input_gear_ratio))
    crank = np.asarray(driver) == "crank"
    g_crank, g_guide = (gb.vane_angle(lam, u, phase, d) for d in gb.DRIVERS)
    rmin, rmax = gb.speed_ratio_range(lam, u, driver)
    # the two equal-speed points, as driving angles of mechanism 1 in [0, 2 pi), ascending
    t = np.mod(np.stack(np.broadcast_arrays(*gb.equal_speed_angles(phase))), 2.0 * np.pi)
    t_a, t_b = np.minimum(t[0], t[1]), np.maximum(t[0], t[1])
    mean = (np.asarray(m7, dtype=float) + np.asarray(m8, dtype=float)) / (u * i12)
    out = {
        "driver": driver,
        "lambda": lam,
        "gear_ratio": u,
        "input_gear_ratio": i12,
        "phase_deg": np.degrees(phase),
        "vane_angle_deg": np.degrees(np.where(crank, g_crank, g_guide)),
        "vane_angle_crank_driven_deg": np.degrees(g_crank),
        "vane_angle_guide_driven_deg": np.degrees(g_guide),
        "vane_angle_other_driver_deg": np.degrees(np.where(crank, g_guide, g_crank)),
        "relative_angle_swing_deg": np.degrees(gb.relative_angle_swing(params)),
        "impeller_speed_ratio_min": rmin,
        "impeller_speed_ratio_max": rmax,
        "impeller_speed_ratio_mean": 1.0 / u,
        "equal_speed_driving_angle_1_deg": np.degrees(t_a),
        "equal_speed_driving_angle_2_deg": np.degrees(t_b),
        "equal_speed_input_angle_1_deg": np.degrees(t_a * i12),
        "equal_speed_input_angle_2_deg": np.degrees(t_b * i12),
        "equal_speed_ratio_1": gb.driven_rates(lam, driver, t_a)[0] / u,
        "equal_speed_ratio_2": gb.driven_rates(lam, driver, t_b)[0] / u,
    }
    if sampled is not None:
        tmin, tmax = sampled["input_torque_min_Nm"], sampled["input_torque_max_Nm"]
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(mean != 0.0, (tmax - tmin) / np.abs(mean), np.nan)
        out |= {
            "input_torque_min_Nm": tmin,
            "input_torque_max_Nm": tmax,
            "input_torque_mean_Nm": mean,
            "input_torque_fluctuation_Nm": tmax - tmin,
            "input_torque_fluctuation_ratio": ratio,
        }
    else:
        out["input_torque_mean_Nm"] = mean
    out |= {
        "impeller_speed_ratio_input_min": rmin / i12,
        "impeller_speed_ratio_input_max": rmax / i12,
    }
    if sampled is not None:
        out |= {
            "impeller_accel_peak_per_rad": sampled["impeller_accel_peak_per_rad"],
            "impeller_jerk_peak_per_rad2": sampled["impeller_jerk_peak_per_rad2"],
        }
    return {k: v if k == "driver" else _out(v) for k, v in out.items()}


def pump_summary(params: gb.GuideBar, pump: vp.VanePump) -> dict:
    """The pump's geometric keys: vanes, chamber angles and volumes, displacement.

    Returns
    -------
    dict
        Summary key -> value; volumes in cm^3, angles in degrees.
    """
    k = pump.volume_per_angle
    phi_min, phi_max = pump.chamber_angle_range
    disp = gb_pump.displacement(params, pump)
    out = {
        "vanes_per_impeller": pump.vanes_per_impeller,
        "chambers": pump.n_chambers,
        "pump_vane_angle_deg": np.degrees(pump.vane_angle),
        "pump_vane_angle_max_deg": np.degrees(pump.vane_angle_max),
        "chamber_angle_min_deg": np.degrees(phi_min),
        "chamber_angle_max_deg": np.degrees(phi_max),
        "chamber_volume_min_cm3": k * phi_min * 1e6,
        "chamber_volume_max_cm3": k * phi_max * 1e6,
        "displacement_cm3_per_rev": disp["per_input_turn"] * 1e6,
        "displacement_per_period_cm3": disp["per_period"] * 1e6,
        "displacement_per_impeller_rev_cm3": disp["per_impeller_rev"] * 1e6,
    }
    return {
        k: (int(v) if np.ndim(v) == 0 else np.asarray(v)) if k in ("vanes_per_impeller", "chambers")
        else _out(v)
        for k, v in out.items()
    }  # fmt: skip


def work_summary(params: gb.GuideBar, pump: vp.VanePump, ports: vp.PortPressures,
                 flow_mean=None) -> dict:  # fmt: skip
    """Pressure rise, hydraulic power, indicated work and mean shaft torque (ideal ports).

    Every chamber takes in its volume change at ``p_s`` and delivers it at ``p_d``
    once per period, so the work per period is ``-(p_d - p_s) D_period`` (exact;
    negative: the shaft drives the pump).

    Parameters
    ----------
    flow_mean : array_like, optional
        Mean delivered flow [m^3/s]; with it, ``hydraulic_power_W = (p_d - p_s) Q``.
    """
    dp = np.asarray(ports.discharge_pressure, dtype=float) - np.asarray(
        ports.suction_pressure, dtype=float)  # fmt: skip
    work_period = -dp * gb_pump.displacement(params, pump)["per_period"]
    out = {"pressure_rise_bar": dp / 1e5}
    if flow_mean is not None:
        out["hydraulic_power_W"] = dp * flow_mean
    out |= {
        "indicated_work_J": work_period / np.asarray(params.input_gear_ratio, dtype=float),
        "indicated_work_per_period_J": work_period,
        "mean_torque_Nm": work_period / gb.period(params),
    }
    return {k: _out(v) for k, v in out.items()}


def dynamics_summary(params: gb.GuideBar, state: dict, inertia, theta, coefficient) -> dict:
    """Flow extremes and ripple, shaft torques, inertia and flywheel over one period.

    :data:`FLOW_KEYS` and :data:`TORQUE_KEYS`, for one design or many: with the
    parameters as columns ``(d, 1)`` against the angles, every key is an array ``(d,)``.

    Parameters
    ----------
    params : GuideBar
    state : dict
        :func:`rotorkin.drives.guide_bar.pump.pump_state` at ``theta``.
    inertia : (J_shaft, (J_1, J_2))
        [kg*m^2], floats or columns.
    theta : ndarray, shape (n,)
        Input angles over one period, ends included [rad].
    coefficient : array_like
        ``machine.speed_fluctuation``, the wanted coefficient of speed fluctuation.
    """
    theta = np.asarray(theta, dtype=float)
    period = theta[-1] - theta[0]
    shaft, net = state["shaft"], state["net"]
    omega = np.broadcast_to(np.asarray(state["omega"], dtype=float), np.shape(shaft))
    omega_mean = np.mean(omega[..., :-1], axis=-1)
    # flywheel: net torque at the mean speed (member inertia included), J_eq already present
    dq, d2q, _ = gb.impeller_rates(params, theta)
    js, jm = inertia
    net_const = shaft - tq.inertia_torque(js, jm, dq, d2q, omega_mean[..., None], 0.0)
    delta_e = fw.energy_fluctuation(net_const, theta)
    j_mean = np.trapezoid(state["J_eq"], theta, axis=-1) / period
    with np.errstate(divide="ignore", invalid="ignore"):
        free = np.where(j_mean > 0.0, delta_e / (j_mean * omega_mean**2), np.nan)
    flow = state["flow"]
    out = {
        "flow_max_l_per_min": np.max(flow, axis=-1) * _M3_TO_L_PER_MIN,
        "flow_min_l_per_min": np.min(flow, axis=-1) * _M3_TO_L_PER_MIN,
        "flow_ripple": vp.flow_ripple(flow, 1.0 / np.asarray(state["omega"], dtype=float)),
        "shaft_torque_min_Nm": np.min(shaft, axis=-1),
        "shaft_torque_max_Nm": np.max(shaft, axis=-1),
        "torque_ripple": tq.torque_ripple(shaft),
        "shaft_torque_with_inertia_min_Nm": np.min(net, axis=-1),
        "shaft_torque_with_inertia_max_Nm": np.max(net, axis=-1),
        "torque_ripple_with_inertia": tq.torque_ripple(net),
        "equivalent_inertia_mean_kgm2": j_mean,
        "energy_fluctuation_J": delta_e,
        "speed_fluctuation_without_flywheel": free,
        "speed_fluctuation": np.asarray(coefficient, dtype=float),
        "flywheel_inertia_kgm2": fw.flywheel_inertia(delta_e, omega_mean, coefficient, j_mean),
    }
    return {k: _out(v) for k, v in out.items()}
